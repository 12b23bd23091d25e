"""The contact's Hertz law against its linearisation at the preload, on the controls' design.

The ``paper`` scene's strike pushes through the contact spring linearised at the 0.5 N preload,
while nearly every strike strikes again and sweeps the force from zero to several times the
preload. This section rebuilds the controls' design
(:func:`~ebantenna.study.physics_controls.control_design`) with ``hertz_contact`` added (the
crossed-cylinder Hertz law in series with the tube wall, as chords within a proven force bound,
:class:`~ebantenna.simulate.effects.HertzContact`) and gives the grouped-split SVM's and the
mode-curve classifier's accuracy under either law, each with its test count and 95 % Wilson
interval (:func:`ebantenna.ml.metrics.accuracy_interval`). The main data set keeps the
linearised law: ``ebantenna bench`` (``contact_cost``) measures what the Hertz law would cost.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..ml.metrics import accuracy_interval
from ..paper.controls import grouped_svm_accuracy
from ..paper.feature_table import signal_features
from ..paper.mode_curves import classify_materials_by_mode_curves
from ..paper.splits import grouped_split
from ..probe import material
from ..simulate import build_dataset
from ..simulate.effects import HertzContact
from ._common import pct
from .physics_controls import control_design

__all__ = ["LAWS", "Accuracy", "ContactLawResult", "compute", "render"]

#: The two laws compared, in report order.
LAWS = ("linearised", "hertz")


@dataclass(frozen=True)
class Accuracy:
    """An accuracy with its test count and 95 % Wilson interval.

    Attributes
    ----------
    correct, n : int
        Test recordings classified right, and in all.
    """

    correct: int
    n: int

    @property
    def value(self) -> float:
        """The accuracy, a fraction."""
        return self.correct / self.n

    @property
    def interval(self) -> tuple[float, float]:
        """The 95 % Wilson interval, fractions."""
        return accuracy_interval(self.correct, self.n)

    def to_dict(self) -> dict:
        """``accuracy``, ``accuracy_n_test``, ``accuracy_ci95`` (fractions), named as every
        accuracy of ``summary.json`` is."""
        lo, hi = self.interval
        return {"accuracy": self.value, "accuracy_n_test": self.n, "accuracy_ci95": [lo, hi]}

    def text(self) -> str:
        """``"83.0 % (95 % CI 74.1-89.2 %, n = 80)"``."""
        lo, hi = self.interval
        return f"{pct(self.value)} (95 % CI {100 * lo:.1f}-{100 * hi:.1f} %, n = {self.n})"


@dataclass(frozen=True, eq=False)
class ContactLawResult:
    """Both contact laws on the controls' design.

    Attributes
    ----------
    design : str
        Name of the design rebuilt.
    recordings : int
        Recordings per data set.
    svm, mode_curves : dict of str to Accuracy
        Grouped-split accuracy of the paper's SVM and of the mode-curve classifier, by law
        (:data:`LAWS`).
    restrikes : dict of str to float
        Median contacts after the first touch per strike, by law.
    chords : dict of str to tuple
        Per material: the Hertz law's chords and their force bound (N).
    force_tolerance : float
        The chords' tolerance, N.
    """

    design: str
    recordings: int
    svm: dict
    mode_curves: dict
    restrikes: dict
    chords: dict
    force_tolerance: float

    def to_dict(self) -> dict:
        """The result as ``summary.json`` holds it."""
        return {
            "design": self.design,
            "recordings": self.recordings,
            "svm_grouped": {law: self.svm[law].to_dict() for law in LAWS},
            "mode_curve_grouped": {law: self.mode_curves[law].to_dict() for law in LAWS},
            "median_restrikes": dict(self.restrikes),
            "hertz_chords": {m: {"chords": n, "bound_N": b} for m, (n, b) in self.chords.items()},
            "force_tolerance_N": self.force_tolerance,
        }


def _scenes(scene):
    """The scene with the linearised contact that only pushes, and with the Hertz law."""
    effects = tuple(e for e in scene.effects if e.name != "hertz_contact")
    names = {e.name for e in effects}
    if "unilateral_contact" not in names:
        effects = (*effects, "unilateral_contact")
    linear = scene if effects == scene.effects else scene.with_(
        name=f"{scene.name}-unilateral", effects=effects)  # fmt: skip
    return {"linearised": linear, "hertz": linear.with_(
        name=f"{linear.name}-hertz_contact", effects=(*effects, "hertz_contact"))}  # fmt: skip


def _accuracies(ds, seed: int, n_jobs: int) -> tuple[Accuracy, Accuracy]:
    """The SVM's and the mode-curve classifier's accuracy on whole held-out positions."""
    split = grouped_split(ds.contact, seed=seed)
    n = int(np.size(split[1]))
    svm = grouped_svm_accuracy(ds, seed=seed)
    feats = signal_features(ds.ax, ds.az, ds.fs, n_jobs=n_jobs, show_progress=False)
    curves = classify_materials_by_mode_curves(
        feats.peaks, feats.dominant, ds.material, ds.contact, split
    ).accuracies["test"]
    return Accuracy(round(svm * n), n), Accuracy(round(curves * n), n)


def compute(scene, seed: int, quick: bool, cache_dir, n_jobs: int) -> ContactLawResult | None:
    """Build the controls' design under both laws and classify it; None when the scene has no
    ``object_modes`` effect (no rod, no strike)."""
    obj = scene.effect("object_modes")
    if obj is None:
        return None
    design = control_design(quick)
    svm, curves, restrikes = {}, {}, {}
    for law, sc in _scenes(scene).items():
        ds = build_dataset(cache_dir, sc, design, seed, n_jobs=n_jobs, show_progress=False)
        svm[law], curves[law] = _accuracies(ds, seed, n_jobs)
        restrikes[law] = float(np.median(ds.metadata["restrikes"]))
    hertz = _scenes(scene)["hertz"].effect("hertz_contact") or HertzContact()
    chords = {}
    for name in design.materials:
        spring = hertz.spring(material(name), scene.probe, obj.diameter, obj.preload)
        chords[name] = (int(spring.slopes.size), spring.bound)
    recordings = len(ds.material)
    return ContactLawResult(design.name, recordings, svm, curves, restrikes, chords,
                            hertz.force_tolerance)  # fmt: skip


def render(result: ContactLawResult | None, report, figures) -> None:
    """The two laws side by side, and what the difference means."""
    if result is None:
        return
    r = result
    report.heading("The contact's Hertz law against its linearisation")
    report.paragraph(
        "The strike's contact pushes through the spring linearised at the 0.5 N preload, while "
        f"nearly every strike strikes again (median {r.restrikes['linearised']:g} times) and "
        "sweeps the force far from it. The controls' design "
        f"({r.recordings} recordings) is simulated again with the crossed-cylinder Hertz law in "
        "series with the tube wall ('hertz_contact'), integrated as chords that differ from it "
        f"by at most {r.force_tolerance:g} N ({min(c for c, _ in r.chords.values())} to "
        f"{max(c for c, _ in r.chords.values())} chords per material). Each accuracy is on "
        "whole held-out positions, with its number of test recordings and 95 % Wilson interval."
    )
    rows = [
        [law, r.svm[law].text(), r.mode_curves[law].text(), f"{r.restrikes[law]:g}"]
        for law in LAWS
    ]
    report.table(["contact law", "SVM", "mode curves", "median re-strikes"], rows)
    report.paragraph(_verdict(r))


def _overlap(a: Accuracy, b: Accuracy) -> bool:
    """Whether the two 95 % intervals overlap."""
    (a_lo, a_hi), (b_lo, b_hi) = a.interval, b.interval
    return a_lo <= b_hi and b_lo <= a_hi


def _verdict(r: ContactLawResult) -> str:
    """What the comparison shows, in plain words."""
    parts = []
    for label, acc in (("the SVM", r.svm), ("the mode-curve classifier", r.mode_curves)):
        same = _overlap(acc["linearised"], acc["hertz"])
        parts.append(
            f"for {label} the two laws' intervals "
            + ("overlap: the linearisation changes nothing this design can resolve"
               if same else "do not overlap: the contact law matters")  # fmt: skip
        )
    text = "; ".join(parts)
    return text[0].upper() + text[1:] + "."
