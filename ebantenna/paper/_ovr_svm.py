"""The one-vs-rest RBF support vector machines of the paper's classifiers, sized and predicted
as one machine.

The paper classifies five materials "with the one vs all strategy": five binary RBF machines
(:class:`ebantenna.ml.SVC`), each trained on every training row, the class of the largest
decision value winning. Three things make that cheaper here, without changing what is computed
beyond rounding:

* **One training kernel for the five machines.** Each machine's dual needs the kernel of all
  ``n`` training rows, the same matrix for every machine. :class:`OneVsRestSVC` computes it once
  and gives it to each machine's fit (:meth:`ebantenna.ml.SVC.fit`'s ``kernel_matrix``), where
  each machine would compute it again, centred on the mean of its rows sorted by its own
  labels. The entries then differ from a machine's own by rounding only, and so do the duals:
  each SMO stops within its tolerance of the same optimum, the decision values a few ``tol``
  apart (on the paper's data set, at most 1.2e-3 over the five grouped folds and the random
  split, with the same accuracies). On 7,900 rows of 256 features it took each fit from about
  6.6 to 4.3 CPU seconds.

* **The whole training kernel in float64.** Each binary fit needs the kernel of all ``n``
  training rows. With the SVC's default ``cache_size`` of 200 MB a kernel of more than 5,120 rows
  does not fit in float64 (``8 n^2`` bytes): its rows are then computed on demand, stored in
  float32, and most of them many times over. :func:`whole_kernel_svc` gives the SVC a cache
  large enough to hold the whole float64 matrix, after checking ``8 n^2`` bytes against the
  package's memory budget (:func:`ebantenna._budget.check_allocation`). Over the budget it keeps
  the default cache (rows on demand, in float32) and says so in a warning: the fit then costs
  more time, and its last digits are those of float32 kernel entries.
* **One test kernel per prediction.** The five machines share their training rows, so their
  support vectors are rows of the same matrix. :class:`OneVsRestSVC` computes the kernel of the
  rows to predict against the union of the support vectors once, and each machine's decision
  value from its columns, where :class:`sklearn.multiclass.OneVsRestClassifier` would compute
  one kernel per machine.

The decision values differ from those of each machine's own
:meth:`~ebantenna.ml.SVC.decision_function` only by rounding: both expand the squared distance
about a centre (see :mod:`ebantenna.ml.kernels`), here the mean of the union of the support
vectors, there the mean of the machine's own, and sum in another order.
"""

from __future__ import annotations

import logging
import math

import numpy as np
import scipy.sparse as sp
from sklearn.base import clone
from sklearn.multiclass import OneVsRestClassifier
from sklearn.preprocessing import LabelBinarizer
from sklearn.utils.validation import check_is_fitted, validate_data

from .._budget import MemoryBudgetError, check_allocation
from ..ml import SVC
from ..ml.kernels import GEMM_ENTRIES, Kernel, resolve_gamma

__all__ = ["OneVsRestSVC", "whole_kernel_svc", "DEFAULT_CACHE_MB"]

logger = logging.getLogger(__name__)

#: The default ``cache_size`` of :class:`ebantenna.ml.SVC`, in MB.
DEFAULT_CACHE_MB = 200

#: The largest error of the RBF exponent that the expansion of the squared distance may leave;
#: above it the machines' own prediction is used, which recomputes direct differences (the
#: criterion of :class:`ebantenna.ml.SVC`'s prediction).
_EXPONENT_RTOL = 2.0**-20


def whole_kernel_svc(n_rows: int, **params) -> SVC:
    """An RBF :class:`ebantenna.ml.SVC` whose binary fits on ``n_rows`` rows hold their whole
    kernel matrix in float64.

    Parameters
    ----------
    n_rows : int
        Training rows of each binary problem (one-vs-rest: all of them).
    **params
        Other parameters of the SVC (``C``, ``gamma``, ``tol``); not ``kernel`` nor
        ``cache_size``.

    Returns
    -------
    SVC
        With ``cache_size`` the larger of the default (200 MB) and the ``8 n_rows^2`` bytes of
        the float64 matrix, rounded up to whole MB. If that matrix is over the memory budget
        (:func:`ebantenna._budget.check_allocation`), the default ``cache_size``, with a warning:
        rows are then computed on demand and stored in float32.

    Examples
    --------
    >>> whole_kernel_svc(1000, C=2.0).cache_size  # 8 MB fit the default cache
    200
    >>> whole_kernel_svc(8000).cache_size  # 8 * 8000**2 bytes = 488.3 MB
    489
    """
    if isinstance(n_rows, bool) or not isinstance(n_rows, int | np.integer) or n_rows < 1:
        raise ValueError(f"n_rows must be a positive int, got {n_rows!r}")
    for name in ("kernel", "cache_size"):
        if name in params:
            raise TypeError(f"whole_kernel_svc sets {name} itself; got {name}={params[name]!r}")
    need = 8 * int(n_rows) ** 2
    try:
        check_allocation(need, parameter="X",
                         what=f"the float64 kernel matrix of {n_rows} training rows")
    except MemoryBudgetError as err:
        logger.warning("%s: the SVM computes its kernel rows on demand instead, stored in "
                       "float32 (cache_size=%d MB)", err, DEFAULT_CACHE_MB)
        return SVC(kernel="rbf", **params)
    return SVC(kernel="rbf", cache_size=max(DEFAULT_CACHE_MB, math.ceil(need / 2**20)),
               **params)


