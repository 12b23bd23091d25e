"""The SMO engine over all variables, with few NumPy calls per update (private).

:func:`ebantenna.ml.smo.solve_smo` runs this engine for the package's default conventions
(:data:`~ebantenna.ml.smo_policy.DEFAULT`: first index on ties): the whole run without
shrinking, and with shrinking the updates before libsvm's first shrinking, after which the
general engine goes on from the state this one hands over (:math:`\\bar G` included). It
takes the same steps in the same floating-point arithmetic as the general engine
:mod:`ebantenna.ml._smo_state` (the second-order scores and the two-variable step are the same
code, :mod:`ebantenna.ml._smo_step`), so the two return the same numbers to the last bit; only
the bookkeeping differs. Both take the steps of the reference loop
:func:`ebantenna.ml.smo.reference_smo`, in libsvm's arithmetic. On vectors of a few thousand
entries a NumPy call costs more than its arithmetic, so the loop is built to make few calls:

* The selection scores are kept instead of being recomputed from the gradient at every update:
  ``up`` holds :math:`-y_t G_t` on :math:`I_{up}` and :math:`-\\infty` elsewhere, ``low`` holds
  :math:`y_t G_t` on :math:`I_{low}` and :math:`-\\infty` elsewhere. An update adds the same
  vector to :math:`y G` and hence to ``low`` and (negated) to ``up``; rounding is symmetric, so
  ``up`` stays the exact negative of the gradient the general engine computes. Only the two
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
  makes equal to :math:`G_{max} + \\max_j \\mathrm{low}_j`, the general engine's violation.

Inputs are taken as checked: :class:`~ebantenna.ml.SVC` validates them once.
"""

from __future__ import annotations

import numpy as np

from ._smo_step import pair_step, second_order_gain
from .smo_policy import TAU, SMOPolicy

__all__ = ["runs_whole", "run_whole"]

#: ``ndarray.max()`` without its Python wrapper.
_largest = np.maximum.reduce


def runs_whole(policy: SMOPolicy, C: np.ndarray) -> bool:
    """Whether :func:`run_whole` takes this policy's first steps with these bounds: first index
    on ties and every :math:`C_t > 0`. Without shrinking it runs to the end; with shrinking it
    takes the updates before libsvm's first shrinking (:func:`updates_before_shrinking`), the
    same steps as :mod:`ebantenna.ml._smo_state` takes until then, and hands over to it.

    Examples
    --------
    >>> from ebantenna.ml.smo_policy import DEFAULT, LIBSVM
    >>> runs_whole(DEFAULT, np.ones(3)), runs_whole(LIBSVM, np.ones(3))
    (True, False)
    """
    return policy.ties == "first" and bool(np.all(C > 0))


def updates_before_shrinking(n: int) -> int:
    """libsvm's first shrinking comes after ``min(n, 1000)`` updates: before it, an SMO run with
    shrinking takes the same steps over all variables as one without.

    Examples
    --------
    >>> updates_before_shrinking(150), updates_before_shrinking(6000)
    (150, 1000)
    """
    return min(n, 1000)


