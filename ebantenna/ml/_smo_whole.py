"""The SMO loop over the active variables, with few NumPy calls per update (private).

:func:`ebantenna.ml.smo.solve_smo` runs this loop for the package's default conventions
(:data:`~ebantenna.ml.smo_policy.DEFAULT`: first index on ties): every update of the run, on
the active variables of the general engine :mod:`ebantenna.ml._smo_state`, which keeps the
state between the loop's runs and does libsvm's shrinking and reconstruction of the gradient
(:math:`\\bar G` is kept here as it keeps it). It takes the same steps in the same
floating-point arithmetic as the general engine's own update (the second-order scores and the
two-variable step are the same code, :mod:`ebantenna.ml._smo_step`), so the two return the same
numbers to the last bit; only the bookkeeping differs. Both take the steps of the reference loop
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
  third of the cost), the largest entry read where ``argmax`` finds it (the same number, and
  the search costs less than the call of ``np.maximum.reduce``), and the scalar work of the
  two-variable step on Python floats.
* The floored curvatures :math:`a_{ij}` of a first index :math:`i` depend on :math:`i` alone:
  the general engine keeps them from one update to the next, as it keeps the kernel rows, until
  the active set changes (SMO picks the same :math:`i` again and again), which saves three or
  four passes per update (:func:`ebantenna.ml._smo_step.curvature`).
* The stopping test uses :math:`\\max_j (\\mathrm{low}_j + G_{max})`, which rounding (monotone)
  makes equal to :math:`G_{max} + \\max_j \\mathrm{low}_j`, the general engine's violation.

Inputs are taken as checked: :class:`~ebantenna.ml.SVC` validates them once.
"""

from __future__ import annotations

import numpy as np

from ._smo_step import pair_step, second_order_gain
from .smo_policy import SMOPolicy

__all__ = ["runs_whole", "updates_before_shrinking", "run_whole"]


def runs_whole(policy: SMOPolicy, C: np.ndarray) -> bool:
    """Whether :func:`run_whole` takes this policy's updates with these bounds: first index
    on ties and every :math:`C_t > 0` (each variable then lies in :math:`I_{up}` or
    :math:`I_{low}`). It takes them all, between the shrinkings of
    :mod:`ebantenna.ml._smo_state` when the policy shrinks: the same steps as that engine's own.

    Examples
    --------
    >>> from ebantenna.ml.smo_policy import DEFAULT, LIBSVM
    >>> runs_whole(DEFAULT, np.ones(3)), runs_whole(LIBSVM, np.ones(3))
    (True, False)
    """
    return policy.ties == "first" and bool(np.all(C > 0))


def updates_before_shrinking(n: int) -> int:
    """libsvm shrinks every ``min(n, 1000)`` updates: before the first shrinking, an SMO run
    with shrinking takes the same steps over all variables as one without.

    Examples
    --------
    >>> updates_before_shrinking(150), updates_before_shrinking(6000)
    (150, 1000)
    """
    return min(n, 1000)


