"""Contract rows for the course's self-check, :func:`ebantenna.course.check`.

A value no answer can be (a number beyond the float range, NaN) must end in a clear error naming
the value's name, or in a report that does not pass it and names it; a tiny non-zero number must
not pass where the expected answer is exactly zero.
"""

from __future__ import annotations

import math

import pytest

from ebantenna.course import check

#: ``(exercise, name, value)``: bad answers that must not pass.
BAD = [
    ("ex05", "tau_fit_ms", 10**400),
    ("ex05", "tau_fit_ms", -(10**400)),
    ("ex05", "tau_fit_ms", math.nan),
    ("ex05", "tau_fit_ms", math.inf),
    ("ex12", "seen_grouped", math.nan),
    ("ex12", "seen_grouped", 1e-323),
]
#: The rows the self-check of this tree does not keep yet (it is being rewritten).
OPEN = {("ex05", "tau_fit_ms", 10**400), ("ex05", "tau_fit_ms", -(10**400)),
        ("ex12", "seen_grouped", 1e-323)}


def _rows():
    for row in BAD:
        marks = [pytest.mark.xfail(strict=True, reason="the self-check does not keep this row "
                                   "yet: 10**400 overflows, 1e-323 passes as zero")] \
            if row in OPEN else []
        yield pytest.param(*row, marks=marks, id=f"{row[0]}-{row[1]}-{row[2]!r:.12}")


@pytest.mark.parametrize(("exercise", "name", "value"), list(_rows()))
def test_a_bad_answer_never_passes_and_is_named(exercise, name, value):
    try:
        report = check(exercise, **{name: value})
    except (ValueError, TypeError) as exc:
        assert name in str(exc), exc
        return
    assert not report.ok and name in str(report), str(report)


def contract_rows() -> dict[str, list[str]]:
    """The surface these rows cover (read by the inventory test)."""
    return {"ebantenna.course.check": [f"{e}-{n}-{v!r:.12}" for e, n, v in BAD]}
