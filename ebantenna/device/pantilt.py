"""The pan-tilt search of the paper (section 3, Figs. 7 and 8): sweep, detect contact, stop, record.

The probe sweeps an elliptical path in (pan, tilt), like the searching antenna of a stick insect
(Fig. 7). The accelerometer's FIFO is drained all the while and every new sample is checked against
a running baseline; the first sample whose acceleration departs from it by more than a threshold is
the contact (Fig. 8). The servos are then stopped at once (held where they were last commanded), the
vibration window is recorded into a :class:`~ebantenna.recording.Recording` (a short stretch before
the contact included), and the servos are released (PWM off). They are released on every way out,
an exception or Ctrl-C included.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field

import numpy as np

from .._validate import check_int, check_nonnegative, check_positive, check_real
from ..recording import Recording
from .mpu6050 import MPU6050
from .pca9685 import PCA9685
from .servo import Servo, ServoCalibration

__all__ = [
    "EllipticalPath",
    "ContactDetector",
    "PanTilt",
    "SearchConfig",
    "AcquisitionResult",
    "search_and_record",
]

logger = logging.getLogger(__name__)


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
    >>> from ebantenna.device.pantilt import EllipticalPath
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
        """Fastest angular speed of the pan servo along the path, degrees/s."""
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
    >>> from ebantenna.device.pantilt import ContactDetector
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
        ax = np.asarray(ax, dtype=np.float64)
        az = np.asarray(az, dtype=np.float64)
        found = None
        if self._x.size >= self.window:
            deviation = np.hypot(ax - self._x.mean(), az - self._z.mean())
            above = np.flatnonzero(deviation > self.threshold)
            if above.size:
                found = int(above[0])
        self._x = np.concatenate([self._x, ax])[-self.window:]
        self._z = np.concatenate([self._z, az])[-self.window:]
        return found


class PanTilt:
    """The two servos of the pan-tilt unit on one PCA9685.

    Parameters
    ----------
    pca : PCA9685
        The controller (initialised by :meth:`initialize`).
    pan, tilt : ServoCalibration
        Calibrations; defaults: pan on channel 0, tilt on channel 1, MG996R 0.5-2.5 ms for
        0-180 degrees, limited to 20-160 degrees.

    Examples
    --------
    >>> from ebantenna.device.simulated import SimulatedRig
    >>> from ebantenna.device.pca9685 import PCA9685
    >>> from ebantenna.device.pantilt import PanTilt
    >>> rig = SimulatedRig.quiet()
    >>> with PanTilt(PCA9685(rig.bus, clock=rig.clock)) as unit:
    ...     unit.initialize()
    ...     _ = unit.move(100.0, 80.0)
    ...     unit.stop()
    True
    >>> rig.pca.outputs_enabled()
    False
    """

    def __init__(self, pca: PCA9685, pan: ServoCalibration | None = None,
                 tilt: ServoCalibration | None = None):
        if not isinstance(pca, PCA9685):
            raise TypeError(f"pca must be a PCA9685, got {type(pca).__name__}")
        self.pca = pca
        self.pan = Servo(pca, pan or ServoCalibration(0, lower_limit=20.0, upper_limit=160.0),
                         "pan")
        self.tilt = Servo(pca, tilt or ServoCalibration(1, lower_limit=20.0, upper_limit=160.0),
                          "tilt")
        if self.pan.calibration.channel == self.tilt.calibration.channel:
            raise ValueError("pan and tilt servos must be on different channels, both are on "
                             f"{self.pan.calibration.channel}")

    def initialize(self) -> None:
        """Set up the PCA9685 (outputs off, 50 Hz)."""
        self.pca.initialize()

    def move(self, pan: float, tilt: float) -> tuple[float, float]:
        """Command both servos (clamped to their limits); returns the angles commanded, degrees."""
        return self.pan.move(pan), self.tilt.move(tilt)

    def stop(self) -> bool:
        """Hold both servos at their last commanded angles and confirm it from the registers.

        Returns True when both channels read back the pulse of the held angle (to within one
        count), i.e. no further motion has been commanded.
        """
        ok = True
        for servo in (self.pan, self.tilt):
            if servo.angle is None:
                ok = False
                continue
            servo.move(servo.angle)
            expected = servo.calibration.pulse(servo.angle)
            ok &= abs(self.pca.pulse(servo.calibration.channel) - expected) <= (
                1.0 / (4096 * self.pca.frequency))
        return bool(ok)

    def release(self) -> None:
        """Switch every PWM output off (the servos go limp)."""
        self.pca.all_off()
        self.pan.angle = self.tilt.angle = None

    def __enter__(self):
        return self

    def __exit__(self, exc_type, exc, tb):
        self.release()
        return False


@dataclass(frozen=True)
class SearchConfig:
    """How to search and what to record.

    Parameters
    ----------
    path : EllipticalPath
        The search path.
    threshold : float
        Contact threshold on the acceleration's departure from its baseline, m/s^2. Default 2.0.
    baseline_window : int
        Samples in the detector's baseline. Default 50.
    pre_trigger : float
        Recorded time before the contact sample, s. Default 0.05 s.
    duration : float
        Recorded time from the contact sample on, s. Default 1.0 s.
    poll_interval : float
        Time between FIFO drains and servo updates, s. Default 20 ms (one 50 Hz servo frame); it
        must stay below the 170 ms the FIFO holds at 1 kHz.
    max_search_time : float
        Give up after this long without a contact, s. Default 12 s (three loops).
    """

    path: EllipticalPath = field(default_factory=EllipticalPath)
    threshold: float = 2.0
    baseline_window: int = 50
    pre_trigger: float = 0.05
    duration: float = 1.0
    poll_interval: float = 0.02
    max_search_time: float = 12.0

    def __post_init__(self):
        if not isinstance(self.path, EllipticalPath):
            raise TypeError(f"path must be an EllipticalPath, got {type(self.path).__name__}")
        check_positive("threshold", self.threshold)
        check_int("baseline_window", self.baseline_window, minimum=1)
        check_nonnegative("pre_trigger", self.pre_trigger)
        check_positive("duration", self.duration)
        check_positive("poll_interval", self.poll_interval)
        check_positive("max_search_time", self.max_search_time)


@dataclass(frozen=True)
class AcquisitionResult:
    """What one search produced.

    Attributes
    ----------
    contact_detected : bool
        Whether a contact was found before ``max_search_time``.
    servos_stopped : bool
        Whether the servos were stopped on the contact (confirmed from the PCA9685's registers).
    recording : Recording or None
        The vibration window, when a contact was found.
    samples_lost : int
        Samples missing from the recording's window (0 when the FIFO was drained in time).
    stream_samples_lost : int
        Samples lost over the whole acquisition, search included.
    contact_time : float or None
        Time from the start of the search to the contact sample, s.
    contact_angles : tuple of float or None
        (pan, tilt) commanded when the servos were stopped, degrees.
    i2c_retries : int
        Transient bus errors retried on the way.
    """

    contact_detected: bool
    servos_stopped: bool
    recording: Recording | None
    samples_lost: int
    stream_samples_lost: int
    contact_time: float | None
    contact_angles: tuple[float, float] | None
    i2c_retries: int

    @property
    def samples(self) -> int:
        """Samples in the recording (0 without a contact)."""
        return 0 if self.recording is None else self.recording.n_samples

    def summary(self) -> dict:
        """JSON-ready description (the ``acquire`` command's contract)."""
        out = {
            "contact_detected": self.contact_detected,
            "servos_stopped": self.servos_stopped,
            "samples": self.samples,
            "samples_lost": self.samples_lost,
            "stream_samples_lost": self.stream_samples_lost,
            "contact_time_s": self.contact_time,
            "contact_angles_deg": None if self.contact_angles is None else
            list(self.contact_angles), "i2c_retries": self.i2c_retries,
        }
        if self.recording is not None:
            out["fs_hz"] = self.recording.fs
            out["samples_saturated"] = self.recording.metadata.get("samples_saturated", 0)
        return out


def search_and_record(mpu: MPU6050, pantilt: PanTilt, config: SearchConfig | None = None, *,
                      labels: dict | None = None) -> AcquisitionResult:
    """Sweep until contact, stop the servos, record the vibration window, release the servos.

    Parameters
    ----------
    mpu : MPU6050
        The accelerometer, already initialised.
    pantilt : PanTilt
        The servos, already initialised. They are released (PWM off) when this returns or raises.
    config : SearchConfig, optional
        Search and recording settings.
    labels : dict, optional
        JSON-serialisable labels stored in the recording's metadata (material, contact ratio, ...).

    Returns
    -------
    AcquisitionResult

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.device.simulated import SimulatedRig
    >>> from ebantenna.device import MPU6050, PCA9685, PanTilt, search_and_record
    >>> t = np.arange(600) / 1000.0
    >>> ring = 20.0 * np.exp(-t / 0.1) * np.sin(2 * np.pi * 40.0 * t)
    >>> rig = SimulatedRig.from_arrays(ring, 0.5 * ring, fs=1000.0, seed=1)
    >>> mpu = MPU6050(rig.bus, clock=rig.clock); mpu.initialize()
    >>> unit = PanTilt(PCA9685(rig.bus, clock=rig.clock)); unit.initialize()
    >>> result = search_and_record(mpu, unit)
    >>> result.contact_detected, result.servos_stopped, result.samples, result.samples_lost
    (True, True, 1050, 0)
    """
    config = SearchConfig() if config is None else config
    if not isinstance(config, SearchConfig):
        raise TypeError(f"config must be a SearchConfig, got {type(config).__name__}")
    clock = mpu.clock
    fs = mpu.config.fs
    mpu.check_poll_interval(config.poll_interval)
    pre = int(round(config.pre_trigger * fs))
    post = int(round(config.duration * fs))
    detector = ContactDetector(config.threshold, config.baseline_window)
    indices: list[np.ndarray] = []
    blocks: list[np.ndarray] = []
    trigger = None
    stopped = False
    angles = None
    try:
        mpu.start_fifo()
        start = clock.monotonic()
        while True:
            # Check the newest samples first, so that no move is commanded after a contact.
            block = mpu.read_fifo()
            if block.index.size:
                indices.append(block.index)
                blocks.append(block.counts)
                if trigger is None:
                    acc = mpu.to_acceleration(block.counts)
                    hit = detector.update(acc[:, 0], acc[:, 2])
                    if hit is not None:
                        stopped = pantilt.stop()
                        angles = (pantilt.pan.angle, pantilt.tilt.angle)
                        trigger = int(block.index[hit])
                        logger.info("contact at sample %d (%.3f s); servos held at %s", trigger,
                                    trigger / fs, angles)
                    else:
                        # While searching keep only what a pre-trigger stretch could need.
                        keep_from = int(block.index[-1]) - pre
                        while len(indices) > 1 and indices[0][-1] < keep_from:
                            indices.pop(0)
                            blocks.pop(0)
            if trigger is None:
                elapsed = clock.monotonic() - start
                if elapsed > config.max_search_time:
                    logger.info("no contact within %.1f s", config.max_search_time)
                    break
                pantilt.move(*config.path.angles(elapsed))
            elif mpu.stream_position >= trigger + post:
                break
            clock.sleep(config.poll_interval)
    finally:
        try:
            pantilt.release()
        finally:
            mpu.stop_fifo()
    retries = mpu.device.retries + pantilt.pca.device.retries
    if trigger is None:
        return AcquisitionResult(False, False, None, 0, mpu.samples_lost, None, None, retries)
    index = np.concatenate(indices)
    counts = np.concatenate(blocks)
    first = max(trigger - pre, 0)
    keep = (index >= first) & (index < trigger + post)
    lost = (trigger + post - first) - int(np.count_nonzero(keep))
    meta = {
        "source": "device",
        "trigger_time": (trigger - first) / fs,
        "contact_angles_deg": list(angles),
        "servos_stopped": stopped,
        "stream_samples_lost": mpu.samples_lost,
        "i2c_retries": retries,
    }
    meta.update(labels or {})
    recording = mpu.to_recording(index[keep], counts[keep], lost=lost, origin=first,
                                 metadata=meta)
    return AcquisitionResult(True, stopped, recording, lost, mpu.samples_lost, trigger / fs,
                             angles, retries)
