"""The kernels of the one-vs-one problems built pair by pair (``ebantenna.ml.pair_kernels``)."""

import numpy as np
import pytest
import scipy.sparse as sp

from ebantenna.ml.kernels import Kernel
from ebantenna.ml.pair_kernels import PairKernels

U = np.finfo(float).eps / 2  # unit roundoff


def _dyadic_classes(sizes, p, offset, seed=0):
    """Points on a grid of 2**-10 shifted by ``offset`` = 2**k, class by class: every difference
    of two coordinates is exact, so the true distances are known."""
    rng = np.random.default_rng(seed)
    base = rng.integers(-2048, 2048, size=(sum(sizes), p)) / 1024.0
    members, start = [], 0
    for size in sizes:
        members.append(np.arange(start, start + size))
        start += size
    perm = rng.permutation(base.shape[0])  # classes interleaved in X, as in real data
    inverse = np.argsort(perm)
    return base[perm] + offset, base[perm], [inverse[m] for m in members]


@pytest.mark.parametrize("offset", [0.0, 2.0**20])
def test_pair_kernels_within_the_documented_bound(offset):
    p, gamma = 6, 0.3
    X, X0, members = _dyadic_classes([9, 14, 5, 11], p, offset)
    kern = Kernel("rbf", gamma=gamma)
    kernels = PairKernels(X, members, kern, np.float64, cache_bytes=1 << 20)
    assert kernels.layout == "pairs" and kernels.stored
    m = X[np.concatenate(members)].mean(axis=0)  # the one centre of every block
    k = len(members)
    seen = []
    # the order of a fit, with blocks kept and moved from pair to pair
    for a, b, rows in kernels.pairs():
        seen.append((a, b))
        idx = np.concatenate([members[a], members[b]])
        K = np.array([rows.row64(i) for i in range(idx.size)])
        d = ((X0[idx, None, :] - X0[None, idx, :]) ** 2).sum(axis=2)  # p u d error
        ref = np.exp(-gamma * d)
        norms = np.linalg.norm(X[idx] - m, axis=1)
        # the module notes' bound on the centred distance, the reference's own rounding, one
        # rounding of exp on each side
        dist_bound = (p + 5) * U * (norms[:, None] + norms[None, :]) ** 2 + p * U * d
        assert np.all(np.abs(K - ref) <= gamma * ref * dist_bound + 2 * U * ref), (a, b)
        np.testing.assert_array_equal(K, K.T)  # mirrored, not recomputed
        np.testing.assert_array_equal(np.diag(K), 1.0)
    assert sorted(seen) == [(a, b) for a in range(k) for b in range(a + 1, k)]
    # any order: a block not at hand is computed (1e-12: the bound above stays below 1e-13 for
    # these points, whose centred norms are at most 2 sqrt(6))
    for a, b in [(2, 3), (0, 1), (0, 3), (1, 2)]:
        K = np.array([kernels.rows(a, b).row64(i) for i in range(6)])
        idx = np.concatenate([members[a], members[b]])[:6]
        ref = np.exp(-gamma * ((X0[idx, None, :] - X0[None, idx, :]) ** 2).sum(axis=2))
        np.testing.assert_allclose(K[:, :6], ref, rtol=0, atol=1e-12)


@pytest.mark.parametrize("kernel", ["linear", "poly", "sigmoid"])
def test_dot_kernels_pair_by_pair_against_direct_formula(kernel):
    rng = np.random.default_rng(2)
    X = rng.normal(size=(40, 5))
    members = [np.flatnonzero(np.arange(40) % 3 == c) for c in range(3)]
    kern = Kernel(kernel, gamma=0.3, coef0=0.5, degree=3)
    kernels = PairKernels(X, members, kern, np.float64, cache_bytes=1 << 20)
    for a, b in [(0, 1), (0, 2), (1, 2)]:
        idx = np.concatenate([members[a], members[b]])
        dots = X[idx] @ X[idx].T
        ref = {"linear": dots, "poly": (0.3 * dots + 0.5) ** 3,
               "sigmoid": np.tanh(0.3 * dots + 0.5)}[kernel]
        rows = kernels.rows(a, b)
        K = np.array([rows.row64(i) for i in range(idx.size)])
        # each dot product of 5 terms is off by at most 5 u |x|_1 |y|_1 on either side; the
        # kernel function's slope is at most max(1, |K|) here (linear 1, sigmoid 0.3, poly
        # 0.9 t^2 <= |t|^3 for t = 0.3 x.y + 0.5 >= 0.9, below that at most 1), and its own
        # evaluation rounds a few times on each side
        scale = np.abs(X[idx]).sum(axis=1)
        slope = max(1.0, np.abs(ref).max())
        tol = 2 * 5 * U * scale[:, None] * scale[None, :] * slope + 8 * U * np.abs(ref)
        assert np.all(np.abs(K - ref) <= tol)


