"""The multilayer perceptron itself: forward pass, output losses and backpropagation, by hand.

Plain functions on lists of arrays: ``coefs[l]`` is the weight matrix of layer ``l``, of shape
(fan_in, fan_out), and ``intercepts[l]`` its bias vector. The estimators of
:mod:`ebantenna.ml.mlp` train with them; a student can call them directly to follow one
gradient step.

The hidden layers apply one activation; the output layer applies ``'softmax'`` (several classes,
cross-entropy), ``'logistic'`` (two classes or several labels, cross-entropy) or ``'identity'``
(regression, half the mean squared error over all entries). Every loss is returned with its exact
gradient with respect to the output pre-activations.

A training loop calls these functions once per mini-batch, with arrays of the same shapes every
time. It may pass a :class:`Workspace`, arrays allocated once per batch size, for them to write
into (``out=``) instead of allocating new ones: the arithmetic, and thus every result, is the same
with or without it.
"""

from __future__ import annotations

import numpy as np
from scipy.special import expit, log_expit

__all__ = [
    "ACTIVATIONS",
    "Workspace",
    "OUTPUT_ACTIVATIONS",
    "activate",
    "activation_derivative",
    "glorot_uniform",
    "forward",
    "output_loss",
    "backprop",
    "pack",
    "unpack",
]

#: Hidden-layer activations.
ACTIVATIONS = ("identity", "logistic", "tanh", "relu")
#: Output activations, each with its loss.
OUTPUT_ACTIVATIONS = ("softmax", "logistic", "identity")


def activate(name: str, z: np.ndarray) -> np.ndarray:
    """Apply an activation in place and return it (logistic via ``expit``: no overflow).

    Examples
    --------
    >>> activate("relu", np.array([-1.0, 2.0]))
    array([0., 2.])
    """
    if name == "tanh":
        return np.tanh(z, out=z)
    if name == "relu":
        return np.maximum(z, 0.0, out=z)
    if name == "logistic":
        return expit(z, out=z)
    return z


