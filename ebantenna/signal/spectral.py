"""Dominant frequency of a vibration signal, to a fraction of an FFT bin.

The plain estimate is the frequency of the largest FFT bin; its error is up to half a bin, ``fs / (2
n)`` (0.5 Hz for one second of data). Two interpolating estimators refine it from the peak bin and
its two
neighbours:

``"parabolic"``
    fits a parabola through the three log-magnitudes (exact for a Gaussian-shaped peak; for a Hann
    window the bias is below 0.02 bin, and it shrinks with zero padding).
``"jacobsen"``
    the complex-ratio estimator of E. Jacobsen and P. Kootsookos, "Fast, accurate frequency
    estimators", *IEEE Signal Processing Magazine* 24(3), 2007:
    ``delta = P * Re[(X[k-1] - X[k+1]) / (2 X[k] - X[k-1] - X[k+1])]`` with ``P = 1`` for the
    rectangular window and ``P = 2`` for the (periodic) Hann window, for which the formula is exact
    for one tone apart from the leakage of its negative-frequency image.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.signal import get_window

from .._validate import check_bool, check_choice, check_int, check_nonnegative, check_positive
from ._checks import check_fs, check_signal

__all__ = ["dominant_frequency", "peak_frequencies", "FREQUENCY_METHODS", "WINDOWS"]

#: Peak-frequency estimators of :func:`dominant_frequency`.
FREQUENCY_METHODS = ("bin", "parabolic", "jacobsen")
#: Windows of :func:`dominant_frequency` (periodic forms, as for spectral analysis).
WINDOWS = ("hann", "rectangular", "blackman", "hamming")


def dominant_frequency(
    x,
    fs,
    *,
    method: str = "jacobsen",
    window: str = "hann",
    zero_pad: int = 1,
    fmin: float | None = None,
    fmax: float | None = None,
    remove_mean: bool = True,
) -> float:
    """Frequency of the strongest spectral peak of ``x``, Hz.

    Parameters
    ----------
    x : array of shape (n,)
        Signal (for instance the resultant acceleration), any unit; at least 4 samples, not
        constant.
    fs : float
        Sampling frequency, Hz.
    method : {"jacobsen", "parabolic", "bin"}
        Peak estimator (see the module notes). ``"jacobsen"`` needs the Hann or rectangular window.
    window : {"hann", "rectangular", "blackman", "hamming"}
        Window applied before the FFT.
    zero_pad : int
        FFT length as a multiple of ``n`` (1 = no padding). Padding interpolates the spectrum: it
        shrinks the bin spacing (and the plain-bin error) but not the resolution.
    fmin, fmax : float, optional
        Search band, Hz. Default: from one bin above DC up to the Nyquist frequency ``fs / 2``
        (for a short transient, from two bins of the analysed segment, see the notes).
    remove_mean : bool
        Subtract the mean first (for a short transient, the median of the record), so that the
        DC bin (gravity, offsets) cannot win.

    Returns
    -------
    float
        Dominant frequency, Hz.

    Raises
    ------
    ValueError
        For an empty, constant, too-short or non-finite ``x``, ``fs <= 0``, or a band outside
        ``[0, fs/2]``.

    Notes
    -----
    **Short transients.** A window over the whole record weights its start by about zero, so a
    decay of a few tens of milliseconds at the start of a one-second record would vanish under
    it. Without ``fmin``, a record whose energy sits in less than half of it (a decay or a burst,
    found block by block) is analysed on that part only: baseline (the median) removed, windowed
    over the part, padded to keep the record's bin spacing.

    **Accuracy.** For a clean damped tone :math:`e^{-t/\\tau}\\sin(2\\pi f t + \\phi)` plus any
    offset (checked for :math:`\\tau` from 5 ms to 10 s, offsets up to 10 g, 1 s at 1 kHz) the
    Jacobsen estimate with the Hann window is within :math:`0.15/(2\\pi\\tau) + 0.01 f_s/n` of
    :math:`f`, provided the tone is at least its half-bandwidth plus six bins,
    :math:`1/(2\\pi\\tau) + 6 f_s/n`, away from 0 and from :math:`f_s/2` (closer, its peak merges
    with its mirror image and is not :math:`f` any more). Values of ``x`` from 1e-300 to 1e308 are
    scaled by a power of two (exact) before the FFT.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal import dominant_frequency
    >>> t = np.arange(1000) / 1000.0
    >>> x = np.exp(-t / 0.2) * np.sin(2 * np.pi * 123.37 * t)
    >>> round(dominant_frequency(x, 1000.0), 2)
    123.37
    >>> dominant_frequency(x, 1000.0, method="bin")
    123.0
    >>> short = np.exp(-t / 0.03) * np.sin(2 * np.pi * 25.0 * t) + 9.81  # a 30 ms tap, gravity
    >>> round(dominant_frequency(short, 1000.0), 1)
    25.0
    """
    spectrum, lo, hi, n, fs, zero_pad = _windowed_spectrum(x, fs, method, window, zero_pad, fmin,
                                                           fmax, remove_mean)
    mag = np.abs(spectrum)
    k = lo + int(np.argmax(mag[lo : hi + 1]))
    if mag[k] == 0.0:
        raise ValueError("x has no energy in the search band [fmin, fmax]")
    return _refine_peak(spectrum, k, fs, n, method, window, zero_pad)


def _windowed_spectrum(x, fs, method, window, zero_pad, fmin, fmax, remove_mean):
    """Validate the arguments; return the windowed spectrum, the bin range of the search band,
    the number of samples and the sampling frequency."""
    fs = check_fs(fs)
    x = check_signal("x", x, min_length=4, allow_constant=False)
    check_choice("method", method, FREQUENCY_METHODS)
    check_choice("window", window, WINDOWS)
    zero_pad = check_int("zero_pad", zero_pad, minimum=1, maximum=64)
    check_bool("remove_mean", remove_mean)
    if method == "jacobsen" and window not in ("hann", "rectangular"):
        raise ValueError(f"method 'jacobsen' needs window 'hann' or 'rectangular', got {window!r}")
    n = x.shape[0]
    n_fft = n * zero_pad
    nyquist = fs / 2.0
    given_fmin = fmin
    fmin = fs / n if fmin is None else check_nonnegative("fmin", fmin)
    fmax = nyquist if fmax is None else check_nonnegative("fmax", fmax)
    if not fmin < fmax <= nyquist:
        raise ValueError(
            f"fmin and fmax must satisfy 0 <= fmin < fmax <= fs/2 = {nyquist:g} Hz, "
            f"got fmin={fmin:g}, fmax={fmax:g}"
        )
    fmin = given_fmin if given_fmin is None else fmin
    # Scale by a power of two (exact) so that the FFT's sums cannot overflow near 1e308.
    x = np.ldexp(x, -math.frexp(float(np.max(np.abs(x))))[1])
    segment = _transient(x) if fmin is None else None
    if segment is not None:
        # A short transient: window the part that holds it, not the whole record (a taper over
        # the whole record would weight the transient's start by about zero), and remove the
        # baseline (the median of the record, the level outside the transient) instead of the
        # mean, which would leave a step. The padding keeps the record's bin spacing.
        if remove_mean:
            x = x - np.median(x)
        x = x[segment]
        m = x.shape[0]
        zero_pad *= -(-n // m)
        n, n_fft = m, m * zero_pad
        # below two bins of the segment the window's DC lobe holds what is left of the baseline
        fmin = 2.0 * fs / m
        if not fmin < fmax:
            raise ValueError(
                f"x is a transient of {m} samples: no frequency below its two-bin limit "
                f"{fmin:g} Hz can be resolved; fmax={fmax:g}"
            )
    else:
        fmin = fs / n if fmin is None else fmin
        if remove_mean:
            x = x - x.mean()
    w = np.ones(n) if window == "rectangular" else get_window(window, n, fftbins=True)
    spectrum = np.fft.rfft(x * w, n=n_fft)
    df = fs / n_fft
    lo = int(np.ceil(fmin / df - 1e-9))
    hi = int(np.floor(fmax / df + 1e-9))
    if hi < lo:
        raise ValueError(f"the band [{fmin:g}, {fmax:g}] Hz holds no FFT bin (bin width {df:g} Hz)")
    return spectrum, lo, hi, n, fs, zero_pad


def _transient(x: np.ndarray) -> slice | None:
    """The samples holding a short transient (a decay, a burst) in ``x``, or None.

    The record is cut into 64 blocks about the median of ``x`` (the baseline). A transient is the
    span from the first to the last block above both 30 times the quietest block (the noise
    floor: for white noise the quietest of 64 blocks of 15 or more samples holds about 0.4 times
    the mean block energy, and a block above 12 times the mean is a 1e-6 chance) and 1e-6 of the
    strongest block (an amplitude 60 dB down, where a noise-free decay counts as over). It counts
    as short when it covers less than half the record, which a steady oscillation never does.
    """
    n = x.shape[0]
    size = max(4, n // 64)
    blocks = (x[: n - n % size] - np.median(x)).reshape(-1, size)
    energy = np.einsum("ij,ij->i", blocks, blocks)
    loud = _loud(energy)
    # A slow steady tone has blocks near its zero crossings far quieter than those at its
    # peaks, enough to pass it off as a few short bursts; over runs of a quarter of the record,
    # each holding half a period of any tone above 2 fs / n, it stands out nowhere.
    if loud.size == 0 or _loud(np.convolve(energy, np.ones(len(energy) // 4), "valid")).size == 0:
        return None
    start, stop = int(loud[0]) * size, (int(loud[-1]) + 1) * size
    return slice(start, stop) if 2 * (stop - start) < n else None


def _loud(energy: np.ndarray) -> np.ndarray:
    """Indices of the blocks above the noise floor (see :func:`_transient`)."""
    return np.flatnonzero(energy > max(30.0 * energy.min(), 1e-6 * energy.max()))


def _refine_peak(spectrum, k, fs, n, method, window, zero_pad) -> float:
    """Frequency (Hz) of the peak at bin ``k`` of the spectrum of ``n`` samples, padded."""
    df = fs / (n * zero_pad)
    step = zero_pad if method == "jacobsen" else 1
    if method == "bin" or k - step < 0 or k + step > spectrum.shape[0] - 1:
        return float(k * df)
    if method == "parabolic":
        lm = np.log(np.maximum(np.abs(spectrum[k - 1 : k + 2]), np.finfo(float).tiny))
        curvature = lm[0] - 2.0 * lm[1] + lm[2]
        delta = 0.0 if curvature == 0.0 else 0.5 * (lm[0] - lm[2]) / curvature
        return float((k + float(np.clip(delta, -1.0, 1.0))) * df)
    # Jacobsen: the neighbours one unpadded bin (zero_pad padded bins) away on either side; the
    # derivation holds about any reference frequency, so it is exact on a padded grid too.
    a, b, c = spectrum[k - step], spectrum[k], spectrum[k + step]
    scale = 2.0 if window == "hann" else 1.0
    denominator = 2.0 * b - a - c
    delta = 0.0 if denominator == 0 else scale * float(np.real((a - c) / denominator))
    return float(k * df + float(np.clip(delta, -1.0, 1.0)) * fs / n)


def peak_frequencies(
    x,
    fs,
    n_peaks: int,
    *,
    method: str = "jacobsen",
    window: str = "hann",
    min_separation: float | None = None,
    fmin: float | None = None,
    fmax: float | None = None,
    remove_mean: bool = True,
) -> np.ndarray:
    """Frequencies of the ``n_peaks`` strongest spectral peaks of ``x`` (several modes), Hz.

    Each peak is a local maximum of the windowed magnitude spectrum, at least ``min_separation``
    apart from any stronger one; it is refined like :func:`dominant_frequency`. The result feeds
    :class:`ebantenna.paper.estimators.MultiModeDistanceEstimator`.

    Parameters
    ----------
    x : array of shape (n,)
        Signal, at least 4 samples, not constant.
    fs : float
        Sampling frequency, Hz.
    n_peaks : int
        Number of peaks wanted (>= 1).
    method, window, fmin, fmax, remove_mean
        As for :func:`dominant_frequency`.
    min_separation : float, optional
        Smallest distance between two reported peaks, Hz; default four bins, ``4 fs / n``
        (the main lobe of the Hann window is four bins wide).

    Returns
    -------
    ndarray of shape (n_peaks,)
        Peak frequencies in ascending order, Hz.

    Raises
    ------
    ValueError
        When the band holds fewer than ``n_peaks`` separated peaks, and for the bad inputs of
        :func:`dominant_frequency`.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal import peak_frequencies
    >>> t = np.arange(1000) / 1000.0
    >>> x = (np.exp(-t / 0.3) * np.sin(2 * np.pi * 43.21 * t)
    ...      + 0.5 * np.exp(-t / 0.1) * np.sin(2 * np.pi * 187.65 * t))
    >>> np.round(peak_frequencies(x, 1000.0, 2), 2)
    array([ 43.21, 187.65])
    """
    n_peaks = check_int("n_peaks", n_peaks, minimum=1)
    spectrum, lo, hi, n, fs, zero_pad = _windowed_spectrum(x, fs, method, window, 1, fmin, fmax,
                                                           remove_mean)
    df = fs / (n * zero_pad)
    sep = (4.0 * fs / n if min_separation is None
           else check_positive("min_separation", min_separation))
    mag = np.abs(spectrum)
    band = mag[lo : hi + 1]
    inner = (band[1:-1] > band[:-2]) & (band[1:-1] >= band[2:])
    candidates = lo + 1 + np.flatnonzero(inner)
    candidates = candidates[np.argsort(mag[candidates])[::-1]]
    chosen: list[int] = []
    for k in candidates:
        if mag[k] > 0.0 and all(abs(k - j) * df >= sep for j in chosen):
            chosen.append(int(k))
            if len(chosen) == n_peaks:
                break
    if len(chosen) < n_peaks:
        raise ValueError(
            f"x holds only {len(chosen)} spectral peak(s) at least {sep:g} Hz apart in the "
            f"search band; n_peaks={n_peaks} requested"
        )
    freqs = [_refine_peak(spectrum, k, fs, n, method, window, zero_pad) for k in chosen]
    return np.sort(np.array(freqs))
