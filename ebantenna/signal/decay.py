"""Exponential decay of a vibration: the model ``a exp(b t)`` of eq. 4 fitted to its envelope.

Section 2.3 of the paper fits ``F(x) = a e^{bx}`` to the band-passed vibration and calls ``tau =
1/b`` the time constant and ``a`` the gain. For a decay ``b < 0``, so the paper's ``1/b`` is
negative; here
``tau = -1/b > 0`` (s), the time in which the envelope falls by the factor ``e``.

The fit works on the envelope, the magnitude of the analytic signal (Hilbert transform), because an
exponential cannot be fitted to the oscillation itself. Four methods:

``"loglinear"``
    weighted least squares of ``log env = log a + b t`` with weights ``env^2`` (the variance of the
    log of a noisy envelope grows like ``1 / env^2``): closed form, fast, the default;
``"nonlinear"``
    least squares of ``a exp(b t)`` to the envelope itself (what a curve-fitting toolbox does),
    started from the log-linear answer;
``"peaks"``
    the log-linear fit through the local maxima of ``|x|`` only (the logarithmic decrement);
``"sinusoid"``
    least squares of the whole damped sinusoid ``e^{bt} (p cos wt + q sin wt) + c`` to the signal
    itself (:func:`scipy.optimize.least_squares`), started from the log-linear envelope fit. Its
    model holds one mode; for that case it is unbiased, where the envelope fits are not (the
    record's abrupt start leaks through the Hilbert transform: the envelope carries an error
    that dies away far more slowly than the decay, a floor a fast decay sinks into, and the
    first and last periods must be dropped; its ripple at twice the tone's frequency is much
    smaller than that). On the clean decays of the tests an ``"ok"`` envelope fit errs by up to
    3 % either way, mostly by less than 0.5 %; a fit with another status may err by any amount.

**The steps.** :func:`fit_decay` validates its arguments once, then follows the textbook: the
envelope (:func:`analytic_envelope`), the log-linear fit (:func:`loglinear_fit`, refined by
:func:`envelope_fit` for ``"nonlinear"``), the damped-sinusoid witness
(:func:`damped_sinusoid_fit`) and the checks (:func:`envelope_status`, :func:`sinusoid_status`).
The steps take checked values. The numerical guards below (the power-of-two scaling, the clipped
samples, the fitted region) live in the private module ``ebantenna/signal/_guards.py``.

Robustness: only the samples from the start up to where the envelope first sinks to
``floor_factor`` times the floor (the median envelope of the last tenth of the record) are
used, so the noise tail does not bend the line, unless the tail is the decay itself (a slow decay
that reaches no noise within the record; ``_fitted_samples`` tells the two apart); the first
and last
period are dropped (Hilbert edge effects); clipped samples (flat runs at the extreme values, as when
the accelerometer saturates) are skipped; and a record with no measurable decay is flagged
(``status="not_decaying"``) instead of being given a meaningless time constant. Logarithms are only
ever taken of positive envelope values. The signal is scaled by a power of two before fitting (an
exact operation), so amplitudes from 1e-300 to 1e300 give the same ``tau``.

**An "ok" is checked.** An envelope fit is only ``"ok"`` if the samples it used span at least two
periods of the signal, and if it agrees within 3 % with the damped-sinusoid fit whenever that fit
explains the record (residual below 10 % of the signal, so one decaying mode is all there is); where
it does not, the decay must stand out of the noise: its fit starts at least ``floor_factor**2``
above the noise floor it was cut at, and three standard errors of its rate
(``_rate_standard_error``, which counts neighbouring envelope samples as correlated: a noisy
envelope is smooth over the inverse of the noise's bandwidth) lie within 3 %; and it must span at
least 50 samples (``UNCONFIRMED_SPAN``: over fewer the envelope's errors at the start, and near
``fs / 2`` the tone's mirror image, are not averaged out). Otherwise the status says what is wrong
(``"too_few_points"``, ``"inconsistent"``, ``"noise_limited"``). Under noise the witness is noisy
too: with white noise of 3 % of the start amplitude, ``"ok"`` fits of the tests err by up to 8 %;
with 1 %, by up to 3.5 %. The damped-sinusoid fit is ``"ok"`` when it converged, decays, its
residual is below 10 % of the signal (R^2 >= 0.99) and the record holds at least one period of the
fitted frequency.

**Filters ring too.** A decaying tone ``exp((-1/tau + i w) t)`` that had always been there would
pass a linear filter as the same exponential; a real decay starts abruptly, and the filter
answers its start with its own transients, which decay with the filter's pole time constants
``tau_f`` (see :func:`~ebantenna.signal.filter_time_constant`): about 0.42 s for the Table 1
Chebyshev filter at the order its table needs, 0.01 s for the "second order" filter of the
paper's text. The filtered envelope is the sum of the decay and that ringing, so the fitted
``tau`` is biased, either way, unless the ringing has died away early in the fit, which needs
``tau`` many times ``tau_f``. On the clean decays of the tests (75-170 Hz), after the second-order
filter the error falls from about 20 % at ``tau = 2 tau_f`` to about 6 % at ``10 tau_f``; after
the Table 1 filter, where every probe decay is shorter than ``tau_f``, it lies between +17 % and
+67 % at 150 Hz and ``tau`` = 30 ms, depending on the tone's phase (the start the filter answers).
:func:`band_passed_decay` does not count on the decay: its status is only what
:func:`fit_decay` finds in the filtered record (``"noise_limited"`` for every phase of this
example).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize
from scipy.signal import find_peaks

from .._validate import check_array, check_bool, check_choice, check_in_range, check_int, check_real
from ._checks import check_fs, check_signal
from ._guards import clipped_mask, decay_region, unit_scaled
from .filters import apply_filter, paper_filter
from .spectral import dominant_frequency

__all__ = [
    "DecayFit",
    "envelope",
    "fit_decay",
    "band_passed_decay",
    "DECAY_METHODS",
    "MIN_DECAY_SAMPLES",
    # the steps of the reference; they take checked arguments
    "analytic_envelope",
    "weighted_line",
    "loglinear_fit",
    "envelope_fit",
    "damped_sinusoid_fit",
    "envelope_status",
    "sinusoid_status",
]

#: Methods of :func:`fit_decay`.
DECAY_METHODS = ("loglinear", "nonlinear", "peaks", "sinusoid")
#: Relative disagreement of an envelope fit with the damped-sinusoid fit above which the envelope
#: fit is ``"inconsistent"``.
CONSISTENCY = 0.03
#: Smallest R^2 of the damped-sinusoid fit (a residual of 10 % of the signal's RMS) for it to be
#: ``"ok"``, and to serve as the witness of the envelope fits.
SINUSOID_R_SQUARED = 0.99
#: Largest relative standard error of the rate of an ``"ok"`` envelope fit: three standard
#: errors make the 3 % of :data:`CONSISTENCY`.
PRECISION = CONSISTENCY / 3
#: Fewest samples an envelope fit must span (first to last fitted sample) to be ``"ok"`` when no
#: damped-sinusoid fit confirms it; a shorter one is ``"too_few_points"``. The envelope's error
#: from the record's abrupt start spreads over tens of samples, whatever the record's length.
UNCONFIRMED_SPAN = 50
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
        periods of its dominant frequency: then ``a = b = 0``; or a decay that rises
        ``floor_factor**2`` above the floor is over before two periods could be fitted: then
        ``a`` and ``b`` are the envelope fit's, not to be trusted); ``"noise_limited"`` (no
        damped sinusoid confirms the fit, and the decay does not stand out of the floor or its
        rate is too uncertain for a usable ``tau``: whatever scatters the envelope about the
        line counts, noise or other modes beating with the first; see the module notes;
        ``a``, ``b`` are the fit of the samples above the floor, not to be trusted);
        ``"inconsistent"`` (an envelope fit that disagrees by more
        than 3 % with a damped sinusoid that explains the record: ``a``, ``b`` and ``tau`` are
        the envelope's, not to be trusted); ``"poor_fit"`` (``"sinusoid"`` only: the model leaves
        more than 10 % of the signal unexplained, or did not converge).
    clipped : bool
        Flat runs at the extremes were found and skipped.
    method : str
        The fitting method.
    r_squared : float
        Weighted coefficient of determination of ``log env`` against the fitted line
        (``"sinusoid"``: of the signal against the fitted damped sinusoid).
    n_points : int
        Envelope samples (or peaks, or signal samples) used.
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
        """The fitted envelope ``a exp(b t)`` at times ``t`` (s, finite)."""
        from .._validate import real_array

        t = real_array("t", t)
        if not np.all(np.isfinite(t)):
            raise ValueError("t must contain only finite times (no NaN or inf)")
        return self.a * np.exp(self.b * t)


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
    return analytic_envelope(check_signal("x", x, min_length=2))


def analytic_envelope(x: np.ndarray) -> np.ndarray:
    """``|x + i H[x]|`` of a checked signal: FFT, negative frequencies removed, positive doubled.

    As :func:`scipy.signal.hilbert` computes it, after an exact power-of-two scaling so that the
    FFT's sums cannot overflow for ``|x|`` up to 1e308. Takes a checked ``x`` (finite, 1-D).

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal.decay import analytic_envelope
    >>> analytic_envelope(np.array([1.0, 0.0, -1.0, 0.0]))  # cos(pi n / 2): envelope 1
    array([1., 1., 1., 1.])
    """
    x = check_signal("x", x, min_length=1)
    n = x.shape[0]
    x, exponent = unit_scaled(x)
    spectrum = np.fft.fft(x)
    h = np.zeros(n)
    h[0] = 1.0
    if n % 2 == 0:
        h[n // 2] = 1.0
        h[1 : n // 2] = 2.0
    else:
        h[1 : (n + 1) // 2] = 2.0
    return np.ldexp(np.abs(np.fft.ifft(spectrum * h)), exponent)


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
    method : {"loglinear", "nonlinear", "peaks", "sinusoid"}
        See the module notes. ``"sinusoid"`` is unbiased for one decaying mode; the envelope
        methods also serve a mix of modes (each is then checked against the sinusoid fit only
        where that fit explains the record).
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

    A short decay at a low frequency: its envelope is too distorted to be trusted, the
    damped-sinusoid fit is exact.

    >>> x = np.exp(-t / 0.03) * np.sin(2 * np.pi * 25 * t)
    >>> fit_decay(x, 1000.0).ok
    False
    >>> fit = fit_decay(x, 1000.0, method="sinusoid")
    >>> fit.status, round(fit.tau, 6)
    ('ok', 0.03)
    """
    x, fs, floor_factor, min_r_squared, remove_mean = _checked_arguments(
        x, fs, method, remove_mean, floor_factor, min_r_squared)
    x, exponent = unit_scaled(x)  # guard: sums, squares and logs neither overflow nor underflow
    clipped = clipped_mask(x)  # guard: samples of a saturated sensor
    xc = x - x.mean() if remove_mean else x
    env = analytic_envelope(xc)
    # guard: at an extreme fs the squared times of the line fit under- or overflow; the fit is
    # then made in samples (a time unit of 1/fs) and its rate converted to 1/s at the end.
    unit = 1.0 if 1e-100 <= fs <= 1e100 else 1.0 / fs  # s
    t = np.arange(x.shape[0]) / (fs * unit)
    # the period, in samples, of the strongest bin of the decay's own samples: a decay that is
    # over within half of the record is analysed on its span (the transient of the spectral peak)
    period = fs / dominant_frequency(xc, fs, method="bin", window="rectangular", transient=True)
    region = decay_region(env, clipped, period, floor_factor)  # guard: edges, clipping, noise
    keep, end, too_short, separable = (None, 0, True, True) if region is None else (
        _fitted_samples(t, env, region, floor_factor))
    if keep is not None and method == "peaks":
        keep = np.intersect1d(find_peaks(np.abs(xc))[0], keep)
    if keep is None or keep.size < 4:
        return _decay_fit(0.0, 0.0, "too_few_points", 0.0, 0, exponent, clipped, method)

    ek = env[keep] if method != "peaks" else np.abs(xc[keep])
    a, b, r2 = envelope_fit(t[keep], ek, nonlinear=method == "nonlinear")
    decaying = b < 0 and r2 >= min_r_squared
    if decaying:  # a tau whose scatter is beyond the 3 % stated does not stand out of the noise
        separable = separable and _rate_standard_error(t[keep], ek, a, b) <= PRECISION * -b
    first = region.first
    sine = damped_sinusoid_fit(xc[first:], t[first:], end - first, b)
    n_points = keep.size
    if method == "sinusoid":
        status = sinusoid_status(sine, decaying)
        if sine is not None:
            a, b, r2, n_points = sine
    else:
        # an envelope fit that no damped sinusoid confirms is trusted over at least
        # UNCONFIRMED_SPAN samples: over fewer the envelope's errors at the decay's start, and
        # near fs/2 the tone's mirror image, are not averaged out (a clean 5 ms decay at 474 Hz
        # sampled at 1 kHz: 24 samples, tau 146 % long)
        too_short = too_short or (decaying and separable and not _confirms(sine)
                                  and keep[-1] - keep[0] + 1 < UNCONFIRMED_SPAN)
        status = envelope_status(b, decaying, too_short, sine, separable=separable)
    return _decay_fit(a, b / unit, status, r2, n_points, exponent, clipped, method)


