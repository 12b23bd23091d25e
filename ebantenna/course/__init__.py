"""Self-checks for the exercises: is a student's value within the stated tolerance?

Every exercise of the documentation states what to compute, the data to compute it from (with its
seed) and, for each expected answer, a tolerance with its reason: how far two legitimate ways of
working may differ. :func:`check` tells whether a value is within that tolerance of the answer of
the worked solution, without printing the answer::

    >>> from ebantenna.course import check
    >>> print(check("ex05", tau_fit_ms=None))
    tau_fit_ms: not yet: no value given (None)

The package does not hold the answers in readable form. Each one is *sealed* (:func:`seal`): the
answer's tolerance is cut into cells of a fifth of its width (on a log scale for a relative
tolerance or a factor), and the key keeps the salted hashes of the cells within the tolerance,
each stretched by scrypt (:data:`KDF`, about 4 ms a cell). A value is checked by hashing its
own cell once: the check says "within" or "not yet" and gives nothing else back, not the answer
nor its place in the cell. A value up to a fifth of the tolerance beyond its edge may still be
"within" (its cell holds values within); a grade uses the teacher's plain answers instead.

What this does not prevent, and the installation page tells teachers: a search. :func:`check`
answers "within" or "not yet", so trying values finds one within the tolerance; a student who
knows an answer to within N tolerance widths needs at most about N / 2 tries, each one hash, by
:func:`check` or by a program over the key (about 4 ms a try either way). The stretching makes
a wide search slower (a million widths take about half an hour), not a narrow one. The worked
solutions are in the public repository. The check is a help for learning, not a grader.

**Graded variants.** For graded work a teacher gives each student their own data:
:func:`parameters` draws an exercise's parameters from a student's id (the same id, the same
parameters, on any machine), the exercise's data block reads them, and
``docs/_tools/make_variant_key.py`` (in the repository, for the teacher) runs the worked solution
for every student of a list and writes the teacher's answer sheet and a sealed key for the
students' self-checks, ``check(..., student=id, key=path)``. Copying another student's answer or
the published one then fails the check (unless the two answers happen to lie within a tolerance
of each other); a search over one's own key, as above, does not. For a
grade the teacher compares the values collected with the teacher's own answer sheet.

The key comes from ``ebantenna/course/_answer_key.py``, which ``docs/_tools/make_answer_key.py``
writes by running the worked solutions; the test suite checks that it still seals what they
compute.
"""

from __future__ import annotations

import hashlib
import math
import numbers
import os
from dataclasses import dataclass

from ._answer_key import ANSWER_KEY

__all__ = [
    "Tolerance", "CheckReport", "exercises", "tolerances", "check", "seal", "VARIANTS",
    "parameters", "load_variant_key", "student_tag", "KEY_FORMAT", "KDF", "SHARES",
]

#: the key-stretching function every sealed cell goes through: scrypt (memory-hard, from the
#: standard library), about 4 ms a cell with these costs on a server core (3.6 ms measured). A
#: check costs one cell a value, a search that much for every cell it tries; the cost is kept low
#: enough that a check stays instant in class and a class's variant key is written in seconds
KDF = {"name": "scrypt", "n": 2**11, "r": 8, "p": 1}

#: cells per tolerance width: the check accepts every value within the tolerance and, at each
#: edge, may accept up to one cell (a fifth of the tolerance) more
SHARES = 5

#: how a tolerance is measured: an absolute difference, a relative one, or a ratio
KINDS = ("abs", "rel", "factor")


