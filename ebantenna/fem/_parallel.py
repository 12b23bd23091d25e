"""Many small solves at once: one thread per core, each with a single-threaded BLAS (private)."""

from __future__ import annotations

import functools
import os
from concurrent.futures import ThreadPoolExecutor

from threadpoolctl import ThreadpoolController


@functools.cache
def _blas_controller() -> ThreadpoolController:
    """The thread pools of the BLAS libraries loaded, found once.

    Finding them reads the process's memory map (milliseconds); a fit that sweeps one position
    at a time calls :func:`map_on_cores` a thousand times. Made at the first call, when NumPy's
    and SciPy's BLAS are loaded (the finite-element modules import both).
    """
    return ThreadpoolController()


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
    with _blas_controller().limit(limits=1, user_api="blas"):
        if workers == 1:
            return [function(item) for item in items]
        with ThreadPoolExecutor(workers) as pool:
            return list(pool.map(function, items))
