"""The sample period and the timestamps of a FIFO stream, from counts of samples at host times.

The host never sees the accelerometer's clock; it sees counts: so many samples in the FIFO,
read between two host times. :class:`PeriodEstimator` turns those counts into a bracket of the
period that does not depend on when a segment's first sample came (the phase cancels in
differences of counts), and into each segment's timestamps with their uncertainty. It is used by
:class:`~ebantenna.device.fifo.FifoStream` (rule 4 of its module notes). Linux's
``inv_mpu6050`` driver does the same job from interrupt timestamps, accepting one only when the
period it implies lies within a few percent of nominal.
"""

from __future__ import annotations

import logging
import math

from .._validate import check_in_range, check_int, check_positive, check_real

__all__ = ["PeriodEstimator", "CLOCK_TOLERANCE"]

logger = logging.getLogger(__name__)

#: Observations kept per segment (:meth:`PeriodEstimator.add` prunes beyond it): the cost of a
#: count stays constant however long a segment runs.
MAX_OBSERVATIONS = 64

#: How far the sample clock may be off its nominal rate before the estimate is not trusted,
#: relative: a few times the +/-1 % variation over temperature of the gyro oscillators that the PLL
#: locks to (PS rev. 3.4, section 7.15).
CLOCK_TOLERANCE = 0.05

