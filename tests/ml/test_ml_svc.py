"""SVC against scikit-learn's libsvm, against the KKT conditions, and on hard numerics."""

import warnings

import numpy as np
import pytest
from sklearn.exceptions import ConvergenceWarning
from sklearn.multiclass import OneVsRestClassifier
from sklearn.svm import SVC as LibSVC
from smo_reference import assert_follows_reference, iteration_slack

from ebantenna.ml import SVC
from ebantenna.ml.kernels import Kernel, KernelRows
from ebantenna.ml.smo import solve_smo
from ebantenna.ml.smo_policy import SMOPolicy


def _data(n=240, d=6, k=3, seed=0, noise=0.6):
    rng = np.random.default_rng(seed)
    centers = rng.normal(size=(k, d)) * 1.5
    y = rng.integers(0, k, n)
    X = centers[y] + noise * rng.normal(size=(n, d))
    return X, y


def _scale(values):
    return max(1.0, float(np.abs(values).max()))


@pytest.mark.parametrize("shrinking", [False, True])
@pytest.mark.parametrize("kernel", ["rbf", "linear", "poly"])
@pytest.mark.parametrize("k", [2, 4])
def test_libsvm_compat_reproduces_sklearn(kernel, k, shrinking):
    X, y = _data(k=k, seed=k)
    params = dict(kernel=kernel, C=3.0, gamma="scale", degree=2, coef0=1.0, shrinking=shrinking)
    ref = LibSVC(**params).fit(X, y)
    ours = SVC(libsvm_compat=True, **params).fit(X, y)
    tol = 1e-3  # both defaults
    same_path = np.array_equal(ours.n_iter_, ref.n_iter_)
    ref.set_params(decision_function_shape="ovo")
    ours.set_params(decision_function_shape="ovo")
    dref, dours = ref.decision_function(X), ours.decision_function(X)
    assert dours.shape == dref.shape
    # libsvm's path in every pairwise problem (within the slack that a last-bit difference of the
    # BLAS kernel can cost); on the same path what is left is summation order in the kernel
    # sums: 1e-12 of the values' scale
    columns = zip(ours.n_iter_, dours.reshape(len(X), -1).T, ref.n_iter_,
                  dref.reshape(len(X), -1).T, strict=True)  # one per pairwise problem
    for n, d, n_ref, d_ref in columns:
        assert_follows_reference(n, d, n_ref, d_ref, tol=tol, same_path_atol=1e-12 * _scale(dref))
    if same_path:  # the same support vectors in the same layout, the same dual coefficients
        np.testing.assert_array_equal(ours.support_, ref.support_)
        np.testing.assert_array_equal(ours.n_support_, ref.n_support_)
        np.testing.assert_array_equal(ours.support_vectors_, ref.support_vectors_)
        np.testing.assert_allclose(ours.dual_coef_, ref.dual_coef_, rtol=0,
                                   atol=1e-12 * _scale(ref.dual_coef_))
        np.testing.assert_allclose(ours.intercept_, ref.intercept_, rtol=0,
                                   atol=1e-12 * _scale(ref.intercept_))
    ref.set_params(decision_function_shape="ovr")
    ours.set_params(decision_function_shape="ovr")
    assert ours.decision_function(X).shape == ref.decision_function(X).shape
    # the same class wherever libsvm's vote is not within the stopping tolerance of a tie
    sure = np.all(np.abs(dref.reshape(len(X), -1)) > 10 * tol, axis=1)
    np.testing.assert_array_equal(ours.predict(X)[sure], ref.predict(X)[sure])


def test_default_mode_agrees_within_libsvm_tolerance():
    X, y = _data(n=300, k=3, seed=5)
    ref = LibSVC(C=2.0).fit(X, y)
    ours = SVC(C=2.0).fit(X, y)
    ref.set_params(decision_function_shape="ovo")
    ours.set_params(decision_function_shape="ovo")
    dref, dours = ref.decision_function(X), ours.decision_function(X)
    # both stop when the KKT violation is below tol = 1e-3; the decision values then differ by
    # a few tol (measured: about 5e-4 on this set)
    assert np.abs(dours - dref).max() < 1e-2
    assert np.abs(dours - dref).max() > 1e-10  # a genuinely different path, not a copy
    sure = np.all(np.abs(dref) > 2e-2, axis=1)
    np.testing.assert_array_equal(ours.predict(X)[sure], ref.predict(X)[sure])
    # support vectors: both solutions satisfy the KKT conditions to within tol, so a point whose
    # margin y f(x) in every pairwise problem of its class is clearly off 1 has the same status
    # in both (inside: alpha = C; outside: alpha = 0). Only points on the margin may differ.
    disputed = set(ref.support_) ^ set(ours.support_)
    pairs = [(i, j) for i in range(3) for j in range(i + 1, 3)]
    for point in disputed:
        margins = [dref[point, p] if y[point] == i else -dref[point, p]
                   for p, (i, j) in enumerate(pairs) if y[point] in (i, j)]
        assert min(abs(m - 1.0) for m in margins) < 1e-2, point


