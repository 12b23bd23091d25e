"""Argument checks shared by the signal-processing modules (private)."""

from __future__ import annotations

import numpy as np

from .._validate import check_array, check_positive

__all__ = ["check_signal", "check_fs", "check_band", "MAX_FFT"]

#: The longest FFT a feature or spectrogram pads to: 2**24 points, a 256 MB complex spectrum
#: and a bin width of fs / 2**24 (60 µHz at 1 kHz), far finer than any record resolves.
MAX_FFT = 2**24


def check_signal(name: str, x, *, min_length: int = 2, allow_constant: bool = True) -> np.ndarray:
    """Return ``x`` as a finite 1-D float array with at least ``min_length`` samples.

    With ``allow_constant=False`` a signal whose samples are all equal is rejected: it carries no
    vibration, so a frequency or a decay rate of it has no meaning.
    """
    x = check_array(name, x, ndim=1, min_length=min_length)
    if not allow_constant and x.max() == x.min():  # not ptp: max - min overflows near 1e308
        raise ValueError(
            f"{name} is constant (all samples equal {x[0]!r}); it carries no vibration"
        )
    return x


def check_fs(fs) -> float:
    """Return the sampling frequency ``fs`` (Hz) as a positive float."""
    return check_positive("fs", fs)


def check_band(name: str, band, fs: float) -> tuple[float, float]:
    """Return a frequency band ``(low, high)`` in Hz with ``0 < low < high < fs/2``."""
    arr = check_array(name, band, ndim=1, min_length=2)
    if arr.shape != (2,):
        raise ValueError(f"{name} must be a pair (low, high) in Hz, got shape {arr.shape}")
    low, high = float(arr[0]), float(arr[1])
    nyquist = fs / 2.0
    if not (0.0 < low < high < nyquist):
        raise ValueError(
            f"{name} must satisfy 0 < low < high < fs/2 = {nyquist:g} Hz, got ({low:g}, {high:g})"
        )
    return low, high
