"""The bookkeeping of shrinking SMO: libsvm's reordering, the reconstruction block, kept rows."""

from dataclasses import replace

import numpy as np
import pytest

from ebantenna.ml import _smo_state
from ebantenna.ml._smo_state import shrink_order
from ebantenna.ml.kernels import Kernel, KernelRows
from ebantenna.ml.smo import solve_smo
from ebantenna.ml.smo_policy import DEFAULT, LIBSVM


@pytest.fixture(autouse=True)
def _numpy_engines(monkeypatch):
    # these tests are about the NumPy engines themselves (the compiled twin has its own tests,
    # tests/ml/test_ml_smo_compiled.py): keep solve_smo on them even when numba is installed
    monkeypatch.setenv("EBANTENNA_ENGINE", "numpy")


def _libsvm_do_shrinking_order(shrink):
    """The swap loop of libsvm's ``Solver::do_shrinking``, transcribed one swap at a time."""
    shrink = list(shrink)
    order = list(range(len(shrink)))
    active = len(shrink)
    i = 0
    while i < active:
        if shrink[i]:
            active -= 1
            while active > i:
                if not shrink[active]:
                    order[i], order[active] = order[active], order[i]
                    shrink[i], shrink[active] = shrink[active], shrink[i]
                    break
                active -= 1
        i += 1
    return order, active


def test_shrink_order_makes_libsvm_swaps_at_once():
    rng = np.random.default_rng(0)
    for _ in range(3000):
        flags = rng.random(int(rng.integers(0, 40))) < rng.random()
        order, keep = shrink_order(flags)
        assert (order.tolist(), keep) == _libsvm_do_shrinking_order(flags)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("stored", [True, False])
def test_block64_is_the_rows_at_the_columns(dtype, stored):
    rng = np.random.default_rng(1)
    X = rng.normal(size=(40, 3))
    rows = KernelRows(X, Kernel("rbf", gamma=0.3), dtype,
                      cache_bytes=(1 << 20) if stored else 8 * 40 * 4)
    assert rows.is_full == stored
    r, c = rng.permutation(40)[:7], rng.permutation(40)[:11]
    block = rows.block64(r, c)
    assert block.dtype == np.float64 and block.shape == (7, 11)
    np.testing.assert_array_equal(block, np.array([rows.row(i)[c] for i in r], dtype=np.float64))
    assert rows.block64(r[:0], c).shape == (0, 11)


def test_block64_of_a_pair_in_the_whole_matrix():
    rng = np.random.default_rng(2)
    X = rng.normal(size=(30, 2))
    full = Kernel("rbf").gram(X, dtype=np.float32)
    parts = (slice(3, 10), slice(20, 30))  # the classes of a pair, not adjacent
    rows = KernelRows(None, Kernel("rbf"), np.float32, 0, full=full, parts=parts)
    r, c = np.array([0, 16, 8]), np.array([5, 1, 12, 7])
    np.testing.assert_array_equal(rows.block64(r, c), np.array([rows.row64(i)[c] for i in r]))


def _shrinking_problem():
    rng = np.random.default_rng(3)
    X = rng.normal(size=(1300, 4))  # over 1000 variables: the loop shrinks more than once
    y = np.where(X[:, 0] + X[:, 1] ** 2 + 0.8 * rng.normal(size=1300) > 1.0, 1.0, -1.0)
    kern = Kernel("rbf", gamma=0.5)
    return KernelRows(X, kern, np.float32, 1 << 24), y, kern.diagonal(X)


@pytest.mark.parametrize("policy", [LIBSVM, replace(DEFAULT, shrinking=True)])
def test_kept_rows_do_not_change_the_solution(monkeypatch, policy):
    # the kernel rows and curvatures kept between updates are the rows themselves: with room
    # for two of them only, the same steps to the last bit, through the general engine's own
    # update (LIBSVM) and through the whole-kernel loop (DEFAULT)
    rows, y, diagonal = _shrinking_problem()
    C = np.full(y.size, 4.0)
    kept = solve_smo(rows, y, C, diagonal=diagonal, policy=policy)
    monkeypatch.setattr(_smo_state, "ROW_MEMO_BYTES", 0)
    few = solve_smo(rows, y, C, diagonal=diagonal, policy=policy)
    assert kept.converged and kept.n_iter > 2000
    assert kept.n_iter == few.n_iter
    np.testing.assert_array_equal(kept.alpha, few.alpha)
    assert (kept.rho, kept.objective) == (few.rho, few.objective)


def test_shrinking_reaches_the_optimum_of_the_whole_problem():
    rows, y, diagonal = _shrinking_problem()
    C = np.full(y.size, 4.0)
    shrunk = solve_smo(rows, y, C, diagonal=diagonal, tol=1e-6, policy=LIBSVM)
    whole = solve_smo(rows, y, C, diagonal=diagonal, tol=1e-6,
                      policy=replace(LIBSVM, shrinking=False))
    assert shrunk.converged and whole.converged
    assert shrunk.objective == pytest.approx(whole.objective, rel=1e-9)
    assert abs(shrunk.rho - whole.rho) < 1e-5



@pytest.mark.parametrize("piece_bytes", [0, 3 * 8 * 1000])
def test_reconstruction_in_pieces_adds_in_the_same_order(monkeypatch, piece_bytes):
    # the gradient of the variables set aside is rebuilt from the (free, set aside) block in
    # pieces of rows, each piece's running sum starting from the last: one row per piece
    # (0 bytes) or a few, the same additions in the same order as the whole block at once
    rows, y, diagonal = _shrinking_problem()
    C = np.full(y.size, 4.0)
    calls = []
    reconstruct = _smo_state.DualState.reconstruct

    def counted(state):
        free = (state.alpha > 0) & (state.alpha < state.C)
        calls.append((int(np.count_nonzero(free[: state.active])), state.n - state.active))
        reconstruct(state)

    monkeypatch.setattr(_smo_state.DualState, "reconstruct", counted)
    whole = solve_smo(rows, y, C, diagonal=diagonal, policy=LIBSVM)
    assert any(free > 3 and aside > 0 for free, aside in calls)  # pieces of several rows
    monkeypatch.setattr(_smo_state, "RECONSTRUCT_BYTES", piece_bytes)
    pieces = solve_smo(rows, y, C, diagonal=diagonal, policy=LIBSVM)
    assert whole.n_iter == pieces.n_iter
    np.testing.assert_array_equal(whole.alpha, pieces.alpha)
    assert (whole.rho, whole.objective) == (pieces.rho, pieces.objective)
