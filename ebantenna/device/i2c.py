"""Register access to one I2C chip, with bounded retries of transient bus errors.

Both drivers talk to their chip through an :class:`I2CDevice`, which wraps any object with the
subset of the :class:`smbus2.SMBus` API used here (``read_byte_data``, ``write_byte_data``,
``read_i2c_block_data``, ``write_i2c_block_data`` and ``i2c_rdwr``): the real bus on a Raspberry Pi,
or :class:`ebantenna.device.simulated.SimulatedBus` anywhere else.

A noisy I2C line makes the kernel report ``OSError`` with errno 121 (``EREMOTEIO``, "Remote I/O
error": the chip did not acknowledge), 5 (``EIO``), 110 (``ETIMEDOUT``) or 11 (``EAGAIN``, bus
arbitration lost). These are retried with an exponential back-off that is bounded both in the number
of attempts and in the longest wait; when the attempts are used up an :class:`I2CError` names the
chip, the register, the operation and the last error. Every retry is counted in
:attr:`I2CDevice.retries` and logged, so that nothing is lost silently. A system call interrupted
by a signal (``EINTR``) is retried the same way. A wrong address is a missing acknowledge too, so it
is retried until the attempts are used up (the error then says to check the address). Other errors
(a missing bus, a permission problem) are not retried.

Giving up is bounded in *time*, not in attempts times retries: a transfer that hangs until the
adapter's timeout (about a second on a stuck bus) is not tried again once
the policy's ``deadline`` (:class:`RetryPolicy`) has passed since its first attempt, and a bus on
which nothing has succeeded for its ``dead_after`` seconds is declared dead: every later call on it
raises :class:`BusDeadError` at once, without touching the bus, for every chip on that bus.

A retry is only safe when the transfer has no side effect on the chip. Reading a FIFO data port or
a clear-on-read status register is not such a transfer: the error may come after the chip has
shifted its bytes out (the kernel reports the failure at the STOP or on a late timeout), and a
second read then returns the *next* bytes. Those reads are made with ``retry=False``: retried only
after a missing acknowledge (:data:`NOTHING_READ_ERRNOS`), which proves that nothing was read, and
any other failure, a short read included, raises :class:`I2CError` at once for the caller to
resynchronise. A read that returns fewer bytes than asked (:class:`ShortReadError`) is a failure
like any other.
"""

from __future__ import annotations

import errno
import logging
import weakref
from dataclasses import dataclass

import numpy as np

from .._validate import check_int, check_nonnegative, check_positive
from .clock import SystemClock

__all__ = [
    "RetryPolicy",
    "I2CError",
    "SettingError",
    "BusDeadError",
    "transfer_bits",
    "transfer_time",
    "RASPBERRY_PI_BUS_HZ",
    "MAX_BUS_HZ",
    "MAX_TRANSFER_TIMEOUT",
    "TRANSFER_OVERHEAD",
    "ShortReadError",
    "I2CDevice",
    "TRANSIENT_ERRNOS",
    "NOTHING_READ_ERRNOS",
    "SMBUS_BLOCK_MAX",
]

logger = logging.getLogger(__name__)

#: errno values treated as transient bus noise (retried), and ``EINTR``: the call was interrupted
#: by a signal and may simply be made again.
TRANSIENT_ERRNOS = frozenset(
    {errno.EREMOTEIO, errno.EIO, errno.ETIMEDOUT, errno.EAGAIN, errno.EINTR}
)
#: errno values that prove a *read* delivered nothing, so that even a FIFO read may be retried:
#: ``EREMOTEIO``, a missing acknowledge. In a read only the chip's address and register bytes are
#: acknowledged by the chip; the data bytes are acknowledged by the master (I2C-bus
#: specification, NXP UM10204 rev. 7, section 3.1.6), so a NACK comes before any data left the
#: chip. Assumption: the adapter reports a NACK as ``EREMOTEIO`` and nothing else as it
#: (Linux's ``i2c-bcm2835`` of the Raspberry Pi does; see its ``BCM2835_I2C_S_ERR`` handling).
NOTHING_READ_ERRNOS = frozenset({errno.EREMOTEIO})

#: I2C clock of a Raspberry Pi's bus unless ``dtparam=i2c_arm_baudrate`` says otherwise, Hz
#: (Raspberry Pi documentation, "config.txt", ``i2c_arm_baudrate``: default 100000).
RASPBERRY_PI_BUS_HZ = 100e3

