"""Each estimator's declared fitted schema is complete, and saving follows it exactly."""

import json
import os
import warnings

import numpy as np
import pytest
import scipy.sparse as sp
from sklearn.exceptions import ConvergenceWarning

from ebantenna.ml import SVC, MLPClassifier, MLPRegressor, persistence
from ebantenna.ml.persistence import load_model, save_model

rng = np.random.default_rng(5)
X = rng.normal(size=(80, 4))
LABELS = np.array(["al", "brass", "pvc"])[(X[:, 0] > 0).astype(int) + (X[:, 1] > 0.5)]
BINARY = (X[:, 2] > 0).astype(int)
MULTILABEL = np.c_[X[:, 0] > 0, X[:, 1] > 0].astype(int)
TWO_OUTPUTS = np.c_[np.sin(X[:, 0]), X[:, 1] * X[:, 2]]

FITS = [
    (SVC(), LABELS),
    (SVC(libsvm_compat=True, kernel="poly", degree=2), BINARY),
    (SVC(cache_size=0.01, class_weight="balanced"), LABELS),
    (MLPClassifier((5,), max_iter=20, random_state=0), LABELS),
    (MLPClassifier((5,), solver="scg", max_iter=20, random_state=0), BINARY),
    (MLPClassifier((5, 3), max_iter=20, random_state=0), MULTILABEL),
    (MLPClassifier((5,), max_iter=20, early_stopping=True, random_state=0), LABELS),
    (MLPRegressor((5,), solver="gd", max_iter=20, random_state=0), TWO_OUTPUTS),
    (MLPRegressor((5,), max_iter=20, early_stopping=True, random_state=0), TWO_OUTPUTS[:, 0]),
]
IDS = [f"{type(m).__name__}-{i}" for i, (m, _) in enumerate(FITS)]


def _fitted(model, y):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        return model.fit(X, y)


def _state(model):
    return {k: v for k, v in vars(model).items() if k not in model.get_params(deep=False)}


@pytest.mark.parametrize("model, y", FITS, ids=IDS)
def test_schema_declares_exactly_what_fit_sets(model, y):
    fitted = _fitted(model, y)
    declared = {a.name: a for a in type(model)._fitted_schema}
    state = _state(fitted)
    assert set(state) <= set(declared), set(state) - set(declared)
    missing = {n for n, a in declared.items() if not a.optional and n not in state}
    assert not missing
    for name, value in state.items():
        attr = declared[name]
        if attr.kind == "array":
            attr.check(np.asarray(value))
        elif attr.kind == "arrays":
            for a in value:
                attr.check(a)


@pytest.mark.parametrize("model, y", FITS, ids=IDS)
def test_every_declared_attribute_comes_back_bit_for_bit(model, y, tmp_path):
    fitted = _fitted(model, y)
    again = load_model(save_model(fitted, tmp_path / "m"))
    before, after = _state(fitted), _state(again)
    assert set(after) == set(before)
    for name, value in before.items():
        if name == "_label_binarizer":  # rebuilt, compared through what it gives
            np.testing.assert_array_equal(after[name].classes_, value.classes_)
        elif isinstance(value, np.ndarray):
            assert after[name].dtype == value.dtype or value.dtype == object, name
            assert after[name].shape == value.shape, name
            np.testing.assert_array_equal(after[name], value)
            if value.dtype != object:
                assert after[name].tobytes() == value.tobytes(), name
        elif name in ("coefs_", "intercepts_"):
            assert [a.tobytes() for a in after[name]] == [a.tobytes() for a in value]
        else:
            assert after[name] == value and type(after[name]) is type(value), name


def test_warm_start_after_loading_continues_exactly(tmp_path):
    a = _fitted(MLPClassifier((6,), solver="sgd", max_iter=5, random_state=1), LABELS)
    b = load_model(save_model(a, tmp_path / "m"))
    for model in (a, b):
        model.set_params(warm_start=True, max_iter=3)
        _fitted(model, LABELS)
    assert [c.tobytes() for c in a.coefs_] == [c.tobytes() for c in b.coefs_]
    assert a.loss_curve_ == b.loss_curve_ and a.t_ == b.t_


def test_an_undeclared_attribute_is_refused_by_name(tmp_path):
    model = _fitted(SVC(), LABELS)
    model.margin_ = np.zeros(3)
    with pytest.raises(TypeError, match="SVC._fitted_schema does not declare.*margin_"):
        save_model(model, tmp_path / "m")


def test_feature_names_are_kept_as_objects(tmp_path):
    model = _fitted(MLPRegressor((3,), max_iter=5, random_state=0), TWO_OUTPUTS[:, 0])
    model.feature_names_in_ = np.array(["f0", "f1", "f2", "f3"], dtype=object)
    again = load_model(save_model(model, tmp_path / "m"))
    assert again.feature_names_in_.dtype == object
    assert again.feature_names_in_.tolist() == ["f0", "f1", "f2", "f3"]


def _rewrite(path, meta_change=None, drop=(), checksum=True, **array_changes):
    """Change a saved file as someone who knows the format would: checksum recomputed."""
    with np.load(path, allow_pickle=False) as data:
        arrays = {k: data[k] for k in data.files if k not in drop}
    meta = json.loads(str(arrays.pop("__meta__")))
    if meta_change is not None:
        meta_change(meta)
    arrays.update(array_changes)
    if checksum:
        meta["checksum_sha256"] = persistence._checksum(arrays, meta)
    np.savez(path, __meta__=np.array(json.dumps(meta)), **arrays)


