"""The datasheet facts of the rig's chips, written once: register maps, bit fields and constants.

Both the drivers (:mod:`ebantenna.device`) and everything that models the chips (the simulated I2C
bus in :mod:`ebantenna.device.simulated`, the sensor effects in :mod:`ebantenna.simulate`) read
them from here, so that a register address, a sensitivity or a filter bandwidth has exactly one
source. Every name cites the datasheet, its revision and the section or table it comes from.

- :mod:`ebantenna.chips.mpu6050`: the InvenSense MPU-6050 accelerometer and gyroscope;
- :mod:`ebantenna.chips.pca9685`: the NXP PCA9685 16-channel PWM controller;
- :mod:`ebantenna.chips.mg996r`: the TowerPro MG996R servos the PCA9685 drives;
- :mod:`ebantenna.chips.bitfield`: :class:`~ebantenna.chips.bitfield.BitField`, a group of
  adjacent bits in one register.

This package imports nothing else of ebantenna but its input checks, so that every stage may
import it.
"""

from .bitfield import BitField

__all__ = ["BitField"]
