"""Small helpers shared by the study's sections (private)."""

from __future__ import annotations

import numpy as np
from threadpoolctl import threadpool_limits

__all__ = ["beyond_chance", "per_contact", "probe_length", "pct", "BLAS_THREADS", "blas_limited"]

#: BLAS threads while a step of a study runs. Measured side by side with
#: ``python benchmarks/study_blas_threads.py`` (the quick study, two cores): no step ran faster
#: on two threads, and the learning steps (ml, splits, seeds, ANN set-up) took 1.6 to 2.3 times
#: the CPU time, and four to five times the wall time while another job ran: their products are
#: too small to gain from a second thread, and a spinning thread takes a core from the rest.
#: The full study's splits step is the exception on an idle machine (its kernel products are
#: large): 190 s on two threads against 271 s on one, for 1.26 times the CPU time. One thread
#: is kept for it too: the numbers then depend neither on the core count nor on the thread
#: count (two threads round a few kernel entries differently, enough to flip a recording within
#: the solver's tolerance of a tie), and the CPU time does not grow when the machine is busy.
BLAS_THREADS = 1


def blas_limited():
    """A context in which BLAS runs on :data:`BLAS_THREADS` threads (``threadpoolctl``)."""
    return threadpool_limits(limits=BLAS_THREADS, user_api="blas")


def probe_length(ds) -> float:
    """Length (m) of the probe the data set was simulated with, from its own metadata."""
    return ds.metadata["config"]["scene"]["probe"]["length"]


def pct(x: float) -> str:
    """A fraction as a percentage with one decimal.

    Examples
    --------
    >>> pct(0.9917)
    '99.2 %'
    """
    return f"{100 * x:.1f} %"


def per_contact(values, contact, mask=None):
    """Median and standard deviation of ``values`` at each distinct contact distance.

    Parameters
    ----------
    values, contact : ndarray of shape (n,)
        Values and the contact distance (m) of each.
    mask : ndarray of bool, optional
        Which values to use; a contact with none left gets NaN.

    Returns
    -------
    grid, median, spread : ndarray
        Distinct contacts (m), median and standard deviation at each.

    Examples
    --------
    >>> grid, med, spread = per_contact(np.array([1.0, 3.0, 5.0]), np.array([0.1, 0.1, 0.2]))
    >>> grid.tolist(), med.tolist(), spread.tolist()
    ([0.1, 0.2], [2.0, 5.0], [1.0, 0.0])
    """
    grid = np.unique(contact)
    med = np.full(grid.size, np.nan)
    spread = np.full(grid.size, np.nan)
    for i, g in enumerate(grid):
        sel = contact == g
        if mask is not None:
            sel &= mask
        if np.any(sel):
            med[i] = np.median(values[sel])
            spread[i] = np.std(values[sel])
    return grid, med, spread


def beyond_chance(accuracy: float, chance: float, n: int) -> bool:
    """Whether an accuracy on ``n`` test recordings stands more than two binomial standard
    deviations of guessing, ``2 sqrt(chance (1 - chance) / n)``, above chance.

    Examples
    --------
    >>> beyond_chance(0.30, 0.2, 1000), beyond_chance(0.30, 0.2, 30)
    (True, False)
    """
    return bool(accuracy - chance > 2 * np.sqrt(chance * (1 - chance) / n))
