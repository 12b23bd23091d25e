"""How an SMO run behaves where the textbook leaves a choice: the
:class:`~ebantenna.ml.smo_policy.SMOPolicy`.

The SMO engines behind :func:`ebantenna.ml.smo.solve_smo` run one algorithm, the reference
loop of :mod:`ebantenna.ml.smo`; the choices they make on the way (which working-set rule, which
index on a tie, how a tiny curvature is floored, whether variables are shrunk, how the bias is
summed, in which precision kernel entries are stored) are fields of a frozen :class:`SMOPolicy`.
Two presets: :data:`DEFAULT`, the package's own, and :data:`LIBSVM`, the conventions of libsvm as
bundled with scikit-learn, which reproduce its path and its digits.
The module text of :mod:`ebantenna.ml.smo` says which digit each convention moves.

Kernels that are not positive semi-definite
-------------------------------------------
With a positive semi-definite (PSD) kernel the dual is a convex quadratic problem: every path of
SMO ends at the same optimum, within what the stopping tolerance allows, so the package's own
conventions are free to take another path than libsvm's. The sigmoid kernel
:math:`\\tanh(\\gamma x^T y + r)` is not PSD in general (H.-T. Lin and C.-J. Lin, "A study on
sigmoid kernels for SVM and the training of non-PSD kernels by SMO-type methods", 2003), nor is
the polynomial kernel :math:`(\\gamma x^T y + r)^d` with :math:`r < 0` (on make_moons, degree 3,
r = -5, its Gram matrix has eigenvalues down to -24364), and a precomputed or callable kernel
need not be. Then the quadratic form :math:`\\alpha^T Q \\alpha` has
directions of negative curvature, the dual is not convex and has several stationary points, and
SMO stops at the one its path leads to: the index taken on a tie (every gradient equals -1 at the
start, so the very first working set is a tie) and the curvature floor (a negative :math:`a_{ij}`
is a step along a direction of negative curvature, which the floor turns into a finite step)
choose among them. The default conventions then land elsewhere than scikit-learn: on
breast_cancer (standardised), sigmoid kernel, C = 100, decision values 1407 apart and 61 of 569
predictions different. So :func:`fit_policy` takes libsvm's conventions, the whole of
:data:`LIBSVM` with its float32 kernel storage, for every kernel that :func:`positive_semidefinite`
does not accept; SMO then takes libsvm's path step by step and stops where scikit-learn stops.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.linalg import lapack

from .._validate import check_array, check_real

__all__ = ["SMOPolicy", "DEFAULT", "LIBSVM", "SELECTIONS", "TAU", "fit_policy",
           "positive_semidefinite"]

#: Working-set selection rules.
SELECTIONS = ("second-order", "first-order")

#: libsvm's floor for a non-positive curvature of the two-variable problem.
TAU = 1e-12


@dataclass(frozen=True)
class SMOPolicy:
    """The conventions of an SMO run: how it selects, breaks ties, floors, shrinks and sums.

    None of them changes the problem solved; each changes the path to its optimum or the last
    digits of the result (see the module text for which digit each one moves).

    Parameters
    ----------
    selection : {'second-order', 'first-order'}
        Working-set selection rule.
    ties : {'first', 'last'}
        Index taken when several candidates of the selection score the same: the first, or the
        last as libsvm's ``>=`` comparisons do.
    curvature_floor : {'tau', 'nonpositive'}
        How the second-order working-set selection scores a curvature :math:`a_{ij}` that is too
        small: ``'tau'`` uses :math:`\\max(a_{ij}, \\tau)`; ``'nonpositive'`` replaces only
        :math:`a_{ij} \\le 0` by :math:`\\tau` (libsvm). :math:`\\tau = 10^{-12}`. The step
        itself (the two-variable step of the SMO loop) always floors libsvm's way.
    bias_sum : {'pairwise', 'sequential'}
        Summation of :math:`y_t G_t` over the free variables for :math:`\\rho`: NumPy's pairwise
        sum, or one term after the other as libsvm does.
    shrinking : bool
        libsvm's shrinking heuristic: every ``min(n, 1000)`` updates, variables at a bound that
        are unlikely to move are set aside (and their gradient rebuilt before the final check).
        The variables are reordered exactly as libsvm reorders them.
    float32_kernel : bool
        Store kernel entries in float32 (libsvm's ``Qfloat``) even when float64 would fit; read
        by whoever builds the :class:`~ebantenna.ml.kernels.KernelRows`
        (see :meth:`kernel_dtype`).

    Examples
    --------
    >>> LIBSVM.ties, LIBSVM.shrinking
    ('last', True)
    >>> from dataclasses import replace
    >>> replace(LIBSVM, shrinking=False).bias_sum
    'sequential'
    """

    selection: str = "second-order"
    ties: str = "first"
    curvature_floor: str = "tau"
    bias_sum: str = "pairwise"
    shrinking: bool = False
    float32_kernel: bool = False

    def __post_init__(self):
        for name, allowed in (("selection", SELECTIONS), ("ties", ("first", "last")),
                              ("curvature_floor", ("tau", "nonpositive")),
                              ("bias_sum", ("pairwise", "sequential"))):
            value = getattr(self, name)
            if not (isinstance(value, str) and value in allowed):
                raise ValueError(f"{name} must be one of {', '.join(map(repr, allowed))}; "
                                 f"got {value!r}")
        for name in ("shrinking", "float32_kernel"):
            if not isinstance(getattr(self, name), bool | np.bool_):
                raise TypeError(f"{name} must be a bool, got {getattr(self, name)!r}")

    def kernel_dtype(self, n: int, cache_bytes: int) -> type:
        """Storage type of a kernel of ``n`` points: float32 if asked for or if float64 of the
        whole ``n × n`` matrix would not fit in ``cache_bytes``, else float64.

        Examples
        --------
        >>> DEFAULT.kernel_dtype(100, 1 << 20), LIBSVM.kernel_dtype(100, 1 << 20)
        (<class 'numpy.float64'>, <class 'numpy.float32'>)
        """
        from .._validate import check_int

        n = check_int("n", n, minimum=0)
        cache_bytes = check_int("cache_bytes", cache_bytes, minimum=0)
        if self.float32_kernel or n * n * 8 > cache_bytes:
            return np.float32
        return np.float64


#: The package's own conventions: first index on ties, :math:`\max(a, \tau)`, pairwise bias sum,
#: no shrinking, float64 kernel entries when they fit.
DEFAULT = SMOPolicy()

#: libsvm's conventions (as bundled with scikit-learn): last index on ties, its curvature floor,
#: sequential bias sum, shrinking, float32 kernel entries.
LIBSVM = SMOPolicy(ties="last", curvature_floor="nonpositive", bias_sum="sequential",
                   shrinking=True, float32_kernel=True)


def fit_policy(libsvm_compat: bool, selection: str, shrinking: bool,
               whole_kernel: bool, convex: bool = True) -> SMOPolicy:
    """The SMO conventions of an :class:`~ebantenna.ml.SVC` fit.

    ``libsvm_compat`` takes all of libsvm's (:data:`LIBSVM`), with ``shrinking`` as given, and so
    does a kernel that is not positive semi-definite (``convex=False``): its dual has several
    stationary points, and only libsvm's path leads to scikit-learn's (see the module text).
    Otherwise the package's (:data:`DEFAULT`), with ``shrinking`` as given: the solver then
    shrinks as libsvm does and keeps the default tie-breaking, curvature floor and bias sum,
    whether the whole kernel is stored or its rows are cached (``whole_kernel`` no longer
    changes the policy; ``cache_size`` still sets the kernel's storage type,
    :meth:`SMOPolicy.kernel_dtype`, and a float32 kernel can take another path). The floor
    :math:`\\max(a_{ij}, \\tau)` differs from libsvm's only for :math:`0 < a_{ij} < \\tau`
    (two points closer than about :math:`10^{-6}`), and costs the NumPy engines one call per
    update less.

    Shrinking pays on the whole kernel too: without it every update passes over all the
    variables of the problem, where libsvm's passes over those it keeps active, on a long run
    a small part of them. (The NumPy engines still take the updates before the first
    shrinking on the loop over all variables, which makes fewer NumPy calls per update.)

    Examples
    --------
    >>> fit_policy(False, "second-order", True, whole_kernel=True).shrinking
    True
    >>> fit_policy(False, "second-order", False, whole_kernel=True).shrinking
    False
    >>> fit_policy(True, "first-order", True, whole_kernel=True).ties
    'last'
    >>> fit_policy(False, "second-order", True, whole_kernel=True, convex=False) == LIBSVM
    True
    """
    if libsvm_compat or not convex:
        return replace(LIBSVM, selection=selection, shrinking=shrinking)
    if shrinking:
        return replace(DEFAULT, selection=selection, shrinking=True)
    return replace(DEFAULT, selection=selection)


def positive_semidefinite(kernel, gram: np.ndarray | None = None, *,
                          coef0: float = 0.0) -> bool:
    """Whether a kernel counts as positive semi-definite, so that the SVM dual is convex.

    Parameters
    ----------
    kernel : str or callable
        The kernel of the :class:`~ebantenna.ml.SVC`. 'linear' and 'rbf' are PSD; 'poly',
        :math:`(\\gamma\\, x \\cdot y + r)^d`, is PSD when ``coef0`` :math:`r \\ge 0` (a sum of
        PSD kernels raised to a whole power: Schur's product theorem) and does not count as PSD
        when :math:`r < 0`, where its Gram matrix can have negative eigenvalues; 'sigmoid'
        never counts as PSD (it is not, for most of its parameters); for 'precomputed' and a
        callable the answer is that of their Gram matrix.
    gram : ndarray of shape (n, n), optional
        The training Gram matrix of a precomputed or callable kernel.
    coef0 : float
        The kernel's :math:`r` (read for 'poly' only).

    Returns
    -------
    bool
        For a Gram matrix :math:`K`: whether the Cholesky factorisation of
        :math:`K + \\delta I` exists, with :math:`\\delta = 2 n \\varepsilon \\max|K_{ij}|`.
        A matrix that differs from a PSD one by rounding errors of at most
        :math:`\\varepsilon \\max|K_{ij}|` per entry has no eigenvalue below
        :math:`-n \\varepsilon \\max|K_{ij}|` (Gershgorin's circles bound the perturbation's
        spectral norm by its largest row sum); the second :math:`n \\varepsilon \\max|K_{ij}|`
        covers the backward error of the factorisation itself. It costs about :math:`n^3/3`
        flops, once per fit.

    Examples
    --------
    >>> X = np.array([[0.0, 1.0], [1.0, 0.0], [1.0, 1.0]])
    >>> positive_semidefinite("precomputed", X @ X.T)
    True
    >>> positive_semidefinite("precomputed", np.tanh(X @ X.T - 1.0))
    False
    >>> positive_semidefinite("sigmoid"), positive_semidefinite("rbf")
    (False, True)
    >>> positive_semidefinite("poly", coef0=1.0), positive_semidefinite("poly", coef0=-1.0)
    (True, False)
    """
    coef0 = check_real("coef0", coef0)
    if isinstance(kernel, str) and kernel != "precomputed":
        if kernel not in ("linear", "poly", "rbf", "sigmoid"):
            raise ValueError(f"kernel must be 'linear', 'poly', 'rbf', 'sigmoid', 'precomputed' "
                             f"or a callable, got {kernel!r}")
        return kernel in ("linear", "rbf") or (kernel == "poly" and coef0 >= 0)
    if not (isinstance(kernel, str) or callable(kernel)):
        raise TypeError(f"kernel must be a kernel's name or a callable, got "
                        f"{type(kernel).__name__}")
    if gram is None:
        raise ValueError("gram must be given: the training Gram matrix of a precomputed or "
                         "callable kernel")
    K = check_array("gram", gram, ndim=2, min_length=0)
    if K.shape[0] != K.shape[1]:
        raise ValueError(f"gram must be a square matrix, got shape {K.shape}")
    n = K.shape[0]
    if n == 0:
        return True
    delta = 2.0 * n * np.finfo(np.float64).eps * float(np.abs(K).max())
    shifted = K + delta * np.eye(n)
    _, info = lapack.dpotrf(shifted, lower=1, overwrite_a=1, clean=0)
    return info == 0