def _kkt_violation(rows, y, C, res):
    """Independent optimality check: the largest KKT violation from the dual solution."""
    K = np.array([rows.row(i) for i in range(y.size)], dtype=np.float64)
    f = K @ (res.alpha * y) - res.rho
    margin = y * f
    at_zero = res.alpha <= 0
    at_c = res.alpha >= C
    free = ~(at_zero | at_c)
    viol = np.zeros_like(margin)
    viol[at_zero] = np.maximum(0, 1 - margin[at_zero])
    viol[at_c] = np.maximum(0, margin[at_c] - 1)
    viol[free] = np.abs(margin[free] - 1)
    return viol.max(), abs(float(res.alpha @ y))


@pytest.mark.parametrize("selection", ["second-order", "first-order"])
def test_smo_solution_satisfies_kkt(selection):
    X, y3 = _data(n=150, k=2, seed=3, noise=1.2)
    y = np.where(y3 == 0, 1.0, -1.0)
    kern = Kernel("rbf", gamma=0.2)
    rows = KernelRows(X, kern, np.float64, cache_bytes=1 << 24)
    C = np.full(y.size, 2.0)
    res = solve_smo(rows, y, C, diagonal=kern.diagonal(X), tol=1e-6,
                    policy=SMOPolicy(selection=selection))
    assert res.converged
    viol, balance = _kkt_violation(rows, y, C, res)
    # stopping rule m - M < tol bounds every KKT violation by about tol (free-variable bias
    # averaging can add at most the same again)
    assert viol < 2e-6
    assert balance < 1e-10
    assert np.all((res.alpha >= 0) & (res.alpha <= C))


def test_second_order_needs_fewer_iterations_same_optimum():
    X, y = _data(n=300, k=2, seed=11, noise=1.5)
    first = SVC(selection="first-order", tol=1e-5, C=10.0).fit(X, y)
    second = SVC(selection="second-order", tol=1e-5, C=10.0).fit(X, y)
    assert second.n_iter_[0] < first.n_iter_[0]
    np.testing.assert_allclose(first.decision_function(X), second.decision_function(X),
                               atol=1e-3)


def test_shrinking_retraces_libsvm_over_many_shrink_rounds():
    # C = 10 on overlapping classes: over 5000 updates, so the active set is shrunk (every 300
    # updates here) and rebuilt several times
    rng = np.random.default_rng(2)
    X = rng.normal(size=(300, 8))
    y = (np.sin(2 * X[:, 0]) + X[:, 1] * X[:, 2] + 0.5 * rng.normal(size=300) > 0).astype(int)
    for kernel in ("poly",):
        ref = LibSVC(C=10.0, kernel=kernel).fit(X, y)
        ours = SVC(C=10.0, kernel=kernel, libsvm_compat=True).fit(X, y)
        plain = SVC(C=10.0, kernel=kernel, libsvm_compat=True, shrinking=False).fit(X, y)
        assert ref.n_iter_[0] > 5000
        dref = ref.decision_function(X)
        assert_follows_reference(ours.n_iter_[0], ours.decision_function(X), ref.n_iter_[0],
                                 dref, tol=1e-3, same_path_atol=1e-12 * _scale(dref) * 10)
        # without shrinking another path (measured 4220 updates against 5495: far outside the
        # slack of a last-bit difference)
        assert abs(plain.n_iter_[0] - ref.n_iter_[0]) > iteration_slack(ref.n_iter_[0])
        # shrinking changes the path, not the optimum: within the stopping tolerance
        np.testing.assert_allclose(plain.decision_function(X), dref, atol=2e-2)


def test_row_cache_matches_full_kernel():
    X, y = _data(n=200, k=3, seed=2)
    full = SVC(libsvm_compat=True).fit(X, y)
    # 0.05 MB holds about 100 rows of 200 float32 entries: the row cache is used
    cached = SVC(libsvm_compat=True, cache_size=0.05).fit(X, y)
    np.testing.assert_array_equal(cached.support_, full.support_)
    np.testing.assert_allclose(cached.decision_function(X), full.decision_function(X),
                               atol=1e-9)


