"""What can go wrong on the simulated bus: the faults asked for, and the seeded injector that
decides, transfer by transfer, which of them happen.

The kinds of failed transfer are those a Linux I2C adapter reports (``i2c-dev`` returns the
adapter's errno from the ``ioctl``):

``"nack"``
    The chip does not acknowledge its address: ``EREMOTEIO`` (121) before anything happens.
``"eio"``, ``"etimedout"``, ``"eagain"``
    An early bus error (``EIO``), a timeout (``ETIMEDOUT``) or lost arbitration (``EAGAIN``)
    before the data phase: the chip is untouched.
``"late"``
    The data phase completes (a read has shifted the bytes out of the chip, a write has reached
    its registers) and the transfer still fails, with ``EIO`` or ``ETIMEDOUT``: the dangerous
    one, since retrying a FIFO read then returns the *next* bytes.
``"short"``
    A read returns fewer bytes than asked; the chip has shifted out only those. (A write drawn
    "short" fails early, like ``"nack"``.)
``"eintr"``
    The system call is interrupted by a signal (``EINTR``) before the transfer starts.
``"overcount"``
    A read of ``FIFO_COUNTH``/``L`` returns more than the chip can have produced since its FIFO
    was last enabled, even at the fastest clock ``MAX_CLOCK_DRIFT`` allows, by a whole
    number of samples (a bit error that the whole-sample check cannot see). Other transfers
    drawn ``"overcount"`` go through untouched.

Besides those, a :class:`Faults` can reset the accelerometer once (a brown-out: power-on
registers, asleep), hold the whole bus stuck for a while (every transfer times out), stall the
host once, make the host slow at moments (``"slow host"``: before a drawn share of transfers
it loses the processor for a random time, as a loaded or throttled host does), run the
accelerometer's sample clock off its nominal rate, let its sample-rate divider run free (the
first sample of a FIFO segment then comes anywhere within a period of the enable, not one
period after it), make it repeat its last byte when the FIFO is read past its end (as the real
part does), make every transfer that times out hang for a stated time first (the adapter's
timeout), and make every write that releases the servos fail (for good, or until a given
time).

The faults below happen with no error on the bus at all; a driver can only notice them from
what it reads (the kinds of :data:`SILENT_FAULTS`, by the name each logs):

``"write bit flip"``
    A write to a register arrives with bits flipped (``flip_write``): the chip takes a setting
    nobody asked for (another range, a self-test bit).
``"register lost"``
    A register of the accelerometer changes on its own at a given time (``register_lost``):
    a partial reset, a glitch, another program writing it.
``"foreign read"``
    Another program reads the accelerometer at a given time (``foreign_reads``): ``i2cget -y 1
    0x68 0x74`` takes one byte of the FIFO, a second driver a whole sample or several at once
    (any number of bytes, a partial sample included), ``i2cdump`` every register once (the
    FIFO's byte and the clear-on-read ``INT_STATUS`` included). With ``drain_reads`` the other
    program takes its bytes in the middle of a drain: after the drain's count was read, just
    before its data are.
``"undercount"``
    A FIFO count reads one sample low, once, at the first count read after each given time.
``"bit error"``
    Bytes read from the FIFO data port arrive with bits flipped at ``bit_error_rate`` per bit,
    with no error reported: I2C carries no checksum.
``"clone"``
    The accelerometer answers ``WHO_AM_I`` 0x68 but samples like a part of the MPU-6500 family
    (``clone_6500``): its divider is ignored with ``DLPF_CFG = 0`` and its FIFO holds 512 bytes.
``"stuck sensor"``
    From a given time the sensor's output stops changing (``stuck_sensor_at``): the FIFO goes on
    filling with the same sample.
``"second device"``
    A second MPU-6050 answers at the accelerometer's address (``second_device``: its AD0 pin
    set like the first's). Both acknowledge, both take every write and both answer every read;
    the open-drain bus delivers the bitwise AND of their bytes. The settings read back as
    written and the FIFO counts agree while the two clocks do; the samples are the AND of two
    streams measuring the same acceleration with noise of their own.
``"pca brown-out"``
    The PCA9685 loses power for a moment (``pca_brown_out_at``): asleep at 200 Hz, every
    output off, its later writes still acknowledged. (``pca_flip_write`` flips bits of its
    writes, logged as ``"write bit flip"``.)
``"reset lost"``
    A self-clearing reset bit written to the accelerometer does not act (``reset_lost``): the
    write lands without it, so a ``USER_CTRL.FIFO_RESET`` leaves the FIFO's bytes where they
    were and a ``PWR_MGMT_1.DEVICE_RESET`` leaves every register as it was. The bit reads back
    0 either way (it clears itself when the reset is done, RM 106 and 107).

A sample clock off by more than ``MAX_CLOCK_DRIFT`` (up to ``MAX_FAULT_DRIFT``, 90 %) is also
allowed, as a fault: outside the tolerance the driver assumes (and beyond 50 %, outside what it
adapts to).
"""

