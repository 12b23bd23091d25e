"""Multilayer perceptrons in NumPy with backpropagation written out by hand.

:class:`MLPClassifier` (softmax or logistic outputs with cross-entropy) and :class:`MLPRegressor`
(identity outputs with squared error) take scikit-learn's parameter names and expose its fitted
attributes (``coefs_``, ``intercepts_``, ``loss_curve_``, ``n_iter_``, ...), so that a student can
swap the import. The solvers are

``'gd'``
    full-batch gradient descent, one step per epoch (the paper's "gradient descent");
``'sgd'``
    mini-batch stochastic gradient descent with (Nesterov) momentum;
``'adam'``
    Adam;
``'scg'``
    scaled conjugate gradient on the full batch (the paper's best distance regressor), in the
    form of Netlab's ``scg.m``, a variant of Møller's algorithm (see
    :mod:`ebantenna.ml.optimizers`). Two parameters beyond scikit-learn's set it: ``sigma0``
    (default 1e-4), the step of the finite-difference curvature estimate, and ``lambda0``
    (default 1), the initial Levenberg-Marquardt scale; MATLAB's ``trainscg`` uses 5e-5 and
    5e-7. A loss or gradient that is not finite stops it with a ``ValueError``, as for the
    other solvers;
``'lbfgs'``
    scikit-learn's: :func:`scipy.optimize.minimize` with L-BFGS-B on the full batch
    (``maxiter=max_iter``, ``maxfun=max_fun``, ``gtol=tol``); ``loss_curve_`` holds the loss
    after each of its iterations, which scikit-learn does not keep.

``learning_rate="invscaling"`` decays once per epoch, ``learning_rate_init / (t_ + 1) ** power_t``
with ``t_`` the samples seen, as scikit-learn's. ``partial_fit`` trains one epoch per call
('gd', 'sgd' and 'adam').

The loss is :math:`L = \\ell + \\frac{\\alpha}{2n}\\sum_l \\lVert W_l \\rVert^2` with :math:`\\ell`
the mean cross-entropy per sample, or, for regression,
:math:`\\ell = \\frac{1}{2 n m}\\sum_{i,k} (y_{ik} - \\hat y_{ik})^2` over ``n`` samples and ``m``
outputs: the same numbers as scikit-learn reports while no predicted probability saturates.
Where one does, scikit-learn clips the probabilities to :math:`[\\epsilon, 1 - \\epsilon]` (a
sample then costs at most :math:`-\\log\\epsilon \\approx 36`), and this package takes the exact
log-sum-exp: with saturated weights the two losses part, by orders of magnitude, and with them
``loss_curve_`` and the stop on ``tol``; the gradients agree.

Difference from scikit-learn for several regression outputs
-----------------------------------------------------------
scikit-learn reports the loss above but back-propagates :math:`(\\hat y - y) / n`, which is ``m``
times the gradient of that loss (only of the data term: its L2 term keeps its own scale). Here the
gradient is the true gradient of the reported loss, :math:`(\\hat y - y) / (n m)`. With one output,
or for classification, both agree, and one ``'gd'`` step equals one full-batch step of
scikit-learn's ``'sgd'`` solver without momentum.

Sparse input: ``fit``, ``partial_fit`` and the predictions take ``scipy.sparse`` matrices and
arrays; CSR and CSC are used as they are, other formats are converted to CSR (scikit-learn's
rule). Only the first layer's products see the sparse matrix; they sum over its stored entries,
in another order than a dense product, so a sparse fit follows the dense one to rounding.
Targets must be dense: a sparse ``y`` raises scikit-learn's ``TypeError`` (scikit-learn's
classifier, unlike this one, also takes a sparse label indicator matrix).

The forward pass, the losses and backpropagation are plain functions of
:mod:`ebantenna.ml.backprop`, written as the textbook writes them; training runs an engine that
does the same arithmetic in arrays reused from batch to batch, held equal to them bit for bit by
the tests. ``engine='reference'`` trains with those functions themselves (and Adam's NumPy
update, without the compiled loops of the ``fast`` extra): the same network to the last bit,
slower, for stepping through the code that actually runs.

The parameters are checked by scikit-learn's own constraint mechanism
(``_parameter_constraints``), so a bad value raises the error scikit-learn raises, in the same
words, except where the package checks more than scikit-learn does (``validation_fraction``
with ``early_stopping``, a negative ``random_state``): those errors are the package's own.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import issparse
from scipy.special import expit, log_expit, logsumexp
from sklearn.base import ClassifierMixin, RegressorMixin, _fit_context
from sklearn.metrics import accuracy_score, r2_score
from sklearn.preprocessing import LabelBinarizer
from sklearn.utils.metaestimators import available_if
from sklearn.utils.multiclass import check_classification_targets, type_of_target
from sklearn.utils.validation import check_array, check_is_fitted, column_or_1d, validate_data

from .._validate import check_samples, check_targets
from .backprop import forward
from .fitted import FittedAttribute
from .mlp_base import ACTIVATIONS, SOLVERS, BaseMLP

__all__ = ["MLPClassifier", "MLPRegressor", "ACTIVATIONS", "SOLVERS"]

#: Sparse formats taken as they are (as scikit-learn's MLPs); others are converted to CSR.
SPARSE = ("csr", "csc")


def _dense_target(y):
    """``y`` as given; a sparse ``y`` is refused in scikit-learn's words (targets are dense here,
    even the label indicator matrices that scikit-learn's classifier takes sparse)."""
    if issparse(y):
        check_array(y, accept_sparse=False, ensure_2d=False, dtype=None, input_name="y")
    return y


