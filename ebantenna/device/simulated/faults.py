"""What can go wrong on the simulated bus: the faults asked for, and the seeded injector that
decides, transfer by transfer, which of them happen."""

from __future__ import annotations

import errno
from dataclasses import dataclass

import numpy as np

from ..._validate import check_in_range, check_int, check_nonnegative
from ...chips.mpu6050 import WHO_AM_I_VALUE

__all__ = ["Faults", "FaultInjector"]


@dataclass(frozen=True)
class Faults:
    """Faults to inject into the simulated bus.

    Parameters
    ----------
    error_rate : float
        Probability that a transfer fails with ``OSError(121, "Remote I/O error")``, in [0, 1).
        A failed transfer has no effect on the chip.
    who_am_i : int
        What the MPU-6050's ``WHO_AM_I`` reads; 0x68 for a genuine chip.
    stall_at : float or None
        Virtual time (s) after which the host stalls once, for ``stall_duration``.
    stall_duration : float
        Length of that stall, s.

    Examples
    --------
    >>> from ebantenna.device.simulated import Faults
    >>> Faults(error_rate=0.05).error_rate
    0.05
    """

    error_rate: float = 0.0
    who_am_i: int = WHO_AM_I_VALUE
    stall_at: float | None = None
    stall_duration: float = 0.0

    def __post_init__(self):
        check_in_range("error_rate", self.error_rate, 0.0, 1.0, low_inclusive=True)
        check_int("who_am_i", self.who_am_i, minimum=0, maximum=255)
        if self.stall_at is not None:
            check_nonnegative("stall_at", self.stall_at)
        check_nonnegative("stall_duration", self.stall_duration)


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
        Transfers failed on purpose so far.

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
        self.errors_injected = 0

    def host_stall(self, now: float) -> float:
        """How long the host stalls before a transfer that starts at virtual time ``now``, s.

        The stall of :attr:`Faults.stall_at` happens once, at the first transfer from then on.
        """
        faults = self.faults
        if faults.stall_at is None or self._stalled or now < faults.stall_at:
            return 0.0
        self._stalled = True
        return faults.stall_duration

    def transfer_error(self) -> OSError | None:
        """The error that makes this whole transfer fail before it reaches the chip, or None."""
        rate = self.faults.error_rate
        if rate and self._rng.random() < rate:
            self.errors_injected += 1
            return OSError(errno.EREMOTEIO, "Remote I/O error")
        return None
