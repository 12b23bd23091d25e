"""The simulated I2C bus: the subset of :class:`smbus2.SMBus` the drivers use, in virtual time.

Each transfer advances the :class:`~ebantenna.device.clock.VirtualClock` by its duration on the
bus plus a fixed per-transfer overhead, and sleeping advances it instantly, so a ten-second search
takes a fraction of a second. Every transfer passes through one place, ``SimulatedBus._begin``,
where the :class:`~ebantenna.device.simulated.faults.FaultInjector` may stall the host, reset the
accelerometer, make the host slow for a moment, time out on a stuck bus or fail the transfer
early; reads then go through
``SimulatedBus._read`` and writes through ``SimulatedBus._write``, where a transfer may
fail late (after the chip has done its part) or, for a read, come back short.

The bus clock defaults to 100 kHz, the rate a Raspberry Pi's I2C bus runs at unless
``dtparam=i2c_arm_baudrate`` in ``/boot/firmware/config.txt`` says otherwise (Raspberry Pi
documentation, "config.txt", ``i2c_arm_baudrate``: default 100000).
"""

from __future__ import annotations

import errno

from ..._validate import check_in_range, check_int, check_nonnegative
from ...chips.mpu6050 import ACCEL_SAMPLE_BYTES, ADDRESS_AD0_LOW, Register
from ...chips.pca9685 import DEFAULT_ADDRESS, LED_FULL, N_CHANNELS, Led, Mode1, led_register
from ...chips.pca9685 import Register as PcaRegister
from ..clock import VirtualClock
from ..i2c import (
    MAX_BUS_HZ,
    RASPBERRY_PI_BUS_HZ,
    SMBUS_BLOCK_MAX,
    TRANSFER_OVERHEAD,
    transfer_bits,
)
from .faults import FaultInjector, Faults

__all__ = ["SimulatedBus", "transfer_bits", "RASPBERRY_PI_BUS_HZ"]


#: Highest 7-bit I2C address.
_LAST_ADDRESS = 0x7F
#: Read/write flag of an I2C message (``I2C_M_RD`` in Linux's ``i2c.h``, as smbus2 sets it).
_I2C_M_RD = 0x0001


def _byte_list(data) -> list[int]:
    """``data`` (a sequence of bytes 0-255) as a list, or a clear error naming ``data``."""
    if isinstance(data, str) or not hasattr(data, "__iter__"):
        raise TypeError(f"data must be a sequence of bytes (0-255), got {type(data).__name__}")
    return [check_int("data", value, minimum=0, maximum=0xFF) for value in data]


