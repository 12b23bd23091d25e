"""Features of the tip accelerations: resultant (eq. 1), norm spectrum and the 256-bin FFT vector.

Section 2.1 of the paper takes the Euclidean norm of the X and Z accelerations as the total tip
acceleration (its eq. 1), and the norm of the two FFT spectra as the spectrum that the dominant
frequency is read from. Section 4.2 feeds "the magnitude values of the FFT frequency spectrum (256
components)", normalised by the maximum magnitude, to the classifiers. With a 1 kHz sampling rate
the paper's "frequencies up to 512 Hz" point to a 512-point FFT, whose first 256 bins (0 to 498 Hz
in steps of
1.953 Hz) are the feature vector.
"""

from __future__ import annotations

import numpy as np

from .._validate import check_array, check_bool, check_choice, check_int
from ..recording import Recording
from ._checks import MAX_FFT, check_fs, check_signal

__all__ = ["resultant_acceleration", "norm_spectrum", "fft_features"]


def _pair(ax, az, fs=None):
    """Return ``(ax, az, fs or None)`` from a :class:`Recording` or two arrays (and ``fs``).

    With a Recording, ``az`` must be omitted and ``fs``, when given, must be the recording's own:
    another rate would silently rescale every frequency.
    """
    if isinstance(ax, Recording):
        if az is not None:
            raise TypeError("az must not be given together with a Recording")
        if fs is not None and check_fs(fs) != ax.fs:
            raise ValueError(f"fs must be the Recording's own sampling frequency, {ax.fs:g} Hz, "
                             f"or be omitted; got {fs:g} Hz")
        return np.asarray(ax.ax), np.asarray(ax.az), ax.fs
    if az is None:
        raise TypeError("az is required unless ax is a Recording")
    return ax, az, fs


def resultant_acceleration(ax, az=None) -> np.ndarray:
    """Resultant tip acceleration ``sqrt(ax**2 + az**2)`` (eq. 1 of the paper), m/s^2.

    Parameters
    ----------
    ax : array of shape (n,) or (n_recordings, n), or Recording
        Acceleration along X, m/s^2, or a :class:`~ebantenna.recording.Recording` (then omit
        ``az``).
    az : array of the shape of ``ax``, optional
        Acceleration along Z, m/s^2.

    Returns
    -------
    ndarray of the shape of ``ax``
        The Euclidean norm sample by sample, m/s^2 (computed with :func:`numpy.hypot`, which does
        not overflow for large values).

    Examples
    --------
    >>> from ebantenna.signal import resultant_acceleration
    >>> resultant_acceleration([3.0, 0.0], [4.0, -2.0])
    array([5., 2.])
    """
    ax, az, _ = _pair(ax, az)
    ax = check_array("ax", ax, ndim=(1, 2), min_length=1)
    az = check_array("az", az, ndim=(1, 2), min_length=1)
    if ax.shape != az.shape:
        raise ValueError(f"ax and az must have the same shape, got {ax.shape} and {az.shape}")
    return np.hypot(ax, az)


