"""The paper's two learning experiments, on plain arrays, beside the paper's printed results.

* Material classification (sections 4.2 and 4.3): an RBF support vector machine trained one-vs-rest
  on an 80/20 split (Fig. 15: 99.7 % training, 99.2 % test accuracy) and a network with one hidden
  layer of 53 tanh neurons trained by gradient descent on a 70/15/15 split (Fig. 12: 80.8 %).
* Contact-distance regression (section 4.2): two tanh layers of 20 neurons on the first 80 % of the
  probe, and one ReLU layer of 9 neurons trained by scaled conjugate gradient over the full length
  on min-max normalised features; errors in cm along the probe.

Every function takes the feature matrix ``X`` of shape (n, 256) (FFT magnitudes), the material
labels and/or the contact distances in metres, and returns a small frozen result object with the
confusion matrices, accuracies and errors. :func:`plot_confusion_comparison` and
:func:`plot_distance_errors` draw them, the first beside :data:`PAPER_SVM` and :data:`PAPER_ANN`,
the confusion matrices printed in Figs. 15 and 12, transcribed here as data.
"""

from __future__ import annotations

import logging
import time
import warnings
from dataclasses import dataclass, field

import numpy as np
from sklearn.exceptions import ConvergenceWarning
from sklearn.model_selection import train_test_split
from sklearn.multiclass import OneVsRestClassifier

from .._validate import check_array, check_in_range, check_positive
from .metrics import absolute_errors, accuracy, confusion_matrix
from .mlp import MLPClassifier, MLPRegressor
from .svc import SVC

__all__ = [
    "PaperConfusion",
    "PAPER_ANN",
    "PAPER_SVM",
    "ClassificationResult",
    "RegressionResult",
    "normalise_by_max",
    "classify_materials_svm",
    "classify_materials_ann",
    "regress_distance_linear_region",
    "regress_distance_full_length",
    "format_confusion",
    "plot_confusion_comparison",
    "plot_distance_errors",
]

logger = logging.getLogger(__name__)


# --------------------------------------------------------------------------- the paper's numbers
@dataclass(frozen=True)
class PaperConfusion:
    """A confusion matrix as printed in the paper.

    Attributes
    ----------
    figure : str
        Where it is printed.
    labels : tuple of str
        Class names in the printed order.
    matrices : dict of str to ndarray
        Counts per split ('train', 'test' or 'all'), rows = true class, columns = predicted class.
    reported_accuracy : dict of str to float
        The accuracies printed with the figure (fractions).
    note : str
        How the printed figure was read.

    Examples
    --------
    >>> round(PAPER_SVM.accuracy("train"), 4), PAPER_SVM.reported_accuracy["train"]
    (0.9965, 0.997)
    >>> int(PAPER_SVM.matrices["test"].sum())
    1200
    """

    figure: str
    labels: tuple[str, ...]
    matrices: dict = field(default_factory=dict)
    reported_accuracy: dict = field(default_factory=dict)
    note: str = ""

    def accuracy(self, split: str) -> float:
        """Accuracy recomputed from the printed counts of ``split``."""
        return accuracy(self.matrices[split])


_FIG12_PRINTED = np.array(
    [  # rows: output (predicted) class; columns: target (true) class, MATLAB's plotconfusion
        [808, 58, 22, 52, 20],
        [32, 685, 33, 74, 23],
        [14, 41, 709, 39, 55],
        [31, 79, 53, 648, 41],
        [21, 43, 70, 55, 757],
    ]
)

#: Fig. 12: the 53-neuron tanh network, all samples (training, validation and test together).
PAPER_ANN = PaperConfusion(
    figure="Fig. 12",
    labels=("aluminium", "pvc", "brass", "wood", "steel"),
    matrices={"all": _FIG12_PRINTED.T.copy()},
    reported_accuracy={"all": 0.808},
    note="Printed as MATLAB's plotconfusion (rows: output class, columns: target class); stored "
    "transposed. The printed row totals give the precisions (84.2 % for aluminium), the column "
    "totals the recalls (89.2 %). The wood row prints '76.1' without its percent sign.",
)

