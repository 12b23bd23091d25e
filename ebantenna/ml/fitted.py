"""The declared fitted state of an estimator: every attribute ``fit`` sets, with its type.

Each estimator of :mod:`ebantenna.ml` lists, next to its code, the attributes that ``fit``
leaves on it, as a tuple of :class:`FittedAttribute` (its ``_fitted_schema``).
:mod:`ebantenna.ml.persistence` saves and loads exactly those, checks arrays against their
declared dtype and number of dimensions, and refuses to save a model holding an attribute that
its schema does not declare: a new attribute cannot be forgotten silently.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["FittedAttribute", "INPUT_ATTRIBUTES", "KINDS"]

#: How an attribute is held and stored.
KINDS = ("array", "arrays", "value", "rebuilt")


@dataclass(frozen=True)
class FittedAttribute:
    """One attribute that ``fit`` sets.

    Parameters
    ----------
    name : str
        Attribute name, e.g. ``'coefs_'``.
    kind : {'array', 'arrays', 'value', 'rebuilt'}
        ``'array'``: one ndarray, stored as it is; ``'arrays'``: a list of ndarrays (one per
        layer), stored one by one; ``'value'``: a number, string, bool, None or a list or tuple of
        them, stored as JSON (floats round-trip exactly); ``'rebuilt'``: derived from the other
        attributes after loading, not stored.
    dtype : str, optional
        For arrays: the dtype every array has (``'float64'``, ``'int32'``...). ``'object'``
        marks strings held in an object array (stored as text, restored as objects); None
        accepts any dtype that is not object (labels), object labels being stored as text.
    ndim : int, optional
        For arrays: their number of dimensions.
    optional : bool
        Set by some fits only (``feature_names_in_`` needs named columns).
    since : int
        First file format version that stores it; older files load without it.
    sparse : bool
        For an ``'array'``: it may also be a ``scipy.sparse`` CSR matrix (after a fit on sparse
        input), stored as its three arrays and checked like the dense one.

    Examples
    --------
    >>> a = FittedAttribute("coefs_", "arrays", dtype="float64", ndim=2)
    >>> a.check(np.zeros((2, 3)))
    >>> a.check(np.zeros(3))
    Traceback (most recent call last):
    ...
    ValueError: coefs_ must hold float64 arrays of 2 dimension(s), got float64 of shape (3,)
    >>> a.check(np.full((2, 3), np.nan))
    Traceback (most recent call last):
    ...
    ValueError: coefs_ must hold finite numbers, got NaN or infinity
    """

    name: str
    kind: str
    dtype: str | None = None
    ndim: int | None = None
    optional: bool = False
    since: int = 1
    sparse: bool = False

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"kind must be one of {KINDS}, got {self.kind!r}")
        if (self.dtype is not None or self.ndim is not None) and self.kind not in (
            "array",
            "arrays",
        ):
            raise ValueError(f"dtype and ndim describe arrays; {self.name} is a {self.kind!r}")
        if self.sparse and self.kind != "array":
            raise ValueError(f"only an 'array' may be sparse; {self.name} is a {self.kind!r}")

    def check(self, array: np.ndarray) -> None:
        """Raise ``ValueError`` unless ``array`` has the declared dtype and dimensions.

        Numbers must be finite too: a NaN or an infinity in a fitted array is a broken model
        (every prediction through it is NaN, or one class for every row), never a fitted one.
        """
        dtype_ok = (
            array.dtype != object if self.dtype is None else array.dtype == np.dtype(self.dtype)
        )
        if not dtype_ok or (self.ndim is not None and array.ndim != self.ndim):
            dims = "any number of" if self.ndim is None else self.ndim
            raise ValueError(
                f"{self.name} must hold {self.dtype or 'label'} arrays of {dims} "
                f"dimension(s), got {array.dtype} of shape {array.shape}"
            )
        if array.dtype.kind in "fc" and not np.all(np.isfinite(array)):
            raise ValueError(f"{self.name} must hold finite numbers, got NaN or infinity")


#: What scikit-learn's input validation sets on every estimator fitted here.
INPUT_ATTRIBUTES = (
    FittedAttribute("n_features_in_", "value"),
    FittedAttribute("feature_names_in_", "array", dtype="object", ndim=1, optional=True, since=2),
)
