"""Many small solves at once: one thread per core, each with a single-threaded BLAS (private)."""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor

from .._threads import limited_threads


def map_on_cores(function, items) -> list:
    """``[function(item) for item in items]``, spread over the cores.

    NumPy and SciPy release the GIL in their kernels, so threads run side by side; BLAS is held to
    one thread each, because threads inside such small matrices only get in each other's way.
    One thread per core (``os.cpu_count()``), at most one per item; a single item runs in the
    calling thread (a pool would only add the cost of starting it). The results come back in
    the order of ``items`` and do not depend on how many threads ran them, as long as
    ``function`` only reads what the items share.
    """
    items = list(items)
    workers = max(1, min(len(items), os.cpu_count() or 1))
    with limited_threads(1):
        if workers == 1:
            return [function(item) for item in items]
        with ThreadPoolExecutor(workers) as pool:
            return list(pool.map(function, items))
