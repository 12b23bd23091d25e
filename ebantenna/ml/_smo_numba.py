"""The SMO loop compiled by numba: the NumPy engines' arithmetic, one scalar at a time (private).

Used only by :mod:`ebantenna.ml._smo_compiled`, when numba is installed and this module
compiled (``IMPORT_ERROR`` says why not); otherwise SMO runs on the NumPy engines. The loop
is that of
:func:`ebantenna.ml._smo_state.run_general` on a :class:`~ebantenna.ml._smo_state.DualState`
(which the whole-kernel engine :mod:`ebantenna.ml._smo_whole` matches to the last bit), written
with plain loops so that one call runs every update, with no NumPy call per update:

* every number is computed by the same IEEE operations in the same order as there: the
  second-order scores ``max(b, 0)**2 / a`` with the policy's floor of ``a`` and its two ways of
  forming ``a`` (``Ki * -2.0 + s`` for a constant diagonal), libsvm's two-variable step
  (:func:`pair_step`, the code of :func:`ebantenna.ml._smo_step.pair_step`), the gradient step
  ``G_t + (K_it c_i + K_jt c_j)``, libsvm's shrinking and its sequential reconstruction of the
  gradient. numba compiles without ``fastmath``: no reassociation, no fused multiply-add, so
  each operation rounds as NumPy's does;
* sums appear only as these per-entry updates; maxima and arg-maxima (the first index on a tie,
  or the last, libsvm's ``>=``) are exact whatever the order;
* the variables live in the columns of one array ``F`` (``y, QD, C, alpha, yG, yGbar``) and
  two penalties, 0 or :math:`-\\infty`, for membership of :math:`I_{up}` and :math:`I_{low}`
  (``up`` and ``low``), in libsvm's permuted order when shrinking; ``g[p]`` is the row of the
  stored kernel matrix that position ``p`` holds. The penalties are added to the scores, as the
  NumPy engines add theirs (``0 - yG`` or ``-inf``, the same numbers as a test of a flag): a
  flag would be a branch per variable that the processor mispredicts half the time, where an
  addition costs a cycle. The second-order score ``max(b, 0)**2 / a`` is 0 for every
  variable with :math:`b \\le 0` (all those outside :math:`I_{low}` among them), as in NumPy,
  and a score of 0 never wins (the selection stops unless the best score is above 0): those
  variables skip the division, the costliest operation of the pass.

Kernel entries are read from the stored matrix (float64, or float32 widened exactly to float64,
as :meth:`~ebantenna.ml.kernels.KernelRows.row64` does).
"""

from __future__ import annotations

import numpy as np

from .smo_policy import TAU

try:
    import numba
except ImportError as exc:  # not installed, or not working with this NumPy
    numba = None
    IMPORT_ERROR = f"{type(exc).__name__}: {exc}"
else:
    IMPORT_ERROR = ""

__all__ = ["smo_loop", "pair_step", "IMPORT_ERROR"]


def _plain(function):
    """Without numba the loops stay Python functions (this module still imports, and
    :mod:`ebantenna.ml._smo_compiled` does not use it)."""
    return function


_jit = numba.njit(cache=True) if numba is not None else _plain

# the rows of F
_Y, _QD, _C, _ALPHA, _YG, _YGBAR = range(6)


@_jit
def pair_step(yi, yj, QD_i, QD_j, C_i, C_j, a_i, a_j, G_i, G_j, K_ij):
    """libsvm's two-variable step: :func:`ebantenna.ml._smo_step.pair_step`, compiled."""
    if yi != yj:
        quad = QD_i + QD_j + 2.0 * (-K_ij)
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


@_jit
def _gather(K, g, p, length, out):
    """Kernel row of position ``p`` over positions ``[0, length)``, as float64, into ``out``."""
    r = g[p]
    for t in range(length):
        out[t] = np.float64(K[r, g[t]])


@_jit
def _better(v, best, last):
    """Whether ``v`` replaces ``best`` in an arg-max: larger, or equal with ties to the last."""
    return v > best or (last and v == best)


@_jit
def _scan(F, up, low, a, last):
    """The two arg-maxima of the selection over the first ``a`` positions:
    ``(i, Gmax, j, top)``, :math:`G_{max} = -y_i G_i` the largest over :math:`I_{up}` and
    ``top`` the largest :math:`y_j G_j` over :math:`I_{low}` (-inf for an empty set)."""
    yG = F[_YG]
    i, Gmax, j, top = 0, -np.inf, 0, -np.inf
    for t in range(a):
        v = up[t] - yG[t]
        if _better(v, Gmax, last):
            i, Gmax = t, v
        w = yG[t] + low[t]
        if _better(w, top, last):
            j, top = t, w
    return i, Gmax, j, top