@dataclass(frozen=True)
class Tolerance:
    """How close a value must be to the expected one, and why that much.

    Parameters
    ----------
    kind : {"abs", "rel", "factor"}
        ``"abs"``: ``|value - expected| <= width`` (in the answer's unit; ``width = 0`` means
        exactly); ``"rel"``: ``|value / expected - 1| <= width``; ``"factor"``: the ratio
        ``value / expected`` lies within ``[1 / width, width]`` (for rounding errors, whose size
        depends on the order of the operations, not their value).
    width : float
        The tolerance (unit of the answer for ``"abs"``, dimensionless otherwise).
    reason : str
        One sentence: which legitimate choices make two correct answers differ by that much.
    """

    kind: str
    width: float
    reason: str

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"kind must be one of {KINDS}, got {self.kind!r}")
        if not isinstance(self.reason, str):
            raise TypeError(f"reason must be a sentence (str), got {type(self.reason).__name__}")
        if not _finite("width", self.width) >= 0:
            raise ValueError(f"width must be finite and >= 0, got {self.width!r}")
        if self.kind == "factor" and self.width < 1:
            raise ValueError(f"a factor tolerance must be >= 1, got {self.width!r}")

    def describe(self) -> str:
        """The tolerance in words: ``"±1 %"``, ``"±0.05"``, ``"exact"`` or ``"a factor 3"``."""
        if self.kind == "abs":
            return "exact" if self.width == 0 else f"±{self.width:g}"
        if self.kind == "rel":
            if self.width >= 1e-3:
                return f"±{100 * self.width:g} %"
            return f"±{self.width:.0e} relative"
        return f"a factor {self.width:g}"

    def accepts(self, value: float, expected: float) -> bool:
        """Whether ``value`` is within this tolerance of ``expected`` (finite real numbers)."""
        value, expected = _finite("value", value), _finite("expected", expected)
        if self.kind == "abs":
            # a few ulps of the answer let "exactly" accept the same share or count reached by
            # another order of operations; an answer of zero has no rounding, so none there
            slack = 4 * math.ulp(expected) if expected else 0.0
            return abs(value - expected) <= self.width + slack
        if self.kind == "rel":
            return abs(value - expected) <= self.width * abs(expected)
        if value == expected:
            return True
        if value * expected <= 0:  # a sign change or a zero is no rounding difference
            return False
        ratio = value / expected
        return 1 / self.width <= ratio <= self.width


def _grid(tolerance: Tolerance) -> tuple[str, float, float, float]:
    """The coordinate a tolerance is sealed in: ``(scale, cell, low, high)``.

    ``"lin"``: ``u = value / cell``; ``"log"``: ``u = log|value| / cell`` (the sign kept apart);
    ``"exact"``: no cells, the value's first 12 significant digits. ``cell`` is a
    :data:`SHARES`-th of the tolerance, and a value is accepted when ``u - u_answer`` lies in
    ``[low, high]`` (``low = -high = -SHARES`` but for a relative tolerance, which is wider above
    the answer than below it on a log scale).
    """
    if tolerance.kind == "abs":
        if tolerance.width == 0:
            return "exact", 1.0, 0.0, 0.0
        return "lin", tolerance.width / SHARES, -SHARES, SHARES
    if tolerance.kind == "rel":
        if not 0 < tolerance.width < 1:
            raise ValueError(f"a relative tolerance to seal must be in (0, 1), got "
                             f"{tolerance.width!r}")
        low, high = math.log1p(-tolerance.width), math.log1p(tolerance.width)
        cell = (high - low) / (2 * SHARES)
        return "log", cell, low / cell, high / cell
    if tolerance.width <= 1:
        raise ValueError(f"a factor tolerance to seal must be > 1, got {tolerance.width!r}")
    return "log", math.log(tolerance.width) / SHARES, -SHARES, SHARES


def _cell_text(scale: str, cell: float, value: float) -> tuple[str, float]:
    """``(sign, u)``: the value in cells (the sign kept apart on a log scale)."""
    if scale == "lin":
        return "", value / cell
    if value == 0:
        return "0", math.nan  # no relative tolerance or factor accepts a zero
    return ("+" if value > 0 else "-"), math.log(abs(value)) / cell


def _digest(salt: str, text: str, kdf: dict) -> str:
    """The stretched hash of one cell (scrypt, :data:`KDF`): 16 hex digits."""
    return hashlib.scrypt(text.encode(), salt=salt.encode(), n=kdf["n"], r=kdf["r"],
                          p=kdf["p"], maxmem=2**26, dklen=8).hex()


