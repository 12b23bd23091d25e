"""The paper's one-vs-rest RBF machines: one test kernel for all of them, the whole training
kernel in float64, and what they predict against scikit-learn's."""

import logging
import pickle

import numpy as np
import pytest
import scipy.sparse as sp
from sklearn.multiclass import OneVsRestClassifier
from sklearn.svm import SVC as LibSVC

from ebantenna._budget import set_memory_budget
from ebantenna.ml import SVC
from ebantenna.ml.kernels import Kernel, resolve_gamma
from ebantenna.ml.pair_kernels import PairKernels
from ebantenna.ml.smo_policy import DEFAULT
from ebantenna.paper._ovr_svm import DEFAULT_CACHE_MB, OneVsRestSVC, whole_kernel_svc
from ebantenna.paper.experiments import classify_materials_svm
from ebantenna.paper.position_aware import PositionAwareMaterialClassifier
from ebantenna.paper.protocol import normalise_by_max

U = np.finfo(np.float64).eps / 2


def _data(n_per=30, k=5, p=12, seed=0):
    """``k`` overlapping classes of ``n_per`` rows in ``p`` dimensions, and rows to predict."""
    rng = np.random.default_rng(seed)
    y = np.repeat(np.array(["aluminium", "brass", "pvc", "steel", "wood"][:k]), n_per)
    centres = rng.normal(size=(k, p))
    X = centres[np.repeat(np.arange(k), n_per)] + rng.normal(scale=0.8, size=(k * n_per, p))
    test = centres[rng.integers(0, k, 50)] + rng.normal(scale=0.8, size=(50, p))
    return X, y, test


@pytest.fixture(scope="module")
def fitted():
    X, y, test = _data()
    shared = OneVsRestSVC(SVC(kernel="rbf", gamma="scale")).fit(X, y)
    plain = OneVsRestClassifier(SVC(kernel="rbf", gamma="scale")).fit(X, y)
    return X, y, test, shared, plain


def _machines_on_one_kernel(X, y, gamma):
    """The witness of the shared training kernel: the RBF matrix of the rows computed once, and
    one machine per class fitted on it as a precomputed kernel (that class against the rest)."""
    K = Kernel("rbf", gamma=resolve_gamma(gamma, X)).gram(X)
    return [SVC(kernel="precomputed").fit(K, (y == c).astype(int)) for c in np.unique(y)]


def _assert_same_machines(machines, witnesses):
    for a, b in zip(machines, witnesses, strict=True):
        # the same dual on the same kernel entries: the same numbers, bit for bit
        np.testing.assert_array_equal(a.support_, b.support_)
        assert a.dual_coef_.tobytes() == b.dual_coef_.tobytes()
        assert a.intercept_.tobytes() == b.intercept_.tobytes()


def test_the_machines_share_one_training_kernel(fitted):
    X, y, test, shared, plain = fitted
    assert isinstance(shared, OneVsRestClassifier)
    _assert_same_machines(shared.estimators_, _machines_on_one_kernel(X, y, "scale"))
    union = np.unique(np.concatenate([e.support_ for e in shared.estimators_]))
    np.testing.assert_array_equal(shared.support_rows_, union)
    # machines that each compute their own kernel round its entries otherwise (another centre,
    # another order): their SMO stops elsewhere within the stopping tolerance (tol = 1e-3 on
    # the KKT violation), so their decision values are a few tol apart, not bit for bit equal
    for rows in (X, test):
        assert np.abs(shared.decision_function(rows) - plain.decision_function(rows)).max() < 1e-2


def test_the_shared_kernel_is_one_product_for_every_machine(monkeypatch):
    X, y, _ = _data(k=4, n_per=10, p=5, seed=4)
    calls = []
    gram = Kernel.gram

    def counted(self, A, B=None, **kw):
        calls.append((A.shape[0], None if B is None else B.shape[0]))
        return gram(self, A, B, **kw)

    monkeypatch.setattr(Kernel, "gram", counted)
    OneVsRestSVC(SVC(kernel="rbf", gamma=0.5)).fit(X, y)
    # one whole matrix; each machine then checks eight of its rows against the kernel
    assert calls.count((40, None)) == 1
    assert calls.count((8, 40)) == 4 and len(calls) == 5


