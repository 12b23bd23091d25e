"""The study on a data set of recordings: every section that needs only the recordings.

:func:`reproduce_recorded` runs, on a data set file (one assembled from a recording session by
:func:`~ebantenna.study.recorded.assemble_dataset`, or any data set in the package's format), the
sections of :func:`ebantenna.study.reproduce.reproduce` that take only recordings: the dominant
frequency against the contact distance and the decay per material (Figs. 9-11), the SVM and ANN
material classifiers and the two distance networks (Figs. 12-15), the SVM on the three splits, the
position-aware and mode-curve classifiers and the other trainers, and the contact distance over
the whole probe. The sections that need the simulator or only the probe's model are named in the
report as not applicable, with the reason (:data:`NOT_APPLICABLE`). The report opens with the data
it ran on: its file, checksum and, for an assembled data set, the session it came from.

The design is checked before any work (``check_design``): each section run on recordings has
a minimum (:data:`SECTION_MINIMUM`: materials, distinct contact positions, repetitions of each
material at each position; and records long enough for the features,
:data:`~ebantenna.study.recorded.assemble.MIN_SAMPLES`); a section whose minimum the data set
does not meet is listed as not applicable with what is missing, and the others run. A data set
too small for every section is refused, with one message that says what each needs.

Every accuracy carries its 95 % interval on the contact position, the unit the repetitions
cluster in, and each distance network the share of test contacts placed within half a contact
step, with its interval on the position too (:func:`intervals`): the numbers to compare with the
same design simulated.
"""

from __future__ import annotations

import json
import math
import time

import numpy as np

from ..._validate import check_array, check_n_jobs, check_positive
from ...paper.experiments import ClassificationResult, RegressionResult
from ...paper.uncertainty import UNITS, ClusteredAccuracy, percent, span
from ...report import FigureSet, Report
from ...simulate import load_dataset
from .. import full_range, learning, material_splits, signals
from .._common import blas_limited, study_folder
from .assemble import MIN_SAMPLES

__all__ = ["NOT_APPLICABLE", "reproduce_recorded", "intervals", "classification_interval",
           "placement_interval", "RECORDED_STEPS", "SECTION_MINIMUM"]

#: The sections run on recordings, in order.
RECORDED_STEPS = ("features", "frequency", "decay", "ml", "splits", "full range")

#: The study's other sections, and why they do not run on a data set of recordings.
NOT_APPLICABLE = {
    "modes": "an analysis of the probe's model (mode zones and shapes, the printed matrices), "
             "not of any data: it is the same for every data set",
    "hinge": "fits the probe's model to the paper's printed transition positions, not to data "
             "(calibrate the scene from recordings with 'ebantenna calibrate')",
    "controls": "the ablation of every effect, the physics controls and the equivalent pair "
                "re-simulate the data set with parts of the physics switched off: they need the "
                "simulator",
    "time-frequency": "simulates its own recordings at five positions of one material",
    "seeds": "the spread over split and initialisation seeds is measured on the simulated data "
             "set, whose design it re-draws: simulator only",
    "ann setup": "compares network set-ups on the simulated data set and its re-simulated "
                 "variants: simulator only",
    "contact law": "re-simulates the controls' design with the other contact law: simulator "
                   "only",
    "rod geometry": "re-simulates the controls' design with the touched rod's geometry varied: "
                    "simulator only",
}

