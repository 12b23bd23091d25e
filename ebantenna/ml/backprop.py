"""The multilayer perceptron as the textbook writes it: forward pass, output loss, backpropagation.

Plain functions on lists of arrays: with the layers numbered :math:`l = 1, \\dots, N`,
``coefs[l - 1]`` is the weight matrix :math:`W_l` of layer :math:`l`, of shape (fan_in,
fan_out), and ``intercepts[l - 1]`` its bias vector :math:`b_l` (Python counts from 0). This
module is the **reference**: read it top to bottom to follow one gradient evaluation, or call its
functions to take one step by hand. With :math:`a_0 = X`,

.. math::

   z_l = a_{l-1} W_l + b_l, \\qquad a_l = f(z_l) \\ (l < N), \\qquad
   \\delta_N = \\frac{\\partial \\ell}{\\partial z_N}, \\qquad
   \\delta_{l-1} = (\\delta_l W_l^T) \\odot f'(z_{l-1}),

   \\frac{\\partial L}{\\partial W_l} = a_{l-1}^T \\delta_l + \\frac{\\alpha}{n} W_l, \\qquad
   \\frac{\\partial L}{\\partial b_l} = \\sum_{\\text{samples}} \\delta_l.

:math:`\\ell` is the loss *averaged* over the ``n`` samples and :math:`L` that loss with the L2
penalty, so :math:`\\delta_N` already holds the factor :math:`1/n`: with the per-sample deltas
:math:`\\delta^{(i)}` of the textbooks, :math:`a^T \\delta = \\frac{1}{n}\\sum_i a^{(i)T}
\\delta^{(i)}` and :math:`\\sum \\delta` is their mean.

The hidden layers apply one activation; the output layer applies ``'softmax'`` (several classes,
cross-entropy), ``'logistic'`` (two classes or several labels, cross-entropy) or ``'identity'``
(regression, half the mean squared error over all entries). Every loss is returned with its exact
gradient with respect to the output pre-activations (the derivative of the output nonlinearity
cancels against that of the loss: :math:`\\delta_N = (\\hat y - y)/n`, divided by the number of
outputs as well for the squared error).

Training is :func:`train_epochs`: mini-batches, each one gradient evaluation and one update of
an optimiser of :mod:`ebantenna.ml.optimizers`, which ``engine="reference"`` of the estimators
runs. By default the estimators of :mod:`ebantenna.ml.mlp` train with an **engine** that does the
same arithmetic in arrays allocated once per batch size (private modules); the tests hold it
equal to these functions bit for bit. The functions here take checked values (float arrays of
matching shapes, known activation names): the estimators validate their input once, at their
public methods.

Examples
--------
One gradient evaluation of a network with one hidden layer, by hand:

>>> import numpy as np
>>> from ebantenna.ml.backprop import glorot_uniform, loss_and_gradients
>>> rng = np.random.default_rng(0)
>>> X, Y = rng.normal(size=(4, 3)), np.eye(2)[[0, 1, 1, 0]]
>>> coefs, intercepts = glorot_uniform([3, 5, 2], "tanh", rng)
>>> loss, coef_grads, intercept_grads = loss_and_gradients(
...     X, Y, coefs, intercepts, "tanh", "softmax", alpha=0.0)
>>> [g.shape for g in coef_grads], [g.shape for g in intercept_grads]
([(3, 5), (5, 2)], [(5,), (2,)])
>>> bool(loss > 0)
True
"""

from __future__ import annotations

import numpy as np
from scipy.special import expit, log_expit

from .._budget import check_allocation
from .._validate import check_choice, check_int, check_nonnegative, describe

__all__ = [
    "ACTIVATIONS",
    "OUTPUT_ACTIVATIONS",
    "activate",
    "activation_derivative",
    "glorot_uniform",
    "forward",
    "output_loss",
    "l2_penalty",
    "backprop",
    "loss_and_gradients",
    "train_epochs",
    "pack",
    "unpack",
]

#: Hidden-layer activations.
ACTIVATIONS = ("identity", "logistic", "tanh", "relu")
#: Output activations, each with its loss.
OUTPUT_ACTIVATIONS = ("softmax", "logistic", "identity")


def activate(name: str, z: np.ndarray) -> np.ndarray:
    """The activation :math:`f(z)`, a new array (``z`` is left as it is; logistic via ``expit``:
    no overflow).

    Examples
    --------
    >>> z = np.array([-1.0, 2.0])
    >>> activate("relu", z), z
    (array([0., 2.]), array([-1.,  2.]))
    """
    if name == "tanh":
        return np.tanh(z)
    if name == "relu":
        return np.maximum(z, 0.0)
    if name == "logistic":
        return expit(z)
    check_choice("name", name, ACTIVATIONS)  # only "identity" is left
    return z.copy()


