"""The MPU-6050's FIFO as a stream of samples that are either right or counted as lost.

The FIFO holds 6-byte samples (X, Y, Z) with nothing in them to say where a sample begins, so a
single byte read but not kept shifts every later frame: X becomes Y, Y becomes Z. The rules here,
modelled on Linux's ``inv_mpu6050`` driver (``drivers/iio/imu/inv_mpu6050/inv_mpu_ring.c``: it
resets the FIFO on an overflow or a failed read, keeps a per-chip FIFO size, accepts an
interrupt's timestamp only when the period it implies lies within a few percent of nominal, and
estimates the sample period from the timestamps of its interrupts), are:

1. **Trust no count.** One drain begins with ``FIFO_COUNT`` (harmless, retried). Before any
   data is read the count must be a whole number of samples, not above the FIFO's size (RM
   114-115; 1024 bytes on the MPU-6050, PS 7.17, 512 on the MPU-6500 family), possible in the
   time since the segment began (:class:`PeriodEstimator`: a count no period within the clock's
   tolerance can explain is *rejected*, logged at WARNING and counted). A count read too high
   would make the driver read past the FIFO's end, where the real part repeats its last byte:
   filler that decodes as a plausible sample. A count equal to the FIFO's size is an overflow.
   (A count too high by less than the clock's tolerance allows cannot be told from a true one
   by any check before the read; the check catches every count the chip cannot have reached.)
2. **One drain** then reads the whole samples waiting in ``FIFO_R_W``, then ``INT_STATUS`` (clear
   on read): each transfer retried only after a missing acknowledge, which proves that nothing
   was read (:mod:`~ebantenna.device.i2c`), any other failure ending the drain. Its samples are
   kept only if every step succeeded, every transfer brought all its bytes, ``INT_STATUS`` shows
   no overflow (RM 58, ``FIFO_OFLOW_INT``), which also catches an overflow between the count and
   the data, and ``USER_CTRL``/``PWR_MGMT_1`` show the chip still running (not reset during the
   drain).
3. **On any failure**, whatever ``OSError`` it raised (``EINTR`` and ``EAGAIN`` are retried as
   transient where a retry is safe; an unknown errno becomes an :class:`I2CError`), the FIFO is
   **restarted** (``FIFO_EN = 0``, ``USER_CTRL.FIFO_RESET``, then ``FIFO_EN`` and
   ``USER_CTRL.FIFO_EN`` again, RM 35 and 106): a new *segment* begins, aligned on a sample
   boundary, and what was kept so far stays kept. The reset bit clears itself, so reading
   ``USER_CTRL`` back cannot show that the reset acted; ``FIFO_COUNT``, read while the FIFO is
   still disabled (no sample can enter it), must then be 0. A reset it does not confirm is
   counted (``fifo_resets_unconfirmed``) and made again, up to :data:`FIFO_RESET_ATTEMPTS`
   times, after which the restart fails and is tried again at the next drain: bytes left from
   before are never read as the new segment's first samples. The whole-sample transfers of a
   drain that came in before a failed one are kept, once ``INT_STATUS`` has confirmed them;
   nothing after a failed transfer can be placed. The write that starts a segment is made
   once; if it fails the whole restart is redone, so the segment's start is always a write
   known to have landed.
4. **Timestamps** do not assume when a segment's first sample came: whether the divider
   restarts when the FIFO is enabled or runs free is a property of the silicon (see the HIL
   checklist of the user guide). The period ``T`` is bracketed from *differences* of counts
   within a segment, in which the first sample's time cancels (:class:`PeriodEstimator`); each
   segment's first sample is then placed from its own counts, and sample ``j`` is at ``t_0 +
   j T``. Every segment carries the uncertainty of its timestamps, true when no other program
   reads the FIFO (a recording says the largest, ``timestamp_uncertainty_sole_reader_s``);
   each sample states the hull of that and its own drain's anchor, true too when another
   reader took single samples unseen, which the counts cannot tell from a slower clock
   (``timestamp_uncertainty_s``, the largest; ``FifoStream._drain_covered``). Each sample also
   gets a *slot*, its position on the grid of the nominal stream, and the slots nobody filled
   are the lost samples, so kept + lost is always the number of slots asked for.
5. **A chip that went quiet** (no sample where some were due) is asked for its configuration; if
   it has been reset (a brown-out leaves it asleep, RM 107), it is configured again and the
   stream restarted. Every fault goes into the ``faults`` of the :class:`FifoStream`.
6. **Read back, every drain.** After the data, every setting the driver wrote is read again
   (:meth:`~ebantenna.device.mpu6050.MPU6050.read_registers`, ``INT_STATUS`` among them) and
   ``FIFO_COUNT`` once more. A changed register discards the drain (counted in
   ``samples_discarded``), names itself from what to what, and the chip is configured again; a
   count after the data that is not whole samples, or does not follow from the count before at
   any rate the tolerance allows, means another reader took bytes: the drain is dropped. So
   does a count after the data that confirms nothing: one above the FIFO's size (read wrong),
   or a full FIFO (it may have overflowed during the drain, and another program may have
   cleared the overflow flag before the driver read ``INT_STATUS``; counted as an overflow).
   A count that contradicts the clock's tolerance flags the timestamps of its segment. Once two
   counts fall off the same side, the clock itself is suspected: if the counts agree with the
   other counts of their segments (a clock, not a wrong count), the period's prior bracket is
   widened to take in the rates they show, up to :data:`MAX_CLOCK_ADAPT`, and the stream goes
   on with timestamps measured from the counts (the fault log says how fast or slow the clock
   runs); if not, every timestamp is flagged. The samples' own plausibility is reported by
   :func:`sensor_check`. What none of this can see is listed
   in the device guide ("What the driver cannot detect").
"""

from __future__ import annotations

import errno
import logging
import math
from array import array
from dataclasses import asdict, dataclass

import numpy as np

from .._validate import check_int, check_real
from ..chips.mpu6050 import (
    ACCEL_SAMPLE_BYTES,
    CHIP_MODELS,
    USER_CONTROL_SELF_CLEARING,
    FifoEnable,
    Interrupt,
    Register,
    UserControl,
)
from ..recording import Recording
from .i2c import SMBUS_BLOCK_MAX, I2CError, SettingError
from .timing import CLOCK_TOLERANCE, PeriodEstimator

__all__ = ["PeriodEstimator", "StreamFault", "FifoBlock", "FifoStream", "CLOCK_TOLERANCE",
           "MAX_CLOCK_ADAPT", "REFUSE_AFTER", "sensor_check", "PARITY_MIN_NOISE_LSB",
           "PREDICTOR_ORDER", "ODD_SHARE_LIMIT", "PARITY_BLOCK", "PARITY_FALSE_ALARM",
           "MIN_PARITY_READINGS", "STOLEN_SHARE_COVERED", "FIFO_RESET_ATTEMPTS"]

logger = logging.getLogger(__name__)

