"""Which of libsvm's conventions moves which digit: each switched off alone, against libsvm."""

from dataclasses import replace

import numpy as np
import pytest
from sklearn.svm import SVC as LibSVC

from ebantenna.ml.kernels import Kernel, resolve_gamma
from ebantenna.ml.smo import DEFAULT, LIBSVM, KernelRows, solve_smo


def _problem(seed):
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(300, 5))
    y = np.where(X[:, 0] + 0.5 * X[:, 1] ** 2 + 0.5 * rng.normal(size=300) > 0.5, 1.0, -1.0)
    return X, y


def _solve(X, y, *, dtype, ties_last):
    """Our solver on libsvm's arrangement: class of the first label first, labelled +1."""
    kern = Kernel("rbf", gamma=resolve_gamma("scale", X))
    order = np.r_[np.flatnonzero(y < 0), np.flatnonzero(y > 0)]
    ys = -y[order]  # libsvm's +1 is scikit-learn's classes_[0], here y = -1
    rows = KernelRows(X[order], kern, dtype, cache_bytes=1 << 26)
    res = solve_smo(rows, ys, np.full(y.size, 2.0), diagonal=kern.diagonal(X[order]),
                    tol=1e-3, policy=replace(LIBSVM, shrinking=False) if ties_last else DEFAULT)
    dec = kern.gram(X, X[order]) @ (res.alpha * ys) - res.rho
    return res.n_iter, -dec  # scikit-learn's sign for two classes


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_each_convention_moves_its_digit(seed):
    X, y = _problem(seed)
    ref = LibSVC(C=2.0, shrinking=False).fit(X, (y > 0).astype(int))
    dref = ref.decision_function(X)
    n_ref = int(ref.n_iter_[0])

    n, dec = _solve(X, y, dtype=np.float32, ties_last=True)  # all of libsvm's conventions
    assert n == n_ref
    assert np.abs(dec - dref).max() < 1e-12

    n, dec = _solve(X, y, dtype=np.float64, ties_last=True)  # float64 kernel: 7th digit
    assert n == n_ref
    assert 1e-9 < np.abs(dec - dref).max() < 1e-5

    n, dec = _solve(X, y, dtype=np.float32, ties_last=False)  # first-index ties: another path
    assert n != n_ref
    assert 1e-5 < np.abs(dec - dref).max() < 5e-3  # within a few tol = 1e-3
