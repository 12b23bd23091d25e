"""Wall time of the hand-written estimators against scikit-learn's, measured side by side.

Run: ``python benchmarks/ml_speed.py [--quick] [--repeat N]``

* ``SVC.fit`` on 6000 x 256 features, 5 classes, RBF kernel, against ``sklearn.svm.SVC`` (libsvm,
  C++), with the held-out accuracy of each so that the times compare equal work. Target: ratio
  <= 0.3 (``libsvm_compat``: <= 0.5). With the NumPy engines it was not reached on the AMD EPYC
  machine of the earlier runs.
  The ratios depend on the machine: on the machine of earlier runs the default mode measured
  0.27-0.33 on two BLAS threads and 0.31-0.36 on one; on the AMD EPYC machine, where libsvm runs
  about 2.5 times as fast (0.87-0.93 s against 2.25 s), 0.36-0.45 and 0.49-0.57, and
  ``libsvm_compat`` 0.44-0.58 on two threads and 0.62-0.69 on one.
* ``MLPClassifier.fit`` with the same network, solver and number of epochs as scikit-learn's
  (full-batch gradient descent = scikit-learn's 'sgd' with one batch and no momentum; Adam with
  mini-batches of 200; SGD with scikit-learn's 'invscaling' schedule; L-BFGS through SciPy on
  both sides). Target: within 10 % of the floor the second table measures (the gathers and
  products both libraries do), not reached: Adam on one BLAS thread measures 0.60-0.66 with the
  compiled loops of the ``fast`` extra (0.71-0.81 on NumPy alone) against a floor of 0.43-0.49,
  and the parts that scikit-learn's arithmetic fixes (those products, Adam's update, tanh) take
  0.55 together in the same run as that floor of 0.49, more than the target of 1.1 times it;
  full-batch gradient descent 0.74-0.92, L-BFGS 0.89-1.26 (its products are threaded on both
  sides, and vary the most from run to run).
  With two BLAS threads on the shared two-core machine the threaded products wait for the busy
  second core (a fit then takes 2-6 s instead of 0.5 s), on both sides alike.
* ``SVC(probability=True).fit``: the fit plus five cross-validation fits per pair of classes on
  both sides.
* ``SVC.fit`` on scikit-learn's small data sets (:data:`SMALL_SETS`: iris, wine, breast_cancer,
  digits; standardised, three quarters for training), the size of a student's own data: RBF in
  both modes and linear with ``C=100``. There a fit takes about a millisecond and the fixed
  costs weigh most: the NumPy loop's dozen or so NumPy calls per SMO update, and the per-fit
  validation and kernel set-up. Target: ratio <= 1.0 with the compiled engine, met on every row
  but the linear kernel with ``C=100`` on breast_cancer (1.10-1.20) and digits (1.15-1.31):
  there the kernel entries and the compiled loop alone take 0.93 of scikit-learn's fit
  (:func:`small_set_parts`), the loop about as many updates as libsvm's (16,795 against 16,813
  on breast_cancer, counted on the NumPy engine, which the tests hold to the compiled one's
  updates, with scikit-learn 1.9.1; the count follows the last bits of the kernel entries, see
  :mod:`ebantenna.ml.smo`) at about the same cost each, and libsvm computes only the kernel rows
  it reads.
* Every ``SVC`` row is measured on each SMO engine that runs here (column ``engine``): the
  NumPy engines, and the compiled one when numba is installed (``pip install ebantenna[fast]``;
  see :mod:`ebantenna.ml.smo`), which returns the same numbers to the last bit. Targets with
  it: the default mode <= 0.3 and ``libsvm_compat`` <= 0.5 on the paper's data. A third table
  gives what the compiled engine costs before its first fit (:func:`engine_rows`): compiling
  the loop in a fresh process with an empty numba cache, and loading it in this one.

A second table (:func:`where_time_goes`) splits our fits into parts, each as a share of
scikit-learn's time, and so shows how low each ratio can go. The ``SVC`` parts are timed on one BLAS
thread, as the ``SVC`` rows and libsvm are: the default ``SVC`` spends its time in kernel entries
(float64 products) and in the SMO loop (14165 updates, the same number as libsvm's, some fifteen
NumPy calls each on vectors of 2400 entries), ``libsvm_compat`` in its float32 kernel matrix and in
the loop with shrinking. (An earlier run on the AMD EPYC machine timed them on two BLAS threads
against libsvm's one: 0.18-0.21 in kernel entries and 0.18-0.22 in the loop at 13-14 us an update,
where a ratio of 0.3 would leave the loop about 4 us.) Adam on one BLAS thread: the gathers and the
two 200 x 256 x 53 products of each mini-batch, the same BLAS calls on both sides, take 0.51-0.53 of
scikit-learn's fit on that machine (0.43-0.44 on a later one), Adam's update of the parameters 0.10
as NumPy calls (0.03 compiled) and the hidden layer's tanh with its derivative 0.03, each the same
arithmetic as scikit-learn's (which the 1e-15 parity needs). The rest is mostly the output loss
(``exp``, ``log``, ``einsum`` and NumPy's pairwise sums, which the compiled loops cannot copy bit
for bit). (On two threads the products' share varies from run to run, 0.33-0.49.) Computing only the
kernel rows that SMO reads (36 % of them, in blocks of 16-64 rows chosen by their violation) was
tried and is slower: each block repacks the pair's points for the product, so an entry costs about
twice as much (0.42-0.52 s against 0.40 s for the fit).

Each pair is timed alternately ``--repeat`` times (5 by default: ours, theirs, ours, ...), so that
other load on the machine affects both sides alike; the table gives the smallest and the median
of the ratios ours / theirs taken within each repetition, which a load that comes and goes moves
less than a ratio of times taken apart. :func:`run` returns the rows, :func:`to_text` prints
them. libsvm runs on one thread, and so do both sides of every ``SVC`` row (BLAS limited to one
thread); the MLP rows keep one row with the default BLAS threads on both sides (the products
then use every thread) beside the Adam row with both sides on one.
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time
import warnings
from contextlib import ExitStack, contextmanager

import numpy as np
from sklearn import datasets
from sklearn.exceptions import ConvergenceWarning
from sklearn.neural_network import MLPClassifier as SkMLP
from sklearn.preprocessing import StandardScaler
from sklearn.svm import SVC as LibSVC
from threadpoolctl import threadpool_limits

from ebantenna._budget import check_allocation
from ebantenna._engines import ENGINES
from ebantenna._validate import check_bool, check_choice, check_in_range, check_int, check_positive
from ebantenna.bench._arguments import (
    MAX_TRIALS,
    check_argv,
    check_callable,
    check_count,
    check_features,
    check_tables,
)
from ebantenna.bench._timing import best_time, clocked
from ebantenna.ml import SVC, MLPClassifier, smo_engine_status
from ebantenna.ml import smo as smo_module
from ebantenna.ml import svc as svc_module
from ebantenna.ml.kernels import Kernel
from ebantenna.ml.mlp_base import training_optimizer
from ebantenna.ml.smo import ENGINE_VARIABLE
from ebantenna.report import text_table

__all__ = ["spectra_like", "SMALL_SETS", "SMALL_CASES", "small_set", "engines", "on_engine", "run",
           "compare", "svc_rows", "small_set_rows", "small_set_parts", "engine_rows",
           "sklearn_adam", "mlp_rows", "where_time_goes", "to_text", "main"]


def spectra_like(n, d, k, seed):
    """Non-negative features with overlapping classes (folded Gaussians in 256 dimensions),
    so that held-out accuracy lies near 95 % (not trivial, not chance)."""
    n, d = check_int("n", n, minimum=1), check_int("d", d, minimum=1)
    k = check_int("k", k, minimum=1, maximum=n)
    check_allocation(24 * n * d, parameter="n and d", what="the features")
    rng = np.random.default_rng(check_int("seed", seed, minimum=0))
    centers = rng.normal(size=(k, d))
    y = rng.integers(0, k, n)
    X = np.abs(centers[y] * 0.55 + rng.normal(size=(n, d)))
    return X, y


#: The row whose scikit-learn time the MLP's parts are shares of (both sides on one thread).
ADAM_ONE_THREAD = "MLP adam, both sides on 1 BLAS thread"


#: scikit-learn's small data sets, the size of a student's own: the fixed cost of a fit and of
#: an SMO update weighs most there.
SMALL_SETS = ("iris", "wine", "breast_cancer", "digits")


def small_set(name: str):
    """One of :data:`SMALL_SETS`, features standardised as a student would, shuffled (seed 0)
    and split three to one: ``(X_train, y_train, X_test, y_test)``."""
    check_choice("name", name, SMALL_SETS)
    X, y = getattr(datasets, f"load_{name}")(return_X_y=True)
    order = np.random.default_rng(0).permutation(len(y))
    X, y = StandardScaler().fit_transform(X[order]), y[order]
    n = 3 * len(y) // 4
    return X[:n], y[:n], X[n:], y[n:]


def engines() -> list[str]:
    """The SMO engines to time: ``'numpy'``, and ``'compiled'`` when numba works here."""
    return ["numpy", "compiled"] if smo_engine_status().available else ["numpy"]


@contextmanager
def on_engine(engine: str):
    """Run the enclosed fits on one SMO engine (through ``EBANTENNA_ENGINE``), then restore.

    ``engine`` is one of ``'auto'``, ``'numpy'`` or ``'compiled'``, checked on entering."""
    check_choice("engine", engine, ENGINES)
    before = os.environ.get(ENGINE_VARIABLE)
    os.environ[ENGINE_VARIABLE] = engine
    try:
        yield
    finally:
        if before is None:
            del os.environ[ENGINE_VARIABLE]
        else:
            os.environ[ENGINE_VARIABLE] = before


def run(quick: bool = False, repeat: int = 5) -> dict:
    """Time each hand-written estimator against scikit-learn's on the same data.

    Parameters
    ----------
    quick : bool
        1500 training samples and 20 epochs instead of 6000 and 50 (the small sets as they are).
    repeat : int
        Interleaved timings per row (ours, theirs, ours, ...); at least 5 for the ratios'
        median to mean something.

    Returns
    -------
    dict
        ``rows``: per task ``task``, ``data``, ``engine``, ``ours_seconds``,
        ``sklearn_seconds`` (best of each), ``ratio`` (of the bests), ``ratio_min`` and
        ``ratio_median`` (of the ratios within each repetition), ``ours_accuracy`` and
        ``sklearn_accuracy`` (held out); ``parts``: the rows of :func:`where_time_goes`;
        ``engine``: the rows of :func:`engine_rows`.
    """
    quick = check_bool("quick", quick)
    repeat = check_count("repeat", repeat)
    n = 1500 if quick else 6000
    d, k = 256, 5
    X, y = spectra_like(n + n // 4, d, k, seed=0)
    X /= X.max()
    Xtr, ytr, Xte, yte = X[:n], y[:n], X[n:], y[n:]
    epochs = 20 if quick else 50
    engine = engine_rows()  # first: the compile time is that of the first call
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        warnings.simplefilter("ignore", FutureWarning)  # probability=True, scikit-learn >= 1.9
        acc = lambda m: m.score(Xte, yte)  # noqa: E731
        svc = svc_rows(Xtr, ytr, acc, repeat)
        small = small_set_rows(repeat)
        mlp = mlp_rows(Xtr, ytr, acc, repeat, epochs)
        adam = next(r for r in mlp if r["task"] == ADAM_ONE_THREAD)
        parts = where_time_goes(Xtr, ytr, svc[0]["sklearn_seconds"], adam["sklearn_seconds"],
                                epochs, adam_fit=sklearn_adam(Xtr, ytr, epochs),
                                repeat=repeat) + small_set_parts(small)
    return {"rows": svc + small + mlp, "parts": parts, "engine": engine}


def compare(task: str, ours, theirs, score, repeat: int, *, data: str = "",
            engine: str = "", clock=time.perf_counter) -> dict:
    """One row of :func:`run`: ``ours()`` and ``theirs()`` timed alternately ``repeat`` times.

    Load on a shared machine comes and goes; alternating lets it hit both sides alike, and the
    ratio within one repetition (ours, then theirs, a moment apart) is steadier than a ratio of
    times taken minutes apart. The row keeps the best time (s) of each side, their ratio, the
    smallest and the median of the ``repeat`` ratios within a repetition, and ``score`` of each
    side's last fitted model.
    """
    if not isinstance(task, str):
        raise TypeError(f"task must be a str (the row's name), got {type(task).__name__}")
    for name, f in (("ours", ours), ("theirs", theirs), ("score", score), ("clock", clock)):
        check_callable(name, f)
    repeat = check_count("repeat", repeat)
    times_ours, times_theirs = [], []
    m_ours = m_theirs = None
    for _ in range(repeat):  # alternate
        start = clock()
        m_ours = ours()
        times_ours.append(clock() - start)
        start = clock()
        m_theirs = theirs()
        times_theirs.append(clock() - start)
    ratios = [a / b for a, b in zip(times_ours, times_theirs, strict=True)]
    t_ours, t_theirs = min(times_ours), min(times_theirs)
    return {"task": task, "data": data, "engine": engine, "ours_seconds": t_ours,
            "sklearn_seconds": t_theirs, "ratio": t_ours / t_theirs, "ratio_min": min(ratios),
            "ratio_median": float(np.median(ratios)), "ours_accuracy": score(m_ours),
            "sklearn_accuracy": score(m_theirs)}


def _on_one_thread(estimator, X, y):
    """``estimator.fit(X, y)`` with BLAS limited to one thread."""
    with threadpool_limits(1):
        return estimator.fit(X, y)


def svc_rows(X, y, score, repeat: int) -> list[dict]:
    """Our ``SVC`` against libsvm's on the paper's data, both on one BLAS thread (libsvm uses
    one): the default and ``libsvm_compat`` (both shrink, as by default) on each SMO engine,
    then ``probability=True``; the first row is the reference of :func:`where_time_goes`."""
    X, y = check_features(X, y)
    check_callable("score", score)
    check_count("repeat", repeat)
    n, d = X.shape
    data = f"paper-like {n}x{d}, {len(np.unique(y))} classes"
    rows = []
    with threadpool_limits(1):
        for engine in engines():
            with on_engine(engine):
                rows += [compare("SVC rbf fit", lambda: SVC().fit(X, y),
                                 lambda: LibSVC().fit(X, y), score, repeat, data=data,
                                 engine=engine),
                         compare("SVC rbf fit, libsvm_compat=True",
                                 lambda: SVC(libsvm_compat=True).fit(X, y),
                                 lambda: LibSVC().fit(X, y), score, repeat, data=data,
                                 engine=engine)]
        # probability=True: five cross-validation fits per pair of classes on each side
        rows.append(compare("SVC rbf fit, probability=True",
                            lambda: SVC(probability=True, random_state=0).fit(X, y),
                            lambda: LibSVC(probability=True, random_state=0).fit(X, y),
                            score, repeat, data=data, engine=engines()[-1]))
    return rows


def _fits(estimator, params: dict, X, y, count: int):
    """A function that fits ``estimator(**params)`` on ``(X, y)`` ``count`` times and returns
    the last model: :func:`small_set_rows` times batches of fits and divides by ``count``."""
    def fits():
        for _ in range(count):
            model = estimator(**params).fit(X, y)
        return model
    return fits


class _Scorer:
    """Held-out accuracy of a fitted model: ``_Scorer(X, y)(model)``."""

    def __init__(self, X, y):
        self.X, self.y = X, y

    def __call__(self, model) -> float:
        return model.score(self.X, self.y)


#: The fits of :func:`small_set_rows`: task -> (our parameters, scikit-learn's).
SMALL_CASES = {
    "SVC rbf fit": ({}, {}),
    "SVC rbf fit, libsvm_compat=True": ({"libsvm_compat": True}, {}),
    "SVC linear fit, C=100": ({"kernel": "linear", "C": 100.0}, {"kernel": "linear", "C": 100.0}),
}


def small_set_rows(repeat: int, batch_seconds: float = 0.02) -> list[dict]:
    """Our ``SVC`` against libsvm's on each of :data:`SMALL_SETS`, on one BLAS thread: the RBF
    kernel in both modes and the linear kernel with ``C=100`` (where the NumPy loop's fixed cost
    per update showed most), on each engine.

    One fit there takes about a millisecond, near the clock's noise, so each timing is of a batch
    of fits lasting about ``batch_seconds`` on scikit-learn's side, and the seconds reported are
    per fit.
    """
    check_count("repeat", repeat)
    check_in_range("batch_seconds", batch_seconds, 0.0, 60.0, low_inclusive=True,
                   high_inclusive=True)
    rows = []
    with threadpool_limits(1):
        for name in SMALL_SETS:
            X, y, Xte, yte = small_set(name)
            score = _Scorer(Xte, yte)
            for task, (params, theirs) in SMALL_CASES.items():
                one = best_time(_fits(LibSVC, theirs, X, y, 1), 3)[0]
                count = max(1, math.ceil(batch_seconds / one))
                for engine in engines():
                    with on_engine(engine):
                        row = compare(task, _fits(SVC, params, X, y, count),
                                      _fits(LibSVC, theirs, X, y, count), score, repeat,
                                      data=f"{name} {X.shape[0]}x{X.shape[1]}", engine=engine)
                    row["ours_seconds"] /= count
                    row["sklearn_seconds"] /= count
                    rows.append(row)
    return rows


def _fastest_clocked_fit(model, X, y, clocks, repeat: int) -> tuple[float, dict]:
    """Fit ``model`` ``repeat`` times with each ``(owner, name, count)`` of ``clocks`` clocked
    (``clocked``): the fastest fit's seconds and its totals."""
    whole, totals = np.inf, {}
    for _ in range(repeat):
        times: dict = {}
        with ExitStack() as stack:
            for owner, name, count in clocks:
                stack.enter_context(clocked(owner, name, times, count=count))
            start = time.perf_counter()
            model.fit(X, y)
            seconds = time.perf_counter() - start
        if seconds < whole:
            whole, totals = seconds, times
    return whole, totals


