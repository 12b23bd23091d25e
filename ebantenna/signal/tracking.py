"""Adaptive band-pass frequency tracking: the filter that section 4.4 of the paper proposes.

Beyond about 80 % of the probe length several modes ring together and the strongest one changes as
they decay at different rates, so one FFT over the record gives no single meaningful dominant
frequency. The paper suggests "an adaptive band pass frequency tracking filter". This module builds
one: a constrained adaptive notch filter (A. Nehorai, "A minimal parameter adaptive notch filter
with constrained poles and zeros", *IEEE Trans. ASSP* 33(4), 1985), whose complement is a narrow
band-pass centred on the tracked frequency.

Model. With ``a = -2 cos(w)`` (``w = 2 pi f / fs``) and pole radius ``rho < 1``::

    notch     H(z) = (1 + a z^-1 + z^-2) / (1 + rho a z^-1 + rho^2 z^-2)
    band-pass B(z) = 1 - H(z)      (unit gain at f, -3 dB bandwidth about (1 - rho) fs / pi Hz)

The input is filtered by the all-pole part, ``s[n] = x[n] - rho a s[n-1] - rho^2 s[n-2]``, the notch
output is ``e[n] = s[n] + a s[n-1] + s[n-2]``, and ``a`` follows a normalised gradient step that
lowers ``e^2`` (the notch power is least when the notch sits on the strongest sinusoid)::

    r[n] = lam r[n-1] + s[n-1]^2,     a <- a - mu e[n] s[n-1] / r[n]

So the filter locks on the strongest component and follows it as it drifts. When a mode dies and
another takes over, the band-pass output falls while the input does not: with ``reacquire=True``
the tracker checks, block by block, the share of the input power that passes its band and, when it
drops below ``reacquire_ratio``, restarts from the dominant frequency of that block. After the start
and after every restart the coefficient is held for ``3 / (1 - rho)`` samples while the band-pass
settles, and no block is judged before it has settled.

Lock gate. After a decay the record holds only noise, and an adaptive filter left running would
follow it (and a restart would jump to the noise's strongest bin). Each block is therefore judged
against the noise floor, the power of the quietest block: a block more than ``lock_snr`` times
above it is *locked* (the filter adapts and may restart); below, the tracker is *unlocked* and
holds its last frequency. A record whose loudest block is not ``lock_snr`` times above its
quietest has no quiet part (a steady tone, a slow decay) and is locked throughout.
:meth:`TrackingResult.final_frequency` reads only locked samples.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import check_in_range, check_int, check_positive, describe
from ._checks import check_fs, check_signal
from ._guards import unit_scaled
from .spectral import dominant_frequency

__all__ = ["TrackingResult", "FrequencyTracker"]


@dataclass(frozen=True, eq=False)
class TrackingResult:
    """Output of :meth:`FrequencyTracker.track`.

    Attributes
    ----------
    t : ndarray of shape (n,)
        Sample times, s.
    frequency : ndarray of shape (n,)
        Tracked instantaneous frequency, Hz.
    bandpass : ndarray of shape (n,)
        The tracked component (band-pass output), unit of the input.
    reacquired : ndarray of int
        Sample indices where the tracker restarted on a new dominant frequency.
    locked : ndarray of bool, shape (n,)
        True where the input stood above the noise floor and the tracker followed it (see the
        module notes on the lock gate).
    """

    t: np.ndarray
    frequency: np.ndarray
    bandpass: np.ndarray
    reacquired: np.ndarray
    locked: np.ndarray

    def final_frequency(self, fraction: float = 0.25) -> float:
        """Median tracked frequency over the last ``fraction`` of the locked samples, Hz.

        Raises
        ------
        ValueError
            If no sample is locked (the record holds nothing above its noise floor).
        """
        fraction = check_in_range("fraction", fraction, 0.0, 1.0, high_inclusive=True)
        followed = self.frequency[self.locked]
        if followed.size == 0:
            raise ValueError("the tracker never locked: no block stood above the noise floor")
        k = max(1, int(round(fraction * followed.shape[0])))
        return float(np.median(followed[-k:]))


@dataclass(frozen=True)
class FrequencyTracker:
    """Adaptive notch / band-pass filter that tracks the strongest sinusoid.

    Parameters
    ----------
    fs : float
        Sampling frequency, Hz.
    pole_radius : float
        ``rho`` in (0, 1): closer to 1 gives a narrower band (about ``(1 - rho) fs / pi`` Hz) and
        slower, smoother tracking. Default 0.95 (about 16 Hz at 1 kHz). The coefficient is held
        for the first ``3 / (1 - rho)`` samples while the filter settles.
    forgetting : float
        ``lam`` in (0, 1]: memory of the step normalisation, about ``1 / (1 - lam)`` samples.
    step : float
        ``mu`` in (0, 1]: fraction of the normalised gradient step taken.
    fmin, fmax : float
        Range the tracked frequency is kept in, Hz; default 1 Hz to ``0.49 fs``.
    reacquire : bool
        Restart on the block's dominant frequency when the tracked band has lost the signal.
    block : int
        Block length for the reacquisition check, samples.
    reacquire_ratio : float
        Restart when the band-pass output holds less than this share of the block's input power.
    lock_snr : float
        Power ratio over the noise floor (the quietest block) above which a block is locked
        (>= 1; default 10, i.e. 10 dB). See the module notes.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal import FrequencyTracker
    >>> t = np.arange(1000) / 1000.0
    >>> x = np.sin(2 * np.pi * (80 * t + 20 * t**2))  # a chirp from 80 Hz to 120 Hz
    >>> res = FrequencyTracker(1000.0).track(x)
    >>> round(float(res.frequency[-1]), 1)  # 120 Hz at the end; the tracker lags by about 1 Hz
    119.2
    """

    fs: float
    pole_radius: float = 0.95
    forgetting: float = 0.95
    step: float = 1.0
    fmin: float | None = None
    fmax: float | None = None
    reacquire: bool = True
    block: int = 50
    reacquire_ratio: float = 0.3
    lock_snr: float = 10.0

    def __post_init__(self):
        fs = check_fs(self.fs)
        object.__setattr__(self, "fs", fs)
        check_in_range("pole_radius", self.pole_radius, 0.0, 1.0)
        check_in_range("forgetting", self.forgetting, 0.0, 1.0, high_inclusive=True)
        check_in_range("step", self.step, 0.0, 1.0, high_inclusive=True)
        fmin = 1.0 if self.fmin is None else check_positive("fmin", self.fmin)
        fmax = 0.49 * fs if self.fmax is None else check_positive("fmax", self.fmax)
        if not fmin < fmax < fs / 2.0:
            raise ValueError(
                f"fmin and fmax must satisfy 0 < fmin < fmax < fs/2 = {fs / 2.0:g} Hz, "
                f"got fmin={fmin:g}, fmax={fmax:g}"
            )
        object.__setattr__(self, "fmin", fmin)
        object.__setattr__(self, "fmax", fmax)
        if not isinstance(self.reacquire, bool):
            raise TypeError(f"reacquire must be True or False, got {self.reacquire!r}")
        check_int("block", self.block, minimum=8)
        check_in_range("reacquire_ratio", self.reacquire_ratio, 0.0, 1.0)
        check_in_range("lock_snr", self.lock_snr, 1.0, 1e12, low_inclusive=True)

    @property
    def bandwidth(self) -> float:
        """Approximate -3 dB bandwidth of the band-pass, Hz: ``(1 - rho) fs / pi``."""
        return (1.0 - self.pole_radius) * self.fs / math.pi

    def _coefficient(self, f: float) -> float:
        f = min(max(f, self.fmin), self.fmax)
        return -2.0 * math.cos(2.0 * math.pi * f / self.fs)

    def track(self, x, f0: float | None = None) -> TrackingResult:
        """Track the strongest sinusoid of ``x`` sample by sample.

        Parameters
        ----------
        x : array of shape (n,)
            Signal (for instance the resultant acceleration), at least ``block`` samples, not
            constant. Its mean is removed first.
        f0 : float, optional
            Starting frequency, Hz; default the dominant frequency of the first four blocks from
            the first locked one.

        Returns
        -------
        TrackingResult
        """
        x = check_signal("x", x, min_length=8, allow_constant=False)
        if x.shape[0] < self.block:
            raise ValueError(
                f"block ({describe(self.block)} samples) must not exceed the length of x "
                f"({x.shape[0]} samples)"
            )
        # The adaptation is scale-free; a power-of-two scaling keeps x * x from overflowing
        # near 1e300 or underflowing near 1e-300, and is undone exactly on the band output.
        x, exponent = unit_scaled(x)
        x = x - x.mean()
        n = x.shape[0]
        locked = self._lock_gate(x)
        if f0 is None:
            # the first four blocks from where the signal starts (a record may begin quietly)
            first = int(np.argmax(locked))
            head = x[first : first + max(self.block, min(n, 4 * self.block))]
            f0 = dominant_frequency(head, self.fs, fmin=self.fmin, fmax=self.fmax)
        else:
            f0 = check_in_range("f0", f0, self.fmin, self.fmax, low_inclusive=True,
                                high_inclusive=True)
        rho, lam, mu = self.pole_radius, self.forgetting, self.step
        a_lo, a_hi = self._coefficient(self.fmin), self._coefficient(self.fmax)
        a = self._coefficient(f0)
        s1 = s2 = 0.0
        # The band-pass settles in about 1 / (1 - rho) samples: adapt only after three times that.
        warmup = int(math.ceil(3.0 / (1.0 - rho)))
        settle_until = warmup
        r = 0.0
        freq = np.empty(n)
        band = np.empty(n)
        restarts = []
        block_in = block_out = 0.0
        for k in range(n):
            s0 = x[k] - rho * a * s1 - rho * rho * s2
            e = s0 + a * s1 + s2
            band[k] = x[k] - e
            r = lam * r + s1 * s1
            if k >= settle_until and r > 0.0 and locked[k]:
                a = min(max(a - mu * e * s1 / r, a_lo), a_hi)
            s2, s1 = s1, s0
            freq[k] = math.acos(-a / 2.0) * self.fs / (2.0 * math.pi)
            if self.reacquire:
                block_in += x[k] * x[k]
                block_out += band[k] * band[k]
                if (k + 1) % self.block == 0:
                    settled = k + 1 - self.block >= settle_until
                    if (settled and locked[k] and block_in > 0.0
                            and block_out < self.reacquire_ratio * block_in):
                        seg = x[k + 1 - self.block : k + 1]
                        if np.ptp(seg) > 0.0:
                            f_new = dominant_frequency(seg, self.fs, fmin=self.fmin,
                                                       fmax=self.fmax)
                            a = self._coefficient(f_new)
                            settle_until = k + 1 + warmup
                            restarts.append(k + 1)
                    block_in = block_out = 0.0
        return TrackingResult(np.arange(n) / self.fs, freq, np.ldexp(band, exponent),
                              np.asarray(restarts, dtype=int), locked)

    def _lock_gate(self, x: np.ndarray) -> np.ndarray:
        """Per sample: does its block stand ``lock_snr`` above the quietest block's power?"""
        n = x.shape[0]
        starts = np.arange(0, n, self.block)
        power = np.add.reduceat(x * x, starts) / np.diff(np.append(starts, n))
        floor = float(power.min())
        if power.max() <= self.lock_snr * floor:
            return np.ones(n, dtype=bool)  # no quiet part: a steady or slowly decaying signal
        return np.repeat(power > self.lock_snr * floor, np.diff(np.append(starts, n)))
