"""Each sensor/acquisition effect changes only what it should."""

import math

import numpy as np
import pytest
import scipy.signal as sps

from ebantenna.simulate import builtin_scene, simulate
from ebantenna.simulate.effects import (
    STANDARD_GRAVITY,
    Clipping,
    ClockJitter,
    LowPassFilter,
    MainsHum,
    Quantisation,
    SensorNoise,
    SteadyStateKalman,
)
from ebantenna.simulate.modes import filtered_exponentials
from ebantenna.simulate.scene import make_effect

BASE = builtin_scene("ideal").with_(contact=0.3, effects=("structural_damping",))


def _with(*names, scene=BASE, **params):
    return scene.with_(effects=scene.effects + tuple(make_effect(n) for n in names), **params)


def test_gravity_adds_g_to_z_only():
    plain, grav = simulate(BASE), simulate(_with("gravity"))
    assert np.array_equal(grav.ax, plain.ax)
    assert np.array_equal(grav.az, plain.az + STANDARD_GRAVITY)


def test_quantisation_leaves_values_on_the_lsb_grid():
    plain, q = simulate(BASE), simulate(_with("quantisation"))
    lsb = Quantisation().lsb()
    assert lsb == pytest.approx(STANDARD_GRAVITY / 2048, rel=1e-15)
    for a, b in ((q.ax, plain.ax), (q.az, plain.az)):
        counts = a / lsb  # integers up to the rounding of the division (|counts| < 2^16)
        assert np.abs(counts - np.round(counts)).max() < 1e-9
        assert np.abs(a - b).max() <= lsb / 2 * (1 + 1e-12)
    assert np.unique(q.ax).size > 100  # a real signal, not a constant


def test_clipping_caps_at_the_range_and_nothing_else():
    loud = BASE.with_(sweep_speed=20.0)  # a hard hit: peaks above 2 g
    plain = simulate(loud)
    clip = simulate(
        _with("clipping", scene=loud).with_(effects=loud.effects + (Clipping(range_g=2),))
    )
    low, high = Clipping(range_g=2).limits()
    assert high == pytest.approx(2 * STANDARD_GRAVITY * (32767 / 32768), rel=1e-15)
    inside = (plain.ax >= low) & (plain.ax <= high)
    assert 0 < inside.sum() < inside.size
    assert np.array_equal(clip.ax[inside], plain.ax[inside])
    assert np.all(clip.ax[plain.ax > high] == high) and np.all(clip.ax[plain.ax < low] == low)


def test_hum_adds_energy_only_at_its_frequency():
    plain, hum = simulate(BASE, seed=2), simulate(_with("mains_hum"), seed=2)
    for diff in (hum.ax - plain.ax, hum.az - plain.az):
        spectrum = np.abs(np.fft.rfft(diff)) / diff.size * 2
        freqs = np.fft.rfftfreq(diff.size, 1 / hum.fs)
        at = np.flatnonzero(freqs == 50.0)[0]
        assert spectrum[at] == pytest.approx(MainsHum().amplitude, rel=1e-9)
        assert np.delete(spectrum, at).max() < 1e-12
    assert not np.array_equal(simulate(_with("mains_hum"), seed=3).ax, hum.ax)  # random phase


def test_sensor_noise_has_the_datasheet_level():
    plain = simulate(BASE.with_(duration=4.0), seed=0)
    noisy = simulate(_with("sensor_noise", scene=BASE.with_(duration=4.0)), seed=0)
    expected = 400e-6 * STANDARD_GRAVITY * math.sqrt(500.0)
    for diff in (noisy.ax - plain.ax, noisy.az - plain.az):
        # 4000 normal samples: the sample std is within 5 % with overwhelming probability.
        assert diff.std() == pytest.approx(expected, rel=0.05)
        assert abs(diff.mean()) < 4 * expected / math.sqrt(diff.size)
    assert SensorNoise().std(1000.0) == pytest.approx(expected, rel=1e-15)


def test_dlpf_is_minus_3db_at_its_bandwidth_and_passes_dc():
    for bandwidth in (260.0, 94.0, 5.0):
        dlpf = LowPassFilter(bandwidth=bandwidth)
        # scipy's bilinear design pre-warps the band edge: -3 dB exactly there, 1 at DC (eps).
        assert abs(dlpf.frequency_response(bandwidth)) == pytest.approx(2**-0.5, rel=1e-12)
        assert abs(dlpf.frequency_response(0.0)) == pytest.approx(1.0, rel=1e-12)
    assert LowPassFilter().divider(1000.0) == 8 and LowPassFilter().divider(500.0) == 16
    with pytest.raises(ValueError, match="whole multiple of fs"):
        LowPassFilter().divider(3000.0)
    with pytest.raises(ValueError, match="internal_rate must exceed twice the bandwidth"):
        LowPassFilter(internal_rate=500.0)


def _sampled(coef, rate, t):
    return (coef[:, :, None] * np.exp(rate[:, :, None] * t)).sum(axis=1).imag


