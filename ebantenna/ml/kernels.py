"""Kernel functions of the support vector machine, computed with BLAS.

A kernel :math:`k(x, x')` measures the similarity of two feature vectors. The four kernels offered
are the ones scikit-learn's :class:`sklearn.svm.SVC` and libsvm call by the same names:

=========== ===========================================================
linear      :math:`k(x, x') = x \\cdot x'`
rbf         :math:`k(x, x') = \\exp(-\\gamma \\lVert x - x' \\rVert^2)`
poly        :math:`k(x, x') = (\\gamma\\, x \\cdot x' + r)^d`
sigmoid     :math:`k(x, x') = \\tanh(\\gamma\\, x \\cdot x' + r)`
=========== ===========================================================

(:class:`~ebantenna.ml.SVC` also takes a precomputed kernel matrix or a callable.)

Every Gram matrix is built from one matrix product (a GEMM), so a whole block of kernel entries
costs about as much as the dot products it needs, instead of one call per entry. The RBF kernel
needs the squared distance, which a GEMM gives through the expansion
:math:`\\lVert x\\rVert^2 + \\lVert y\\rVert^2 - 2\\, x\\cdot y`.

**Cancellation, and how it is avoided.** The expansion subtracts numbers of size :math:`\\lVert
x\\rVert^2` to get one of size :math:`\\lVert x - y\\rVert^2`. If every feature carries a common
offset :math:`c` (a sensor bias, gravity), :math:`\\lVert x\\rVert^2` grows like :math:`c^2` while
the distance does not, and the rounding error of the sum, about :math:`u\\,c^2` (unit roundoff
:math:`u = 2^{-53}`), swamps it: at :math:`c = 10^6` the error is of order :math:`10^{-4}` on
distances of order 1. The distance itself does not depend on the origin, so :meth:`Kernel.gram`
first subtracts one common centre :math:`m` (the mean of the reference points) from both sets, then
expands. With :math:`\\tilde x = \\mathrm{fl}(x - m)`, :math:`p` features and first order in
:math:`u`, the computed squared distance :math:`\\hat d` obeys

.. math:: |\\hat d - \\lVert x - y\\rVert^2| \\le (p + 5)\\, u\\,
          (\\lVert \\tilde x\\rVert + \\lVert \\tilde y\\rVert)^2

(:math:`p + 3` for the three inner products and the two additions, 2 for rounding the centred
coordinates; the error of :math:`m` itself cancels because both sets use the same :math:`m`), and
the kernel value :math:`K = e^{-\\gamma d}` is off by at most :math:`\\gamma K |\\hat d - d| + u K`.
The bound now scales with the spread of the data about their mean, not with their distance from
the origin: a common shift of the features no longer changes the kernel beyond its last bits.
(It can still change the machine where SMO meets a near-tie: the shifted features themselves
carry rounding, and a last bit can pick another working set; the machine then stops elsewhere
within ``tol``.)

libsvm trains with the uncentred expansion (its ``Kernel::kernel_rbf``) and predicts with direct
differences (``Kernel::k_function``), so its training path changes when the features are shifted
(its decision values drift by about 2e-8 relative at a shift of :math:`10^3`, 2e-4 at :math:`10^6`;
exercise 11 shows it). ``center=False`` reproduces its training arithmetic on purpose; the
``libsvm_compat`` mode of :class:`~ebantenna.ml.SVC` uses it to follow libsvm's path and digits.

Sparse points (``scipy.sparse`` matrices, used as CSR) cannot be centred without filling them:
their rows are expanded about the origin and the entries whose error bound is not small against
the distance are recomputed from direct differences, which bounds every squared distance
*relative to itself* (:mod:`ebantenna.ml.sparse_input` gives the bound and the rule).

:class:`KernelRows` hands the SMO solver the rows of a training kernel: it either holds the whole
matrix (one GEMM) or keeps a least-recently-used cache of rows computed on demand
(:mod:`ebantenna.ml.pair_kernels` decides which, for each problem of a fit).
"""

from __future__ import annotations

import logging
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np
from scipy.sparse import issparse

from .._budget import check_allocation
from .._validate import check_choice, check_int, check_real, describe, real_array
from .sparse_input import as_csr, recompute_cancelled, sparse_variance, squared_norms_sparse