def _cell_of(tolerance: Tolerance, value: float) -> str | None:
    """The text of the cell ``value`` falls in, or None if no answer's cell can hold it."""
    scale, cell, _, _ = _grid(tolerance)
    if scale == "exact":
        return f"={value + 0.0:.12g}"
    sign, u = _cell_text(scale, cell, value)
    if not math.isfinite(u):  # a zero on a log scale, or 1e308 in cells of 1e-9
        return None
    return f"{sign}{math.floor(u)}"


def _finite(name: str, value) -> float:
    """``value`` as a float, once it is a finite real number (a bool or a string is not)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a real number, got {value!r:.40} "
                        f"({type(value).__name__})")
    try:
        value = float(value)
    except OverflowError:
        value = math.inf
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return value


def seal(value: float, tolerance: Tolerance, salt: str) -> dict:
    """The answer ``value`` in the form the key holds: the hashes of the cells it accepts.

    The tolerance's coordinate (``value / width`` for an absolute tolerance, ``log|value|`` for a
    relative one or a factor) is cut into cells of a :data:`SHARES`-th of the tolerance; the key
    keeps the stretched hash (:data:`KDF`) of every cell that holds a value within the
    tolerance, in sorted order. An exact answer (``width = 0``) keeps the hash of its first 12
    significant digits. Nothing in the result says where in those cells the answer lies.

    Parameters
    ----------
    value : float
        The expected answer (finite; not zero when the tolerance is relative or a factor).
    tolerance : Tolerance
        Its tolerance: it sets the cells.
    salt : str
        Text hashed with every cell, different for every answer (``"ex05_decay/tau_fit_ms"``),
        so that two answers in the same cell do not show it.

    Returns
    -------
    dict
        ``{"salt", "kdf", "cells"}``; :func:`check` says whether a value's cell is one of
        ``cells`` (one hash a value) and gives nothing else back.
    """
    if not isinstance(tolerance, Tolerance):
        raise TypeError(f"tolerance must be a Tolerance, got {type(tolerance).__name__}")
    if not isinstance(salt, str) or not salt:
        raise ValueError(f"salt must be a non-empty str, got {salt!r}")
    value = _finite("value", value)
    scale, cell, low, high = _grid(tolerance)
    if scale == "log" and value == 0:
        raise ValueError("value must not be zero for a relative or factor tolerance")
    if scale == "exact":
        texts = [_cell_of(tolerance, value)]
    else:
        sign, u = _cell_text(scale, cell, value)
        if not math.isfinite(u) or not math.isfinite(u + high):
            raise ValueError(f"value must be within the range of floats in cells of the "
                             f"tolerance, got {value!r} in cells of {cell!r}")
        texts = [f"{sign}{i}" for i in range(math.floor(u + low), math.floor(u + high) + 1)]
    cells = sorted(_digest(salt, text, KDF) for text in texts)
    return {"salt": salt, "kdf": dict(KDF), "cells": cells}


def _is_sealed(sealed) -> bool:
    return (isinstance(sealed, dict) and isinstance(sealed.get("salt"), str)
            and isinstance(sealed.get("cells"), list)
            and all(isinstance(c, str) for c in sealed["cells"])
            and isinstance(sealed.get("kdf"), dict) and sealed["kdf"].get("name") == "scrypt"
            and all(isinstance(sealed["kdf"].get(k), int) for k in ("n", "r", "p")))


def _within(sealed: dict, tolerance: Tolerance, value: float) -> bool:
    """Whether the finite ``value`` falls in one of the sealed answer's cells (one hash)."""
    text = _cell_of(tolerance, value)
    return text is not None and _digest(sealed["salt"], text, sealed["kdf"]) in sealed["cells"]


