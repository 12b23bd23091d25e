"""Saving and loading fitted models as ``.npz`` (arrays) + JSON (parameters), never pickle.

What is saved is what the estimator declares: its ``_fitted_schema`` of
:class:`~ebantenna.ml.fitted.FittedAttribute` lists every attribute that ``fit`` sets. A saved
file holds every fitted array under its attribute name (a list of arrays as ``name0``,
``name1``, ...) and one JSON document with the estimator's class, its parameters and its other
fitted values. Loading rebuilds the estimator from those alone, with
``numpy.load(..., allow_pickle=False)``: nothing is ever unpickled. Arrays are checked against
their declared dtype and dimensions, and for finite numbers, on the way out and on the way in, and
a model holding an attribute that its schema does not declare is refused rather than saved
incompletely.

A file is read against that schema and nothing else: only declared attributes are set, each
array checked, each value a plain JSON number, string, bool or list of them (no NaN); the
parameters pass the estimator's own validation; a SHA-256 checksum over the arrays and the JSON
catches a file changed after it was written; and the rebuilt model must predict a finite answer
before it is handed out. Whatever is wrong ends in one ``ValueError`` naming the file.

A CSR matrix (the support vectors of an :class:`SVC` fitted on sparse input) is stored as its
arrays ``name__data``, ``name__indices`` and ``name__indptr`` with its shape in the JSON
(``sparse_shapes``), and rebuilt only if scipy's full format check passes.
"""

from __future__ import annotations

import hashlib
import json
import math
import warnings
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from .._validate import check_path, load_json, open_npz, output_path
from .mlp import MLPClassifier, MLPRegressor
from .svc import SVC

__all__ = ["save_model", "load_model", "FORMAT_VERSION"]

#: Version of the file layout: 2 adds attributes that version 1 did not store (see each
#: attribute's ``since``), 3 a checksum, 4 requires the attributes in ``REQUIRED_SINCE_4``.
#: Files of versions 1 to 3 still load. A file that carries a checksum must match it whatever
#: version it claims; a file of version 1 or 2 without one loads only when asked for explicitly
#: (``load_model(path, unchecked=True)``), so that editing the version cannot skip the check.
FORMAT_VERSION = 4

#: The versions :func:`load_model` reads.
READABLE_VERSIONS = (1, 2, 3, 4)

#: Attributes that the estimators' schemas mark optional, because files written before they
#: were kept lack them, and that files of format 4 must hold (the final loss of an MLP).
REQUIRED_SINCE_4 = frozenset({"loss_"})

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


def _checksum(arrays: dict, meta: dict) -> str:
    """SHA-256 over every array (name, dtype, shape, bytes) and the JSON without the checksum."""
    h = hashlib.sha256()
    for name in sorted(arrays):
        a = np.ascontiguousarray(arrays[name])
        h.update(f"{name}|{a.dtype.str}|{a.shape}|".encode())
        h.update(a.tobytes())
    rest = {k: v for k, v in meta.items() if k != "checksum_sha256"}
    h.update(json.dumps(rest, sort_keys=True).encode())
    return h.hexdigest()


def _check_plain(name: str, value) -> None:
    """Raise unless ``value`` is JSON as :func:`_plain` writes it, without NaN."""
    if isinstance(value, float) and math.isnan(value):
        raise ValueError(f"{name} must not be NaN")
    if isinstance(value, list):
        for v in value:
            _check_plain(name, v)
    elif isinstance(value, dict):
        if set(value) not in ({"__tuple__"}, {"__dict__"}) or not isinstance(
            next(iter(value.values())), list
        ):
            raise ValueError(f"{name} holds an object that no fitted value is: {value!r:.80}")
        _check_plain(name, next(iter(value.values())))
    elif not (value is None or isinstance(value, bool | int | float | str)):
        raise ValueError(f"{name} must be a number, string, bool or list, got {value!r:.80}")


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
                raise TypeError(f"{attr.name} holds Python objects that cannot be stored") from exc
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


#: The arrays that hold a CSR matrix.
_CSR_PARTS = ("data", "indices", "indptr")


