"""The engine of :func:`.modes.damped_exponentials` on a uniform time grid.

:func:`.modes.damped_exponentials` is written as the sum reads, ``Im(sum_k C_k exp(r_k t_n))``:
one complex exponential per term and sample. On a uniform grid ``t_n = t_0 + n dt`` most of
them can be had by products instead: with ``n = a B + b`` (``B`` = :data:`GRID_BLOCK`),

    exp(r t_n) = exp(r (t_0 + a B dt)) exp(r b dt),

so each term costs ``n / B + B`` exponentials, and the sum over terms becomes one batched
matrix product ``(A, k) x (k, B)`` per signal. The arguments are rounded as the direct
evaluation's are (both reach ``|r| t``), so the two agree to a few ulps of
``|r| t_max sum_k |C_k|``; the test suite holds them to that bound. The simulator uses this
engine by default (``engine="grid"``) wherever it applies (:func:`fits_grid`), and the reference
:func:`.modes.direct_exponentials` elsewhere (:func:`grid_or_direct`); times given per signal (a
jittered clock) never reach it, :func:`.modes.damped_exponentials` sends them to the reference.
This module imports the reference and adds ``"grid"`` to :data:`.modes.EXPONENTIAL_ENGINES` (the
package does, when it is imported); the reference imports nothing from it.
"""

from __future__ import annotations

import numpy as np

from .modes import EXPONENTIAL_ENGINES, direct_exponentials

__all__ = ["GRID_BLOCK", "fits_grid", "grid_exponentials", "grid_or_direct"]

#: Block length ``B`` of the grid: the samples whose exponentials are taken once per term.
GRID_BLOCK = 32


def fits_grid(t: np.ndarray) -> bool:
    """Whether the engine applies to the times ``t``: one row, longer than two blocks, and
    ``t_0 + n dt`` to rounding (within 8 eps of the largest ``|t|``)."""
    if t.ndim != 1 or t.size <= 2 * GRID_BLOCK:
        return False
    n = np.arange(t.size)
    dt = (t[-1] - t[0]) / (t.size - 1)
    return bool(np.all(np.abs(t - (t[0] + n * dt)) <= 8 * np.finfo(float).eps * np.abs(t).max()))


def grid_exponentials(t: np.ndarray, coef, rate, max_elements: int) -> np.ndarray:
    """``Im(sum_k coef_k exp(rate_k t))`` on the uniform grid ``t`` (:func:`fits_grid`), shape
    ``(n_signals, n_samples)``; arguments as in :func:`.modes.damped_exponentials`, checked
    there."""
    n_signals, n_terms = coef.shape
    n_samples = t.size
    out = np.empty((n_signals, n_samples))
    dt = (t[-1] - t[0]) / (n_samples - 1)
    n_blocks = -(-n_samples // GRID_BLOCK)
    inner = np.arange(GRID_BLOCK) * dt
    outer = t[0] + np.arange(n_blocks) * (GRID_BLOCK * dt)
    per_signal = n_terms * (n_blocks + GRID_BLOCK) + n_samples
    block = max(1, max_elements // max(1, per_signal))
    for start in range(0, n_signals, block):
        rows = slice(start, start + block)
        r = rate[rows, :, None]
        head = coef[rows, :, None] * np.exp(r * outer)  # (s, k, A)
        tail = np.exp(r * inner)  # (s, k, B)
        grid = np.matmul(head.transpose(0, 2, 1), tail).imag  # (s, A, B)
        out[rows] = grid.reshape(grid.shape[0], -1)[:, :n_samples]
    return out


def grid_or_direct(t: np.ndarray, coef, rate, max_elements: int) -> np.ndarray:
    """The engine ``"grid"`` of :func:`.modes.damped_exponentials`: :func:`grid_exponentials`
    where the grid applies (:func:`fits_grid`), the reference elsewhere."""
    if fits_grid(t):
        return grid_exponentials(t, coef, rate, max_elements)
    return direct_exponentials(t, coef, rate, max_elements)


EXPONENTIAL_ENGINES["grid"] = grid_or_direct
