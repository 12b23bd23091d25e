"""Input validation shared by the whole package.

Every public function checks its arguments at the boundary with these helpers, so that bad input
raises a :class:`ValueError` or :class:`TypeError` that names the parameter, the allowed range and
the value given, instead of a NaN or a traceback from deep inside NumPy.
"""

from __future__ import annotations

import errno
import json
import math
import os
import re
import stat
import tempfile
import tokenize
import zipfile
import zlib
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from numbers import Real
from pathlib import Path

import numpy as np
from numpy.lib import format as npformat

from ._budget import MemoryBudgetError, check_allocation

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
    "check_n_jobs",
    "more_jobs_allowed",
    "check_choice",
    "real_array",
    "check_array",
    "check_split",
    "check_samples",
    "check_targets",
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


#: Set by :func:`more_jobs_allowed`: counts of workers above the cores are then accepted.
_MORE_JOBS = False


@contextmanager
def more_jobs_allowed(allowed: bool = True) -> Iterator[None]:
    """A context in which :func:`check_n_jobs` accepts more workers than the machine's cores
    (what ``--force-jobs`` asks for on the command line)."""
    global _MORE_JOBS
    before, _MORE_JOBS = _MORE_JOBS, bool(allowed)
    try:
        yield
    finally:
        _MORE_JOBS = before


def check_n_jobs(name: str, value):
    """Return ``value``, a count of workers: None (one, or the caller's default), -1 (every
    core) or an integer from 1 to the machine's cores (``os.cpu_count()``).

    More workers than cores only compete for them, and a count such as 100000 starts a process
    for each task until memory runs out: it is refused, naming ``name``, unless inside
    :func:`more_jobs_allowed`.

    Examples
    --------
    >>> check_n_jobs("n_jobs", -1)
    -1
    >>> check_n_jobs("n_jobs", 0)
    Traceback (most recent call last):
    ...
    ValueError: n_jobs must be -1 (every core), None or a count of workers >= 1, got 0
    """
    if value is None:
        return None
    value = check_int(name, value)
    if value == -1:
        return value
    if value < 1:
        raise ValueError(f"{name} must be -1 (every core), None or a count of workers >= 1, "
                         f"got {describe(value)}")
    cores = os.cpu_count() or 1
    if value > cores and not _MORE_JOBS:
        raise ValueError(f"{name} must be at most this machine's {cores} core"
                         f"{'s' if cores > 1 else ''} (or -1), got {describe(value)}: more "
                         "workers than cores only compete for them")
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


# --- Files: the paths a user names, and what a loader may read from them -----------------------

#: How deep the JSON that a loader reads may nest. The package's own files nest at most 6
#: levels (a model's parameters); 100 keeps the parser far below Python's recursion limit.
MAX_JSON_DEPTH = 100

#: The largest text file (a scene) a loader reads, bytes: a scene is under 2 KiB; 1 MiB leaves
#: room for comments and still bounds the parsed objects to a few tens of MiB.
MAX_TEXT_BYTES = 2**20