class PeriodEstimator:
    """The sample period, bracketed by counts of samples at known host times, without assuming
    when a segment's first sample came.

    Each FIFO *segment* starts with the write that enables the FIFO, made between host times
    ``before`` and ``after``: that is an observation "0 samples at ``before``, and the first one
    at most one period after ``after``" (the divider, restarted or free-running, ticks within a
    period). Each confirmed count is an observation "``n`` samples by ``after``, fewer than
    ``n + 1`` at ``before``". With ``t_k`` the time of the segment's sample ``k`` (0-based) and
    ``T`` the period, two observations ``(n1, b1, a1)`` and ``(n2, b2, a2)`` of one segment,
    ``n2 > n1``, give ``t_(n2) > b2`` and ``t_(n1 - 1) <= a1``, so ``(n2 - n1 + 1) T > b2 - a1``;
    and ``t_(n2 - 1) <= a2``, ``t_(n1) > b1``, so ``(n2 - n1 - 1) T < a2 - b1``. The time of the
    first sample cancels: the bracket needs no phase. It starts from the rate's tolerance, two
    sided on the *rate*: ``nominal / (1 + tolerance) <= T <= nominal / (1 - tolerance)``, the
    *prior*; a clock that the counts show outside it widens the prior (:meth:`widen`).

    A count that contradicts the bracket (no period in it can explain the count) is not used:
    it is logged at WARNING and counted in ``rejected``.

    Parameters
    ----------
    nominal : float
        The period the registers set, s.
    tolerance : float
        The rate is assumed within ``(1 +/- tolerance)`` times the nominal rate.

    Attributes
    ----------
    low, high : float
        The bracket of the period, s.
    prior : tuple of float
        The bracket before any observation, s: the tolerance's, or wider once :meth:`widen` let
        in a period the counts showed (a clock outside the tolerance).
    rejected : int
        Counts rejected because they contradict the bracket.
    segments : list of list of (int, float, float)
        The observations ``(n, before, after)`` of each segment, the enable first.

    Examples
    --------
    >>> from ebantenna.device.timing import PeriodEstimator
    >>> est = PeriodEstimator(1e-3)
    >>> est.begin(before=0.0, after=0.0003)  # the write that enabled the FIFO
    >>> est.add(produced=100, before=0.10045, after=0.10088)  # one count read
    True
    >>> round(est.period * 1e3, 4), round(est.uncertainty * 1e6, 1)  # ms, us
    (1.0053, 13.7)
    >>> est.add(produced=900, before=0.2, after=0.2004)  # impossible: 900 samples in 0.2 s
    False
    >>> est.rejected
    1
    """

    def __init__(self, nominal: float, tolerance: float = CLOCK_TOLERANCE):
        nominal = check_positive("nominal", nominal)
        tolerance = check_in_range("tolerance", tolerance, 0.0, 1.0)
        self.nominal = nominal
        self.tolerance = tolerance
        #: The bracket the observations narrow, s: the tolerance's, until :meth:`widen`.
        self.prior = (nominal / (1.0 + tolerance), nominal / (1.0 - tolerance))
        self.low, self.high = self.prior
        self.rejected = 0
        self.segments: list[list[tuple[int, float, float]]] = []
        # each segment's bracket from its own observations alone (every pair of them, pruned
        # ones included), no prior: kept as they come, so that recomputing the bracket costs
        # one step per segment, not one per pair of observations
        self._own: list[tuple[float, float]] = []
        #: Segments whose observations no longer narrow the bracket (:meth:`forget`).
        self.excluded: set[int] = set()

    def begin(self, *, before: float, after: float) -> None:
        """A new segment: the FIFO was enabled by a write made between host times ``before`` and
        ``after`` (s)."""
        _, before, after = _observation(0, before, after)
        self.segments.append([(0, before, after)])
        self._own.append((0.0, math.inf))

    def bounds(self, produced: int, before: float, after: float) -> tuple[float, float]:
        """The bracket ``(low, high)`` of the period, s, if ``produced`` samples of the current
        segment were counted between host times ``before`` and ``after``; empty (``low >=
        high``) when the count contradicts what is known. ``before`` may be ``-inf``: nothing
        known of when the sample after the count came (a full FIFO)."""
        observation = _observation(produced, before, after)
        if not self.segments:
            raise ValueError("a count needs a segment begun (begin()), and none is yet")
        return _narrowed_by(self.segments[-1], observation, self.low, self.high)

    def check(self, *, produced: int, before: float, after: float) -> bool:
        """Whether the count is possible; if not it is rejected: logged and counted."""
        produced, before, after = _observation(produced, before, after)
        low, high = self.bounds(produced, before, after)
        if low < high:
            return True
        self.rejected += 1
        logger.warning(
            "MPU-6050 FIFO: a count of %d samples at %.6f s is impossible (the period would "
            "lie outside [%.4g, %.4g] s); rejected", produced, after, self.low, self.high)
        return False

    def add(self, *, produced: int, before: float, after: float,
            start: float | None = None) -> bool:
        """Narrow the bracket with a confirmed count; False (and rejected) if it contradicts.

        ``start`` (s), if given, is the instant the count's segment began, for a segment whose
        enable is known to that precision: a new segment unless the current one began then.
        """
        produced, before, after = _observation(produced, before, after)
        if start is not None:
            start = check_real("start", start)
        if start is not None and (not self.segments or self.segments[-1][0] != (0, start, start)):
            self.begin(before=start, after=start)
        if not self.check(produced=produced, before=before, after=after):
            return False
        self.low, self.high = self.bounds(produced, before, after)
        observation = (produced, before, after)
        self._own[-1] = _narrowed_by(self.segments[-1], observation, *self._own[-1])
        self.segments[-1].append(observation)
        if len(self.segments[-1]) > MAX_OBSERVATIONS:
            self._prune(self.segments[-1])
        return True

    def _prune(self, observations: list) -> None:
        """Keep a segment's observations few, so that a count costs the same however long the
        segment: the enable, the newest, and those that bound the phase most tightly (the
        earliest ``after`` and the latest ``before`` on the grid of the current period). Any
        subset of true observations gives a true bracket; these lose almost nothing of it."""
        keep = MAX_OBSERVATIONS // 4
        period = self.period
        rest = observations[1:]
        chosen = {0} | {len(observations) - 1 - k for k in range(keep)}
        by_after = sorted(range(1, len(observations)),
                          key=lambda i: rest[i - 1][2] - rest[i - 1][0] * period)
        by_before = sorted(range(1, len(observations)),
                           key=lambda i: rest[i - 1][1] - rest[i - 1][0] * period, reverse=True)
        chosen |= set(by_after[:keep]) | set(by_before[:keep])
        observations[:] = [observations[i] for i in sorted(chosen)]

    def forget(self, segment: int) -> None:
        """Take ``segment``'s observations out of the bracket (they contradicted it: a sample
        taken by another reader, a count read wrong, a clock off its tolerance, and the ones
        before the contradiction may have narrowed the bracket wrongly). The bracket is
        recomputed from the prior and the other segments' own brackets (every pair of their
        observations, kept as they came: one step per segment, however long the recording);
        the segment's own observations stay for its timestamps, which the caller flags.

        ``segment`` is the index of a segment begun (0 for the first :meth:`begin`)."""
        if not self.segments:
            raise ValueError(f"segment must be a segment begun, and none is yet; got {segment!r}")
        segment = check_int("segment", segment, minimum=0, maximum=len(self.segments) - 1)
        self.excluded.add(segment)
        self._recompute()

    def widen(self, low: float, high: float) -> None:
        """Let the period lie in ``[low, high]`` (s) too: the prior bracket becomes the smallest
        that holds both it and ``[low, high]``, and the bracket is recomputed from it and the
        observations of the segments not taken out (:meth:`forget`).

        For a clock that the counts show outside the tolerance: observations bound the period
        whatever the prior, so once the prior holds the true period the bracket does too.

        Parameters
        ----------
        low, high : float
            The period's bounds to take in, s; ``0 < low <= high``, both finite.
        """
        low = check_positive("low", low)
        high = check_positive("high", high)
        if not high >= low:
            raise ValueError(f"high must be >= low ({low!r} s), got {high!r}")
        self.prior = (min(self.prior[0], low), max(self.prior[1], high))
        self._recompute()

    def _recompute(self) -> None:
        """The bracket from the prior and the segments not taken out: one step per segment."""
        low, high = self.prior
        for k, (own_low, own_high) in enumerate(self._own):
            if k not in self.excluded:
                low, high = max(low, own_low), min(high, own_high)
        self.low, self.high = low, high

    def _seen(self, extra=()) -> tuple[float, float]:
        """The period bracket ``(low, high)`` (s) that the current segment's observations and
        the observations ``extra`` (``(n, before, after)`` each) give alone, no prior assumed:
        empty (``low >= high``) when they contradict each other, ``high`` infinite when they
        bound the period from below only."""
        if not self.segments:
            return 0.0, math.inf
        low, high = self._own[-1]
        observations = list(self.segments[-1])
        for observation in extra:
            low, high = _narrowed_by(observations, observation, low, high)
            observations.append(observation)
        return low, high

    def _own_bracket(self, segment: int) -> tuple[float, float]:
        """The period bracket from ``segment``'s observations alone, no tolerance assumed (for a
        segment taken out of the bracket, :meth:`forget`); where they bound it from one side
        only, the tolerance's bound (widened to the other side's) stands in."""
        low, high = self._own[segment]
        prior_low, prior_high = self.prior
        if not math.isfinite(high):
            high = max(prior_high, low)
        if low <= 0.0:
            low = min(prior_low, high)
        return low, high

    def sample_interval(self, segment: int, j: int) -> tuple[float, float]:
        """Host times ``(earliest, latest)`` (s) at which sample ``j`` of ``segment`` can have
        been taken, from that segment's observations and the bracket (a segment taken out of
        the bracket by :meth:`forget` uses its own observations' bracket)."""
        segment, j = self._segment_and("j", segment, j)
        low, high = (self._own_bracket(segment) if segment in self.excluded
                     else (self.low, self.high))
        earliest, latest = -math.inf, math.inf
        for n, before, after in self.segments[segment]:
            k = j - n  # t_j = t_n + k T > before + k T
            earliest = max(earliest, before + k * (low if k >= 0 else high))
            k += 1  # t_j = t_(n-1) + k T <= after + k T
            latest = min(latest, after + k * (high if k >= 0 else low))
        return earliest, latest

    def timestamps(self, segment: int, last: int) -> tuple[float, float]:
        """The estimated time of sample 0 of ``segment`` (s) and the uncertainty (s) of every
        timestamp ``t_0 + j T`` (``T``: :attr:`period`) for ``j`` in ``0 ... last``.

        ``t_0`` is the middle of sample 0's interval. The error ``(t_0 - true t_0) + j (T -
        true T)`` is linear in ``j``, so its largest size is at ``j = 0`` or ``j = last``, where
        :meth:`sample_interval` bounds it.
        """
        segment, last = self._segment_and("last", segment, last)
        earliest, latest = self.sample_interval(segment, 0)
        t0 = 0.5 * (earliest + latest)
        uncertainty = 0.5 * (latest - earliest)
        lo, hi = self.sample_interval(segment, last)
        t_last = t0 + last * self.period
        return t0, max(uncertainty, t_last - lo, hi - t_last)

    def _segment_and(self, name: str, segment, j) -> tuple[int, int]:
        """``segment`` (a segment begun) and the sample index ``j`` (>= 0, called ``name``),
        checked."""
        if not self.segments:
            raise ValueError(f"segment must be a segment begun, and none is yet; got {segment!r}")
        segment = check_int("segment", segment, minimum=0, maximum=len(self.segments) - 1)
        return segment, check_int(name, j, minimum=0)

    @property
    def period(self) -> float:
        """Best estimate of the period, s."""
        return 0.5 * (self.low + self.high)

    @property
    def uncertainty(self) -> float:
        """Half the width of the bracket, s."""
        return 0.5 * (self.high - self.low)