#: What each section run on recordings needs at least: distinct materials, distinct contact
#: positions, repetitions of every material at every position, and recordings within the
#: distance networks' region (0.8 L), with why. ``after``: the section reuses another's results.
SECTION_MINIMUM = {
    "frequency": {"materials": 1, "positions": 2, "repetitions": 1,
                  "why": "a curve of frequency against distance needs two positions"},
    "decay": {"materials": 1, "positions": 1, "repetitions": 1, "in_region": 1,
              "why": "the decays are fitted within 0.8 L of the hinge"},
    "ml": {"materials": 2, "positions": 3, "repetitions": 2, "in_region": 10,
           "why": "the classifiers need two materials to tell apart and a test split of every "
                  "material; the distance networks three positions and ten recordings within "
                  "0.8 L"},
    "splits": {"materials": 2, "positions": 5, "repetitions": 2, "after": "ml",
               "why": "the grouped split holds out every fifth position; the mode curves need "
                      "three training positions of each material"},
    "full range": {"materials": 2, "positions": 5, "repetitions": 1,
                   "why": "calibrates on every other position (three at least) and tests on "
                          "those between; its joint estimate finds the material among two or "
                          "more"},
}


def intervals(learnt, contact_step: float) -> dict:
    """The 95 % intervals of the paper's four learning results, on the contact position.

    The repetitions at one position are near copies of each other, so the unit of every
    interval is the position (:class:`~ebantenna.paper.uncertainty.ClusteredAccuracy`); the
    interval counting every recording as independent is kept beside it, for comparison only.

    Parameters
    ----------
    learnt : ebantenna.study.learning.LearningResult
    contact_step : float
        Spacing of the data set's contact positions, m: a distance estimate is *placed* when it
        lies within half of it of the truth.

    Returns
    -------
    dict
        Under ``svm`` and ``ann`` the test accuracy (:func:`classification_interval`); under
        ``linear_region`` and ``full_length`` the mean absolute error (cm) and the share placed
        (:func:`placement_interval`).
    """
    if not isinstance(learnt, learning.LearningResult):
        raise TypeError(f"learnt must be a LearningResult (of ebantenna.study.learning), got "
                        f"{type(learnt).__name__}")
    contact_step = check_positive("contact_step", contact_step)
    return {"svm": classification_interval(learnt.svm, learnt.positions),
            "ann": classification_interval(learnt.ann, learnt.positions),
            "linear_region": placement_interval(learnt.linear_region, contact_step),
            "full_length": placement_interval(learnt.full_length, contact_step)}


def _on_the_position(share: str, measured: ClusteredAccuracy) -> dict:
    return {share: measured.estimate, "n_test": measured.n_recordings, "unit": measured.unit,
            "n_units": measured.n_units, "design_effect": measured.design_effect,
            "interval95": list(measured.ci95), "method": measured.method,
            "recording_interval95": list(measured.recording_ci95)}


def classification_interval(result, positions) -> dict:
    """A classifier's test accuracy with its 95 % interval on the contact position.

    Parameters
    ----------
    result : ebantenna.paper.experiments.ClassificationResult
    positions : array-like
        The nominal contact position of every row the classifier was given.

    Returns
    -------
    dict
        ``test_accuracy``, ``n_test`` (recordings), ``unit`` and ``n_units`` (positions),
        ``design_effect``, ``interval95`` (on the position) with its ``method``, and
        ``recording_interval95`` (Wilson's, every recording counted as independent: too narrow
        when the repetitions at a position agree).
    """
    if not isinstance(result, ClassificationResult):
        raise TypeError(f"result must be a ClassificationResult, got {type(result).__name__}")
    positions = check_array("positions", positions, ndim=1)
    rows = result.rows()
    if rows.size and int(rows.max()) >= positions.size:
        raise ValueError(f"positions must hold the position of every row the classifier was "
                         f"given (at least {int(rows.max()) + 1}), got {positions.size}")
    return _on_the_position("test_accuracy", learning.held_out_accuracy(result, positions))


def placement_interval(result, contact_step: float) -> dict:
    """A distance network's mean absolute error (cm) and the share of its test contacts placed
    within half a contact step (``contact_step``, m), with the share's 95 % interval on the
    contact position (the keys of :func:`classification_interval`, ``placed`` for the share).

    Parameters
    ----------
    result : ebantenna.paper.experiments.RegressionResult
    contact_step : float
    """
    if not isinstance(result, RegressionResult):
        raise TypeError(f"result must be a RegressionResult, got {type(result).__name__}")
    contact_step = check_positive("contact_step", contact_step)
    errors = result.errors_cm
    placed = ClusteredAccuracy.from_recordings(errors <= 50.0 * contact_step,  # half a step, cm
                                               result.distance_test, UNITS["random"])
    return {"mae_cm": float(errors.mean()), **_on_the_position("placed", placed)}