def _samples(estimator, X, *, reset: bool):
    """Refuse samples ``X`` the network cannot read, in the package's words, before
    scikit-learn's conversion: not 2-D numbers, NaN or inf, or (``reset`` false) another number
    of features than the network was fitted on."""
    n_features = None if reset else getattr(estimator, "n_features_in_", None)
    check_samples(X, n_features=n_features, owner=type(estimator).__name__)
    return X


def _partial_classes(classes) -> np.ndarray:
    """The ``classes`` of a first ``partial_fit`` call as a non-empty 1-D array of labels."""
    if isinstance(classes, str | bytes | dict | set):
        raise TypeError(f"classes must be an array-like of class labels, got "
                        f"{type(classes).__name__} {classes!r:.60}")
    try:
        out = np.asarray(classes)
    except ValueError:
        raise ValueError("classes must be a 1-D array of class labels, got a ragged list") from None
    if out.ndim != 1 or out.size == 0:
        raise ValueError(f"classes must be a non-empty 1-D array of class labels, got shape "
                         f"{out.shape}")
    if out.dtype.kind == "f" and not np.all(np.isfinite(out)):
        raise ValueError("classes must not hold NaN or infinity")
    return out


def _check_seen(y, classes) -> None:
    """Refuse labels of ``y`` that are not in the fitted ``classes`` (a continued fit keeps the
    network's outputs; LabelBinarizer would give those rows no class at all)."""
    unseen = np.setdiff1d(np.unique(y), classes)
    if unseen.size:
        raise ValueError(f"y holds labels {unseen.tolist()!r} that are not in classes_ "
                         f"{classes.tolist()!r} of the previous fit (warm_start continues that "
                         "network, with its classes)")


def _indicator(y, classes) -> np.ndarray:
    """``LabelBinarizer().fit(classes).transform(y)`` as float64 for 1-D string labels ``y``,
    all in the sorted ``classes``: one column per class (one 0/1 column for two classes, a
    column of zeros for one), found by one binary search per label."""
    column = np.searchsorted(classes, y)
    found = column < classes.size
    found[found] = classes[column[found]] == y[found]
    if not found.all():
        _check_seen(y, classes)
    if classes.size > 2:
        Y = np.zeros((y.size, classes.size))
        Y[np.arange(y.size), column] = 1.0
        return Y
    return (column == 1).astype(np.float64)[:, None]


def _first_order(estimator) -> bool:
    """``partial_fit`` exists for the first-order solvers only (as scikit-learn's for 'sgd' and
    'adam'): 'scg' and 'lbfgs' work on the full batch until they converge."""
    if estimator.solver not in ("gd", "sgd", "adam"):
        raise AttributeError(f"partial_fit is only available for the first-order solvers 'gd', "
                             f"'sgd' and 'adam'; solver={estimator.solver!r} is not one.")
    return True


