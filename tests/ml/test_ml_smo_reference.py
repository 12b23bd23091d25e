"""The textbook SMO of ``ebantenna.ml.smo``: each step against an independent computation, and
the engines held equal to the reference loop."""

from dataclasses import replace

import numpy as np
import pytest

from ebantenna.ml import SVC
from ebantenna.ml.kernels import Kernel, KernelRows
from ebantenna.ml.smo import (
    bias,
    reference_smo,
    select_working_set,
    solve_smo,
    solve_two_variable,
    update_gradient,
)
from ebantenna.ml.smo_policy import DEFAULT, LIBSVM

EPS = np.finfo(float).eps


def _problem(seed, n=None, kernel="rbf"):
    """Two overlapping classes, per-sample bounds, and the kernel of the points."""
    rng = np.random.default_rng(seed)
    n = n or int(rng.integers(30, 90))
    X = rng.normal(size=(n, 3))
    y = np.where(X[:, 0] + 0.8 * rng.normal(size=n) > 0, 1.0, -1.0)
    y[:2] = [1.0, -1.0]
    C = rng.uniform(0.2, 3.0, n) if seed % 2 else np.full(n, 1.5)
    kern = Kernel(kernel, gamma=0.4, coef0=1.0, degree=2)
    return X, y, C, kern


def _state(seed, n=12):
    """A feasible point somewhere in the box (some variables at a bound) and its gradient."""
    X, y, C, kern = _problem(seed, n)
    rng = np.random.default_rng(seed + 100)
    alpha = rng.uniform(0, 1, n) * C
    alpha[rng.random(n) < 0.3] = 0.0
    upper = rng.random(n) < 0.2
    alpha[upper] = C[upper]
    K = kern.gram(X)
    G = (y[:, None] * y[None, :] * K) @ alpha - 1.0  # (y^T alpha = 0 does not matter here)
    return G, y, alpha, C, K


def _objective(alpha, y, K):
    Q = y[:, None] * y[None, :] * K
    return 0.5 * alpha @ Q @ alpha - alpha.sum()


@pytest.mark.parametrize("seed", range(6))
def test_first_order_selection_is_the_maximal_violating_pair(seed):
    G, y, alpha, C, K = _state(seed)
    # I_up and I_low written out from their definition, one variable at a time
    up = [t for t in range(y.size) if (y[t] > 0 and alpha[t] < C[t]) or (y[t] < 0 and alpha[t] > 0)]
    low = [t for t in range(y.size)
           if (y[t] > 0 and alpha[t] > 0) or (y[t] < 0 and alpha[t] < C[t])]
    i_expected = max(up, key=lambda t: -y[t] * G[t])
    j_expected = min(low, key=lambda t: -y[t] * G[t])
    i, j, violation = select_working_set(G, y, alpha, C, K, rule="first-order", tol=0.0)
    assert (i, j) == (i_expected, j_expected)
    assert violation == -y[i] * G[i] + y[j] * G[j]


@pytest.mark.parametrize("seed", range(6))
def test_second_order_selection_maximises_the_decrease_of_the_objective(seed):
    G, y, alpha, C, K = _state(seed)
    i, j, _ = select_working_set(G, y, alpha, C, K, rule="second-order", tol=0.0)
    # every candidate j: the objective itself, evaluated before and after the unclipped step
    # along the direction that keeps y^T alpha (the RBF kernel is positive definite: a > 0)
    decrease = {}
    for t in range(y.size):
        in_low = (y[t] > 0 and alpha[t] > 0) or (y[t] < 0 and alpha[t] < C[t])
        b = -y[i] * G[i] + y[t] * G[t]
        if t == i or not in_low or b <= 0:
            continue
        direction = np.zeros(y.size)
        direction[i], direction[t] = y[i], -y[t]
        a = K[i, i] + K[t, t] - 2 * K[i, t]
        before = _objective(alpha, y, K)
        decrease[t] = before - _objective(alpha + (b / a) * direction, y, K)
    best = max(decrease.values())
    # the two objectives are sums of n^2 terms of size ~ max|alpha|^2: rounding ~ n^2 u of that
    assert decrease[j] >= best - y.size**2 * EPS * C.max() ** 2