#: Fig. 15: the RBF SVM trained one-vs-rest; white cells training, red cells test.
PAPER_SVM = PaperConfusion(
    figure="Fig. 15",
    labels=("aluminium", "brass", "pvc", "steel", "wood"),
    matrices={
        "train": np.array([
            [886, 1, 0, 1, 1],
            [3, 966, 0, 1, 0],
            [0, 1, 980, 3, 0],
            [2, 0, 0, 1020, 1],
            [1, 0, 1, 1, 931],
        ]),
        "test": np.array([
            [217, 2, 1, 1, 1],
            [0, 238, 0, 0, 1],
            [0, 0, 272, 0, 0],
            [2, 2, 0, 238, 0],
            [0, 0, 0, 0, 225],
        ]),
    },
    reported_accuracy={"train": 0.997, "test": 0.992},
    note="Rows are read as the true class (the row labels of the figure); each row has a "
    "training line (white) and a test line (red). The counts add up to 4800 and 1200 samples, "
    "the 80/20 split of 6000, and give 99.65 % (printed 99.7 %) and 99.17 % (printed 99.2 %).",
)


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
    """

    method: str
    labels: tuple
    confusions: dict
    fit_seconds: float
    model: object = None

    @property
    def accuracies(self) -> dict:
        """Accuracy (fraction) of every split."""
        return {k: accuracy(m) for k, m in self.confusions.items()}

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
    """

    name: str
    distance_test: np.ndarray
    predicted_test: np.ndarray
    positions: np.ndarray
    mean_error_cm: np.ndarray
    fit_seconds: float
    model: object = None

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
def normalise_by_max(X) -> np.ndarray:
    """Divide the whole feature matrix by its largest magnitude, as in section 4.2.

    Examples
    --------
    >>> normalise_by_max(np.array([[1.0, -4.0], [2.0, 0.0]]))
    array([[ 0.25, -1.  ],
           [ 0.5 ,  0.  ]])
    """
    X = np.asarray(X, dtype=np.float64)
    peak = np.abs(X).max()
    if peak == 0:
        raise ValueError("X must not be all zeros")
    return X / peak


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


def _three_way_split(n, fractions, seed, stratify=None):
    """Indices of train / validation / test parts with the given fractions."""
    _, f_val, f_test = fractions
    n_test, n_val = int(round(f_test * n)), int(round(f_val * n))
    if min(n_test, n_val, n - n_test - n_val) < 1:
        raise ValueError(f"{n} samples cannot be split by fractions {fractions!r}")
    idx = np.arange(n)
    rest, test = train_test_split(idx, test_size=n_test, random_state=seed, stratify=stratify)
    strat_rest = None if stratify is None else stratify[rest]
    train, val = train_test_split(rest, test_size=n_val, random_state=seed + 1,
                                  stratify=strat_rest)
    return train, val, test


def _check_fractions(fractions):
    if len(fractions) != 3:
        raise ValueError(f"fractions must be (train, validation, test), got {fractions!r}")
    for name, f in zip(("train", "validation", "test"), fractions, strict=True):
        check_in_range(f"fractions[{name}]", f, 0.0, 1.0)
    if abs(sum(fractions) - 1.0) > 1e-9:
        raise ValueError(f"fractions must add up to 1, got {fractions!r}")


def _label_order(y, labels):
    if labels is None:
        return tuple(np.unique(y).tolist())
    labels = tuple(labels)
    missing = set(np.unique(y).tolist()) - set(labels)
    if missing:
        raise ValueError(f"labels must list every material; missing {sorted(missing)!r}")
    return labels


# ---------------------------------------------------------------------- classification
def classify_materials_svm(X, materials, *, test_fraction=0.2, C=1.0, gamma=2.0, seed=0,
                           labels=None, normalise=True, tol=1e-3) -> ClassificationResult:
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
        Row order of the confusion matrices (default: sorted).
    normalise : bool, default=True
        Divide ``X`` by its largest magnitude first, as the paper did.
    tol : float, default=1e-3
        SMO stopping tolerance.

    Returns
    -------
    ClassificationResult
        Confusion matrices for 'train' and 'test'.

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
    order = _label_order(y, labels)
    if normalise:
        X = normalise_by_max(X)
    idx = np.arange(X.shape[0])
    train, test = train_test_split(idx, test_size=test_fraction, random_state=seed, stratify=y)
    model = OneVsRestClassifier(SVC(kernel="rbf", C=C, gamma=gamma, tol=tol))
    start = time.perf_counter()
    model.fit(X[train], y[train])
    seconds = time.perf_counter() - start
    confusions = {
        "train": confusion_matrix(y[train], model.predict(X[train]), order),
        "test": confusion_matrix(y[test], model.predict(X[test]), order),
    }
    logger.info("SVM: train %.3f, test %.3f in %.2f s", accuracy(confusions["train"]),
                accuracy(confusions["test"]), seconds)
    return ClassificationResult("svm", order, confusions, seconds, model)


