"""Section 6d: how the study's accuracies depend on the touched rod's assumed geometry.

The paper gives no geometry of the touched objects; the scene assumes a rod of 12 mm diameter
and 250 mm free length (:class:`~ebantenna.simulate.effects.ObjectModes`). The rod's stiffness
and mass are what the probe feels, so the accuracies hold for that rod. Here the diameter and
the free length are varied one at a time (:data:`DIAMETER_FACTORS`, :data:`LENGTH_FACTORS`),
and for each rod the controls' design is simulated again: the grouped SVM's accuracy, the
mode-curve classifier's, and how close the two closest materials' rods put their second
coupled mode (:func:`closest_materials`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from itertools import combinations

import numpy as np

from ..fem.coupled_sweep import coupled_sweep
from ..paper.controls import grouped_svm_spread
from ..paper.data import PAPER_DESIGN
from ..paper.uncertainty import clustered_entries, format_clustered, percent
from ..probe import material
from ..simulate import build_dataset
from ._common import check_render, check_step
from .physics_controls import control_design, mode_curve_spread

__all__ = ["DIAMETER_FACTORS", "LENGTH_FACTORS", "GAP_POSITIONS", "GeometryResult",
           "closest_materials", "compute", "render"]

#: Diameters tried, as factors of the scene's (12 mm: 8, 12 and 16 mm).
DIAMETER_FACTORS = (2 / 3, 1.0, 4 / 3)
#: Free lengths tried, as factors of the scene's (250 mm: 200, 250 and 300 mm).
LENGTH_FACTORS = (0.8, 1.0, 1.2)
#: Contact positions of the coupled-mode comparison, fractions of the probe length.
GAP_POSITIONS = np.linspace(0.05, 0.95, 10)


def closest_materials(scene, diameter: float, free_length: float, materials=None):
    """The two materials whose rods of this geometry move the probe's modes most alike.

    For each material, the probe's coupled modes with the rod
    (:func:`~ebantenna.fem.coupled_sweep.coupled_sweep`, the scene's contact spring per material)
    at :data:`GAP_POSITIONS`; the gap of
    two materials is the median over the positions of the difference of their second coupled
    modes, Hz, and the pair with the smallest gap is returned.

    Parameters
    ----------
    scene : Scene
        With the ``object_modes`` effect (its contact spring and preload).
    diameter, free_length : float
        The rod's, m.
    materials : sequence of str, optional
        Default: the paper's five.

    Returns
    -------
    (str, str, float)
        The two materials and their gap, Hz.
    """
    effect = replace(scene.effect("object_modes"), diameter=diameter, free_length=free_length)
    names = tuple(PAPER_DESIGN.materials if materials is None else materials)
    rods = [effect.rod(material(n)) for n in names]
    k = np.array([effect.contact_stiffness(r.material, scene.probe) for r in rods])
    sweep = coupled_sweep(scene.probe, rods, GAP_POSITIONS * scene.probe.length, k,
                          hinge=scene.hinge, n_modes=2)
    second = sweep.frequencies[:, :, 1]
    gaps = {(a, b): float(np.median(np.abs(second[a] - second[b])))
            for a, b in combinations(range(len(names)), 2)}
    a, b = min(gaps, key=gaps.get)
    return names[a], names[b], gaps[a, b]


@dataclass(frozen=True, eq=False)
class GeometryResult:
    """One row per rod geometry tried.

    Attributes
    ----------
    rows : list of dict
        ``diameter_mm``, ``free_length_mm``, ``svm`` (seed-0 grouped accuracy), ``svm_spread``
        (:class:`~ebantenna.paper.uncertainty.SeedSpread`), ``n_test``, ``mode_curves``,
        ``closest`` (the two materials) and ``gap_hz``.
    recordings : int
        Recordings of each data set.
    """

    rows: list
    recordings: int

    def to_dict(self) -> dict:
        """Under ``materials``: ``rod_geometry``, each accuracy over all folds with its interval
        on the position, each geometry paired against the scene's rod, and the rank
        correlations of the accuracies with the closest materials' gap
        (``rod_geometry_gap_correlation``)."""
        out = []
        for r in self.rows:
            out.append({
                "diameter_mm": r["diameter_mm"], "free_length_mm": r["free_length_mm"],
                **clustered_entries("svm_grouped_accuracy", r["svm_spread"].folds()),
                "svm_grouped_seed_spread": r["svm_spread"].to_dict(),
                **clustered_entries("mode_curve_grouped_accuracy", r["curve_spread"].folds()),
                "svm_against_scene_rod": (None if r["paired"] is None
                                          else r["paired"].to_dict()),
                "closest_materials": list(r["closest"]), "second_mode_gap_hz": r["gap_hz"],
            })  # fmt: skip
        return {"rod_geometry": out, "rod_geometry_gap_correlation": self.gap_correlation()}

    def gap_correlation(self) -> dict:
        """Spearman's rank correlation of each classifier's accuracy (all folds) with the
        closest materials' second-mode gap, over the geometries."""
        gaps = [r["gap_hz"] for r in self.rows]
        out = {}
        for key, name in (("svm_spread", "svm"), ("curve_spread", "mode_curves")):
            acc = [r[key].folds().estimate for r in self.rows]
            out[name] = _spearman(gaps, acc)
        return out


def _spearman(x, y) -> float | None:
    """Spearman's rank correlation (average ranks for ties), or None when a side is constant.

    Examples
    --------
    >>> _spearman([1, 2, 3], [3, 2, 1]), _spearman([1, 2, 3], [1, 1, 1])
    (-1.0, None)
    """
    from scipy.stats import rankdata

    rx, ry = rankdata(x), rankdata(y)
    if np.ptp(rx) == 0 or np.ptp(ry) == 0:
        return None
    return float(np.corrcoef(rx, ry)[0, 1])


def _geometries(effect):
    """(diameter, free length) pairs: the scene's, then each varied alone."""
    d0, l0 = effect.diameter, effect.free_length
    pairs = [(d0 * f, l0) for f in DIAMETER_FACTORS] + [(d0, l0 * f) for f in LENGTH_FACTORS]
    return list(dict.fromkeys((round(d, 6), round(ln, 6)) for d, ln in pairs))


def compute(scene, seed: int, quick: bool, cache_dir, n_jobs: int) -> GeometryResult | None:
    """The scene's rod and each of its diameter and free length varied alone
    (:data:`DIAMETER_FACTORS`, :data:`LENGTH_FACTORS`), on the controls' design; None without
    rod modes."""
    check_step(scene=scene, seed=seed, quick=quick, cache_dir=cache_dir, n_jobs=n_jobs)
    effect = scene.effect("object_modes")
    if effect is None:
        return None
    design = control_design(quick)
    rows = []
    for d, ln in _geometries(effect):
        if (d, ln) == (round(effect.diameter, 6), round(effect.free_length, 6)):
            variant = scene  # shares its data set with the ablation's baseline
        else:
            moved = replace(effect, diameter=d, free_length=ln)
            variant = scene.with_(
                name=f"{scene.name}-rod-d{1e3 * d:g}mm-l{1e3 * ln:g}mm",
                effects=[moved if e.name == "object_modes" else e for e in scene.effects],
            )
        ds = build_dataset(cache_dir, variant, design, seed, n_jobs=n_jobs, show_progress=False)
        spread = grouped_svm_spread(ds, seed=seed, n_jobs=n_jobs)
        curves = mode_curve_spread(ds, seed, n_jobs)
        a, b, gap = closest_materials(scene, d, ln, design.materials)
        rows.append({
            "diameter_mm": 1e3 * d, "free_length_mm": 1e3 * ln,
            "svm": float(spread.values[0]), "svm_spread": spread,
            "n_test": int(spread.n_test[0]), "mode_curves": float(curves.values[0]),
            "curve_spread": curves, "closest": (a, b), "gap_hz": gap,
            "scene_rod": variant is scene,
        })  # fmt: skip
    reference = next(r["svm_spread"] for r in rows if r["scene_rod"])
    for r in rows:
        r["paired"] = None if r["scene_rod"] else reference.paired_with(r["svm_spread"])
    return GeometryResult(rows, int(ds.material.size))


def render(result: GeometryResult | None, report, figures) -> None:
    """The sensitivity table and what it shows, generated from its numbers."""
    check_render(result, GeometryResult, report, figures, optional=True)
    if result is None:
        return
    report.heading("How much the accuracies owe to the assumed rod")
    report.paragraph(
        "The paper gives no dimensions of the touched objects; the scene assumes a rod, and "
        "in the simulator the probe feels that rod's stiffness and mass through its coupled "
        "modes (the 'object_modes' effect, an assumption). Below, the "
        "rod's diameter and free length varied one at a time, each on the controls' reduced "
        f"design ({result.recordings} recordings, the same rows for every rod): the paper's "
        "SVM and the mode-curve classifier on whole held-out positions over all folds, the "
        "SVM paired against the scene's rod on the same rows, and the two materials whose "
        "rods put the probe's second coupled mode closest together (median over "
        f"{GAP_POSITIONS.size} contact positions, {GAP_POSITIONS[0]:g} L to "
        f"{GAP_POSITIONS[-1]:g} L)."
    )
    report.table(
        ["diameter (mm)", "free length (mm)", "grouped SVM, all folds",
         "SVM against the scene's rod", "mode curves, all folds", "closest materials",
         "2nd-mode gap (Hz)"],
        [
            [f"{r['diameter_mm']:.0f}", f"{r['free_length_mm']:.0f}",
             format_clustered(r["svm_spread"].folds()),
             "(the scene's rod)" if r["paired"] is None else str(r["paired"]),
             format_clustered(r["curve_spread"].folds()), " / ".join(r["closest"]),
             f"{r['gap_hz']:.2f}"]
            for r in result.rows
        ],
    )
    report.paragraph(gap_sentence(result))


def _gap_clause(corr: dict) -> str:
    """Whether a smaller gap goes with lower accuracy, from both classifiers' rank correlations
    (``{"svm": rho, "mode_curves": rho}``, None where the accuracy does not change).

    Examples
    --------
    >>> _gap_clause({"svm": 0.9, "mode_curves": 0.5})
    'goes with lower accuracy here'
    >>> _gap_clause({"svm": -0.9, "mode_curves": None})
    'does not go with lower accuracy here'
    >>> _gap_clause({"svm": 1.0, "mode_curves": -1.0})
    'goes with lower accuracy for the SVM here, not for the mode curves'
    """
    labels = {"svm": "the SVM", "mode_curves": "the mode curves"}
    rises = {name: (corr[name] or 0) > 0 for name in labels}
    if all(rises.values()):
        return "goes with lower accuracy here"
    if not any(rises.values()):
        return "does not go with lower accuracy here"
    yes, no = (next(labels[n] for n in labels if rises[n] is flag) for flag in (True, False))
    return f"goes with lower accuracy for {yes} here, not for {no}"


def gap_sentence(result: GeometryResult) -> str:
    """What the geometries show, every clause from the table's numbers: the direction of the
    accuracies with the closest materials' gap (rank correlation), and how many geometries
    the paired SVM resolves from the scene's rod.

    Examples
    --------
    >>> from ebantenna.paper.uncertainty import SeedSpread
    >>> def spread(a):
    ...     return SeedSpread([0, 1], [a, a], [10, 10])
    >>> class Folds(SeedSpread):
    ...     def folds(self, *args, **kwargs):
    ...         from ebantenna.paper.uncertainty import ClusteredAccuracy
    ...         k = int(round(10 * self.mean))
    ...         return ClusteredAccuracy([k, k], [10, 10], "position")
    >>> def row(gap, a):
    ...     f = Folds([0, 1], [a, a], [10, 10])
    ...     return dict(gap_hz=gap, svm_spread=f, curve_spread=f, paired=None)
    >>> up = GeometryResult([row(1, 0.5), row(2, 0.6), row(3, 0.7)], 30)
    >>> "rises with the gap" in gap_sentence(up)
    True
    >>> down = GeometryResult([row(1, 0.7), row(2, 0.6), row(3, 0.5)], 30)
    >>> "falls as the gap grows" in gap_sentence(down)
    True
    """
    corr = result.gap_correlation()
    parts = []
    for name, label in (("svm", "the SVM's"), ("mode_curves", "the mode curves'")):
        rho = corr[name]
        if rho is None:
            parts.append(f"{label} accuracy does not change with the gap")
        elif rho > 0:
            parts.append(f"{label} accuracy rises with the gap (Spearman {rho:+.2f})")
        elif rho < 0:
            parts.append(f"{label} accuracy falls as the gap grows (Spearman {rho:+.2f})")
        else:
            parts.append(f"{label} accuracy shows no rank order with the gap")
    pairs = [r["paired"] for r in result.rows if r["paired"] is not None]
    resolved = [p for p in pairs if p.resolved]
    svm = [r["svm_spread"].folds().estimate for r in result.rows]
    text = (
        f"Over the {len(result.rows)} geometries, " + "; ".join(parts) + ": a smaller gap "
        "between the two closest materials "
        + _gap_clause(corr)
        + f" ({len(result.rows)} geometries, a rank order, not a test). The SVM's accuracy "
        f"spans {percent(min(svm))} to {percent(max(svm))}"
    )
    if pairs:
        text += (f"; paired on the same rows, {len(resolved)} of the {len(pairs)} other rods "
                 "differ from the scene's rod beyond their interval")
    return text + (". The study's accuracies hold for the assumed rod; these rows show how "
                   "far they move when the rod does.")