def run_whole(rows, up: np.ndarray, low: np.ndarray, lists, tol: float, budget: float,
              second_order: bool, gbar=None):
    """Run SMO on the active positions from the scores ``up`` and ``low`` until the violation
    is below ``tol`` or ``budget`` updates are done.

    Parameters
    ----------
    rows : tuple of four callables
        ``(kept_row, row, kept_curvature, curvature)``: ``row(p)``, the kernel row of position
        ``p`` over the active positions (float64, never written), and ``curvature(p, row(p))``,
        the floored curvatures of the pairs of ``p``
        (:func:`ebantenna.ml._smo_step.curvature`); both may keep what they return, and
        ``kept_row(p)``, ``kept_curvature(p)`` return it when they have (else None: the
        ``get`` of a dictionary, cheaper to call than a function).
    up, low : ndarray of shape (a,)
        The selection scores of the module text, updated in place.
    lists : tuple of four lists
        Labels (+1 or -1), kernel diagonal, bounds (all > 0) and :math:`\\alpha` by position, as
        Python floats; :math:`\\alpha` is updated in place.
    tol, budget : float
        Stopping tolerance on the maximal violation, and the largest number of updates.
    second_order : bool
        Fan, Chen and Lin's selection; else the maximal violating pair.
    gbar : tuple (callable, ndarray of shape (n,)), optional
        ``(full_row, yGbar)``: also keep :math:`y_t \\bar G_t` (:math:`\\bar G_t = \\sum_{s:
        \\alpha_s = C_s} C_s Q_{ts}`, over every position, active or not, with ``full_row(p)``
        the kernel row over all of them) as the general engine keeps it for shrinking, in the
        same order of additions.

    Returns
    -------
    tuple
        ``(done, converged, violation)``: the updates made, whether the active positions are
        optimal within ``tol``, and the violation last measured.

    Examples
    --------
    Two points at 0 and 2 (linear kernel), one per class, from :math:`\\alpha = 0`:

    >>> K = np.array([[0.0, 0.0], [0.0, 4.0]])
    >>> alpha = [0.0, 0.0]
    >>> up, low = np.array([-np.inf, 1.0]), np.array([1.0, -np.inf])  # y G = -y at alpha = 0
    >>> rows = ({}.get, K.__getitem__, {}.get,
    ...         lambda p, Kp: np.maximum(K[p, p] + np.diag(K) - 2 * Kp, 1e-12))
    >>> run_whole(rows, up, low, ([-1.0, 1.0], [0.0, 4.0], [10.0, 10.0], alpha), 1e-3, np.inf,
    ...           True)
    (1, True, 0.0)
    >>> alpha
    [0.5, 0.5]
    """
    kept_row, row, kept_curvature, curvature = rows
    zeros = np.zeros(up.shape)  # np.maximum against an array of 0: about three times faster
    done, converged, violation = 0, False, np.inf
    while done < budget:
        i = int(up.argmax())
        Gmax = up.item(i)  # .item(): a Python float, without a NumPy scalar on the way
        if second_order:
            b = low + Gmax  # b_j = Gmax + y_j G_j: positive for the candidates j
            violation = b.item(b.argmax())  # the largest b, as a Python float
            if not violation >= tol:  # also stops on -inf (an empty set)
                converged = True
                break
            Ki = kept_row(i)
            if Ki is None:
                Ki = row(i)
            quad = kept_curvature(i)
            second_order_gain(b, curvature(i, Ki) if quad is None else quad, zeros)
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
        done += 1
        Kj = kept_row(j)
        _update(row(j) if Kj is None else Kj, Ki, i, j, Gmax, up, low, lists, gbar)
    return done, converged, float(violation)


def _update(Kj, Ki, i, j, Gmax, up, low, lists, gbar) -> None:
    """Solve for the pair ``(i, j)`` and move the scores ``up`` and ``low`` (in place), and
    :math:`y \\bar G` unless ``gbar`` is None."""
    y, QD, C, alpha = lists
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
    alpha[i], alpha[j] = a_i, a_j
    for t, a, old in ((i, a_i, old_i), (j, a_j, old_j)):
        C_t = C[t]
        if (a < C_t) == (old < C_t) and (a > 0) == (old > 0):
            continue  # in the same sets as before: the step has moved its scores already
        if gbar is not None and (old >= C_t) != (a >= C_t):  # i first, then j, as libsvm
            full_row, yGbar = gbar
            gbar_step = (C_t * y[t]) * full_row(t)  # Gbar_k += C_t Q_tk, y-scaled
            if old >= C_t:
                yGbar -= gbar_step
            else:
                yGbar += gbar_step
        lo = low.item(t)
        yG_t = lo if lo > -np.inf else -up.item(t)
        in_up, in_low = a < C_t, a > 0  # y = 1: up while below C, down while above 0
        if y[t] < 0:
            in_up, in_low = in_low, in_up
        up[t] = -yG_t if in_up else -np.inf
        low[t] = yG_t if in_low else -np.inf
