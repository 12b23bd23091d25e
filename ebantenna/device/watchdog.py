"""The watchdog of a recording: a rig that stops producing samples ends the run with a clear error
instead of a loop that never returns, and what was recorded until then is kept.

A chip that browns out and is not brought back, a loose wire, a bus that stays stuck: in each case
no new sample reaches the host. :func:`record_stream` drains the FIFO every poll interval, and when
no sample has been kept for ``watchdog`` seconds it stops the FIFO (if the bus still answers) and
raises :class:`StreamStalledError`, naming the last fault seen and carrying the partial
:class:`~ebantenna.recording.Recording`.
"""

from __future__ import annotations

import logging

from .._validate import check_int, check_positive
from .i2c import I2CError

__all__ = ["StreamStalledError", "record_stream", "check_watchdog", "stop_quietly"]

logger = logging.getLogger(__name__)


class StreamStalledError(RuntimeError):
    """No sample arrived for longer than the watchdog allows.

    Attributes
    ----------
    recording : Recording or None
        What was recorded before the stall (None if nothing was).
    cause : str
        The last fault seen, or why none could be named.
    """

    def __init__(self, message: str, recording=None, cause: str = ""):
        super().__init__(message)
        self.recording = recording
        self.cause = cause


def stop_quietly(mpu) -> None:
    """Stop the FIFO; a bus error here is logged, not raised (the run is ending anyway)."""
    if not callable(getattr(mpu, "stop_fifo", None)):
        raise TypeError(f"mpu must be an MPU6050, got {type(mpu).__name__}")
    try:
        mpu.stop_fifo()
    except I2CError as exc:
        logger.warning("could not stop the MPU-6050 FIFO: %s", exc)


def _stream_of(mpu):
    """``mpu``'s running stream, or a clear error naming ``mpu``."""
    stream = getattr(mpu, "stream", None)
    if stream is None or not callable(getattr(mpu, "to_recording", None)):
        raise TypeError(f"mpu must be an MPU6050 with its FIFO started, got "
                        f"{type(mpu).__name__}")
    return stream


def check_watchdog(
    mpu, watchdog: float, *, window: tuple[int, int] | None = None, metadata: dict | None = None
) -> None:
    """Raise :class:`StreamStalledError` if ``mpu``'s stream kept no sample for ``watchdog`` s,
    or at once if it refused the chip's sample clock (``clock_refused``: a rate beyond what it
    adapts to).

    ``window`` is the ``(first, stop)`` slots of the partial recording to attach (default all
    kept so far).
    """
    stream = _stream_of(mpu)
    watchdog = check_positive("watchdog", watchdog)
    if window is not None:
        if not isinstance(window, tuple | list) or len(window) != 2:
            raise TypeError(f"window must be a (first, stop) pair of slots or None, got "
                            f"{window!r}")
        first = check_int("window first", window[0], minimum=0)
        window = (first, check_int("window stop", window[1], minimum=first))
    silent = mpu.clock.monotonic() - stream.last_progress
    refused = getattr(stream, "clock_refused", None)  # a clock beyond what the stream adapts to
    if silent <= watchdog and refused is None:
        return
    cause = refused or (stream.faults[-1].cause if stream.faults else "the FIFO stayed empty")
    first, stop = window if window is not None else (0, stream.next_slot)
    stop = min(stop, stream.next_slot)
    partial = None
    if stream.kept(first, stop)["slot"].size:
        partial = mpu.to_recording(first, stop, metadata={**(metadata or {}), "stalled": cause})
    kept = 0 if partial is None else partial.n_samples
    head = (f"the MPU-6050's sample clock is refused: {refused}" if refused else
            f"no sample from the MPU-6050 for {silent:.3f} s (watchdog {watchdog:g} s); last "
            f"fault: {cause}")
    raise StreamStalledError(
        f"{head}. {kept} samples were recorded before the {'refusal' if refused else 'stall'} "
        "and are kept in the error's recording",
        partial,
        cause,
    )


def record_stream(mpu, duration: float, *, poll_interval: float = 0.02, watchdog: float = 1.0):
    """Record ``duration`` s of ``mpu``'s FIFO (the body of
    :meth:`~ebantenna.device.mpu6050.MPU6050.record`)."""
    duration = check_positive("duration", duration)
    if not callable(getattr(mpu, "check_poll_interval", None)):
        raise TypeError(f"mpu must be an MPU6050, got {type(mpu).__name__}")
    poll_interval = mpu.check_poll_interval(poll_interval)
    watchdog = check_positive("watchdog", watchdog)
    wanted = max(1, round(duration * mpu.config.fs))
    stream = mpu.start_fifo()
    try:
        while stream.next_slot < wanted:
            mpu.clock.sleep(mpu.poll_wait(poll_interval))  # follows the measured clock
            stream.drain()
            check_watchdog(mpu, watchdog, window=(0, wanted))
    finally:
        stop_quietly(mpu)
    if stream.kept(0, wanted)["slot"].size == 0:
        cause = stream.faults[-1].cause if stream.faults else "no sample in the window"
        raise StreamStalledError(
            f"all {wanted} samples of the recording were lost; last fault: {cause}", None, cause
        )
    return mpu.to_recording(0, wanted)