#: The exercises with graded variants: for each parameter, its published value and the range a
#: variant draws it from, ``(published, low, high, decimals)`` (``decimals=None``: an integer
#: seed). The ranges keep every step of the exercise meaningful (ex04: a partner beyond the peak
#: exists for a contact from 0.66 L; ex05: the decay spans the record; ex06: the two clouds
#: overlap a little, so that the soft margin matters).
VARIANTS = {
    "ex04_peak": {"twin_of": (0.7, 0.66, 0.75, 2), "length_m": (0.4, 0.35, 0.45, 3)},
    "ex05_decay": {"tau_ms": (80.0, 60.0, 100.0, 0), "f0_hz": (120.0, 100.0, 140.0, 0),
                   "seed": (42, 0, 2**31 - 1, None)},
    "ex06_svm_dual": {"seed": (3, 0, 2**31 - 1, None), "spread": (0.7, 0.55, 0.8, 2)},
}


def _variant_seed(exercise: str, student: str) -> int:
    digest = hashlib.sha256(f"ebantenna.course/{exercise}/{student}".encode()).digest()
    return int.from_bytes(digest[:8], "little")


def parameters(exercise: str, student: str | None = None) -> dict:
    """The parameters of an exercise with graded variants: the published ones, or a student's.

    Parameters
    ----------
    exercise : str
        ``"ex05"`` or ``"ex05_decay"``; one of :data:`VARIANTS`.
    student : str or None
        The student's id as the teacher gives it (any non-empty text). ``None``: the published
        parameters, those of the expected answers on the exercise's page.

    Returns
    -------
    dict
        Parameter name -> value; the same id gives the same values on any machine (the draw is
        seeded by a SHA-256 of the exercise and the id).

    Examples
    --------
    >>> parameters("ex05")
    {'tau_ms': 80.0, 'f0_hz': 120.0, 'seed': 42}
    >>> parameters("ex05", student="s1") == parameters("ex05", student="s1")
    True
    """
    import numpy as np

    name = _full_name(exercise)
    if name not in VARIANTS:
        raise ValueError(f"exercise must be one with graded variants, {sorted(VARIANTS)}, "
                         f"got {exercise!r}")
    space = VARIANTS[name]
    if student is None:
        return {key: published for key, (published, *_rest) in space.items()}
    if not isinstance(student, str) or not student.strip():
        raise ValueError(f"student must be a non-empty str (the id the teacher gave), "
                         f"got {student!r}")
    rng = np.random.default_rng(_variant_seed(name, student.strip()))
    out = {}
    for key, (_, low, high, decimals) in space.items():
        if decimals is None:
            out[key] = int(rng.integers(low, high))
        else:
            out[key] = round(float(rng.uniform(low, high)), decimals)
    return out


#: what a variant key file says it is; a key without it (an earlier version's, which kept each
#: answer's place in its cell) is refused
KEY_FORMAT = "ebantenna.course variant key 2"


def student_tag(key_salt: str, student: str) -> str:
    """How a variant key names a student: a hash of the key's salt and the id, not the id.

    The key handed to a class then does not list the class (an id that is short or guessable,
    ``s1``, ``s2``, ..., can still be tried against it).
    """
    if not isinstance(key_salt, str) or not isinstance(student, str):
        raise TypeError("key_salt and student must be str")
    return hashlib.sha256(f"{key_salt}/{student.strip()}".encode()).hexdigest()[:16]


def _checked_key(key) -> dict:
    if not (isinstance(key, dict) and isinstance(key.get("students"), dict)
            and key.get("exercise") in ANSWER_KEY):
        raise ValueError("key must be a variant key file, this is not one")
    if key.get("format") != KEY_FORMAT or not isinstance(key.get("salt"), str):
        raise ValueError(f"key must be a variant key file of this version ({KEY_FORMAT!r}); "
                         "this one was written by an earlier ebantenna, whose keys showed more "
                         "than they should: ask the teacher for a key written by "
                         "docs/_tools/make_variant_key.py of this version")
    if not all(isinstance(v, dict) and all(_is_sealed(x) for x in v.values())
               for v in key["students"].values()):
        raise ValueError("key must be a variant key file: a student's answers are not sealed")
    return key


