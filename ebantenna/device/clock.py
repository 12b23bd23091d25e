"""Clocks: the drivers measure and wait through one of these, so that a simulated rig can run in
virtual time.

A clock has two methods, ``monotonic()`` (seconds, never decreasing) and ``sleep(seconds)``.
:class:`SystemClock` uses :func:`time.monotonic` and :func:`time.sleep`; the simulated bus brings
its own :class:`VirtualClock`, which advances only when somebody sleeps or the bus transfers bytes.
"""

from __future__ import annotations

import time

from .._validate import check_nonnegative

__all__ = ["SystemClock", "VirtualClock"]


class SystemClock:
    """The wall clock of the host.

    Examples
    --------
    >>> from ebantenna.device.clock import SystemClock
    >>> clock = SystemClock()
    >>> a = clock.monotonic(); clock.sleep(0.0); clock.monotonic() >= a
    True
    """

    def monotonic(self) -> float:
        """Seconds since an arbitrary origin (:func:`time.monotonic`)."""
        return time.monotonic()

    def sleep(self, seconds: float) -> None:
        """Wait ``seconds`` (s)."""
        time.sleep(check_nonnegative("seconds", seconds))


class VirtualClock:
    """A clock that only moves when told to: sleeping advances it instantly.

    Parameters
    ----------
    start : float
        Initial reading, s.

    Examples
    --------
    >>> from ebantenna.device.clock import VirtualClock
    >>> clock = VirtualClock()
    >>> clock.sleep(0.25); clock.advance(0.5); clock.monotonic()
    0.75
    """

    def __init__(self, start: float = 0.0):
        self._now = check_nonnegative("start", start)

    def monotonic(self) -> float:
        """The current virtual time, s."""
        return self._now

    def sleep(self, seconds: float) -> None:
        """Advance the virtual time by ``seconds`` (s), returning at once."""
        self.advance(seconds)

    def advance(self, seconds: float) -> None:
        """Advance the virtual time by ``seconds`` (s)."""
        self._now += check_nonnegative("seconds", seconds)
