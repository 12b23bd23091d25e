"""The paper's two learning experiments, on plain arrays.

* Material classification (sections 4.2 and 4.3): an RBF support vector machine trained one-vs-rest
  on an 80/20 split and a network with one hidden layer of 53 tanh neurons trained by gradient
  descent on a 70/15/15 split; what the paper printed for them is in
  :mod:`ebantenna.paper.printed` (Figs. 12 and 15).
* Contact-distance regression (section 4.2): two tanh layers of 20 neurons on the first 80 % of the
  probe, and one ReLU layer of 9 neurons trained by scaled conjugate gradient over the full length
  on min-max normalised features; errors in cm along the probe.

The settings come from :mod:`ebantenna.paper.protocol`. Every function takes the feature matrix
``X`` of shape (n, 256) (FFT magnitudes), the material labels and/or the contact distances in
metres, and returns a small frozen result object with the confusion matrices, accuracies and
errors; :mod:`ebantenna.paper.plots` draws them.
"""

from __future__ import annotations

import logging
import time
import warnings
from dataclasses import dataclass, replace

import numpy as np
from sklearn.exceptions import ConvergenceWarning
from sklearn.model_selection import train_test_split

from .._validate import check_array, check_in_range, check_positive, check_split
from ..ml import MLPClassifier, MLPRegressor
from ..ml.metrics import absolute_errors, accuracy, confusion_matrix
from ._ovr_svm import OneVsRestSVC, whole_kernel_svc
from .protocol import (
    DISTANCE_FULL_LENGTH,
    DISTANCE_LINEAR_REGION,
    MATERIAL_ANN,
    MATERIAL_SVM,
    check_fractions,
    normalise_by_max,
    three_way_split,
)

__all__ = [
    "ClassificationResult",
    "RegressionResult",
    "classify_materials_svm",
    "classify_materials_ann",
    "regress_distance_linear_region",
    "regress_distance_full_length",
    "format_confusion",
]

logger = logging.getLogger(__name__)


# --------------------------------------------------------------------------------- results
@dataclass(frozen=True)
class ClassificationResult:
    """Outcome of a material-classification experiment.

    Attributes
    ----------
    method : str
        'svm' or 'ann'.
    labels : tuple of str
        Class order of the confusion matrices.
    confusions : dict of str to ndarray
        Counts per split ('train', 'test', 'all'); rows = true, columns = predicted class.
    fit_seconds : float
        Wall time of training, in s.
    model : object
        The fitted estimator.
    tested : dict of str to (ndarray, ndarray), optional
        Per split: the row indices (into the ``X`` given) and whether each was classified
        right, in the same order; what an interval on the design's clusters is computed from
        (:mod:`ebantenna.paper.uncertainty`).
    stopped_by : str, optional
        What ended a network's training: ``"epoch cap"`` (it ran ``max_iter`` epochs),
        ``"validation"`` (the validation check) or ``"tolerance"`` (the training loss stopped
        falling by ``tol``); None for the SVM.
    routes : dict of str to dict, optional
        Per split, how many rows each way of classifying took, where a classifier has more than
        one (:func:`~ebantenna.paper.mode_curves.classify_materials_by_mode_curves`: ``"two
        peaks"``, ``"dominant frequency"``, ``"most common material"``); None where every row
        takes the same way.
    """

    method: str
    labels: tuple
    confusions: dict
    fit_seconds: float
    model: object = None
    tested: dict | None = None
    stopped_by: str | None = None
    routes: dict | None = None

    def correct(self, split: str = "test") -> np.ndarray:
        """Whether each recording of ``split`` was classified right (row order of
        ``tested[split][0]``)."""
        if not isinstance(split, str):
            raise TypeError(f"split must be the name of a split, got {type(split).__name__}")
        if not self.tested or split not in self.tested:
            raise ValueError(f"split {split!r} was not recorded row by row; recorded: "
                             f"{sorted(self.tested or ())}")
        return self.tested[split][1]

    def rows(self, split: str = "test") -> np.ndarray:
        """Row indices of ``split`` (into the ``X`` the classifier was given)."""
        self.correct(split)
        return self.tested[split][0]

    @property
    def accuracies(self) -> dict:
        """Accuracy (fraction) of every split."""
        return {k: accuracy(m) for k, m in self.confusions.items()}

    @property
    def counts(self) -> dict:
        """Recordings (rows) of every split: what each accuracy was measured on."""
        return {k: int(m.sum()) for k, m in self.confusions.items()}

    def report(self) -> str:
        """The confusion matrices and accuracies as text."""
        lines = []
        for split, m in self.confusions.items():
            lines.append(f"{self.method.upper()} {split}: accuracy "
                         f"{100 * accuracy(m):.1f} % of {int(m.sum())} samples")
            lines.append(format_confusion(m, self.labels))
        return "\n".join(lines)