#: The fastest I2C clock, Hz: the High-speed mode's 3.4 Mbit/s (NXP UM10204, "I2C-bus
#: specification and user manual", rev. 7.0, section 1). A simulated bus refuses a faster one.
MAX_BUS_HZ = 3.4e6

#: The longest adapter timeout a simulated transfer may hang for, s. Linux gives an adapter that
#: sets none one second (``adap->timeout = HZ`` in ``i2c_register_adapter``,
#: drivers/i2c/i2c-core-base.c); ten times that bounds what any adapter is set to here.
MAX_TRANSFER_TIMEOUT = 10.0
#: Fixed cost of one transfer besides its bits on the wire (the system call and the adapter's
#: set-up), s: an assumed 50 us, of the order of a Linux ``ioctl`` on a Raspberry Pi.
TRANSFER_OVERHEAD = 50e-6

#: The SMBus protocol carries at most 32 data bytes per block transfer.
SMBUS_BLOCK_MAX = 32

#: 7-bit addresses accepted: 0x03-0x77, the range Linux's ``i2cdetect`` probes by default. The
#: I2C-bus specification (NXP UM10204, section 3.1.12) reserves 0x00-0x07 and 0x78-0x7F.
_FIRST_ADDRESS, _LAST_ADDRESS = 0x03, 0x77


class I2CError(OSError):
    """A bus transfer that still failed after every permitted retry."""


class SettingError(I2CError):
    """A register does not read back the value written to it (a bit flipped on the wire, a
    write the chip did not take, a second device at the address answering too)."""


class BusDeadError(I2CError):
    """Nothing on the bus has succeeded for the :class:`RetryPolicy`'s ``dead_after`` seconds: no
    more transfers are attempted on it (errno ``ETIMEDOUT``)."""


def transfer_bits(nbytes: int, *, read: bool = False) -> int:
    """Bus clock cycles of a register transfer carrying ``nbytes`` data bytes.

    Every byte takes nine clocks (eight bits and the acknowledge), and each START, repeated
    START and STOP condition about one more. A register write is ``S, address+W, register,
    data..., P``: ``9 (nbytes + 2) + 2``. A register read (``read=True``: SMBus
    ``read_byte_data``, a block read, or an ``i2c_rdwr`` of a register write and a read) first
    writes the register and then sends the address again to read, ``S, address+W, register, Sr,
    address+R, data..., P``: ``9 (nbytes + 3) + 3``.

    Examples
    --------
    >>> from ebantenna.device.i2c import transfer_bits
    >>> transfer_bits(1), transfer_bits(1, read=True)
    (29, 39)
    """
    nbytes = check_int("nbytes", nbytes, minimum=0)
    if read:
        return 9 * (nbytes + 3) + 3
    return 9 * (nbytes + 2) + 2


def transfer_time(nbytes: int, bus_hz: float = RASPBERRY_PI_BUS_HZ,
                  overhead: float = TRANSFER_OVERHEAD, *, read: bool = False) -> float:
    """Time one register transfer of ``nbytes`` data bytes takes at ``bus_hz`` (Hz), s (a read
    with ``read=True``, see :func:`transfer_bits`).

    Examples
    --------
    >>> from ebantenna.device.i2c import transfer_time
    >>> round(transfer_time(30, read=True) * 1e3, 2)  # ms: five FIFO samples read at 100 kHz
    3.05
    """
    overhead = check_nonnegative("overhead", overhead)
    return overhead + transfer_bits(nbytes, read=read) / check_positive("bus_hz", bus_hz)


class ShortReadError(OSError):
    """A read transfer returned fewer bytes than it asked for (errno ``EIO``)."""

    def __init__(self, asked: int, got: int):
        super().__init__(errno.EIO, f"short read: {got} of {asked} bytes")
        self.asked, self.got = asked, got