def _loaded_csr(attr, parts, shape, path) -> sp.csr_matrix:
    """A stored CSR matrix, rebuilt only if its arrays and shape make a valid one."""
    data, indices, indptr = parts
    if not (isinstance(shape, list) and len(shape) == 2 and all(
            isinstance(n, int) and not isinstance(n, bool) and n >= 0 for n in shape)):
        raise ValueError(f"{path}: the shape of {attr.name} must be two counts, got {shape!r}")
    if indices.dtype.kind not in "iu" or indptr.dtype.kind not in "iu":
        raise ValueError(f"{path}: the indices of {attr.name} must be integers")
    _loaded_array(attr, data.reshape(1, -1) if attr.ndim == 2 else data, path)
    try:
        matrix = sp.csr_matrix((data, indices, indptr), shape=tuple(shape))
        matrix.check_format(full_check=True)
    except ValueError as exc:
        raise ValueError(f"{path}: {attr.name} is not a valid CSR matrix ({exc})") from None
    return matrix


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
        raise TypeError(
            f"model must be an SVC, MLPClassifier or MLPRegressor of ebantenna.ml, "
            f"got {type(model).__name__}"
        )
    if not hasattr(model, "n_features_in_"):
        raise ValueError("model must be fitted before it is saved")
    undeclared = _undeclared(model)
    if undeclared:
        raise TypeError(
            f"model holds attributes that {name}._fitted_schema does not declare, "
            f"so they would not be saved: {', '.join(undeclared)}"
        )
    path = output_path("path", path, ".npz")
    arrays, values, lengths, sparse_shapes = {}, {}, {}, {}
    for attr in model._fitted_schema:
        if attr.kind == "rebuilt" or (
            attr.optional and attr.name not in REQUIRED_SINCE_4 and not hasattr(model, attr.name)
        ):
            continue
        if not hasattr(model, attr.name):
            raise ValueError(f"model lacks its fitted attribute {attr.name}: fit it again")
        value = getattr(model, attr.name)
        if attr.kind == "array" and attr.sparse and sp.issparse(value):
            value = value.tocsr()
            attr.check(value.data.reshape(1, -1) if attr.ndim == 2 else value.data)
            for part in _CSR_PARTS:
                arrays[f"{attr.name}__{part}"] = getattr(value, part)
            sparse_shapes[attr.name] = [int(n) for n in value.shape]
        elif attr.kind == "array":
            arrays[attr.name] = _array_to_save(attr, value)
        elif attr.kind == "arrays":
            lengths[attr.name] = len(value)
            for i, a in enumerate(value):
                arrays[f"{attr.name}{i}"] = _array_to_save(attr, a)
        else:
            values[attr.name] = _plain(value)
            _check_plain(attr.name, values[attr.name])
    meta = {
        "format_version": FORMAT_VERSION,
        "class": name,
        "params": {k: _plain(v) for k, v in model.get_params(deep=False).items()},
        "attributes": values,
        "list_lengths": lengths,
    }
    if sparse_shapes:
        meta["sparse_shapes"] = sparse_shapes
    meta["checksum_sha256"] = _checksum(arrays, meta)
    arrays["__meta__"] = np.array(json.dumps(meta))
    np.savez(path, **arrays)
    return path


def load_model(path, *, unchecked: bool = False):
    """Load a model written by :func:`save_model` (no pickle involved).

    Parameters
    ----------
    path : str or os.PathLike
        A file written by :func:`save_model` (format version 1 to 4).
    unchecked : bool
        Accept a file of format 1 or 2 that carries no checksum (those versions wrote none).
        Without it such a file is refused: anyone can write that version number into a file.

    Returns
    -------
    SVC, MLPClassifier or MLPRegressor
        The fitted model, with every stored array bit for bit as it was saved.

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    TypeError
        If ``path`` is not a ``str`` or ``os.PathLike`` (bytes are refused).
    ValueError
        Naming the file, if it is not a regular file, truncated or damaged, declares arrays
        over the memory budget, is not a model file of this package, of an unknown version or
        class, changed since it was written (checksum), or if a parameter or fitted attribute is
        missing, undeclared, of the wrong type or shape, or not finite.
    """
    path = Path(check_path("path", path))
    if not isinstance(unchecked, bool):
        raise TypeError(f"unchecked must be True or False, got {unchecked!r}")
    what = "a model file of ebantenna.ml"
    with open_npz(path, what) as data:
        if "__meta__" not in data.files:
            raise ValueError(f"{path} is not {what} (no metadata)")
        arrays = {k: data[k] for k in data.files if k != "__meta__"}
        text = data["__meta__"]
    meta = load_json(str(text), path, what)
    try:
        return _rebuild(path, arrays, meta, unchecked)
    except (KeyError, TypeError, AttributeError, ValueError) as exc:
        if isinstance(exc, ValueError) and str(path) in str(exc):
            raise
        raise ValueError(f"{path} is not {what}: {type(exc).__name__}: {exc}") from None


