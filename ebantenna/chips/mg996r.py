"""TowerPro MG996R hobby servo: the figures the pan-tilt unit is built on.

The servo is no chip on the bus, but the drivers (:mod:`ebantenna.device.servo`) and the simulated
rig (:mod:`ebantenna.device.simulated.world`) rely on the same figures of it, so they are written
here once. Source, cited as "DS": the maker's *MG996R High Torque Metal Gear Dual Ball Bearing
Servo* data sheet (TowerPro). It gives speeds and torques but no pulse range; the pulse range is
the one hobby vendors list for the MG996R, and each unit differs (hence
:class:`~ebantenna.device.servo.ServoCalibration`).

Examples
--------
>>> from ebantenna.chips.mg996r import PULSE_RANGE, SAFE_ANGLES, SLEW_RATE, TRAVEL
>>> round(SLEW_RATE, 1), PULSE_RANGE, TRAVEL, SAFE_ANGLES
(352.9, (0.0005, 0.0025), 180.0, (22.5, 157.5))

At 6 V it is 21 % faster, and its stall torque presses 5.4 N at 0.2 m:

>>> from ebantenna.chips.mg996r import SLEW_RATE_6V, STALL_TORQUE_6V
>>> round(SLEW_RATE_6V / SLEW_RATE - 1, 2), round(STALL_TORQUE_6V, 2)
(0.21, 1.08)
>>> round(STALL_TORQUE_6V / 0.2, 1)  # N
5.4
"""

from __future__ import annotations

__all__ = ["SLEW_RATE", "PULSE_RANGE", "TRAVEL", "SAFE_PULSE_RANGE", "SAFE_ANGLES",
           "OPERATING_VOLTAGE", "STALL_CURRENT", "SLEW_RATE_6V", "STALL_TORQUE_6V"]

#: Operating voltage, V (DS, specifications).
OPERATING_VOLTAGE = (4.8, 7.2)
#: Stall current at 6 V, A (DS, specifications).
STALL_CURRENT = 2.5

#: Operating speed at 4.8 V, no load: 0.17 s per 60 degrees (DS), in degrees/s. The slower of
#: the two ratings, which the simulated rig takes: the rig's supply
#: (:data:`ebantenna.device.wiring.SERVO_SUPPLY`, 5-6 V) lies between them, and the probe is a
#: load, which neither rating includes.
SLEW_RATE = 60.0 / 0.17
#: Operating speed at 6 V, no load: 0.14 s per 60 degrees (DS), in degrees/s (21 % faster).
SLEW_RATE_6V = 60.0 / 0.14
#: Stall torque at 6 V: 11 kgf cm (DS), in N m (11 * 9.80665 / 100).
STALL_TORQUE_6V = 11.0 * 9.80665e-2
#: Pulse widths at the two ends of the travel, s: 0.5 ms and 2.5 ms (vendors' listings; not in DS).
PULSE_RANGE = (0.5e-3, 2.5e-3)
#: Travel between those pulses, degrees (vendors' listings: "180 degrees").
TRAVEL = 180.0
#: The conservative default pulse range, s: 750-2250 us, the default of Adafruit's ServoKit
#: (``adafruit_motor.servo.Servo``: ``min_pulse=750``, ``max_pulse=2250``), which keeps most units
#: off their end stops; many MG996R reach a stop before 0.5 or 2.5 ms and stall there, hot.
SAFE_PULSE_RANGE = (0.75e-3, 2.25e-3)
#: The angles that range gives on the nominal line through :data:`PULSE_RANGE` and
#: :data:`TRAVEL` (22.5 and 157.5 degrees): the same slope, less travel.
SAFE_ANGLES = tuple(
    round((p - PULSE_RANGE[0]) / (PULSE_RANGE[1] - PULSE_RANGE[0]) * TRAVEL, 9)
    for p in SAFE_PULSE_RANGE)