from __future__ import annotations

import errno
import math
from dataclasses import dataclass

import numpy as np

from ..._validate import check_in_range, check_int, check_nonnegative, check_real
from ...chips.mpu6050 import (
    ACCEL_SAMPLE_BYTES,
    WHO_AM_I_VALUE,
    PowerManagement1,
    Register,
    UserControl,
)
from ..i2c import MAX_TRANSFER_TIMEOUT
from .mpu6050 import MAX_CLOCK_DRIFT, REGISTER_SPACE

__all__ = ["Faults", "FaultInjector", "TRANSFER_FAULTS", "SILENT_FAULTS", "MAX_CLOCK_DRIFT",
           "MAX_OVERCOUNT", "MAX_FAULT_DRIFT", "MAX_PREEMPTION", "MAX_READ_BYTES", "RESET_BITS"]

#: Kinds of failed transfer the injector can draw (see the module notes).
TRANSFER_FAULTS = ("nack", "eio", "etimedout", "eagain", "late", "short", "eintr", "overcount")

_EARLY_ERRNO = {"nack": errno.EREMOTEIO, "eio": errno.EIO, "etimedout": errno.ETIMEDOUT,
                "eagain": errno.EAGAIN, "eintr": errno.EINTR}
#: Largest over-report of a FIFO count, samples: up to a whole FIFO's worth.
MAX_OVERCOUNT = 170
#: The last register of the accelerometer that ``i2cdump`` reads: the last the simulated chip
#: models (its map ends at WHO_AM_I, RM section 3).
_LAST_REGISTER = REGISTER_SPACE - 1

#: Faults that no bus error reveals (see the module notes), by the name each logs.
SILENT_FAULTS = ("write bit flip", "register lost", "foreign read", "undercount", "bit error",
                 "clone", "stuck sensor", "second device", "pca brown-out", "reset lost")
#: The self-clearing reset bits a ``reset_lost`` entry can make fail, by name: the register
#: and the bit (RM 106 and 107).
RESET_BITS = {"fifo": (Register.USER_CTRL, UserControl.FIFO_RESET),
              "device": (Register.PWR_MGMT_1, PowerManagement1.DEVICE_RESET)}
#: Largest sample-clock error the faults allow, relative (beyond MAX_CLOCK_DRIFT: a fault;
#: beyond the driver's MAX_CLOCK_ADAPT of 50 %: a part not sampling as configured).
MAX_FAULT_DRIFT = 0.9
#: Most bytes one read of another program can take: the length of a Linux ``struct i2c_msg`` is
#: 16 bits (``include/uapi/linux/i2c.h``).
MAX_READ_BYTES = (1 << 16) - 1
#: Longest time a slow host (``Faults.slow_host``) loses the processor at one moment, s.
MAX_PREEMPTION = 10.0


def _time(now) -> float:
    """A virtual time ``now`` (s), checked: a float is taken at once (the bus asks five times a
    transfer), anything else goes through the full check."""
    if type(now) is float and 0.0 <= now < math.inf:
        return now
    return check_nonnegative("now", now)


def _what(what):
    """A ``foreign_reads`` entry's ``what``, checked: ``"byte"``, ``"sample"``, ``"dump"`` or a
    number of FIFO bytes (an int >= 1)."""
    if what in ("byte", "sample", "dump") and isinstance(what, str):
        return what
    if isinstance(what, int) and not isinstance(what, bool):
        return check_int("foreign_reads n", what, minimum=1, maximum=MAX_READ_BYTES)
    raise ValueError(f"foreign_reads must read a 'byte', a 'sample', a 'dump' or a number of "
                     f"bytes >= 1, got {what!r}")