@_jit
def _select(K, g, F, low, a, tol, opts, pair_sum, Ki, scan):
    """The working pair ``(i, j, violation)`` among the first ``a`` positions from their
    :func:`_scan`, ``i = -1`` when optimal within ``tol``; ``Ki`` receives the row of ``i``.
    ``opts``: second order, ties to the last, libsvm's floor, constant diagonal."""
    second_order, last, floor_nonpositive, same_diagonal = opts
    i, Gmax, j_low, top_low = scan
    violation = Gmax + top_low
    if not violation >= tol:  # also stops on -inf (an empty set)
        return -1, -1, violation
    if not second_order:
        _gather(K, g, i, a, Ki)
        return i, j_low, violation
    yG, QD = F[_YG], F[_QD]
    QD_i, j, best, r = QD[i], 0, -np.inf, g[i]
    for t in range(a):  # the scores of ebantenna.ml._smo_step.second_order_gain, and the row
        K_it = np.float64(K[r, g[t]])
        Ki[t] = K_it
        b = (yG[t] + low[t]) + Gmax  # -inf outside I_low
        if not b > 0.0:  # scores 0, which cannot win: only a score above 0 is taken
            continue
        if same_diagonal:
            quad = K_it * -2.0 + pair_sum
        else:
            quad = (QD[t] + QD_i) - K_it * 2.0
        if floor_nonpositive:
            quad = quad if quad > 0 else TAU
        else:
            quad = quad if quad >= TAU else TAU
        score = b * b / quad
        if _better(score, best, last):
            j, best = t, score
    if not best > 0:
        return -1, -1, violation
    return i, j, violation


@_jit
def _set_membership(F, up, low, t):
    """``t`` in :math:`I_{up}` (can move so that :math:`y_t\\alpha_t` grows) and in
    :math:`I_{low}`, from its value."""
    a, C_t = F[_ALPHA, t], F[_C, t]
    below = 0.0 if not a >= C_t else -np.inf
    above = 0.0 if not a <= 0 else -np.inf
    if F[_Y, t] > 0:
        up[t], low[t] = below, above
    else:
        up[t], low[t] = above, below


@_jit
def _update(K, g, F, up, low, a, i, j, Ki, shrinking, last):
    """Solve for the pair ``(i, j)``, update the gradient (and ``Gbar`` when shrinking);
    returns the next :func:`_scan`, made in the same pass as the gradient."""
    y, QD, C, alpha, yG = F[_Y], F[_QD], F[_C], F[_ALPHA], F[_YG]
    old_i, old_j = alpha[i], alpha[j]
    a_i, a_j = pair_step(y[i], y[j], QD[i], QD[j], C[i], C[j], old_i, old_j, y[i] * yG[i],
                         y[j] * yG[j], Ki[j])
    alpha[i], alpha[j] = a_i, a_j
    _set_membership(F, up, low, i)
    _set_membership(F, up, low, j)
    c_i, c_j, r = y[i] * (a_i - old_i), y[j] * (a_j - old_j), g[j]
    i_next, Gmax, j_next, top = 0, -np.inf, 0, -np.inf
    for t in range(a):  # G += Q_i dalpha_i + Q_j dalpha_j, on y G; then the next scan
        v = yG[t] + (Ki[t] * c_i + np.float64(K[r, g[t]]) * c_j)
        yG[t] = v
        u = up[t] - v
        if _better(u, Gmax, last):
            i_next, Gmax = t, u
        w = v + low[t]
        if _better(w, top, last):
            j_next, top = t, w
    if shrinking:
        _move_gbar(K, g, F, i, old_i)
        _move_gbar(K, g, F, j, old_j)
    return i_next, Gmax, j_next, top


@_jit
def _move_gbar(K, g, F, t, old):
    """:math:`\\bar G \\mathrel{+}= \\pm C_t Q_t` when :math:`\\alpha_t` reached or left
    :math:`C_t`, in y-scaled form (libsvm's ``G_bar``)."""
    C_t, yGbar = F[_C, t], F[_YGBAR]
    was_upper = old >= C_t
    if was_upper == (F[_ALPHA, t] >= C_t):
        return
    coef, r = C_t * F[_Y, t], g[t]
    for k in range(F.shape[1]):
        step = coef * np.float64(K[r, g[k]])
        if was_upper:
            yGbar[k] -= step
        else:
            yGbar[k] += step


@_jit
def _reconstruct(K, g, F, a):
    """Rebuild the gradient of the shrunk positions ``[a, n)``; returns ``n``, all active."""
    y, C, alpha, yG, yGbar = F[_Y], F[_C], F[_ALPHA], F[_YG], F[_YGBAR]
    n = F.shape[1]
    for t in range(a, n):
        yG[t] = yGbar[t] - y[t]
    for s in range(a):  # the free variables, one after the other: libsvm's sequential sum
        if alpha[s] > 0 and alpha[s] < C[s]:
            w, r = alpha[s] * y[s], g[s]
            for t in range(a, n):
                yG[t] += np.float64(K[r, g[t]]) * w
    return n