class MLPClassifier(ClassifierMixin, BaseMLP):
    """Multilayer perceptron classifier: softmax (or logistic) output and cross-entropy loss.

    Parameters are those of :class:`sklearn.neural_network.MLPClassifier`, with ``solver`` one of
    'gd', 'sgd', 'adam', 'scg' or 'lbfgs', plus ``sigma0`` and ``lambda0`` of 'scg' (see the
    module text) and ``engine``: 'auto' (default) trains on the engine, 'reference' with the
    functions of :mod:`ebantenna.ml.backprop` and NumPy's optimiser steps, the same network to
    the last bit.
    ``random_state`` seeds a
    :func:`numpy.random.default_rng` (initial weights, shuffling); the validation split of
    ``early_stopping`` is drawn as scikit-learn draws it, the same samples for the same
    ``random_state``.

    Attributes
    ----------
    classes_ : ndarray
    coefs_, intercepts_ : list of ndarray
        Weight matrix (fan_in, fan_out) and bias vector of each layer.
    loss_ : float
        As scikit-learn's: the loss of the last epoch (mean over its batches), or for 'lbfgs'
        the loss at the final weights.
    loss_curve_ : list of float
        Loss at each epoch (mean over its batches).
    n_iter_ : int
    best_loss_ : float
    validation_scores_, best_validation_score_ : list, float or None
        Accuracy on the validation split when ``early_stopping``; the split is scikit-learn's
        for the same ``random_state``. With ``warm_start`` both carry on from the previous
        fit, as in scikit-learn.
    n_layers_, n_outputs_, out_activation_ : int, int, str

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> X = np.vstack([rng.normal(-1, 0.5, (30, 2)), rng.normal(1, 0.5, (30, 2))])
    >>> y = np.repeat(["pvc", "steel"], 30)
    >>> clf = MLPClassifier((5,), activation="tanh", solver="scg", max_iter=100,
    ...                     random_state=0).fit(X, y)
    >>> clf.score(X, y)
    1.0
    """

    _fitted_schema = (
        *BaseMLP._fitted_schema,
        FittedAttribute("classes_", "array", ndim=1),
        FittedAttribute("out_activation_", "value"),
        FittedAttribute("_multilabel", "value"),
        FittedAttribute("_label_binarizer", "rebuilt"),
    )

    @_fit_context(prefer_skip_nested_validation=True)
    def fit(self, X, y):
        """Train on features ``X`` (n_samples, n_features) and labels ``y``."""
        reset = not (self.warm_start and hasattr(self, "coefs_"))
        X = _samples(self, X, reset=reset)
        X, y = validate_data(self, X, _dense_target(check_targets(X, y, numeric=False)),
                             dtype=np.float64, accept_sparse=SPARSE, multi_output=True,
                             reset=reset)
        if y.ndim == 2 and y.shape[1] == 1:
            y = column_or_1d(y, warn=True)
        continued = self.warm_start and hasattr(self, "_label_binarizer")
        if (continued and y.ndim == 1 and y.dtype.kind == "U" and not self._multilabel
                and self.classes_.dtype.kind == "U"):
            Y = _indicator(y, self.classes_)  # one search instead of sorting the labels 5 times
            return self._fit(X, Y, y)
        check_classification_targets(y)
        if not continued:
            self._label_binarizer = LabelBinarizer().fit(y)
            self.classes_ = self._label_binarizer.classes_
        elif not type_of_target(y).startswith("multilabel"):
            _check_seen(y, self.classes_)
        Y = self._label_binarizer.transform(y).astype(np.float64)
        self._multilabel = type_of_target(y).startswith("multilabel")
        self.out_activation_ = "logistic" if (Y.shape[1] == 1 or self._multilabel) else "softmax"
        return self._fit(X, Y, y)

    @available_if(_first_order)
    @_fit_context(prefer_skip_nested_validation=True)
    def partial_fit(self, X, y, classes=None):
        """One epoch on ``X``, ``y``, continuing from the previous call (as scikit-learn's).

        The optimiser's state (momentum velocities or Adam's moments, the learning rate of
        'invscaling' and 'adaptive', the samples seen ``t_``) carries over from one call to the
        next. It is not kept by :meth:`fit` nor saved with the model: the first ``partial_fit``
        after either starts a fresh optimiser (scikit-learn's continues the one of ``fit``).

        Parameters
        ----------
        X : array-like of shape (n_samples, n_features)
        y : array-like of shape (n_samples,) or (n_samples, n_classes)
        classes : array-like of shape (n_classes,), optional
            Every class that will ever be seen; required on the first call only.

        Returns
        -------
        self
        """
        first = not hasattr(self, "classes_")
        if first and classes is None:
            raise ValueError("classes must be passed on the first call to partial_fit.")
        if not first and classes is not None and not np.array_equal(self.classes_,
                                                                    np.unique(classes)):
            raise ValueError(f"`classes={classes!r}` is not the same as on the first call to "
                             f"partial_fit, was: {self.classes_!r}")
        X = _samples(self, X, reset=first)
        X, y = validate_data(self, X, _dense_target(check_targets(X, y, numeric=False)),
                             dtype=np.float64, accept_sparse=SPARSE, multi_output=True,
                             reset=first)
        if y.ndim == 2 and y.shape[1] == 1:
            y = column_or_1d(y, warn=True)
        check_classification_targets(y)
        if first:
            self._multilabel = type_of_target(y).startswith("multilabel")
            fit_on = _partial_classes(classes) if not self._multilabel else y
            self._label_binarizer = LabelBinarizer().fit(fit_on)
            self.classes_ = self._label_binarizer.classes_
        if not self._multilabel:
            unseen = np.setdiff1d(np.unique(y), self.classes_)
            if unseen.size:  # LabelBinarizer would give their rows no class at all
                where = "given on the first call" if first else "of the first call"
                raise ValueError(f"y holds labels {unseen.tolist()!r} that are not in classes "
                                 f"{self.classes_.tolist()!r} ({where} to partial_fit)")
        Y = self._label_binarizer.transform(y).astype(np.float64)
        n_classes = self.classes_.size
        self.out_activation_ = ("logistic" if (n_classes <= 2 or self._multilabel)
                                else "softmax")
        return self._fit(X, Y, y, incremental=True)

    def _rebuild_fitted(self) -> None:
        """Rebuild the attributes that the schema marks 'rebuilt' (after loading)."""
        if self._multilabel:
            self._label_binarizer = LabelBinarizer().fit(np.eye(self.classes_.size, dtype=int))
        else:
            self._label_binarizer = LabelBinarizer().fit(self.classes_)

    def _validation_score(self, X, Y):
        return accuracy_score(self._label_binarizer.inverse_transform(Y), self.predict(X))

    def predict_proba(self, X):
        """Class probabilities, shape (n_samples, n_classes)."""
        check_is_fitted(self)
        X = validate_data(self, _samples(self, X, reset=False), dtype=np.float64,
                          accept_sparse=SPARSE, reset=False)
        z = forward(X, self.coefs_, self.intercepts_, self.activation)[-1]
        if self.out_activation_ == "softmax":
            z = z - z.max(axis=1, keepdims=True)
            e = np.exp(z)
            return e / e.sum(axis=1, keepdims=True)
        p = expit(z)
        if self._multilabel:
            return p
        return np.hstack([1.0 - p, p])

    def predict_log_proba(self, X):
        """Logarithm of :meth:`predict_proba`, computed stably."""
        check_is_fitted(self)
        X = validate_data(self, _samples(self, X, reset=False), dtype=np.float64,
                          accept_sparse=SPARSE, reset=False)
        z = forward(X, self.coefs_, self.intercepts_, self.activation)[-1]
        if self.out_activation_ == "softmax":
            return z - logsumexp(z, axis=1, keepdims=True)
        if self._multilabel:
            return log_expit(z)
        return np.hstack([log_expit(-z), log_expit(z)])

    def predict(self, X):
        """Predicted class labels."""
        proba = self.predict_proba(X)
        if self._multilabel:
            return self._label_binarizer.inverse_transform((proba > 0.5).astype(int))
        return self.classes_[np.argmax(proba, axis=1)]

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.classifier_tags.multi_label = True
        tags.input_tags.sparse = True
        return tags


