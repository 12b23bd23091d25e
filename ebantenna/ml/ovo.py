"""One-vs-one bookkeeping of a multiclass SVM, in libsvm's (and scikit-learn's) layout.

With :math:`k` classes, one binary machine is trained per pair :math:`(a, b)`, :math:`a < b`, in
the order ``(0, 1), (0, 2), ..., (1, 2), ...``. The functions here turn the pairwise results into
one-vs-rest scores and, for the linear kernel, the weight vectors of the pairs; the pairs' votes,
which predict the class, are counted where it is predicted (:meth:`ebantenna.ml.SVC.predict`).
They take checked values: :class:`~ebantenna.ml.SVC` validates its input once, in ``fit`` and
``predict``.
"""

from __future__ import annotations

import numpy as np

__all__ = ["ovr_decision_function", "one_vs_one_coef", "dual_layout"]


def ovr_decision_function(predictions: np.ndarray, confidences: np.ndarray, n_classes: int):
    """One-vs-rest scores from one-vs-one results, aggregated as scikit-learn does.

    Each class gets its number of pairwise votes plus a tie-breaking term
    :math:`s / (3(|s| + 1))` in :math:`(-1/3, 1/3)`, where :math:`s` is its summed confidence.

    Parameters
    ----------
    predictions : ndarray of shape (n_samples, n_pairs)
        0 where the pair's first class won, 1 where the second did.
    confidences : ndarray of shape (n_samples, n_pairs)
        Confidence in the second class of each pair.
    n_classes : int
        Number of classes; the pairs are ``(0, 1), (0, 2), ..., (1, 2), ...``.

    Examples
    --------
    >>> ovr_decision_function(np.array([[0, 0, 1]]), np.array([[-1.0, -2.0, 0.5]]), 3)
    array([[ 2.25, -0.2 ,  0.8 ]])
    """
    from .._validate import check_array, check_int

    n_classes = check_int("n_classes", n_classes, minimum=2, maximum=10**4)
    pairs = n_classes * (n_classes - 1) // 2
    predictions = np.asarray(predictions)
    if predictions.dtype == bool:  # which class of each pair won: True is the second
        predictions = predictions.astype(np.int8)
    predictions = check_array("predictions", predictions, ndim=2, min_length=0)
    confidences = check_array("confidences", confidences, ndim=2, min_length=0)
    if predictions.shape[1] != pairs or not np.all((predictions == 0) | (predictions == 1)):
        raise ValueError(f"predictions must be 0 or 1 in one column per pair of the {n_classes} "
                         f"classes ({pairs}), got shape {predictions.shape}")
    if confidences.shape != predictions.shape:
        raise ValueError(f"confidences must have the shape of predictions "
                         f"{predictions.shape}, got {confidences.shape}")
    n = predictions.shape[0]
    votes = np.zeros((n, n_classes))
    conf = np.zeros((n, n_classes))
    k = 0
    for i in range(n_classes):
        for j in range(i + 1, n_classes):
            conf[:, i] -= confidences[:, k]
            conf[:, j] += confidences[:, k]
            votes[predictions[:, k] == 0, i] += 1
            votes[predictions[:, k] == 1, j] += 1
            k += 1
    return votes + conf / (3 * (np.abs(conf) + 1))


def one_vs_one_coef(dual_coef: np.ndarray, n_support: np.ndarray,
                    support_vectors: np.ndarray) -> np.ndarray:
    """Weight vectors :math:`w = \\sum_t y_t \\alpha_t x_t` of the pairwise linear machines.

    Parameters
    ----------
    dual_coef : ndarray of shape (n_classes - 1, n_SV)
        ``dual_coef_`` of a fitted :class:`~ebantenna.ml.SVC` (scikit-learn's layout and signs).
    n_support : ndarray of shape (n_classes,)
        Support vectors per class.
    support_vectors : ndarray of shape (n_SV, n_features)

    Returns
    -------
    ndarray of shape (1, n_features) for two classes, else (n_pairs, n_features)
        As scikit-learn's ``coef_``.

    Examples
    --------
    >>> one_vs_one_coef(np.array([[-0.5, 0.5]]), np.array([1, 1]), np.array([[0.0], [2.0]]))
    array([[1.]])
    """
    from .._validate import check_array

    dual_coef = check_array("dual_coef", dual_coef, ndim=2)
    if not (hasattr(support_vectors, "tocsr") and getattr(support_vectors, "ndim", 0) == 2):
        support_vectors = check_array("support_vectors", support_vectors, ndim=2)  # or sparse
    n_support = np.asarray(n_support)
    if (n_support.ndim != 1 or n_support.dtype.kind not in "iu" or n_support.size < 2
            or np.any(n_support < 0)):
        raise ValueError(f"n_support must be a 1-D array of counts (one per class, two at "
                         f"least), got {n_support!r:.60}")
    n_sv = int(n_support.sum())
    if dual_coef.shape != (n_support.size - 1, n_sv):
        raise ValueError(f"dual_coef must have shape (n_classes - 1, n_SV) = "
                         f"({n_support.size - 1}, {n_sv}), got {dual_coef.shape}")
    if support_vectors.shape[0] != n_sv:
        raise ValueError(f"support_vectors must hold the {n_sv} support vectors of n_support, "
                         f"got {support_vectors.shape[0]}")
    if dual_coef.shape[0] == 1:
        return dual_coef @ support_vectors
    bounds = np.concatenate([[0], np.cumsum(n_support)])
    k = n_support.shape[0]
    rows = []
    for a in range(k):
        sa = slice(bounds[a], bounds[a + 1])
        for b in range(a + 1, k):
            sb = slice(bounds[b], bounds[b + 1])
            rows.append(dual_coef[b - 1, sa] @ support_vectors[sa]
                        + dual_coef[a, sb] @ support_vectors[sb])
    return np.vstack(rows)


