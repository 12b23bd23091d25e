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

Kernel rows come from :class:`KernelRows`, which either holds the whole matrix (one GEMM) or keeps a
least-recently-used cache of rows that are computed on demand.

Conventions and the digits they move
------------------------------------
With ``libsvm_compat=True`` the solver follows libsvm's arithmetic exactly, and scikit-learn's
:class:`~sklearn.svm.SVC` is reproduced to about 1e-12 with the same iteration counts, with
shrinking on (libsvm's variable order and gradient reconstruction included) or off. What each
convention does:

* **float32 kernel storage** (libsvm's ``Qfloat``): kernel entries carry a relative error of about
  6e-8. Solving with a float64 kernel instead keeps the path (same iteration count on the test
  problems) but moves the decision values by a few 1e-7: the 7th digit.
* **ties broken by the last index** (libsvm's ``>=`` comparisons): at the start every gradient
  equals -1, so the first working set is a tie. Taking the first index instead sends SMO down
  another path: another iteration count, and an optimum that differs within the stopping
  tolerance (decision values agree to about ``tol`` = 1e-3, the 3rd digit).
* **libsvm's two-variable update** (clip to the box in its order of cases) and **rho formula**
  (sequential sum over the free variables): these move the last one or two bits (about 1e-16),
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
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np

from .kernels import Kernel, squared_norms

__all__ = ["KernelRows", "SMOResult", "solve_smo", "SELECTIONS"]

logger = logging.getLogger(__name__)

#: Working-set selection rules.
SELECTIONS = ("second-order", "first-order")

#: libsvm's floor for a non-positive curvature of the two-variable problem.
TAU = 1e-12


class KernelRows:
    """Rows of the kernel matrix of ``X`` with itself, stored or cached.

    Parameters
    ----------
    X : ndarray of shape (n, n_features)
        Training points (float64).
    kernel : Kernel
        The kernel function.
    dtype : numpy dtype
        Storage type of the rows (float32 as libsvm, or float64).
    cache_bytes : int
        Memory allowed for kernel rows, in bytes. If the whole matrix fits it is computed at once
        with one matrix product; otherwise rows are computed on demand and the least recently used
        ones are dropped.
    full : ndarray of shape (N, N), optional
        A precomputed kernel matrix to use as it is.
    parts : sequence of slice, optional
        With ``full``: the problem's points are the rows of ``full`` in these slices, one after
        the other (the classes of a one-vs-one pair). Rows are then assembled from the slices on
        demand instead of copying the block.

    Examples
    --------
    >>> X = np.array([[0.0], [1.0], [3.0]])
    >>> rows = KernelRows(X, Kernel("linear"), np.float64, cache_bytes=8)
    >>> rows.is_full
    False
    >>> rows.row(2)
    array([0., 3., 9.])
    """

    def __init__(self, X, kernel: Kernel, dtype, cache_bytes: int, full=None, parts=None):
        self.X = X
        self.kernel = kernel
        self.dtype = np.dtype(dtype)
        self._norms = squared_norms(X) if X is not None else None
        self._parts = None
        if full is not None and parts is not None:
            parts = list(parts)
            self.matrix = full
            self.n = sum(p.stop - p.start for p in parts)
            # row i of the problem is row _rows[i] of `full`; touching slices are merged
            self._rows = np.concatenate([np.arange(p.start, p.stop) for p in parts])
            merged = [parts[0]]
            for p in parts[1:]:
                if p.start == merged[-1].stop:
                    merged[-1] = slice(merged[-1].start, p.stop)
                else:
                    merged.append(p)
            self._parts = merged
            self.rows_computed = 0
            return
        self.n = X.shape[0] if full is None else full.shape[0]
        if full is not None:
            self.matrix = np.asarray(full, dtype=self.dtype)
        elif self.n * self.n * self.dtype.itemsize <= cache_bytes:
            self.matrix = kernel.gram(X, x_norms=self._norms, dtype=self.dtype)
        else:
            self.matrix = None
            self._cache: OrderedDict[int, np.ndarray] = OrderedDict()
            row_bytes = self.n * self.dtype.itemsize
            self._capacity = max(2, int(cache_bytes // row_bytes))
            logger.info("kernel of %d points does not fit: caching %d rows", self.n,
                        self._capacity)
        self.rows_computed = 0

    @property
    def is_full(self) -> bool:
        """True when the whole matrix is stored."""
        return self.matrix is not None

    def row64(self, i: int) -> np.ndarray:
        """Kernel row :math:`k(x_i, x_t)` as float64 (a new array, or a view of float64 storage)."""
        if self._parts is not None:
            r = self.matrix[self._rows[i]]
            if len(self._parts) == 1:
                return r[self._parts[0]].astype(np.float64)
            return np.concatenate([r[p] for p in self._parts], dtype=np.float64)
        return np.asarray(self.row(i), dtype=np.float64)

    def row(self, i: int) -> np.ndarray:
        """Kernel row :math:`k(x_i, x_t)` for all t, in the storage type."""
        if self._parts is not None:
            r = self.matrix[self._rows[i]]
            if len(self._parts) == 1:
                return r[self._parts[0]]
            return np.concatenate([r[p] for p in self._parts])
        if self.matrix is not None:
            return self.matrix[i]
        cached = self._cache.get(i)
        if cached is not None:
            self._cache.move_to_end(i)
            return cached
        r = self.kernel.gram(self.X[i : i + 1], self.X, x_norms=self._norms[i : i + 1],
                             y_norms=self._norms, dtype=self.dtype)[0]
        if self.kernel.name == "rbf":
            r[i] = 1.0
        self.rows_computed += 1
        self._cache[i] = r
        if len(self._cache) > self._capacity:
            self._cache.popitem(last=False)
        return r


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
        Final maximal violation :math:`m(\\alpha) - M(\\alpha)`.
    """

    alpha: np.ndarray
    rho: float
    n_iter: int
    converged: bool
    objective: float
    violation: float


def _argmax(values: np.ndarray, last: bool) -> int:
    if last:
        return values.size - 1 - int(np.argmax(values[::-1]))
    return int(np.argmax(values))


def _argmin(values: np.ndarray, last: bool) -> int:
    if last:
        return values.size - 1 - int(np.argmin(values[::-1]))
    return int(np.argmin(values))


def _two_variable_update(i, j, yi, yj, a_i, a_j, G_i, G_j, QD_i, QD_j, K_ij, C_i, C_j):
    """libsvm's analytic solution of the two-variable subproblem, clipped to the box."""
    if yi != yj:
        quad = QD_i + QD_j + 2.0 * (-K_ij)  # Q_ij = y_i y_j K_ij = -K_ij
        if quad <= 0:
            quad = TAU
        delta = (-G_i - G_j) / quad
        diff = a_i - a_j
        a_i += delta
        a_j += delta
        if diff > 0:
            if a_j < 0:
                a_j = 0.0
                a_i = diff
        elif a_i < 0:
            a_i = 0.0
            a_j = -diff
        if diff > C_i - C_j:
            if a_i > C_i:
                a_i = C_i
                a_j = C_i - diff
        elif a_j > C_j:
            a_j = C_j
            a_i = C_j + diff
    else:
        quad = QD_i + QD_j - 2.0 * K_ij
        if quad <= 0:
            quad = TAU
        delta = (G_i - G_j) / quad
        total = a_i + a_j
        a_i -= delta
        a_j += delta
        if total > C_i:
            if a_i > C_i:
                a_i = C_i
                a_j = total - C_i
        elif a_j < 0:
            a_j = 0.0
            a_i = total
        if total > C_j:
            if a_j > C_j:
                a_j = C_j
                a_i = total - C_j
        elif a_i < 0:
            a_i = 0.0
            a_j = total
    return a_i, a_j


def solve_smo(
    rows: KernelRows,
    y: np.ndarray,
    C: np.ndarray,
    *,
    diagonal: np.ndarray,
    tol: float = 1e-3,
    max_iter: int = 10_000_000,
    selection: str = "second-order",
    ties_last: bool = True,
    shrinking: bool = False,
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
    selection : {'second-order', 'first-order'}
        Working-set selection rule (see the module text).
    ties_last : bool
        Break ties in the selection by the last index, as libsvm does.
    shrinking : bool
        Use libsvm's shrinking heuristic: every ``min(n, 1000)`` updates, variables at a bound
        that are unlikely to move are set aside (and their gradient rebuilt before the final
        check). It reorders the variables exactly as libsvm does, so that with ``ties_last`` the
        path is libsvm's with shrinking on.

    Returns
    -------
    SMOResult

    Examples
    --------
    Two points on a line, one per class: the margin is the whole gap, so
    :math:`\\alpha = 2 / 2^2` and the bias is the midpoint.

    >>> X = np.array([[0.0], [2.0]])
    >>> rows = KernelRows(X, Kernel("linear"), np.float64, cache_bytes=1 << 20)
    >>> res = solve_smo(rows, np.array([-1.0, 1.0]), np.full(2, 10.0),
    ...                 diagonal=np.array([0.0, 4.0]))
    >>> res.alpha, res.rho, res.converged
    (array([0.5, 0.5]), 1.0, True)
    """
    if shrinking:
        return _solve_shrinking(rows, y, C, diagonal, tol, max_iter, selection, ties_last)
    n = y.shape[0]
    yf = np.asarray(y, dtype=np.float64)
    pos = yf > 0
    QD = np.asarray(diagonal, dtype=np.float64)
    C = np.asarray(C, dtype=np.float64)
    alpha = np.zeros(n)
    # The loop keeps yG = y * G (G = Q alpha - e); G itself is y * yG. Membership of I_up and
    # I_low is kept as penalties 0 / -inf added to the scores, one vector operation each.
    yG = -yf.copy()
    up_pen = np.where(pos, 0.0, -np.inf)  # alpha = 0: positives can go up,
    low_pen = np.where(pos, -np.inf, 0.0)  # negatives can go down
    second = selection == "second-order"
    converged = False
    violation = np.inf
    n_iter = 0
    # work buffers: every vector operation of the loop writes into one of these
    up_vals, low_vals, quad, gain = (np.empty(n) for _ in range(4))
    while n_iter < max_iter:
        np.subtract(up_pen, yG, out=up_vals)
        i = _argmax(up_vals, ties_last)
        Gmax = up_vals[i]
        np.add(yG, low_pen, out=low_vals)
        Gmax2 = low_vals.max()
        violation = Gmax + Gmax2
        if not violation >= tol:  # also stops on -inf (an empty set)
            converged = True
            break
        Ki = rows.row64(i)
        if second:
            # libsvm minimises -b^2/a over j in I_low with b = Gmax + y_j G_j > 0; the same j
            # maximises b^2/a with b clipped at 0 (non-candidates score 0, and the best candidate
            # scores > 0 because b >= tol there). a = (K_ii + K_jj) - 2 K_ij, floored at TAU.
            np.add(QD, QD[i], out=quad)
            np.multiply(Ki, 2.0, out=gain)
            np.subtract(quad, gain, out=quad)
            if ties_last:
                quad[quad <= 0] = TAU  # libsvm: exactly TAU where a <= 0, a itself elsewhere
            else:
                np.maximum(quad, TAU, out=quad)
            np.add(low_vals, Gmax, out=gain)
            np.maximum(gain, 0.0, out=gain)
            np.multiply(gain, gain, out=gain)
            np.divide(gain, quad, out=gain)
            j = _argmax(gain, ties_last)
            if not gain[j] > 0:
                converged = True
                break
        else:
            j = _argmax(low_vals, ties_last)
        n_iter += 1
        Kj = rows.row64(j)
        old_i, old_j = alpha[i], alpha[j]
        a_i, a_j = _two_variable_update(
            i, j, yf[i], yf[j], old_i, old_j, yf[i] * yG[i], yf[j] * yG[j], QD[i], QD[j],
            Ki[j], C[i], C[j],
        )
        alpha[i], alpha[j] = a_i, a_j
        # libsvm: G += Q_i * dalpha_i + Q_j * dalpha_j with Q_t = y_t y K_t, hence on yG:
        step_i = Ki * (yf[i] * (a_i - old_i))  # a new array: stored rows are never written
        np.multiply(Kj, yf[j] * (a_j - old_j), out=quad)
        np.add(step_i, quad, out=step_i)
        yG += step_i
        for t, a in ((i, a_i), (j, a_j)):
            can_up = -np.inf if a >= C[t] else 0.0
            can_down = -np.inf if a <= 0 else 0.0
            if pos[t]:
                up_pen[t], low_pen[t] = can_up, can_down
            else:
                up_pen[t], low_pen[t] = can_down, can_up
    G = yf * yG
    if not converged:
        logger.info("SMO stopped at max_iter=%d with violation %.3g", max_iter, violation)
    rho = _rho(alpha, G, yf, C, ties_last)
    objective = float(np.sum(alpha * (G - 1.0)) / 2.0)
    return SMOResult(alpha, rho, n_iter, converged, objective, float(violation))


def _rho(alpha, G, yf, C, sequential: bool) -> float:
    """libsvm's bias: mean of y G over free variables, else the middle of the feasible range."""
    yG = yf * G
    upper = alpha >= C
    lower = alpha <= 0
    free = ~(upper | lower)
    if free.any():
        vals = yG[free]
        total = np.cumsum(vals)[-1] if sequential else vals.sum()
        return float(total / vals.size)
    pos = yf > 0
    ub_set = (upper & ~pos) | (lower & pos)
    lb_set = (upper & pos) | (lower & ~pos)
    ub = yG[ub_set].min() if ub_set.any() else np.inf
    lb = yG[lb_set].max() if lb_set.any() else -np.inf
    return float((ub + lb) / 2)


def _solve_shrinking(rows, y, C, diagonal, tol, max_iter, selection, ties_last) -> SMOResult:
    """SMO with libsvm's shrinking, on arrays kept in libsvm's (permuted) order.

    Position ``p`` holds variable ``perm[p]``; the first ``active`` positions are the active set.
    As in :func:`solve_smo` the loop keeps ``yG = y * G``, and ``yGbar = y * Gbar`` with
    :math:`\\bar G_t = \\sum_{s: \\alpha_s = C_s} C_s Q_{ts}`, from which the gradient of the
    shrunk variables is rebuilt.
    """
    n = y.shape[0]
    perm = np.arange(n)
    yf = np.array(y, dtype=np.float64)
    QD = np.array(diagonal, dtype=np.float64)
    C = np.array(C, dtype=np.float64)
    alpha = np.zeros(n)
    yG = -yf.copy()
    yGbar = np.zeros(n)
    pos = yf > 0
    up_pen = np.where(pos, 0.0, -np.inf)
    low_pen = np.where(pos, -np.inf, 0.0)
    arrays = [yf, QD, C, alpha, yG, yGbar, up_pen, low_pen, perm]
    active = n
    unshrink = False
    second = selection == "second-order"

    def krow(p, length):
        """Kernel row of position p over positions [0, length), float64."""
        return rows.row(perm[p])[perm[:length]].astype(np.float64)

    def is_free():
        return (alpha > 0) & (alpha < C)

    def reconstruct():
        nonlocal active
        if active == n:
            return
        # G = Gbar + p with p = -1, in y-scaled form: yG = yGbar - y
        yG[active:] = yGbar[active:] - yf[active:]
        free = np.flatnonzero(is_free()[:active])
        n_free = free.size
        if n_free:
            if n_free * n > 2 * active * (n - active):
                # for each inactive i: G_i += sum over free j of alpha_j Q_ij, in order of j
                K = np.array([rows.row(perm[i])[perm[free]] for i in range(active, n)],
                             dtype=np.float64)
                terms = K * (alpha[free] * yf[free])[None, :]
                acc = np.concatenate([yG[active:, None], terms], axis=1)
                yG[active:] = np.cumsum(acc, axis=1)[:, -1]
            else:
                # for each free i in order: G_j += alpha_i Q_ij for every inactive j
                K = np.array([rows.row(perm[i])[perm[active:]] for i in free], dtype=np.float64)
                terms = K * (alpha[free] * yf[free])[:, None]
                acc = np.concatenate([yG[None, active:], terms], axis=0)
                yG[active:] = np.cumsum(acc, axis=0)[-1]
        active = n

    def swap(i, j):
        for a in arrays:
            a[i], a[j] = a[j], a[i]

    def do_shrinking():
        nonlocal active, unshrink
        up = up_pen[:active] == 0
        low = low_pen[:active] == 0
        Gmax1 = np.max(np.where(up, -yG[:active], -np.inf))
        Gmax2 = np.max(np.where(low, yG[:active], -np.inf))
        if not unshrink and Gmax1 + Gmax2 <= tol * 10:
            unshrink = True
            reconstruct()
        up = up_pen[:active] == 0
        low = low_pen[:active] == 0
        shrink = ((low & ~up & (-yG[:active] > Gmax1))
                  | (up & ~low & (yG[:active] > Gmax2))).tolist()
        i = 0
        while i < active:
            if shrink[i]:
                active -= 1
                while active > i:
                    if not shrink[active]:
                        swap(i, active)
                        shrink[i], shrink[active] = shrink[active], shrink[i]
                        break
                    active -= 1
            i += 1

    def select():
        """Working pair among the active positions, or None when optimal there."""
        yGa = yG[:active]
        up_vals = up_pen[:active] - yGa
        i = _argmax(up_vals, ties_last)
        Gmax = up_vals[i]
        low_vals = yGa + low_pen[:active]
        Gmax2 = low_vals.max()
        if not Gmax + Gmax2 >= tol:
            return None
        Ki = krow(i, active)
        if second:
            quad = (QD[i] + QD[:active]) - 2.0 * Ki
            quad = np.where(quad > 0, quad, TAU)
            grad_diff = np.maximum(Gmax + low_vals, 0.0)
            gain = grad_diff * grad_diff
            gain /= quad
            j = _argmax(gain, ties_last)
            if not gain[j] > 0:
                return None
        else:
            j = _argmax(low_vals, ties_last)
        return i, j, Ki, float(Gmax + Gmax2)

    n_iter = 0
    counter = min(n, 1000) + 1
    converged = False
    violation = np.inf
    while n_iter < max_iter:
        counter -= 1
        if counter == 0:
            counter = min(n, 1000)
            do_shrinking()
        picked = select()
        if picked is None:
            reconstruct()
            picked = select()
            if picked is None:
                converged = True
                break
            counter = 1
        i, j, Ki, violation = picked
        n_iter += 1
        Kj = krow(j, active)
        old_i, old_j = alpha[i], alpha[j]
        a_i, a_j = _two_variable_update(
            i, j, yf[i], yf[j], old_i, old_j, yf[i] * yG[i], yf[j] * yG[j], QD[i], QD[j],
            Ki[j], C[i], C[j],
        )
        alpha[i], alpha[j] = a_i, a_j
        yG[:active] += Ki * (yf[i] * (a_i - old_i)) + Kj * (yf[j] * (a_j - old_j))
        for t, a, old in ((i, a_i, old_i), (j, a_j, old_j)):
            was_upper = old >= C[t]
            is_upper = a >= C[t]
            can_up = -np.inf if is_upper else 0.0
            can_down = -np.inf if a <= 0 else 0.0
            if yf[t] > 0:
                up_pen[t], low_pen[t] = can_up, can_down
            else:
                up_pen[t], low_pen[t] = can_down, can_up
            if was_upper != is_upper:
                full_row = rows.row(perm[t])[perm].astype(np.float64)
                # Gbar_k += C_t Q_tk (Q_tk = y_t y_k K_tk), in y-scaled form
                step = (C[t] * yf[t]) * full_row
                if was_upper:
                    yGbar -= step
                else:
                    yGbar += step
    if not converged:
        reconstruct()
        up_vals = up_pen - yG
        low_vals = yG + low_pen
        violation = float(up_vals.max() + low_vals.max())
        logger.info("SMO stopped at max_iter=%d with violation %.3g", max_iter, violation)
    G = yf * yG
    rho = _rho(alpha, G, yf, C, ties_last)
    objective = float(np.sum(alpha * (G - 1.0)) / 2.0)
    out = np.empty(n)
    out[perm] = alpha
    return SMOResult(out, rho, n_iter, converged, objective, float(violation))