def small_set_parts(rows: list[dict], repeat: int = 5) -> list[dict]:
    """What the compiled engine's small-set fits of :func:`small_set_rows` spend in kernel
    entries and in the compiled SMO loop, as shares of scikit-learn's fit time in the same row.

    Their sum is the lowest ratio the fit can reach while it keeps the same arithmetic (every
    kernel entry of every pair's problem, computed by BLAS, and the same updates): the rest of
    the fit (validation, the pairs' set-up, the bias and the layout of the result) comes on
    top. Empty without the compiled engine.

    Parameters
    ----------
    rows : list of dict
        The rows of :func:`small_set_rows` (their ``sklearn_seconds`` per fit).
    repeat : int
        Clocked fits per row; the fastest is kept.
    """
    if not isinstance(rows, list) or not all(
            isinstance(r, dict) and {"engine", "data", "task", "sklearn_seconds"} <= set(r)
            for r in rows):
        raise TypeError("rows must be the list of rows of small_set_rows (dicts with 'engine', "
                        "'data', 'task' and 'sklearn_seconds')")
    check_count("repeat", repeat)
    parts = []
    if "compiled" not in engines():
        return parts
    with threadpool_limits(1), on_engine("compiled"):
        for row in (r for r in rows if r["engine"] == "compiled"):
            name = row["data"].split()[0]
            X, y, _, _ = small_set(name)
            params = SMALL_CASES[row["task"]][0]
            clocks = [(Kernel, "gram", None), (smo_module.SMO_ENGINES, "compiled", None)]
            whole, totals = _fastest_clocked_fit(SVC(**params), X, y, clocks, repeat)
            kernel, loop = totals["gram"], totals["compiled"]
            parts.append({"part": f"{row['task']}, {name}: kernel entries + compiled loop",
                          "seconds": kernel + loop,
                          "share": (kernel + loop) / row["sklearn_seconds"],
                          "note": f"kernel {kernel / row['sklearn_seconds']:.2f}, loop "
                                  f"{loop / row['sklearn_seconds']:.2f}, fit "
                                  f"{whole / row['sklearn_seconds']:.2f}"})
    return parts