def norm_spectrum(ax, az=None, fs=None, *, n_fft=None, remove_mean: bool = False):
    """Norm of the X and Z amplitude spectra, ``sqrt(|FFT ax|^2 + |FFT az|^2)`` (section 2.1).

    Parameters
    ----------
    ax, az : arrays of shape (n,), or a Recording as ``ax``
        Accelerations, m/s^2.
    fs : float
        Sampling frequency, Hz. Taken from the recording when one is given: omit it then (another
        value than the recording's raises a ValueError).
    n_fft : int, optional
        FFT length: the signals are cut or zero-padded to it (default ``n``).
    remove_mean : bool
        Subtract each axis' mean first (removes gravity and sensor offset from bin 0).

    Returns
    -------
    freqs : ndarray of shape (n_fft // 2 + 1,)
        Bin frequencies, Hz.
    magnitude : ndarray of shape (n_fft // 2 + 1,)
        One-sided amplitude spectrum of the resultant: a sinusoid of amplitude A (m/s^2) on either
        axis gives a peak of A at its bin (bins 0 and Nyquist are not doubled).

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal import norm_spectrum
    >>> t = np.arange(1000) / 1000.0
    >>> ax, az = 3 * np.sin(2 * np.pi * 50 * t), 4 * np.cos(2 * np.pi * 50 * t)
    >>> f, mag = norm_spectrum(ax, az, 1000.0)
    >>> float(f[np.argmax(mag)]), round(float(mag.max()), 6)
    (50.0, 5.0)
    """
    ax, az, fs = _pair(ax, az, fs)
    fs = check_fs(fs)
    ax = check_signal("ax", ax)
    az = check_signal("az", az)
    if ax.shape != az.shape:
        raise ValueError(f"ax and az must have the same shape, got {ax.shape} and {az.shape}")
    n = ax.shape[0]
    n_fft = n if n_fft is None else check_int("n_fft", n_fft, minimum=2, maximum=MAX_FFT)
    if check_bool("remove_mean", remove_mean):
        ax = ax - ax.mean()
        az = az - az.mean()
    scale = np.full(n_fft // 2 + 1, 2.0 / min(n, n_fft))
    scale[0] /= 2.0
    if n_fft % 2 == 0:
        scale[-1] /= 2.0
    mx = np.abs(np.fft.rfft(ax, n=n_fft))
    mz = np.abs(np.fft.rfft(az, n=n_fft))
    return np.fft.rfftfreq(n_fft, d=1.0 / fs), scale * np.hypot(mx, mz)


def fft_features(
    ax,
    az=None,
    *,
    n_fft: int = 512,
    n_bins: int = 256,
    normalise: str = "sample",
    remove_mean: bool = False,
) -> np.ndarray:
    """The paper's feature vector: the first ``n_bins`` FFT norm magnitudes, normalised.

    Parameters
    ----------
    ax, az : arrays of shape (n,) or (n_recordings, n), or a Recording as ``ax``
        Accelerations, m/s^2; each row is one recording.
    n_fft : int
        FFT length (default 512: the first 512 samples, zero-padded if shorter).
    n_bins : int
        Number of bins kept, ``1 <= n_bins <= n_fft // 2 + 1`` (default 256).
    normalise : {"sample", "dataset", "none"}
        The paper says only that the data set is "normalized by dividing by the maximum magnitude of
        the frequency component". ``"sample"`` divides each vector by its own maximum (the shape of
        the spectrum, independent of how hard the probe hit); ``"dataset"`` divides every vector by
        the largest magnitude of all rows (keeps the relative levels); ``"none"`` leaves m/s^2.
    remove_mean : bool
        Subtract each axis' mean first. The paper keeps the DC bin (its spectrograms show it), so
        the default is False.

    Returns
    -------
    ndarray of shape (n_bins,) or (n_recordings, n_bins)
        Dimensionless when normalised, m/s^2 otherwise.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal import fft_features
    >>> t = np.arange(1000) / 1000.0
    >>> x = np.sin(2 * np.pi * 125 * t)
    >>> v = fft_features(x, np.zeros_like(x))
    >>> v.shape, int(np.argmax(v)), float(v.max())  # 125 Hz is bin 64 of a 512-point FFT at 1 kHz
    ((256,), 64, 1.0) """
    ax, az, _ = _pair(ax, az)
    n_fft = check_int("n_fft", n_fft, minimum=2, maximum=MAX_FFT)
    n_bins = check_int("n_bins", n_bins, minimum=1, maximum=n_fft // 2 + 1)
    check_choice("normalise", normalise, ("sample", "dataset", "none"))
    ax = check_array("ax", ax, ndim=(1, 2), min_length=2)
    az = check_array("az", az, ndim=(1, 2), min_length=2)
    if ax.shape != az.shape:
        raise ValueError(f"ax and az must have the same shape, got {ax.shape} and {az.shape}")
    if check_bool("remove_mean", remove_mean):
        ax = ax - ax.mean(axis=-1, keepdims=True)
        az = az - az.mean(axis=-1, keepdims=True)
    mx = np.abs(np.fft.rfft(ax, n=n_fft, axis=-1))
    mz = np.abs(np.fft.rfft(az, n=n_fft, axis=-1))
    mag = np.hypot(mx, mz)
    mag = mag[..., :n_bins]
    if normalise == "none":
        return mag
    peak = mag.max(axis=-1, keepdims=True) if normalise == "sample" else mag.max()
    if np.any(peak == 0.0):
        raise ValueError(
            "ax and az are zero in every kept bin; there is no maximum to normalise by"
        )
    return mag / peak
