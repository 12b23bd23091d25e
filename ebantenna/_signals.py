"""The signal that stops a command, kept until the command has acted on it.

The command line turns Ctrl-C into :class:`KeyboardInterrupt` and SIGTERM or SIGHUP into
:class:`Terminated` (a subclass, so that every ``finally`` and ``except KeyboardInterrupt`` that
makes the work safe runs for them too). A library may catch :class:`KeyboardInterrupt` and go
on: scikit-learn's MLP training does ("Training interrupted by user") and returns, and the
command would then run to its end and exit with success. So the handlers also note the signal
here, and :func:`raise_pending` raises it again where the package checks: at each step of a
progress bar (:func:`ebantenna._progress.progress`) and when the command returns.
"""

from __future__ import annotations

import signal

__all__ = ["Terminated", "note", "pending", "clear", "raise_pending"]

_PENDING: list[int] = []


class Terminated(KeyboardInterrupt):
    """SIGTERM (or another terminating signal), raised like Ctrl-C so that every ``finally`` and
    ``except KeyboardInterrupt`` that makes the work safe (servos released, temporary files
    removed) runs for it too."""

    def __init__(self, signum: int = signal.SIGTERM):
        super().__init__(signal.Signals(signum).name)
        self.signum = int(signum)


def note(signum: int) -> None:
    """Keep ``signum`` as the signal that stops the command (the first one counts)."""
    if not _PENDING:
        _PENDING.append(int(signum))


def pending() -> int | None:
    """The signal noted and not yet acted on, or ``None``."""
    return _PENDING[0] if _PENDING else None


def clear() -> None:
    """Forget the noted signal (the command has acted on it, or a new one starts)."""
    _PENDING.clear()


def raise_pending() -> None:
    """Raise the noted signal again, if any: :class:`KeyboardInterrupt` for SIGINT, else
    :class:`Terminated`."""
    signum = pending()
    if signum is None:
        return
    if signum == signal.SIGINT:
        raise KeyboardInterrupt
    raise Terminated(signum)
