"""Sparse feature matrices (:mod:`scipy.sparse`, CSR) in the kernels, without cancellation.

The dense kernels (:mod:`ebantenna.ml.kernels`) keep the expansion
:math:`\\lVert x\\rVert^2 + \\lVert y\\rVert^2 - 2\\, x\\cdot y` of the RBF kernel free of
cancellation by centring the points once on their mean. Centring a sparse matrix fills it: every
zero becomes :math:`-m_k`, and the memory and products that sparsity saves are gone. Sparse rows
are therefore expanded about the origin, as libsvm does, and every entry that the expansion
cannot be trusted with is computed again from direct differences.

**Which entries.** Let :math:`n_x, n_y` be the stored entries of the rows :math:`x, y` and
:math:`m = \\max(n_x, n_y)`. The norms are sums of :math:`n_x` and :math:`n_y` squares, the dot
product a sum of at most :math:`m` products, and the expansion adds two more roundings; to first
order in the unit roundoff :math:`u = 2^{-53}` the computed squared distance :math:`\\hat d`
obeys

.. math:: |\\hat d - \\lVert x - y\\rVert^2| \\le b_{xy} = (m + 3)\\, u\\,
          (\\lVert x\\rVert + \\lVert y\\rVert)^2

(:math:`m + 2` from the sums and additions, one more for using the computed norms in the bound).
Where :math:`b_{xy} \\le \\eta\\, \\hat d` with :math:`\\eta = 2^{-30} \\approx 9.3\\times
10^{-10}` (:data:`ETA`) the expanded value is kept: its relative error is at most
:math:`\\eta / (1 - \\eta)`. Elsewhere (near-duplicate rows, rows far from the origin compared with
their distance) the entry is recomputed as :math:`\\sum_k (x_k - y_k)^2` over the union of the
stored entries: one rounding per difference, two per square and :math:`n_x + n_y` additions,
a relative error of at most :math:`(n_x + n_y + 2)\\, u`. Every squared distance from sparse rows
is therefore within :math:`\\max(\\eta, (n_x + n_y + 2) u)` of the exact one, relative: a bound
on the distance itself (the dense path's is relative to the spread of the data), independent of
any offset of the features. Through :math:`K = e^{-\\gamma d}` it moves a kernel value by at most
:math:`\\gamma K \\eta d \\le \\eta / e \\approx 3.4\\times 10^{-10}`: below the float32 storage of
the kernel (:math:`6\\times 10^{-8}`) and far below any SMO tolerance, while a smaller
:math:`\\eta` would send more entries to the slower direct path.

Why not centre dense copies of bounded row blocks instead: that would spend the dense arithmetic
(all :math:`p` products of every pair) and :math:`p` floats per row on data that are mostly
zeros, for every entry, where the bound above singles out the few entries that need more care.
Only the entries that need it are recomputed, in chunks of at most :data:`CHUNK` pairs (their
differences are sparse matrices of that many rows), so memory stays bounded; on typical sparse
data those are the diagonal of a training kernel and the duplicates. With ``center=False``
(libsvm's training arithmetic, used by ``libsvm_compat``) nothing is recomputed.

Examples
--------
Two rows far from the origin, at distance 1: the expansion loses the distance entirely (the first
squared norm, :math:`10^{16} + 1`, is no float64 and rounds to :math:`10^{16}`), the direct
difference keeps it.

>>> import numpy as np
>>> X = as_csr(np.array([[1e8, 0.0, 1.0], [1e8, 0.0, 2.0]]))
>>> n = squared_norms_sparse(X)
>>> d = np.maximum(n[:1, None] + n[None, 1:] - 2.0 * (X[:1] @ X[1:].T).toarray(), 0.0)
>>> d
array([[0.]])
>>> recompute_cancelled(d, X[:1], X[1:], n[:1], n[1:])
1
>>> d
array([[1.]])
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = [
    "ETA",
    "CHUNK",
    "as_csr",
    "squared_norms_sparse",
    "sparse_variance",
    "recompute_cancelled",
]

#: Unit roundoff of float64.
U = np.finfo(np.float64).eps / 2
#: Relative accuracy to which the expansion's squared distances are trusted; entries whose error
#: bound exceeds it are recomputed from direct differences.
ETA = 2.0**-30
#: Most pairs recomputed at once (bounds the memory of their sparse differences).
CHUNK = 1 << 14


def as_csr(X) -> sp.csr_matrix:
    """``X`` as a float64 CSR matrix with sorted, summed indices (a copy only when needed).

    Examples
    --------
    >>> as_csr(np.eye(2)).nnz
    2
    """
    if not (sp.issparse(X) and X.format == "csr" and X.dtype == np.float64):
        if not sp.issparse(X):
            from .._validate import real_array

            X = real_array("X", X)  # refused by name: strings, objects, complex, ragged
            if X.ndim != 2:
                raise ValueError(f"X must be 2-D (one point per row), got shape {X.shape}")
        elif X.dtype.kind not in "fiub":
            raise TypeError(f"X must hold real numbers, got a sparse matrix of {X.dtype}")
        X = sp.csr_matrix(X, dtype=np.float64)
    if not X.has_canonical_format:
        X = X.copy()
        X.sum_duplicates()
    return X


def _check_csr(X, name: str = "X") -> None:
    """Refuse anything but a CSR matrix (in :func:`as_csr` form), naming ``name``."""
    if not (sp.issparse(X) and X.format == "csr"):
        raise TypeError(f"{name} must be a CSR matrix (see as_csr), got {type(X).__name__}")


def _row_of_entries(X) -> np.ndarray:
    return np.repeat(np.arange(X.shape[0]), np.diff(X.indptr))


def squared_norms_sparse(X) -> np.ndarray:
    """Row-wise squared norms of a CSR matrix (float64), summed over the stored entries.

    Examples
    --------
    >>> squared_norms_sparse(sp.csr_matrix(np.array([[3.0, 4.0], [0.0, 0.0]])))
    array([25.,  0.])
    """
    _check_csr(X)
    return np.bincount(_row_of_entries(X), weights=X.data * X.data, minlength=X.shape[0])


def sparse_variance(X) -> float:
    """Variance of every entry of a CSR matrix in :func:`as_csr` form (zeros included), as
    ``X.toarray().var()``.

    Two passes over the stored entries,
    :math:`\\frac1N\\bigl(\\sum (x - \\mu)^2 + z\\,\\mu^2\\bigr)` with :math:`z` the zeros: no
    cancellation, unlike :math:`E[x^2] - E[x]^2`.

    Examples
    --------
    >>> sparse_variance(sp.csr_matrix(np.array([[0.0, 2.0], [2.0, 0.0]])))
    1.0
    """
    _check_csr(X)
    total = X.shape[0] * X.shape[1]
    data = X.data
    mean = float(data.sum()) / total
    dev = data - mean
    return (float(dev @ dev) + (total - data.size) * mean * mean) / total


def recompute_cancelled(d, X, Y, x_norms, y_norms) -> int:
    """Recompute in place the squared distances that the expansion cannot be trusted with.

    Parameters
    ----------
    d : ndarray of shape (n, m)
        Squared distances of the rows of ``X`` to those of ``Y`` from the expansion (clipped at
        0); changed in place.
    X, Y : csr_matrix of shapes (n, p) and (m, p)
        The rows, in :func:`as_csr` form.
    x_norms, y_norms : ndarray
        Their :func:`squared_norms_sparse`, as used in the expansion.

    Returns
    -------
    int
        How many entries were recomputed.
    """
    _check_csr(X, "X")
    _check_csr(Y, "Y")
    if X.shape[1] != Y.shape[1]:
        raise ValueError(f"Y must have the {X.shape[1]} columns of X, got {Y.shape[1]}")
    if not (isinstance(d, np.ndarray) and d.shape == (X.shape[0], Y.shape[0])
            and d.dtype == np.float64 and d.flags.writeable):
        raise ValueError(f"d must be a writeable float64 array of shape (rows of X, rows of Y) "
                         f"= {(X.shape[0], Y.shape[0])} (it is changed in place), got "
                         f"{type(d).__name__} {getattr(d, 'shape', '')}")
    for name, norms, size in (("x_norms", x_norms, X.shape[0]), ("y_norms", y_norms, Y.shape[0])):
        if np.shape(norms) != (size,):
            raise ValueError(f"{name} must hold one squared norm per row ({size}), got shape "
                             f"{np.shape(norms)}")
    x_nnz, y_nnz = np.diff(X.indptr), np.diff(Y.indptr)
    bound = (np.maximum.outer(x_nnz, y_nnz) + 3) * U
    bound *= (np.sqrt(x_norms)[:, None] + np.sqrt(y_norms)[None, :]) ** 2
    rows, cols = np.nonzero(bound > ETA * d)
    for start in range(0, rows.size, CHUNK):
        i, j = rows[start : start + CHUNK], cols[start : start + CHUNK]
        diff = X[i] - Y[j]  # one rounding per difference, over the union of stored entries
        d[i, j] = squared_norms_sparse(diff)
    return int(rows.size)