class MLPRegressor(RegressorMixin, BaseMLP):
    """Multilayer perceptron regressor: identity output and squared-error loss.

    Parameters are those of :class:`sklearn.neural_network.MLPRegressor`, with ``solver`` one of
    'gd', 'sgd', 'adam', 'scg' or 'lbfgs', plus ``sigma0`` and ``lambda0`` of 'scg' (see the
    module text) and ``engine``: 'auto' (default) trains on the engine, 'reference' with the
    functions of :mod:`ebantenna.ml.backprop` and NumPy's optimiser steps, the same network to
    the last bit.
    With several outputs the gradient is the true gradient of the
    reported loss, which is ``1 / n_outputs`` of scikit-learn's (see the module text).

    Attributes
    ----------
    coefs_, intercepts_ : list of ndarray
    loss_ : float
        The loss of the last epoch, or for 'lbfgs' at the final weights.
    loss_curve_ : list of float
    n_iter_ : int
    best_loss_ : float
    validation_scores_, best_validation_score_ : list, float or None
        R² on the validation split when ``early_stopping``; the split is scikit-learn's for the
        same ``random_state``, and ``warm_start`` carries both on, as there.
    n_layers_, n_outputs_, out_activation_ : int, int, str

    Examples
    --------
    >>> import numpy as np
    >>> X = np.linspace(0, 1, 40)[:, None]
    >>> reg = MLPRegressor((9,), activation="relu", solver="scg", max_iter=300,
    ...                    random_state=1).fit(X, 0.5 * X[:, 0])
    >>> bool(reg.score(X, 0.5 * X[:, 0]) > 0.99)
    True
    """

    out_activation_ = "identity"

    _fitted_schema = (*BaseMLP._fitted_schema, FittedAttribute("_y_ndim", "value"))

    @_fit_context(prefer_skip_nested_validation=True)
    def fit(self, X, y):
        """Train on features ``X`` (n_samples, n_features) and targets ``y``."""
        reset = not (self.warm_start and hasattr(self, "coefs_"))
        X = _samples(self, X, reset=reset)
        X, y = validate_data(self, X, _dense_target(check_targets(X, y, numeric=True)),
                             dtype=np.float64, accept_sparse=SPARSE, multi_output=True,
                             y_numeric=True, reset=reset)
        self._y_ndim = y.ndim
        Y = y.reshape(-1, 1) if y.ndim == 1 else y
        return self._fit(X, np.asarray(Y, dtype=np.float64), None)

    @available_if(_first_order)
    @_fit_context(prefer_skip_nested_validation=True)
    def partial_fit(self, X, y):
        """One epoch on ``X``, ``y``, continuing from the previous call (as scikit-learn's).

        Returns
        -------
        self
        """
        first = not hasattr(self, "coefs_")
        X = _samples(self, X, reset=first)
        X, y = validate_data(self, X, _dense_target(check_targets(X, y, numeric=True)),
                             dtype=np.float64, accept_sparse=SPARSE, multi_output=True,
                             y_numeric=True, reset=first)
        if not first and y.ndim != self._y_ndim:
            raise ValueError(f"y has {y.ndim} dimension(s); the first call had {self._y_ndim}")
        self._y_ndim = y.ndim
        Y = y.reshape(-1, 1) if y.ndim == 1 else y
        return self._fit(X, np.asarray(Y, dtype=np.float64), None, incremental=True)

    def _validation_score(self, X, Y):
        return r2_score(Y if Y.shape[1] > 1 else Y[:, 0], self.predict(X))

    def predict(self, X):
        """Predicted targets, shape (n_samples,) or (n_samples, n_outputs)."""
        check_is_fitted(self)
        X = validate_data(self, _samples(self, X, reset=False), dtype=np.float64,
                          accept_sparse=SPARSE, reset=False)
        z = forward(X, self.coefs_, self.intercepts_, self.activation)[-1]
        return z[:, 0] if self._y_ndim == 1 else z

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.target_tags.multi_output = True
        tags.target_tags.single_output = True
        tags.input_tags.sparse = True
        return tags
