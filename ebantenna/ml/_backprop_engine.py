"""The training engine of the multilayer perceptrons: :mod:`ebantenna.ml.backprop`'s arithmetic in
arrays allocated once per batch size.

A training loop evaluates the loss and its gradient once per mini-batch, with arrays of the same
shapes every time. :func:`loss_and_gradients_into` does what
:func:`ebantenna.ml.backprop.loss_and_gradients` does, operation for operation, but writes every
intermediate result into a :class:`Workspace` (``out=``) and the gradient into arrays given by the
caller (views of one flat vector, which the optimiser moves with a handful of NumPy calls). The
operations are the same, so are the results: the tests hold this engine equal to the reference
bit for bit.

What differs from the reference, and why:

* ``out=`` everywhere: NumPy spares an allocation per array and batch (the activations of a wide
  first layer are larger than the allocator keeps at hand), and the memory is still in cache when
  the next batch comes;
* a sparse input is multiplied by scipy, which has no ``out=``: its product is copied in;
* the softmax's row maxima are picked through ``argmax``: with a few classes ``z.max(axis=1)``
  runs one tiny reduction per row and costs three times as much; the values picked are the same;
* the logits' array receives their gradient, since nothing reads them after the loss;
* with numba installed, :class:`Workspace` carries the compiled loops of
  :mod:`ebantenna.ml._mlp_numba` (``compiled``), and the arithmetic between the NumPy calls
  that must stay (the products, ``tanh``, ``exp``, ``log`` and the loss's sums) runs in them:
  the biases added, the softmax's row maxima subtracted and its gradient formed, the weight
  gradient's L2 term, each hidden delta's derivative with its bias gradient. One pass each
  instead of two to four NumPy calls, the same operations in the same order.

The functions take checked values, as the reference's do.
"""

from __future__ import annotations

import numpy as np
from scipy.special import expit, log_expit

from ._mlp_compiled import ACTIVATION_CODES
from .backprop import l2_penalty

__all__ = ["Workspace", "forward_into", "output_loss_into", "backprop_into",
           "loss_and_gradients_into", "activate_in_place", "derivative_in_place"]


def activate_in_place(name: str, z: np.ndarray) -> np.ndarray:
    """:func:`ebantenna.ml.backprop.activate` written over ``z`` (the workspace's own array).

    Examples
    --------
    >>> z = np.array([-1.0, 2.0])
    >>> _ = activate_in_place("relu", z); z
    array([0., 2.])
    """
    if name == "tanh":
        return np.tanh(z, out=z)
    if name == "relu":
        return np.maximum(z, 0.0, out=z)
    if name == "logistic":
        return expit(z, out=z)
    return z


def derivative_in_place(name: str, a: np.ndarray, delta: np.ndarray,
                        scratch: np.ndarray | None = None) -> np.ndarray:
    """:func:`ebantenna.ml.backprop.activation_derivative` written over ``delta`` (the
    workspace's own array), the derivative formed in ``scratch``: the same operations.

    Examples
    --------
    >>> delta = np.ones(2)
    >>> _ = derivative_in_place("tanh", np.array([0.0, 0.5]), delta); delta
    array([1.  , 0.75])
    """
    if name == "tanh":
        d = np.multiply(a, a, out=scratch)
        np.subtract(1.0, d, out=d)
        delta *= d
    elif name == "relu":
        delta[a <= 0] = 0.0
    elif name == "logistic":
        d = np.subtract(1.0, a, out=scratch)
        d *= a
        delta *= d
    return delta


