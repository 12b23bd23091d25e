"""A continued fit (``warm_start``) on 1-D string labels finds each label's output column by one
binary search in ``classes_`` instead of sorting the labels again (the per-epoch loop of the
paper's gradient descent calls ``fit`` a thousand times). The witness is the general path: the
same labels as an object array, which goes through scikit-learn's ``LabelBinarizer``; the two
must train the same network to the last bit."""

import warnings

import numpy as np
import pytest
from sklearn.exceptions import ConvergenceWarning

from ebantenna.ml import MLPClassifier


def _epochs(labels, X, n_epochs=4):
    model = MLPClassifier(hidden_layer_sizes=(4,), activation="tanh", solver="gd",
                          learning_rate_init=0.1, max_iter=1, warm_start=True, alpha=0.0,
                          random_state=3)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        for _ in range(n_epochs):
            model.fit(X, labels)
    return model


@pytest.mark.parametrize("n_classes", [1, 2, 3, 5])
def test_continued_fits_on_string_labels_equal_the_general_path(n_classes):
    rng = np.random.default_rng(n_classes)
    X = rng.normal(size=(40, 3))
    names = np.array(["steel", "brass", "wood", "pvc", "aluminium"][:n_classes])
    labels = names[rng.integers(0, n_classes, X.shape[0])]
    fast = _epochs(labels, X)
    general = _epochs(labels.astype(object), X)
    assert np.array_equal(fast.classes_.astype(object), general.classes_)
    for a, b in zip(fast.coefs_ + fast.intercepts_, general.coefs_ + general.intercepts_,
                    strict=True):
        assert np.array_equal(a, b)
    assert fast.loss_curve_ == general.loss_curve_
    assert np.array_equal(fast.predict(X).astype(object), general.predict(X))


def test_a_continued_fit_refuses_a_label_it_has_no_output_for():
    rng = np.random.default_rng(0)
    X = rng.normal(size=(30, 2))
    labels = np.array(["a", "b", "c"])[rng.integers(0, 3, 30)]
    model = _epochs(labels, X, n_epochs=1)
    with pytest.raises(ValueError, match=r"labels \['d'\] that are not in classes_"):
        model.fit(X, np.where(labels == "c", "d", labels))