@dataclass(frozen=True)
class RegressionResult:
    """Outcome of a contact-distance regression.

    Attributes
    ----------
    name : str
        Which network.
    distance_test : ndarray
        True contact distances of the test samples, in m.
    predicted_test : ndarray
        Predicted distances, in m.
    positions : ndarray
        Distinct contact distances of the test set, in m.
    mean_error_cm : ndarray
        Mean absolute error at each of ``positions``, in cm.
    fit_seconds : float
        Wall time of training, in s.
    model : object
        The fitted estimator.
    test_rows : ndarray of int or None
        The rows of the ``X`` given that were tested, in the order of ``distance_test``: two
        networks tested on the same rows can be compared recording by recording (paired). None
        where they are not known.
    """

    name: str
    distance_test: np.ndarray
    predicted_test: np.ndarray
    positions: np.ndarray
    mean_error_cm: np.ndarray
    fit_seconds: float
    model: object = None
    test_rows: np.ndarray | None = None

    @property
    def errors_cm(self) -> np.ndarray:
        """Absolute error of every test sample, in cm."""
        return 100.0 * absolute_errors(self.distance_test, self.predicted_test)

    @property
    def mae_cm(self) -> float:
        """Mean absolute error over the test set, in cm."""
        return float(self.errors_cm.mean())

    @property
    def rmse_cm(self) -> float:
        """Root-mean-square error over the test set, in cm."""
        return float(np.sqrt(np.mean(self.errors_cm**2)))

    def report(self) -> str:
        """A one-paragraph summary with the error along the probe."""
        lines = [f"{self.name}: {self.distance_test.size} test samples, mean absolute error "
                 f"{self.mae_cm:.2f} cm, RMS {self.rmse_cm:.2f} cm"]
        for d, e in zip(self.positions, self.mean_error_cm, strict=True):
            lines.append(f"  contact {100 * d:6.1f} cm: mean |error| {e:6.2f} cm")
        return "\n".join(lines)


# ------------------------------------------------------------------------------- helpers
def _features(X) -> np.ndarray:
    return check_array("X", X, ndim=2)


def _labels(materials, n) -> np.ndarray:
    y = np.asarray(materials)
    if y.ndim != 1 or y.size != n:
        raise ValueError(f"materials must be 1-D with one label per row of X ({n}), "
                         f"got shape {y.shape}")
    if np.unique(y).size < 2:
        raise ValueError("materials must contain at least two classes")
    return y


def _distances(distances, n) -> np.ndarray:
    d = check_array("distances", distances, ndim=1)
    if d.size != n:
        raise ValueError(f"distances must have one value per row of X ({n}), got {d.size}")
    if np.any(d < 0):
        raise ValueError("distances must be >= 0 (metres from the hinge)")
    return d


def label_order(y, labels):
    """The class order of the confusion matrices: ``labels`` as given, which must list every
    material of ``y`` (a row whose label it lacks would drop out of every matrix while the
    accuracy still counted it as tested), or the sorted materials of ``y``.

    Examples
    --------
    >>> label_order(["wood", "al", "wood"], None)
    ('al', 'wood')
    >>> label_order(["wood", "al"], ["al", "Wood"])
    Traceback (most recent call last):
    ...
    ValueError: labels must list every material; missing ['wood']
    """
    if labels is None:
        return tuple(np.unique(y).tolist())
    labels = tuple(labels)
    missing = set(np.unique(y).tolist()) - set(labels)
    if missing:
        raise ValueError(f"labels must list every material; missing {sorted(missing)!r}")
    return labels