def _checked_arguments(x, fs, method, remove_mean, floor_factor, min_r_squared):
    """Validate the arguments of :func:`fit_decay` once, at the public boundary.

    Returns ``(x, fs, floor_factor, min_r_squared, remove_mean)``.
    """
    fs = check_fs(fs)
    x = check_signal("x", x, min_length=MIN_DECAY_SAMPLES, allow_constant=False)
    check_choice("method", method, DECAY_METHODS)
    floor_factor = check_in_range("floor_factor", floor_factor, 1.0, 1e6, low_inclusive=True)
    min_r_squared = check_in_range("min_r_squared", min_r_squared, 0.0, 1.0, low_inclusive=True,
                                   high_inclusive=True)
    remove_mean = check_bool("remove_mean", remove_mean)
    return x, fs, floor_factor, min_r_squared, remove_mean


def _decay_fit(a, b, status, r_squared, n_points, exponent, clipped, method) -> DecayFit:
    """The :class:`DecayFit` of a fit to ``x * 2**-exponent``, with ``a`` scaled back."""
    tau = -1.0 / b if b < 0 else math.inf
    return DecayFit(float(np.ldexp(a, exponent)), float(b), float(tau), status,
                    bool(clipped.any()), method, float(r_squared), int(n_points))


def _series(min_length: int = 1, **arrays) -> list[np.ndarray]:
    """``arrays`` as 1-D finite float arrays of one length (at least ``min_length``); else an
    error naming the first that is not."""
    out, n, first = [], None, None
    for name, value in arrays.items():
        a = check_array(name, value, ndim=1, min_length=min_length)
        if n is None:
            n, first = a.size, name
        elif a.size != n:
            raise ValueError(f"{name} must have one value per entry of {first} ({n}), got "
                             f"{a.size}")
        out.append(a)
    return out


