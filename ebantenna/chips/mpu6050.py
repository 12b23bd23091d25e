"""InvenSense MPU-6050: register map, bit fields and datasheet constants.

Sources, cited by their short names below:

- "RM": *MPU-6000 and MPU-6050 Register Map and Descriptions*, document RM-MPU-6000A-00,
  revision 4.2, InvenSense, 2013. Registers are cited by their decimal number, as the document
  numbers its sections ("RM 26" is register 26, ``CONFIG``, 0x1A).
- "PS": *MPU-6000 and MPU-6050 Product Specification*, document PS-MPU-6000A-00, revision 3.4,
  InvenSense, 2013, cited by section or table.

Only what the drivers and the simulated chip use is listed, but each register listed is complete:
all its named bits and fields.

Examples
--------
>>> from ebantenna.chips.mpu6050 import AFS_SEL, ACCEL_LSB_PER_G, DLPF, Register
>>> hex(Register.WHO_AM_I), AFS_SEL.register == Register.ACCEL_CONFIG
('0x75', True)
>>> ACCEL_LSB_PER_G[3], DLPF[0].accel_bandwidth, DLPF[1].accel_delay
(2048, 260.0, 0.002)
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum, IntFlag

from .._validate import check_int
from .bitfield import BitField

__all__ = [
    "STANDARD_GRAVITY",
    "ADDRESS_AD0_LOW",
    "ADDRESS_AD0_HIGH",
    "ADDRESSES",
    "SUPPLY_VOLTAGE",
    "MAX_I2C_CLOCK_HZ",
    "Register",
    "READ_ONLY",
    "POWER_ON",
    "WHO_AM_I_VALUE",
    "EXT_SYNC_SET",
    "DLPF_CFG",
    "AFS_SEL",
    "FS_SEL",
    "CLKSEL",
    "ClockSource",
    "PowerManagement1",
    "FifoEnable",
    "Interrupt",
    "UserControl",
    "USER_CONTROL_SELF_CLEARING",
    "GYRO_RATE_DLPF_OFF",
    "GYRO_RATE_DLPF_ON",
    "ACCEL_OUTPUT_RATE",
    "gyro_output_rate",
    "DlpfSetting",
    "DLPF",
    "ACCEL_RANGES_G",
    "ACCEL_LSB_PER_G",
    "ACCEL_NOISE_DENSITY",
    "INTERNAL_OSCILLATOR_HZ",
    "FIFO_SIZE",
    "ACCEL_SAMPLE_BYTES",
    "DATA_DTYPE",
    "RESET_WAIT",
    "GYRO_STARTUP",
    "COMPATIBLE_WHO_AM_I",
    "ChipModel",
    "CHIP_MODELS",
    "A_DLPF_CFG",
    "ACCEL_DLPF_6500",
]

#: Standard acceleration of gravity, m/s^2 (3rd CGPM, 1901): the "g" in which the datasheet states
#: the accelerometer's full-scale ranges and sensitivities.
STANDARD_GRAVITY = 9.80665

#: 7-bit I2C address with pin AD0 low and high: ``b110100X`` with X the level of AD0 (PS 9.2).
ADDRESS_AD0_LOW = 0x68
ADDRESS_AD0_HIGH = 0x69
ADDRESSES = (ADDRESS_AD0_LOW, ADDRESS_AD0_HIGH)

#: Supply voltage range, V (PS 6.3, "VDD power supply, operating voltages").
SUPPLY_VOLTAGE = (2.375, 3.46)
#: Fastest I2C clock, Hz: fast mode, 400 kHz (PS 6.4, "I2C operating frequency").
MAX_I2C_CLOCK_HZ = 400_000


class Register(IntEnum):
    """Register addresses (RM section 3, "Register Map"); the decimal number follows each."""

    SMPLRT_DIV = 0x19  # 25
    CONFIG = 0x1A  # 26
    GYRO_CONFIG = 0x1B  # 27
    ACCEL_CONFIG = 0x1C  # 28
    ACCEL_CONFIG2 = 0x1D  # 29 on the MPU-6500 family only (its RM, register 29); reserved here
    FIFO_EN = 0x23  # 35
    INT_PIN_CFG = 0x37  # 55
    INT_ENABLE = 0x38  # 56
    INT_STATUS = 0x3A  # 58
    ACCEL_XOUT_H = 0x3B  # 59
    ACCEL_XOUT_L = 0x3C  # 60
    ACCEL_YOUT_H = 0x3D  # 61
    ACCEL_YOUT_L = 0x3E  # 62
    ACCEL_ZOUT_H = 0x3F  # 63
    ACCEL_ZOUT_L = 0x40  # 64
    TEMP_OUT_H = 0x41  # 65
    TEMP_OUT_L = 0x42  # 66
    GYRO_XOUT_H = 0x43  # 67
    GYRO_XOUT_L = 0x44  # 68
    GYRO_YOUT_H = 0x45  # 69
    GYRO_YOUT_L = 0x46  # 70
    GYRO_ZOUT_H = 0x47  # 71
    GYRO_ZOUT_L = 0x48  # 72
    SIGNAL_PATH_RESET = 0x68  # 104
    USER_CTRL = 0x6A  # 106
    PWR_MGMT_1 = 0x6B  # 107
    PWR_MGMT_2 = 0x6C  # 108
    FIFO_COUNTH = 0x72  # 114
    FIFO_COUNTL = 0x73  # 115
    FIFO_R_W = 0x74  # 116
    WHO_AM_I = 0x75  # 117


#: Registers marked read-only ("R") in the register map (RM section 3): the sensor outputs
#: ``ACCEL_XOUT_H`` to ``GYRO_ZOUT_L``, ``INT_STATUS``, ``FIFO_COUNTH``/``L`` and ``WHO_AM_I``.
READ_ONLY = frozenset(
    {Register.INT_STATUS, Register.FIFO_COUNTH, Register.FIFO_COUNTL, Register.WHO_AM_I}
    | {r for r in Register if Register.ACCEL_XOUT_H <= r <= Register.GYRO_ZOUT_L}
)

#: ``WHO_AM_I`` of every MPU-6050, whatever the level of AD0 (RM 117).
WHO_AM_I_VALUE = 0x68

#: Power-on values that are not 0x00: "The reset value is 0x00 for all registers other than"
#: ``PWR_MGMT_1`` (0x40, asleep) and ``WHO_AM_I`` (RM section 3).
POWER_ON = {Register.PWR_MGMT_1: 0x40, Register.WHO_AM_I: WHO_AM_I_VALUE}

#: ``CONFIG[5:3]``: frame synchronisation input (RM 26).
EXT_SYNC_SET = BitField(Register.CONFIG, 3, 3)
#: ``CONFIG[2:0]``: digital low-pass filter setting, see :data:`DLPF` (RM 26).
DLPF_CFG = BitField(Register.CONFIG, 0, 3)
#: ``GYRO_CONFIG[4:3]``: gyroscope full-scale range, +/-250, 500, 1000, 2000 deg/s (RM 27).
FS_SEL = BitField(Register.GYRO_CONFIG, 3, 2)
#: ``ACCEL_CONFIG[4:3]``: accelerometer full-scale range, see :data:`ACCEL_RANGES_G` (RM 28).
AFS_SEL = BitField(Register.ACCEL_CONFIG, 3, 2)
#: ``PWR_MGMT_1[2:0]``: clock source, see :class:`ClockSource` (RM 107).
CLKSEL = BitField(Register.PWR_MGMT_1, 0, 3)


class ClockSource(IntEnum):
    """Values of ``CLKSEL`` (RM 107, table of clock sources)."""

    INTERNAL_8MHZ = 0
    PLL_X_GYRO = 1
    PLL_Y_GYRO = 2
    PLL_Z_GYRO = 3
    PLL_EXTERNAL_32KHZ = 4
    PLL_EXTERNAL_19MHZ = 5
    STOP = 7


class PowerManagement1(IntFlag):
    """Single bits of ``PWR_MGMT_1`` (RM 107); ``CLKSEL`` is the field :data:`CLKSEL`."""

    DEVICE_RESET = 0x80
    SLEEP = 0x40
    CYCLE = 0x20
    TEMP_DIS = 0x08


class FifoEnable(IntFlag):
    """Bits of ``FIFO_EN``: which sensor data are written into the FIFO (RM 35)."""

    TEMP = 0x80
    XG = 0x40
    YG = 0x20
    ZG = 0x10
    ACCEL = 0x08
    SLV2 = 0x04
    SLV1 = 0x02
    SLV0 = 0x01


class Interrupt(IntFlag):
    """Bits of ``INT_ENABLE`` (the ``_EN`` bits, RM 56) and ``INT_STATUS`` (RM 58), which share
    their positions."""

    FIFO_OFLOW = 0x10
    I2C_MST = 0x08
    DATA_RDY = 0x01


class UserControl(IntFlag):
    """Bits of ``USER_CTRL`` (RM 106)."""

    FIFO_EN = 0x40
    I2C_MST_EN = 0x20
    I2C_IF_DIS = 0x10
    FIFO_RESET = 0x04
    I2C_MST_RESET = 0x02
    SIG_COND_RESET = 0x01


#: The reset bits of ``USER_CTRL``, which clear themselves once the reset is done (RM 106).
USER_CONTROL_SELF_CLEARING = (
    UserControl.FIFO_RESET | UserControl.I2C_MST_RESET | UserControl.SIG_COND_RESET
)

#: Gyroscope output rate with the low-pass filter off (``DLPF_CFG`` 0 or 7) and on (1-6), Hz:
#: the rate that ``SMPLRT_DIV`` divides, "Sample Rate = Gyroscope Output Rate / (1 + SMPLRT_DIV)"
#: (RM 25).
GYRO_RATE_DLPF_OFF = 8000.0
GYRO_RATE_DLPF_ON = 1000.0
#: Accelerometer output rate, Hz; above it the same accelerometer sample is repeated (RM 25).
ACCEL_OUTPUT_RATE = 1000.0


def gyro_output_rate(dlpf_cfg: int) -> float:
    """Gyroscope output rate for ``DLPF_CFG`` 0-7, Hz (RM 25 and 26).

    Examples
    --------
    >>> from ebantenna.chips.mpu6050 import gyro_output_rate
    >>> gyro_output_rate(0), gyro_output_rate(3), gyro_output_rate(7)
    (8000.0, 1000.0, 8000.0)
    """
    dlpf_cfg = check_int("dlpf_cfg", dlpf_cfg, minimum=0, maximum=DLPF_CFG.maximum)
    return GYRO_RATE_DLPF_OFF if dlpf_cfg in (0, 7) else GYRO_RATE_DLPF_ON


@dataclass(frozen=True)
class DlpfSetting:
    """One row of the digital low-pass filter table (RM 26).

    Attributes
    ----------
    accel_bandwidth, gyro_bandwidth : float
        -3 dB bandwidth of the accelerometer and the gyroscope, Hz.
    accel_delay, gyro_delay : float
        Their delay, s.
    gyro_rate : float
        Gyroscope output rate, Hz.
    """

    accel_bandwidth: float
    accel_delay: float
    gyro_bandwidth: float
    gyro_delay: float
    gyro_rate: float


#: The filter table for ``DLPF_CFG`` 0-6 (RM 26; ``DLPF_CFG`` = 7 is reserved).
DLPF = (
    DlpfSetting(260.0, 0.0, 256.0, 0.98e-3, GYRO_RATE_DLPF_OFF),
    DlpfSetting(184.0, 2.0e-3, 188.0, 1.9e-3, GYRO_RATE_DLPF_ON),
    DlpfSetting(94.0, 3.0e-3, 98.0, 2.8e-3, GYRO_RATE_DLPF_ON),
    DlpfSetting(44.0, 4.9e-3, 42.0, 4.8e-3, GYRO_RATE_DLPF_ON),
    DlpfSetting(21.0, 8.5e-3, 20.0, 8.3e-3, GYRO_RATE_DLPF_ON),
    DlpfSetting(10.0, 13.8e-3, 10.0, 13.4e-3, GYRO_RATE_DLPF_ON),
    DlpfSetting(5.0, 19.0e-3, 5.0, 18.6e-3, GYRO_RATE_DLPF_ON),
)

#: Accelerometer full-scale range for ``AFS_SEL`` 0-3, +/- g (RM 28, PS table 6.2).
ACCEL_RANGES_G = (2, 4, 8, 16)
#: Accelerometer sensitivity for ``AFS_SEL`` 0-3, LSB/g (PS table 6.2).
ACCEL_LSB_PER_G = (16384, 8192, 4096, 2048)
#: Accelerometer noise power spectral density at 10 Hz, ``AFS_SEL`` = 0, 1 kHz output rate:
#: 400 ug/sqrt(Hz), here in g/sqrt(Hz) (PS table 6.2).
ACCEL_NOISE_DENSITY = 400e-6
#: Frequency of the internal relaxation oscillator (``CLKSEL`` = 0), Hz (RM 107).
INTERNAL_OSCILLATOR_HZ = 8e6

#: FIFO size, bytes (PS section 7.17).
FIFO_SIZE = 1024
#: Bytes one accelerometer sample takes in the FIFO with only ``FifoEnable.ACCEL`` set:
#: ``ACCEL_XOUT_H`` to ``ACCEL_ZOUT_L`` in register order (RM 35).
ACCEL_SAMPLE_BYTES = 6
#: Every sensor output is a 16-bit two's-complement value, high byte first (RM 59-72):
#: a NumPy dtype string.
DATA_DTYPE = ">i2"

#: Wait after ``PWR_MGMT_1.DEVICE_RESET`` before the registers are written again, s: the
#: register map gives no figure; 100 ms is the power-up start-up time for register access (PS
#: section 6.3, "Start-up time for register read/write": 100 ms maximum).
RESET_WAIT = 0.1
#: Gyroscope start-up time, s (PS section 6.1, table "Gyroscope specifications": 30 ms, DLPF_CFG =
#: 0, to within 1 deg/s of final). With ``CLKSEL`` = 1 the sample clock comes from the X gyro's
#: PLL, so the samples are not trusted before it has started.
GYRO_STARTUP = 30e-3

#: ``WHO_AM_I`` values of parts that answer the same registers as far as this package uses them
#: (accelerometer data, FIFO of 6-byte samples, the same power and rate registers); from the
#: table of Linux's ``inv_mpu6050`` driver (``drivers/iio/imu/inv_mpu6050/inv_mpu_iio.h``,
#: ``INV_*_WHOAMI_VALUE``). Their FIFO sizes and filter registers differ (the MPU-6500 family
#: holds 512 bytes, others 4 kB), so only the parts of :data:`CHIP_MODELS` are driven (with a
#: warning, as what they are); the others are refused by name
#: (:class:`~ebantenna.device.mpu6050.ChipIdentityError`).
COMPATIBLE_WHO_AM_I = {
    0x70: "MPU-6500",
    0x71: "MPU-9250",
    0x73: "MPU-9255",
    0x74: "MPU-6515",
    0x78: "MPU-6880",
    0x98: "ICM-20689",
    0xA6: "ICM-20609",
    0xAF: "ICM-20608",
}


#: ``ACCEL_CONFIG2[2:0]`` of the MPU-6500 family: the accelerometer's own low-pass filter
#: (MPU-6500 Register Map RM-MPU-6500A-00 rev. 2.1, register 29); bit 3, ``ACCEL_FCHOICE_B``, is
#: left 0 (filter in use, 1 kHz output).
A_DLPF_CFG = BitField(Register.ACCEL_CONFIG2, 0, 3)
#: Accelerometer -3 dB bandwidth by ``A_DLPF_CFG`` 0-7 on the MPU-6500 family, Hz (same source,
#: table of register 29).
ACCEL_DLPF_6500 = (218.1, 218.1, 99.0, 44.8, 21.2, 10.2, 5.05, 420.0)


@dataclass(frozen=True)
class ChipModel:
    """What differs between the parts this package drives.

    Attributes
    ----------
    name : str
        Part name.
    fifo_size : int
        FIFO size, bytes.
    accel_config2 : bool
        True for the MPU-6500 family: the accelerometer filter lives in ``ACCEL_CONFIG2`` and
        ``SMPLRT_DIV`` applies only when ``0 < DLPF_CFG < 7`` (otherwise the FIFO runs at the
        gyroscope's 8 kHz or faster, whatever the divider says); MPU-6500 register map,
        registers 25, 26 and 29.
    """

    name: str
    fifo_size: int
    accel_config2: bool


#: The parts driven, by ``WHO_AM_I``: the MPU-6050 (1024-byte FIFO, PS 7.17) and the MPU-6500
#: family (512-byte FIFO, MPU-6500 Product Specification PS-MPU-6500A-01 rev. 1.1, section 4.15;
#: MPU-9250 PS-MPU-9250A-01 rev. 1.1, section 4.17; the MPU-9255 is an MPU-9250 with another
#: ``WHO_AM_I``). The other parts of :data:`COMPATIBLE_WHO_AM_I` are refused by name: their FIFO
#: sizes and filter registers are not modelled here.
CHIP_MODELS = {
    WHO_AM_I_VALUE: ChipModel("MPU-6050", FIFO_SIZE, False),
    0x70: ChipModel("MPU-6500", 512, True),
    0x71: ChipModel("MPU-9250", 512, True),
    0x73: ChipModel("MPU-9255", 512, True),
}