def engine_rows() -> list[dict]:
    """What the compiled engine costs before its first fit: importing numba and compiling the
    loop in a fresh process with an empty numba cache (the first call after installing), and
    in this process (a load from numba's cache when it holds the loop). Empty without numba."""
    status = smo_engine_status()
    if not status.available:
        return [{"part": "compiled engine", "seconds": float("nan"), "note": status.reason}]
    probe = ("from ebantenna.ml import smo_engine_status; "
             "print(smo_engine_status().load_seconds)")
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        out = subprocess.run([sys.executable, "-c", probe], env=env, check=True,
                             capture_output=True, text=True).stdout
    return [{"part": "compiled engine: first call, empty numba cache (compile)",
             "seconds": float(out.split()[-1]), "note": "a fresh process, NUMBA_CACHE_DIR empty"},
            {"part": "compiled engine: first call in this process",
             "seconds": status.load_seconds, "note": "loaded from numba's cache if it was there"}]


def _mlp_common(epochs: int) -> dict:
    """The network and training length both sides of every MLP row share."""
    return dict(hidden_layer_sizes=(53,), activation="tanh", max_iter=epochs, tol=0.0,
                n_iter_no_change=10**6, random_state=0, alpha=1e-4)


def sklearn_adam(X, y, epochs: int):
    """A function that fits scikit-learn's MLP of the row ``ADAM_ONE_THREAD`` on one BLAS thread
    (Adam, mini-batches of 200) and returns it."""
    X, y = check_features(X, y)
    check_count("epochs", epochs)
    return lambda: _on_one_thread(SkMLP(solver="adam", batch_size=200, **_mlp_common(epochs)),
                                  X, y)


