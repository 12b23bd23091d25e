"""The two SMO loops: the whole-kernel one (``_smo_whole``) against the general engine's own
update (``_smo_state``), to the last bit, and libsvm's two-variable step (``_smo_step``)."""

from dataclasses import replace

import numpy as np
import pytest

from ebantenna.ml import _smo_state, smo
from ebantenna.ml._smo_step import pair_step
from ebantenna.ml._smo_whole import runs_whole
from ebantenna.ml.kernels import Kernel, KernelRows
from ebantenna.ml.smo_policy import DEFAULT, LIBSVM


@pytest.fixture(autouse=True)
def _numpy_engines(monkeypatch):
    # these tests are about the NumPy engines themselves (the compiled twin has its own tests,
    # tests/ml/test_ml_smo_compiled.py): keep solve_smo on them even when numba is installed
    monkeypatch.setenv("EBANTENNA_ENGINE", "numpy")


def _problem(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(20, 160))
    X = rng.normal(size=(n, 3))
    y = np.where(X[:, 0] + 0.7 * rng.normal(size=n) > 0, 1.0, -1.0)
    y[:2] = [1.0, -1.0]  # both classes
    C = rng.uniform(0.1, 5.0, n) if seed % 2 else np.full(n, 1.0)
    return X, y, C


def _solve_both(monkeypatch, rows, y, C, diagonal, **kwargs):
    # the NumPy engines, whether numba is installed or not
    fast = smo.solve_smo(rows, y, C, diagonal=diagonal, engine="numpy", **kwargs)
    with monkeypatch.context() as m:
        m.setattr(_smo_state, "runs_whole", lambda policy, C: False)
        general = smo.solve_smo(rows, y, C, diagonal=diagonal, engine="numpy", **kwargs)
    return fast, general


@pytest.mark.parametrize("selection", ["second-order", "first-order"])
@pytest.mark.parametrize("kernel", ["rbf", "linear", "poly"])
@pytest.mark.parametrize("seed", range(4))
def test_same_steps_as_the_general_loop(monkeypatch, seed, kernel, selection):
    # The same floating-point operations in the same order (the module text): the same path and
    # the same numbers to the last bit, whatever the BLAS, because the loop uses no BLAS.
    X, y, C = _problem(seed)
    kern = Kernel(kernel, gamma=0.5, coef0=1.0)
    policy = replace(DEFAULT, selection=selection)
    rows = KernelRows(X, kern, np.float64, cache_bytes=1 << 24)
    fast, general = _solve_both(monkeypatch, rows, y, C, kern.diagonal(X), tol=1e-6,
                                policy=policy)
    assert fast.converged and general.converged
    assert fast.n_iter == general.n_iter
    np.testing.assert_array_equal(fast.alpha, general.alpha)
    assert (fast.rho, fast.objective, fast.violation) == (
        general.rho, general.objective, general.violation)


def test_same_stop_at_max_iter_on_float32_rows(monkeypatch):
    # rows assembled from two slices of a float32 matrix (the whole-matrix layout of a fit)
    X, y, C = _problem(5)
    kern = Kernel("rbf", gamma=0.5)
    order = np.concatenate([np.flatnonzero(y > 0), np.flatnonzero(y < 0)])
    X, y, C = X[order], y[order], C[order]
    full = kern.gram(np.vstack([X[:3], X]), dtype=np.float32)  # three extra points first
    npos = int((y > 0).sum())
    parts = (slice(3, 3 + npos), slice(3 + npos, 3 + y.size))
    rows = KernelRows(None, kern, np.float32, 0, full=full, parts=parts)
    fast, general = _solve_both(monkeypatch, rows, y, C, kern.diagonal(X), max_iter=7)
    assert fast.n_iter == general.n_iter == 7
    assert not fast.converged and not general.converged
    np.testing.assert_array_equal(fast.alpha, general.alpha)
    assert (fast.rho, fast.violation) == (general.rho, general.violation)