def _rounding_bound(model, X, rows, gamma="scale"):
    """How far one machine's decision values from the shared kernel may be from its own.

    Each kernel entry is computed twice, about two centres (the mean of the union of the
    support vectors, the mean of the machine's own), each within ``gamma K (p + 5) u (|x~| +
    |s~|)^2 + u K`` of the exact value (ebantenna.ml.kernels). A centre is a mean of support
    vectors, so ``|x~| + |s~| <= 2 R`` with ``R`` the diameter of the rows and the support
    vectors, and K <= 1. The sums over ``n_SV`` terms add ``n_SV u sum |c K|`` each, and the
    intercept one rounding of the result.
    """
    gamma = resolve_gamma(gamma, X)
    points = np.vstack([rows, X[model.support_rows_]])
    R2 = float(np.max(np.sum((points[:, None, :] - points[None, :, :]) ** 2, axis=-1)))
    p = rows.shape[1]
    bounds = []
    for e in model.estimators_:
        c = np.abs(e.dual_coef_[0]).sum()
        entry = 2 * U * (gamma * (p + 5) * 4 * R2 + 1)
        bounds.append(c * (entry + 2 * e.support_.size * U) + 2 * U * (c + abs(e.intercept_[0])))
    return np.array(bounds)


def test_one_test_kernel_gives_every_machines_own_decision(fitted):
    X, _, test, shared, plain = fitted
    for rows in (X, test):
        dec = shared.decision_function(rows)
        own = np.column_stack([e.decision_function(rows) for e in shared.estimators_])
        assert dec.shape == own.shape == (rows.shape[0], 5)
        bound = _rounding_bound(shared, X, rows)
        assert np.all(np.abs(dec - own) <= bound), (np.abs(dec - own).max(axis=0), bound)
        # the same class wherever the two largest values are further apart than that
        top = np.sort(own, axis=1)
        clear = top[:, -1] - top[:, -2] > 2 * bound.max()
        assert clear.sum() >= 0.9 * rows.shape[0]
        np.testing.assert_array_equal(shared.predict(rows)[clear],
                                      shared.classes_[own[clear].argmax(axis=1)])
    again = pickle.loads(pickle.dumps(shared))
    np.testing.assert_array_equal(again.decision_function(test), shared.decision_function(test))


def test_decisions_agree_with_scikit_learn_within_the_stopping_tolerance(fitted):
    X, y, test, shared, _ = fitted
    ref = OneVsRestClassifier(LibSVC(kernel="rbf", gamma="scale")).fit(X, y)
    dref = ref.decision_function(test)
    # both SMOs stop when the KKT violation is below tol = 1e-3: decision values a few tol apart
    assert np.abs(shared.decision_function(test) - dref).max() < 1e-2
    top = np.sort(dref, axis=1)
    clear = top[:, -1] - top[:, -2] > 2e-2
    np.testing.assert_array_equal(shared.predict(test)[clear], ref.predict(test)[clear])


@pytest.mark.parametrize("n", [100, 5120, 5121, 8000])
def test_the_whole_training_kernel_is_kept_in_float64(n):
    svc = whole_kernel_svc(n, C=2.0, gamma=0.5, tol=1e-4)
    assert (svc.kernel, svc.C, svc.gamma, svc.tol) == ("rbf", 2.0, 0.5, 1e-4)
    cache_bytes = int(svc.cache_size * 2**20)  # as SVC.fit reads it
    assert cache_bytes >= 8 * n * n and svc.cache_size >= DEFAULT_CACHE_MB
    assert DEFAULT.kernel_dtype(n, cache_bytes) is np.float64
    # one-vs-rest: a binary problem on all n rows, kept whole in float64 ('pairs'); with the
    # default cache a kernel of more than 5120 rows is cached row by row in float32 instead
    X = np.arange(float(n))[:, None]
    members = [np.arange(0, n, 2), np.arange(1, n, 2)]
    kernels = PairKernels(X, members, Kernel("rbf"), np.float64, cache_bytes)
    assert kernels.layout == "pairs"
    default_bytes = DEFAULT_CACHE_MB * 2**20
    default = PairKernels(X, members, Kernel("rbf"), DEFAULT.kernel_dtype(n, default_bytes),
                          default_bytes)
    assert (default.layout == "pairs") == (n <= 5120)


