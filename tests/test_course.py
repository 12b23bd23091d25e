"""The students' self-check: within the stated tolerance or "not yet", never the answer."""

import math

import numpy as np
import pytest

from ebantenna.course import ANSWER_KEY, Tolerance, check, exercises, tolerances


def test_every_exercise_and_answer_has_a_tolerance_with_a_reason():
    assert exercises() == sorted(ANSWER_KEY) and len(exercises()) >= 13
    for exercise in exercises():
        for name, tol in tolerances(exercise).items():
            assert tol.kind in ("abs", "rel", "factor") and tol.reason.strip(), (exercise, name)


@pytest.mark.parametrize(
    ("tol", "expected", "inside", "outside", "words"),
    [
        (Tolerance("rel", 0.01, "r"), 80.0, 80.79, 80.81, "±1 %"),
        (Tolerance("abs", 0.05, "r"), 0.73, 0.779, 0.781, "±0.05"),
        (Tolerance("abs", 0, "r"), 56.0, 56.0, 57.0, "exact"),
        (Tolerance("factor", 10, "r"), 7.2e-5, 7.3e-6, 7.3e-4, "a factor 10"),
        (Tolerance("rel", 1e-9, "r"), 23.0, 23.0 + 2e-8, 23.0 + 3e-8, "±1e-09 relative"),
    ],
)
def test_tolerance_kinds(tol, expected, inside, outside, words):
    assert tol.describe() == words
    assert tol.accepts(inside, expected) and tol.accepts(expected, expected)
    assert not tol.accepts(outside, expected)


def test_exact_accepts_the_float_of_an_integer_answer():
    assert Tolerance("abs", 0, "a count").accepts(float(np.int64(1024)), 1024.0)


def test_a_factor_never_accepts_the_other_sign_or_zero():
    tol = Tolerance("factor", 10, "r")
    assert not tol.accepts(-7.2e-5, 7.2e-5) and not tol.accepts(0.0, 7.2e-5)


@pytest.mark.parametrize(
    ("kind", "width"), [("near", 1.0), ("rel", -0.1), ("rel", math.nan), ("factor", 0.5)]
)
def test_bad_tolerances_are_refused(kind, width):
    with pytest.raises(ValueError, match="kind|width|factor"):
        Tolerance(kind, width, "r")


def test_messages_name_the_value_and_the_tolerance_not_the_answer():
    report = check("ex05", tau_hand_ms=80.9, tau_fit_ms=70.0, a_fit=None)
    assert report.lines == (
        "tau_hand_ms: within ±1 % of the expected value",
        "tau_fit_ms: not yet: not within ±0.1 % of the expected value",
        "a_fit: not yet: no value given (None)",
    )
    assert report.passed == (True, False, False) and not report.ok
    assert str(report) == "\n".join(report.lines)
    assert "80.29" not in str(report)  # the answer (80.29 ms) is not printed


def test_numpy_values_and_non_numbers():
    assert check("ex01_element", M11=np.float64(156.0), M14=np.array(-13)).ok
    report = check("ex01", M11="156", M14=math.inf)
    assert report.lines == ("M11: not yet: '156' is not a number",
                            "M14: not yet: inf is not a finite number")


@pytest.mark.parametrize(
    ("exercise", "values", "message"),
    [
        ("ex99", {"x": 1.0}, "exercise must be one of"),
        ("ex05", {"tau": 80.0}, "named"),
        ("ex05", {}, "named"),
    ],
)
def test_unknown_exercise_or_name_is_refused(exercise, values, message):
    with pytest.raises(ValueError, match=message):
        check(exercise, **values)


def test_exercise_must_be_a_string():
    with pytest.raises(TypeError, match="exercise must be a str"):
        check(5, tau_fit_ms=80.0)