@pytest.mark.parametrize("seed", range(20))
def test_two_variable_solution_is_the_minimiser_on_the_feasible_segment(seed):
    G, y, alpha, C, K = _state(seed, n=6)
    rng = np.random.default_rng(seed)
    i, j = rng.choice(y.size, 2, replace=False)
    a_i, a_j = solve_two_variable(i, j, alpha, G, y, C, K)
    assert 0 <= a_i <= C[i] and 0 <= a_j <= C[j]
    # y_i a_i + y_j a_j is kept up to the rounding of one sum and one difference
    kept = y[i] * alpha[i] + y[j] * alpha[j]
    assert abs(y[i] * a_i + y[j] * a_j - kept) <= 4 * EPS * max(C[i], C[j])

    def objective(ai, aj):  # the whole dual objective, the other variables held
        trial = alpha.copy()
        trial[i], trial[j] = ai, aj
        return _objective(trial, y, K)

    # brute force: a fine grid of alpha_j over its box, alpha_i from the constraint, kept where
    # alpha_i lies in its box too
    grid_j = np.linspace(0.0, C[j], 20001)
    grid_i = y[i] * (kept - y[j] * grid_j)
    feasible = (grid_i >= 0) & (grid_i <= C[i])
    values = [objective(ai, aj) for ai, aj in zip(grid_i[feasible], grid_j[feasible], strict=True)]
    # the grid's least value is >= the minimum: ours may exceed it only by rounding
    # (a sum of n^2 terms, n = 6)
    assert objective(a_i, a_j) <= min(values) + 64 * EPS * max(1.0, abs(min(values)))


def test_two_variable_solution_lands_exactly_on_the_bound():
    # a long step that alpha_i's bound stops: alpha_j = C_i - d with d = alpha_i - alpha_j, and
    # here (C_i - d) + d rounds to one ulp below C_i; alpha_i must be C_i itself (at its bound,
    # not free)
    C = np.array([0.1148748719756762, 5.0])
    alpha = np.array([0.09342431460975885, 2.738266731833165])
    d = alpha[0] - alpha[1]
    assert (C[0] - d) + d != C[0]
    K = np.array([[1.0, 0.1], [0.1, 1.0]])
    a_i, a_j = solve_two_variable(0, 1, alpha, np.array([-10.0, -10.0]), np.array([1.0, -1.0]),
                                  C, K)
    assert (a_i, a_j) == (C[0], C[0] - d)


@pytest.mark.parametrize("seed", range(4))
def test_gradient_update_equals_the_gradient_recomputed(seed):
    G, y, alpha, C, K = _state(seed)
    new = alpha.copy()
    new[2], new[5] = C[2] / 3, C[5] / 7
    updated = update_gradient(G, K, y, 2, 5, new[2] - alpha[2], new[5] - alpha[5])
    Q = y[:, None] * y[None, :] * K
    # both are sums of n terms of size <= max C (|K| <= 1): each within n u max C of exact
    np.testing.assert_allclose(updated, Q @ new - 1.0, rtol=0, atol=4 * y.size * EPS * C.max())


def test_bias_is_the_mean_over_free_variables_or_the_middle_of_the_interval():
    y = np.array([1.0, -1.0, 1.0, -1.0])
    C = np.ones(4)
    G = np.array([0.2, -0.6, 0.9, 0.5])  # y G = 0.2, 0.6, 0.9, -0.5
    assert bias(G, y, np.array([0.5, 0.4, 0.0, 1.0]), C) == pytest.approx((0.2 + 0.6) / 2)
    # none free: y_t G_t bounds rho from above where (y = 1, alpha = 0) or (y = -1, alpha = C):
    # 0.2, 0.9 and -0.5 -> min -0.5; from below where (y = 1, alpha = C) or (y = -1, alpha = 0)
    assert bias(G, y, np.array([1.0, 0.0, 0.0, 1.0]), C) == pytest.approx((-0.5 + 0.6) / 2)
    assert bias(G, y, np.array([0.5, 0.4, 0.0, 1.0]), C, sequential=True) == pytest.approx(0.4)


def _engine_policies():
    # every way solve_smo runs: the whole-kernel engine, and the general one with the default
    # conventions and shrinking (as with the row cache) and with libsvm's (with and without
    # shrinking); float64 kernel rows throughout, so that all solve the same problem
    return {
        "whole": DEFAULT,
        "shrinking": replace(DEFAULT, shrinking=True, curvature_floor="nonpositive"),
        "libsvm": LIBSVM,
        "libsvm-no-shrinking": replace(LIBSVM, shrinking=False),
    }


