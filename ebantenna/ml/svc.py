"""``SVC``: a kernel support vector classifier trained by hand-written SMO.

A drop-in for :class:`sklearn.svm.SVC` (C-SVC): the same parameter names, kernels (including a
precomputed matrix and a callable), one-vs-one multiclass training, probability estimates as libsvm
makes them (:mod:`ebantenna.ml.platt`) and the same fitted attributes, layout and signs, so that a
student can swap the import and compare. The dual problems are solved by SMO
(:mod:`ebantenna.ml.smo`): by default on its fast engines (:func:`~ebantenna.ml.smo.solve_smo`),
with ``solver="reference"`` by the textbook loop :func:`~ebantenna.ml.smo.reference_smo`.

The parameters are validated once, here, when :meth:`SVC.fit` starts; the functions it calls
take checked values.

Sparse input: :meth:`SVC.fit` takes ``scipy.sparse`` matrices and arrays, used as CSR (CSC, COO
and the other formats are converted, as scikit-learn does), with every kernel but 'precomputed'.
The RBF kernel of sparse rows stays free of cancellation without centring them
(:mod:`ebantenna.ml.sparse_input`). A model fitted on sparse rows predicts dense ones too, and,
unlike scikit-learn's, a model fitted on dense rows also predicts sparse ones.
"""

from __future__ import annotations

import logging
import math
import warnings
from numbers import Integral, Real

import numpy as np
import scipy.sparse as sp
from sklearn.base import BaseEstimator, ClassifierMixin, _fit_context
from sklearn.exceptions import ConvergenceWarning, NotFittedError
from sklearn.utils import check_random_state
from sklearn.utils._param_validation import Interval, Options, StrOptions
from sklearn.utils.class_weight import compute_class_weight
from sklearn.utils.metaestimators import available_if
from sklearn.utils.multiclass import check_classification_targets
from sklearn.utils.validation import (
    _check_sample_weight,
    check_is_fitted,
    column_or_1d,
    validate_data,
)

from .._validate import (
    check_int,
    check_nonnegative,
    check_positive,
    check_python_number,
    check_real,
    check_samples,
    check_targets,
)
from .fitted import INPUT_ATTRIBUTES, FittedAttribute
from .kernels import Kernel, KernelRows, call_kernel, resolve_gamma
from .ovo import dual_layout, one_vs_one_coef, ovr_decision_function
from .pair_kernels import PairKernels
from .platt import LibsvmRandom, pairwise_coupling, pairwise_sigmoids
from .smo import reference_smo, solve_smo
from .smo_policy import DEFAULT, LIBSVM, fit_policy, positive_semidefinite
from .sparse_input import as_csr

__all__ = ["SVC", "ovr_decision_function"]

logger = logging.getLogger(__name__)


#: The largest error of the RBF exponent ``gamma * d`` that the expansion of the squared distance
#: may leave at prediction, 2**-20 (about 1e-6 relative in the kernel value); above it the
#: distances are recomputed from direct differences.
EXPONENT_RTOL = 2.0**-20


def _expansion_unreliable(X: np.ndarray, S: np.ndarray, gamma: float) -> bool:
    """Could the expanded squared distance, times ``gamma``, be off by more than 2**-20?

    The expansion ``|x|^2 + |s|^2 - 2 x.s`` is off by up to ``(p + 5) u (|x| + |s|)^2``
    (:mod:`ebantenna.ml.kernels`), here bounded with the norms about the origin (an upper bound
    of the centred ones' error). At ``gamma = 1e300`` that error of about 1e-15 makes
    ``exp(-gamma d)`` of a point and itself 0 instead of 1, and a training point is
    misclassified; libsvm predicts with direct differences (``Kernel::k_function``), so
    recomputing them keeps the drop-in's answers.
    """
    if X.size == 0 or S.size == 0:
        return False
    u = np.finfo(np.float64).eps / 2
    reach = float(np.sqrt(np.max(np.einsum("ij,ij->i", X, X)))
                  + np.sqrt(np.max(np.einsum("ij,ij->i", S, S))))
    return gamma * (X.shape[1] + 5) * u * reach**2 > EXPONENT_RTOL


