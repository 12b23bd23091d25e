"""Input validation shared by the whole package.

Every public function checks its arguments at the boundary with these helpers, so that bad input
raises a :class:`ValueError` or :class:`TypeError` that names the parameter, the allowed range and
the value given, instead of a NaN or a traceback from deep inside NumPy.
"""

from __future__ import annotations

import math
import os
import zipfile
import zlib
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from numbers import Real
from pathlib import Path

import numpy as np

__all__ = [
    "describe",
    "check_real",
    "check_python_number",
    "check_bool",
    "check_positive",
    "check_nonnegative",
    "check_in_range",
    "check_range",
    "check_int",
    "check_choice",
    "real_array",
    "check_array",
    "output_path",
    "open_npz",
]


def describe(value) -> str:
    """A short repr of ``value`` for an error message, safe for a Python int of any size.

    ``repr(10**5000)`` raises (Python limits int-to-str conversion to 4300 digits), and even
    ``repr(10**400)`` would fill a screen, so a large integer is described by its size.

    Examples
    --------
    >>> describe(10**400)
    'an integer of 401 digits (about 1e+400)'
    >>> describe(0.5)
    '0.5'
    """
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) >= 10**18:
        digits = len(str(abs(value))) if value.bit_length() < 14000 else None
        if digits is None:
            digits = int(value.bit_length() * math.log10(2)) + 1
        sign = "-" if value < 0 else ""
        return f"an integer of {digits} digits (about {sign}1e+{digits - 1})"
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


def check_real(name: str, value, *, allow_inf: bool = False) -> float:
    """Return ``value`` as a float; raise if it is not a real number (or is NaN / inf).

    Any Python number is accepted as input, however large: a value beyond the float range (an
    int such as ``10**400``, a :class:`~fractions.Fraction`) is refused as not finite, with a
    :class:`ValueError` naming ``name``, instead of the :class:`OverflowError` of ``float()``.
    """
    if isinstance(value, bool) or not isinstance(value, Real | np.floating | np.integer):
        raise TypeError(f"{name} must be a real number, got {describe(value)} "
                        f"({type(value).__name__})")
    try:
        number = float(value)
    except (OverflowError, ValueError):
        number = math.inf if value > 0 else -math.inf
        if not allow_inf:
            raise ValueError(
                f"{name} must be a finite number (at most about 1.8e308), got {describe(value)}"
            ) from None
    if math.isnan(number) or (math.isinf(number) and not allow_inf):
        raise ValueError(f"{name} must be a finite number, got {number!r}")
    return number


def check_python_number(name: str, value) -> None:
    """Refuse what scikit-learn's parameter checks cannot: an int beyond the float range
    (``10**400`` passes them, then ``float()`` overflows) and a non-builtin real such as a
    :class:`~fractions.Fraction` (NumPy's ``isnan`` fails on it). Anything else is left to them.
    """
    if isinstance(value, bool) or not isinstance(value, Real):
        return
    if not isinstance(value, int | float | np.number):
        raise TypeError(f"{name} must be a float or an int, got {describe(value)} "
                        f"({type(value).__name__})")
    if isinstance(value, int) and not isinstance(value, np.number):
        check_real(name, value)


def check_bool(name: str, value) -> bool:
    """Return ``value``; raise unless it is ``True`` or ``False``.

    A string such as ``"no"`` is truthy: taken as a flag it would silently mean the opposite.
    """
    if not isinstance(value, bool | np.bool_):
        raise TypeError(f"{name} must be True or False, got {value!r} ({type(value).__name__})")
    return bool(value)


def check_positive(name: str, value, *, allow_inf: bool = False, maximum: float | None = None,
                   reason: str = "") -> float:
    """Return ``value`` as a float; raise unless ``0 < value`` (``< inf`` unless allowed).

    ``maximum`` (inclusive) bounds a physical parameter; ``reason`` says why, in the error.
    """
    value = check_real(name, value, allow_inf=allow_inf)
    if not value > 0:
        raise ValueError(f"{name} must be > 0, got {value!r}")
    if maximum is not None and value > maximum:
        why = f" ({reason})" if reason else ""
        raise ValueError(f"{name} must be at most {maximum:g}{why}, got {value!r}")
    return value


def check_nonnegative(name: str, value, *, allow_inf: bool = False) -> float:
    """Return ``value`` as a float; raise unless ``0 <= value``."""
    value = check_real(name, value, allow_inf=allow_inf)
    if not value >= 0:
        raise ValueError(f"{name} must be >= 0, got {value!r}")
    return value


def check_in_range(
    name: str,
    value,
    low: float,
    high: float,
    *,
    low_inclusive: bool = False,
    high_inclusive: bool = False,
    reason: str = "",
) -> float:
    """Return ``value`` as a float; raise unless it lies between ``low`` and ``high``.

    ``reason`` says why the range is what it is; the error message carries it.
    """
    value = check_real(name, value)
    above = value >= low if low_inclusive else value > low
    below = value <= high if high_inclusive else value < high
    if not (above and below):
        left = "[" if low_inclusive else "("
        right = "]" if high_inclusive else ")"
        why = f" ({reason})" if reason else ""
        raise ValueError(
            f"{name} must lie in {left}{low:g}, {high:g}{right}{why}, got {value!r}"
        )
    return value


