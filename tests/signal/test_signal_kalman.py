import numpy as np
import pytest
from scipy.linalg import solve_discrete_are

from ebantenna.signal import KalmanFilter

FS = 1000.0


def _steady_gain(kf):
    """Witness: the steady-state gain from the discrete algebraic Riccati equation."""
    f = kf.transition
    h = kf.observation[None, :]
    p = solve_discrete_are(f.T, h.T, kf.process_covariance, np.array([[kf.measurement_variance]]))
    return (p @ h.T / (h @ p @ h.T + kf.measurement_variance)).ravel()


def test_random_walk_gain_converges_to_riccati_solution():
    kf = KalmanFilter.random_walk(process_std=0.05, measurement_std=0.5)
    res = kf.filter(np.random.default_rng(0).standard_normal(400))
    np.testing.assert_allclose(res.gain[-1], _steady_gain(kf), rtol=1e-9)
    # Closed form for the scalar case: K = (-q + sqrt(q^2 + 4 q r)) / (2 r) ... written as P/(P+r).
    q, r = 0.05**2, 0.5**2
    p_prior = (q + np.sqrt(q * q + 4 * q * r)) / 2
    assert res.gain[-1, 0] == pytest.approx(p_prior / (p_prior + r), rel=1e-9)


def test_resonator_gain_converges_to_riccati_solution():
    kf = KalmanFilter.resonator(120.0, FS, 0.02, process_std=0.3, measurement_std=1.0)
    res = kf.filter(np.random.default_rng(1).standard_normal(2000))
    np.testing.assert_allclose(res.gain[-1], _steady_gain(kf), rtol=1e-7)


def test_random_walk_error_matches_reported_variance():
    rng = np.random.default_rng(3)
    n, q, r = 20000, 0.05, 0.5
    truth = np.cumsum(q * rng.standard_normal(n))
    y = truth + r * rng.standard_normal(n)
    res = KalmanFilter.random_walk(q, r).filter(y)
    err = res.estimate[100:] - truth[100:]
    # Consistency: the empirical error variance equals the filter's own variance (2 % for 20k
    # correlated samples), and is far below the measurement noise variance.
    assert np.var(err) == pytest.approx(res.variance[-1], rel=0.05)
    assert np.var(err) < 0.25 * r**2


def test_resonator_cleans_a_noisy_vibration():
    rng = np.random.default_rng(4)
    t = np.arange(2000) / FS
    clean = np.exp(-t / 0.5) * np.sin(2 * np.pi * 120 * t)
    y = clean + 0.3 * rng.standard_normal(t.size)
    res = KalmanFilter.resonator(120.0, FS, 0.01, process_std=0.02, measurement_std=0.3).filter(y)
    raw_rms = np.sqrt(np.mean((y - clean) ** 2))
    kf_rms = np.sqrt(np.mean((res.estimate[200:] - clean[200:]) ** 2))
    assert kf_rms < raw_rms / 3
    # A random walk with the same noise model lags the oscillation and does much worse.
    rw = KalmanFilter.random_walk(0.02, 0.3).filter(y).estimate
    assert np.sqrt(np.mean((rw[200:] - clean[200:]) ** 2)) > 2 * kf_rms


@pytest.mark.parametrize(
    "call, exc, match",
    [
        (lambda: KalmanFilter.random_walk(0.0, 1.0), ValueError, "process_std"),
        (lambda: KalmanFilter.random_walk(1.0, -1.0), ValueError, "measurement_std"),
        (lambda: KalmanFilter.resonator(600.0, FS, 0.01, 1.0, 1.0), ValueError, "frequency"),
        (lambda: KalmanFilter.resonator(100.0, FS, 1.5, 1.0, 1.0), ValueError, "damping_ratio"),
        (lambda: KalmanFilter(np.eye(2), np.ones(3), np.eye(2), 1.0), ValueError, "observation"),
        (lambda: KalmanFilter(np.ones((2, 3)), np.ones(2), np.eye(2), 1.0), ValueError, "square"),
        (lambda: KalmanFilter(np.eye(2), np.ones(2), -np.eye(2), 1.0), ValueError, "semi-definite"),
        (lambda: KalmanFilter.random_walk(1.0, 1.0).filter([]), ValueError, "y"),
        (lambda: KalmanFilter.random_walk(1.0, 1.0).filter([np.nan]), ValueError, "y"),
        (lambda: KalmanFilter.random_walk("a", 1.0), TypeError, "process_std"),
    ],
)
def test_bad_input(call, exc, match):
    with pytest.raises(exc, match=match):
        call()
