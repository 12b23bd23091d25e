"""The real rig: MPU-6050 and PCA9685 drivers over smbus2, servos, the pan-tilt search, and a
register-level simulated I2C bus on which the same code runs without hardware.

The chips' register maps and datasheet constants live in :mod:`ebantenna.chips`, shared by the
drivers here and the simulated chips in :mod:`ebantenna.device.simulated`. The drivers know
nothing of the scene simulator; only :mod:`ebantenna.device.simulated` uses it, and only when a
simulated contact needs a vibration.
"""

from .clock import SystemClock, VirtualClock
from .i2c import I2CDevice, I2CError, RetryPolicy
from .mpu6050 import MPU6050, ChipIdentityError, MPU6050Config, sample_rate_divider
from .pantilt import (
    AcquisitionResult,
    ContactDetector,
    EllipticalPath,
    PanTilt,
    SearchConfig,
    search_and_record,
)
from .pca9685 import PCA9685, prescale_for
from .servo import Servo, ServoCalibration, ServoLimitWarning
from .simulated import Faults, Obstacle, SimulatedBus, SimulatedRig

__all__ = [
    "SystemClock",
    "VirtualClock",
    "I2CDevice",
    "I2CError",
    "RetryPolicy",
    "MPU6050",
    "MPU6050Config",
    "ChipIdentityError",
    "sample_rate_divider",
    "PCA9685",
    "prescale_for",
    "Servo",
    "ServoCalibration",
    "ServoLimitWarning",
    "EllipticalPath",
    "ContactDetector",
    "PanTilt",
    "SearchConfig",
    "AcquisitionResult",
    "search_and_record",
    "SimulatedBus",
    "SimulatedRig",
    "Faults",
    "Obstacle",
]
