"""What scikit-learn's MLPs report beside the weights: ``loss_``, the validation split of
``early_stopping`` and the score history that ``warm_start`` carries, against scikit-learn."""

import warnings

import numpy as np
import pytest
import sklearn.neural_network._multilayer_perceptron as sk_mlp
from mlp_reference import max_abs, rounding
from sklearn import datasets
from sklearn.exceptions import ConvergenceWarning
from sklearn.neural_network import MLPClassifier as SkClassifier
from sklearn.neural_network import MLPRegressor as SkRegressor

import ebantenna.ml.mlp_base as our_mlp
from ebantenna.ml import MLPClassifier, MLPRegressor

MAKE = {"classifier": (MLPClassifier, SkClassifier), "regressor": (MLPRegressor, SkRegressor)}


def _data(kind, n_classes=3, n=150, seed=0):
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(n, 6))
    if kind == "regressor":
        return X, X[:, 0] - 0.5 * X[:, 1] ** 2 + 0.1 * rng.normal(size=n)
    return X, (X[:, 0] + 0.7 * rng.normal(size=n) > 0).astype(int) + (
        X[:, 1] > 0.8 if n_classes == 3 else 0)


def _record_splits(monkeypatch):
    """The validation rows each library draws: train_test_split wrapped in both modules."""
    seen = {"ours": [], "sklearn": []}

    def recorder(name, split):
        def wrapped(*arrays, **kwargs):
            out = split(*arrays, **kwargs)
            seen[name].append(out[1].copy())  # X_val
            return out
        return wrapped

    monkeypatch.setattr(our_mlp, "train_test_split", recorder("ours", our_mlp.train_test_split))
    monkeypatch.setattr(sk_mlp, "train_test_split", recorder("sklearn", sk_mlp.train_test_split))
    return seen


def _same_start(ours, theirs, X, y, **then):
    """One epoch each (to set up), then our weights and score history copied into theirs and
    both fitted again with ``warm_start`` and the parameters ``then``."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        for est in (ours, theirs):
            est.set_params(max_iter=1).fit(X, y)
        # in place: scikit-learn's early stopping restores its best weights by aliasing
        # (coefs_ is _best_coefs after a fit, and its optimiser updates them in place)
        for mine, yours in zip(ours.coefs_ + ours.intercepts_,
                               theirs.coefs_ + theirs.intercepts_, strict=True):
            yours[...] = mine
        if ours.early_stopping:
            theirs.validation_scores_ = list(ours.validation_scores_)
            theirs.best_validation_score_ = ours.best_validation_score_
        for est in (ours, theirs):
            est.t_ = 0
            est.set_params(warm_start=True, **then).fit(X, y)


@pytest.mark.parametrize("kind", ["classifier", "regressor"])
@pytest.mark.parametrize("n_classes", [2, 3])
@pytest.mark.parametrize("random_state", [0, 5])
def test_early_stopping_draws_scikit_learns_validation_split(monkeypatch, kind, n_classes,
                                                               random_state):
    if kind == "regressor" and n_classes == 3:
        pytest.skip("one regression target")
    seen = _record_splits(monkeypatch)
    X, y = _data(kind, n_classes)
    ours, theirs = MAKE[kind]
    params = dict(hidden_layer_sizes=(4, 3), early_stopping=True, validation_fraction=0.2,
                  max_iter=3, random_state=random_state)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        for est in (ours(**params), theirs(**params)):
            est.fit(X, y)                               # fresh: after the initial weights
            est.set_params(warm_start=True).fit(X, y)   # warm: from a fresh RandomState
    assert len(seen["ours"]) == len(seen["sklearn"]) == 2
    for a, b in zip(seen["ours"], seen["sklearn"], strict=True):
        np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("kind, solver", [("classifier", "adam"), ("classifier", "sgd"),
                                          ("regressor", "adam"), ("classifier", "lbfgs"),
                                          ("regressor", "lbfgs")])
def test_loss_is_scikit_learns(kind, solver):
    X, y = _data(kind)
    ours, theirs = (make(hidden_layer_sizes=(5,), solver=solver, shuffle=False, alpha=0.01,
                         learning_rate_init=0.01, random_state=0) for make in MAKE[kind])
    epochs = 6
    _same_start(ours, theirs, X, y, max_iter=epochs)
    assert ours.n_iter_ == theirs.n_iter_
    # the same steps from the same weights: rounding of each step, carried with a gain below 2
    # (the bound of test_ml_mlp's several-epochs test); lbfgs runs the same SciPy minimiser
    atol = 2 * epochs * rounding(X, (5,), max_abs(theirs.coefs_ + theirs.intercepts_))
    assert abs(ours.loss_ - theirs.loss_) <= atol
    if solver != "lbfgs":
        assert ours.loss_ == ours.loss_curve_[-1]


@pytest.mark.parametrize("kind", ["classifier", "regressor"])
def test_warm_start_keeps_the_validation_history_as_scikit_learn(kind):
    X, y = _data(kind)
    ours, theirs = (make(hidden_layer_sizes=(5,), solver="sgd", shuffle=False,
                         learning_rate_init=0.05, early_stopping=True, validation_fraction=0.2,
                         n_iter_no_change=3, random_state=0) for make in MAKE[kind])
    _same_start(ours, theirs, X, y, max_iter=12)
    best_before = ours.best_validation_score_
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        for est in (ours, theirs):
            est.fit(X, y)  # a second warm refit: the history carries on
    assert ours.best_validation_score_ >= best_before
    assert len(ours.validation_scores_) == len(theirs.validation_scores_)
    # accuracies: counts of equal predictions; R^2: the rounding of the same steps
    atol = 0 if kind == "classifier" else 1e-9
    np.testing.assert_allclose(ours.validation_scores_, theirs.validation_scores_, rtol=0,
                               atol=atol)
    assert ours.best_validation_score_ == pytest.approx(theirs.best_validation_score_, abs=atol)
    assert ours.n_iter_ == theirs.n_iter_


def test_digits_logistic_early_stop_follows_scikit_learn_from_the_same_start():
    # The short run of the measurement (stopped at epoch 10, validation score 0.19) sat on the
    # plateau of a logistic network trained by plain SGD: the validation accuracy stays near
    # chance for many epochs while the units are near-symmetric, and early stopping ends the run
    # there. Whether a run leaves the plateau within n_iter_no_change epochs depends on its
    # initial weights and its validation split; from the same ones both libraries take the same
    # epochs, stop at the same one and report the same scores.
    X, y = datasets.load_digits(return_X_y=True)
    X = X / 16.0
    common = dict(activation="logistic", solver="sgd", shuffle=False, early_stopping=True,
                  random_state=0)
    ours, theirs = MLPClassifier(**common), SkClassifier(**common)
    _same_start(ours, theirs, X, y, max_iter=100)
    # the plateau stop itself: long before max_iter, far below what the network can reach
    assert ours.n_iter_ < 100 and ours.best_validation_score_ < 0.5
    assert ours.n_iter_ == theirs.n_iter_
    np.testing.assert_array_equal(ours.validation_scores_, theirs.validation_scores_)
    # the same steps: rounding of each, carried with a gain below 2 (small steps, rate 1e-3)
    n_steps = (ours.n_iter_ + 1) * int(np.ceil(0.9 * X.shape[0] / 200))
    atol = 2 * n_steps * rounding(X, (100,), max_abs(theirs.coefs_ + theirs.intercepts_))
    for a, b in zip(ours.coefs_ + ours.intercepts_, theirs.coefs_ + theirs.intercepts_,
                    strict=True):
        np.testing.assert_allclose(a, b, rtol=0, atol=atol)