def test_over_the_memory_budget_the_rows_are_cached_with_a_warning(caplog):
    set_memory_budget(8 * 1000**2 - 1)
    try:
        with caplog.at_level(logging.WARNING, logger="ebantenna.paper._ovr_svm"):
            svc = whole_kernel_svc(1000, C=3.0)
    finally:
        set_memory_budget(None)
    assert svc.cache_size == DEFAULT_CACHE_MB and svc.C == 3.0
    assert "float32" in caplog.text and "1000 training rows" in caplog.text


@pytest.mark.parametrize("bad", [0, -3, 2.0, True, "10"])
def test_whole_kernel_svc_refuses_a_bad_row_count(bad):
    with pytest.raises(ValueError, match="n_rows"):
        whole_kernel_svc(bad)


@pytest.mark.parametrize("name", ["kernel", "cache_size"])
def test_whole_kernel_svc_refuses_what_it_sets(name):
    with pytest.raises(TypeError, match=name):
        whole_kernel_svc(10, **{name: 1})


def test_other_cases_predict_as_the_plain_one_vs_rest():
    X, y, test = _data(k=3, n_per=20, p=6, seed=1)
    two = y != "pvc"
    cases = [
        (SVC(kernel="rbf", gamma=0.3), X[two], y[two], test),  # two classes: one machine
        (SVC(kernel="rbf", gamma=0.3), sp.csr_matrix(X), y, sp.csr_matrix(test)),  # sparse
        (SVC(kernel="linear"), X, y, test),  # not RBF
        (LibSVC(gamma=0.3), X, y, test),  # another estimator
    ]
    for estimator, rows, labels, new in cases:
        shared = OneVsRestSVC(estimator).fit(rows, labels)
        plain = OneVsRestClassifier(estimator).fit(rows, labels)
        assert shared.support_rows_ is None
        np.testing.assert_array_equal(shared.decision_function(new), plain.decision_function(new))
        np.testing.assert_array_equal(shared.predict(new), plain.predict(new))
    shared = OneVsRestSVC(SVC(kernel="rbf", gamma=0.3)).fit(X, y)
    assert shared.support_rows_ is not None
    with pytest.raises(ValueError, match="features"):
        shared.predict(test[:, :4])
    with pytest.raises(ValueError, match="NaN"):
        shared.predict(np.full_like(test, np.nan))


def test_the_svm_experiments_model_predicts_from_features():
    X, y, test = _data(n_per=24, p=8, seed=2)
    X = np.abs(X)
    res = classify_materials_svm(X, y, gamma=2.0, seed=1)
    assert isinstance(res.model, OneVsRestSVC)
    train, rows = res.rows("train"), res.rows("test")
    Xn = normalise_by_max(X, train)
    np.testing.assert_array_equal(res.model.predict(Xn[rows]) == y[rows], res.correct("test"))
    _assert_same_machines(res.model.estimators_,
                          _machines_on_one_kernel(Xn[train], y[train], 2.0))


def test_the_position_aware_classifier_uses_the_same_machines():
    X, y, test = _data(k=3, n_per=24, p=8, seed=3)
    d = np.tile(np.repeat([0.1, 0.2, 0.3], 8), 3)
    clf = PositionAwareMaterialClassifier(gamma=0.2).fit(np.column_stack([d, X]), y)
    assert isinstance(clf.svm_, OneVsRestSVC) and clf.svm_.support_rows_ is not None
    Z = clf.standardise(np.column_stack([d, X]))
    _assert_same_machines(clf.svm_.estimators_, _machines_on_one_kernel(Z, y, 0.2))
    rows = np.column_stack([np.full(len(test), 0.15), test])
    Zrows = clf.standardise(rows)
    own = np.column_stack([e.decision_function(Zrows) for e in clf.svm_.estimators_])
    bound = _rounding_bound(clf.svm_, Z, Zrows, gamma=0.2)
    assert np.all(np.abs(clf.svm_.decision_function(Zrows) - own) <= bound)
    top = np.sort(own, axis=1)
    clear = top[:, -1] - top[:, -2] > 2 * bound.max()
    assert clear.sum() >= 0.9 * len(test)
    np.testing.assert_array_equal(clf.predict(rows)[clear],
                                  clf.svm_.classes_[own[clear].argmax(axis=1)])
