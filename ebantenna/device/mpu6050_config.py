"""The MPU-6050's settings: sample rate, low-pass filter and range, and the register values they
take (RM registers 25, 26 and 28; the rules are in the module notes of
:mod:`ebantenna.device.mpu6050`, which uses them and re-exports them).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .._validate import check_choice, check_int, check_positive
from ..chips.mpu6050 import (
    ACCEL_LSB_PER_G,
    ACCEL_OUTPUT_RATE,
    ACCEL_RANGES_G,
    ADDRESS_AD0_LOW,
    ADDRESSES,
    AFS_SEL,
    DLPF,
    gyro_output_rate,
)

__all__ = ["MPU6050Config", "sample_rate_divider", "accel_bandwidth", "LSB_PER_G"]

#: Sensitivity by full-scale range (+/- g), LSB per g (PS, table 6.2).
LSB_PER_G = dict(zip(ACCEL_RANGES_G, ACCEL_LSB_PER_G, strict=True))


def sample_rate_divider(fs: float, dlpf_cfg: int) -> int:
    """``SMPLRT_DIV`` for a sample rate ``fs`` with low-pass setting ``dlpf_cfg`` (RM, register 25).

    Parameters
    ----------
    fs : float
        Wanted sample rate, Hz. At most 1 kHz, the accelerometer's output rate.
    dlpf_cfg : int
        ``DLPF_CFG``, 0-6.

    Returns
    -------
    int
        The divider, 0-255, such that ``gyro_rate / (1 + divider) == fs`` exactly.

    Raises
    ------
    ValueError
        When no divider gives ``fs`` exactly.

    Examples
    --------
    >>> from ebantenna.device.mpu6050 import sample_rate_divider
    >>> sample_rate_divider(1000.0, 0), sample_rate_divider(1000.0, 1), sample_rate_divider(500, 3)
    (7, 0, 1)
    """
    dlpf_cfg = check_int("dlpf_cfg", dlpf_cfg, minimum=0, maximum=6)
    fs = check_positive("fs", fs)
    if fs > ACCEL_OUTPUT_RATE:
        raise ValueError(f"fs must be <= {ACCEL_OUTPUT_RATE:g} Hz (the accelerometer's output "
                         f"rate), got {fs!r}")
    gyro_rate = gyro_output_rate(dlpf_cfg)
    # below gyro_rate / 256 no divider fits; there gyro_rate / fs would overflow for a subnormal fs
    divider = round(gyro_rate / fs) - 1 if fs >= gyro_rate / 257 else 256
    if not (0 <= divider <= 255 and math.isclose(gyro_rate / (1 + divider), fs, rel_tol=1e-12)):
        raise ValueError(
            f"fs must be {gyro_rate:g} Hz / (1 + n) for an integer n in [0, 255] when "
            f"dlpf_cfg={dlpf_cfg}; got {fs!r}"
        )
    return divider


def accel_bandwidth(dlpf_cfg: int) -> float:
    """The accelerometer's -3 dB bandwidth for ``DLPF_CFG`` 0-6, Hz (RM, register 26).

    Examples
    --------
    >>> from ebantenna.device.mpu6050 import accel_bandwidth
    >>> accel_bandwidth(0)
    260.0
    """
    return DLPF[check_int("dlpf_cfg", dlpf_cfg, minimum=0, maximum=len(DLPF) - 1)].accel_bandwidth


@dataclass(frozen=True)
class MPU6050Config:
    """Settings of the accelerometer.

    Parameters
    ----------
    fs : float
        Sample rate, Hz. Default 1000 Hz (paper, section 3).
    dlpf_cfg : int
        Digital low-pass filter setting 0-6. Default 0: 260 Hz, the widest (see the module notes).
    full_scale_g : int
        Full-scale range, +/- g: 2, 4, 8 or 16. Default 16 (paper, section 3).
    address : int
        I2C address: 0x68 (AD0 low, default) or 0x69 (AD0 high).

    Examples
    --------
    >>> from ebantenna.device.mpu6050 import MPU6050Config
    >>> cfg = MPU6050Config()
    >>> cfg.smplrt_div, cfg.accel_config, cfg.lsb_per_g
    (7, 24, 2048)
    """

    fs: float = 1000.0
    dlpf_cfg: int = 0
    full_scale_g: int = 16
    address: int = ADDRESS_AD0_LOW

    def __post_init__(self):
        sample_rate_divider(self.fs, self.dlpf_cfg)
        if self.full_scale_g not in LSB_PER_G:
            valid = ", ".join(str(g) for g in ACCEL_RANGES_G)
            raise ValueError(f"full_scale_g must be one of {valid}; got {self.full_scale_g!r}")
        check_choice("address", self.address, ADDRESSES)

    @property
    def smplrt_div(self) -> int:
        """Value of ``SMPLRT_DIV``."""
        return sample_rate_divider(self.fs, self.dlpf_cfg)

    @property
    def accel_config(self) -> int:
        """Value of ``ACCEL_CONFIG``: ``AFS_SEL`` in bits 4:3."""
        return AFS_SEL.put(ACCEL_RANGES_G.index(self.full_scale_g))

    @property
    def lsb_per_g(self) -> int:
        """Sensitivity, LSB/g."""
        return LSB_PER_G[self.full_scale_g]

    @property
    def bandwidth(self) -> float:
        """Accelerometer -3 dB bandwidth, Hz."""
        return accel_bandwidth(self.dlpf_cfg)
