"""The pan-tilt search of the paper (section 3, Figs. 7 and 8): sweep, detect contact, stop, record.

The probe sweeps an elliptical path in (pan, tilt), like the searching antenna of a stick insect
(Fig. 7). The accelerometer's FIFO is drained all the while and every new sample is checked against
a running baseline; the first sample whose acceleration departs from it by more than a threshold is
the contact (Fig. 8). The servos are then stopped at once: held a small stated angle
(``back_off`` of :class:`SearchConfig`) behind the position they had certainly reached when the
contact sample was taken (the command before the one then in effect), so that the probe never pushes
further into the object. The vibration window is recorded
into a :class:`~ebantenna.recording.Recording` (a short stretch before the contact included), and
the servos are released (PWM off). They are released on every way out, an exception, Ctrl-C,
SIGTERM or SIGHUP included (:class:`~ebantenna.device.safety.ServoGuard`), and a run whose
accelerometer stops producing ends with
:class:`~ebantenna.device.watchdog.StreamStalledError` after ``watchdog`` seconds
(:class:`SearchConfig`).
"""

from __future__ import annotations

import errno
import logging
import math
from dataclasses import dataclass, field

from .._validate import (
    check_in_range,
    check_int,
    check_nonnegative,
    check_positive,
    check_real,
)
from ..chips.pca9685 import Led
from ..recording import Recording
from .i2c import I2CError, SettingError, transfer_time
from .mpu6050 import MPU6050
from .oe import OutputEnable
from .pca9685 import PCA9685
from .safety import ReleaseError, ServoGuard, SignalReceived
from .servo import Servo, ServoCalibration
from .sweep import ContactDetector, EllipticalPath
from .timing import CLOCK_TOLERANCE
from .watchdog import check_watchdog, stop_quietly

__all__ = [
    "EllipticalPath",
    "ContactDetector",
    "PanTilt",
    "SearchConfig",
    "AcquisitionResult",
    "search_and_record",
    "servo_bus_time",
]

logger = logging.getLogger(__name__)

#: Longest recording a search makes after a contact, s: the paper's windows last about 1 s.
MAX_DURATION = 60.0


#: The PCA9685's settings are read back every this many steps of the search: a backstop. A
#: brown-out is found at the next servo update already (the chip wakes without its register
#: auto-increment, so the pulse reads back wrong, ``_Search.sweep``, which sets the chip up
#: again and commands the same pulse at once), which bounds the dead servos by one step of the
#: search: the poll *and* the drain, up to 69 ms at 100 kHz and
#: 27 ms at 400 kHz (not the 20 ms poll alone).
PCA_CHECK_EVERY = 10