_FILE_KINDS = (
    (stat.S_ISDIR, "a directory"),
    (stat.S_ISFIFO, "a FIFO (named pipe)"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)


def check_path(name: str, path) -> str:
    """Return ``path`` as text; raise unless it is a ``str`` or ``os.PathLike`` naming a file.

    Bytes are refused (decode them with :func:`os.fsdecode`), and so is a NUL character, which
    no file name can hold.

    Examples
    --------
    >>> check_path("path", b"rec.npz")
    Traceback (most recent call last):
    ...
    TypeError: path must be a str or os.PathLike, got bytes b'rec.npz' (decode it with os.fsdecode)
    >>> check_path("--out", "a\\x00b")
    Traceback (most recent call last):
    ...
    ValueError: --out holds a NUL character, which no file name can contain: 'a\\x00b'
    """
    if isinstance(path, bytes | bytearray | memoryview):
        raise TypeError(
            f"{name} must be a str or os.PathLike, got bytes {bytes(path)!r:.80} "
            "(decode it with os.fsdecode)"
        )
    try:
        text = os.fspath(path)
    except TypeError:
        raise TypeError(
            f"{name} must be a str or os.PathLike, got {type(path).__name__} {path!r:.80}"
        ) from None
    if not isinstance(text, str):
        raise TypeError(f"{name} must be a str or os.PathLike giving a str, got bytes {text!r:.80}")
    if "\x00" in text:
        raise ValueError(
            f"{name} holds a NUL character, which no file name can contain: {text!r:.80}"
        )
    if not text:
        raise ValueError(f"{name} must name a file, got an empty path")
    return text


def _kind(mode: int) -> str | None:
    """What a file of ``st_mode`` ``mode`` is, unless it is a regular file (then None)."""
    if stat.S_ISREG(mode):
        return None
    return next((kind for test, kind in _FILE_KINDS if test(mode)), "not a regular file")


def open_regular(path, what: str, *, name: str = "path"):
    """Open ``path`` for binary reading; raise unless it is a regular file.

    A FIFO, a device or a directory is refused before it is opened (opening a FIFO waits for a
    writer: forever). The file is opened non-blocking and checked again through its descriptor,
    so that a FIFO put in its place after the first check is refused too, not waited on.

    Raises
    ------
    FileNotFoundError
        If there is no such file (or a directory on the way is missing).
    IsADirectoryError
        If it is a directory.
    ValueError
        Naming the file, if it is a FIFO, a device or a socket.
    """
    path = Path(check_path(name, path))
    kind = _kind(os.stat(path).st_mode)  # follows symlinks; a missing file raises here
    if kind == "a directory":  # as open() reports it
        raise IsADirectoryError(errno.EISDIR, f"Is a directory, not {what}", str(path))
    if kind is not None:
        raise ValueError(f"{path} is {kind}, not {what}")
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0)
    fd = os.open(path, flags)
    try:
        kind = _kind(os.fstat(fd).st_mode)
        if kind is not None:
            raise ValueError(f"{path} is {kind}, not {what}")
        if hasattr(os, "set_blocking"):
            os.set_blocking(fd, True)
    except BaseException:
        os.close(fd)
        raise
    return os.fdopen(fd, "rb")


def read_text(path, what: str, *, max_bytes: int = MAX_TEXT_BYTES) -> str:
    """The UTF-8 text of the regular file ``path``, at most ``max_bytes`` bytes long.

    Raises
    ------
    ValueError
        Naming the file, if it is not a regular file, is longer, or is not UTF-8 text.
    """
    with open_regular(path, what) as file:
        raw = file.read(max_bytes + 1)  # a file of /proc reports a size of 0: read, then count
    path = Path(os.fspath(path))
    if len(raw) > max_bytes:
        raise ValueError(f"{path} is not {what}: it is longer than {max_bytes} bytes")
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ValueError(
            f"{path} is not {what}: it is not UTF-8 text (byte {raw[exc.start]:#04x} at "
            f"offset {exc.start})"
        ) from None


_JSON_STRING = re.compile(r'"(?:[^"\\]|\\.)*"', re.DOTALL)


def json_depth(text: str) -> int:
    """How deep the arrays and objects of the JSON ``text`` nest (0 for a bare value).

    Brackets inside strings do not count. Counted without parsing, so that a document nested
    deeper than the parser's recursion limit is measured, not crashed on.

    Examples
    --------
    >>> json_depth('{"a": [1, "]]", {"b": []}]}')
    4
    """
    skeleton = _JSON_STRING.sub("", text).encode("utf-8", "surrogatepass")
    codes = np.frombuffer(skeleton, dtype=np.uint8)
    steps = np.isin(codes, (ord("["), ord("{"))).astype(np.int64)
    steps -= np.isin(codes, (ord("]"), ord("}")))
    return int(np.cumsum(steps).max(initial=0))


def load_json(text: str, path, what: str):
    """Parse the JSON ``text`` read from ``path``; any fault is one ``ValueError`` naming it.

    Documents nested deeper than :data:`MAX_JSON_DEPTH` are refused before parsing.
    """
    depth = json_depth(text)
    if depth > MAX_JSON_DEPTH:
        raise ValueError(
            f"{path} is not {what}: its JSON nests {depth} levels deep, more than the "
            f"{MAX_JSON_DEPTH} allowed"
        )
    try:
        return json.loads(text)
    except (ValueError, RecursionError) as exc:
        raise ValueError(f"{path} is not {what}: not valid JSON ({exc})") from None