def _check_sine(sine) -> None:
    """``sine`` is None or ``(a, b, r_squared, n_fit)`` as :func:`damped_sinusoid_fit` returns."""
    if sine is None:
        return
    if not isinstance(sine, tuple) or len(sine) != 4:
        raise TypeError(f"sine must be None or a tuple (a, b, r_squared, n_fit), got "
                        f"{sine!r:.60}")
    for name, value in zip(("a", "b", "r_squared"), sine[:3], strict=True):
        check_real(f"sine's {name}", value)
    check_int("sine's n_fit", sine[3], minimum=1)


def weighted_line(t, y, w):
    """Weighted least squares ``y ~ c0 + c1 t``; returns ``(c0, c1, r_squared)``.

    The normal equations in centred form: ``c1 = sum w (t - tm)(y - ym) / sum w (t - tm)^2``,
    ``c0 = ym - c1 tm`` with ``tm``, ``ym`` the weighted means. A single abscissa (no slope to
    fit) gives ``(ym, 0, 0)``.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal.decay import weighted_line
    >>> t = np.array([0.0, 1.0, 2.0])
    >>> weighted_line(t, 1.0 + 2.0 * t, np.ones(3))
    (1.0, 2.0, 1.0)
    """
    t, y, w = _series(t=t, y=y, w=w)
    if np.any(w < 0) or not w.sum() > 0:
        raise ValueError("w must hold weights >= 0, not all zero")
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


