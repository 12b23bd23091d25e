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

Every accuracy carries its 95 % Wilson interval (:func:`ebantenna.ml.metrics.accuracy_interval`),
and each distance network the share of test contacts placed within half a contact step, with its
interval (:func:`intervals`): the numbers to compare with the same design simulated.
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

import numpy as np

from ...ml.metrics import accuracy_interval
from ...report import FigureSet, Report
from ...simulate import load_dataset
from .. import full_range, learning, material_splits, signals

__all__ = ["NOT_APPLICABLE", "reproduce_recorded", "intervals", "classification_interval",
           "placement_interval", "RECORDED_STEPS"]

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
}


def intervals(learnt, contact_step: float) -> dict:
    """The 95 % intervals of the paper's four learning results.

    Parameters
    ----------
    learnt : ebantenna.study.learning.LearningResult
    contact_step : float
        Spacing of the data set's contact positions, m: a distance estimate is *placed* when it
        lies within half of it of the truth.

    Returns
    -------
    dict
        Under ``svm`` and ``ann`` the test accuracy, its test size and interval; under
        ``linear_region`` and ``full_length`` the mean absolute error (cm), the share placed, its
        size and interval.
    """
    return {"svm": classification_interval(learnt.svm),
            "ann": classification_interval(learnt.ann),
            "linear_region": placement_interval(learnt.linear_region, contact_step),
            "full_length": placement_interval(learnt.full_length, contact_step)}


def classification_interval(result) -> dict:
    """A classifier's test accuracy, test size and 95 % Wilson interval.

    Parameters
    ----------
    result : ebantenna.paper.experiments.ClassificationResult
    """
    m = result.confusions["test"]
    correct, n = int(np.trace(m)), int(m.sum())
    return {"test_accuracy": correct / n, "n_test": n,
            "interval95": list(accuracy_interval(correct, n))}


def placement_interval(result, contact_step: float) -> dict:
    """A distance network's mean absolute error (cm) and the share of its test contacts placed
    within half a contact step (``contact_step``, m), with the share's 95 % Wilson interval.

    Parameters
    ----------
    result : ebantenna.paper.experiments.RegressionResult
    contact_step : float
    """
    errors = result.errors_cm
    placed = int(np.sum(errors <= 50.0 * contact_step))  # half a step, in cm
    return {"mae_cm": float(errors.mean()), "placed": placed / errors.size,
            "n_test": int(errors.size), "interval95": list(accuracy_interval(placed, errors.size))}


def reproduce_recorded(data, out_dir="ebantenna-recorded", *, seed: int = 0,
                       n_jobs: int | None = -1, show_progress=None) -> dict:
    """Run the recorded-data sections on the data set file ``data``; returns the summary.

    Parameters
    ----------
    data : path
        A data set file (``.npz`` of :func:`~ebantenna.simulate.load_dataset`'s format).
    out_dir : path
        Where the figures, ``report.md``, ``report.html`` and ``summary.json`` go.
    seed : int
        Seed of every split and initialisation.
    n_jobs : int or None
        joblib workers for the features (-1: all cores).
    show_progress : bool, optional
        Progress bars (default: on a terminal).

    Returns
    -------
    dict
        What ``summary.json`` holds: ``data`` (what it ran on), the sections' results as in the
        simulated study's summary, ``intervals``, ``not_applicable`` and ``timings_s``.
    """
    import matplotlib

    matplotlib.use("Agg")
    from ...paper.feature_table import signal_features

    ds = load_dataset(data)
    out_dir = Path(os.fspath(out_dir))
    out_dir.mkdir(parents=True, exist_ok=True)
    figures, seconds = FigureSet(out_dir), {}
    report = _opening(ds)

    def timed(step, fn, *args):
        start = time.perf_counter()
        result = fn(*args)
        seconds[step] = time.perf_counter() - start
        return result

    materials = tuple(dict.fromkeys(ds.material.tolist()))
    feats = timed("features", lambda: signal_features(ds.ax, ds.az, ds.fs, n_jobs=n_jobs,
                                                      show_progress=show_progress))
    results = {"frequency": timed("frequency", signals.compute_frequency, ds, feats, materials),
               "decay": timed("decay", signals.compute_decay, ds, feats, materials)}
    signals.render_frequency(results["frequency"], report, figures)
    signals.render_decay(results["decay"], report, figures)
    learnt = results["ml"] = timed("ml", learning.compute, ds, feats, seed)
    learning.render(learnt, report, figures)
    results["splits"] = timed("splits", lambda: material_splits.compute(
        ds, feats, seed, random_svm=learnt.svm, paper_ann=learnt.ann,
        paper_distance=learnt.linear_region))
    material_splits.render(results["splits"], report, figures)
    results["full range"] = timed("full range", full_range.compute, ds, feats)
    full_range.render(results["full range"], report, figures)
    summary = _summary(ds, results, seed, _contact_step(ds))
    _closing(report, summary["intervals"], seconds)
    md, page = report.write(out_dir)
    summary.update(timings_s=seconds, report={"markdown": str(md), "html": str(page)},
                   figures={k: str(v) for k, v in figures.paths.items()})
    (out_dir / "summary.json").write_text(json.dumps(summary, indent=2), encoding="utf-8")
    return summary