def _probe_directory(name: str, directory: Path) -> None:
    """Raise unless a file can be created in ``directory`` (by creating and removing one)."""
    try:
        fd, probe = tempfile.mkstemp(prefix=".ebantenna-write-test-", dir=directory)
    except OSError as exc:
        why = exc.strerror or str(exc)
        if exc.errno == errno.ENOENT:  # the directory exists: it refuses files (/proc, /sys)
            why = "it does not accept new files (a kernel file system such as /proc or /sys?)"
        raise OSError(f"{name}: cannot write in {directory}: {why}") from None
    os.close(fd)
    os.unlink(probe)


def _check_writable(name: str, target: Path) -> None:
    """Raise unless ``target`` can be written: a regular file or a new name in a directory that
    exists and accepts files."""
    if os.path.exists(target):
        kind = _kind(os.stat(target).st_mode)
        if kind is not None:
            raise ValueError(f"{name} must name a regular file, got {str(target)!r} ({kind})")
        if not os.access(target, os.W_OK):
            raise PermissionError(f"{name}: {target} is not writable")
        return
    parent = target.parent
    if not parent.exists():
        raise FileNotFoundError(f"{name}: the directory {parent} does not exist (for {target})")
    if not parent.is_dir():
        raise NotADirectoryError(f"{name}: {parent} is not a directory")
    _probe_directory(name, parent)


def output_path(name: str, path, suffix: str, *, any_suffix: bool = False) -> Path:
    """The file a writer creates for ``path``: ``suffix`` appended as the writer would append it.

    NumPy's ``savez`` appends ``.npz`` unless the name ends with it; matplotlib's ``savefig``
    appends ``.png`` only to a name without any suffix (``any_suffix=True``). Reporting this path,
    not the one given, keeps what is reported equal to what is written. A name that is empty or
    a directory is refused instead of becoming a hidden file such as ``..npz``.

    The path is checked as a writer would meet it, so that a command can refuse it before its
    work starts: its directory must exist and accept a new file (one is created and removed), and
    an existing file there must be a regular, writable file (a FIFO would block the writer).

    Examples
    --------
    >>> output_path("out", "rec", ".npz").as_posix()
    'rec.npz'
    >>> output_path("plot", "modes.svg", ".png", any_suffix=True).as_posix()
    'modes.svg'
    >>> output_path("out", ".", ".npz")
    Traceback (most recent call last):
    ...
    ValueError: out must name a file, got '.' (a directory)
    >>> output_path("--out", "no-such-dir/rec", ".npz")
    Traceback (most recent call last):
    ...
    FileNotFoundError: --out: the directory no-such-dir does not exist (for no-such-dir/rec.npz)
    """
    if isinstance(path, str) and not path.strip():
        raise ValueError(f"{name} must name a file, got {path!r}")
    text = check_path(name, path)
    target = Path(text)
    if text.endswith(("/", os.sep)) or target.name in ("", ".", "..") or target.is_dir():
        raise ValueError(f"{name} must name a file, got {text!r} (a directory)")
    has_suffix = bool(target.suffix) if any_suffix else target.name.endswith(suffix)
    target = target if has_suffix else target.with_name(target.name + suffix)
    _check_writable(name, target)
    return target


def output_dir(name: str, path) -> Path:
    """The directory ``path`` that a command will write into, checked before its work starts.

    An existing directory must accept new files; a missing one must be creatable (its nearest
    existing ancestor a directory that accepts new files). It is not created here.

    Examples
    --------
    >>> output_dir("--out", "runs/today").as_posix()
    'runs/today'
    """
    if isinstance(path, str) and not path:
        raise ValueError(f"{name} must name a directory, got an empty path")
    target = Path(check_path(name, path))
    if target.exists():
        kind = _kind(os.stat(target).st_mode)
        if kind != "a directory":
            raise NotADirectoryError(
                f"{name} must be a directory, got {str(target)!r} ({kind or 'a regular file'})"
            )
        _probe_directory(name, target)
        return target
    ancestor = target.parent
    while not ancestor.exists() and ancestor != ancestor.parent:
        ancestor = ancestor.parent
    if not ancestor.is_dir():
        raise NotADirectoryError(
            f"{name}: {ancestor} is not a directory, so {target} cannot be made"
        )
    _probe_directory(name, ancestor)
    return target