def load_variant_key(path) -> dict:
    """Read a variant key written by ``docs/_tools/make_variant_key.py`` (a JSON file).

    Returns ``{"format", "exercise", "salt", "students": {tag: {value name: sealed answer}}}``,
    a student's tag being :func:`student_tag` of the key's salt and their id; raises ValueError
    if the file is not such a key (a key of an earlier version included).
    """
    import json
    from pathlib import Path

    if not isinstance(path, str | os.PathLike) or isinstance(os.fspath(path), bytes):
        raise TypeError(f"path must be a str or os.PathLike, got {type(path).__name__}")
    if not os.fspath(path):
        raise ValueError("path must name a file, got an empty path")
    try:
        key = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError) as error:
        raise ValueError(f"key must be a variant key file, could not read {path!r}: "
                         f"{error}") from error
    try:
        return _checked_key(key)
    except ValueError as error:
        raise ValueError(f"{error} ({path!r})") from None


@dataclass(frozen=True)
class CheckReport:
    """The outcome of :func:`check`: one line per value, and whether all of them passed.

    Attributes
    ----------
    exercise : str
        The exercise's full name, e.g. ``"ex05_decay"``.
    lines : tuple of str
        ``"name: within ..."`` or ``"name: not yet: ..."``, in the order given.
    passed : tuple of bool
        Whether each value is within its tolerance.
    """

    exercise: str
    lines: tuple[str, ...]
    passed: tuple[bool, ...]

    def __post_init__(self):
        if not isinstance(self.exercise, str):
            raise TypeError(f"exercise must be a str, got {type(self.exercise).__name__}")
        if not isinstance(self.lines, tuple) or not all(isinstance(x, str) for x in self.lines):
            raise TypeError("lines must be a tuple of str")
        if not isinstance(self.passed, tuple) or not all(isinstance(x, bool)
                                                         for x in self.passed):
            raise TypeError("passed must be a tuple of True or False (one per line)")
        if len(self.passed) != len(self.lines):
            raise ValueError(f"passed must hold one verdict per line: {len(self.lines)} lines, "
                             f"{len(self.passed)} verdicts")

    @property
    def ok(self) -> bool:
        """True when every value given is within its tolerance."""
        return all(self.passed)

    def __str__(self) -> str:
        return "\n".join(self.lines)

    def _repr_pretty_(self, printer, cycle):  # a notebook cell shows the lines, not the repr
        printer.text(str(self))


def exercises() -> list[str]:
    """The exercises with expected answers, by full name (``"ex01_element"``, ...)."""
    return sorted(ANSWER_KEY)


def _full_name(exercise: str) -> str:
    if not isinstance(exercise, str):
        raise TypeError(f"exercise must be a str such as 'ex05', got {type(exercise).__name__}")
    names = [name for name in ANSWER_KEY if name == exercise or name.split("_")[0] == exercise]
    if len(names) != 1:
        raise ValueError(f"exercise must be one of {exercises()} (or their ex01-style prefix), "
                         f"got {exercise!r}")
    return names[0]


def tolerances(exercise: str) -> dict[str, Tolerance]:
    """The stated tolerance of every expected answer of ``exercise`` (``"ex05"`` or its full name).

    Examples
    --------
    >>> tolerances("ex05")["tau_hand_ms"].describe()
    '±4 %'
    """
    key = ANSWER_KEY[_full_name(exercise)]
    return {name: Tolerance(a["kind"], a["width"], a["reason"]) for name, a in key.items()}


def _huge(value) -> str:
    """A number beyond the floats, named by its size (not by a truncated repr)."""
    try:
        digits = math.floor(math.log10(abs(value))) + 1
    except (TypeError, ValueError, OverflowError):
        return f"a {type(value).__name__} beyond the range of a float (above 1.8e308)"
    return f"a number of {digits} digits, beyond the range of a float (above 1.8e308)"


