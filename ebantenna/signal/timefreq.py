"""Time-frequency views: the short-time FFT (spectrogram) and the Morlet wavelet scalogram.

Section 4.4 of the paper reads the mode changes of the probe from spectrograms and wavelet plots:
near the hinge one frequency lasts through the record, beyond about 80 % of the length several modes
start together and die quickly. Both views are written here with NumPy FFTs.

Spectrogram
    Frames of ``nperseg`` samples, ``hop = nperseg - noverlap`` apart, each windowed and
    transformed.
    Amplitude scaling: ``2 |X| / sum(w)``, so a steady sinusoid of amplitude ``A`` on a bin gives a
    ridge of height ``A``; between two bins the ridge is lower, down to 0.85 ``A`` (Hann) or
    0.64 ``A`` (rectangular, about 2/pi) half a bin off. Resolution is fixed: ``fs / nperseg`` in
    frequency, ``nperseg / fs`` in time.

Morlet scalogram
    The continuous wavelet transform with the complex Morlet wavelet of PyWavelets' ``cmorB-C``
    family, ``psi(t) = (pi B)^(-1/2) exp(-t^2 / B) exp(2 pi i C t)``:
    ``W(a, b) = a^(-1/2) sum_n x[n] conj(psi((n - b) / a))`` with the scale ``a = C fs / f``
    (samples) for the frequency ``f`` (Hz). It is computed in the frequency domain, where the
    wavelet is the Gaussian ``Psi(nu) = exp(-pi^2 B (nu - C)^2)`` summed over its aliases
    ``nu + k`` (the spectrum of the sampled wavelet, which matters near ``fs / 2``), on a
    zero-padded FFT so that the record does not wrap around. Its time resolution improves as the
    frequency grows (``a sqrt(B)`` samples), which is what makes short-lived high modes visible.
    PyWavelets integrates the wavelet and differentiates the result instead; its coefficients
    equal these times ``sinc(f / fs)`` (an average over one sample) and a half-sample shift.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.signal import get_window

from .._budget import check_allocation
from .._validate import check_array, check_choice, check_int, check_positive, describe
from ._checks import MAX_FFT, check_fs, check_signal
from .spectral import WINDOWS

__all__ = ["TimeFrequency", "spectrogram", "morlet_scalogram"]


@dataclass(frozen=True, eq=False)
class TimeFrequency:
    """A time-frequency map.

    Attributes
    ----------
    t : ndarray of shape (n_times,)
        Time of each column, s (frame centres for a spectrogram, samples for a scalogram).
    f : ndarray of shape (n_freqs,)
        Frequency of each row, Hz.
    values : ndarray of shape (n_freqs, n_times)
        Amplitudes (spectrogram, real, unit of the signal) or wavelet coefficients (complex).
    kind : str
        ``"spectrogram"`` or ``"scalogram"``.
    """

    t: np.ndarray
    f: np.ndarray
    values: np.ndarray
    kind: str

    @property
    def magnitude(self) -> np.ndarray:
        """``|values|``."""
        return np.abs(self.values)

    def ridge(self) -> np.ndarray:
        """Frequency of the largest magnitude in each column, Hz, shape ``(n_times,)``."""
        return self.f[np.argmax(self.magnitude, axis=0)]

    def plot(self, ax=None, *, db: bool = True, dynamic_range: float = 60.0):
        """Draw the map; returns the matplotlib Figure.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Where to draw; a new figure is made if omitted.
        db : bool
            Colour by ``20 log10`` of the magnitude (clipped ``dynamic_range`` dB below its peak).
        dynamic_range : float
            Shown range, dB.
        """
        import matplotlib.pyplot as plt

        check_positive("dynamic_range", dynamic_range)
        from .._validate import check_bool

        db = check_bool("db", db)
        if ax is None:
            fig, ax = plt.subplots(figsize=(6.0, 3.5))
        else:
            from matplotlib.axes import Axes

            if not isinstance(ax, Axes):
                raise TypeError(f"ax must be matplotlib Axes or None, got {type(ax).__name__}")
            fig = ax.figure
        mag = self.magnitude
        if db:
            peak = mag.max() if mag.max() > 0 else 1.0
            mag = 20.0 * np.log10(np.maximum(mag / peak, 10.0 ** (-dynamic_range / 20.0)))
        mesh = ax.pcolormesh(self.t, self.f, mag, shading="nearest")
        fig.colorbar(mesh, ax=ax, label="dB re peak" if db else "magnitude")
        ax.set_xlabel("time (s)")
        ax.set_ylabel("frequency (Hz)")
        ax.set_title(self.kind)
        return fig


def spectrogram(x, fs, *, nperseg: int = 64, noverlap: int | None = None,
                window: str = "hann", n_fft: int | None = None) -> TimeFrequency:
    """Short-time FFT amplitude of ``x``.

    Parameters
    ----------
    x : array of shape (n,)
        Signal, at least ``nperseg`` samples.
    fs : float
        Sampling frequency, Hz.
    nperseg : int
        Frame length, samples (>= 4).
    noverlap : int, optional
        Overlap of consecutive frames, samples (default ``nperseg // 2``;
        ``0 <= noverlap < nperseg``).
    window : {"hann", "rectangular", "blackman", "hamming"}
        Frame window.
    n_fft : int, optional
        FFT length per frame (>= ``nperseg``; zero padding), default ``nperseg``.

    Returns
    -------
    TimeFrequency
        ``values`` of shape ``(n_fft // 2 + 1, n_frames)``: one-sided amplitudes, unit of ``x``;
        ``t`` the frame centres, s. Only whole frames are transformed, ``n_frames = 1 + (n -
        nperseg) // hop``: the last ``(n - nperseg) % hop`` samples, after the last whole frame,
        are not in any frame (8 of 1000 at the defaults' 64-sample frames and 32-sample hop).

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal import spectrogram
    >>> t = np.arange(1000) / 1000.0
    >>> tf = spectrogram(2.0 * np.sin(2 * np.pi * 125 * t), 1000.0, nperseg=64)
    >>> tf.values.shape, float(tf.f[np.argmax(tf.values[:, 5])]), round(float(tf.values.max()), 3)
    ((33, 30), 125.0, 2.0)
    """
    fs = check_fs(fs)
    x = check_signal("x", x, min_length=4)
    nperseg = check_int("nperseg", nperseg, minimum=4)
    if nperseg > x.shape[0]:
        raise ValueError(f"nperseg ({describe(nperseg)}) must not exceed the length of x "
                         f"({x.shape[0]} samples)")
    noverlap = nperseg // 2 if noverlap is None else check_int(
        "noverlap", noverlap, minimum=0, maximum=nperseg - 1)
    check_choice("window", window, WINDOWS)
    if n_fft is None:
        n_fft = nperseg
    n_fft = check_int("n_fft", n_fft, minimum=nperseg, maximum=MAX_FFT)
    w = np.ones(nperseg) if window == "rectangular" else get_window(window, nperseg, fftbins=True)
    hop = nperseg - noverlap
    n_frames = 1 + (x.shape[0] - nperseg) // hop
    # frames (and their windowed copy), then the complex spectrum and its amplitude
    check_allocation(n_frames * (16 * nperseg + 24 * (n_fft // 2 + 1)), parameter="n_fft",
                     what=f"a spectrogram of {n_frames} frames of {n_fft} points")
    starts = hop * np.arange(n_frames)
    frames = x[starts[:, None] + np.arange(nperseg)[None, :]]
    spectrum = np.abs(np.fft.rfft(frames * w, n=n_fft, axis=1)).T
    scale = np.full(spectrum.shape[0], 2.0 / w.sum())
    scale[0] /= 2.0
    if n_fft % 2 == 0:
        scale[-1] /= 2.0
    t = (starts + nperseg / 2.0) / fs
    return TimeFrequency(t, np.fft.rfftfreq(n_fft, d=1.0 / fs), scale[:, None] * spectrum,
                         "spectrogram")


#: The longest wavelet, in samples, that :func:`morlet_scalogram` pads for: its FFTs of twice that
#: many complex points take 256 MB, and a wavelet much longer than any record says nothing more.
MAX_WAVELET_SAMPLES = 2**23


def morlet_scalogram(x, fs, frequencies, *, bandwidth: float = 1.5,
                     center: float = 1.0) -> TimeFrequency:
    """Continuous wavelet transform of ``x`` with the complex Morlet wavelet ``cmorB-C``.

    Parameters
    ----------
    x : array of shape (n,)
        Signal.
    fs : float
        Sampling frequency, Hz.
    frequencies : array of shape (n_freqs,)
        Analysis frequencies, Hz, in ``(0, fs/2]``.
    bandwidth : float
        ``B`` of the wavelet (larger: finer in frequency, coarser in time).
    center : float
        ``C``, the wavelet's centre frequency in cycles per unit of scale.

    Returns
    -------
    TimeFrequency
        Complex coefficients of shape ``(n_freqs, n)``, ``t = arange(n) / fs``. A steady tone of
        amplitude ``A`` at an analysis frequency well below ``fs / 2`` gives
        ``|W| = A sqrt(a) / 2`` in the interior, with ``a = C fs / f`` the scale (the
        ``a^(-1/2)`` normalisation keeps the energy per scale); towards ``fs / 2`` the tone's
        mirror image at ``fs - f`` enters through the sampled wavelet's spectrum with the gain
        ``g = exp(-pi^2 B C^2 (fs / f - 2)^2)``, and beats with the tone: ``|W|`` swings between
        ``(1 - g)`` and ``(1 + g)`` times ``A sqrt(a) / 2`` (defaults, 1 kHz: ``g < 1e-11`` up to
        300 Hz, 0.025 at 400 Hz, 0.48 at 450 Hz).

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal import morlet_scalogram
    >>> t = np.arange(1000) / 1000.0
    >>> tf = morlet_scalogram(np.sin(2 * np.pi * 100 * t), 1000.0, [50.0, 100.0, 200.0])
    >>> np.round(np.abs(tf.values[:, 500]) / np.sqrt(1000.0 / tf.f) * 2, 3)
    array([0.   , 1.   , 0.025])
    """
    fs = check_fs(fs)
    x = check_signal("x", x, min_length=2)
    freqs = check_array("frequencies", frequencies, ndim=1)
    if np.any(freqs <= 0) or np.any(freqs > fs / 2.0):
        raise ValueError(
            f"frequencies must lie in (0, fs/2 = {fs / 2.0:g}] Hz, got [{freqs.min():g}, "
            f"{freqs.max():g}]"
        )
    bandwidth = check_positive("bandwidth", bandwidth)
    center = check_positive("center", center)
    n = x.shape[0]
    scales = center * fs / freqs
    # The Gaussian envelope exp(-t^2/B) is below 1e-15 beyond 6 sqrt(B) scale units.
    span = 6.0 * np.sqrt(bandwidth) * scales.max()
    if not span <= MAX_WAVELET_SAMPLES:
        raise ValueError(
            f"bandwidth={bandwidth:g} and center={center:g} make the wavelet at "
            f"{freqs.min():g} Hz {span:.3g} samples long (6 sqrt(B) C fs / f), more than "
            f"{MAX_WAVELET_SAMPLES}; lower bandwidth or center, or raise the lowest frequency"
        )
    pad = int(np.ceil(span))
    n_fft = 1 << int(np.ceil(np.log2(n + pad)))
    # The result (16 bytes a value) and, per frequency, 7 aliases of the FFT grid and two spectra.
    check_allocation(16 * freqs.shape[0] * n + 16 * 9 * n_fft, parameter="frequencies",
                     what=f"a scalogram of {freqs.shape[0]} frequencies by {n} samples")
    spectrum = np.fft.fft(x, n_fft)
    nu = np.fft.fftfreq(n_fft)
    out = np.empty((freqs.shape[0], n), dtype=complex)
    # The sampled wavelet's spectrum is the continuous one summed over its aliases (Poisson
    # summation); with the aliases the FFT result equals the defining sum over samples.
    aliases = np.arange(-3, 4)[:, None]
    for i, a in enumerate(scales):
        psi_hat = np.exp(-(np.pi**2) * bandwidth * (a * (nu + aliases) - center) ** 2).sum(axis=0)
        out[i] = np.fft.ifft(spectrum * np.sqrt(a) * psi_hat)[:n]
    return TimeFrequency(np.arange(n) / fs, freqs.copy(), out, "scalogram")
