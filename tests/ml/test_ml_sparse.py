"""Sparse input: the kernels' error bound, and every estimator against itself on the dense copy
and against scikit-learn on the same sparse matrix."""

import warnings

import numpy as np
import pytest
import scipy.sparse as sp
from mlp_reference import max_abs, one_step_pair, rounding
from sklearn.exceptions import ConvergenceWarning
from sklearn.neural_network import MLPClassifier as SkClassifier
from sklearn.svm import SVC as LibSVC
from smo_reference import assert_follows_reference

from ebantenna.ml import SVC, MLPClassifier, MLPRegressor
from ebantenna.ml.kernels import Kernel, KernelRows
from ebantenna.ml.sparse_input import ETA, sparse_variance

U = np.finfo(float).eps / 2  # unit roundoff


def _sparse_data(n=150, p=30, k=3, seed=0, density=0.2):
    """Classes that differ in which features are on and how strongly (bag-of-words like)."""
    rng = np.random.default_rng(seed)
    y = rng.integers(0, k, n)
    profile = rng.uniform(0.5, 3.0, size=(k, p))
    X = profile[y] * rng.exponential(size=(n, p)) * (rng.random((n, p)) < density)
    return sp.csr_matrix(X), y


def _scale(values):
    return max(1.0, float(np.abs(values).max()))


def _per_problem(clf, X):
    """Decision values in the one-vs-one layout, one column per binary problem."""
    d = clf.decision_function(X)
    return d.reshape(X.shape[0], -1).T


