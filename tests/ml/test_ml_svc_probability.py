"""SVC(probability=True): Platt's sigmoid and pairwise coupling against libsvm and an exact
optimum."""

import copy
import warnings

import numpy as np
import pytest
from scipy import optimize
from sklearn import datasets
from sklearn.exceptions import NotFittedError
from sklearn.preprocessing import StandardScaler
from sklearn.svm import SVC as LibSVC

from ebantenna.ml import SVC
from ebantenna.ml.platt import (
    LibsvmRandom,
    multiclass_probability,
    sigmoid_predict,
    sigmoid_train,
)

EPS = np.finfo(float).eps


def _data(k, n=120, seed=0):
    rng = np.random.default_rng(seed)
    y = rng.integers(0, k, n)
    X = rng.normal(size=(n, 4)) + 0.8 * y[:, None]
    return X, y, rng.normal(size=(30, 4)) + 0.8


def _libsvm(X, y, **params):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FutureWarning)  # scikit-learn >= 1.9 deprecates it
        return LibSVC(**params).fit(X, y)


def _platt_objective(theta, f, t):
    fab = theta[0] * f + theta[1]
    return np.sum(t * fab + np.logaddexp(0, -fab))


@pytest.mark.parametrize("seed", range(4))
def test_sigmoid_train_reaches_the_optimum_within_its_stopping_rule(seed):
    rng = np.random.default_rng(seed)
    labels = rng.choice([-1, 1], 80)
    f = labels * rng.gamma(2.0, 0.6, 80) + 0.7 * rng.normal(size=80)  # overlapping classes
    A, B = sigmoid_train(f, labels)
    n_pos, n_neg = np.sum(labels > 0), np.sum(labels < 0)
    t = np.where(labels > 0, (n_pos + 1) / (n_pos + 2), 1 / (n_neg + 2))
    exact = optimize.minimize(_platt_objective, [A, B], args=(f, t), method="Newton-CG",
                              jac=lambda th, f, t: _gradient(th, f, t),
                              hess=lambda th, f, t: _hessian(th, f, t),
                              options={"xtol": 1e-14}).x
    # libsvm stops once both gradient components are below 1e-5: the distance to the optimum is
    # then at most |H^-1| * sqrt(2) * 1e-5 (the objective is strictly convex)
    bound = np.linalg.norm(np.linalg.inv(_hessian(exact, f, t)), 2) * np.sqrt(2) * 1e-5
    assert np.hypot(A - exact[0], B - exact[1]) <= bound


def _gradient(theta, f, t):
    p = sigmoid_predict(f, *theta)  # P(+1) = 1 / (1 + exp(A f + B))
    d = t - p
    return np.array([np.sum(f * d), np.sum(d)])


def _hessian(theta, f, t):
    p = sigmoid_predict(f, *theta)
    w = p * (1 - p)
    return np.array([[np.sum(f * f * w), np.sum(f * w)], [np.sum(f * w), np.sum(w)]])


def test_coupling_solves_wu_lin_weng_problem():
    rng = np.random.default_rng(1)
    k = 4
    r = np.zeros((50, k, k))
    for i in range(k):
        for j in range(i + 1, k):
            r[:, i, j] = rng.uniform(0.05, 0.95, 50)
            r[:, j, i] = 1 - r[:, i, j]
    p = multiclass_probability(r)
    assert np.allclose(p.sum(axis=1), 1.0, atol=64 * EPS) and (p > 0).all()
    for n in range(5):
        # the minimiser of p^T Q p on the simplex solves [[Q, 1], [1^T, 0]] [p; b] = [0; 1]
        Q = np.diag([(r[n, :, t] ** 2).sum() - r[n, t, t] ** 2 for t in range(k)])
        for t in range(k):
            for j in range(k):
                if j != t:
                    Q[t, j] = -r[n, j, t] * r[n, t, j]
        kkt = np.block([[Q, np.ones((k, 1))], [np.ones((1, k)), np.zeros((1, 1))]])
        exact = np.linalg.solve(kkt, np.r_[np.zeros(k), 1.0])[:k]
        # the iteration stops when max_t |(Qp)_t - p^T Q p| < 0.005 / k: an error of at most
        # that over the smallest eigenvalue of Q on the simplex's tangent space
        basis = np.linalg.svd(np.ones((1, k)))[2][1:].T
        lam = np.linalg.eigvalsh(basis.T @ Q @ basis).min()
        assert np.abs(p[n] - exact).max() <= 2 * 0.005 / k / lam


