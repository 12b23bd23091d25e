"""Servos that always let go: released on every way out, a termination signal included.

:class:`ServoGuard` is a context manager around a run. On entry it installs handlers for SIGINT
(Ctrl-C), SIGTERM (``kill``, a service manager stopping the run) and SIGHUP (the terminal closed,
an SSH session dropped) that turn the signal into an exception (:class:`KeyboardInterrupt` for
SIGINT, :class:`SignalReceived` for the others), so that the run unwinds through its ``finally``
clauses. On exit, whatever the reason, it releases the servos, retrying a release that fails on a
noisy bus, and puts the previous handlers back; an exception leaving the guard gets an attribute
``servos_released`` that says whether the release succeeded. Signals arriving during the release
are held and re-raised after it, unless an exception is already leaving the guard: that exception
goes on, and the held signal is dropped.

Handlers can only be installed from the main thread (a rule of Python's :mod:`signal` module);
elsewhere the guard still releases on exit and says so in the log.
"""

from __future__ import annotations

import contextlib
import errno
import logging
import signal
import threading

from .._validate import check_in_range, check_int, check_nonnegative, check_positive
from .i2c import BusDeadError, I2CError
from .oe import OE_ONLY

__all__ = ["ServoGuard", "SignalReceived", "GUARDED_SIGNALS", "ReleaseError", "signals_held",
           "MAX_HELD_RETRY", "DEFAULT_HELD_RETRY"]

logger = logging.getLogger(__name__)

#: The signals after which the servos are released: interrupt, terminate, hang-up.
GUARDED_SIGNALS = tuple(
    getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name)
)

#: Longest time a :class:`ServoGuard` retries the I2C release while the ``OE`` pin holds the
#: outputs off, s: the operator is told to cut the supply only after it.
MAX_HELD_RETRY = 60.0
#: Default of that time, s: a bus that a brown-out or a stuck slave held for a few seconds.
#: Not shorter on purpose: while the ``OE`` pin holds the outputs off the servos are limp,
#: and once the program exits the line is released and the outputs follow the registers
#: again (the servos' pulses), so ending sooner makes nothing safer; it only gives up a bus
#: that may come back.
DEFAULT_HELD_RETRY = 10.0


