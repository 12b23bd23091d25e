"""MG996R hobby servos on PCA9685 channels: angle to pulse width, with calibration and limits.

A hobby servo turns to an angle set by the width of a pulse repeated at about 50 Hz. For the
MG996R the usable range is roughly 0.5-2.5 ms for about 180 degrees of travel, but each unit
differs, so the mapping is a per-servo :class:`ServoCalibration`. Its limits keep the mechanism
away from its stops (and the probe away from the frame): a command outside them is clamped to the
nearest limit with a :class:`ServoLimitWarning`, never silently.
"""

from __future__ import annotations

import logging
import warnings
from dataclasses import dataclass

from .._validate import check_int, check_real
from ..chips.mg996r import PULSE_RANGE, SAFE_ANGLES, SAFE_PULSE_RANGE
from ..chips.pca9685 import N_CHANNELS
from .pca9685 import PCA9685

__all__ = ["ServoCalibration", "Servo", "ServoLimitWarning"]

logger = logging.getLogger(__name__)

#: Round-off allowed at the ends of a servo's travel, s: a few ulps of a millisecond pulse
#: computed through the angle line.
_ROUND_OFF = 1e-15


class ServoLimitWarning(UserWarning):
    """A servo command was outside the calibrated limits and has been clamped."""


@dataclass(frozen=True)
class ServoCalibration:
    """Linear map from servo angle to pulse width, and the allowed range of angles.

    Parameters
    ----------
    channel : int
        PCA9685 output, 0-15.
    min_pulse, max_pulse : float
        Pulse widths at ``min_angle`` and ``max_angle``, s. Defaults 0.75 ms and 2.25 ms, the
        conservative range :data:`ebantenna.chips.mg996r.SAFE_PULSE_RANGE` that keeps a servo
        off its end stops; measure a unit's own range and pass it here to use more travel.
    min_angle, max_angle : float
        The angles those pulses give, degrees. Defaults 22.5 and 157.5, on the MG996R's nominal
        line (0.5-2.5 ms for 0-180 degrees, :data:`ebantenna.chips.mg996r.SAFE_ANGLES`).
    lower_limit, upper_limit : float
        Commands are clamped to this range, degrees; it must lie within ``[min_angle, max_angle]``.
        Defaults: the full range.

    Examples
    --------
    >>> from ebantenna.device.servo import ServoCalibration
    >>> cal = ServoCalibration(channel=0)
    >>> cal.pulse(90.0)
    0.0015
    >>> cal.angle(0.002)
    135.0
    >>> cal.to_dict()["min_pulse"]
    0.00075
    >>> cal.pulse(1000.0)  # 11.6 ms: far past the end stop
    Traceback (most recent call last):
    ...
    ValueError: angle must give a pulse within the servo's travel [0.5, 2.5] ms, got 1000.0 deg...
    """

    channel: int
    min_pulse: float = SAFE_PULSE_RANGE[0]
    max_pulse: float = SAFE_PULSE_RANGE[1]
    min_angle: float = SAFE_ANGLES[0]
    max_angle: float = SAFE_ANGLES[1]
    lower_limit: float | None = None
    upper_limit: float | None = None

    def __post_init__(self):
        check_int("channel", self.channel, minimum=0, maximum=N_CHANNELS - 1)
        for name in ("min_pulse", "max_pulse"):
            value = check_real(name, getattr(self, name))
            if not 0 < value < 0.02:
                raise ValueError(f"{name} must lie in (0, 0.02) s, got {value!r}")
        if not self.min_pulse != self.max_pulse:
            raise ValueError("min_pulse and max_pulse must differ")
        check_real("min_angle", self.min_angle)
        check_real("max_angle", self.max_angle)
        if not self.min_angle < self.max_angle:
            raise ValueError(
                f"min_angle must be < max_angle ({self.max_angle!r}), got {self.min_angle!r}")
        if self.lower_limit is None:
            object.__setattr__(self, "lower_limit", float(self.min_angle))
        if self.upper_limit is None:
            object.__setattr__(self, "upper_limit", float(self.max_angle))
        lo = check_real("lower_limit", self.lower_limit)
        hi = check_real("upper_limit", self.upper_limit)
        if not self.min_angle <= lo < hi <= self.max_angle:
            raise ValueError(
                f"lower_limit and upper_limit must satisfy {self.min_angle!r} <= lower_limit < "
                f"upper_limit <= {self.max_angle!r}; got {lo!r} and {hi!r}")

    def to_dict(self) -> dict:
        """JSON-ready form (stored with a recording): plain ``int`` and ``float`` values, whatever
        NumPy scalars the calibration was made with."""
        out = {name: float(getattr(self, name)) for name in self.__dataclass_fields__}
        out["channel"] = int(self.channel)
        return out

    def pulse(self, angle: float) -> float:
        """Pulse width for ``angle`` (degrees), s.

        The angle is not clamped to ``[lower_limit, upper_limit]`` (:meth:`clamp` does that,
        and :meth:`Servo.move` clamps with a :class:`ServoLimitWarning`), but the pulse must
        lie within the servo's travel: the MG996R's nominal 0.5-2.5 ms
        (:data:`ebantenna.chips.mg996r.PULSE_RANGE`), widened to the calibration's own
        ``min_pulse`` and ``max_pulse`` if a measured unit goes further.

        Raises
        ------
        ValueError
            When the pulse falls outside that travel: it would drive the servo into its stops.
        """
        angle = check_real("angle", angle)
        frac = (angle - self.min_angle) / (self.max_angle - self.min_angle)
        pulse = self.min_pulse + frac * (self.max_pulse - self.min_pulse)
        low, high = self.travel
        if not low - _ROUND_OFF <= pulse <= high + _ROUND_OFF:
            raise ValueError(
                f"angle must give a pulse within the servo's travel [{low * 1e3:g}, "
                f"{high * 1e3:g}] ms, got {angle!r} deg ({pulse * 1e3:.4g} ms); clamp() it, or "
                "use Servo.move, which clamps with a warning")
        return pulse

    @property
    def travel(self) -> tuple[float, float]:
        """The pulses the servo can take, s: the MG996R's nominal range, widened to this
        calibration's ``min_pulse`` and ``max_pulse``."""
        return (min(PULSE_RANGE[0], self.min_pulse, self.max_pulse),
                max(PULSE_RANGE[1], self.min_pulse, self.max_pulse))

    def angle(self, pulse: float) -> float:
        """Angle for a pulse width of ``pulse`` seconds, degrees."""
        pulse = check_real("pulse", pulse)
        frac = (pulse - self.min_pulse) / (self.max_pulse - self.min_pulse)
        return self.min_angle + frac * (self.max_angle - self.min_angle)

    def clamp(self, angle: float) -> float:
        """``angle`` limited to ``[lower_limit, upper_limit]``, degrees."""
        return min(max(check_real("angle", angle), self.lower_limit), self.upper_limit)


