"""Wall time of the hand-written estimators against scikit-learn's, measured side by side.

Run: ``python benchmarks/ml_speed.py [--quick] [--repeat N]``

* ``SVC.fit`` on 6000 x 256 features, 5 classes, RBF kernel, against ``sklearn.svm.SVC`` (libsvm,
  C++), with the held-out accuracy of each so that the times compare equal work. Target: ratio
  <= 0.3 (``libsvm_compat``: <= 0.5), not reached on the AMD EPYC machine of the latest runs.
  The ratios depend on the machine: on the machine of earlier runs the default mode measured
  0.27-0.33 on two BLAS threads and 0.31-0.36 on one; on the AMD EPYC machine, where libsvm runs
  about 2.5 times as fast (0.87-0.93 s against 2.25 s), 0.36-0.45 and 0.49-0.57, and
  ``libsvm_compat`` 0.44-0.58 on two threads and 0.62-0.69 on one.
* ``MLPClassifier.fit`` with the same network, solver and number of epochs as scikit-learn's
  (full-batch gradient descent = scikit-learn's 'sgd' with one batch and no momentum; Adam with
  mini-batches of 200; SGD with scikit-learn's 'invscaling' schedule; L-BFGS through SciPy on
  both sides). Target: ratio <= 0.6, not reached: Adam and SGD with mini-batches measure
  0.71-0.81 (one or two BLAS threads), full-batch gradient descent 0.87-0.92, L-BFGS 0.91-1.26
  (its products are threaded on both sides, and vary the most from run to run).
  With two BLAS threads on the shared two-core machine the threaded products wait for the busy
  second core (a fit then takes 2-6 s instead of 0.5 s), on both sides alike.
* ``SVC(probability=True).fit``: the fit plus five cross-validation fits per pair of classes on
  both sides.

A second table (:func:`where_time_goes`) splits our fits into parts, each as a share of
scikit-learn's time, and so shows how low each ratio can go. On the AMD EPYC machine: the default
``SVC`` (two BLAS threads) spends 0.18-0.21 in kernel entries (float64 products at the cores'
peak) and 0.18-0.22 in the SMO loop (14165 updates, the same number as libsvm's, at 13-14 us
each, some fifteen NumPy calls on vectors of 2400 entries); a ratio of 0.3 would leave the loop
about 4 us per update. ``libsvm_compat``: 0.14-0.17 in its float32 kernel matrix and 0.29-0.36
in the loop with shrinking (22-23 us per update). Adam on one BLAS thread: the gathers and the
two 200 x 256 x 53 products of each mini-batch, the same BLAS calls on both sides, take 0.51-0.53
of scikit-learn's fit, Adam's update of the parameters 0.10 and the hidden layer's tanh with its
derivative 0.03, each the same arithmetic as scikit-learn's (which the 1e-15 parity needs): 0.66
in all, above the target of 0.6 before the loss and the output layer. (On two threads the
products' share varies from run to run, 0.33-0.49.)
Computing only the kernel rows that SMO reads (36 % of them, in blocks of 16-64 rows chosen by
their violation) was tried and is slower: each block repacks the pair's points for the product,
so an entry costs about twice as much (0.42-0.52 s against 0.40 s for the fit).

Each pair is timed alternately ``--repeat`` times and the best time of each is kept, so that
other load on the machine affects both sides alike. The table prints the ratio ours / theirs.
:func:`run` returns the rows, :func:`to_text` prints them.
libsvm runs on one thread; our Gram matrix is a BLAS product that uses every BLAS thread, which
helps on an idle machine and hurts on a busy one, so one row repeats our fit on one BLAS thread,
and one repeats the Adam fit with both sides on one BLAS thread.
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np
from sklearn.exceptions import ConvergenceWarning
from sklearn.neural_network import MLPClassifier as SkMLP
from sklearn.svm import SVC as LibSVC
from threadpoolctl import threadpool_limits

from ebantenna.bench._timing import best_time, clocked
from ebantenna.ml import SVC, MLPClassifier
from ebantenna.ml import svc as svc_module
from ebantenna.ml.backprop import activation_derivative
from ebantenna.ml.kernels import Kernel
from ebantenna.ml.optimizers import Adam
from ebantenna.report import text_table

__all__ = ["spectra_like", "run", "compare", "svc_rows", "mlp_rows", "where_time_goes", "to_text",
           "main"]


def spectra_like(n, d, k, seed):
    """Non-negative features with overlapping classes (folded Gaussians in 256 dimensions),
    so that held-out accuracy lies near 95 % (not trivial, not chance)."""
    rng = np.random.default_rng(seed)
    centers = rng.normal(size=(k, d))
    y = rng.integers(0, k, n)
    X = np.abs(centers[y] * 0.55 + rng.normal(size=(n, d)))
    return X, y


#: The row whose scikit-learn time the MLP's parts are shares of (both sides on one thread).
ADAM_ONE_THREAD = "MLP adam, both sides on 1 BLAS thread"


def run(quick: bool = False, repeat: int = 2) -> dict:
    """Time each hand-written estimator against scikit-learn's on the same data.

    Parameters
    ----------
    quick : bool
        1500 training samples and 20 epochs instead of 6000 and 50.
    repeat : int
        Alternating timings per pair; the best of each side is kept.

    Returns
    -------
    dict
        ``rows``: per task ``task``, ``ours_seconds``, ``sklearn_seconds``, ``ratio`` (ours /
        theirs), ``ours_accuracy`` and ``sklearn_accuracy`` (held out); ``parts``: the rows of
        :func:`where_time_goes`.
    """
    if repeat < 1:
        raise ValueError(f"repeat must be >= 1, got {repeat}")
    n = 1500 if quick else 6000
    d, k = 256, 5
    X, y = spectra_like(n + n // 4, d, k, seed=0)
    X /= X.max()
    Xtr, ytr, Xte, yte = X[:n], y[:n], X[n:], y[n:]
    epochs = 20 if quick else 50
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        warnings.simplefilter("ignore", FutureWarning)  # probability=True, scikit-learn >= 1.9
        acc = lambda m: m.score(Xte, yte)  # noqa: E731
        svc = svc_rows(Xtr, ytr, acc, repeat)
        mlp = mlp_rows(Xtr, ytr, acc, repeat, epochs)
        adam = next(r for r in mlp if r["task"] == ADAM_ONE_THREAD)
        parts = where_time_goes(Xtr, ytr, svc[0]["sklearn_seconds"], adam["sklearn_seconds"],
                                epochs)
    return {"rows": svc + mlp, "parts": parts}


def compare(task: str, ours, theirs, score, repeat: int) -> dict:
    """One row of :func:`run`: ``ours()`` and ``theirs()`` timed alternately ``repeat`` times,
    the best time (s) of each kept, and ``score`` of each side's last fitted model."""
    t_ours = t_theirs = np.inf
    m_ours = m_theirs = None
    for _ in range(repeat):  # alternate, keep the best of each
        t, m_ours = best_time(ours, 1)
        t_ours = min(t_ours, t)
        t, m_theirs = best_time(theirs, 1)
        t_theirs = min(t_theirs, t)
    return {"task": task, "ours_seconds": t_ours, "sklearn_seconds": t_theirs,
            "ratio": t_ours / t_theirs, "ours_accuracy": score(m_ours),
            "sklearn_accuracy": score(m_theirs)}