def _decision(alpha, rho, y, K):
    return K @ (alpha * y) - rho


@pytest.mark.parametrize("engine", sorted(_engine_policies()))
@pytest.mark.parametrize("selection", ["second-order", "first-order"])
@pytest.mark.parametrize("kernel, seed", [("rbf", 0), ("rbf", 1), ("linear", 2), ("poly", 3),
                                          ("rbf", 5)])
def test_engines_find_the_reference_solution(engine, selection, kernel, seed):
    X, y, C, kern = _problem(seed, kernel=kernel)
    tol = 1e-8
    policy = replace(_engine_policies()[engine], selection=selection)
    rows = KernelRows(X, kern, np.float64, cache_bytes=1 << 24)
    K = rows.block64(np.arange(y.size), np.arange(y.size))
    ref = reference_smo(K, y, C, tol=tol, selection=selection)
    fast = solve_smo(rows, y, C, diagonal=kern.diagonal(X), tol=tol, policy=policy)
    assert ref.converged and fast.converged
    np.testing.assert_array_equal(ref.alpha > 0, fast.alpha > 0)  # the same support vectors
    # Both stop with a maximal KKT violation below tol, so each duality gap is at most
    # tol * sum(C), and the primal objective, 1-strongly convex in w, puts each w within
    # sqrt(2 tol sum(C)) of the optimal one: |w_1 - w_2| <= 2 sqrt(2 tol sum(C)). On a
    # variable s free in both, |f(x_s) - y_s| <= tol for each, which bounds the biases apart by
    # 2 tol + |w_1 - w_2| sqrt(k_ss). Hence |f_1(x) - f_2(x)| <= |w_1 - w_2| (sqrt(k_xx) +
    # sqrt(k_ss)) + 2 tol.
    free = (ref.alpha > 0) & (ref.alpha < C) & (fast.alpha > 0) & (fast.alpha < C)
    assert free.any()
    root_k = np.sqrt(np.diag(K))
    dw = 2 * np.sqrt(2 * tol * C.sum())
    bound = dw * (root_k + root_k[free].min()) + 2 * tol
    difference = np.abs(_decision(ref.alpha, ref.rho, y, K) - _decision(fast.alpha, fast.rho,
                                                                          y, K))
    assert np.all(difference <= bound)


def test_svc_reference_solver_matches_the_default_fit():
    X, y, _, _ = _problem(7, n=80)
    labels = np.digitize(X[:, 1], [-0.4, 0.4])  # three classes
    fast = SVC(C=2.0, tol=1e-8).fit(X, labels)
    ref = SVC(C=2.0, tol=1e-8, solver="reference").fit(X, labels)  # the other defaults as they are
    np.testing.assert_array_equal(ref.support_, fast.support_)
    # the bound of the test above with sum(C) of the largest pair problem, k_xx = 1 (RBF)
    bound = 4 * np.sqrt(2 * 1e-8 * 2.0 * X.shape[0]) + 2e-8
    ovo = dict(decision_function_shape="ovo")
    fast.set_params(**ovo)
    ref.set_params(**ovo)
    assert np.abs(ref.decision_function(X) - fast.decision_function(X)).max() <= bound


def test_svc_reference_solver_names_what_it_does_not_do():
    X, y, _, _ = _problem(0)
    with pytest.raises(ValueError, match="libsvm_compat=True needs solver='auto'"):
        SVC(solver="reference", libsvm_compat=True).fit(X, y)


def test_svc_reference_solver_keeps_a_float64_kernel_whatever_cache_size():
    # A cache too small for the kernel in float64 sends the engines to float32 storage; the
    # reference keeps float64, so its fit does not depend on cache_size, bit for bit, and
    # shrinking (the engines' heuristic) changes nothing either.
    X, y, _, _ = _problem(3, n=60)
    fits = [SVC(C=2.0, solver="reference", cache_size=size, shrinking=shrinking).fit(X, y)
            for size in (200, 1e-4) for shrinking in (True, False)]
    for fit in fits[1:]:
        np.testing.assert_array_equal(fit.dual_coef_, fits[0].dual_coef_)
        np.testing.assert_array_equal(fit.intercept_, fits[0].intercept_)
