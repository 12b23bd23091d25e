"""The SMO engine with shrinking, a kernel-row memo and libsvm's conventions (private).

:func:`ebantenna.ml.smo.solve_smo` runs this engine for every policy. With the policies that
the loop of :mod:`ebantenna.ml._smo_whole` takes (first index on ties, every bound above 0: the
default conventions) the state is this engine's and the updates between two shrinkings are that
loop's (:meth:`DualState.run_whole`); with the others (libsvm's conventions,
``SVC(libsvm_compat=True)``) they are this engine's own (:meth:`DualState.run_steps`), the same
steps with more NumPy calls each. It takes the steps of the reference loop of
:mod:`ebantenna.ml.smo` (select a pair, solve it, update the gradient, and the bias at the end),
with what makes them fast or libsvm's to the last digit:

* the variables kept in libsvm's (permuted) order, with its shrinking heuristic
  (:meth:`DualState.shrink`, :func:`shrink_order`) and its reconstruction of the gradient of the
  variables set aside (:meth:`DualState.reconstruct`);
* the selection written on work buffers with membership of :math:`I_{up}` and :math:`I_{low}`
  kept as penalties 0 / :math:`-\\infty` (one vector operation each), the ties of the policy,
  and the second-order scores of :func:`ebantenna.ml._smo_step.second_order_gain`, the code
  that the whole-kernel loop runs too. The reference's
  :func:`~ebantenna.ml.smo.select_working_set` recomputes both sets from :math:`\\alpha` at
  every update, a few passes more per update than this engine can afford;
* libsvm's two-variable step :func:`ebantenna.ml._smo_step.pair_step`;
* kernel rows, and the curvatures of the pairs of a first index, kept from one update to the
  next (:meth:`DualState.kernel_row`, :meth:`DualState.curvature_row`).

Inputs are taken as checked: :class:`~ebantenna.ml.SVC` validates them once. This module adds
:func:`run_numpy` to :data:`ebantenna.ml.smo.SMO_ENGINES` as ``"numpy"`` when the package is
imported.
"""

from __future__ import annotations

import numpy as np

from ._smo_step import argmax, curvature, pair_step, second_order_gain
from ._smo_whole import run_whole, runs_whole, updates_before_shrinking
from .kernels import KernelRows
from .smo import SMO_ENGINES
from .smo_policy import TAU, SMOPolicy

__all__ = ["DualState", "ROW_MEMO_BYTES", "RECONSTRUCT_BYTES", "run_general", "run_numpy",
           "shrink_order"]

#: Memory for the kernel rows and the rows of curvatures that the SMO state keeps between updates
#: (float64, in bytes, the two together), on top of the kernel's own storage; kernel rows that
#: are views of a float64 kernel take none.
ROW_MEMO_BYTES = 64 << 20

#: Memory for one piece of the kernel block that rebuilds the gradient of the variables set
#: aside (float64, in bytes; :meth:`DualState.reconstruct`).
RECONSTRUCT_BYTES = 8 << 20


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


def _sum_down(K: np.ndarray) -> np.ndarray:
    """The sum of the rows of a C-ordered ``K``, one row after the other: ``(K[0] + K[1]) +
    K[2] ...``, libsvm's order of additions, in one call.

    NumPy sums pairwise only along the fast axis in memory (see :func:`numpy.sum`); down the
    rows of a C-ordered array of two columns or more it adds row after row. A single column is
    the fast axis, so there the running sum, sequential by definition, gives the last entry.

    Examples
    --------
    Sequentially, 1e16 + 1 rounds back to 1e16 (the spacing of floats there is 2):

    >>> _sum_down(np.array([[1e16, 1.0], [1.0, 1e16], [-1e16, -1e16]]))
    array([0., 0.])
    >>> _sum_down(np.array([[1e16], [1.0], [-1e16]]))
    array([0.])
    """
    if K.shape[1] > 1:
        return np.add.reduce(K, axis=0)
    return np.add.accumulate(K[:, 0])[-1:]