def dual_layout(n: int, members: list[np.ndarray], coefs: dict) -> tuple:
    """Arrange the pairwise dual solutions in libsvm's (and scikit-learn's) layout.

    Parameters
    ----------
    n : int
        Number of training points.
    members : list of ndarray
        Indices of the points of each class.
    coefs : dict
        ``coefs[a, b] = (idx, y_alpha)``: the points of the pair (class ``a`` first) and their
        :math:`y_t \\alpha_t`.

    Returns
    -------
    support : ndarray of int32
        Support vectors (nonzero in any pair), grouped by class.
    n_support : ndarray of int32, shape (n_classes,)
    dual : ndarray of shape (n_classes - 1, n_SV)
        Row ``b - 1`` holds the coefficients of class ``a``'s points in pair ``(a, b)``, row
        ``a`` those of class ``b``'s points (libsvm's signs: +1 for the pair's first class).

    Examples
    --------
    >>> pair = (np.array([0, 1, 2]), np.array([0.5, 0.0, -0.5]))
    >>> support, n_sv, dual = dual_layout(3, [np.array([0, 1]), np.array([2])], {(0, 1): pair})
    >>> support, n_sv, dual
    (array([0, 2], dtype=int32), array([1, 1], dtype=int32), array([[ 0.5, -0.5]]))
    """
    from .._validate import check_int

    n = check_int("n", n, minimum=1)
    if not isinstance(members, list | tuple) or len(members) < 2:
        raise TypeError("members must be a list of index arrays, one per class (two at least)")
    for c, m in enumerate(members):
        if (not isinstance(m, np.ndarray) or m.ndim != 1 or m.dtype.kind not in "iu"
                or (m.size and (m.min() < 0 or m.max() >= n))):
            raise ValueError(f"members[{c}] must be a 1-D integer array of indices below n={n}")
    k = len(members)
    if not isinstance(coefs, dict):
        raise TypeError(f"coefs must be a dict {{(a, b): (idx, y_alpha)}}, got "
                        f"{type(coefs).__name__}")
    for key, value in coefs.items():
        if (not isinstance(key, tuple) or len(key) != 2 or not 0 <= key[0] < key[1] < k
                or not isinstance(value, tuple) or len(value) != 2):
            raise ValueError(f"coefs must map pairs (a, b) of classes a < b < {k} to "
                             f"(idx, y_alpha), got the entry {key!r:.40}")
        idx, coef = np.asarray(value[0]), np.asarray(value[1])
        a, b = key
        if (idx.dtype.kind not in "iu" or idx.shape != coef.shape
                or idx.shape != (members[a].size + members[b].size,)):
            raise ValueError(f"coefs[{a}, {b}] must hold the points of classes {a} and {b} "
                             f"({members[a].size + members[b].size}) and one y_alpha each")
    nonzero = np.zeros(n, dtype=bool)
    for idx, coef in coefs.values():
        nonzero[idx[coef != 0]] = True
    sv_per_class = [m[nonzero[m]] for m in members]
    support = np.concatenate(sv_per_class)
    pos = np.full(n, -1)
    pos[support] = np.arange(support.size)
    dual = np.zeros((k - 1, support.size))
    for (a, b), (idx, coef) in coefs.items():
        na = members[a].size
        ia, ib = idx[:na], idx[na:]
        sa, sb = nonzero[ia], nonzero[ib]
        dual[b - 1, pos[ia[sa]]] = coef[:na][sa]
        dual[a, pos[ib[sb]]] = coef[na:][sb]
    n_support = np.array([c.size for c in sv_per_class], dtype=np.int32)
    return support.astype(np.int32), n_support, dual