def design_of(ds) -> dict:
    """The design of a data set: its ``materials``, distinct contact ``positions``, ``samples`` per
    record, the fewest
    ``repetitions`` of a material at a position (0 if one is missing), the recordings within
    0.8 L of the hinge (``in_region``) and the contact ``spacing`` (m)."""
    from ...paper.protocol import DISTANCE_LINEAR_REGION
    from .._common import probe_length

    materials = list(dict.fromkeys(ds.material.tolist()))
    grid = np.unique(ds.contact)
    counts = [int(np.sum((ds.material == m) & (ds.contact == c))) for m in materials
              for c in grid]
    region = DISTANCE_LINEAR_REGION.region * probe_length(ds)
    return {"materials": len(materials), "positions": int(grid.size), "samples": ds.n_samples,
            "repetitions": min(counts) if counts else 0,
            "in_region": int(np.sum(ds.contact <= region)),
            "spacing": float(np.diff(grid).min()) if grid.size > 1 else math.nan}


def check_design(design: dict) -> tuple[list, dict]:
    """Which sections the design (:func:`design_of`) can run, and what the others miss.

    Every section also needs records of
    :data:`~ebantenna.study.recorded.assemble.MIN_SAMPLES` samples at least: the features are
    spectra of ``2 * fft_bins`` samples.

    Returns
    -------
    runnable : list of str
        The sections of :data:`SECTION_MINIMUM` the design meets, in order.
    missing : dict
        ``section -> reason``: what the design lacks for each other section.
    """
    if design["samples"] < MIN_SAMPLES:  # every section starts from the features
        return [], dict.fromkeys(SECTION_MINIMUM, (
            f"needs records of {MIN_SAMPLES} samples at least (has {design['samples']}): the "
            "features are spectra of that many samples"))
    runnable, missing = [], {}
    for section, need in SECTION_MINIMUM.items():
        short = [f"{need[k]} {k.replace('_', ' ')} (has {design[k]})"
                 for k in ("materials", "positions", "repetitions", "in_region")
                 if k in need and design[k] < need[k]]
        if "after" in need and need["after"] not in runnable:
            short.append(f"the {need['after']!r} section's results")
        if short:
            missing[section] = f"needs at least {', '.join(short)}: {need['why']}"
        else:
            runnable.append(section)
    return runnable, missing


def design_message(design: dict, runnable: list, missing: dict) -> str:
    """One message: the design, what each section it cannot run misses, and what still runs."""
    lines = [f"the data set has {design['materials']} material(s) x {design['positions']} "
             f"contact position(s), {design['repetitions']} repetition(s) at least; "]
    lines += [f"{section}: {why}; " for section, why in missing.items()]
    lines.append(f"sections that run: {', '.join(runnable) or 'none'}")
    return "".join(lines)


