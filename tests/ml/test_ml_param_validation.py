"""Parameters are checked by scikit-learn's constraint mechanism, with scikit-learn's words."""

import re

import numpy as np
import pytest
from sklearn.neural_network import MLPClassifier as SkClassifier
from sklearn.neural_network import MLPRegressor as SkRegressor
from sklearn.utils._param_validation import InvalidParameterError

from ebantenna.ml import MLPClassifier, MLPRegressor

X = np.random.default_rng(0).normal(size=(12, 3))
Y = {MLPRegressor: X[:, 0], MLPClassifier: (X[:, 0] > 0).astype(int)}
THEIRS = {MLPRegressor: SkRegressor, MLPClassifier: SkClassifier}
OURS = {theirs: ours for ours, theirs in THEIRS.items()}


def _in_set_order(message):
    """The message with the options inside {...} sorted: a set's order is not reproducible."""
    return re.sub(r"\{([^}]*)\}", lambda m: "{" + ", ".join(sorted(m[1].split(", "))) + "}",
                  message)


def _raised(estimator, params):
    with pytest.raises((ValueError, TypeError)) as info:
        estimator(**params).fit(X, Y[OURS.get(estimator, estimator)])
    return info


@pytest.mark.parametrize("ours", [MLPRegressor, MLPClassifier])
@pytest.mark.parametrize("params", [
    dict(alpha=-1.0), dict(learning_rate_init=0.0), dict(power_t=-0.5), dict(momentum=1.5),
    dict(max_iter=0), dict(max_iter=2.5), dict(batch_size=2.5), dict(batch_size="big"),
    dict(beta_1=1.0), dict(beta_2=-0.1), dict(epsilon=0.0), dict(tol=-1.0),
    dict(activation="softplus"), dict(learning_rate="fast"), dict(shuffle="yes"),
    dict(early_stopping=1), dict(n_iter_no_change=0), dict(hidden_layer_sizes="wide"),
    dict(hidden_layer_sizes=(4, 0)),
])
def test_bad_parameter_gives_scikit_learns_message(ours, params):
    mine = _raised(ours, params)
    theirs = _raised(THEIRS[ours], params)
    # the same error type and the same sentence, naming the parameter and the allowed values
    assert mine.type is theirs.type
    assert _in_set_order(str(mine.value)) == _in_set_order(str(theirs.value))
    assert next(iter(params)) in str(mine.value)


@pytest.mark.parametrize("params, allowed", [
    (dict(solver="newton"), ["'gd'", "'sgd'", "'adam'", "'scg'", "'lbfgs'"]),
    (dict(validation_fraction=0.0), ["range (0.0, 1.0)"]),  # 0 would leave no validation data
    (dict(random_state=-1), ["None", "Generator"]),
])
def test_own_options_are_named_in_the_same_words(params, allowed):
    with pytest.raises(InvalidParameterError, match="parameter of MLPRegressor must be") as info:
        MLPRegressor(**params).fit(X, Y[MLPRegressor])
    for words in allowed:
        assert words in str(info.value)


def test_hidden_layer_sizes_must_hold_integers():
    with pytest.raises(TypeError, match=r"hidden_layer_sizes must contain integers, got \[2.5\]"):
        MLPRegressor(hidden_layer_sizes=[2.5]).fit(X, Y[MLPRegressor])


def test_n_iter_no_change_may_be_infinite_as_in_scikit_learn():
    reg = MLPRegressor(hidden_layer_sizes=(3,), max_iter=5, n_iter_no_change=np.inf,
                       random_state=0)
    with pytest.warns(UserWarning, match="maximum iterations"):
        reg.fit(X, Y[MLPRegressor])
    assert reg.n_iter_ == 5


@pytest.mark.parametrize("params", [
    dict(degree=-1), dict(gamma="wide"),
    dict(gamma=-1.0), dict(coef0="0"), dict(shrinking="no"), dict(tol=0.0), dict(cache_size=0),
    dict(class_weight="even"), dict(decision_function_shape="ovx"), dict(break_ties=2.0),
])
def test_svc_gives_scikit_learns_message(params):
    from sklearn.svm import SVC as SkSVC

    from ebantenna.ml import SVC

    y = (X[:, 0] > 0).astype(int)
    with pytest.raises(InvalidParameterError) as mine:
        SVC(**params).fit(X, y)
    with pytest.raises(InvalidParameterError) as theirs:
        SkSVC(**params).fit(X, y)
    assert _in_set_order(str(mine.value)) == _in_set_order(str(theirs.value))


@pytest.mark.parametrize("params, match", [
    (dict(max_iter=0), r"'max_iter' parameter of SVC must be .*range \[1, inf\).* among \{-1\}"),
    (dict(C=0.0), r"'C' parameter of SVC must be a float in the range \(0.0, inf\)"),
    (dict(C=np.inf), r"'C' parameter of SVC must be a float in the range \(0.0, inf\)"),
    (dict(selection="random"), "'selection' parameter of SVC must be a str among"),
    (dict(kernel="cosine"), "'kernel' parameter of SVC must be a str among"),
])
def test_svc_own_constraints(params, match):
    from ebantenna.ml import SVC

    with pytest.raises(ValueError, match=match):
        SVC(**params).fit(X, (X[:, 0] > 0).astype(int))