def _observation(produced, before, after) -> tuple[int, float, float]:
    """A count's observation ``(produced, before, after)``, checked: ``produced`` an int >= 0,
    ``after`` a finite time not before ``before`` (which may be ``-inf``, nothing known)."""
    if (type(produced) is int and produced >= 0 and type(before) is float
            and type(after) is float and before <= after and -math.inf < after < math.inf):
        return produced, before, after  # the stream's own counts: checked at once
    produced = check_int("produced", produced, minimum=0)
    after = check_real("after", after)
    before = check_real("before", before, allow_inf=True)
    if before == math.inf:
        raise ValueError(f"before must be finite or -inf, got {before!r}")
    if not before <= after:
        raise ValueError(f"after must be >= before ({before!r} s), got {after!r}")
    return produced, before, after


def _narrowed_by(observations, observation, low: float, high: float) -> tuple[float, float]:
    """The period bracket ``(low, high)`` narrowed by every pair of one of a segment's
    ``observations`` and a later ``observation`` ``(n, before, after)`` of it (the pair rule of
    :class:`PeriodEstimator`); empty when ``observation`` counts fewer samples than one of
    them."""
    produced, before, after = observation
    for n1, b1, a1 in observations:
        if produced < n1:  # fewer samples than an earlier count: impossible
            return math.inf, -math.inf
        low = max(low, (before - a1) / (produced - n1 + 1))
        if produced - n1 > 1:
            high = min(high, (after - b1) / (produced - n1 - 1))
    return low, high
