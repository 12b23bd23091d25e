"""The input contract of the period bracket's widening (a sample clock outside its tolerance).

Each row gives one bad input (refused with a ValueError or TypeError naming the parameter) or a
good one whose bracket is checked against the observations' own bracket, recomputed here by
hand from the pair rule of :class:`~ebantenna.device.timing.PeriodEstimator`.
"""

from __future__ import annotations

import math

import pytest

from ebantenna.device.timing import PeriodEstimator


def _slow_segment():
    """One segment of a clock 10 % slow (period 1/0.9 ms): 0 samples at the enable (0 to 0.3 ms),
    then 90 samples counted between 100.05 and 100.10 ms, outside a 5 % tolerance."""
    est = PeriodEstimator(1e-3, 0.05)
    est.begin(before=0.0, after=3e-4)
    return est


@pytest.mark.parametrize(("row", "low", "high", "error", "name"), [
    ("low-zero", 0.0, 1e-3, ValueError, "low"),
    ("low-negative", -1e-3, 1e-3, ValueError, "low"),
    ("low-nan", math.nan, 1e-3, ValueError, "low"),
    ("low-inf", math.inf, math.inf, ValueError, "low"),
    ("low-text", "1e-3", 1e-3, TypeError, "low"),
    ("high-below-low", 2e-3, 1e-3, ValueError, "high"),
    ("high-inf", 1e-3, math.inf, ValueError, "high"),
    ("high-none", 1e-3, None, TypeError, "high"),
])
def test_widen_refuses_a_bad_bracket(row, low, high, error, name):
    est = _slow_segment()
    with pytest.raises(error, match=name):
        est.widen(low, high)
    assert est.prior == (1e-3 / 1.05, 1e-3 / 0.95)  # nothing changed


def test_widen_lets_in_a_period_the_counts_show():
    est = _slow_segment()
    count = dict(produced=90, before=0.10005, after=0.10010)
    assert est.add(**count) is False  # 90 samples by 0.1 s: slower than 5 % allows
    # the pair (enable, count) alone: (before - 0.3 ms) / 91 <= T <= (after - 0) / 89
    low, high = (0.10005 - 3e-4) / 91, 0.10010 / 89
    assert 1e-3 / 0.9 > low and 1e-3 / 0.9 < high  # the true period lies in it
    est.widen(low, high)
    assert est.prior == (1e-3 / 1.05, high)  # the smallest bracket holding both
    assert est.add(**count) is True
    assert (est.low, est.high) == (low, high)
    assert est.low <= 1e-3 / 0.9 <= est.high


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    return {"PeriodEstimator.widen": ["low-zero", "low-negative", "low-nan", "low-inf",
                                      "low-text", "high-below-low", "high-inf", "high-none",
                                      "lets-in-the-counts"]}
