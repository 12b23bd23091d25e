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

Compatible chips (MPU-6500 family)
----------------------------------
The MPU-6500, MPU-9250 and MPU-9255 answer the same accelerometer, FIFO and power registers, with
three differences that matter here (MPU-6500 Register Map RM-MPU-6500A-00 rev. 2.1, registers 25,
26 and 29): ``SMPLRT_DIV`` applies only when ``0 < DLPF_CFG < 7`` (with the default
``DLPF_CFG = 0`` they would stream at 8 kHz); the accelerometer's filter is ``A_DLPF_CFG`` in
``ACCEL_CONFIG2``, not ``CONFIG``; and the FIFO holds 512 bytes. They are configured with
``DLPF_CFG = max(dlpf_cfg, 1)`` (1 kHz internal rate, so the divider applies), ``SMPLRT_DIV =
1 kHz / fs - 1`` and ``A_DLPF_CFG = max(dlpf_cfg, 1)`` (218.1 Hz for the default, the nearest
to the MPU-6050's 260 Hz). Other parts Linux's driver knows are refused by name: their FIFO sizes
and filter registers are not modelled here.

FIFO (RM, registers 35, 56, 58, 106, 114-116)
---------------------------------------------
With only ``ACCEL_FIFO_EN`` set, each sample is 6 bytes (X, Y, Z, big-endian, signed). The FIFO
holds 1024 bytes, 170 samples, 170 ms at 1 kHz. When it is full the chip overwrites the oldest
bytes and sets ``FIFO_OFLOW_INT`` in ``INT_STATUS``; since 1024 is not a multiple of 6, what
remains is no longer aligned on sample boundaries. How the driver keeps every kept sample right
through overflows, failed and short reads and chip resets, and counts every one it could not
keep, is the subject of :mod:`ebantenna.device.fifo`.
"""

from __future__ import annotations

import errno
import logging
import math
import warnings

import numpy as np

from .._budget import check_allocation
from .._validate import check_bool, check_nonnegative, check_positive
from ..chips.mpu6050 import (
    ACCEL_DLPF_6500,
    ACCEL_SAMPLE_BYTES,
    CHIP_MODELS,
    CLKSEL,
    COMPATIBLE_WHO_AM_I,
    DATA_DTYPE,
    GYRO_RATE_DLPF_ON,
    GYRO_STARTUP,
    RESET_WAIT,
    STANDARD_GRAVITY,
    USER_CONTROL_SELF_CLEARING,
    WHO_AM_I_VALUE,
    ClockSource,
    FifoEnable,
    Interrupt,
    PowerManagement1,
    Register,
    UserControl,
)
from ..recording import Recording
from .clock import SystemClock
from .fifo import CLOCK_TOLERANCE, FIFO_CHUNK, FifoBlock, FifoStream
from .i2c import RASPBERRY_PI_BUS_HZ, I2CDevice, RetryPolicy, SettingError, transfer_time
from .mpu6050_config import LSB_PER_G, MPU6050Config, accel_bandwidth, sample_rate_divider
from .watchdog import StreamStalledError, record_stream

__all__ = [
    "MPU6050",
    "MPU6050Config",
    "ChipIdentityError",
    "CompatibleChipWarning",
    "SettingError",
    "FifoBlock",
    "STANDARD_GRAVITY",
    "LSB_PER_G",
    "sample_rate_divider",
    "accel_bandwidth",
    "MAX_RECORD_SAMPLES",
]

logger = logging.getLogger(__name__)

#: Most samples one :meth:`MPU6050.record` takes: ten minutes at 1 kHz. A longer stream is a
#: count no window of the package needs (a search records at most a minute), and on the
#: simulated rig it takes a minute of computing per 10**6 samples.
MAX_RECORD_SAMPLES = 600_000

#: Bytes per FIFO sample with only the accelerometer enabled.
SAMPLE_BYTES = ACCEL_SAMPLE_BYTES
#: Memory a recorded sample takes, bytes: about 100 in the stream (counts, slot, segment,
#: position), then the recording's t, ax and az and its raw account as JSON-ready lists (each
#: count and index a Python object): 340 measured by tracemalloc at 30 s, with a margin
#: (tests/device/test_device_silent_faults.py measures it).
BYTES_PER_SAMPLE = 400
#: Samples kept free in the FIFO by the poll-interval limit (Linux's ``inv_mpu6050`` resets its
#: FIFO when fewer than three samples' room is left).
FIFO_MARGIN = 3


class ChipIdentityError(OSError):
    """The chip at the address is not the one expected (WHO_AM_I mismatch)."""


class CompatibleChipWarning(UserWarning):
    """The chip is not an MPU-6050 but a part known to answer the same registers."""


#: Writes of ``PWR_MGMT_1.DEVICE_RESET`` :meth:`MPU6050.initialize` makes before it fails: each
#: is confirmed by the settings it must have cleared (``MPU6050._reset_device``).
DEVICE_RESET_ATTEMPTS = 2

#: Bits of ``USER_CTRL`` that read back as written (the reset bits clear themselves, RM 106).
USER_CTRL_STABLE = 0xFF & ~int(USER_CONTROL_SELF_CLEARING)


def register_name(register: int) -> str:
    """``"ACCEL_CONFIG (0x1C)"`` for a register of the map, else its number."""
    try:
        return f"{Register(register).name} (0x{int(register):02X})"
    except ValueError:
        return f"register 0x{int(register):02X}"


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
    clock : SystemClock or VirtualClock, optional
        ``monotonic``/``sleep`` provider. Default the system clock.
    use_rdwr : bool
        Drain the FIFO with combined ``i2c_rdwr`` transfers (any length) instead of 30-byte SMBus
        blocks.
    bus_hz : float, optional
        The bus's I2C clock, Hz, for the poll-interval limit (:meth:`max_poll_interval`).
        Default: the bus's ``bus_hz`` attribute if it has one (the simulated bus), else a
        Raspberry Pi's default 100 kHz.

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
                 retry: RetryPolicy | None = None, clock=None, use_rdwr: bool = False,
                 bus_hz: float | None = None):
        self.config = MPU6050Config() if config is None else config
        if not isinstance(self.config, MPU6050Config):
            raise TypeError(f"config must be an MPU6050Config, got {type(config).__name__}")
        self.clock = SystemClock() if clock is None else clock
        self.device = I2CDevice(bus, self.config.address, retry=retry, clock=self.clock,
                                use_rdwr=use_rdwr)
        #: The running FIFO stream (None before :meth:`start_fifo`).
        self.stream: FifoStream | None = None
        self._shortened = None  # the poll wait last announced as shortened (poll_wait)
        #: The part found by :meth:`check_identity` (an MPU-6050 until then).
        self.model = CHIP_MODELS[WHO_AM_I_VALUE]
        #: The I2C clock assumed for the poll-interval limit, Hz.
        self.bus_hz = check_positive(
            "bus_hz", getattr(bus, "bus_hz", RASPBERRY_PI_BUS_HZ) if bus_hz is None else bus_hz)

    @property
    def part(self) -> str:
        """Name of the part found by :meth:`check_identity`."""
        return self.model.name

    @property
    def fifo_size(self) -> int:
        """The part's FIFO size, bytes (1024 on the MPU-6050, 512 on the MPU-6500 family)."""
        return self.model.fifo_size

    # -- setup -----------------------------------------------------------------------------
    def who_am_i(self) -> int:
        """Read ``WHO_AM_I`` (RM, register 117)."""
        return self.device.read_byte(Register.WHO_AM_I)

    def check_identity(self) -> None:
        """Check ``WHO_AM_I`` (RM 117): 0x68 is an MPU-6050; a part of the MPU-6500 family is
        accepted with a :class:`CompatibleChipWarning` and configured as such (see the module
        notes); another part Linux's driver knows is refused by name, and anything else raises
        :class:`ChipIdentityError`."""
        value = self.who_am_i()
        if value == WHO_AM_I_VALUE:
            self.model = CHIP_MODELS[value]
            return
        if value in CHIP_MODELS:
            self.model = CHIP_MODELS[value]
            message = (f"the chip at I2C address 0x{self.config.address:02X} reads WHO_AM_I "
                       f"0x{value:02X}: an {self.part}, not an MPU-6050. It is configured as "
                       f"one (its {self.fifo_size}-byte FIFO, the accelerometer filter in "
                       "ACCEL_CONFIG2); check its noise figures before comparing recordings")
            logger.warning(message)
            warnings.warn(message, CompatibleChipWarning, stacklevel=3)
            return
        if value in COMPATIBLE_WHO_AM_I:
            raise ChipIdentityError(
                f"the chip at I2C address 0x{self.config.address:02X} is an "
                f"{COMPATIBLE_WHO_AM_I[value]} (WHO_AM_I 0x{value:02X}): not supported, its FIFO "
                "size and filter registers are not modelled here (supported: "
                + ", ".join(m.name for m in CHIP_MODELS.values()) + ")")
        known = ", ".join(f"0x{v:02X} ({name})" for v, name in COMPATIBLE_WHO_AM_I.items())
        raise ChipIdentityError(
            f"the chip at I2C address 0x{self.config.address:02X} is not an MPU-6050: "
            f"WHO_AM_I reads 0x{value:02X}, expected 0x{WHO_AM_I_VALUE:02X} (or a compatible "
            f"part: {known}). A value of 0x00 or 0xFF usually means a wiring fault"
        )

    def initialize(self) -> None:
        """Check the chip, reset it, wake it on the PLL clock and set rate, filter and range.

        Register writes, in order: ``PWR_MGMT_1 = 0x80`` (device reset, then a
        :data:`~ebantenna.chips.mpu6050.RESET_WAIT` of 100 ms, confirmed by the settings it
        clears and made again if they did not clear: ``_reset_device``), then
        :meth:`configure`.
        """
        self.check_identity()
        self._reset_device()
        self.configure()

    def _reset_device(self) -> None:
        """``PWR_MGMT_1.DEVICE_RESET`` and the :data:`~ebantenna.chips.mpu6050.RESET_WAIT`,
        confirmed from what the reset leaves.

        The bit clears itself once the reset is done (RM 107), so reading it back cannot tell
        whether the reset acted. A reset returns every register to its reset value: 0 for every
        setting the driver writes but ``PWR_MGMT_1`` (RM section 3; the MPU-6500 and MPU-9250
        register maps say the same), whose reset value differs between the families. Those
        settings (:meth:`expected_registers`) are read: one that is not 0 is a reset that did
        not act, logged, and the reset is made again, :data:`DEVICE_RESET_ATTEMPTS` times in
        all. A chip whose settings already read 0 (just powered on, or set up by a program that
        left them so) cannot show a lost reset this way; its settings are written and read
        back by :meth:`configure` all the same.

        Raises
        ------
        SettingError
            When a setting still reads non-zero after the last reset.
        """
        for attempt in range(DEVICE_RESET_ATTEMPTS):
            self.device.write_byte(Register.PWR_MGMT_1, PowerManagement1.DEVICE_RESET)
            self.clock.sleep(RESET_WAIT)
            left = self._left_after_reset()
            if not left:
                return
            logger.warning("%s at 0x%02X: %s after PWR_MGMT_1.DEVICE_RESET: the reset did not "
                           "act%s", self.part, self.config.address, left,
                           "; resetting again" if attempt + 1 < DEVICE_RESET_ATTEMPTS else "")
        raise SettingError(
            errno.EIO, f"the {self.part} at 0x{self.config.address:02X} does not reset: {left} "
            f"after PWR_MGMT_1.DEVICE_RESET (0x6B = 0x80) was written {DEVICE_RESET_ATTEMPTS} "
            "times (a write lost on the bus, or another program setting it up at the same time)")

    def _left_after_reset(self) -> str:
        """The settings the driver writes, but ``PWR_MGMT_1``, that do not read their reset value
        0, and ``PWR_MGMT_1`` if its reset bit still reads set, as ``"ACCEL_CONFIG (0x1C) reads
        0x18, ..."``; empty when none. Every read is retried after a missing acknowledge
        (nothing read here clears on read)."""
        seen, _ = self._read_settings(status=False)
        expected = self.expected_registers()
        left = [(r, v) for r, v in seen.items()
                if r in expected and r != Register.PWR_MGMT_1 and v]
        if seen[Register.PWR_MGMT_1] & PowerManagement1.DEVICE_RESET:
            left.append((Register.PWR_MGMT_1, seen[Register.PWR_MGMT_1]))
        return ", ".join(f"{register_name(r)} reads 0x{v:02X}" for r, v in sorted(left))

    def configure(self) -> None:
        """Wake the chip and set rate, filter, range and the overflow interrupt.

        Every write is read back (:meth:`write_verified`). Register writes, in order:
        ``USER_CTRL = 0`` (FIFO off while the clock starts),
        ``PWR_MGMT_1 = 0x01`` (SLEEP cleared, CLKSEL = 1: PLL on the X
        gyroscope, recommended over the internal 8 MHz oscillator for stability, RM 107), a wait
        of :data:`~ebantenna.chips.mpu6050.GYRO_STARTUP` (30 ms, the gyroscope's start-up time,
        PS 6.1), ``CONFIG = dlpf_cfg``, ``SMPLRT_DIV``, ``ACCEL_CONFIG = AFS_SEL << 3``,
        ``INT_ENABLE = 0x10`` (FIFO_OFLOW_EN). Also used to bring back a chip that was reset
        (a brown-out) in the middle of a run.
        """
        cfg = self.config
        self.write_verified(Register.USER_CTRL, 0)
        self.write_verified(Register.PWR_MGMT_1, CLKSEL.put(ClockSource.PLL_X_GYRO))
        self.clock.sleep(GYRO_STARTUP)
        for register, value in self._settings().items():
            self.write_verified(register, value)
        logger.info("%s at 0x%02X: %g Hz, DLPF %d (%g Hz), +/-%d g", self.part, cfg.address,
                    cfg.fs, cfg.dlpf_cfg, self.bandwidth, cfg.full_scale_g)

    def _settings(self) -> dict:
        cfg = self.config
        if not self.model.accel_config2:
            return {Register.CONFIG: cfg.dlpf_cfg, Register.SMPLRT_DIV: cfg.smplrt_div,
                    Register.ACCEL_CONFIG: cfg.accel_config,
                    Register.INT_ENABLE: Interrupt.FIFO_OFLOW}
        # MPU-6500 family (module notes): the divider needs the filter on; the accelerometer's
        # own filter lives in ACCEL_CONFIG2.
        divider = round(GYRO_RATE_DLPF_ON / cfg.fs) - 1
        if not (0 <= divider <= 255 and math.isclose(GYRO_RATE_DLPF_ON / (1 + divider), cfg.fs,
                                                     rel_tol=1e-12)):
            raise ValueError(f"fs must be 1000 Hz / (1 + n) for an integer n in [0, 255] on an "
                             f"{self.part}; got {cfg.fs!r}")
        filtered = self.dlpf_cfg
        return {Register.CONFIG: filtered, Register.SMPLRT_DIV: divider,
                Register.ACCEL_CONFIG: cfg.accel_config, Register.ACCEL_CONFIG2: filtered,
                Register.INT_ENABLE: Interrupt.FIFO_OFLOW}

    @property
    def dlpf_cfg(self) -> int:
        """The ``DLPF_CFG`` written to ``CONFIG`` on this part (on the MPU-6500 family
        ``max(dlpf_cfg, 1)``, also its ``A_DLPF_CFG``: module notes), what a recording states."""
        if self.model.accel_config2:
            return max(self.config.dlpf_cfg, 1)
        return self.config.dlpf_cfg

    @property
    def bandwidth(self) -> float:
        """The accelerometer's -3 dB bandwidth as configured on this part, Hz."""
        if self.model.accel_config2:
            return ACCEL_DLPF_6500[self.dlpf_cfg]
        return self.config.bandwidth

    def write_verified(self, register: int, value: int) -> None:
        """Write a setting and read it back; written once more if it reads back wrong.

        Raises
        ------
        SettingError
            When it still reads back wrong: the message says what was written and what was
            seen (a bit flipped on the wire twice in a row, a register the chip does not take,
            two devices answering at one address).
        """
        mask = USER_CTRL_STABLE if register == Register.USER_CTRL else 0xFF
        seen = self.device.write_read_back(
            register, value, mask, lambda: f"{register_name(register)} of the {self.part}")
        if seen is None:
            return
        raise SettingError(
            errno.EIO, f"{register_name(register)} of the {self.part} at 0x"
            f"{self.config.address:02X} reads back 0x{seen:02X} after 0x{value:02X} was written "
            "twice: a bit error on the bus, or two devices answering at this address "
            "('i2cdetect' cannot tell two of one kind apart: check the AD0 pins)")

    def expected_registers(self, streaming: bool = True) -> dict:
        """Every setting the driver wrote, as ``{register: value}``: rate, filter, range, the
        overflow interrupt, the clock (awake), and with ``streaming`` the FIFO's enables."""
        streaming = check_bool("streaming", streaming)
        expected = {Register.PWR_MGMT_1: CLKSEL.put(ClockSource.PLL_X_GYRO), **self._settings()}
        if streaming:
            expected[Register.FIFO_EN] = FifoEnable.ACCEL
            expected[Register.USER_CTRL] = UserControl.FIFO_EN
        return {Register(r): int(v) for r, v in expected.items()}

    def read_registers(self) -> tuple[dict, int]:
        """Read every setting of :meth:`expected_registers` back in four bursts, and
        ``INT_STATUS`` (clear on read, read once, in the burst that starts at ``INT_ENABLE``).

        Returns ``({register: value}, int_status)``.
        """
        return self._read_settings(status=True)

    def _read_settings(self, status: bool) -> tuple[dict, int | None]:
        """The settings' registers in four bursts, as :meth:`read_registers`; without
        ``status``, ``INT_ENABLE`` is read alone, retried after a missing acknowledge, and
        ``INT_STATUS`` is left unread (None)."""
        device = self.device
        first = Register.SMPLRT_DIV
        last = Register.ACCEL_CONFIG2 if self.model.accel_config2 else Register.ACCEL_CONFIG
        seen = dict(zip(range(first, last + 1), device.read_block(first, last - first + 1),
                        strict=True))
        seen[Register.FIFO_EN] = device.read_byte(Register.FIFO_EN)
        int_status = None
        if status:  # INT_ENABLE (0x38), 0x39, INT_STATUS (0x3A): one attempt, clear on read
            seen[Register.INT_ENABLE], _, int_status = device.read_block(Register.INT_ENABLE, 3,
                                                                         retry=False)
        else:
            seen[Register.INT_ENABLE] = device.read_byte(Register.INT_ENABLE)
        seen[Register.USER_CTRL], seen[Register.PWR_MGMT_1] = device.read_block(
            Register.USER_CTRL, 2)
        return {Register(r): v for r, v in seen.items()}, int_status

    def _changed_registers(self, seen: dict, streaming: bool = True) -> list:
        """The settings of ``seen`` (from :meth:`read_registers`) that differ from what was
        written: ``[(register, written, seen), ...]``."""
        changed = []
        for register, value in self.expected_registers(streaming).items():
            mask = USER_CTRL_STABLE if register == Register.USER_CTRL else 0xFF
            if seen[register] & mask != value & mask:
                changed.append((register, value, seen[register]))
        return changed

    @staticmethod
    def _describe_changes(changed: list) -> str:
        """``"ACCEL_CONFIG (0x1C) changed from 0x18 to 0x00, ..."``, with what the values mean
        when the chip is asleep (a reset, e.g. a brown-out)."""
        text = ", ".join(f"{register_name(r)} changed from 0x{w:02X} to 0x{s:02X}"
                         for r, w, s in changed)
        if any(r == Register.PWR_MGMT_1 and s & PowerManagement1.SLEEP for r, _, s in changed):
            text += " (the chip is asleep: reset, e.g. by a brown-out)"
        return text

    def configuration_lost(self, streaming: bool = False) -> str | None:
        """Why the chip no longer runs as configured (which settings changed, from what to
        what), or None. ``streaming``: also check the FIFO's enables."""
        seen, _ = self.read_registers()
        changed = self._changed_registers(seen, streaming)
        return self._describe_changes(changed) if changed else None

    # -- conversion ------------------------------------------------------------------------
    def to_acceleration(self, counts) -> np.ndarray:
        """Raw counts to acceleration, m/s^2.

        Raises
        ------
        ValueError
            For a count that no 16-bit output register can hold (outside -32768 ... 32767, RM
            59-64) or that is not a number.

        Examples
        --------
        >>> from ebantenna.device.simulated import SimulatedRig
        >>> from ebantenna.device.mpu6050 import MPU6050
        >>> rig = SimulatedRig.quiet()
        >>> MPU6050(rig.bus, clock=rig.clock).to_acceleration([2048, -32768]).round(3)
        array([  9.807, -156.906])
        """
        try:
            counts = np.asarray(counts, dtype=np.float64)
        except (TypeError, ValueError):
            raise TypeError(f"counts must be 16-bit register values (integers), got "
                            f"{type(counts).__name__}") from None
        limit = np.iinfo(np.int16)
        bad = ~((counts >= limit.min) & (counts <= limit.max) & (counts == np.round(counts)))
        if bad.any():  # NaN compares False
            raise ValueError(f"counts must be 16-bit register values, whole numbers in "
                             f"[{limit.min}, {limit.max}], got {counts[bad].flat[0]!r}")
        return counts * (STANDARD_GRAVITY / self.config.lsb_per_g)

    @staticmethod
    def decode(raw: bytes) -> np.ndarray:
        """Bytes of whole samples (big-endian X, Y, Z, RM 59-64) to (n, 3) int16 counts.

        ``raw`` must be bytes-like and hold whole samples of 6 bytes.
        """
        if not isinstance(raw, bytes | bytearray | memoryview):
            raise TypeError(f"raw must be bytes, got {type(raw).__name__}")
        if len(raw) % SAMPLE_BYTES:
            raise ValueError(f"raw must hold whole samples of {SAMPLE_BYTES} bytes (X, Y, Z), "
                             f"got {len(raw)} bytes")
        return np.frombuffer(raw, dtype=DATA_DTYPE).astype(np.int16).reshape(-1, 3)

    def read_acceleration(self) -> np.ndarray:
        """The latest X, Y, Z acceleration, m/s^2, from one 6-byte burst read (not byte by byte)."""
        return self.to_acceleration(self.decode(self.device.read_block(Register.ACCEL_XOUT_H,
                                                                  SAMPLE_BYTES))[0])

    # -- FIFO ------------------------------------------------------------------------------
    def start_fifo(self) -> FifoStream:
        """Empty the FIFO and start a stream of accelerometer samples (:mod:`~.fifo`)."""
        self.stream = FifoStream(self)
        return self.stream

    def stop_fifo(self) -> None:
        """Stop filling the FIFO (the stream's record stays readable). Both enables are read
        back (:meth:`write_verified`): a stop that did not land would leave the FIFO filling
        and overflowing behind a recording said to be over."""
        self.write_verified(Register.USER_CTRL, 0)
        self.write_verified(Register.FIFO_EN, 0)

    def fifo_count(self) -> int:
        """Bytes waiting in the FIFO (``FIFO_COUNTH``/``L`` read in one burst, RM 114-115)."""
        high, low = self.device.read_block(Register.FIFO_COUNTH, 2)
        return (high << 8) | low

    def read_fifo(self) -> FifoBlock:
        """Drain every whole sample waiting in the FIFO (see :meth:`FifoStream.drain`)."""
        if self.stream is None:
            raise ValueError("the FIFO is not running: call start_fifo() first")
        return self.stream.drain()

    @property
    def fifo_capacity(self) -> float:
        """How long the FIFO can go undrained before it overflows, s (170 ms at 1 kHz)."""
        return (self.fifo_size // SAMPLE_BYTES) / self.config.fs

    def max_poll_interval(self, busy: float = 0.0) -> float:
        """The longest wait between drains after which the FIFO still cannot overflow, s.

        A drain loop sleeps ``P``, then reads the ``N`` samples waiting, ``c`` seconds each on
        the bus (register reads, the chip's address sent twice:
        :func:`~ebantenna.device.i2c.transfer_bits`), plus ``F`` seconds of fixed transfers
        (the count before and after the data, and the settings read back,
        :meth:`read_registers`) and ``busy`` seconds of other
        traffic (servo updates). Samples arrive at up to ``r`` while it sleeps *and* while it
        drains (``r``: :meth:`fastest_rate`, ``fs (1 + tolerance)`` until a running stream has
        measured a faster clock), so ``N = r (P + F + busy + N c)``: ``N = r (P + F +
        busy) / (1 - r c)``. Keeping ``N`` three samples below the
        FIFO's size (Linux's ``inv_mpu6050`` keeps the same margin) gives
        ``P < N_max (1 - r c) / r - F - busy``. When ``r c >= 1`` the bus cannot keep up at all.

        Parameters
        ----------
        busy : float
            Other bus time per poll, s.

        Examples
        --------
        >>> from ebantenna.device.simulated import SimulatedRig
        >>> from ebantenna.device.mpu6050 import MPU6050
        >>> rig = SimulatedRig.quiet()
        >>> round(MPU6050(rig.bus, clock=rig.clock).max_poll_interval() * 1e3, 1)  # ms, 100 kHz
        53.8
        >>> rig.bus.bus_hz = 400e3
        >>> round(MPU6050(rig.bus, clock=rig.clock).max_poll_interval() * 1e3, 1)  # ms, 400 kHz
        131.3
        """
        busy = check_nonnegative("busy", busy)
        rate = self.fastest_rate()
        per_sample = transfer_time(FIFO_CHUNK, self.bus_hz, read=True) / (
            FIFO_CHUNK // SAMPLE_BYTES)
        settings = 5 if self.model.accel_config2 else 4
        fixed = sum(transfer_time(n, self.bus_hz, read=True) for n in (2, 2, settings, 1, 3, 2))
        most = self.fifo_size // SAMPLE_BYTES - FIFO_MARGIN
        return most * (1.0 - rate * per_sample) / rate - fixed - busy

    def fastest_rate(self) -> float:
        """The fastest the chip can be sampling, Hz: ``fs (1 + tolerance)``, or, once the
        running stream has adapted to a clock outside that tolerance
        (:class:`~ebantenna.device.fifo.FifoStream`), the fastest rate its period's prior
        bracket now holds (the counts measured it). A FIFO found full sooner than the bracket
        allows shows a least rate (``rate_at_least``), which counts too: the poll then follows
        the fast clock until drains that do not overflow bracket it (the stream adapts to it,
        and the bracket replaces the least rate) or the chip is configured again after a
        setting changed (the least rate was shown at the old settings, and is forgotten)."""
        rate = self.config.fs * (1.0 + CLOCK_TOLERANCE)
        if self.stream is not None:
            stream = self.stream
            rate = max(rate, 1.0 / stream.estimator.prior[0], stream.rate_at_least)
        return rate

    def poll_wait(self, poll_interval: float, busy: float = 0.0) -> float:
        """How long a drain loop polling every ``poll_interval`` s should sleep now, s: the
        interval itself while it stays below :meth:`max_poll_interval` (which follows the clock
        the stream measured), else nine tenths of that limit (0 when the bus cannot keep up at
        all), said once at WARNING. ``busy``: other bus time per poll, s."""
        poll_interval = check_positive("poll_interval", poll_interval)
        limit = self.max_poll_interval(busy)
        if poll_interval < limit:
            return poll_interval
        wait = max(0.9 * limit, 0.0)
        if self._shortened != round(wait, 6):
            self._shortened = round(wait, 6)
            logger.warning(
                "the %s samples at up to %s Hz (its clock, as the FIFO counts measured it): "
                "the poll interval is shortened from %.4g to %.4g s so that the FIFO cannot "
                "overflow", self.part, f"{self.fastest_rate():.4g}", poll_interval, wait)
        return wait

    def check_poll_interval(self, poll_interval: float, busy: float = 0.0) -> float:
        """Return ``poll_interval`` (s) if the FIFO, drained that often, cannot overflow (see
        :meth:`max_poll_interval`; ``busy``: other bus time per poll, s)."""
        poll_interval = check_positive("poll_interval", poll_interval)
        limit = self.max_poll_interval(busy)
        if not poll_interval < limit:
            raise ValueError(
                f"poll_interval must be < {max(limit, 0.0):.4f} s (the {self.part}'s FIFO holds "
                f"{self.fifo_size // SAMPLE_BYTES} samples at {self.config.fs:g} Hz, and draining "
                f"them at {self.bus_hz / 1e3:g} kHz takes time too), got {poll_interval!r}")
        return poll_interval

    @property
    def stream_position(self) -> int:
        """The slot after the last sample kept since :meth:`start_fifo` (0 before)."""
        return 0 if self.stream is None else self.stream.next_slot

    @property
    def overflows(self) -> int:
        """FIFO overflows seen in the current stream."""
        return 0 if self.stream is None else self.stream.overflows

    @property
    def samples_read(self) -> int:
        """Samples kept in the current stream."""
        return 0 if self.stream is None else self.stream.samples_read

    @property
    def samples_lost(self) -> int:
        """Slots of the current stream, up to the last kept sample, that hold no sample."""
        return self.stream_position - self.samples_read

    def metadata(self) -> dict:
        """What a recording from this chip should say about its origin."""
        cfg = self.config
        meta = {
            "device": self.part,
            "address": cfg.address,
            "sample_rate_hz": cfg.fs,
            "dlpf_cfg": self.dlpf_cfg,
            "bandwidth_hz": self.bandwidth,
            "fifo_size_bytes": self.fifo_size,
            "full_scale_g": cfg.full_scale_g,
            "lsb_per_g": cfg.lsb_per_g,
            "i2c_retries": self.device.retries,
        }
        if self.stream is not None:
            meta.update(self.stream.report())
        return meta

    def to_recording(self, first: int, stop: int, *, metadata: dict | None = None) -> Recording:
        """The stream's samples in slots ``[first, stop)`` as a
        :class:`~ebantenna.recording.Recording` (see :meth:`FifoStream.recording`)."""
        if self.stream is None:
            raise ValueError("no stream to make a recording of: call start_fifo() first")
        return self.stream.recording(first, stop, metadata=metadata)

    def record(self, duration: float, *, poll_interval: float = 0.02,
               watchdog: float = 1.0) -> Recording:
        """Record ``duration`` seconds through the FIFO, draining it every ``poll_interval``.

        Parameters
        ----------
        duration : float
            Length of the recording, s: ``round(duration * fs)`` slots, at most
            :data:`MAX_RECORD_SAMPLES`.
        poll_interval : float
            Time between drains, s. Must be below :meth:`max_poll_interval` (54 ms at 1 kHz on
            a 100 kHz bus); a host that stalls for longer loses samples (and counts them).
        watchdog : float
            Longest time without a new sample, s. Default 1 s.

        Returns
        -------
        Recording
            ``metadata["samples_lost"]`` says how many of the slots hold no sample.

        Raises
        ------
        StreamStalledError
            When no sample came for ``watchdog`` seconds; it holds what was recorded so far.
        """
        duration = check_positive("duration", duration)
        if duration * self.config.fs > MAX_RECORD_SAMPLES:
            raise ValueError(f"duration {duration:g} s asks for {duration * self.config.fs:.3g} "
                             f"samples at {self.config.fs:g} Hz, more than the "
                             f"{MAX_RECORD_SAMPLES} one recording may hold; record in parts")
        check_allocation(BYTES_PER_SAMPLE * duration * self.config.fs, parameter="duration",
                         what=f"a recording of {duration * self.config.fs:.3g} samples")
        return record_stream(self, duration, poll_interval=poll_interval, watchdog=watchdog)


__all__ += ["StreamStalledError"]