def _rbf_direct(X: np.ndarray, S: np.ndarray, gamma: float) -> np.ndarray:
    """``exp(-gamma |x - s|^2)`` from direct differences, in blocks of about 8 MB."""
    out = np.empty((X.shape[0], S.shape[0]))
    rows = max(1, 2**20 // max(1, S.shape[0] * X.shape[1]))
    for i in range(0, X.shape[0], rows):
        diff = X[i : i + rows, None, :] - S[None, :, :]
        out[i : i + rows] = np.exp(-gamma * np.einsum("ijk,ijk->ij", diff, diff))
    return out


def _all_finite(a: np.ndarray) -> bool:
    """Whether every entry of the float array ``a`` is finite. A sum is finite only if every
    term is (NaN and inf propagate, inf - inf is NaN): one pass over ``a`` without the boolean
    copy of ``isfinite``, which is made only when the sum is not finite (finite entries whose
    sum overflows)."""
    with np.errstate(over="ignore", invalid="ignore"):
        if np.isfinite(np.add.reduce(a, axis=None)):
            return True
    return bool(np.isfinite(a).all())


def plain_training_data(X, y):
    """``(X, y)`` when both are plain and valid, checked without scikit-learn; else None.

    Plain: ``X`` a 2-D NumPy array of floats or ints with at least one row and one column,
    finite; ``y`` a 1-D NumPy array of ints, floats (finite) or strings, one label per row. These
    are what scikit-learn's ``validate_data``, ``column_or_1d`` and
    ``check_classification_targets`` accept unchanged (a float label must be a whole number, or
    scikit-learn calls the target continuous); everything else returns None, for scikit-learn's
    own conversions and error messages. About half of an iris fit went into those checks.

    Examples
    --------
    >>> X, y = plain_training_data(np.eye(2, dtype=np.float32), np.array([0, 1]))
    >>> X.dtype, X.flags.c_contiguous, y
    (dtype('float64'), True, array([0, 1]))
    >>> plain_training_data(np.eye(2), np.array([0.5, 1.0])) is None  # continuous: sklearn's error
    True
    """
    if type(X) is not np.ndarray or type(y) is not np.ndarray:
        return None
    if X.ndim != 2 or X.dtype.kind not in "fiu" or 0 in X.shape or y.ndim != 1:
        return None
    if y.shape[0] != X.shape[0] or y.dtype.kind not in "fiuU":
        return None
    X = np.ascontiguousarray(X, dtype=np.float64)
    if not np.isfinite(X).all():
        return None
    if y.dtype.kind == "f" and not (np.isfinite(y).all() and np.array_equal(y, np.round(y))):
        return None
    return X, y


class SVC(ClassifierMixin, BaseEstimator):
    """C-support vector classifier with a hand-written SMO solver.

    Parameters
    ----------
    C : float, default=1.0
        Penalty of the slack variables (upper bound of the dual variables), > 0.
    kernel : {'rbf', 'linear', 'poly', 'sigmoid', 'precomputed'} or callable, default='rbf'
        Kernel function (see :mod:`ebantenna.ml.kernels`). With 'precomputed', ``X`` is the
        kernel matrix: (n_samples, n_samples) for :meth:`fit`, (n_test, n_samples) later. A
        callable ``kernel(X, Y)`` returns the matrix of ``X`` against ``Y`` (it is evaluated once
        on the training set; the training ``X`` is kept to evaluate it for new points).
    degree : int, default=3
        Degree of the 'poly' kernel.
    gamma : {'scale', 'auto'} or float, default='scale'
        Kernel coefficient, as in scikit-learn: 'scale' is ``1 / (n_features * X.var())``.
    coef0 : float, default=0.0
        Constant term of the 'poly' and 'sigmoid' kernels.
    shrinking : bool, default=True
        libsvm's shrinking heuristic (see :class:`~ebantenna.ml.smo_policy.SMOPolicy`); the
        solution is the same within ``tol`` either way. Shrinking leaves out the variables that
        sit at a bound, so each update passes over the few that can still move; it is used
        whether the kernel of a pair of classes is stored whole or cached by rows (the result
        still depends on ``cache_size`` through the kernel's storage: see there).
        ``shrinking=False`` passes over every variable at
        every update. It concerns the engines only: ``solver="reference"`` passes over every
        variable whatever it says.
    probability : bool, default=False
        Also fit Platt's sigmoids on five-fold cross-validated decision values (five more fits
        per pair of classes), for :meth:`predict_proba`. As in scikit-learn, :meth:`predict`
        still votes and may disagree with the most probable class.
    tol : float, default=1e-3
        Stopping tolerance on the maximal KKT violation.
    cache_size : float, default=200
        Memory for kernel entries, in MB. In the default mode the kernel of each pair of classes
        is built in float64 in one buffer reused from pair to pair, when the largest pair fits
        (:mod:`ebantenna.ml.pair_kernels`); otherwise, and with ``libsvm_compat``, the whole
        kernel matrix is built with one matrix product when it fits (in float64 if that fits
        too, unless ``libsvm_compat``), else rows are computed on demand and the least recently
        used are dropped. With shrinking the solver also keeps the float64 rows it has used
        since the last reordering, up to 64 MB (kernel rows and their curvatures together).
        A kernel stored in float32 (libsvm's storage) takes libsvm's rounding, and can take
        another path than float64 storage: the machine then stops elsewhere within ``tol``
        (:mod:`ebantenna.ml.smo`), so a fit can change with ``cache_size``.
        Engines only: ``solver="reference"`` holds the kernel matrix of each pair of classes as
        one float64 array, whatever ``cache_size``.
    class_weight : dict or 'balanced', default=None
        Multiply ``C`` by this weight for the samples of each class.
    verbose : bool, default=False
        Log each binary problem at INFO level.
    max_iter : int, default=-1
        Largest number of SMO updates per binary problem; -1 means no limit, as in
        scikit-learn's bundled libsvm (upstream libsvm stops at ``max(1e7, 100 n)``). Stopping
        at the limit raises a ``ConvergenceWarning``.
    decision_function_shape : {'ovr', 'ovo'}, default='ovr'
        Shape of :meth:`decision_function` with more than two classes: the raw one-vs-one values,
        or one-vs-rest scores aggregated from their votes.
    break_ties : bool, default=False
        With 'ovr' and more than two classes, predict the argmax of the decision function instead
        of the majority vote.
    random_state : int, RandomState instance or None, default=None
        Seeds the folds of ``probability=True`` as scikit-learn does: the seed is
        ``check_random_state(random_state).randint(2**31 - 1)``, and the folds are drawn by
        libsvm's own generator (:class:`~ebantenna.ml.platt.LibsvmRandom`), so that they are
        scikit-learn's; the solver itself is deterministic.
    selection : {'second-order', 'first-order'}, default='second-order'
        Working-set selection: libsvm's second-order rule or the maximal violating pair.
    libsvm_compat : bool, default=False
        Follow libsvm's arithmetic (the :data:`~ebantenna.ml.smo_policy.LIBSVM` policy: float32
        kernel storage, ties broken by the last index, its curvature floor, sequential bias sum) so
        that scikit-learn's ``SVC`` with the same ``shrinking`` is usually reproduced to about
        1e-12 with the same iteration counts (a last bit of a kernel entry formed another way can
        change the path, most often with the linear kernel). See :mod:`ebantenna.ml.smo` for
        what each convention changes. On purpose this includes libsvm's cancelling RBF
        arithmetic in training (the expansion of :math:`\\lVert x - y\\rVert^2` about the
        origin, see :mod:`ebantenna.ml.kernels`): its path, like libsvm's, changes when every
        feature is shifted by the same amount. Predictions use centred points in both modes, as
        close as a GEMM gets to libsvm's direct differences when it predicts.
        A kernel that is not positive semi-definite is always fitted this way by the engines,
        whatever ``libsvm_compat`` says (``solver="reference"`` follows none of these
        conventions): 'sigmoid', and a precomputed or callable kernel whose training
        Gram matrix :func:`~ebantenna.ml.smo_policy.positive_semidefinite` refuses. Its dual is
        not convex, and the default conventions would stop at another of its stationary points
        than scikit-learn (see :mod:`ebantenna.ml.smo_policy`).
    solver : {'auto', 'reference'}, default='auto'
        Which SMO solves the dual problems. 'auto': the engines, chosen by the other parameters
        (libsvm's solver with shrinking and a row cache, or a run over the whole kernel of a
        pair of classes), fast and, with ``libsvm_compat``, libsvm's to the last digits.
        'reference': the textbook loop of :mod:`ebantenna.ml.smo`
        (:func:`~ebantenna.ml.smo.reference_smo`), slower, to read and to step through; it
        finds the same support vectors and decision values within what ``tol`` allows. It runs
        with the other defaults as they are: it never shrinks (``shrinking`` is the engines'
        heuristic) and its kernel is float64 whatever ``cache_size``. It does not follow
        libsvm's conventions: ``libsvm_compat=True`` with it raises a ``ValueError``. With a
        kernel that is not positive semi-definite it may stop at another stationary point of
        the dual than the engines.

    Attributes
    ----------
    classes_ : ndarray of shape (n_classes,)
    support_ : ndarray of shape (n_SV,)
        Indices of the support vectors, grouped by class.
    support_vectors_ : ndarray or CSR matrix of shape (n_SV, n_features)
        A ``scipy.sparse.csr_matrix`` after a fit on sparse ``X``; empty, of shape (0, 0), for a
        precomputed or callable kernel (both as in scikit-learn).
    n_support_ : ndarray of shape (n_classes,), int32
    dual_coef_ : ndarray or CSR matrix of shape (n_classes - 1, n_SV)
        :math:`y_t\\alpha_t` in libsvm's one-vs-one layout (sign flipped for two classes, as
        scikit-learn does); a ``csr_matrix`` after a sparse fit, as there.
    intercept_ : ndarray of shape (n_classes * (n_classes - 1) / 2,)
    n_iter_ : ndarray of shape (n_classes * (n_classes - 1) / 2,)
        SMO updates per binary problem.
    probA_, probB_ : ndarray of shape (n_classes * (n_classes - 1) / 2,)
        Platt's :math:`A` and :math:`B` of each pair (empty unless ``probability``).
    fit_status_ : int
        0 if every problem converged, 1 otherwise.
    class_weight_ : ndarray of shape (n_classes,)
    shape_fit_ : tuple

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> X = np.vstack([rng.normal(-2, 1, (20, 2)), rng.normal(2, 1, (20, 2))])
    >>> y = np.repeat([0, 1], 20)
    >>> clf = SVC(kernel="rbf", C=1.0).fit(X, y)
    >>> clf.score(X, y)
    1.0
    >>> clf.predict([[-2.0, -2.0], [2.0, 2.0]])
    array([0, 1])

    The textbook SMO finds the same classifier:

    >>> ref = SVC(kernel="rbf", C=1.0, solver="reference").fit(X, y)
    >>> bool(np.array_equal(ref.support_, clf.support_))
    True
    """

    # scikit-learn's constraints and wording for the parameters shared with sklearn.svm.SVC;
    # C must be finite and max_iter=0 (no update at all) is refused
    _parameter_constraints: dict = {
        "C": [Interval(Real, 0.0, None, closed="neither")],
        "kernel": [StrOptions({"linear", "rbf", "poly", "sigmoid", "precomputed"}), callable],
        "degree": [Interval(Integral, 0, None, closed="left")],
        "gamma": [StrOptions({"scale", "auto"}), Interval(Real, 0.0, None, closed="left")],
        "coef0": [Interval(Real, None, None, closed="neither")],
        "shrinking": ["boolean"],
        "probability": ["boolean"],
        "tol": [Interval(Real, 0.0, None, closed="neither")],
        "cache_size": [Interval(Real, 0, None, closed="neither")],
        "class_weight": [StrOptions({"balanced"}), dict, None],
        "verbose": ["verbose"],
        "max_iter": [Interval(Integral, 1, None, closed="left"), Options(Integral, {-1})],
        "decision_function_shape": [StrOptions({"ovr", "ovo"})],
        "break_ties": ["boolean"],
        "random_state": ["random_state"],
        "selection": [StrOptions({"second-order", "first-order"})],
        "libsvm_compat": ["boolean"],
        "solver": [StrOptions({"auto", "reference"})],
    }

    #: Every attribute that :meth:`fit` sets (see :mod:`ebantenna.ml.fitted`).
    _fitted_schema = (
        FittedAttribute("classes_", "array", ndim=1),
        FittedAttribute("class_weight_", "array", dtype="float64", ndim=1),
        FittedAttribute("support_", "array", dtype="int32", ndim=1),
        FittedAttribute("support_vectors_", "array", dtype="float64", ndim=2, sparse=True),
        FittedAttribute("n_support_", "array", dtype="int32", ndim=1),
        FittedAttribute("dual_coef_", "array", dtype="float64", ndim=2, sparse=True),
        FittedAttribute("intercept_", "array", dtype="float64", ndim=1),
        FittedAttribute("_dual_coef_", "array", dtype="float64", ndim=2),
        FittedAttribute("_intercept_", "array", dtype="float64", ndim=1),
        FittedAttribute("n_iter_", "array", dtype="int32", ndim=1),
        FittedAttribute("_gamma", "value"),
        FittedAttribute("fit_status_", "value"),
        FittedAttribute("shape_fit_", "value", since=2),
        FittedAttribute("probA_", "array", dtype="float64", ndim=1, optional=True),
        FittedAttribute("probB_", "array", dtype="float64", ndim=1, optional=True),
        *INPUT_ATTRIBUTES,
    )

    def __init__(
        self,
        *,
        C=1.0,
        kernel="rbf",
        degree=3,
        gamma="scale",
        coef0=0.0,
        shrinking=True,
        probability=False,
        tol=1e-3,
        cache_size=200,
        class_weight=None,
        verbose=False,
        max_iter=-1,
        decision_function_shape="ovr",
        break_ties=False,
        random_state=None,
        selection="second-order",
        libsvm_compat=False,
        solver="auto",
    ):
        self.C = C
        self.kernel = kernel
        self.degree = degree
        self.gamma = gamma
        self.coef0 = coef0
        self.shrinking = shrinking
        self.probability = probability
        self.tol = tol
        self.cache_size = cache_size
        self.class_weight = class_weight
        self.verbose = verbose
        self.max_iter = max_iter
        self.decision_function_shape = decision_function_shape
        self.break_ties = break_ties
        self.random_state = random_state
        self.selection = selection
        self.libsvm_compat = libsvm_compat
        self.solver = solver

    # --------------------------------------------------------------------- fit
    @_fit_context(prefer_skip_nested_validation=True)
    def fit(self, X, y, sample_weight=None, kernel_matrix=None):
        """Train one binary SVM per pair of classes.

        Parameters
        ----------
        X : array-like or sparse matrix of shape (n_samples, n_features)
            Training features. Sparse matrices are used as CSR (other formats are converted, as
            scikit-learn does); a sparse kernel matrix ('precomputed') is refused, as there.
        y : array-like of shape (n_samples,)
            Class labels (dense).
        sample_weight : array-like of shape (n_samples,), optional
            Per-sample multiplier of ``C``; samples with weight <= 0 are left out.
        kernel_matrix : ndarray of shape (n_samples, n_samples), optional
            The kernel matrix :math:`k(x_i, x_j)` of ``X`` with itself, already computed, for a
            named kernel: machines trained on the same rows with the same kernel share it (the
            one-vs-rest machines of the paper's classifiers) instead of each computing it. It
            is used as it is (rows gathered from it, not copied, when it is float64 and the
            kernel is stored in float64), after a spot check: its diagonal and eight of its
            rows must be those of the kernel within :math:`2^{-20}` relative (two evaluations
            differ by rounding only, far below that; another ``X``, ``gamma`` or kernel differs
            by much more). The check cannot see a wrong entry elsewhere. Prediction computes
            its own kernel, as without it.

        Returns
        -------
        self
        """
        self._check_combination()
        X, y_idx, sw = self._training_data(X, y, sample_weight)
        classes = self.classes_
        self._gamma = resolve_gamma(self.gamma, X)
        named = not (self.kernel == "precomputed" or callable(self.kernel))
        kern = self._kernel() if named else None
        # precomputed or callable: the whole matrix; a named kernel: the shared one, if given
        given = (self._shared_kernel_matrix(kernel_matrix, X, kern) if named
                 else self._given_kernel_matrix(X, kernel_matrix))
        c_vec = float(self.C) * self.class_weight_[y_idx] * sw
        keep = c_vec > 0
        cache_bytes = int(float(self.cache_size) * 2**20)
        # a kernel that is not PSD takes libsvm's conventions whole: see smo_policy's module text
        compat = self.libsvm_compat or not positive_semidefinite(self.kernel, given,
                                                                 coef0=self.coef0)
        base = LIBSVM if compat else DEFAULT
        dtype = base.kernel_dtype(int(keep.sum()), cache_bytes)
        if self.solver == "reference":  # each pair's whole kernel in float64, whatever the cache
            dtype = np.float64
            cache_bytes = max(cache_bytes, 8 * int(keep.sum()) ** 2)
        members = [np.flatnonzero((y_idx == c) & keep) for c in range(classes.size)]
        if any(m.size == 0 for m in members):
            raise ValueError("every class needs at least one sample with a positive weight")
        kernels = PairKernels(X, members, kern, dtype, cache_bytes, given=given,
                              libsvm_compat=compat)
        diag = kern.diagonal(X) if named else np.diag(given).astype(np.float64)
        policy = fit_policy(compat, self.selection, bool(self.shrinking),
                            whole_kernel=kernels.stored)
        # -1: no cap, as in scikit-learn's libsvm ("set max_iter to -1 to disable the mechanism"
        # in its Solver::Solve; upstream libsvm stops at max(1e7, 100 n) updates instead)
        max_iter = math.inf if self.max_iter == -1 else int(self.max_iter)
        coefs, rhos, n_iter, status = self._solve_pairs(kernels, members, c_vec, diag, policy,
                                                         max_iter)
        self._store(X, classes, members, coefs, rhos, n_iter)
        self.probA_ = self.probB_ = np.empty(0)
        if self.probability:
            self._fit_probability(X, members, given, kern, dtype, c_vec, diag, policy, max_iter,
                                  compat)
        self.fit_status_ = status
        self.shape_fit_ = X.shape
        self._check_solution(status)
        return self

    def _validate_params(self):
        """Numbers scikit-learn's constraints cannot take (10**400, a Fraction) refused by name,
        then those constraints, with scikit-learn's errors."""
        for name in ("C", "gamma", "coef0", "tol", "cache_size", "degree"):
            check_python_number(name, getattr(self, name))
        super()._validate_params()

    def _check_combination(self):
        """Refuse the parameters that do not go together (their types are checked already)."""
        self._check_numbers()
        if self.break_ties and self.decision_function_shape == "ovo":
            raise ValueError("break_ties must be False when decision_function_shape is 'ovo'")
        if self.solver == "reference" and self.libsvm_compat:
            raise ValueError("libsvm_compat=True needs solver='auto': the reference SMO does not "
                             "follow libsvm's conventions; set libsvm_compat=False")

    def _training_data(self, X, y, sample_weight):
        """Validated ``X``, the class index of each sample and the sample weights; sets
        ``classes_``, ``class_weight_`` and ``n_features_in_``.

        A plain 2-D real array with labels of one 1-D array takes the package's own checks
        (:func:`plain_training_data`); anything else (sparse matrices, data frames, lists, bad
        input) is checked in the package's words (``check_samples``, ``check_targets``: shape,
        values, one label per row), then converted by scikit-learn's validation.
        """
        plain = plain_training_data(X, y)
        if plain is None or self.kernel == "precomputed":
            check_samples(X)  # in the package's words, before scikit-learn's conversion
            check_targets(X, y)
            X, y = validate_data(self, X, y, dtype=np.float64, order="C", accept_sparse="csr")
            X = self._sparse_input(X)
            y = column_or_1d(y, warn=True)
            check_classification_targets(y)
        else:
            X, y = plain
            self.n_features_in_ = X.shape[1]
            if hasattr(self, "feature_names_in_"):
                del self.feature_names_in_
        if self.kernel == "precomputed" and X.shape[0] != X.shape[1]:
            raise ValueError("Precomputed matrix must be a square matrix. Input is a "
                             f"{X.shape[0]}x{X.shape[1]} matrix.")
        classes, y_idx = np.unique(y, return_inverse=True)
        self.classes_ = classes
        if classes.size < 2:
            raise ValueError(
                f"The number of classes has to be greater than one; got {classes.size} class"
            )
        self.class_weight_ = self._class_weights(classes, y)
        if sample_weight is None:
            return X, y_idx, np.ones(X.shape[0])
        return X, y_idx, _check_sample_weight(sample_weight, X, dtype=np.float64)

    def _class_weights(self, classes, y) -> np.ndarray:
        """``class_weight_``: scikit-learn's, each given weight a finite number >= 0."""
        if self.class_weight is None:  # scikit-learn's answer, without its validation's cost
            return np.ones(classes.shape[0])
        if isinstance(self.class_weight, dict):
            for label, weight in self.class_weight.items():
                check_nonnegative(f"class_weight[{label!r}]", weight)
        return compute_class_weight(self.class_weight, classes=classes, y=y)

    def _check_numbers(self):
        """The numeric parameters as finite numbers in range, whatever their Python size.

        scikit-learn's constraints take ``C=10**400`` as a real number; ``float()`` of it would
        overflow. ``degree`` is a 32-bit int in libsvm.
        """
        check_positive("C", self.C)
        if not isinstance(self.gamma, str):
            check_nonnegative("gamma", self.gamma)
        check_real("coef0", self.coef0)
        check_positive("tol", self.tol)
        check_positive("cache_size", self.cache_size)
        check_int("degree", self.degree, minimum=0, maximum=2**31 - 1)

    def _solve_pairs(self, kernels, members, c_vec, diag, policy, max_iter):
        """One binary dual per pair of classes: ``(coefs, rhos, n_iter, status)``, the pairs in
        libsvm's order for ``rhos`` and ``n_iter``."""
        classes = self.classes_
        coefs, solved, status = {}, {}, 0
        for a, b, rows in kernels.pairs():  # in the order that reuses kernel blocks
            idx = np.concatenate([members[a], members[b]])
            ys = np.concatenate([np.ones(members[a].size), -np.ones(members[b].size)])
            res = self._solve_dual(rows, ys, c_vec[idx], diag[idx], policy, max_iter)
            if self.verbose:
                logger.info("classes (%r, %r): %d updates, %d support vectors", classes[a],
                            classes[b], res.n_iter, int(np.count_nonzero(res.alpha)))
            if not res.converged:
                status = 1
            coefs[a, b] = (idx, res.alpha * ys)
            solved[a, b] = res
        order = sorted(solved)  # libsvm's order of the pairs: (0, 1), (0, 2), ..., (1, 2), ...
        rhos = np.array([solved[pair].rho for pair in order])
        return coefs, rhos, [solved[pair].n_iter for pair in order], status

    def _solve_dual(self, rows, ys, C, diagonal, policy, max_iter):
        """One binary dual, on the engines or, with ``solver='reference'``, by the reference
        loop on the float64 kernel matrix of its points."""
        if self.solver == "reference":
            points = np.arange(ys.size)
            return reference_smo(rows.block64(points, points), ys, C, tol=float(self.tol),
                                 max_iter=max_iter, selection=self.selection)
        return solve_smo(rows, ys, C, diagonal=diagonal, tol=float(self.tol), max_iter=max_iter,
                         policy=policy)

    def _check_solution(self, status):
        """Warn if a problem stopped at ``max_iter``; refuse coefficients that are not finite."""
        if status:
            warnings.warn(
                f"Solver terminated early (max_iter={self.max_iter}).  Consider pre-processing "
                "your data with StandardScaler or MinMaxScaler.",
                ConvergenceWarning,
                stacklevel=3,
            )
        if not (np.isfinite(self._dual_coef_).all() and np.isfinite(self._intercept_).all()):
            raise ValueError("The dual coefficients or intercepts are not finite. The input data "
                             "may contain large values and need to be preprocessed.")

    def _store(self, X, classes, members, coefs, rhos, n_iter):
        """Arrange the pairwise solutions in libsvm's (and scikit-learn's) layout."""
        k = classes.size
        support, n_support, dual = dual_layout(X.shape[0], members, coefs)
        self.support_ = support.astype(np.int32)
        sparse = sp.issparse(X) and not callable(self.kernel)
        if self.kernel == "precomputed" or callable(self.kernel):
            self.support_vectors_ = np.empty((0, 0))
            if callable(self.kernel):
                self._X_fit = X
        else:  # CSR matrices for a sparse fit, as scikit-learn's
            self.support_vectors_ = sp.csr_matrix(X[support]) if sparse else X[support]
        self.n_support_ = n_support
        self._dual_coef_ = dual
        self._intercept_ = -rhos
        self.n_iter_ = np.array(n_iter, dtype=np.int32)
        self.dual_coef_ = -dual if k == 2 else dual
        self.intercept_ = rhos.copy() if k == 2 else -rhos
        if sparse:
            self.dual_coef_ = sp.csr_matrix(self.dual_coef_)

    def _fit_probability(self, X, members, given, kern, dtype, c_vec, diag, policy, max_iter,
                         compat):
        """Platt's sigmoids of every pair, on five-fold decision values (libsvm's procedure)."""
        center = not compat

        def kernel_block(rows, cols):
            if given is not None:
                return given[np.ix_(rows, cols)]
            same = rows is cols or np.array_equal(rows, cols)
            return kern.gram(X[rows], None if same else X[cols], center=center or not same)

        def solve(points, ys, K):
            rows = KernelRows(None, kern, dtype, 0, full=K)
            res = self._solve_dual(rows, ys, c_vec[points], diag[points], policy, max_iter)
            return res.alpha * ys, res.rho

        self.probA_, self.probB_ = pairwise_sigmoids(members, kernel_block, solve,
                                                     LibsvmRandom(self._libsvm_seed()))

    def _libsvm_seed(self) -> int:
        """libsvm's ``random_seed`` for ``random_state``, drawn as ``BaseLibSVM.fit`` draws it:
        ``check_random_state(random_state).randint(2**31 - 1)``."""
        return int(check_random_state(self.random_state).randint(np.iinfo(np.int32).max))

    def _check_proba(self):
        if not self.probability:
            raise AttributeError("predict_proba is not available when probability=False")
        return True

    @available_if(_check_proba)
    def predict_proba(self, X):
        """Class probabilities, shape (n_samples, n_classes), from Platt's sigmoids coupled
        pairwise (see :mod:`ebantenna.ml.platt`)."""
        check_is_fitted(self)
        if getattr(self, "probA_", np.empty(0)).size == 0:
            raise NotFittedError("predict_proba is not available when fitted with "
                                 "probability=False")
        return pairwise_coupling(self._ovo_decision(X), self.probA_, self.probB_,
                                 self.classes_.size)

    @available_if(_check_proba)
    def predict_log_proba(self, X):
        """Logarithm of :meth:`predict_proba`."""
        return np.log(self.predict_proba(X))

    def _given_kernel_matrix(self, X, kernel_matrix=None):
        """The training kernel matrix for 'precomputed' (``X`` itself) or a callable, else None."""
        if kernel_matrix is not None:
            raise ValueError("kernel_matrix is for a named kernel ('linear', 'poly', 'rbf', "
                             "'sigmoid'); with 'precomputed' X is the kernel matrix, and a "
                             "callable's matrix is computed once already")
        if self.kernel == "precomputed":
            return X
        if callable(self.kernel):
            return call_kernel(self.kernel, X, X)
        return None

    def _shared_kernel_matrix(self, kernel_matrix, X, kern: Kernel):
        """``kernel_matrix`` checked as the kernel matrix of ``X`` with itself (see :meth:`fit`),
        or None."""
        if kernel_matrix is None:
            return None
        n = X.shape[0]
        if not isinstance(kernel_matrix, np.ndarray) or kernel_matrix.shape != (n, n):
            raise ValueError(f"kernel_matrix must be a NumPy array of shape ({n}, {n}), the "
                             f"kernel of X with itself; got {type(kernel_matrix).__name__} "
                             f"{getattr(kernel_matrix, 'shape', '')}")
        if kernel_matrix.dtype.kind != "f" or not _all_finite(kernel_matrix):
            raise ValueError("kernel_matrix must hold finite real numbers")
        rows = np.unique(np.linspace(0, n - 1, min(n, 8)).astype(np.intp))
        reference = kern.gram(X[rows], X)
        diagonal = kern.diagonal(X)
        # rounding differs between two evaluations far below 2**-20 relative (the kernels' error
        # bound); a matrix of other points, another width or another kernel differs by much more
        def close(a, b):
            return bool(np.all(np.abs(a - b) <= 2.0**-20 * (1 + np.abs(b))))

        if not (close(kernel_matrix[rows], reference)
                and close(np.diagonal(kernel_matrix), diagonal)):
            raise ValueError(f"kernel_matrix is not the {self.kernel!r} kernel of X with itself "
                             f"(gamma={self._gamma!r}): its diagonal or its rows {rows.tolist()} "
                             "differ from the kernel's")
        return kernel_matrix

    def _sparse_input(self, X):
        """A validated sparse ``X`` in canonical CSR form (sorted, summed indices)."""
        if not sp.issparse(X):
            return X
        if self.kernel == "precomputed":  # scikit-learn's words
            raise TypeError("Sparse precomputed kernels are not supported.")
        return as_csr(X)

    # ----------------------------------------------------------------- predict
    def _kernel(self) -> Kernel:
        return Kernel(self.kernel, gamma=self._gamma, degree=int(self.degree),
                      coef0=float(self.coef0))

    def _test_kernel(self, X) -> np.ndarray:
        """Kernel matrix of test points ``X`` (validated) against the support vectors."""
        if self.kernel == "precomputed":
            return X[:, self.support_]
        if callable(self.kernel):
            return call_kernel(self.kernel, X, self._X_fit[self.support_])
        if self.kernel == "rbf" and not sp.issparse(X) and not sp.issparse(self.support_vectors_):
            if _expansion_unreliable(X, self.support_vectors_, self._gamma):
                return _rbf_direct(X, self.support_vectors_, self._gamma)
        return self._kernel().gram(X, self.support_vectors_)

    @property
    def coef_(self) -> np.ndarray:
        """Weights :math:`w` of the separating hyperplanes, linear kernel only.

        Shape (1, n_features) for two classes, else one row per pair of classes in the order of
        ``intercept_``; computed from ``dual_coef_`` and ``support_vectors_`` as scikit-learn
        does, read-only (a CSR matrix after a sparse fit, as there).
        """
        if self.kernel != "linear":
            raise AttributeError("coef_ is only available when using a linear kernel")
        check_is_fitted(self)
        dual = self.dual_coef_
        sparse = sp.issparse(dual)
        coef = one_vs_one_coef(dual.toarray() if sparse else dual, self.n_support_,
                               self.support_vectors_)
        coef = sp.csr_matrix(coef) if sparse else coef
        (coef.data if sparse else coef).flags.writeable = False
        return coef

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.input_tags.pairwise = self.kernel == "precomputed"
        tags.input_tags.sparse = self.kernel != "precomputed"
        return tags

    def _ovo_decision(self, X) -> np.ndarray:
        """libsvm's pairwise decision values (positive: the pair's first class)."""
        check_is_fitted(self)
        check_samples(X, n_features=getattr(self, "n_features_in_", None),
                      owner=type(self).__name__)
        X = validate_data(self, X, dtype=np.float64, order="C", accept_sparse="csr", reset=False)
        X = self._sparse_input(X)
        kx = self._test_kernel(X)
        k = self.classes_.size
        bounds = np.concatenate([[0], np.cumsum(self.n_support_)])
        out = np.empty((X.shape[0], k * (k - 1) // 2))
        p = 0
        for a in range(k):
            for b in range(a + 1, k):
                sa = slice(bounds[a], bounds[a + 1])
                sb = slice(bounds[b], bounds[b + 1])
                out[:, p] = (kx[:, sa] @ self._dual_coef_[b - 1, sa]
                             + kx[:, sb] @ self._dual_coef_[a, sb] + self._intercept_[p])
                p += 1
        return out

    def decision_function(self, X):
        """Signed distances to the separating surfaces.

        Returns
        -------
        ndarray of shape (n_samples,) for two classes (positive: ``classes_[1]``), otherwise
        (n_samples, n_classes) for 'ovr' or (n_samples, n_classes * (n_classes - 1) / 2) for 'ovo'.
        """
        dec = self._ovo_decision(X)
        k = self.classes_.size
        if k == 2:
            return -dec.ravel()
        if self.decision_function_shape == "ovr":
            return ovr_decision_function(dec < 0, -dec, k)
        return dec

    def predict(self, X):
        """Class labels by one-vs-one majority vote (ties: the first class): the machine of the
        pair ``(a, b)`` votes for ``a`` where its decision value is positive, else for ``b``."""
        dec = self._ovo_decision(X)
        k = self.classes_.size
        if self.break_ties and self.decision_function_shape == "ovr" and k > 2:
            return self.classes_[np.argmax(ovr_decision_function(dec < 0, -dec, k), axis=1)]
        votes = np.zeros((dec.shape[0], k), dtype=np.int64)
        pairs = zip(*np.triu_indices(k, 1), strict=True)  # (0, 1), (0, 2), ..., (1, 2), ...
        for p, (a, b) in enumerate(pairs):
            wins = dec[:, p] > 0
            votes[wins, a] += 1
            votes[~wins, b] += 1
        return self.classes_[np.argmax(votes, axis=1)]