__all__ = ["KERNELS", "Kernel", "KernelRows", "resolve_gamma", "gram_matrix", "squared_norms",
           "call_kernel", "rbf_in_place", "GEMM_ENTRIES", "CACHE_ENTRIES"]

logger = logging.getLogger(__name__)

#: Most float64 entries of one matrix product of :meth:`Kernel.gram` (32 MB).
GEMM_ENTRIES = 1 << 22
#: Entries of the sub-blocks that the kernel function is applied to (512 kB, cache-resident).
CACHE_ENTRIES = 1 << 16

#: Names of the kernels, as scikit-learn spells them.
KERNELS = ("linear", "rbf", "poly", "sigmoid")


def resolve_gamma(gamma, X: np.ndarray) -> float:
    """The numeric kernel width for ``gamma`` as scikit-learn interprets it.

    Parameters
    ----------
    gamma : {'scale', 'auto'} or float
        ``'scale'`` gives ``1 / (n_features * X.var())`` (1 if the variance is zero), ``'auto'``
        gives ``1 / n_features``, a number is used as it is (it must be >= 0).
    X : ndarray or sparse matrix of shape (n_samples, n_features)
        Training features (for a sparse matrix, its zeros count in the variance).

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
        var = sparse_variance(as_csr(X)) if issparse(X) else float(X.var())
        return 1.0 / (X.shape[1] * var) if var != 0 else 1.0
    value = check_real("gamma", gamma)
    if value < 0:
        raise ValueError(f"gamma must be >= 0, 'scale' or 'auto'; got {gamma!r}")
    return value


def squared_norms(X) -> np.ndarray:
    """Row-wise squared Euclidean norms :math:`\\lVert x_i \\rVert^2` (float64) of an array or a
    CSR matrix.

    Examples
    --------
    >>> squared_norms(np.array([[3.0, 4.0], [1.0, 0.0]]))
    array([25.,  1.])
    """
    if issparse(X):
        return squared_norms_sparse(as_csr(X))
    X = real_array("X", X)
    if X.ndim != 2:
        raise ValueError(f"X must be 2-D (one point per row), got shape {X.shape}")
    return np.einsum("ij,ij->i", X, X)


@dataclass(frozen=True)
class Kernel:
    """A kernel function with its parameters.

    Parameters
    ----------
    name : {'linear', 'rbf', 'poly', 'sigmoid'}
        Kernel type.
    gamma : float
        Coefficient :math:`\\gamma` of 'rbf', 'poly' and 'sigmoid' (1 / feature²), >= 0.
    degree : int
        Degree :math:`d` of 'poly', >= 0.
    coef0 : float
        Constant term :math:`r` of 'poly' and 'sigmoid'.

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
        X,
        Y=None,
        *,
        x_norms: np.ndarray | None = None,
        y_norms: np.ndarray | None = None,
        dtype=np.float64,
        center: bool = True,
        out: np.ndarray | None = None,
    ) -> np.ndarray:
        """Kernel matrix :math:`K_{ij} = k(x_i, y_j)`, computed in float64, returned as ``dtype``.

        With ``Y`` omitted the matrix of ``X`` with itself is returned; for 'rbf' its diagonal is
        then set to exactly 1, the value :math:`\\exp(0)` that rounding in the expansion can miss.

        Parameters
        ----------
        X : ndarray or sparse matrix of shape (n, n_features)
        Y : ndarray or sparse matrix of shape (m, n_features), optional
            Reference points (default: ``X``). If either set is sparse, both are taken as CSR
            matrices (see :mod:`ebantenna.ml.sparse_input`).
        x_norms, y_norms : ndarray, optional
            Precomputed :func:`squared_norms` of ``X`` and ``Y`` for 'rbf'; for dense points only
            with ``center=False`` (they would be the norms of the uncentred points otherwise).
        dtype : numpy dtype
            Type of the returned matrix.
        center : bool
            For 'rbf', keep the squared distances free of cancellation: dense points are centred
            on the mean of the reference points before the expansion (see the module notes),
            sparse rows keep their sparsity and the entries the expansion cannot be trusted with
            are recomputed from direct differences (see :mod:`ebantenna.ml.sparse_input`).
            ``False`` expands the points as given, as libsvm trains.
        out : ndarray of shape (n, m), optional
            Where to write the matrix (``dtype`` is then its type), for example a block of a
            larger array. A float64 ``out`` of dense points receives the products directly,
            without the staging buffer; the numbers are the same.
        """
        same = Y is None
        X = _points("X", X)
        if not same:
            Y = _points("Y", Y)
            if Y.shape[1] != X.shape[1]:
                raise ValueError(f"Y must have the {X.shape[1]} features of X, got {Y.shape[1]}")
        X, Y, sparse, xn, yn = self._expansion_points(X, Y, x_norms, y_norms, center)
        if out is None:
            check_allocation(X.shape[0] * Y.shape[0] * np.dtype(dtype).itemsize,
                             parameter="X", what="the kernel matrix")
            out = np.empty((X.shape[0], Y.shape[0]), dtype=dtype)
        elif out.shape != (X.shape[0], Y.shape[0]):
            raise ValueError(f"out must have shape {(X.shape[0], Y.shape[0])}; got {out.shape}")
        direct = out.dtype == np.float64 and not sparse  # products straight into out
        # The products come in row blocks of up to GEMM_ENTRIES float64 (32 MB): tall enough for
        # BLAS to run near its peak. The kernel function is then applied to sub-blocks of about
        # 512 kB, which stay in cache through its five passes. For the matrix of X with itself
        # only the blocks on and above the diagonal are computed (half the products and
        # exponentials) and mirrored.
        step = max(1, GEMM_ENTRIES // max(1, Y.shape[0]))
        if same and direct:  # at least two strips: a quarter is computed needlessly, not half
            step = min(step, max(64, -(-X.shape[0] // 2)))
        # one buffer for every block: fresh memory per block would be faulted in page by page
        buffer = None if direct else np.empty(min(step, X.shape[0]) * Y.shape[0])
        # a block of a larger array is not contiguous, and NumPy is several times slower on it:
        # its sub-blocks go through a contiguous scratch
        largest = min(max(CACHE_ENTRIES, Y.shape[0]), X.shape[0] * Y.shape[0])  # of a sub-block
        scratch = np.empty(largest) if direct else None
        sums = np.empty(largest) if self.name == "rbf" else None  # of the norms, reused
        for start in range(0, X.shape[0], step):
            stop = min(start + step, X.shape[0])
            first = start if same else 0
            if direct:
                product = out[start:stop, first:]
            else:
                product = buffer[: (stop - start) * (Y.shape[0] - first)]
                product = product.reshape(stop - start, Y.shape[0] - first)
            if sparse:
                (X[start:stop] @ Y[first:].T).toarray(out=product)
            else:
                np.matmul(X[start:stop], Y[first:].T, out=product)
            if not (direct and self.name == "linear"):  # a linear kernel's products are in out
                self._apply_to_strip(product, out, (start, first), direct, scratch, sums,
                                     (X, Y, xn, yn, sparse and center))
            if same and stop < X.shape[0]:
                out[stop:, start:stop] = out[start:stop, stop:].T
        if same and self.name == "rbf":
            np.fill_diagonal(out, 1.0)
        return out

    def _expansion_points(self, X, Y, x_norms, y_norms, center):
        """The points that :meth:`gram` expands (CSR if either set is sparse, dense ones centred
        for 'rbf' with ``center``) and, for 'rbf', their squared norms:
        ``(X, Y, sparse, x_norms, y_norms)``; ``Y`` is ``X`` itself when omitted."""
        same = Y is None
        sparse = issparse(X) or (not same and issparse(Y))
        if sparse:
            X = as_csr(X)
            Y = X if same else as_csr(Y)
        Y = X if same else Y
        if self.name == "rbf" and center and not sparse:
            if x_norms is not None or y_norms is not None:
                raise ValueError("x_norms and y_norms can only be given with center=False")
            m = Y.mean(axis=0)
            X = X - m
            Y = X if same else Y - m
        if self.name != "rbf":
            return X, Y, sparse, None, None
        xn = squared_norms(X) if x_norms is None else x_norms
        yn = (xn if same else squared_norms(Y)) if y_norms is None else y_norms
        return X, Y, sparse, xn, yn

    def _apply_to_strip(self, product, out, corner, direct, scratch, sums, points) -> None:
        """The kernel function on a strip of dot products, in cache-sized sub-blocks, written
        to ``out`` from ``corner`` = (first row, first column); ``product`` is already that part
        of ``out`` when ``direct``. ``points`` = ``(X, Y, x_norms, y_norms, direct_differences)``
        as :meth:`gram` prepared them."""
        start, first = corner
        X, Y, xn, yn, differences = points
        sub = max(1, CACHE_ENTRIES // max(1, product.shape[1]))
        for lo in range(0, product.shape[0], sub):
            hi = min(lo + sub, product.shape[0])
            rows = slice(start + lo, start + hi)
            block = dest = product[lo:hi] if direct else out[rows, first:]
            if not direct:
                block = product[lo:hi]
            elif not block.flags.c_contiguous:
                block = scratch[: block.size].reshape(block.shape)
                block[...] = dest
            if self.name == "rbf":
                rbf_in_place(block, self.gamma, xn[rows], yn[first:],
                             (X[rows], Y[first:]) if differences else None, sums)
            else:
                self._dot_kernel_in_place(block)
            if block is not dest:
                dest[...] = block

    def _dot_kernel_in_place(self, block: np.ndarray) -> None:
        """'linear', 'poly' or 'sigmoid' of a block of dot products, in place."""
        if self.name == "poly":
            block *= self.gamma
            block += self.coef0
            block **= self.degree
        elif self.name == "sigmoid":
            block *= self.gamma
            block += self.coef0
            np.tanh(block, out=block)

    def diagonal(self, X: np.ndarray) -> np.ndarray:
        """The diagonal :math:`k(x_i, x_i)` in float64 (exactly 1 for 'rbf')."""
        X = _points("X", X)
        if self.name == "rbf":
            return np.ones(X.shape[0])
        sq = squared_norms(X)
        if self.name == "linear":
            return sq
        if self.name == "sigmoid":
            return np.tanh(self.gamma * sq + self.coef0)
        return (self.gamma * sq + self.coef0) ** self.degree


def rbf_in_place(block, gamma, x_norms, y_norms, sparse_rows=None, scratch=None) -> None:
    """Turn a block of dot products :math:`x \\cdot y` into RBF kernel values, in place.

    ``exp(-gamma * (|x|^2 + |y|^2 - 2 x.y))`` in libsvm's order of operations, the squared
    distance clipped at 0. With ``sparse_rows = (X, Y)`` (CSR) the entries that the expansion
    cannot be trusted with are recomputed first
    (:func:`~ebantenna.ml.sparse_input.recompute_cancelled`). ``scratch``, a float64 array of at
    least ``block.size`` entries, receives the sum of the norms instead of a fresh array (fresh
    memory is faulted in page by page at every call).

    Examples
    --------
    >>> block = np.array([[1.0, 0.0]])
    >>> rbf_in_place(block, 0.5, np.array([1.0]), np.array([1.0, 1.0]))
    >>> np.round(block, 6)
    array([[1.      , 0.367879]])
    """
    if not (isinstance(block, np.ndarray) and block.ndim == 2 and block.dtype == np.float64
            and block.flags.writeable):
        raise TypeError(f"block must be a writeable 2-D float64 array (it is changed in place), "
                        f"got {type(block).__name__} {getattr(block, 'dtype', '')}")
    gamma = check_real("gamma", gamma)
    if not gamma >= 0:  # 0: every entry 1, as scikit-learn's SVC(gamma=0) fits
        raise ValueError(f"gamma must be >= 0, got {gamma!r}")
    for name, norms, size in (("x_norms", x_norms, block.shape[0]),
                              ("y_norms", y_norms, block.shape[1])):
        if np.shape(norms) != (size,):
            raise ValueError(f"{name} must hold one squared norm per {name[0]} row of block "
                             f"({size}), got shape {np.shape(norms)}")
    if scratch is not None and not (isinstance(scratch, np.ndarray) and scratch.ndim == 1
                                    and scratch.dtype == np.float64
                                    and scratch.size >= block.size):
        raise ValueError(f"scratch must be a 1-D float64 array of at least block.size "
                         f"({block.size}) entries")
    block *= -2.0
    sums = None if scratch is None else scratch[: block.size].reshape(block.shape)
    block += np.add(x_norms[:, None], y_norms[None, :], out=sums)
    np.maximum(block, 0.0, out=block)
    if sparse_rows is not None:
        recompute_cancelled(block, *sparse_rows, x_norms, y_norms)
    block *= -gamma
    np.exp(block, out=block)


def _points(name: str, X):
    """``X`` as a 2-D real array (or a sparse matrix, as given), else an error naming it."""
    if issparse(X):
        return X
    X = real_array(name, X)
    if X.ndim != 2:
        raise ValueError(f"{name} must be 2-D (one point per row), got shape {X.shape}")
    return X


def _finite(name: str, X) -> None:
    """Refuse NaN or inf in ``X`` (dense or sparse), naming it."""
    values = X.data if issparse(X) else X
    if not np.all(np.isfinite(values)):
        raise ValueError(f"{name} must contain only finite values (no NaN or inf)")


def gram_matrix(X, Y=None, *, kernel="rbf", gamma=1.0, degree=3, coef0=0.0) -> np.ndarray:
    """Kernel matrix between the rows of ``X`` and ``Y`` (float64); arrays or sparse matrices.

    Examples
    --------
    >>> gram_matrix(np.eye(2), kernel="linear")
    array([[1., 0.],
           [0., 1.]])
    """
    k = Kernel(kernel, gamma=gamma, degree=degree, coef0=coef0)
    X = _points("X", X)
    _finite("X", X)
    if Y is not None:
        Y = _points("Y", Y)
        _finite("Y", Y)
    return k.gram(X, Y)


def call_kernel(kernel, X, Y) -> np.ndarray:
    """The matrix ``kernel(X, Y)`` of a user's kernel callable, checked (float64, dense).

    A sparse result is converted to an array, as scikit-learn does.

    Examples
    --------
    >>> call_kernel(lambda a, b: a @ b.T, np.eye(2), np.ones((1, 2)))
    array([[1.],
           [1.]])
    """
    if not callable(kernel):
        raise TypeError(f"kernel must be a callable kernel(X, Y), got {type(kernel).__name__}")
    K = kernel(X, Y)
    K = K.toarray() if issparse(K) else np.asarray(K, dtype=np.float64)
    if K.shape != (X.shape[0], Y.shape[0]):
        raise ValueError(f"the kernel callable must return an array of shape "
                         f"{(X.shape[0], Y.shape[0])}; got {K.shape}")
    if not np.isfinite(K).all():
        raise ValueError("the kernel callable returned values that are not finite")
    return K.astype(np.float64, copy=False)


class KernelRows:
    """Rows of the kernel matrix of ``X`` with itself, stored or cached.

    Parameters
    ----------
    X : ndarray or CSR matrix of shape (n, n_features)
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
    center : bool
        For 'rbf': compute the rows without cancellation, from the points centred once on their
        mean or, for sparse points, with the cancelling entries recomputed (see
        :meth:`Kernel.gram`); ``False`` keeps libsvm's uncentred arithmetic.
    parts : sequence of slice or ndarray, optional
        With ``full``: the problem's points are the rows of ``full`` in these slices (or at these
        indices), one after the other (the classes of a one-vs-one pair). Rows are then assembled
        from the parts on demand instead of copying the block.

    Examples
    --------
    >>> X = np.array([[0.0], [1.0], [3.0]])
    >>> rows = KernelRows(X, Kernel("linear"), np.float64, cache_bytes=8)
    >>> rows.is_full
    False
    >>> rows.row(2)
    array([0., 3., 9.])
    """

    def __init__(self, X, kernel: Kernel, dtype, cache_bytes: int, full=None, parts=None,
                 center: bool = True):
        if kernel is not None and not isinstance(kernel, Kernel):  # None: a precomputed matrix
            raise TypeError(f"kernel must be a Kernel, got {type(kernel).__name__}")
        if X is not None:
            X = _points("X", X)
        check_int("cache_bytes", cache_bytes, minimum=0)
        sparse = issparse(X)
        if sparse:
            X = as_csr(X)
        elif X is not None and center and kernel.name == "rbf":
            X = X - X.mean(axis=0)
        # rows are expanded about the origin: dense points are centred already, sparse ones keep
        # their zeros and have their cancelling entries recomputed
        self._center = center and sparse
        self.X = X
        self.kernel = kernel
        self.dtype = np.dtype(dtype)
        self._norms = squared_norms(X) if X is not None else None
        self._parts = None
        if full is not None and parts is not None:
            parts = [p if isinstance(p, slice) else np.asarray(p, dtype=np.intp) for p in parts]
            self.matrix = full
            # row i of the problem is row _rows[i] of `full`; touching slices are merged
            self._rows = np.concatenate([np.arange(p.start, p.stop) if isinstance(p, slice)
                                         else p for p in parts])
            self.n = self._rows.size
            merged = [parts[0]]
            for p in parts[1:]:
                if (isinstance(p, slice) and isinstance(merged[-1], slice)
                        and p.start == merged[-1].stop):
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
            self.matrix = kernel.gram(X, x_norms=self._norms, dtype=self.dtype,
                                      center=self._center)
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

    def stored_entries(self):
        """The stored matrix and, per position of the problem, its row there: ``(matrix,
        index)`` with :math:`k(x_p, x_q)` = ``matrix[index[p], index[q]]``, or None when rows
        are computed on demand.

        Examples
        --------
        >>> X = np.array([[0.0], [1.0], [3.0]])
        >>> K = Kernel("linear").gram(X)
        >>> matrix, index = KernelRows(None, Kernel("linear"), np.float64, 0, full=K,
        ...                            parts=[slice(0, 1), slice(2, 3)]).stored_entries()
        >>> index, float(matrix[index[1], index[1]])
        (array([0, 2]), 9.0)
        """
        if self.matrix is None:
            return None
        if self._parts is not None:
            return self.matrix, self._rows
        return self.matrix, np.arange(self.n)

    def _index(self, i) -> int:
        """``i`` checked as a row of the problem (a negative index would silently wrap)."""
        if isinstance(i, bool) or not isinstance(i, int | np.integer) or not 0 <= i < self.n:
            raise ValueError(f"i must be a row index from 0 to {self.n - 1}, got {describe(i)}")
        return i

    def row64(self, i: int) -> np.ndarray:
        """Kernel row :math:`k(x_i, x_t)` as float64 (a new array, or a view of float64 storage)."""
        self._index(i)
        if self._parts is not None:
            r = self.matrix[self._rows[i]]
            if len(self._parts) == 1:
                return r[self._parts[0]].astype(np.float64)
            return np.concatenate([r[p] for p in self._parts], dtype=np.float64)
        return np.asarray(self.row(i), dtype=np.float64)

    def block64(self, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
        """Kernel entries :math:`k(x_r, x_c)` for ``r`` in ``rows`` and ``c`` in ``cols``, as a
        new float64 array of shape ``(rows.size, cols.size)``.

        Each row is one gather (``take``, about three times faster than fancy indexing with
        ``np.ix_`` on a large matrix), from a stored row or a computed one: the same numbers as
        :meth:`row64` at the columns, whole matrix or pair of classes.

        Examples
        --------
        >>> X = np.array([[0.0], [1.0], [3.0]])
        >>> KernelRows(X, Kernel("linear"), np.float32, 1 << 10).block64(np.array([2]),
        ...                                                               np.array([0, 1]))
        array([[0., 3.]])
        """
        for name, index in (("rows", rows), ("cols", cols)):
            if (not isinstance(index, np.ndarray) or index.ndim != 1
                    or index.dtype.kind not in "iu"):
                raise TypeError(f"{name} must be a 1-D integer NumPy array of row indices, got "
                                f"{type(index).__name__} {getattr(index, 'dtype', '')}")
            if index.size and (index.min() < 0 or index.max() >= self.n):
                raise ValueError(f"{name} must index the {self.n} rows (0 to {self.n - 1})")
        if self.matrix is None:
            row = self.row
        else:
            row = self.matrix.__getitem__
            if self._parts is not None:  # positions of the problem -> rows of the stored matrix
                rows, cols = self._rows[rows], self._rows[cols]
        out = np.empty((len(rows), len(cols)))
        for k, r in enumerate(rows.tolist()):
            out[k] = row(r).take(cols)
        return out

    def row_reader(self):
        """The fastest way to :meth:`row64`: indexing of the stored matrix when it is whole and
        float64 (rows are then views, never to be written), else :meth:`row64` itself."""
        if self._parts is None and self.matrix is not None and self.dtype == np.float64:
            return self.matrix.__getitem__
        return self.row64

    def row(self, i: int) -> np.ndarray:
        """Kernel row :math:`k(x_i, x_t)` for all t, in the storage type."""
        self._index(i)
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
                             y_norms=self._norms, dtype=self.dtype, center=self._center)[0]
        if self.kernel.name == "rbf":
            r[i] = 1.0
        self.rows_computed += 1
        self._cache[i] = r
        if len(self._cache) > self._capacity:
            self._cache.popitem(last=False)
        return r
