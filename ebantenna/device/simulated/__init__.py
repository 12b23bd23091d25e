"""A simulated I2C bus with an MPU-6050 and a PCA9685 on it, so that the drivers run unchanged
without the rig.

One module per part, each reading its chip's register map from :mod:`ebantenna.chips`:

- :mod:`~ebantenna.device.simulated.bus`: :class:`SimulatedBus`, the :class:`smbus2.SMBus` subset
  the drivers use, in virtual time;
- :mod:`~ebantenna.device.simulated.faults`: :class:`Faults` to inject and the
  :class:`FaultInjector` that draws them;
- :mod:`~ebantenna.device.simulated.mpu6050`: :class:`SimulatedMPU6050`, registers, sampling and
  FIFO;
- :mod:`~ebantenna.device.simulated.pca9685`: :class:`SimulatedPCA9685`, registers and pulses;
- :mod:`~ebantenna.device.simulated.world`: the servos' motion, the :class:`Obstacle` and the
  contact;
- :mod:`~ebantenna.device.simulated.rig`: :class:`SimulatedRig`, all of it wired together, with
  the vibration to play from the contact on.

This package is the only part of :mod:`ebantenna.device` that uses :mod:`ebantenna.simulate`
(in :mod:`~ebantenna.device.simulated.rig`, and only when a simulated contact needs a vibration).

Examples
--------
>>> from ebantenna.device import MPU6050
>>> from ebantenna.device.simulated import SimulatedRig
>>> rig = SimulatedRig.quiet(seed=1)
>>> mpu = MPU6050(rig.bus, clock=rig.clock)
>>> mpu.initialize()
>>> mpu.record(0.05).n_samples
50
"""

from .bus import SimulatedBus
from .faults import FaultInjector, Faults
from .mpu6050 import SimulatedMPU6050
from .pca9685 import SimulatedPCA9685
from .rig import SimulatedRig
from .world import MG996R_SLEW_RATE, Obstacle, World

__all__ = [
    "SimulatedBus",
    "SimulatedMPU6050",
    "SimulatedPCA9685",
    "SimulatedRig",
    "World",
    "Obstacle",
    "Faults",
    "FaultInjector",
    "MG996R_SLEW_RATE",
]