def mlp_rows(X, y, score, repeat: int, epochs: int) -> list[dict]:
    """Our ``MLPClassifier`` against scikit-learn's with the same network, solver and epochs:
    full-batch gradient descent, Adam (also with both sides on one BLAS thread), SGD with
    scikit-learn's 'invscaling' schedule and L-BFGS."""
    X, y = check_features(X, y)
    check_callable("score", score)
    check_count("repeat", repeat)
    check_count("epochs", epochs)
    n = len(X)
    common = _mlp_common(epochs)
    pairs = [
        (f"MLP 53 tanh, full-batch gd, {epochs} epochs",
         lambda: MLPClassifier(solver="gd", learning_rate_init=0.1, **common).fit(X, y),
         lambda: SkMLP(solver="sgd", momentum=0.0, batch_size=n, shuffle=False,
                       learning_rate_init=0.1, **common).fit(X, y)),
        (f"MLP 53 tanh, adam batch 200, {epochs} epochs",
         lambda: MLPClassifier(solver="adam", batch_size=200, **common).fit(X, y),
         lambda: SkMLP(solver="adam", batch_size=200, **common).fit(X, y)),
        (ADAM_ONE_THREAD,
         lambda: _on_one_thread(MLPClassifier(solver="adam", batch_size=200, **common), X, y),
         sklearn_adam(X, y, epochs)),
        (f"MLP 53 tanh, sgd invscaling batch 200, {epochs} epochs",
         lambda: MLPClassifier(solver="sgd", batch_size=200, learning_rate="invscaling",
                               learning_rate_init=0.5, **common).fit(X, y),
         lambda: SkMLP(solver="sgd", batch_size=200, learning_rate="invscaling",
                       learning_rate_init=0.5, **common).fit(X, y)),
        (f"MLP 53 tanh, lbfgs, {epochs} iterations",
         lambda: MLPClassifier(solver="lbfgs", **common).fit(X, y),
         lambda: SkMLP(solver="lbfgs", **common).fit(X, y)),
    ]
    data = f"paper-like {n}x{X.shape[1]}, {len(np.unique(y))} classes"
    return [compare(task, ours, theirs, score, repeat, data=data)
            for task, ours, theirs in pairs]