def loglinear_fit(t, env):
    """Fit ``env ~ a exp(b t)`` as the line ``log env = log a + b t``, weighted by ``env^2``.

    The weights undo what the logarithm does to noise: an envelope error ``s`` becomes a log
    error ``s / env``. Takes checked values: ``env > 0`` and of moderate size, so that
    ``env^2`` neither overflows nor underflows (:func:`fit_decay` scales the signal by a power of
    two first). Returns ``(a, b)``.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal.decay import loglinear_fit
    >>> t = np.linspace(0.0, 1.0, 11)
    >>> a, b = loglinear_fit(t, 2.0 * np.exp(-3.0 * t))
    >>> round(a, 12), round(b, 12)
    (2.0, -3.0)
    """
    t, env = _series(t=t, env=env)
    if not np.all(env > 0):
        raise ValueError("env must be > 0 everywhere (its logarithm is fitted)")
    log_a, b, _ = weighted_line(t, np.log(env), env**2)
    return math.exp(log_a), b


def envelope_fit(tk, ek, *, nonlinear):
    """Fit ``a exp(b t)`` to envelope samples ``ek > 0`` at times ``tk``; return ``(a, b, r2)``.

    The weighted log-linear fit (:func:`loglinear_fit`), refined by least squares on ``ek``
    itself if ``nonlinear``; ``r2`` is the weighted R^2 of ``log ek`` against the final line.
    Takes checked values.
    """
    tk, ek = _series(tk=tk, ek=ek)
    if not np.all(ek > 0):
        raise ValueError("ek must be > 0 everywhere (its logarithm is fitted)")
    nonlinear = check_bool("nonlinear", nonlinear)
    a, b = loglinear_fit(tk, ek)
    if nonlinear:
        def residual(p):
            return p[0] * np.exp(p[1] * tk) - ek

        def jacobian(p):
            e = np.exp(p[1] * tk)
            return np.column_stack([e, p[0] * tk * e])

        sol = optimize.least_squares(residual, x0=[a, b], jac=jacobian, method="lm")
        if sol.success and np.all(np.isfinite(sol.x)) and sol.x[0] > 0:
            a, b = float(sol.x[0]), float(sol.x[1])
    ly = np.log(ek)
    w = ek**2
    fitted = math.log(a) + b * tk
    ym = (w * ly).sum() / w.sum()
    ss_tot = (w * (ly - ym) ** 2).sum()
    r2 = 1.0 - (w * (ly - fitted) ** 2).sum() / ss_tot if ss_tot > 0 else 0.0
    return a, b, r2


