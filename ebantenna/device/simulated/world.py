"""The physical side of the simulated rig: two MG996R servos slewing towards their commands, the
post in the probe's reach, and the moment the probe meets it.

The servos slew at the MG996R's rated speed, 60 degrees in 0.17 s at 4.8 V, the slower of its
two no-load ratings (0.14 s at 6 V; the rig's 5-6 V supply lies between them): a real servo may
arrive about a fifth sooner, or later under the probe's load. When the pan angle reaches the
:class:`Obstacle` with the tilt inside its span, that is the contact: the probe stops there.
Everything advances lazily, in virtual time, when somebody asks.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..._validate import check_nonnegative, check_positive, check_real
from ...chips.mg996r import PULSE_RANGE, SLEW_RATE, TRAVEL

__all__ = [
    "MG996R_SLEW_RATE",
    "mg996r_angle",
    "Obstacle",
    "DEFAULT_OBSTACLE",
    "ServoMotion",
    "World",
]

#: MG996R speed at 4.8 V, no load, degrees/s (see :data:`ebantenna.chips.mg996r.SLEW_RATE`).
MG996R_SLEW_RATE = SLEW_RATE


def mg996r_angle(width: float) -> float | None:
    """Angle (degrees) the simulated MG996R turns to for pulses of ``width`` (s); None: no pulses.

    Linear from 0 to :data:`~ebantenna.chips.mg996r.TRAVEL` over
    :data:`~ebantenna.chips.mg996r.PULSE_RANGE`, against its end stops beyond.

    Examples
    --------
    >>> from ebantenna.device.simulated.world import mg996r_angle
    >>> mg996r_angle(1.5e-3), mg996r_angle(3e-3), mg996r_angle(0.0) is None
    (90.0, 180.0, True)
    """
    width = check_nonnegative("width", width)
    if width == 0:
        return None
    low, high = PULSE_RANGE
    return min(max((width - low) / (high - low) * TRAVEL, 0.0), TRAVEL)


@dataclass(frozen=True)
class Obstacle:
    """An upright post in the probe's reach.

    Parameters
    ----------
    pan : float
        Pan angle (servo degrees) at which the probe meets the post.
    tilt_low, tilt_high : float
        Tilt range (servo degrees) over which the post is there.

    Examples
    --------
    >>> from ebantenna.device.simulated import Obstacle
    >>> Obstacle().blocks(90.0), Obstacle().blocks(60.0)
    (True, False)
    """

    pan: float = 125.0
    tilt_low: float = 70.0
    tilt_high: float = 110.0

    def __post_init__(self):
        check_real("pan", self.pan)
        check_real("tilt_low", self.tilt_low)
        check_real("tilt_high", self.tilt_high)
        if not self.tilt_low < self.tilt_high:
            raise ValueError(
                f"tilt_low must be < tilt_high ({self.tilt_high!r}), got {self.tilt_low!r}")

    def blocks(self, tilt: float) -> bool:
        """Whether the post is there at this tilt (degrees)."""
        tilt = check_real("tilt", tilt)
        return self.tilt_low <= tilt <= self.tilt_high


#: The post of a default rig: met at pan 125 degrees, over tilts 70-110 degrees.
DEFAULT_OBSTACLE = Obstacle()


class ServoMotion:
    """A servo slewing at constant speed towards its command.

    Parameters
    ----------
    angle : float
        Where it starts, degrees.
    rate : float
        Slew rate, degrees/s.

    Attributes
    ----------
    target : float or None
        The commanded angle, degrees; None when the servo gets no pulses (unpowered, it stays).
    """

    def __init__(self, angle: float, rate: float):
        self.angle = check_real("angle", angle)
        self.target = None
        self.rate = check_positive("rate", rate)

    def position(self, dt: float) -> float:
        """Where it will be ``dt`` seconds from now, degrees."""
        if not (type(dt) is float and 0.0 <= dt < math.inf):
            dt = check_nonnegative("dt", dt)
        if self.target is None:
            return self.angle
        step = self.rate * dt
        delta = self.target - self.angle
        return self.target if abs(delta) <= step else self.angle + math.copysign(step, delta)

    def arrival(self) -> float:
        """Seconds until it reaches its target (0 without one)."""
        return 0.0 if self.target is None else abs(self.target - self.angle) / self.rate


class World:
    """Servo motion, the obstacle and the moment of contact, advanced lazily in virtual time.

    Parameters
    ----------
    obstacle : Obstacle or None
        The post; None for empty space.
    rate : float
        Slew rate of both servos, degrees/s.

    Attributes
    ----------
    pan, tilt : ServoMotion
        The two servos, both starting at 90 degrees.
    contact_time : float or None
        Virtual time at which the probe met the post, s.
    contact_tilt : float or None
        Tilt angle at that moment, degrees.
    max_push : float
        Furthest the pan was commanded past the post after the contact, degrees.
    commands : list of (time, axis, angle)
        Every servo command, in order.

    Examples
    --------
    >>> from ebantenna.device.simulated.world import Obstacle, World
    >>> world = World(Obstacle(pan=100.0), rate=100.0)
    >>> world.command(0.0, "pan", 120.0)
    >>> world.advance_to(1.0)
    >>> world.contact_time, world.pan.angle, world.max_push
    (0.1, 100.0, 20.0)
    """

    def __init__(self, obstacle: Obstacle | None, rate: float):
        if not (obstacle is None or isinstance(obstacle, Obstacle)):
            raise TypeError(f"obstacle must be an Obstacle or None, got "
                            f"{type(obstacle).__name__}")
        rate = check_positive("rate", rate)
        self.obstacle = obstacle
        self.pan = ServoMotion(90.0, rate)
        self.tilt = ServoMotion(90.0, rate)
        self.time = 0.0
        self.contact_time = None
        self.contact_tilt = None
        #: Furthest the pan was commanded past the post after the contact, degrees.
        self.max_push = 0.0
        self.blocked = False
        self.direction = 1.0
        self.commands: list[tuple[float, str, float | None]] = []

    def advance_to(self, now: float) -> None:
        """Move everything on to virtual time ``now`` (s), noting the contact when it happens
        (a time already passed moves nothing)."""
        if not (type(now) is float and -math.inf < now < math.inf):  # a float passes at once
            now = check_real("now", now)
        while now > self.time:
            # Move in pieces that end where a servo arrives, so motion within a piece is linear.
            dt = now - self.time
            for servo in (self.pan, self.tilt):
                arrival = servo.arrival()
                if 0.0 < arrival < dt:
                    dt = arrival
            pan0 = self.pan.angle
            pan1 = self.pan.position(dt)
            if self.contact_time is None and self.obstacle is not None:
                lo, hi = sorted((pan0, pan1))
                if lo <= self.obstacle.pan <= hi and pan0 != pan1:
                    tau = abs(self.obstacle.pan - pan0) / self.pan.rate
                    tilt = self.tilt.position(tau)
                    if self.obstacle.blocks(tilt):
                        self.contact_time = self.time + tau
                        self.contact_tilt = tilt
                        self.direction = math.copysign(1.0, pan1 - pan0)
                        self.blocked = True
                        self.max_push = (self.pan.target - self.obstacle.pan) * self.direction
            if self.blocked:
                # The post stops the probe: the pan cannot pass it.
                if (pan1 - self.obstacle.pan) * self.direction > 0:
                    pan1 = self.obstacle.pan
            self.tilt.angle = self.tilt.position(dt)
            self.pan.angle = pan1
            self.time += dt
            if dt <= 0.0:  # pragma: no cover - guards against a zero step
                break

    def command(self, now: float, axis: str, angle: float | None) -> None:
        """At virtual time ``now`` (s), send servo ``axis`` ("pan" or "tilt") towards ``angle``
        (degrees; None: stop the pulses)."""
        if axis not in ("pan", "tilt"):
            raise ValueError(f"axis must be 'pan' or 'tilt', got {axis!r}")
        if angle is not None:
            angle = check_real("angle", angle)
        self.advance_to(now)
        servo = self.pan if axis == "pan" else self.tilt
        servo.target = angle
        self.commands.append((now, axis, angle))
        if axis == "pan" and angle is not None and self.blocked:
            push = (angle - self.obstacle.pan) * self.direction
            self.max_push = max(self.max_push, push)
