"""Dominant frequency of a vibration signal, to a fraction of an FFT bin.

:func:`dominant_frequency` reads as the textbook writes the spectral peak, one named step a line:

1. remove the mean, apply the window, take the real FFT (:func:`windowed_spectrum`,
   :func:`window_weights`);
2. take the magnitude and its strongest bin in the search band (:func:`strongest_bin`);
3. interpolate between the bins (:func:`interpolated_frequency`, with :func:`parabolic_offset` or
   :func:`jacobsen_offset`).

:func:`peak_frequencies` shares steps 1 and 3 and picks several peaks in step 2
(:func:`local_maxima`, :func:`strongest_separated`). Each step checks its own arguments, so that
called on its own it answers bad input with an error naming the parameter. The two public
functions validate theirs once and then run the steps' unchecked cores (the private functions of
the same names with a leading underscore), so that nothing is checked twice. The numerical
guards (an exact power-of-two scaling against overflow, the slack of a band edge on a bin) and
the search for a short transient that ``transient=True`` asks for live in the private module
``ebantenna/signal/_guards.py``, each explained there. By default the whole record is analysed
and the frequency returned lies in the search band ``[fmin, fmax]``.

The plain estimate is the frequency of the largest FFT bin; its error is up to half a bin, ``fs / (2
n)`` (0.5 Hz for one second of data). Two interpolating estimators refine it from the peak bin and
its two neighbours:

``"parabolic"``
    fits a parabola through the three log-magnitudes (exact for a Gaussian-shaped peak; for a Hann
    window the bias is below 0.02 bin, and it shrinks with zero padding).
``"jacobsen"``
    the complex-ratio estimator of E. Jacobsen and P. Kootsookos, "Fast, accurate frequency
    estimators", *IEEE Signal Processing Magazine* 24(3), 2007:
    ``delta = P * Re[(X[k-1] - X[k+1]) / (2 X[k] - X[k-1] - X[k+1])]`` with ``P = 1`` for the
    rectangular window and ``P = 2`` for the (periodic) Hann window, for which the formula is exact
    for one tone apart from the leakage of its negative-frequency image and a finite-length error
    below ``4 / n**2`` bin (the DFT's Dirichlet kernel against the sinc of the derivation).
"""

from __future__ import annotations

import numpy as np
from scipy.signal import get_window

from .._budget import check_allocation
from .._validate import (
    check_array,
    check_bool,
    check_choice,
    check_int,
    check_nonnegative,
    check_positive,
)
from ._checks import check_fs, check_signal
from ._guards import analysed_part, unit_scaled