class SimulatedBus:
    """The :class:`smbus2.SMBus` subset the drivers use, with simulated chips behind it.

    Parameters
    ----------
    clock : VirtualClock, optional
        Virtual time; a new one by default.
    devices : dict, optional
        Simulated chips by 7-bit address (objects with ``read(register, n)`` and
        ``write(register, data)``); an address with no chip does not acknowledge (errno 121).
    faults : Faults, optional
        What to inject.
    seed : int
        Seed of the fault injector.
    bus_hz : float
        I2C clock, Hz. Default 100 kHz, a Raspberry Pi's default (:data:`RASPBERRY_PI_BUS_HZ`);
        400 kHz (fast mode) when ``i2c_arm_baudrate=400000`` is set.
    overhead : float
        Fixed cost of one transfer (system call, driver), s. Default 50 us.

    Attributes
    ----------
    devices : dict
        Chips by 7-bit address.
    writes : list of (address, register, tuple of int)
        Every completed write, in order.
    transfers : int
        Transfers attempted on the bus (including the failed ones).

    Examples
    --------
    >>> from ebantenna.device.simulated import SimulatedBus
    >>> bus = SimulatedBus()
    >>> bus.read_byte_data(0x68, 0)
    Traceback (most recent call last):
    ...
    OSError: [Errno 121] Remote I/O error
    >>> round(bus.clock.monotonic() * 1e6, 1)  # us: 50 us overhead + a read's 39 clocks, 100 kHz
    440.0
    """

    def __init__(self, clock=None, *, devices: dict | None = None, faults: Faults | None = None,
                 seed: int = 0, bus_hz: float = RASPBERRY_PI_BUS_HZ,
                 overhead: float = TRANSFER_OVERHEAD,
                 reset_address: int = ADDRESS_AD0_LOW):
        self.clock = VirtualClock() if clock is None else clock
        self.faults = Faults() if faults is None else faults
        self.bus_hz = bus_hz
        self.overhead = check_nonnegative("overhead", overhead)
        self.injector = FaultInjector(self.faults, seed)
        self.devices: dict[int, object] = dict(devices or {})
        self.writes: list[tuple[int, int, tuple[int, ...]]] = []
        self.transfers = 0
        self.closed = False
        #: The chip that the ``chip_reset_at`` of :class:`Faults` browns out.
        self.reset_address = reset_address

    @property
    def bus_hz(self) -> float:
        """The bus clock, Hz, in (0, :data:`~ebantenna.device.i2c.MAX_BUS_HZ`]: checked whenever
        it is set."""
        return self._bus_hz

    @bus_hz.setter
    def bus_hz(self, value) -> None:
        self._bus_hz = check_in_range("bus_hz", value, 0.0, MAX_BUS_HZ, high_inclusive=True,
                                      reason="no I2C mode clocks faster (NXP UM10204)")

    @property
    def errors_injected(self) -> int:
        """Transfers failed on purpose."""
        return self.injector.errors_injected

    def _fail(self, error: OSError) -> OSError:
        """``error``, after the transfer has hung for the adapter's timeout if it is one."""
        self.clock.advance(self.injector.timeout_wait(error))
        return error

    def _begin(self, address: int, nbytes: int, *, counting: bool = False,
               read: bool = False):
        """Run a transfer's bus phase: time, faults, acknowledge.

        Returns the chip addressed and the kind of late fault drawn for it (None, "late",
        "short" or, for a read of the MPU-6050's FIFO count (``counting``), "overcount"); an
        early fault raises here, before the chip sees anything.
        """
        if self.closed:
            raise OSError(errno.EBADF, "the simulated bus is closed")
        injector, clock = self.injector, self.clock
        clock.advance(self.overhead + transfer_bits(nbytes, read=read) / self.bus_hz)
        # a stall or a preemption of 0 s (most transfers) leaves the clock as it is: not added
        stall = injector.host_stall(clock.monotonic())
        if stall:
            clock.advance(stall)
        lost = injector.preemption(clock.monotonic())
        if lost:
            clock.advance(lost)
        now = clock.monotonic()
        self.transfers += 1
        if injector.chip_reset(now) and self.reset_address in self.devices:
            self.devices[self.reset_address].brown_out()
        if self.reset_address in self.devices:
            injector._chip_events(now, self.devices[self.reset_address])
        if injector._pca_brown_out(now) and DEFAULT_ADDRESS in self.devices:
            self.devices[DEFAULT_ADDRESS].reset()
        stuck = injector.stuck(now)
        if stuck is not None:
            raise self._fail(stuck)
        kind = injector.draw(now)
        if kind == "overcount" and not counting:
            injector.cancel()
            kind = None
        if kind is not None and kind not in ("late", "short", "overcount"):
            raise self._fail(injector.early_error(kind))
        if address not in self.devices:
            raise OSError(errno.EREMOTEIO, "Remote I/O error")
        return self.devices[address], kind

    def _read(self, address: int, register: int, length: int, nbytes: int) -> list[int]:
        """One read transfer of ``length`` bytes from ``register`` on (``nbytes`` on the wire)."""
        counting = address == self.reset_address and register == Register.FIFO_COUNTH
        chip, kind = self._begin(address, nbytes, counting=counting and length >= 2,
                                 read=True)
        if address == self.reset_address and register == Register.FIFO_R_W:
            self.injector._drain_read(self.clock.monotonic(), chip)
        if kind == "short":
            return chip.read(register, self.injector.short_length(length))
        data = chip.read(register, length)
        if kind == "late":
            raise self._fail(self.injector.late_error())
        if kind == "overcount":
            extra = chip.impossible_samples() + self.injector.overcount()
            count = min(((data[0] << 8) | data[1]) + ACCEL_SAMPLE_BYTES * extra, (1 << 16) - 1)
            data[0], data[1] = count >> 8, count & 0xFF
        elif counting and length >= 2 and self.injector._undercount(self.clock.monotonic()):
            count = max(((data[0] << 8) | data[1]) - ACCEL_SAMPLE_BYTES, 0)
            data[0], data[1] = count >> 8, count & 0xFF
        if address == self.reset_address and register == Register.FIFO_R_W:
            data = self.injector._bit_errors(data)
        return data

    def _releases(self, address: int, register: int, data: list[int]) -> bool:
        """Whether this write switches PCA9685 outputs off and must fail (``release_fails``,
        ``release_fails_until`` of :class:`Faults`)."""
        until = self.faults.release_fails_until
        failing = self.faults.release_fails or (
            until is not None and self.clock.monotonic() < until)
        if address != DEFAULT_ADDRESS or not failing:
            return False
        if self.devices[address].regs[PcaRegister.MODE1] & Mode1.SLEEP:
            return False  # not set up yet: the outputs are off anyway
        last = register + len(data) - 1
        if not data[-1] & LED_FULL:
            return False
        return last == PcaRegister.ALL_LED_OFF_H or (
            PcaRegister.LED0_ON_L <= last <= led_register(N_CHANNELS - 1, Led.OFF_H)
            and (last - PcaRegister.LED0_ON_L) % 4 == 3)

    def _write(self, address: int, register: int, data: list[int]) -> None:
        """One write transfer of ``data`` from ``register`` on."""
        chip, kind = self._begin(address, len(data))
        if kind == "short":
            raise self._fail(self.injector.early_error("nack"))
        if self._releases(address, register, data):
            self.injector.errors_injected += 1
            self.injector.log.append((self.clock.monotonic(), "release refused"))
            raise self._fail(self.injector.early_error("eio"))
        if address == self.reset_address and self.faults.reset_lost:
            data = self.injector._without_reset(register, data, self.clock.monotonic())
        if address == self.reset_address and self.faults.flip_write:
            data = [self.injector._flipped(register + k, v) for k, v in enumerate(data)]
        elif address == DEFAULT_ADDRESS and self.faults.pca_flip_write:
            data = [self.injector._flipped(register + k, v, pca=True) for k, v in enumerate(data)]
        chip.write(register, data)
        self.writes.append((address, register, tuple(data)))
        if kind == "late":
            raise self._fail(self.injector.late_error())

    @staticmethod
    def _check(i2c_addr, register) -> None:
        """Refuse an address outside 0-127 or a register outside 0-255, as a real bus would."""
        check_int("i2c_addr", i2c_addr, minimum=0, maximum=_LAST_ADDRESS)
        check_int("register", register, minimum=0, maximum=0xFF)

    def read_byte_data(self, i2c_addr: int, register: int, force=None) -> int:
        """Read one register (a short transfer of it, no byte at all, is an ``EIO``)."""
        self._check(i2c_addr, register)
        data = self._read(i2c_addr, register, 1, 1)
        if not data:
            raise OSError(errno.EIO, "Input/output error")
        return data[0]

    def write_byte_data(self, i2c_addr: int, register: int, value: int, force=None) -> None:
        """Write one register."""
        self._check(i2c_addr, register)
        check_int("value", value, minimum=0, maximum=0xFF)
        self._write(i2c_addr, register, [value])

    def read_i2c_block_data(self, i2c_addr: int, register: int, length: int, force=None):
        """Read ``length`` (at most 32) bytes from ``register`` on."""
        self._check(i2c_addr, register)
        length = check_int("length", length, minimum=0, maximum=SMBUS_BLOCK_MAX)
        return self._read(i2c_addr, register, length, length)

    def write_i2c_block_data(self, i2c_addr: int, register: int, data, force=None) -> None:
        """Write up to 32 bytes from ``register`` on."""
        self._check(i2c_addr, register)
        data = _byte_list(data)
        if len(data) > SMBUS_BLOCK_MAX:
            raise ValueError(f"data must hold at most {SMBUS_BLOCK_MAX} bytes (an SMBus block), "
                             f"got {len(data)}")
        self._write(i2c_addr, register, data)

    def i2c_rdwr(self, *msgs) -> None:
        """Combined transfer: a one-byte register write followed by a read of any length."""
        if len(msgs) == 2 and not all(hasattr(m, name) for m in msgs
                                      for name in ("flags", "len", "addr", "buf")):
            raise TypeError("msgs must be i2c_msg objects (smbus2.i2c_msg.write and .read), got "
                            f"{', '.join(type(m).__name__ for m in msgs)}")
        if (len(msgs) != 2 or msgs[0].flags & _I2C_M_RD or not msgs[1].flags & _I2C_M_RD
                or msgs[0].len != 1):
            raise ValueError("the simulated bus supports i2c_rdwr(write [register], read n) only")
        register = bytes(msgs[0])[0]
        data = bytes(self._read(msgs[0].addr, register, msgs[1].len, msgs[1].len))
        for k, value in enumerate(data):
            msgs[1].buf[k] = bytes([value])
        msgs[1].len = len(data)  # a short read: the kernel reports the bytes it received

    def close(self) -> None:
        """Close the bus."""
        self.closed = True

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False