def _rate_standard_error(tk, ek, a, b):
    """Standard error of the rate ``b`` of the weighted log-linear fit ``ek ~ a exp(b tk)``, with
    neighbouring envelope samples counted as the correlated samples they are.

    The textbook formula of weighted least squares, with the weights ``w = ek^2`` of
    :func:`loglinear_fit` and the noise variance estimated from the residuals ``r = log ek -
    log a - b tk``: ``se0^2 = (sum w r^2 / (n - 2)) / sum w (tk - tm)^2``, ``tm`` the weighted
    mean time, counts the ``n`` samples as independent. They are not: the envelope of a noisy
    tone is smooth over about the inverse of the noise's bandwidth, and after a band-pass
    filter over many samples. ``se0`` is therefore multiplied by the square root of the
    weighted residuals' integrated autocorrelation time ``1 + 2 sum_k rho_k`` (``n`` over it is
    the samples' effective number), summed up to the lag before the first autocorrelation that
    is not positive: the initial positive sequence (C. J. Geyer, "Practical Markov chain Monte
    Carlo", *Statistical Science* 7, 1992, 473-483), taken lag by lag. On decays under white
    noise, and under noise band-passed to 100 or 50 Hz about the tone, the rate's scatter over
    repeated records is then 0.9-1.3 times this error (``se0`` alone: 1.4, 3.6 and 5.2 times;
    the tests check it). Takes checked values (``ek > 0``, at least 3 samples).

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal.decay import _rate_standard_error
    >>> tk = np.arange(4.0)
    >>> ek = np.exp(-tk + np.array([0.0, 0.1, -0.1, 0.0]))  # residuals 0, 0.1, -0.1, 0 about b=-1
    >>> round(_rate_standard_error(tk, ek, 1.0, -1.0), 4)  # no positive autocorrelation: se0
    0.0651
    """
    tk, ek = _series(tk=tk, ek=ek)
    w = ek**2
    r = np.log(ek) - math.log(a) - b * tk
    tm = (w * tk).sum() / w.sum()
    stt = (w * (tk - tm) ** 2).sum()
    if tk.size < 3 or stt == 0.0:
        return math.inf
    return math.sqrt((w * r * r).sum() / (tk.size - 2) / stt * _correlation_time(np.sqrt(w) * r))