def test_row_cache_in_default_mode_uses_shrinking_and_agrees():
    X, y = _data(n=200, k=3, seed=2)
    full = SVC().fit(X, y)  # whole kernel in memory: solved without shrinking
    cached = SVC(cache_size=0.05).fit(X, y)  # row cache: shrinking on, a different path
    ref = LibSVC().fit(X, y)
    for model in (full, cached):
        np.testing.assert_allclose(model.decision_function(X), ref.decision_function(X),
                                   atol=5e-3)


def test_kernel_rows_cache_evicts_and_recomputes():
    X = np.random.default_rng(0).normal(size=(50, 3))
    kern = Kernel("rbf", gamma=0.5)
    rows = KernelRows(X, kern, np.float64, cache_bytes=3 * 50 * 8)
    assert not rows.is_full
    ref = kern.gram(X)
    for i in [0, 1, 2, 3, 0, 4, 1]:
        np.testing.assert_allclose(rows.row(i), ref[i], rtol=1e-14, atol=1e-15)
    assert rows.rows_computed == 7  # 3 rows fit: row 0 and row 1 were evicted before reuse


@pytest.mark.parametrize("kernel", ["rbf", "linear", "poly"])
def test_gram_matrix_against_direct_formula(kernel):
    rng = np.random.default_rng(4)
    X, Y = rng.normal(size=(7, 3)), rng.normal(size=(5, 3))
    k = Kernel(kernel, gamma=0.3, degree=3, coef0=0.5)
    direct = np.empty((7, 5))
    for i in range(7):
        for j in range(5):
            if kernel == "rbf":
                direct[i, j] = np.exp(-0.3 * np.sum((X[i] - Y[j]) ** 2))
            elif kernel == "linear":
                direct[i, j] = X[i] @ Y[j]
            else:
                direct[i, j] = (0.3 * X[i] @ Y[j] + 0.5) ** 3
    np.testing.assert_allclose(k.gram(X, Y), direct, rtol=1e-13, atol=1e-14)


def test_duplicate_points_with_conflicting_labels():
    X, y = _data(n=60, k=2, seed=1)
    X = np.vstack([X, X])
    y = np.concatenate([y, 1 - y])  # every point appears once in each class
    clf = SVC(C=1.0, libsvm_compat=True).fit(X, y)
    ref = LibSVC(C=1.0, shrinking=False).fit(X, y)
    assert np.all(np.isfinite(clf.dual_coef_)) and np.all(np.isfinite(clf.intercept_))
    assert_follows_reference(clf.n_iter_[0], clf.decision_function(X), ref.n_iter_[0],
                             ref.decision_function(X), tol=1e-3, same_path_atol=1e-12)


def test_large_c_stops_at_max_iter_with_warning():
    rng = np.random.default_rng(7)
    X = rng.normal(size=(120, 2))
    y = (X[:, 0] * X[:, 1] + 0.8 * rng.normal(size=120) > 0).astype(int)  # not separable
    with pytest.warns(ConvergenceWarning, match="max_iter=50"):
        clf = SVC(C=1e6, kernel="linear", max_iter=50).fit(X, y)
    assert clf.fit_status_ == 1
    assert clf.n_iter_[0] == 50
    assert np.all(np.isfinite(clf.decision_function(X)))


def test_large_c_and_large_gamma_converge_finite():
    X, y = _data(n=100, k=2, seed=8, noise=1.0)
    clf = SVC(C=1e6, gamma=1e3).fit(X, y)
    ref = LibSVC(C=1e6, gamma=1e3).fit(X, y)
    # with gamma = 1e3 the kernel is the identity to 1e-300: every point is its own support
    # vector and the training set is memorised
    assert clf.fit_status_ == 0
    assert clf.score(X, y) == 1.0
    assert clf.support_.size == X.shape[0] == ref.support_.size
    # different paths stop at different points of the tol = 1e-3 neighbourhood ...
    np.testing.assert_allclose(clf.decision_function(X), ref.decision_function(X), atol=2e-3)
    # ... while libsvm's arithmetic retraces libsvm's path
    compat = SVC(C=1e6, gamma=1e3, libsvm_compat=True).fit(X, y)
    ref = LibSVC(C=1e6, gamma=1e3, shrinking=False).fit(X, y)
    np.testing.assert_allclose(compat.decision_function(X), ref.decision_function(X), atol=1e-12)


