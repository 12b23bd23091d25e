"""The contact's Hertz law against its linearisation at the preload, on the controls' design.

The ``paper`` scene's strike pushes through the contact spring linearised at the 0.5 N preload;
a strike that strikes again has lifted off, so its force has passed through zero, away from the
preload. This section rebuilds the controls' design
(:func:`~ebantenna.study.physics_controls.control_design`) with ``hertz_contact`` added (the
crossed-cylinder Hertz law in series with the tube wall, as chords within a proven force bound,
:class:`~ebantenna.simulate.effects.HertzContact`) and gives the grouped-split SVM's and the
mode-curve classifier's accuracy under either law over all folds, each with its 95 % interval
on the position, and the two laws paired on the same rows. The main data set keeps the
linearised law: ``ebantenna bench`` (``contact_cost``) measures what the Hertz law would cost.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..paper.controls import grouped_svm_spread
from ..paper.uncertainty import clustered_entries, format_clustered, percent
from ..probe import material
from ..simulate import build_dataset
from ..simulate.effects import HertzContact
from ._common import check_render, check_step
from .physics_controls import control_design, mode_curve_spread

__all__ = ["LAWS", "ContactLawResult", "compute", "render"]

#: The two laws compared, in report order.
LAWS = ("linearised", "hertz")


@dataclass(frozen=True, eq=False)
class ContactLawResult:
    """Both contact laws on the controls' design.

    Attributes
    ----------
    design : str
        Name of the design rebuilt.
    recordings : int
        Recordings per data set.
    svm, mode_curves : dict of str to ebantenna.paper.uncertainty.SeedSpread
        Grouped-split accuracy of the paper's SVM and of the mode-curve classifier over all
        folds, by law (:data:`LAWS`), with each row's result.
    paired : dict of str to ebantenna.paper.uncertainty.PairedDifference
        ``"svm"`` and ``"mode_curves"``: the Hertz law against the linearised one on the same
        rows and folds, paired within the position.
    restrikes : dict of str to float
        Median contacts after the first touch per strike, by law.
    restrike_shares : dict of str to float or None
        Share of the strikes with at least one contact after the first touch, by law.
    chords : dict of str to tuple
        Per material: the Hertz law's chords and their force bound (N).
    force_tolerance : float
        The chords' tolerance, N.
    preload : float or None
        The preload the linearised spring is taken at (the scene's ``object_modes``), N.
    """

    design: str
    recordings: int
    svm: dict
    mode_curves: dict
    restrikes: dict
    chords: dict
    force_tolerance: float
    paired: dict = None
    preload: float | None = None
    restrike_shares: dict | None = None

    def to_dict(self) -> dict:
        """The result as ``summary.json`` holds it."""
        return {
            "design": self.design,
            "recordings": self.recordings,
            "svm_grouped": {law: clustered_entries("accuracy", self.svm[law].folds())
                            for law in LAWS},
            "mode_curve_grouped": {law: clustered_entries("accuracy",
                                                          self.mode_curves[law].folds())
                                   for law in LAWS},
            "hertz_against_linearised": {k: p.to_dict() for k, p in (self.paired or {}).items()},
            "median_restrikes": dict(self.restrikes),
            "hertz_chords": {m: {"chords": n, "bound_N": b} for m, (n, b) in self.chords.items()},
            "force_tolerance_N": self.force_tolerance,
            "preload_N": self.preload,
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


def _accuracies(ds, seed: int, n_jobs: int):
    """The SVM and the mode-curve classifier over all folds of whole held-out positions."""
    return grouped_svm_spread(ds, seed=seed, n_jobs=n_jobs), mode_curve_spread(ds, seed, n_jobs)


def compute(scene, seed: int, quick: bool, cache_dir, n_jobs: int) -> ContactLawResult | None:
    """Build the controls' design under both laws and classify it; None when the scene has no
    ``object_modes`` effect (no rod, no strike)."""
    check_step(scene=scene, seed=seed, quick=quick, cache_dir=cache_dir, n_jobs=n_jobs)
    obj = scene.effect("object_modes")
    if obj is None:
        return None
    design = control_design(quick)
    svm, curves, restrikes, shares = {}, {}, {}, {}
    for law, sc in _scenes(scene).items():
        ds = build_dataset(cache_dir, sc, design, seed, n_jobs=n_jobs, show_progress=False)
        svm[law], curves[law] = _accuracies(ds, seed, n_jobs)
        restrikes[law] = float(np.median(ds.metadata["restrikes"]))
        shares[law] = float(np.mean(np.asarray(ds.metadata["restrikes"]) > 0))
    hertz = _scenes(scene)["hertz"].effect("hertz_contact") or HertzContact()
    chords = {}
    for name in design.materials:
        spring = hertz.spring(material(name), scene.probe, obj.diameter, obj.preload)
        chords[name] = (int(spring.slopes.size), spring.bound)
    recordings = len(ds.material)
    paired = {"svm": svm["linearised"].paired_with(svm["hertz"]),
              "mode_curves": curves["linearised"].paired_with(curves["hertz"])}
    return ContactLawResult(design.name, recordings, svm, curves, restrikes, chords,
                            hertz.force_tolerance, paired, float(obj.preload),
                            shares)  # fmt: skip


def render(result: ContactLawResult | None, report, figures) -> None:
    """The two laws side by side, and what the difference means."""
    check_render(result, ContactLawResult, report, figures, optional=True)
    if result is None:
        return
    r = result
    report.heading("The contact's Hertz law against its linearisation")
    report.paragraph(
        "The strike's contact pushes through the spring linearised at the "
        + ("scene's preload; " if r.preload is None else f"{r.preload:g} N preload; ")
        + restrike_words(r.restrikes["linearised"],
                         None if r.restrike_shares is None else r.restrike_shares["linearised"])
        + " The controls' design "
        f"({r.recordings} recordings) is simulated again with the crossed-cylinder Hertz law in "
        "series with the tube wall ('hertz_contact'), integrated as chords that differ from it "
        f"by at most {r.force_tolerance:g} N ({min(c for c, _ in r.chords.values())} to "
        f"{max(c for c, _ in r.chords.values())} chords per material). Each accuracy is on "
        "whole held-out positions over all folds, with its 95 % interval on the position; the "
        "two laws are compared on the same rows, paired."
    )
    rows = [
        [law, format_clustered(r.svm[law].folds()), format_clustered(r.mode_curves[law].folds()),
         f"{r.restrikes[law]:g}"]
        for law in LAWS
    ]
    report.table(["contact law", "SVM", "mode curves", "median re-strikes"], rows)
    report.paragraph(_verdict(r))


def restrike_words(median: float, share: float | None = None) -> str:
    """How many strikes strike again (``share``, counted, or what the median number of
    re-strikes per strike says of it), and what a re-strike does to the contact force.

    Without ``share``: a median of at least one means at least half the strikes strike again;
    one strictly between zero and one (two middle values 0 and 1) exactly half; zero, fewer
    than half.

    Examples
    --------
    >>> restrike_words(12)[:38]
    'at least half the strikes strike again'
    >>> restrike_words(0.5)[:33]
    'exactly half the strikes strike a'
    >>> restrike_words(0)[:36]
    'fewer than half the strikes strike a'
    >>> restrike_words(18, 0.976)[:40]
    '97.6 % of the strikes strike again (medi'
    """
    if share is not None:
        how_many = f"{percent(share)} of"
    else:
        how_many = ("at least half" if median >= 1 else "exactly half" if median > 0 else
                    "fewer than half")
    return (f"{how_many} the strikes strike again (median {median:g} re-strikes per strike), "
            "and a strike that strikes again has lifted off, so its contact force has passed "
            "through zero, away from the preload the spring is linearised at; how much that "
            "changes the accuracy is what the comparison below measures.")


def _verdict(r: ContactLawResult) -> str:
    """What the comparison shows, from the paired differences of the two laws.

    Examples
    --------
    >>> from ebantenna.paper.uncertainty import PairedDifference
    >>> same = PairedDifference([2, 1, 2, 1], [1, 2, 1, 2], [3] * 4, "position")
    >>> down = PairedDifference([3, 3, 2, 3], [2, 1, 1, 2], [3] * 4, "position")
    >>> r = ContactLawResult("d", 10, {}, {}, {}, {}, 0.1, {"svm": same, "mode_curves": down})
    >>> text = _verdict(r)
    >>> "changes nothing this design resolves" in text, "lowers" in text
    (True, True)
    >>> alike = PairedDifference([2, 1, 2, 1], [2, 1, 2, 1], [3] * 4, "position")
    >>> r.paired["svm"] = alike
    >>> "as many test recordings right under both laws" in _verdict(r)
    True
    """
    parts = []
    for label, key in (("the SVM", "svm"), ("the mode-curve classifier", "mode_curves")):
        pair = r.paired[key]
        if pair.identical:
            parts.append(f"{label} classifies as many test recordings right under both laws in "
                         f"every one of the {pair.n_units} {pair.unit}s, so there is no "
                         "difference between the laws to resolve")
        elif pair.resolved:
            verb = "raises" if pair.direction == "higher" else "lowers"
            parts.append(f"for {label} the Hertz law {verb} the accuracy, {pair}: the contact "
                         "law matters")
        else:
            parts.append(f"for {label} the Hertz law changes it by {pair}: the linearisation "
                         "changes nothing this design resolves")
    text = "; ".join(parts)
    return text[0].upper() + text[1:] + "."
