"""A Kalman filter for the accelerometer noise.

Section 3 of the paper filters the sensor noise with a Kalman filter without saying which.

Model (linear, Gaussian, stated in full)::

    state        s[k] = F s[k-1] + w[k],    w ~ N(0, Q)
    measurement  y[k] = H s[k]   + v[k],    v ~ N(0, r)

Two state models are built in:

``random_walk(process_std, measurement_std)``
    ``s = [acceleration]``, ``F = [[1]]``, ``Q = [[process_std^2]]``: a slowly wandering level, the
    textbook choice for sensor noise (it lags an oscillation);
``resonator(frequency, fs, damping_ratio, process_std, measurement_std)``
    ``s = [a[k], a[k-1]]``, a damped mode of the probe driven by white noise (an AR(2) process)::

        a[k] = 2 rho cos(theta) a[k-1] - rho^2 a[k-2] + w[k],
        theta = 2 pi f / fs,  rho = exp(-zeta theta)

    so ``F = [[2 rho cos(theta), -rho^2], [1, 0]]``, ``Q = diag(process_std^2, 0)``,
    ``H = [1, 0]``. It follows a vibration near ``f`` without lag and removes noise outside its
    band.

The filter starts from ``s = 0`` with a diffuse covariance ``P0 = initial_variance I``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import check_in_range, check_positive
from ._checks import check_fs, check_signal

__all__ = ["KalmanFilter", "KalmanResult"]


@dataclass(frozen=True, eq=False)
class KalmanResult:
    """Output of :meth:`KalmanFilter.filter`.

    Attributes
    ----------
    estimate : ndarray of shape (n,)
        Filtered measurement ``H s[k|k]``, unit of the input.
    states : ndarray of shape (n, n_states)
        Filtered states ``s[k|k]``.
    variance : ndarray of shape (n,)
        Variance of the filtered measurement ``H P[k|k] H^T``, unit squared.
    gain : ndarray of shape (n, n_states)
        Kalman gains ``K[k]``.
    """

    estimate: np.ndarray
    states: np.ndarray
    variance: np.ndarray
    gain: np.ndarray


@dataclass(frozen=True, eq=False)
class KalmanFilter:
    """Linear Kalman filter with a scalar measurement.

    Parameters
    ----------
    transition : array of shape (m, m)
        ``F``.
    observation : array of shape (m,)
        ``H`` (one row).
    process_covariance : array of shape (m, m)
        ``Q``, symmetric positive semi-definite.
    measurement_variance : float
        ``r`` > 0, unit squared.
    initial_variance : float
        Diagonal of the diffuse starting covariance ``P0``.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal import KalmanFilter
    >>> kf = KalmanFilter.random_walk(process_std=0.1, measurement_std=1.0)
    >>> res = kf.filter(np.ones(200))
    >>> round(float(res.estimate[-1]), 6), round(float(res.gain[-1, 0]), 4)
    (1.0, 0.0951)
    """

    transition: np.ndarray
    observation: np.ndarray
    process_covariance: np.ndarray
    measurement_variance: float
    initial_variance: float = 1e6

    def __post_init__(self):
        from .._validate import check_array

        f = check_array("transition", self.transition, ndim=2)
        m = f.shape[0]
        if f.shape != (m, m):
            raise ValueError(f"transition must be square, got shape {f.shape}")
        h = check_array("observation", self.observation, ndim=1)
        if h.shape != (m,):
            raise ValueError(f"observation must have shape ({m},), got {h.shape}")
        q = check_array("process_covariance", self.process_covariance, ndim=2)
        if q.shape != (m, m) or not np.allclose(q, q.T):
            raise ValueError(f"process_covariance must be a symmetric ({m}, {m}) matrix")
        if np.min(np.linalg.eigvalsh(q)) < -1e-12 * max(1.0, np.abs(q).max()):
            raise ValueError("process_covariance must be positive semi-definite")
        object.__setattr__(self, "transition", f)
        object.__setattr__(self, "observation", h)
        object.__setattr__(self, "process_covariance", q)
        object.__setattr__(self, "measurement_variance",
                           check_positive("measurement_variance", self.measurement_variance))
        object.__setattr__(self, "initial_variance",
                           check_positive("initial_variance", self.initial_variance))

    @classmethod
    def random_walk(cls, process_std: float, measurement_std: float) -> KalmanFilter:
        """Scalar random walk ``s[k] = s[k-1] + w``, ``y = s + v`` (see the module notes)."""
        q = check_positive("process_std", process_std) ** 2
        r = check_positive("measurement_std", measurement_std) ** 2
        return cls(np.eye(1), np.ones(1), np.array([[q]]), r)

    @classmethod
    def resonator(cls, frequency: float, fs: float, damping_ratio: float, process_std: float,
                  measurement_std: float) -> KalmanFilter:
        """Damped mode at ``frequency`` (Hz) driven by white noise, sampled at ``fs`` (Hz)."""
        fs = check_fs(fs)
        frequency = check_in_range("frequency", frequency, 0.0, fs / 2.0)
        zeta = check_in_range("damping_ratio", damping_ratio, 0.0, 1.0, low_inclusive=True)
        q = check_positive("process_std", process_std) ** 2
        r = check_positive("measurement_std", measurement_std) ** 2
        theta = 2.0 * math.pi * frequency / fs
        rho = math.exp(-zeta * theta)
        f = np.array([[2.0 * rho * math.cos(theta), -rho * rho], [1.0, 0.0]])
        return cls(f, np.array([1.0, 0.0]), np.diag([q, 0.0]), r)

    def filter(self, y) -> KalmanResult:
        """Run the filter over the measurements ``y`` (shape ``(n,)``)."""
        y = check_signal("y", y, min_length=1)
        f, h, q, r = (self.transition, self.observation, self.process_covariance,
                      self.measurement_variance)
        m = f.shape[0]
        s = np.zeros(m)
        p = self.initial_variance * np.eye(m)
        n = y.shape[0]
        states = np.empty((n, m))
        gains = np.empty((n, m))
        variance = np.empty(n)
        identity = np.eye(m)
        for k in range(n):
            if k > 0:
                s = f @ s
                p = f @ p @ f.T + q
            ph = p @ h
            innovation_variance = h @ ph + r
            gain = ph / innovation_variance
            s = s + gain * (y[k] - h @ s)
            # Joseph form: stays symmetric positive semi-definite under rounding.
            a = identity - np.outer(gain, h)
            p = a @ p @ a.T + r * np.outer(gain, gain)
            states[k] = s
            gains[k] = gain
            variance[k] = h @ p @ h
        return KalmanResult(states @ h, states, variance, gains)