def test_one_vs_rest_wrapper_and_a_single_class_split():
    X, y = _data(n=150, k=3, seed=9)
    ovr = OneVsRestClassifier(SVC(C=2.0)).fit(X, y)
    ref = OneVsRestClassifier(LibSVC(C=2.0)).fit(X, y)
    assert (ovr.predict(X) == ref.predict(X)).mean() > 0.97
    # a label present in every training example: scikit-learn warns and predicts it constantly
    Y = np.column_stack([np.ones(X.shape[0], dtype=int), (y == 1).astype(int)])
    with pytest.warns(UserWarning, match="present in all training examples"):
        single = OneVsRestClassifier(SVC()).fit(X, Y)
    assert np.all(single.predict(X)[:, 0] == 1)


@pytest.mark.parametrize(
    "params, match",
    [
        (dict(C=0.0), "C"),
        (dict(C=-1.0), "C"),
        (dict(kernel="cosine"), "kernel"),
        (dict(gamma="wide"), "gamma"),
        (dict(gamma=-1.0), "gamma"),
        (dict(tol=0.0), "tol"),
        (dict(max_iter=0), "max_iter"),
        (dict(selection="random"), "selection"),
        (dict(decision_function_shape="ovo", break_ties=True), "break_ties"),
    ],
)
def test_bad_parameters_name_themselves(params, match):
    X, y = _data(n=20, k=2)
    with pytest.raises(ValueError, match=match):
        SVC(**params).fit(X, y)


def test_single_class_is_refused():
    with pytest.raises(ValueError, match="class"):
        SVC().fit([[0.0], [1.0]], [3, 3])


def test_break_ties_predicts_argmax_of_ovr_scores():
    X, y = _data(n=200, k=4, seed=12, noise=1.5)
    clf = SVC(break_ties=True).fit(X, y)
    np.testing.assert_array_equal(clf.predict(X),
                                  clf.classes_[np.argmax(clf.decision_function(X), axis=1)])


@pytest.mark.parametrize("k", [2, 3, 5])
def test_predict_counts_the_pairs_votes(k):
    # the vote of the pair (a, b), counted here over itertools' pairs: a where its decision
    # value is positive, b elsewhere; the class with most votes, the first of a tie
    from itertools import combinations

    X, y = _data(n=150, k=k, seed=10 + k, noise=1.5)  # overlapping classes: some votes split
    svc = SVC(kernel="rbf", C=1.0, gamma=0.5).fit(X[:100], y[:100])
    dec = svc.set_params(decision_function_shape="ovo").decision_function(X[100:])
    dec = dec.reshape(len(X) - 100, -1) if k > 2 else -dec[:, None]  # binary: the pair's sign
    votes = np.zeros((dec.shape[0], k), dtype=int)
    for p, (a, b) in enumerate(combinations(range(k), 2)):
        votes[:, a] += dec[:, p] > 0
        votes[:, b] += dec[:, p] <= 0
    assert np.array_equal(svc.predict(X[100:]), svc.classes_[np.argmax(votes, axis=1)])


def test_string_labels_and_binary_sign_convention():
    X, y = _data(n=80, k=2, seed=13)
    names = np.array(["pvc", "steel"])[y]
    clf = SVC().fit(X, names)
    dec = clf.decision_function(X)
    # positive decision values mean classes_[1], as in scikit-learn
    np.testing.assert_array_equal(clf.predict(X), np.where(dec > 0, "steel", "pvc"))


def test_no_warning_on_normal_fit():
    X, y = _data()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        SVC().fit(X, y).predict(X)


@pytest.mark.parametrize("kernel", ["rbf", "linear", "poly"])
def test_identical_points_of_both_classes(kernel):
    # every kernel entry equal: the curvature of each two-variable step is 0 (libsvm's TAU
    # floor), and the bias decides alone
    X = np.zeros((21, 3))
    y = np.r_[np.zeros(10), np.ones(11)].astype(int)
    ours = SVC(kernel=kernel, libsvm_compat=True).fit(X, y)
    ref = LibSVC(kernel=kernel).fit(X, y)
    # every kernel value is exact here (exp(0) = 1, 0, coef0 ** degree), so no BLAS kernel can
    # change a comparison: the path is libsvm's, update for update
    np.testing.assert_array_equal(ours.n_iter_, ref.n_iter_)
    np.testing.assert_allclose(ours.intercept_, ref.intercept_, atol=1e-12)
    np.testing.assert_array_equal(ours.predict(X), ref.predict(X))
