"""Probability estimates of an SVM, as libsvm computes them.

A decision value :math:`f` is turned into a probability by Platt's sigmoid

.. math:: P(y = +1 \\mid f) = \\frac{1}{1 + e^{A f + B}},

with :math:`A` and :math:`B` fitted by maximum likelihood to decision values that the training
points did not help to make: those of an internal five-fold cross-validation. The targets are
Platt's regularised ones, :math:`(N_+ + 1)/(N_+ + 2)` and :math:`1/(N_- + 2)`, and the fit is the
Newton method with a backtracking line search of H.-T. Lin, C.-J. Lin and R. C. Weng, "A note on
Platt's probabilistic outputs for support vector machines", *Machine Learning* 68, 2007 (libsvm's
``sigmoid_train``: at most 100 iterations, stopping when both gradient components are below
1e-5). With more than two classes, the pairwise probabilities :math:`r_{ij}` are coupled into one
distribution by the second method of T.-F. Wu, C.-J. Lin and R. C. Weng, "Probability estimates
for multi-class classification by pairwise coupling", *JMLR* 5, 2004 (libsvm's
``multiclass_probability``), which minimises
:math:`\\sum_i \\sum_{j \\ne i} (r_{ji} p_i - r_{ij} p_j)^2` over the simplex.

These follow libsvm's code (as bundled with scikit-learn) operation by operation, so that given
the same decision values they give libsvm's numbers.

The folds are libsvm's too. scikit-learn's copy of libsvm draws them with its own generator
(``sklearn/svm/src/newrand/newrand.h``): a Mersenne twister ``std::mt19937`` seeded with
``set_seed(seed)`` (the standard 32-bit initialisation, the same as NumPy's
``numpy.random.RandomState`` with an integer seed), and ``bounded_rand_int(range)``, which
maps a 32-bit draw :math:`x` to :math:`\\lfloor x \\cdot \\mathrm{range} / 2^{32} \\rfloor`,
drawing again while the low 32 bits of the product fall below
:math:`(2^{32} - \\mathrm{range}) \\bmod \\mathrm{range}` (Lemire's unbiased method).
``svm_binary_svc_probability`` shuffles the points of a pair with it, Fisher and Yates' way
(``j = i + bounded_rand_int(l - i)`` for ``i = 0 .. l - 1``), and fold :math:`i` is the points
``perm[i l / 5 : (i + 1) l / 5]``. The seed is
``check_random_state(random_state).randint(2**31 - 1)``, drawn in ``BaseLibSVM.fit``
(``sklearn/svm/_base.py``). Two details of the C code decide the numbers:

* every training run re-seeds the generator with the same seed (``svm_train`` calls
  ``set_seed(param->random_seed)``, and the five training runs of the folds copy that
  parameter), so the shuffle of every pair starts from the freshly seeded generator;
* the training part of a fold is grouped by class with the labels sorted, so the negative
  points come first and are the positive class of that run; its decision values are then
  multiplied by -1 (``dec_values[perm[j]] *= submodel->label[0]``).

:class:`LibsvmRandom` is that generator and :func:`cross_validated_decisions` that procedure, so
that ``A`` and ``B``, and with them :meth:`~ebantenna.ml.svc.SVC.predict_proba`, are scikit-learn's
for the same ``random_state``, within what the stopping tolerance of the fold's training runs
leaves of their decision values.

The functions take checked values: :class:`~ebantenna.ml.SVC` validates its input once.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from .._budget import check_allocation
from .._validate import check_array, check_int, check_real, real_array

__all__ = ["sigmoid_train", "sigmoid_predict", "multiclass_probability", "LibsvmRandom",
           "cross_validated_decisions", "pairwise_sigmoids", "pairwise_coupling",
           "MIN_PROBABILITY"]

#: Pairwise probabilities are kept in [MIN_PROBABILITY, 1 - MIN_PROBABILITY] before coupling.
MIN_PROBABILITY = 1e-7


def sigmoid_train(dec_values, labels) -> tuple[float, float]:
    """Platt's sigmoid ``(A, B)`` for decision values and labels, libsvm's Newton method.

    Parameters
    ----------
    dec_values : array of shape (n,)
        Decision values (positive: the positive class).
    labels : array of shape (n,)
        Positive for the positive class, otherwise the negative one.

    Returns
    -------
    (A, B) : tuple of float
        ``P(+1 | f) = 1 / (1 + exp(A f + B))``.

    Examples
    --------
    >>> A, B = sigmoid_train([-2.0, -1.0, -0.5, 0.5, 1.0, 2.0], [-1, -1, 1, -1, 1, 1])
    >>> A < 0
    True
    """
    f = check_array("dec_values", dec_values, ndim=1)
    labels = real_array("labels", labels)
    if labels.shape != f.shape:
        raise ValueError(f"labels must hold one label per decision value ({f.size}), got shape "
                         f"{labels.shape}")
    positive = labels > 0
    prior1 = float(np.count_nonzero(positive))
    prior0 = float(f.size - prior1)
    hi, lo = (prior1 + 1.0) / (prior1 + 2.0), 1.0 / (prior0 + 2.0)
    t = np.where(positive, hi, lo)
    max_iter, min_step, sigma, eps = 100, 1e-10, 1e-12, 1e-5

    def objective(a, b):
        fab = f * a + b
        # libsvm's stable form: log(1 + exp(-|fApB|)), plus t fApB or (t - 1) fApB by its sign
        tail = np.log(1 + np.exp(-np.abs(fab)))
        return _sequential_sum(np.where(fab >= 0, t * fab + tail, (t - 1) * fab + tail))

    A, B = 0.0, math.log((prior0 + 1.0) / (prior1 + 1.0))
    fval = objective(A, B)
    for _ in range(max_iter):
        fab = f * A + B
        e = np.exp(-np.abs(fab))
        p = np.where(fab >= 0, e / (1.0 + e), 1.0 / (1.0 + e))
        q = np.where(fab >= 0, 1.0 / (1.0 + e), e / (1.0 + e))
        d2 = p * q
        d1 = t - p
        h11 = _sequential_sum(f * f * d2, start=sigma)
        h22 = _sequential_sum(d2, start=sigma)
        h21 = _sequential_sum(f * d2)
        g1 = _sequential_sum(f * d1)
        g2 = _sequential_sum(d1)
        if abs(g1) < eps and abs(g2) < eps:
            break
        det = h11 * h22 - h21 * h21
        dA = -(h22 * g1 - h21 * g2) / det
        dB = -(-h21 * g1 + h11 * g2) / det
        gd = g1 * dA + g2 * dB
        step = 1.0
        while step >= min_step:
            new_a, new_b = A + step * dA, B + step * dB
            new_f = objective(new_a, new_b)
            if new_f < fval + 0.0001 * step * gd:
                A, B, fval = new_a, new_b, new_f
                break
            step /= 2.0
        if step < min_step:
            break  # line search failed, as libsvm reports and accepts
    return float(A), float(B)


def _sequential_sum(values: np.ndarray, start: float = 0.0) -> float:
    """``start`` plus the terms one after the other, as libsvm's loops add them (NumPy's sum is
    pairwise)."""
    return float(np.cumsum(np.concatenate([[start], values]))[-1])


def sigmoid_predict(dec_values, A: float, B: float) -> np.ndarray:
    """``1 / (1 + exp(A f + B))``, computed without overflow (libsvm's ``sigmoid_predict``).

    Examples
    --------
    >>> sigmoid_predict(np.array([0.0, 1e3]), -2.0, 0.0)
    array([0.5, 1. ])
    """
    A, B = check_real("A", A), check_real("B", B)
    fab = real_array("dec_values", dec_values) * A + B
    e = np.exp(-np.abs(fab))
    return np.where(fab >= 0, e / (1.0 + e), 1.0 / (1.0 + e))


def multiclass_probability(r: np.ndarray) -> np.ndarray:
    """Couple pairwise probabilities into class probabilities (Wu, Lin and Weng, method 2).

    Parameters
    ----------
    r : ndarray of shape (n_samples, k, k)
        ``r[:, i, j]`` estimates :math:`P(i \\mid i \\text{ or } j)`; ``r[:, j, i] = 1 - r[:, i,
        j]``; the diagonal is not used.

    Returns
    -------
    ndarray of shape (n_samples, k)
        Probabilities summing to 1 in each row; libsvm's fixed-point iteration, stopped when
        :math:`\\max_t |(Qp)_t - p^T Q p| < 0.005 / k` or after :math:`\\max(100, k)` sweeps.

    Examples
    --------
    >>> r = np.array([[[0, 0.9, 0.9], [0.1, 0, 0.5], [0.1, 0.5, 0]]])
    >>> np.round(multiclass_probability(r), 2)  # stopped within 0.005 / 3 of the optimum
    array([[0.82, 0.09, 0.09]])
    """
    r = check_array("r", r, ndim=3)
    if r.shape[1] != r.shape[2] or r.shape[1] < 2:
        raise ValueError(f"r must have shape (n_samples, k, k), k >= 2, got {r.shape}")
    n, k = r.shape[0], r.shape[1]
    Q = np.empty((n, k, k))
    for t in range(k):
        Q[:, t, t] = 0.0
        for j in range(t):
            Q[:, t, t] += r[:, j, t] * r[:, j, t]
            Q[:, t, j] = Q[:, j, t]
        for j in range(t + 1, k):
            Q[:, t, t] += r[:, j, t] * r[:, j, t]
            Q[:, t, j] = -r[:, j, t] * r[:, t, j]
    p = np.full((n, k), 1.0 / k)
    eps = 0.005 / k
    active = np.ones(n, dtype=bool)
    for _ in range(max(100, k)):
        Qp = np.zeros((n, k))
        pQp = np.zeros(n)
        for t in range(k):
            for j in range(k):
                Qp[:, t] += Q[:, t, j] * p[:, j]
            pQp += p[:, t] * Qp[:, t]
        max_error = np.abs(Qp - pQp[:, None]).max(axis=1)
        active &= ~(max_error < eps)
        if not active.any():
            break
        for t in range(k):
            diff = np.where(active, (-Qp[:, t] + pQp) / Q[:, t, t], 0.0)
            p[:, t] += diff
            pQp = (pQp + diff * (diff * Q[:, t, t] + 2 * Qp[:, t])) / (1 + diff) / (1 + diff)
            for j in range(k):
                Qp[:, j] = (Qp[:, j] + diff * Q[:, t, j]) / (1 + diff)
                p[:, j] /= 1 + diff
    return p


class LibsvmRandom:
    """The random generator of scikit-learn's libsvm: ``std::mt19937`` and Lemire's bounded ints.

    Parameters
    ----------
    seed : int
        In [0, 2**32): libsvm's ``random_seed``.

    Examples
    --------
    The C++ standard fixes the 10000th draw of ``std::mt19937`` with its default seed:

    >>> rng = LibsvmRandom(5489)
    >>> [rng.raw() for _ in range(10000)][-1]
    4123659995
    >>> LibsvmRandom(0).permutation(8)
    array([4, 5, 6, 7, 2, 3, 1, 0])
    """

    def __init__(self, seed: int):
        self.seed = check_int("seed", seed, minimum=0, maximum=2**32 - 1)
        self.reseed()

    def reseed(self) -> None:
        """``set_seed(seed)``: back to the first draw."""
        self._mt = np.random.RandomState(self.seed)  # init_genrand(seed), as std::mt19937

    def raw(self) -> int:
        """The next 32-bit output of the twister."""
        return int(self._mt.randint(0, 2**32, dtype=np.uint32))

    def bounded(self, bound: int) -> int:
        """``bounded_rand_int(bound)``: uniform in [0, bound), Lemire's method as libsvm's."""
        bound = check_int("bound", bound, minimum=1, maximum=2**32)
        m = self.raw() * bound
        low = m & 0xFFFFFFFF
        if low < bound:
            threshold = (2**32 - bound) % bound
            while low < threshold:
                m = self.raw() * bound
                low = m & 0xFFFFFFFF
        return m >> 32

    def permutation(self, n: int) -> np.ndarray:
        """libsvm's shuffle of ``0 .. n - 1``: swap ``i`` with ``i + bounded(n - i)``."""
        n = check_int("n", n, minimum=0)
        check_allocation(40 * n, parameter="n", what="the permutation (a list of Python ints)")
        perm = list(range(n))
        for i in range(n):
            j = i + self.bounded(n - i)
            perm[i], perm[j] = perm[j], perm[i]
        return np.array(perm, dtype=np.intp)


def cross_validated_decisions(
    n: int,
    positive: np.ndarray,
    decide: Callable[[np.ndarray, np.ndarray], np.ndarray],
    rng: LibsvmRandom,
    n_folds: int = 5,
) -> np.ndarray:
    """Decision values of each point from a machine trained without it (libsvm's five folds).

    Parameters
    ----------
    n : int
        Number of points.
    positive : ndarray of bool, shape (n,)
        The points of the positive class.
    decide : callable
        ``decide(train, test)`` trains on the points ``train`` (indices, in the order of the
        training run) and returns the decision values of the points ``test``, positive for the
        first class of ``train``.
    rng : LibsvmRandom
        Shuffles the points; re-seeded after a training run, as libsvm's ``svm_train`` does.
    n_folds : int
        Number of folds (libsvm: 5).

    Returns
    -------
    ndarray of shape (n,)
        As libsvm: a fold whose training part holds one class only gets +1 or -1.
    """
    n = check_int("n", n, minimum=1)
    positive = np.asarray(positive)
    if positive.dtype != bool or positive.shape != (n,):
        raise ValueError(f"positive must be a boolean array with one entry per point (n={n}), "
                         f"got {positive.dtype} of shape {positive.shape}")
    if not callable(decide):
        raise TypeError(f"decide must be a callable decide(train, test), got "
                        f"{type(decide).__name__}")
    if not isinstance(rng, LibsvmRandom):
        raise TypeError(f"rng must be a LibsvmRandom, got {type(rng).__name__}")
    n_folds = check_int("n_folds", n_folds, minimum=2, maximum=n)
    perm = rng.permutation(n)
    dec = np.empty(n)
    for i in range(n_folds):
        begin, end = i * n // n_folds, (i + 1) * n // n_folds
        test = perm[begin:end]
        train = np.concatenate([perm[:begin], perm[end:]])
        n_pos = int(np.count_nonzero(positive[train]))
        if test.size == 0:
            continue
        if n_pos == train.size:
            dec[test] = 1.0
        elif n_pos == 0:
            dec[test] = -1.0 if train.size else 0.0
        else:
            # libsvm groups the training part by sorted label: the negatives come first and are
            # the first class of that run, whose decision values it then negates
            grouped = np.concatenate([train[~positive[train]], train[positive[train]]])
            dec[test] = -decide(grouped, test)
            rng.reseed()
    return dec


def pairwise_sigmoids(
    members: list[np.ndarray],
    kernel_block: Callable[[np.ndarray, np.ndarray], np.ndarray],
    solve: Callable[[np.ndarray, np.ndarray, np.ndarray], tuple[np.ndarray, float]],
    rng: LibsvmRandom,
) -> tuple[np.ndarray, np.ndarray]:
    """Platt's ``A`` and ``B`` for every pair of classes, from five-fold decision values.

    Parameters
    ----------
    members : list of ndarray
        Indices of the (positively weighted) points of each class.
    kernel_block : callable
        ``kernel_block(rows, cols)``: the kernel matrix of the points ``rows`` against ``cols``.
    solve : callable
        ``solve(points, labels, K)``: train on ``points`` with labels +-1 and their kernel matrix
        ``K``; return the dual coefficients :math:`y_t \\alpha_t` and :math:`\\rho`.
    rng : LibsvmRandom
        Draws the folds.

    Returns
    -------
    probA, probB : ndarray of shape (n_pairs,)
        In the order of the pairs ``(0, 1), (0, 2), ..., (1, 2), ...``.
    """
    if not isinstance(members, list | tuple) or len(members) < 2:
        raise TypeError("members must be a list of index arrays, one per class (two at least)")
    for c, m in enumerate(members):
        if not isinstance(m, np.ndarray) or m.ndim != 1 or m.dtype.kind not in "iu" or (
                m.size == 0 or m.min() < 0):
            raise ValueError(f"members[{c}] must be a non-empty 1-D array of point indices")
    for name, f in (("kernel_block", kernel_block), ("solve", solve)):
        if not callable(f):
            raise TypeError(f"{name} must be a callable, got {type(f).__name__}")
    if not isinstance(rng, LibsvmRandom):
        raise TypeError(f"rng must be a LibsvmRandom, got {type(rng).__name__}")
    prob_a, prob_b = [], []
    k = len(members)
    for a in range(k):
        for b in range(a + 1, k):
            idx = np.concatenate([members[a], members[b]])
            ys = np.concatenate([np.ones(members[a].size), -np.ones(members[b].size)])

            def decide(train, test, idx=idx, ys=ys):
                # the first class of the run (the pair's negatives) is its positive class
                labels = ys[train[0]] * ys[train]
                coef, rho = solve(idx[train], labels, kernel_block(idx[train], idx[train]))
                return kernel_block(idx[test], idx[train]) @ coef - rho

            dec = cross_validated_decisions(idx.size, ys > 0, decide, rng)
            A, B = sigmoid_train(dec, ys)
            prob_a.append(A)
            prob_b.append(B)
    return np.array(prob_a), np.array(prob_b)


def pairwise_coupling(decisions: np.ndarray, prob_a: np.ndarray, prob_b: np.ndarray,
                      n_classes: int) -> np.ndarray:
    """Class probabilities from one-vs-one decision values, as libsvm's ``predict_probability``.

    Parameters
    ----------
    decisions : ndarray of shape (n_samples, n_pairs)
        Pairwise decision values (positive: the pair's first class).
    prob_a, prob_b : ndarray of shape (n_pairs,)
        The pairs' sigmoids.
    n_classes : int

    Returns
    -------
    ndarray of shape (n_samples, n_classes)

    Examples
    --------
    >>> pairwise_coupling(np.array([[0.0]]), np.array([-1.0]), np.array([0.0]), 2)
    array([[0.5, 0.5]])
    >>> np.round(pairwise_coupling(np.array([[2.0]]), np.array([-1.0]), np.array([0.0]), 2), 4)
    array([[0.8808, 0.1192]])
    """
    n_classes = check_int("n_classes", n_classes, minimum=2, maximum=10**4)
    pairs = n_classes * (n_classes - 1) // 2
    decisions = check_array("decisions", decisions, ndim=2, min_length=0)
    if decisions.shape[1] != pairs:
        raise ValueError(f"decisions must have one column per pair of the {n_classes} classes "
                         f"({pairs}), got shape {decisions.shape}")
    prob_a = check_array("prob_a", prob_a, ndim=1)
    prob_b = check_array("prob_b", prob_b, ndim=1)
    if prob_a.shape != (pairs,) or prob_b.shape != (pairs,):
        raise ValueError(f"prob_a and prob_b must hold one sigmoid per pair ({pairs}), got "
                         f"{prob_a.shape} and {prob_b.shape}")
    check_allocation(8 * decisions.shape[0] * n_classes**2, parameter="decisions",
                     what="the pairwise probabilities")
    n = decisions.shape[0]
    r = np.zeros((n, n_classes, n_classes))
    p = 0
    for i in range(n_classes):
        for j in range(i + 1, n_classes):
            rij = np.clip(sigmoid_predict(decisions[:, p], prob_a[p], prob_b[p]),
                          MIN_PROBABILITY, 1 - MIN_PROBABILITY)
            r[:, i, j], r[:, j, i] = rij, 1 - rij
            p += 1
    # scikit-learn's libsvm couples two classes too (upstream libsvm 3.x returns r_01, r_10): its
    # fixed-point iteration then stops once its gradient is below 0.005, which leaves it up to
    # about 0.005 from them
    return multiclass_probability(r)