def _on_one_thread(estimator, X, y):
    """``estimator.fit(X, y)`` with BLAS limited to one thread."""
    with threadpool_limits(1):
        return estimator.fit(X, y)


def svc_rows(X, y, score, repeat: int) -> list[dict]:
    """Our ``SVC`` against libsvm's: the default, on one BLAS thread, ``libsvm_compat`` and
    ``probability=True``; the first row is the reference of :func:`where_time_goes`."""
    n, d = X.shape
    k = len(np.unique(y))
    rows = [
        compare(f"SVC rbf fit, {n}x{d}, {k} classes",
                lambda: SVC().fit(X, y), lambda: LibSVC().fit(X, y), score, repeat),
        compare("SVC rbf fit, ours on 1 BLAS thread", lambda: _on_one_thread(SVC(), X, y),
                lambda: LibSVC().fit(X, y), score, repeat),
        compare("SVC rbf fit, libsvm_compat=True",  # both sides shrink, as by default
                lambda: SVC(libsvm_compat=True).fit(X, y),
                lambda: LibSVC().fit(X, y), score, repeat),
    ]
    # probability=True: five cross-validation fits per pair of classes on each side
    rows.append(compare("SVC rbf fit, probability=True",
                        lambda: SVC(probability=True, random_state=0).fit(X, y),
                        lambda: LibSVC(probability=True, random_state=0).fit(X, y),
                        score, repeat))
    return rows


def mlp_rows(X, y, score, repeat: int, epochs: int) -> list[dict]:
    """Our ``MLPClassifier`` against scikit-learn's with the same network, solver and epochs:
    full-batch gradient descent, Adam (also with both sides on one BLAS thread), SGD with
    scikit-learn's 'invscaling' schedule and L-BFGS."""
    n = len(X)
    common = dict(hidden_layer_sizes=(53,), activation="tanh", max_iter=epochs, tol=0.0,
                  n_iter_no_change=10**6, random_state=0, alpha=1e-4)
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
         lambda: _on_one_thread(SkMLP(solver="adam", batch_size=200, **common), X, y)),
        (f"MLP 53 tanh, sgd invscaling batch 200, {epochs} epochs",
         lambda: MLPClassifier(solver="sgd", batch_size=200, learning_rate="invscaling",
                               learning_rate_init=0.5, **common).fit(X, y),
         lambda: SkMLP(solver="sgd", batch_size=200, learning_rate="invscaling",
                       learning_rate_init=0.5, **common).fit(X, y)),
        (f"MLP 53 tanh, lbfgs, {epochs} iterations",
         lambda: MLPClassifier(solver="lbfgs", **common).fit(X, y),
         lambda: SkMLP(solver="lbfgs", **common).fit(X, y)),
    ]
    return [compare(task, ours, theirs, score, repeat) for task, ours, theirs in pairs]


