"""Saving and loading fitted models as ``.npz`` (arrays) + JSON (parameters), never pickle.

What is saved is what the estimator declares: its ``_fitted_schema`` of
:class:`~ebantenna.ml.fitted.FittedAttribute` lists every attribute that ``fit`` sets. A saved
file holds every fitted array under its attribute name (a list of arrays as ``name0``,
``name1``, ...) and one JSON document with the estimator's class, its parameters and its other
fitted values. Loading rebuilds the estimator from those alone, with
``numpy.load(..., allow_pickle=False)``: nothing is ever unpickled. Arrays are checked against
their declared dtype and dimensions on the way out and on the way in, and a model holding an
attribute that its schema does not declare is refused rather than saved incompletely.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np

from .mlp import MLPClassifier, MLPRegressor
from .svc import SVC

__all__ = ["save_model", "load_model", "FORMAT_VERSION"]

#: Version of the file layout: 2 adds attributes that version 1 did not store (see each
#: attribute's ``since``); files of version 1 still load.
FORMAT_VERSION = 2

_CLASSES = {cls.__name__: cls for cls in (SVC, MLPClassifier, MLPRegressor)}

#: Instance attributes that scikit-learn itself may set (routing requests, output settings):
#: configuration, not fitted state, and not saved.
_SKLEARN_SETTINGS = frozenset({"_metadata_request", "_sklearn_output_config"})


def _plain(value):
    """A JSON-ready copy of a parameter or fitted value."""
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


def _array_to_save(attr, value) -> np.ndarray:
    """The array stored for ``attr``: labels or names held as objects become text."""
    value = np.asarray(value)
    if attr.dtype is None or attr.dtype == "object":
        if value.dtype == object:
            try:
                value = value.astype(str)
            except (TypeError, ValueError) as exc:
                raise TypeError(f"{attr.name} holds Python objects that cannot be "
                                "stored") from exc
        if attr.dtype == "object":
            attr.check(value.astype(object))
            return value
    attr.check(value)
    return value


def _loaded_array(attr, value: np.ndarray, path) -> np.ndarray:
    if attr.dtype == "object":
        value = value.astype(object)
    try:
        attr.check(value)
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None
    return value


def _undeclared(model) -> list[str]:
    """Attributes of ``model`` that are neither parameters nor in its fitted schema."""
    known = {a.name for a in model._fitted_schema} | set(model.get_params(deep=False))
    return sorted(set(vars(model)) - known - _SKLEARN_SETTINGS)


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

    Raises
    ------
    TypeError
        If ``model`` is not one of the three estimators, or holds an attribute that its
        ``_fitted_schema`` does not declare.
    ValueError
        If ``model`` is not fitted, or a fitted array does not have its declared dtype and
        dimensions.

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
    undeclared = _undeclared(model)
    if undeclared:
        raise TypeError(f"model holds attributes that {name}._fitted_schema does not declare, "
                        f"so they would not be saved: {', '.join(undeclared)}")
    path = Path(os.fspath(path))
    if path.suffix != ".npz":
        path = path.with_name(path.name + ".npz")
    arrays, values, lengths = {}, {}, {}
    for attr in model._fitted_schema:
        if attr.kind == "rebuilt" or (attr.optional and not hasattr(model, attr.name)):
            continue
        if not hasattr(model, attr.name):
            raise ValueError(f"model lacks its fitted attribute {attr.name}: fit it again")
        value = getattr(model, attr.name)
        if attr.kind == "array":
            arrays[attr.name] = _array_to_save(attr, value)
        elif attr.kind == "arrays":
            lengths[attr.name] = len(value)
            for i, a in enumerate(value):
                arrays[f"{attr.name}{i}"] = _array_to_save(attr, a)
        else:
            values[attr.name] = _plain(value)
    meta = {
        "format_version": FORMAT_VERSION,
        "class": name,
        "params": {k: _plain(v) for k, v in model.get_params(deep=False).items()},
        "attributes": values,
        "list_lengths": lengths,
    }
    arrays["__meta__"] = np.array(json.dumps(meta))
    np.savez(path, **arrays)
    return path


def load_model(path):
    """Load a model written by :func:`save_model` (no pickle involved).

    Parameters
    ----------
    path : str or os.PathLike
        A file written by :func:`save_model` (format version 1 or 2).

    Returns
    -------
    SVC, MLPClassifier or MLPRegressor
        The fitted model, with every stored array bit for bit as it was saved.

    Raises
    ------
    ValueError
        If the file is not a model file of this package, is of an unknown version or class, or
        lacks or misdescribes a fitted attribute.
    """
    path = Path(os.fspath(path))
    with np.load(path, allow_pickle=False) as data:
        if "__meta__" not in data.files:
            raise ValueError(f"{path} is not a model file of ebantenna.ml (no metadata)")
        meta = json.loads(str(data["__meta__"]))
        version = meta.get("format_version")
        if version not in (1, FORMAT_VERSION):
            raise ValueError(f"{path}: unsupported format version {version!r}")
        name = meta["class"]
        if name not in _CLASSES:
            raise ValueError(f"{path}: unknown model class {name!r}")
        cls = _CLASSES[name]
        model = cls(**{k: _unplain(v) for k, v in meta["params"].items()})
        stored = {"array": set(data.files) - {"__meta__"},
                  "arrays": set(meta["list_lengths"]), "value": set(meta["attributes"])}
        used = set()
        for attr in cls._fitted_schema:
            if attr.kind == "rebuilt":
                continue
            if attr.kind == "array" and attr.name in stored["array"]:
                setattr(model, attr.name, _loaded_array(attr, data[attr.name], path))
            elif attr.kind == "arrays" and attr.name in stored["arrays"]:
                keys = [f"{attr.name}{i}" for i in range(meta["list_lengths"][attr.name])]
                setattr(model, attr.name, [_loaded_array(attr, data[k], path) for k in keys])
                used.update(keys)
            elif attr.kind == "value" and attr.name in stored["value"]:
                setattr(model, attr.name, _unplain(meta["attributes"][attr.name]))
            elif not attr.optional and attr.since <= version:
                raise ValueError(f"{path}: the fitted attribute {attr.name} of {name} is missing")
            used.add(attr.name)
        unknown = (stored["array"] - used) | ((stored["arrays"] | stored["value"]) - used)
        if unknown:
            raise ValueError(f"{path}: {name} declares no fitted attribute "
                             f"{', '.join(sorted(unknown))}")
    if hasattr(model, "_rebuild_fitted"):
        model._rebuild_fitted()
    return model