def check_range(name: str, value, bounds: tuple[float, float], reason: str) -> float:
    """Return ``value`` as a float; raise unless ``bounds[0] <= value <= bounds[1]`` (inclusive).

    For a physical parameter with a documented range: a value <= 0 is first refused as not
    positive (``"must be > 0"``) unless ``bounds[0]`` is 0, and the range's error carries
    ``reason``, why the range is what it is.

    Examples
    --------
    >>> check_range("loss_factor", 2.0, (0.0, 1.0), "the model is for light damping")
    Traceback (most recent call last):
    ...
    ValueError: loss_factor must lie in [0, 1] (the model is for light damping), got 2.0
    """
    if bounds[0] > 0:
        check_positive(name, value)
    return check_in_range(name, value, *bounds, low_inclusive=True, high_inclusive=True,
                          reason=reason)


def check_int(name: str, value, *, minimum: int | None = None, maximum: int | None = None) -> int:
    """Return ``value`` as an int; raise unless it is an integer within the given bounds."""
    if isinstance(value, bool) or not isinstance(value, int | np.integer):
        raise TypeError(
            f"{name} must be an integer, got {describe(value)} ({type(value).__name__})"
        )
    value = int(value)
    if minimum is not None and value < minimum:
        raise ValueError(f"{name} must be >= {minimum}, got {describe(value)}")
    if maximum is not None and value > maximum:
        raise ValueError(f"{name} must be <= {maximum}, got {describe(value)}")
    return value


def check_choice(name: str, value, choices: Iterable[str]) -> str:
    """Return ``value``; raise unless it is one of ``choices`` (listing them)."""
    choices = tuple(choices)
    if value not in choices:
        valid = ", ".join(repr(c) for c in choices)
        raise ValueError(f"{name} must be one of {valid}; got {value!r}")
    return value


#: What each refused NumPy dtype kind is called in an error message.
_REFUSED_KINDS = {"c": "complex", "b": "bool", "M": "datetime", "m": "timedelta",
                  "O": "object (not all numbers, or an int beyond 64 bits)", "U": "string",
                  "S": "bytes", "V": "structured"}


def real_array(name: str, value) -> np.ndarray:
    """Return ``value`` as a float64 array, refusing every array that is not real numeric data.

    Accepted: floating arrays (float16, float32 and longdouble are computed in float64) and
    integer arrays, or nested lists of Python numbers of equal lengths. Refused, with a
    :class:`TypeError` naming ``name``: complex (NumPy would drop the imaginary part), masked
    (the mask would be lost and the masked samples used as data), bool, datetime, timedelta,
    string, bytes, object and structured arrays. A ragged list raises a :class:`ValueError`.

    Examples
    --------
    >>> real_array("x", np.array([1, 2], dtype=np.float32)).dtype
    dtype('float64')
    >>> real_array("x", [1 + 2j])
    Traceback (most recent call last):
    ...
    TypeError: x must be array-like of real numbers, got a complex array (dtype complex128)
    >>> real_array("x", [[1.0, 2.0], [3.0]])
    Traceback (most recent call last):
    ...
    ValueError: x must be a rectangular array: its rows have different lengths (a ragged list)
    """
    if isinstance(value, np.ma.MaskedArray):
        raise TypeError(
            f"{name} must be a plain array, got a masked array: its mask would be lost "
            "(fill it with .filled() or drop masked samples with .compressed() first)"
        )
    try:
        raw = np.asarray(value)
    except ValueError:
        raise ValueError(
            f"{name} must be a rectangular array: its rows have different lengths (a ragged list)"
        ) from None
    except (TypeError, OverflowError, RecursionError, MemoryError) as exc:
        raise TypeError(
            f"{name} must be array-like of numbers, got {type(value).__name__}"
        ) from exc
    kind = raw.dtype.kind
    if kind not in "fiu":
        refused = _REFUSED_KINDS.get(kind, kind)
        raise TypeError(
            f"{name} must be array-like of real numbers, got a {refused} array (dtype {raw.dtype})"
        )
    with np.errstate(over="ignore"):  # a longdouble beyond float64 becomes inf, refused later
        return raw.astype(np.float64, copy=False)


def check_array(
    name: str,
    value,
    *,
    ndim: int | tuple[int, ...] | None = None,
    min_length: int = 1,
    finite: bool = True,
    dtype=np.float64,
) -> np.ndarray:
    """Return ``value`` as a NumPy array of ``dtype``; raise on wrong shape, emptiness or NaN/inf.

    Only real numeric data is accepted (see :func:`real_array`): float32 and integers are
    converted to float64 and computed in float64. ``min_length`` applies to the last axis. The
    array is converted, never modified in place.
    """
    array = real_array(name, value)
    if dtype is not np.float64:
        array = array.astype(dtype)
    if ndim is not None:
        allowed = (ndim,) if isinstance(ndim, int) else tuple(ndim)
        if array.ndim not in allowed:
            raise ValueError(
                f"{name} must have {' or '.join(map(str, allowed))} dimension(s), "
                f"got shape {array.shape}"
            )
    if array.size == 0 or (array.ndim > 0 and array.shape[-1] < min_length):
        raise ValueError(f"{name} must have at least {min_length} samples, got shape {array.shape}")
    if finite and not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must contain only finite values (no NaN or inf)")
    return array


