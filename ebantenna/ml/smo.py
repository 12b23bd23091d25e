"""Sequential minimal optimisation (SMO) for the binary C-support vector classifier.

The dual problem solved here is libsvm's (Chang and Lin, 2011):

.. math::

    \\min_\\alpha \\tfrac12 \\alpha^T Q \\alpha - e^T \\alpha
    \\quad\\text{s.t.}\\quad y^T \\alpha = 0,\\; 0 \\le \\alpha_i \\le C_i,
    \\qquad Q_{ij} = y_i y_j k(x_i, x_j).

Each iteration picks a *working set* of two variables :math:`(i, j)` that violate the optimality
conditions, solves the two-variable problem analytically and updates the gradient
:math:`G = Q\\alpha - e` with two kernel rows. With
:math:`I_{up} = \\{t : y_t = 1, \\alpha_t < C_t \\text{ or } y_t = -1, \\alpha_t > 0\\}` and
:math:`I_{low}` its mirror, the index :math:`i` maximises :math:`-y_t G_t` over :math:`I_{up}`; then

* ``'first-order'`` (the maximal violating pair of Keerthi et al., the refinement of Platt's
  heuristics that libsvm used before version 2.8) takes :math:`j` maximising :math:`y_t G_t` over
  :math:`I_{low}`;
* ``'second-order'`` (Fan, Chen and Lin, 2005; libsvm's choice) takes the :math:`j` whose
  two-variable step decreases the objective most, :math:`-b_{ij}^2 / a_{ij}` with
  :math:`b_{ij} = -y_i G_i + y_j G_j > 0` and :math:`a_{ij} = K_{ii} + K_{jj} - 2 K_{ij}`.

The loop stops when the maximal violation :math:`m(\\alpha) - M(\\alpha)` drops below ``tol``. The
bias is libsvm's: :math:`\\rho` is the mean of :math:`y_t G_t` over the free variables, or the
midpoint of the feasible interval when none is free; the decision function is
:math:`f(x) = \\sum_t y_t \\alpha_t k(x_t, x) - \\rho`.

Kernel rows come from :class:`~ebantenna.ml.kernels.KernelRows`, which either holds the whole matrix
(one GEMM) or keeps a least-recently-used cache of rows that are computed on demand. There is one
loop, :func:`solve_smo`; how it selects, breaks ties, floors the curvature, shrinks and sums the
bias is an :class:`~ebantenna.ml.smo_policy.SMOPolicy`, a frozen value with two
presets: :data:`~ebantenna.ml.smo_policy.DEFAULT` and :data:`~ebantenna.ml.smo_policy.LIBSVM`.
For the default conventions without shrinking, :mod:`ebantenna.ml.smo_whole` takes the same
steps, to the last bit, with fewer NumPy calls.

Conventions and the digits they move
------------------------------------
With the :data:`~ebantenna.ml.smo_policy.LIBSVM` policy (``SVC(libsvm_compat=True)``) the
solver follows libsvm's arithmetic exactly, and scikit-learn's :class:`~sklearn.svm.SVC` is
reproduced to about 1e-12 with the same iteration counts, with shrinking on (libsvm's variable
order and gradient reconstruction included) or off. What each convention does, with the field of
:class:`~ebantenna.ml.smo_policy.SMOPolicy` that holds it:

* **float32 kernel storage** (libsvm's ``Qfloat``; ``float32_kernel``): kernel entries carry a
  relative error of about 6e-8. Solving with a float64 kernel instead keeps the path (same
  iteration count on the test problems) but moves the decision values by a few 1e-7: the 7th
  digit.
* **ties broken by the last index** (libsvm's ``>=`` comparisons; ``ties='last'``): at the start
  every gradient equals -1, so the first working set is a tie. Taking the first index instead
  sends SMO down another path: another iteration count, and an optimum that differs within the
  stopping tolerance (decision values agree to about ``tol`` = 1e-3, the 3rd digit).
* **libsvm's two-variable update** (clip to the box in its order of cases; used by every policy),
  its **curvature floor** (:math:`a_{ij} \\le 0` replaced by :math:`\\tau`, where the default
  takes :math:`\\max(a_{ij}, \\tau)`; ``curvature_floor``) and its **rho formula** (sequential
  sum over the free variables; ``bias_sum``): these move the last one or two bits (about 1e-16),
  which the comparisons of the selection can amplify.
* **an RBF diagonal of exactly 1**: the expansion :math:`|x|^2 + |x|^2 - 2x\\cdot x` is exactly 0
  only when the norms and the dot products come from the same summation; with a different BLAS
  routine the diagonal is 1 - 1e-16 or so, a last-bit change of every step denominator. libsvm's
  value is exactly 1, and so is the diagonal here for 'rbf'.

What is left between the two implementations is the summation order of the kernel sums in the
decision function: about 1e-14 of the values' scale.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np

from .kernels import KernelRows
from .smo_policy import DEFAULT, LIBSVM, SELECTIONS, TAU, SMOPolicy
from .smo_whole import pair_step, run_whole, runs_whole

__all__ = ["SMOPolicy", "DEFAULT", "LIBSVM", "SMOResult", "solve_smo", "KernelRows", "SELECTIONS",
           "shrink_order", "ROW_MEMO_BYTES"]

logger = logging.getLogger(__name__)


@dataclass(frozen=True)
class SMOResult:
    """Solution of one binary SVM dual problem.

    Attributes
    ----------
    alpha : ndarray of shape (n,)
        Dual variables, :math:`0 \\le \\alpha_t \\le C_t`.
    rho : float
        Bias term: the decision function is :math:`\\sum_t y_t\\alpha_t k(x_t, x) - \\rho`.
    n_iter : int
        Number of two-variable updates.
    converged : bool
        False if ``max_iter`` stopped the loop before the violation fell below ``tol``.
    objective : float
        Dual objective :math:`\\tfrac12\\alpha^TQ\\alpha - e^T\\alpha` at the solution.
    violation : float
        Maximal violation :math:`m(\\alpha) - M(\\alpha)` at the last check: below ``tol`` when
        converged, that of the final :math:`\\alpha` otherwise.
    """

    alpha: np.ndarray
    rho: float
    n_iter: int
    converged: bool
    objective: float
    violation: float


#: Memory for the kernel rows that the SMO state keeps between updates (float64, in bytes), on
#: top of the kernel's own storage; rows that are views of a float64 kernel take none.
ROW_MEMO_BYTES = 64 << 20

#: ``ndarray.max()`` without its Python wrapper.
_largest = np.maximum.reduce


def _argmax(values: np.ndarray, last: bool) -> int:
    # the array methods, not np.argmax: the wrapper's dispatch costs more than the search on the
    # vectors of a few thousand entries that SMO scans twice per update
    if last:
        return values.size - 1 - int(values[::-1].argmax())
    return int(values.argmax())


def shrink_order(shrink: np.ndarray) -> tuple[np.ndarray, int]:
    """libsvm's reordering of the active variables when ``shrink`` marks those set aside.

    libsvm's ``do_shrinking`` walks one index up from the front and one down from the back:
    each variable to set aside that the first meets trades places with the next variable to
    keep that the second meets, until the two cross. So the k-th variable to set aside among
    the first ``keep`` positions trades places with the k-th variable to keep counted from the
    end, and all the swaps can be made at once, with one gather per array.

    Parameters
    ----------
    shrink : ndarray of bool, shape (a,)
        True for the active variables to set aside.

    Returns
    -------
    order : ndarray of int, shape (a,)
        Position ``p`` receives the variable at ``order[p]``.
    keep : int
        The new number of active variables (those not set aside come first).

    Examples
    --------
    >>> shrink_order(np.array([True, False, True, False, False]))
    (array([4, 1, 3, 2, 0]), 3)
    """
    a = shrink.size
    keep = a - int(np.count_nonzero(shrink))
    front = np.flatnonzero(shrink[:keep])
    back = keep + np.flatnonzero(~shrink[keep:])[::-1]
    order = np.arange(a)
    order[front], order[back] = back, front
    return order, keep


class _DualState:
    """SMO's variables, kept in libsvm's (permuted) order.

    Position ``p`` holds variable ``perm[p]``; the first ``active`` positions are the active set
    (all of them without shrinking, and then ``perm`` stays the identity). The loop keeps
    ``yG = y * G`` (:math:`G = Q\\alpha - e`; G itself is ``y * yG``) and, for shrinking,
    ``yGbar = y * Gbar`` with :math:`\\bar G_t = \\sum_{s: \\alpha_s = C_s} C_s Q_{ts}`, from which
    the gradient of the shrunk variables is rebuilt. Membership of :math:`I_{up}` and
    :math:`I_{low}` is kept as penalties 0 / -inf added to the scores, one vector operation each.

    An update costs a few NumPy calls on vectors of a few thousand entries, and at that size the
    cost of a call is mostly its overhead, so the state saves what it can around them: the views
    of the active positions are made once per change of the active set (:meth:`_activate`), the
    scalars of the two-variable step are read from Python lists (arithmetic on NumPy scalars is
    several times slower), and the kernel rows of the active set are kept from one update to the
    next until the order changes (:meth:`kernel_row`).
    """

    def __init__(self, rows: KernelRows, y, C, diagonal, policy: SMOPolicy):
        n = y.shape[0]
        self.rows, self.policy, self.n = rows, policy, n
        self.perm = np.arange(n)
        self.permuted = False
        self.unshrink = False
        self.y = np.array(y, dtype=np.float64)
        self.QD = np.array(diagonal, dtype=np.float64)
        self.C = np.array(C, dtype=np.float64)
        self.alpha = np.zeros(n)
        self.yG = -self.y
        self.yGbar = np.zeros(n)
        pos = self.y > 0
        self.up_pen = np.where(pos, 0.0, -np.inf)  # alpha = 0: positives can go up,
        self.low_pen = np.where(pos, -np.inf, 0.0)  # negatives can go down
        # the same numbers as Python lists, for the scalar work of an update (shrink swaps them
        # along with the arrays)
        self.y_list, self.QD_list, self.C_list = (v.tolist() for v in (self.y, self.QD, self.C))
        # the policy's choices as plain booleans, read at every update
        self._last = policy.ties == "last"
        self._second_order = policy.selection == "second-order"
        self._floor_nonpositive = policy.curvature_floor == "nonpositive"
        # a constant diagonal (the RBF kernel's is 1) makes K_ii + K_jj one number: a pass less
        self._same_diagonal = bool(np.all(self.QD == self.QD[0]))
        self._diagonal_sum = float(self.QD[0] + self.QD[0])
        # work buffers: every vector operation of selection and update writes into one of these
        self._up, self._low, self._quad, self._gain, self._step = (np.empty(n) for _ in range(5))
        self._zeros = np.zeros(n)
        # kernel rows over the active set by position, valid until the order or the active set
        # changes; at most about ROW_MEMO_BYTES of them
        self._rows_memo: dict[int, np.ndarray] = {}
        self._memo_capacity = max(2, ROW_MEMO_BYTES // (8 * n))
        self._activate(n)

    def _activate(self, active: int) -> None:
        """Make the first ``active`` positions the active set: their views, no kept rows."""
        self.active = a = active
        self._rows_memo.clear()  # positions now hold other variables, or rows another length
        self._yG_a, self._up_pen_a, self._low_pen_a, self._QD_a = (
            v[:a] for v in (self.yG, self.up_pen, self.low_pen, self.QD))
        self._up_a, self._low_a, self._quad_a, self._gain_a, self._step_a, self._zeros_a = (
            v[:a] for v in (self._up, self._low, self._quad, self._gain, self._step, self._zeros))

    def _argmax(self, values: np.ndarray) -> int:
        """Index of the largest value; on a tie the first, or the last as libsvm's ``>=``."""
        return _argmax(values, self._last)

    def kernel_row(self, p: int, length: int | None = None) -> np.ndarray:
        """Kernel row of position ``p`` over positions ``[0, length)`` (default: the active set),
        float64; possibly a view of the stored kernel, never to be written.

        Rows of the active set are kept until the next change of the order or of the active
        set: SMO picks the same variables again and again (libsvm keeps them in its kernel
        cache), and a row assembled from float32 storage, or gathered in the permuted order,
        costs several NumPy calls.
        """
        if length is not None and length != self.active:
            return self._assemble_row(p, length)
        row = self._rows_memo.get(p)
        if row is None:
            if len(self._rows_memo) >= self._memo_capacity:
                self._rows_memo.clear()
            row = self._rows_memo[p] = self._assemble_row(p, self.active)
        return row

    def _assemble_row(self, p: int, length: int) -> np.ndarray:
        """Kernel row of position ``p`` over positions ``[0, length)``, from the stored rows."""
        if self.permuted:
            return self.rows.row(self.perm[p])[self.perm[:length]].astype(np.float64)
        row = self.rows.row64(p)
        return row if length == self.n else row[:length]

    def select(self, tol: float):
        """Working pair ``(i, j, K_i, violation)`` among the active positions; ``i`` is None when
        they are optimal within ``tol``."""
        yG = self._yG_a
        up_vals, low_vals = self._up_a, self._low_a
        np.subtract(self._up_pen_a, yG, out=up_vals)
        i = self._argmax(up_vals)
        Gmax = up_vals.item(i)
        np.add(yG, self._low_pen_a, out=low_vals)
        violation = Gmax + _largest(low_vals)
        if not violation >= tol:  # also stops on -inf (an empty set)
            return None, None, None, violation
        Ki = self.kernel_row(i)
        if not self._second_order:
            return i, self._argmax(low_vals), Ki, violation
        # libsvm minimises -b^2/a over j in I_low with b = Gmax + y_j G_j > 0; the same j
        # maximises b^2/a with b clipped at 0 (non-candidates score 0, and the best candidate
        # scores > 0 because b >= tol there). a = (K_ii + K_jj) - 2 K_ij, floored.
        quad, gain = self._quad_a, self._gain_a
        if self._same_diagonal:  # -2 K_ij + (K_ii + K_jj): the same number, one pass fewer
            np.multiply(Ki, -2.0, out=quad)
            quad += self._diagonal_sum
        else:
            np.add(self._QD_a, self.QD_list[i], out=quad)
            np.multiply(Ki, 2.0, out=gain)
            quad -= gain
        if self._floor_nonpositive:
            quad[quad <= 0] = TAU  # exactly TAU where a <= 0, a itself elsewhere
        else:
            np.maximum(quad, TAU, out=quad)
        np.add(low_vals, Gmax, out=gain)
        np.maximum(gain, self._zeros_a, out=gain)  # an array of zeros: 3x faster than 0.0
        gain *= gain
        gain /= quad
        j = self._argmax(gain)
        if not gain.item(j) > 0:
            return None, None, None, violation
        return i, j, Ki, violation

    def pair_step(self, i: int, j: int, K_ij: float) -> tuple[float, float]:
        """libsvm's analytic solution of the two-variable subproblem, clipped to the box."""
        y, QD, C, alpha, yG = self.y_list, self.QD_list, self.C_list, self.alpha, self.yG
        return pair_step(y[i], y[j], QD[i], QD[j], C[i], C[j], alpha.item(i), alpha.item(j),
                         y[i] * yG.item(i), y[j] * yG.item(j), K_ij)

    def update(self, i: int, j: int, Ki: np.ndarray) -> None:
        """Solve for the pair ``(i, j)`` and update the gradient (and ``Gbar`` when shrinking)."""
        y, C, alpha = self.y_list, self.C_list, self.alpha
        Kj = self.kernel_row(j)
        old_i, old_j = alpha.item(i), alpha.item(j)
        a_i, a_j = self.pair_step(i, j, Ki.item(j))
        alpha[i], alpha[j] = a_i, a_j
        # libsvm: G += Q_i * dalpha_i + Q_j * dalpha_j with Q_t = y_t y K_t, hence on yG:
        step, step_j = self._step_a, self._quad_a
        np.multiply(Ki, y[i] * (a_i - old_i), out=step)
        np.multiply(Kj, y[j] * (a_j - old_j), out=step_j)
        step += step_j
        self._yG_a += step
        for t, a, old in ((i, a_i, old_i), (j, a_j, old_j)):
            C_t = C[t]
            can_up = -np.inf if a >= C_t else 0.0
            can_down = -np.inf if a <= 0 else 0.0
            if y[t] > 0:
                self.up_pen[t], self.low_pen[t] = can_up, can_down
            else:
                self.up_pen[t], self.low_pen[t] = can_down, can_up
            was_upper = old >= C_t
            if self.policy.shrinking and was_upper != (a >= C_t):
                # Gbar_k += C_t Q_tk (Q_tk = y_t y_k K_tk), in y-scaled form
                gbar_step = (C_t * y[t]) * self.kernel_row(t, self.n)
                if was_upper:
                    self.yGbar -= gbar_step
                else:
                    self.yGbar += gbar_step

    def violation(self) -> float:
        """Maximal violation over all variables (after :meth:`reconstruct`)."""
        return float((self.up_pen - self.yG).max() + (self.yG + self.low_pen).max())

    def reconstruct(self) -> None:
        """Rebuild the gradient of the shrunk variables and make every variable active again."""
        n, active, perm = self.n, self.active, self.perm
        if active == n:
            return
        alpha, y = self.alpha, self.y
        # G = Gbar + p with p = -1, in y-scaled form: yG = yGbar - y
        inactive = self.yGbar[active:] - y[active:]
        free = np.flatnonzero(((alpha > 0) & (alpha < self.C))[:active])
        if free.size:
            # G_t += alpha_s Q_ts for every inactive t, over the free s one after the other in
            # their order. libsvm has two loops for this (by inactive t, or by free s, whichever
            # computes fewer kernel rows); both add the same terms in this order, and the kernel
            # is symmetric, so one gather of the (free, inactive) block gives libsvm's numbers.
            K = self.rows.block64(perm[free], perm[active:])
            weights = alpha[free] * y[free]  # alpha_s Q_ts = alpha_s y_s K_ts y_t
            for K_s, w_s in zip(K, weights.tolist(), strict=True):  # in order: sequential sum
                K_s *= w_s
                inactive += K_s
        self.yG[active:] = inactive
        self._activate(n)

    def shrink(self, tol: float) -> None:
        """libsvm's ``do_shrinking``: set aside the variables at a bound unlikely to move."""
        a = self.active
        up, low = self.up_pen[:a] == 0, self.low_pen[:a] == 0
        Gmax1 = np.max(np.where(up, -self.yG[:a], -np.inf))
        Gmax2 = np.max(np.where(low, self.yG[:a], -np.inf))
        if not self.unshrink and Gmax1 + Gmax2 <= tol * 10:
            self.unshrink = True
            self.reconstruct()
        a = self.active
        up, low = self.up_pen[:a] == 0, self.low_pen[:a] == 0
        yG = self.yG[:a]
        shrink = (low & ~up & (-yG > Gmax1)) | (up & ~low & (yG > Gmax2))
        order, keep = shrink_order(shrink)
        if not np.array_equal(order, np.arange(a)):  # some variables trade places
            for arr in (self.y, self.QD, self.C, self.alpha, self.yG, self.yGbar, self.up_pen,
                        self.low_pen, self.perm):
                arr[:a] = arr[order]
            self.y_list, self.QD_list, self.C_list = (
                v.tolist() for v in (self.y, self.QD, self.C))
            self.permuted = True
        self._activate(keep)

    def rho(self) -> float:
        """libsvm's bias: mean of y G over the free variables, else the middle of the feasible
        range."""
        yG, y, alpha, C = self.yG, self.y, self.alpha, self.C
        upper = alpha >= C
        lower = alpha <= 0
        free = ~(upper | lower)
        if free.any():
            vals = yG[free]
            total = np.cumsum(vals)[-1] if self.policy.bias_sum == "sequential" else vals.sum()
            return float(total / vals.size)
        pos = y > 0
        ub_set = (upper & ~pos) | (lower & pos)
        lb_set = (upper & pos) | (lower & ~pos)
        ub = yG[ub_set].min() if ub_set.any() else np.inf
        lb = yG[lb_set].max() if lb_set.any() else -np.inf
        return float((ub + lb) / 2)

    def result(self, n_iter: int, converged: bool, violation: float) -> SMOResult:
        """The solution in the callers' order of the variables."""
        G = self.y * self.yG
        objective = float(np.sum(self.alpha * (G - 1.0)) / 2.0)
        alpha = np.empty(self.n)
        alpha[self.perm] = self.alpha
        return SMOResult(alpha, self.rho(), n_iter, converged, objective, float(violation))


