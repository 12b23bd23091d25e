"""Comparing an SMO run with a reference run of the same algorithm (libsvm's, or our own)."""

import numpy as np


def iteration_slack(n_ref):
    """How far an SMO iteration count may stray from a reference run of the same algorithm.

    Kernel values come out of BLAS sums whose last bit depends on the CPU kernel OpenBLAS picks.
    Where that bit breaks a tie between two candidate pairs differently, the path forks and rejoins
    after a few updates: measured at most 2 % apart under the OpenBLAS kernels Haswell, Prescott and
    Sandybridge. The slack allows 5 % (and 5 updates on short runs).
    """
    return max(5, int(0.05 * n_ref))


def assert_follows_reference(n, dec, n_ref, dec_ref, *, tol, same_path_atol):
    """Our SMO run against a reference run of the same algorithm on the same data.

    Iteration counts agree within :func:`iteration_slack`. Where the two paths are identical (equal
    counts) what is left of the difference is summation order: ``same_path_atol``. Where a last-bit
    difference forked them, both still stop with every KKT violation below ``tol``, and their
    decision values then differ by a few ``tol`` (measured up to 1.7 tol): 10 tol is the bound.
    """
    assert abs(int(n) - int(n_ref)) <= iteration_slack(n_ref), (n, n_ref)
    bound = same_path_atol if n == n_ref else 10.0 * tol
    assert np.abs(np.asarray(dec) - np.asarray(dec_ref)).max() <= bound


def assert_pairs_follow_reference(ours, ref, X, *, tol):
    """Every pair's dual of two fitted one-against-one SVCs (``decision_function_shape="ovo"``)
    against the reference's, by :func:`assert_follows_reference` on the decision values at ``X``.

    ``tol`` is the solvers' stopping tolerance; both bounds scale with the largest decision value
    (at least 1), as the violations do.
    """
    d_ours = ours.decision_function(X).reshape(X.shape[0], -1)
    d_ref = ref.decision_function(X).reshape(X.shape[0], -1)
    scale = max(1.0, float(np.abs(d_ref).max()))
    for p in range(ours.n_iter_.size):
        assert_follows_reference(ours.n_iter_[p], d_ours[:, p], ref.n_iter_[p], d_ref[:, p],
                                 tol=tol * scale, same_path_atol=1e-12 * scale)
