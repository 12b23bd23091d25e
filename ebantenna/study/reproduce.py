"""The main job: the whole study, the paper beside its reproduction, and one step beyond it.

:func:`reproduce` runs, in order,

1. the modal analysis of the probe: the dominant mode's zones along the probe and its mode shapes
   (Figs. 16 and 17), the paper's two-element model against fine meshes and the exact solution,
   and the errata of the printed matrices; one hinge stiffness and tip mass fitted to both of
   the paper's probe lengths;
2. the simulated data set (built once, then reused from its cache);
3. the signal features of every recording (in parallel through :class:`joblib.Parallel`);
4. the dominant frequency against the contact distance per material and its spread (Figs. 9, 10);
5. the gain and time constant of the band-passed decay per material (Fig. 11);
6. the SVM and ANN material classifiers with their confusion matrices beside the paper's
   (Figs. 12 and 15) and the two distance networks (Figs. 13 and 14); the SVM on three splits
   (random recordings, whole positions held out interleaved, a contiguous range held out) beside
   a position-aware classifier that estimates the contact distance first; the networks with
   other trainers (SCG, Adam); the classifiers over five split seeds and the grouped SVM
   against the repetitions per position; the paper network's training budget; what the
   classifier learns: the ablation of every effect of the scene and two equivalent pairs, over
   five split seeds; the touched rod's diameter and free length varied;
7. beyond the paper: the contact distance over the *whole* probe from two modes, tested on
   contact positions that the calibration never saw, against the first-mode-only estimator
   (which of the two errs less, and where, is the report's paired comparison, not assumed
   here);
8. spectrograms and scalograms at 0.25 L ... 0.9 L (Figs. 18 and 19);

and writes every figure as PNG, a report in Markdown and HTML, and a JSON summary. Every test
accuracy comes with its number of test recordings, its unit of replication (the contact
position; the held-out block for the blocked split) and the 95 % interval on that unit with its
method; the grouped and blocked splits over all their folds; every comparison paired on the same
recordings, with its interval, its verdict and the difference its design detects
(:mod:`ebantenna.paper.uncertainty`). Training accuracies carry their count only.

Each section is a module with a pure ``compute(...)`` returning a frozen result (with
``to_dict()``) and a ``render(result, report, figures)`` that draws its figures and writes its
part of the report; :func:`reproduce` only runs them in order, and ``summary.json`` is the
results' dictionaries put together.
"""

from __future__ import annotations

import json
import logging
import os
import time
from dataclasses import dataclass
from pathlib import Path

from .._progress import progress
from .._validate import check_bool, check_int, check_n_jobs, output_dir
from ..report import FigureSet, Report
from . import (
    ann_setup,
    contact_law,
    data_summary,
    full_range,
    hinge_fit,
    learning,
    material_splits,
    mode_zones,
    physics_controls,
    rod_geometry,
    seed_spread,
    signals,
    time_frequency,
)
from ._common import (  # noqa: F401 (MAX_SEED, REPORT_FILES: the CLI)
    MAX_SEED,
    REPORT_FILES,
    blas_limited,
    fits_in_parallel,
    study_folder,
)

__all__ = ["StudyResult", "reproduce", "default_cache_dir"]

log = logging.getLogger(__name__)

#: The steps of the study, timed one by one, in order.
STEPS = ("modes", "hinge", "data set", "features", "frequency", "decay", "ml", "splits",
         "seeds", "ann setup", "controls", "contact law", "rod geometry", "full range",
         "time-frequency")


def default_cache_dir() -> Path:
    """Where data sets are cached: ``$EBANTENNA_CACHE``, else ``~/.cache/ebantenna``.

    The path is made absolute (``~`` expanded, a relative one taken from the current directory
    when this is called), so that what is reported and reused does not change with a later
    change of directory.

    Examples
    --------
    >>> default_cache_dir().is_absolute()
    True
    """
    env = os.environ.get("EBANTENNA_CACHE")
    path = Path(env).expanduser() if env else Path.home() / ".cache" / "ebantenna"
    return path.absolute()


@dataclass(frozen=True, eq=False)
class StudyResult:
    """Outcome of :func:`reproduce`.

    Attributes
    ----------
    summary : dict
        JSON-serialisable numbers (``svm.test_accuracy``, ``ann.test_accuracy``,
        ``distance.full_range_mae_cm``; under ``materials`` the SVM on the three splits
        ``svm_random_test_accuracy``, ``svm_grouped_test_accuracy``,
        ``svm_blocked_test_accuracy``, ``position_aware_test_accuracy``,
        ``mode_curve_test_accuracy``, ``ann`` by trainer,
        ``ablation`` and ``equivalent_pair_accuracy``; ``hinge``; ``timings_s``, ...), accuracies
        as fractions.
    out_dir : Path
        Where the figures and the report were written.
    figures : dict of str to Path
        Every PNG written.
    report_markdown, report_html : Path
    """

    summary: dict
    out_dir: Path
    figures: dict
    report_markdown: Path
    report_html: Path


