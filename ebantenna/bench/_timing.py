"""Timing shared by the sweeps (private)."""

from __future__ import annotations

import functools
import time
from contextlib import contextmanager

__all__ = ["best_time", "best_times", "clocked"]


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


def best_times(fns, repeat: int, clock=time.perf_counter):
    """Call each of ``fns`` once per round, ``repeat`` rounds; return, for each, the shortest
    time (s) and its last result.

    The cases alternate, so that a change of the machine's load during the run reaches all of
    them alike and the ratios between them stay comparable, where timing every repeat of one
    case before the next would put the load on one case only.

    Examples
    --------
    >>> [(t >= 0, out) for t, out in best_times([lambda: 1, lambda: 2], 3)]
    [(True, 1), (True, 2)]
    """
    best, out = [float("inf")] * len(fns), [None] * len(fns)
    for _ in range(repeat):
        for i, fn in enumerate(fns):
            start = clock()
            out[i] = fn()
            best[i] = min(best[i], clock() - start)
    return list(zip(best, out, strict=True))


@contextmanager
def clocked(owner, name: str, totals: dict, count=None):
    """While inside, add the wall time (s) of every call of ``owner.name`` (``owner[name]`` for
    a dict, such as an engine registry) to ``totals[name]`` (and ``count(result)`` to
    ``totals[name + ' count']``); the attribute is restored on exit, also when a call raises.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> owner, totals = SimpleNamespace(double=lambda x: 2 * x), {}
    >>> with clocked(owner, "double", totals, count=lambda out: out):
    ...     owner.double(3), owner.double(4)
    (6, 8)
    >>> totals["double count"], totals["double"] >= 0
    (14, True)
    """
    if isinstance(owner, dict):
        get, put = owner.__getitem__, owner.__setitem__
    else:
        get, put = functools.partial(getattr, owner), functools.partial(setattr, owner)
    inner = get(name)

    def timed(*args, **kwargs):
        start = time.perf_counter()
        out = inner(*args, **kwargs)
        totals[name] = totals.get(name, 0.0) + time.perf_counter() - start
        if count is not None:
            totals[name + " count"] = totals.get(name + " count", 0) + count(out)
        return out

    put(name, timed)
    try:
        yield totals
    finally:
        put(name, inner)