# ---------------------------------------------------------------------- classification
def classify_materials_svm(X, materials, *, test_fraction=MATERIAL_SVM.test_fraction, C=1.0,
                           gamma=MATERIAL_SVM.gamma, seed=0, labels=None, normalise=True,
                           tol=1e-3, split=None) -> ClassificationResult:
    """Material classification by an RBF SVM trained one-vs-rest (section 4.3, Fig. 15).

    Parameters
    ----------
    X : array-like of shape (n, n_features)
        Features (the paper: 256 FFT magnitudes).
    materials : array-like of shape (n,)
        Material label of each row.
    test_fraction : float, default=0.2
        Share of the samples held out for testing (stratified by material).
    C : float, default=1.0
        SVM penalty.
    gamma : float or {'scale', 'auto'}, default=2.0
        RBF width; the paper's optimum was 2.0 on features divided by their maximum.
    seed : int, default=0
        Seed of the split.
    labels : sequence of str, optional
        Row order of the confusion matrices (default: sorted); it must list every material
        of ``materials``: a row whose material it lacks would leave every matrix.
    normalise : bool, default=True
        Divide ``X`` by its largest magnitude, as the paper did, taken over the training rows
        only (:func:`~ebantenna.paper.protocol.normalise_by_max`).
    tol : float, default=1e-3
        SMO stopping tolerance.
    split : (ndarray, ndarray), optional
        Train and test row indices (e.g. from :mod:`ebantenna.paper.splits`), replacing the
        random split; ``test_fraction`` and ``seed`` are then not used.

    Returns
    -------
    ClassificationResult
        Confusion matrices for 'train' and 'test'. Its ``model`` is a
        ``sklearn.multiclass.OneVsRestClassifier`` of RBF :class:`ebantenna.ml.SVC`
        machines that predicts from features scaled as they were here
        (``model.predict(normalise_by_max(X, train)[rows])``). Each machine holds the whole
        kernel matrix of the training rows in float64 when it fits the memory budget (else
        rows computed on demand and stored in float32, with a warning), and the machines share
        one test kernel per prediction.

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> y = np.repeat(["brass", "pvc", "steel"], 40)
    >>> X = rng.normal(size=(120, 8)) + 3 * (y[:, None] == ["brass", "pvc", "steel"]).repeat(
    ...     [3, 3, 2], axis=1)
    >>> res = classify_materials_svm(X, y, gamma="scale")
    >>> int(res.confusions["test"].sum()), res.accuracies["test"] > 0.9
    (24, True)
    """
    X = _features(X)
    y = _labels(materials, X.shape[0])
    check_in_range("test_fraction", test_fraction, 0.0, 1.0)
    check_positive("C", C)
    order = label_order(y, labels)
    if split is None:
        train, test = train_test_split(np.arange(X.shape[0]), test_size=test_fraction,
                                       random_state=seed, stratify=y)
    else:
        train, test = check_split(split, X.shape[0])
    if normalise:  # the scale from the training rows only: the test rows stay unseen
        X = normalise_by_max(X, train)
    model = OneVsRestSVC(whole_kernel_svc(train.size, C=C, gamma=gamma, tol=tol))
    start = time.perf_counter()
    model.fit(X[train], y[train])
    seconds = time.perf_counter() - start
    predicted = {"train": model.predict(X[train]), "test": model.predict(X[test])}
    confusions, tested = confusions_and_tested(y, predicted, {"train": train, "test": test}, order)
    logger.info("SVM: train %.3f, test %.3f in %.2f s", accuracy(confusions["train"]),
                accuracy(confusions["test"]), seconds)
    return ClassificationResult("svm", order, confusions, seconds, model, tested)


