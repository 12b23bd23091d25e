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
host once, run the accelerometer's sample clock off its nominal rate, let its sample-rate divider
run free (the first sample of a FIFO segment then comes anywhere within a period of the enable,
not one period after it), make it repeat its last byte when the FIFO is read past its end (as the
real part does), make every transfer that times out hang for a stated time first (the adapter's
timeout), and make every write that releases the servos fail.
"""

from __future__ import annotations

import errno
from dataclasses import dataclass

import numpy as np

from ..._validate import check_in_range, check_int, check_nonnegative, check_real
from ...chips.mpu6050 import WHO_AM_I_VALUE
from .mpu6050 import MAX_CLOCK_DRIFT

__all__ = ["Faults", "FaultInjector", "TRANSFER_FAULTS", "MAX_CLOCK_DRIFT", "MAX_OVERCOUNT"]

#: Kinds of failed transfer the injector can draw (see the module notes).
TRANSFER_FAULTS = ("nack", "eio", "etimedout", "eagain", "late", "short", "eintr", "overcount")

_EARLY_ERRNO = {"nack": errno.EREMOTEIO, "eio": errno.EIO, "etimedout": errno.ETIMEDOUT,
                "eagain": errno.EAGAIN, "eintr": errno.EINTR}
#: Largest over-report of a FIFO count, samples: up to a whole FIFO's worth.
MAX_OVERCOUNT = 170


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
        clock_drift)``. At most ``MAX_CLOCK_DRIFT`` in magnitude.
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

    def __post_init__(self):
        check_in_range("error_rate", self.error_rate, 0.0, 1.0, low_inclusive=True)
        kinds = tuple(self.kinds)
        unknown = [k for k in kinds if k not in TRANSFER_FAULTS]
        if not kinds or unknown:
            raise ValueError(f"kinds must be a non-empty selection of {TRANSFER_FAULTS}, got "
                             f"{self.kinds!r}")
        object.__setattr__(self, "kinds", kinds)
        check_int("who_am_i", self.who_am_i, minimum=0, maximum=255)
        for name in ("stall_at", "chip_reset_at", "stuck_at"):
            if getattr(self, name) is not None:
                check_nonnegative(name, getattr(self, name))
        check_nonnegative("stall_duration", self.stall_duration)
        check_nonnegative("stuck_duration", self.stuck_duration)
        check_nonnegative("transfer_timeout", self.transfer_timeout)
        for name in ("free_running_divider", "repeat_last_byte", "release_fails"):
            if not isinstance(getattr(self, name), bool):
                raise TypeError(f"{name} must be a bool, got {getattr(self, name)!r}")
        drift = check_real("clock_drift", self.clock_drift)
        if abs(drift) > MAX_CLOCK_DRIFT:
            raise ValueError(f"clock_drift must lie in [-{MAX_CLOCK_DRIFT}, {MAX_CLOCK_DRIFT}], "
                             f"got {drift!r}")

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
        self.errors_injected = 0
        self.log: list[tuple[float, str]] = []

    def host_stall(self, now: float) -> float:
        """How long the host stalls before a transfer that starts at virtual time ``now``, s.

        The stall at ``stall_at`` (:class:`Faults`) happens once, at the first transfer from then
        on.
        """
        faults = self.faults
        if faults.stall_at is None or self._stalled or now < faults.stall_at:
            return 0.0
        self._stalled = True
        self.log.append((now, "stall"))
        return faults.stall_duration

    def chip_reset(self, now: float) -> bool:
        """Whether the accelerometer browns out before a transfer at virtual time ``now`` (once)."""
        at = self.faults.chip_reset_at
        if at is None or self._reset_done or now < at:
            return False
        self._reset_done = True
        self.log.append((now, "chip reset"))
        return True

    def stuck(self, now: float) -> OSError | None:
        """``ETIMEDOUT`` while the bus is stuck at virtual time ``now``, else None."""
        at = self.faults.stuck_at
        if at is None or not at <= now < at + self.faults.stuck_duration:
            return None
        self.errors_injected += 1
        self.log.append((now, "stuck"))
        return _error(errno.ETIMEDOUT)

    def draw(self, now: float = 0.0) -> str | None:
        """The kind of failure of this transfer (one of the ``kinds`` of :class:`Faults`), or
        None."""
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
        """The error of a transfer that fails before its data phase."""
        return _error(_EARLY_ERRNO.get(kind, errno.EREMOTEIO))

    def late_error(self) -> OSError:
        """The error of a transfer that fails after its data phase: ``EIO`` or ``ETIMEDOUT``."""
        return _error(errno.EIO if self._rng.random() < 0.5 else errno.ETIMEDOUT)

    def timeout_wait(self, error: OSError) -> float:
        """How long a transfer failing with ``error`` hangs first, s (``ETIMEDOUT`` only)."""
        return self.faults.transfer_timeout if error.errno == errno.ETIMEDOUT else 0.0

    def overcount(self) -> int:
        """Samples a corrupted FIFO count claims beyond what the chip can have produced: 1 to
        :data:`MAX_OVERCOUNT`."""
        return int(self._rng.integers(1, MAX_OVERCOUNT + 1))

    def short_length(self, length: int) -> int:
        """How many of ``length`` bytes a short read delivers: 0 to ``length - 1``."""
        return int(self._rng.integers(length))

    def transfer_error(self) -> OSError | None:
        """An early error for this transfer, or None (kinds other than early ones count as none).

        Kept for callers that model only whole-transfer failures.
        """
        kind = self.draw()
        if kind is None or kind not in _EARLY_ERRNO:
            return None
        return self.early_error(kind)
