"""Saved models reload to identical predictions without pickle; metrics against scikit-learn."""

import json
import warnings

import numpy as np
import pytest
import sklearn.metrics as skm
from scipy.stats import binomtest
from sklearn.exceptions import ConvergenceWarning

from ebantenna.ml import SVC, MLPClassifier, MLPRegressor
from ebantenna.ml.metrics import (
    absolute_errors,
    accuracy,
    accuracy_interval,
    confusion_matrix,
    per_class_rates,
)
from ebantenna.ml.persistence import load_model, save_model


def _data(seed=0):
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(90, 4))
    y = np.array(["al", "brass", "pvc"])[(X[:, 0] > 0).astype(int) + (X[:, 1] > 0.5)]
    return X, y


@pytest.mark.parametrize("model", [
    SVC(C=3.0, gamma=0.5),
    SVC(kernel="poly", degree=2, decision_function_shape="ovo"),
    MLPClassifier(hidden_layer_sizes=(6, 4), activation="tanh", solver="scg", max_iter=30),
    MLPRegressor(hidden_layer_sizes=(5,), solver="adam", max_iter=30),
])
def test_round_trip_is_exact_and_pickle_free(model, tmp_path):
    X, y = _data()
    target = X[:, :2] if isinstance(model, MLPRegressor) else y
    model.set_params(random_state=0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        model.fit(X, target)
    path = save_model(model, tmp_path / "model")
    assert path.suffix == ".npz"
    with np.load(path, allow_pickle=False) as data:  # loads without pickle
        meta = json.loads(str(data["__meta__"]))
    assert meta["class"] == type(model).__name__
    again = load_model(path)
    assert again.get_params() == model.get_params()
    np.testing.assert_array_equal(again.predict(X), model.predict(X))
    if hasattr(model, "decision_function"):
        np.testing.assert_array_equal(again.decision_function(X), model.decision_function(X))
    if hasattr(model, "predict_proba"):
        np.testing.assert_array_equal(again.predict_proba(X), model.predict_proba(X))


def test_save_refuses_unfitted_and_foreign_models(tmp_path):
    from sklearn.svm import SVC as LibSVC

    with pytest.raises(ValueError, match="fitted"):
        save_model(SVC(), tmp_path / "a")
    with pytest.raises(TypeError, match="model"):
        save_model(LibSVC().fit([[0.0], [1.0]], [0, 1]), tmp_path / "b")


def test_load_refuses_other_npz(tmp_path):
    np.savez(tmp_path / "x.npz", a=np.zeros(3))
    with pytest.raises(ValueError, match="metadata"):
        load_model(tmp_path / "x.npz")


def test_confusion_matrix_and_rates_against_sklearn():
    rng = np.random.default_rng(3)
    labels = ["al", "brass", "pvc", "steel", "wood"]
    t = rng.choice(labels, 500)
    p = np.where(rng.random(500) < 0.7, t, rng.choice(labels, 500))
    order = ["wood", "al", "steel", "brass", "pvc"]  # any order of rows/columns
    ours = confusion_matrix(t, p, labels=order)
    np.testing.assert_array_equal(ours, skm.confusion_matrix(t, p, labels=order))
    assert accuracy(ours) == pytest.approx(skm.accuracy_score(t, p), abs=1e-15)
    recall, precision = per_class_rates(ours)
    np.testing.assert_allclose(recall, skm.recall_score(t, p, labels=order, average=None))
    np.testing.assert_allclose(precision, skm.precision_score(t, p, labels=order, average=None))


def test_metrics_reject_bad_input():
    with pytest.raises(ValueError, match="y_true"):
        confusion_matrix([1, 2], [1], labels=[1, 2])
    with pytest.raises(ValueError, match="labels"):
        confusion_matrix([1], [1], labels=[1, 1])
    with pytest.raises(ValueError, match="matrix"):
        accuracy(np.zeros((2, 2)))
    with pytest.raises(ValueError, match="shapes"):
        absolute_errors([1.0], [1.0, 2.0])


@pytest.mark.parametrize(
    "correct, n", [(0, 1), (0, 7), (0, 10), (3, 7), (80, 100), (399, 400), (7, 7), (400, 400)]
)
def test_accuracy_interval_is_scipys_wilson_interval(correct, n):
    witness = binomtest(correct, n).proportion_ci(confidence_level=0.95, method="wilson")
    # a closed form of a few operations on numbers of order 1: agreement to a few ulps of 1
    np.testing.assert_allclose(accuracy_interval(correct, n), (witness.low, witness.high),
                               rtol=0, atol=1e-14)


@pytest.mark.parametrize("correct, n", [(-1, 5), (6, 5), (0, 0), (True, 5)])
def test_accuracy_interval_refuses_counts_that_are_not_a_proportion(correct, n):
    with pytest.raises((ValueError, TypeError), match="correct"):
        accuracy_interval(correct, n)
