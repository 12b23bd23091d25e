"""Saved models whose parts contradict each other are refused, naming the file.

Each row edits a saved file as someone who knows the format would (the checksum recomputed), so
that every array and value passes alone and only the contradiction is wrong: an MLP whose
``hidden_layer_sizes`` or ``n_layers_`` disagree with its weights, a weight of the wrong shape,
duplicate ``classes_``, an SVC whose ``n_support_`` counts other classes, a list declared
10**10 arrays long.
"""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest
from sklearn.exceptions import ConvergenceWarning

from ebantenna.ml import SVC, MLPClassifier, MLPRegressor, load_model, persistence, save_model

X = np.random.default_rng(0).normal(size=(30, 4))
Y3 = np.arange(30) % 3


def _rewrite(path, meta_change=None, **arrays):
    with np.load(path, allow_pickle=False) as data:
        stored = {k: data[k] for k in data.files}
    meta = json.loads(str(stored.pop("__meta__")))
    if meta_change is not None:
        meta_change(meta)
    stored.update(arrays)
    meta["checksum_sha256"] = persistence._checksum(stored, meta)
    np.savez(path, __meta__=np.array(json.dumps(meta)), **stored)
    return path


def _params(**changes):
    return lambda meta: meta["params"].update(changes)


def _attrs(**changes):
    return lambda meta: meta["attributes"].update(changes)


def _lengths(**changes):
    return lambda meta: meta["list_lengths"].update(changes)


MODELS = {
    "mlp": lambda: MLPClassifier((5,), max_iter=20, random_state=0).fit(X, Y3),
    "mlp-regressor": lambda: MLPRegressor((5, 3), max_iter=20, random_state=0).fit(X, X[:, 0]),
    "svc": lambda: SVC().fit(X, Y3),
}

#: ``(model, id, meta change, array changes, words the message must hold)``
ROWS = [
    ("mlp", "hidden-sizes-contradict-weights", _params(hidden_layer_sizes={"__tuple__": [7]}),
     {}, "hidden_layer_sizes"),
    ("mlp", "n-layers-7-for-3", _attrs(n_layers_=7), {}, "n_layers_"),
    ("mlp", "n-layers-bool", _attrs(n_layers_=True), {}, "n_layers_"),
    ("mlp", "duplicate-classes", None, {"classes_": np.array([0, 1, 1])}, "classes_"),
    ("mlp", "list-of-10**10-layers", _lengths(coefs_=10**10), {}, "coefs_"),
    ("mlp", "weights-transposed", None,
     {"coefs_0": np.zeros((5, 4))}, "weights"),
    ("mlp-regressor", "second-layer-wrong", None, {"coefs_1": np.zeros((5, 2))}, "weights"),
    ("mlp-regressor", "n-outputs-2", _attrs(n_outputs_=2), {}, "layer"),
    ("svc", "duplicate-classes", None, {"classes_": np.array([0, 1, 1])}, "classes_"),
    ("svc", "n-support-2-of-3", None, {"n_support_": np.array([3, 3], dtype=np.int32)},
     "n_support_"),
    ("svc", "list-of-10**10", _lengths(support_vectors_=10**10), {}, "support_vectors_"),
]


@pytest.fixture(scope="module")
def saved(tmp_path_factory):
    where = tmp_path_factory.mktemp("models")
    out = {}
    for name, make in MODELS.items():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ConvergenceWarning)  # a few epochs are enough here
            model = make()
        out[name] = (model, save_model(model, where / name))
    return out


@pytest.mark.parametrize(("model", "case", "change", "arrays", "word"), ROWS,
                         ids=[f"{r[0]}-{r[1]}" for r in ROWS])
def test_a_contradiction_is_refused_naming_the_file(saved, tmp_path, model, case, change, arrays,
                                                    word):
    path = tmp_path / "m.npz"
    path.write_bytes(saved[model][1].read_bytes())
    _rewrite(path, change, **arrays)
    with pytest.raises(ValueError) as caught:
        load_model(path)
    assert str(path) in str(caught.value) and word in str(caught.value), caught.value


@pytest.mark.parametrize("model", MODELS)
def test_an_untouched_model_loads_and_predicts_the_same(saved, tmp_path, model):
    fitted, path = saved[model]
    again = load_model(_rewrite(path))  # the checksum recomputed over the same content
    np.testing.assert_array_equal(again.predict(X), fitted.predict(X))


def contract_rows() -> dict[str, list[str]]:
    """The surface these rows cover (read by the inventory test)."""
    return {"ebantenna.ml.persistence.load_model": [f"{r[0]}-{r[1]}" for r in ROWS],
            "file:model": [f"{r[0]}-{r[1]}" for r in ROWS]}