#: Longest SMBus chunk that holds whole samples (30 bytes: 5 samples).
FIFO_CHUNK = (SMBUS_BLOCK_MAX // ACCEL_SAMPLE_BYTES) * ACCEL_SAMPLE_BYTES
#: Writes of ``USER_CTRL.FIFO_RESET`` one restart makes before it fails: each is confirmed by a
#: count of 0 read before the FIFO is enabled again (``FifoStream._reset_fifo``). A reset
#: lost once (a bit that did not act, a ``USER_CTRL.FIFO_EN`` the silicon still saw set) or a
#: count read wrong once is made good by the next; three in a row is a chip that does not reset.
FIFO_RESET_ATTEMPTS = 3
#: A chip is asked whether it was reset when this many samples were due and none came.
QUIET_SAMPLES = 3
#: Counts off the same side of the clock's tolerance after which the clock itself is suspected
#: (one can be a count read wrong; two on one side point at the clock).
CLOCK_SUSPECT_AFTER = 2
#: Largest error of the sample clock the stream adapts to, relative to the nominal rate. A
#: part whose counts agree on a rate further off is not sampling as configured (an
#: MPU-6500-family clone at 8 kHz, a divider that did not land): the stream refuses it, naming
#: the rate, and keeps nothing more (``FifoStream.clock_refused``).
MAX_CLOCK_ADAPT = 0.5
#: How far, relative, samples taken unseen by another reader (whole samples between drains, a
#: few at a time: a clock that much slower, as far as the counts can tell) may raise the low end
#: of the period's bracket while every stated timestamp uncertainty still holds
#: (``FifoStream._drain_covered``): one sample in a hundred over the stretch of counts that sets
#: that end. A reader taking more is covered only if the bracket's other counts bound the period.
STOLEN_SHARE_COVERED = 0.01
#: Counts in a row, no drain kept between them, that must agree on a rate beyond
#: :data:`MAX_CLOCK_ADAPT` before the stream refuses the clock: a corrupted count shows such a
#: rate once, a part sampling at another rate at every count.
REFUSE_AFTER = 3
#: The FIFO sizes of the parts driven, bytes. A count equal to a smaller one than the chip's own
#: is a full FIFO of a part with that FIFO answering this part's ``WHO_AM_I`` (512 bytes: an
#: MPU-6500-family clone answering 0x68), not bytes taken by another reader, although it is not
#: a whole number of samples.
FIFO_SIZES = frozenset(model.fifo_size for model in CHIP_MODELS.values())
#: The gyroscope's rate, which an MPU-6500-family part samples at with ``DLPF_CFG = 0``, Hz.
CLONE_RATE = 8000.0


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
        What the driver did ("restart", "reconfigure", "wait", "reset again", "adapt",
        "stop").
    """

    time: float
    cause: str
    action: str

    def __post_init__(self):
        check_real("time", self.time)
        for name in ("cause", "action"):
            if not isinstance(getattr(self, name), str):
                raise TypeError(f"{name} must be a str, got {type(getattr(self, name)).__name__}")

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

    def __post_init__(self):
        index, counts = self.index, self.counts
        if not (isinstance(index, np.ndarray) and index.ndim == 1 and index.dtype.kind in "iu"):
            raise TypeError(f"index must be a 1-D integer array of slots, got "
                            f"{getattr(index, 'shape', type(index).__name__)}")
        if not (isinstance(counts, np.ndarray) and counts.ndim == 2 and counts.shape[1] == 3
                and counts.dtype.kind in "iu"):
            raise TypeError(f"counts must be an (n, 3) integer array, got "
                            f"{getattr(counts, 'shape', type(counts).__name__)}")
        if index.size != counts.shape[0]:
            raise ValueError(f"index must give one slot per sample ({counts.shape[0]}), got "
                             f"{index.size}")
        check_int("lost", self.lost, minimum=0)


def _empty_block(lost: int = 0) -> FifoBlock:
    return FifoBlock(np.empty(0, np.int64), np.empty((0, 3), np.int16), lost)


def _as_i2c_error(exc: OSError) -> I2CError:
    """Every ``OSError`` of the FIFO path as an :class:`I2CError` (an unknown errno included),
    so that one failure path handles them all."""
    if isinstance(exc, I2CError):
        return exc
    return I2CError(exc.errno, f"{type(exc).__name__}: {exc.strerror or exc}")


def _cause(exc: OSError) -> str:
    return f"bus error ({exc.strerror or exc})"


class FifoStream:
    """A running FIFO stream of one :class:`~ebantenna.device.mpu6050.MPU6050`.

    Made by :meth:`~ebantenna.device.mpu6050.MPU6050.start_fifo`; see the module notes for the rules
    it follows.
    """

    def __init__(self, mpu):
        if not all(callable(getattr(mpu, name, None))
                   for name in ("fifo_count", "configure", "configuration_lost", "decode")):
            raise TypeError(f"mpu must be an MPU6050, got {type(mpu).__name__}")
        self.mpu = mpu
        self.device = mpu.device
        self.clock = mpu.clock
        self.fifo_size = mpu.fifo_size
        self.estimator = PeriodEstimator(1.0 / mpu.config.fs)
        self.faults: list[StreamFault] = []
        self.starts: list[float] = []  # host time each segment started (its enable write ended)
        self.offsets: list[int] = []  # slot of each segment's first sample
        self.delivered: list[int] = []  # samples kept from each segment
        # per kept drain, as compact arrays (a recording's memory per sample is budgeted)
        self.drain_times = array("d")  # host time its count was read (ended)
        self.drain_sizes = array("q")
        self._segment, self._position, self._slot, self._counts = [], [], [], []
        # each kept drain's own count, as (position of the newest sample the FIFO held when it
        # was read, when its read began): with drain_times (when it ended), the anchor of the
        # drain's samples (_anchored)
        self._anchor = array("d")
        self.next_slot = 0
        self.overflows = 0
        self.discarded = 0  # samples read but dropped: their drain could not be confirmed
        self.resets_unconfirmed = 0  # FIFO resets after which the FIFO was not empty
        self.foreign = 0  # drains dropped because another reader took bytes from the FIFO
        self.suspect: set[int] = set()  # segments whose timestamps are flagged (_suspect)
        self.contradictions = {"more": 0, "fewer": 0}  # counts off the tolerance, by side
        # what the contradicting counts showed of the period with their segments' observations
        # (when they agree with each other and lie within MAX_CLOCK_ADAPT), by side: how many,
        # the hull and the common part of their brackets, the foreign reads they were blamed
        # on, the last one's count and time since its segment began; what the clock is adapted
        # to (_adapt). A fixed size, whatever the number of counts.
        self.clock_seen = {side: _seen_record() for side in ("more", "fewer")}
        # the same for brackets wholly beyond MAX_CLOCK_ADAPT, in a row on one side (a drain
        # kept breaks the row): what _refuse decides from
        self._beyond = _seen_record(side=None)
        self.clock_adapted = False  # the period's prior bracket took in what the counts showed
        #: The least rate a FIFO found full too soon showed, Hz (0 until one did, and again
        #: once counts bracket the rate, ``_adapt``, or the chip is configured again).
        self.rate_at_least = 0.0
        #: Why the stream refuses the chip's clock (a rate beyond MAX_CLOCK_ADAPT), or None.
        self.clock_refused: str | None = None
        self._last_times = (0.0, 0.0)
        self.pending: str | None = "start"
        self.unconfigured = False  # a reset chip whose configuration is not written back yet
        self.last_progress = self.clock.monotonic()
        self._try_restart()

    @property
    def clock_suspect(self) -> bool:
        """Whether counts fell off the same side of the clock's tolerance more than once: the
        clock itself is then likely outside it. Unless the stream adapted to the rate the
        counts showed (``clock_adapted``), every timestamp of the stream is then flagged
        (each segment's bracket rests on the tolerance)."""
        return max(self.contradictions.values()) >= CLOCK_SUSPECT_AFTER

    @property
    def timing_flagged_all(self) -> bool:
        """Whether every timestamp is flagged: the clock is suspected and the stream could not
        adapt to it (the counts disagree with each other, or show a rate beyond
        :data:`MAX_CLOCK_ADAPT`)."""
        return self.clock_suspect and not self.clock_adapted

    @property
    def counts_rejected(self) -> int:
        """FIFO counts rejected as impossible (see :class:`PeriodEstimator`)."""
        return self.estimator.rejected

    # -- restarting ------------------------------------------------------------------------
    def _note(self, cause: str, action: str) -> None:
        self.faults.append(StreamFault(self.clock.monotonic(), cause, action))
        logger.warning("MPU-6050 FIFO: %s; %s", cause, action)

    def _restart(self) -> None:
        """Empty the FIFO and start a new segment (raises :class:`I2CError` if the bus fails)."""
        device = self.device
        self.mpu.write_verified(Register.FIFO_EN, 0)
        self._reset_fifo()
        device.read_byte(Register.INT_STATUS)  # clears a stale overflow flag (RM 58)
        self.mpu.write_verified(Register.FIFO_EN, FifoEnable.ACCEL)
        before = self.clock.monotonic()
        device.write_byte(Register.USER_CTRL, UserControl.FIFO_EN, retry=False)
        start = self.clock.monotonic()  # the write landed at its last acknowledge, just before
        seen = device.read_byte(Register.USER_CTRL)  # read back: the segment starts only if
        stable = 0xFF & ~int(USER_CONTROL_SELF_CLEARING)  # the write landed whole (every bit
        if seen & stable != UserControl.FIFO_EN & stable:  # but the self-clearing resets)
            raise SettingError(errno.EIO, f"USER_CTRL (0x6A) reads back 0x{seen:02X} after "
                               f"0x{int(UserControl.FIFO_EN):02X} was written")
        period = self.estimator.period
        if self.starts:
            offset = max(round((start - self.starts[0]) / period), self.next_slot)
        else:
            offset = 0
        self.estimator.begin(before=before, after=start)
        self.starts.append(start)
        self.offsets.append(offset)
        self.delivered.append(0)
        self.pending = None

    def _reset_fifo(self) -> None:
        """Empty the FIFO (``USER_CTRL.FIFO_RESET``) and confirm it from ``FIFO_COUNT``.

        The reset bit clears itself (RM 106), so the read-back of ``USER_CTRL`` cannot tell
        whether the reset acted; what it leaves can be read. ``FIFO_EN`` (register 35) and
        ``USER_CTRL.FIFO_EN`` are both 0 from the reset until the FIFO is enabled again, so no
        sample can enter: the count read in between must be 0. One that is not (a reset that
        did not act, or a count read wrong) is counted in ``resets_unconfirmed``, noted in the
        fault log and the reset made again, :data:`FIFO_RESET_ATTEMPTS` times in all.

        Raises
        ------
        SettingError
            When the FIFO is still not empty after the last reset (the restart fails: what the
            FIFO holds is never read as a sample of a new segment).
        """
        for _ in range(FIFO_RESET_ATTEMPTS):
            # FIFO_RESET only acts while USER_CTRL.FIFO_EN is 0 (RM 106): this write clears it
            self.mpu.write_verified(Register.USER_CTRL, UserControl.FIFO_RESET)
            count = self.mpu.fifo_count()
            if count == 0:
                return
            self.resets_unconfirmed += 1
            self._note(f"FIFO_COUNT reads {count} bytes after USER_CTRL.FIFO_RESET with the FIFO "
                       "disabled: the reset did not act (or the count was read wrong)",
                       "reset again")
        raise SettingError(
            errno.EIO, f"the FIFO still holds {count} bytes after USER_CTRL.FIFO_RESET (0x6A = "
            f"0x{int(UserControl.FIFO_RESET):02X}) was written {FIFO_RESET_ATTEMPTS} times with "
            "the FIFO disabled: the chip does not reset its FIFO (or FIFO_COUNT reads wrong)")

    def _try_restart(self) -> None:
        try:
            self._restart()
        except OSError as exc:
            exc = _as_i2c_error(exc)
            self._note(f"restart failed ({exc.strerror or exc})", "wait")

    # -- draining --------------------------------------------------------------------------
    def _quiet(self, now: float) -> FifoBlock:
        """An empty FIFO: fine unless samples are overdue; then find out why and recover."""
        due = (now - self.starts[-1]) / self.estimator.period - self.delivered[-1]
        if due < QUIET_SAMPLES:
            return _empty_block()
        return self._diagnose("no samples from the FIFO")

    def _diagnose(self, cause: str) -> FifoBlock:
        """A count that cannot be trusted, or a quiet FIFO: read the settings back; a changed
        one is named (from what to what) and the chip reconfigured, else ``cause`` restarts."""
        try:
            why = self.mpu.configuration_lost(streaming=True)
        except OSError as exc:
            return self._fail(_cause(_as_i2c_error(exc)))
        if why is not None:
            return self._fail(f"{why} ({cause.split('; is this')[0]})", reconfigure=True)
        return self._fail(cause)

    def _rate_seen(self, count: int, after: float, verdict: str) -> str:
        """What a count says about the rate: ``"N bytes (n samples) X ms after the FIFO was
        started: a rate of R Hz, not F Hz"``, with a hint when the rate is a part's known one."""
        fs = 1.0 / self.estimator.nominal
        since = after - self.starts[-1]
        samples = self.delivered[-1] + count / ACCEL_SAMPLE_BYTES
        if since <= 0:
            return f"FIFO count {count} {verdict}"
        rate = samples / since
        text = (f"FIFO count {count} {verdict} ({samples:g} samples in {1e3 * since:.1f} ms "
                f"since the FIFO was started: a rate of {_hz(rate)}, not {_hz(fs)})")
        if self._clone_possible() and abs(rate / CLONE_RATE - 1) < 0.2:
            text += _CLONE_HINT
        return text

    def _clone_possible(self) -> bool:
        """Whether the part, driven as an MPU-6050 below 8 kHz, may be an MPU-6500-family
        clone (whose FIFO is smaller)."""
        return self.fifo_size > min(FIFO_SIZES) and 1.0 / self.estimator.nominal < CLONE_RATE

    def _full(self, count: int) -> bool:
        """Whether ``count`` says the FIFO is full: the FIFO's size, or a smaller part's FIFO
        size that is not whole samples (:data:`FIFO_SIZES`)."""
        return count == self.fifo_size or (
            count in FIFO_SIZES and count < self.fifo_size and count % ACCEL_SAMPLE_BYTES != 0)

    def _trusted_count(self) -> tuple[int | None, tuple | None, str | None]:
        """Read ``FIFO_COUNT`` and check it before any data is read (rule 1 of the module notes).

        Returns the bytes to read (None when the count cannot be trusted), the observation
        ``(produced, before, after)`` it makes for the :class:`PeriodEstimator`, and why it was
        refused (None when it was not).
        """
        before = self.clock.monotonic()
        count = self.mpu.fifo_count()
        after = self.clock.monotonic()
        self._last_times = (before, after)
        if count > self.fifo_size:
            self.estimator.rejected += 1
            logger.warning("MPU-6050 FIFO: a count of %d bytes exceeds the FIFO's %d; rejected",
                           count, self.fifo_size)
            return None, None, f"FIFO count {count} exceeds the FIFO's {self.fifo_size} bytes"
        if self._full(count):  # before the whole-sample check: a clone's full FIFO is not
            return count, None, "overflow"  # a foreign read
        if count % ACCEL_SAMPLE_BYTES:  # the driver reads whole samples: someone else read
            self.foreign += 1
            return None, None, self._rate_seen(
                count, after, "is not a whole number of samples: another program read part of "
                "a sample (i2cget, i2cdump, a second driver), or the count was read wrong")
        produced = self.delivered[-1] + count // ACCEL_SAMPLE_BYTES
        if count and not self.estimator.check(produced=produced, before=before, after=after):
            self._suspect()
            return None, None, self._rate_seen(count, after, f"is {self._impossible(produced)}")
        return count, (produced, before, after), None

    def _suspect(self) -> None:
        """A count of the current segment contradicts the clock's tolerance: a clock outside
        it, a count read wrong, or another reader. The timestamps of the samples the segment
        kept rest on that tolerance: they are flagged (``samples_timing_suspect``)."""
        seg = len(self.starts) - 1
        if seg not in self.estimator.excluded:
            self.estimator.forget(seg)
        if self.delivered[seg] and seg not in self.suspect:
            self.suspect.add(seg)
            logger.warning("MPU-6050 FIFO: the timestamps of the %d samples of FIFO segment %d "
                           "are flagged: its counts contradict the clock's tolerance",
                           self.delivered[seg], seg)

    def _contradicted(self, fewer: bool, extra: list, *, foreign: bool = False) -> None:
        """A count of the current segment contradicts the period's bracket, on the side
        ``fewer`` says; ``extra`` are the observations ``(n, before, after)`` that contradict,
        newest last; ``foreign`` says whether it was counted as a foreign read.

        What the segment's observations and ``extra`` show of the period alone (no prior) is
        kept when they agree with each other and bound it on both sides, as it is (a bracket
        clipped to a limit would no longer hold the truth). When it reaches within
        :data:`MAX_CLOCK_ADAPT` of the nominal rate, after :data:`CLOCK_SUSPECT_AFTER` such
        counts on one side the stream adapts to the clock (:meth:`_adapt`). When it lies wholly
        beyond, and :data:`REFUSE_AFTER` such counts in a row, with no drain kept between them,
        agree on one rate, the stream refuses the clock (:meth:`_refuse`): a part sampling at
        another rate shows it at every count, a corrupted count once. Counts that disagree with
        each other are a count read wrong or a reader that took samples, not a clock."""
        side = "fewer" if fewer else "more"
        self.contradictions[side] += 1
        est = self.estimator
        low, high = est._seen(extra)
        cap_low = est.nominal / (1.0 + MAX_CLOCK_ADAPT)
        cap_high = est.nominal / (1.0 - MAX_CLOCK_ADAPT)
        beyond = low < high and (high <= cap_low or low >= cap_high)
        if not (beyond or 0.0 < low < high < math.inf):
            return  # they disagree, or bound the period from one side only within the limit
        seen = self._beyond if beyond else self.clock_seen[side]
        if beyond and seen["side"] != side:  # the other side's run is broken
            seen.update(_seen_record(), side=side)
        n, _, after = extra[-1]
        seen["counts"] += 1
        seen["hull"] = min(seen["hull"][0], low), max(seen["hull"][1], high)
        seen["common"] = max(seen["common"][0], low), min(seen["common"][1], high)
        seen["blamed"] += foreign
        seen["last"] = (n, after - self.starts[-1])
        if self.clock_refused is not None:
            return
        if not beyond:
            if seen["counts"] >= CLOCK_SUSPECT_AFTER:
                self._adapt(side)
        elif seen["counts"] >= REFUSE_AFTER and seen["common"][0] < seen["common"][1]:
            self._refuse()

    def _rate_text(self, seen: dict) -> tuple[str, float]:
        """What the counts recorded in ``seen`` (a :func:`_seen_record`) showed, as a sentence
        (samples since the FIFO started, the rate's bracket against the nominal one), and the
        clock's error there, %."""
        est = self.estimator
        common = seen["common"]
        p_low, p_high = common if common[0] < common[1] else seen["hull"]
        fs = 1.0 / est.nominal
        produced, since = seen["last"]
        if p_low <= 0.0:  # full FIFOs: they bound the rate from below only
            error = 100 * (1 / (p_high * fs) - 1)
            return (f"the FIFO was full {1e3 * since:.1f} ms after it was started ({produced} "
                    f"samples or more): its clock runs at least {error:.1f} % fast (a rate of "
                    f"at least {_hz(1 / p_high)}, not {_hz(fs)})"), error
        error = 50 * (1 / (p_high * fs) + 1 / (p_low * fs) - 2)  # %, the rate's middle
        runs = f"{abs(error):.1f} % {'slow' if error < 0 else 'fast'}"
        return (f"the chip produced {produced} samples in {1e3 * since:.1f} ms since the FIFO "
                f"was started: its clock runs {runs} (a rate between {_hz(1 / p_high)} and "
                f"{_hz(1 / p_low)}, not {_hz(fs)})"), error

    def _refuse(self) -> None:
        """The counts agree on a rate beyond :data:`MAX_CLOCK_ADAPT` of the nominal one: the
        part is not sampling as configured. The period's prior takes in what they showed, so
        that the samples kept so far state timestamps that hold (all flagged, the clock not
        being adapted to), and the stream keeps nothing more (``clock_refused``; the watchdog
        ends the run with it at once). Full FIFOs show a least rate only: the prior is then
        left as it is (every kept timestamp is flagged all the same)."""
        hull = self._beyond["hull"]
        if hull[0] > 0.0:
            self.estimator.widen(*hull)
        text, _ = self._rate_text(self._beyond)
        common = self._beyond["common"]
        p_low, p_high = common if common[0] < common[1] else hull
        # the rates the counts allow, 20 % wider (a clone's clock is 8 kHz give or take that)
        clone = 0.8 * CLONE_RATE * p_low <= 1.0 and 1.2 * CLONE_RATE * p_high >= 1.0
        hint = ("; an MPU-6500-family clone answering WHO_AM_I 0x68 samples at 8 kHz with "
                "DLPF_CFG = 0" if clone and self._clone_possible() else "")
        self.clock_refused = (
            f"{text}: beyond the {100 * MAX_CLOCK_ADAPT:g} % the driver adapts to, the part is "
            f"not sampling as configured (a divider or filter setting that did not land, a "
            f"part of another family{hint}); no more samples are kept")
        self._note(self.clock_refused, "stop")

    def _adapt(self, side: str) -> None:
        """Let the period's prior take in every bracket the counts of ``side`` showed, so that
        the stream goes on with timestamps whose stated uncertainty holds the true period; say
        what was seen. Foreign reads those counts were blamed on go back to the clock."""
        est = self.estimator
        seen = self.clock_seen[side]
        low, high = seen["hull"]
        if est.prior[0] <= low and high <= est.prior[1]:
            return  # the prior holds them: they contradict other segments' counts, not it
        est.widen(low, high)
        self.clock_adapted = True
        if side == "more":  # counts now bracket the fast clock: the prior holds its rate
            self.rate_at_least = 0.0
        self.foreign -= seen["blamed"]
        seen["blamed"] = 0
        text, _ = self._rate_text(seen)
        self._note(
            f"{text}, outside the {100 * est.tolerance:g} % tolerance; the period's bracket "
            f"takes that rate in ({1e3 * est.low:.4g} to {1e3 * est.high:.4g} ms) and narrows "
            "with the counts", "adapt")

    def _impossible(self, produced: int) -> str:
        """Which side of the rate's bracket an impossible count lies on."""
        low, _ = self.estimator.bounds(produced, *self._last_times)
        fewer = low >= self.estimator.high  # the count needs a longer period than allowed
        self._contradicted(fewer, [(produced, *self._last_times)])
        if fewer:
            return ("fewer than the chip must have produced (its clock slower than the "
                    f"{100 * self.estimator.tolerance:g} % tolerance, or another program read "
                    "the FIFO)")
        return ("more than the chip can have produced (its clock faster than the "
                f"{100 * self.estimator.tolerance:g} % tolerance, or a corrupted count)")

    def _overflow_seen(self, count: int) -> str:
        """A full FIFO at the count just read (``count``: the FIFO's size, or a smaller part's,
        :meth:`_full`): the chip had produced at least the samples it holds since the segment
        began. Sooner than any period in the bracket allows, that is a count
        on the fast side of the clock's tolerance (an observation "``n`` samples by ``after``",
        nothing said of ``before``), so that a clock too fast to be drained in time is still
        measured and adapted to (:meth:`_contradicted`) instead of overflowing every poll; full
        sooner than a clock :data:`MAX_CLOCK_ADAPT` fast can fill it, it counts towards the
        refusal (an MPU-6500-family clone at 8 kHz)."""
        after = self._last_times[1]
        produced = self.delivered[-1] + count // ACCEL_SAMPLE_BYTES
        observation = (produced, -math.inf, after)
        low, high = self.estimator.bounds(*observation)
        full, hint = "FIFO full (overflow)", ""
        if count != self.fifo_size:
            full = f"FIFO count {count}, the FIFO size of the MPU-6500 family: a full FIFO"
            hint = _CLONE_HINT
        if low < high:
            return full + hint
        self._contradicted(False, [observation])
        # a full FIFO bounds the rate from below only: too little to adapt the timestamps to,
        # enough for the poll to follow (MPU6050.fastest_rate), until drains that do not
        # overflow bracket the rate on both sides
        self.rate_at_least = max(self.rate_at_least, 1.0 / self.estimator._seen([observation])[1])
        return (f"{full}, {1e3 * (after - self.starts[-1]):.1f} ms after the FIFO "
                f"was started: sooner than the chip can fill it at the "
                f"{100 * self.estimator.tolerance:g} % tolerance (its clock runs fast){hint}")

    def drain(self) -> FifoBlock:
        """Drain every whole sample waiting; on any fault restart and return what was kept."""
        if self.clock_refused is not None:  # a part not sampling as configured: nothing kept
            return _empty_block()
        if self.unconfigured:  # never restart a chip whose rate and range are not set again
            self._try_configure()
            if self.unconfigured:
                return _empty_block()
        if self.pending is not None:
            self._try_restart()
            if self.pending is not None:
                return _empty_block()
        try:
            count, observed, refused = self._trusted_count()
        except OSError as exc:
            return self._fail(_cause(_as_i2c_error(exc)))
        if refused == "overflow":
            return self._fail(self._overflow_seen(count), overflow=True)
        if refused is not None:
            return self._diagnose(refused)
        if count == 0:
            return self._quiet(observed[2])
        return self._drain_data(count, observed)

    def _drain_data(self, count: int, observed: tuple) -> FifoBlock:
        """Read ``count`` bytes of samples, confirm them from the settings read back and the
        count after the drain, keep them."""
        raw, broken = self._read_data(count)
        n = len(raw) // ACCEL_SAMPLE_BYTES
        try:
            # every setting and INT_STATUS: a register changed since the last drain costs this
            # drain, never more (a chip reset during the drain would have emptied the FIFO, and
            # the data port then reads filler bytes)
            seen, status = self.mpu.read_registers()
            before = self.clock.monotonic()
            # after a failed transfer the count cannot be placed in time (what the transfer took
            # is unknown), but it must still be whole samples: a reader that took part of one
            # between the count and the data has shifted the chunks kept before the failure
            after_count = self.mpu.fifo_count()
            after = self.clock.monotonic()
        except OSError as exc:
            return self._fail(_cause(_as_i2c_error(exc)), discarded=n)
        changed = self.mpu._changed_registers(seen)
        if changed:
            overflow = bool(status & Interrupt.FIFO_OFLOW)
            return self._fail(self.mpu._describe_changes(changed), reconfigure=True, discarded=n,
                              overflow=overflow)
        if status & Interrupt.FIFO_OFLOW:
            return self._fail("FIFO overflow", overflow=True, discarded=n)
        foreign = self._check_after(observed, n, after_count, before, after, broken is not None)
        if foreign is not None:  # a full FIFO is counted with the overflows
            return self._fail(foreign, discarded=n, overflow=self._full(after_count))
        block = self._keep(raw, observed)
        if broken is None and after_count < self.fifo_size:  # one more observation of the clock
            self.estimator.add(produced=self.delivered[-1] + after_count // ACCEL_SAMPLE_BYTES,
                               before=before, after=after)
        if broken is not None:  # the whole chunks before the failed transfer are kept
            self._fail(_cause(broken))
        return block

    def _check_after(self, observed, n: int, count: int, before: float, after: float,
                     broken: bool) -> str | None:
        """Why the count read after a drain shows that the drain's bytes were not the ones
        counted (another program read the FIFO), or None. ``count`` bytes waited after ``n``
        samples were read; they must be whole samples, and with the count before the drain
        they must be a number the chip can have produced by then.

        After a failed transfer (``broken``) what that transfer took out of the FIFO is unknown,
        so only two things are judged: the count must still be whole samples (a reader that
        took part of one between the count and the data has shifted the chunks kept before the
        failure), and it may not claim more samples than the chip can have produced even if the
        failed transfer took nothing. Fewer samples than expected say nothing there: whole
        samples taken by another reader cannot be told from the failed transfer's.

        A count that cannot be judged confirms nothing, and the drain is dropped: one above the
        FIFO's size (read wrong: no chip makes it), and a full FIFO, which may have overflowed
        during the drain (an overflow moves the FIFO's head by any number of bytes, and its flag
        in ``INT_STATUS`` is gone if another program read that register first)."""
        if count > self.fifo_size:  # a corrupted count: no reader can make it
            self.estimator.rejected += 1
            logger.warning("MPU-6050 FIFO: a count of %d bytes after the drain exceeds the "
                           "FIFO's %d; rejected", count, self.fifo_size)
            return (f"the FIFO count after the drain, {count}, exceeds the FIFO's "
                    f"{self.fifo_size} bytes (a count read wrong): nothing confirms the drain, "
                    "which is dropped")
        if self._full(count):
            return (f"the FIFO is full after the drain ({count} bytes): it may have overflowed "
                    "during the drain, which moves its head, and nothing confirms the drain, "
                    "which is dropped")
        if count % ACCEL_SAMPLE_BYTES and not broken:
            self.foreign += 1
            return (f"the FIFO count after the drain, {count}, is not a whole number of samples: "
                    "another program read bytes from the FIFO (i2cget, i2cdump, a second "
                    "driver); the drain is dropped")
        produced, b1, a1 = observed
        total = self.delivered[-1] + n + count // ACCEL_SAMPLE_BYTES
        est = self.estimator
        low, high = est.bounds(produced, b1, a1)
        if low < high:
            saved = est.low, est.high
            est.low, est.high = low, high
            est.segments[-1].append((produced, b1, a1))
            possible = est.bounds(total, before, after)
            est.segments[-1].pop()
            est.low, est.high = saved
            if possible[0] < possible[1]:
                return _shifted(count) if broken else None
            fewer = possible[0] >= est.high  # it needs a longer period than allowed
        else:
            fewer = low >= est.high
        if broken and fewer:  # the failed transfer may have taken the samples missing
            return _shifted(count)
        est.rejected += 1
        self._suspect()
        self.foreign += fewer
        self._contradicted(fewer, [observed, (total, before, after)], foreign=fewer)
        logger.warning("MPU-6050 FIFO: a count of %d bytes after the drain does not follow from "
                       "the %d samples before it; rejected", count, produced - self.delivered[-1])
        why = ("fewer samples than the clock's tolerance allows: another program read samples "
               "from the FIFO, or the clock is slower than the tolerance" if fewer else
               "more samples than the clock's tolerance allows: the clock is faster than the "
               "tolerance, or a count was read wrong")
        return (f"the FIFO count after the drain, {count}, does not follow from the one before "
                f"it ({produced - self.delivered[-1]} samples): {why}; the drain is dropped")

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
            except OSError as exc:
                return bytes(raw), _as_i2c_error(exc)
        return bytes(raw), None

    def _fail(self, cause: str, *, overflow: bool = False, reconfigure: bool = False,
              discarded: int = 0):
        self.overflows += overflow
        self.discarded += discarded
        if discarded:
            cause += f" ({discarded} samples read and discarded)"
        self.pending = cause
        if self.clock_refused is not None:  # nothing more is kept: no restart
            self._note(cause, "stop")
            return _empty_block()
        if reconfigure:
            self._note(cause, "reconfigure")
            # what a full FIFO showed was at the settings that changed: forgotten
            self.rate_at_least = 0.0
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
        except OSError as exc:
            exc = _as_i2c_error(exc)
            self._note(f"reconfigure failed ({exc.strerror or exc})", "wait")
        else:
            self.unconfigured = False

    def _keep(self, raw: bytes, observed: tuple) -> FifoBlock:
        """Keep the samples of ``raw``; ``observed`` is the drain's count, now confirmed by the
        status registers, as ``(produced, before, after)`` for the period estimate."""
        seg = len(self.starts) - 1
        first = self.delivered[seg]
        produced, before, after = observed
        self.estimator.add(produced=produced, before=before, after=after)
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
        self._anchor.extend((produced - 1, before))
        self.delivered[seg] += n
        self._beyond.update(_seen_record(side=None))  # a drain kept: no run of refusals
        self.next_slot = int(slots[-1]) + 1
        self.last_progress = after
        self.drain_times.append(after)
        self.drain_sizes.append(n)
        return FifoBlock(slots, counts, lost)

    def host_time(self, slot: int) -> float:
        """Host time at which the sample in ``slot`` of the current segment was taken, s."""
        slot = check_int("slot", slot, minimum=0)
        seg = len(self.starts) - 1
        j = slot - self.offsets[seg]
        t0, _ = self.estimator.timestamps(seg, max(j, 0))
        return t0 + j * self.estimator.period

    # -- what was kept ---------------------------------------------------------------------
    @property
    def samples_read(self) -> int:
        """Samples kept so far."""
        return int(sum(self.delivered))

    def segment_timing(self) -> tuple[np.ndarray, np.ndarray]:
        """For every segment: the estimated host time of its sample 0 (s, from the stream's
        first segment start) and the uncertainty of its kept timestamps (s; 0 for a segment
        with none kept); see :meth:`PeriodEstimator.timestamps`."""
        first = np.zeros(len(self.starts))
        uncertainty = np.zeros(len(self.starts))
        for seg, n in enumerate(self.delivered):
            t0, u = self.estimator.timestamps(seg, max(n - 1, 0))
            first[seg] = t0 - self.starts[0]
            uncertainty[seg] = u if n else 0.0
        return first, uncertainty

    def kept(self, first: int = 0, stop: int | None = None) -> dict:
        """The kept samples with slots in ``[first, stop)``: arrays ``slot``, ``segment``,
        ``position`` (within the segment), ``counts``, ``time`` (s, estimated, from the stream's
        first segment start), ``uncertainty`` (s: how far ``time`` can be from the truth, even
        with samples taken unseen by another reader, see ``_drain_covered``),
        ``uncertainty_sole_reader`` (s: the same when no other program reads the FIFO: that of
        the sample's segment, widened for a flagged one, see ``_anchored``) and ``suspect``
        (its timestamp flagged)."""
        first = check_int("first", first, minimum=0)
        if stop is not None:
            stop = check_int("stop", stop, minimum=first)
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
        anchor = np.column_stack([np.frombuffer(self._anchor, np.float64).reshape(-1, 2),
                                  np.frombuffer(self.drain_times, np.float64)])
        out["anchor"] = np.repeat(anchor, [len(c) for c in self._counts], axis=0)
        stop = self.next_slot if stop is None else stop
        keep = (out["slot"] >= first) & (out["slot"] < stop)
        out = {k: v[keep] for k, v in out.items()}
        if self.starts:
            t0, uncertainty = self.segment_timing()
        else:
            t0 = uncertainty = np.zeros(1)
        out["time"] = t0[out["segment"]] + out["position"] * self.estimator.period
        out["uncertainty"] = uncertainty[out["segment"]]
        out["suspect"] = (np.ones(out["segment"].shape, bool) if self.timing_flagged_all else
                          np.isin(out["segment"], sorted(self.suspect)))
        if out["suspect"].any():
            self._anchored(out)
        out["uncertainty_sole_reader"] = out["uncertainty"]
        if out["slot"].size:
            self._drain_covered(out)
        del out["anchor"]
        return out

    def _drain_covered(self, out: dict) -> None:
        """Widen every timestamp's uncertainty to reach its drain's anchor, so that it holds
        whatever single samples another reader took unseen (see
        :data:`STOLEN_SHARE_COVERED` for the limit).

        A reader that takes whole samples from the FIFO between drains, a few at a time, makes
        the segment's later counts short: a clock that slow, as far as the counts can tell
        (``k`` samples taken in ``N`` is a clock ``k / N`` slower), and the segment's grid
        then runs through its observations at the wrong slope, off the true times between them
        by up to a period. What no such reader can mislead is the drain's own anchor: when the
        drain's count was read (between ``b`` and ``a``), the newest of the samples the FIFO
        held was taken in ``(b - T, a]`` (its successor was not yet there), and the sample
        ``k`` before it ``k`` periods earlier (a reader takes the oldest bytes, so the FIFO's
        samples stay consecutive). One more period is allowed after ``a``: a sample taken
        between the count and the data, which the count after the data need not reveal, makes
        the drain's newest sample the one after.

        Stolen samples make counts short, which biases the bracket's *low* end up, never the
        high end: a pair's upper bound on ``T`` counts the periods between a sample not yet
        there at one count and one there by a later count, and a take only adds periods
        between them. So ``T`` is taken in ``[low / (1 + STOLEN_SHARE_COVERED), high]``, no
        lower than the prior. The timestamp stays on its segment's grid; only its uncertainty
        grows, to reach both ends of the anchor's interval: one to two periods, plus the
        drain's samples times the covered share of one.
        """
        est = self.estimator
        t_high = est.high
        t_low = max(est.prior[0], est.low / (1.0 + STOLEN_SHARE_COVERED))
        origin = self.starts[0]
        newest, b, a = out["anchor"].T
        k = newest - out["position"]
        lo = b - origin - (k + 1) * t_high
        hi = a - origin - (k - 1) * t_low  # a period later: one sample taken mid-drain
        time = out["time"]
        out["uncertainty"] = np.maximum(out["uncertainty"], np.maximum(time - lo, hi - time))

    def _anchored(self, out: dict) -> None:
        """Timestamps of flagged samples that hold whatever contradicted their segment.

        A flagged segment's counts contradict each other: samples taken by another reader
        (every later position of the segment is then that many samples late), or a count read
        low (its own observation false). Either way the segment's timestamps, which rest on all
        its counts and on its positions, can be wrong by whole periods. Each flagged sample
        is given the hull of three intervals, one of which holds its true time in each case:
        its segment's timestamp and uncertainty; the *enable's* anchor (the segment began
        between ``before`` and ``after`` of its enable, its first sample at most a period
        later: ``t_j`` in ``(b0 + j T_low, a0 + (j + 1) T_high]``), which no count can
        mislead; and its *drain's* anchor (the newest of the ``n`` samples the FIFO held when
        the drain's count was read, between ``b`` and ``a``, was taken in ``(b - T, a]``; the
        sample ``k`` before it ``k`` periods earlier; one more period of slack for a count read
        one sample low), which no sample taken before that count can mislead. ``T`` ranges
        over the bracket the other segments give (the prior, when every segment is flagged).
        The timestamp stays on its segment's grid (a recording's steps stay regular); its
        uncertainty grows to reach both ends of the hull.
        """
        flagged = out["suspect"]
        est = self.estimator
        t_low, t_high = est.prior if self.timing_flagged_all else (est.low, est.high)
        origin = self.starts[0]
        seg = out["segment"][flagged]
        j = out["position"][flagged].astype(np.float64)
        enable = np.array([est.segments[k][0][1:] for k in range(len(self.starts))])
        b0, a0 = enable[seg, 0] - origin, enable[seg, 1] - origin
        lo = np.minimum(out["time"][flagged] - out["uncertainty"][flagged], b0 + j * t_low)
        hi = np.maximum(out["time"][flagged] + out["uncertainty"][flagged],
                        a0 + (j + 1) * t_high)
        newest, b, a = out["anchor"][flagged].T
        k = newest - j
        lo = np.minimum(lo, b - origin - (k + 2) * t_high)
        hi = np.maximum(hi, a - origin - k * t_low)
        time = out["time"][flagged]
        out["uncertainty"] = out["uncertainty"].copy()
        out["uncertainty"][flagged] = np.maximum(time - lo, hi - time)

    def recording(self, first: int, stop: int, *, metadata: dict | None = None):
        """The stream's samples in slots ``[first, stop)`` as a
        :class:`~ebantenna.recording.Recording` (X -> ax, Z -> az), and the raw record.

        ``t`` is each sample's estimated time (s), counted from the estimated time of slot
        ``first`` on the first segment's grid, with the period estimated over the run
        (:class:`~ebantenna.device.timing.PeriodEstimator`), and ``fs`` the estimated rate. The
        metadata hold ``samples_lost`` (slots in the window without a sample), the stream's
        report (period estimate, restarts, rejected counts, fault log),
        ``timestamp_uncertainty_s`` (how far any timestamp of the window can be from the truth,
        with up to :data:`STOLEN_SHARE_COVERED` of the samples taken unseen by another reader),
        ``timestamp_uncertainty_sole_reader_s`` (the same when no other program reads the FIFO:
        the largest of its segments', see :meth:`kept`) and under ``"raw"`` what the rig
        measured: the counts of all three axes (Y included), each sample's slot, FIFO segment
        and position in it, each segment's start, estimated first sample and its timestamps'
        uncertainty, and each drain's host time (s from the stream's start) and size.

        Returns
        -------
        Recording
        """
        first = check_int("first", first, minimum=0)
        stop = check_int("stop", stop, minimum=first + 1)
        mpu = self.mpu
        kept = self.kept(first, stop)
        if kept["slot"].size == 0:
            raise ValueError("no samples to make a recording of")
        counts = kept["counts"]
        saturated = _saturated(counts, mpu.config.full_scale_g)
        acc = mpu.to_acceleration(counts)
        period = self.estimator.period
        meta = mpu.metadata()
        meta.update(
            {
                "samples_lost": int((stop - first) - kept["slot"].size),
                "samples_saturated": saturated,
                "first_index": int(kept["slot"][0]),
                "timestamp_uncertainty_s": float(kept["uncertainty"].max()),
                "timestamp_uncertainty_sole_reader_s": float(
                    kept["uncertainty_sole_reader"].max()),
                "samples_timing_suspect": int(kept["suspect"].sum()),
                "sensor_check": sensor_check(counts, mpu.config.lsb_per_g),
            }
        )
        meta.update(metadata or {})
        first_sample, uncertainty = self.segment_timing()
        t = kept["time"] - (first_sample[0] + (first - self.offsets[0]) * period)
        meta["raw"] = self._raw(kept, first, first_sample, uncertainty)
        return Recording(t, acc[:, 0], acc[:, 2], 1.0 / period, meta)

    def _raw(self, kept: dict, first: int, first_sample, uncertainty) -> dict:
        """What the rig measured, as measured (see the module notes)."""
        return {
            "counts_xyz": kept["counts"].tolist(),
            "slot": (kept["slot"] - first).tolist(),
            "segment": kept["segment"].tolist(),
            "position": kept["position"].tolist(),
            "segment_start_s": (np.asarray(self.starts) - self.starts[0]).tolist(),
            "segment_first_sample_s": first_sample.tolist(),
            "segment_uncertainty_s": uncertainty.tolist(),
            "drain_time_s": (np.asarray(self.drain_times) - self.starts[0]).tolist(),
            "drain_samples": list(self.drain_sizes),
            "timing_suspect_segments": sorted(self.suspect),
        }

    def report(self) -> dict:
        """JSON-ready account of the stream: period estimate, restarts, rejected counts, how far
        the timestamps can be trusted, faults."""
        est = self.estimator
        _, uncertainty = self.segment_timing() if self.starts else (None, np.zeros(1))
        sole = float(np.max(uncertainty))
        kept = self.kept() if self._slot else None
        return {
            "sample_rate_estimated_hz": 1.0 / est.period,
            "sample_period_s": est.period,
            "sample_period_uncertainty_s": est.uncertainty,
            # what the kept samples state (see kept), and their segments' alone
            "timestamp_uncertainty_s": sole if kept is None else float(kept["uncertainty"].max()),
            "timestamp_uncertainty_sole_reader_s": sole,
            "fifo_restarts": len(self.starts) - 1,
            "fifo_overflows": self.overflows,
            "fifo_counts_rejected": est.rejected,
            "fifo_resets_unconfirmed": self.resets_unconfirmed,
            "clock_outside_tolerance_suspected": self.clock_suspect,
            "clock_rate_adapted": self.clock_adapted,
            "clock_refused": self.clock_refused,
            "clock_error_estimated": 1.0 / (est.period * (1.0 / est.nominal)) - 1.0,
            "samples_discarded": self.discarded,
            "foreign_reads_detected": self.foreign,
            "faults": [f.to_dict() for f in self.faults],
        }


#: Longest run of identical consecutive samples (all three axes) a live sensor plausibly gives:
#: its noise (about 13 LSB rms at +/-16 g, see :func:`sensor_check`) makes a repeat rare, and
#: ten in a row practically impossible.
MAX_REPEATS = 10
#: Sample-to-sample noise below which a live MPU-6050 is implausible, LSB rms: the data sheet's
#: 400 ug/sqrt(Hz) (PS rev. 3.4, table 6.2) over a 260 Hz bandwidth is about 6.5 mg, 13 LSB at
#: +/-16 g (the simulator's second-order filter lets through about 14); less than a tenth of
#: an LSB means the values are not being measured.
MIN_NOISE_LSB = 0.1
#: Unpredictable noise (LSB rms: the error of predicting a reading from the
#: :data:`PREDICTOR_ORDER` before it, see :func:`sensor_check`) from which the parity of a live
#: reading is a fair coin whatever came before: Gaussian noise of sigma LSB, rounded, is odd with
#: a probability within (2/pi) exp(-pi^2 sigma^2 / 2) of 1/2 (the first Fourier term of the
#: period-2 square wave (-1)^k; the bound is attained), below 2e-9 at 2 LSB. The MPU-6050's
#: floor is about 13 LSB at +/-16 g (above); its narrow DLPF settings leave less.
PARITY_MIN_NOISE_LSB = 2.0
#: Readings before the one predicted, in that prediction (least squares, with a constant): the
#: memory of a low-pass filter or a smooth signal is taken out of the noise the gate sees.
PREDICTOR_ORDER = 4
#: Odd share at or below which the readings are flagged as the AND of two devices: halfway
#: between a live sensor's 1/2 and the 1/4 of two independent streams ANDed (odd only when
#: both are).
ODD_SHARE_LIMIT = 3 / 8
#: Readings counted as one in the false-alarm bound. Given everything before it, a reading whose
#: unpredictable part passes the gate is odd with a probability within 2e-9 of 1/2, so the odd
#: count is a martingale and Hoeffding-Azuma's bound holds with no independence assumed; the
#: bound is still taken on a quarter of the readings, a margin for the gate being an estimate.
PARITY_BLOCK = 4
#: Largest probability that a live sensor (odd share 1/2) is flagged, per recording.
PARITY_FALSE_ALARM = 1e-6
#: Readings (over the axes that pass the noise gate) from which the parity test decides:
#: Hoeffding's bound exp(-2 (n / PARITY_BLOCK) (1/2 - ODD_SHARE_LIMIT)^2) on a share of n
#: readings falling to the limit is then at most PARITY_FALSE_ALARM (n = 1769); the same
#: bound holds for the share of two such noisy devices (1/4) rising to it.
MIN_PARITY_READINGS = math.ceil(PARITY_BLOCK * math.log(1 / PARITY_FALSE_ALARM)
                                / (2 * (0.5 - ODD_SHARE_LIMIT) ** 2))


def sensor_check(counts: np.ndarray, lsb_per_g: int) -> dict:
    """Signs of a dead, stuck or duplicated sensor in ``counts`` ((n, 3) int16), for the
    operator to judge (nothing is dropped).

    Returns a JSON-ready dict: ``noise_lsb`` (per axis, the rms of the sample-to-sample change
    over sqrt(2): the noise floor of a slowly varying signal), ``longest_repeat`` (the longest
    run of identical consecutive samples), ``constant_axes`` (axes that never change),
    ``odd_share`` (per axis, the share of odd readings; None with no reading),
    ``unpredictable_lsb`` (per axis, the rms error of predicting each reading from the
    :data:`PREDICTOR_ORDER` before it by least squares: the noise no filter memory or smooth
    signal explains), ``parity_decided`` (whether the parity test below could decide) and
    ``flags``, a list of sentences, empty when nothing looks wrong.

    The parity test looks for two devices answering at one address. Both drive the open-drain
    bus, which carries the AND of their bits, so a reading is odd only when both devices' are:
    about 1/4 of the time for two independent noisy streams, where one live sensor's
    unpredictable noise (at least :data:`PARITY_MIN_NOISE_LSB`) makes it odd half of the time.
    Over the axes that pass that gate, the readings are flagged when their share of odd ones is
    at most :data:`ODD_SHARE_LIMIT`; the test decides only from :data:`MIN_PARITY_READINGS`
    readings on, where a live sensor is flagged with a probability below
    :data:`PARITY_FALSE_ALARM` (Hoeffding-Azuma's bound, on a quarter of the readings).
    A quieter or more heavily filtered sensor, or a shorter recording, leaves
    ``parity_decided`` False and says nothing.

    Parameters
    ----------
    counts : ndarray
        (n, 3) integer counts, X, Y, Z.
    lsb_per_g : int
        Sensitivity the counts were taken at, LSB/g (>= 1).

    Returns
    -------
    dict

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.device.fifo import sensor_check
    >>> sensor_check(np.full((100, 3), 7, np.int16), 2048)["flags"][0]
    'all 100 samples are identical: a stuck or dead sensor'
    >>> rng = np.random.default_rng(0)
    >>> one, two = (rng.normal(0, 16, (1000, 3)).round().astype(np.int16) for _ in range(2))
    >>> sensor_check(one, 2048)["flags"], sensor_check(one, 2048)["parity_decided"]
    ([], True)
    >>> print(sensor_check(one & two, 2048)["flags"][0])  # doctest: +NORMALIZE_WHITESPACE
    axis x, y, z: 26 %, 25 %, 23 % of 1000 readings are odd where a noisy live sensor gives
    half: two devices answering at one address (the AND of their bits)? Check the AD0 pins.
    """
    if not isinstance(counts, np.ndarray) or counts.ndim != 2 or counts.shape[1] != 3 or (
            counts.dtype.kind not in "iu"):
        raise TypeError("counts must be an (n, 3) integer array of X, Y, Z counts, got "
                        f"{getattr(counts, 'shape', type(counts).__name__)}")
    check_int("lsb_per_g", lsb_per_g, minimum=1)
    n = counts.shape[0]
    odd = np.count_nonzero(counts & 1, axis=0)
    out = {"noise_lsb": [0.0, 0.0, 0.0], "longest_repeat": 0, "constant_axes": [],
           "odd_share": [round(float(k) / n, 4) if n else None for k in odd],
           "unpredictable_lsb": [0.0, 0.0, 0.0], "parity_decided": False, "flags": []}
    if n < 2:
        return out
    diff = np.diff(counts.astype(np.int32), axis=0)
    noise = np.sqrt(np.mean(diff.astype(np.float64) ** 2, axis=0) / 2.0)
    same = np.all(diff == 0, axis=1)
    edges = np.flatnonzero(np.diff(np.concatenate(([0], same.astype(np.int8), [0]))))
    longest = int((edges[1::2] - edges[::2]).max()) + 1 if edges.size else 1
    constant = [axis for k, axis in enumerate("xyz") if np.all(diff[:, k] == 0)]
    out.update(noise_lsb=[round(float(v), 3) for v in noise], longest_repeat=longest,
               constant_axes=constant)
    if same.all():
        out["flags"].append(f"all {n} samples are identical: a stuck or dead sensor")
    else:
        if longest >= MAX_REPEATS:
            out["flags"].append(f"{longest} identical samples in a row: the sensor stopped "
                                "updating for a while")
        if constant:
            out["flags"].append(f"axis {', '.join(constant)} never changes: a dead axis")
        quiet = [axis for k, axis in enumerate("xyz") if 0 < noise[k] < MIN_NOISE_LSB]
        if quiet:
            out["flags"].append(f"axis {', '.join(quiet)}: noise below {MIN_NOISE_LSB} LSB, "
                                "implausibly quiet for a live MPU-6050")
    unpredictable = [_unpredictable(counts[:, k]) for k in range(3)]
    out["unpredictable_lsb"] = [round(v, 3) for v in unpredictable]
    noisy = [k for k in range(3) if unpredictable[k] >= PARITY_MIN_NOISE_LSB]
    if n * len(noisy) >= MIN_PARITY_READINGS:
        out["parity_decided"] = True
        if odd[noisy].sum() <= ODD_SHARE_LIMIT * n * len(noisy):
            shares = ", ".join(f"{100 * odd[k] / n:.0f} %" for k in noisy)
            out["flags"].append(
                f"axis {', '.join('xyz'[k] for k in noisy)}: {shares} of {n} readings are odd "
                "where a noisy live sensor gives half: two devices answering at one address "
                "(the AND of their bits)? Check the AD0 pins.")
    return out


def _unpredictable(x: np.ndarray) -> float:
    """The rms error of predicting each of ``x`` from the :data:`PREDICTOR_ORDER` before it
    (least squares with a constant, on the centred values), LSB; 0 when too short to fit."""
    p = PREDICTOR_ORDER
    x = x.astype(np.float64)
    rows = x.size - p
    if rows <= 2 * (p + 1):
        return 0.0
    x = x - x.mean()
    past = np.column_stack([x[p - 1 - k:x.size - 1 - k] for k in range(p)] + [np.ones(rows)])
    coef, *_ = np.linalg.lstsq(past, x[p:], rcond=None)
    residual = x[p:] - past @ coef
    return float(np.sqrt(residual @ residual / (rows - p - 1)))


def _seen_record(**extra) -> dict:
    """An empty record of what contradicting counts showed of the period (see
    :meth:`FifoStream._contradicted`): how many, the hull and the common part of their
    brackets, the foreign reads they were blamed on, the last one's count and time since its
    segment began."""
    return {"counts": 0, "hull": (math.inf, 0.0), "common": (0.0, math.inf), "blamed": 0,
            "last": (0, 0.0), **extra}


_CLONE_HINT = ("; is this an MPU-6500-family clone answering WHO_AM_I 0x68? Its divider is "
               "ignored with DLPF_CFG = 0, so it samples at 8 kHz")


def _hz(rate: float) -> str:
    return f"{rate / 1e3:.3g} kHz" if rate >= 1e3 else f"{rate:.4g} Hz"


def _saturated(counts: np.ndarray, full_scale_g: int) -> int:
    """X and Z readings at the int16 limits (clipped), logged at WARNING when there are any."""
    limit = np.iinfo(np.int16)
    xz = counts[:, [0, 2]]
    saturated = int(np.count_nonzero((xz == limit.min) | (xz == limit.max)))
    if saturated:
        logger.warning("%d accelerometer readings at the +/-%d g limit (clipped)", saturated,
                       full_scale_g)
    return saturated


def _shifted(count: int) -> str | None:
    """After a drain with a failed transfer: why its count after shows the chunks kept before the
    failure may be shifted (not a whole number of samples: another program, or the failed
    transfer itself, took part of one, and the two cannot be told apart), or None."""
    if count % ACCEL_SAMPLE_BYTES == 0:
        return None
    return (f"the FIFO count after a drain with a failed transfer, {count}, is not a whole "
            "number of samples: the failed transfer or another program (i2cget, i2cdump, a "
            "second driver) took part of a sample, and the chunks read before it may be shifted; "
            "the drain is dropped")