def run_whole(rows, y: np.ndarray, QD: np.ndarray, C: np.ndarray, second_order: bool, tol: float,
              max_iter: float, floor_nonpositive: bool = False, track_gbar: bool = False):
    """Run SMO from :math:`\\alpha = 0` until the violation is below ``tol`` or ``max_iter``
    updates are done.

    Parameters
    ----------
    rows : KernelRows
        Kernel rows of the training points.
    y, QD, C : ndarray of shape (n,)
        Labels (+1 or -1), kernel diagonal and bounds (all > 0), float64, checked.
    second_order : bool
        Fan, Chen and Lin's selection; else the maximal violating pair.
    tol, max_iter : float
        Stopping tolerance on the maximal violation, and the largest number of updates.
    floor_nonpositive : bool
        The policy's curvature floor in the second-order scores: libsvm's (only
        :math:`a_{ij} \\le 0` replaced by :math:`\\tau`) or :math:`\\max(a_{ij}, \\tau)`.
    track_gbar : bool
        Also keep :math:`y_t \\bar G_t` (:math:`\\bar G_t = \\sum_{s: \\alpha_s = C_s} C_s
        Q_{ts}`) as the general engine keeps it for shrinking, in the same order of additions.

    Returns
    -------
    tuple
        ``(alpha, yG, n_iter, converged, violation, yGbar)``: the solution, :math:`y_t G_t`
        there, the loop's report as the general engine makes it, and :math:`y_t \\bar G_t`
        (None without ``track_gbar``).

    Examples
    --------
    >>> from ebantenna.ml.kernels import Kernel, KernelRows
    >>> rows = KernelRows(np.array([[0.0], [2.0]]), Kernel("linear"), np.float64, 1 << 20)
    >>> alpha, yG, n_iter, converged, _, _ = run_whole(rows, np.array([-1.0, 1.0]),
    ...     np.array([0.0, 4.0]), np.full(2, 10.0), True, 1e-3, np.inf)
    >>> alpha, yG, n_iter, converged
    (array([0.5, 0.5]), array([1., 1.]), 1, True)
    """
    row = rows.row_reader()
    up = np.where(y > 0, 0.0, -np.inf) + y  # -y G = y at alpha = 0, on I_up (y = 1)
    low = np.where(y > 0, -np.inf, 0.0) - y  # y G = -y, on I_low (y = -1)
    ys, QDs, Cs, alpha = (v.tolist() for v in (y, QD, C, np.zeros(y.shape)))
    # K_ii + K_jj is one number for a constant diagonal (as for 'rbf', all 1)
    pair_diagonal = QDs[0] + QDs[0] if bool(np.all(QD == QD[0])) else None
    taus, zeros = np.full(QD.shape, TAU), np.zeros(QD.shape)
    yGbar = np.zeros(QD.shape) if track_gbar else None
    n_iter, converged, violation = 0, False, np.inf
    while n_iter < max_iter:
        i = int(up.argmax())
        Gmax = up.item(i)  # .item(): a Python float, without a NumPy scalar on the way
        if second_order:
            b = low + Gmax  # b_j = Gmax + y_j G_j: positive for the candidates j
            violation = _largest(b)
            if not violation >= tol:  # also stops on -inf (an empty set)
                converged = True
                break
            Ki = row(i)
            second_order_gain(b, Ki, (QD, QDs[i]) if pair_diagonal is None else pair_diagonal,
                              taus, zeros, floor_nonpositive)
            j = int(b.argmax())
            if not b.item(j) > 0:
                converged = True
                break
        else:
            j = int(low.argmax())
            violation = Gmax + low.item(j)
            if not violation >= tol:
                converged = True
                break
            Ki = row(i)
        n_iter += 1
        _update(row(j), Ki, i, j, Gmax, up, low, ys, QDs, Cs, alpha, yGbar)
    if not converged:
        violation = _largest(up) + _largest(low)
    return (np.array(alpha), np.where(low > -np.inf, low, -up), n_iter, converged,
            float(violation), yGbar)


def _update(Kj, Ki, i, j, Gmax, up, low, y, QD, C, alpha, yGbar) -> None:
    """Solve for the pair ``(i, j)`` and move the scores ``up`` and ``low`` (in place), and
    ``yGbar`` unless it is None."""
    yi, yj, old_i, old_j = y[i], y[j], alpha[i], alpha[j]
    yG_i, yG_j = -Gmax, low.item(j)  # i is in I_up, j in I_low
    a_i, a_j = pair_step(yi, yj, QD[i], QD[j], C[i], C[j], old_i, old_j, yi * yG_i, yj * yG_j,
                         Ki.item(j))
    # G += Q_i dalpha_i + Q_j dalpha_j with Q_t = y_t y K_t, on y G:
    step = Ki * (yi * (a_i - old_i))
    step_j = Kj * (yj * (a_j - old_j))
    step += step_j
    up -= step
    low += step
    if yGbar is not None:  # in the general engine's order: i, then j
        for t, K_t, a, old in ((i, Ki, a_i, old_i), (j, Kj, a_j, old_j)):
            was_upper = old >= C[t]
            if was_upper != (a >= C[t]):
                gbar_step = (C[t] * y[t]) * K_t  # Gbar_k += C_t Q_tk, in y-scaled form
                if was_upper:
                    yGbar -= gbar_step
                else:
                    yGbar += gbar_step
    alpha[i], alpha[j] = a_i, a_j
    for t, a in ((i, a_i), (j, a_j)):  # the two may have changed sets
        lo = low.item(t)
        yG_t = lo if lo > -np.inf else -up.item(t)
        in_up, in_low = a < C[t], a > 0  # y = 1: up while below C, down while above 0
        if y[t] < 0:
            in_up, in_low = in_low, in_up
        up[t] = -yG_t if in_up else -np.inf
        low[t] = yG_t if in_low else -np.inf