def test_layouts_follow_the_memory_bound():
    rng = np.random.default_rng(0)
    X = rng.normal(size=(30, 2))
    members = [np.arange(0, 10), np.arange(10, 20), np.arange(20, 30)]
    kern = Kernel("rbf")
    pair_bytes, whole_bytes = 20 * 20 * 8, 30 * 30 * 4
    assert PairKernels(X, members, kern, np.float64, pair_bytes).layout == "pairs"
    # libsvm's storage: the whole matrix in its own type, or rows on demand
    assert PairKernels(X, members, kern, np.float32, whole_bytes,
                       libsvm_compat=True).layout == "whole"
    assert PairKernels(X, members, kern, np.float32, pair_bytes - 1).layout == "cache"
    assert not PairKernels(X, members, kern, np.float32, pair_bytes - 1).stored
    assert PairKernels(sp.csr_matrix(X), members, kern, np.float32,
                       whole_bytes).layout == "whole"
    given = X @ X.T
    assert PairKernels(None, members, None, np.float64, 0, given=given).layout == "given"


def test_gram_into_a_block_of_a_larger_array():
    rng = np.random.default_rng(4)
    X, Y = rng.normal(size=(70, 3)), rng.normal(size=(50, 3))
    kern = Kernel("rbf", gamma=0.4)
    big = np.zeros((90, 90))

    def bound(A, B, K):
        # both results within the documented bound (p = 3) of the same centred expansion
        m = B.mean(axis=0)
        a, b = np.linalg.norm(A - m, axis=1), np.linalg.norm(B - m, axis=1)
        return 2 * (0.4 * K * (3 + 5) * U * (a[:, None] + b[None, :]) ** 2 + U * K)

    kern.gram(X, Y, out=big[5:75, 20:70])
    ref = kern.gram(X, Y)
    assert np.all(np.abs(big[5:75, 20:70] - ref) <= bound(X, Y, ref))
    assert not big[:5].any() and not big[75:].any() and not big[:, :20].any()
    kern.gram(X, out=big[:70, :70])
    ref = kern.gram(X)
    assert np.all(np.abs(big[:70, :70] - ref) <= bound(X, X, ref))
    with pytest.raises(ValueError, match="out must have shape"):
        kern.gram(X, Y, out=np.empty((70, 49)))


def test_a_given_float64_matrix_is_read_in_place_at_the_members_indices():
    """A float64 matrix is not copied: each pair's rows are gathered from it at its members'
    indices, the same entries as the copy sorted by class that a float32 store makes."""
    X, _, members = _dyadic_classes([6, 4, 5], 3, 0.0, seed=2)
    K = Kernel("rbf", gamma=0.4).gram(X)
    inplace = PairKernels(X, members, None, np.float64, 1 << 20, given=K)
    copied = PairKernels(X, members, None, np.float32, 1 << 20, given=K)
    assert inplace.layout == copied.layout == "given"
    for (a, b, rows), (_, _, rows32) in zip(inplace.pairs(), copied.pairs(), strict=True):
        idx = np.concatenate([members[a], members[b]])
        matrix, index = rows.stored_entries()
        assert matrix is K and np.array_equal(index, idx)
        points = np.arange(idx.size)
        np.testing.assert_array_equal(rows.block64(points, points), K[np.ix_(idx, idx)])
        for i in (0, idx.size - 1):
            np.testing.assert_array_equal(rows.row64(i), K[idx[i], idx])
            np.testing.assert_array_equal(rows32.row64(i), K[idx[i], idx].astype(np.float32))


def test_an_svc_on_a_shared_kernel_is_the_svc_on_that_kernel_precomputed():
    """``SVC.fit(X, y, kernel_matrix=K)`` solves every pair's dual on the entries of ``K``, as
    ``SVC(kernel='precomputed').fit(K, y)`` does: the same numbers, bit for bit, samples left
    out by a zero weight included; its predictions then use the named kernel."""
    from ebantenna.ml import SVC

    X, _, members = _dyadic_classes([12, 9, 10], 4, 0.0, seed=3)
    y = np.empty(X.shape[0], dtype=int)
    for c, m in enumerate(members):
        y[m] = c
    weight = np.ones(X.shape[0])
    weight[::7] = 0.0
    K = Kernel("rbf", gamma=0.5).gram(X)
    shared = SVC(gamma=0.5).fit(X, y, sample_weight=weight, kernel_matrix=K)
    witness = SVC(kernel="precomputed").fit(K, y, sample_weight=weight)
    np.testing.assert_array_equal(shared.support_, witness.support_)
    assert shared.dual_coef_.tobytes() == witness.dual_coef_.tobytes()
    assert shared.intercept_.tobytes() == witness.intercept_.tobytes()
    np.testing.assert_array_equal(shared.support_vectors_, X[shared.support_])
    # the named kernel's test matrix against the precomputed rows: entries a few 1e-16 apart
    # (two expansions of the same distances), times sum |coef| <= C n = 31: far below 1e-9
    assert np.abs(shared.decision_function(X) - witness.decision_function(K)).max() < 1e-9


def test_a_finite_matrix_whose_sum_overflows_is_not_called_infinite():
    # the given kernel's finiteness is read from its sum; finite entries near the largest
    # float overflow it, and the entries themselves are then looked at: the matrix is refused
    # for what it is (not the kernel of X), not as holding infinities
    from ebantenna.ml import SVC

    X = np.random.default_rng(0).normal(size=(6, 2))
    y = np.array([0, 1] * 3)
    huge = np.full((6, 6), np.finfo(float).max / 2)
    with np.errstate(over="ignore"):
        assert not np.isfinite(huge.sum())
    with pytest.raises(ValueError, match="kernel_matrix is not the 'rbf' kernel of X"):
        SVC(gamma=0.5).fit(X, y, kernel_matrix=huge)
