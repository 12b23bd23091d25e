"""Each named step of the spectral peak and the decay fit, against an independent witness.

The public functions are tested in test_signal_spectral.py and test_signal_decay.py; here each
step they are built from is held to what the mathematics guarantees for it, with tolerances
derived from the operation.
"""

import math

import numpy as np
import pytest
from scipy import signal as sps

from ebantenna.signal import dominant_frequency
from ebantenna.signal._guards import (
    analysed_part,
    clipped_mask,
    decay_region,
    search_bins,
    transient_span,
    unit_scaled,
)
from ebantenna.signal.decay import (
    _fitted_samples,
    _rate_standard_error,
    analytic_envelope,
    damped_sinusoid_fit,
    envelope_fit,
    envelope_status,
    loglinear_fit,
    sinusoid_status,
    weighted_line,
)
from ebantenna.signal.spectral import (
    interpolated_frequency,
    jacobsen_offset,
    local_maxima,
    parabolic_offset,
    strongest_bin,
    strongest_separated,
    window_weights,
    windowed_spectrum,
)

EPS = np.finfo(float).eps


# --- the spectral peak ------------------------------------------------------------------------


@pytest.mark.parametrize("n", [4, 7, 64, 1000])
def test_window_weights_are_the_periodic_textbook_windows(n):
    phase = 2 * np.pi * np.arange(n) / n
    witness = {
        "rectangular": np.ones(n),
        "hann": 0.5 * (1 - np.cos(phase)),
        "hamming": 0.54 - 0.46 * np.cos(phase),
        "blackman": 0.42 - 0.5 * np.cos(phase) + 0.08 * np.cos(2 * phase),
    }
    for window, w in witness.items():
        # each cosine term rounds within an ulp of its coefficient (<= 1): a few eps in all
        np.testing.assert_allclose(window_weights(window, n), w, rtol=0, atol=8 * EPS)