@pytest.mark.parametrize("k", [2, 3])
def test_predict_proba_is_libsvm_given_libsvm_sigmoids(k):
    X, y, Xt = _data(k)
    ours = SVC(probability=True, libsvm_compat=True, random_state=0).fit(X, y)
    ref = _libsvm(X, y, probability=True, random_state=0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FutureWarning)
        ours.probA_, ours.probB_ = ref.probA_.copy(), ref.probB_.copy()
        expected = ref.predict_proba(Xt)
    np.testing.assert_array_equal(ours.n_iter_, ref.n_iter_)
    # the same path gives decision values equal to rounding (1e-12 of their size); the sigmoid
    # and the coupling iteration are then the same operations on the same numbers
    np.testing.assert_allclose(ours.predict_proba(Xt), expected, rtol=0, atol=1e-10)
    np.testing.assert_allclose(ours.predict_log_proba(Xt), np.log(expected), rtol=1e-9)


def test_the_generator_is_scikit_learns_libsvm_generator():
    # scikit-learn's own wrappers of newrand.h are the witness
    from sklearn.svm._newrand import bounded_rand_int_wrap, set_seed_wrap

    for seed in (0, 1, 12345, 2**31 - 2):
        ours = LibsvmRandom(seed)
        set_seed_wrap(seed)
        bounds = [1, 2, 3, 7, 1000, 2**31 - 1, 2**32 - 1, 3 * 2**30]
        for bound in bounds * 50:
            assert ours.bounded(bound) == bounded_rand_int_wrap(bound)


@pytest.mark.parametrize("name", ["iris", "wine", "breast_cancer"])
@pytest.mark.parametrize("kernel", ["rbf", "linear", "sigmoid"])
def test_predict_proba_is_scikit_learns_with_libsvm_compat(name, kernel):
    X, y = getattr(datasets, f"load_{name}")(return_X_y=True)
    X = StandardScaler().fit_transform(X)
    for random_state in (0, 7, np.random.RandomState(3)):
        theirs = copy.deepcopy(random_state)
        ours = SVC(kernel=kernel, probability=True, random_state=random_state,
                   libsvm_compat=True).fit(X, y)
        ref = _libsvm(X, y, kernel=kernel, probability=True, random_state=theirs)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", FutureWarning)
            expected = ref.predict_proba(X)
            ref_a, ref_b = ref.probA_, ref.probB_
        # the same folds, and in each the same training run as libsvm's (same path): decision
        # values equal to rounding, then the same Newton steps on them; the coupling iteration
        # and the sigmoid are a few dozen operations on numbers of order 1
        np.testing.assert_allclose(ours.probA_, ref_a, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(ours.probB_, ref_b, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(ours.predict_proba(X), expected, rtol=0, atol=1e-12)


def test_predict_proba_of_the_default_mode_within_what_tol_allows():
    X, y = datasets.load_breast_cancer(return_X_y=True)
    X = StandardScaler().fit_transform(X)
    tol = 1e-3
    ours = SVC(probability=True, random_state=0, tol=tol).fit(X, y)
    ref = _libsvm(X, y, probability=True, random_state=0, tol=tol)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FutureWarning)
        expected, ref_a, ref_b = ref.predict_proba(X), ref.probA_, ref.probB_
    # the same folds; each training run stops at a KKT violation below tol on its own path, so
    # the decision values differ by a few tol of their scale (10 tol bounds the forks of
    # smo_reference). P = 1 / (1 + exp(A f + B)) has dP = P (1 - P) (f dA + dB + A df), and
    # P (1 - P) <= 1/4: that bounds the probabilities, with dA, dB as fitted
    f = ref.decision_function(X)
    scale = float(np.abs(f).max())
    dA, dB = abs(ours.probA_[0] - ref_a[0]), abs(ours.probB_[0] - ref_b[0])
    assert dA <= 0.01 * abs(ref_a[0]) and dB <= 0.01 * max(1.0, abs(ref_b[0]))
    bound = 0.25 * (np.abs(f) * dA + dB + abs(ref_a[0]) * 10 * tol * scale)
    assert np.all(np.abs(ours.predict_proba(X)[:, 0] - expected[:, 0]) <= bound)
    same_seed = SVC(probability=True, random_state=0).fit(X, y)
    np.testing.assert_array_equal(same_seed.probA_, ours.probA_)


def test_predict_proba_only_with_probability():
    X, y, _ = _data(2)
    assert not hasattr(SVC(), "predict_proba")
    fitted = SVC().fit(X, y).set_params(probability=True)
    with pytest.raises(NotFittedError, match="probability=False"):
        fitted.predict_proba(X)
