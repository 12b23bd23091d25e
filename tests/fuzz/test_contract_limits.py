"""The memory budget reads the process's own limits: ``RLIMIT_AS`` and cgroup v2 ``memory.max``.

A process started under ``ulimit -v`` (or in a container whose cgroup caps its memory) was given
a budget from the machine's available memory, so that a request the budget allowed ended in a
bare ``MemoryError`` from the limit. The budget is now half of the least of the three.
"""

from __future__ import annotations

import os
import sys
import textwrap

import pytest
from unloaded_time import run

from ebantenna import _budget

GIB = 2**30


def test_a_cgroup_memory_max_lowers_the_budget(tmp_path, monkeypatch):
    (tmp_path / "memory.max").write_text(f"{GIB}\n")
    (tmp_path / "memory.current").write_text(f"{GIB // 4}\n")
    real = _budget._cgroup_left
    monkeypatch.setattr(_budget, "_cgroup_left", lambda: real(str(tmp_path)))
    monkeypatch.setattr(_budget, "_available_bytes", lambda: 64 * GIB)
    monkeypatch.setattr(_budget, "_address_space_left", lambda: None)
    monkeypatch.delenv("EBANTENNA_MEMORY_BUDGET", raising=False)
    if real(str(tmp_path)) is None:
        pytest.skip("this process is in no cgroup v2 group ('0::' missing)")
    # half of what the group leaves: (1 GiB - 1/4 GiB) / 2
    assert _budget.memory_budget() == int(0.5 * (GIB - GIB // 4))


def test_an_unlimited_cgroup_leaves_the_available_memory(tmp_path, monkeypatch):
    (tmp_path / "memory.max").write_text("max\n")
    assert _budget._cgroup_left(str(tmp_path)) is None


def test_rlimit_as_lowers_the_budget_and_a_request_over_it_is_refused_by_name():
    """In a child under a 3 GiB address-space limit: 1.5 GiB is refused by the budget, by name,
    instead of the bare MemoryError the limit would give."""
    code = textwrap.dedent(f"""
        import resource
        resource.setrlimit(resource.RLIMIT_AS, ({3 * GIB}, resource.RLIM_INFINITY))
        from ebantenna import _budget
        budget = _budget.memory_budget()
        assert budget <= {3 * GIB} // 2, budget
        try:
            _budget.check_allocation({3 * GIB // 2}, parameter="n_points", what="the grid")
        except _budget.MemoryBudgetError as exc:
            assert "n_points" in str(exc), exc
            print("refused")
    """)
    env = {k: v for k, v in os.environ.items() if k != "EBANTENNA_MEMORY_BUDGET"}
    # an import and one refused allocation: 60 s of the child's own time (waits for a CPU left
    # out) is a hang
    out = run([sys.executable, "-c", code], 60, capture_output=True, text=True, env=env)
    assert out.returncode == 0 and out.stdout.strip() == "refused", out.stderr[-2000:]