@pytest.mark.parametrize("window", ["rectangular", "hann"])
def test_windowed_spectrum_is_the_dft_of_the_windowed_record_less_its_mean(window):
    rng = np.random.default_rng(3)
    n = 200
    x = 5.0 + rng.standard_normal(n)
    spectrum, part = windowed_spectrum(x, 100.0, window, 2, 1.0, 50.0, True)
    scaled, _ = unit_scaled(x)  # the step works on the exactly scaled record
    y = (scaled - scaled.mean()) * window_weights(window, n)
    k = np.arange(2 * n // 2 + 1)[:, None]
    direct = (y * np.exp(-2j * np.pi * k * np.arange(n) / (2 * n))).sum(axis=1)
    # a sum of n terms rounds within n eps of the sum of their magnitudes, for both sums
    np.testing.assert_allclose(spectrum, direct, rtol=0, atol=2 * n * EPS * np.abs(y).sum())
    assert (part.n, part.zero_pad, part.is_transient) == (n, 2, False)
    assert (part.lo, part.hi) == (4, 200)  # 1 Hz and 50 Hz on the 0.25 Hz grid


def test_windowed_spectrum_analyses_a_short_tap_on_its_own():
    fs, n = 1000.0, 1000
    t = np.arange(n) / fs
    tap = np.where(t >= 0.6, np.exp(-(t - 0.6) / 0.02) * np.sin(2 * np.pi * 140 * (t - 0.6)), 0)
    _, part = windowed_spectrum(tap + 9.81, fs, "hann", 1, None, fs / 2, True, transient=True)
    assert part.is_transient and part.samples.start <= 600 < part.samples.stop
    assert 2 * part.n < n
    assert part.n_fft >= n  # padded to the record's bin spacing or finer


@pytest.mark.parametrize("window", ["rectangular", "hann", "blackman"])
def test_the_strongest_bin_of_a_tone_on_a_bin_is_that_bin(window):
    fs, n = 1000.0, 1000
    t = np.arange(n) / fs
    for k0 in (3, 50, 123, 497):
        spectrum, part = windowed_spectrum(np.sin(2 * np.pi * k0 * fs / n * t + 0.4), fs, window,
                                           1, None, fs / 2, True)
        assert strongest_bin(np.abs(spectrum), part.lo, part.hi) == k0
        # on a bin the plain-bin estimate is that bin's frequency, exactly
        x = np.sin(2 * np.pi * k0 * fs / n * t + 0.4)
        assert dominant_frequency(x, fs, method="bin", window=window) == k0 * (fs / n)


def test_strongest_bin_takes_the_first_of_equal_values_inside_the_band():
    assert strongest_bin(np.array([9.0, 2.0, 5.0, 5.0, 1.0]), 1, 4) == 2
    assert strongest_bin(np.array([9.0, 2.0, 5.0, 5.0, 1.0]), 3, 4) == 3


@pytest.mark.parametrize("sigma", [0.7, 1.0, 2.5])
def test_parabolic_offset_is_exact_for_a_gaussian_peak(sigma):
    bins = np.arange(9.0)
    for delta in np.linspace(-0.5, 0.5, 11):
        peak = np.exp(-((bins - 4 - delta) ** 2) / (2 * sigma**2))
        # log|X| is then an exact parabola: only the rounding of the logs (about eps times
        # |log X| <= 2) over the curvature 1/sigma^2 is left
        assert parabolic_offset(peak, 4) == pytest.approx(delta, abs=100 * EPS * sigma**2)


@pytest.mark.parametrize("n", [256, 1000])
def test_parabolic_offset_bias_for_the_hann_window_is_below_its_stated_bound(n):
    k = n // 4
    for delta in np.linspace(-0.5, 0.5, 21):
        tone = np.exp(2j * np.pi * (k + delta) * np.arange(n) / n)
        spectrum = np.fft.fft(tone * window_weights("hann", n))
        # the module's stated bias of the log-parabola on the Hann main lobe: below 0.02 bin
        assert abs(parabolic_offset(spectrum, k) - delta) < 0.02


@pytest.mark.parametrize("window", ["hann", "rectangular"])
@pytest.mark.parametrize("n", [64, 256, 1000])
def test_jacobsen_offset_of_one_complex_tone(window, n):
    k = n // 4
    for delta in np.linspace(-0.5, 0.5, 21):
        tone = np.exp(2j * np.pi * (k + delta) * np.arange(n) / n)
        spectrum = np.fft.fft(tone * window_weights(window, n))
        # The estimator is derived for the sinc kernel; the DFT's Dirichlet kernel differs from it
        # by a relative (pi x)^2 / (6 n^2) at a distance of x <= 1.5 bins from the tone, which
        # moves the offset by at most about (1.5 pi)^2 / (6 n^2) < 4 / n^2 bin.
        assert abs(jacobsen_offset(spectrum, k, 1, window) - delta) < 4.0 / n**2


def test_interpolated_frequency_is_the_bin_where_a_neighbour_is_missing():
    spectrum = np.array([3.0, 2.0, 1.0, 0.5]) + 0j
    for method in ("bin", "parabolic", "jacobsen"):
        assert interpolated_frequency(spectrum, 0, 6.0, 6, method, "hann", 1) == 0.0
        assert interpolated_frequency(spectrum, 3, 6.0, 6, method, "hann", 1) == 3.0


def test_local_maxima_against_their_definition():
    rng = np.random.default_rng(7)
    for _ in range(50):
        magnitude = rng.integers(0, 4, 30).astype(float)  # small integers: many plateaus
        lo, hi = sorted(rng.choice(30, 2, replace=False))
        witness = [k for k in range(lo + 1, hi)
                   if magnitude[k] > magnitude[k - 1] and magnitude[k] >= magnitude[k + 1]]
        got = local_maxima(magnitude, lo, hi)
        assert sorted(got.tolist()) == witness
        assert np.all(np.diff(magnitude[got]) <= 0)  # strongest first


def test_strongest_separated_keeps_the_stronger_of_two_close_peaks():
    rng = np.random.default_rng(9)
    for _ in range(50):
        magnitude = rng.random(60)
        candidates = local_maxima(magnitude, 0, 59)
        chosen = strongest_separated(magnitude, candidates, 4, 5.0, 0.5)  # 10 bins apart
        assert all(abs(i - j) * 0.5 >= 5.0 for i in chosen for j in chosen if i != j)
        for k in candidates:  # a candidate left out is close to a stronger chosen peak
            if k not in chosen and len(chosen) < 4:
                assert any(abs(k - j) * 0.5 < 5.0 and magnitude[j] >= magnitude[k]
                           for j in chosen)


# --- the guards of the spectral peak ---------------------------------------------------------


@pytest.mark.parametrize("scale", [1e-300, 1e-20, 1.0, 3.0, 1e200, np.finfo(float).max])
def test_unit_scaled_is_exact_and_lands_in_half_to_one(scale):
    x = scale * np.array([0.3, -1.0, 0.7])
    scaled, exponent = unit_scaled(x)
    assert 0.5 <= np.max(np.abs(scaled)) < 1.0
    assert np.array_equal(np.ldexp(scaled, exponent), x)  # a power of two is exact


def test_transient_span_finds_a_burst_and_leaves_a_steady_tone_alone():
    rng = np.random.default_rng(2)
    n = 1000
    t = np.arange(n) / 1000.0
    burst = np.where((t >= 0.3) & (t < 0.4), np.sin(2 * np.pi * 60 * t), 0.0)
    span = transient_span(burst + 1e-3 * rng.standard_normal(n))
    # blocks of 15 samples: the span is the burst rounded out to whole blocks
    assert span.start <= 300 and 400 <= span.stop <= 400 + 15
    assert transient_span(np.sin(2 * np.pi * 3.3 * t)) is None  # a slow steady tone
    assert transient_span(rng.standard_normal(n)) is None  # white noise


def test_search_bins_count_edges_on_a_bin_despite_rounding():
    fs, n = 1000.0, 3 * 7 * 11
    df = fs / n
    for k in range(1, n // 2):
        assert search_bins(k * df, (k + 0.5) * df, df) == (k, k)
        assert search_bins((k - 0.5) * df, k * df, df) == (k, k)
    with pytest.raises(ValueError, match="holds no FFT bin"):
        search_bins(1.1 * df, 1.9 * df, df)


def test_analysed_part_starts_the_band_two_bins_into_a_transient():
    fs, n = 1000.0, 1000
    t = np.arange(n) / fs
    tap, _ = unit_scaled(np.exp(-t / 0.02) * np.sin(2 * np.pi * 140 * t))
    part = analysed_part(tap, fs, 1, None, fs / 2, transient=True)
    assert part.is_transient
    assert part.lo == math.ceil(2.0 * fs / part.n / (fs / part.n_fft) - 1e-9)
    given = analysed_part(tap, fs, 1, 0.0, fs / 2, transient=True)  # a given fmin is kept
    assert given.is_transient and given.lo == 0
    whole = analysed_part(tap, fs, 1, None, fs / 2)  # the default: the whole record
    assert not whole.is_transient and (whole.n, whole.lo) == (n, 1)


# --- the decay fit ----------------------------------------------------------------------------


@pytest.mark.parametrize("n", [64, 65])
def test_analytic_envelope_of_a_tone_on_a_bin_is_its_amplitude(n):
    x = 3.0 * np.cos(2 * np.pi * 5 * np.arange(n) / n + 0.2)  # its Hilbert pair is 3 sin(...)
    # two FFTs of n terms: rounding of order n eps relative to the amplitude
    np.testing.assert_allclose(analytic_envelope(x), 3.0, rtol=0, atol=3.0 * n * EPS)
    np.testing.assert_allclose(analytic_envelope(x), np.abs(sps.hilbert(x)), atol=3.0 * n * EPS)


def test_weighted_line_against_numpy_polyfit():
    rng = np.random.default_rng(4)
    t = np.sort(rng.random(40))
    y = 0.5 - 2.0 * t + 0.1 * rng.standard_normal(40)
    w = rng.random(40) + 0.1
    c0, c1, r2 = weighted_line(t, y, w)
    # polyfit minimises sum (w_p r)^2: w_p = sqrt(w) gives the same problem; t in [0, 1] keeps
    # its normal equations well conditioned (condition below 100), so both agree to 1e-12
    slope, intercept = np.polyfit(t, y, 1, w=np.sqrt(w))
    assert (c0, c1) == pytest.approx((intercept, slope), rel=1e-12, abs=1e-12)
    residual = y - c0 - c1 * t
    mean = (w * y).sum() / w.sum()
    assert r2 == pytest.approx(1 - (w * residual**2).sum() / (w * (y - mean) ** 2).sum(),
                               rel=1e-12)


def test_loglinear_fit_recovers_an_exact_exponential():
    t = np.arange(500) / 1000.0
    for a, b in [(1.5, -10.0), (0.6, -3.0), (0.9, -200.0)]:  # scaled, as fit_decay passes it
        got_a, got_b = loglinear_fit(t, a * np.exp(b * t))
        # log(a e^{bt}) is a line up to the rounding of exp and log (a few eps times |log env|),
        # spread over t in [0, 0.5]
        scale = 8 * EPS * max(1.0, abs(math.log(a)) + abs(b) * t[-1])
        assert got_b == pytest.approx(b, abs=scale / t[-1] * 4)
        assert math.log(got_a) == pytest.approx(math.log(a), abs=scale * 4)


def test_nonlinear_envelope_fit_stays_at_an_exact_exponential():
    t = np.arange(400) / 1000.0
    env = 1.5 * np.exp(-12.0 * t)
    a, b, r2 = envelope_fit(t, env, nonlinear=True)
    # started at the exact answer, least_squares stops at its relative step tolerance 1e-8
    assert (a, b) == pytest.approx((1.5, -12.0), rel=1e-8)
    assert r2 == pytest.approx(1.0, abs=1e-12)


def test_damped_sinusoid_fit_recovers_an_exact_damped_sinusoid():
    fs = 1000.0
    t = np.arange(600) / fs
    x = 2.0 * np.exp(-t / 0.08) * np.sin(2 * np.pi * 61.3 * t + 0.9)
    a, b, r2, n_fit = damped_sinusoid_fit(x, t, 600, -11.0)
    # exact model, noise-free: least_squares stops at its relative step tolerance xtol=1e-8
    assert (a, b) == pytest.approx((2.0, -1 / 0.08), rel=1e-6)
    assert r2 == pytest.approx(1.0, abs=1e-9) and n_fit == 600
    # a window shorter than one period of the tone cannot name its frequency
    assert damped_sinusoid_fit(x, t, 12, -11.0) is None


def test_the_checks_follow_the_documented_rules():
    witness = (1.0, -10.0, 0.999, 500)  # explains the record, decays
    assert envelope_status(-10.0, False, False, witness) == "not_decaying"
    assert envelope_status(-10.0, True, True, witness) == "too_few_points"
    assert envelope_status(-10.0 / 1.04, True, False, witness) == "inconsistent"  # 4 % apart
    assert envelope_status(-10.0 / 1.02, True, False, witness) == "ok"  # 2 % apart
    assert envelope_status(-5.0, True, False, (1.0, -10.0, 0.9, 500)) == "ok"  # poor witness
    assert envelope_status(-5.0, True, False, None) == "ok"
    assert sinusoid_status(witness, False) == "ok"
    assert sinusoid_status((1.0, 2.0, 0.999, 500), True) == "not_decaying"
    assert sinusoid_status((1.0, -10.0, 0.5, 500), True) == "poor_fit"
    assert sinusoid_status((1.0, -10.0, 0.5, 500), False) == "not_decaying"
    assert sinusoid_status(None, False) == "not_decaying"


# --- the guards of the decay fit -------------------------------------------------------------


def test_clipped_mask_against_its_definition():
    x = np.array([0.0, 1.0, 1.0, 0.5, -1.0, -1.0, -1.0, 0.2, 1.0, 0.3])
    # flat runs (two or more neighbours) at the maximum or the minimum; a lone 1.0 is no run
    expected = [False, True, True, False, True, True, True, False, False, False]
    assert clipped_mask(x).tolist() == expected


def test_a_maximum_beside_a_minimum_is_no_flat_run():
    # a tone near the Nyquist frequency swings from one extreme to the other in one sample
    assert not clipped_mask(np.array([0.0, 0.3, 1.0, -1.0, 0.2, 0.0])).any()
    fs, f, tau = 1000.0, 494.0, 0.02
    t = np.arange(1000) / fs
    for phase in np.linspace(0.0, np.pi, 12, endpoint=False):
        assert not clipped_mask(np.exp(-t / tau) * np.sin(2 * np.pi * f * t + phase)).any()


def test_decay_region_leaves_out_the_edges_the_clipping_and_the_noise_tail():
    fs, n = 1000.0, 1000
    t = np.arange(n) / fs
    rng = np.random.default_rng(6)
    x = 3.0 * np.exp(-t / 0.05) * np.sin(2 * np.pi * 80 * t) + 1e-3 * rng.standard_normal(n)
    x = np.clip(x, -1.0, 1.0)
    clipped = clipped_mask(x)
    env = analytic_envelope(x - x.mean())
    period = fs / 80.0
    region = decay_region(env, clipped, period, 3.0)
    edge = math.ceil(period)
    assert region.first == np.flatnonzero(clipped)[-1] + 1
    assert region.keep[0] == region.first + edge and not region.too_short
    # it stops before the envelope first sinks to three times the floor of the noise tail
    floor = np.median(env[n - edge - (n - 2 * edge - region.first) // 10 : n - edge])
    assert np.all(env[region.keep] > 3.0 * floor)
    assert region.end == region.keep[-1] + 1 + edge
    # a record shorter than four periods has no region
    assert decay_region(env[:30], clipped[:30], period, 3.0) is None


def test_rate_standard_error_against_numpy_polyfit():
    rng = np.random.default_rng(9)
    tk = np.arange(50) / 1000.0
    ek = 0.8 * np.exp(-20.0 * tk + 0.05 * rng.standard_normal(50))
    a, b = loglinear_fit(tk, ek)
    # polyfit's covariance with cov="unscaled" is (X^T W X)^-1; times the residual variance
    # sum w r^2 / (n - 2) it is the textbook standard error; both solve the same 2x2 system
    _, cov = np.polyfit(tk, np.log(ek), 1, w=ek, cov="unscaled")
    r = np.log(ek) - math.log(a) - b * tk
    # the weighted residuals' autocorrelations, lag by lag, summed while they stay positive
    u = ek * r
    rho = [float(u[k:] @ u[: u.size - k]) / float(u @ u) for k in range(1, u.size)]
    positive = next((k for k, value in enumerate(rho) if value <= 0), len(rho))
    time = 1 + 2 * sum(rho[:positive])
    expected = math.sqrt(cov[0, 0] * (ek**2 * r**2).sum() / (50 - 2) * time)
    assert _rate_standard_error(tk, ek, a, b) == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize(("bandwidth", "understated"), [(None, 1.3), (100.0, 3.0), (50.0, 4.5)])
def test_the_rate_standard_error_covers_the_scatter_of_correlated_envelopes(bandwidth,
                                                                           understated):
    """Over repeated records of one decay under noise (white, or band-passed about the tone as
    a filter leaves it), the fitted rate scatters by about its standard error. The samples of
    an envelope are correlated; counted as independent, the error is 1.4 to 5 times too small."""
    from scipy.signal import butter, sosfiltfilt

    fs, n, f = 1000.0, 1000, 120.0
    t = np.arange(n) / fs
    clean = np.exp(-t / 0.15) * np.sin(2 * np.pi * f * t)
    rng = np.random.default_rng(1)
    sos = None if bandwidth is None else butter(
        2, [f - bandwidth / 2, f + bandwidth / 2], btype="bandpass", fs=fs, output="sos")
    rates, errors, naive = [], [], []
    for _ in range(300):
        e = rng.standard_normal(n)
        if sos is not None:
            e = sosfiltfilt(sos, e)
            e /= e.std()
        env = analytic_envelope(clean + 0.02 * e)
        stop = 20 + np.flatnonzero(env[20:] < 9 * np.median(env[-100:]))[0]
        tk, ek = t[20:stop], env[20:stop]
        a, b = loglinear_fit(tk, ek)
        rates.append(b)
        errors.append(_rate_standard_error(tk, ek, a, b))
        w, r = ek**2, np.log(ek) - math.log(a) - b * tk
        naive.append(math.sqrt((w * r * r).sum() / (tk.size - 2)
                               / (w * (tk - (w * tk).sum() / w.sum()) ** 2).sum()))
    scatter = np.std(rates)
    # 300 records measure a standard deviation to about 1/sqrt(2 * 300) = 4 %; the correlation
    # time is itself estimated from each record's residuals, which leaves up to about 20 %
    assert 0.8 < scatter / np.mean(errors) < 1.3
    # the independent count understates it (docs/theory/decay.rst: 1.4 and 5.2 times)
    assert scatter / np.mean(naive) > understated


def test_fitted_samples_cuts_a_noise_tail_and_keeps_a_decaying_one():
    fs, n = 1000.0, 1000
    t = np.arange(n) / fs
    clean = np.zeros(n, bool)
    rng = np.random.default_rng(3)
    noisy = np.exp(-t / 0.05) * np.sin(2 * np.pi * 80 * t) + 1e-3 * rng.standard_normal(n)
    env = analytic_envelope(noisy)
    region = decay_region(env, clean, fs / 80.0, 3.0)
    keep, _, too_short, separable = _fitted_samples(t, env, region, 3.0)
    assert np.array_equal(keep, region.keep) and not too_short and separable
    slow = analytic_envelope(np.exp(-t / 1.0) * np.sin(2 * np.pi * 80 * t))
    region = decay_region(slow, clean, fs / 80.0, 3.0)
    keep, end, too_short, separable = _fitted_samples(t, slow, region, 3.0)
    assert np.array_equal(keep, region.whole) and end == n and not too_short and separable
