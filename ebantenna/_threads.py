"""BLAS held to a number of threads, with its libraries found once per process (private).

:func:`threadpoolctl.threadpool_limits` looks for the thread pools of the process every time it
is entered: it reads the process's memory map and opens each library it finds there, some
milliseconds. The package limits BLAS around batches that can be small and many (a hinge fit
sweeps one contact position at a time, a thousand times; a data set simulates one range of
positions at a time), so it finds the libraries once, with one
:class:`threadpoolctl.ThreadpoolController`, and reuses it.

The controller is made at the first call, after NumPy and SciPy are loaded (SciPy's wheels
bring an OpenBLAS of their own, loaded with :mod:`scipy.linalg`). A library that a process loads
later (another package's OpenMP runtime, say) is not seen by it, and not limited.
"""

from __future__ import annotations

import functools


@functools.cache
def _controller():
    import numpy  # noqa: F401  (loads NumPy's BLAS)
    import scipy.linalg  # noqa: F401  (loads SciPy's)
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


def limited_threads(limits: int = 1, user_api: str | None = "blas"):
    """A context in which the thread pools of ``user_api`` (``"blas"``, ``"openmp"``, or None
    for both) run on at most ``limits`` threads; the counts before it come back after it.

    As ``threadpoolctl.threadpool_limits(limits=limits, user_api=user_api)``, over the
    libraries found at the first call.

    Examples
    --------
    >>> from threadpoolctl import threadpool_info
    >>> with limited_threads(1):
    ...     {lib["num_threads"] for lib in threadpool_info() if lib["user_api"] == "blas"}
    {1}
    """
    return _controller().limit(limits=limits, user_api=user_api)