def where_time_goes(X, y, svc_seconds: float, adam_seconds: float, epochs: int,
                    batch_size: int = 200, adam_fit=None, repeat: int = 2) -> list[dict]:
    """Split our fits into their parts, each as a share of scikit-learn's fit time.

    ``SVC``: one fit per mode with :meth:`Kernel.gram` (every kernel entry) and the SMO solver
    clocked; the solver's updates are counted. ``MLPClassifier`` (Adam), on one BLAS thread
    (steadier on a shared machine than two): the work that both sides do with the same
    arithmetic, which parity with scikit-learn fixes, timed alone: the gather of each mini-batch
    with the two ``batch x n_features x n_hidden`` products, Adam's update of the parameters (as
    many steps as mini-batches), and the hidden layer's tanh with its derivative. A target ratio
    below the sum of these shares cannot be met by a loop that keeps the same arithmetic.
    With ``adam_fit`` (scikit-learn's fit, :func:`sklearn_adam`) each MLP part is timed
    alternately with it, as :func:`compare` times a row, and its share is the median of the
    ratios within a repetition, which load that comes and goes moves least.

    Parameters
    ----------
    X, y : ndarray
        Training set of the timed fits.
    svc_seconds, adam_seconds : float
        scikit-learn's best fit times, measured in the same run (``adam_seconds`` on one BLAS
        thread).
    epochs, batch_size : int
        The MLP's epochs and mini-batch size.
    adam_fit : callable, optional
        scikit-learn's Adam fit on one BLAS thread, to time each MLP part against.
    repeat : int
        Timings of each MLP part (alternated with ``adam_fit`` when it is given).

    Returns
    -------
    list of dict
        ``part``, ``seconds``, ``share`` (of scikit-learn's time) and ``note``; the SMO rows
        also ``updates``, the solver's updates over all pairs of classes.
    """
    X, y = check_features(X, y)
    check_positive("svc_seconds", svc_seconds)
    check_positive("adam_seconds", adam_seconds)
    check_count("epochs", epochs)
    check_int("batch_size", batch_size, minimum=1, maximum=MAX_TRIALS)
    if adam_fit is not None:
        check_callable("adam_fit", adam_fit)
    check_count("repeat", repeat)
    return (_svc_parts(X, y, svc_seconds)
            + _mlp_parts(X, y, adam_seconds, epochs, batch_size, adam_fit, repeat))


