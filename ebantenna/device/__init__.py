"""The real rig: MPU-6050 and PCA9685 drivers over smbus2, servos, the pan-tilt search, and a
register-level simulated I2C bus on which the same code runs without hardware.

The chips' register maps and datasheet constants live in :mod:`ebantenna.chips`, shared by the
drivers here and the simulated chips in :mod:`ebantenna.device.simulated`. The drivers know
nothing of the scene simulator; only :mod:`ebantenna.device.simulated` uses it, and only when a
simulated contact needs a vibration.
"""

from .clock import SystemClock, VirtualClock
from .fifo import FifoStream, PeriodEstimator
from .i2c import I2CDevice, I2CError, RetryPolicy, ShortReadError
from .mpu6050 import (
    MPU6050,
    ChipIdentityError,
    CompatibleChipWarning,
    MPU6050Config,
    sample_rate_divider,
)
from .pantilt import (
    AcquisitionResult,
    ContactDetector,
    EllipticalPath,
    PanTilt,
    SearchConfig,
    search_and_record,
)
from .pca9685 import PCA9685, oscillator_from_measurement, prescale_for
from .safety import ReleaseError, ServoGuard, SignalReceived
from .servo import Servo, ServoCalibration, ServoLimitWarning
from .simulated import Faults, Obstacle, SimulatedBus, SimulatedRig
from .watchdog import StreamStalledError

__all__ = [
    "SystemClock",
    "VirtualClock",
    "I2CDevice",
    "I2CError",
    "RetryPolicy",
    "ShortReadError",
    "FifoStream",
    "PeriodEstimator",
    "StreamStalledError",
    "MPU6050",
    "MPU6050Config",
    "ChipIdentityError",
    "CompatibleChipWarning",
    "sample_rate_divider",
    "PCA9685",
    "prescale_for",
    "oscillator_from_measurement",
    "ServoGuard",
    "SignalReceived",
    "ReleaseError",
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
