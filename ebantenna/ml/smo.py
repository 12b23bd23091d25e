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

This module is the **reference**: the algorithm as the textbook writes it, on a full kernel
matrix, each step a function that fits on a screen: :func:`select_working_set` (first and second
order), :func:`solve_two_variable` (Platt's :math:`L` and :math:`H`), :func:`update_gradient` and
:func:`bias`, put together by the loop :func:`reference_smo`, which ``SVC(solver="reference")``
runs.

:func:`solve_smo` runs the same algorithm on the **engines**, private modules that make it fast
or libsvm's to the last digit. Kernel rows come from :class:`~ebantenna.ml.kernels.KernelRows`,
which either holds the whole matrix (one GEMM) or keeps a least-recently-used cache of rows that
are computed on demand. How an engine selects, breaks ties, floors the curvature, shrinks and
sums the bias is an :class:`~ebantenna.ml.smo_policy.SMOPolicy`, a frozen value with two
presets: :data:`~ebantenna.ml.smo_policy.DEFAULT` and :data:`~ebantenna.ml.smo_policy.LIBSVM`.
``_smo_state`` is libsvm's solver: its shrinking, its variable order, its reconstruction of the
gradient and a memo of kernel rows. It runs libsvm's conventions with its own update, and the
default conventions with the loop of ``_smo_whole``, which takes the updates between two
shrinkings (all of them when the policy does not shrink) on the active variables with few NumPy
calls each. The two share libsvm's two-variable step and the second-order scores
(``_smo_step``) and return the same numbers to the last bit for the same policy. Tests hold
both equal to the reference within what the stopping rule allows. This module imports none of
them: each engine's module imports it and adds itself to :data:`SMO_ENGINES` when the package is
imported, which is all :func:`solve_smo` reads.

The optional compiled engine
----------------------------
With numba installed (``pip install ebantenna[fast]``) the loop of both engines also exists
compiled (``_smo_numba``): the same floating-point operations in the same order, so the same
:math:`\alpha`, :math:`\rho`, number of updates and violation to the last bit (tests hold it
there on every kernel and both conventions), run in one call with no NumPy call per update.
:func:`solve_smo` uses it whenever the whole kernel is stored and numba works
(``ebantenna.ml.smo_engine_status()``); otherwise the NumPy engines run, and the reason is
said once per process (an INFO log when numba is not installed, a :class:`RuntimeWarning` when
it fails). The environment variable ``EBANTENNA_ENGINE`` (``ENGINE_VARIABLE`` here) set to
``numpy``, ``compiled`` or ``auto`` (the default), or the ``engine`` argument of
:func:`solve_smo`, chooses; ``compiled`` raises when it is not available.

Conventions and the digits they move
------------------------------------
With the :data:`~ebantenna.ml.smo_policy.LIBSVM` policy (``SVC(libsvm_compat=True)``) the
solver follows libsvm's arithmetic exactly, and scikit-learn's :class:`~sklearn.svm.SVC` is
usually reproduced to about 1e-12 with the same iteration counts, with shrinking on (libsvm's
variable order and gradient reconstruction included) or off. What each convention does, with
the field of :class:`~ebantenna.ml.smo_policy.SMOPolicy` that holds it:

* **float32 kernel storage** (libsvm's ``Qfloat``; ``float32_kernel``): kernel entries carry a
  relative error of about 6e-8. Solving with a float64 kernel instead moves the decision values
  by a few 1e-7 where it keeps the path, but where an entry's lost bits decide a selection the
  path changes and the machine stops elsewhere within ``tol`` (on iris classes 1 and 2, with
  the RBF and the linear kernel, it does).
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

What is left between libsvm and this package is the summation order of the kernel sums in the
decision function: about 1e-14 of the values' scale, and the summation order of the kernel
entries themselves: libsvm forms each dot product on its own, the package all of them in one
matrix product, and the two can differ in the last bit of an entry. On a problem scaled as
SVMs want, that bit rarely survives the float32 storage and the iteration counts agree, but
rarely is not never: with the linear kernel, 8 of 200 subsets of 80 iris rows (two classes)
took another number of updates (19 against 18, 42 against 40) with decision values up to 0.02
apart, on problems of fewer than 200 updates. On one that SMO needs millions of updates to solve
(unscaled features spanning several orders of magnitude, a large ``C``) a last bit changes the
path as a rule: the same optimum within ``tol``, but another number of updates, and
scikit-learn itself counts differently for the linear kernel and for the same kernel passed as a
precomputed matrix. Given the same matrix
(``kernel='precomputed'``) both take the same updates there too.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np

from .._engines import ENGINE_VARIABLE, EngineStatus
from .._validate import check_array, check_choice, check_int, check_positive
from .kernels import KernelRows
from .smo_policy import DEFAULT, TAU, SMOPolicy

__all__ = ["SMOResult", "select_working_set", "solve_two_variable", "update_gradient", "bias",
           "reference_smo", "solve_smo", "SMO_ENGINES", "ENGINE_VARIABLE", "EngineStatus"]

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


# ----------------------------------------------------------------------------- the reference
def _vectors(**arrays) -> int:
    """The common length of ``arrays``, each a non-empty 1-D NumPy array of numbers; else an
    error naming the first that is not. Shapes only: the step functions run once per SMO
    iteration, where a pass over the values would cost as much as the step."""
    n = None
    for name, a in arrays.items():
        if not isinstance(a, np.ndarray) or a.ndim != 1 or a.dtype.kind not in "fiu":
            raise TypeError(f"{name} must be a 1-D NumPy array of numbers, got "
                            f"{type(a).__name__} {getattr(a, 'shape', '')}")
        if a.size == 0:
            raise ValueError(f"{name} must not be empty")
        if n is None:
            n = a.size
        elif a.size != n:
            first = next(iter(arrays))
            raise ValueError(f"{name} must have one entry per variable ({n}, as {first}), got "
                             f"{a.size}")
    return n


def _square(K, n: int) -> None:
    if not isinstance(K, np.ndarray) or K.shape != (n, n) or K.dtype.kind not in "fiu":
        raise ValueError(f"K must be the ({n}, {n}) NumPy kernel matrix of the {n} variables, got "
                         f"{type(K).__name__} {getattr(K, 'shape', '')}")


def _pair(i, j, n: int) -> None:
    check_int("i", i, minimum=0, maximum=n - 1)
    check_int("j", j, minimum=0, maximum=n - 1)


def select_working_set(G, y, alpha, C, K, *, rule="second-order", tol=1e-3, tau=TAU):
    """The working pair :math:`(i, j)` of an SMO step, or none when :math:`\\alpha` is optimal.

    :math:`i` maximises :math:`-y_t G_t` over :math:`I_{up}` (the variables that can move so
    that :math:`y_t\\alpha_t` grows); its value is :math:`m(\\alpha)`, and :math:`M(\\alpha)` is
    the smallest :math:`-y_t G_t` over :math:`I_{low}` (those that can move the other way).
    :math:`\\alpha` is optimal when :math:`m(\\alpha) \\le M(\\alpha)`: SMO stops when the
    violation :math:`m - M` is below ``tol``. Then :math:`j`, in :math:`I_{low}`:

    * ``'first-order'``: the one of :math:`M(\\alpha)`, the maximal violating pair;
    * ``'second-order'`` (Fan, Chen and Lin): among the :math:`j` with
      :math:`b_{ij} = m + y_j G_j > 0`, the one whose two-variable step lowers the objective
      most, by :math:`b_{ij}^2 / (2 a_{ij})` with :math:`a_{ij} = K_{ii} + K_{jj} - 2K_{ij}`
      (floored at ``tau``).

    Parameters
    ----------
    G, y, alpha, C : ndarray of shape (n,)
        Gradient :math:`Q\\alpha - e`, labels (+1 or -1), variables and their bounds.
    K : ndarray of shape (n, n)
        Kernel matrix (the second-order rule reads row :math:`i` and the diagonal).
    rule : {'second-order', 'first-order'}
    tol, tau : float
        Stopping tolerance; floor of the curvature :math:`a_{ij}`.

    Returns
    -------
    i, j : int or None
        The pair, or None twice when the violation is below ``tol``.
    violation : float
        :math:`m(\\alpha) - M(\\alpha)`.

    Examples
    --------
    At :math:`\\alpha = 0` every gradient is -1; :math:`I_{up}` holds the positives, so the
    violation is 1 - (-1) = 2:

    >>> y = np.array([1.0, 1.0, -1.0]); K = np.eye(3)
    >>> select_working_set(-np.ones(3), y, np.zeros(3), np.ones(3), K)
    (0, 2, 2.0)
    """
    n = _vectors(G=G, y=y, alpha=alpha, C=C)
    check_choice("rule", rule, ("second-order", "first-order"))
    if rule == "second-order":
        _square(K, n)
    minus_yG = -y * G
    up = ((y > 0) & (alpha < C)) | ((y < 0) & (alpha > 0))  # I_up
    low = ((y > 0) & (alpha > 0)) | ((y < 0) & (alpha < C))  # I_low
    up_score = np.where(up, minus_yG, -np.inf)
    low_score = np.where(low, minus_yG, np.inf)
    i = int(np.argmax(up_score))
    violation = float(up_score[i] - low_score.min())  # m(alpha) - M(alpha)
    if not violation >= tol:  # also when a set is empty (-inf)
        return None, None, violation
    if rule == "first-order":
        return i, int(np.argmin(low_score)), violation
    b = up_score[i] - low_score  # b_ij = m + y_j G_j; -inf outside I_low
    a = np.maximum(K[i, i] + np.diag(K) - 2.0 * K[i], tau)  # a_ij, floored
    gain = np.where(b > 0, b * b / a, 0.0)  # twice the decrease of the objective
    return i, int(np.argmax(gain)), violation


def solve_two_variable(i, j, alpha, G, y, C, K, *, tau=TAU):
    """Platt's solution of the dual in :math:`(\\alpha_i, \\alpha_j)`, the others held fixed.

    The constraint :math:`y_i\\alpha_i + y_j\\alpha_j = \\text{const}` leaves a segment: in
    :math:`\\alpha_j`, the interval :math:`[L, H]` where both variables stay in their boxes
    (:math:`L = \\max(0, \\alpha_j - \\alpha_i)`, :math:`H = \\min(C_j, C_i + \\alpha_j -
    \\alpha_i)` when :math:`y_i \\ne y_j`; :math:`L = \\max(0, \\alpha_i + \\alpha_j - C_i)`,
    :math:`H = \\min(C_j, \\alpha_i + \\alpha_j)` otherwise). Along it the objective is a
    parabola of curvature :math:`a_{ij} = K_{ii} + K_{jj} - 2K_{ij}` (Platt's
    :math:`\\eta`, ``eta`` in the code), least at
    :math:`\\alpha_j + y_j (E_i - E_j) / a_{ij}` with Platt's errors
    :math:`E_i - E_j = y_i G_i - y_j G_j`. Clip that to :math:`[L, H]`; :math:`\\alpha_i`
    follows from the constraint. An :math:`a_{ij} \\le \\tau` (a kernel that is not positive
    definite, or two points too close to tell apart) is replaced by ``tau``. libsvm replaces
    only :math:`a_{ij} \\le 0`, and keeps :math:`0 < a_{ij} < \\tau` as it is (the
    ``'nonpositive'`` curvature floor of :class:`~ebantenna.ml.smo_policy.SMOPolicy`).

    Parameters
    ----------
    i, j : int
        The working pair.
    alpha, G, y, C : ndarray of shape (n,)
        Variables, gradient :math:`Q\\alpha - e`, labels and bounds.
    K : ndarray of shape (n, n)
        Kernel matrix.

    Returns
    -------
    tuple of float
        The new :math:`(\\alpha_i, \\alpha_j)`.

    Examples
    --------
    Two points of opposite classes at distance 2 (linear kernel), from :math:`\\alpha = 0`:

    >>> K = np.array([[4.0, 0.0], [0.0, 0.0]])
    >>> solve_two_variable(0, 1, np.zeros(2), -np.ones(2), np.array([1.0, -1.0]),
    ...                    np.full(2, 10.0), K)
    (0.5, 0.5)
    """
    n = _vectors(alpha=alpha, G=G, y=y, C=C)
    _square(K, n)
    _pair(i, j, n)
    if y[i] != y[j]:  # alpha_i - alpha_j = d stays
        d = alpha[i] - alpha[j]
        L, H, top = max(0.0, -d), min(C[j], C[i] - d), C[i] - d
    else:  # alpha_i + alpha_j = t stays
        t = alpha[i] + alpha[j]
        L, H, top = max(0.0, t - C[i]), min(C[j], t), t - C[i]
    eta = max(K[i, i] + K[j, j] - 2.0 * K[i, j], tau)
    a_j = alpha[j] + y[j] * (y[i] * G[i] - y[j] * G[j]) / eta  # the parabola's minimum
    a_j = min(max(a_j, L), H)
    # alpha_i from the constraint; at a_j = top it is C_i, which the rounding of C_i - d + d or
    # t - (t - C_i) could miss by one unit in the last place (at the other end, d - d = 0 exactly)
    a_i = C[i] if a_j == top else (a_j + d if y[i] != y[j] else t - a_j)
    return float(a_i), float(a_j)


def update_gradient(G, K, y, i, j, delta_i, delta_j):
    """The gradient :math:`G = Q\\alpha - e` after :math:`\\alpha_i` and :math:`\\alpha_j` moved.

    Only two columns of :math:`Q` (:math:`Q_{ts} = y_t y_s K_{ts}`) enter:
    :math:`G \\leftarrow G + Q_{:i}\\,\\Delta\\alpha_i + Q_{:j}\\,\\Delta\\alpha_j`.

    Examples
    --------
    >>> K = np.array([[4.0, 0.0], [0.0, 0.0]]); y = np.array([1.0, -1.0])
    >>> update_gradient(-np.ones(2), K, y, 0, 1, 0.5, 0.5)
    array([ 1., -1.])
    """
    n = _vectors(G=G, y=y)
    _square(K, n)
    _pair(i, j, n)
    return G + y * (K[i] * (y[i] * delta_i) + K[j] * (y[j] * delta_j))


def bias(G, y, alpha, C, *, sequential=False) -> float:
    """libsvm's :math:`\\rho`, the bias of :math:`f(x) = \\sum_t y_t\\alpha_t k(x_t, x) - \\rho`.

    At the optimum every free variable (:math:`0 < \\alpha_t < C_t`) has :math:`y_t G_t = \\rho`:
    :math:`\\rho` is their mean. Without a free variable the optimality conditions only bound
    :math:`\\rho` by variables at their bounds; it is the middle of that interval.

    Parameters
    ----------
    G, y, alpha, C : ndarray of shape (n,)
        Gradient, labels, variables and bounds.
    sequential : bool
        Sum one term after the other as libsvm does (last bits only), not pairwise.

    Examples
    --------
    >>> bias(np.array([0.5, -0.25]), np.array([1.0, -1.0]), np.array([0.5, 0.5]), np.ones(2))
    0.375
    """
    _vectors(G=G, y=y, alpha=alpha, C=C)
    yG = y * G
    free = (alpha > 0) & (alpha < C)
    if free.any():
        total = np.cumsum(yG[free])[-1] if sequential else yG[free].sum()
        return float(total / np.count_nonzero(free))
    upper, lower, pos = alpha >= C, alpha <= 0, y > 0
    above = yG[(upper & ~pos) | (lower & pos)]  # rho <= y_t G_t there
    below = yG[(upper & pos) | (lower & ~pos)]  # rho >= y_t G_t there
    return float(((above.min() if above.size else np.inf)
                  + (below.max() if below.size else -np.inf)) / 2)


def _checked_problem(K, y, C):
    """``(K, y, C)`` of a dual problem checked: ``K`` a finite square matrix, ``y`` its labels,
    each +1 or -1, ``C`` one finite bound > 0 per label."""
    K = check_array("K", K, ndim=2)
    if K.shape[0] != K.shape[1]:
        raise ValueError(f"K must be a square kernel matrix, got shape {K.shape}")
    y = check_array("y", y, ndim=1)
    if y.size != K.shape[0] or not np.all(np.abs(y) == 1):
        raise ValueError(f"y must hold one label, +1 or -1, per row of K ({K.shape[0]})")
    C = check_array("C", C, ndim=1)
    if C.shape != y.shape or np.any(C <= 0):
        raise ValueError(f"C must hold one bound > 0 per label ({y.size})")
    return K, y, C


def reference_smo(K, y, C, *, tol=1e-3, max_iter=10_000_000, selection="second-order"):
    """SMO as the textbook writes it: select a pair, solve it, update the gradient; repeat.

    It checks its arguments once; the steps it calls take checked values (as
    :class:`~ebantenna.ml.SVC` gives them) and compute nothing that they do not need.

    Parameters
    ----------
    K : ndarray of shape (n, n)
        Kernel matrix, float64.
    y, C : ndarray of shape (n,)
        Labels (+1 or -1) and bounds :math:`C_t > 0`.
    tol : float
        Stopping tolerance on the maximal violation.
    max_iter : int or float
        Largest number of updates.
    selection : {'second-order', 'first-order'}
        Rule of :func:`select_working_set`.

    Returns
    -------
    SMOResult

    Examples
    --------
    >>> K = np.array([[0.0, 0.0], [0.0, 4.0]])  # the points 0 and 2, linear kernel
    >>> res = reference_smo(K, np.array([-1.0, 1.0]), np.full(2, 10.0))
    >>> res.alpha, res.rho, res.n_iter
    (array([0.5, 0.5]), 1.0, 1)
    """
    K, y, C = _checked_problem(K, y, C)
    tol = check_positive("tol", tol)
    if not (isinstance(max_iter, int | float | np.integer | np.floating)
            and not isinstance(max_iter, bool) and max_iter >= 1):  # NaN fails too
        raise ValueError(f"max_iter must be a number of updates >= 1, got {max_iter!r:.40}")
    check_choice("selection", selection, ("second-order", "first-order"))
    alpha = np.zeros(y.size)
    G = -np.ones(y.size)  # Q alpha - e at alpha = 0
    n_iter = 0
    i, j, violation = select_working_set(G, y, alpha, C, K, rule=selection, tol=tol)
    while i is not None and n_iter < max_iter:
        a_i, a_j = solve_two_variable(i, j, alpha, G, y, C, K)
        G = update_gradient(G, K, y, i, j, a_i - alpha[i], a_j - alpha[j])
        alpha[i], alpha[j] = a_i, a_j
        n_iter += 1
        i, j, violation = select_working_set(G, y, alpha, C, K, rule=selection, tol=tol)
    objective = float(np.sum(alpha * (G - 1.0)) / 2.0)
    return SMOResult(alpha, bias(G, y, alpha, C), n_iter, i is None, objective, violation)


# ----------------------------------------------------------------------------- the engines
#: The engines that run :func:`solve_smo`'s loop, by name, each added by its own private module
#: when the package is imported: ``"numpy"``, libsvm's solver and the whole-kernel loop
#: (``ml/_smo_state.py``), and ``"compiled"``, their numba twin (``ml/_smo_compiled.py``). Each is
#: called as ``run(engine, rows, y, C, diagonal, policy, tol, max_iter)`` on checked values,
#: with ``engine`` the caller's choice (None: ``EBANTENNA_ENGINE``), and returns ``(y, C, alpha,
#: yG, perm, n_iter, converged, violation)``, the arrays in its own order (``perm[p]`` the
#: variable at position ``p``; None: the caller's order). The compiled engine returns None where
#: it does not run: the choice is ``'numpy'``, numba does not work under ``'auto'``, or the
#: kernel is not stored whole.
SMO_ENGINES: dict = {}


def solve_smo(
    rows: KernelRows,
    y: np.ndarray,
    C: np.ndarray,
    *,
    diagonal: np.ndarray,
    tol: float = 1e-3,
    max_iter: int = 10_000_000,
    policy: SMOPolicy = DEFAULT,
    engine: str | None = None,
) -> SMOResult:
    """Solve the binary C-SVC dual by SMO on the engines (the policy chooses which).

    The same algorithm as :func:`reference_smo`, from kernel rows, in libsvm's arithmetic:
    the policy's conventions without shrinking on the whole-kernel engine, every other policy
    on libsvm's engine with shrinking and a row memo (see the module text). Inputs are taken
    as checked (:class:`~ebantenna.ml.SVC` validates them once); only the policy's type is
    checked here.

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
    engine : {'auto', 'numpy', 'compiled'} or None
        Which engine runs the loop (see the module text): the NumPy engines,
        or their compiled twin (numba, ``pip install ebantenna[fast]``), which returns the same
        numbers to the last bit when the whole kernel is stored. None reads the environment
        variable ``EBANTENNA_ENGINE``, default ``'auto'``: compiled when numba works.

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
    if not isinstance(rows, KernelRows):
        raise TypeError(f"rows must be KernelRows, got {type(rows).__name__}")
    y, C, diagonal = (np.array(check_array(name, v, ndim=1)) for name, v in
                      (("y", y), ("C", C), ("diagonal", diagonal)))  # copies: the engines sort

    if y.size != rows.n or not np.all(np.abs(y) == 1):
        raise ValueError(f"y must hold one label, +1 or -1, per kernel row ({rows.n})")
    if C.shape != y.shape or np.any(C <= 0):
        raise ValueError(f"C must hold one bound > 0 per label ({y.size})")
    if diagonal.shape != y.shape:
        raise ValueError(f"diagonal must hold k(x_t, x_t) for each of the {y.size} points")
    check_positive("tol", tol)
    if max_iter != math.inf:  # no limit
        check_int("max_iter", max_iter, minimum=1)
    args = (engine, rows, y, C, diagonal, policy, tol, max_iter)
    ran = SMO_ENGINES["compiled"](*args)
    if ran is None:
        ran = SMO_ENGINES["numpy"](*args)
    y, C, alpha, yG, perm, n_iter, converged, violation = ran
    if not converged:
        logger.info("SMO stopped at max_iter=%d with violation %.3g", max_iter, violation)
    G = y * yG  # in the engine's order: the sums of the objective and the bias follow it
    objective = float(np.sum(alpha * (G - 1.0)) / 2.0)
    rho = bias(G, y, alpha, C, sequential=policy.bias_sum == "sequential")
    if perm is not None:  # back to the callers' order
        in_order = np.empty_like(alpha)
        in_order[perm] = alpha
        alpha = in_order
    return SMOResult(alpha, rho, n_iter, converged, objective, float(violation))
