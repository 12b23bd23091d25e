"""Backpropagation: the training engine against the textbook reference (bit for bit), the
reference against central finite differences, and the training loop on the engine."""

import warnings

import numpy as np
import pytest
import scipy.sparse as sp
from sklearn.exceptions import ConvergenceWarning

from ebantenna.ml import MLPClassifier, _mlp_numba
from ebantenna.ml._backprop_engine import Workspace, loss_and_gradients_into
from ebantenna.ml.backprop import (
    activation_derivative,
    glorot_uniform,
    loss_and_gradients,
    pack,
    unpack,
)

EPS = np.finfo(float).eps
SIZES = [6, 7, 4, 3]


def _problem(out_activation, activation, n=25, seed=5, sparse=False, sizes=SIZES):
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(n, sizes[0]))
    if sparse:
        X[np.abs(X) < 0.7] = 0.0
        X = sp.csr_matrix(X)
    coefs, intercepts = glorot_uniform(sizes, activation, rng)
    if out_activation == "identity":
        Y = rng.normal(size=(n, sizes[-1]))
    elif out_activation == "softmax":
        Y = np.eye(sizes[-1])[rng.integers(0, sizes[-1], n)]
    else:  # logistic: several labels
        Y = (rng.random((n, sizes[-1])) < 0.5).astype(float)
    return X, Y, coefs, intercepts


@pytest.mark.parametrize("sizes", [SIZES, [6, 1, 5, 1]])
@pytest.mark.parametrize("compiled", [False, True])
@pytest.mark.parametrize("sparse", [False, True])
@pytest.mark.parametrize("activation", ["tanh", "logistic", "identity", "relu"])
@pytest.mark.parametrize("out_activation", ["softmax", "logistic", "identity"])
def test_engine_equals_reference_bit_for_bit(activation, out_activation, sparse, compiled,
                                             sizes):
    """The engine claims the reference's arithmetic in reused arrays: the same bits, also when
    its arrays still hold the previous batch's values and the gradient lands in views of one
    flat vector; and with the compiled loops (run as Python loops when numba is missing, so
    that their arithmetic is checked either way). Layers of one unit too: NumPy sums a single
    column pairwise, several columns row after row."""
    if out_activation == "softmax" and sizes[-1] == 1:
        pytest.skip("a softmax over one output is constant")
    X, Y, coefs, intercepts = _problem(out_activation, activation, sparse=sparse, sizes=sizes)
    loss, coef_grads, intercept_grads = loss_and_gradients(
        X, Y, coefs, intercepts, activation, out_activation, alpha=0.3)
    work = Workspace(X.shape[0], sizes, _mlp_numba if compiled else None)
    flat = np.empty(pack(coefs, intercepts).size)
    grads = unpack(flat, [c.shape for c in coefs])
    for _ in range(2):  # the second pass writes over the arrays of the first
        engine_loss = loss_and_gradients_into(X, Y, coefs, intercepts, activation,
                                              out_activation, 0.3, grads, work)
        assert engine_loss == loss
        assert np.array_equal(flat, pack(coef_grads, intercept_grads))


def test_reference_leaves_its_inputs_alone():
    X, Y, coefs, intercepts = _problem("softmax", "tanh")
    before = [a.copy() for a in (X, Y, *coefs, *intercepts)]
    loss_and_gradients(X, Y, coefs, intercepts, "tanh", "softmax", alpha=0.1)
    for a, b in zip(before, (X, Y, *coefs, *intercepts), strict=True):
        assert np.array_equal(a, b)


@pytest.mark.parametrize("activation", ["tanh", "logistic", "identity"])
@pytest.mark.parametrize("out_activation", ["softmax", "logistic", "identity"])
def test_reference_gradient_matches_central_differences(activation, out_activation):
    """(f(w + h e) - f(w - h e)) / 2h = f'(w) + h^2 f'''(xi) / 6 + r.

    Truncation: along one coordinate, f''' is a mean over the samples of products of the
    activations' and losses' derivatives (the third ones at most 2 in size for tanh, logistic
    and the cross-entropies) with weights below 1 (Glorot) and unit-scale inputs: below 10 here.
    Rounding: each loss value is a sum over n samples of terms built from dot products of at
    most sum(SIZES) terms and a few exp/log, so its error is at most (n + sum(SIZES) + 10) eps |f|
    (recursive summation, gamma_k); the difference of two of them, divided by 2h, adds
    r <= (n + sum(SIZES) + 10) eps |f| / h. h = 1e-5 makes both terms small.
    """
    X, Y, coefs, intercepts = _problem(out_activation, activation, n=12, seed=8)
    shapes = [c.shape for c in coefs]
    w = pack(coefs, intercepts)

    def loss_at(v):
        c, b = unpack(v, shapes)
        return loss_and_gradients(X, Y, c, b, activation, out_activation, alpha=0.7)[0]

    loss, coef_grads, intercept_grads = loss_and_gradients(
        X, Y, coefs, intercepts, activation, out_activation, alpha=0.7)
    grad = pack(coef_grads, intercept_grads)
    h = 1e-5
    terms = X.shape[0] + sum(SIZES) + 10
    bound = 10.0 * h**2 / 6.0 + terms * EPS * max(1.0, abs(loss)) / h
    for i in np.random.default_rng(0).choice(w.size, size=30, replace=False):
        up, down = w.copy(), w.copy()
        up[i] += h
        down[i] -= h
        assert abs((loss_at(up) - loss_at(down)) / (2 * h) - grad[i]) <= bound