def _svc_parts(X, y, svc_seconds: float) -> list[dict]:
    """Per mode, the faster of two fits with :meth:`Kernel.gram` and the SMO solver clocked:
    kernel entries, the SMO loop (with its updates) and the rest, as shares of ``svc_seconds``
    (scikit-learn's fit on one thread, so the fits are timed on one BLAS thread too)."""
    parts = []
    for compat in (False, True):
        with threadpool_limits(1):
            whole, totals = _fastest_clocked_fit(  # the faster of two clocked fits
                SVC(libsvm_compat=compat), X, y,
                [(Kernel, "gram", None), (svc_module, "solve_smo", lambda res: res.n_iter)], 2)
        mode = "libsvm_compat" if compat else "default"
        updates = totals["solve_smo count"]
        for part, seconds, note in (
                ("kernel entries (Kernel.gram)", totals["gram"], ""),
                ("SMO loop", totals["solve_smo"],
                 f"{updates} updates, {1e6 * totals['solve_smo'] / updates:.1f} us each"),
                ("the rest", whole - totals["gram"] - totals["solve_smo"], "")):
            parts.append({"part": f"SVC {mode}: {part}", "seconds": seconds,
                          "share": seconds / svc_seconds, "note": note,
                          "updates": updates if part == "SMO loop" else None})
    return parts


