"""Contract rows for the course's self-check, :func:`ebantenna.course.check`.

A value no answer can be (a number beyond the float range, NaN) must end in a clear error naming
the value's name, or in a report that does not pass it and names it; a tiny non-zero number must
not pass where the expected answer is exactly zero.
"""

from __future__ import annotations

import math
from fractions import Fraction

import pytest

from ebantenna.course import check

#: ``(exercise, name, value)``: bad answers that must not pass.
BAD = [
    ("ex05", "tau_fit_ms", 10**400),
    ("ex05", "tau_fit_ms", -(10**400)),
    ("ex05", "tau_fit_ms", math.nan),
    ("ex05", "tau_fit_ms", math.inf),
    ("ex12", "seen_grouped", math.nan),
    ("ex05", "tau_fit_ms", Fraction(10**400, 3)),
    ("ex12", "seen_grouped", 1e-323),
    ("ex12", "seen_grouped", 5e-324),
    ("ex12", "seen_grouped", -1e-310),
]


def _rows():
    for row in BAD:
        yield pytest.param(*row, id=f"{row[0]}-{row[1]}-{row[2]!r:.12}")


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


def test_exact_accepts_rounding_of_a_non_zero_answer_and_nothing_beside_zero():
    from ebantenna.course import Tolerance

    exact = Tolerance("abs", 0, "a share of whole recordings")
    # a share reached by another order of operations: a few ulps of the answer
    assert exact.accepts(0.1 + 0.2, 0.3) and exact.accepts(sum([0.1] * 10), 1.0)
    # zero has no rounding: the smallest subnormal is already another answer
    assert exact.accepts(0.0, 0.0) and exact.accepts(-0.0, 0.0)
    assert not exact.accepts(5e-324, 0.0) and not exact.accepts(-1e-310, 0.0)
