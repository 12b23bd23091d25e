"""Numerical guards of the spectral peak and of the decay fit (private).

The textbook steps of :mod:`~ebantenna.signal.spectral` (remove the mean, window, rFFT, the
strongest bin, interpolate) and of :mod:`~ebantenna.signal.decay` (envelope, log-linear fit, the
checks) assume a signal of moderate size that fills its record and never saturates. The helpers
here keep those assumptions true; each one's first docstring line says what it guards against.

Every helper takes checked values (a finite 1-D float array, a positive ``fs``, a valid band):
the public functions validate their arguments once, before calling any of them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["unit_scaled", "transient_span", "loud_blocks", "AnalysedPart", "analysed_part",
           "search_bins", "clipped_mask", "DecayRegion", "decay_region"]


def unit_scaled(x: np.ndarray) -> tuple[np.ndarray, int]:
    """Scale by a power of two so that no sum overflows near 1e308 nor underflows near 1e-300.

    Returns ``(x * 2**-e, e)`` with ``e`` the binary exponent of ``max |x|``, so that the scaled
    largest magnitude lies in [0.5, 1). Multiplying by a power of two is exact (barring
    subnormals), so ``np.ldexp(scaled, e)`` gives ``x`` back bit for bit.
    """
    exponent = math.frexp(float(np.max(np.abs(x))))[1]
    return np.ldexp(x, -exponent), exponent


def transient_span(x: np.ndarray) -> slice | None:
    """Find a short transient, which a window over the whole record would weight by about zero.

    Returns the samples holding a short transient (a decay, a burst) in ``x``, or None. The record
    is cut into 64 blocks about the median of ``x`` (the baseline). A transient is the span from
    the first to the last block above both 30 times the quietest block (the noise floor: for
    white noise the quietest of 64 blocks of 15 or more samples holds about 0.4 times the mean
    block energy, and a block above 12 times the mean, a chi-squared tail of 15 degrees of
    freedom beyond 180, has a chance of about 1e-28 among 64 blocks) and 1e-6 of the
    strongest block (an amplitude 60 dB down, where a noise-free decay counts as over). It counts
    as short when it covers less than half the record, which a steady oscillation never does.
    """
    n = x.shape[0]
    size = max(4, n // 64)
    blocks = (x[: n - n % size] - np.median(x)).reshape(-1, size)
    energy = np.einsum("ij,ij->i", blocks, blocks)
    loud = loud_blocks(energy)
    # A slow steady tone has blocks near its zero crossings far quieter than those at its
    # peaks, enough to pass it off as a few short bursts; over runs of a quarter of the record,
    # each holding half a period of any tone above 2 fs / n, it stands out nowhere.
    if loud.size == 0:
        return None
    if loud_blocks(np.convolve(energy, np.ones(len(energy) // 4), "valid")).size == 0:
        return None
    start, stop = int(loud[0]) * size, (int(loud[-1]) + 1) * size
    return slice(start, stop) if 2 * (stop - start) < n else None


def loud_blocks(energy: np.ndarray) -> np.ndarray:
    """Tell signal from noise: the blocks above the floor of :func:`transient_span` (indices)."""
    return np.flatnonzero(energy > max(30.0 * energy.min(), 1e-6 * energy.max()))


@dataclass(frozen=True)
class AnalysedPart:
    """The samples a spectral peak is read from: the whole record, or a short transient in it.

    Attributes
    ----------
    samples : slice
        The samples analysed.
    n : int
        Their number.
    zero_pad : int
        FFT length as a multiple of ``n``; a transient is padded to the record's bin spacing.
    is_transient : bool
        True for a short transient: its baseline is the median of the whole record.
    lo, hi : int
        The first and last FFT bins of the search band.
    fmin, fmax : float
        The search band, Hz: the frequency returned lies in it.
    """

    samples: slice
    n: int
    zero_pad: int
    is_transient: bool
    lo: int
    hi: int
    fmin: float
    fmax: float

    @property
    def n_fft(self) -> int:
        """FFT length, ``n * zero_pad``."""
        return self.n * self.zero_pad

    def in_band(self, f: float) -> float:
        """``f`` moved to the nearer edge of the band when an interpolation put it beyond.

        The strongest bin lies in the band; an interpolated peak past an edge means that the
        interpolated spectrum grows up to that edge, where its largest value in the band is.
        """
        return float(min(max(f, self.fmin), self.fmax))


def analysed_part(x: np.ndarray, fs: float, zero_pad: int, fmin: float | None,
                  fmax: float, transient: bool = False) -> AnalysedPart:
    """Keep a short transient from vanishing under the window: analyse only the part holding it.

    With ``transient=False`` (the default of the public functions) the whole record is
    analysed, from ``fmin`` (None: one bin, ``fs / n``) up to ``fmax``. With ``transient=True``
    a short transient is looked for (:func:`transient_span`); when one is found only its samples
    are analysed, and the band starts at ``fmin`` or, for ``fmin=None``, two bins of the
    transient above 0 Hz, because below that the window's DC lobe holds what is left of the
    baseline. Takes checked values: ``fmin < fmax <= fs / 2`` for the whole record.

    Raises
    ------
    ValueError
        When the transient is too short for any frequency of the band, or the band holds no
        FFT bin.
    """
    n = x.shape[0]
    segment = transient_span(x) if transient else None
    if segment is None:
        fmin = fs / n if fmin is None else fmin
        part = slice(0, n)
    else:
        part = segment
        m = segment.stop - segment.start
        zero_pad *= -(-n // m)
        n = m
        if fmin is None:
            fmin = 2.0 * fs / m
            if not fmin < fmax:
                raise ValueError(
                    f"x is a transient of {m} samples: no frequency below its two-bin limit "
                    f"{fmin:g} Hz can be resolved; fmax={fmax:g}"
                )
    lo, hi = search_bins(fmin, fmax, fs / (n * zero_pad))
    return AnalysedPart(part, n, zero_pad, segment is not None, lo, hi, float(fmin), float(fmax))


def search_bins(fmin: float, fmax: float, df: float) -> tuple[int, int]:
    """Count a band edge that sits on a bin as inside, despite rounding: the bins of [fmin, fmax].

    A slack of 1e-9 bin on either side absorbs the rounding of ``fmin / df``; ``df`` is the bin
    width, Hz.

    Raises
    ------
    ValueError
        When the band holds no bin.
    """
    lo = int(np.ceil(fmin / df - 1e-9))
    hi = int(np.floor(fmax / df + 1e-9))
    if hi < lo:
        raise ValueError(f"the band [{fmin:g}, {fmax:g}] Hz holds no FFT bin (bin width {df:g} Hz)")
    return lo, hi


def clipped_mask(x: np.ndarray) -> np.ndarray:
    """Skip a saturated accelerometer: the samples in flat runs at the signal's maximum or minimum.

    A flat run is two or more neighbouring samples all within 1e-9 of the signal's range of its
    largest value, or all within it of its smallest: a sample at the maximum beside one at the
    minimum (a tone near the Nyquist frequency) is no run.
    """
    tol = 1e-9 * float(np.ptp(x))
    mask = np.zeros(x.shape, dtype=bool)
    for at_extreme in (x >= x.max() - tol, x <= x.min() + tol):
        run = at_extreme[1:] & at_extreme[:-1]
        mask[1:] |= run
        mask[:-1] |= run
    return mask


@dataclass(frozen=True)
class DecayRegion:
    """The envelope samples a decay is fitted to (see :func:`decay_region`).

    Attributes
    ----------
    first : int
        First sample after the last clipped one (0 when nothing is clipped).
    keep : ndarray of int
        Indices of the envelope samples to fit: from the start of the region up to where the
        envelope first sinks to ``floor_factor`` times the floor.
    end : int
        End (exclusive) of the window the damped-sinusoid witness is fitted to.
    too_short : bool
        The decay is over before two periods: ``keep`` is then every positive envelope sample
        of the region, to tell a decay too short to measure from no decay at all.
    whole : ndarray of int
        Every positive envelope sample of the region (edges and clipping left out), for a decay
        that has not reached the floor by the tail, whose tail is then the decay itself.
    floor : float
        The floor, the median envelope of the last tenth of the region.
    tail_start : int
        Index of the first sample of that last tenth.
    peak : float
        The largest envelope sample from ``first`` to the end of the region (the first period
        included: a decay may be over within it).
    tail_spread : float
        Standard deviation of the log envelope over the tail about its least-squares line: about
        ``sigma / D`` for a decay ``D`` under noise of standard deviation ``sigma`` per
        component, and ``pi / sqrt(24) = 0.64`` for a tail of noise (the log of a Rayleigh
        envelope).
    """

    first: int
    keep: np.ndarray
    end: int
    too_short: bool
    whole: np.ndarray
    floor: float
    tail_start: int
    peak: float
    tail_spread: float


def decay_region(env: np.ndarray, clipped: np.ndarray, period: float,
                 floor_factor: float) -> DecayRegion | None:
    """Fit the decay only where it stands out: edges, clipped samples and the noise tail left out.

    The first and last period are dropped (the Hilbert transform's edge effects), and so is
    everything up to the last clipped sample; the fit runs from there up to where the envelope
    first sinks to ``floor_factor`` times the floor (the median envelope of the last tenth of the
    region): later samples are noise, Hilbert leakage from the record's ends, or the offset left
    by removing the mean. Whether the tail is that, or the decay itself, is for the caller to
    decide (``_fitted_samples`` of :mod:`~ebantenna.signal.decay`). The cut is "too short" when
    it holds fewer than two periods. Takes checked values: ``period`` in samples,
    ``floor_factor >= 1``.

    Returns
    -------
    DecayRegion or None
        None when the record holds fewer than four periods or too few samples between its edges.
    """
    n = env.shape[0]
    edge = int(min(max(2, math.ceil(period)), n // 8))
    first = int(np.flatnonzero(clipped)[-1]) + 1 if clipped.any() else 0
    start = max(edge, first + edge)
    stop = n - edge
    if period > n / 4 or stop - start < 4:
        return None
    region = np.arange(start, stop)
    tail_start = int(region[-max(2, region.size // 10)])
    floor = float(np.median(env[tail_start:stop]))
    # half of the tail lies at or below its median, so the envelope sinks to the cut level
    below = np.flatnonzero(env[region] <= floor_factor * floor)
    keep = region[: below[0]]
    end = min(n, int(keep[-1]) + 1 + edge) if keep.size else start
    whole = region[env[region] > 0.0]
    too_short = keep.size < 2 * period
    return DecayRegion(first, whole if too_short else keep, end, bool(too_short), whole, floor,
                       tail_start, float(env[first:stop].max()), _log_spread(env[tail_start:stop]))


def _log_spread(tail: np.ndarray) -> float:
    """Tell a decaying tail from noise: the spread of ``log tail`` about its straight line."""
    if not np.all(tail > 0):
        return math.inf
    u = np.arange(tail.size, dtype=float)
    log_tail = np.log(tail)
    return float(np.std(log_tail - np.polyval(np.polyfit(u, log_tail, 1), u)))