def _correlation_time(u) -> float:
    """The integrated autocorrelation time ``1 + 2 sum_k rho_k`` of the series ``u``, summed over
    the initial positive sequence of its autocorrelations ``rho_k`` (see
    :func:`_rate_standard_error`); 1 for a series without positive correlation.

    Examples
    --------
    >>> _correlation_time(np.array([1.0, -1.0, 1.0, -1.0]))
    1.0
    >>> round(_correlation_time(np.repeat([1.0, -1.0, 1.0, -1.0], 3)), 3)  # 1 + 2 (5 / 12)
    1.833
    """
    n = u.size
    spectrum = np.fft.rfft(u, 2 * n)  # zero-padded: the products do not wrap around
    ac = np.fft.irfft(spectrum.real**2 + spectrum.imag**2, 2 * n)[:n]
    if not ac[0] > 0:
        return 1.0
    rho = ac[1:] / ac[0]
    stop = np.flatnonzero(rho <= 0)
    return 1.0 + 2.0 * float(rho[: stop[0] if stop.size else rho.size].sum())


def _fitted_samples(t, env, region, floor_factor):
    """The samples to fit, and whether the decay stands out of the noise: the noise-tail check.

    :func:`~ebantenna.signal._guards.decay_region` cuts the region where the envelope first sinks
    to ``floor_factor`` times its floor, the median envelope of the last tenth. That floor is
    either noise (or Hilbert leakage) that the decay sank into, or, in a record that ends before
    its decay reaches any noise, the decay itself. The check tells the two apart:

    * the tail is noise when the log-linear fit of the cut samples (:func:`loglinear_fit`),
      extrapolated to the first time of the tail, lies below the floor there (the decay had sunk
      into the floor before the tail began), or when the tail's log envelope scatters about its
      line by more than ``1 / floor_factor`` (a decay ``D`` under noise ``sigma`` scatters by
      about ``sigma / D``; a tail of noise by 0.64): the cut stands;
    * otherwise the tail is the decay, and the whole region is fitted.

    A decay cut at a noise floor *stands out of the noise* when the fit of the cut samples starts
    at least ``floor_factor**2`` times above the floor: the fitted samples then span a factor of at
    least ``floor_factor`` of the decay (``ln 3 = 1.1`` time constants for the default). A cut
    shorter than two periods is a decay over too soon to measure (``too_short``) when the
    envelope rises that far above the floor, and nothing that stands out (``separable`` False)
    when it does not and the tail is noise; when it does not and the tail is smooth, the whole
    region is fitted, a slow decay that never reaches any noise (its R^2 tells it from a steady
    tone). Takes checked values: ``region`` a
    :class:`~ebantenna.signal._guards.DecayRegion` of ``env``, ``t`` the sample times.

    Returns
    -------
    keep : ndarray of int
        The envelope samples to fit.
    end : int
        End (exclusive) of the window of the damped-sinusoid witness.
    too_short : bool
        The decay is over before two periods.
    separable : bool
        False when the decay was cut at a noise floor it does not stand out of.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal.decay import analytic_envelope, _fitted_samples
    >>> from ebantenna.signal._guards import decay_region
    >>> t = np.arange(1000) / 1000.0
    >>> env = analytic_envelope(np.exp(-t / 0.5) * np.sin(2 * np.pi * 100 * t))
    >>> region = decay_region(env, np.zeros(1000, bool), 10.0, 3.0)
    >>> keep, end, too_short, separable = _fitted_samples(t, env, region, 3.0)  # tail: the decay
    >>> int(region.keep[-1]), int(keep[-1]), end, too_short, separable
    (380, 989, 1000, False, True)
    """
    n, level = env.shape[0], floor_factor**2 * region.floor
    noisy_tail = region.tail_spread > 1.0 / floor_factor
    if region.too_short:
        if region.peak >= level or noisy_tail:  # the witness may still fit the whole record
            return region.keep, n, True, region.peak >= level
        return region.whole, n, False, True
    a, b = loglinear_fit(t[region.keep], env[region.keep])
    sunk = b < 0 and a * math.exp(b * t[region.tail_start]) < region.floor
    if sunk or noisy_tail:
        return region.keep, region.end, False, a * math.exp(b * t[region.keep[0]]) >= level
    return region.whole, n, False, True