def check_per_row(n: int, of: str, **arrays) -> None:
    """Raise unless every array of ``arrays`` has shape ``(n,)``: one entry per row of ``of``.

    Examples
    --------
    >>> check_per_row(2, "X", y=[1, 2], distance=[0.1])
    Traceback (most recent call last):
    ...
    ValueError: y and distance must have one entry per row of X (2), got (2,) and (1,)
    """
    shapes = [np.shape(a) for a in arrays.values()]
    if any(shape != (n,) for shape in shapes):
        names, got = list(arrays), [str(shape) for shape in shapes]
        raise ValueError(
            f"{', '.join(names[:-1])} and {names[-1]} must have one entry per row of {of} ({n}), "
            f"got {', '.join(got[:-1])} and {got[-1]}"
        )


def output_path(name: str, path, suffix: str, *, any_suffix: bool = False) -> Path:
    """The file a writer creates for ``path``: ``suffix`` appended as the writer would append it.

    NumPy's ``savez`` appends ``.npz`` unless the name ends with it; matplotlib's ``savefig``
    appends ``.png`` only to a name without any suffix (``any_suffix=True``). Reporting this path,
    not the one given, keeps what is reported equal to what is written. A name that is empty or
    a directory is refused instead of becoming a hidden file such as ``..npz``.

    Examples
    --------
    >>> output_path("out", "runs/rec", ".npz").as_posix()
    'runs/rec.npz'
    >>> output_path("plot", "modes.svg", ".png", any_suffix=True).as_posix()
    'modes.svg'
    >>> output_path("out", ".", ".npz")
    Traceback (most recent call last):
    ...
    ValueError: out must name a file, got '.' (a directory)
    """
    text = os.fspath(path)
    if not isinstance(text, str) or not text.strip():
        raise ValueError(f"{name} must name a file, got {text!r}")
    target = Path(text)
    if text.endswith(("/", os.sep)) or target.name in ("", ".", "..") or target.is_dir():
        raise ValueError(f"{name} must name a file, got {text!r} (a directory)")
    has_suffix = bool(target.suffix) if any_suffix else target.name.endswith(suffix)
    return target if has_suffix else target.with_name(target.name + suffix)


@contextmanager
def open_npz(path, what: str) -> Iterator[np.lib.npyio.NpzFile]:
    """Open an ``.npz`` archive without pickle; any damage becomes one ``ValueError`` naming it.

    A truncated, foreign or corrupted file makes NumPy and :mod:`zipfile` raise half a dozen
    kinds of errors (``BadZipFile``, ``EOFError``, ``zlib.error``, a ``KeyError`` for a missing
    array, a ``ValueError`` for pickled data), some only when an array is read. Inside this
    context they all end as ``ValueError("<path> is not <what>: ...")``; a missing file stays a
    :class:`FileNotFoundError`.

    Examples
    --------
    >>> import tempfile, os
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = os.path.join(d, "x.npz")
    ...     with open(p, "wb") as f:
    ...         _ = f.write(b"t,ax,az")
    ...     with open_npz(p, "a recording") as data:
    ...         pass
    Traceback (most recent call last):
    ...
    ValueError: ...x.npz is not a recording: not an .npz archive (it does not begin like a zip file)
    """
    path = Path(os.fspath(path))
    if path.is_dir():
        raise ValueError(f"{path} is a directory, not {what}")
    damaged = (zipfile.BadZipFile, EOFError, zlib.error, ValueError, OSError)
    # The file is opened here, not by NumPy, so that it is closed whatever fails.
    with open(path, "rb") as file:  # a missing file raises FileNotFoundError here
        head = file.read(4)
        file.seek(0)
        if not head:
            raise ValueError(f"{path} is not {what}: the file is empty")
        if head not in (b"PK\x03\x04", b"PK\x05\x06"):
            raise ValueError(
                f"{path} is not {what}: not an .npz archive (it does not begin like a zip file)"
            )
        try:
            data = np.load(file, allow_pickle=False)
        except damaged as exc:
            damage = f"the file is truncated or damaged ({exc})"
            raise ValueError(f"{path} is not {what}: {damage}") from None
        with data:
            try:
                yield data
            except KeyError as exc:
                raise ValueError(f"{path} is not {what}: it lacks the array {exc}") from None
            except damaged as exc:
                if isinstance(exc, ValueError) and str(path) in str(exc):
                    raise  # already names the file
                raise ValueError(f"{path} is not {what}: {exc}") from None
