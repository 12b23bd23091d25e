"""Timing shared by the sweeps (private)."""

from __future__ import annotations

import time

__all__ = ["best_time"]


def best_time(fn, repeat: int):
    """Call ``fn`` ``repeat`` times; return the shortest wall time (s) and the last result."""
    best, out = float("inf"), None
    for _ in range(repeat):
        start = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - start)
    return best, out