def _contact_step(ds) -> float:
    """The smallest spacing of the data set's contact positions, m."""
    grid = np.unique(ds.contact)
    return float(np.diff(grid).min()) if grid.size > 1 else float(grid[0])


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


def _opening(ds) -> Report:
    """The title and the paragraph that says which data the study ran on."""
    data = _data_description(ds)
    report = Report("ebantenna: the study on recorded data")
    origin = (f"recorded in the session {data['session']} (plan {data['plan']!r}, rig "
              f"{json.dumps(data['rig'])})" if data["source"] == "recordings"
              else "simulated (a data set of the package's simulator)")
    report.paragraph(
        f"Every number below comes from the data set {data['path']} (SHA-256 "
        f"{data['checksum_sha256']}): {data['signals']} recordings of {data['samples']} samples "
        f"at {data['fs']:g} Hz, {len(data['materials'])} materials x {data['contacts']} contact "
        f"positions, {origin}. The paper's value stands beside each one.")
    report.heading("Sections not applicable to recorded data")
    report.table(["section", "why not"], [[k, v] for k, v in NOT_APPLICABLE.items()])
    return report


def _closing(report: Report, found: dict, seconds: dict) -> None:
    """The intervals of the four learning results, and the run time."""
    report.heading("The learning results with their 95 % intervals")
    rows = [[name, f"{v['test_accuracy']:.3f}", str(v["n_test"]),
             f"{v['interval95'][0]:.3f} - {v['interval95'][1]:.3f}"]
            for name, v in found.items() if "test_accuracy" in v]
    rows += [[f"{name} (placed within half a step; MAE {v['mae_cm']:.2f} cm)",
              f"{v['placed']:.3f}", str(v["n_test"]),
              f"{v['interval95'][0]:.3f} - {v['interval95'][1]:.3f}"]
             for name, v in found.items() if "placed" in v]
    report.table(["result", "share", "test size", "95 % interval (Wilson)"], rows)
    report.heading("Run time")
    report.table(["step", "seconds"], [[k, f"{v:.1f}"] for k, v in seconds.items()]
                 + [["total", f"{sum(seconds.values()):.1f}"]])


def _summary(ds, results: dict, seed: int, step: float) -> dict:
    learnt, splits = results["ml"], results["splits"].to_dict()
    return {
        "data": _data_description(ds),
        "seed": seed,
        "frequency": results["frequency"].to_dict(),
        "decay": results["decay"].to_dict(),
        **learnt.to_dict(),
        "materials": splits["materials"],
        "distance": {**results["full range"].to_dict(), **learnt.distance_dict(),
                     **splits["distance"]},
        "intervals": intervals(learnt, step),
        "not_applicable": dict(NOT_APPLICABLE),
    }
