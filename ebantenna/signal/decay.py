"""Exponential decay of a vibration: the model ``a exp(b t)`` of eq. 4 fitted to its envelope.

Section 2.3 of the paper fits ``F(x) = a e^{bx}`` to the band-passed vibration and calls ``tau =
1/b`` the time constant and ``a`` the gain. For a decay ``b < 0``, so the paper's ``1/b`` is
negative; here
``tau = -1/b > 0`` (s), the time in which the envelope falls by the factor ``e``.

The fit works on the envelope, the magnitude of the analytic signal (Hilbert transform), because an
exponential cannot be fitted to the oscillation itself. Three methods:

``"loglinear"``
    weighted least squares of ``log env = log a + b t`` with weights ``env^2`` (the variance of the
    log of a noisy envelope grows like ``1 / env^2``): closed form, fast, the default;
``"nonlinear"``
    least squares of ``a exp(b t)`` to the envelope itself (what a curve-fitting toolbox does),
    started from the log-linear answer;
``"peaks"``
    the log-linear fit through the local maxima of ``|x|`` only (the logarithmic decrement).

Robustness: only the samples from the start up to where the envelope first sinks to
``floor_factor`` times the noise floor (the median envelope of the last tenth of the record) are
used, so the noise tail does not bend the line; the first and last
period are dropped (Hilbert edge effects); clipped samples (flat runs at the extreme values, as when
the accelerometer saturates) are skipped; and a record with no measurable decay is flagged
(``status="not_decaying"``) instead of being given a meaningless time constant. Logarithms are only
ever taken of positive envelope values.

**Filters ring too.** A decaying tone ``exp((-1/tau + i w) t)`` passes a linear filter as the same
exponential, so band-pass filtering does not change ``tau`` by itself; but the filter adds its own
transients, which decay with the filter's pole time constants (see
:func:`~ebantenna.signal.filter_time_constant`): about 0.42 s for the Table 1 Chebyshev filter at
the order its table needs. That is longer than the probe's own decay (about 0.1 s for a loss factor
of 0.03
at 100 Hz), so after the filter the tail of the record is the filter ringing and the fitted ``tau``
is biased upwards unless the decay is fitted before the ringing takes over. The "second order"
filter of
the paper's text rings only for about 0.01 s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize
from scipy.signal import find_peaks

from .._validate import check_choice, check_in_range
from ._checks import check_fs, check_signal
from .spectral import dominant_frequency

__all__ = [
    "DecayFit",
    "envelope",
    "fit_decay",
    "band_passed_decay",
    "DECAY_METHODS",
    "MIN_DECAY_SAMPLES",
]

#: Methods of :func:`fit_decay`.
DECAY_METHODS = ("loglinear", "nonlinear", "peaks")
#: Shortest record :func:`fit_decay` accepts, samples.
MIN_DECAY_SAMPLES = 16


@dataclass(frozen=True)
class DecayFit:
    """Result of :func:`fit_decay`: ``envelope(t) ~ a exp(b t)``, ``t`` from the first sample.

    Attributes
    ----------
    a : float
        Gain, the envelope at ``t = 0``, in the unit of the signal.
    b : float
        Rate, 1/s; negative for a decay.
    tau : float
        Time constant ``-1/b``, s; ``math.inf`` when ``b >= 0``.
    status : str
        ``"ok"``; ``"not_decaying"`` (no exponential decay stands out of the noise: noise only, a
        steady or growing oscillation); ``"too_few_points"`` (the record holds fewer than four
        periods of its dominant frequency, or nothing is left to fit after trimming; then ``a = b =
        0``).
    clipped : bool
        Flat runs at the extremes were found and skipped.
    method : str
        The fitting method.
    r_squared : float
        Weighted coefficient of determination of ``log env`` against the fitted line.
    n_points : int
        Envelope samples (or peaks) used.
    """

    a: float
    b: float
    tau: float
    status: str
    clipped: bool
    method: str
    r_squared: float
    n_points: int

    @property
    def ok(self) -> bool:
        """True when the time constant is usable."""
        return self.status == "ok"

    def model(self, t) -> np.ndarray:
        """The fitted envelope ``a exp(b t)`` at times ``t`` (s)."""
        return self.a * np.exp(self.b * np.asarray(t, dtype=float))


def envelope(x) -> np.ndarray:
    """Envelope of an oscillation: the magnitude of its analytic signal (Hilbert transform).

    Parameters
    ----------
    x : array of shape (n,)
        Zero-mean oscillation, any unit.

    Returns
    -------
    ndarray of shape (n,)
        ``|x + i H[x]|``, same unit as ``x``.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal import envelope
    >>> t = np.arange(1000) / 1000.0
    >>> env = envelope(2.0 * np.sin(2 * np.pi * 50 * t))
    >>> bool(np.allclose(env, 2.0))
    True
    """
    x = check_signal("x", x, min_length=2)
    n = x.shape[0]
    spectrum = np.fft.fft(x)
    h = np.zeros(n)
    h[0] = 1.0
    if n % 2 == 0:
        h[n // 2] = 1.0
        h[1 : n // 2] = 2.0
    else:
        h[1 : (n + 1) // 2] = 2.0
    return np.abs(np.fft.ifft(spectrum * h))


def _clipped_mask(x: np.ndarray) -> np.ndarray:
    """Samples in flat runs (two or more equal samples) at the signal's maximum or minimum."""
    tol = 1e-9 * float(np.ptp(x))
    at_extreme = (x >= x.max() - tol) | (x <= x.min() + tol)
    run = at_extreme[1:] & at_extreme[:-1]
    mask = np.zeros_like(at_extreme)
    mask[1:] |= run
    mask[:-1] |= run
    return mask


