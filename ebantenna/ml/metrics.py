"""Classification and regression scores used by the paper's experiments.

Written out in NumPy so that each number can be followed by hand; the tests check them against
:mod:`sklearn.metrics`.
"""

from __future__ import annotations

import numpy as np

from .._validate import describe, real_array

__all__ = [
    "confusion_matrix", "accuracy", "accuracy_interval", "per_class_rates", "absolute_errors"
]


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
    m = _confusion(matrix)
    total = m.sum()
    if total <= 0:
        raise ValueError("matrix must contain at least one sample")
    return float(np.trace(m) / total)


def _confusion(matrix) -> np.ndarray:
    """``matrix`` as a float array if it is a square matrix of finite, non-negative, whole
    counts; else an error naming ``matrix``."""
    m = real_array("matrix", matrix)
    if m.ndim != 2 or m.shape[0] != m.shape[1] or m.size == 0:
        raise ValueError(f"matrix must be a square confusion matrix, got shape {m.shape}")
    if not np.all(np.isfinite(m)) or np.any(m < 0) or np.any(m != np.floor(m)):
        raise ValueError("matrix must hold finite, non-negative, whole counts")
    return m


#: The largest count a float64 holds exactly: the interval is computed in floats.
_EXACT_COUNT = 2**53


def _count(name: str, value) -> int:
    """``value`` as a whole count: an integer, or a float with no fractional part; a fraction
    (3.7 recordings), a bool or a non-number is refused, naming ``name``."""
    if isinstance(value, bool) or not isinstance(value, int | np.integer | float | np.floating):
        raise TypeError(f"{name} must be a whole count, got {describe(value)} "
                        f"({type(value).__name__})")
    if isinstance(value, float | np.floating):
        if not np.isfinite(value) or value != np.floor(value):
            raise ValueError(f"{name} must be a whole count, got {describe(value)}")
    return int(value)


def accuracy_interval(correct: int, n: int, *, z: float = 1.959963984540054) -> tuple[float, float]:
    """Wilson score interval of an accuracy of ``correct`` out of ``n`` (95 % for the default z).

    Unlike the normal approximation :math:`p \\pm z\\sqrt{p(1-p)/n}`, Wilson's interval stays
    within [0, 1] and keeps much closer to its nominal coverage for small ``n`` and for
    accuracies near 0 or 1, though very near them it dips to about 84 % (Wilson 1927, *J. Am.
    Stat. Assoc.* 22:209; Brown, Cai & DasGupta 2001, *Statist. Sci.* 16:101). With :math:`p = k/n`,

    .. math:: \\frac{p + z^2/2n \\pm z\\sqrt{p(1-p)/n + z^2/4n^2}}{1 + z^2/n}.

    ``z`` defaults to the standard normal's 97.5 % quantile.

    Examples
    --------
    >>> lo, hi = accuracy_interval(80, 100)
    >>> round(lo, 4), round(hi, 4)
    (0.7112, 0.8666)
    >>> accuracy_interval(0, 7)[0], accuracy_interval(7, 7)[1]
    (0.0, 1.0)
    """
    correct, n = _count("correct", correct), _count("n", n)
    if n > _EXACT_COUNT:
        raise ValueError(f"n must be at most 2**53 (a count a float holds exactly), got "
                         f"{describe(n)}")
    if n < 1 or not 0 <= correct <= n:
        raise ValueError(f"need 0 <= correct <= n and n >= 1, got correct={correct}, n={n}")
    if not z > 0:
        raise ValueError(f"z must be > 0, got {z!r}")
    p = correct / n
    centre = p + z * z / (2 * n)
    half = z * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    scale = 1 + z * z / n
    # At k = 0 (k = n) the lower (upper) end is 0 (1) exactly; computed, it is off by rounding.
    low = 0.0 if correct == 0 else float((centre - half) / scale)
    high = 1.0 if correct == n else float((centre + half) / scale)
    return low, high


def per_class_rates(matrix) -> tuple[np.ndarray, np.ndarray]:
    """Recall (per true class, row-wise) and precision (per predicted class, column-wise).

    Classes without samples get NaN-free zeros.

    Examples
    --------
    >>> recall, precision = per_class_rates(np.array([[3, 1], [0, 4]]))
    >>> recall, precision
    (array([0.75, 1.  ]), array([1. , 0.8]))
    """
    m = _confusion(matrix)
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
    a = real_array("y_true", y_true)
    b = real_array("y_pred", y_pred)
    if a.shape != b.shape:
        raise ValueError(f"y_true and y_pred must have equal shapes, got {a.shape} and {b.shape}")
    for name, v in (("y_true", a), ("y_pred", b)):
        if not np.all(np.isfinite(v)):
            raise ValueError(f"{name} must contain only finite values (no NaN or inf)")
    return np.abs(b - a)
