"""The MPU-6050's FIFO as a stream of samples that are either right or counted as lost.

The FIFO holds 6-byte samples (X, Y, Z) with nothing in them to say where a sample begins, so a
single byte read but not kept shifts every later frame: X becomes Y, Y becomes Z. The rules here,
modelled on Linux's ``inv_mpu6050`` driver (``drivers/iio/imu/inv_mpu6050/inv_mpu_ring.c``: it
resets the FIFO on an overflow or a failed read, and estimates the sample period from the
timestamps of its interrupts), are:

1. **One drain** is: read ``FIFO_COUNT`` (harmless, retried), read the whole samples waiting in
   ``FIFO_R_W`` (one attempt per transfer, never retried), then read ``INT_STATUS`` (clear on
   read, one attempt). Its samples are kept only if every step succeeded, every transfer brought
   all its bytes, the count was a whole number of samples below the FIFO's size (RM 114-115: the
   FIFO holds 1024 bytes, PS 7.17) and ``INT_STATUS`` shows no overflow (RM 58,
   ``FIFO_OFLOW_INT``), which also catches an overflow between the count and the data, and
   ``USER_CTRL``/``PWR_MGMT_1`` show the chip still running (not reset during the drain).
2. **On any failure**, the FIFO is **restarted** (``FIFO_EN = 0``, ``USER_CTRL.FIFO_RESET``,
   then ``FIFO_EN`` and ``USER_CTRL.FIFO_EN`` again, RM 35 and 106): a new *segment* begins,
   aligned on a sample boundary. The whole-sample transfers of a drain that came in before a
   failed one are kept, once ``INT_STATUS`` has confirmed them; nothing after a failed transfer
   can be placed. The write that starts a segment is made once; if it fails the whole restart
   is redone, so the segment's start time is always that of a write known to have landed.
3. **Timestamps**: sample ``j`` of a segment started at host time ``t_e`` is taken at
   ``t_e + (j + 1) T``. The period ``T`` is estimated over the run from every confirmed count:
   ``n`` samples produced between ``t_e`` and the end of the count's transfer, and not ``n + 1``
   by its beginning, bound ``T`` from both sides; the estimate is the middle of the tightest
   bounds. Each sample also gets a *slot*, its position on the grid of the nominal stream,
   and the slots nobody filled are the lost samples, so kept + lost is always the number of
   slots asked for.
4. **A chip that went quiet** (no sample where some were due) is asked for its configuration; if
   it has been reset (a brown-out leaves it asleep, RM 107), it is configured again and the
   stream restarted. Every fault goes into :attr:`FifoStream.faults`.
"""

from __future__ import annotations

import logging
import math
from dataclasses import asdict, dataclass

import numpy as np

from .._validate import check_in_range, check_positive
from ..chips.mpu6050 import (
    ACCEL_SAMPLE_BYTES,
    FIFO_SIZE,
    FifoEnable,
    Interrupt,
    PowerManagement1,
    Register,
    UserControl,
)
from ..recording import Recording
from .i2c import SMBUS_BLOCK_MAX, I2CError

__all__ = ["PeriodEstimator", "StreamFault", "FifoBlock", "FifoStream", "CLOCK_TOLERANCE"]

logger = logging.getLogger(__name__)