@dataclass(frozen=True)
class RetryPolicy:
    """How often, and after which waits, a transient I2C error is retried.

    The wait before retry ``k`` (``k = 1, 2, ...``) is ``min(initial_delay * factor**(k-1),
    max_delay)``, so the total time spent waiting is bounded by ``(attempts - 1) * max_delay``.

    Parameters
    ----------
    attempts : int
        Total number of tries of one transfer, >= 1. Default 5.
    initial_delay : float
        Wait before the first retry, s. Default 0.5 ms.
    factor : float
        Growth of the wait from one retry to the next, >= 1. Default 2.
    max_delay : float
        Longest single wait, s. Default 20 ms.
    deadline : float
        No new attempt of one transfer starts later than this after its first attempt began, s.
        Default 1 s: the retries of a noisy bus take milliseconds, while one attempt on a stuck
        bus can take the adapter's whole timeout (about 1 s), so ``attempts`` alone would
        multiply that timeout.
    dead_after : float
        A bus on which no transfer has succeeded for this long is dead, s (see the module notes).
        Default 2 s: far longer than any transient fault, short enough that a run on a dead bus
        gives up within a few seconds.

    Examples
    --------
    >>> from ebantenna.device.i2c import RetryPolicy
    >>> RetryPolicy(attempts=4, initial_delay=0.001, factor=3.0, max_delay=0.005).delays()
    (0.001, 0.003, 0.005)
    """

    attempts: int = 5
    initial_delay: float = 5e-4
    factor: float = 2.0
    max_delay: float = 0.02
    deadline: float = 1.0
    dead_after: float = 2.0

    def __post_init__(self):
        check_int("attempts", self.attempts, minimum=1, maximum=MAX_ATTEMPTS)
        check_nonnegative("initial_delay", self.initial_delay)
        check_positive("factor", self.factor)
        if self.factor < 1:
            raise ValueError(f"factor must be >= 1, got {self.factor!r}")
        check_nonnegative("max_delay", self.max_delay)
        check_positive("deadline", self.deadline)
        check_positive("dead_after", self.dead_after)

    def delays(self) -> tuple[float, ...]:
        """The waits before each retry, s (``attempts - 1`` of them)."""
        return tuple(
            min(self.initial_delay * self.factor**k, self.max_delay)
            for k in range(self.attempts - 1)
        )


#: The most attempts a :class:`RetryPolicy` makes: a transient error clears within a few
#: milliseconds, and a bus failing a hundred times in a row is broken, not busy.
MAX_ATTEMPTS = 100


def _check_byte(name: str, value) -> int:
    return check_int(name, value, minimum=0, maximum=255)


class BusHealth:
    """When a bus last answered, shared by every :class:`I2CDevice` on it.

    Attributes
    ----------
    failing_since : float or None
        Host time at which the first of the transfers failing since the last success began, s;
        None while the bus answers.
    """

    def __init__(self):
        self.failing_since = None

    def failed(self, began: float) -> None:
        """A transfer that began at host time ``began`` (s) failed."""
        if self.failing_since is None:
            self.failing_since = began

    def succeeded(self) -> None:
        """A transfer succeeded: the bus answers."""
        self.failing_since = None

    def revive(self) -> None:
        """Let the next transfer try the bus though it was declared dead (``dead_after``): for
        a transfer worth its timeout, the release of the servos retried while the ``OE`` pin
        holds their outputs off. A failure declares it failing again from that transfer on."""
        self.failing_since = None

    def failing_for(self, now: float) -> float:
        """How long nothing has succeeded on the bus at host time ``now``, s (0 if it answers)."""
        return 0.0 if self.failing_since is None else now - self.failing_since


#: The health of each open bus object, shared by the devices on it.
_HEALTH: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def bus_health(bus) -> BusHealth:
    """The :class:`BusHealth` of ``bus`` (one per bus object; a new one for a bus that cannot be
    weakly referenced)."""
    try:
        return _HEALTH.setdefault(bus, BusHealth())
    except TypeError:  # not weakly referenceable: health per device
        return BusHealth()


#: What every bus offers (the reads and writes of single registers, which every chip here uses).
_BUS_METHODS = ("read_byte_data", "write_byte_data")


