"""The SMO loop over all variables (no shrinking), with as few NumPy calls per update as it takes.

:func:`ebantenna.ml.smo.solve_smo` runs this loop for the package's default conventions
(:data:`~ebantenna.ml.smo_policy.DEFAULT`: first index on ties, the :math:`\\max(a, \\tau)`
curvature floor, no shrinking). It takes the same steps in the same floating-point arithmetic as
the general loop of :mod:`ebantenna.ml.smo`, so the two return the same numbers to the last bit;
only the bookkeeping differs. On vectors of a few thousand entries a NumPy call costs more than
its arithmetic, so the loop is built to make few calls:

* The selection scores are kept instead of being recomputed from the gradient at every update:
  ``up`` holds :math:`-y_t G_t` on :math:`I_{up}` and :math:`-\\infty` elsewhere, ``low`` holds
  :math:`y_t G_t` on :math:`I_{low}` and :math:`-\\infty` elsewhere. An update adds the same
  vector to :math:`y G` and hence to ``low`` and (negated) to ``up``; rounding is symmetric, so
  ``up`` stays the exact negative of the gradient the general loop computes. Only the two
  updated variables can change set, and they are reset one by one.
* The gradient itself is not stored during the loop: with :math:`C_t > 0` every variable lies in
  :math:`I_{up}` or :math:`I_{low}` (or both), so :math:`y_t G_t` is read from whichever score is
  finite.
* In-place operators (``b *= b``) instead of ufunc calls with ``out=`` (about half the call
  cost), ``np.maximum`` against an array of the constant rather than the constant itself (a
  third of the cost), and the scalar work of the two-variable step on Python floats.
* A constant kernel diagonal (the RBF kernel's is 1) saves one pass: :math:`a_{ij}` is then
  ``Ki * -2.0 + (K_ii + K_jj)``, the same number as ``(K_ii + K_jj) - 2.0 * Ki``.
* The stopping test uses :math:`\\max_j (\\mathrm{low}_j + G_{max})`, which rounding (monotone)
  makes equal to :math:`G_{max} + \\max_j \\mathrm{low}_j`, the general loop's violation.
"""

from __future__ import annotations

import numpy as np

from .smo_policy import TAU, SMOPolicy

__all__ = ["pair_step", "runs_whole", "run_whole"]


def pair_step(yi, yj, QD_i, QD_j, C_i, C_j, a_i, a_j, G_i, G_j, K_ij) -> tuple[float, float]:
    """libsvm's analytic solution of the two-variable subproblem, clipped to the box.

    Parameters are the labels, kernel diagonals, bounds, current values and gradients
    :math:`G = Q\\alpha - e` of the two variables, and their kernel entry :math:`K_{ij}`.

    Returns
    -------
    tuple of float
        The new :math:`(\\alpha_i, \\alpha_j)`; :math:`y_i\\alpha_i + y_j\\alpha_j` is unchanged.

    Examples
    --------
    Two points of opposite classes at distance 2 (linear kernel), starting from zero:

    >>> pair_step(1.0, -1.0, 4.0, 0.0, 10.0, 10.0, 0.0, 0.0, -1.0, -1.0, 0.0)
    (0.5, 0.5)
    """
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


def runs_whole(policy: SMOPolicy, C: np.ndarray) -> bool:
    """Whether :func:`run_whole` solves a problem with this policy and these bounds: no
    shrinking, first index on ties, the ``'tau'`` floor and every :math:`C_t > 0`.

    Examples
    --------
    >>> from ebantenna.ml.smo_policy import DEFAULT, LIBSVM
    >>> runs_whole(DEFAULT, np.ones(3)), runs_whole(LIBSVM, np.ones(3))
    (True, False)
    """
    return (not policy.shrinking and policy.ties == "first" and policy.curvature_floor == "tau"
            and bool(np.all(C > 0)))


