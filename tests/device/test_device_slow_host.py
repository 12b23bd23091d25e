"""A slow host: a drain whose cost does not grow with the recording, and overflows that are
counted losses, never wrong samples kept (judged against the simulated chip's ground truth)."""

from __future__ import annotations

import numpy as np
import pytest

from ebantenna.device import MPU6050, SimulatedRig, timing
from ebantenna.device.timing import PeriodEstimator

#: Float round-off of a timestamp: sums of a few thousand periods of 1e-3 s.
ROUND_OFF = 1e-9


def _preempted(rig, seed: int, share: float, longest: float):
    """Make the host lose the processor before a ``share`` of the read transfers, drawn at
    random (its own seeded generator), for a time uniform in [0, longest] s: a host too slow at
    moments, between the count and the data of a drain as well as between drains."""
    rng = np.random.default_rng(seed)
    read = rig.bus.read_i2c_block_data

    def slow(*args, **kwargs):
        if rng.random() < share:
            rig.clock.advance(float(rng.uniform(0.0, longest)))
        return read(*args, **kwargs)

    rig.bus.read_i2c_block_data = slow


@pytest.mark.parametrize("bus_hz", [100e3, 400e3])
def test_a_host_too_slow_at_moments_loses_counted_samples_and_keeps_none_wrong(bus_hz):
    rig = SimulatedRig.quiet(seed=4)
    rig.bus.bus_hz = bus_hz
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    # one read in fifty (a drain makes about ten) waits up to 0.4 s: often more than the
    # 170 ms the FIFO holds at 1 kHz
    _preempted(rig, seed=4, share=0.02, longest=0.4)
    asked = 3000
    rec = mpu.record(asked / 1000.0)
    meta = rec.metadata
    assert meta["fifo_overflows"] >= 1  # the host was too slow: the FIFO overflowed
    assert meta["fifo_overflows"] == sum("overflow" in f["cause"].lower()
                                         for f in meta["faults"])
    assert rec.n_samples + meta["samples_lost"] == asked  # every overflow is a counted loss
    assert rig.wrong_samples(mpu, rec) == 0  # none of the overwritten bytes kept
    kept = mpu.stream.kept(0, asked)
    error = np.abs(kept["time"] - rig.true_times(mpu, rec))
    assert np.all(error <= kept["uncertainty"] + ROUND_OFF)


def _observations(segments: int, per_segment: int) -> PeriodEstimator:
    """An estimator fed counts of a 1 kHz clock 1 % slow, 20 samples per count."""
    est = PeriodEstimator(1e-3)
    period = 1e-3 / 0.99
    for s in range(segments):
        t0 = 3.0 * s
        est.begin(before=t0, after=t0 + 1e-4)
        for k in range(1, per_segment + 1):
            n = 20 * k
            assert est.add(produced=n, before=t0 + 1e-4 + n * period - 5e-5,
                           after=t0 + n * period + 3e-4)
    return est


def test_taking_a_segment_out_costs_no_pair_of_observations(monkeypatch):
    """Recomputing the bracket (a count that contradicts it, a clock adapted to) visits each
    segment once, never the pairs of its observations: a drain costs the same whatever the
    recording's length and number of restarts."""
    est = _observations(segments=40, per_segment=30)
    calls = []
    pair_rule = timing._narrowed_by
    monkeypatch.setattr(timing, "_narrowed_by", lambda *a: calls.append(1) or pair_rule(*a))
    est.forget(39)
    est.widen(1e-3 / 1.2, 1e-3 / 0.8)
    assert calls == []


def test_the_bracket_kept_as_counts_come_equals_the_pair_rule_over_all_observations():
    """The reference: every pair of a segment's observations, narrowed from the prior, computed
    here from the stored observations; the kept bracket equals it (none pruned below the
    limit), and holds the true period."""
    est = _observations(segments=3, per_segment=timing.MAX_OBSERVATIONS - 1)
    low, high = est.prior
    for observations in est.segments:
        for j, (n2, b2, a2) in enumerate(observations):
            for n1, b1, a1 in observations[:j]:
                low = max(low, (b2 - a1) / (n2 - n1 + 1))
                if n2 - n1 > 1:
                    high = min(high, (a2 - b1) / (n2 - n1 - 1))
    assert (est.low, est.high) == (low, high)
    est.forget(2)
    est.forget(2)  # again: nothing changes
    assert est.low <= 1e-3 / 0.99 <= est.high


def test_the_bracket_survives_pruning_and_a_long_segment():
    # far beyond the observations kept per segment: the bracket keeps every pair seen
    est = _observations(segments=1, per_segment=5 * timing.MAX_OBSERVATIONS)
    assert len(est.segments[0]) <= timing.MAX_OBSERVATIONS
    tight = (est.low, est.high)
    est.forget(0)  # out, then the prior alone
    assert (est.low, est.high) == est.prior
    assert est._own_bracket(0) == tight  # its own bracket: every pair, pruned ones included
    assert tight[0] <= 1e-3 / 0.99 <= tight[1]