class I2CDevice:
    """One chip at one address on a bus, with retried register reads and writes.

    Parameters
    ----------
    bus : smbus2.SMBus or compatible
        The open bus.
    address : int
        7-bit I2C address of the chip, 0x03-0x77.
    retry : RetryPolicy, optional
        Retry policy for transient errors. Default :class:`RetryPolicy()`.
    clock : SystemClock or VirtualClock, optional
        Supplies ``sleep`` for the back-off. Default :class:`~ebantenna.device.clock.SystemClock`.
    use_rdwr : bool
        Read long blocks in one combined ``i2c_rdwr`` transfer instead of 32-byte SMBus blocks.

    Examples
    --------
    >>> from ebantenna.device.simulated import SimulatedRig
    >>> from ebantenna.device.i2c import I2CDevice
    >>> rig = SimulatedRig.quiet()
    >>> I2CDevice(rig.bus, 0x68, clock=rig.clock).read_byte(0x75) == 0x68  # MPU-6050 WHO_AM_I
    True
    """

    def __init__(self, bus, address: int, *, retry: RetryPolicy | None = None, clock=None,
                 use_rdwr: bool = False):
        missing = [m for m in _BUS_METHODS if not callable(getattr(bus, m, None))]
        if missing:
            raise TypeError(
                f"bus must be an open I2C bus (smbus2.SMBus or SimulatedBus), got "
                f"{type(bus).__name__} without {', '.join(missing)}"
            )
        self.bus = bus
        self.address = check_int("address", address, minimum=_FIRST_ADDRESS,
                                 maximum=_LAST_ADDRESS)
        self.retry = RetryPolicy() if retry is None else retry
        if not isinstance(self.retry, RetryPolicy):
            raise TypeError(f"retry must be a RetryPolicy, got {type(retry).__name__}")
        self.clock = SystemClock() if clock is None else clock
        self.use_rdwr = bool(use_rdwr)
        #: Number of transient errors that were retried.
        self.retries = 0
        #: When the bus last answered (shared with the other devices on ``bus``).
        self.health = bus_health(bus)

    def _check_alive(self, what: str, register: int) -> None:
        failing = self.health.failing_for(self.clock.monotonic())
        if failing > self.retry.dead_after:
            raise BusDeadError(
                errno.ETIMEDOUT,
                f"I2C {what} of register 0x{register:02X} at address 0x{self.address:02X} not "
                f"attempted: nothing on the bus has succeeded for {failing:.3f} s (more than "
                f"{self.retry.dead_after:g} s); the bus is dead")

    def _attempt(self, call):
        """One attempt of ``call``, noting in :attr:`health` whether the bus answered."""
        began = self.clock.monotonic()
        try:
            result = call()
        except OSError:
            self.health.failed(began)
            raise
        self.health.succeeded()
        return result

    def _transfer(self, what: str, register: int, call, *, retryable=TRANSIENT_ERRNOS):
        self._check_alive(what, register)
        delays = None  # the retry waits, worked out at the first transient error only
        first = self.clock.monotonic()
        attempt = 0
        while True:
            try:
                return self._attempt(call)
            except OSError as exc:
                if exc.errno not in TRANSIENT_ERRNOS:
                    raise
                delays = self.retry.delays() if delays is None else delays
                late = self.clock.monotonic() - first + (
                    delays[attempt] if attempt < len(delays) else 0.0) > self.retry.deadline
                if attempt == len(delays) or exc.errno not in retryable or late:
                    hint = (" (no acknowledge: check the wiring, the power and the address)"
                            if exc.errno == errno.EREMOTEIO else "")
                    raise I2CError(
                        exc.errno,
                        f"I2C {what} of register 0x{register:02X} at address 0x{self.address:02X} "
                        f"failed after {attempt + 1} attempt{'s' if attempt else ''}: "
                        f"{exc.strerror or exc}{hint}",
                    ) from exc
                self.retries += 1
                logger.info(
                    "I2C %s of register 0x%02X at 0x%02X: %s; retry %d of %d in %.1f ms",
                    what, register, self.address, exc, attempt + 1, len(delays),
                    1e3 * delays[attempt],
                )
                self.clock.sleep(delays[attempt])
                attempt += 1

    def read_byte(self, register: int, *, retry: bool = True) -> int:
        """Read one register; ``retry=False`` for a clear-on-read register (retried only when
        the chip provably sent nothing, see :data:`NOTHING_READ_ERRNOS`)."""
        register = _check_byte("register", register)
        return self._transfer(
            "read", register,
            lambda: _bus_byte(self.bus, self.bus.read_byte_data(self.address, register)),
            retryable=TRANSIENT_ERRNOS if retry else NOTHING_READ_ERRNOS)

    def write_byte(self, register: int, value: int, *, retry: bool = True) -> None:
        """Write one register; ``retry=False`` when the caller must know the single write that
        landed (one attempt)."""
        register = _check_byte("register", register)
        value = _check_byte("value", value)
        self._transfer(
            "write", register, lambda: self.bus.write_byte_data(self.address, register, value),
            retryable=TRANSIENT_ERRNOS if retry else frozenset())

    def write_read_back(self, register: int, value: int, mask: int, describe) -> int | None:
        """Write a setting and read it back, bits ``mask``; once more if it reads back wrong.

        Returns None when the setting landed, else the value the second read-back saw (the
        caller raises its :class:`SettingError`, naming the chip). ``describe()`` names the
        register in the warning logged after a wrong read-back (called only then, once the
        register is known to be a byte).
        """
        mask = _check_byte("mask", mask)
        if not callable(describe):
            raise TypeError(f"describe must be callable, got {type(describe).__name__}")
        for attempt in range(2):
            self.write_byte(register, value)
            seen = self.read_byte(register)
            if seen & mask == value & mask:
                return None
            logger.warning("%s reads back 0x%02X after 0x%02X was written%s", describe(), seen,
                           value, "; writing it again" if attempt == 0 else "")
        return seen

    def write_block(self, register: int, data) -> None:
        """Write up to 32 bytes to consecutive registers in one transfer (one I2C STOP)."""
        register = _check_byte("register", register)
        data = [_check_byte("data", b) for b in data]
        if not 1 <= len(data) <= SMBUS_BLOCK_MAX:
            raise ValueError(f"data must hold 1 to {SMBUS_BLOCK_MAX} bytes, got {len(data)}")
        self._transfer(
            "block write", register,
            lambda: self.bus.write_i2c_block_data(self.address, register, data))

    def read_block(self, register: int, length: int, *, increment: bool = True,
                   chunk: int = SMBUS_BLOCK_MAX, retry: bool = True) -> bytes:
        """Read ``length`` bytes starting at ``register``, in one burst or a few.

        Reading several registers in one burst is what keeps a multi-byte sample whole: the chip
        latches all of them for the duration of the transfer, whereas separate one-byte reads can
        mix the high byte of one sample with the low byte of the next.

        Parameters
        ----------
        register : int
            First register.
        length : int
            Number of bytes, >= 1.
        increment : bool
            True for ordinary registers, whose address auto-increments (a read longer than
            ``chunk`` continues at ``register + offset``); False for a FIFO data port, which
            delivers successive bytes at one address.
        chunk : int
            Longest SMBus block transfer, 1-32 bytes. A FIFO of 6-byte samples is best drained in
            30-byte chunks so that a transfer never splits a sample.
        retry : bool
            Retry transient errors (default). False for a read with a side effect, such as a FIFO
            data port: retried only when the error proves the chip sent nothing
            (:data:`NOTHING_READ_ERRNOS`); any other failure, a short transfer included, raises
            :class:`I2CError` at once.

        With ``use_rdwr`` the whole read is one combined ``i2c_rdwr`` transfer of any length.
        """
        register = _check_byte("register", register)
        length = check_int("length", length, minimum=1)
        retryable = TRANSIENT_ERRNOS if retry else NOTHING_READ_ERRNOS
        chunk = check_int("chunk", chunk, minimum=1, maximum=SMBUS_BLOCK_MAX)
        if increment and register + length > 256:
            raise ValueError(f"register 0x{register:02X} + length {length} runs past 0xFF")
        if self.use_rdwr:
            from smbus2 import i2c_msg

            def call():
                write = i2c_msg.write(self.address, [register])
                read = i2c_msg.read(self.address, length)
                self.bus.i2c_rdwr(write, read)
                return _whole(bytes(read)[: read.len], length)

            return self._transfer("combined read", register, call, retryable=retryable)
        out = bytearray()
        while len(out) < length:
            n = min(chunk, length - len(out))
            start = register + len(out) if increment else register
            out += self._transfer(
                "block read", start,
                lambda n=n, start=start: _whole(_bus_bytes(
                    self.bus, self.bus.read_i2c_block_data(self.address, start, n)), n),
                retryable=retryable)
        return bytes(out)