def activation_derivative(name: str, a: np.ndarray, delta: np.ndarray,
                          scratch: np.ndarray | None = None) -> None:
    """Multiply ``delta`` in place by the activation's derivative, written with its output ``a``.

    ``scratch``, an array of ``a``'s shape, holds the derivative on the way (a new array when
    not given).

    Examples
    --------
    >>> delta = np.ones(2)
    >>> activation_derivative("tanh", np.array([0.0, 0.5]), delta); delta
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


def glorot_uniform(sizes, activation: str, rng: np.random.Generator):
    """Glorot-uniform weights and biases: bound ``sqrt(f / (fan_in + fan_out))``, f = 6 (2 for
    'logistic'), as scikit-learn initialises them.

    Parameters
    ----------
    sizes : sequence of int
        Width of every layer, input and output included.
    activation : str
        Hidden-layer activation.
    rng : numpy.random.Generator
        Source of the draws: for each layer its weights, then its biases.

    Returns
    -------
    coefs, intercepts : list of ndarray

    Examples
    --------
    >>> coefs, intercepts = glorot_uniform([3, 2, 1], "relu", np.random.default_rng(0))
    >>> [c.shape for c in coefs], [b.shape for b in intercepts]
    ([(3, 2), (2, 1)], [(2,), (1,)])
    """
    factor = 2.0 if activation == "logistic" else 6.0
    coefs, intercepts = [], []
    for fan_in, fan_out in zip(sizes[:-1], sizes[1:], strict=True):
        bound = np.sqrt(factor / (fan_in + fan_out))
        coefs.append(rng.uniform(-bound, bound, (fan_in, fan_out)))
        intercepts.append(rng.uniform(-bound, bound, fan_out))
    return coefs, intercepts


class Workspace:
    """Arrays that one mini-batch step writes into, allocated once and reused by the next batches
    of the same size.

    Every batch computes arrays of the same shapes: each layer's activations, the deltas that
    backpropagation carries to the hidden layers, the derivative of the activation, and the L2
    term of each weight gradient. Writing into these arrays with ``out=`` spares NumPy an
    allocation per array and batch (the activations of a wide first layer are larger than the
    allocator keeps at hand), and the memory is still in cache when the next batch comes; the
    operations are the same, so are the results.

    Parameters
    ----------
    n_samples : int
        Rows of the batches that will use it.
    sizes : sequence of int
        Width of every layer, input and output included.

    Examples
    --------
    >>> work = Workspace(4, [3, 2, 1])
    >>> [a.shape for a in work.activations], [d.shape for d in work.deltas]
    ([(4, 2), (4, 1)], [(4, 2)])
    """

    def __init__(self, n_samples: int, sizes):
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


def forward(X, coefs, intercepts, activation: str, out=None) -> list[np.ndarray]:
    """Activations of every layer, ``X`` first; the last entry is the output pre-activation.

    ``out``, one array of shape (n_samples, fan_out) per layer (``Workspace.activations``),
    receives the activations instead of new arrays.

    Examples
    --------
    >>> acts = forward(np.ones((1, 2)), [np.ones((2, 1))], [np.zeros(1)], "relu")
    >>> acts[-1]
    array([[2.]])
    """
    acts = [X]
    last = len(coefs) - 1
    for i, (W, b) in enumerate(zip(coefs, intercepts, strict=True)):
        if out is None:
            z = acts[-1] @ W
        elif isinstance(acts[-1], np.ndarray):
            z = np.matmul(acts[-1], W, out=out[i])
        else:  # sparse input: scipy's product, copied in
            z = out[i]
            z[...] = acts[-1] @ W
        z += b
        if i < last:
            activate(activation, z)
        acts.append(z)
    return acts


def output_loss(out_activation: str, z: np.ndarray, Y: np.ndarray,
                out=None) -> tuple[float, np.ndarray]:
    """Mean loss per sample at the output pre-activations ``z`` and its gradient with respect
    to ``z``.

    Parameters
    ----------
    out_activation : {'softmax', 'logistic', 'identity'}
        Output activation: cross-entropy for the first two, half the mean squared error over all
        entries for 'identity'.
    z : ndarray of shape (n_samples, n_outputs)
        Output pre-activations (logits).
    Y : ndarray of shape (n_samples, n_outputs)
        Encoded targets (one-hot or 0/1 for classes).
    out : ndarray of shape (n_samples, n_outputs), optional
        Where to write the gradient instead of a new array. It may be ``z`` itself, which a
        training loop no longer needs once the loss is known: the loss is computed before ``z``
        is overwritten.

    Returns
    -------
    loss : float
    delta : ndarray of shape (n_samples, n_outputs)

    Examples
    --------
    >>> loss, delta = output_loss("identity", np.array([[1.0], [3.0]]), np.array([[0.0], [3.0]]))
    >>> loss, delta
    (0.25, array([[0.5],
           [0. ]]))
    """
    n = z.shape[0]
    if out_activation == "softmax":
        # log-sum-exp shifted by the row maximum: no overflow, exact for saturated logits.
        # The maxima are picked through argmax: with a few classes z.max(axis=1) runs one tiny
        # reduction per row and costs three times as much; the values picked are the same.
        shift = z[np.arange(n), z.argmax(axis=1)][:, np.newaxis]
        y_dot_z = np.einsum("ij,ij->", Y, z)  # before z may be overwritten by out
        prob = np.subtract(z, shift, out=out)
        np.exp(prob, out=prob)
        total = prob.sum(axis=1, keepdims=True)
        lse = np.log(total)
        lse += shift
        loss = float(lse.sum() - y_dot_z) / n
        prob /= total
        prob -= Y
        prob /= n
        return loss, prob
    if out_activation == "logistic":
        # -[y log s(z) + (1-y) log s(-z)], finite for any z
        loss = float(-np.sum(Y * log_expit(z) + (1.0 - Y) * log_expit(-z))) / n
        delta = expit(z, out=out)
        delta -= Y
        delta /= n
        return loss, delta
    diff = np.subtract(z, Y, out=out)
    loss = 0.5 * float(np.mean(diff * diff))
    diff /= diff.size
    return loss, diff


def backprop(acts, delta, coefs, activation: str, alpha_per_sample: float, out=None,
             work: Workspace | None = None):
    """Gradients of every weight matrix and bias vector, from the output gradient backwards.

    Parameters
    ----------
    acts : list of ndarray
        The activations from :func:`forward`.
    delta : ndarray of shape (n_samples, n_outputs)
        Gradient of the data loss with respect to the output pre-activations.
    coefs : list of ndarray
        Weight matrices.
    activation : str
        Hidden-layer activation.
    alpha_per_sample : float
        L2 coefficient divided by the number of samples: the penalty
        :math:`\\frac{\\alpha}{2n}\\sum_l \\lVert W_l \\rVert^2` adds ``alpha_per_sample * W`` to
        each weight gradient.
    out : tuple of two lists of ndarray, optional
        Arrays of the gradients' shapes to write them into (for instance views of one flat
        vector from :func:`unpack`), instead of new ones.
    work : Workspace, optional
        Arrays for the hidden layers' deltas and the other intermediate results, instead of new
        ones.

    Returns
    -------
    coef_grads, intercept_grads : list of ndarray

    Examples
    --------
    >>> X, coefs = np.array([[1.0, 2.0]]), [np.array([[1.0], [1.0]])]
    >>> acts = forward(X, coefs, [np.zeros(1)], "relu")
    >>> backprop(acts, np.array([[1.0]]), coefs, "relu", 0.0)
    ([array([[1.],
           [2.]])], [array([1.])])
    """
    if out is None:
        out = ([np.empty_like(W) for W in coefs], [np.empty(W.shape[1]) for W in coefs])
    coef_grads, intercept_grads = out
    for layer in range(len(coefs) - 1, -1, -1):
        if isinstance(acts[layer], np.ndarray):
            np.matmul(acts[layer].T, delta, out=coef_grads[layer])
        else:  # sparse input: scipy's product, copied in
            coef_grads[layer][...] = acts[layer].T @ delta
        penalty = None if work is None else work.penalties[layer]
        coef_grads[layer] += np.multiply(coefs[layer], alpha_per_sample, out=penalty)
        delta.sum(axis=0, out=intercept_grads[layer])  # the method: no Python wrapper
        if layer > 0:
            if work is None:
                delta = delta @ coefs[layer].T
                activation_derivative(activation, acts[layer], delta)
            else:
                delta = np.matmul(delta, coefs[layer].T, out=work.deltas[layer - 1])
                activation_derivative(activation, acts[layer], delta,
                                      work.derivatives[layer - 1])
    return coef_grads, intercept_grads


def pack(coefs, intercepts) -> np.ndarray:
    """All weights and biases in one flat vector, layer by layer (weights, then biases).

    Examples
    --------
    >>> pack([np.ones((2, 1))], [np.zeros(1)])
    array([1., 1., 0.])
    """
    return np.concatenate([a.ravel() for pair in zip(coefs, intercepts, strict=True)
                           for a in pair])


def unpack(w: np.ndarray, shapes):
    """Inverse of :func:`pack` for layers of the given (fan_in, fan_out) ``shapes`` (views of
    ``w``).

    Examples
    --------
    >>> coefs, intercepts = unpack(np.arange(3.0), [(2, 1)])
    >>> coefs[0].ravel(), intercepts[0]
    (array([0., 1.]), array([2.]))
    """
    coefs, intercepts, pos = [], [], 0
    for fan_in, fan_out in shapes:
        coefs.append(w[pos : pos + fan_in * fan_out].reshape(fan_in, fan_out))
        pos += fan_in * fan_out
        intercepts.append(w[pos : pos + fan_out])
        pos += fan_out
    return coefs, intercepts
