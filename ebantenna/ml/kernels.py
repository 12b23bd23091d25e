"""Kernel functions of the support vector machine, computed with BLAS.

A kernel :math:`k(x, x')` measures the similarity of two feature vectors. The three kernels offered
are the ones scikit-learn's :class:`sklearn.svm.SVC` and libsvm call by the same names:

=========== ===========================================================
linear      :math:`k(x, x') = x \\cdot x'`
rbf         :math:`k(x, x') = \\exp(-\\gamma \\lVert x - x' \\rVert^2)`
poly        :math:`k(x, x') = (\\gamma\\, x \\cdot x' + r)^d`
=========== ===========================================================

Every Gram matrix is built from one matrix product (a GEMM), so a whole block of kernel entries
costs about as much as the dot products it needs, instead of one call per entry. The RBF kernel uses
libsvm's expansion :math:`\\lVert x\\rVert^2 + \\lVert x'\\rVert^2 - 2\\, x\\cdot x'`, which is what
lets a NumPy solver reproduce libsvm's training kernel bit for bit once rounded to float32.

:class:`KernelRows` hands the SMO solver the rows of a training kernel: it either holds the whole
matrix (one GEMM) or keeps a least-recently-used cache of rows computed on demand.
"""

from __future__ import annotations

import logging
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np

from .._validate import check_choice, check_int, check_real

__all__ = ["KERNELS", "Kernel", "KernelRows", "resolve_gamma", "gram_matrix", "squared_norms"]

logger = logging.getLogger(__name__)

#: Names of the kernels, as scikit-learn spells them.
KERNELS = ("linear", "rbf", "poly")


def resolve_gamma(gamma, X: np.ndarray) -> float:
    """The numeric kernel width for ``gamma`` as scikit-learn interprets it.

    Parameters
    ----------
    gamma : {'scale', 'auto'} or float
        ``'scale'`` gives ``1 / (n_features * X.var())`` (1 if the variance is zero), ``'auto'``
        gives ``1 / n_features``, a number is used as it is (it must be >= 0).
    X : ndarray of shape (n_samples, n_features)
        Training features.

    Returns
    -------
    float
        The kernel coefficient :math:`\\gamma` (in units of 1 / feature²).

    Examples
    --------
    >>> import numpy as np
    >>> resolve_gamma("auto", np.zeros((3, 4)))
    0.25
    >>> resolve_gamma("scale", np.array([[0.0, 2.0], [2.0, 0.0]]))
    0.5
    """
    if isinstance(gamma, str):
        check_choice("gamma", gamma, ("scale", "auto"))
        if gamma == "auto":
            return 1.0 / X.shape[1]
        var = float(X.var())
        return 1.0 / (X.shape[1] * var) if var != 0 else 1.0
    value = check_real("gamma", gamma)
    if value < 0:
        raise ValueError(f"gamma must be >= 0, 'scale' or 'auto'; got {gamma!r}")
    return value


def squared_norms(X: np.ndarray) -> np.ndarray:
    """Row-wise squared Euclidean norms :math:`\\lVert x_i \\rVert^2` (float64).

    Examples
    --------
    >>> squared_norms(np.array([[3.0, 4.0], [1.0, 0.0]]))
    array([25.,  1.])
    """
    return np.einsum("ij,ij->i", X, X)