def _bus_byte(bus, value) -> int:
    """``value``, returned by ``bus.read_byte_data``, if it is a byte (an int in 0-255)."""
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or not 0 <= value <= 255:
        raise TypeError(f"bus: {type(bus).__name__}.read_byte_data returned {value!r:.40} "
                        f"({type(value).__name__}), not a byte (an int in 0-255)")
    return int(value)


def _bus_bytes(bus, values) -> bytes:
    """``values``, returned by ``bus.read_i2c_block_data``, if they are bytes (ints in 0-255)."""
    if isinstance(values, bytes | bytearray):
        return bytes(values)
    if type(values) is list and set(map(type, values)) <= {int} and (  # smbus2's: checked in C
            0 <= min(values, default=0) and max(values, default=0) <= 255):
        return bytes(values)
    if isinstance(values, list | tuple) and all(
            not isinstance(v, bool) and isinstance(v, int | np.integer) and 0 <= v <= 255
            for v in values):
        return bytes(int(v) for v in values)
    raise TypeError(f"bus: {type(bus).__name__}.read_i2c_block_data returned {values!r:.40} "
                    f"({type(values).__name__}), not a list of bytes (ints in 0-255)")


def _whole(data: bytes, asked: int) -> bytes:
    """``data`` if it holds the ``asked`` bytes, else :class:`ShortReadError`."""
    if len(data) != asked:
        raise ShortReadError(asked, len(data))
    return data