def test_which_policies_run_the_whole_loop():
    C = np.ones(4)
    assert runs_whole(DEFAULT, C)
    assert runs_whole(replace(DEFAULT, selection="first-order", bias_sum="sequential"), C)
    assert not runs_whole(LIBSVM, C)
    # with shrinking or libsvm's floor it takes the updates before the first shrinking
    assert runs_whole(replace(DEFAULT, shrinking=True), C)
    assert runs_whole(replace(DEFAULT, curvature_floor="nonpositive"), C)
    assert not runs_whole(replace(DEFAULT, ties="last"), C)
    # a zero bound puts a variable in neither I_up nor I_low: its gradient would be lost
    assert not runs_whole(DEFAULT, np.array([1.0, 0.0, 1.0, 1.0]))


@pytest.mark.parametrize("floor", ["tau", "nonpositive"])
@pytest.mark.parametrize("max_iter", [10_000_000, 1000, 1500])
def test_runs_between_shrinkings_take_the_same_steps(monkeypatch, floor, max_iter):
    # the whole-kernel loop takes the updates between libsvm's shrinkings (every 1000 here) on
    # the general engine's state: the path and the numbers of the general engine alone, to the
    # last bit, through several shrinkings and a gradient reconstruction, and when max_iter
    # stops the run at the first shrinking or after it
    rng = np.random.default_rng(7)
    X = rng.normal(size=(1300, 2))
    y = np.where(X[:, 0] + X[:, 1] ** 2 + 0.8 * rng.normal(size=1300) > 1.0, 1.0, -1.0)
    kern = Kernel("rbf", gamma=0.5)
    rows = KernelRows(X, kern, np.float64, cache_bytes=1 << 24)
    policy = replace(DEFAULT, shrinking=True, curvature_floor=floor)
    fast, general = _solve_both(monkeypatch, rows, y, np.full(y.size, 4.0), kern.diagonal(X),
                                tol=1e-5, policy=policy, max_iter=max_iter)
    assert fast.n_iter == general.n_iter and fast.n_iter >= 1000
    assert fast.converged == general.converged == (max_iter > 1500)
    np.testing.assert_array_equal(fast.alpha, general.alpha)
    assert (fast.rho, fast.objective, fast.violation) == (
        general.rho, general.objective, general.violation)


@pytest.mark.parametrize("seed, kernel, C", [(0, "rbf", 10.0), (4, "linear", 1.0)])
def test_every_stop_between_shrinkings_is_the_general_engines(monkeypatch, seed, kernel, C):
    # 40 variables: shrinkings every 40 updates, gradient reconstructions (two and one here)
    # and the single update after each; stopped by max_iter at every count, the loop leaves
    # the state of the general engine, to the last bit
    X, y, _ = _problem(seed)
    X, y, C = X[:40], y[:40], np.full(40, C)
    kern = Kernel(kernel, gamma=0.5)
    rows = KernelRows(X, kern, np.float64, cache_bytes=1 << 24)
    policy = replace(DEFAULT, shrinking=True)
    full, _ = _solve_both(monkeypatch, rows, y, C, kern.diagonal(X), policy=policy)
    assert full.converged and full.n_iter > 2 * 40  # past two shrinkings
    for max_iter in range(1, full.n_iter + 2):
        fast, general = _solve_both(monkeypatch, rows, y, C, kern.diagonal(X), policy=policy,
                                    max_iter=max_iter)
        assert fast.n_iter == general.n_iter == min(max_iter, full.n_iter)
        assert fast.converged == general.converged == (max_iter > full.n_iter)
        np.testing.assert_array_equal(fast.alpha, general.alpha)
        assert (fast.rho, fast.violation) == (general.rho, general.violation)


def test_pair_step_keeps_the_equality_constraint_and_the_box():
    rng = np.random.default_rng(0)
    for _ in range(200):
        yi, yj = rng.choice([-1.0, 1.0], 2)
        Ci, Cj = rng.uniform(0.1, 3.0, 2)
        ai, aj = rng.uniform(0, Ci), rng.uniform(0, Cj)
        Gi, Gj = rng.normal(size=2)
        Kij = rng.uniform(-1, 1)
        ni, nj = pair_step(yi, yj, 2.0, 2.0, Ci, Cj, ai, aj, Gi, Gj, Kij)
        # y_i a_i + y_j a_j is kept up to the rounding of the two sums (a few u of max(C))
        assert abs((yi * ni + yj * nj) - (yi * ai + yj * aj)) <= 8 * np.finfo(float).eps * 3
        assert 0 <= ni <= Ci and 0 <= nj <= Cj
