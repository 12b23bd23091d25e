"""libsvm's arithmetic of one SMO step, shared by the two engines (private).

The reference :mod:`ebantenna.ml.smo` writes the working-set selection and the two-variable
update as the textbook does. The engines (:mod:`ebantenna.ml._smo_state` with shrinking and
libsvm's conventions, :mod:`ebantenna.ml._smo_whole` for the default run over all variables)
take the same steps in libsvm's floating-point order instead, which is what makes their digits
those of scikit-learn's ``SVC``; the two pieces they share are here, written once:

* :func:`pair_step`, libsvm's closed-form solution of the two-variable problem, clipped in its
  order of cases (mathematically the reference's
  :func:`~ebantenna.ml.smo.solve_two_variable`, but not to the last bit);
* :func:`curvature` and :func:`second_order_gain`, the scores of Fan, Chen and Lin's
  second-order selection over a whole vector of candidates, computed with as few NumPy calls as
  it takes (the curvatures, which depend on the first index alone, apart, so that an engine can
  keep them from one update to the next).

Inputs are taken as checked: :class:`~ebantenna.ml.SVC` validates them once.
"""

from __future__ import annotations

import numpy as np

from .smo_policy import TAU

__all__ = ["pair_step", "curvature", "second_order_gain", "argmax"]


def argmax(values: np.ndarray, last: bool) -> int:
    """Index of the largest value; on a tie the first, or the last (libsvm's ``>=``).

    The array methods, not ``np.argmax``: the wrapper's dispatch costs more than the search on
    the vectors of a few thousand entries that SMO scans twice per update.

    Examples
    --------
    >>> argmax(np.array([1.0, 3.0, 3.0]), last=False), argmax(np.array([1.0, 3.0, 3.0]), last=True)
    (1, 2)
    """
    if last:
        return values.size - 1 - int(values[::-1].argmax())
    return int(values.argmax())


def curvature(Ki: np.ndarray, pair_diagonal, taus: np.ndarray,
              floor_nonpositive: bool) -> np.ndarray:
    """The floored curvatures :math:`a_{ij} = K_{ii} + K_{jj} - 2 K_{ij}` of the pairs
    :math:`(i, j)` over all :math:`j`, as a new array.

    They depend on :math:`i` alone, not on the gradient: an engine may keep them from one
    update to the next while the positions stay (SMO picks the same :math:`i` again and again).

    Parameters
    ----------
    Ki : ndarray of shape (a,)
        Kernel row of :math:`i`, float64.
    pair_diagonal : float or tuple (ndarray of shape (a,), float)
        :math:`K_{ii} + K_{jj}`: one number when the diagonal is constant (as the RBF kernel's),
        which saves a pass (``Ki * -2.0 + s`` is the same number as ``s - 2.0 * Ki``), else the
        diagonal and :math:`K_{ii}`.
    taus : ndarray of shape (a,)
        The constant :math:`\\tau` as an array: ``np.maximum`` against an array gives the same
        numbers about three times as fast as against a Python float.
    floor_nonpositive : bool
        Replace only :math:`a_{ij} \\le 0` by :math:`\\tau` (libsvm), instead of
        :math:`\\max(a_{ij}, \\tau)`.

    Examples
    --------
    >>> curvature(np.array([1.0, 0.0, 1.0]), 2.0, np.full(3, 1e-12), False)
    array([1.e-12, 2.e+00, 1.e-12])
    """
    if isinstance(pair_diagonal, float):
        quad = Ki * -2.0
        quad += pair_diagonal
    else:
        diagonal, K_ii = pair_diagonal
        quad = diagonal + K_ii
        twice = Ki * 2.0
        quad -= twice
    if floor_nonpositive:
        quad[quad <= 0] = TAU  # exactly TAU where a <= 0, a itself elsewhere
    else:
        np.maximum(quad, taus, out=quad)
    return quad


def second_order_gain(b: np.ndarray, quad: np.ndarray, zeros: np.ndarray) -> np.ndarray:
    """Fan, Chen and Lin's second-order scores :math:`\\max(b_{ij}, 0)^2 / a_{ij}`, in place.

    For the chosen :math:`i`, libsvm minimises :math:`-b_{ij}^2 / a_{ij}` over the :math:`j` of
    :math:`I_{low}` with :math:`b_{ij} = G_{max} + y_j G_j > 0`. The same :math:`j` maximises
    these scores, with :math:`b` clipped at 0: the other candidates score 0, the best one more
    than 0 (:math:`b \\ge` ``tol`` there).

    Parameters
    ----------
    b : ndarray of shape (a,)
        :math:`G_{max} + y_j G_j` on :math:`I_{low}`, :math:`-\\infty` elsewhere; overwritten
        by the scores and returned.
    quad : ndarray of shape (a,)
        The floored curvatures :math:`a_{ij}` (:func:`curvature`).
    zeros : ndarray of shape (a,)
        The constant 0 as an array (faster in ``np.maximum``, as ``taus`` in :func:`curvature`).

    Returns
    -------
    ndarray
        ``b``, now holding the scores.

    Examples
    --------
    Candidates 1 and 2 improve the objective by :math:`b^2/(2a)`: 1/4 and 4/4.

    >>> b = np.array([-np.inf, 1.0, 2.0])
    >>> second_order_gain(b, np.array([2.0, 2.0, 2.0]), np.zeros(3))
    array([0. , 0.5, 2. ])
    """
    np.maximum(b, zeros, out=b)
    b *= b
    b /= quad
    return b


def pair_step(yi, yj, QD_i, QD_j, C_i, C_j, a_i, a_j, G_i, G_j, K_ij) -> tuple[float, float]:
    """libsvm's analytic solution of the two-variable subproblem, clipped to the box.

    The same minimiser as :func:`ebantenna.ml.smo.solve_two_variable` (Platt's L and H),
    reached in libsvm's order of operations: both variables move by the unclipped step, then
    each clipping case puts one on its bound and the other where the equality constraint says.

    Parameters are the labels, kernel diagonals, bounds, current values and gradients
    :math:`G = Q\\alpha - e` of the two variables, and their kernel entry :math:`K_{ij}`, as
    Python floats.

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