def where_time_goes(X, y, svc_seconds: float, adam_seconds: float, epochs: int,
                    batch_size: int = 200) -> list[dict]:
    """Split our fits into their parts, each as a share of scikit-learn's fit time.

    ``SVC``: one fit per mode with :meth:`Kernel.gram` (every kernel entry) and the SMO solver
    clocked; the solver's updates are counted. ``MLPClassifier`` (Adam), on one BLAS thread
    (steadier on a shared machine than two): the work that both sides do with the same
    arithmetic, which parity with scikit-learn fixes, timed alone: the gather of each mini-batch
    with the two ``batch x n_features x n_hidden`` products, Adam's update of the parameters (as
    many steps as mini-batches), and the hidden layer's tanh with its derivative. A target ratio
    below the sum of these shares cannot be met by a loop that keeps the same arithmetic.

    Parameters
    ----------
    X, y : ndarray
        Training set of the timed fits.
    svc_seconds, adam_seconds : float
        scikit-learn's best fit times, measured in the same run (``adam_seconds`` on one BLAS
        thread).
    epochs, batch_size : int
        The MLP's epochs and mini-batch size.

    Returns
    -------
    list of dict
        ``part``, ``seconds``, ``share`` (of scikit-learn's time) and ``note``; the SMO rows
        also ``updates``, the solver's updates over all pairs of classes.
    """
    return (_svc_parts(X, y, svc_seconds)
            + _mlp_parts(X, y, adam_seconds, epochs, batch_size))


def _svc_parts(X, y, svc_seconds: float) -> list[dict]:
    """Per mode, the faster of two fits with :meth:`Kernel.gram` and the SMO solver clocked:
    kernel entries, the SMO loop (with its updates) and the rest, as shares of ``svc_seconds``."""
    parts = []
    for compat in (False, True):
        whole = np.inf
        for _ in range(2):  # the faster of two clocked fits
            times: dict = {}
            with (clocked(Kernel, "gram", times),
                  clocked(svc_module, "solve_smo", times, count=lambda res: res.n_iter)):
                start = time.perf_counter()
                SVC(libsvm_compat=compat).fit(X, y)
                seconds = time.perf_counter() - start
            if seconds < whole:
                whole, totals = seconds, times
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


def _mlp_parts(X, y, adam_seconds: float, epochs: int, batch_size: int) -> list[dict]:
    """The Adam fit's work shared with scikit-learn's, each part timed alone on one BLAS
    thread, as shares of ``adam_seconds``."""
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
        opt = Adam(params)
        for _ in range(steps):
            opt.update(params, grads)

    hidden_layer = rng.normal(size=(batch_size, hidden))
    activated, back, scratch = (np.empty_like(hidden_layer) for _ in range(3))

    def tanh():  # the hidden layer's activation forward, its derivative backward
        for _ in range(steps):
            np.tanh(hidden_layer, out=activated)  # what activate('tanh', z) does to z in place
            np.copyto(back, delta)
            activation_derivative("tanh", activated, back, scratch)

    with threadpool_limits(1):  # steadier than two threads on a shared machine
        for part, fn, note in (
                (f"gathers and the two {batch_size}x{d}x{hidden} products", products,
                 f"{steps} mini-batches, the same BLAS calls on both sides"),
                ("Adam's update of the parameters", adam, f"{steps} steps"),
                ("tanh and its derivative in the hidden layer", tanh, f"{steps} mini-batches")):
            seconds = best_time(fn, 2)[0]
            parts.append({"part": f"MLP adam, 1 BLAS thread: {part}", "seconds": seconds,
                          "share": seconds / adam_seconds, "note": note})
    return parts


def to_text(tables: dict) -> str:
    """The table of :func:`run` as text."""
    return text_table(
        [("task", "task", "<48"), ("ours_seconds", "ours (s)", "9.3f"),
         ("sklearn_seconds", "sklearn (s)", "11.3f"), ("ratio", "ratio", "6.2f"),
         ("ours_accuracy", "acc ours", "9.4f"), ("sklearn_accuracy", "acc sklearn", "11.4f")],
        tables["rows"],
    ) + "\n\nWhere our time goes, as a share of scikit-learn's fit time:\n" + text_table(
        [("part", "part", "<58"), ("seconds", "seconds", "8.3f"), ("share", "share", "6.2f"),
         ("note", "", "<")],
        tables["parts"],
    )


def main(argv=None):
    """Command-line entry: print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller problems")
    parser.add_argument("--repeat", type=int, default=2, help="timings per estimator")
    args = parser.parse_args(argv)
    print(to_text(run(args.quick, args.repeat)))


if __name__ == "__main__":
    main()