def classify_materials_ann(X, materials, *, hidden_layer_sizes=MATERIAL_ANN.hidden_layer_sizes,
                           activation=MATERIAL_ANN.activation, solver=MATERIAL_ANN.solver,
                           learning_rate_init=0.05, max_iter=1000,
                           fractions=MATERIAL_ANN.fractions, seed=0, labels=None, normalise=True,
                           n_iter_no_change=6) -> ClassificationResult:
    """Material classification by a tanh network (section 4.2, Fig. 12).

    The samples are split 70/15/15 (stratified). With gradient descent (``solver='gd'``)
    training runs on the first part and stops when the cross-entropy on the validation part has
    not decreased for ``n_iter_no_change`` epochs (MATLAB's validation check), keeping the best
    weights. A trainer that carries state from one epoch to the next (``'scg'``: its conjugate
    directions, ``'adam'``: its moment estimates, ``'sgd'``: momentum) runs in one call instead,
    on the train and validation parts together, with the estimator's own early stopping on the
    same validation share (validation accuracy, scikit-learn's rule); the 'validation'
    confusion matrix is then left out, since the estimator drew its own validation rows.

    Parameters
    ----------
    X, materials
        As in :func:`classify_materials_svm`.
    hidden_layer_sizes : tuple of int, default=(53,)
        The paper's optimum: one hidden layer of 53 neurons.
    activation : str, default='tanh'
    solver : {'gd', 'scg', 'adam', 'sgd'}, default='gd'
        Full-batch gradient descent, as in the paper, or another trainer of
        :class:`ebantenna.ml.MLPClassifier`.
    learning_rate_init : float, default=0.05
        Step of 'gd', 'sgd' and 'adam' (SCG chooses its own).
    max_iter : int, default=1000
        Largest number of epochs.
    fractions : (float, float, float), default=(0.70, 0.15, 0.15)
        Train, validation and test shares.
    seed : int, default=0
        Seed of the split and of the initial weights.
    labels, normalise
        As in :func:`classify_materials_svm`.
    n_iter_no_change : int, default=6
        Validation patience, in epochs.

    Returns
    -------
    ClassificationResult
        Confusion matrices for 'train', 'validation', 'test' and 'all' (the paper's Fig. 12 shows
        'all').

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> y = np.repeat(["al", "wood"], 60)
    >>> X = rng.normal(size=(120, 5)) + 2.0 * (y == "wood")[:, None]
    >>> res = classify_materials_ann(X, y, hidden_layer_sizes=(4,), max_iter=200, seed=0)
    >>> sorted(res.confusions), res.accuracies["all"] > 0.9
    (['all', 'test', 'train', 'validation'], True)
    """
    X = _features(X)
    y = _labels(materials, X.shape[0])
    check_fractions(fractions)
    order = label_order(y, labels)
    train, val, test = three_way_split(X.shape[0], fractions, seed, stratify=y)
    if normalise:  # the scale from the rows the network learns and stops on, never the test's
        X = normalise_by_max(X, np.concatenate([train, val]))
    model = MLPClassifier(hidden_layer_sizes=hidden_layer_sizes, activation=activation,
                          solver=solver, learning_rate_init=learning_rate_init, max_iter=1,
                          random_state=seed, warm_start=True, alpha=0.0)
    start = time.perf_counter()
    if solver != "gd":
        fit_rows = np.concatenate([train, val])
        model.set_params(max_iter=max_iter, warm_start=False, early_stopping=True,
                         validation_fraction=len(val) / len(fit_rows),
                         n_iter_no_change=n_iter_no_change)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ConvergenceWarning)
            model.fit(X[fit_rows], y[fit_rows])
        stopped = "epoch cap" if model.n_iter_ >= max_iter else "validation"
        return _ann_result(model, X, y, order, {"train": fit_rows, "test": test}, start,
                           stopped)
    best, best_loss, since, stopped = None, np.inf, 0, "epoch cap"
    X_train, y_train, X_val = X[train], y[train], X[val]
    with warnings.catch_warnings():
        # one epoch per call: the per-call iteration limit is reached on purpose
        warnings.simplefilter("ignore", ConvergenceWarning)
        for _ in range(max_iter):
            model.fit(X_train, y_train)
            log_p = model.predict_log_proba(X_val)
            cols = np.searchsorted(model.classes_, y[val])
            val_loss = -float(np.mean(log_p[np.arange(cols.size), cols]))
            if val_loss < best_loss:
                best_loss, since = val_loss, 0
                best = ([c.copy() for c in model.coefs_], [b.copy() for b in model.intercepts_])
            else:
                since += 1
                if since >= n_iter_no_change:
                    stopped = "validation"
                    break
    model.coefs_, model.intercepts_ = best
    return _ann_result(model, X, y, order, {"train": train, "validation": val, "test": test},
                       start, stopped)


def _ann_result(model, X, y, order, parts, start, stopped) -> ClassificationResult:
    seconds = time.perf_counter() - start
    parts = {**parts, "all": np.arange(X.shape[0])}
    predicted = {k: model.predict(X[i]) for k, i in parts.items()}
    confusions, tested = confusions_and_tested(y, predicted, parts, order)
    logger.info("ANN (%s): all %.3f, test %.3f after %d epochs", model.solver,
                accuracy(confusions["all"]), accuracy(confusions["test"]), model.n_iter_)
    return ClassificationResult("ann", order, confusions, seconds, model, tested, stopped)


def confusions_and_tested(y, predicted: dict, rows: dict, order) -> tuple[dict, dict]:
    """Per split: the confusion matrix, and the rows with whether each was classified right
    (the ``tested`` of :class:`ClassificationResult`)."""
    confusions, tested = {}, {}
    for k, pred in predicted.items():
        r = np.asarray(rows[k], dtype=np.intp)
        truth = np.asarray(y)[r]
        confusions[k] = confusion_matrix(truth, pred, order)
        tested[k] = (r, np.asarray(pred) == truth)
    return confusions, tested