def reproduce_recorded(data, out_dir="ebantenna-recorded", *, seed: int = 0,
                       n_jobs: int | None = -1, show_progress=None, say=None) -> dict:
    """Run the recorded-data sections on the data set file ``data``; returns the summary.

    The design is checked first (``check_design``): the sections it cannot run are listed
    as not applicable with what they miss, and ``say`` is told before any work.

    Parameters
    ----------
    data : path
        A data set file (``.npz`` of :func:`~ebantenna.simulate.load_dataset`'s format).
    out_dir : path
        Where the figures, ``report.md``, ``report.html`` and ``summary.json`` go.
    seed : int
        Seed of every split and initialisation.
    n_jobs : int or None
        joblib workers for the features, at most the machine's cores (-1: all cores).
    show_progress : bool, optional
        Progress bars (default: on a terminal).
    say : callable, optional
        ``say(text)`` for the design check's message and each section as it starts.

    Returns
    -------
    dict
        What ``summary.json`` holds: ``data`` (what it ran on), ``design``, the sections'
        results as in the simulated study's summary, ``intervals`` (of the learning results
        that ran), ``not_applicable`` (every section not run, with why) and ``timings_s``.

    Raises
    ------
    ValueError
        When the design meets no section's minimum.
    """
    import matplotlib

    matplotlib.use("Agg")
    from ...paper.feature_table import signal_features

    say = say or (lambda text: None)
    n_jobs = check_n_jobs("n_jobs", n_jobs)
    out_dir = study_folder("out_dir", out_dir, make=False)  # before any work
    ds = load_dataset(data)
    design = design_of(ds)
    runnable, missing = check_design(design)
    if not runnable:
        raise ValueError(f"{data}: too small for any section of the study: "
                         f"{design_message(design, runnable, missing)}")
    if missing:
        say(design_message(design, runnable, missing))
    out_dir.mkdir(parents=True, exist_ok=True)
    figures, seconds = FigureSet(out_dir), {}
    not_applicable = {**NOT_APPLICABLE, **missing}
    report = _opening(ds, design, not_applicable)
    steps = ["features", *runnable]

    def timed(step, fn, *args):
        say(f"{step} ({steps.index(step) + 1}/{len(steps)})")
        start = time.perf_counter()
        with blas_limited():
            result = fn(*args)
        seconds[step] = time.perf_counter() - start
        return result

    feats = timed("features", lambda: signal_features(ds.ax, ds.az, ds.fs, n_jobs=n_jobs,
                                                      show_progress=show_progress))
    results = _run_sections(ds, feats, runnable, seed, report, figures, not_applicable,
                            timed, say)
    failed = [[k, v] for k, v in not_applicable.items() if v.startswith("did not run")]
    if failed:
        report.heading("Sections the data themselves did not allow")
        report.table(["section", "why not"], failed)
    summary = _summary(ds, results, seed, design, not_applicable)
    _closing(report, summary["intervals"], seconds)
    md, page = report.write(out_dir)
    summary.update(timings_s=seconds, report={"markdown": str(md), "html": str(page)},
                   figures={k: str(v) for k, v in figures.paths.items()})
    (out_dir / "summary.json").write_text(json.dumps(summary, indent=2), encoding="utf-8")
    return summary


def _run_sections(ds, feats, runnable, seed, report, figures, not_applicable, timed,
                  say) -> dict:
    """Compute and render every runnable section in order; returns their results."""
    materials = tuple(dict.fromkeys(ds.material.tolist()))
    results, learnt = {}, None

    def section(step, compute, render):
        """Compute and render one section; a requirement the design check cannot see (one the
        data themselves miss) lists it as not run, with the reason, and the others go on."""
        try:
            results[step] = timed(step, compute)
        except ValueError as exc:
            not_applicable[step] = f"did not run on this data set: {exc}"
            say(f"{step}: did not run: {exc}")
            return None
        render(results[step])
        return results[step]

    if "frequency" in runnable:
        section("frequency", lambda: signals.compute_frequency(ds, feats, materials),
                lambda r: signals.render_frequency(r, report, figures))
    if "decay" in runnable:
        section("decay", lambda: signals.compute_decay(ds, feats, materials),
                lambda r: signals.render_decay(r, report, figures))
    if "ml" in runnable:
        learnt = section("ml", lambda: learning.compute(ds, feats, seed),
                         lambda r: learning.render(r, report, figures, simulated=False))
    if "splits" in runnable and learnt is not None:
        section("splits", lambda: material_splits.compute(
            ds, feats, seed, random_svm=learnt.svm, paper_ann=learnt.ann,
            paper_distance=learnt.linear_region),
            lambda r: material_splits.render(r, report, figures, simulated=False))
    if "full range" in runnable:
        section("full range", lambda: full_range.compute(ds, feats),
                lambda r: full_range.render(r, report, figures, simulated=False))
    return results