def run_whole(state, tol: float, max_iter: float) -> tuple[int, bool, float]:
    """Run SMO on a fresh dual state of :mod:`ebantenna.ml.smo` until the violation is below
    ``tol`` or ``max_iter`` updates are done.

    ``state`` carries the labels ``y``, diagonal ``QD``, bounds ``C``, the start ``alpha`` and
    ``yG``, the membership penalties ``up_pen``/``low_pen``, the ``rows`` and the ``policy``;
    ``alpha`` and ``yG`` are overwritten with the solution.

    Returns
    -------
    tuple
        ``(n_iter, converged, violation)``, as the general loop reports them.
    """
    second = state.policy.selection == "second-order"
    row = state.rows.row_reader()
    largest = np.maximum.reduce  # ndarray.max() without its Python wrapper
    QD = state.QD
    up = state.up_pen - state.yG  # -y G on I_up, -inf elsewhere
    low = state.yG + state.low_pen  # y G on I_low, -inf elsewhere
    y, QDs, C, alpha = (v.tolist() for v in (state.y, QD, state.C, state.alpha))
    same_diagonal = bool(np.all(QD == QD[0]))  # as for 'rbf' (all 1)
    diagonal_sum = QDs[0] + QDs[0]
    inf = np.inf
    # np.maximum against arrays of the constant: the same numbers, and about three times faster
    # than against the Python float, which takes a slower loop
    taus, zeros = np.full(QD.shape, TAU), np.zeros(QD.shape)
    n_iter, converged, violation = 0, False, inf
    while n_iter < max_iter:
        i = int(up.argmax())
        Gmax = float(up[i])
        if second:
            b = low + Gmax  # b_j = Gmax + y_j G_j: positive for the candidates j
            violation = largest(b)
            if not violation >= tol:  # also stops on -inf (an empty set)
                converged = True
                break
            Ki = row(i)
            # a_ij = (K_ii + K_jj) - 2 K_ij, floored
            if same_diagonal:  # (K_ii + K_jj) is one number: one pass fewer, the same result
                quad = Ki * -2.0
                quad += diagonal_sum
            else:
                quad = QD + QDs[i]
                twice = Ki * 2.0
                quad -= twice
            np.maximum(quad, taus, out=quad)
            np.maximum(b, zeros, out=b)
            b *= b
            b /= quad
            j = int(b.argmax())
            if not b[j] > 0:
                converged = True
                break
        else:
            j = int(low.argmax())
            violation = Gmax + low[j]
            if not violation >= tol:
                converged = True
                break
            Ki = row(i)
        n_iter += 1
        Kj = row(j)
        yi, yj, old_i, old_j = y[i], y[j], alpha[i], alpha[j]
        yG_i, yG_j = -Gmax, float(low[j])  # i is in I_up, j in I_low
        a_i, a_j = pair_step(yi, yj, QDs[i], QDs[j], C[i], C[j], old_i, old_j, yi * yG_i,
                             yj * yG_j, float(Ki[j]))
        # G += Q_i dalpha_i + Q_j dalpha_j with Q_t = y_t y K_t, on y G:
        step = Ki * (yi * (a_i - old_i))
        step_j = Kj * (yj * (a_j - old_j))
        step += step_j
        up -= step
        low += step
        alpha[i], alpha[j] = a_i, a_j
        for t, a in ((i, a_i), (j, a_j)):  # the two may have changed sets
            lo = low[t]
            yG_t = lo if lo > -inf else -up[t]
            in_up, in_low = a < C[t], a > 0  # y = 1: up while below C, down while above 0
            if y[t] < 0:
                in_up, in_low = in_low, in_up
            up[t] = -yG_t if in_up else -inf
            low[t] = yG_t if in_low else -inf
    if not converged:
        violation = largest(up) + largest(low)
    state.alpha[:] = alpha
    state.yG[:] = np.where(low > -inf, low, -up)
    return n_iter, converged, float(violation)