# -------------------------------------------------------------------------- regression
def _regression(name, X, d, model, fractions, seed, min_max, split=None) -> RegressionResult:
    if split is None:
        train, val, test = three_way_split(X.shape[0], fractions, seed)
        fit_rows = np.concatenate([train, val])
    else:  # whole positions held out: the estimator draws its validation share from the rest
        fit_rows, test = split
    if min_max:
        lo = X[fit_rows].min(axis=0)
        span = X[fit_rows].max(axis=0) - lo
        span[span == 0] = 1.0  # a constant feature stays constant (0)
        X = (X - lo) / span
    # the validation part drives early stopping: train + validation are given to fit, which
    # holds out the validation share itself
    model.set_params(early_stopping=True,
                     validation_fraction=fractions[1] / (fractions[0] + fractions[1]))
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        model.fit(X[fit_rows], 100.0 * d[fit_rows])  # trained in cm: targets of order 1-10
    seconds = time.perf_counter() - start
    pred = model.predict(X[test]) / 100.0
    truth = d[test]
    positions = np.unique(truth)
    err_cm = 100.0 * np.abs(pred - truth)
    mean_err = np.array([err_cm[truth == p].mean() for p in positions])
    return RegressionResult(name, truth, pred, positions, mean_err, seconds, model,
                            np.asarray(test, dtype=np.intp))


def regress_distance_linear_region(X, distances, *, probe_length,
                                   fraction_of_length=DISTANCE_LINEAR_REGION.region,
                                   hidden_layer_sizes=DISTANCE_LINEAR_REGION.hidden_layer_sizes,
                                   activation=DISTANCE_LINEAR_REGION.activation,
                                   solver=DISTANCE_LINEAR_REGION.solver,
                                   learning_rate_init=0.01, max_iter=2000,
                                   fractions=DISTANCE_LINEAR_REGION.fractions, seed=0,
                                   normalise=True, split=None):
    """Contact distance on the first 80 % of the probe by a 2 x 20 tanh network (section 4.2).

    Parameters
    ----------
    X : array-like of shape (n, n_features)
        Features.
    distances : array-like of shape (n,)
        Contact distance from the hinge of each row, in m.
    probe_length : float
        Probe length, in m; samples beyond ``fraction_of_length * probe_length`` are left out.
    fraction_of_length : float, default=0.8
        The "linear" part of the probe used by the paper.
    hidden_layer_sizes, activation, solver, learning_rate_init, max_iter
        The network (the paper: two tanh layers of 20, gradient descent).
    fractions : (float, float, float)
        Train, validation and test shares.
    seed : int
        Seed of the split and the initial weights.
    normalise : bool
        Divide ``X`` by its largest magnitude on the training and validation rows.
    split : (ndarray, ndarray), optional
        Rows (of ``X``) to learn from and to test on, replacing the random 70/15/15 split, e.g.
        whole positions held out (:func:`~ebantenna.paper.splits.split_folds`); rows beyond the
        region are dropped from both, and the validation share is drawn from the first.

    Returns
    -------
    RegressionResult

    Examples
    --------
    >>> d = np.repeat(np.linspace(0.02, 0.30, 15), 8)
    >>> X = np.column_stack([np.cos(8 * d), np.sin(8 * d), d * 0 + 1.0])
    >>> X = X + np.random.default_rng(0).normal(0, 0.01, X.shape)
    >>> res = regress_distance_linear_region(X, d, probe_length=0.3, solver="scg",
    ...                                      max_iter=300)
    >>> bool(res.distance_test.max() <= 0.24), res.mae_cm < 2.0
    (True, True)
    """
    X = _features(X)
    d = _distances(distances, X.shape[0])
    check_positive("probe_length", probe_length)
    check_in_range("fraction_of_length", fraction_of_length, 0.0, 1.0, high_inclusive=True)
    check_fractions(fractions)
    keep = d <= fraction_of_length * probe_length
    if keep.sum() < 10:
        raise ValueError("fewer than 10 samples lie within fraction_of_length of the hinge")
    if split is not None:  # the given rows renumbered among those kept
        index = np.full(X.shape[0], -1)
        index[keep] = np.arange(int(keep.sum()))
        split = tuple(index[r][index[r] >= 0] for r in check_split(split, X.shape[0]))
        if np.intersect1d(*split).size or min(r.size for r in split) < 1:
            raise ValueError("split must give disjoint, non-empty rows within the region")
    X, d = X[keep], d[keep]
    if normalise:  # the scale from the rows the network learns and stops on, never the test's
        if split is None:
            train, val, _ = three_way_split(X.shape[0], fractions, seed)
            X = normalise_by_max(X, np.concatenate([train, val]))
        else:
            X = normalise_by_max(X, split[0])
    model = MLPRegressor(hidden_layer_sizes=hidden_layer_sizes, activation=activation,
                         solver=solver, learning_rate_init=learning_rate_init, max_iter=max_iter,
                         random_state=seed, alpha=0.0, n_iter_no_change=20)
    result = _regression(f"{'x'.join(map(str, hidden_layer_sizes))} {activation} ({solver}), "
                         f"first {100 * fraction_of_length:.0f} % of the probe",
                         X, d, model, fractions, seed, min_max=False, split=split)
    # the tested rows numbered among all the rows given, not among those kept
    return replace(result, test_rows=np.flatnonzero(keep)[result.test_rows])