def plain_name(text) -> bool:
    """Whether ``text`` can name a file inside a folder and nothing else: a non-empty string,
    not ``.`` or ``..``, with no path separator and no NUL.

    Examples
    --------
    >>> plain_name("paper-small-seed1.npz"), plain_name("x/../../escaped"), plain_name("..")
    (True, False, False)
    """
    return (isinstance(text, str) and text not in ("", ".", "..")
            and not any(c in text for c in ("/", "\\", "\x00", os.sep)))


def output_file_in(name: str, directory, file_name: str, *, renamed: bool = False) -> Path:
    """The file ``file_name`` that a command will write in ``directory``, checked before its
    work starts; ``directory`` is checked by :func:`output_dir` (it may not exist yet), and
    ``file_name`` must be a plain name (no path separator, not ``.`` or ``..``): a name made
    from the user's input cannot write outside ``directory``.

    Where the file exists it must be a regular file, which the writer replaces: a directory, a
    FIFO or a device in its place is refused with a ``ValueError`` naming ``name`` and the path
    (found only at the end of the work otherwise, when the finished file cannot take its place,
    or the writer waits on the FIFO for ever). A writer that puts its finished file in place by
    renaming (``renamed``) replaces a FIFO or a device too; only a directory is refused then.

    Examples
    --------
    >>> output_file_in("--out", ".", "x.npz").as_posix()
    'x.npz'
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     (Path(tmp) / "x.npz").mkdir()
    ...     output_file_in("--out", tmp, "x.npz")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: --out: .../x.npz is a directory where the file goes; move it or choose another --out
    """
    directory = output_dir(name, directory)
    if not plain_name(file_name):
        # a name made from the user's input (a scene's name) would write outside the folder
        raise ValueError(f"{name}: {file_name!r:.80} is not a plain file name: it would be "
                         f"written outside {directory}; rename what it was made from")
    target = directory / file_name
    try:
        mode = os.stat(target).st_mode  # follows a link: what the writer would meet
    except FileNotFoundError:
        return target  # new (or a dangling link, which the writer replaces)
    except OSError as exc:
        raise OSError(f"{name}: cannot reach {target}: {exc.strerror or exc}") from None
    kind = _kind(mode)
    if kind is not None and (kind == "a directory" or not renamed):
        raise ValueError(f"{name}: {target} is {kind} where the file goes; move it or choose "
                         f"another {name}")
    return target


def _check_npz_sizes(archive: zipfile.ZipFile, path: Path) -> None:
    """Raise unless every array's header in ``archive`` declares a size within the budget.

    The headers are read, not the arrays: a header that declares 2**40 values is refused before
    NumPy allocates them. The error names the file and the array.
    """
    readers = {(1, 0): npformat.read_array_header_1_0, (2, 0): npformat.read_array_header_2_0}
    total = 0
    for info in archive.infolist():
        if not info.filename.endswith(".npy"):
            continue
        with archive.open(info) as member:
            version = npformat.read_magic(member)
            if version not in readers:
                raise ValueError(f"its array {info.filename} has .npy version {version}")
            try:
                shape, _, dtype = readers[version](member)
            except ValueError as exc:  # NumPy's message runs over several lines
                first = str(exc).strip().splitlines()[0]
                raise ValueError(f"its array {info.filename} has a bad header: {first}") from None
        if any(n < 0 for n in shape):
            raise ValueError(f"its array {info.filename} declares the shape {shape}")
        nbytes = math.prod(shape) * dtype.itemsize
        total += nbytes
        check_allocation(nbytes, parameter=f"the file {path}",
                         what=f"its array {info.filename[:-4]!r} of shape {shape}")
    check_allocation(total, parameter=f"the file {path}", what="its arrays together")


