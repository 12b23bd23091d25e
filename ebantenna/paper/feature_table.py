"""Per-signal features of a data set, computed in parallel chunks through joblib.

Every signal of the data set goes through the same small pipeline (dominant frequency, the two
strongest spectral peaks, the band-passed decay fit, the paper's FFT feature vectors). The rows are
cut into chunks and the chunks handed to :class:`joblib.Parallel`, so the work spreads over local
cores by default, and over a cluster when a joblib backend such as Dask is active::

    from joblib import parallel_config
    with parallel_config(backend="dask"):        # needs a dask.distributed Client
        feats = signal_features(ds.ax, ds.az, ds.fs, n_jobs=-1)

The result does not depend on the backend or on the number of jobs.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from joblib import Parallel, delayed

from .._progress import progress
from .._validate import check_int, check_n_jobs, check_positive
from ..signal import (
    apply_filter,
    dominant_frequency,
    fft_features,
    fit_decay,
    paper_filter,
    resultant_acceleration,
)
from ..signal.spectral import peak_frequencies

__all__ = ["SignalFeatures", "signal_features", "mode_peaks"]


@dataclass(frozen=True, eq=False)
class SignalFeatures:
    """Features of every signal (one row each).

    Attributes
    ----------
    dominant : ndarray (n,)
        Dominant frequency of the sweep-plane (X) acceleration, Hz.
    peaks : ndarray (n, 2)
        The two strongest spectral peaks of X, ascending, Hz (NaN where fewer than two stand out).
    tau, gain : ndarray (n,)
        Time constant (s) and gain (m/s^2) of the exponential fit to the Chebyshev band-passed
        resultant acceleration (section 4.1.2).
    decay_ok : ndarray of bool (n,)
        Whether the decay fit is usable (its ``status == "ok"``).
    decay_status : ndarray of str (n,)
        The decay fit's ``status`` (:class:`~ebantenna.signal.DecayFit`): why a fit is not
        usable.
    fft : ndarray (n, 256)
        The paper's FFT feature vector of X and Z, each row divided by its maximum.
    fft_elliptic : ndarray (n, 256)
        The same after the Table 2 elliptic band-pass (the full-length regression's input).
    """

    dominant: np.ndarray
    peaks: np.ndarray
    tau: np.ndarray
    gain: np.ndarray
    decay_ok: np.ndarray
    decay_status: np.ndarray
    fft: np.ndarray
    fft_elliptic: np.ndarray


def _peaks_chunk(ax, fs):
    """The dominant frequency and the two strongest peaks of each row of ``ax``."""
    n = ax.shape[0]
    dominant = np.empty(n)
    peaks = np.full((n, 2), np.nan)
    # The paper's spectrum is that of the whole record: the band starts one bin above DC, which
    # also keeps the spectral functions from analysing a short transient on its own span.
    band = {"fmin": fs / ax.shape[1]}
    for i in range(n):
        dominant[i] = dominant_frequency(ax[i], fs, **band)
        try:
            peaks[i] = peak_frequencies(ax[i], fs, 2, **band)
        except ValueError:
            pass  # fewer than two separated peaks: stays NaN and is counted by the caller
    return dominant, peaks


def _chunk(ax, az, fs, cheb, ellip):
    # Filters run on the whole chunk at once (row by row inside SciPy); the fits go one by one.
    banded = apply_filter(cheb, resultant_acceleration(ax, az))
    fx, fz = apply_filter(ellip, ax), apply_filter(ellip, az)
    dominant, peaks = _peaks_chunk(ax, fs)
    n = ax.shape[0]
    tau = np.full(n, np.nan)
    gain = np.full(n, np.nan)
    ok = np.zeros(n, dtype=bool)
    status = np.empty(n, dtype=object)
    for i in range(n):
        fit = fit_decay(banded[i], fs)
        tau[i], gain[i], ok[i], status[i] = fit.tau, fit.a, fit.ok, fit.status
    return dominant, peaks, tau, gain, ok, status.astype(str), fx, fz


def _checked(ax, az, fs, chunk, n_jobs):
    """The arguments of :func:`signal_features` and :func:`mode_peaks` checked."""
    ax = np.asarray(ax, dtype=float)
    az = ax if az is None else np.asarray(az, dtype=float)
    if ax.ndim != 2 or ax.shape != az.shape:
        raise ValueError(f"ax and az must be 2-D of one shape, got {ax.shape} and {az.shape}")
    return (ax, az, check_positive("fs", fs), check_int("chunk", chunk, minimum=1),
            check_n_jobs("n_jobs", n_jobs))


def _in_chunks(function, rows: int, chunk: int, n_jobs, show_progress, *arrays, args=()):
    """``function(*(a[s:s + chunk] for a in arrays), *args)`` for every chunk of ``rows`` on
    joblib's workers, its outputs concatenated."""
    starts = range(0, rows, chunk)
    tasks = (delayed(function)(*(a[s : s + chunk] for a in arrays), *args) for s in starts)
    parts = progress(Parallel(n_jobs=n_jobs, return_as="generator")(tasks), total=len(starts),
                     desc="features", enabled=show_progress)
    return [np.concatenate(p) for p in zip(*list(parts), strict=True)]


def mode_peaks(ax, fs, *, n_jobs=None, chunk: int = 250, show_progress=None):
    """The dominant frequency and the two strongest peaks of every row of X, as
    :func:`signal_features` gives them (bit for bit), without its decay fits and filtered
    spectra: what the mode-curve classifier reads
    (:func:`~ebantenna.paper.mode_curves.classify_materials_by_mode_curves`).

    Parameters
    ----------
    ax : array of shape (n, n_samples)
        Accelerations along X, m/s^2.
    fs, n_jobs, chunk, show_progress
        As in :func:`signal_features`.

    Returns
    -------
    dominant : ndarray (n,)
    peaks : ndarray (n, 2)
        As ``SignalFeatures.dominant`` and ``SignalFeatures.peaks``.
    """
    ax, _, fs, chunk, n_jobs = _checked(ax, None, fs, chunk, n_jobs)
    dominant, peaks = _in_chunks(_peaks_chunk, ax.shape[0], chunk, n_jobs, show_progress, ax,
                                 args=(fs,))
    return dominant, peaks


def signal_features(ax, az, fs, *, n_jobs=None, chunk: int = 250, show_progress=None):
    """Compute :class:`SignalFeatures` for rows of X and Z accelerations.

    Parameters
    ----------
    ax, az : arrays of shape (n, n_samples)
        Accelerations, m/s^2.
    fs : float
        Sampling frequency, Hz.
    n_jobs : int, optional
        joblib workers, at most the machine's cores (``-1``: all cores; ``None``: joblib's
        current default).
    chunk : int
        Rows per task.
    show_progress : bool, optional
        Progress bar (default: on a terminal).

    Returns
    -------
    SignalFeatures
    """
    ax, az, fs, chunk, n_jobs = _checked(ax, az, fs, chunk, n_jobs)
    # Table 1 (before the decay fit) and Table 2 (before the full-length network), each at the
    # order its specification needs; see ebantenna.signal.filters.
    cheb = paper_filter("chebyshev", fs=fs)
    ellip = paper_filter("elliptic", fs=fs)
    dominant, peaks, tau, gain, ok, status, fx, fz = _in_chunks(
        _chunk, ax.shape[0], chunk, n_jobs, show_progress, ax, az, args=(fs, cheb, ellip))
    return SignalFeatures(
        dominant=dominant,
        peaks=peaks,
        tau=tau,
        gain=gain,
        decay_ok=ok,
        decay_status=status,
        fft=fft_features(ax, az),
        fft_elliptic=fft_features(fx, fz),
    )
