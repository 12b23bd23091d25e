"""Kernel rows of the one-vs-one problems of :class:`~ebantenna.ml.SVC`, and where they are kept.

A fit on :math:`k` classes solves :math:`k(k-1)/2` binary problems, one per pair of classes;
the problem of the pair :math:`(a, b)` needs the kernel entries among the points of the two
classes. :class:`PairKernels` hands each problem its :class:`~ebantenna.ml.kernels.KernelRows`,
kept in one of three ways, the first that applies:

* **the given matrix**: a precomputed kernel, a callable's matrix, or the kernel matrix that
  machines trained on the same points share (:meth:`~ebantenna.ml.SVC.fit`'s
  ``kernel_matrix``), used as it is: the rows of a pair are gathered from it at the pair's
  indices (no copy when it is stored in ``dtype`` already).
* **pair by pair, in float64** (the default mode, dense points, when the kernel of the two
  largest classes fits in ``cache_bytes`` in float64): the kernel matrix of each pair is built
  in one float64 buffer, reused from pair to pair, and each row is a contiguous view of it. The
  pairs come in the order :math:`(0, k-1), (0, k-2), \\dots, (0, 1), (1, k-1), \\dots, (1, 2),
  \\dots`: the block of the first class stays in the buffer's corner while the second class
  changes, and the last pair of a run leaves the block of the next first class in the buffer,
  where it is copied to the corner instead of being computed again. Each pair then costs its
  cross block and one diagonal block: for five classes of equal size about 1.5 times the
  entries of the whole matrix, but one pair's kernel in memory instead of all of them (at 6000
  points in five classes, 46 MB instead of 288 MB in float64 or 144 MB in float32). When the
  diagonal blocks of all classes fit in ``cache_bytes`` beside the buffer (another 58 MB
  there), each is computed once and kept until its class has been the first of its last pair:
  every entry of the whole matrix is then computed once, the diagonal blocks a quarter more
  (their strips, see :meth:`~ebantenna.ml.kernels.Kernel.gram`). Keeping a block costs a copy,
  about 1 ms for 1200 points against about 30 ms to compute its 1.4 million entries in 256
  dimensions (fresh memory, faulted in page by page, costs about twice the copy). float64
  keeps the error bound of :mod:`ebantenna.ml.kernels` without a float32 rounding on top.
* **the whole matrix** (``libsvm_compat``, sparse points, or when a pair does not fit but the
  whole matrix does in ``dtype``): one Gram product over the points sorted by class; the rows of
  a pair are assembled from two slices of it.
* **a row cache** otherwise: each problem computes its rows on demand and keeps the most recently
  used (:class:`~ebantenna.ml.kernels.KernelRows`).

:class:`PairKernels` takes checked values: :class:`~ebantenna.ml.SVC` validates its input once.
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import issparse

from .._validate import check_int
from .kernels import Kernel, KernelRows, squared_norms

__all__ = ["PairKernels"]


def _check_arguments(X, members, kernel, cache_bytes, given) -> None:
    """The arguments of :class:`PairKernels` checked (see its parameters)."""
    if isinstance(members, np.ndarray) or not isinstance(members, list | tuple) or len(
            members) < 2:
        raise TypeError("members must be a list of index arrays, one per class (two at "
                        "least)")
    n_points = given.shape[0] if given is not None else getattr(X, "shape", (0,))[0]
    for c, m in enumerate(members):
        if (not isinstance(m, np.ndarray) or m.ndim != 1 or m.dtype.kind not in "iu"
                or m.size == 0 or m.min() < 0 or m.max() >= n_points):
            raise ValueError(f"members[{c}] must be a non-empty 1-D integer array of row "
                             f"indices below {n_points}")
    check_int("cache_bytes", cache_bytes, minimum=0)
    if given is not None:
        if (not isinstance(given, np.ndarray) or given.ndim != 2
                or given.shape[0] != given.shape[1]):
            raise ValueError(f"given must be a square kernel matrix (NumPy array), got "
                             f"{type(given).__name__} {getattr(given, 'shape', '')}")
    else:
        if not isinstance(kernel, Kernel):
            raise TypeError(f"kernel must be a Kernel (or given the whole matrix), got "
                            f"{type(kernel).__name__}")
        if not (issparse(X) or (isinstance(X, np.ndarray) and X.ndim == 2)):
            raise TypeError(f"X must be a 2-D NumPy array or a sparse matrix of points, got "
                            f"{type(X).__name__}")


class PairKernels:
    """The kernel rows of the one-vs-one problems, kept the cheapest way that fits.

    Parameters
    ----------
    X : ndarray or CSR matrix of shape (n_samples, n_features)
        Training points (ignored when ``given`` is set).
    members : list of ndarray
        Indices of the points of each class that take part (positive weight).
    kernel : Kernel or None
        The kernel function (None when ``given`` is set).
    dtype : numpy dtype
        Storage type of the whole matrix or of the row cache (float32 or float64).
    cache_bytes : int
        Memory allowed for kernel entries, in bytes.
    given : ndarray of shape (n_samples, n_samples), optional
        The whole kernel matrix (precomputed kernel or callable).
    libsvm_compat : bool
        Keep libsvm's storage and arithmetic: the whole matrix (or the row cache) in ``dtype``,
        the RBF kernel expanded about the origin.

    Attributes
    ----------
    layout : {'given', 'pairs', 'whole', 'cache'}
        Which of the ways of the module text is used.

    Examples
    --------
    >>> X = np.array([[0.0], [1.0], [3.0], [4.0], [6.0]])
    >>> members = [np.array([0, 1]), np.array([2]), np.array([3, 4])]
    >>> kernels = PairKernels(X, members, Kernel("linear"), np.float64, 1 << 20)
    >>> kernels.layout
    'pairs'
    >>> kernels.rows(0, 2).row(1)  # point 1 against points 0, 1, 3, 4
    array([0., 1., 4., 6.])
    """

    def __init__(self, X, members, kernel: Kernel | None, dtype, cache_bytes: int, *,
                 given=None, libsvm_compat: bool = False):
        _check_arguments(X, members, kernel, cache_bytes, given)
        self.members = members
        self.kernel = kernel
        self.dtype = np.dtype(dtype)
        self.cache_bytes = cache_bytes
        self.center = not libsvm_compat
        self.X = X
        self._starts = np.concatenate([[0], np.cumsum([m.size for m in members])])
        order = np.concatenate(members)
        n = order.size
        largest = sum(sorted(m.size for m in members)[-2:])
        self._matrix = None
        self._indexed = False  # the pairs' rows at the members' indices of the given matrix
        if given is not None:
            self.layout = "given"
            if given.dtype == self.dtype:  # read in place, at the members' indices
                self._matrix, self._indexed = given, True
            else:  # stored in dtype, sorted by class: each class a slice
                self._matrix = np.asarray(given[np.ix_(order, order)], dtype=self.dtype)
        elif not libsvm_compat and not issparse(X) and largest**2 * 8 <= cache_bytes:
            self.layout = "pairs"
            # the points sorted by class (each class a slice), centred once on their mean for
            # 'rbf': every block is then expanded about the same centre (the error bound of
            # ebantenna.ml.kernels)
            points = X[order]
            if kernel.name == "rbf":
                points -= points.mean(axis=0)
            self._points = points
            self._norms = squared_norms(points) if kernel.name == "rbf" else None
            self._buffer = np.empty((largest, largest))
            self._corner = self._last = self._lower = None
            # the diagonal block of each class, once computed, while all of them fit
            self._diagonal: dict[int, np.ndarray] | None = None
            if (largest**2 + sum(m.size**2 for m in members)) * 8 <= cache_bytes:
                self._diagonal = {}
        elif n * n * self.dtype.itemsize <= cache_bytes:
            self.layout = "whole"
            self._matrix = kernel.gram(X[order], dtype=self.dtype, center=self.center)
        else:
            self.layout = "cache"

    def pairs(self):
        """The problems ``(a, b, rows)`` of every pair of classes ``a < b``, in the order that
        reuses the blocks of the 'pairs' layout (see the module text); each ``rows`` is valid
        until the next one is taken."""
        k = len(self.members)
        for a in range(k):
            for b in range(k - 1, a, -1):
                yield a, b, self.rows(a, b)

    @property
    def stored(self) -> bool:
        """True when every problem has its whole kernel at hand (no row is computed twice)."""
        return self.layout != "cache"

    def rows(self, a: int, b: int) -> KernelRows:
        """Kernel rows of the problem of classes ``a < b``: the points of ``a``, then of ``b``.

        With the 'pairs' layout the rows are views of the buffer, valid until the next call.
        """
        k = len(self.members)
        check_int("a", a, minimum=0, maximum=k - 2)
        check_int("b", b, minimum=a + 1, maximum=k - 1)
        if self.layout == "pairs":
            return KernelRows(None, self.kernel, np.float64, 0, full=self._pair_matrix(a, b))
        if self._matrix is not None:
            s = self._starts
            parts = ((self.members[a], self.members[b]) if self._indexed
                     else (slice(s[a], s[a + 1]), slice(s[b], s[b + 1])))
            return KernelRows(None, self.kernel, self.dtype, self.cache_bytes,
                              full=self._matrix, parts=parts)
        idx = np.concatenate([self.members[a], self.members[b]])
        return KernelRows(self.X[idx], self.kernel, self.dtype, self.cache_bytes,
                          center=self.center)

    def _pair_matrix(self, a: int, b: int) -> np.ndarray:
        """The kernel of classes ``a`` and ``b`` in the buffer (float64, rows contiguous)."""
        s = self._starts
        A, B = slice(s[a], s[a + 1]), slice(s[b], s[b + 1])
        na, n = A.stop - A.start, A.stop - A.start + B.stop - B.start
        K = self._buffer[:n, :n]
        if self._corner != a:  # the block of the first class stays while the second changes
            if self._diagonal is not None and a in self._diagonal:  # its last use as a corner
                K[:na, :na] = self._diagonal.pop(a)
            elif self._last == a:  # left by the pair (a - 1, a) in the lower right: moved up
                m = self._lower
                K[:na, :na] = self._buffer[m : m + na, m : m + na]
            else:
                self._block(A, None, K[:na, :na])
            self._corner = a
        self._last, self._lower = b, na
        self._block(A, B, K[:na, na:])
        K[na:, :na] = K[:na, na:].T
        if self._diagonal is None:
            self._block(B, None, K[na:, na:])
        elif b in self._diagonal:
            K[na:, na:] = self._diagonal[b]
        else:  # computed where it is used, then kept: the same numbers every time
            self._block(B, None, K[na:, na:])
            self._diagonal[b] = K[na:, na:].copy()
        return K

    def _block(self, rows: slice, cols: slice | None, out: np.ndarray) -> None:
        """``out[:] = k(x_r, x_c)`` for the sorted points in the slices ``rows`` and ``cols``
        (``cols`` None: the points of ``rows`` with themselves)."""
        X = self._points[rows]
        Y = None if cols is None else self._points[cols]
        if self._norms is None:
            self.kernel.gram(X, Y, out=out)
        else:  # centred already: expanded about the origin, with the norms computed once
            self.kernel.gram(X, Y, x_norms=self._norms[rows],
                             y_norms=None if cols is None else self._norms[cols], center=False,
                             out=out)