def activation_derivative(name: str, a: np.ndarray, delta: np.ndarray) -> np.ndarray:
    """``delta`` times the activation's derivative :math:`f'(z)`, written with its output
    ``a = f(z)``: a new array.

    ``'tanh'``: :math:`1 - a^2`; ``'logistic'``: :math:`a (1 - a)`; ``'relu'``: 1 where
    :math:`a > 0`, else 0 (the entries are set to 0, not multiplied, so that an infinite
    ``delta`` gives 0 there and not NaN); ``'identity'``: 1.

    Parameters
    ----------
    name : str
        Hidden-layer activation, one of :data:`ACTIVATIONS`.
    a : ndarray
        The activation's output.
    delta : ndarray of ``a``'s shape
        The gradient to multiply; not modified.

    Returns
    -------
    ndarray
        :math:`\\delta \\odot f'(z)`.

    Examples
    --------
    >>> activation_derivative("tanh", np.array([0.0, 0.5]), np.ones(2))
    array([1.  , 0.75])
    """
    if name == "tanh":
        return delta * (1.0 - a * a)
    if name == "relu":
        return np.where(a <= 0, 0.0, delta)
    if name == "logistic":
        return delta * ((1.0 - a) * a)
    check_choice("name", name, ACTIVATIONS)  # only "identity" is left
    return delta.copy()


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
    check_choice("activation", activation, ACTIVATIONS)
    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"rng must be a numpy.random.Generator, got {type(rng).__name__}")
    if isinstance(sizes, str | bytes) or not hasattr(sizes, "__len__") or len(sizes) < 2:
        raise ValueError(f"sizes must list 2 layer widths at least (input and output), got "
                         f"{describe(sizes)}")
    sizes = [check_int("sizes", w, minimum=1) for w in sizes]
    check_allocation(8 * sum(a * b + b for a, b in zip(sizes[:-1], sizes[1:], strict=True)),
                     parameter="sizes", what="the weights")
    factor = 2.0 if activation == "logistic" else 6.0
    coefs, intercepts = [], []
    for fan_in, fan_out in zip(sizes[:-1], sizes[1:], strict=True):
        bound = np.sqrt(factor / (fan_in + fan_out))
        coefs.append(rng.uniform(-bound, bound, (fan_in, fan_out)))
        intercepts.append(rng.uniform(-bound, bound, fan_out))
    return coefs, intercepts


def _check_network(X, coefs, intercepts, activation: str) -> None:
    """Refuse a network whose layers do not chain: ``coefs`` and ``intercepts`` lists of one
    2-D weight matrix and one bias vector per layer, each layer's fan-in the previous one's
    fan-out, the first the columns of ``X``. Shapes only (the values are the training's own)."""
    check_choice("activation", activation, ACTIVATIONS)
    for name, layers in (("coefs", coefs), ("intercepts", intercepts)):
        if not isinstance(layers, list | tuple) or not layers:
            raise TypeError(f"{name} must be a non-empty list of arrays, one per layer, got "
                            f"{type(layers).__name__}")
    if len(coefs) != len(intercepts):
        raise ValueError(f"intercepts must hold one bias vector per weight matrix of coefs "
                         f"({len(coefs)}), got {len(intercepts)}")
    if getattr(X, "ndim", None) != 2:
        raise ValueError(f"X must be a 2-D array (n_samples, n_features), got "
                         f"{type(X).__name__} {getattr(X, 'shape', '')}")
    fan_in = X.shape[1]
    for layer, (W, b) in enumerate(zip(coefs, intercepts, strict=True)):
        shape = getattr(W, "shape", None)
        if shape is None or len(shape) != 2 or shape[0] != fan_in:
            raise ValueError(f"coefs[{layer}] must be a ({fan_in}, fan_out) weight matrix, got "
                             f"{type(W).__name__} {shape or ''}")
        if np.shape(b) != (shape[1],):
            raise ValueError(f"intercepts[{layer}] must hold {shape[1]} biases, got shape "
                             f"{np.shape(b)}")
        fan_in = shape[1]