def _check_version(path: Path, arrays: dict, meta: dict, unchecked: bool) -> int:
    """The file's format version, once its checksum (required from version 3) is verified."""
    version = meta.get("format_version")
    if type(version) is not int or version not in READABLE_VERSIONS:  # not True, not 3.0
        raise ValueError(f"{path}: unsupported format version {version!r}")
    if "checksum_sha256" in meta or version >= 3:
        if meta.get("checksum_sha256") != _checksum(arrays, meta):
            raise ValueError(f"{path}: checksum mismatch, the file is corrupt or was modified")
    elif not unchecked:
        raise ValueError(
            f"{path}: a file of format {version} carries no checksum, so a change to it cannot "
            "be detected; load it with load_model(path, unchecked=True) if you trust it"
        )
    return version


def _required(attr, version: int) -> bool:
    """Whether a file of format ``version`` must hold ``attr``."""
    if attr.name in REQUIRED_SINCE_4 and version >= 4:
        return True
    return not attr.optional and attr.since <= version


def _rebuild(path: Path, arrays: dict, meta, unchecked: bool = False):
    """The model described by a file's arrays and JSON, checked at every step."""
    if not isinstance(meta, dict):
        raise ValueError("its metadata is not a JSON object")
    version = _check_version(path, arrays, meta, unchecked)
    name = meta["class"]
    if name not in _CLASSES:
        raise ValueError(f"{path}: unknown model class {name!r}")
    cls = _CLASSES[name]
    params, attributes, lengths = meta["params"], meta["attributes"], meta["list_lengths"]
    for key, group in (("params", params), ("attributes", attributes), ("list_lengths", lengths)):
        if not isinstance(group, dict):
            raise ValueError(f"{path}: {key} must be a JSON object")
    for key, value in params.items():
        _check_plain(f"parameter {key}", value)
    model = cls(**{k: _unplain(v) for k, v in params.items()})
    model._validate_params()  # scikit-learn's own parameter constraints
    shapes = meta.get("sparse_shapes", {})
    if not isinstance(shapes, dict):
        raise ValueError(f"{path}: sparse_shapes must be a JSON object")
    stored = {"array": set(arrays), "arrays": set(lengths), "value": set(attributes)}
    _check_kinds(path, cls, stored)
    used = set()
    for attr in cls._fitted_schema:
        if attr.kind == "rebuilt":
            continue
        if attr.kind == "array" and attr.sparse and attr.name in shapes:
            keys = [f"{attr.name}__{part}" for part in _CSR_PARTS]
            setattr(model, attr.name, _loaded_csr(attr, [arrays[k] for k in keys],
                                                  shapes[attr.name], path))
            used.update(keys)
        elif attr.kind == "array" and attr.name in stored["array"]:
            setattr(model, attr.name, _loaded_array(attr, arrays[attr.name], path))
        elif attr.kind == "arrays" and attr.name in stored["arrays"]:
            count = lengths[attr.name]
            if isinstance(count, bool) or not isinstance(count, int) or count < 0:
                raise ValueError(f"{path}: list_lengths of {attr.name} must be a count")
            if count > len(arrays):  # checked before a list of names is made for it
                raise ValueError(f"{path}: list_lengths of {attr.name} declares {count} arrays; "
                                 f"the file holds {len(arrays)}")
            keys = [f"{attr.name}{i}" for i in range(count)]
            setattr(model, attr.name, [_loaded_array(attr, arrays[k], path) for k in keys])
            used.update(keys)
        elif attr.kind == "value" and attr.name in stored["value"]:
            _check_plain(attr.name, attributes[attr.name])
            setattr(model, attr.name, _unplain(attributes[attr.name]))
        elif _required(attr, version):
            raise ValueError(f"{path}: the fitted attribute {attr.name} of {name} is missing")
        used.add(attr.name)
    unknown = (stored["array"] - used) | ((stored["arrays"] | stored["value"]) - used)
    if unknown:
        raise ValueError(
            f"{path}: {name} declares no fitted attribute {', '.join(sorted(unknown))}"
        )
    _check_consistent(model, path)
    if hasattr(model, "_rebuild_fitted"):
        model._rebuild_fitted()
    _check_predicts(model, path)
    return model


