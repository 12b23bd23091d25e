"""Servos that always let go: released on every way out, a termination signal included.

:class:`ServoGuard` is a context manager around a run. On entry it installs handlers for SIGINT
(Ctrl-C), SIGTERM (``kill``, a service manager stopping the run) and SIGHUP (the terminal closed,
an SSH session dropped) that turn the signal into an exception (:class:`KeyboardInterrupt` for
SIGINT, :class:`SignalReceived` for the others), so that the run unwinds through its ``finally``
clauses. On exit, whatever the reason, it releases the servos, retrying a release that fails on a
noisy bus, and puts the previous handlers back; an exception leaving the guard gets an attribute
``servos_released`` that says whether the release succeeded. Signals arriving during the release
are held and re-raised after it.

Handlers can only be installed from the main thread (Python's :mod:`signal` rule); elsewhere the
guard still releases on exit and says so in the log.
"""

from __future__ import annotations

import logging
import signal
import threading

from .._validate import check_int, check_nonnegative
from .i2c import I2CError

__all__ = ["ServoGuard", "SignalReceived", "GUARDED_SIGNALS", "ReleaseError"]

logger = logging.getLogger(__name__)

#: The signals after which the servos are released: interrupt, terminate, hang-up.
GUARDED_SIGNALS = tuple(
    getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name)
)


class SignalReceived(BaseException):
    """A termination signal (SIGTERM, SIGHUP) arrived; a :class:`BaseException`, like
    :class:`KeyboardInterrupt`, so that ``except Exception`` does not swallow it."""

    def __init__(self, signum: int):
        super().__init__(f"received {signal.Signals(signum).name}")
        self.signum = signum


class ReleaseError(OSError):
    """The servos could not be released: they may still be powered."""


class ServoGuard:
    """Release the servos on exit and on SIGINT, SIGTERM and SIGHUP.

    Parameters
    ----------
    release : callable
        Releases the servos (e.g. :meth:`PanTilt.release`); may raise :class:`I2CError`.
    clock : clock
        ``sleep`` provider for the waits between release attempts.
    attempts : int
        Tries of the release, >= 1. Default 6.
    delay : float
        Wait before the first retry, s, doubled before each further one. Default 50 ms: six
        tries span 1.55 s, longer than a bus stuck for a moment.

    Attributes
    ----------
    released : bool
        Whether the last release succeeded.
    signal_received : int or None
        The guarded signal that ended the run, if one did.

    Examples
    --------
    >>> from ebantenna.device.simulated import SimulatedRig
    >>> from ebantenna.device import PCA9685, PanTilt
    >>> from ebantenna.device.safety import ServoGuard
    >>> rig = SimulatedRig.quiet()
    >>> unit = PanTilt(PCA9685(rig.bus, clock=rig.clock)); unit.initialize()
    >>> with ServoGuard(unit.release, rig.clock) as guard:
    ...     _ = unit.move(100.0, 80.0)
    >>> guard.released, rig.pca.outputs_enabled()
    (True, False)
    """

    def __init__(self, release, clock, *, attempts: int = 6, delay: float = 0.05):
        if not callable(release):
            raise TypeError(f"release must be callable, got {type(release).__name__}")
        self.release = release
        self.clock = clock
        self.attempts = check_int("attempts", attempts, minimum=1)
        self.delay = check_nonnegative("delay", delay)
        self.released = False
        self.signal_received = None
        self._previous: dict[int, object] = {}
        self._held: list[int] = []

    def _raise(self, signum, frame):
        self.signal_received = signum
        if signum == signal.SIGINT:
            raise KeyboardInterrupt
        raise SignalReceived(signum)

    def _hold(self, signum, frame):
        self._held.append(signum)

    def _install(self, handler) -> None:
        for signum in GUARDED_SIGNALS:
            previous = signal.signal(signum, handler)
            self._previous.setdefault(signum, previous)

    def __enter__(self) -> ServoGuard:
        if threading.current_thread() is threading.main_thread():
            self._install(self._raise)
        else:
            logger.warning(
                "not in the main thread: the servos are released on exit, but not on a signal"
            )
        return self

    def release_with_retries(self) -> None:
        """Release, retrying a failure ``attempts`` times; :class:`ReleaseError` if all fail."""
        last = None
        for attempt in range(self.attempts):
            try:
                self.release()
            except I2CError as exc:
                last = exc
                logger.warning(
                    "releasing the servos failed (attempt %d of %d): %s",
                    attempt + 1,
                    self.attempts,
                    exc,
                )
                if attempt + 1 < self.attempts:
                    self.clock.sleep(self.delay * 2**attempt)
                continue
            self.released = True
            return
        self.released = False
        raise ReleaseError(
            last.errno,
            f"the servos could not be released after {self.attempts} attempts "
            f"({last}): they may still be powered; switch off the servo supply",
        ) from last

    def __exit__(self, exc_type, exc, tb):
        installed = bool(self._previous)
        if installed:
            self._install(self._hold)
        try:
            self.release_with_retries()
        except ReleaseError:
            if exc is None:
                raise
            logger.error("the servos could not be released while handling %r", exc)
        finally:
            for signum, previous in self._previous.items():
                signal.signal(signum, previous)
            self._previous.clear()
        if exc is not None:  # the error on its way out says whether the servos let go
            exc.servos_released = self.released
        if self._held and exc is None:
            self._raise(self._held[0], None)
        return False