def forward(X, coefs, intercepts, activation: str) -> list[np.ndarray]:
    """Activations of every layer, ``X`` first; the last entry is the output pre-activation.

    :math:`z_l = a_{l-1} W_l + b_l`, then :math:`a_l = f(z_l)` on the hidden layers; the output
    layer's nonlinearity belongs to the loss (:func:`output_loss`).

    Parameters
    ----------
    X : ndarray or scipy.sparse matrix of shape (n_samples, n_features)
        Inputs (float; a sparse matrix is multiplied by scipy, its stored entries only).
    coefs, intercepts : list of ndarray
        Weight matrices (fan_in, fan_out) and bias vectors (fan_out,).
    activation : str
        Hidden-layer activation, one of :data:`ACTIVATIONS`.

    Returns
    -------
    list of ndarray
        ``[X, a_1, ..., a_{N-1}, z_N]``.

    Examples
    --------
    >>> acts = forward(np.ones((1, 2)), [np.ones((2, 1))], [np.zeros(1)], "relu")
    >>> acts[-1]
    array([[2.]])
    """
    _check_network(X, coefs, intercepts, activation)
    acts = [X]
    last = len(coefs) - 1
    for layer, (W, b) in enumerate(zip(coefs, intercepts, strict=True)):
        z = acts[-1] @ W + b
        if layer < last:
            z = activate(activation, z)
        acts.append(z)
    return acts


def output_loss(out_activation: str, z: np.ndarray, Y: np.ndarray) -> tuple[float, np.ndarray]:
    """Mean loss per sample at the output pre-activations ``z`` and its gradient with respect
    to ``z``.

    ``'softmax'``: :math:`\\ell = \\frac1n \\sum_i (\\log\\sum_k e^{z_{ik}} - y_i \\cdot z_i)`,
    which is the cross-entropy :math:`-\\frac1n\\sum_{ik} y_{ik}\\log p_{ik}` of the softmax
    probabilities :math:`p` for targets whose rows sum to 1; :math:`\\delta = (p - y)/n`.
    ``'logistic'``: :math:`\\ell = -\\frac1n\\sum [y\\log\\sigma(z) + (1-y)\\log\\sigma(-z)]`;
    :math:`\\delta = (\\sigma(z) - y)/n`. ``'identity'``: :math:`\\ell = \\frac{1}{2nm}\\sum(z-y)^2`
    over ``m`` outputs; :math:`\\delta = (z - y)/(nm)`.

    Parameters
    ----------
    out_activation : {'softmax', 'logistic', 'identity'}
        Output activation: cross-entropy for the first two, half the mean squared error over all
        entries for 'identity'.
    z : ndarray of shape (n_samples, n_outputs)
        Output pre-activations (logits); not modified.
    Y : ndarray of shape (n_samples, n_outputs)
        Encoded targets (one-hot or 0/1 for classes).

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
        # log-sum-exp shifted by the row maximum: no overflow, exact for saturated logits
        shift = z.max(axis=1, keepdims=True)
        e = np.exp(z - shift)
        total = e.sum(axis=1, keepdims=True)
        log_sum_exp = np.log(total) + shift
        loss = float(log_sum_exp.sum() - np.einsum("ij,ij->", Y, z)) / n
        return loss, (e / total - Y) / n
    if out_activation == "logistic":
        # log_expit(z) = log(sigma(z)), finite for any z
        loss = float(-np.sum(Y * log_expit(z) + (1.0 - Y) * log_expit(-z))) / n
        return loss, (expit(z) - Y) / n
    check_choice("out_activation", out_activation, OUTPUT_ACTIVATIONS)  # only "identity" left
    diff = z - Y
    loss = 0.5 * float(np.mean(diff * diff))
    return loss, diff / diff.size


def l2_penalty(coefs, alpha: float, n_samples: int) -> float:
    """The weight-decay term :math:`\\frac{\\alpha}{2n}\\sum_l \\lVert W_l \\rVert^2` of the loss
    (the biases are not penalised).

    Examples
    --------
    >>> l2_penalty([np.full((2, 1), 3.0)], alpha=1.0, n_samples=9)
    1.0
    """
    alpha = check_nonnegative("alpha", alpha)
    n_samples = check_int("n_samples", n_samples, minimum=1)
    # einsum, not a BLAS dot: no thread start-up for a reduction this small
    squares = sum(float(np.einsum("ij,ij->", W, W)) for W in coefs)
    return 0.5 * alpha * squares / n_samples


def backprop(acts, delta, coefs, activation: str, alpha_per_sample: float):
    """Gradients of every weight matrix and bias vector, from the output gradient backwards.

    The chain rule, layer by layer from the last:
    :math:`\\partial L/\\partial W_l = a_{l-1}^T \\delta_l + (\\alpha/n) W_l`,
    :math:`\\partial L/\\partial b_l = \\sum \\delta_l` (``delta`` holds the :math:`1/n` of the
    mean loss), then :math:`\\delta_{l-1} = (\\delta_l W_l^T) \\odot f'(z_{l-1})`.

    Parameters
    ----------
    acts : list of ndarray
        The activations from :func:`forward`.
    delta : ndarray of shape (n_samples, n_outputs)
        Gradient of the data loss with respect to the output pre-activations
        (from :func:`output_loss`); not modified.
    coefs : list of ndarray
        Weight matrices.
    activation : str
        Hidden-layer activation.
    alpha_per_sample : float
        L2 coefficient divided by the number of samples: the penalty
        :math:`\\frac{\\alpha}{2n}\\sum_l \\lVert W_l \\rVert^2` adds ``alpha_per_sample * W`` to
        each weight gradient.

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
    if not isinstance(acts, list | tuple) or not isinstance(coefs, list | tuple) or (
            len(acts) != len(coefs) + 1):
        raise ValueError("acts must be the activations from forward: one more array than coefs")
    _check_network(acts[0], coefs, [np.empty(getattr(W, "shape", (0, 0))[-1]) for W in coefs],
                   activation)
    n_out = coefs[-1].shape[1]
    if np.shape(delta) != (acts[0].shape[0], n_out):
        raise ValueError(f"delta must have shape (n_samples, n_outputs) = "
                         f"{(acts[0].shape[0], n_out)}, got {np.shape(delta)}")
    alpha_per_sample = check_nonnegative("alpha_per_sample", alpha_per_sample)
    n_layers = len(coefs)
    coef_grads, intercept_grads = [None] * n_layers, [None] * n_layers
    for layer in reversed(range(n_layers)):
        # layer = l - 1: coefs[layer] is W_l, acts[layer] is a_{l-1} (acts[0] is X)
        coef_grads[layer] = acts[layer].T @ delta + coefs[layer] * alpha_per_sample
        intercept_grads[layer] = delta.sum(axis=0)
        if layer > 0:
            delta = activation_derivative(activation, acts[layer], delta @ coefs[layer].T)
    return coef_grads, intercept_grads


