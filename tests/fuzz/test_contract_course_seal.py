"""The input contract of the course's sealed answers and graded variants: :func:`seal`,
:func:`unseal`, :func:`parameters` and :func:`load_variant_key`.

A bad input is refused with a ValueError or TypeError naming the parameter; a good one is
checked against a witness: a sealed value comes back from any value the tolerance accepts (and
not from one it refuses), a student's parameters lie in the ranges of :data:`VARIANTS`, a key
file reads back as written.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from ebantenna.course import VARIANTS, Tolerance, load_variant_key, parameters, seal, unseal

REL = Tolerance("rel", 0.05, "two correct fits differ by a few percent")
SEALED = seal(3.0, REL, "ex/x")

SEAL_BAD = [  # (id, value, tolerance, salt, error, name)
    ("value-text", "3", REL, "s", TypeError, "value"),
    ("value-none", None, REL, "s", TypeError, "value"),
    ("value-nan", math.nan, REL, "s", ValueError, "value"),
    ("value-beyond-floats", 10**400, REL, "s", ValueError, "value"),
    ("value-bool", True, REL, "s", TypeError, "value"),
    ("tolerance-text", 3.0, "rel", "s", TypeError, "tolerance"),
    ("salt-empty", 3.0, REL, "", ValueError, "salt"),
    ("salt-int", 3.0, REL, 3, ValueError, "salt"),
]
UNSEAL_BAD = [  # (id, sealed, tolerance, near, error, name)
    ("sealed-text", "abc", REL, 3.0, ValueError, "sealed"),
    ("sealed-empty", {}, REL, 3.0, ValueError, "sealed"),
    ("sealed-offset-text", {**SEALED, "offset": "0.5"}, REL, 3.0, ValueError, "sealed"),
    ("tolerance-text", SEALED, "rel", 3.0, TypeError, "tolerance"),
    ("near-text", SEALED, REL, "3", TypeError, "near"),
    ("near-none", SEALED, REL, None, TypeError, "near"),
    ("near-inf", SEALED, REL, math.inf, ValueError, "near"),
]
PARAMETERS_BAD = [  # (id, exercise, student, error, name)
    ("exercise-int", 5, None, TypeError, "exercise"),
    ("exercise-without-variants", "ex01", None, ValueError, "exercise"),
    ("student-int", "ex05", 5, ValueError, "student"),
    ("student-blank", "ex05", "  ", ValueError, "student"),
]


@pytest.mark.parametrize("row", SEAL_BAD, ids=[r[0] for r in SEAL_BAD])
def test_seal_refuses_bad_input(row):
    _, value, tolerance, salt, error, name = row
    with pytest.raises(error, match=name):
        seal(value, tolerance, salt)


@pytest.mark.parametrize("row", UNSEAL_BAD, ids=[r[0] for r in UNSEAL_BAD])
def test_unseal_refuses_bad_input(row):
    _, sealed, tolerance, near, error, name = row
    with pytest.raises(error, match=name):
        unseal(sealed, tolerance, near)


@pytest.mark.parametrize("value", [3.0, -0.0123, 4.5e7])
def test_a_sealed_value_comes_back_from_within_its_tolerance_only(value):
    sealed = seal(value, REL, "ex/v")
    for near in (value, value * 1.049, value * 0.951):  # accepted by the tolerance
        assert unseal(sealed, REL, near) == pytest.approx(value, rel=1e-12)  # exp(log): ulps
    assert unseal(sealed, REL, value * 1.3) is None  # six cells away
    assert unseal(sealed, REL, -value) is None  # the sign is part of the seal


@pytest.mark.parametrize("row", PARAMETERS_BAD, ids=[r[0] for r in PARAMETERS_BAD])
def test_parameters_refuse_bad_input(row):
    _, exercise, student, error, name = row
    with pytest.raises(error, match=name):
        parameters(exercise, student)


@pytest.mark.parametrize("exercise", sorted(VARIANTS))
def test_a_students_parameters_lie_in_the_variant_ranges(exercise):
    published = parameters(exercise)
    assert published == {k: v[0] for k, v in VARIANTS[exercise].items()}
    for student in ("s1", "another student"):
        drawn = parameters(exercise, student)
        assert drawn == parameters(exercise, f"  {student} ")  # the id, stripped
        for key, (_, low, high, decimals) in VARIANTS[exercise].items():
            # rounding to ``decimals`` may reach the range's end, never beyond it
            assert low <= drawn[key] <= high, (key, drawn[key])
            assert isinstance(drawn[key], int if decimals is None else float)


@pytest.mark.parametrize(("row", "path", "error"), [
    ("path-int", 5, TypeError), ("path-none", None, TypeError),
    ("path-bytes", b"key.json", TypeError), ("path-empty", "", ValueError),
])
def test_load_variant_key_refuses_a_bad_path(row, path, error):
    with pytest.raises(error, match="path"):
        load_variant_key(path)


@pytest.mark.parametrize(("row", "text"), [
    ("not-json", "{"), ("a-list", "[]"), ("no-students", '{"exercise": "ex05_decay"}'),
    ("unknown-exercise", '{"exercise": "ex99", "students": {}}'),
])
def test_load_variant_key_refuses_a_file_that_is_no_key(tmp_path, row, text):
    path = tmp_path / "key.json"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(ValueError, match="key must be a variant key file"):
        load_variant_key(path)


def test_load_variant_key_reads_back_what_was_written(tmp_path):
    key = {"exercise": "ex05_decay",
           "students": {"s1": {"tau_fit_ms": seal(81.0, REL, "ex05_decay/s1/tau_fit_ms")}}}
    path = tmp_path / "key.json"
    path.write_text(json.dumps(key), encoding="utf-8")
    back = load_variant_key(str(path))
    assert back == key
    assert unseal(back["students"]["s1"]["tau_fit_ms"], REL, np.float64(80.0)) == pytest.approx(
        81.0, rel=1e-12)


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    return {
        "ebantenna.course.seal": [r[0] for r in SEAL_BAD] + ["back-from-within-tolerance"],
        "ebantenna.course.unseal": [r[0] for r in UNSEAL_BAD] + ["back-from-within-tolerance"],
        "ebantenna.course.parameters": [r[0] for r in PARAMETERS_BAD] + ["in-variant-ranges"],
        "ebantenna.course.load_variant_key": ["path-int", "path-none", "path-bytes",
                                              "path-empty", "not-json", "a-list", "no-students",
                                              "unknown-exercise", "reads-back"],
    }
