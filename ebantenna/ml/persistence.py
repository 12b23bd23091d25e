"""Saving and loading fitted models as ``.npz`` (arrays) + JSON (parameters), never pickle.

A saved file holds every fitted array under its attribute name and one JSON document with the
estimator's class, its parameters and its scalar attributes. Loading rebuilds the estimator from
those alone, with ``numpy.load(..., allow_pickle=False)``: nothing is ever unpickled.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np

from .mlp import MLPClassifier, MLPRegressor
from .svc import SVC

__all__ = ["save_model", "load_model", "FORMAT_VERSION"]

#: Version of the file layout.
FORMAT_VERSION = 1

_CLASSES = {cls.__name__: cls for cls in (SVC, MLPClassifier, MLPRegressor)}

#: Fitted array attributes of each estimator (lists of arrays are stored as name_0, name_1, ...).
_ARRAYS = {
    "SVC": ("classes_", "support_", "support_vectors_", "n_support_", "dual_coef_",
            "intercept_", "_dual_coef_", "_intercept_", "n_iter_", "class_weight_"),
    "MLPClassifier": ("classes_",),
    "MLPRegressor": (),
}
_LISTS = {"SVC": (), "MLPClassifier": ("coefs_", "intercepts_"),
          "MLPRegressor": ("coefs_", "intercepts_")}
_SCALARS = {
    "SVC": ("_gamma", "fit_status_", "n_features_in_"),
    "MLPClassifier": ("n_iter_", "n_layers_", "n_outputs_", "out_activation_", "best_loss_",
                      "t_", "n_features_in_", "_multilabel", "loss_curve_"),
    "MLPRegressor": ("n_iter_", "n_layers_", "n_outputs_", "best_loss_", "t_",
                     "n_features_in_", "_y_ndim", "loss_curve_"),
}


def _plain(value):
    """A JSON-ready copy of a parameter or scalar attribute."""
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, tuple):
        return {"__tuple__": [_plain(v) for v in value]}
    if isinstance(value, list):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {"__dict__": [[_plain(k), _plain(v)] for k, v in value.items()]}
    if value is None or isinstance(value, bool | int | float | str):
        return value
    raise TypeError(f"cannot store {type(value).__name__} value {value!r} as JSON")


def _unplain(value):
    if isinstance(value, dict) and "__tuple__" in value:
        return tuple(_unplain(v) for v in value["__tuple__"])
    if isinstance(value, dict) and "__dict__" in value:
        return {_unplain(k): _unplain(v) for k, v in value["__dict__"]}
    if isinstance(value, list):
        return [_unplain(v) for v in value]
    return value


def save_model(model, path) -> Path:
    """Save a fitted :class:`SVC`, :class:`MLPClassifier` or :class:`MLPRegressor`.

    Parameters
    ----------
    model : estimator
        A fitted model of this package.
    path : str or os.PathLike
        Target file; ``.npz`` is appended if missing.

    Returns
    -------
    pathlib.Path
        The file written.

    Examples
    --------
    >>> import tempfile, os
    >>> clf = SVC(kernel="linear").fit([[0.0], [1.0], [3.0], [4.0]], [0, 0, 1, 1])
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = save_model(clf, os.path.join(d, "svc"))
    ...     again = load_model(p)
    >>> again.predict([[0.5], [3.5]])
    array([0, 1])
    """
    name = type(model).__name__
    if name not in _CLASSES or type(model) is not _CLASSES[name]:
        raise TypeError(f"model must be an SVC, MLPClassifier or MLPRegressor of ebantenna.ml, "
                        f"got {type(model).__name__}")
    if not hasattr(model, "n_features_in_"):
        raise ValueError("model must be fitted before it is saved")
    path = Path(os.fspath(path))
    if path.suffix != ".npz":
        path = path.with_name(path.name + ".npz")
    arrays = {}
    for attr in _ARRAYS[name]:
        value = np.asarray(getattr(model, attr))
        if value.dtype == object:
            try:
                value = value.astype(str)
            except (TypeError, ValueError) as exc:
                raise TypeError(f"{attr} holds Python objects that cannot be stored") from exc
        arrays[attr] = value
    for attr in _LISTS[name]:
        for i, a in enumerate(getattr(model, attr)):
            arrays[f"{attr}{i}"] = np.asarray(a)
    meta = {
        "format_version": FORMAT_VERSION,
        "class": name,
        "params": {k: _plain(v) for k, v in model.get_params(deep=False).items()},
        "attributes": {a: _plain(getattr(model, a)) for a in _SCALARS[name]
                       if hasattr(model, a)},
        "list_lengths": {a: len(getattr(model, a)) for a in _LISTS[name]},
    }
    arrays["__meta__"] = np.array(json.dumps(meta))
    np.savez(path, **arrays)
    return path


def load_model(path):
    """Load a model written by :func:`save_model` (no pickle involved)."""
    path = Path(os.fspath(path))
    with np.load(path, allow_pickle=False) as data:
        if "__meta__" not in data.files:
            raise ValueError(f"{path} is not a model file of ebantenna.ml (no metadata)")
        meta = json.loads(str(data["__meta__"]))
        if meta.get("format_version") != FORMAT_VERSION:
            raise ValueError(f"{path}: unsupported format version {meta.get('format_version')!r}")
        name = meta["class"]
        if name not in _CLASSES:
            raise ValueError(f"{path}: unknown model class {name!r}")
        model = _CLASSES[name](**{k: _unplain(v) for k, v in meta["params"].items()})
        for attr in _ARRAYS[name]:
            setattr(model, attr, data[attr])
        for attr, length in meta["list_lengths"].items():
            setattr(model, attr, [data[f"{attr}{i}"] for i in range(length)])
    for attr, value in meta["attributes"].items():
        setattr(model, attr, _unplain(value))
    if name == "MLPClassifier":
        from sklearn.preprocessing import LabelBinarizer

        model._label_binarizer = LabelBinarizer().fit(model.classes_)
        if model._multilabel:
            model._label_binarizer = LabelBinarizer().fit(np.eye(model.classes_.size, dtype=int))
    return model