def loss_and_gradients(X, Y, coefs, intercepts, activation: str, out_activation: str,
                       alpha: float):
    """The loss :math:`L = \\ell + \\frac{\\alpha}{2n}\\sum_l \\lVert W_l \\rVert^2` and its
    gradient with respect to every weight and bias: one forward and one backward pass.

    Parameters
    ----------
    X : ndarray or scipy.sparse matrix of shape (n_samples, n_features)
    Y : ndarray of shape (n_samples, n_outputs)
        Encoded targets.
    coefs, intercepts : list of ndarray
    activation : str
        Hidden-layer activation, one of :data:`ACTIVATIONS`.
    out_activation : str
        Output activation, one of :data:`OUTPUT_ACTIVATIONS`.
    alpha : float
        L2 coefficient (divided by ``n_samples`` in the loss).

    Returns
    -------
    loss : float
    coef_grads, intercept_grads : list of ndarray

    Examples
    --------
    >>> loss, coef_grads, intercept_grads = loss_and_gradients(
    ...     np.ones((2, 1)), np.zeros((2, 1)), [np.ones((1, 1))], [np.zeros(1)], "relu",
    ...     "identity", alpha=0.0)
    >>> loss, coef_grads, intercept_grads
    (0.5, [array([[1.]])], [array([1.])])
    """
    _check_network(X, coefs, intercepts, activation)
    n = X.shape[0]
    if np.shape(Y) != (n, coefs[-1].shape[1]):
        raise ValueError(f"Y must have shape (n_samples, n_outputs) = {(n, coefs[-1].shape[1])}, "
                         f"got {np.shape(Y)}")
    alpha = check_nonnegative("alpha", alpha)
    acts = forward(X, coefs, intercepts, activation)
    data_loss, delta = output_loss(out_activation, acts[-1], Y)
    loss = data_loss + l2_penalty(coefs, alpha, n)
    coef_grads, intercept_grads = backprop(acts, delta, coefs, activation, alpha / n)
    return loss, coef_grads, intercept_grads


