"""Self-checks for the exercises: is a student's value within the stated tolerance?

Every exercise of the documentation states what to compute, the data to compute it from (with its
seed) and, for each expected answer, a tolerance with its reason: how far two legitimate ways of
working may differ. :func:`check` tells whether a value is within that tolerance of the answer of
the worked solution, without printing the answer::

    >>> from ebantenna.course import check
    >>> print(check("ex05", tau_fit_ms=None))
    tau_fit_ms: not yet: no value given (None)

The package does not hold the answers in readable form. Each one is *sealed* (:func:`seal`): the
answer is written as a coordinate ``u`` in units of its tolerance (``value / width`` for an
absolute tolerance, ``log|value| / log-width`` for a relative one or a factor); the key keeps the
salted, iterated hash of the cell ``floor(u)`` and the position ``u - floor(u)`` inside the cell,
which alone says nothing of the value. A value is checked by hashing its own cell and the cells
next to it: a match gives back the answer, and the stated tolerance decides, exactly as if the
answer were stored (so a right value near a cell's edge passes, and the tolerance's edges are
where they were).

What this does not prevent, and the installation page tells teachers: :func:`check` answers
"within" or "not yet", so a search over it (or over the cells) finds a value within the
tolerance, which for a small count takes a few tries; and the worked solutions are in the public
repository. The check is a help for learning, not a grader.

**Graded variants.** For graded work a teacher gives each student their own data:
:func:`parameters` draws an exercise's parameters from a student's id (the same id, the same
parameters, on any machine), the exercise's data block reads them, and
``docs/_tools/make_variant_key.py`` (in the repository, for the teacher) runs the worked solution
for every student of a list and writes the teacher's answer sheet and a sealed key for the
students' self-checks, ``check(..., student=id, key=path)``. A student's answer is then of no
use to another student, and the published answers are of no use to anyone.

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
    "Tolerance", "CheckReport", "exercises", "tolerances", "check", "seal", "unseal", "VARIANTS",
    "parameters", "load_variant_key",
]

#: rounds of PBKDF2-HMAC-SHA256 per sealed cell: about a millisecond, so a check of a value (up to
#: five cells) stays instant while a search over many cells is slowed by the same factor
ROUNDS = 1000

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


def _scale(tolerance: Tolerance) -> tuple[str, float]:
    """The coordinate a tolerance is measured in, and the width of one cell of it.

    ``"lin"``: ``u = value / cell``, with ``cell = width`` (an exact answer: cells of 1, the
    answer's position in its cell kept); ``"log"``: ``u = log|value| / cell``, with ``cell`` the
    widest log-distance the tolerance accepts, ``-log(1 - width)`` for a relative one and
    ``log(width)`` for a factor. Either way every accepted value is within one cell of the answer.
    """
    if tolerance.kind == "abs":
        return "lin", tolerance.width if tolerance.width > 0 else 1.0
    if tolerance.kind == "rel":
        if not 0 < tolerance.width < 1:
            raise ValueError(f"a relative tolerance to seal must be in (0, 1), got "
                             f"{tolerance.width!r}")
        return "log", -math.log1p(-tolerance.width)
    if tolerance.width <= 1:
        raise ValueError(f"a factor tolerance to seal must be > 1, got {tolerance.width!r}")
    return "log", math.log(tolerance.width)


def _coordinate(scale: str, cell: float, value: float) -> tuple[str, float]:
    """``(sign, u)``: the value in cells of its tolerance (the sign kept apart on a log scale)."""
    if scale == "lin":
        return "", value / cell
    return ("+" if value > 0 else "-"), math.log(abs(value)) / cell


def _digest(salt: str, sign: str, cell_index: int) -> str:
    text = f"{sign}{cell_index}".encode()
    return hashlib.pbkdf2_hmac("sha256", text, salt.encode(), ROUNDS).hex()[:32]


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
    """The answer ``value`` in the form the key holds: a cell's hash and a place in the cell.

    Parameters
    ----------
    value : float
        The expected answer (finite; not zero when the tolerance is relative or a factor).
    tolerance : Tolerance
        Its tolerance: it sets the cells (see the module's description).
    salt : str
        Text hashed with the cell, different for every answer (``"ex05_decay/tau_fit_ms"``), so
        that two answers in the same cell do not show it.

    Returns
    -------
    dict
        ``{"salt", "digest", "offset"}``: :func:`unseal` gives the value back from any value
        within one cell of it, and nothing without one.
    """
    if not isinstance(tolerance, Tolerance):
        raise TypeError(f"tolerance must be a Tolerance, got {type(tolerance).__name__}")
    if not isinstance(salt, str) or not salt:
        raise ValueError(f"salt must be a non-empty str, got {salt!r}")
    value = _finite("value", value)
    scale, cell = _scale(tolerance)
    if scale == "log" and value == 0:
        raise ValueError("value must not be zero for a relative or factor tolerance")
    sign, u = _coordinate(scale, cell, value)
    if not math.isfinite(u):
        raise ValueError(f"value must be within the range of floats in cells of the tolerance, "
                         f"got {value!r} in cells of {cell!r}")
    index = math.floor(u)
    return {"salt": salt, "digest": _digest(salt, sign, index), "offset": u - index}


def unseal(sealed: dict, tolerance: Tolerance, near: float) -> float | None:
    """The sealed answer, if ``near`` is within two cells of it; else ``None``.

    ``near`` must be a finite number. Two cells cover every value the tolerance accepts (one
    cell) with room for rounding at the edge; the tolerance then decides. ``sealed`` is what
    :func:`seal` returned.
    """
    if not (isinstance(sealed, dict) and isinstance(sealed.get("salt"), str)
            and isinstance(sealed.get("digest"), str)
            and isinstance(sealed.get("offset"), float | int)):
        raise ValueError(f"sealed must be a dict from seal() with 'salt', 'digest' and 'offset', "
                         f"got {sealed!r:.80}")
    if not isinstance(tolerance, Tolerance):
        raise TypeError(f"tolerance must be a Tolerance, got {type(tolerance).__name__}")
    near = _finite("near", near)
    scale, cell = _scale(tolerance)
    if scale == "log" and near == 0:
        return None  # no relative tolerance or factor accepts a zero
    sign, u = _coordinate(scale, cell, near)
    if not math.isfinite(u):  # far beyond any answer (1e308 in cells of 1e-6)
        return None
    start = math.floor(u)
    for index in (start, start - 1, start + 1, start - 2, start + 2):
        if _digest(sealed["salt"], sign, index) == sealed["digest"]:
            u = index + sealed["offset"]
            if scale == "lin":
                return u * cell
            return (1.0 if sign == "+" else -1.0) * math.exp(u * cell)
    return None


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


def load_variant_key(path) -> dict:
    """Read a variant key written by ``docs/_tools/make_variant_key.py`` (a JSON file).

    Returns ``{"exercise": name, "students": {id: {value name: sealed answer}}}``; raises
    ValueError if the file is not such a key.
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
    if not (isinstance(key, dict) and isinstance(key.get("students"), dict)
            and key.get("exercise") in ANSWER_KEY):
        raise ValueError(f"key must be a variant key file, {path!r} is not one")
    return key


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


def _verdict(name: str, value, sealed: dict, tolerance: Tolerance) -> tuple[str, bool]:
    stated = tolerance.describe()
    stated = "equal to" if stated == "exact" else f"within {stated} of"
    stated += " the expected value"
    if value is None:
        return f"{name}: not yet: no value given (None)", False
    try:  # a NumPy scalar or a 0-d array is a number too; a string or a bool is not
        if isinstance(value, (str, bytes, bool)):
            raise TypeError(value)
        value = float(value)
    except OverflowError:  # an int or a Fraction beyond the largest float
        return f"{name}: not yet: {value!r:.20} is beyond the range of a float", False
    except (TypeError, ValueError):
        return f"{name}: not yet: {value!r} is not a number", False
    if not math.isfinite(value):
        return f"{name}: not yet: {value} is not a finite number", False
    expected = unseal(sealed, tolerance, value)
    if expected is not None and tolerance.accepts(value, expected):
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
        for one not computed yet.

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
        variants = key if isinstance(key, dict) else load_variant_key(key)
        if variants.get("exercise") != name:
            raise ValueError(f"key is a key of {variants.get('exercise')!r}, not of {name!r}")
        if not isinstance(student, str) or student.strip() not in variants["students"]:
            raise ValueError(f"student {student!r} is not in this key: ask the teacher for the "
                             "key of your group")
        sealed = variants["students"][student.strip()]
    unknown = sorted(set(values) - set(sealed))
    if unknown or not values:
        raise ValueError(f"the values of {name} are named {sorted(sealed)}, got {sorted(values)}")
    verdicts = [_verdict(v, values[v], sealed[v], stated[v]) for v in values]
    return CheckReport(name, tuple(v[0] for v in verdicts), tuple(v[1] for v in verdicts))