class DualState:
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
        self._up, self._low, self._step, self._step_j = (np.empty(n) for _ in range(4))
        self._zeros, self._taus = np.zeros(n), np.full(n, TAU)
        # kernel rows over the active set by position, valid until the order or the active set
        # changes, and the floored curvatures of the pairs of a first index, likewise; the two
        # together at most about ROW_MEMO_BYTES
        self._rows_memo: dict[int, np.ndarray] = {}
        self._curvature_memo: dict[int, np.ndarray] = {}
        self._memo_capacity = max(2, ROW_MEMO_BYTES // (8 * n))
        # the stored rows themselves when they are views of a whole float64 kernel: while every
        # variable is active and in its own place, they need no memo
        reader = rows.row_reader()
        self._views = None if reader == rows.row64 else reader
        self._activate(n)

    def _activate(self, active: int) -> None:
        """Make the first ``active`` positions the active set: their views, no kept rows."""
        self.active = a = active
        self._rows_memo.clear()  # positions now hold other variables, or rows another length
        self._curvature_memo.clear()
        self._yG_a, self._up_pen_a, self._low_pen_a, self._QD_a = (
            v[:a] for v in (self.yG, self.up_pen, self.low_pen, self.QD))
        self._up_a, self._low_a, self._step_a, self._step_j_a, self._zeros_a, self._taus_a = (
            v[:a] for v in (self._up, self._low, self._step, self._step_j, self._zeros,
                            self._taus))

    def _argmax(self, values: np.ndarray) -> int:
        """Index of the largest value; on a tie the first, or the last as libsvm's ``>=``."""
        return argmax(values, self._last)

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
            self._make_room()
            row = self._rows_memo[p] = self._assemble_row(p, self.active)
        return row

    def curvature_row(self, p: int, Kp: np.ndarray) -> np.ndarray:
        """The floored curvatures :math:`a_{pq}` over the active positions ``q``
        (:func:`~ebantenna.ml._smo_step.curvature`), from ``Kp = kernel_row(p)``; kept, as the
        kernel rows are, until the next change of the order or of the active set."""
        quad = self._curvature_memo.get(p)
        if quad is None:
            self._make_room()
            pair_diagonal = (self._diagonal_sum if self._same_diagonal
                             else (self._QD_a, self.QD_list[p]))
            quad = self._curvature_memo[p] = curvature(Kp, pair_diagonal, self._taus_a,
                                                       self._floor_nonpositive)
        return quad

    def _make_room(self) -> None:
        """Forget the kept rows when there are as many as :data:`ROW_MEMO_BYTES` allows."""
        if len(self._rows_memo) + len(self._curvature_memo) >= self._memo_capacity:
            self._rows_memo.clear()
            self._curvature_memo.clear()

    def _assemble_row(self, p: int, length: int) -> np.ndarray:
        """Kernel row of position ``p`` over positions ``[0, length)``, from the stored rows."""
        if self.permuted:  # one gather, a new array already (astype copies float32 only)
            row = self.rows.row(self.perm[p]).take(self.perm[:length])
            return row.astype(np.float64, copy=False)
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
        violation = Gmax + low_vals.item(low_vals.argmax())  # the largest, cheaper than max
        if not violation >= tol:  # also stops on -inf (an empty set)
            return None, None, None, violation
        Ki = self.kernel_row(i)
        if not self._second_order:
            return i, self._argmax(low_vals), Ki, violation
        # Fan, Chen and Lin's scores, as the whole-kernel loop computes them
        gain = second_order_gain(low_vals + Gmax, self.curvature_row(i, Ki), self._zeros_a)
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
        step, step_j = self._step_a, self._step_j_a
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

    def run_steps(self, tol: float, budget: float) -> tuple[int, bool, float]:
        """Up to ``budget`` updates on the active set, by :meth:`select` and :meth:`update`:
        ``(done, optimal, violation)``, ``optimal`` when the active set is optimal within
        ``tol`` (``violation`` then measured there)."""
        done, violation = 0, np.inf
        while done < budget:
            i, j, Ki, violation = self.select(tol)
            if i is None:
                return done, True, violation
            done += 1
            self.update(i, j, Ki)
        return done, False, violation

    def run_whole(self, tol: float, budget: float) -> tuple[int, bool, float]:
        """:meth:`run_steps` by the whole-kernel loop :func:`~ebantenna.ml._smo_whole.run_whole`
        (first index on ties, every bound above 0): the same steps and numbers, fewer NumPy
        calls per update. The state is read into its scores before and written back after."""
        a = self.active
        up = self._up_pen_a - self._yG_a  # the scores that select() computes
        low = self._yG_a + self._low_pen_a
        alpha = self.alpha[:a].tolist()
        gbar = (self._full_row, self.yGbar) if self.policy.shrinking else None
        if self._views is not None and a == self.n and not self.permuted:
            kept_row = row = self._views  # a view is always there: nothing to keep
        else:
            kept_row, row = self._rows_memo.get, self.kernel_row
        done, optimal, violation = run_whole(
            (kept_row, row, self._curvature_memo.get, self.curvature_row), up, low,
            (self.y_list, self.QD_list, self.C_list, alpha), tol, budget, self._second_order,
            gbar)
        if done:
            self.alpha[:a] = alpha
            self._yG_a[:] = np.where(low > -np.inf, low, -up)  # y G from its finite score
            # membership of I_up and I_low, as update() sets it
            can_up = np.where(self.alpha[:a] >= self.C[:a], -np.inf, 0.0)
            can_down = np.where(self.alpha[:a] <= 0, -np.inf, 0.0)
            pos = self.y[:a] > 0
            self._up_pen_a[:] = np.where(pos, can_up, can_down)
            self._low_pen_a[:] = np.where(pos, can_down, can_up)
        return done, optimal, violation

    def _full_row(self, p: int) -> np.ndarray:
        """Kernel row of position ``p`` over all positions, active or not."""
        return self.kernel_row(p, self.n)

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
        # G_t += alpha_s Q_ts for every inactive t, over the free s one after the other in
        # their order. libsvm has two loops for this (by inactive t, or by free s, whichever
        # computes fewer kernel rows); both add the same terms in this order, and the kernel
        # is symmetric, so gathers of the (free, inactive) block give libsvm's numbers: in
        # pieces of rows, each summed down its rows in one call, starting from the last sum.
        weights = alpha[free] * y[free]  # alpha_s Q_ts = alpha_s y_s K_ts y_t
        piece = max(1, RECONSTRUCT_BYTES // (8 * (n - active)))
        for start in range(0, free.size, piece):
            K = self.rows.block64(perm[free[start : start + piece]], perm[active:])
            K *= weights[start : start + piece, None]
            K[0] += inactive
            inactive = _sum_down(K)
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


def run_general(state: DualState, tol: float, max_iter: float,
                whole: bool = False) -> tuple[int, bool, float]:
    """SMO on a fresh :class:`DualState`, any policy: ``(n_iter, converged, violation)``.

    The updates between two shrinkings run on the active set by
    :meth:`~DualState.run_whole` when ``whole`` (the policies of
    :func:`~ebantenna.ml._smo_whole.runs_whole`), else by :meth:`~DualState.run_steps`: the
    same steps and numbers either way. ``state`` holds the solution in its own (permuted) order
    when this returns.
    """
    run = state.run_whole if whole else state.run_steps
    shrinking, n = state.policy.shrinking, state.n
    every = updates_before_shrinking(n)
    counter = every + 1  # libsvm's: shrink when it reaches 0, counted down before each update
    n_iter, converged, violation = 0, False, np.inf
    while n_iter < max_iter:
        budget = max_iter - n_iter
        if shrinking:
            counter -= 1
            if counter == 0:
                counter = every
                state.shrink(tol)
            budget = min(budget, counter)  # this update and those before the next shrinking
        done, optimal, violation = run(tol, budget)
        n_iter += done
        if not optimal:
            counter -= done - 1
            continue
        if state.active == n:
            converged = True
            break
        # optimal on the active set: check again on all variables, and shrink after one update
        state.reconstruct()
        done, optimal, violation = run(tol, 1)
        n_iter += done
        if optimal:
            converged = True
            break
        counter = 1
    if not converged:
        state.reconstruct()
        violation = state.violation()
    return n_iter, converged, violation


def run_numpy(engine, rows, y, C, diagonal, policy, tol, max_iter):
    """The NumPy engines, as :data:`ebantenna.ml.smo.SMO_ENGINES` calls them (``engine``, the
    caller's choice, does not change what runs here): ``(y, C, alpha, yG, perm, n_iter,
    converged, violation)``, the arrays in the engine's order (``perm`` None when it is the
    callers').

    libsvm's engine keeps the state, shrinks and rebuilds gradients; the whole-kernel loop
    takes the updates in between when the policy allows it (the same steps, with fewer NumPy
    calls each).
    """
    state = DualState(rows, y, C, diagonal, policy)
    n_iter, converged, violation = run_general(state, tol, max_iter, runs_whole(policy, C))
    if state.permuted:
        perm = state.perm
        y, C = y[perm], C[perm]
    else:
        perm = None
    return y, C, state.alpha, state.yG, perm, n_iter, converged, violation


SMO_ENGINES["numpy"] = run_numpy