def solve_smo(
    rows: KernelRows,
    y: np.ndarray,
    C: np.ndarray,
    *,
    diagonal: np.ndarray,
    tol: float = 1e-3,
    max_iter: int = 10_000_000,
    policy: SMOPolicy = DEFAULT,
) -> SMOResult:
    """Solve the binary C-SVC dual by SMO.

    Parameters
    ----------
    rows : KernelRows
        Kernel rows of the training points.
    y : ndarray of shape (n,)
        Labels, +1 or -1.
    C : ndarray of shape (n,)
        Upper bounds :math:`C_t > 0` (the penalty, per sample).
    diagonal : ndarray of shape (n,)
        :math:`k(x_t, x_t)` in float64.
    tol : float
        Stopping tolerance on the maximal violation.
    max_iter : int
        Largest number of updates.
    policy : SMOPolicy
        Selection rule, tie-breaking, curvature floor, bias sum and shrinking:
        :data:`~ebantenna.ml.smo_policy.DEFAULT`, :data:`~ebantenna.ml.smo_policy.LIBSVM` or any
        :class:`~ebantenna.ml.smo_policy.SMOPolicy`. With ``LIBSVM`` the path is libsvm's, shrinking
        on or off (``dataclasses.replace(LIBSVM, shrinking=False)``).

    Returns
    -------
    SMOResult

    Examples
    --------
    Two points on a line, one per class: the margin is the whole gap, so
    :math:`\\alpha = 2 / 2^2` and the bias is the midpoint.

    >>> from ebantenna.ml.kernels import Kernel
    >>> X = np.array([[0.0], [2.0]])
    >>> rows = KernelRows(X, Kernel("linear"), np.float64, cache_bytes=1 << 20)
    >>> res = solve_smo(rows, np.array([-1.0, 1.0]), np.full(2, 10.0),
    ...                 diagonal=np.array([0.0, 4.0]))
    >>> res.alpha, res.rho, res.converged
    (array([0.5, 0.5]), 1.0, True)
    """
    if not isinstance(policy, SMOPolicy):
        raise TypeError(f"policy must be an SMOPolicy, got {type(policy).__name__}")
    state = _DualState(rows, y, C, diagonal, policy)
    if runs_whole(policy, state.C):  # the same steps with fewer NumPy calls (smo_whole)
        n_iter, converged, violation = run_whole(state, tol, max_iter)
    else:
        n_iter, converged, violation = _run(state, tol, max_iter)
    if not converged:
        logger.info("SMO stopped at max_iter=%d with violation %.3g", max_iter, violation)
    return state.result(n_iter, converged, violation)


def _run(state: _DualState, tol: float, max_iter: float) -> tuple[int, bool, float]:
    """The general SMO loop (any policy): ``(n_iter, converged, violation)``."""
    policy = state.policy
    n = state.n
    n_iter = 0
    counter = min(n, 1000) + 1
    converged = False
    violation = np.inf
    while n_iter < max_iter:
        if policy.shrinking:
            counter -= 1
            if counter == 0:
                counter = min(n, 1000)
                state.shrink(tol)
        i, j, Ki, violation = state.select(tol)
        if i is None:
            if state.active == n:
                converged = True
                break
            # optimal on the active set: check again on all variables, and shrink at once
            state.reconstruct()
            i, j, Ki, violation = state.select(tol)
            if i is None:
                converged = True
                break
            counter = 1
        n_iter += 1
        state.update(i, j, Ki)
    if not converged:
        state.reconstruct()
        violation = state.violation()
    return n_iter, converged, violation
