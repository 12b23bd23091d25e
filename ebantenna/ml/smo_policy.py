"""How an SMO run behaves where the textbook leaves a choice: the
:class:`~ebantenna.ml.smo_policy.SMOPolicy`.

The SMO engines behind :func:`ebantenna.ml.smo.solve_smo` run one algorithm, the reference
loop of :mod:`ebantenna.ml.smo`; the choices they make on the way (which working-set rule, which
index on a tie, how a tiny curvature is floored, whether variables are shrunk, how the bias is
summed, in which precision kernel entries are stored) are fields of a frozen :class:`SMOPolicy`.
Two presets: :data:`DEFAULT`, the package's own, and :data:`LIBSVM`, the conventions of libsvm as
bundled with scikit-learn, which reproduce its path and its digits.
The module text of :mod:`ebantenna.ml.smo` says which digit each convention moves.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

__all__ = ["SMOPolicy", "DEFAULT", "LIBSVM", "SELECTIONS", "TAU", "fit_policy"]

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
               whole_kernel: bool) -> SMOPolicy:
    """The SMO conventions of an :class:`~ebantenna.ml.SVC` fit.

    ``libsvm_compat`` takes all of libsvm's (:data:`LIBSVM`), with ``shrinking`` as given.
    Otherwise the package's (:data:`DEFAULT`): shrinking only pays with the row cache, where the
    solver then shrinks as libsvm does, with libsvm's curvature floor, and keeps the default
    tie-breaking and bias sum.

    Examples
    --------
    >>> fit_policy(False, "second-order", True, whole_kernel=True).shrinking
    False
    >>> fit_policy(True, "first-order", True, whole_kernel=True).ties
    'last'
    """
    if libsvm_compat:
        return replace(LIBSVM, selection=selection, shrinking=shrinking)
    if shrinking and not whole_kernel:
        return replace(DEFAULT, selection=selection, shrinking=True,
                       curvature_floor="nonpositive")
    return replace(DEFAULT, selection=selection)
