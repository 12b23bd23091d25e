"""Driver for the InvenSense MPU-6050 accelerometer at the probe tip, over I2C.

Register numbers and bit fields follow the *MPU-6000 and MPU-6050 Register Map and Descriptions*,
document RM-MPU-6000A-00, revision 4.2 (InvenSense, 2013), cited below as "RM" with the register
number in decimal as the document gives it, and the *MPU-6000/MPU-6050 Product Specification*,
PS-MPU-6000A-00, revision 3.4, cited as "PS".

Sample rate and low-pass filter (RM, registers 25 and 26)
---------------------------------------------------------
The datasheet's rule is

    Sample Rate = Gyroscope Output Rate / (1 + SMPLRT_DIV),

where the gyroscope output rate is 8 kHz when the digital low-pass filter is disabled
(``DLPF_CFG`` = 0 or 7) and 1 kHz when it is enabled (``DLPF_CFG`` = 1 to 6). The accelerometer
itself is output at 1 kHz at most: above that the same accelerometer sample is repeated. The paper
samples at 1 kHz, which can be had two ways:

- ``DLPF_CFG = 0``, ``SMPLRT_DIV = 7``: 8 kHz / 8 = 1 kHz, accelerometer bandwidth 260 Hz (the
  widest the chip offers, delay 0 ms). This is the default here, because it keeps the most of the
  band the paper filters;
- ``DLPF_CFG = 1``, ``SMPLRT_DIV = 0``: 1 kHz / 1 = 1 kHz, bandwidth 184 Hz (delay 2.0 ms).

Table 2 of the paper sets the elliptic band-pass filter's pass band to 52-325 Hz. The
accelerometer's widest bandwidth is 260 Hz, so the band from 260 to 325 Hz has already been
attenuated by the chip before the paper's filter sees it: the effective upper edge of the pass band
is the sensor's 260 Hz (-3 dB), not 325 Hz, and components up there are both weakened and
phase-shifted. Moreover, with a 1 kHz sample rate the Nyquist frequency is 500 Hz and the chip's
first-order-like roll-off above 260 Hz leaves content between 500 and 740 Hz only partly
suppressed; it aliases into the 260-500 Hz range. Only the band below 260 Hz is measured faithfully.

Range (RM, register 28)
-----------------------
``AFS_SEL = 3`` selects +/-16 g, 2048 LSB/g (PS, table 6.2), the paper's "maximum sensitivity".
Raw counts are converted with the standard gravity 9.80665 m/s^2.

FIFO (RM, registers 35, 56, 58, 106, 114-116)
---------------------------------------------
With only ``ACCEL_FIFO_EN`` set, each sample is 6 bytes (X, Y, Z, big-endian, signed). The FIFO
holds 1024 bytes, 170 samples, 170 ms at 1 kHz. When it is full the chip overwrites the oldest
bytes and sets ``FIFO_OFLOW_INT`` in ``INT_STATUS``; since 1024 is not a multiple of 6, what
remains is no longer aligned on sample boundaries, so the driver discards it, resets the FIFO and
counts the lost samples from the elapsed time. A recording states how many samples were lost, and
that number is exactly zero when the FIFO is drained in time (no overflow).
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np

from .._validate import check_choice, check_int, check_positive
from ..chips.mpu6050 import (
    ACCEL_LSB_PER_G,
    ACCEL_OUTPUT_RATE,
    ACCEL_RANGES_G,
    ACCEL_SAMPLE_BYTES,
    ADDRESS_AD0_LOW,
    ADDRESSES,
    AFS_SEL,
    CLKSEL,
    DATA_DTYPE,
    DLPF,
    FIFO_SIZE,
    STANDARD_GRAVITY,
    WHO_AM_I_VALUE,
    ClockSource,
    FifoEnable,
    Interrupt,
    PowerManagement1,
    Register,
    UserControl,
    gyro_output_rate,
)
from ..recording import Recording
from .clock import SystemClock
from .i2c import SMBUS_BLOCK_MAX, I2CDevice, RetryPolicy

__all__ = [
    "MPU6050",
    "MPU6050Config",
    "ChipIdentityError",
    "FifoBlock",
    "STANDARD_GRAVITY",
    "LSB_PER_G",
    "sample_rate_divider",
    "accel_bandwidth",
]

logger = logging.getLogger(__name__)

#: Sensitivity by full-scale range (+/- g), LSB per g (PS, table 6.2).
LSB_PER_G = dict(zip(ACCEL_RANGES_G, ACCEL_LSB_PER_G, strict=True))

#: Bytes per FIFO sample with only the accelerometer enabled.
SAMPLE_BYTES = ACCEL_SAMPLE_BYTES
#: Longest SMBus chunk that holds whole samples.
_FIFO_CHUNK = (SMBUS_BLOCK_MAX // SAMPLE_BYTES) * SAMPLE_BYTES


class ChipIdentityError(OSError):
    """The chip at the address is not the one expected (WHO_AM_I mismatch)."""


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
    divider = round(gyro_rate / fs) - 1
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


@dataclass(frozen=True)
class FifoBlock:
    """Samples drained from the FIFO in one go.

    Attributes
    ----------
    index : ndarray of int, shape (n,)
        Position of each sample in the stream since :meth:`MPU6050.start_fifo` (0-based). A jump
        means samples were lost in between.
    counts : ndarray of int16, shape (n, 3)
        Raw X, Y, Z counts.
    lost : int
        Samples lost (to an overflow) just before this block.
    """

    index: np.ndarray
    counts: np.ndarray
    lost: int


class MPU6050:
    """The accelerometer, configured for the paper's acquisition.

    Parameters
    ----------
    bus : smbus2.SMBus or compatible
        The open I2C bus.
    config : MPU6050Config, optional
        Settings; default :class:`MPU6050Config()` (1 kHz, 260 Hz, +/-16 g).
    retry : RetryPolicy, optional
        Retries of transient bus errors.
    clock : clock, optional
        ``monotonic``/``sleep`` provider. Default the system clock.
    use_rdwr : bool
        Drain the FIFO with combined ``i2c_rdwr`` transfers (any length) instead of 30-byte SMBus
        blocks.

    Examples
    --------
    >>> from ebantenna.device.simulated import SimulatedRig
    >>> from ebantenna.device.mpu6050 import MPU6050
    >>> rig = SimulatedRig.quiet(seed=0)
    >>> mpu = MPU6050(rig.bus, clock=rig.clock)
    >>> mpu.initialize()
    >>> rec = mpu.record(0.1)
    >>> rec.n_samples, rec.metadata["samples_lost"]
    (100, 0)
    """

    def __init__(self, bus, config: MPU6050Config | None = None, *,
                 retry: RetryPolicy | None = None, clock=None, use_rdwr: bool = False):
        self.config = MPU6050Config() if config is None else config
        if not isinstance(self.config, MPU6050Config):
            raise TypeError(f"config must be an MPU6050Config, got {type(config).__name__}")
        self.clock = SystemClock() if clock is None else clock
        self.device = I2CDevice(bus, self.config.address, retry=retry, clock=self.clock,
                                use_rdwr=use_rdwr)
        self._stream_start = None
        self._segment_start = None
        self._segment_base = 0
        self._segment_read = 0
        self.samples_read = 0
        self.samples_lost = 0
        self.overflows = 0

    # -- setup -----------------------------------------------------------------------------
    def who_am_i(self) -> int:
        """Read ``WHO_AM_I`` (RM, register 117)."""
        return self.device.read_byte(Register.WHO_AM_I)

    def check_identity(self) -> None:
        """Raise :class:`ChipIdentityError` unless ``WHO_AM_I`` reads 0x68."""
        value = self.who_am_i()
        if value != WHO_AM_I_VALUE:
            raise ChipIdentityError(
                f"the chip at I2C address 0x{self.config.address:02X} is not an MPU-6050: "
                f"WHO_AM_I reads 0x{value:02X}, expected 0x{WHO_AM_I_VALUE:02X}"
            )

    def initialize(self) -> None:
        """Check the chip, reset it, wake it on the PLL clock and set rate, filter and range.

        Register writes, in order: ``PWR_MGMT_1 = 0x80`` (device reset, then 100 ms wait, RM
        register 107 and PS section 4.20), ``PWR_MGMT_1 = 0x01`` (SLEEP cleared, CLKSEL = 1: PLL on
        the X gyroscope, recommended over the internal 8 MHz oscillator for stability), ``CONFIG =
        dlpf_cfg``, ``SMPLRT_DIV``, ``ACCEL_CONFIG = AFS_SEL << 3``, ``INT_ENABLE = 0x10``
        (FIFO_OFLOW_EN).
        """
        cfg = self.config
        self.check_identity()
        self.device.write_byte(Register.PWR_MGMT_1, PowerManagement1.DEVICE_RESET)
        self.clock.sleep(0.1)
        self.device.write_byte(Register.PWR_MGMT_1, CLKSEL.put(ClockSource.PLL_X_GYRO))
        self.clock.sleep(0.01)
        self.device.write_byte(Register.CONFIG, cfg.dlpf_cfg)
        self.device.write_byte(Register.SMPLRT_DIV, cfg.smplrt_div)
        self.device.write_byte(Register.ACCEL_CONFIG, cfg.accel_config)
        self.device.write_byte(Register.INT_ENABLE, Interrupt.FIFO_OFLOW)
        logger.info("MPU-6050 at 0x%02X: %g Hz, DLPF %d (%g Hz), +/-%d g", cfg.address, cfg.fs,
                    cfg.dlpf_cfg, cfg.bandwidth, cfg.full_scale_g)

    # -- conversion ------------------------------------------------------------------------
    def to_acceleration(self, counts) -> np.ndarray:
        """Raw counts to acceleration, m/s^2."""
        return np.asarray(counts, dtype=np.float64) * (STANDARD_GRAVITY / self.config.lsb_per_g)

    @staticmethod
    def _decode(raw: bytes) -> np.ndarray:
        return np.frombuffer(raw, dtype=DATA_DTYPE).astype(np.int16).reshape(-1, 3)

    def read_acceleration(self) -> np.ndarray:
        """The latest X, Y, Z acceleration, m/s^2, from one 6-byte burst read (not byte by byte)."""
        return self.to_acceleration(self._decode(self.device.read_block(Register.ACCEL_XOUT_H,
                                                                   SAMPLE_BYTES))[0])

    # -- FIFO ------------------------------------------------------------------------------
    def _reset_fifo(self) -> None:
        # FIFO_RESET only acts while USER_CTRL.FIFO_EN is 0 (RM, register 106).
        self.device.write_byte(Register.FIFO_EN, 0)
        self.device.write_byte(Register.USER_CTRL, UserControl.FIFO_RESET)
        self.device.read_byte(Register.INT_STATUS)  # clears a stale overflow flag
        self.device.write_byte(Register.FIFO_EN, FifoEnable.ACCEL)
        self.device.write_byte(Register.USER_CTRL, UserControl.FIFO_EN)
        self._segment_start = self.clock.monotonic()
        self._segment_read = 0

    def start_fifo(self) -> None:
        """Empty the FIFO and start filling it with accelerometer samples."""
        self._reset_fifo()
        self._stream_start = self._segment_start
        self._segment_base = 0
        self.samples_read = self.samples_lost = self.overflows = 0

    def stop_fifo(self) -> None:
        """Stop filling the FIFO."""
        self.device.write_byte(Register.USER_CTRL, 0)
        self.device.write_byte(Register.FIFO_EN, 0)

    def fifo_count(self) -> int:
        """Bytes waiting in the FIFO (``FIFO_COUNTH``/``L`` read in one burst)."""
        high, low = self.device.read_block(Register.FIFO_COUNTH, 2)
        return (high << 8) | low

    def read_fifo(self) -> FifoBlock:
        """Drain every whole sample waiting in the FIFO.

        ``INT_STATUS`` is read first: if it reports an overflow (or the FIFO is full), the FIFO's
        content is no longer aligned on samples, so it is discarded, the FIFO is reset, and the
        samples produced since the last good read are counted as lost (from the elapsed time and
        the sample rate), logged and returned in :attr:`FifoBlock.lost`.
        """
        if self._stream_start is None:
            raise ValueError("the FIFO is not running: call start_fifo() first")
        fs = self.config.fs
        status = self.device.read_byte(Register.INT_STATUS)
        count = self.fifo_count()
        if status & Interrupt.FIFO_OFLOW or count >= FIFO_SIZE:
            old_start, read = self._segment_start, self._segment_read
            self._reset_fifo()
            # Everything produced between the last good read and the restart is gone.
            produced = max(int(math.floor((self._segment_start - old_start) * fs)), read)
            lost = produced - read
            self.overflows += 1
            self.samples_lost += lost
            self._segment_base += produced
            logger.warning("MPU-6050 FIFO overflow: %d samples lost; drain the FIFO faster", lost)
            return FifoBlock(np.empty(0, dtype=np.int64), np.empty((0, 3), np.int16), lost)
        n = count // SAMPLE_BYTES
        if n == 0:
            return FifoBlock(np.empty(0, dtype=np.int64), np.empty((0, 3), np.int16), 0)
        raw = self.device.read_block(Register.FIFO_R_W, n * SAMPLE_BYTES, increment=False,
                                     chunk=_FIFO_CHUNK)
        index = self._segment_base + self._segment_read + np.arange(n)
        self._segment_read += n
        self.samples_read += n
        return FifoBlock(index, self._decode(raw), 0)

    @property
    def fifo_capacity(self) -> float:
        """How long the FIFO can go undrained before it overflows, s (170 ms at 1 kHz)."""
        return (FIFO_SIZE // SAMPLE_BYTES) / self.config.fs

    def check_poll_interval(self, poll_interval: float) -> float:
        """Return ``poll_interval`` (s) if the FIFO, drained that often, cannot overflow."""
        poll_interval = check_positive("poll_interval", poll_interval)
        if not poll_interval < self.fifo_capacity:
            raise ValueError(
                f"poll_interval must be < {self.fifo_capacity:.3f} s (the FIFO holds "
                f"{FIFO_SIZE // SAMPLE_BYTES} samples at {self.config.fs:g} Hz), "
                f"got {poll_interval!r}")
        return poll_interval

    @property
    def stream_start(self) -> float | None:
        """Clock reading when :meth:`start_fifo` started the stream, s (None before)."""
        return self._stream_start

    @property
    def stream_position(self) -> int:
        """Samples produced since :meth:`start_fifo` that have been read or counted as lost."""
        return self._segment_base + self._segment_read

    def metadata(self) -> dict:
        """What a recording from this chip should say about its origin."""
        cfg = self.config
        return {
            "device": "MPU-6050",
            "address": cfg.address,
            "sample_rate_hz": cfg.fs,
            "dlpf_cfg": cfg.dlpf_cfg,
            "bandwidth_hz": cfg.bandwidth,
            "full_scale_g": cfg.full_scale_g,
            "lsb_per_g": cfg.lsb_per_g,
            "i2c_retries": self.device.retries,
            "fifo_overflows": self.overflows,
        }

    def to_recording(self, index, counts, *, lost: int, origin: int | None = None,
                     metadata: dict | None = None) -> Recording:
        """Turn stream positions and raw counts into a :class:`Recording` (X -> ax, Z -> az).

        ``t`` is ``(index - origin) / fs`` (``origin`` defaults to ``index[0]``): a lost stretch
        shows as a gap in ``t``.
        """
        index = np.asarray(index, dtype=np.int64)
        counts = np.asarray(counts, dtype=np.int16).reshape(-1, 3)
        if index.size == 0:
            raise ValueError("no samples to make a recording of")
        limit = np.iinfo(np.int16)
        saturated = int(np.count_nonzero(
            (counts[:, [0, 2]] == limit.min) | (counts[:, [0, 2]] == limit.max)))
        if saturated:
            logger.warning("%d accelerometer readings at the +/-%d g limit (clipped)",
                           saturated, self.config.full_scale_g)
        acc = self.to_acceleration(counts)
        meta = self.metadata()
        meta.update({"samples_lost": int(lost), "samples_saturated": saturated,
                     "first_index": int(index[0])})
        meta.update(metadata or {})
        origin = int(index[0]) if origin is None else int(origin)
        return Recording((index - origin) / self.config.fs, acc[:, 0], acc[:, 2],
                         self.config.fs, meta)

    def record(self, duration: float, *, poll_interval: float = 0.02) -> Recording:
        """Record ``duration`` seconds through the FIFO, draining it every ``poll_interval``.

        Parameters
        ----------
        duration : float
            Length of the recording, s.
        poll_interval : float
            Time between drains, s. Must be below the FIFO's 170 ms at 1 kHz; a host that stalls
            for longer loses samples (and counts them).

        Returns
        -------
        Recording
            ``metadata["samples_lost"]`` says how many of the ``round(duration * fs)`` samples
            were lost.
        """
        duration = check_positive("duration", duration)
        poll_interval = self.check_poll_interval(poll_interval)
        wanted = max(1, round(duration * self.config.fs))
        self.start_fifo()
        indices, blocks = [], []
        try:
            while True:
                self.clock.sleep(poll_interval)
                block = self.read_fifo()
                indices.append(block.index)
                blocks.append(block.counts)
                if self.stream_position >= wanted:
                    break
        finally:
            self.stop_fifo()
        index = np.concatenate(indices)
        counts = np.concatenate(blocks)
        keep = index < wanted
        lost = wanted - int(np.count_nonzero(keep))
        return self.to_recording(index[keep], counts[keep], lost=lost, origin=0)