def train_epochs(X, Y, coefs, intercepts, optimizer, *, activation: str, out_activation: str,
                 alpha: float, batch_size: int, n_epochs: int, rng=None, end_of_epoch=None):
    """Mini-batch training as the textbook writes it: the reference of the estimators' loop.

    Each epoch shuffles the samples (when ``rng`` is given), then for each batch of
    ``batch_size`` rows evaluates :func:`loss_and_gradients` and lets the ``optimizer`` move
    the weights and biases, in place. ``MLPClassifier(engine="reference")`` and
    ``MLPRegressor(engine="reference")`` train their 'gd', 'sgd' and 'adam' solvers with it.

    Parameters
    ----------
    X, Y, coefs, intercepts, activation, out_activation, alpha
        As for :func:`loss_and_gradients`; ``coefs`` and ``intercepts`` are moved in place.
    optimizer : ebantenna.ml.optimizers.Adam or ebantenna.ml.optimizers.Momentum
        Made for the list ``[*coefs, *intercepts]``; any object with the method
        ``update(params, grads)`` that moves ``params`` in place will do.
    batch_size : int
        Rows of a batch; the last batch of an epoch may be shorter. A batch of all the rows is
        ``X`` itself, in its order.
    n_epochs : int
        Passes over the samples.
    rng : numpy.random.Generator, optional
        Shuffles the order of the samples at the start of every epoch; None keeps their order.
    end_of_epoch : callable, optional
        ``end_of_epoch(mean_loss) -> bool`` after each epoch; True stops the training.

    Returns
    -------
    list of float
        The mean loss of each epoch run (over its batches, weighted by their sizes).

    Examples
    --------
    >>> from ebantenna.ml.optimizers import Adam
    >>> rng = np.random.default_rng(0)
    >>> X = rng.normal(size=(40, 2))
    >>> Y = np.eye(2)[(X[:, 0] > 0).astype(int)]
    >>> coefs, intercepts = glorot_uniform([2, 4, 2], "tanh", rng)
    >>> losses = train_epochs(X, Y, coefs, intercepts, Adam([*coefs, *intercepts], 0.05),
    ...                       activation="tanh", out_activation="softmax", alpha=0.0,
    ...                       batch_size=10, n_epochs=30, rng=rng)
    >>> bool(losses[-1] < losses[0] / 2)
    True
    """
    batch_size = check_int("batch_size", batch_size, minimum=1)
    n_epochs = check_int("n_epochs", n_epochs, minimum=0)
    if not callable(getattr(optimizer, "update", None)):
        raise TypeError(f"optimizer must have a method update(params, grads), got "
                        f"{type(optimizer).__name__}")
    if rng is not None and not isinstance(rng, np.random.Generator):
        raise TypeError(f"rng must be a numpy.random.Generator or None, got {type(rng).__name__}")
    if end_of_epoch is not None and not callable(end_of_epoch):
        raise TypeError(f"end_of_epoch must be callable or None, got {type(end_of_epoch).__name__}")
    n = X.shape[0]
    order = np.arange(n)
    params = [*coefs, *intercepts]
    losses = []
    for _ in range(n_epochs):
        if rng is not None:
            rng.shuffle(order)
        total = 0.0
        for start in range(0, n, batch_size):
            rows = order[start : start + batch_size]
            Xb, Yb = (X, Y) if batch_size >= n else (X[rows], Y[rows])
            loss, coef_grads, intercept_grads = loss_and_gradients(
                Xb, Yb, coefs, intercepts, activation, out_activation, alpha)
            optimizer.update(params, [*coef_grads, *intercept_grads])
            total += loss * Xb.shape[0]
        losses.append(total / n)
        if end_of_epoch is not None and end_of_epoch(losses[-1]):
            break
    return losses


def pack(coefs, intercepts) -> np.ndarray:
    """All weights and biases in one flat vector, layer by layer (weights, then biases).

    Examples
    --------
    >>> pack([np.ones((2, 1))], [np.zeros(1)])
    array([1., 1., 0.])
    """
    coefs, intercepts = list(coefs), list(intercepts)
    if len(coefs) != len(intercepts):
        raise ValueError(f"coefs and intercepts must list one array per layer, got {len(coefs)} "
                         f"and {len(intercepts)}")
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
    shapes = [(check_int("shapes", a, minimum=1), check_int("shapes", b, minimum=1))
              for a, b in shapes]
    if np.ndim(w) != 1 or np.size(w) != sum(a * b + b for a, b in shapes):
        raise ValueError(f"w must be a flat vector of {sum(a * b + b for a, b in shapes)} "
                         f"weights and biases for these shapes, got shape {np.shape(w)}")
    coefs, intercepts, pos = [], [], 0
    for fan_in, fan_out in shapes:
        coefs.append(w[pos : pos + fan_in * fan_out].reshape(fan_in, fan_out))
        pos += fan_in * fan_out
        intercepts.append(w[pos : pos + fan_out])
        pos += fan_out
    return coefs, intercepts