def _mlp_parts(X, y, adam_seconds: float, epochs: int, batch_size: int, adam_fit=None,
               repeat: int = 2) -> list[dict]:
    """The Adam fit's work shared with scikit-learn's, each part timed alone on one BLAS
    thread, as shares of ``adam_seconds`` (or, with ``adam_fit``, as the median ratio to it
    timed alternately)."""
    parts = []
    rng = np.random.default_rng(0)
    n, d = X.shape
    hidden = 53
    W = rng.normal(size=(d, hidden))
    delta = rng.normal(size=(batch_size, hidden))

    def products():  # forward X_b W and the weight gradient X_b^T delta of every mini-batch
        for _ in range(epochs):
            order = rng.permutation(n)
            for start in range(0, n, batch_size):
                Xb = X[order[start : start + batch_size]]
                Xb @ W
                Xb.T @ delta[: len(Xb)]

    steps = epochs * -(-n // batch_size)
    shapes = [(d, hidden), (hidden,), (hidden, len(np.unique(y))), (len(np.unique(y)),)]
    params = [rng.normal(size=shape) for shape in shapes]
    grads = [1e-3 * rng.normal(size=shape) for shape in shapes]

    def adam():
        opt = training_optimizer("adam", params)  # the Adam the estimators train with
        for _ in range(steps):
            opt.update(params, grads)

    hidden_layer = rng.normal(size=(batch_size, hidden))
    activated, back, scratch = (np.empty_like(hidden_layer) for _ in range(3))

    def tanh():  # the hidden layer's activation forward, its derivative backward
        for _ in range(steps):
            np.tanh(hidden_layer, out=activated)  # what the engine's activation does in place
            np.copyto(back, delta)
            # and its derivative, on the delta in place: delta *= 1 - a * a
            np.multiply(activated, activated, out=scratch)
            np.subtract(1.0, scratch, out=scratch)
            np.multiply(back, scratch, out=back)

    with threadpool_limits(1):  # steadier than two threads on a shared machine
        for part, fn, note in (
                (f"gathers and the two {batch_size}x{d}x{hidden} products", products,
                 f"{steps} mini-batches, the same BLAS calls on both sides"),
                ("Adam's update of the parameters", adam, f"{steps} steps"),
                ("tanh and its derivative in the hidden layer", tanh, f"{steps} mini-batches")):
            if adam_fit is None:
                seconds = best_time(fn, repeat)[0]
                share = seconds / adam_seconds
            else:
                row = compare(part, fn, adam_fit, lambda model: 0.0, repeat)
                seconds, share = row["ours_seconds"], row["ratio_median"]
            parts.append({"part": f"MLP adam, 1 BLAS thread: {part}", "seconds": seconds,
                          "share": share, "note": note})
    parts.append({"part": "MLP adam, 1 BLAS thread: the three parts above together",
                  "seconds": sum(p["seconds"] for p in parts),
                  "share": sum(p["share"] for p in parts),
                  "note": "the lowest ratio with scikit-learn's arithmetic (the output loss "
                          "comes on top)"})
    return parts


def to_text(tables: dict) -> str:
    """The tables of :func:`run` as text."""
    check_tables(tables, "run", rows=list, parts=list, engine=list)
    return text_table(
        [("task", "task", "<36"), ("data", "data", "<34"), ("engine", "engine", "<8"),
         ("ours_seconds", "ours (s)", "9.4f"), ("sklearn_seconds", "sklearn (s)", "11.4f"),
         ("ratio_min", "ratio min", "9.2f"), ("ratio_median", "median", "6.2f"),
         ("ours_accuracy", "acc ours", "8.4f"), ("sklearn_accuracy", "acc sklearn", "11.4f")],
        tables["rows"],
    ) + "\n\nWhere our time goes, as a share of scikit-learn's fit time:\n" + text_table(
        [("part", "part", "<58"), ("seconds", "seconds", "8.3f"), ("share", "share", "6.2f"),
         ("note", "", "<")],
        tables["parts"],
    ) + "\n\nThe compiled SMO engine before its first fit:\n" + text_table(
        [("part", "part", "<58"), ("seconds", "seconds", "8.2f"), ("note", "", "<")],
        tables["engine"],
    )


def main(argv=None):
    """Command-line entry: print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller problems")
    parser.add_argument("--repeat", type=int, default=5,
                        help="interleaved timings per row (at least 5 for a median)")
    args = parser.parse_args(check_argv(argv))
    print(to_text(run(args.quick, args.repeat)))


if __name__ == "__main__":
    main()
