"""The memory budget's floor: small requests under the default budget skip the system's state."""

from __future__ import annotations

import pytest

from ebantenna import _budget


def _no_reading():
    raise AssertionError("the system's memory was read for a request under the floor")


def test_a_request_under_the_floor_reads_nothing(monkeypatch):
    monkeypatch.delenv("EBANTENNA_MEMORY_BUDGET", raising=False)
    monkeypatch.setattr(_budget, "_process_available", _no_reading)
    _budget.check_allocation(_budget.UNCHECKED_BYTES, parameter="n", what="a small array")
    with pytest.raises(AssertionError, match="was read"):  # one byte more is checked
        _budget.check_allocation(_budget.UNCHECKED_BYTES + 1, parameter="n", what="an array")


def test_a_budget_the_user_sets_is_checked_at_every_size(monkeypatch):
    monkeypatch.delenv("EBANTENNA_MEMORY_BUDGET", raising=False)
    _budget.set_memory_budget(100)
    try:
        with pytest.raises(_budget.MemoryBudgetError, match="n_points"):
            _budget.check_allocation(101, parameter="n_points", what="the grid")
    finally:
        _budget.set_memory_budget(None)
    monkeypatch.setenv("EBANTENNA_MEMORY_BUDGET", "100")
    with pytest.raises(_budget.MemoryBudgetError, match="n_points"):
        _budget.check_allocation(101, parameter="n_points", what="the grid")


def test_a_negative_or_nan_size_is_refused_under_the_floor_too():
    for bad in (-1, float("nan")):
        with pytest.raises(ValueError, match="not a size in bytes"):
            _budget.check_allocation(bad, parameter="n", what="an array")
