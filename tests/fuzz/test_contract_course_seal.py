"""The input contract of the course's sealed answers and graded variants: :func:`seal`,
:func:`student_tag`, :func:`parameters` and :func:`load_variant_key`.

A bad input is refused with a ValueError or TypeError naming the parameter; a good one is
checked against a witness: a sealed answer accepts every value its tolerance accepts (and none
a cell beyond), a student's parameters lie in the ranges of :data:`VARIANTS`, a key file reads
back as written, and a key of the earlier format is refused.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from ebantenna.course import (
    KEY_FORMAT,
    VARIANTS,
    Tolerance,
    _within,
    load_variant_key,
    parameters,
    seal,
    student_tag,
)

REL = Tolerance("rel", 0.05, "two correct fits differ by a few percent")

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
TAG_BAD = [  # (id, key_salt, student, error, name)
    ("key-salt-none", None, "s1", TypeError, "key_salt"),
    ("student-int", "k", 5, TypeError, "student"),
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


@pytest.mark.parametrize("row", TAG_BAD, ids=[r[0] for r in TAG_BAD])
def test_student_tag_refuses_bad_input(row):
    _, key_salt, student, error, name = row
    with pytest.raises(error, match=name):
        student_tag(key_salt, student)


def test_student_tag_hides_the_id():
    tag = student_tag("k", "alice")
    assert "alice" not in tag and tag == student_tag("k", " alice ")
    assert tag != student_tag("other key", "alice")


@pytest.mark.parametrize("value", [3.0, -0.0123, 4.5e7])
def test_a_sealed_answer_accepts_its_tolerance_only(value):
    sealed = seal(value, REL, "ex/v")
    assert set(sealed) == {"salt", "kdf", "cells"}  # no value, no place in a cell
    for near in (value, value * 1.049, value * 0.951):  # accepted by the tolerance
        assert _within(sealed, REL, near)
    # a cell is a fifth of the tolerance: beyond 1.2 tolerances, refused
    for far in (value * 1.3, value * (1 - 0.05 * 1.25), -value, 0.0):
        assert not _within(sealed, REL, far)


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
    tag = student_tag("k", "s1")
    key = {"format": KEY_FORMAT, "exercise": "ex05_decay", "salt": "k",
           "students": {tag: {"tau_fit_ms": seal(81.0, REL, f"ex05_decay/{tag}/tau_fit_ms")}}}
    path = tmp_path / "key.json"
    path.write_text(json.dumps(key), encoding="utf-8")
    back = load_variant_key(str(path))
    assert back == key
    assert _within(back["students"][tag]["tau_fit_ms"], REL, np.float64(80.0))


def test_load_variant_key_refuses_a_key_of_the_earlier_format(tmp_path):
    # the earlier keys kept each answer's place in its cell, and the ids in plain text
    old = {"exercise": "ex05_decay", "students": {"s1": {"tau_fit_ms": {
        "salt": "ex05_decay/s1/tau_fit_ms", "digest": "0" * 32, "offset": 0.25}}}}
    path = tmp_path / "key.json"
    path.write_text(json.dumps(old), encoding="utf-8")
    with pytest.raises(ValueError, match="written by an earlier ebantenna"):
        load_variant_key(path)


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    return {
        "ebantenna.course.seal": [r[0] for r in SEAL_BAD] + ["accepts-its-tolerance-only"],
        "ebantenna.course.student_tag": [r[0] for r in TAG_BAD] + ["hides-the-id"],
        "ebantenna.course.parameters": [r[0] for r in PARAMETERS_BAD] + ["in-variant-ranges"],
        "ebantenna.course.load_variant_key": ["path-int", "path-none", "path-bytes",
                                              "path-empty", "not-json", "a-list", "no-students",
                                              "unknown-exercise", "reads-back",
                                              "earlier-format"],
    }
