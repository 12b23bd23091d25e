"""Section 1: modes of the probe, the three zones (Figs. 16, 17), the two-element model against
fine meshes and the exact solution, and the errata of the printed matrices."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..fem import Supports, dominant_mode_zones, exact_frequencies, modal_analysis
from ..fem.symbolic import PAPER_NOTES, paper_errata
from ..paper import printed
from ..paper.protocol import TIME_FREQUENCY_RATIOS
from ..probe import Probe
from ._common import check_render, check_step

__all__ = ["ModesResult", "compute", "render"]


@dataclass(frozen=True, eq=False)
class ModesResult:
    """The modal analysis of the study's probe.

    Attributes
    ----------
    length : float
        Probe length, m.
    tip_mass : float
        Tip mass, kg.
    zones : ebantenna.fem.zones.ZoneResult
        Dominant frequency and its zones along the probe.
    zone2_start, zone3_start : float
        Where zones 2 and 3 begin, m.
    peak : float
        Contact where the lowest frequency peaks, m.
    shapes : tuple of (str, float, ModalResult)
        Label, contact (m) and modes for the three mode-shape panels.
    comparison : tuple of dict
        Per contact ratio: ``ratio`` and the first two frequencies (Hz) from 2 and 64 elements
        and from the exact solution, bare tube.
    errata : tuple
        :func:`ebantenna.fem.symbolic.paper_errata`.
    """

    length: float
    tip_mass: float
    zones: object
    zone2_start: float
    zone3_start: float
    peak: float
    shapes: tuple
    comparison: tuple
    errata: tuple

    def to_dict(self) -> dict:
        """The summary numbers (ratios of the probe length)."""
        return {
            "zone2_start_ratio": self.zone2_start / self.length,
            "zone3_start_ratio": self.zone3_start / self.length,
            "lowest_frequency_peak_ratio": self.peak / self.length,
            "errata": len(self.errata),
        }


def compute(probe, quick: bool) -> ModesResult:
    """Zones, mode shapes, the two-element model against the references, and the errata.

    Parameters
    ----------
    probe : Probe
        The study's probe (with its tip mass).
    quick : bool
        50 contacts for the zones instead of 99.
    """
    check_step(probe=probe, quick=quick)
    L = probe.length
    contacts = np.linspace(0.01, 0.99, 50 if quick else 99) * L
    zones = dominant_mode_zones(probe, contacts)
    start2, start3 = zones.boundaries()
    peak = float(contacts[np.argmax(zones.frequency)])
    picks = {"a": 0.25 * L, "b": 0.5 * (start2 + start3), "c": 0.9 * L}
    shapes = tuple(
        (label, float(c), modal_analysis(probe, Supports(contact=float(c)), n_elements=64,
                                          n_modes=2))
        for label, c in picks.items()
    )
    bare = Probe(**{**probe.to_dict(), "tip_mass": 0.0})
    comparison = []
    for r in TIME_FREQUENCY_RATIOS:
        comparison.append({
            "ratio": r,
            "two": modal_analysis(bare, Supports(r * L), n_elements=2, n_modes=2).frequencies,
            "fine": modal_analysis(bare, Supports(r * L), n_elements=64, n_modes=2).frequencies,
            "exact": exact_frequencies(bare, r * L, n_modes=2),
        })
    return ModesResult(L, probe.tip_mass, zones, start2, start3, peak, shapes,
                       tuple(comparison), tuple(paper_errata()))


def render(result: ModesResult, report, figures) -> None:
    """Figures 16 and 17, the comparison table and the errata."""
    check_render(result, ModesResult, report, figures)
    fig16, fig17 = _plot_zones(result, figures), _plot_mode_shapes(result, figures)
    _render_zones(result, report, fig16, fig17)
    _render_two_elements_against_exact(result, report)
    _render_errata(result, report)


def _plot_zones(result: ModesResult, figures) -> str:
    """Fig. 16: the dominant frequency against the contact distance, zones shaded."""
    ax = result.zones.plot()
    ax.set_title("Dominant (lowest) frequency and its zones (cf. Fig. 16)")
    return figures.save(ax.figure, "fig16_zones")


def _plot_mode_shapes(result: ModesResult, figures) -> str:
    """Fig. 17: the mode shapes with the contact in zones 1, 2 and 3."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(13, 3.6), sharey=True)
    for axis, (label, c, res) in zip(axes, result.shapes, strict=True):
        res.plot(ax=axis)
        axis.set_title(f"({label}) contact at {c / result.length:.2f} L")
    return figures.save(fig, "fig17_mode_shapes")


def _render_zones(result: ModesResult, report, fig16: str, fig17: str) -> None:
    """Where the zones begin, beside the paper's mode change, and Figs. 16 and 17."""
    L = result.length
    report.heading("Modes of the probe and the three zones (Figs. 16, 17)")
    report.paragraph(
        f"Probe of the paper scene: L = {100 * L:g} cm acrylic tube with a "
        f"{1000 * result.tip_mass:g} g sensor board at the tip, hinge clamped, contact a rigid "
        "pin. The zones are read off the mode shapes: zone 1 where the overhang holds at least "
        "90 % of the lowest mode's kinetic energy, zone 3 where it holds at most 10 %."
    )
    peak = result.peak
    report.table(
        ["quantity", "paper", "this reproduction"],
        [
            [
                "mode change complete",
                f"{printed.MODE_CHANGE_RATIO.value:.2f} L",
                f"zone 3 from {result.zone3_start / L:.2f} L",
            ],
            ["transition (zone 2) begins", "-", f"{result.zone2_start / L:.2f} L"],
            ["lowest frequency peaks at", "-", f"{peak / L:.2f} L ({100 * peak:.1f} cm)"],
        ],
    )
    report.figure(fig16, "Dominant frequency against contact distance, zones shaded (cf. Fig. 16)")
    report.figure(
        fig17, "Mode shapes in zones 1, 2 and 3, drawn with the shape functions (cf. Fig. 17)"
    )


def _render_two_elements_against_exact(result: ModesResult, report) -> None:
    """The paper's two-element frequencies against a fine mesh and the exact equation."""
    report.paragraph(
        "The paper's two-element model against 64 elements and the exact frequency equation "
        "(bare tube, no tip mass, so that the exact solution applies):"
    )
    report.table(
        ["contact", "f1, 2 elements", "f1, 64 elements", "f1, exact", "f2, 2 elements",
         "f2, exact"],
        [
            [f"{row['ratio']:.2f} L", f"{row['two'][0]:.2f}", f"{row['fine'][0]:.4f}",
             f"{row['exact'][0]:.4f}", f"{row['two'][1]:.1f}", f"{row['exact'][1]:.2f}"]
            for row in result.comparison
        ],
    )


def _render_errata(result: ModesResult, report) -> None:
    """The printed matrices' entries that differ from the derivation, and the paper's notes."""
    errata = result.errata
    report.paragraph(
        f"Errata of the printed element and two-element matrices: {len(errata)} entries differ "
        "from the sympy derivation (typo: wrong however the printed factor's l is read, as the "
        "entry's own element's length or, at the node both elements share, with l1 = l2; common "
        "factor: a shared entry right only when l1 = l2, the one printed factor serving two "
        "lengths)."
    )
    report.table(
        ["matrix", "row", "col", "printed", "derived", "why"],
        [[e.matrix, e.row, e.col, e.printed, e.derived, e.reason] for e in errata],
    )
    for note in PAPER_NOTES:
        report.paragraph(f"Note: {note}")
