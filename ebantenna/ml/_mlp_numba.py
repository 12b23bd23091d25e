"""The multilayer perceptron's elementwise steps compiled by numba: the NumPy engine's arithmetic,
one entry at a time (private).

Used only by :mod:`ebantenna.ml._backprop_engine` and :class:`ebantenna.ml.optimizers.Adam`,
through :func:`ebantenna.ml._mlp_compiled.compiled_kernels`, when numba is installed and these
loops compile (``IMPORT_ERROR`` says why not); otherwise those steps run as NumPy calls. The
matrix products, ``tanh``, ``exp`` and ``log`` stay NumPy's on both paths; what is compiled is
the arithmetic around them, which NumPy does in several passes over the arrays, each pass one
NumPy call:

* every number is computed by the same IEEE operations in the same order as the NumPy path:
  Adam's ``m b_1 + g (1 - b_1)``, ``v b_2 + (g (1 - b_2)) g`` and
  ``p - (m \\, lr) / (\\sqrt{v} + \\epsilon)``; the weight gradient's ``product + W \\alpha/n``;
  the activation's derivative ``delta (1 - a a)`` (tanh), ``delta ((1 - a) a)`` (logistic) or
  0 where ``a <= 0`` (relu). numba compiles without ``fastmath``: no reassociation and no fused
  multiply-add, so each operation rounds as NumPy's does;
* the only sums are the bias gradients, the column sums of ``delta``: NumPy adds the rows of a
  C-ordered array of several columns one after the other (its reduction runs along the outer
  axis), and so do these loops, from the first row. A single column NumPy sums pairwise, as a
  contiguous vector; that sum stays NumPy's.

The tests hold both paths equal bit for bit.
"""

from __future__ import annotations

import numpy as np

try:
    import numba
except ImportError as exc:  # not installed, or not working with this NumPy
    numba = None
    IMPORT_ERROR = f"{type(exc).__name__}: {exc}"
else:
    IMPORT_ERROR = ""

__all__ = ["adam_step", "add_scaled", "derivative_and_bias_gradient", "add_bias",
           "subtract_row_max", "softmax_gradient", "smoke_test", "IMPORT_ERROR"]


def _plain(function):
    """Without numba the loops stay Python functions (this module still imports, and nothing
    uses it: :func:`~ebantenna.ml._mlp_compiled.compiled_kernels` returns None)."""
    return function


# error_model="numpy": a division by zero gives inf or NaN as NumPy's does, with no test per
# division, which lets LLVM vectorise the loops (the IEEE operations stay the same)
_jit = numba.njit(cache=True, error_model="numpy") if numba is not None else _plain

@_jit
def adam_step(p, g, m, v, beta_1, beta_2, one_minus_beta_1, one_minus_beta_2, lr, epsilon):
    """One Adam step on flat float64 vectors, in place: the moments ``m``, ``v`` and the
    parameters ``p`` (:meth:`ebantenna.ml.optimizers.Adam.update`'s operations)."""
    for i in range(p.size):
        gi = g[i]
        mi = m[i] * beta_1 + gi * one_minus_beta_1
        vi = v[i] * beta_2 + (gi * one_minus_beta_2) * gi
        m[i] = mi
        v[i] = vi
        p[i] = p[i] - (mi * lr) / (np.sqrt(vi) + epsilon)


@_jit
def add_scaled(out, W, scale):
    """``out += W * scale`` in place (the L2 term of a weight gradient), for 2-D arrays."""
    rows, cols = W.shape
    for i in range(rows):
        for j in range(cols):
            out[i, j] = out[i, j] + W[i, j] * scale


@_jit
def derivative_and_bias_gradient(code, a, delta, bias_grad, with_sums):
    """``delta`` multiplied in place by the activation's derivative written with its output
    ``a`` (``code`` from :data:`ebantenna.ml._mlp_compiled.ACTIVATION_CODES`), then, if
    ``with_sums``, ``bias_grad`` = its column sums, each row added after the other from the
    first, as NumPy adds the rows of an array of several columns (a single column it sums
    pairwise, as a contiguous vector: that sum is left to NumPy)."""
    rows, cols = delta.shape
    for i in range(rows):
        if code == 1:
            for j in range(cols):
                delta[i, j] = delta[i, j] * (1.0 - a[i, j] * a[i, j])
        elif code == 2:
            for j in range(cols):
                delta[i, j] = delta[i, j] * ((1.0 - a[i, j]) * a[i, j])
        elif code == 3:
            for j in range(cols):
                if a[i, j] <= 0.0:
                    delta[i, j] = 0.0
        if not with_sums:
            continue
        if i == 0:
            for j in range(cols):
                bias_grad[j] = delta[0, j]
        else:
            for j in range(cols):
                bias_grad[j] = bias_grad[j] + delta[i, j]


@_jit
def add_bias(z, b):
    """``z += b`` in place, ``b`` added to every row."""
    rows, cols = z.shape
    for i in range(rows):
        for j in range(cols):
            z[i, j] = z[i, j] + b[j]


@_jit
def subtract_row_max(z, shift):
    """``shift[i, 0]`` = the largest entry of row ``i`` (the first NaN if there is one, as
    ``argmax`` picks), subtracted from the row in place."""
    rows, cols = z.shape
    for i in range(rows):
        m = z[i, 0]
        for j in range(1, cols):
            if z[i, j] > m or (z[i, j] != z[i, j] and m == m):
                m = z[i, j]
        shift[i, 0] = m
        for j in range(cols):
            z[i, j] = z[i, j] - m


@_jit
def softmax_gradient(prob, total, Y, n):
    """``prob = (prob / total - Y) / n`` in place: the softmax's probabilities from the
    exponentials and their row sums ``total`` (shape (rows, 1)), minus the targets, per sample."""
    rows, cols = prob.shape
    for i in range(rows):
        for j in range(cols):
            prob[i, j] = (prob[i, j] / total[i, 0] - Y[i, j]) / n


def smoke_test() -> None:
    """Compile (or load) the loops and check one known value of each."""
    p, g, m, v = np.ones(2), np.full(2, 3.0), np.zeros(2), np.zeros(2)
    adam_step(p, g, m, v, 0.9, 0.999, 0.1, 0.001, 0.5, 0.0)
    grad = np.array([[1.0], [2.0]])
    add_scaled(grad, np.array([[1.0], [1.0]]), 0.5)
    delta, bias = np.ones((2, 1)), np.empty(1)
    derivative_and_bias_gradient(1, np.full((2, 1), 0.5), delta, bias, True)
    expected = (np.allclose(m, 0.3) and np.allclose(p, 1.0 - 0.5 * 0.3 / np.sqrt(0.009))
                and np.array_equal(grad.ravel(), [1.5, 2.5]) and np.array_equal(bias, [1.5]))
    if not expected:
        raise RuntimeError("the compiled MLP loops computed a known step wrongly")
