"""The sigmoid, precomputed and callable kernels and ``coef_``, against scikit-learn's libsvm."""

import numpy as np
import pytest
from sklearn.svm import SVC as LibSVC
from smo_reference import assert_pairs_follow_reference

from ebantenna.ml import SVC

EPS = np.finfo(float).eps


def _data(n=90, d=4, k=3, seed=2):
    rng = np.random.default_rng(seed)
    y = rng.integers(0, k, n)
    X = rng.normal(size=(k, d))[y] * 1.2 + rng.normal(size=(n, d))
    return X, y, rng.normal(size=(25, d))


def _compare(ours, ref, X_test, tol=1e-3):
    """libsvm_compat against libsvm: same path (equal counts) gives rounding-level agreement."""
    assert_pairs_follow_reference(ours, ref, X_test, tol=tol)


@pytest.mark.parametrize("k", [2, 3])
def test_sigmoid_kernel_matches_libsvm(k):
    X, y, Xt = _data(k=k)
    params = dict(kernel="sigmoid", gamma=0.05, coef0=0.3, C=2.0, decision_function_shape="ovo")
    ours = SVC(libsvm_compat=True, **params).fit(X, y)
    ref = LibSVC(**params).fit(X, y)
    _compare(ours, ref, Xt)


def test_precomputed_kernel_matches_libsvm_and_the_named_kernel():
    X, y, Xt = _data()
    K, Kt = X @ X.T, Xt @ X.T
    params = dict(C=2.0, decision_function_shape="ovo")
    ours = SVC(kernel="precomputed", libsvm_compat=True, **params).fit(K, y)
    ref = LibSVC(kernel="precomputed", **params).fit(K, y)
    _compare(ours, ref, Kt)
    assert ours.support_vectors_.shape == ref.support_vectors_.shape == (0, 0)
    np.testing.assert_array_equal(ours.support_, ref.support_)
    # the same machine as kernel="linear" on X: the same arithmetic, the same dual solution
    linear = SVC(kernel="linear", libsvm_compat=True, **params).fit(X, y)
    np.testing.assert_array_equal(linear.n_iter_, ours.n_iter_)
    np.testing.assert_allclose(ours.decision_function(Kt), linear.decision_function(Xt),
                               rtol=0, atol=1e-10)
    assert ours.predict(Kt).shape == (25,)


def test_precomputed_refuses_what_scikit_learn_refuses():
    X, y, _ = _data()
    for make in (SVC, LibSVC):
        with pytest.raises(ValueError, match="square"):
            make(kernel="precomputed").fit(X, y)
        fitted = make(kernel="precomputed").fit(X @ X.T, y)
        with pytest.raises(ValueError, match="features"):
            fitted.predict(X)


def test_callable_kernel_matches_libsvm():
    X, y, Xt = _data()

    def quadratic(A, B):
        return (A @ B.T + 1.0) ** 2

    params = dict(C=1.0, decision_function_shape="ovo")
    ours = SVC(kernel=quadratic, libsvm_compat=True, **params).fit(X, y)
    ref = LibSVC(kernel=quadratic, **params).fit(X, y)
    _compare(ours, ref, Xt)
    assert ours.support_vectors_.shape == ref.support_vectors_.shape == (0, 0)


def test_callable_kernel_output_is_checked():
    X, y, _ = _data()
    with pytest.raises(ValueError, match="shape"):
        SVC(kernel=lambda A, B: A @ B.T[:, :3]).fit(X, y)
    with pytest.raises(ValueError, match="not finite"):
        SVC(kernel=lambda A, B: np.full((A.shape[0], B.shape[0]), np.nan)).fit(X, y)


@pytest.mark.parametrize("k", [2, 4])
def test_coef_of_the_linear_kernel_matches_libsvm(k):
    X, y, Xt = _data(k=k, seed=5)
    ours = SVC(kernel="linear", libsvm_compat=True).fit(X, y)
    ref = LibSVC(kernel="linear").fit(X, y)
    assert ours.coef_.shape == ref.coef_.shape == (k * (k - 1) // 2, X.shape[1])
    assert not ours.coef_.flags.writeable
    np.testing.assert_array_equal(ours.n_iter_, ref.n_iter_)
    # same path: the dual coefficients agree to rounding (1e-12 of their size), and coef_ is one
    # sum over at most n support vectors of them
    scale = float(np.abs(ref.dual_coef_).sum(axis=1).max() * np.abs(X).max())
    np.testing.assert_allclose(ours.coef_, ref.coef_, rtol=0, atol=1e-12 * scale)
    # w . x + b is the decision function of each pair
    ours.set_params(decision_function_shape="ovo")
    dec = ours.decision_function(Xt)
    np.testing.assert_allclose(Xt @ ours.coef_.T + ours.intercept_,
                               dec if k > 2 else dec[:, None], atol=64 * EPS * scale)


def test_coef_only_for_the_linear_kernel():
    X, y, _ = _data()
    with pytest.raises(AttributeError, match="linear kernel"):
        _ = SVC().fit(X, y).coef_


def test_max_iter_minus_one_has_no_cap_as_in_scikit_learns_libsvm():
    # A nearly hard-margin linear problem that needs more than 100 updates per sample (upstream
    # libsvm's per-sample factor): scikit-learn's libsvm runs it to the end, and so do we.
    rng = np.random.default_rng(0)
    X = rng.normal(size=(40, 2))
    y = (X[:, 0] + 0.8 * rng.normal(size=40) > 0).astype(int)
    params = dict(kernel="linear", C=100.0, tol=1e-8, shrinking=False)
    ours = SVC(libsvm_compat=True, **params).fit(X, y)
    ref = LibSVC(**params).fit(X, y)
    assert ours.n_iter_[0] > 100 * X.shape[0]
    np.testing.assert_array_equal(ours.n_iter_, ref.n_iter_)
    assert ours.fit_status_ == ref.fit_status_ == 0


@pytest.mark.parametrize("kernel", ["rbf", "linear", "poly", "sigmoid"])
def test_gamma_zero_fits_as_in_scikit_learn(kernel):
    # gamma >= 0 is the parameter's range (scikit-learn's); with 'rbf' a gamma of 0 makes every
    # kernel entry exp(0) = 1, which the RBF step once refused with "gamma must be > 0". Every
    # entry is a constant (or, linear, gamma is unused): libsvm's path, the same decision values
    # to rounding of sums of at most n entries of size 1.
    X, y, Xt = _data(k=3)
    ours = SVC(kernel=kernel, gamma=0.0, libsvm_compat=True).fit(X, y)
    ref = LibSVC(kernel=kernel, gamma=0.0).fit(X, y)
    np.testing.assert_allclose(ours.decision_function(Xt), ref.decision_function(Xt),
                               atol=X.shape[0] * 1e3 * EPS)
