"""Classification and regression scores used by the paper's experiments.

Written out in NumPy so that each number can be followed by hand; the tests check them against
:mod:`sklearn.metrics`.
"""

from __future__ import annotations

import numpy as np

__all__ = ["confusion_matrix", "accuracy", "per_class_rates", "absolute_errors"]


def confusion_matrix(y_true, y_pred, labels) -> np.ndarray:
    """Counts ``C[i, j]`` of samples of true class ``labels[i]`` predicted as ``labels[j]``.

    Parameters
    ----------
    y_true, y_pred : array-like of shape (n,)
        True and predicted labels.
    labels : sequence
        Class order of the rows and columns. Samples whose labels are not listed are ignored.

    Returns
    -------
    ndarray of shape (n_labels, n_labels), int64

    Examples
    --------
    >>> confusion_matrix(["al", "al", "pvc"], ["al", "pvc", "pvc"], labels=["al", "pvc"])
    array([[1, 1],
           [0, 1]])
    """
    y_true = np.asarray(y_true)
    y_pred = np.asarray(y_pred)
    if y_true.shape != y_pred.shape or y_true.ndim != 1:
        raise ValueError(f"y_true and y_pred must be 1-D of equal length, got shapes "
                         f"{y_true.shape} and {y_pred.shape}")
    labels = np.asarray(labels)
    if labels.ndim != 1 or labels.size == 0:
        raise ValueError(f"labels must be a non-empty 1-D sequence, got {labels!r}")
    if np.unique(labels).size != labels.size:
        raise ValueError(f"labels must be distinct, got {labels.tolist()!r}")
    k = labels.size
    order = np.argsort(labels)
    sorted_labels = labels[order]

    def index(values):
        pos = np.searchsorted(sorted_labels, values)
        pos = np.clip(pos, 0, k - 1)
        found = sorted_labels[pos] == values
        return np.where(found, order[pos], -1)

    ti, pi = index(y_true), index(y_pred)
    ok = (ti >= 0) & (pi >= 0)
    out = np.zeros((k, k), dtype=np.int64)
    np.add.at(out, (ti[ok], pi[ok]), 1)
    return out


def accuracy(matrix) -> float:
    """Fraction of correct predictions: trace over total of a confusion matrix.

    Examples
    --------
    >>> accuracy(np.array([[3, 1], [0, 4]]))
    0.875
    """
    m = np.asarray(matrix, dtype=np.float64)
    total = m.sum()
    if total <= 0:
        raise ValueError("matrix must contain at least one sample")
    return float(np.trace(m) / total)


def per_class_rates(matrix) -> tuple[np.ndarray, np.ndarray]:
    """Recall (per true class, row-wise) and precision (per predicted class, column-wise).

    Classes without samples get NaN-free zeros.

    Examples
    --------
    >>> recall, precision = per_class_rates(np.array([[3, 1], [0, 4]]))
    >>> recall, precision
    (array([0.75, 1.  ]), array([1. , 0.8]))
    """
    m = np.asarray(matrix, dtype=np.float64)
    rows, cols = m.sum(axis=1), m.sum(axis=0)
    diag = np.diag(m)
    recall = np.divide(diag, rows, out=np.zeros_like(diag), where=rows > 0)
    precision = np.divide(diag, cols, out=np.zeros_like(diag), where=cols > 0)
    return recall, precision


def absolute_errors(y_true, y_pred) -> np.ndarray:
    """Absolute errors :math:`|\\hat y - y|` in the units of ``y`` (finite arrays of equal shape).

    Examples
    --------
    >>> absolute_errors([0.25, 0.5], [0.5, 0.375])
    array([0.25 , 0.125])
    """
    a = np.asarray(y_true, dtype=np.float64)
    b = np.asarray(y_pred, dtype=np.float64)
    if a.shape != b.shape:
        raise ValueError(f"y_true and y_pred must have equal shapes, got {a.shape} and {b.shape}")
    return np.abs(b - a)
