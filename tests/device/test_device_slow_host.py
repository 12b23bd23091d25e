"""A slow host: a drain whose cost does not grow with the recording, and overflows that are
counted losses, never wrong samples kept (judged against the simulated chip's ground truth)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from ebantenna.device import MPU6050, SimulatedRig, timing
from ebantenna.device.simulated import FaultInjector, Faults
from ebantenna.device.timing import PeriodEstimator

#: Float round-off of a timestamp: sums of a few thousand periods of 1e-3 s.
ROUND_OFF = 1e-9


@pytest.mark.parametrize("bus_hz", [100e3, 400e3])
def test_a_host_too_slow_at_moments_loses_counted_samples_and_keeps_none_wrong(bus_hz):
    # one transfer in a hundred (a drain makes about ten) waits up to 0.4 s: often more than the
    # 170 ms the FIFO holds at 1 kHz ("slow host", drawn by the bus's fault injector)
    rig = SimulatedRig.quiet(seed=4, faults=Faults(slow_host=(0.01, 0.4)))
    rig.bus.bus_hz = bus_hz
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    asked = 3000
    rec = mpu.record(asked / 1000.0)
    meta = rec.metadata
    assert "slow host" in {kind for _, kind in rig.bus.injector.log}
    assert meta["fifo_overflows"] >= 1  # the host was too slow: the FIFO overflowed
    assert meta["fifo_overflows"] == sum("overflow" in f["cause"].lower()
                                         for f in meta["faults"])
    assert rec.n_samples + meta["samples_lost"] == asked  # every overflow is a counted loss
    assert rig.wrong_samples(mpu, rec) == 0  # none of the overwritten bytes kept
    kept = mpu.stream.kept(0, asked)
    error = np.abs(kept["time"] - rig.true_times(mpu, rec))
    assert np.all(error <= kept["uncertainty"] + ROUND_OFF)


def test_the_slow_host_is_drawn_from_its_own_generator_and_replays_from_its_seed():
    def draws(faults, seed):
        injector = FaultInjector(faults, seed)
        return [injector.preemption(0.0) for _ in range(200)], injector

    first, injector = draws(Faults(slow_host=(0.1, 0.3)), 7)
    again, _ = draws(Faults(slow_host=(0.1, 0.3)), 7)
    assert first == again and any(first)  # the same seed, the same moments
    assert all(0.0 <= d <= 0.3 for d in first)
    assert sum(k == "slow host" for _, k in injector.log) == sum(d > 0 for d in first)
    # asking for it changes none of the transfer faults' draws
    plain, slow = FaultInjector(Faults(error_rate=0.3), 7), FaultInjector(
        Faults(error_rate=0.3, slow_host=(0.5, 0.1)), 7)
    drawn = []
    for _ in range(100):
        slow.preemption(0.0)  # its own generator's draw, between the transfer faults' draws
        drawn.append(slow.draw())
    assert [plain.draw() for _ in range(100)] == drawn
    assert draws(Faults(), 7)[0] == [0.0] * 200


@pytest.mark.parametrize("bad, error, words", [
    ((0.5,), TypeError, "slow_host must be a pair"),
    ((1.0, 0.1), ValueError, "slow_host share"),
    ((0.1, -0.1), ValueError, "slow_host longest"),
    ((0.1, 11.0), ValueError, "slow_host longest"),
    ("ab", TypeError, "slow_host must be a pair"),
])
def test_slow_host_settings_are_checked(bad, error, words):
    with pytest.raises(error, match=words):
        Faults(slow_host=bad)


def test_acquire_reproduces_a_slow_host_from_the_command_line(capsys):
    from ebantenna.cli import main

    args = ["acquire", "--simulated", "--seed", "1", "--slow-host", "0.02", "0.4", "--json"]
    code = main(args)
    data = json.loads(capsys.readouterr().out)
    assert code == 0 and "slow host" in data["faults_injected"]
    assert data["samples"] + data["samples_lost"] == 1050 and data["samples_wrong"] == 0
    assert main(args) == 0 and json.loads(capsys.readouterr().out) == data  # replayed
    with pytest.raises(SystemExit):  # a setting of the simulated bus, refused on a real one
        main(["acquire", "--bus", "1", "--slow-host", "0.1", "0.1"])
    assert "--slow-host work(s) only with --simulated" in capsys.readouterr().err


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