def _slow_host(value) -> tuple:
    """``Faults.slow_host`` checked: ``()`` or ``(share, longest)``, share in [0, 1), longest in
    [0, :data:`MAX_PREEMPTION`] s."""
    if value == ():
        return ()
    if not isinstance(value, tuple | list) or len(value) != 2:
        raise TypeError(f"slow_host must be a pair (share, longest) or (), got {value!r}")
    share = check_in_range("slow_host share", value[0], 0.0, 1.0, low_inclusive=True)
    longest = check_in_range("slow_host longest", value[1], 0.0, MAX_PREEMPTION,
                             low_inclusive=True, high_inclusive=True,
                             reason="a longer loss of the processor is a stall (stall_at)")
    return share, longest


def _reset_lost(value) -> tuple:
    """``Faults.reset_lost`` checked: ``((time, which), ...)``, sorted by time, ``which`` a key
    of :data:`RESET_BITS`."""
    if isinstance(value, str) or not isinstance(value, tuple | list):
        raise TypeError(f"reset_lost must be a tuple of (time, which) pairs, got {value!r}")
    out = []
    for entry in value:
        if not isinstance(entry, tuple | list) or len(entry) != 2:
            raise TypeError(f"reset_lost must be a tuple of (time, which) pairs, got {entry!r}")
        time, which = entry
        if not isinstance(which, str) or which not in RESET_BITS:
            raise ValueError(f"reset_lost which must be one of {sorted(RESET_BITS)}, got "
                             f"{which!r}")
        out.append((check_nonnegative("reset_lost time", time), which))
    return tuple(sorted(out, key=lambda entry: entry[0]))


def _error(code: int) -> OSError:
    import os

    return OSError(code, os.strerror(code))