def classify_materials_ann(X, materials, *, hidden_layer_sizes=(53,), activation="tanh",
                           solver="gd", learning_rate_init=0.05, max_iter=1000,
                           fractions=(0.70, 0.15, 0.15), seed=0, labels=None, normalise=True,
                           n_iter_no_change=6) -> ClassificationResult:
    """Material classification by a tanh network (section 4.2, Fig. 12).

    The samples are split 70/15/15 (stratified). Training runs on the first part and stops when
    the cross-entropy on the validation part has not decreased for ``n_iter_no_change`` epochs
    (MATLAB's validation check), keeping the best weights.

    Parameters
    ----------
    X, materials
        As in :func:`classify_materials_svm`.
    hidden_layer_sizes : tuple of int, default=(53,)
        The paper's optimum: one hidden layer of 53 neurons.
    activation : str, default='tanh'
    solver : str, default='gd'
        Full-batch gradient descent, as in the paper.
    learning_rate_init : float, default=0.05
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
    _check_fractions(fractions)
    order = _label_order(y, labels)
    if normalise:
        X = normalise_by_max(X)
    train, val, test = _three_way_split(X.shape[0], fractions, seed, stratify=y)
    model = MLPClassifier(hidden_layer_sizes=hidden_layer_sizes, activation=activation,
                          solver=solver, learning_rate_init=learning_rate_init, max_iter=1,
                          random_state=seed, warm_start=True, alpha=0.0)
    start = time.perf_counter()
    best, best_loss, since = None, np.inf, 0
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
                    break
    model.coefs_, model.intercepts_ = best
    seconds = time.perf_counter() - start
    parts = {"train": train, "validation": val, "test": test, "all": np.arange(X.shape[0])}
    confusions = {k: confusion_matrix(y[i], model.predict(X[i]), order) for k, i in parts.items()}
    logger.info("ANN: all %.3f, test %.3f after %d epochs", accuracy(confusions["all"]),
                accuracy(confusions["test"]), model.n_iter_)
    return ClassificationResult("ann", order, confusions, seconds, model)


# -------------------------------------------------------------------------- regression
def _regression(name, X, d, model, fractions, seed, min_max) -> RegressionResult:
    train, val, test = _three_way_split(X.shape[0], fractions, seed)
    fit_rows = np.concatenate([train, val])
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
    return RegressionResult(name, truth, pred, positions, mean_err, seconds, model)


def regress_distance_linear_region(X, distances, *, probe_length, fraction_of_length=0.8,
                                   hidden_layer_sizes=(20, 20), activation="tanh", solver="gd",
                                   learning_rate_init=0.01, max_iter=2000,
                                   fractions=(0.70, 0.15, 0.15), seed=0, normalise=True):
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
        Divide ``X`` by its largest magnitude first.

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
    _check_fractions(fractions)
    keep = d <= fraction_of_length * probe_length
    if keep.sum() < 10:
        raise ValueError("fewer than 10 samples lie within fraction_of_length of the hinge")
    X, d = X[keep], d[keep]
    if normalise:
        X = normalise_by_max(X)
    model = MLPRegressor(hidden_layer_sizes=hidden_layer_sizes, activation=activation,
                         solver=solver, learning_rate_init=learning_rate_init, max_iter=max_iter,
                         random_state=seed, alpha=0.0, n_iter_no_change=20)
    return _regression(f"{'x'.join(map(str, hidden_layer_sizes))} {activation} ({solver}), "
                       f"first {100 * fraction_of_length:.0f} % of the probe",
                       X, d, model, fractions, seed, min_max=False)


def regress_distance_full_length(X, distances, *, hidden_layer_sizes=(9,), activation="relu",
                                 solver="scg", max_iter=1000, fractions=(0.70, 0.15, 0.15),
                                 seed=0):
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
    _check_fractions(fractions)
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
    """
    m = np.asarray(matrix)
    width = max(6, *(len(str(lab)) for lab in labels), len(str(int(m.max()))))
    head = "true \\ predicted".ljust(16) + "".join(str(lab).rjust(width + 1) for lab in labels)
    rows = [str(lab).ljust(16) + "".join(str(int(v)).rjust(width + 1) for v in row)
            for lab, row in zip(labels, m, strict=True)]
    return "\n".join([head, *rows])


