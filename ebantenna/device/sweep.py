"""The two halves of the search's loop that need no hardware: the elliptical path the probe
sweeps (the searching antenna of a stick insect, Fig. 7 of the paper) and the detector that
flags the contact in the accelerometer's samples (Fig. 8). :mod:`~ebantenna.device.pantilt`
drives the servos along the one and stops them on the other.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import check_array, check_int, check_nonnegative, check_positive, check_real

__all__ = ["EllipticalPath", "ContactDetector"]


@dataclass(frozen=True)
class EllipticalPath:
    """The search path: an ellipse in (pan, tilt) traversed at constant angular rate.

    ``pan(t) = pan_center + pan_amplitude sin(2 pi t / period)`` and
    ``tilt(t) = tilt_center + tilt_amplitude cos(2 pi t / period)``.

    Parameters
    ----------
    pan_center, tilt_center : float
        Centre of the ellipse, degrees (servo angles). Defaults 90, 90.
    pan_amplitude, tilt_amplitude : float
        Semi-axes, degrees. Defaults 60 and 15: a wide, flat sweep.
    period : float
        Time for one loop, s. Default 4 s.

    Examples
    --------
    >>> from ebantenna.device.sweep import EllipticalPath
    >>> path = EllipticalPath()
    >>> [round(a, 6) for a in path.angles(1.0)]  # a quarter loop: pan at its maximum
    [150.0, 90.0]
    """

    pan_center: float = 90.0
    tilt_center: float = 90.0
    pan_amplitude: float = 60.0
    tilt_amplitude: float = 15.0
    period: float = 4.0

    def __post_init__(self):
        check_real("pan_center", self.pan_center)
        check_real("tilt_center", self.tilt_center)
        check_nonnegative("pan_amplitude", self.pan_amplitude)
        check_nonnegative("tilt_amplitude", self.tilt_amplitude)
        check_positive("period", self.period)

    def angles(self, t: float) -> tuple[float, float]:
        """(pan, tilt) at time ``t`` (s) after the start, degrees."""
        phase = 2.0 * math.pi * check_real("t", t) / self.period
        return (self.pan_center + self.pan_amplitude * math.sin(phase),
                self.tilt_center + self.tilt_amplitude * math.cos(phase))

    def peak_rate(self) -> float:
        """Fastest angular speed of either servo along the path (the larger amplitude's),
        degrees/s."""
        return 2.0 * math.pi * max(self.pan_amplitude, self.tilt_amplitude) / self.period


class ContactDetector:
    """Flags the first sample whose acceleration leaves a running baseline by more than a threshold.

    The baseline is the mean of the last ``window`` samples before the block being examined; the
    deviation of a sample is ``hypot(ax - mean_x, az - mean_z)``. Nothing is flagged until the
    window is full.

    Parameters
    ----------
    threshold : float
        Deviation that counts as a contact, m/s^2.
    window : int
        Samples in the baseline.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.device.sweep import ContactDetector
    >>> det = ContactDetector(threshold=1.0, window=10)
    >>> print(det.update(np.zeros(10), np.zeros(10)))
    None
    >>> det.update(np.array([0.1, 0.2, 3.0]), np.zeros(3))
    2
    """

    def __init__(self, threshold: float, window: int = 50):
        self.threshold = check_positive("threshold", threshold)
        self.window = check_int("window", window, minimum=1)
        self._x = np.empty(0)
        self._z = np.empty(0)

    def update(self, ax, az) -> int | None:
        """Check new samples (m/s^2); return the position of the first contact in them, or None."""
        if np.size(ax) == 0 and np.size(az) == 0:  # a poll that found no new samples
            return None
        ax = check_array("ax", ax, ndim=1)
        az = check_array("az", az, ndim=1)
        if ax.shape != az.shape:
            raise ValueError(f"ax and az must have the same length, got {ax.size} and {az.size}")
        found = None
        if self._x.size >= self.window:
            deviation = np.hypot(ax - self._x.mean(), az - self._z.mean())
            above = np.flatnonzero(deviation > self.threshold)
            if above.size:
                found = int(above[0])
        self._x = np.concatenate([self._x, ax])[-self.window:]
        self._z = np.concatenate([self._z, az])[-self.window:]
        return found
