"""Timing shared by the sweeps (private)."""

from __future__ import annotations

import time

__all__ = ["best_time"]


def best_time(fn, repeat: int, clock=time.perf_counter):
    """Call ``fn`` ``repeat`` times; return the shortest time (s) and the last result.

    ``clock`` is wall time by default; :func:`time.process_time` measures CPU seconds instead.
    """
    best, out = float("inf"), None
    for _ in range(repeat):
        start = clock()
        out = fn()
        best = min(best, clock() - start)
    return best, out