__all__ = [
    "dominant_frequency",
    "peak_frequencies",
    "FREQUENCY_METHODS",
    "WINDOWS",
    # the steps of the reference; each checks its own arguments
    "windowed_spectrum",
    "window_weights",
    "strongest_bin",
    "interpolated_frequency",
    "parabolic_offset",
    "jacobsen_offset",
    "local_maxima",
    "strongest_separated",
]

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
    transient: bool = False,
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
        Search band, Hz. Default: from one bin above DC, ``fs / n``, up to the Nyquist
        frequency ``fs / 2`` (for a transient analysed on its own, from two bins of its
        samples, see the notes).
    remove_mean : bool
        Subtract the mean first (for a transient analysed on its own, the median of the
        record), so that the DC bin (gravity, offsets) cannot win.
    transient : bool, default=False
        Look for a short transient (a decay or a burst filling less than half of the record)
        and, when there is one, analyse its samples only (see the notes). The default analyses
        the whole record, whatever it holds.

    Returns
    -------
    float
        Dominant frequency, Hz, within the search band: when the strongest bin sits on an edge
        of the band and the interpolation places the peak beyond it, the edge itself (where the
        interpolated spectrum is largest within the band).

    Raises
    ------
    ValueError
        For an empty, constant, too-short or non-finite ``x``, ``fs <= 0``, or a band outside
        ``[0, fs/2]``.

    Notes
    -----
    **Short transients.** A window over the whole record weights its start by about zero, so a
    decay of a few tens of milliseconds at the start of a one-second record would vanish under
    it. With ``transient=True``, a record whose energy sits in less than half of it (a decay or a
    burst, found block by block) is analysed on that part only: baseline (the median) removed,
    windowed over the part, padded to keep the record's bin spacing. Which samples are analysed
    then depends on the record, so the choice is the caller's: by default every sample is.

    **Accuracy.** For a clean damped tone :math:`e^{-t/\\tau}\\sin(2\\pi f t + \\phi)` plus any
    offset (checked for offsets up to 10 g, 1 s at 1 kHz) the Jacobsen estimate with the Hann
    window is within :math:`0.15/(2\\pi\\tau) + 0.01 f_s/n` of :math:`f`, provided the tone is at
    least its half-bandwidth plus six bins, :math:`1/(2\\pi\\tau) + 6 f_s/n`, away from 0 and
    from :math:`f_s/2` (closer, its peak merges with its mirror image and is not :math:`f` any
    more). On the whole record this is checked for :math:`\\tau` from a tenth of the record to
    10 s. With ``transient=True`` a decay found as a transient is analysed on its ``m`` samples
    alone, whose bins are wider, :math:`f_s/m`: checked from :math:`\\tau` = 5 ms, the tone must
    then also be its half-bandwidth plus two of these bins,
    :math:`1/(2\\pi\\tau) + 2 f_s/m`, away from 0 and from :math:`f_s/2`. Nearer 0, the band
    searched, which starts at :math:`2 f_s/m`, returns its edge (a 28 Hz tone with
    :math:`\\tau` = 8 ms gives 33.3 Hz); nearer :math:`f_s/2`, the peak merges with its mirror
    (466 Hz with :math:`\\tau` = 6 ms and :math:`\\phi` = 4.47, ``m`` = 45, gives 470.3 Hz). A
    decay too long to be found as a transient (:math:`\\tau` from about 70 ms in a one-second
    record) is analysed whole, where the statement needs :math:`\\tau` from a tenth of the
    record: in between, a tone near 0 can be lost (9 Hz with :math:`\\tau` = 80 ms gives 1 Hz,
    the band's edge). Values of ``x`` from 1e-300 to 1e308 are scaled by a power of two (exact)
    before the FFT.

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
    >>> round(dominant_frequency(short, 1000.0, transient=True), 1)
    25.0
    """
    x, fs, zero_pad, fmin, fmax = _checked_arguments(x, fs, method, window, zero_pad, fmin,
                                                     fmax, remove_mean, transient)
    # the steps, checked above once: their unchecked cores
    spectrum, part = _windowed_spectrum(x, fs, window, zero_pad, fmin, fmax, remove_mean,
                                        transient)
    magnitude = np.abs(spectrum)
    k = _strongest_bin(magnitude, part.lo, part.hi)
    if magnitude[k] == 0.0:
        raise ValueError("x has no energy in the search band [fmin, fmax]")
    return part.in_band(_interpolated_frequency(spectrum, k, fs, part.n, method, window,
                                                part.zero_pad))


def _checked_arguments(x, fs, method, window, zero_pad, fmin, fmax, remove_mean, transient):
    """Validate the arguments of :func:`dominant_frequency` once, at the public boundary.

    Returns ``(x, fs, zero_pad, fmin, fmax)``.

    ``fmin=None`` is returned as None: it asks for the default band start, ``fs / n`` of the
    analysed samples (two bins of a transient analysed on its own, see
    :func:`~ebantenna.signal._guards.analysed_part`); the band is checked with the start
    ``fs / n``. ``fmax=None`` becomes the Nyquist frequency.
    """
    _check_method_window(method, window)
    return _checked_spectrum(x, fs, window, zero_pad, fmin, fmax, remove_mean, transient)


def _check_method_window(method, window) -> None:
    """Refuse an unknown ``method`` or ``window``, and Jacobsen's estimator with a window it has
    no factor ``P`` for."""
    check_choice("method", method, FREQUENCY_METHODS)
    if method == "jacobsen" and window not in ("hann", "rectangular"):
        check_choice("window", window, WINDOWS)
        raise ValueError(f"method 'jacobsen' needs window 'hann' or 'rectangular', got {window!r}")
    check_choice("window", window, WINDOWS)


def _checked_spectrum(x, fs, window, zero_pad, fmin, fmax, remove_mean, transient):
    """The checks of :func:`_checked_arguments` but the method's: those of
    :func:`windowed_spectrum`. Returns ``(x, fs, zero_pad, fmin, fmax)``."""
    fs = check_fs(fs)
    x = check_signal("x", x, min_length=4, allow_constant=False)
    check_choice("window", window, WINDOWS)
    zero_pad = check_int("zero_pad", zero_pad, minimum=1, maximum=64)
    # the scaled, windowed copies of x and the complex spectrum with its magnitude
    n_fft = x.shape[0] * zero_pad
    check_allocation(32 * x.shape[0] + 24 * (n_fft // 2 + 1),
                     parameter="x" if zero_pad == 1 else "x and zero_pad",
                     what=f"the spectrum of {n_fft} points")
    check_bool("remove_mean", remove_mean)
    check_bool("transient", transient)
    nyquist = fs / 2.0
    low = fs / x.shape[0] if fmin is None else check_nonnegative("fmin", fmin)
    fmax = nyquist if fmax is None else check_nonnegative("fmax", fmax)
    if not low < fmax <= nyquist:
        raise ValueError(
            f"fmin and fmax must satisfy 0 <= fmin < fmax <= fs/2 = {nyquist:g} Hz, "
            f"got fmin={low:g}, fmax={fmax:g}"
        )
    return x, fs, zero_pad, None if fmin is None else low, fmax


def windowed_spectrum(x, fs, window, zero_pad, fmin, fmax, remove_mean, transient=False):
    """Spectrum the peak is read from: the mean removed, the window applied, the real FFT.

    The textbook steps, behind a numerical guard: ``x`` is first scaled by a power of two
    (exact) so that the FFT's sums cannot overflow near 1e308. With ``transient=True`` a short
    transient is analysed on its own part of the record (see the notes of
    :func:`dominant_frequency`). Checks its arguments as :func:`dominant_frequency` does.

    Returns
    -------
    spectrum : ndarray of complex
        ``rfft(w * (x - mean), n_fft)`` of the analysed part, in the (scaled) unit of ``x``.
    part : AnalysedPart
        The analysed samples, their number ``n``, the padding and the bins of the search band.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal.spectral import windowed_spectrum
    >>> x = 3.0 + np.sin(2 * np.pi * 10 * np.arange(100) / 100.0)  # 10 Hz, 1 s at 100 Hz
    >>> spectrum, part = windowed_spectrum(x, 100.0, "rectangular", 1, None, 50.0, True)
    >>> int(np.argmax(np.abs(spectrum))), part.lo, part.hi  # 1 Hz bins; DC left out
    (10, 1, 50)
    """
    x, fs, zero_pad, fmin, fmax = _checked_spectrum(x, fs, window, zero_pad, fmin, fmax,
                                                    remove_mean, transient)
    return _windowed_spectrum(x, fs, window, zero_pad, fmin, fmax, remove_mean, transient)


def _windowed_spectrum(x, fs, window, zero_pad, fmin, fmax, remove_mean, transient):
    """:func:`windowed_spectrum` of checked arguments (as :func:`_checked_spectrum` returns)."""
    x, _ = unit_scaled(x)
    part = analysed_part(x, fs, zero_pad, fmin, fmax, transient)
    y = x[part.samples]
    if remove_mean:
        # a transient's baseline is the level outside it, the median of the whole record (its
        # own mean would leave a step)
        y = y - (np.median(x) if part.is_transient else y.mean())
    return np.fft.rfft(y * _window_weights(window, part.n), n=part.n_fft), part


def window_weights(window: str, n: int) -> np.ndarray:
    """Weights of the periodic ``window`` over ``n`` samples (the form for spectral analysis).

    Examples
    --------
    >>> from ebantenna.signal.spectral import window_weights
    >>> window_weights("hann", 4)  # (1 - cos(2 pi k / 4)) / 2
    array([0. , 0.5, 1. , 0.5])
    """
    check_choice("window", window, WINDOWS)
    n = check_int("n", n, minimum=1)
    check_allocation(8 * n, parameter="n", what="the window's weights")
    return _window_weights(window, n)


def _window_weights(window: str, n: int) -> np.ndarray:
    """:func:`window_weights` of a known window and a checked ``n``."""
    return np.ones(n) if window == "rectangular" else get_window(window, n, fftbins=True)


def strongest_bin(magnitude: np.ndarray, lo: int, hi: int) -> int:
    """Index of the largest of ``magnitude[lo : hi + 1]`` (the first one of equal values).

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal.spectral import strongest_bin
    >>> strongest_bin(np.array([9.0, 1.0, 4.0, 2.0]), 1, 3)  # the search band leaves out bin 0
    2
    """
    magnitude, lo, hi = _band_of(magnitude, lo, hi)
    return _strongest_bin(magnitude, lo, hi)


def _strongest_bin(magnitude: np.ndarray, lo: int, hi: int) -> int:
    """:func:`strongest_bin` of checked arguments."""
    return lo + int(np.argmax(magnitude[lo : hi + 1]))


def interpolated_frequency(spectrum, k, fs, n, method, window, zero_pad) -> float:
    """Frequency (Hz) of the peak at bin ``k`` of the spectrum of ``n`` samples, padded.

    ``method="bin"`` gives the bin's own frequency ``k fs / (n zero_pad)``; ``"parabolic"`` and
    ``"jacobsen"`` move it by the offset of :func:`parabolic_offset` or :func:`jacobsen_offset`.
    At the ends of the spectrum, where a neighbour is missing, the bin's frequency is returned.
    ``spectrum`` is finite and 1-D, complex for ``"jacobsen"`` (which reads the phases); ``k``
    is one of its bins; ``fs`` > 0; ``n`` and ``zero_pad`` >= 1.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal.spectral import interpolated_frequency
    >>> n = 64
    >>> x = np.sin(2 * np.pi * 10.25 * np.arange(n) / n)  # 10.25 cycles: between bins 10 and 11
    >>> spectrum = np.fft.rfft(x * np.hanning(n + 1)[:-1])
    >>> round(interpolated_frequency(spectrum, 10, 64.0, n, "jacobsen", "hann", 1), 6)
    10.25
    """
    _check_method_window(method, window)
    spectrum = _spectrum_of("spectrum", spectrum, phases=method == "jacobsen")
    k = check_int("k", k, minimum=0, maximum=spectrum.shape[0] - 1)
    fs = check_fs(fs)
    n = check_int("n", n, minimum=1)
    zero_pad = check_int("zero_pad", zero_pad, minimum=1)
    return _interpolated_frequency(spectrum, k, fs, n, method, window, zero_pad)


def _interpolated_frequency(spectrum, k, fs, n, method, window, zero_pad) -> float:
    """:func:`interpolated_frequency` of checked arguments."""
    df = fs / (n * zero_pad)
    # Jacobsen's neighbours are one unpadded bin (zero_pad padded bins) away on either side: the
    # derivation holds about any reference frequency, so it is exact on a padded grid too.
    step = zero_pad if method == "jacobsen" else 1
    if method == "bin" or k - step < 0 or k + step > spectrum.shape[0] - 1:
        return float(k * df)
    if method == "parabolic":
        return float((k + _parabolic_offset(spectrum, k)) * df)
    return float(k * df + _jacobsen_offset(spectrum, k, step, window) * fs / n)


def parabolic_offset(spectrum: np.ndarray, k: int) -> float:
    """Offset (bins) of the vertex of the parabola through the log-magnitudes at ``k - 1 .. k + 1``.

    ``delta = (L[k-1] - L[k+1]) / (2 (L[k-1] - 2 L[k] + L[k+1]))`` with ``L = log |X|``: exact
    for a Gaussian-shaped peak. Guards: a zero magnitude is read as the smallest normal float
    (its log is finite), a flat top gives 0, and the offset is clipped to one bin. ``spectrum``
    (complex or a magnitude) is finite and 1-D.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal.spectral import parabolic_offset
    >>> bins = np.arange(5.0)
    >>> round(parabolic_offset(np.exp(-((bins - 2.3) ** 2)), 2), 12)  # a Gaussian peak at 2.3
    0.3
    """
    spectrum = _spectrum_of("spectrum", spectrum, min_length=3)
    k = check_int("k", k, minimum=1, maximum=spectrum.shape[0] - 2)  # both neighbours
    return _parabolic_offset(spectrum, k)


def _parabolic_offset(spectrum: np.ndarray, k: int) -> float:
    """:func:`parabolic_offset` of checked arguments."""
    lm = np.log(np.maximum(np.abs(spectrum[k - 1 : k + 2]), np.finfo(float).tiny))
    curvature = lm[0] - 2.0 * lm[1] + lm[2]
    delta = 0.0 if curvature == 0.0 else 0.5 * (lm[0] - lm[2]) / curvature
    return float(np.clip(delta, -1.0, 1.0))


def jacobsen_offset(spectrum: np.ndarray, k: int, step: int, window: str) -> float:
    """Offset (unpadded bins) of Jacobsen and Kootsookos' complex-ratio estimator at bin ``k``.

    ``delta = P Re[(X[k-s] - X[k+s]) / (2 X[k] - X[k-s] - X[k+s])]`` with the neighbours ``s =
    step`` padded bins away, ``P = 2`` for the Hann window and ``P = 1`` for the rectangular one.
    Guards: a zero denominator gives 0, and the offset is clipped to one bin. ``spectrum`` is
    complex (the estimator reads its phases), finite and 1-D; ``window`` is one of these two.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal.spectral import jacobsen_offset
    >>> n = 1000
    >>> tone = np.exp(2j * np.pi * 50.4 * np.arange(n) / n)  # one complex tone, 50.4 cycles
    >>> spectrum = np.fft.fft(tone * np.hanning(n + 1)[:-1])
    >>> round(jacobsen_offset(spectrum, 50, 1, "hann"), 9)  # Hann: exact as n grows
    0.4
    """
    check_choice("window", window, ("hann", "rectangular"))
    spectrum = _spectrum_of("spectrum", spectrum, min_length=3, phases=True)
    k = check_int("k", k, minimum=0, maximum=spectrum.shape[0] - 1)
    step = check_int("step", step, minimum=1)
    if k - step < 0 or k + step > spectrum.shape[0] - 1:
        raise ValueError(f"k must be at least step = {step} bins from either end of the "
                         f"spectrum ({spectrum.shape[0]} bins), got {k}")
    return _jacobsen_offset(spectrum, k, step, window)


def _jacobsen_offset(spectrum: np.ndarray, k: int, step: int, window: str) -> float:
    """:func:`jacobsen_offset` of checked arguments."""
    a, b, c = spectrum[k - step], spectrum[k], spectrum[k + step]
    scale = 2.0 if window == "hann" else 1.0
    denominator = 2.0 * b - a - c
    delta = 0.0 if denominator == 0 else scale * float(np.real((a - c) / denominator))
    return float(np.clip(delta, -1.0, 1.0))


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
    transient: bool = False,
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
    method, window, fmin, fmax, remove_mean, transient
        As for :func:`dominant_frequency`.
    min_separation : float, optional
        Smallest distance between two reported peaks, Hz; default four bins, ``4 fs / n``
        (the main lobe of the Hann window is four bins wide).

    Returns
    -------
    ndarray of shape (n_peaks,)
        Peak frequencies in ascending order, Hz, each within the search band (as for
        :func:`dominant_frequency`).

    Raises
    ------
    ValueError
        When the band holds fewer than ``n_peaks`` separated local maxima of non-zero
        magnitude, and for the bad inputs of :func:`dominant_frequency`. There is no threshold
        on a peak's strength: a local maximum of rounding noise counts (a pure 50 Hz sine of one
        second at 1 kHz asked for three peaks gives a second and a third near 290 dB below it).

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
    x, fs, _, fmin, fmax = _checked_arguments(x, fs, method, window, 1, fmin, fmax, remove_mean,
                                              transient)
    if min_separation is not None:
        min_separation = check_positive("min_separation", min_separation)
    # the steps, checked above once: their unchecked cores
    spectrum, part = _windowed_spectrum(x, fs, window, 1, fmin, fmax, remove_mean, transient)
    separation = 4.0 * fs / part.n if min_separation is None else min_separation
    magnitude = np.abs(spectrum)
    candidates = _local_maxima(magnitude, part.lo, part.hi)
    chosen = _strongest_separated(magnitude, candidates, n_peaks, separation, fs / part.n_fft)
    if len(chosen) < n_peaks:
        raise ValueError(
            f"x holds only {len(chosen)} spectral peak(s) at least {separation:g} Hz apart in the "
            f"search band; n_peaks={n_peaks} requested"
        )
    freqs = [part.in_band(_interpolated_frequency(spectrum, k, fs, part.n, method, window,
                                                  part.zero_pad)) for k in chosen]
    return np.sort(np.array(freqs))


def _spectrum_of(name: str, spectrum, min_length: int = 1, phases: bool = False) -> np.ndarray:
    """``spectrum`` as a finite 1-D array, complex (an FFT) or, unless the ``phases`` are needed,
    real (a magnitude), else an error naming ``name``."""
    if isinstance(spectrum, np.ma.MaskedArray):
        return check_array(name, spectrum)  # refused, saying why
    try:
        is_complex = np.iscomplexobj(spectrum)
    except (TypeError, ValueError):  # a ragged list: check_array says what is wrong
        is_complex = False
    if not is_complex and phases:
        kind = getattr(spectrum, "dtype", type(spectrum).__name__)
        raise TypeError(f"{name} must be a complex spectrum (the estimator reads its phases), "
                        f"got {kind}")
    if not is_complex:
        return check_array(name, spectrum, ndim=1, min_length=min_length)
    spectrum = np.asarray(spectrum, dtype=np.complex128)
    check_array(name, spectrum.real, ndim=1, min_length=min_length)
    if not np.all(np.isfinite(spectrum.imag)):
        raise ValueError(f"{name} must contain only finite values (no NaN or inf)")
    return spectrum


def _magnitude_of(magnitude) -> np.ndarray:
    """``magnitude`` as a finite 1-D float array of values >= 0, else an error naming it."""
    magnitude = check_array("magnitude", magnitude, ndim=1)
    if np.any(magnitude < 0):
        raise ValueError("magnitude must be a magnitude spectrum (values >= 0)")
    return magnitude


def _band_of(magnitude, lo, hi) -> tuple[np.ndarray, int, int]:
    """``(magnitude, lo, hi)`` if ``magnitude`` is a magnitude spectrum and ``lo <= hi`` are
    bins of it, else an error."""
    magnitude = _magnitude_of(magnitude)
    size = magnitude.shape[0]
    lo = check_int("lo", lo, minimum=0, maximum=size - 1)
    return magnitude, lo, check_int("hi", hi, minimum=lo, maximum=size - 1)


def local_maxima(magnitude: np.ndarray, lo: int, hi: int) -> np.ndarray:
    """Bins strictly inside ``[lo, hi]`` above their left and not below their right neighbour.

    A plateau counts once, at its left end. Returned strongest first (by ``magnitude``).

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal.spectral import local_maxima
    >>> local_maxima(np.array([0.0, 3.0, 1.0, 5.0, 5.0, 2.0]), 0, 5)
    array([3, 1])
    """
    magnitude, lo, hi = _band_of(magnitude, lo, hi)
    return _local_maxima(magnitude, lo, hi)


def _local_maxima(magnitude: np.ndarray, lo: int, hi: int) -> np.ndarray:
    """:func:`local_maxima` of checked arguments."""
    band = magnitude[lo : hi + 1]
    inner = (band[1:-1] > band[:-2]) & (band[1:-1] >= band[2:])
    candidates = lo + 1 + np.flatnonzero(inner)
    return candidates[np.argsort(magnitude[candidates])[::-1]]


def strongest_separated(magnitude, candidates, n_peaks: int, separation: float,
                        df: float) -> list[int]:
    """The first ``n_peaks`` of ``candidates`` (strongest first) at least ``separation`` Hz apart.

    Greedy: a candidate is taken when its magnitude is not zero (however small: rounding noise
    counts) and it lies ``separation`` Hz (``df`` Hz a bin) or more from every peak taken before
    it. May return fewer than ``n_peaks``.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal.spectral import strongest_separated
    >>> magnitude = np.array([0.0, 5.0, 4.0, 0.0, 3.0])
    >>> strongest_separated(magnitude, np.array([1, 2, 4]), 2, 2.0, 1.0)  # bin 2 is too close
    [1, 4]
    """
    magnitude = _magnitude_of(magnitude)
    candidates = np.asarray(candidates)
    if candidates.ndim != 1 or (candidates.size and candidates.dtype.kind not in "iu"):
        raise TypeError(f"candidates must be a 1-D array of bin indices, got "
                        f"{candidates.dtype} of shape {candidates.shape}")
    if candidates.size and (candidates.min() < 0 or candidates.max() >= magnitude.size):
        raise ValueError(f"candidates must be bins of magnitude (0 to {magnitude.size - 1})")
    n_peaks = check_int("n_peaks", n_peaks, minimum=1)
    separation = check_positive("separation", separation)
    df = check_positive("df", df)
    return _strongest_separated(magnitude, candidates, n_peaks, separation, df)


def _strongest_separated(magnitude, candidates, n_peaks, separation, df) -> list[int]:
    """:func:`strongest_separated` of checked arguments."""
    chosen: list[int] = []
    for k in candidates:
        if magnitude[k] > 0.0 and all(abs(k - j) * df >= separation for j in chosen):
            chosen.append(int(k))
            if len(chosen) == n_peaks:
                break
    return chosen