def damped_sinusoid_fit(x, t, n_fit, b0):
    """Fit ``exp(b t) (p cos wt + q sin wt) + c`` to the first ``n_fit`` samples of ``x``.

    The ``"sinusoid"`` method of :func:`fit_decay` and the witness each envelope fit is checked
    against. The model is the whole damped sinusoid, fitted to the signal itself (not to its
    envelope) by :func:`scipy.optimize.least_squares` (Levenberg-Marquardt) with its Jacobian,
    the columns ``d/db = t osc``, ``d/dw = t e (q cos wt - p sin wt)``, ``d/dp = e cos wt``,
    ``d/dq = e sin wt``, ``d/dc = 1``, where ``e = exp(b t)`` and ``osc = e (p cos wt + q sin wt)``.
    Times are counted from ``t[0]``; the amplitude at ``t = 0`` is then ``hypot(p, q) exp(-b t0)``.

    The start: the rate ``b0`` of the envelope fit (or, if that does not decay, ``-1 / (2 t_E)``
    with ``t_E`` the energy centroid of the window, since ``exp(2 b t)`` has its centroid at
    ``1 / (2 |b|)``); the frequency of the strongest peak of the window's spectrum, zero-padded 8
    times; the linear parameters ``p, q, c`` at their least-squares values for that rate and
    frequency. Takes checked values: :func:`fit_decay` validates its arguments and scales the
    signal before calling it.

    Parameters
    ----------
    x, t : ndarray of shape (n,)
        Signal and its sample times (any time unit; ``b`` comes out in its inverse).
    n_fit : int
        Number of samples fitted, from the first (at most ``n``).
    b0 : float
        Starting rate, from the envelope fit; a value that is not negative is replaced by the
        energy-centroid start above.

    Returns
    -------
    sine : tuple or None
        ``(a, b, r_squared, n_fit)``: ``a`` the amplitude at ``t = 0`` (unit of ``x``), ``b``
        the rate (1/unit of ``t``), ``r_squared`` of the signal against the fit, ``n_fit`` the
        samples fitted; None when the window has fewer than 8 samples or less than one period
        of the fitted frequency, or the solver fails.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal.decay import damped_sinusoid_fit
    >>> t = np.arange(600) / 1000.0
    >>> x = 2.0 * np.exp(-t / 0.08) * np.sin(2 * np.pi * 61.3 * t + 0.9)
    >>> a, b, r2, n = damped_sinusoid_fit(x, t, 600, -11.0)
    >>> round(a, 6), round(-1 / b, 6), n
    (2.0, 0.08, 600)
    """
    x, t = _series(x=x, t=t)
    if x.size > 1 and not np.all(np.diff(t) > 0):
        raise ValueError("t must be strictly increasing sample times")
    n_fit = min(check_int("n_fit", n_fit, minimum=1), x.size)
    b0 = check_real("b0", b0, allow_inf=True)
    if n_fit < 8:
        return None
    y, t0 = x[:n_fit], t[0]
    tw = t[:n_fit] - t0
    if not b0 < 0:
        energy = y**2
        b0 = -0.5 / max(float((tw * energy).sum() / energy.sum()), tw[1])
    # the strongest peak of the window's spectrum, 8x zero-padded, near the record's dominant bin
    spectrum = np.abs(np.fft.rfft(y - y.mean(), 8 * n_fit))
    omegas = 2 * np.pi * np.fft.rfftfreq(8 * n_fit, tw[1])
    omega = float(omegas[1 + np.argmax(spectrum[1:])])  # n_fit >= 8: bins beyond DC exist

    def columns(b, w):
        e = np.exp(b * tw)
        return e, np.cos(w * tw), np.sin(w * tw)

    e, co, si = columns(b0, omega)
    lin, *_ = np.linalg.lstsq(np.column_stack([e * co, e * si, np.ones(n_fit)]), y, rcond=None)

    def residual(v):
        b, w, p, q, c = v
        e, co, si = columns(b, w)
        return e * (p * co + q * si) + c - y

    def jacobian(v):
        b, w, p, q, c = v
        e, co, si = columns(b, w)
        osc = e * (p * co + q * si)
        return np.column_stack([tw * osc, tw * e * (q * co - p * si), e * co, e * si,
                                np.ones(n_fit)])

    sol = optimize.least_squares(residual, x0=[b0, omega, *lin], jac=jacobian, method="lm",
                                 x_scale="jac")
    b, w, p, q, _ = sol.x
    if not (sol.success and np.all(np.isfinite(sol.x))) or abs(w) * tw[-1] < 2 * np.pi:
        return None
    ss_tot = float(((y - y.mean()) ** 2).sum())
    r2 = 1.0 - float((sol.fun**2).sum()) / ss_tot if ss_tot > 0 else 0.0
    return math.hypot(p, q) * math.exp(-b * t0), float(b), r2, n_fit


