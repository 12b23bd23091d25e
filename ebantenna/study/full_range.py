"""Section 7, beyond the paper: the contact distance over the whole probe from two modes, tested
on contact positions the calibration never saw, against the first-mode-only estimator."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .._validate import check_bool
from ..paper import printed
from ..paper.estimators import FrequencyDistanceEstimator, MultiModeDistanceEstimator
from ..paper.mode_curves import ModeCurveClassifier
from ..paper.protocol import DISTANCE_LINEAR_REGION
from ..paper.uncertainty import (
    ClusteredAccuracy,
    clustered_entries,
    format_clustered,
    percent,
)
from ._common import (
    check_render,
    check_step,
    error_entry,
    format_error,
    format_mae,
    format_paired_mae,
    mae_entry,
    paired_mae,
    per_contact,
    probe_length,
)

__all__ = ["FullRangeResult", "compute", "render"]


@dataclass(frozen=True, eq=False)
class FullRangeResult:
    """Errors of the two distance estimators on the held-out contact positions.

    Attributes
    ----------
    length : float
        Probe length, m.
    region : float
        End of the paper's usable region, fraction of the length.
    contact_two, error_two_cm : ndarray
        Contacts (m) and absolute errors (cm) of the two-mode estimate.
    contact_one, error_one_cm : ndarray
        The same for the first-mode-only estimate.
    error_known_material_cm : ndarray
        Absolute errors (cm) of the two-mode estimate calibrated per material, for the same test
        recordings as ``error_two_cm``, with each recording's material taken as known.
    error_joint_cm : ndarray
        The same with the material fitted together with the distance from the two peaks
        (:class:`~ebantenna.paper.mode_curves.ModeCurveClassifier`), nothing taken as known.
    joint_material_accuracy : float
        How often that fit found the right material.
    turning_point : float
        Where the calibrated first-mode curve turns, m: its highest calibration point, which is
        the last one where the curve rises over the whole calibrated range.
    without_two_peaks, recordings : int
        Recordings with fewer than two separable peaks, and all recordings.
    joint_material : ClusteredAccuracy
        ``joint_material_accuracy`` with its interval on the held-out position.
    chance : float or None
        Guessing among the tested materials, ``1 / n_materials``.
    """

    length: float
    region: float
    contact_two: np.ndarray
    error_two_cm: np.ndarray
    contact_one: np.ndarray
    error_one_cm: np.ndarray
    error_known_material_cm: np.ndarray
    error_joint_cm: np.ndarray
    joint_material_accuracy: float
    turning_point: float
    without_two_peaks: int
    recordings: int
    joint_material: ClusteredAccuracy = None
    chance: float | None = None
    calibrated_to: float | None = None

    @property
    def beyond(self) -> np.ndarray:
        """Which two-mode test contacts lie beyond the region."""
        return self.contact_two > self.region * self.length

    @property
    def two_against_one_mode(self) -> dict | None:
        """The two-mode errors against the first mode's alone, paired on the same test
        recordings (``paired_mae``); None where some recordings had
        no two separable peaks, so that the two estimators were tested on different rows."""
        if self.without_two_peaks or not np.array_equal(self.contact_one, self.contact_two):
            return None
        return paired_mae(self.error_two_cm, self.error_one_cm, self.contact_two)

    @property
    def known_material_gain(self) -> dict:
        """How much larger the two-mode errors are with one calibration for every material than
        calibrated per material, paired on the same test recordings and taken on the test
        positions (``paired_mae``)."""
        return paired_mae(self.error_two_cm, self.error_known_material_cm, self.contact_two)

    @property
    def estimators(self) -> tuple:
        """The four estimators of the table: each its summary key, its row's name, its errors
        (cm) and its test contacts (m)."""
        return (
            ("first_mode_only", "first mode only", self.error_one_cm, self.contact_one),
            ("full_range", "two modes", self.error_two_cm, self.contact_two),
            ("full_range_known_material", "two modes, calibrated per material (material known)",
             self.error_known_material_cm, self.contact_two),
            ("full_range_joint", "two modes, material fitted with the distance",
             self.error_joint_cm, self.contact_two),
        )

    @cached_property
    def tails(self) -> dict:
        """Per estimator (by its key of :attr:`estimators`): ``"beyond"``, its mean error beyond
        the region (``mae_entry`` on the test contacts there; None if none lies there), and
        ``"p95"``, the 95th percentile of its errors (``error_entry``, a bootstrap over the
        test positions). Each interval is on the test position."""
        out = {}
        for key, _, errors, contact in self.estimators:
            beyond = contact > self.region * self.length
            out[key] = {
                "beyond": mae_entry(errors[beyond], contact[beyond]) if np.any(beyond) else None,
                "p95": error_entry(errors, contact, "p95"),
            }
        return out

    def to_dict(self) -> dict:
        """The summary numbers, in cm."""
        beyond = self.beyond
        tails = self.tails
        return {
            "full_range_mae_cm": float(self.error_two_cm.mean()),
            "full_range_mae_beyond_80_cm": (
                float(self.error_two_cm[beyond].mean()) if np.any(beyond) else None
            ),
            "first_mode_only_mae_cm": float(self.error_one_cm.mean()),
            "full_range_known_material_mae_cm": float(self.error_known_material_cm.mean()),
            "full_range_joint_mae_cm": float(self.error_joint_cm.mean()),
            # each with its interval over the test positions (their repetitions are near copies)
            "full_range": mae_entry(self.error_two_cm, self.contact_two),
            "first_mode_only": mae_entry(self.error_one_cm, self.contact_one),
            "full_range_known_material": mae_entry(self.error_known_material_cm,
                                                   self.contact_two),
            "full_range_joint": mae_entry(self.error_joint_cm, self.contact_two),
            "one_calibration_against_known_material": self.known_material_gain,
            "two_modes_against_first_mode": self.two_against_one_mode,
            **clustered_entries("full_range_joint_material_accuracy", self.joint_material),
            "first_mode_turning_point_cm": 100 * self.turning_point,
            "first_mode_calibrated_to_cm": (None if self.calibrated_to is None
                                            else 100 * self.calibrated_to),
            "recordings_without_two_peaks": self.without_two_peaks,
            # the table's other columns, each with its interval on the test position: the mean
            # error beyond the region (t over the positions there) and the 95th percentile
            # (position bootstrap). Each key is spelled out: the docs' paper map finds a stored
            # key by its literal name in the study's source.
            "first_mode_only_beyond_80": tails["first_mode_only"]["beyond"],
            "full_range_beyond_80": tails["full_range"]["beyond"],
            "full_range_known_material_beyond_80": tails["full_range_known_material"]["beyond"],
            "full_range_joint_beyond_80": tails["full_range_joint"]["beyond"],
            "first_mode_only_p95": tails["first_mode_only"]["p95"],
            "full_range_p95": tails["full_range"]["p95"],
            "full_range_known_material_p95": tails["full_range_known_material"]["p95"],
            "full_range_joint_p95": tails["full_range_joint"]["p95"],
        }


def compute(ds, feats) -> FullRangeResult:
    """Calibrate on every other contact position, test on the ones in between."""
    check_step(ds=ds, feats=feats)
    grid = np.unique(ds.contact)
    # The estimate must interpolate, it cannot just recognise a position it has seen.
    calibration = np.isin(ds.contact, grid[::2])
    ok = np.all(np.isfinite(feats.peaks), axis=1)
    multi = MultiModeDistanceEstimator().fit(
        feats.peaks[calibration & ok], ds.contact[calibration & ok]
    )
    test = ~calibration & ok
    error_cm = 100 * np.abs(multi.predict(feats.peaks[test]) - ds.contact[test])
    # The touched rod moves the modes by material: one calibration per material.
    known = np.empty(int(test.sum()))
    for name in np.unique(ds.material[test]):
        mine = ds.material == name
        per_material = MultiModeDistanceEstimator().fit(
            feats.peaks[calibration & ok & mine], ds.contact[calibration & ok & mine]
        )
        rows = mine[test]
        known[rows] = 100 * np.abs(
            per_material.predict(feats.peaks[test & mine]) - ds.contact[test & mine]
        )
    # Nothing known: material and distance fitted together on each material's curves.
    fit = calibration & ok
    joint = ModeCurveClassifier().fit(feats.peaks[fit], ds.material[fit], ds.contact[fit])
    material, distance = joint.place(feats.peaks[test])  # each row's curves found once
    joint_cm = 100 * np.abs(distance - ds.contact[test])
    joint_accuracy = float(np.mean(material == ds.material[test]))
    joint_measured = ClusteredAccuracy.from_recordings(material == ds.material[test],
                                                       ds.contact[test], "position")
    single = FrequencyDistanceEstimator(out_of_range="clip").fit(
        feats.dominant[calibration], ds.contact[calibration]
    )
    test1 = ~calibration
    error1_cm = 100 * np.abs(single.predict(feats.dominant[test1]) - ds.contact[test1])
    return FullRangeResult(
        length=probe_length(ds),
        region=DISTANCE_LINEAR_REGION.region,
        contact_two=ds.contact[test],
        error_two_cm=error_cm,
        contact_one=ds.contact[test1],
        error_one_cm=error1_cm,
        error_known_material_cm=known,
        error_joint_cm=joint_cm,
        joint_material_accuracy=joint_accuracy,
        turning_point=single.limit_,
        without_two_peaks=int((~ok).sum()),
        recordings=int(ok.size),
        joint_material=joint_measured,
        chance=1 / np.unique(ds.material[test]).size,
        calibrated_to=float(single.distances_[-1]),
    )


def _step_cm(r: FullRangeResult) -> str:
    """The calibration positions' spacing, cm: twice the data's, read from the test positions
    (every other one)."""
    grid = np.unique(r.contact_two)
    return f"{100 * np.diff(grid).min():.3g}" if grid.size > 1 else "?"


def render(result: FullRangeResult, report, figures, *, simulated: bool = True) -> None:
    """The error along the probe, one mode against two, and its table (``simulated``: the data
    come from the simulator, and the report names the assumptions it reads them through)."""
    check_render(result, FullRangeResult, report, figures)
    check_bool("simulated", simulated)
    r = result
    name = _plot_error_along_probe(r, figures)
    report.heading("Beyond the paper: contact distance over the whole probe")
    report.paragraph(
        "Where the first mode's frequency rises and then falls along the probe, it cannot place a "
        f"contact beyond its turning point. {_turning_point_text(r)} The second estimator "
        "takes the two strongest spectral peaks together, on the premise that the pair is "
        "unique along the whole length: each is calibrated against distance (median over "
        "recordings) and a new recording is placed where both fit best. Calibration uses every "
        f"other contact position ({_step_cm(r)} cm apart), the test the positions in between, "
        "which the calibration never saw. " + _two_against_one_text(r.two_against_one_mode)
    )
    report.table(
        ["estimator", "range", "MAE (95 % CI over the test positions)",
         f"MAE beyond {r.region:g} L (95 % CI over the test positions there)",
         "95th percentile (cm, 95 % CI: bootstrap over the test positions)"],
        _error_rows(r),
    )
    report.paragraph(
        ("In the simulator the touched rod is part of the vibrating system (by assumption, the "
         "'object_modes' effect), and each material moves the coupled modes by its own amount; "
         if simulated else "The touched object can move the probe's modes by an amount of its "
         "own; ")
        + "whether one calibration for all materials suffers from it is measured here. "
        "Calibrated per material (the material taken as known), the two-mode estimate errs by "
        f"{format_mae(mae_entry(r.error_known_material_cm, r.contact_two))}; "
        + _known_material_verdict(r.known_material_gain, simulated) + " " + _joint_text(r)
    )
    report.paragraph(
        f"Paper: the earlier ANN reached about {printed.PRIOR_DISTANCE_ACCURACY_CM.value} cm on "
        "the first 75-80 % of the probe. Recordings without two separable peaks: "
        f"{r.without_two_peaks} of {r.recordings} (left out of the two-mode estimate and counted "
        "here)."
    )
    report.figure(name, "Mean absolute error along the probe: one mode against two")


def _plot_error_along_probe(r: FullRangeResult, figures) -> str:
    """The mean absolute error at each test contact, one mode against two."""
    import matplotlib.pyplot as plt

    pos, mae, _ = per_contact(r.error_two_cm, r.contact_two)
    pos1, mae1, _ = per_contact(r.error_one_cm, r.contact_one)
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.semilogy(100 * pos1, mae1, ".-", label="first mode only (the paper's feature)")
    ax.semilogy(100 * pos, mae, ".-", label="two modes (full range)")
    ax.axvline(100 * r.turning_point, color="0.5", ls="--", lw=1, label="turning point of f1")
    ax.set_xlabel("contact distance (cm)")
    ax.set_ylabel("mean absolute error (cm)")
    ax.legend(fontsize="small")
    ax.set_title("Contact distance along the whole probe")
    return figures.save(fig, "beyond_full_range_distance")


def _turning_point_text(r: FullRangeResult) -> str:
    """Whether the first mode's calibrated curve turns inside the calibrated range, read from
    it: a curve whose highest point is its last calibration position has shown no turn (it may
    turn beyond, where nothing was calibrated).

    Examples
    --------
    >>> from types import SimpleNamespace as S
    >>> r = S(contact_one=np.array([0.05, 0.375]), turning_point=0.325, calibrated_to=0.325)
    >>> text = _turning_point_text(r)
    >>> text.split(": ")[0]
    'Here its calibrated curve is highest at its last calibration position (32.5 cm)'
    >>> text.split(". ")[-1]
    'The tested positions beyond it, up to 37.5 cm, lie outside that range.'
    >>> _turning_point_text(S(contact_one=np.array([0.05, 0.375]), turning_point=0.30,
    ...                       calibrated_to=0.35)).split(":")[0]
    'Here its calibrated curve turns at 30.0 cm, inside the calibrated range (up to 35.0 cm)'
    """
    last = float(np.max(r.contact_one))
    end = r.calibrated_to if r.calibrated_to is not None else last
    if r.turning_point < end - 1e-9:
        return (f"Here its calibrated curve turns at {100 * r.turning_point:.1f} cm, inside the "
                f"calibrated range (up to {100 * end:.1f} cm): the first mode alone cannot place "
                "a contact beyond it.")
    text = (f"Here its calibrated curve is highest at its last calibration position "
            f"({100 * end:.1f} cm): no turning point lies inside the calibrated range (the "
            "curve need not rise at every position on the way: where it dips, the estimator keeps "
            "the highest value reached so far).")
    if last > end + 1e-9:
        text += (f" The tested positions beyond it, up to {100 * last:.1f} cm, lie outside that "
                 "range.")
    return text


def _two_against_one_text(d: dict | None) -> str:
    """The two-mode estimate against the first mode's alone, from their paired difference.

    Examples
    --------
    >>> d = {"difference_cm": 0.4, "ci95": [0.1, 0.7], "n_units": 39, "resolved": True}
    >>> _two_against_one_text(d).split(" (")[0]
    'On the same test recordings the two modes err by 0.40 cm more than the first mode alone'
    >>> "not resolved" in _two_against_one_text(dict(d, ci95=[-0.2, 0.7], resolved=False))
    True
    >>> "less" in _two_against_one_text(dict(d, difference_cm=-0.4, ci95=[-0.7, -0.1]))
    True
    """
    if d is None:
        return ("The two estimators were tested on different recordings (some had no two "
                "separable peaks), so they are not compared.")
    if d["ci95"] is None:
        return (f"On the one test position the two modes err by {d['difference_cm']:+.2f} cm "
                "against the first mode alone, which gives no interval.")
    said = ("On the same test recordings the two modes err by "
            + format_paired_mae(d, "the first mode alone"))
    return said + (": resolved." if d["resolved"] else ": not resolved.")


def _joint_text(r: FullRangeResult) -> str:
    """What the two peaks placed on every material's curves find, from its interval against
    chance."""
    accuracy = format_clustered(r.joint_material)
    if r.chance is not None and r.joint_material.ci95[0] > r.chance:
        found = f"find the material too, right in {accuracy} of these recordings"
    elif r.chance is not None:
        found = (f"name the right material in {accuracy} of these recordings, an interval that "
                 f"reaches chance ({percent(r.chance)})")
    else:
        found = f"name the right material in {accuracy} of these recordings"
    joint = format_mae(mae_entry(r.error_joint_cm, r.contact_two))
    return ("Placed on every material's curves at once (the mode-curve classifier of the "
            f"section above), the two peaks {found}, and place the contact within {joint}.")


def _known_material_verdict(gain: dict, simulated: bool = True) -> str:
    """What knowing the material gains the two-mode estimate, from the paired difference.

    Examples
    --------
    >>> gain = {"difference_cm": 2.3, "ci95": [1.9, 2.7], "n_units": 39, "resolved": True}
    >>> _known_material_verdict(gain).split(" (")[0]
    'one calibration for all materials errs by 2.30 cm more'
    >>> "must know what it touched" in _known_material_verdict(gain)
    True
    >>> "does not show" in _known_material_verdict(dict(gain, ci95=[-0.1, 0.4], resolved=False))
    True
    """
    if gain["ci95"] is None:
        return (f"one calibration for all materials errs by {gain['difference_cm']:+.2f} cm "
                "against it on one test position, which gives no interval.")
    said = "one calibration for all materials errs by " + format_paired_mae(gain)
    if gain["resolved"] and gain["difference_cm"] > 0:
        return said + (": the simulated probe must know what it touched to know where (a "
                       "statement about the simulator's assumed rods, not about the rig)."
                       if simulated else ": on these recordings the probe must know what it "
                       "touched to know where.")
    if gain["resolved"]:
        return said + ": knowing the material makes the estimate worse here."
    return said + ": this design does not show that knowing the material helps."


def _error_rows(r: FullRangeResult) -> list[list[str]]:
    """One row per estimator: its MAE over the whole probe, beyond the first mode's region
    (``-`` if no test contact lies there) and its 95th percentile, in cm, each with its interval
    on the test position (:attr:`FullRangeResult.tails`)."""
    tails = r.tails
    return [
        [
            name,
            "whole probe",
            format_mae(mae_entry(errors, contact)),
            "-" if tails[key]["beyond"] is None else format_mae(tails[key]["beyond"]),
            format_error(tails[key]["p95"], "p95"),
        ]
        for key, name, errors, contact in r.estimators
    ]