# ------------------------------------------------------------------------------- the kernels
@pytest.mark.parametrize("offset", [0.0, 2.0**20, 2.0**30])
def test_sparse_rbf_distances_within_documented_bound(offset):
    rng = np.random.default_rng(4)
    n, p, gamma = 40, 12, 0.2
    # dyadic values on a grid of 2**-10: differences and squares are exact, so are the distances
    base = rng.integers(-2048, 2048, size=(n, p)) / 1024.0 * (rng.random((n, p)) < 0.4)
    base[:, 0] = offset + rng.integers(0, 4, n) / 1024.0  # one large shared feature
    Y0 = base[: n // 2].copy()
    Y0[:, 3] += 1.0 / 1024.0  # near-duplicates of the first rows: the expansion cancels there
    X, Y = sp.csr_matrix(base), sp.csr_matrix(Y0)
    d = ((base[:, None, :] - Y0[None, :, :]) ** 2).sum(axis=2)  # exact (dyadic, few bits)
    ref = np.exp(-gamma * d)
    got = Kernel("rbf", gamma=gamma).gram(X, Y)
    nnz_x, nnz_y = np.diff(X.indptr), np.diff(Y.indptr)
    relative = np.maximum(ETA, (nnz_x[:, None] + nnz_y[None, :] + 2) * U)
    # the module's bound on each distance, relative to itself, then one rounding of exp per side
    bound = gamma * ref * relative * d + 2 * U * ref
    assert np.all(np.abs(got - ref) <= bound)
    if offset >= 2.0**20:
        # libsvm's uncentred expansion (center=False) breaks the bound: cancellation
        raw = Kernel("rbf", gamma=gamma).gram(X, Y, center=False)
        assert np.any(np.abs(raw - ref) > 100 * bound)


@pytest.mark.parametrize("kernel", ["linear", "rbf", "poly", "sigmoid"])
def test_sparse_gram_and_cached_rows_match_the_dense_gram(kernel):
    X, _ = _sparse_data(n=40, p=9)
    k = Kernel(kernel, gamma=0.1, coef0=0.5, degree=2)
    dense = k.gram(X.toarray())
    scale = _scale(dense)
    # the sums run over different orders (stored entries against BLAS blocks): a few p u of the
    # entries' scale for every kernel; for rbf the two expansions' bounds add about the same
    np.testing.assert_allclose(k.gram(X), dense, rtol=0, atol=64 * 9 * U * scale)
    rows = KernelRows(X, k, np.float64, cache_bytes=3 * 40 * 8)
    assert not rows.is_full
    for i in (0, 17, 39):
        np.testing.assert_allclose(rows.row(i), dense[i], rtol=0, atol=64 * 9 * U * scale)


def test_sparse_variance_is_the_variance_of_every_entry():
    X, _ = _sparse_data(n=30, p=7)
    X = X + sp.csr_matrix(np.where(X.toarray() > 0, 1e6, 0.0))  # a large mean: E[x²]-E[x]² fails
    dense = X.toarray()
    # both are two-pass sums of the same N = 210 squares in different orders: N u relative
    assert abs(sparse_variance(X) - dense.var()) <= 210 * U * dense.var()


# ----------------------------------------------------------------------------------- the SVC
def _exact_sparse_data(k=3, seed=0, n=128, p=16):
    """Sparse features in quarters from 1/4 to 7/4, n a power of two: every norm, dot product,
    mean over the n points, centred coordinate, squared distance and variance is exact in
    float64, whatever the order of its sums. The training kernels of a sparse and a dense fit
    (and libsvm's) are then the same numbers, so the solvers take the same path, on any BLAS."""
    rng = np.random.default_rng(seed)
    y = rng.integers(0, k, n)
    on = rng.random((k, p)) < 0.5  # each class has its own likely features
    mask = rng.random((n, p)) < np.where(on[y], 0.6, 0.15)
    return sp.csr_matrix(rng.integers(1, 8, size=(n, p)) / 4.0 * mask), y


def _decision_bound(clf, X, kernel):
    """How far the decision values of two fits with the same dual coefficients may be apart when
    one computes its test kernel from the dense, the other from the sparse rows."""
    sv = clf.support_vectors_
    sv = sv.toarray() if sp.issparse(sv) else sv
    Xd = X.toarray()
    entry = 0.0  # dot products of these quarters are exact on both sides
    if kernel == "rbf":
        # the dense path centres on the mean of the support vectors, which is not exact: the
        # bound of ebantenna.ml.kernels, (p + 5) u (|x~| + |y~|)^2, times gamma, plus exp's
        m = sv.mean(axis=0)
        reach = np.linalg.norm(Xd - m, axis=1).max() + np.linalg.norm(sv - m, axis=1).max()
        entry = clf._gamma * (X.shape[1] + 5) * U * reach**2 + 2 * U
    k_max = max(1.0, float(np.abs(Kernel(kernel, gamma=clf._gamma, coef0=clf.coef0,
                                         degree=clf.degree).gram(Xd, sv)).max()))
    alpha = np.abs(clf._dual_coef_).sum(axis=1).max()
    # a decision value is sum_t alpha_t K_t + b: each entry's error weighted by |alpha|, plus
    # the sum's own rounding on each side (n_SV u sum |alpha_t K_t|)
    return alpha * (entry + 2 * sv.shape[0] * U * k_max) + 2 * U * _scale(clf.intercept_)


@pytest.mark.parametrize("libsvm_compat", [False, True])
@pytest.mark.parametrize("kernel", ["rbf", "linear", "poly", "sigmoid"])
@pytest.mark.parametrize("k", [2, 3])
def test_sparse_fit_follows_the_dense_fit(kernel, libsvm_compat, k):
    X, y = _exact_sparse_data(k=k)
    params = dict(kernel=kernel, libsvm_compat=libsvm_compat, coef0=0.25)
    s = SVC(**params).fit(X, y)
    d = SVC(**params).fit(X.toarray(), y)
    # the same training kernel (see _exact_sparse_data): the same path, update for update
    np.testing.assert_array_equal(s.n_iter_, d.n_iter_)
    np.testing.assert_array_equal(s.support_, d.support_)
    assert sp.isspmatrix_csr(s.support_vectors_) and sp.isspmatrix_csr(s.dual_coef_)
    np.testing.assert_array_equal(s.support_vectors_.toarray(), d.support_vectors_)
    np.testing.assert_array_equal(s.dual_coef_.toarray(), d.dual_coef_)
    np.testing.assert_array_equal(s.intercept_, d.intercept_)
    bound = _decision_bound(d, X, kernel)
    np.testing.assert_allclose(s.decision_function(X), d.decision_function(X.toarray()),
                               rtol=0, atol=bound)


@pytest.mark.parametrize("kernel", ["rbf", "linear", "poly", "sigmoid"])
@pytest.mark.parametrize("k", [2, 3])
def test_sparse_fit_reproduces_sklearn_on_the_same_sparse_matrix(kernel, k):
    X, y = _exact_sparse_data(k=k, seed=1)
    params = dict(kernel=kernel, coef0=0.25)
    ours = SVC(libsvm_compat=True, **params).fit(X, y)
    ref = LibSVC(**params).fit(X, y)
    dref = _per_problem(ref, X)
    # as the dense parity test: libsvm's path (its kernel is the same numbers but for the last
    # bit of exp or tanh), or a fork by such a bit that both runs close within the stopping
    # tolerance; on one path summation order is left, 1e-12 of the values' scale
    for n, d, n_ref, d_ref in zip(ours.n_iter_, _per_problem(ours, X), ref.n_iter_, dref,
                                  strict=True):
        assert_follows_reference(n, d, n_ref, d_ref, tol=1e-3, same_path_atol=1e-12 * _scale(dref))
    if np.array_equal(ours.n_iter_, ref.n_iter_):
        np.testing.assert_array_equal(ours.support_, ref.support_)
        assert (ours.support_vectors_ != ref.support_vectors_).nnz == 0
        np.testing.assert_allclose(ours.dual_coef_.toarray(), ref.dual_coef_.toarray(), rtol=0,
                                   atol=1e-12 * _scale(ref.dual_coef_.toarray()))
        if kernel == "linear":
            assert sp.issparse(ours.coef_) and not ours.coef_.data.flags.writeable
            np.testing.assert_allclose(ours.coef_.toarray(), ref.coef_.toarray(), rtol=0,
                                       atol=1e-12 * _scale(ref.coef_.toarray()))


def test_default_mode_on_sparse_data_agrees_with_sklearn_within_tolerance():
    X, y = _sparse_data(seed=2)
    ours, ref = SVC().fit(X, y), LibSVC().fit(X, y)
    # a different path (no shrinking, first index on ties), both stopped with every KKT
    # violation below tol = 1e-3: the decision values differ by a few tol
    np.testing.assert_allclose(ours.decision_function(X), ref.decision_function(X), atol=1e-2)
    np.testing.assert_array_equal(ours.predict(X), ref.predict(X))


@pytest.mark.parametrize("fmt", ["csc", "coo", "lil", "dok", "bsr", "csr_array", "csc_array"])
def test_other_sparse_formats_are_converted_to_csr(fmt):
    X, y = _sparse_data(n=60)
    other = sp.csr_array(X).tocsc() if fmt == "csc_array" else (
        sp.csr_array(X) if fmt == "csr_array" else X.asformat(fmt))
    base = SVC().fit(X, y)
    clf = SVC().fit(other, y)
    # the conversion is exact, so the fit is the same computation
    np.testing.assert_array_equal(clf.decision_function(other), base.decision_function(X))
    assert sp.isspmatrix_csr(clf.support_vectors_)


def test_unsorted_and_duplicate_indices_mean_what_they_sum_to():
    X, y = _sparse_data(n=60)
    data, indices, indptr = [], [], [0]
    for i in range(X.shape[0]):  # every entry stored twice, as halves, in reversed order
        lo, hi = X.indptr[i], X.indptr[i + 1]
        cols, vals = X.indices[lo:hi][::-1], X.data[lo:hi][::-1] / 2
        indices += [*cols, *cols]
        data += [*vals, *vals]
        indptr.append(len(indices))
    messy = sp.csr_matrix((np.array(data), np.array(indices), np.array(indptr)), shape=X.shape)
    assert not messy.has_canonical_format
    a, b = SVC().fit(X, y), SVC().fit(messy, y)
    # halves of binary floats add back exactly: once summed, the same matrix and computation
    np.testing.assert_array_equal(b.decision_function(messy), a.decision_function(X))


def test_dense_and_sparse_predictions_mix():
    X, y = _sparse_data(n=80)
    dense = SVC().fit(X.toarray(), y)
    sparse = SVC().fit(X, y)
    scale = _scale(dense.decision_function(X.toarray()))
    # other orders of the same sums in the test kernel: 1e-12 of the scale is ample
    np.testing.assert_allclose(dense.decision_function(X), dense.decision_function(X.toarray()),
                               rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(sparse.decision_function(X.toarray()),
                               sparse.decision_function(X), rtol=0, atol=1e-12 * scale)


def test_probability_and_callable_kernels_on_sparse_input():
    X, y = _sparse_data(n=90)
    # The same folds, but sparse and dense kernels round differently (1e-15), and SMO's path
    # can fork on that: a fold's fit then stops elsewhere within its tolerance (at the default
    # 1e-3, decision values 3e-4 apart were seen with numpy 1.24). Fitted to tol = 1e-10 both
    # stop within 1e-10 of the same optimum, and the Newton method on Platt's strictly convex
    # function moves its optimum by that times its condition: 1e-8 leaves a factor 100.
    s = SVC(probability=True, random_state=0, tol=1e-10).fit(X, y)
    d = SVC(probability=True, random_state=0, tol=1e-10).fit(X.toarray(), y)
    np.testing.assert_allclose(s.probA_, d.probA_, rtol=0, atol=1e-8)
    np.testing.assert_allclose(s.predict_proba(X), d.predict_proba(X.toarray()), atol=1e-8)

    def linear(a, b):  # returns a sparse matrix for sparse input, as a user's callable may
        return a @ b.T

    c = SVC(kernel=linear).fit(X, y)
    ref = SVC(kernel="linear").fit(X, y)
    scale = _scale(ref.decision_function(X))
    np.testing.assert_allclose(c.decision_function(X), ref.decision_function(X), rtol=0,
                               atol=1e-12 * scale)


def test_what_scikit_learn_refuses_is_refused_in_its_words():
    X, y = _sparse_data(n=40)
    with pytest.raises(TypeError, match="Sparse precomputed kernels are not supported"):
        SVC(kernel="precomputed").fit(sp.csr_matrix(X @ X.T), y)
    pre = SVC(kernel="precomputed").fit((X @ X.T).toarray(), y)
    with pytest.raises(TypeError, match="Sparse precomputed kernels are not supported"):
        pre.predict(sp.csr_matrix(X @ X.T))
    for est in (SVC(), MLPClassifier(max_iter=1), MLPRegressor(max_iter=1)):
        with pytest.raises(TypeError, match="Sparse data was passed for y"):
            est.fit(X, sp.csr_matrix(y[:, None].astype(float)))


# ----------------------------------------------------------------------------------- the MLPs
@pytest.mark.parametrize("fmt", ["csr", "csc", "coo"])
@pytest.mark.parametrize("solver", ["gd", "sgd", "adam", "lbfgs"])
def test_mlp_sparse_fit_follows_the_dense_fit(solver, fmt):
    X, y = _sparse_data(n=60, p=8)
    Xs = X.asformat(fmt)
    common = dict(hidden_layer_sizes=(7,), solver=solver, max_iter=8, batch_size=20,
                  learning_rate_init=0.05, random_state=0, tol=0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        s = MLPClassifier(**common).fit(Xs, y)
        d = MLPClassifier(**common).fit(X.toarray(), y)
    assert s.n_iter_ == d.n_iter_
    # only the first layer's products see the sparse matrix, summed in another order: each step
    # adds one step's rounding, carried with a gain below 2 by these small steps; lbfgs's line
    # search and two-loop recursion carry it with a gain far below 1e5 over 8 iterations
    steps = 8 * (1 if solver in ("gd", "lbfgs") else 3)
    gain = 1e5 if solver == "lbfgs" else 2
    atol = gain * steps * rounding(X, (7,), max_abs(d.coefs_ + d.intercepts_))
    for a, b in zip(s.coefs_ + s.intercepts_, d.coefs_ + d.intercepts_, strict=True):
        np.testing.assert_allclose(a, b, rtol=0, atol=atol)
    np.testing.assert_allclose(s.predict_proba(Xs), d.predict_proba(X.toarray()), rtol=0,
                               atol=atol)


def test_mlp_gd_step_on_sparse_input_equals_sklearn():
    X, y = _sparse_data(n=60, p=8)
    step = dict(hidden_layer_sizes=(5,), alpha=0.3, max_iter=1, learning_rate_init=0.05,
                random_state=0, batch_size=60)
    ours = MLPClassifier(solver="gd", **step)
    theirs = SkClassifier(solver="sgd", momentum=0.0, shuffle=False, **step)
    one_step_pair(ours, theirs, X, y)
    # one full-batch step each, sums in different orders: the rounding bound of one step
    atol = rounding(X, (5,), max_abs(theirs.coefs_ + theirs.intercepts_))
    for a, b in zip(ours.coefs_ + ours.intercepts_, theirs.coefs_ + theirs.intercepts_,
                    strict=True):
        np.testing.assert_allclose(a, b, rtol=0, atol=atol)


def test_mlp_regressor_partial_fit_on_sparse_input():
    X, _ = _sparse_data(n=60, p=8)
    target = np.asarray(X[:, 0].toarray()).ravel() - np.asarray(X[:, 1].toarray()).ravel()
    s = MLPRegressor((6,), solver="sgd", batch_size=20, random_state=0)
    d = MLPRegressor((6,), solver="sgd", batch_size=20, random_state=0)
    for _ in range(4):
        s.partial_fit(X.tocsc(), target)
        d.partial_fit(X.toarray(), target)
    # 4 epochs of 3 steps, each adding one step's rounding carried with a gain below 2
    atol = 2 * 12 * rounding(X, (6,), max_abs(d.coefs_ + d.intercepts_))
    np.testing.assert_allclose(s.predict(X), d.predict(X.toarray()), rtol=0, atol=atol)
    np.testing.assert_allclose(s.loss_curve_, d.loss_curve_, rtol=0, atol=atol)