def _confirms(sine) -> bool:
    """Whether the damped-sinusoid fit ``sine`` (``(a, b, r_squared, n_fit)`` or None) is a
    witness: it explains the record (R^2 >= :data:`SINUSOID_R_SQUARED`) and decays."""
    return sine is not None and sine[2] >= SINUSOID_R_SQUARED and sine[1] < 0


def envelope_status(b, decaying, too_short, sine, *, separable=True) -> str:
    """The checks of an envelope fit with rate ``b`` (1/s): its ``status`` of a :class:`DecayFit`.

    In this order: a decay over before two periods (``too_short``, whose fit then spans the whole
    region and need not decay) is ``"too_few_points"`` if it stands out of the floor
    (``separable``), ``"not_decaying"`` if not; otherwise ``"not_decaying"`` unless
    ``decaying`` (``b < 0`` and R^2 high enough); then, when the damped-sinusoid fit ``sine``,
    ``(a, b, r_squared, n_fit)`` or None, explains the record (R^2 >= 0.99) and decays, it
    decides: ``"inconsistent"`` if it disagrees with ``b`` by more than 3 %, else ``"ok"``;
    without it, ``"noise_limited"`` unless ``separable`` (the decay does not rise
    ``floor_factor**2`` above the floor it was cut at, or its rate is uncertain by more than
    3 % in three standard errors, see the module notes), else ``"ok"``.

    Examples
    --------
    >>> from ebantenna.signal.decay import envelope_status
    >>> envelope_status(-10.0, True, False, (1.0, -10.1, 0.999, 500))  # 1 % apart
    'ok'
    >>> envelope_status(-10.0, True, False, (1.0, -12.0, 0.999, 500))  # 20 % apart
    'inconsistent'
    """
    b = check_real("b", b)
    decaying = check_bool("decaying", decaying)
    too_short = check_bool("too_short", too_short)
    separable = check_bool("separable", separable)
    _check_sine(sine)
    if decaying and not b < 0:
        raise ValueError(f"b must be < 0 when decaying is True, got {b!r}")
    if too_short:
        return "too_few_points" if separable else "not_decaying"
    if not decaying:
        return "not_decaying"
    if _confirms(sine):
        return "inconsistent" if abs(sine[1] / b - 1.0) > CONSISTENCY else "ok"
    return "ok" if separable else "noise_limited"


def sinusoid_status(sine, envelope_decays: bool) -> str:
    """The checks of the damped-sinusoid fit ``sine`` (None when it failed): its status.

    ``"ok"`` when it explains the record (R^2 >= 0.99) and decays; ``"not_decaying"`` when it
    explains the record without decaying, or when neither it nor the envelope fit finds a
    decay; ``"poor_fit"`` otherwise (the envelope decays, the sinusoid does not explain it).

    Examples
    --------
    >>> from ebantenna.signal.decay import sinusoid_status
    >>> sinusoid_status((1.0, -10.0, 0.999, 500), True), sinusoid_status(None, True)
    ('ok', 'poor_fit')
    """
    _check_sine(sine)
    envelope_decays = check_bool("envelope_decays", envelope_decays)
    if sine is None:
        return "poor_fit" if envelope_decays else "not_decaying"
    good = sine[2] >= SINUSOID_R_SQUARED
    if good and sine[1] < 0:
        return "ok"
    return "not_decaying" if good or not envelope_decays else "poor_fit"


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
    method : {"loglinear", "nonlinear", "peaks", "sinusoid"}
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
    fs = check_fs(fs)
    return fit_decay(apply_filter(paper_filter(kind, order, fs=fs), x), fs, method=method)
