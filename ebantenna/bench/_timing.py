"""Timing shared by the sweeps (private)."""

from __future__ import annotations

import functools
import time
from contextlib import contextmanager

import numpy as np

__all__ = ["best_time", "best_times", "timed_rounds", "blas_threads", "forget_probe_reductions",
           "clocked"]


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


def best_times(fns, repeat: int, clock=time.perf_counter, before=None):
    """Call each of ``fns`` once per round, ``repeat`` rounds; return, for each, the shortest
    time (s) and its last result.

    The cases alternate, so that a change of the machine's load during the run reaches all of
    them alike and the ratios between them stay comparable, where timing every repeat of one
    case before the next would put the load on one case only. ``before``, if given, is called
    (not timed) before every call (:func:`timed_rounds`).

    Examples
    --------
    >>> [(t >= 0, out) for t, out in best_times([lambda: 1, lambda: 2], 3)]
    [(True, 1), (True, 2)]
    """
    return [(r["min"], r["result"]) for r in timed_rounds(fns, repeat, clock, before)]


def timed_rounds(fns, repeat: int, clock=time.perf_counter, before=None) -> list[dict]:
    """Call each of ``fns`` once per round, ``repeat`` rounds, the cases alternating as in
    :func:`best_times`; ``before()``, if given, runs before every call and is not timed (it
    empties a cache, say, so that every call pays for what the first would).

    Returns, for each of ``fns``, a dict: ``times`` (s, one per round), ``min``, ``median`` and
    ``result`` (of the last call).

    Examples
    --------
    >>> ticks = iter(range(100))
    >>> rounds = timed_rounds([lambda: "a", lambda: "b"], 2, clock=lambda: next(ticks) ** 2)
    >>> [(r["times"], r["min"], r["median"], r["result"]) for r in rounds]
    [([1, 9], 1, 5.0, 'a'), ([5, 13], 5, 9.0, 'b')]
    """
    times: list[list[float]] = [[] for _ in fns]
    out: list = [None] * len(fns)
    for _ in range(repeat):
        for i, fn in enumerate(fns):
            if before is not None:
                before()
            start = clock()
            out[i] = fn()
            times[i].append(clock() - start)
    return [{"times": t, "min": min(t) if t else float("inf"),
             "median": float(np.median(t)) if t else float("inf"), "result": r}
            for t, r in zip(times, out, strict=True)]


def blas_threads() -> int:
    """The most threads any BLAS library loaded in this process runs on now (what a sweep
    reports beside its times: inside ``limited_threads(1)``, 1).

    Examples
    --------
    >>> from ebantenna._threads import limited_threads
    >>> with limited_threads(1):
    ...     blas_threads()
    1
    """
    from threadpoolctl import threadpool_info

    counts = [lib["num_threads"] for lib in threadpool_info() if lib["user_api"] == "blas"]
    return max(counts, default=0)


def forget_probe_reductions() -> None:
    """Empty the process's cache of the probe's reductions (one per contact position, kept by
    :mod:`ebantenna.simulate.touched_object` for later simulations in the same process), so that
    the next simulation pays for its own, as the first one in a fresh process does.

    A sweep calls it before every timed simulation of a scene with ``object_modes``: without it
    the first row to touch a position pays its reduction and every later row or round finds it
    made, and the rows' costs depend on their order. The simulator offers no way to empty the
    cache, so this clears its dict (``_KEPT``) under its lock: a bench's reach into a private
    name, to be replaced by the module's own function if it gets one.
    """
    from ebantenna.simulate import touched_object

    with touched_object._kept_lock:
        touched_object._KEPT.clear()


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