def regress_distance_full_length(X, distances, *,
                                 hidden_layer_sizes=DISTANCE_FULL_LENGTH.hidden_layer_sizes,
                                 activation=DISTANCE_FULL_LENGTH.activation,
                                 solver=DISTANCE_FULL_LENGTH.solver, max_iter=1000,
                                 fractions=DISTANCE_FULL_LENGTH.fractions, seed=0):
    """Contact distance over the whole probe by a 9-neuron ReLU network trained by SCG.

    The features are min-max normalised per feature (range taken from the training and
    validation parts), as in section 4.2; the paper filters the signals first (Table 2), which
    belongs to the feature extraction, not here.

    Returns
    -------
    RegressionResult

    Examples
    --------
    >>> d = np.repeat(np.linspace(0.02, 0.30, 15), 8)
    >>> X = np.column_stack([np.cos(8 * d), np.sin(8 * d)])
    >>> X = X + np.random.default_rng(0).normal(0, 0.01, X.shape)
    >>> res = regress_distance_full_length(X, d, max_iter=400)
    >>> res.mae_cm < 2.0
    True
    """
    X = _features(X)
    d = _distances(distances, X.shape[0])
    check_fractions(fractions)
    model = MLPRegressor(hidden_layer_sizes=hidden_layer_sizes, activation=activation,
                         solver=solver, max_iter=max_iter, random_state=seed, alpha=0.0,
                         n_iter_no_change=30)
    return _regression(f"{'x'.join(map(str, hidden_layer_sizes))} {activation} ({solver}), "
                       "full length", X, d, model, fractions, seed, min_max=True)


# ---------------------------------------------------------------------------- reporting
def format_confusion(matrix, labels) -> str:
    """A confusion matrix as a text table (rows: true class, columns: predicted class).

    Examples
    --------
    >>> print(format_confusion(np.array([[5, 1], [0, 4]]), ["al", "pvc"]))
    true \\ predicted     al    pvc
    al                    5      1
    pvc                   0      4

    ``matrix`` must be a square array of counts (non-negative whole numbers, at least one of
    them not zero) and ``labels`` a sequence of one name per class; anything else is refused
    with an error naming the parameter.
    """
    m = check_array("matrix", matrix, ndim=2)
    if m.shape[0] != m.shape[1]:
        raise ValueError(f"matrix must be square (one row and one column per class), got shape "
                         f"{m.shape}")
    if np.any(m < 0) or np.any(m != np.round(m)) or np.any(m >= 2.0**53):
        raise ValueError("matrix must hold counts: whole numbers from 0 to 2**53 (no fractions, "
                         "no negatives)")
    if not m.sum() > 0:
        raise ValueError("matrix must hold at least one count: it is all zeros (no sample)")
    if isinstance(labels, str | bytes) or not hasattr(labels, "__len__"):
        raise TypeError(f"labels must be a sequence of class names, got "
                        f"{type(labels).__name__} {labels!r:.60}")
    if len(labels) != m.shape[0]:
        raise ValueError(f"labels must name each of the {m.shape[0]} classes of matrix, got "
                         f"{len(labels)} label(s)")
    width = max(6, *(len(str(lab)) for lab in labels), len(str(int(m.max()))))
    head = "true \\ predicted".ljust(16) + "".join(str(lab).rjust(width + 1) for lab in labels)
    rows = [str(lab).ljust(16) + "".join(str(int(v)).rjust(width + 1) for v in row)
            for lab, row in zip(labels, m, strict=True)]
    return "\n".join([head, *rows])