def _data_description(ds) -> dict:
    """What the study ran on: the file, its checksum, and where its recordings came from."""
    config = ds.metadata.get("config", {})
    provenance = ds.metadata.get("provenance", {})
    return {"path": str(ds.path), "checksum_sha256": ds.metadata.get("checksum_sha256"),
            "source": config.get("source", "simulated"),
            "session": provenance.get("session"), "plan": config.get("plan", {}).get("name"),
            "rig": config.get("rig"), "signals": ds.n_signals, "samples": ds.n_samples,
            "fs": ds.fs, "materials": list(dict.fromkeys(ds.material.tolist())),
            "contacts": int(np.unique(ds.contact).size)}


def _opening(ds, design: dict, not_applicable: dict) -> Report:
    """The title, the paragraph that says which data the study ran on, and the sections that do
    not run on it."""
    data = _data_description(ds)
    report = Report("ebantenna: the study on recorded data")
    origin = (f"recorded in the session {data['session']} (plan {data['plan']!r}, rig "
              f"{json.dumps(data['rig'])})" if data["source"] == "recordings"
              else "simulated (a data set of the package's simulator)")
    report.paragraph(
        f"Every number below comes from the data set {data['path']} (SHA-256 "
        f"{data['checksum_sha256']}): {data['signals']} recordings of {data['samples']} samples "
        f"at {data['fs']:g} Hz, {len(data['materials'])} materials x {data['contacts']} contact "
        f"positions{_spacing(design)}, at least {design['repetitions']} repetitions of each, "
        f"{origin}. A section that compares with the paper puts its value beside the number.")
    report.heading("Sections not applicable to this data set")
    report.table(["section", "why not"], [[k, v] for k, v in not_applicable.items()])
    return report


def _spacing(design: dict) -> str:
    """`` x cm apart`` from the design's contact spacing (nothing for one position)."""
    return "" if math.isnan(design["spacing"]) else (
        f" at least {100 * design['spacing']:.3g} cm apart")


def _closing(report: Report, found: dict, seconds: dict) -> None:
    """The intervals of the four learning results, and the run time."""
    if found:
        report.heading("The learning results with their 95 % intervals")
    rows = [[name if "test_accuracy" in v else
             f"{name} (placed within half a step; MAE {v['mae_cm']:.2f} cm)",
             percent(v.get("test_accuracy", v.get("placed"))),
             f"{v['n_test']} ({v['n_units']})", span(v["interval95"]),
             span(v["recording_interval95"])] for name, v in found.items()]
    if rows:
        report.table(["result", "share", "test size (positions)", "95 % interval on the position",
                      "if every recording were independent"], rows)
    report.heading("Run time")
    report.table(["step", "seconds"], [[k, f"{v:.1f}"] for k, v in seconds.items()]
                 + [["total", f"{sum(seconds.values()):.1f}"]])


def _summary(ds, results: dict, seed: int, design: dict, not_applicable: dict) -> dict:
    """The summary of the sections that ran (a section not run has no key)."""
    out = {"data": _data_description(ds), "design": design, "seed": seed}
    for name in ("frequency", "decay"):
        if name in results:
            out[name] = results[name].to_dict()
    distance = {}
    if "ml" in results:
        out.update(results["ml"].to_dict())
        distance.update(results["ml"].distance_dict())
    if "splits" in results:
        splits = results["splits"].to_dict()
        out["materials"] = splits["materials"]
        distance.update(splits["distance"])
    if "full range" in results:
        distance = {**results["full range"].to_dict(), **distance}
    if distance:
        out["distance"] = distance
    out["intervals"] = (intervals(results["ml"], design["spacing"]) if "ml" in results else {})
    out["not_applicable"] = dict(not_applicable)
    return out