def test_a_version_1_file_still_loads(tmp_path):
    model = _fitted(SVC(C=2.0), LABELS)
    path = save_model(model, tmp_path / "m")

    def as_version_1(meta):  # version 1 stored neither shape_fit_ nor feature names
        meta["format_version"] = 1
        del meta["attributes"]["shape_fit_"]

    _rewrite(path, as_version_1)
    again = load_model(path)
    np.testing.assert_array_equal(again.decision_function(X), model.decision_function(X))
    assert not hasattr(again, "shape_fit_")


def test_a_file_that_misdescribes_an_attribute_is_refused(tmp_path):
    model = _fitted(SVC(), LABELS)
    path = save_model(model, tmp_path / "m")
    _rewrite(path, support_=model.support_.astype(np.int64))
    with pytest.raises(ValueError, match="support_ must hold int32 arrays"):
        load_model(path)
    path = save_model(model, tmp_path / "m")
    _rewrite(path, lambda meta: meta["attributes"].pop("fit_status_"))
    with pytest.raises(ValueError, match="fit_status_ of SVC is missing"):
        load_model(path)


def _saved_svc(tmp_path):
    model = _fitted(SVC(), LABELS)
    return model, save_model(model, tmp_path / "m")


def test_an_edited_file_fails_its_checksum(tmp_path):
    model, path = _saved_svc(tmp_path)
    _rewrite(path, checksum=False, dual_coef_=model.dual_coef_ * 2)
    with pytest.raises(ValueError, match="m.npz: checksum mismatch"):
        load_model(path)


def test_a_nan_weight_is_refused_even_with_a_valid_checksum(tmp_path):
    model, path = _saved_svc(tmp_path)
    bad = model.dual_coef_.copy()
    bad[0, 0] = np.nan
    _rewrite(path, dual_coef_=bad)
    with pytest.raises(ValueError, match="dual_coef_ must hold finite numbers"):
        load_model(path)
    with pytest.raises(ValueError, match="finite"):  # nor is such a model saved
        model.dual_coef_ = bad
        save_model(model, tmp_path / "again")


@pytest.mark.parametrize(
    "change, match",
    [
        (lambda m: m["attributes"].update(predict="x"), "declares no fitted attribute predict"),
        (lambda m: m["params"].update(predict="x"), "unexpected keyword argument 'predict'"),
        (lambda m: m["params"].update(kernel="bogus"), "kernel"),
        (lambda m: m["params"].update(C=float("nan")), "parameter C must not be NaN"),
        (lambda m: m["attributes"].update(fit_status_={"evil": 1}), "fit_status_ holds an obj"),
        (lambda m: m["attributes"].update(n_features_in_=7), "inconsistent"),
        (lambda m: m["attributes"].update(n_features_in_=10**12), "n_features_in_ must be"),
        (lambda m: m.pop("class"), "KeyError"),
        (lambda m: m.update(format_version=99), "unsupported format version 99"),
    ],
)
def test_a_tampered_file_is_refused_naming_what_is_wrong(tmp_path, change, match):
    _, path = _saved_svc(tmp_path)
    _rewrite(path, change)
    with pytest.raises(ValueError, match=match) as exc:
        load_model(path)
    assert str(path) in str(exc.value)


def test_a_truncated_or_foreign_file_is_one_clear_error(tmp_path):
    _, path = _saved_svc(tmp_path)
    os.truncate(path, path.stat().st_size // 2)
    with pytest.raises(ValueError, match="m.npz is not a model file.*truncated or damaged"):
        load_model(path)
    path.write_text("C=1.0")
    with pytest.raises(ValueError, match="not an .npz archive"):
        load_model(path)
    with pytest.raises(ValueError, match="must name a file"):
        save_model(_fitted(SVC(), LABELS), tmp_path)


def test_a_sparse_fit_round_trips_with_its_csr_matrices(tmp_path):
    Xs = sp.csr_matrix(np.where(X > 0.3, X, 0.0))
    model = SVC(kernel="linear").fit(Xs, LABELS)
    again = load_model(save_model(model, tmp_path / "m"))
    for name in ("support_vectors_", "dual_coef_"):
        before, after = getattr(model, name), getattr(again, name)
        assert sp.isspmatrix_csr(after) and after.shape == before.shape
        for part in ("data", "indices", "indptr"):
            assert getattr(after, part).tobytes() == getattr(before, part).tobytes(), name
    np.testing.assert_array_equal(again.decision_function(Xs), model.decision_function(Xs))


@pytest.mark.parametrize("change, match", [
    (dict(support_vectors___indices=np.array([99] * 3)), "support_vectors_ is not a valid CSR"),
    (dict(dual_coef___data=np.array([np.inf])), "dual_coef_ must hold finite numbers"),
    (lambda m: m["sparse_shapes"].update(dual_coef_=[1]), "shape of dual_coef_ must be two"),
])
def test_a_damaged_csr_matrix_is_refused(tmp_path, change, match):
    Xs = sp.csr_matrix(np.where(X > 0.3, X, 0.0))
    path = save_model(SVC().fit(Xs, LABELS), tmp_path / "m")
    if callable(change):
        _rewrite(path, change)
    else:
        _rewrite(path, **change)
    with pytest.raises(ValueError, match=match):
        load_model(path)
