"""Small helpers shared by the study's sections (private)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from joblib import Parallel, delayed

from .._threads import limited_threads
from .._validate import (
    check_bool,
    check_int,
    check_n_jobs,
    describe,
    output_dir,
    output_file_in,
)
from ..paper import experiments
from ..paper.feature_table import SignalFeatures
from ..paper.mode_curves import classify_materials_by_mode_curves
from ..paper.position_aware import classify_materials_position_aware
from ..paper.uncertainty import cluster_mean_interval
from ..probe import Probe
from ..report import FigureSet, Report
from ..simulate import Dataset, Scene

__all__ = ["beyond_chance", "per_contact", "probe_length", "pct", "BLAS_THREADS", "blas_limited",
           "TRAINED_ONCE", "fits_in_parallel", "classifier_call", "MAX_SEED", "check_step",
           "check_instance", "check_render", "REPORT_FILES", "study_folder", "mae_entry",
           "format_mae", "paired_mae", "format_paired_mae", "listed", "ERROR_STATISTICS",
           "position_bootstrap", "error_entry", "format_error"]

#: The files a study writes into its output folder besides its figures.
REPORT_FILES = ("report.md", "report.html", "summary.json")


def study_folder(name: str, out_dir, *, make: bool = True) -> Path:
    """The output folder of a study, checked before its work starts and made if missing
    (unless ``make`` is false).

    ``out_dir`` must be a path (not a file; writable, or creatable), and no directory or FIFO
    may stand where one of ``REPORT_FILES`` goes (the finished report could not take its
    place, after hours of work); errors name ``name``.
    """
    folder = output_dir(name, out_dir)
    for file_name in REPORT_FILES:
        output_file_in(name, folder, file_name)
    if make:
        folder.mkdir(parents=True, exist_ok=True)
    return folder

#: The largest seed: scikit-learn takes 32-bit seeds, and the splits use ``seed + 1`` too.
MAX_SEED = 2**32 - 2

#: BLAS threads while a step of a study runs. Measured side by side with
#: ``python benchmarks/study_blas_threads.py`` (the quick study, two cores): no step ran faster
#: on two threads, and the learning steps (ml, splits, seeds, ANN set-up) took 1.6 to 2.3 times
#: the CPU time, and four to five times the wall time while another job ran: their products are
#: too small to gain from a second thread, and a spinning thread takes a core from the rest.
#: The full study's splits step is the exception on an idle machine (its kernel products are
#: large): 190 s on two threads against 271 s on one, for 1.26 times the CPU time. One thread
#: is kept for it too: the numbers then depend neither on the core count nor on the thread
#: count (two threads round a few kernel entries differently, enough to flip a recording within
#: the solver's tolerance of a tie), and the CPU time does not grow when the machine is busy.
BLAS_THREADS = 1


def blas_limited():
    """A context in which BLAS runs on :data:`BLAS_THREADS` threads (``threadpoolctl``)."""
    return limited_threads(BLAS_THREADS)


#: What a network's test interval holds fixed, said beside every network trained once. Its
#: training is not convex: on the data set of the compiled strike march, which differs from the
#: NumPy march's only in the strikes that chatter near the tip, the full-length distance network's
#: error moved from 2.56 to 2.88 cm (seed 0), outside its interval over the test positions
#: (``benchmarks/summary_moves.py``).
TRAINED_ONCE = ("{what} trained once, from one draw of starting weights: an interval on it holds "
                "the trained network fixed and counts the test positions' spread, not how far "
                "another training run (from other starting weights, or on data that differ "
                "slightly) would move it.")


def fits_in_parallel(calls, n_jobs: int) -> list:
    """Each call ``(function, args, kwargs)`` of ``calls`` on ``n_jobs`` worker processes
    (:class:`joblib.Parallel`), every one with BLAS on :data:`BLAS_THREADS` threads; the results
    in the order of ``calls``.

    The calls are independent fits (one fold, one classifier each) that share no state, and
    each runs single-threaded wherever it runs, so the results are those of making the calls
    in turn: the workers change the wall time, not a number.

    Examples
    --------
    >>> fits_in_parallel([(divmod, (7, 2), {}), (pow, (2,), {"exp": 3})], n_jobs=1)
    [(3, 1), 8]
    """
    if n_jobs == 1 or len(calls) < 2:
        return [_limited(f, args, kwargs) for f, args, kwargs in calls]
    return Parallel(n_jobs=min(n_jobs, len(calls)))(
        delayed(_limited)(f, args, kwargs) for f, args, kwargs in calls)


def classifier_call(classifier: str, X, y, positions, peaks, dominant, split) -> tuple:
    """The fit of one of the study's three material classifiers on one split, as a call
    ``(function, args, kwargs)`` for :func:`fits_in_parallel`: ``"svm"`` the paper's SVM
    (:func:`~ebantenna.paper.experiments.classify_materials_svm`), ``"position_aware"``
    (:func:`~ebantenna.paper.position_aware.classify_materials_position_aware`) or
    ``"mode_curves"`` (:func:`~ebantenna.paper.mode_curves.classify_materials_by_mode_curves`).
    """
    if classifier == "svm":
        return experiments.classify_materials_svm, (X, y), {"split": split}
    if classifier == "position_aware":
        return classify_materials_position_aware, (X, y, positions, peaks, dominant, split), {}
    if classifier == "mode_curves":
        return classify_materials_by_mode_curves, (peaks, dominant, y, positions, split), {}
    raise ValueError(f"classifier must be 'svm', 'position_aware' or 'mode_curves', got "
                     f"{classifier!r}")


def _limited(function, args, kwargs):
    with blas_limited():
        return function(*args, **kwargs)


def probe_length(ds) -> float:
    """Length (m) of the probe the data set was simulated with, from its own metadata."""
    return ds.metadata["config"]["scene"]["probe"]["length"]


def pct(x: float) -> str:
    """A fraction as a percentage with one decimal.

    Examples
    --------
    >>> pct(0.9917)
    '99.2 %'
    """
    return f"{100 * x:.1f} %"


def per_contact(values, contact, mask=None):
    """Median and standard deviation of ``values`` at each distinct contact distance.

    Parameters
    ----------
    values, contact : ndarray of shape (n,)
        Values and the contact distance (m) of each.
    mask : ndarray of bool, optional
        Which values to use; a contact with none left gets NaN.

    Returns
    -------
    grid, median, spread : ndarray
        Distinct contacts (m), median and standard deviation at each.

    Examples
    --------
    >>> grid, med, spread = per_contact(np.array([1.0, 3.0, 5.0]), np.array([0.1, 0.1, 0.2]))
    >>> grid.tolist(), med.tolist(), spread.tolist()
    ([0.1, 0.2], [2.0, 5.0], [1.0, 0.0])
    """
    grid = np.unique(contact)
    med = np.full(grid.size, np.nan)
    spread = np.full(grid.size, np.nan)
    for i, g in enumerate(grid):
        sel = contact == g
        if mask is not None:
            sel &= mask
        if np.any(sel):
            med[i] = np.median(values[sel])
            spread[i] = np.std(values[sel])
    return grid, med, spread


def mae_entry(errors_cm, positions) -> dict:
    """A mean absolute distance error (cm) on its unit of replication, the test position (a
    position's repetitions are near copies, not independent tests).

    Returns ``mae_cm`` (over the recordings) and, from
    :func:`~ebantenna.paper.uncertainty.cluster_mean_interval`, ``mae_cm_estimate`` (the mean of
    the positions' mean errors), ``mae_cm_ci95``, ``mae_cm_n_units``, ``mae_cm_n_test`` and
    ``mae_cm_method``; one test position gives no interval (``mae_cm_ci95`` None).

    Examples
    --------
    >>> e = mae_entry([1.0, 1.2, 3.0, 2.8], [0.1, 0.1, 0.2, 0.2])
    >>> round(e["mae_cm"], 2), e["mae_cm_n_units"], [round(v, 1) for v in e["mae_cm_ci95"]]
    (2.0, 2, [-9.4, 13.4])
    """
    errors = np.asarray(errors_cm, dtype=float)
    positions = np.asarray(positions)
    if np.unique(positions).size < 2:  # one test position: no spread to take
        return {"mae_cm": float(errors.mean()), "mae_cm_estimate": float(errors.mean()),
                "mae_cm_ci95": None, "mae_cm_n_units": 1, "mae_cm_n_test": int(errors.size),
                "mae_cm_method": "one test position: no interval"}
    return {"mae_cm": float(errors.mean()), **{
        f"mae_cm_{k}": v for k, v in cluster_mean_interval(errors, positions).items()}}


#: The error statistics :func:`error_entry` takes, by name: the root mean square and the 95th
#: percentile of the absolute errors (cm), each over the recordings it is given.
ERROR_STATISTICS = {
    "rms": lambda e: float(np.sqrt(np.mean(np.square(e)))),
    "p95": lambda e: float(np.percentile(e, 95)),
}

#: Resamples and seed of :func:`error_entry`'s position bootstrap: fixed, so that the report's
#: intervals are the same on every run; 2000 resamples put the 2.5 % and 97.5 % quantiles of the
#: bootstrap distribution on 50 draws each (Davison & Hinkley 1997, section 5.2.3).
BOOTSTRAP_RESAMPLES, BOOTSTRAP_SEED = 2000, 0
#: Fewest test positions for a 95 % interval of :func:`error_entry`. A bootstrap over ``G``
#: positions never leaves the range of their values, and that range holds even the median of
#: the positions' distribution only with probability ``1 - 2**(1 - G)`` (the chance that the
#: ``G`` draws are not all on one side of it): 93.8 % at five positions, 96.9 % at six.
BOOTSTRAP_MIN_UNITS = 6


def position_bootstrap(values, clusters, statistic, *, resamples: int = BOOTSTRAP_RESAMPLES,
                       seed: int = BOOTSTRAP_SEED, level: float = 0.95) -> tuple[float, float]:
    """Percentile interval of ``statistic(values)`` with whole clusters resampled.

    Each resample draws the ``G`` clusters (distinct labels of ``clusters``, sorted) ``G`` times
    with replacement, every cluster with all its recordings (Davison & Hinkley 1997, *Bootstrap
    Methods and their Application*, section 3.8), and takes ``statistic`` of the recordings it
    drew; the draws are ``numpy.random.default_rng(seed).integers(0, G, size=(resamples, G))``,
    the draws of :func:`~ebantenna.paper.uncertainty.cluster_bootstrap`. When every cluster holds
    one recording this is the ordinary bootstrap of the recordings.

    Parameters
    ----------
    values : array-like of float, shape (n,)
        One number per recording.
    clusters : array-like, shape (n,)
        Each recording's unit of replication (its test position); at least two distinct.
    statistic : callable
        Takes a 1-D array of values and returns a float.
    resamples : int
        10 to ``10**6``.
    seed : int
        >= 0.
    level : float
        Coverage, in (0, 1).

    Returns
    -------
    (float, float)

    Examples
    --------
    Three positions: a resample of one position three times comes one time in 27, more often
    than the 2.5 % tail, so the interval runs from the lowest position's mean to the highest's.

    >>> lo, hi = position_bootstrap([1.0, 1.2, 3.0, 2.8, 2.0, 2.2], [0, 0, 1, 1, 2, 2], np.mean)
    >>> round(lo, 6), round(hi, 6)
    (1.1, 2.9)
    """
    v = np.asarray(values, dtype=float)
    g = np.asarray(clusters)
    if v.ndim != 1 or v.shape != g.shape or v.size == 0:
        raise ValueError(f"values and clusters must be non-empty 1-D arrays of one shape, got "
                         f"{v.shape} and {g.shape}")
    if not np.all(np.isfinite(v)):
        raise ValueError("values must be finite")
    if not callable(statistic):
        raise TypeError(f"statistic must be callable, got {describe(statistic)}")
    resamples = check_int("resamples", resamples, minimum=10, maximum=10**6)
    seed = check_int("seed", seed, minimum=0)
    if not 0.0 < level < 1.0:
        raise ValueError(f"level must lie in (0, 1), got {describe(level)}")
    labels, inverse = np.unique(g, return_inverse=True)
    if labels.size < 2:
        raise ValueError("clusters must hold at least two distinct units")
    order = np.argsort(inverse.ravel(), kind="stable")
    members = np.split(v[order], np.cumsum(np.bincount(inverse.ravel()))[:-1])
    pick = np.random.default_rng(seed).integers(0, labels.size, size=(resamples, labels.size))
    stats = np.array([statistic(np.concatenate([members[i] for i in row])) for row in pick])
    tail = (1 - level) / 2
    lo, hi = np.quantile(stats, [tail, 1 - tail])
    return float(lo), float(hi)


def error_entry(errors_cm, positions, statistic: str) -> dict:
    """An error statistic of :data:`ERROR_STATISTICS` (``"rms"``, ``"p95"``) over the recordings,
    with its interval on the unit of replication, the test position: a position bootstrap
    (:func:`position_bootstrap`, :data:`BOOTSTRAP_RESAMPLES` resamples, seed
    :data:`BOOTSTRAP_SEED`), the method named.

    Returns ``{statistic}_cm``, ``{statistic}_cm_ci95``, ``{statistic}_cm_n_units``,
    ``{statistic}_cm_n_test`` and ``{statistic}_cm_method``. With fewer than
    :data:`BOOTSTRAP_MIN_UNITS` test positions no interval can hold 95 %: ``_ci95`` is None and
    ``{statistic}_cm_range`` gives the lowest and highest of the positions' own statistics.

    Examples
    --------
    >>> e = error_entry([1.0, 1.2, 3.0, 2.8, 2.0, 2.2], [0.1, 0.1, 0.2, 0.2, 0.3, 0.3], "rms")
    >>> round(e["rms_cm"], 3), e["rms_cm_n_units"], e["rms_cm_n_test"], e["rms_cm_ci95"]
    (2.165, 3, 6, None)
    >>> [round(v, 3) for v in e["rms_cm_range"]]
    [1.105, 2.902]
    """
    if statistic not in ERROR_STATISTICS:
        raise ValueError(f"statistic must be one of {', '.join(ERROR_STATISTICS)}, got "
                         f"{describe(statistic)}")
    errors = np.asarray(errors_cm, dtype=float)
    positions = np.asarray(positions)
    if errors.ndim != 1 or errors.shape != positions.shape or errors.size == 0:
        raise ValueError(f"errors_cm and positions must be non-empty 1-D arrays of one shape, "
                         f"got {errors.shape} and {positions.shape}")
    f = ERROR_STATISTICS[statistic]
    units = int(np.unique(positions).size)
    key = f"{statistic}_cm"
    entry = {key: f(errors), f"{key}_n_units": units, f"{key}_n_test": int(errors.size)}
    if units < 2:  # one test position: nothing to resample
        return {**entry, f"{key}_ci95": None,
                f"{key}_method": "one test position: no interval"}
    if units < BOOTSTRAP_MIN_UNITS:
        own = [f(errors[positions == p]) for p in np.unique(positions)]
        return {**entry, f"{key}_ci95": None, f"{key}_range": [min(own), max(own)],
                f"{key}_method": (f"{units} test positions: too few for a 95 % interval (at "
                                  f"least {BOOTSTRAP_MIN_UNITS}); the range of the positions' "
                                  f"own values")}
    return {**entry, f"{key}_ci95": list(position_bootstrap(errors, positions, f)),
            f"{key}_method": (f"percentile interval of a bootstrap over the {units} test "
                              f"positions (each drawn with all its recordings), "
                              f"{BOOTSTRAP_RESAMPLES} resamples, seed {BOOTSTRAP_SEED}")}


def format_error(entry: dict, statistic: str) -> str:
    """An :func:`error_entry` as the report's tables print it, cm.

    Examples
    --------
    >>> format_error({"rms_cm": 2.176, "rms_cm_ci95": [1.6, 2.7], "rms_cm_n_units": 3}, "rms")
    '2.18 (95 % CI 1.60 to 2.70, 3 positions)'
    >>> format_error({"p95_cm": 3.0, "p95_cm_ci95": None, "p95_cm_n_units": 1}, "p95")
    '3.00 (one test position, no interval)'
    >>> format_error({"p95_cm": 3.0, "p95_cm_ci95": None, "p95_cm_n_units": 4,
    ...               "p95_cm_range": [1.9, 5.0]}, "p95")
    '3.00 (4 positions, too few for a 95 % interval; the positions range from 1.90 to 5.00)'
    """
    key = f"{statistic}_cm"
    if entry[f"{key}_ci95"] is None:
        if entry.get(f"{key}_range") is None:
            return f"{entry[key]:.2f} (one test position, no interval)"
        lo, hi = entry[f"{key}_range"]
        return (f"{entry[key]:.2f} ({entry[f'{key}_n_units']} positions, too few for a 95 % "
                f"interval; the positions range from {lo:.2f} to {hi:.2f})")
    lo, hi = entry[f"{key}_ci95"]
    return f"{entry[key]:.2f} (95 % CI {lo:.2f} to {hi:.2f}, {entry[f'{key}_n_units']} positions)"


def format_mae(entry: dict) -> str:
    """A :func:`mae_entry` as the report prints it.

    Examples
    --------
    >>> format_mae(mae_entry([1.0, 1.2, 3.0, 2.8], [0.1, 0.1, 0.2, 0.2]))
    '2.00 cm (mean over 2 test positions 2.00 cm, 95 % CI -9.44 to 13.44)'
    """
    if entry["mae_cm_ci95"] is None:
        return f"{entry['mae_cm']:.2f} cm (one test position, no interval)"
    lo, hi = entry["mae_cm_ci95"]
    return (f"{entry['mae_cm']:.2f} cm (mean over {entry['mae_cm_n_units']} test positions "
            f"{entry['mae_cm_estimate']:.2f} cm, 95 % CI {lo:.2f} to {hi:.2f})")


def paired_mae(errors_a, errors_b, positions) -> dict:
    """How much larger the errors ``errors_a`` (cm) are than ``errors_b`` on the same test
    recordings, paired recording by recording and taken on the test positions:
    ``difference_cm`` (the mean of the positions' mean differences), ``ci95``, ``n_units``,
    ``method`` and ``resolved`` (the interval excludes 0; never from one position).

    Examples
    --------
    >>> d = paired_mae([2.0, 2.2, 3.1, 3.0, 2.5, 2.4], [1.0, 1.1, 2.0, 2.1, 1.4, 1.5],
    ...                [0.1, 0.1, 0.2, 0.2, 0.3, 0.3])
    >>> round(d["difference_cm"], 2), d["resolved"]
    (1.02, True)
    """
    a, b = (np.asarray(e, dtype=float) for e in (errors_a, errors_b))
    if a.shape != b.shape:
        raise ValueError(f"errors_a and errors_b must be paired (one shape), got {a.shape} and "
                         f"{b.shape}")
    positions = np.asarray(positions)
    if np.unique(positions).size < 2:
        return {"difference_cm": float(np.mean(a - b)), "ci95": None, "n_units": 1,
                "method": "one test position: no interval", "resolved": False}
    e = cluster_mean_interval(a - b, positions)
    return {"difference_cm": e["estimate"], "ci95": e["ci95"], "n_units": e["n_units"],
            "method": "paired on the same test recordings, " + e["method"],
            "resolved": bool(e["ci95"][0] > 0 or e["ci95"][1] < 0)}


def format_paired_mae(d: dict, than: str = "") -> str:
    """A :func:`paired_mae` difference with its interval, as the report's sentences print it
    (``than``: what it is compared with, if the sentence names it).

    Examples
    --------
    >>> format_paired_mae({"difference_cm": -0.4, "ci95": [-0.7, -0.1], "n_units": 39},
    ...                   "the first mode alone")
    '0.40 cm less than the first mode alone (paired, 95 % CI -0.70 to -0.10, 39 positions)'
    """
    lo, hi = d["ci95"]
    more = "more" if d["difference_cm"] > 0 else "less"
    return (f"{abs(d['difference_cm']):.2f} cm {more}{' than ' + than if than else ''} "
            f"(paired, 95 % CI {lo:.2f} to {hi:.2f}, {d['n_units']} positions)")


def listed(words) -> str:
    """Words as a sentence lists them: ``a``, ``a and b``, ``a, b and c``.

    Examples
    --------
    >>> listed(["a"]), listed(["a", "b"]), listed(["a", "b", "c"])
    ('a', 'a and b', 'a, b and c')
    """
    words = list(words)
    return words[0] if len(words) == 1 else ", ".join(words[:-1]) + " and " + words[-1]


def beyond_chance(accuracy: float, chance: float, n: int) -> bool:
    """Whether an accuracy on ``n`` test recordings stands more than two binomial standard
    deviations of guessing, ``2 sqrt(chance (1 - chance) / n)``, above chance.

    Examples
    --------
    >>> beyond_chance(0.30, 0.2, 1000), beyond_chance(0.30, 0.2, 30)
    (True, False)
    """
    return bool(accuracy - chance > 2 * np.sqrt(chance * (1 - chance) / n))


def check_instance(name: str, value, kind: type, *, optional: bool = False):
    """Return ``value``; a :class:`TypeError` naming ``name`` unless it is a ``kind`` (or None,
    when ``optional``).

    Examples
    --------
    >>> check_instance("result", 5, Report)
    Traceback (most recent call last):
    ...
    TypeError: result must be a Report, got 5 (int)
    """
    if not (isinstance(value, kind) or (optional and value is None)):
        also = " or None" if optional else ""
        raise TypeError(f"{name} must be a {kind.__name__}{also}, got {describe(value)} "
                        f"({type(value).__name__})")
    return value


def _check_materials(materials, ds) -> None:
    """Refuse ``materials`` unless it is a sequence of distinct names of ``ds``'s materials."""
    if isinstance(materials, str | bytes) or not hasattr(materials, "__iter__"):
        raise TypeError(f"materials must be a sequence of material names, got "
                        f"{describe(materials)} ({type(materials).__name__})")
    names = list(materials)
    if not names or not all(isinstance(m, str) for m in names):
        raise TypeError(f"materials must be a non-empty sequence of material names (str), got "
                        f"{describe(materials)}")
    if len(set(names)) < len(names):
        raise ValueError(f"materials must name each material once, got {describe(materials)}")
    if ds is not None:
        absent = [m for m in names if m not in set(ds.material.tolist())]
        if absent:
            raise ValueError(f"materials must be materials of the data set "
                             f"({', '.join(dict.fromkeys(ds.material.tolist()))}); "
                             f"{', '.join(map(repr, absent))} is not")


#: The default of :func:`check_step`'s parameters: an argument the step does not take.
_NOT_GIVEN = object()


def check_step(*, probe=_NOT_GIVEN, scene=_NOT_GIVEN, ds=_NOT_GIVEN, feats=_NOT_GIVEN,
               materials=_NOT_GIVEN, seed=_NOT_GIVEN, quick=_NOT_GIVEN, cache_dir=_NOT_GIVEN,
               n_jobs=_NOT_GIVEN) -> None:
    """Refuse, naming the parameter, the arguments of a study step's ``compute`` that it cannot
    run on, before any work starts; only the arguments given are checked (None included).

    ``probe`` a :class:`~ebantenna.probe.Probe`; ``scene`` a
    :class:`~ebantenna.simulate.Scene`; ``ds`` a :class:`~ebantenna.simulate.Dataset`;
    ``feats`` the :class:`~ebantenna.paper.feature_table.SignalFeatures` of its rows, one row per
    recording of ``ds``; ``materials`` distinct names of ``ds``'s materials; ``seed`` an
    integer in 0 ... :data:`MAX_SEED`; ``quick`` True or False (a string such as ``"no"`` would
    be taken as true); ``cache_dir`` a folder that exists and accepts files, or can be made
    (``_validate.output_dir``; not made here); ``n_jobs`` -1 or a count of workers, at most
    the machine's cores (``_validate.check_n_jobs``; not None: a step's fits need a count).

    Examples
    --------
    >>> check_step(seed=0, quick=True)
    >>> check_step(quick="no")
    Traceback (most recent call last):
    ...
    TypeError: quick must be True or False, got 'no' (str)
    """
    for name, value, kind in (("probe", probe, Probe), ("scene", scene, Scene),
                              ("ds", ds, Dataset), ("feats", feats, SignalFeatures)):
        if value is not _NOT_GIVEN:
            check_instance(name, value, kind)
    if feats is not _NOT_GIVEN and ds is not _NOT_GIVEN:
        rows = {np.shape(feats.dominant)[:1], np.shape(feats.fft)[:1]}
        if rows != {(ds.n_signals,)}:
            raise ValueError(f"feats must hold one row per recording of ds ({ds.n_signals}), got "
                             f"{sorted(r[0] if r else 0 for r in rows)}")
    if materials is not _NOT_GIVEN:
        _check_materials(materials, None if ds is _NOT_GIVEN else ds)
    if seed is not _NOT_GIVEN:
        check_int("seed", seed, minimum=0, maximum=MAX_SEED)
    if quick is not _NOT_GIVEN:
        check_bool("quick", quick)
    if cache_dir is not _NOT_GIVEN:
        output_dir("cache_dir", cache_dir)
    if n_jobs is not _NOT_GIVEN:
        if n_jobs is None:
            raise TypeError("n_jobs must be -1 (every core) or a count of workers >= 1, got None")
        check_n_jobs("n_jobs", n_jobs)


def check_render(result, kind: type, report, figures, *, optional: bool = False) -> None:
    """Refuse, naming the parameter, what a study step's ``render`` cannot write: a ``result``
    that is not the step's ``kind`` (or None, when the step may have measured nothing:
    ``optional``), a ``report`` that is not a :class:`~ebantenna.report.Report`, ``figures``
    that are not a :class:`~ebantenna.report.FigureSet`.

    Examples
    --------
    >>> check_render(None, Report, Report("t"), None)
    Traceback (most recent call last):
    ...
    TypeError: result must be a Report, got None (NoneType)
    """
    check_instance("result", result, kind, optional=optional)
    check_instance("report", report, Report)
    check_instance("figures", figures, FigureSet)
