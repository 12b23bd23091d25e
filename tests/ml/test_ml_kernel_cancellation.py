"""The RBF kernel without cancellation: its error bound, and a machine that a common shift of the
features cannot change."""

import numpy as np
import pytest
from sklearn.svm import SVC as LibSVC

from ebantenna.ml import SVC
from ebantenna.ml.kernels import Kernel, KernelRows

U = np.finfo(float).eps / 2  # unit roundoff


def _dyadic_points(rng, n, p, offset):
    """Points on a grid of 2**-10 shifted by ``offset`` = 2**k: every coordinate, and every
    difference of two of them, is exact in float64, so the true distances are known."""
    base = rng.integers(-2048, 2048, size=(n, p)) / 1024.0
    return base + offset, base


@pytest.mark.parametrize("offset", [0.0, 2.0**10, 2.0**20, 2.0**30])
def test_rbf_gram_within_documented_bound(offset):
    rng = np.random.default_rng(3)
    p, gamma = 8, 0.2
    X, X0 = _dyadic_points(rng, 40, p, offset)
    Y, Y0 = _dyadic_points(rng, 30, p, offset)
    k = Kernel("rbf", gamma=gamma)
    got = k.gram(X, Y)
    d = ((X0[:, None, :] - Y0[None, :, :]) ** 2).sum(axis=2)  # exact differences, p u d error
    ref = np.exp(-gamma * d)
    m = Y.mean(axis=0)
    xn = np.linalg.norm(X - m, axis=1)
    yn = np.linalg.norm(Y - m, axis=1)
    # bound of the module notes on the centred distance, plus the reference's own rounding and
    # one rounding of exp on each side
    dist_bound = (p + 5) * U * (xn[:, None] + yn[None, :]) ** 2 + p * U * d
    bound = gamma * ref * dist_bound + 2 * U * ref
    assert np.all(np.abs(got - ref) <= bound)
    if offset >= 2.0**20:
        # the uncentred expansion (libsvm's training arithmetic) breaks the bound: cancellation
        raw = k.gram(X, Y, center=False)
        assert np.any(np.abs(raw - ref) > 100 * bound)


def test_kernel_rows_match_centred_gram():
    rng = np.random.default_rng(5)
    X = rng.normal(size=(30, 4)) + 1e6
    k = Kernel("rbf", gamma=0.5)
    cached = KernelRows(X, k, np.float64, cache_bytes=5 * 30 * 8)
    whole = k.gram(X)
    assert not cached.is_full
    for i in (0, 7, 29):
        # both centre on the same mean and expand the same way; only the GEMM blocking differs
        np.testing.assert_allclose(cached.row(i), whole[i], rtol=0, atol=64 * U)


def test_norms_only_with_uncentred_expansion():
    X = np.ones((3, 2))
    with pytest.raises(ValueError, match="center=False"):
        Kernel("rbf").gram(X, x_norms=np.ones(3))


def _three_classes(n=300, p=5, seed=1):
    rng = np.random.default_rng(seed)
    y = rng.integers(0, 3, n)
    X = rng.normal(size=(3, p))[y] * 1.5 + 0.8 * rng.normal(size=(n, p))
    return X, y, rng.normal(size=(50, p)) * 1.5


@pytest.mark.parametrize("shift", [1e3, 1e4, 1e5, 1e6])
def test_decision_values_invariant_to_a_common_shift(shift):
    X, y, Xt = _three_classes()
    params = dict(C=2.0, tol=1e-10, decision_function_shape="ovo")
    d0 = SVC(**params).fit(X, y).decision_function(Xt)
    d1 = SVC(**params).fit(X + shift, y).decision_function(Xt + shift)
    # Storing x + shift rounds each feature by up to u * shift = 1.1e-10 (features of size 1),
    # and the two runs each stop within tol = 1e-10 of the optimum: both effects are a few 1e-10.
    assert np.abs(d1 - d0).max() <= 1e-8 * np.abs(d0).max()


def test_libsvm_compat_keeps_libsvm_cancellation():
    # scikit-learn's libsvm and the libsvm_compat mode both train on the uncentred expansion:
    # at a shift of 1e6 the cancellation error (u * 1e12 ~ 1e-4 on distances of order 1) moves
    # their decision values far beyond what the shift's input rounding (1e-10) explains.
    X, y, Xt = _three_classes()
    params = dict(C=2.0, tol=1e-10, decision_function_shape="ovo")
    for make in (lambda: LibSVC(**params), lambda: SVC(libsvm_compat=True, **params)):
        d0 = make().fit(X, y).decision_function(Xt)
        d1 = make().fit(X + 1e6, y).decision_function(Xt + 1e6)
        assert np.abs(d1 - d0).max() > 1e-5 * np.abs(d0).max()