def _reorder(paper: PaperConfusion, split: str, labels) -> tuple[np.ndarray, tuple]:
    """The paper's matrix in ``labels`` order when the names match, else as printed."""
    m = paper.matrices[split]
    if set(labels) == set(paper.labels):
        pos = [paper.labels.index(lab) for lab in labels]
        return m[np.ix_(pos, pos)], tuple(labels)
    return m, paper.labels


def _draw_matrix(ax, m, labels, title):
    m = np.asarray(m)
    rows = m.sum(axis=1, keepdims=True)
    share = np.divide(m, rows, out=np.zeros(m.shape), where=rows > 0)
    ax.imshow(share, cmap="Blues", vmin=0, vmax=1)
    for (i, j), v in np.ndenumerate(m):
        ax.text(j, i, str(int(v)), ha="center", va="center", fontsize=8,
                color="white" if share[i, j] > 0.6 else "black")
    ax.set_xticks(range(len(labels)), labels, rotation=45, ha="right")
    ax.set_yticks(range(len(labels)), labels)
    ax.set_xlabel("predicted class")
    ax.set_ylabel("true class")
    ax.set_title(f"{title}\naccuracy {100 * accuracy(m):.1f} %", fontsize=9)


def plot_confusion_comparison(result: ClassificationResult, paper: PaperConfusion | None = None):
    """Our confusion matrices beside the paper's printed ones.

    Parameters
    ----------
    result : ClassificationResult
    paper : PaperConfusion, optional
        Default: :data:`PAPER_SVM` for an SVM result, :data:`PAPER_ANN` for an ANN result.

    Returns
    -------
    matplotlib.figure.Figure
        Top row: this run; bottom row: the paper, for each split the paper prints.

    Examples
    --------
    >>> res = ClassificationResult("ann", PAPER_ANN.labels, {"all": PAPER_ANN.matrices["all"]},
    ...                            0.0)
    >>> fig = plot_confusion_comparison(res)
    >>> len(fig.axes)
    2
    """
    from matplotlib.figure import Figure

    if paper is None:
        paper = PAPER_SVM if result.method == "svm" else PAPER_ANN
    splits = list(paper.matrices)
    fig = Figure(figsize=(4.2 * len(splits), 8.0), layout="constrained")
    axes = fig.subplots(2, len(splits), squeeze=False)
    for col, split in enumerate(splits):
        ours = result.confusions.get(split)
        if ours is None:
            axes[0, col].set_axis_off()
            axes[0, col].set_title(f"no '{split}' split in this run", fontsize=9)
        else:
            _draw_matrix(axes[0, col], ours, result.labels,
                         f"this run, {result.method.upper()} {split}")
        m, labs = _reorder(paper, split, result.labels)
        printed = paper.reported_accuracy.get(split)
        note = "" if printed is None else f" (printed {100 * printed:.1f} %)"
        _draw_matrix(axes[1, col], m, labs, f"paper {paper.figure}, {split}{note}")
    return fig


def plot_distance_errors(*results: RegressionResult):
    """Mean absolute error (cm) along the probe for one or more regressions.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> r = RegressionResult("net", np.array([0.1, 0.2]), np.array([0.11, 0.2]),
    ...                      np.array([0.1, 0.2]), np.array([1.0, 0.0]), 0.0)
    >>> fig = plot_distance_errors(r)
    >>> fig.axes[0].get_xlabel()
    'contact distance from the hinge (cm)'
    """
    from matplotlib.figure import Figure

    if not results:
        raise ValueError("plot_distance_errors needs at least one RegressionResult")
    fig = Figure(figsize=(7.0, 4.0), layout="constrained")
    ax = fig.subplots()
    for r in results:
        ax.plot(100 * r.distance_test, r.errors_cm, ".", alpha=0.25, ms=3)
        ax.plot(100 * r.positions, r.mean_error_cm, "-o", ms=3,
                label=f"{r.name}: MAE {r.mae_cm:.2f} cm", color=ax.lines[-1].get_color())
    ax.set_xlabel("contact distance from the hinge (cm)")
    ax.set_ylabel("absolute error (cm)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return fig