def _weighted_line(t, y, w):
    """Weighted least squares ``y ~ c0 + c1 t``; returns ``(c0, c1, r_squared)``."""
    sw = w.sum()
    tm = (w * t).sum() / sw
    ym = (w * y).sum() / sw
    stt = (w * (t - tm) ** 2).sum()
    if stt == 0.0:
        return ym, 0.0, 0.0
    c1 = (w * (t - tm) * (y - ym)).sum() / stt
    c0 = ym - c1 * tm
    ss_res = (w * (y - c0 - c1 * t) ** 2).sum()
    ss_tot = (w * (y - ym) ** 2).sum()
    r2 = 1.0 - ss_res / ss_tot if ss_tot > 0 else 0.0
    return float(c0), float(c1), float(r2)


def fit_decay(
    x,
    fs,
    *,
    method: str = "loglinear",
    remove_mean: bool = True,
    floor_factor: float = 3.0,
    min_r_squared: float = 0.5,
) -> DecayFit:
    """Fit ``a exp(b t)`` (eq. 4) to the envelope of the vibration ``x``.

    Parameters
    ----------
    x : array of shape (n,)
        Vibration (for instance the band-passed resultant acceleration), at least 16 samples, not
        constant.
    fs : float
        Sampling frequency, Hz.
    method : {"loglinear", "nonlinear", "peaks"}
        See the module notes.
    remove_mean : bool
        Subtract the mean before taking the envelope.
    floor_factor : float
        Envelope samples below ``floor_factor`` times the noise floor are not fitted (>= 1).
    min_r_squared : float
        Below this weighted R^2 of the log-envelope line, the record is flagged ``"not_decaying"``.

    Returns
    -------
    DecayFit
        ``a`` (unit of ``x``), ``b`` (1/s), ``tau`` (s), ``status`` and diagnostics.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal import fit_decay
    >>> t = np.arange(1000) / 1000.0
    >>> fit = fit_decay(2.0 * np.exp(-t / 0.1) * np.sin(2 * np.pi * 80 * t), 1000.0)
    >>> fit.status, round(fit.tau, 3), round(fit.a, 2)
    ('ok', 0.1, 2.0)
    >>> rng = np.random.default_rng(0)
    >>> fit_decay(rng.standard_normal(1000), 1000.0).status
    'not_decaying'
    """
    fs = check_fs(fs)
    x = check_signal("x", x, min_length=MIN_DECAY_SAMPLES, allow_constant=False)
    check_choice("method", method, DECAY_METHODS)
    floor_factor = check_in_range("floor_factor", floor_factor, 1.0, 1e6, low_inclusive=True)
    min_r_squared = check_in_range("min_r_squared", min_r_squared, 0.0, 1.0, low_inclusive=True,
                                   high_inclusive=True)
    n = x.shape[0]
    clipped = _clipped_mask(x)
    is_clipped = bool(clipped.any())
    xc = x - x.mean() if remove_mean else x
    env = envelope(xc)
    t = np.arange(n) / fs

    period = fs / dominant_frequency(xc, fs, method="bin", window="rectangular")
    edge = int(min(max(2, math.ceil(period)), n // 8))
    start = edge
    if is_clipped:
        start = max(start, int(np.flatnonzero(clipped)[-1]) + 1 + edge)
    stop = n - edge

    def failed(status):
        return DecayFit(0.0, 0.0, math.inf, status, is_clipped, method, 0.0, 0)

    if period > n / 4 or stop - start < 4:
        return failed("too_few_points")
    region = np.arange(start, stop)
    tail = env[region[-max(2, region.size // 10) :]]
    floor = float(np.median(tail))
    # Fit from the start up to where the envelope first sinks to the floor: later samples are noise,
    # Hilbert leakage from the record's ends, or the offset left by removing the mean.
    below = np.flatnonzero(env[region] <= floor_factor * floor)
    keep = region[: below[0]] if below.size else region
    if keep.size < max(4, region.size // 20):
        keep = region[env[region] > 0.0]
    if method == "peaks":
        peaks, _ = find_peaks(np.abs(xc))
        keep = np.intersect1d(peaks, keep)
    if keep.size < 4:
        return failed("too_few_points")

    tk, ek = t[keep], env[keep]
    if method == "peaks":
        ek = np.abs(xc[keep])
    ly = np.log(ek)  # ek > 0 by construction of keep
    log_a, b, _ = _weighted_line(tk, ly, ek**2)
    a = math.exp(log_a)
    if method == "nonlinear":
        def residual(p):
            return p[0] * np.exp(p[1] * tk) - ek

        def jacobian(p):
            e = np.exp(p[1] * tk)
            return np.column_stack([e, p[0] * tk * e])

        sol = optimize.least_squares(residual, x0=[a, b], jac=jacobian, method="lm")
        if sol.success and np.all(np.isfinite(sol.x)) and sol.x[0] > 0:
            a, b = float(sol.x[0]), float(sol.x[1])
    w = ek**2
    fitted = math.log(a) + b * tk
    ym = (w * ly).sum() / w.sum()
    ss_tot = (w * (ly - ym) ** 2).sum()
    r2 = 1.0 - (w * (ly - fitted) ** 2).sum() / ss_tot if ss_tot > 0 else 0.0
    tau = -1.0 / b if b < 0 else math.inf
    status = "ok" if (b < 0 and r2 >= min_r_squared) else "not_decaying"
    return DecayFit(float(a), float(b), float(tau), status, is_clipped, method, float(r2),
                    int(keep.size))


def band_passed_decay(x, fs, *, kind: str = "chebyshev", order=None,
                      method: str = "loglinear") -> DecayFit:
    """Material features of section 4.1.2: band-pass with zero phase, then :func:`fit_decay`.

    Parameters
    ----------
    x : array of shape (n,)
        Vibration, for instance the resultant acceleration of a contact, m/s^2.
    fs : float
        Sampling frequency, Hz; the filter's band edges (Hz) must lie below ``fs / 2``.
    kind : {"chebyshev", "elliptic"}
        Table 1 (the paper's choice before the decay fit) or Table 2.
    order : int or None or "stated"
        As for :func:`~ebantenna.signal.paper_filter`. See the module notes on filter ringing.
    method : {"loglinear", "nonlinear", "peaks"}
        Fitting method.

    Returns
    -------
    DecayFit
        ``tau`` (s) and ``a`` (the gain, m/s^2) are the two material features.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal import band_passed_decay
    >>> t = np.arange(1000) / 1000.0
    >>> x = np.exp(-t / 0.1) * np.sin(2 * np.pi * 110 * t) + 0.5 * np.sin(2 * np.pi * 20 * t)
    >>> fit = band_passed_decay(x, 1000.0, order="stated")  # the 20 Hz hum is filtered out
    >>> fit.status, round(fit.tau, 2)
    ('ok', 0.1)
    """
    from .filters import apply_filter, paper_filter

    fs = check_fs(fs)
    return fit_decay(apply_filter(paper_filter(kind, order, fs=fs), x), fs, method=method)