class PanTilt:
    """The two servos of the pan-tilt unit on one PCA9685.

    Parameters
    ----------
    pca : PCA9685
        The controller (initialised by :meth:`initialize`).
    pan, tilt : ServoCalibration
        Calibrations; defaults: pan on channel 0, tilt on channel 1, the conservative default
        pulse range of :class:`ServoCalibration` (22.5-157.5 degrees).

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
        # "is None", not "or": a falsy wrong value must reach Servo's check, not become a default
        self.pan = Servo(pca, ServoCalibration(0) if pan is None else pan, "pan")
        self.tilt = Servo(pca, ServoCalibration(1) if tilt is None else tilt, "tilt")
        if self.pan.calibration.channel == self.tilt.calibration.channel:
            raise ValueError("pan and tilt servos must be on different channels, both are on "
                             f"{self.pan.calibration.channel}")
        #: Whether the servo outputs were last read back switched off (False once a servo is
        #: commanded, or while that could not be confirmed).
        self.released = False

    def initialize(self) -> None:
        """Set up the PCA9685: outputs off first, then 50 Hz. Call it before anything else is
        started, so that servos left driven by an earlier run go limp at once. The servo
        outputs are read back switched off (:attr:`released`)."""
        self.released = False
        self.pca.initialize()
        self._confirm_off()

    def _confirm_off(self) -> None:
        """Read both servo channels back; :class:`I2CError` unless both are off."""
        on = [servo.name for servo in (self.pan, self.tilt)
              if self.pca.pulse(servo.calibration.channel)]
        if on:
            raise I2CError(errno.EIO, f"the {' and '.join(on)} servo output(s) read back ON "
                           "after being switched off")
        self.released = True

    def move(self, pan: float, tilt: float) -> tuple[float, float]:
        """Command both servos (clamped to their limits); returns the angles commanded, degrees."""
        pan, tilt = check_real("pan", pan), check_real("tilt", tilt)
        self.released = False
        return self.pan.move(pan), self.tilt.move(tilt)

    def stop(self, back_off: float = 0.0, at: tuple | None = None) -> bool:
        """Hold both servos and confirm it from the registers.

        Each servo is held ``back_off`` degrees behind ``at`` (its commanded angle when the
        contact happened; default its last commanded angle), against its last direction of
        motion, so that it never pushes further. Returns True when both channels read back the
        pulse of the held angle (to within one count).
        """
        back_off = check_nonnegative("back_off", back_off)
        if at is not None:
            if not isinstance(at, tuple | list) or len(at) != 2:
                raise TypeError(f"at must be a (pan, tilt) pair of angles or None, got {at!r}")
            at = (check_real("at pan", at[0]), check_real("at tilt", at[1]))
        self.released = False
        ok = True
        for k, servo in enumerate((self.pan, self.tilt)):
            if servo.angle is None:
                ok = False
                continue
            target = servo.angle if at is None else at[k]
            direction = 0.0 if servo.previous is None else math.copysign(
                1.0, servo.angle - servo.previous) if servo.angle != servo.previous else 0.0
            held = servo.calibration.clamp(target - direction * back_off)
            servo.move(held)
            expected = servo.calibration.pulse(held)
            ok &= abs(self.pca.pulse(servo.calibration.channel) - expected) <= (
                1.0 / (4096 * self.pca.frequency))
        return bool(ok)

    def release(self) -> None:
        """Switch every PWM output off (the servos go limp); raises :class:`I2CError` if the
        bus fails or a servo output reads back ON afterwards
        (:class:`~ebantenna.device.safety.ServoGuard` retries)."""
        self.released = False
        self.pca.all_off()
        self.pan.angle = self.tilt.angle = None
        self.pan.previous = self.tilt.previous = None
        self._confirm_off()

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
    back_off : float
        On contact, hold the servos this far behind the position they had certainly reached when
        the contact sample was taken, degrees. Default 7: more than one servo update along the
        default path on the Raspberry Pi's 100 kHz bus. An update comes once per step of the
        search, the poll interval *plus* the drain, which the bus makes long: up to 69 ms at
        100 kHz (27 ms at 400 kHz), so at the path's peak 94 deg/s a step moves a servo up to
        6.5 deg (2.5 deg). A faster path or a longer poll needs a larger ``back_off``.
    watchdog : float
        Longest time without a new accelerometer sample, s. Default 1 s.
    """

    path: EllipticalPath = field(default_factory=EllipticalPath)
    threshold: float = 2.0
    baseline_window: int = 50
    pre_trigger: float = 0.05
    duration: float = 1.0
    poll_interval: float = 0.02
    max_search_time: float = 12.0
    back_off: float = 7.0
    watchdog: float = 1.0

    def __post_init__(self):
        if not isinstance(self.path, EllipticalPath):
            raise TypeError(f"path must be an EllipticalPath, got {type(self.path).__name__}")
        check_positive("threshold", self.threshold)
        check_int("baseline_window", self.baseline_window, minimum=1)
        check_nonnegative("pre_trigger", self.pre_trigger)
        check_in_range("duration", self.duration, 0.0, MAX_DURATION, high_inclusive=True)
        check_positive("poll_interval", self.poll_interval)
        check_positive("max_search_time", self.max_search_time)
        check_nonnegative("back_off", self.back_off)
        check_positive("watchdog", self.watchdog)


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
    servos_released : bool
        Whether the PWM outputs were switched off at the end and read back so over I2C (the
        ``OE`` pin alone is not a release: :data:`~ebantenna.device.oe.OE_ONLY`).
    stream : dict
        The FIFO stream's report: estimated sample rate, restarts, overflows, rejected counts,
        timestamp uncertainty, fault log.
    servos_released_by : str or None
        What switched the outputs off: ``"i2c"`` (the release), ``"oe"`` (the ``OE`` pin
        alone, which holds them off only while the program runs; ``servos_released`` is then
        False) or None.
    """

    contact_detected: bool
    servos_stopped: bool
    recording: Recording | None
    samples_lost: int
    stream_samples_lost: int
    contact_time: float | None
    contact_angles: tuple[float, float] | None
    i2c_retries: int
    servos_released: bool = False
    stream: dict = field(default_factory=dict)
    servos_released_by: str | None = None

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
            "servos_released": self.servos_released,
            "servos_released_by": self.servos_released_by,
            "sample_rate_estimated_hz": self.stream.get("sample_rate_estimated_hz"),
            "sample_period_uncertainty_s": self.stream.get("sample_period_uncertainty_s"),
            "timestamp_uncertainty_s": (
                self.stream.get("timestamp_uncertainty_s") if self.recording is None
                else self.recording.metadata["timestamp_uncertainty_s"]),
            "timestamp_uncertainty_sole_reader_s": (
                self.stream.get("timestamp_uncertainty_sole_reader_s") if self.recording is None
                else self.recording.metadata["timestamp_uncertainty_sole_reader_s"]),
            "fifo_counts_rejected": self.stream.get("fifo_counts_rejected", 0),
            "fifo_restarts": self.stream.get("fifo_restarts", 0),
            "faults": len(self.stream.get("faults", [])),
        }
        out["pca9685_faults"] = self.stream.get("pca9685_faults", [])
        out["samples_discarded"] = self.stream.get("samples_discarded", 0)
        out["fifo_resets_unconfirmed"] = self.stream.get("fifo_resets_unconfirmed", 0)
        out["foreign_reads_detected"] = self.stream.get("foreign_reads_detected", 0)
        out["clock_outside_tolerance_suspected"] = self.stream.get(
            "clock_outside_tolerance_suspected", False)
        out["clock_rate_adapted"] = self.stream.get("clock_rate_adapted", False)
        out["clock_error_estimated"] = self.stream.get("clock_error_estimated")
        if self.recording is not None:
            meta = self.recording.metadata
            out["fs_hz"] = self.recording.fs
            out["samples_saturated"] = meta.get("samples_saturated", 0)
            out["samples_timing_suspect"] = meta.get("samples_timing_suspect", 0)
            out["sensor_flags"] = meta.get("sensor_check", {}).get("flags", [])
        return out

    def warnings(self) -> list[str]:
        """What the operator should judge before using the recording (one sentence each)."""
        out = [f"sensor: {flag}" for flag in self.summary().get("sensor_flags", [])]
        summary = self.summary()
        if summary.get("samples_timing_suspect"):
            out.append(f"{summary['samples_timing_suspect']} samples have flagged timestamps: "
                       "FIFO counts contradicted the clock's 5 % tolerance"
                       + (" (the clock itself is suspected)"
                          if summary["clock_outside_tolerance_suspected"] else ""))
        if summary["clock_rate_adapted"]:
            error = summary["clock_error_estimated"]
            side = "slow" if error < 0 else "fast"
            out.append(f"the accelerometer's clock runs {100 * abs(error):.1f} % {side}, "
                       f"outside its {100 * CLOCK_TOLERANCE:g} % tolerance: the timestamps and "
                       "the sample rate are those the FIFO counts measured")
        for fault in summary["pca9685_faults"]:
            again = "" if fault.endswith("written again") else ": set up again"
            out.append(f"PCA9685 {fault} during the search{again}")
        if summary["foreign_reads_detected"]:
            out.append(f"another program read the FIFO {summary['foreign_reads_detected']} "
                       "time(s): those drains were dropped")
        return out


def search_and_record(mpu: MPU6050, pantilt: PanTilt, config: SearchConfig | None = None, *,
                      labels: dict | None = None,
                      output_enable: OutputEnable | None = None) -> AcquisitionResult:
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
    output_enable : OutputEnable, optional
        The PCA9685's ``OE`` pin on a GPIO line: the release used when I2C cannot release the
        servos (:mod:`~ebantenna.device.oe`).

    Returns
    -------
    AcquisitionResult

    Raises
    ------
    ReleaseError
        When the servos could not be released after a search that finished: the error's
        ``result`` holds the :class:`AcquisitionResult`, recording included.

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
    if not isinstance(mpu, MPU6050):
        raise TypeError(f"mpu must be an MPU6050, got {type(mpu).__name__}")
    if not isinstance(pantilt, PanTilt):
        raise TypeError(f"pantilt must be a PanTilt, got {type(pantilt).__name__}")
    config = SearchConfig() if config is None else config
    if not isinstance(config, SearchConfig):
        raise TypeError(f"config must be a SearchConfig, got {type(config).__name__}")
    if not (output_enable is None or isinstance(output_enable, OutputEnable)):
        raise TypeError(f"output_enable must be an OutputEnable or None, got "
                        f"{type(output_enable).__name__}")
    busy = servo_bus_time(mpu.bus_hz)
    mpu.check_poll_interval(config.poll_interval, busy=busy)
    search = _Search(mpu, pantilt, config, labels, busy)
    guard = ServoGuard(pantilt.release, mpu.clock,
                       fallback=None if output_enable is None else output_enable.disable_outputs,
                       revive=pantilt.pca.device.health.revive)
    try:
        with guard:
            search.run()
    except ReleaseError as exc:  # the search finished: its recording is not dropped
        exc.result = search.result(guard)
        raise
    return search.result(guard)


def servo_bus_time(bus_hz: float) -> float:
    """The servos' bus time in one step of the search, s: two 4-byte pulse writes, each read
    back, and the PCA9685's settings read back (MODE1-MODE2, PRE_SCALE), which share the bus
    with the FIFO's drains.

    Examples
    --------
    >>> from ebantenna.device.pantilt import servo_bus_time
    >>> round(servo_bus_time(100e3) * 1e3, 2), round(servo_bus_time(400e3) * 1e3, 2)  # ms
    (3.61, 1.13)
    """
    pulses = 2 * (transfer_time(len(Led), bus_hz) + transfer_time(len(Led), bus_hz, read=True))
    return pulses + transfer_time(2, bus_hz, read=True) + transfer_time(1, bus_hz, read=True)


class _Search:
    """The steps of one :func:`search_and_record`: sweep and watch, stop on contact, record."""

    def __init__(self, mpu, pantilt, config, labels, busy=0.0):
        self.mpu, self.pantilt, self.config, self.labels = mpu, pantilt, config, labels
        self.busy = busy  # the servos' bus time per poll, s
        fs = mpu.config.fs
        self.pre = int(round(config.pre_trigger * fs))
        self.post = int(round(config.duration * fs))
        self.detector = ContactDetector(config.threshold, config.baseline_window)
        self.commands: list[tuple[float, float, float]] = []  # (host time, pan, tilt) of moves
        self.trigger = None
        self.stopped = False
        self.angles = None
        self.stream = None
        self.report: dict = {}
        self.steps = 0
        # PCA9685 settings found changed (and the chip set up again), pulses written again
        self.pca_faults: list[str] = []
        self.rewritten_before = len(pantilt.pca.rewritten)

    def run(self) -> None:
        """Poll until the window after a contact is recorded or the search time is up."""
        mpu, config, clock = self.mpu, self.config, self.mpu.clock
        try:
            self.stream = mpu.start_fifo()
            start = clock.monotonic()
            while True:
                # Check the newest samples first, so that no move is commanded after a contact.
                self.detect(mpu.read_fifo())
                if self.trigger is None:
                    elapsed = clock.monotonic() - start
                    if elapsed > config.max_search_time:
                        logger.info("no contact within %.1f s", config.max_search_time)
                        break
                    self.sweep(elapsed)
                elif mpu.stream_position >= self.trigger + self.post:
                    break
                window = (None if self.trigger is None
                          else (max(self.trigger - self.pre, 0), self.trigger + self.post))
                check_watchdog(mpu, config.watchdog, window=window, metadata=self.labels)
                # the poll follows the clock the stream measured (a fast one fills the FIFO
                # sooner than the check at the start assumed)
                clock.sleep(mpu.poll_wait(config.poll_interval, self.busy))
        except (KeyboardInterrupt, SignalReceived) as exc:
            # Interrupted after the contact: hand back what the window holds so far, marked.
            if self.trigger is not None:
                exc.recording = _partial(mpu, max(self.trigger - self.pre, 0),
                                         self.trigger + self.post, self.labels)
            raise
        finally:
            stop_quietly(mpu)
            self.report = {} if self.stream is None else self.stream.report()
            rewritten = self.pantilt.pca.rewritten[self.rewritten_before:]
            self.report["pca9685_faults"] = self.pca_faults + rewritten

    def detect(self, block) -> None:
        """Look for the contact in a drained block; on contact hold the servos where they had
        certainly been when the contact sample was taken."""
        if not block.index.size or self.trigger is not None:
            return
        acc = self.mpu.to_acceleration(block.counts)
        hit = self.detector.update(acc[:, 0], acc[:, 2])
        if hit is None:
            return
        self.trigger = int(block.index[hit])
        at = _reached_by(self.commands, self.stream.host_time(self.trigger))
        self.stopped = self.pantilt.stop(self.config.back_off, at)
        self.angles = (self.pantilt.pan.angle, self.pantilt.tilt.angle)
        logger.info("contact at sample %d (%.3f s); servos held at %s", self.trigger,
                    self.trigger / self.mpu.config.fs, self.angles)

    def sweep(self, elapsed: float) -> None:
        """Command the next point of the path; a failed update leaves the last command.

        Each pulse is read back (:meth:`~ebantenna.device.pca9685.PCA9685.write_channel`). One
        that reads back wrong twice is a brown-out (the chip lost its register auto-increment,
        so the block landed in one register) or a pulse that does not land: the PCA9685's
        settings are read back; a brown-out is logged and the chip set up again, anything else
        ends the search (the servo may hold a wrong pulse; the guard releases it). The settings
        are also read back every :data:`PCA_CHECK_EVERY` steps."""
        self.steps += 1
        if self.steps % PCA_CHECK_EVERY == 0:
            self.check_pca()
        try:
            moved = self.pantilt.move(*self.config.path.angles(elapsed))
        except SettingError:
            if not self.check_pca():
                raise
            try:  # set up again, its outputs off: the same command at once, not a step later
                moved = self.pantilt.move(*self.config.path.angles(elapsed))
            except I2CError as exc:
                logger.warning("servo update after the set-up failed (%s); the search goes on",
                               exc)
                return
        except I2CError as exc:  # the servos keep their last command
            logger.warning("servo update failed (%s); the search goes on", exc)
            return
        self.commands.append((self.mpu.clock.monotonic(), *moved))

    def check_pca(self) -> bool:
        """Read the PCA9685's settings back; set it up again if one changed (returns True)."""
        pca = self.pantilt.pca
        try:
            changed = pca.changed_settings()
            if not changed:
                return False
            what = ", ".join(f"{name} changed from 0x{w:02X} to 0x{v:02X}"
                             for name, w, v in changed)
            logger.warning("PCA9685: %s (a brown-out?); setting it up again", what)
            self.pca_faults.append(what)
            self.pantilt.initialize()
        except I2CError as exc:
            logger.warning("PCA9685 check failed (%s); the search goes on", exc)
            return False
        return True

    def result(self, guard: ServoGuard) -> AcquisitionResult:
        """What the search produced, with the release's outcome."""
        mpu, pantilt, fs = self.mpu, self.pantilt, self.mpu.config.fs
        retries = mpu.device.retries + pantilt.pca.device.retries
        released = dict(servos_released=guard.released, servos_released_by=guard.released_by)
        if self.trigger is None:
            return AcquisitionResult(False, False, None, 0, mpu.samples_lost, None, None,
                                     retries, stream=self.report, **released)
        first = max(self.trigger - self.pre, 0)
        meta = {
            "source": "device",
            "trigger_time": (self.trigger - first) / fs,
            "contact_angles_deg": list(self.angles),
            "servos_stopped": self.stopped,
            "back_off_deg": self.config.back_off,
            "stream_samples_lost": mpu.samples_lost,
            "i2c_retries": retries,
            "servo_calibration": {"pan": pantilt.pan.calibration.to_dict(),
                                  "tilt": pantilt.tilt.calibration.to_dict(),
                                  "pwm_frequency_hz": pantilt.pca.frequency,
                                  "oscillator_hz": pantilt.pca.oscillator_hz},
        }
        meta.update(self.labels or {})
        recording = mpu.to_recording(first, self.trigger + self.post, metadata=meta)
        lost = recording.metadata["samples_lost"]
        return AcquisitionResult(True, self.stopped, recording, lost, mpu.samples_lost,
                                 self.trigger / fs, self.angles, retries, stream=self.report,
                                 **released)


def _partial(mpu, first: int, stop: int, labels):
    """The samples of the window ``[first, stop)`` kept so far, as a recording marked
    ``interrupted``; None when none were kept."""
    stop = min(stop, mpu.stream_position)
    if stop <= first:
        return None
    try:
        return mpu.to_recording(first, stop, metadata={**(labels or {}), "interrupted": True})
    except ValueError:  # no sample of the window was kept
        return None


def _reached_by(commands, when: float) -> tuple[float, float] | None:
    """The (pan, tilt) the servos had certainly reached by host time ``when``, degrees.

    That is the command *before* the one in effect at ``when``: the servo was on its way from
    there to the newer one (a step of the path, up to 6.5 degrees by default at 100 kHz, takes
    an MG996R at its 353 deg/s, :data:`~ebantenna.chips.mg996r.SLEW_RATE`, about 18 ms of the
    step's 69 ms). None before two commands.
    """
    earlier = [(pan, tilt) for t, pan, tilt in commands if t <= when]
    return earlier[-2] if len(earlier) >= 2 else None
