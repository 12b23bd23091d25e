"""Time limits in tests that hold on a loaded machine: the clock leaves out the time spent waiting
for a CPU.

A test's time limit guards against a hang (a FIFO that blocks, a child that never ends) or a
runaway computation, not against a busy machine. Wall time mixes the two: on two cores shared
with other jobs a call gets a fraction of a core, and a limit set for an idle machine fails. This
clock counts what the task would have taken alone on a core: wall time minus the time it waited,
runnable, for a CPU (Linux's ``/proc/<pid>/task/<tid>/schedstat``, second field: time spent on a
run queue, in ns). Computing and blocking (sleeping, waiting on a pipe or a lock) both count; being
starved of a CPU does not. Where the kernel does not give the figure (another system), the clock
is the wall clock.

For a child process the clock reads the child's main thread: its own waits for a CPU are left
out; time it spends waiting on its own children counts as blocked time (a grandchild slowed by
the load still shows), so a child that starts processes of its own needs a bound with room for
that.
"""

from __future__ import annotations

import contextlib
import signal
import subprocess
import threading
import time

__all__ = ["UnloadedClock", "time_limit", "communicate", "readline", "run"]


def _run_queue_seconds(where: str) -> float | None:
    """Time ``where`` (``thread-self`` or ``<pid>``) waited for a CPU, s; None if unknown."""
    path = "/proc/thread-self/schedstat" if where == "thread-self" else f"/proc/{where}/schedstat"
    try:
        with open(path, encoding="ascii") as f:
            return int(f.read().split()[1]) * 1e-9
    except (OSError, ValueError, IndexError):
        return None


class UnloadedClock:
    """Seconds since creation, less the time the thread (or process ``pid``) waited for a CPU.

    Parameters
    ----------
    pid : int, optional
        A child process to time (its main thread); default: the calling thread.
    """

    def __init__(self, pid: int | None = None):
        self._where = "thread-self" if pid is None else str(pid)
        self._wall = time.monotonic()
        self._queued = _run_queue_seconds(self._where)
        self._last = 0.0

    def elapsed(self) -> float:
        """Seconds the task took or would have taken alone on a core, so far (never decreasing:
        a child's figure stays at its last value once the child is gone)."""
        wall = time.monotonic() - self._wall
        queued = _run_queue_seconds(self._where)
        if self._queued is not None and queued is not None:
            self._last = max(self._last, wall - (queued - self._queued))
        elif self._queued is None:
            self._last = wall
        return self._last


@contextlib.contextmanager
def time_limit(seconds: float, exception: type[BaseException]):
    """Raise ``exception()`` in the main thread once the block has taken ``seconds`` on the
    :class:`UnloadedClock`.

    A wall-clock alarm fires at the limit; if the block spent part of that waiting for a CPU, the
    alarm is set again for what is left. A blocking system call (``open`` on a FIFO) is
    interrupted by the alarm and, if the limit is not reached, resumed by Python (PEP 475).
    Main thread only (POSIX signals).
    """
    clock = UnloadedClock()

    def on_alarm(signum, frame):
        left = seconds - clock.elapsed()
        if left <= 0:
            raise exception()
        signal.setitimer(signal.ITIMER_REAL, max(left, 1e-3))

    previous = signal.signal(signal.SIGALRM, on_alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield clock
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def _expire(proc: subprocess.Popen, seconds: float, before_kill) -> None:
    """Past a limit of ``seconds``: ``before_kill(proc)`` (if given) and up to 5 s for the child
    to answer it, then the child killed and ``subprocess.TimeoutExpired`` raised with what it
    printed."""
    if before_kill is not None:
        before_kill(proc)
        with contextlib.suppress(subprocess.TimeoutExpired):
            proc.wait(timeout=5)
    proc.kill()
    out, err = proc.communicate()
    raise subprocess.TimeoutExpired(proc.args, seconds, output=out, stderr=err)


def communicate(proc: subprocess.Popen, seconds: float, poll: float = 0.5, before_kill=None):
    """``proc.communicate()`` with a limit of ``seconds`` on the child's :class:`UnloadedClock`.

    Past the limit ``before_kill(proc)`` is called (if given: to ask the child for its stacks,
    say), the child is killed and ``subprocess.TimeoutExpired`` raised with what it printed, as
    ``communicate(timeout=...)`` does; but a child slowed by other work on the machine is waited
    for. Returns ``(stdout, stderr)``.
    """
    clock = UnloadedClock(proc.pid)
    while True:
        try:
            return proc.communicate(timeout=poll)
        except subprocess.TimeoutExpired:
            if clock.elapsed() <= seconds:
                continue
        _expire(proc, seconds, before_kill)


def readline(proc: subprocess.Popen, stream, seconds: float, poll: float = 0.5,
             before_kill=None) -> str:
    """``stream.readline()`` of a pipe of ``proc``, within ``seconds`` on the child's
    :class:`UnloadedClock` (past it: ``before_kill(proc)``, the child killed,
    ``subprocess.TimeoutExpired``)."""
    clock, line = UnloadedClock(proc.pid), []
    reader = threading.Thread(target=lambda: line.append(stream.readline()), daemon=True)
    reader.start()
    while True:
        reader.join(poll)
        if not reader.is_alive():
            return line[0]
        if clock.elapsed() > seconds:
            break
    _expire(proc, seconds, before_kill)


def run(args, seconds: float, **kwargs) -> subprocess.CompletedProcess:
    """``subprocess.run(args, timeout=seconds, ...)`` on the child's :class:`UnloadedClock`
    (``check`` is not supported: read ``returncode``)."""
    capture = kwargs.pop("capture_output", False)
    if capture:
        kwargs.setdefault("stdout", subprocess.PIPE)
        kwargs.setdefault("stderr", subprocess.PIPE)
    with subprocess.Popen(args, **kwargs) as proc:
        out, err = communicate(proc, seconds)
    return subprocess.CompletedProcess(args, proc.returncode, out, err)