@dataclass(frozen=True)
class Faults:
    """Faults to inject into the simulated bus.

    Parameters
    ----------
    error_rate : float
        Probability that a transfer fails, in [0, 1). Which way it fails is drawn uniformly from
        ``kinds``.
    kinds : tuple of str
        Kinds of failed transfer, from :data:`TRANSFER_FAULTS`. Default ``("nack",)``: the
        chip does not acknowledge and nothing happens.
    who_am_i : int
        What the MPU-6050's ``WHO_AM_I`` reads; 0x68 for a genuine chip.
    stall_at : float or None
        Virtual time (s) after which the host stalls once, for ``stall_duration``.
    stall_duration : float
        Length of that stall, s.
    chip_reset_at : float or None
        Virtual time (s) at which the accelerometer browns out once: its registers return to
        their power-on values (asleep, FIFO off and empty).
    stuck_at : float or None
        Virtual time (s) from which the bus is stuck for ``stuck_duration``: every transfer fails
        with ``ETIMEDOUT``.
    stuck_duration : float
        How long the bus stays stuck, s.
    clock_drift : float
        Relative error of the accelerometer's sample clock: it samples at ``fs * (1 +
        clock_drift)``. Within ``MAX_CLOCK_DRIFT`` the driver's tolerance holds; up to
        ``MAX_FAULT_DRIFT`` in magnitude it is a fault the driver must notice.
    free_running_divider : bool
        The accelerometer's sample-rate divider runs free instead of restarting when the FIFO is
        enabled: a segment's first sample comes at the next tick of its own grid, anywhere in
        the period after the enable.
    repeat_last_byte : bool
        Reading the FIFO past its end repeats the last byte read (the real part) instead of
        returning 0xFF.
    transfer_timeout : float
        How long a transfer that fails with ``ETIMEDOUT`` (drawn, late, or on a stuck bus) hangs
        before it fails, s. Default 0; about 1 s on a real adapter.
    release_fails : bool
        Once the PCA9685 is awake (initialised), every write that switches its outputs off
        (``ALL_LED_OFF_H``, an ``LEDn_OFF_H`` with the full-OFF bit) fails with ``EIO``, before
        it reaches the chip.
    release_fails_until : float or None
        As ``release_fails``, but only until this virtual time, s: a release that fails for a
        while (a bus held by a stuck slave, a controller browning out) and then lands.
    flip_write : tuple of (int, int, int)
        ``(register, mask, n)``: the first ``n`` writes of that accelerometer register arrive
        with ``mask`` XOR-ed in ("write bit flip").
    register_lost : tuple of (float, int, int)
        ``(time, register, value)``: at that virtual time the accelerometer's register takes
        ``value`` by itself ("register lost").
    foreign_reads : tuple of (float, str)
        ``(time, what)``: at that virtual time another program reads the accelerometer, ``what``
        being ``"byte"`` (one FIFO byte, ``i2cget``), ``"sample"`` (six FIFO bytes), an int
        ``n`` >= 1 (``n`` FIFO bytes at once: ``6 k`` for ``k`` whole samples, any other number
        a partial one) or ``"dump"`` (every register once, ``i2cdump``) ("foreign read").
    drain_reads : tuple of (float, int)
        ``(time, n)``: the first read of the FIFO data port after that virtual time is preceded
        by another program's read of ``n`` >= 1 FIFO bytes, between the drain's count and its
        data ("foreign read").
    undercount_at : tuple of float
        The first FIFO count read after each of these virtual times reads one sample low.
    bit_error_rate : float
        Probability that a bit read from the FIFO data port arrives flipped, in [0, 0.5].
    clone_6500 : bool
        The accelerometer samples like the MPU-6500 family while answering WHO_AM_I 0x68.
    stuck_sensor_at : float or None
        Virtual time from which the sensor's output stops changing.
    second_device : bool
        A second MPU-6050 shares the accelerometer's address ("second device"): it takes the
        same writes, measures the same acceleration with its own noise, and every read returns
        the AND of the two chips' bytes.
    pca_brown_out_at : float or None
        Virtual time at which the PCA9685 browns out once: power-on registers (asleep, every
        output off, 200 Hz), its later writes still acknowledged ("pca brown-out").
    pca_flip_write : tuple of (int, int, int)
        ``(register, mask, n)`` as ``flip_write``, for the PCA9685 (e.g. a ``PRE_SCALE`` that
        does not land as written).
    slow_host : tuple of (float, float)
        ``(share, longest)``: before each transfer, with probability ``share`` (in [0, 1)), the
        host loses the processor for a time drawn uniformly in ``[0, longest]`` s (``longest``
        at most :data:`MAX_PREEMPTION`), from a generator of its own ("slow host"): a host
        loaded by other programs or throttled, slow at moments, between the count and the data
        of a drain as well as between drains. Empty (the default): never.
    reset_lost : tuple of (float, str)
        ``(time, which)``: the first write after that virtual time that sets the reset bit
        ``which`` names (a key of :data:`RESET_BITS`: ``"fifo"``, ``USER_CTRL.FIFO_RESET``;
        ``"device"``, ``PWR_MGMT_1.DEVICE_RESET``) lands without it: the reset does not act
        ("reset lost"). Each entry acts once.

    Examples
    --------
    >>> from ebantenna.device.simulated import Faults
    >>> Faults(error_rate=0.05, kinds=("late", "short")).kinds
    ('late', 'short')
    """

    error_rate: float = 0.0
    kinds: tuple = ("nack",)
    who_am_i: int = WHO_AM_I_VALUE
    stall_at: float | None = None
    stall_duration: float = 0.0
    chip_reset_at: float | None = None
    stuck_at: float | None = None
    stuck_duration: float = 0.0
    clock_drift: float = 0.0
    free_running_divider: bool = False
    repeat_last_byte: bool = False
    transfer_timeout: float = 0.0
    release_fails: bool = False
    release_fails_until: float | None = None
    flip_write: tuple = ()
    register_lost: tuple = ()
    foreign_reads: tuple = ()
    drain_reads: tuple = ()
    undercount_at: tuple = ()
    bit_error_rate: float = 0.0
    clone_6500: bool = False
    stuck_sensor_at: float | None = None
    second_device: bool = False
    pca_brown_out_at: float | None = None
    pca_flip_write: tuple = ()
    slow_host: tuple = ()
    reset_lost: tuple = ()

    def __post_init__(self):
        check_in_range("error_rate", self.error_rate, 0.0, 1.0, low_inclusive=True)
        kinds = tuple(self.kinds)
        unknown = [k for k in kinds if k not in TRANSFER_FAULTS]
        if not kinds or unknown:
            raise ValueError(f"kinds must be a non-empty selection of {TRANSFER_FAULTS}, got "
                             f"{self.kinds!r}")
        object.__setattr__(self, "kinds", kinds)
        check_int("who_am_i", self.who_am_i, minimum=0, maximum=255)
        for name in ("stall_at", "chip_reset_at", "stuck_at", "release_fails_until"):
            if getattr(self, name) is not None:
                check_nonnegative(name, getattr(self, name))
        check_nonnegative("stall_duration", self.stall_duration)
        check_nonnegative("stuck_duration", self.stuck_duration)
        check_in_range("transfer_timeout", self.transfer_timeout, 0.0, MAX_TRANSFER_TIMEOUT,
                       low_inclusive=True, high_inclusive=True,
                       reason="no I2C adapter waits longer (Linux: one second by default)")
        for name in ("free_running_divider", "repeat_last_byte", "release_fails"):
            if not isinstance(getattr(self, name), bool):
                raise TypeError(f"{name} must be a bool, got {getattr(self, name)!r}")
        drift = check_real("clock_drift", self.clock_drift)
        if abs(drift) > MAX_FAULT_DRIFT:
            raise ValueError(f"clock_drift must lie in [-{MAX_FAULT_DRIFT}, {MAX_FAULT_DRIFT}], "
                             f"got {drift!r}")
        check_in_range("bit_error_rate", self.bit_error_rate, 0.0, 0.5, low_inclusive=True,
                       high_inclusive=True)
        for name in ("clone_6500", "second_device"):
            if not isinstance(getattr(self, name), bool):
                raise TypeError(f"{name} must be a bool, got {getattr(self, name)!r}")
        for name in ("stuck_sensor_at", "pca_brown_out_at"):
            if getattr(self, name) is not None:
                check_nonnegative(name, getattr(self, name))
        flips = tuple((check_int("flip_write register", r, minimum=0, maximum=_LAST_REGISTER),
                       check_int("flip_write mask", m, minimum=1, maximum=0xFF),
                       check_int("flip_write n", n, minimum=1)) for r, m, n in self.flip_write)
        pca_flips = tuple((check_int("pca_flip_write register", r, minimum=0, maximum=0xFF),
                           check_int("pca_flip_write mask", m, minimum=1, maximum=0xFF),
                           check_int("pca_flip_write n", n, minimum=1))
                          for r, m, n in self.pca_flip_write)
        object.__setattr__(self, "pca_flip_write", pca_flips)
        lost = tuple((check_nonnegative("register_lost time", t),
                      check_int("register_lost register", r, minimum=0, maximum=_LAST_REGISTER),
                      check_int("register_lost value", v, minimum=0, maximum=0xFF))
                     for t, r, v in self.register_lost)
        reads = tuple(sorted(((check_nonnegative("foreign_reads time", t), _what(what))
                              for t, what in self.foreign_reads), key=lambda r: r[0]))
        in_drain = tuple(sorted((check_nonnegative("drain_reads time", t),
                                 check_int("drain_reads n", n, minimum=1,
                                           maximum=MAX_READ_BYTES))
                                for t, n in self.drain_reads))
        object.__setattr__(self, "drain_reads", in_drain)
        object.__setattr__(self, "slow_host", _slow_host(self.slow_host))
        object.__setattr__(self, "reset_lost", _reset_lost(self.reset_lost))
        under = tuple(sorted(check_nonnegative("undercount_at", t) for t in self.undercount_at))
        for name, value in (("flip_write", flips), ("register_lost", lost),
                            ("foreign_reads", reads), ("undercount_at", under)):
            object.__setattr__(self, name, value)

    @classmethod
    def every_kind(cls, error_rate: float, **kwargs) -> Faults:
        """Transfer faults of every kind at ``error_rate``, plus whatever ``kwargs`` add."""
        return cls(error_rate=error_rate, kinds=TRANSFER_FAULTS, **kwargs)