class _Timer:
    """Wall time of each step, with a progress bar over the steps."""

    def __init__(self, show_progress):
        self.seconds: dict[str, float] = {}
        self._bar = progress(total=len(STEPS), desc="study", enabled=show_progress)

    def run(self, name, fn, *args):
        self._bar.set_postfix_str(name)
        start = time.perf_counter()
        with blas_limited():
            out = fn(*args)
        self.seconds[name] = time.perf_counter() - start
        self._bar.update()
        log.info("%s done in %.1f s", name, self.seconds[name])
        return out

    def close(self):
        self._bar.close()


class _Sections:
    """Each section of the study in turn: its ``compute`` timed as one step, its ``render``
    writing its figures and its part of the report; the results kept by step."""

    def __init__(self, timer: _Timer, report: Report, figures: FigureSet):
        self.timer, self.report, self.figures = timer, report, figures
        self.results: dict = {}

    def run(self, step: str, compute, render, *args):
        result = self.results[step] = self.timer.run(step, compute, *args)
        render(result, self.report, self.figures)
        return result


def reproduce(
    out_dir="ebantenna-output",
    *,
    quick: bool = False,
    seed: int = 0,
    n_jobs: int | None = -1,
    cache_dir=None,
    show_progress=None,
) -> StudyResult:
    """Run the whole study and write its figures and report.

    Parameters
    ----------
    out_dir : path
        Where the PNG figures, ``report.md``, ``report.html`` and ``summary.json`` go.
    quick : bool
        The small data set (contacts every 5 cm, 3 repetitions) and coarser sweeps: well under a
        minute, for tests and the documentation. Its numbers are not the study's.
    seed : int
        Seed of the data set and of every split and initialisation, 0 ... ``MAX_SEED``.
    n_jobs : int or None
        joblib workers for the data set and the features, at most the machine's cores
        (``-1``: all cores).
    cache_dir : path, optional
        Data set cache; default :func:`default_cache_dir`.
    show_progress : bool, optional
        Progress bars (default: on a terminal).

    Returns
    -------
    StudyResult
    """
    import matplotlib

    matplotlib.use("Agg")
    from ..paper.data import build_paper_dataset
    from ..paper.feature_table import signal_features
    from ..simulate import builtin_scene

    seed, quick = _checked_options(seed, quick, n_jobs)
    out_dir, cache_dir = _folders(out_dir, cache_dir)
    figures = FigureSet(out_dir)
    report = _opening(quick)
    scene = builtin_scene("paper")
    workers = (os.cpu_count() or 1) if n_jobs is None or n_jobs < 0 else n_jobs
    timer = _Timer(show_progress)
    study = _Sections(timer, report, figures)

    study.run("modes", mode_zones.compute, mode_zones.render, scene.probe, quick)
    study.run("hinge", hinge_fit.compute, hinge_fit.render, scene.probe, quick, workers)
    before = {p: p.stat().st_mtime_ns for p in cache_dir.glob("*.npz")}
    ds = timer.run(
        "data set",
        lambda: build_paper_dataset(cache_dir, seed=seed, quick=quick, n_jobs=workers,
                                    show_progress=show_progress),
    )
    data_result = study.results["data set"] = data_summary.compute(ds)
    feats = timer.run(
        "features",
        lambda: signal_features(ds.ax, ds.az, ds.fs, n_jobs=n_jobs, show_progress=show_progress),
    )
    data_summary.render(data_result, report, figures)
    _learn_materials_and_distance(study, ds, feats, data_result.materials, seed, quick, workers)
    controls = _controls(study, scene, seed, quick, cache_dir, workers)
    study.run("full range", full_range.compute, full_range.render, ds, feats)
    study.run("time-frequency", time_frequency.compute, time_frequency.render, scene, seed)
    timer.close()

    cached = before.get(ds.path) == ds.path.stat().st_mtime_ns
    _run_time(report, timer.seconds, workers, cached, ds.path.name,
              controls.data_sets + int(study.results["contact law"] is not None))
    md, page = report.write(out_dir)
    summary = {
        "quick": quick,
        "seed": seed,
        **_summary(study.results),
        "timings_s": dict(timer.seconds),
        "dataset_cached": cached,
        "report": {"markdown": str(md), "html": str(page)},
        "figures": {k: str(v) for k, v in figures.paths.items()},
    }
    (out_dir / "summary.json").write_text(json.dumps(summary, indent=2), encoding="utf-8")
    return StudyResult(summary, out_dir, dict(figures.paths), md, page)


def _checked_options(seed, quick, n_jobs) -> tuple[int, bool]:
    """``seed`` and ``quick`` checked; ``n_jobs`` -1, None or a count >= 1, at most the cores."""
    seed = check_int("seed", seed, minimum=0, maximum=MAX_SEED)
    quick = check_bool("quick", quick)
    check_n_jobs("n_jobs", n_jobs)
    return seed, quick


def _folders(out_dir, cache_dir) -> tuple[Path, Path]:
    """The output folder, made if missing, and the cache (default :func:`default_cache_dir`),
    both checked before any work (a file in the folder's place, a folder that cannot be
    written, a directory where the report or the summary goes)."""
    cache_dir = output_dir("cache_dir", default_cache_dir() if cache_dir is None else cache_dir)
    return study_folder("out_dir", out_dir), cache_dir