class Workspace:
    """Arrays that one mini-batch step writes into, allocated once and reused by the next batches
    of the same size.

    Every batch computes arrays of the same shapes: each layer's activations, the deltas that
    backpropagation carries to the hidden layers, the derivative of the activation, and the L2
    term of each weight gradient.

    Parameters
    ----------
    n_samples : int
        Rows of the batches that will use it.
    sizes : sequence of int
        Width of every layer, input and output included.
    compiled : module or None
        The compiled loops (:func:`ebantenna.ml._mlp_compiled.compiled_kernels`), or None for
        NumPy calls only; both give the same bits.

    Examples
    --------
    >>> work = Workspace(4, [3, 2, 1])
    >>> [a.shape for a in work.activations], [d.shape for d in work.deltas]
    ([(4, 2), (4, 1)], [(4, 2)])
    """

    def __init__(self, n_samples: int, sizes, compiled=None):
        widths = list(sizes[1:])
        #: output of each layer (the last holds the logits, then their gradient)
        self.activations = [np.empty((n_samples, w)) for w in widths]
        #: gradient with respect to each hidden layer's pre-activation
        self.deltas = [np.empty((n_samples, w)) for w in widths[:-1]]
        #: the activation's derivative at each hidden layer
        self.derivatives = [np.empty((n_samples, w)) for w in widths[:-1]]
        #: the L2 term ``alpha_per_sample * W`` of each weight gradient
        self.penalties = [np.empty((fan_in, fan_out))
                          for fan_in, fan_out in zip(sizes[:-1], sizes[1:], strict=True)]
        #: the row indices, which pick each row's largest logit
        self.rows = np.arange(n_samples)
        #: each row's largest logit
        self.shift = np.empty((n_samples, 1))
        #: the compiled loops (:mod:`ebantenna.ml._mlp_numba`) or None: NumPy calls
        self.compiled = compiled


def forward_into(X, coefs, intercepts, activation: str, work: Workspace) -> list[np.ndarray]:
    """:func:`ebantenna.ml.backprop.forward`, written into ``work.activations``.

    Examples
    --------
    >>> acts = forward_into(np.ones((1, 2)), [np.ones((2, 1))], [np.zeros(1)], "relu",
    ...                     Workspace(1, [2, 1]))
    >>> acts[-1]
    array([[2.]])
    """
    acts = [X]
    last = len(coefs) - 1
    for layer, (W, b) in enumerate(zip(coefs, intercepts, strict=True)):
        if isinstance(acts[-1], np.ndarray):
            z = np.matmul(acts[-1], W, out=work.activations[layer])
        else:  # sparse input: scipy's product, copied in
            z = work.activations[layer]
            z[...] = acts[-1] @ W
        if work.compiled is not None:
            work.compiled.add_bias(z, b)
        else:
            z += b
        if layer < last:
            activate_in_place(activation, z)
        acts.append(z)
    return acts


def _softmax_loss_into(z, Y, work) -> tuple[float, np.ndarray]:
    """The softmax's cross-entropy and its gradient over ``z``, as the reference computes them;
    with the compiled loops, the row maxima and their subtraction take one pass, and so do the
    three operations from the exponentials to the gradient."""
    n = z.shape[0]
    compiled = None if work is None else work.compiled
    y_dot_z = np.einsum("ij,ij->", Y, z)  # before z is overwritten
    if compiled is not None:
        shift = work.shift
        compiled.subtract_row_max(z, shift)
        prob = z
    else:
        rows = np.arange(n) if work is None else work.rows
        shift = z[rows, z.argmax(axis=1)][:, np.newaxis]
        prob = np.subtract(z, shift, out=z)
    np.exp(prob, out=prob)
    total = prob.sum(axis=1, keepdims=True)
    log_sum_exp = np.log(total)
    log_sum_exp += shift
    loss = float(log_sum_exp.sum() - y_dot_z) / n
    if compiled is not None:
        compiled.softmax_gradient(prob, total, Y, float(n))
    else:
        prob /= total
        prob -= Y
        prob /= n
    return loss, prob


def output_loss_into(out_activation: str, z: np.ndarray, Y: np.ndarray,
                     work: Workspace | None = None) -> tuple[float, np.ndarray]:
    """:func:`ebantenna.ml.backprop.output_loss`, the gradient written over ``z``; ``work``
    (optional) gives the row indices and the compiled loops.

    Examples
    --------
    >>> z = np.array([[1.0], [3.0]])
    >>> loss, delta = output_loss_into("identity", z, np.array([[0.0], [3.0]]))
    >>> loss, delta is z, z.ravel()
    (0.25, True, array([0.5, 0. ]))
    """
    n = z.shape[0]
    if out_activation == "softmax":
        return _softmax_loss_into(z, Y, work)
    if out_activation == "logistic":
        loss = float(-np.sum(Y * log_expit(z) + (1.0 - Y) * log_expit(-z))) / n
        delta = expit(z, out=z)
        delta -= Y
        delta /= n
        return loss, delta
    diff = np.subtract(z, Y, out=z)
    loss = 0.5 * float(np.mean(diff * diff))
    diff /= diff.size
    return loss, diff