@contextmanager
def open_npz(path, what: str) -> Iterator[np.lib.npyio.NpzFile]:
    """Open an ``.npz`` archive without pickle; any damage becomes one ``ValueError`` naming it.

    A truncated, foreign or corrupted file makes NumPy and :mod:`zipfile` raise half a dozen
    kinds of errors (``BadZipFile``, ``EOFError``, ``zlib.error``, a ``KeyError`` for a missing
    array, a ``ValueError`` for pickled data, tokenize's ``TokenError`` for an array header that
    is no literal), some only when an array is read. Inside this
    context they all end as ``ValueError("<path> is not <what>: ...")``; a missing file stays a
    :class:`FileNotFoundError`. Only a regular file is opened (:func:`open_regular`), and every
    array's size is read from its header and checked against the memory budget
    (:func:`ebantenna.memory_budget`) before any array is read.

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
    # zipfile raises NotImplementedError for an unknown compression method, RuntimeError for
    # an encrypted member; NumPy's reader of an array's header lets tokenize's TokenError out of
    # a header it cannot parse as a literal (its fallback for headers written by Python 2)
    damaged = (zipfile.BadZipFile, EOFError, zlib.error, ValueError, OSError,
               NotImplementedError, RuntimeError, tokenize.TokenError, SyntaxError)
    if os.path.isdir(check_path("path", path)):
        raise ValueError(f"{Path(path)} is a directory, not {what}")
    # The file is opened here, not by NumPy, so that it is closed whatever fails.
    with open_regular(path, what) as file:  # a missing file raises FileNotFoundError here
        path = Path(os.fspath(path))
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
                _check_npz_sizes(data.zip, path)
            except MemoryBudgetError:
                raise
            except damaged as exc:
                raise ValueError(f"{path} is not {what}: the file is damaged ({exc})") from None
            try:
                yield data
            except KeyError as exc:
                raise ValueError(f"{path} is not {what}: it lacks the array {exc}") from None
            except RecursionError:
                raise ValueError(f"{path} is not {what}: it nests too deeply") from None
            except damaged as exc:
                if isinstance(exc, ValueError) and str(path) in str(exc):
                    raise  # already names the file
                raise ValueError(f"{path} is not {what}: {exc}") from None


def check_split(split, n_rows: int) -> tuple[np.ndarray, np.ndarray]:
    """``split`` as ``(train, test)`` row indices of ``n_rows`` rows: a pair of non-empty 1-D
    integer arrays, each index in ``0 ... n_rows - 1``, no row in both; else an error naming
    ``split``.

    Examples
    --------
    >>> [r.tolist() for r in check_split(([0, 2], [1]), 3)]
    [[0, 2], [1]]
    >>> check_split("x", 3)
    Traceback (most recent call last):
    ...
    TypeError: split must be a pair (train rows, test rows), got 'x'
    """
    if isinstance(split, str | bytes | dict) or not hasattr(split, "__len__") or len(split) != 2:
        raise TypeError(f"split must be a pair (train rows, test rows), got {describe(split)}")
    out = []
    for part, rows in zip(("train", "test"), split, strict=True):
        a = np.asarray(rows)
        if a.ndim != 1 or a.size == 0 or a.dtype.kind not in "iu":
            raise ValueError(f"split's {part} rows must be a non-empty 1-D array of integer row "
                             f"indices, got {a.dtype} of shape {a.shape}")
        if a.min() < 0 or a.max() >= n_rows:
            raise ValueError(f"split's {part} rows must lie in 0 ... {n_rows - 1}, got "
                             f"{int(a.min())} ... {int(a.max())}")
        out.append(a.astype(np.intp))
    if np.intersect1d(*out).size:
        raise ValueError("split must not put one row in both train and test")
    return out[0], out[1]



def check_samples(X, *, n_features: int | None = None, owner: str = "the estimator",
                  name: str = "X") -> None:
    """Refuse, in the package's words, samples ``X`` that no estimator can read: not a
    rectangular 2-D array of numbers, no row, a NaN or an infinity, or (``n_features`` given)
    another number of columns than the fit saw. ``X`` itself is left as it is, for the
    estimator's own conversion (scikit-learn's ``validate_data``) that follows.

    Sparse matrices are checked by their stored values and their shape; arrays of objects (a
    DataFrame of mixed columns) by their shape only, their conversion names what fails. The
    messages keep the phrases scikit-learn's estimator checks look for ("Reshape your data",
    "NaN", "inf", "X has 2 features, but SVC is expecting 3 features as input").

    Examples
    --------
    >>> check_samples([[1.0, float("nan")]])
    Traceback (most recent call last):
    ...
    ValueError: X must contain only finite values (no NaN, no infinity): row 0, column 1 is nan
    >>> check_samples([[1.0, 2.0]], n_features=3, owner="SVC")
    Traceback (most recent call last):
    ...
    ValueError: X has 2 features, but SVC is expecting 3 features as input.
    """
    if hasattr(X, "tocsr") and hasattr(X, "nnz"):  # a SciPy sparse matrix or array
        shape, values = tuple(X.shape), np.asarray(X.tocsr().data)
    else:
        if isinstance(X, str | bytes):
            raise TypeError(f"{name} must be a 2-D array of numbers (n_samples, n_features), "
                            f"got {type(X).__name__} {describe(X)}")
        try:
            values = np.asarray(X)
        except ValueError:
            raise ValueError(f"{name} must be a rectangular array: its rows have different "
                             "lengths (a ragged list)") from None
        except (TypeError, OverflowError, RecursionError, MemoryError):
            raise TypeError(f"{name} must be array-like of numbers, got "
                            f"{type(X).__name__}") from None
        shape = values.shape
        if values.dtype.kind in "USV":
            raise TypeError(f"{name} must be array-like of real numbers, got a "
                            f"{_REFUSED_KINDS[values.dtype.kind]} array (dtype {values.dtype})")
        if values.dtype.kind == "c":
            raise ValueError(f"{name} must hold real numbers: Complex data not supported "
                             f"(dtype {values.dtype})")
    if len(shape) != 2:
        raise ValueError(
            f"{name} must be a 2-D array (n_samples, n_features), got {len(shape)} dimension(s), "
            f"shape {shape}: Expected 2D array. Reshape your data with {name}.reshape(-1, 1) "
            f"if it has a single feature, or {name}.reshape(1, -1) if it is a single sample.")
    if shape[0] == 0:
        raise ValueError(f"{name} must hold at least one sample, got 0 sample(s) (shape={shape})")
    if values.dtype.kind in "fiu" and values.size:
        finite = np.isfinite(values)
        if not finite.all():
            where = np.argwhere(~finite)[0]
            at = (f"row {where[0]}, column {where[1]}" if values.ndim == 2
                  else "a stored value")
            raise ValueError(f"{name} must contain only finite values (no NaN, no infinity): "
                             f"{at} is {values[tuple(where)]}")
    if n_features is not None and shape[1] != n_features:
        raise ValueError(f"{name} has {shape[1]} features, but {owner} is expecting "
                         f"{n_features} features as input.")


def check_targets(X, y, *, numeric: bool = False):
    """Refuse, in the package's words, targets ``y`` of another length than the rows of ``X``
    (samples checked by :func:`check_samples`), a ragged ``y``, and for a regressor
    (``numeric``) NaN or infinity; return ``y`` as given. None, a string and a sparse ``y`` are
    left to the estimator's own conversion.

    Examples
    --------
    >>> check_targets([[1.0], [2.0]], [0])
    Traceback (most recent call last):
    ...
    ValueError: y must hold one target per row of X (2), got 1: inconsistent numbers of samples
    """
    if y is None or isinstance(y, str | bytes) or (hasattr(y, "tocsr") and hasattr(y, "nnz")):
        return y
    try:
        values = np.asarray(y)
    except ValueError:
        raise ValueError("y must be a rectangular array: its rows have different lengths "
                         "(a ragged list)") from None
    except (TypeError, OverflowError, RecursionError, MemoryError):
        raise TypeError(f"y must be array-like, got {type(y).__name__}") from None
    n = X.shape[0] if hasattr(X, "shape") else np.asarray(X).shape[0]  # (no array functions)
    if values.ndim and values.shape[0] != n:
        raise ValueError(f"y must hold one target per row of X ({n}), got {values.shape[0]}: "
                         "inconsistent numbers of samples")
    if numeric and values.dtype.kind in "fc" and not np.all(np.isfinite(values)):
        raise ValueError("y must contain only finite values (no NaN, no infinity)")
    return y