@_jit
def _shrink(K, g, F, up, low, perm, a, tol, unshrink):
    """libsvm's ``do_shrinking`` and its swaps: ``(active, unshrink)``."""
    yG = F[_YG]
    Gmax1, Gmax2 = -np.inf, -np.inf
    for t in range(a):
        if up[t] == 0 and -yG[t] > Gmax1:
            Gmax1 = -yG[t]
        if low[t] == 0 and yG[t] > Gmax2:
            Gmax2 = yG[t]
    if not unshrink and Gmax1 + Gmax2 <= tol * 10:
        unshrink = True
        a = _reconstruct(K, g, F, a)
    marks = np.empty(a, dtype=np.bool_)
    count = 0
    for t in range(a):
        in_up, in_low = up[t] == 0, low[t] == 0
        marks[t] = ((in_low and not in_up and -yG[t] > Gmax1)
                    or (in_up and not in_low and yG[t] > Gmax2))
        count += marks[t]
    keep = a - count
    front, back = 0, a - 1  # the k-th set aside among the first `keep` trades with the k-th
    while True:  # kept counted from the end (ebantenna.ml._smo_state.shrink_order)
        while front < keep and not marks[front]:
            front += 1
        while back >= keep and marks[back]:
            back -= 1
        if front >= keep or back < keep:
            break
        for row in range(F.shape[0]):
            F[row, front], F[row, back] = F[row, back], F[row, front]
        for arr in (up, low):
            arr[front], arr[back] = arr[back], arr[front]
        for idx in (perm, g):
            idx[front], idx[back] = idx[back], idx[front]
        front += 1
        back -= 1
    return keep, unshrink


@_jit
def _max_violation(F, up, low):
    """Maximal violation over all positions."""
    yG = F[_YG]
    top_up, top_low = -np.inf, -np.inf
    for t in range(F.shape[1]):
        if up[t] - yG[t] > top_up:
            top_up = up[t] - yG[t]
        if yG[t] + low[t] > top_low:
            top_low = yG[t] + low[t]
    return top_up + top_low


#: The two specialisations compiled (float64 and float32 kernel matrices, any strides), so
#: that a view and a contiguous matrix share one compiled loop.
_SIGNATURES = [] if numba is None else [
    (numba.types.Array(dtype, 2, "A"), numba.int64[::1], numba.float64[:, ::1],
     numba.float64[::1], numba.float64[::1], numba.int64[::1], numba.float64, numba.float64,
     numba.types.UniTuple(numba.boolean, 4), numba.boolean, numba.float64)
    for dtype in (numba.float64, numba.float32)]
_jit_loop = numba.njit(_SIGNATURES, cache=True) if numba is not None else _plain


@_jit_loop
def smo_loop(K, g, F, up, low, perm, tol, max_iter, opts, shrinking, pair_sum):
    """SMO from the state in ``F``, ``up``, ``low`` (updated in place, in libsvm's order on
    return, ``perm`` the variables' positions): ``(n_iter, converged, violation)``.

    ``opts`` is ``(second_order, ties_last, floor_nonpositive, constant_diagonal)`` and
    ``pair_sum`` :math:`K_{ii} + K_{jj}` for a constant diagonal.
    """
    n = F.shape[1]
    last = opts[1]
    Ki = np.empty(n)
    n_iter, active, unshrink = 0, n, False
    counter = min(n, 1000) + 1
    converged, violation = False, np.inf
    scan = _scan(F, up, low, active, last)
    while n_iter < max_iter:
        if shrinking:
            counter -= 1
            if counter == 0:
                counter = min(n, 1000)
                active, unshrink = _shrink(K, g, F, up, low, perm, active, tol, unshrink)
                scan = _scan(F, up, low, active, last)
        i, j, violation = _select(K, g, F, low, active, tol, opts, pair_sum, Ki, scan)
        if i < 0:
            if active == n:
                converged = True
                break
            # optimal on the active set: check again on all variables, and shrink at once
            active = _reconstruct(K, g, F, active)
            scan = _scan(F, up, low, active, last)
            i, j, violation = _select(K, g, F, low, active, tol, opts, pair_sum, Ki, scan)
            if i < 0:
                converged = True
                break
            counter = 1
        n_iter += 1
        scan = _update(K, g, F, up, low, active, i, j, Ki, shrinking, last)
    if not converged:
        _reconstruct(K, g, F, active)
        violation = _max_violation(F, up, low)
    return n_iter, converged, violation