def _check_kinds(path: Path, cls, stored: dict) -> None:
    """Refuse a list length or a value given for an attribute the schema stores otherwise."""
    schema = {a.name: a.kind for a in cls._fitted_schema}
    for kind, key in (("arrays", "list_lengths"), ("value", "attributes")):
        misplaced = sorted(n for n in stored[kind] if n in schema and schema[n] != kind)
        if misplaced:
            raise ValueError(f"{path}: {key} holds {', '.join(misplaced)}, which "
                             f"{cls.__name__} stores otherwise (not as a {kind})")


def _check_consistent(model, path: Path) -> None:
    """Refuse a model whose parameters contradict its arrays (each checked alone passes).

    Classes must be distinct; an MLP's layer count, ``hidden_layer_sizes`` and the shapes of
    its weights and biases must describe one network; an SVC's support counts one per class.
    """
    classes = getattr(model, "classes_", None)
    if classes is not None and len(np.unique(classes)) != len(classes):
        raise ValueError(f"{path}: classes_ names a class twice ({classes.tolist()!r:.80})")
    if isinstance(model, MLPClassifier | MLPRegressor):
        coefs, intercepts = model.coefs_, model.intercepts_
        hidden = model.hidden_layer_sizes
        hidden = [hidden] if isinstance(hidden, int) else list(hidden)
        n_out = model.n_outputs_
        sizes = [model.n_features_in_, *hidden, n_out]
        if model.n_layers_ != len(sizes) or len(coefs) != len(sizes) - 1 or len(
                intercepts) != len(sizes) - 1:
            raise ValueError(f"{path}: n_layers_ is {model.n_layers_!r}, hidden_layer_sizes "
                             f"{model.hidden_layer_sizes!r} makes {len(sizes)} layers, and the "
                             f"file holds {len(coefs)} weight and {len(intercepts)} bias arrays")
        for i, (w, b) in enumerate(zip(coefs, intercepts, strict=True)):
            if w.shape != (sizes[i], sizes[i + 1]) or b.shape != (sizes[i + 1],):
                raise ValueError(f"{path}: layer {i}'s weights are {w.shape} and biases "
                                 f"{b.shape}; n_features_in_, hidden_layer_sizes and n_outputs_ "
                                 f"make {(sizes[i], sizes[i + 1])} and {(sizes[i + 1],)}")
    if isinstance(model, SVC) and classes is not None:
        n_support = getattr(model, "n_support_", None)
        if n_support is not None and len(n_support) != len(classes):
            raise ValueError(f"{path}: n_support_ counts {len(n_support)} classes, classes_ "
                             f"holds {len(classes)}")


#: The most input features a loaded model may declare (a bound for the prediction check).
MAX_FEATURES = 1_000_000


def _check_predicts(model, path: Path) -> None:
    """The loaded model must answer one row of zeros, with finite scores (a shape check too)."""
    n = model.n_features_in_
    if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= MAX_FEATURES:
        raise ValueError(f"{path}: n_features_in_ must be an int in [1, {MAX_FEATURES}], got {n!r}")
    X = np.zeros((1, n))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # e.g. "X does not have valid feature names"
        try:
            y = np.asarray(model.predict(X))
            scores = [
                np.asarray(getattr(model, method)(X))
                for method in ("decision_function", "predict_proba")
                if hasattr(model, method)
            ]
        except (ValueError, TypeError, IndexError, KeyError, AttributeError) as exc:
            raise ValueError(f"{path}: the stored model is inconsistent ({exc})") from None
    if y.dtype.kind in "fc":
        scores.append(y)
    if any(not np.all(np.isfinite(s)) for s in scores):
        raise ValueError(f"{path}: the stored model predicts NaN or infinity")