class OneVsRestSVC(OneVsRestClassifier):
    """:class:`sklearn.multiclass.OneVsRestClassifier` whose RBF machines share one test kernel.

    Trained as the class it extends: one clone of ``estimator`` per class, on all the rows, that
    class against the rest. When there are more than two classes, the rows are a dense float
    array and ``estimator`` is an RBF :class:`ebantenna.ml.SVC` whose cache holds the whole
    kernel in float64 (see :func:`whole_kernel_svc`), with ``n_jobs`` None or 1, the training
    kernel is computed once for all the machines (see the module text). When there are more
    than two classes and the machines are
    RBF :class:`ebantenna.ml.SVC` fitted on dense rows, :meth:`decision_function` and
    :meth:`predict` compute the kernel of the rows to predict against the union of the machines'
    support vectors once, in blocks of at most ``GEMM_ENTRIES`` entries, and every machine's
    decision value from it; otherwise (two classes, another estimator, sparse rows, or a
    ``gamma`` so large that the expanded distances are not accurate enough) they are those of
    the class it extends.

    Parameters
    ----------
    estimator : estimator
        The binary classifier (the paper's: an RBF :class:`ebantenna.ml.SVC`, see
        :func:`whole_kernel_svc`).
    n_jobs, verbose
        As in :class:`~sklearn.multiclass.OneVsRestClassifier`.

    Attributes
    ----------
    estimators_, classes_, label_binarizer_
        As in :class:`~sklearn.multiclass.OneVsRestClassifier`.
    support_rows_ : ndarray of int or None
        The training rows that are a support vector of at least one machine, sorted (None when
        the machines' own prediction is used).

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> y = np.repeat(["a", "b", "c"], 20)
    >>> X = rng.normal(size=(60, 2)) + 3 * (y[:, None] == ["b", "c"])
    >>> model = OneVsRestSVC(SVC(kernel="rbf", gamma=0.5)).fit(X, y)
    >>> own = np.column_stack([e.decision_function(X) for e in model.estimators_])
    >>> bool(np.allclose(model.decision_function(X), own, rtol=0, atol=1e-12))
    True
    >>> model.predict([[0.0, 0.0], [3.0, 0.0], [0.0, 3.0]]).tolist()
    ['a', 'b', 'c']
    """

    def fit(self, X, y, **fit_params):
        """Fit one machine per class, then gather their support vectors.

        Parameters
        ----------
        X : array-like or sparse matrix of shape (n_samples, n_features)
        y : array-like of shape (n_samples,)
        **fit_params
            Passed on as :meth:`sklearn.multiclass.OneVsRestClassifier.fit` passes them.

        Returns
        -------
        self
        """
        kernel = None if fit_params else self._training_kernel(X, y)
        if kernel is None:
            super().fit(X, y, **fit_params)
        else:
            self._fit_on_one_kernel(X, y, kernel)
        self.support_rows_ = None
        self._shared = None
        shared = (
            self.label_binarizer_.y_type_ == "multiclass"
            and not sp.issparse(X)
            and all(isinstance(e, SVC) and isinstance(e.kernel, str) and e.kernel == "rbf"
                    and not sp.issparse(e.support_vectors_) for e in self.estimators_)
        )
        if shared:
            self._gather(X)
        return self

    def _training_kernel(self, X, y):
        """The RBF kernel matrix of the training rows, computed once for every machine, or None
        where the machines compute their own (see the class text)."""
        e = self.estimator
        if not (isinstance(e, SVC) and isinstance(e.kernel, str) and e.kernel == "rbf"
                and self.n_jobs in (None, 1) and isinstance(X, np.ndarray) and X.ndim == 2
                and X.dtype.kind == "f" and X.shape[0] >= 2):
            return None
        labels = np.asarray(y)
        if labels.ndim != 1 or labels.shape[0] != X.shape[0] or np.unique(labels).size < 3:
            return None
        n = X.shape[0]
        if 8 * n * n > float(e.cache_size) * 2**20:  # each machine stores it whole in float64
            return None
        # SVC.fit's own conversion, so that 'scale' resolves the same width from the same sums
        X = np.ascontiguousarray(X, dtype=np.float64)
        if not np.isfinite(X).all():
            return None  # each machine's fit refuses it in its own words
        return Kernel("rbf", gamma=resolve_gamma(e.gamma, X)).gram(X)

    def _fit_on_one_kernel(self, X, y, kernel: np.ndarray) -> None:
        """What :meth:`sklearn.multiclass.OneVsRestClassifier.fit` does, each machine given the
        shared training kernel."""
        self._validate_params()
        self.label_binarizer_ = LabelBinarizer(sparse_output=True)
        columns = self.label_binarizer_.fit_transform(y).tocsc()
        self.classes_ = self.label_binarizer_.classes_
        self.estimators_ = [clone(self.estimator).fit(X, c.toarray().ravel(), kernel_matrix=kernel)
                            for c in columns.T]
        self.n_features_in_ = self.estimators_[0].n_features_in_

    def _gather(self, X) -> None:
        """The union of the support vectors and, per machine, its dual coefficients at their
        places in it."""
        # the width each machine resolved from the same rows (SVC.fit's own conversion: float64,
        # C order, so that 'scale' sums the variance in the same order)
        X = np.ascontiguousarray(np.asarray(X, dtype=np.float64))
        gammas = {resolve_gamma(e.gamma, X) for e in self.estimators_}
        rows = np.unique(np.concatenate([e.support_ for e in self.estimators_]))
        points = np.empty((rows.size, X.shape[1]))
        weights = np.zeros((rows.size, len(self.estimators_)))
        for k, e in enumerate(self.estimators_):
            at = np.searchsorted(rows, e.support_)
            points[at] = e.support_vectors_  # the rows themselves, as each machine keeps them
            weights[at, k] = e.dual_coef_[0]
        self.support_rows_ = rows
        self._shared = {
            "gamma": gammas.pop() if len(gammas) == 1 else None,
            "points": points,
            "weights": weights,
            "intercepts": np.array([e.intercept_[0] for e in self.estimators_]),
        }
        if self._shared["gamma"] is None:  # machines of different widths: each its own kernel
            self.support_rows_ = self._shared = None

    def _shared_input(self, X):
        """``X`` validated for the shared kernel, or None when the machines' own prediction is
        used (see the class text)."""
        check_is_fitted(self)
        shared = getattr(self, "_shared", None)
        if shared is None or sp.issparse(X):
            return None
        X = validate_data(self, X, reset=False, dtype=np.float64, order="C")
        S, gamma = shared["points"], shared["gamma"]
        if X.size and S.size:
            # the bound of ebantenna.ml.kernels, with the norms about the origin (an upper bound)
            u = np.finfo(np.float64).eps / 2
            reach = float(np.sqrt(np.max(np.einsum("ij,ij->i", X, X)))
                          + np.sqrt(np.max(np.einsum("ij,ij->i", S, S))))
            if gamma * (X.shape[1] + 5) * u * reach**2 > _EXPONENT_RTOL:
                return None
        return X

    def decision_function(self, X):
        """Decision value of every machine, shape (n_samples, n_classes) (``(n_samples,)`` for
        two classes), as :meth:`sklearn.multiclass.OneVsRestClassifier.decision_function`.

        Parameters
        ----------
        X : array-like or sparse matrix of shape (n_samples, n_features)
        """
        valid = self._shared_input(X)
        if valid is None:
            return super().decision_function(X)
        return self._shared_decision(valid)

    def _shared_decision(self, X: np.ndarray) -> np.ndarray:
        """Every machine's decision value from one kernel of ``X`` (validated) against the
        union of the support vectors."""
        shared = self._shared
        S = shared["points"]
        out = np.empty((X.shape[0], shared["weights"].shape[1]))
        kernel = Kernel("rbf", gamma=shared["gamma"])
        step = max(1, GEMM_ENTRIES // max(1, S.shape[0]))  # at most 32 MB of kernel at a time
        for start in range(0, X.shape[0], step):
            block = out[start : start + step]
            np.matmul(kernel.gram(X[start : start + step], S), shared["weights"], out=block)
            block += shared["intercepts"]
        return out

    def predict(self, X):
        """The class of the largest decision value (the first class on a tie), as
        :meth:`sklearn.multiclass.OneVsRestClassifier.predict`.

        Parameters
        ----------
        X : array-like or sparse matrix of shape (n_samples, n_features)
        """
        valid = self._shared_input(X)
        if valid is None:
            return super().predict(X)
        return self.classes_[np.argmax(self._shared_decision(valid), axis=1)]
