"""The simulated I2C bus: the subset of :class:`smbus2.SMBus` the drivers use, in virtual time.

Each transfer advances the :class:`~ebantenna.device.clock.VirtualClock` by its duration on the
bus plus a fixed per-transfer overhead, and sleeping advances it instantly, so a ten-second search
takes a fraction of a second. Every transfer passes through one place, :meth:`SimulatedBus._begin`,
where the :class:`~ebantenna.device.simulated.faults.FaultInjector` may stall the host or fail it;
reads then go through :meth:`SimulatedBus._read` and writes through :meth:`SimulatedBus._write`.
"""

from __future__ import annotations

import errno

from ..._validate import check_int, check_nonnegative, check_positive
from ..clock import VirtualClock
from ..i2c import SMBUS_BLOCK_MAX
from .faults import FaultInjector, Faults

__all__ = ["SimulatedBus", "transfer_bits"]

#: Read/write flag of an I2C message (``I2C_M_RD`` in Linux's ``i2c.h``, as smbus2 sets it).
_I2C_M_RD = 0x0001


def transfer_bits(nbytes: int) -> int:
    """Bus clock cycles of a register transfer carrying ``nbytes`` data bytes.

    The address byte, the register byte and the data bytes each take nine clocks (eight bits and
    the acknowledge), plus about one clock each for the START and the STOP condition.

    Examples
    --------
    >>> from ebantenna.device.simulated.bus import transfer_bits
    >>> transfer_bits(1)
    29
    """
    return 9 * (check_int("nbytes", nbytes, minimum=0) + 2) + 2


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
        I2C clock, Hz. Default 400 kHz (fast mode, the paper's rate).
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
    >>> round(bus.clock.monotonic() * 1e6, 1)  # us: 50 us overhead + 29 clocks at 400 kHz
    122.5
    """

    def __init__(self, clock=None, *, devices: dict | None = None, faults: Faults | None = None,
                 seed: int = 0, bus_hz: float = 400e3, overhead: float = 50e-6):
        self.clock = VirtualClock() if clock is None else clock
        self.faults = Faults() if faults is None else faults
        self.bus_hz = check_positive("bus_hz", bus_hz)
        self.overhead = check_nonnegative("overhead", overhead)
        self.injector = FaultInjector(self.faults, seed)
        self.devices: dict[int, object] = dict(devices or {})
        self.writes: list[tuple[int, int, tuple[int, ...]]] = []
        self.transfers = 0
        self.closed = False

    @property
    def errors_injected(self) -> int:
        """Transfers failed on purpose."""
        return self.injector.errors_injected

    def _begin(self, address: int, nbytes: int):
        """Run a transfer's bus phase: time, faults, acknowledge. Returns the chip addressed."""
        if self.closed:
            raise OSError(errno.EBADF, "the simulated bus is closed")
        self.clock.advance(self.overhead + transfer_bits(nbytes) / self.bus_hz)
        self.clock.advance(self.injector.host_stall(self.clock.monotonic()))
        self.transfers += 1
        error = self.injector.transfer_error()
        if error is not None:
            raise error
        if address not in self.devices:
            raise OSError(errno.EREMOTEIO, "Remote I/O error")
        return self.devices[address]

    def _read(self, address: int, register: int, length: int, nbytes: int) -> list[int]:
        """One read transfer of ``length`` bytes from ``register`` on (``nbytes`` on the wire)."""
        return self._begin(address, nbytes).read(register, length)

    def _write(self, address: int, register: int, data: list[int]) -> None:
        """One write transfer of ``data`` from ``register`` on."""
        self._begin(address, len(data)).write(register, data)
        self.writes.append((address, register, tuple(data)))

    def read_byte_data(self, i2c_addr: int, register: int, force=None) -> int:
        """Read one register."""
        return self._read(i2c_addr, register, 1, 1)[0]

    def write_byte_data(self, i2c_addr: int, register: int, value: int, force=None) -> None:
        """Write one register."""
        self._write(i2c_addr, register, [value])

    def read_i2c_block_data(self, i2c_addr: int, register: int, length: int, force=None):
        """Read ``length`` (at most 32) bytes from ``register`` on."""
        if length > SMBUS_BLOCK_MAX:
            raise ValueError("Desired block length over 32 bytes")
        return self._read(i2c_addr, register, length, length)

    def write_i2c_block_data(self, i2c_addr: int, register: int, data, force=None) -> None:
        """Write up to 32 bytes from ``register`` on."""
        data = list(data)
        if len(data) > SMBUS_BLOCK_MAX:
            raise ValueError("Data length cannot exceed 32 bytes")
        self._write(i2c_addr, register, data)

    def i2c_rdwr(self, *msgs) -> None:
        """Combined transfer: a one-byte register write followed by a read of any length."""
        if (len(msgs) != 2 or msgs[0].flags & _I2C_M_RD or not msgs[1].flags & _I2C_M_RD
                or msgs[0].len != 1):
            raise ValueError("the simulated bus supports i2c_rdwr(write [register], read n) only")
        register = bytes(msgs[0])[0]
        data = bytes(self._read(msgs[0].addr, register, msgs[1].len, msgs[1].len + 1))
        for k, value in enumerate(data):
            msgs[1].buf[k] = bytes([value])

    def close(self) -> None:
        """Close the bus."""
        self.closed = True

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False
