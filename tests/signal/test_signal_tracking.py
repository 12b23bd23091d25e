import numpy as np
import pytest

from ebantenna.signal import FrequencyTracker, morlet_scalogram

FS = 1000.0
T = np.arange(1000) / FS


def test_tracks_a_noisy_chirp():
    rng = np.random.default_rng(0)
    x = np.sin(2 * np.pi * (80 * T + 20 * T**2)) + 0.1 * rng.standard_normal(T.size)
    truth = 80 + 40 * T  # instantaneous frequency of the chirp, Hz
    res = FrequencyTracker(FS).track(x)
    err = np.abs(res.frequency - truth)[100:]
    assert err.max() < 2.5  # lag plus noise, after 0.1 s of settling
    assert np.median(err) < 1.5
    # The band-pass output is the chirp itself: most of the power, in phase.
    corr = np.corrcoef(res.bandpass[100:], np.sin(2 * np.pi * (80 * T + 20 * T**2))[100:])[0, 1]
    assert corr > 0.95


def test_agrees_with_the_scalogram_ridge():
    x = np.sin(2 * np.pi * (150 * T - 30 * T**2))  # 150 Hz down to 90 Hz
    res = FrequencyTracker(FS).track(x)
    freqs = np.arange(60.0, 200.0, 0.5)
    ridge = morlet_scalogram(x, FS, freqs, bandwidth=4.0).ridge()
    mid = slice(150, 850)
    assert np.max(np.abs(res.frequency[mid] - ridge[mid])) < 2.5


def test_follows_the_strongest_of_two_decaying_modes():
    """The strong low mode dies within ~0.1 s; the weaker high mode then dominates (zone 3)."""
    rng = np.random.default_rng(1)
    x = (3 * np.exp(-T / 0.03) * np.sin(2 * np.pi * 60 * T)
         + np.exp(-T / 0.4) * np.sin(2 * np.pi * 150 * T) + 0.01 * rng.standard_normal(T.size))
    res = FrequencyTracker(FS).track(x)
    assert np.all(np.abs(res.frequency[150:] - 150.0) < 1.0)
    assert res.final_frequency() == pytest.approx(150.0, abs=0.2)


def test_reacquires_after_a_mode_change():
    x = np.where(T < 0.4, np.sin(2 * np.pi * 70 * T), 0.6 * np.sin(2 * np.pi * 260 * T))
    with_restart = FrequencyTracker(FS).track(x)
    assert np.all(np.abs(with_restart.frequency[520:] - 260.0) < 1.0)
    assert with_restart.reacquired.size >= 1
    assert np.all((with_restart.reacquired > 400) & (with_restart.reacquired <= 520))
    assert np.all(np.abs(with_restart.frequency[150:390] - 70.0) < 0.5)


def test_bandwidth_and_fixed_start():
    tracker = FrequencyTracker(FS, pole_radius=0.98)
    assert tracker.bandwidth == pytest.approx(0.02 * FS / np.pi)
    res = tracker.track(np.sin(2 * np.pi * 100 * T), f0=95.0)
    assert res.frequency[0] == pytest.approx(95.0)
    assert res.final_frequency() == pytest.approx(100.0, abs=0.05)


@pytest.mark.parametrize(
    "call, exc, match",
    [
        (lambda: FrequencyTracker(0.0), ValueError, "fs"),
        (lambda: FrequencyTracker(FS, pole_radius=1.0), ValueError, "pole_radius"),
        (lambda: FrequencyTracker(FS, forgetting=0.0), ValueError, "forgetting"),
        (lambda: FrequencyTracker(FS, fmin=300.0, fmax=200.0), ValueError, "fmin"),
        (lambda: FrequencyTracker(FS, fmax=600.0), ValueError, "fs/2"),
        (lambda: FrequencyTracker(FS, block=2), ValueError, "block"),
        (lambda: FrequencyTracker(FS, reacquire=1), TypeError, "reacquire"),
        (lambda: FrequencyTracker(FS).track(np.ones(1000)), ValueError, "constant"),
        (lambda: FrequencyTracker(FS).track(np.ones(10)), ValueError, "x"),
        (lambda: FrequencyTracker(FS).track(np.sin(T * 300), f0=600.0), ValueError, "f0"),
    ],
)
def test_bad_input(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


@pytest.mark.parametrize("tau", [0.03, 0.1, 0.3])
def test_lock_gate_stops_following_noise_after_a_decay(tau):
    rng = np.random.default_rng(3)
    x = np.exp(-T / tau) * np.sin(2 * np.pi * 87.0 * T) + 0.01 * rng.standard_normal(T.size)
    res = FrequencyTracker(FS).track(x)
    # the noise tail is unlocked: the tracker holds the decay's frequency and never restarts on
    # a noise bin (the band is 16 Hz wide; the held value is within the lock-in error, 0.5 Hz)
    assert res.reacquired.size == 0
    assert not res.locked[-100:].any()
    assert res.final_frequency() == pytest.approx(87.0, abs=0.5)
    assert np.all(np.abs(res.frequency[~res.locked] - res.frequency[res.locked][-1]) == 0)
    if tau <= 0.1:
        # without the gate (every block but the quietest counts as signal) it follows the noise
        # that fills the last half second (at tau = 0.3 s the decay still outlasts the record)
        ungated = FrequencyTracker(FS, lock_snr=1.0).track(x)
        assert abs(ungated.final_frequency() - 87.0) > 5.0


def test_quiet_start_is_not_constant():
    x = np.where(T < 0.3, 0.0, np.exp(-(T - 0.3) / 0.2) * np.sin(2 * np.pi * 120 * (T - 0.3)))
    res = FrequencyTracker(FS).track(x)
    assert not res.locked[:300].any() and res.locked[300:400].all()
    assert res.final_frequency() == pytest.approx(120.0, abs=0.5)


def test_never_locked_has_no_final_frequency():
    res = FrequencyTracker(FS).track(np.sin(2 * np.pi * 50 * T))
    assert res.locked.all()  # a steady tone has no quiet part
    empty = type(res)(res.t, res.frequency, res.bandpass, res.reacquired, np.zeros(T.size, bool))
    with pytest.raises(ValueError, match="never locked"):
        empty.final_frequency()