@dataclass(frozen=True)
class Kernel:
    """A kernel function with its parameters.

    Parameters
    ----------
    name : {'linear', 'rbf', 'poly'}
        Kernel type.
    gamma : float
        Coefficient :math:`\\gamma` of 'rbf' and 'poly' (1 / feature²), >= 0.
    degree : int
        Degree :math:`d` of 'poly', >= 0.
    coef0 : float
        Constant term :math:`r` of 'poly'.

    Examples
    --------
    >>> k = Kernel("rbf", gamma=0.5)
    >>> X = np.array([[0.0, 0.0], [1.0, 1.0]])
    >>> np.round(k.gram(X), 6)
    array([[1.      , 0.367879],
           [0.367879, 1.      ]])
    >>> k.diagonal(X)
    array([1., 1.])
    """

    name: str = "rbf"
    gamma: float = 1.0
    degree: int = 3
    coef0: float = 0.0

    def __post_init__(self):
        check_choice("kernel", self.name, KERNELS)
        if check_real("gamma", self.gamma) < 0:
            raise ValueError(f"gamma must be >= 0, got {self.gamma!r}")
        check_int("degree", self.degree, minimum=0)
        check_real("coef0", self.coef0)

    def gram(
        self,
        X: np.ndarray,
        Y: np.ndarray | None = None,
        *,
        x_norms: np.ndarray | None = None,
        y_norms: np.ndarray | None = None,
        dtype=np.float64,
    ) -> np.ndarray:
        """Kernel matrix :math:`K_{ij} = k(x_i, y_j)`, computed in float64, returned as ``dtype``.

        With ``Y`` omitted the matrix of ``X`` with itself is returned; for 'rbf' its diagonal is
        then set to exactly 1, the value :math:`\\exp(0)` that rounding in the expansion can miss.
        """
        same = Y is None
        Y = X if same else Y
        if self.name == "rbf":
            xn = squared_norms(X) if x_norms is None else x_norms
            yn = (xn if same else squared_norms(Y)) if y_norms is None else y_norms
        out = np.empty((X.shape[0], Y.shape[0]), dtype=dtype)
        # Row blocks of about 4 MB keep the float64 intermediates in cache. For the matrix of X
        # with itself only the blocks on and above the diagonal are computed (half the
        # products and exponentials) and mirrored.
        step = max(1, (1 << 19) // max(1, Y.shape[0]))
        for start in range(0, X.shape[0], step):
            stop = min(start + step, X.shape[0])
            first = start if same else 0
            block = X[start:stop] @ Y[first:].T
            if self.name == "poly":
                block *= self.gamma
                block += self.coef0
                block **= self.degree
            elif self.name == "rbf":
                # libsvm's order of operations: exp(-gamma * (|x|^2 + |y|^2 - 2 x.y))
                block *= -2.0
                block += xn[start:stop, None] + yn[None, first:]
                np.maximum(block, 0.0, out=block)
                block *= -self.gamma
                np.exp(block, out=block)
            out[start:stop, first:] = block
            if same and stop < X.shape[0]:
                out[stop:, start:stop] = out[start:stop, stop:].T
        if same and self.name == "rbf":
            np.fill_diagonal(out, 1.0)
        return out

    def diagonal(self, X: np.ndarray) -> np.ndarray:
        """The diagonal :math:`k(x_i, x_i)` in float64 (exactly 1 for 'rbf')."""
        if self.name == "rbf":
            return np.ones(X.shape[0])
        sq = squared_norms(X)
        if self.name == "linear":
            return sq
        return (self.gamma * sq + self.coef0) ** self.degree


def gram_matrix(X, Y=None, *, kernel="rbf", gamma=1.0, degree=3, coef0=0.0) -> np.ndarray:
    """Kernel matrix between the rows of ``X`` and ``Y`` (float64).

    Examples
    --------
    >>> gram_matrix(np.eye(2), kernel="linear")
    array([[1., 0.],
           [0., 1.]])
    """
    X = np.asarray(X, dtype=np.float64)
    Y = None if Y is None else np.asarray(Y, dtype=np.float64)
    return Kernel(kernel, gamma=gamma, degree=degree, coef0=coef0).gram(X, Y)


class KernelRows:
    """Rows of the kernel matrix of ``X`` with itself, stored or cached.

    Parameters
    ----------
    X : ndarray of shape (n, n_features)
        Training points (float64).
    kernel : Kernel
        The kernel function.
    dtype : numpy dtype
        Storage type of the rows (float32 as libsvm, or float64).
    cache_bytes : int
        Memory allowed for kernel rows, in bytes. If the whole matrix fits it is computed at once
        with one matrix product; otherwise rows are computed on demand and the least recently used
        ones are dropped.
    full : ndarray of shape (N, N), optional
        A precomputed kernel matrix to use as it is.
    parts : sequence of slice, optional
        With ``full``: the problem's points are the rows of ``full`` in these slices, one after
        the other (the classes of a one-vs-one pair). Rows are then assembled from the slices on
        demand instead of copying the block.

    Examples
    --------
    >>> X = np.array([[0.0], [1.0], [3.0]])
    >>> rows = KernelRows(X, Kernel("linear"), np.float64, cache_bytes=8)
    >>> rows.is_full
    False
    >>> rows.row(2)
    array([0., 3., 9.])
    """

    def __init__(self, X, kernel: Kernel, dtype, cache_bytes: int, full=None, parts=None):
        self.X = X
        self.kernel = kernel
        self.dtype = np.dtype(dtype)
        self._norms = squared_norms(X) if X is not None else None
        self._parts = None
        if full is not None and parts is not None:
            parts = list(parts)
            self.matrix = full
            self.n = sum(p.stop - p.start for p in parts)
            # row i of the problem is row _rows[i] of `full`; touching slices are merged
            self._rows = np.concatenate([np.arange(p.start, p.stop) for p in parts])
            merged = [parts[0]]
            for p in parts[1:]:
                if p.start == merged[-1].stop:
                    merged[-1] = slice(merged[-1].start, p.stop)
                else:
                    merged.append(p)
            self._parts = merged
            self.rows_computed = 0
            return
        self.n = X.shape[0] if full is None else full.shape[0]
        if full is not None:
            self.matrix = np.asarray(full, dtype=self.dtype)
        elif self.n * self.n * self.dtype.itemsize <= cache_bytes:
            self.matrix = kernel.gram(X, x_norms=self._norms, dtype=self.dtype)
        else:
            self.matrix = None
            self._cache: OrderedDict[int, np.ndarray] = OrderedDict()
            row_bytes = self.n * self.dtype.itemsize
            self._capacity = max(2, int(cache_bytes // row_bytes))
            logger.info("kernel of %d points does not fit: caching %d rows", self.n,
                        self._capacity)
        self.rows_computed = 0

    @property
    def is_full(self) -> bool:
        """True when the whole matrix is stored."""
        return self.matrix is not None

    def row64(self, i: int) -> np.ndarray:
        """Kernel row :math:`k(x_i, x_t)` as float64 (a new array, or a view of float64 storage)."""
        if self._parts is not None:
            r = self.matrix[self._rows[i]]
            if len(self._parts) == 1:
                return r[self._parts[0]].astype(np.float64)
            return np.concatenate([r[p] for p in self._parts], dtype=np.float64)
        return np.asarray(self.row(i), dtype=np.float64)

    def row(self, i: int) -> np.ndarray:
        """Kernel row :math:`k(x_i, x_t)` for all t, in the storage type."""
        if self._parts is not None:
            r = self.matrix[self._rows[i]]
            if len(self._parts) == 1:
                return r[self._parts[0]]
            return np.concatenate([r[p] for p in self._parts])
        if self.matrix is not None:
            return self.matrix[i]
        cached = self._cache.get(i)
        if cached is not None:
            self._cache.move_to_end(i)
            return cached
        r = self.kernel.gram(self.X[i : i + 1], self.X, x_norms=self._norms[i : i + 1],
                             y_norms=self._norms, dtype=self.dtype)[0]
        if self.kernel.name == "rbf":
            r[i] = 1.0
        self.rows_computed += 1
        self._cache[i] = r
        if len(self._cache) > self._capacity:
            self._cache.popitem(last=False)
        return r