class FaultInjector:
    """Draws the faults of :class:`Faults` for each transfer, from its own seeded generator.

    The bus asks it at fixed points of a transfer; each method answers for one kind of fault, so
    the same seed gives the same faults at the same transfers.

    Parameters
    ----------
    faults : Faults
        What to inject.
    seed : int
        Seed of the generator, >= 0.

    Attributes
    ----------
    errors_injected : int
        Transfers failed on purpose so far (stuck-bus timeouts included).
    log : list of (float, str)
        Every fault injected: virtual time and kind.

    Examples
    --------
    >>> from ebantenna.device.simulated import Faults, FaultInjector
    >>> injector = FaultInjector(Faults(stall_at=1.0, stall_duration=0.5), seed=0)
    >>> injector.host_stall(0.9), injector.host_stall(1.2), injector.host_stall(2.0)
    (0.0, 0.5, 0.0)
    """

    def __init__(self, faults: Faults, seed: int):
        if not isinstance(faults, Faults):
            raise TypeError(f"faults must be a Faults, got {type(faults).__name__}")
        self.faults = faults
        self._rng = np.random.default_rng(check_int("seed", seed, minimum=0))
        self._stalled = False
        self._reset_done = False
        # the silent faults draw from their own generator: the transfer faults stay as they were
        self._bits = np.random.default_rng([check_int("seed", seed, minimum=0), 1])
        # and the slow host from a third, so that asking for it changes no other draw
        self._slow = np.random.default_rng([seed, 2])
        self._flips_done: dict[tuple, int] = {}
        self._pca_reset_done = False
        self._lost_done = self._reads_done = self._under_done = self._drain_done = 0
        self._resets_done: set[int] = set()  # the reset_lost entries that have acted
        self._now = 0.0
        self.errors_injected = 0
        self.log: list[tuple[float, str]] = []

    def host_stall(self, now: float) -> float:
        """How long the host stalls before a transfer that starts at virtual time ``now``, s.

        The stall at ``stall_at`` (:class:`Faults`) happens once, at the first transfer from then
        on.
        """
        now = _time(now)
        faults = self.faults
        if faults.stall_at is None or self._stalled or now < faults.stall_at:
            return 0.0
        self._stalled = True
        self.log.append((now, "stall"))
        return faults.stall_duration

    def preemption(self, now: float) -> float:
        """How long the host loses the processor before a transfer at virtual time ``now``, s
        (``slow_host`` of :class:`Faults`; 0 most of the time). Each one is logged as
        ``"slow host"``."""
        now = _time(now)
        if not self.faults.slow_host:
            return 0.0
        share, longest = self.faults.slow_host
        if not self._slow.random() < share:
            return 0.0
        self.log.append((now, "slow host"))
        return float(self._slow.uniform(0.0, longest))

    def chip_reset(self, now: float) -> bool:
        """Whether the accelerometer browns out before a transfer at virtual time ``now`` (once)."""
        now = _time(now)
        at = self.faults.chip_reset_at
        if at is None or self._reset_done or now < at:
            return False
        self._reset_done = True
        self.log.append((now, "chip reset"))
        return True

    def stuck(self, now: float) -> OSError | None:
        """``ETIMEDOUT`` while the bus is stuck at virtual time ``now``, else None."""
        now = _time(now)
        at = self.faults.stuck_at
        if at is None or not at <= now < at + self.faults.stuck_duration:
            return None
        self.errors_injected += 1
        self.log.append((now, "stuck"))
        return _error(errno.ETIMEDOUT)

    def draw(self, now: float = 0.0) -> str | None:
        """The kind of failure of this transfer (one of the ``kinds`` of :class:`Faults`), or
        None."""
        now = _time(now)
        faults = self.faults
        if not (faults.error_rate and self._rng.random() < faults.error_rate):
            return None
        kind = faults.kinds[int(self._rng.integers(len(faults.kinds)))]
        self.errors_injected += 1
        self.log.append((now, kind))
        return kind

    def cancel(self) -> None:
        """Take back the last fault drawn: it did not apply to its transfer."""
        self.errors_injected -= 1
        self.log.pop()

    def early_error(self, kind: str) -> OSError:
        """The error of a transfer that fails before its data phase (``kind``: one of the early
        kinds of :data:`TRANSFER_FAULTS`, or ``"short"``, a write cut short: no acknowledge)."""
        if not isinstance(kind, str) or kind not in (*_EARLY_ERRNO, "short"):
            raise ValueError(f"kind must be one of {(*_EARLY_ERRNO, 'short')}, got {kind!r}")
        return _error(_EARLY_ERRNO.get(kind, errno.EREMOTEIO))

    def late_error(self) -> OSError:
        """The error of a transfer that fails after its data phase: ``EIO`` or ``ETIMEDOUT``."""
        return _error(errno.EIO if self._rng.random() < 0.5 else errno.ETIMEDOUT)

    def timeout_wait(self, error: OSError) -> float:
        """How long a transfer failing with ``error`` hangs first, s (``ETIMEDOUT`` only)."""
        if not isinstance(error, OSError):
            raise TypeError(f"error must be an OSError, got {type(error).__name__}")
        return self.faults.transfer_timeout if error.errno == errno.ETIMEDOUT else 0.0

    def _flipped(self, register: int, value: int, pca: bool = False) -> int:
        """The value a write of ``value`` to ``register`` of the accelerometer (or, with
        ``pca``, of the PCA9685) delivers."""
        table = self.faults.pca_flip_write if pca else self.faults.flip_write
        for k, (reg, mask, n) in enumerate(table):
            if reg == register and self._flips_done.get((pca, k), 0) < n:
                self._flips_done[(pca, k)] = self._flips_done.get((pca, k), 0) + 1
                self.log.append((self._now, "write bit flip"))
                return value ^ mask
        return value

    def _without_reset(self, register: int, data: list[int], now: float) -> list[int]:
        """``data`` written from ``register`` on to the accelerometer at ``now``, with the reset
        bit of every ``reset_lost`` entry due by then and not yet acted taken out (each once)."""
        out = list(data)
        for k, (at, which) in enumerate(self.faults.reset_lost):
            if at > now or k in self._resets_done:
                continue
            reg, bit = RESET_BITS[which]
            place = reg - register
            if 0 <= place < len(out) and out[place] & bit:
                out[place] &= ~int(bit) & 0xFF
                self._resets_done.add(k)
                self.log.append((now, "reset lost"))
        return out

    def _pca_brown_out(self, now: float) -> bool:
        """Whether the PCA9685 browns out before a transfer at ``now`` (once)."""
        at = self.faults.pca_brown_out_at
        if at is None or self._pca_reset_done or now < at:
            return False
        self._pca_reset_done = True
        self.log.append((now, "pca brown-out"))
        return True

    def _chip_events(self, now: float, mpu) -> None:
        """Apply the lost registers and foreign reads due by ``now`` to the accelerometer."""
        self._now = now
        faults = self.faults
        while self._lost_done < len(faults.register_lost) and (
                faults.register_lost[self._lost_done][0] <= now):
            _, register, value = faults.register_lost[self._lost_done]
            mpu._corrupt(register, value)
            self._lost_done += 1
            self.log.append((now, "register lost"))
        while self._reads_done < len(faults.foreign_reads) and (
                faults.foreign_reads[self._reads_done][0] <= now):
            what = faults.foreign_reads[self._reads_done][1]
            if what == "dump":
                for register in range(_LAST_REGISTER + 1):
                    mpu.read(register, 1)
            else:
                nbytes = {"byte": 1, "sample": ACCEL_SAMPLE_BYTES}.get(what, what)
                mpu.read(Register.FIFO_R_W, nbytes)
            self._reads_done += 1
            self.log.append((now, "foreign read"))

    def _drain_read(self, now: float, mpu) -> None:
        """Before a read of the FIFO data port at ``now``: another program's read, if one of
        ``drain_reads`` is due (each once)."""
        due = self.faults.drain_reads
        if self._drain_done < len(due) and due[self._drain_done][0] <= now:
            mpu.read(Register.FIFO_R_W, due[self._drain_done][1])
            self._drain_done += 1
            self.log.append((now, "foreign read"))

    def _undercount(self, now: float) -> bool:
        """Whether this FIFO count read reports one sample fewer (once per ``undercount_at``)."""
        due = self.faults.undercount_at
        if self._under_done < len(due) and due[self._under_done] <= now:
            self._under_done += 1
            self.log.append((now, "undercount"))
            return True
        return False

    def _bit_errors(self, data: list[int]) -> list[int]:
        """``data`` (bytes read from the FIFO) with bits flipped at ``bit_error_rate``."""
        rate = self.faults.bit_error_rate
        if not rate or not data:
            return data
        flips = self._bits.random((len(data), 8)) < rate
        if not flips.any():
            return data
        masks = (flips * (1 << np.arange(8))).sum(axis=1)
        self.log.append((self._now, "bit error"))
        return [b ^ int(m) for b, m in zip(data, masks, strict=True)]

    def overcount(self) -> int:
        """Samples a corrupted FIFO count claims beyond what the chip can have produced: 1 to
        :data:`MAX_OVERCOUNT`."""
        return int(self._rng.integers(1, MAX_OVERCOUNT + 1))

    def short_length(self, length: int) -> int:
        """How many of ``length`` bytes a short read delivers: 0 to ``length - 1``."""
        length = check_int("length", length, minimum=1)
        return int(self._rng.integers(length))

    def transfer_error(self) -> OSError | None:
        """An early error for this transfer, or None (kinds other than early ones count as none).

        Kept for callers that model only whole-transfer failures.
        """
        kind = self.draw()
        if kind is None or kind not in _EARLY_ERRNO:
            return None
        return self.early_error(kind)