@contextlib.contextmanager
def signals_held():
    """Ignore SIGINT, SIGTERM and SIGHUP inside (main thread only): for the few steps that must
    finish once the servos could not be released (saving the recording, marking the session
    unsafe), after which the run ends anyway with the instruction to cut the servo supply."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = {signum: signal.signal(signum, signal.SIG_IGN) for signum in GUARDED_SIGNALS}
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)


class SignalReceived(BaseException):
    """A termination signal (SIGTERM, SIGHUP) arrived; a :class:`BaseException`, like
    :class:`KeyboardInterrupt`, so that ``except Exception`` does not swallow it."""

    def __init__(self, signum: int):
        super().__init__(f"received {signal.Signals(signum).name}")
        self.signum = signum


class ReleaseError(OSError):
    """The servos could not be released: they may still be powered.

    Attributes
    ----------
    result : object or None
        What the run had finished before the release failed (an
        :class:`~ebantenna.device.pantilt.AcquisitionResult` for a search), so that a failure
        after the recording was made never loses it; None if nothing was finished.
    """

    result = None


class ServoGuard:
    """Release the servos on exit and on SIGINT, SIGTERM and SIGHUP.

    Parameters
    ----------
    release : callable
        Releases the servos (e.g. :meth:`~ebantenna.device.pantilt.PanTilt.release`). An
        :class:`I2CError` (a noisy or stuck bus) is retried; any other exception (an errno the
        bus layer does not retry, such as ``ENXIO`` or ``ENODEV`` from a missing adapter, or a
        bug) ends the attempts at once. Either way a release that failed leads to ``fallback``.
    clock : SystemClock or VirtualClock
        ``sleep`` provider for the waits between release attempts.
    attempts : int
        Tries of the release, >= 1. Default 6.
    delay : float
        Wait before the first retry, s, doubled before each further one. Default 50 ms: six
        tries span 1.55 s, longer than a bus stuck for a moment.
    deadline : float
        No attempt starts that would end more than this after the first began, judged by the
        longest attempt so far, s. Default 2 s. A bus declared dead
        (:class:`~ebantenna.device.i2c.BusDeadError`), or a failure that is not an
        :class:`I2CError`, ends the attempts at once.
    fallback : callable, optional
        A way to switch the outputs off that needs no I2C, called when the I2C release failed
        (e.g. :meth:`~ebantenna.device.oe.OutputEnable.disable_outputs`). It holds them off
        only while the program runs (:data:`~ebantenna.device.oe.OE_ONLY`): not a release.
        While it holds them, the I2C release is tried again, every ``held_interval`` seconds
        for ``held_retry`` seconds (the servos are limp meanwhile, so waiting costs nothing
        but time); if it still fails, :class:`ReleaseError` is raised all the same.
    held_retry : float
        How long the I2C release is retried while the fallback holds the outputs off, s, at
        most :data:`MAX_HELD_RETRY`. Default :data:`DEFAULT_HELD_RETRY` (10 s). 0: not
        retried.
    held_interval : float
        Wait between those retries, s (> 0). Default 1 s.
    revive : callable, optional
        Called before each of those retries to let the bus be tried though it was declared
        dead (``BusHealth.revive`` of the servo controller's bus, :mod:`ebantenna.device.i2c`).

    Attributes
    ----------
    released : bool
        Whether the last release succeeded: the outputs written off over I2C and read back so.
    released_by : str or None
        What switched the outputs off: ``"i2c"`` (the release), ``"oe"`` (the fallback alone,
        ``released`` False) or None.
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

    def __init__(self, release, clock, *, attempts: int = 6, delay: float = 0.05,
                 deadline: float = 2.0, fallback=None, held_retry: float = DEFAULT_HELD_RETRY,
                 held_interval: float = 1.0, revive=None):
        if not callable(release):
            raise TypeError(f"release must be callable, got {type(release).__name__}")
        for name, value in (("fallback", fallback), ("revive", revive)):
            if value is not None and not callable(value):
                raise TypeError(f"{name} must be callable or None, got {type(value).__name__}")
        self.release = release
        self.fallback = fallback
        self.revive = revive
        self.held_retry = check_in_range(
            "held_retry", held_retry, 0.0, MAX_HELD_RETRY, low_inclusive=True,
            high_inclusive=True, reason="the operator waits for the instruction meanwhile")
        self.held_interval = check_positive("held_interval", held_interval)
        self.clock = clock
        self.attempts = check_int("attempts", attempts, minimum=1)
        self.delay = check_nonnegative("delay", delay)
        self.deadline = check_positive("deadline", deadline)
        self.released = False
        self.released_by = None
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

    def _release_over_i2c(self) -> Exception | None:
        """Try the release until it succeeds, the attempts are used up or the deadline is near;
        returns the last error (None on success). Every exception counts as a failed release
        (so that the fallback follows); only an :class:`I2CError` other than a dead bus is
        retried."""
        first = self.clock.monotonic()
        longest = 0.0
        for attempt in range(self.attempts):
            began = self.clock.monotonic()
            try:
                self.release()
            except Exception as exc:  # noqa: BLE001 - any failure must lead to the fallback
                longest = max(longest, self.clock.monotonic() - began)
                logger.warning("releasing the servos failed (attempt %d of %d): %s",
                               attempt + 1, self.attempts, exc)
                wait = self.delay * 2**attempt
                spent = self.clock.monotonic() - first
                retried = isinstance(exc, I2CError) and not isinstance(exc, BusDeadError)
                if (not retried or attempt + 1 == self.attempts
                        or spent + wait + longest > self.deadline):
                    return exc
                self.clock.sleep(wait)
                continue
            return None
        raise AssertionError("unreachable")  # pragma: no cover

    def _retry_while_held(self, last: Exception) -> Exception | None:
        """While the fallback holds the outputs off, try the I2C release again every
        ``held_interval`` s for ``held_retry`` s (no attempt starts that would end later,
        judged by the longest so far); returns the last error, None once one succeeded."""
        first = self.clock.monotonic()
        longest = 0.0
        tries = 0
        while True:
            spent = self.clock.monotonic() - first
            if spent + self.held_interval + longest > self.held_retry:
                if tries:
                    logger.error("releasing the servos over I2C failed %d more times in %.1f s "
                                 "while the OE pin held their outputs off", tries, spent)
                return last
            self.clock.sleep(self.held_interval)
            if self.revive is not None:
                self.revive()
            began = self.clock.monotonic()
            tries += 1
            try:
                self.release()
            except Exception as exc:  # noqa: BLE001 - the outputs stay held: try again
                longest = max(longest, self.clock.monotonic() - began)
                last = exc
                continue
            logger.warning("the servos were released over I2C at the %d. retry, %.1f s after "
                           "the OE pin switched their outputs off", tries,
                           self.clock.monotonic() - first)
            return None

    def release_with_retries(self) -> None:
        """Release over I2C, retrying a failure within ``deadline`` seconds; if it still failed,
        switch the outputs off through ``fallback`` for as long as the program runs and retry
        the release for ``held_retry`` seconds more; if that fails too, raise
        :class:`ReleaseError` (the servos are not released: at exit the fallback lets go)."""
        last = self._release_over_i2c()
        if last is None:
            self.released, self.released_by = True, "i2c"
            return
        held = False
        if self.fallback is not None:
            try:
                self.fallback()
            except Exception as exc:  # noqa: BLE001 - any failure of the fallback is reported
                logger.error("switching the outputs off without I2C failed too: %s", exc)
            else:
                held = True
        if held:
            last = self._retry_while_held(last)
            if last is None:
                self.released, self.released_by = True, "i2c"
                return
        self.released, self.released_by = False, "oe" if held else None
        state = OE_ONLY if held else "they may still be powered"
        raise ReleaseError(
            getattr(last, "errno", None) or errno.EIO,
            f"the servos could not be released ({last}): {state}; switch off the servo supply",
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