def test_dlpf_closed_form_equals_sosfilt_at_the_internal_rate_then_decimation():
    dlpf = LowPassFilter()
    # Three decaying modes per signal, one in band, two far above fs / 2 = 500 Hz.
    freqs = np.array([[40.0, 700.0, 1900.0], [130.0, 620.0, 2900.0]])
    rate = -np.array([[5.0, 30.0, 3.0], [1.0, 8.0, 60.0]]) + 2j * math.pi * freqs
    coef = np.array([[1 + 0.5j, -2 + 1j, 0.3 - 0.2j], [0.7j, 1.5, -0.4 + 0.1j]])
    t_internal = np.arange(8000) / dlpf.internal_rate
    witness = sps.sosfilt(dlpf.sos, _sampled(coef, rate, t_internal), axis=-1)[:, ::8]
    c2, r2 = filtered_exponentials(coef, rate, dlpf.sos, dlpf.internal_rate)
    closed = _sampled(c2, r2, np.arange(1000) / 1000.0)
    # Both sum a handful of O(1) terms over 8000 steps of a stable filter: rounding, 1e-12.
    assert np.abs(closed - witness).max() <= 1e-12 * np.abs(witness).max()


def test_a_tone_above_nyquist_lands_at_its_alias_with_the_filter_gain():
    dlpf = LowPassFilter()
    fs, f_tone = 1000.0, 700.0
    coef, rate = np.array([[1.0 + 0j]]), np.array([[2j * math.pi * f_tone]])
    c2, r2 = filtered_exponentials(coef, rate, dlpf.sos, dlpf.internal_rate)
    y = _sampled(c2, r2, np.arange(4000) / fs)[0, 2000:]  # the filter's transient long gone
    spectrum = np.abs(np.fft.rfft(y)) * 2 / y.size
    freqs = np.fft.rfftfreq(y.size, 1 / fs)
    assert freqs[np.argmax(spectrum)] == fs - f_tone  # 300 Hz
    # A whole number of periods: the bin holds the tone's amplitude, |H(700 Hz)|, to rounding.
    assert spectrum.max() == pytest.approx(abs(dlpf.frequency_response(f_tone)), rel=1e-9)


def test_dlpf_noise_has_the_datasheet_density_in_band():
    # White noise at the internal rate, filtered and decimated: in band (well below the 260 Hz
    # corner) its one-sided density is the datasheet's 400 ug/sqrt(Hz).
    dlpf, noise = LowPassFilter(), SensorNoise()
    rng = np.random.default_rng(1)
    raw = noise.draw(rng, 8 * 2**16, dlpf.internal_rate)
    y = dlpf.apply_internal(raw, 1000.0)[:, 1000:]
    f, psd = sps.welch(y, fs=1000.0, nperseg=1024)
    band = (f > 5) & (f < 50)
    density = np.sqrt(psd[:, band].mean())
    # Welch's estimate over ~60 segments x 2 axes x ~45 bins: about 1 % standard error.
    assert density == pytest.approx(noise.density, rel=0.05)


def test_kalman_gain_solves_the_riccati_equation_and_filter_matches_the_recursion():
    for ratio in (0.01, 1.0, 30.0):
        kf = SteadyStateKalman(ratio=ratio)
        # Witness: iterate the time-varying covariance recursion with r = 1, q = ratio.
        p = 1.0
        for _ in range(2000):
            prior = p + ratio
            gain = prior / (prior + 1.0)
            p = (1 - gain) * prior
        assert kf.gain() == pytest.approx(gain, rel=1e-12)
    z = np.random.default_rng(0).normal(size=(2, 50))
    kf = SteadyStateKalman()
    y = kf.apply(z, np.array([0.5, -1.0]))
    for row, level in ((0, 0.5), (1, -1.0)):
        est = level
        for n in range(50):
            est = est + kf.gain() * (z[row, n] - est)
            assert y[row, n] == pytest.approx(est, abs=1e-12)


def test_clock_jitter_samples_the_analytic_signal_at_jittered_times():
    scene = builtin_scene("ideal").with_(contact=0.25, effects=({"clock_jitter": {"rms": 2e-4}}))
    rec = simulate(scene, seed=11)
    offsets = ClockJitter(rms=2e-4).offsets(np.random.default_rng([11, ClockJitter.stream]), 1000)
    when = rec.t + offsets
    from ebantenna.simulate import modal_terms

    x, _ = modal_terms(scene)
    live = x.live[0]
    amp, w = x.amplitude[0, live], x.omega[0, live]
    expected = -(amp * w * np.sin(np.outer(np.maximum(when, 0.0), w))).sum(axis=1)
    expected[when < 0] = 0.0
    assert np.allclose(rec.ax, expected, rtol=0, atol=1e-11 * np.abs(expected).max())
    assert not np.allclose(rec.ax, simulate(builtin_scene("ideal").with_(contact=0.25)).ax)


def test_random_effects_are_reproducible_by_seed():
    paper = builtin_scene("paper")
    a, b, c = simulate(paper, seed=7), simulate(paper, seed=7), simulate(paper, seed=8)
    assert np.array_equal(a.ax, b.ax) and np.array_equal(a.az, b.az)
    assert not np.array_equal(a.ax, c.ax)
    # Dropping one random effect does not change another's draws.
    only_noise = BASE.with_(effects=("sensor_noise",))
    noise_and_hum = BASE.with_(effects=("sensor_noise", "mains_hum"))
    hum_only = BASE.with_(effects=("mains_hum",))
    lhs = simulate(noise_and_hum, seed=4).ax
    rhs = (
        simulate(only_noise, seed=4).ax
        + simulate(hum_only, seed=4).ax
        - simulate(BASE.with_(effects=()), seed=4).ax
    )
    assert np.allclose(lhs, rhs, rtol=0, atol=1e-12)


def test_paper_scene_readings_stay_in_range_and_z_reads_gravity():
    rec = simulate(builtin_scene("paper"), seed=1)
    assert np.abs(rec.ax).max() <= 16 * STANDARD_GRAVITY
    assert rec.az[-100:].mean() == pytest.approx(STANDARD_GRAVITY, abs=0.1)