def test_relu_derivative_zeroes_an_infinite_delta():
    """The relu's derivative is 0 for a <= 0: the entry is set, not multiplied (inf * 0 = NaN)."""
    delta = np.array([np.inf, -np.inf, 2.0])
    assert np.array_equal(activation_derivative("relu", np.array([0.0, 1.0, -1.0]), delta),
                          [0.0, -np.inf, 0.0])
    assert np.array_equal(delta, [np.inf, -np.inf, 2.0])  # the input is left as it is


def test_lbfgs_ignores_early_stopping():
    """As scikit-learn's: 'lbfgs' trains on the whole set and keeps no validation scores."""
    rng = np.random.default_rng(0)
    X = rng.normal(size=(40, 3))
    y = (X[:, 0] > 0).astype(int)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        clf = MLPClassifier((3,), solver="lbfgs", early_stopping=True, max_iter=5,
                            random_state=0).fit(X, y)
        plain = MLPClassifier((3,), solver="lbfgs", max_iter=5, random_state=0).fit(X, y)
    assert clf.validation_scores_ is None and clf.best_validation_score_ is None
    for a, b in zip(clf.coefs_ + clf.intercepts_, plain.coefs_ + plain.intercepts_, strict=True):
        assert np.array_equal(a, b)


def _same_network(a, b) -> bool:
    """The same weights, biases and loss curve, to the last bit."""
    return (all(np.array_equal(p, q) for p, q in
                zip(a.coefs_ + a.intercepts_, b.coefs_ + b.intercepts_, strict=True))
            and a.loss_curve_ == b.loss_curve_)


@pytest.mark.parametrize("solver", ["adam", "sgd", "gd", "scg", "lbfgs"])
@pytest.mark.parametrize("target", ["classes", "labels", "outputs"])
def test_engine_reference_trains_the_same_network_bit_for_bit(solver, target):
    # engine='reference' trains with ebantenna.ml.backprop's functions and NumPy's optimiser
    # steps; the engine claims their arithmetic, so the networks must be identical
    from ebantenna.ml import MLPRegressor

    rng = np.random.default_rng(3)
    X = rng.normal(size=(90, 5))
    if target == "classes":
        cls, y = MLPClassifier, (X[:, 0] > 0).astype(int) + (X[:, 1] > 0.5)
    elif target == "labels":
        cls, y = MLPClassifier, (X[:, :3] > 0).astype(int)
    else:
        cls, y = MLPRegressor, X[:, :2] @ np.array([[1.0, -0.5], [0.3, 2.0]])
    params = dict(hidden_layer_sizes=(6, 4), activation="tanh", solver=solver, max_iter=8,
                  batch_size=32, random_state=0, early_stopping=solver == "adam")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        engine = cls(**params).fit(X, y)
        reference = cls(engine="reference", **params).fit(X, y)
        assert _same_network(engine, reference)
        if solver in ("adam", "sgd"):  # partial_fit continues the same way on both
            engine.set_params(early_stopping=False).partial_fit(X, y)
            reference.set_params(early_stopping=False).partial_fit(X, y)
            assert _same_network(engine, reference)


def test_engine_takes_two_names_only():
    from ebantenna.ml.optimizers import Adam

    X, y = np.zeros((4, 2)), np.array([0, 1, 0, 1])
    with pytest.raises(ValueError, match="'engine' parameter of MLPClassifier"):
        MLPClassifier(engine="numba").fit(X, y)
    with pytest.raises(TypeError, match="engine"):  # the reference has one engine: itself
        Adam([np.zeros(2)], engine="fast")


@pytest.mark.parametrize("name", ["identity", "tanh", "relu", "logistic"])
def test_activate_and_its_derivative_leave_their_inputs_alone(name):
    from ebantenna.ml.backprop import activate

    z = np.array([-2.0, -0.0, 0.5, 3.0])
    a = activate(name, z)
    delta = np.array([1.0, -2.0, 3.0, np.inf])
    activation_derivative(name, a, delta)
    assert np.array_equal(z, [-2.0, -0.0, 0.5, 3.0])
    assert np.array_equal(delta, [1.0, -2.0, 3.0, np.inf])
    assert not np.shares_memory(a, z)


@pytest.mark.parametrize("solver", ["adam", "sgd"])
def test_the_reference_loop_trains_the_default_engines_network_bit_for_bit(solver):
    # train_epochs with the textbook optimiser, from the estimator's own start (its generator
    # draws the initial weights, then the shuffles), against a fit on the default engine: the
    # engine claims the reference's operations in their order, so the weights are identical.
    from ebantenna.ml.backprop import glorot_uniform, train_epochs
    from ebantenna.ml.optimizers import Adam, Momentum

    rng = np.random.default_rng(8)
    X = rng.normal(size=(70, 4))
    y = (X[:, 0] > 0).astype(int) + (X[:, 1] > 0.3)
    params = dict(hidden_layer_sizes=(5,), activation="tanh", solver=solver, batch_size=16,
                  max_iter=6, tol=0.0, n_iter_no_change=100, random_state=2)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        engine = MLPClassifier(**params).fit(X, y)
    draws = np.random.default_rng(2)
    coefs, intercepts = glorot_uniform([4, 5, 3], "tanh", draws)
    weights = [*coefs, *intercepts]
    optimizer = (Adam(weights, 1e-3) if solver == "adam"
                 else Momentum(weights, 1e-3, 0.9, nesterov=True))
    losses = train_epochs(X, np.eye(3)[y], coefs, intercepts, optimizer, activation="tanh",
                          out_activation="softmax", alpha=1e-4, batch_size=16, n_epochs=6,
                          rng=draws)
    assert losses == engine.loss_curve_
    for a, b in zip(weights, engine.coefs_ + engine.intercepts_, strict=True):
        assert np.array_equal(a, b)