#: How far the sample clock may be off its nominal rate before the estimate is not trusted,
#: relative: a few times the +/-1 % variation over temperature of the gyro oscillators that the PLL
#: locks to (PS rev. 3.4, section 7.15).
CLOCK_TOLERANCE = 0.05
#: Longest SMBus chunk that holds whole samples (30 bytes: 5 samples).
FIFO_CHUNK = (SMBUS_BLOCK_MAX // ACCEL_SAMPLE_BYTES) * ACCEL_SAMPLE_BYTES
#: A chip is asked whether it was reset when this many samples were due and none came.
QUIET_SAMPLES = 3


class PeriodEstimator:
    """The sample period, bracketed by counts of samples at known host times.

    Parameters
    ----------
    nominal : float
        The period the registers set, s.
    tolerance : float
        The period is assumed within ``nominal * (1 +/- tolerance)``.

    Examples
    --------
    >>> from ebantenna.device.fifo import PeriodEstimator
    >>> est = PeriodEstimator(1e-3)
    >>> est.add(start=0.0, produced=101, before=0.10145, after=0.10185)  # one count read
    >>> round(est.period * 1e3, 4), round(est.uncertainty * 1e6, 2)  # ms, us
    (1.0015, 6.9)
    """

    def __init__(self, nominal: float, tolerance: float = CLOCK_TOLERANCE):
        nominal = check_positive("nominal", nominal)
        tolerance = check_in_range("tolerance", tolerance, 0.0, 1.0)
        self.nominal = nominal
        self.low = nominal * (1.0 - tolerance)
        self.high = nominal * (1.0 + tolerance)

    def add(self, *, start: float, produced: int, before: float, after: float) -> None:
        """``produced`` samples since ``start`` (s) by the time ``after``, and fewer than
        ``produced + 1`` at ``before`` (the count's transfer ran from ``before`` to ``after``)."""
        low = (before - start) / (produced + 1)
        high = (after - start) / produced if produced else math.inf
        if max(low, self.low) >= min(high, self.high):
            logger.debug(
                "sample count %d at %.6f s contradicts the period bounds; ignored", produced, after
            )
            return
        self.low, self.high = max(low, self.low), min(high, self.high)

    @property
    def period(self) -> float:
        """Best estimate of the period, s."""
        return 0.5 * (self.low + self.high)

    @property
    def uncertainty(self) -> float:
        """Half the width of the bracket, s."""
        return 0.5 * (self.high - self.low)


@dataclass(frozen=True)
class StreamFault:
    """One thing that went wrong while streaming, and what it cost.

    Attributes
    ----------
    time : float
        Host time when it was noticed, s.
    cause : str
        What happened.
    action : str
        What the driver did ("restart", "reconfigure", "wait").
    """

    time: float
    cause: str
    action: str

    def to_dict(self) -> dict:
        """JSON-ready form."""
        return asdict(self)


@dataclass(frozen=True)
class FifoBlock:
    """Samples drained from the FIFO in one go.

    Attributes
    ----------
    index : ndarray of int, shape (n,)
        Slot of each sample on the stream's grid (0-based). A jump means samples were lost.
    counts : ndarray of int16, shape (n, 3)
        Raw X, Y, Z counts.
    lost : int
        Slots skipped just before this block.
    """

    index: np.ndarray
    counts: np.ndarray
    lost: int


def _empty_block(lost: int = 0) -> FifoBlock:
    return FifoBlock(np.empty(0, np.int64), np.empty((0, 3), np.int16), lost)


class FifoStream:
    """A running FIFO stream of one :class:`~ebantenna.device.mpu6050.MPU6050`.

    Made by :meth:`MPU6050.start_fifo`; see the module notes for the rules it follows.
    """

    def __init__(self, mpu):
        from .mpu6050 import MPU6050  # the driver imports this module

        if not isinstance(mpu, MPU6050):
            raise TypeError(f"mpu must be an MPU6050, got {type(mpu).__name__}")
        self.mpu = mpu
        self.device = mpu.device
        self.clock = mpu.clock
        self.estimator = PeriodEstimator(1.0 / mpu.config.fs)
        self.faults: list[StreamFault] = []
        self.starts: list[float] = []  # host time each segment started
        self.offsets: list[int] = []  # slot of each segment's first sample
        self.delivered: list[int] = []  # samples kept from each segment
        self.drain_times: list[float] = []
        self.drain_sizes: list[int] = []
        self._segment, self._position, self._slot, self._counts = [], [], [], []
        self.next_slot = 0
        self.overflows = 0
        self.pending: str | None = "start"
        self.unconfigured = False  # a reset chip whose configuration is not written back yet
        self.last_progress = self.clock.monotonic()
        self._try_restart()

    # -- restarting ------------------------------------------------------------------------
    def _note(self, cause: str, action: str) -> None:
        self.faults.append(StreamFault(self.clock.monotonic(), cause, action))
        logger.warning("MPU-6050 FIFO: %s; %s", cause, action)

    def _restart(self) -> None:
        """Empty the FIFO and start a new segment (raises :class:`I2CError` if the bus fails)."""
        device = self.device
        device.write_byte(Register.FIFO_EN, 0)
        # FIFO_RESET only acts while USER_CTRL.FIFO_EN is 0 (RM 106).
        device.write_byte(Register.USER_CTRL, UserControl.FIFO_RESET)
        device.read_byte(Register.INT_STATUS)  # clears a stale overflow flag (RM 58)
        device.write_byte(Register.FIFO_EN, FifoEnable.ACCEL)
        device.write_byte(Register.USER_CTRL, UserControl.FIFO_EN, retry=False)
        start = self.clock.monotonic()  # the write landed at its last acknowledge, just before
        period = self.estimator.period
        if self.starts:
            offset = max(round((start - self.starts[0]) / period), self.next_slot)
        else:
            offset = 0
        self.starts.append(start)
        self.offsets.append(offset)
        self.delivered.append(0)
        self.pending = None

    def _try_restart(self) -> None:
        try:
            self._restart()
        except I2CError as exc:
            self._note(f"restart failed ({exc.strerror or exc})", "wait")

    # -- draining --------------------------------------------------------------------------
    def _quiet(self, now: float) -> FifoBlock:
        """An empty FIFO: fine unless samples are overdue; then find out why and recover."""
        due = (now - self.starts[-1]) / self.estimator.period - self.delivered[-1]
        if due < QUIET_SAMPLES:
            return _empty_block()
        why = self.mpu.configuration_lost()
        if why is not None:
            return self._fail(why, reconfigure=True)
        return self._fail("no samples from the FIFO")

    def drain(self) -> FifoBlock:
        """Drain every whole sample waiting; on any fault restart and return what was kept."""
        if self.unconfigured:  # never restart a chip whose rate and range are not set again
            self._try_configure()
            if self.unconfigured:
                return _empty_block()
        if self.pending is not None:
            self._try_restart()
            if self.pending is not None:
                return _empty_block()
        try:
            before = self.clock.monotonic()
            count = self.mpu.fifo_count()
            after = self.clock.monotonic()
        except I2CError as exc:
            return self._fail(f"bus error ({exc.strerror or exc})")
        if count >= FIFO_SIZE:
            return self._fail("FIFO full (overflow)", overflow=True)
        if count % ACCEL_SAMPLE_BYTES:
            return self._fail(f"FIFO count {count} is not a whole number of samples")
        if count == 0:
            return self._quiet(after)
        raw, broken = self._read_data(count)
        try:
            status = self.device.read_byte(Register.INT_STATUS, retry=False)
            # USER_CTRL and PWR_MGMT_1 (RM 106-107) in one burst: a chip reset during the drain
            # would have emptied the FIFO, and the data port then reads filler bytes.
            user_ctrl, power = self.device.read_block(Register.USER_CTRL, 2)
        except I2CError as exc:
            return self._fail(f"bus error ({exc.strerror or exc})")
        if status & Interrupt.FIFO_OFLOW:
            return self._fail("FIFO overflow", overflow=True)
        if not user_ctrl & UserControl.FIFO_EN or power & PowerManagement1.SLEEP:
            return self._fail("the chip was reset during the drain", reconfigure=True)
        block = self._keep(raw, count // ACCEL_SAMPLE_BYTES, before, after)
        if broken is not None:  # the whole chunks before the failed transfer are kept
            self._fail(f"bus error ({broken.strerror or broken})")
        return block

    def _read_data(self, count: int) -> tuple[bytes, I2CError | None]:
        """Read ``count`` bytes of the data port in whole-sample transfers, one attempt each.

        Returns the bytes of the transfers that succeeded before the first failure (whole
        samples, in order) and that failure (None if all succeeded): a failed transfer may have
        taken any number of bytes out of the FIFO, so nothing after it can be placed.
        """
        device = self.device
        chunk = count if device.use_rdwr else FIFO_CHUNK
        raw = bytearray()
        while len(raw) < count:
            try:
                raw += device.read_block(
                    Register.FIFO_R_W,
                    min(chunk, count - len(raw)),
                    increment=False,
                    chunk=FIFO_CHUNK,
                    retry=False,
                )
            except I2CError as exc:
                return bytes(raw), exc
        return bytes(raw), None

    def _fail(self, cause: str, *, overflow: bool = False, reconfigure: bool = False):
        self.overflows += overflow
        self.pending = cause
        if reconfigure:
            self._note(cause, "reconfigure")
            self.unconfigured = True
            self._try_configure()
            if self.unconfigured:
                return _empty_block()
        else:
            self._note(cause, "restart")
        self._try_restart()
        return _empty_block()

    def _try_configure(self) -> None:
        try:
            self.mpu.configure()
        except I2CError as exc:
            self._note(f"reconfigure failed ({exc.strerror or exc})", "wait")
        else:
            self.unconfigured = False

    def _keep(self, raw: bytes, waiting: int, before: float, after: float) -> FifoBlock:
        """Keep the samples of ``raw``; ``waiting`` samples were counted in the FIFO between
        host times ``before`` and ``after``."""
        seg = len(self.starts) - 1
        first = self.delivered[seg]
        self.estimator.add(
            start=self.starts[seg], produced=first + waiting, before=before, after=after
        )
        n = len(raw) // ACCEL_SAMPLE_BYTES
        if n == 0:
            return _empty_block()
        slots = self.offsets[seg] + first + np.arange(n)
        lost = int(slots[0]) - self.next_slot
        counts = self.mpu.decode(raw)
        self._segment.append(np.full(n, seg))
        self._position.append(first + np.arange(n))
        self._slot.append(slots)
        self._counts.append(counts)
        self.delivered[seg] += n
        self.next_slot = int(slots[-1]) + 1
        self.last_progress = after
        self.drain_times.append(after)
        self.drain_sizes.append(n)
        return FifoBlock(slots, counts, lost)

    def host_time(self, slot: int) -> float:
        """Host time at which the sample in ``slot`` of the current segment was taken, s."""
        return self.starts[-1] + (slot - self.offsets[-1] + 1) * self.estimator.period

    # -- what was kept ---------------------------------------------------------------------
    @property
    def samples_read(self) -> int:
        """Samples kept so far."""
        return int(sum(self.delivered))

    def kept(self, first: int = 0, stop: int | None = None) -> dict:
        """The kept samples with slots in ``[first, stop)``: arrays ``slot``, ``segment``,
        ``position`` (within the segment), ``counts`` and ``time`` (s, estimated, from the
        stream's first sample)."""
        if not self._slot:
            slot = np.empty(0, np.int64)
            out = {
                "slot": slot,
                "segment": slot,
                "position": slot,
                "counts": np.empty((0, 3), np.int16),
            }
        else:
            out = {
                "slot": np.concatenate(self._slot),
                "segment": np.concatenate(self._segment),
                "position": np.concatenate(self._position),
                "counts": np.concatenate(self._counts),
            }
        stop = self.next_slot if stop is None else stop
        keep = (out["slot"] >= first) & (out["slot"] < stop)
        out = {k: v[keep] for k, v in out.items()}
        starts = np.asarray(self.starts or [0.0]) - (self.starts or [0.0])[0]
        out["time"] = starts[out["segment"]] + out["position"] * self.estimator.period
        return out

    def recording(self, first: int, stop: int, *, metadata: dict | None = None):
        """The stream's samples in slots ``[first, stop)`` as a
        :class:`~ebantenna.recording.Recording` (X -> ax, Z -> az), and the raw record.

        ``t`` is each sample's estimated time (s) from slot ``first``, with the period estimated
        over the run (:class:`~ebantenna.device.fifo.PeriodEstimator`), and ``fs`` the estimated
        rate. The metadata hold ``samples_lost`` (slots in the window without a sample), the
        stream's report (period estimate, restarts, fault log) and under ``"raw"`` what the rig
        measured: the counts of all three axes (Y included), each sample's slot, FIFO segment
        and position in it, each segment's start and each drain's host time (s from the
        stream's start) and size.

        Returns
        -------
        Recording
        """
        mpu = self.mpu
        kept = self.kept(first, stop)
        if kept["slot"].size == 0:
            raise ValueError("no samples to make a recording of")
        counts = kept["counts"]
        limit = np.iinfo(np.int16)
        saturated = int(
            np.count_nonzero((counts[:, [0, 2]] == limit.min) | (counts[:, [0, 2]] == limit.max))
        )
        if saturated:
            logger.warning(
                "%d accelerometer readings at the +/-%d g limit (clipped)",
                saturated,
                mpu.config.full_scale_g,
            )
        acc = mpu.to_acceleration(counts)
        period = self.estimator.period
        meta = mpu.metadata()
        meta.update(
            {
                "samples_lost": int((stop - first) - kept["slot"].size),
                "samples_saturated": saturated,
                "first_index": int(kept["slot"][0]),
            }
        )
        meta.update(metadata or {})
        t = kept["time"] - first * period
        starts = np.asarray(self.starts) - self.starts[0]
        meta["raw"] = {  # what the rig measured, as measured (see the module notes of .fifo)
            "counts_xyz": counts.tolist(),
            "slot": (kept["slot"] - first).tolist(),
            "segment": kept["segment"].tolist(),
            "position": kept["position"].tolist(),
            "segment_start_s": starts.tolist(),
            "drain_time_s": (np.asarray(self.drain_times) - self.starts[0]).tolist(),
            "drain_samples": list(self.drain_sizes),
        }
        return Recording(t, acc[:, 0], acc[:, 2], 1.0 / period, meta)

    def report(self) -> dict:
        """JSON-ready account of the stream: period estimate, restarts, faults."""
        est = self.estimator
        return {
            "sample_rate_estimated_hz": 1.0 / est.period,
            "sample_period_s": est.period,
            "sample_period_uncertainty_s": est.uncertainty,
            "fifo_restarts": len(self.starts) - 1,
            "fifo_overflows": self.overflows,
            "faults": [f.to_dict() for f in self.faults],
        }