def _opening(quick: bool) -> Report:
    """The report's title and its first paragraph: where every number comes from."""
    report = Report("ebantenna: the study reproduced" + (" (quick run)" if quick else ""))
    report.paragraph(
        "Every number below comes from the simulated probe (scene 'paper'), not from the paper's "
        "recordings; a section that compares with the paper puts its value beside the number. "
        + ("This is the quick run: a small data set, numbers only indicative." if quick else "")
    )
    return report


def _learn_materials_and_distance(study: _Sections, ds, feats, materials, seed: int,
                                  quick: bool = False, workers: int = 1) -> None:
    """Steps 4 to 6: the dominant frequency and the decay per material, the paper's classifiers
    and distance networks, and the same on the three splits and with other trainers (their
    independent fits on ``workers`` processes)."""
    study.run("frequency", signals.compute_frequency, signals.render_frequency,
              ds, feats, materials)
    study.run("decay", signals.compute_decay, signals.render_decay, ds, feats, materials)
    setup_calls = ann_setup.fit_calls(ds, feats, seed, quick, paper_ann_given=True)
    setup_fits: dict = {}
    learnt = study.run("ml", _ml_with, learning.render, ds, feats, seed, setup_calls, setup_fits,
                       workers)
    study.run(
        "splits",
        lambda: material_splits.compute(ds, feats, seed, random_svm=learnt.svm,
                                        paper_ann=learnt.ann, paper_distance=learnt.linear_region,
                                        n_jobs=workers),
        material_splits.render,
    )
    grouped = study.results["splits"].measured["svm", "grouped"]
    answers = study.results["splits"].grouped_answers["svm"]
    study.run("seeds", lambda: seed_spread.compute(ds, feats, seed, grouped, workers,
                                                   grouped_answers=answers),
              seed_spread.render)
    study.run("ann setup",
              lambda: ann_setup.from_fits(ds, feats, seed, setup_fits, paper_ann=learnt.ann),
              ann_setup.render)


def _ml_with(ds, feats, seed: int, setup_calls: dict, setup_fits: dict, workers: int):
    """The 'ml' step's fits (:func:`.learning.fit_calls`), with the 'ann setup' step's
    ``setup_calls`` queued behind them on the same ``workers``: the paper network's 1000 epochs
    would leave the second worker idle for about half the step. The setup's results go into
    ``setup_fits``, by name; the numbers are those of each step fitting alone."""
    calls = learning.fit_calls(ds, feats, seed)
    fits = fits_in_parallel(calls + list(setup_calls.values()), workers)
    setup_fits.update(zip(setup_calls, fits[len(calls):], strict=True))
    return learning.from_fits(ds, fits[: len(calls)])


def _controls(study: _Sections, scene, seed: int, quick: bool, cache_dir, workers: int):
    """The controls, the two contact laws and the rod's geometry varied: the small data sets
    rebuilt and measured."""
    controls = study.run("controls", physics_controls.compute, physics_controls.render,
                         scene, seed, quick, cache_dir, workers)
    study.run("contact law", contact_law.compute, contact_law.render,
              scene, seed, quick, cache_dir, workers)
    study.run("rod geometry", rod_geometry.compute, rod_geometry.render,
              scene, seed, quick, cache_dir, workers)
    return controls


def _run_time(report: Report, seconds: dict, workers: int, cached: bool, dataset: str,
              control_sets: int) -> None:
    """The last section: the wall time of every step, and whether the data set was cached."""
    report.heading("Run time")
    report.paragraph(
        f"Wall time of every step on {workers} worker(s). The data set was "
        + ("reused from its cache" if cached else "simulated in this run")
        + f" ({dataset}); the controls and the contact law rebuild {control_sets} small "
        "data sets, and the rod's geometry a few more, cached likewise. The ANN setup's networks "
        "train in the ml step, beside the paper's network; its own row is their assembly."
    )
    report.table(["step", "seconds"], [[k, f"{v:.1f}"] for k, v in seconds.items()]
                 + [["total", f"{sum(seconds.values()):.1f}"]])


def _summary(results: dict) -> dict:
    """The sections' results put together as ``summary.json`` holds them (timings aside)."""
    learnt, splits = results["ml"], results["splits"].to_dict()
    return {
        "modes": results["modes"].to_dict(),
        "dataset": results["data set"].to_dict(),
        "frequency": results["frequency"].to_dict(),
        "decay": results["decay"].to_dict(),
        **learnt.to_dict(),
        "materials": {
            **splits["materials"],
            **results["seeds"].to_dict(),
            **results["ann setup"].to_dict(),
            **results["controls"].to_dict(),
            **(results["rod geometry"].to_dict() if results["rod geometry"] else {}),
        },
        "distance": {**results["full range"].to_dict(), **learnt.distance_dict(),
                     **splits["distance"]},
        "hinge": results["hinge"].to_dict(),
        "contact_law": None if results["contact law"] is None else results["contact law"].to_dict(),
        **results["time-frequency"].to_dict(),
    }