def _weight_gradient_into(a, delta, W, alpha_per_sample: float, out, layer: int,
                          work: Workspace) -> None:
    """``out = a.T @ delta + alpha_per_sample * W``: the product, then the L2 term added (one
    compiled pass, or two NumPy calls through ``work.penalties``)."""
    if isinstance(a, np.ndarray):
        np.matmul(a.T, delta, out=out)
    else:  # sparse input: scipy's product, copied in
        out[...] = a.T @ delta
    if work.compiled is not None:
        work.compiled.add_scaled(out, W, alpha_per_sample)
    else:
        out += np.multiply(W, alpha_per_sample, out=work.penalties[layer])


def backprop_into(acts, delta, coefs, activation: str, alpha_per_sample: float, grads,
                  work: Workspace) -> None:
    """:func:`ebantenna.ml.backprop.backprop`, the gradients written into ``grads`` (two lists of
    arrays of the weights' and biases' shapes), the hidden deltas into ``work``.

    With the compiled loops (``work.compiled``), each hidden delta's activation derivative and
    the column sums that are its layer's bias gradient take one pass.

    Examples
    --------
    >>> X, coefs = np.array([[1.0, 2.0]]), [np.array([[1.0], [1.0]])]
    >>> work = Workspace(1, [2, 1])
    >>> acts = forward_into(X, coefs, [np.zeros(1)], "relu", work)
    >>> grads = ([np.empty((2, 1))], [np.empty(1)])
    >>> backprop_into(acts, np.array([[1.0]]), coefs, "relu", 0.0, grads, work)
    >>> grads[0][0].ravel(), grads[1][0]
    (array([1., 2.]), array([1.]))
    """
    coef_grads, intercept_grads = grads
    compiled = work.compiled
    last = len(coefs) - 1
    # the compiled loop sums the columns of a delta of several columns as NumPy does
    fused = compiled is not None and delta.shape[1] > 1
    if fused:  # the output layer's bias gradient: code 0, no derivative
        compiled.derivative_and_bias_gradient(0, delta, delta, intercept_grads[last], True)
    for layer in range(last, -1, -1):
        _weight_gradient_into(acts[layer], delta, coefs[layer], alpha_per_sample,
                              coef_grads[layer], layer, work)
        if not fused:
            delta.sum(axis=0, out=intercept_grads[layer])  # the method: no Python wrapper
        if layer > 0:
            delta = np.matmul(delta, coefs[layer].T, out=work.deltas[layer - 1])
            if compiled is None:
                derivative_in_place(activation, acts[layer], delta,
                                    work.derivatives[layer - 1])
                continue
            fused = delta.shape[1] > 1
            compiled.derivative_and_bias_gradient(ACTIVATION_CODES[activation], acts[layer],
                                                  delta, intercept_grads[layer - 1], fused)


def loss_and_gradients_into(X, Y, coefs, intercepts, activation: str, out_activation: str,
                            alpha: float, grads, work: Workspace) -> float:
    """:func:`ebantenna.ml.backprop.loss_and_gradients`, the gradients written into ``grads``
    (two lists of arrays), the intermediate arrays into ``work`` (of ``X``'s number of rows).

    Returns
    -------
    loss : float

    Examples
    --------
    >>> grads = ([np.empty((1, 1))], [np.empty(1)])
    >>> loss_and_gradients_into(np.ones((2, 1)), np.zeros((2, 1)), [np.ones((1, 1))],
    ...                         [np.zeros(1)], "relu", "identity", 0.0, grads,
    ...                         Workspace(2, [1, 1]))
    0.5
    >>> grads
    ([array([[1.]])], [array([1.])])
    """
    n = X.shape[0]
    acts = forward_into(X, coefs, intercepts, activation, work)
    data_loss, delta = output_loss_into(out_activation, acts[-1], Y, work)
    loss = data_loss + l2_penalty(coefs, alpha, n)
    backprop_into(acts, delta, coefs, activation, alpha / n, grads, work)
    return loss