def _as_float(value) -> float | str:
    """The value as a float, or why it is not a number to check (the same on NumPy 1 and 2).

    A Python or NumPy real number and a 0-d array are numbers; an array with a dimension is not,
    even of one element (NumPy 2 no longer converts those): the message says to pick the element.
    """
    if isinstance(value, (str, bytes, bool)) or str(getattr(value, "dtype", "")) == "bool":
        return f"{value!r:.40} is not a number"
    shape = getattr(value, "shape", ())
    if shape != () and hasattr(value, "ndim"):
        return (f"an array of shape {tuple(shape)} is not a number: give one element "
                "(value[0] or value.item())")
    try:
        number = float(value)
    except OverflowError:  # an int or a Fraction beyond the largest float
        return _huge(value)
    except (TypeError, ValueError):
        return f"{value!r:.40} is not a number"
    if isinstance(number, float) and math.isinf(number):
        try:  # a Decimal or a long double beyond the floats converts to inf without an error
            finite = not (value * 2 == value)
        except Exception:  # noqa: BLE001 - any type: then it is taken as the inf it gave
            finite = False
        if finite:
            return _huge(value)
    if not math.isfinite(number):
        return f"{number} is not a finite number"
    return number


def _verdict(name: str, value, sealed: dict, tolerance: Tolerance) -> tuple[str, bool]:
    stated = tolerance.describe()
    stated = "equal to" if stated == "exact" else f"within {stated} of"
    stated += " the expected value"
    if value is None:
        return f"{name}: not yet: no value given (None)", False
    number = _as_float(value)
    if isinstance(number, str):
        return f"{name}: not yet: {number}", False
    if _within(sealed, tolerance, number):
        return f"{name}: {stated}", True
    return f"{name}: not yet: not {stated}", False


def check(exercise: str, *, student: str | None = None, key=None, **values) -> CheckReport:
    """Whether each value is within the stated tolerance of the exercise's expected answer.

    The answers themselves are not shown: a value is either within the tolerance or "not yet".

    Parameters
    ----------
    exercise : str
        ``"ex05"`` or ``"ex05_decay"``.
    student, key : str and path, optional
        For a graded variant: the student's id and the variant key the teacher handed out
        (``docs/_tools/make_variant_key.py`` writes it). Both or neither.
    **values : float or None
        The answers to check, by the names the exercise page gives (``tau_fit_ms=80.1``); ``None``
        for one not computed yet. A Python or NumPy real number or a 0-d array is a number; an
        array with a dimension is not, even of one element (the same verdict on every supported
        NumPy: NumPy 2 no longer converts those): the line says to give ``value[0]``. A number
        beyond the floats (``10**400``) is named by its size.

    Returns
    -------
    CheckReport
        One line per value; ``report.ok`` is True when all of them are within tolerance.

    Examples
    --------
    >>> report = check("ex01", M11=156, M14=-12)
    >>> print(report)
    M11: within ±1e-06 of the expected value
    M14: not yet: not within ±1e-06 of the expected value
    >>> report.ok
    False
    """
    name = _full_name(exercise)
    sealed, stated = ANSWER_KEY[name], tolerances(name)
    if (student is None) != (key is None):
        raise ValueError("student and key go together: give both for a graded variant, or "
                         "neither for the published exercise")
    if key is not None:
        variants = _checked_key(key) if isinstance(key, dict) else load_variant_key(key)
        if variants.get("exercise") != name:
            raise ValueError(f"key is a key of {variants.get('exercise')!r}, not of {name!r}")
        tag = student_tag(variants["salt"], student) if isinstance(student, str) else None
        if tag not in variants["students"]:
            raise ValueError(f"student {student!r} is not in this key: ask the teacher for the "
                             "key of your group")
        sealed = variants["students"][tag]
    unknown = sorted(set(values) - set(sealed))
    if unknown or not values:
        raise ValueError(f"the values of {name} are named {sorted(sealed)}, got {sorted(values)}")
    verdicts = [_verdict(v, values[v], sealed[v], stated[v]) for v in values]
    return CheckReport(name, tuple(v[0] for v in verdicts), tuple(v[1] for v in verdicts))