class Servo:
    """One servo on a PCA9685 channel.

    Parameters
    ----------
    pca : PCA9685
        The initialised controller.
    calibration : ServoCalibration
        Mapping and limits of this servo.
    name : str
        Used in warnings and logs ("pan", "tilt").

    Examples
    --------
    >>> import warnings
    >>> from ebantenna.device.simulated import SimulatedRig
    >>> from ebantenna.device.pca9685 import PCA9685
    >>> from ebantenna.device.servo import Servo, ServoCalibration, ServoLimitWarning
    >>> rig = SimulatedRig.quiet()
    >>> pca = PCA9685(rig.bus, clock=rig.clock); pca.initialize()
    >>> pan = Servo(pca, ServoCalibration(0, lower_limit=30.0, upper_limit=150.0), "pan")
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     pan.move(170.0)
    150.0
    >>> caught[0].category is ServoLimitWarning
    True
    """

    def __init__(self, pca: PCA9685, calibration: ServoCalibration, name: str = "servo"):
        if not isinstance(pca, PCA9685):
            raise TypeError(f"pca must be a PCA9685, got {type(pca).__name__}")
        if not isinstance(calibration, ServoCalibration):
            raise TypeError(
                f"calibration must be a ServoCalibration, got {type(calibration).__name__}")
        self.pca = pca
        self.calibration = calibration
        self.name = str(name)
        #: Last commanded angle, degrees (None before the first command or after release).
        self.angle = None
        #: The angle commanded before it, degrees (its direction of motion), or None.
        self.previous = None

    def move(self, angle: float) -> float:
        """Command ``angle`` (degrees), clamped to the limits; returns the angle commanded."""
        cal = self.calibration
        target = cal.clamp(angle)
        if target != float(angle):
            message = (f"{self.name} servo: {float(angle):.2f} deg is outside its limits "
                       f"[{cal.lower_limit:g}, {cal.upper_limit:g}] deg; clamped to {target:g}")
            logger.warning(message)
            warnings.warn(message, ServoLimitWarning, stacklevel=2)
        self.pca.set_pulse(cal.channel, cal.pulse(target))
        if target != self.angle:
            self.previous = self.angle
        self.angle = target
        return target

    def release(self) -> None:
        """Stop driving this servo (its output off: the motor goes limp)."""
        self.pca.channel_off(self.calibration.channel)
        self.angle = self.previous = None
