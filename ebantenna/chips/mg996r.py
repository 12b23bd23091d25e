"""TowerPro MG996R hobby servo: the figures the pan-tilt unit is built on.

The servo is no chip on the bus, but the drivers (:mod:`ebantenna.device.servo`) and the simulated
rig (:mod:`ebantenna.device.simulated.world`) rely on the same figures of it, so they are written
here once. Source, cited as "DS": the maker's *MG996R High Torque Metal Gear Dual Ball Bearing
Servo* data sheet (TowerPro). It gives speeds and torques but no pulse range; the pulse range is
the one hobby vendors list for the MG996R, and each unit differs (hence
:class:`~ebantenna.device.servo.ServoCalibration`).

Examples
--------
>>> from ebantenna.chips.mg996r import PULSE_RANGE, SLEW_RATE, TRAVEL
>>> round(SLEW_RATE, 1), PULSE_RANGE, TRAVEL
(352.9, (0.0005, 0.0025), 180.0)
"""

from __future__ import annotations

__all__ = ["SLEW_RATE", "PULSE_RANGE", "TRAVEL"]

#: Operating speed at 4.8 V, no load: 0.17 s per 60 degrees (DS), in degrees/s.
SLEW_RATE = 60.0 / 0.17
#: Pulse widths at the two ends of the travel, s: 0.5 ms and 2.5 ms (vendors' listings; not in DS).
PULSE_RANGE = (0.5e-3, 2.5e-3)
#: Travel between those pulses, degrees (vendors' listings: "180 degrees").
TRAVEL = 180.0
