"""A sample clock outside the tolerance, measured by the stream: the poll follows it, and a
clock too far off is refused with the rate it showed. Judged against the simulated chip's ground
truth (its true rate, the counts it put into its FIFO, the true time of each sample)."""

from __future__ import annotations

import logging
import re

import numpy as np
import pytest

from ebantenna.device import MPU6050, SimulatedRig
from ebantenna.device.fifo import CLOCK_SUSPECT_AFTER
from ebantenna.device.i2c import transfer_time
from ebantenna.device.simulated import Faults
from ebantenna.device.watchdog import StreamStalledError

#: Float round-off of a timestamp: sums of a few thousand periods of 1e-3 s.
ROUND_OFF = 1e-9


def _record(drift, bus_hz, poll, seconds=2.0, seed=0):
    rig = SimulatedRig.quiet(seed=seed, faults=Faults(clock_drift=drift))
    rig.bus.bus_hz = bus_hz
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    return rig, mpu, mpu.record(seconds, poll_interval=poll)


def _holds(rig, mpu, rec, asked):
    kept = mpu.stream.kept(0, asked)
    assert rec.n_samples + rec.metadata["samples_lost"] == asked
    assert rig.wrong_samples(mpu, rec) == 0
    error = np.abs(kept["time"] - rig.true_times(mpu, rec))
    assert np.all(error <= kept["uncertainty"] + ROUND_OFF)


@pytest.mark.parametrize("drift, bus_hz, poll", [(0.3, 100e3, 0.05), (0.45, 400e3, 0.12)])
def test_the_poll_follows_a_fast_clock_the_stream_measured(drift, bus_hz, poll, caplog):
    # the poll interval is accepted at the start (below the limit for a clock 5 % fast); a
    # clock 30-45 % fast overflowed the FIFO at every poll: 25-45 overflows in 5 runs of 3 s
    rig = SimulatedRig.quiet()
    rig.bus.bus_hz = bus_hz
    nominal_limit = MPU6050(rig.bus, clock=rig.clock).max_poll_interval()
    assert poll < nominal_limit
    with caplog.at_level(logging.WARNING, logger="ebantenna.device.mpu6050"):
        rig, mpu, rec = _record(drift, bus_hz, poll)
    _holds(rig, mpu, rec, 2000)
    assert rec.metadata["clock_rate_adapted"]
    # the limit now uses the fastest rate the measured bracket holds, which holds the truth
    fastest = 1.0 / mpu.stream.estimator.prior[0]
    assert rig.mpu.true_rate() <= fastest == mpu.fastest_rate()
    assert mpu.max_poll_interval() < min(poll, nominal_limit)
    # the overflows are the ones that revealed the clock, before the poll followed it
    assert rec.metadata["fifo_overflows"] <= CLOCK_SUSPECT_AFTER
    assert any("poll interval is shortened" in r.getMessage() for r in caplog.records)


def test_the_limit_is_the_drain_balance_at_the_fastest_rate():
    """The reference: N = r (P + F) / (1 - r c) samples must stay 3 below the FIFO's 170."""
    rig, mpu, _ = _record(0.3, 100e3, 0.02, seconds=1.0)
    r = mpu.fastest_rate()
    c = transfer_time(30, 100e3, read=True) / 5
    fixed = sum(transfer_time(n, 100e3, read=True) for n in (2, 2, 4, 1, 3, 2))
    limit = mpu.max_poll_interval()
    n = r * (limit + fixed) / (1 - r * c)
    assert n == pytest.approx(167, rel=1e-12)  # float: a few operations on O(1) values
    assert mpu.poll_wait(0.5 * limit) == 0.5 * limit  # below the limit: the interval as asked
    assert mpu.poll_wait(1.0) == pytest.approx(0.9 * limit, rel=1e-12)


def test_a_clock_within_the_tolerance_never_shortens_the_poll():
    rig, mpu, rec = _record(0.04, 100e3, 0.05)
    assert mpu.fastest_rate() == pytest.approx(1050.0, rel=1e-12)
    assert mpu.poll_wait(0.05) == 0.05 and rec.metadata["fifo_overflows"] == 0
    _holds(rig, mpu, rec, 2000)


@pytest.mark.parametrize("bad", [0.0, -1.0, float("nan"), "x"])
def test_the_poll_wait_refuses_a_bad_interval(bad):
    mpu = MPU6050(SimulatedRig.quiet().bus)
    with pytest.raises((ValueError, TypeError), match="poll_interval"):
        mpu.poll_wait(bad)


@pytest.mark.parametrize("bus_hz", [100e3, 400e3])
@pytest.mark.parametrize("drift", [-0.8, -0.6, -0.55, 0.7, 0.9])
def test_a_clock_beyond_what_the_stream_adapts_to_is_refused_naming_its_rate(drift, bus_hz):
    # before, these ran a full second of watchdog and said "fewer than the chip must have
    # produced (... or another program read the FIFO)"; at +55 % and 400 kHz six samples were
    # kept unflagged outside their stated uncertainty
    rig = SimulatedRig.quiet(faults=Faults(clock_drift=drift))
    rig.bus.bus_hz = bus_hz
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    start = rig.clock.monotonic()
    with pytest.raises(StreamStalledError, match="sample clock is refused") as info:
        mpu.record(1.0)
    assert rig.clock.monotonic() - start < 0.5  # at once, not after the watchdog's second
    refused = mpu.stream.clock_refused
    assert refused in str(info.value) and "beyond the 50 % the driver adapts to" in refused
    low, high = (float(v) * (1e3 if u == "kHz" else 1.0) for v, u in re.findall(
        r"rate between ([\d.]+) (k?Hz) and", refused) + re.findall(
        r"and ([\d.]+) (k?Hz), not", refused))
    true_rate = rig.mpu.true_rate()
    # the rate said is the one the counts bracket (printed to 3-4 significant digits)
    assert low * (1 - 5e-3) <= true_rate <= high * (1 + 5e-3)
    side = "slow" if drift < 0 else "fast"
    assert f"% {side} (a rate between" in refused
    est = mpu.stream.estimator
    assert est.prior[0] <= 1.0 / true_rate <= est.prior[1]  # what was kept states honest times
    rec = info.value.recording
    if rec is not None:
        kept = mpu.stream.kept(0, mpu.stream.next_slot)
        assert kept["suspect"].all()
        error = np.abs(kept["time"] - rig.true_times(mpu, rec))
        assert np.all(error <= kept["uncertainty"] + ROUND_OFF)


@pytest.mark.parametrize("bus_hz", [100e3, 400e3])
def test_a_clock_whose_counts_reach_within_the_limit_is_adapted_to_as_measured(bus_hz):
    # 55 % fast: the first counts bracket a rate that reaches below 1.5 kHz, so the stream
    # adapts, taking in the whole bracket they showed (never clipped at the limit)
    rig, mpu, rec = _record(0.55, bus_hz, 0.02, seconds=1.0)
    _holds(rig, mpu, rec, 1000)
    assert rec.metadata["clock_rate_adapted"] and rec.metadata["clock_refused"] is None
    est = mpu.stream.estimator
    assert 1.0 / est.high <= rig.mpu.true_rate() <= 1.0 / est.low


def test_acquire_says_the_clock_is_refused_and_its_rate(capsys):
    from ebantenna.cli import main

    with pytest.raises(SystemExit) as info:
        main(["acquire", "--simulated", "--seed", "1", "--clock-drift", "0.7"])
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert info.value.code == 2 and "sample clock is refused" in err and "% fast" in err
    low, high = map(float, re.search(r"a rate between ([\d.]+) kHz and ([\d.]+) kHz",
                                     err).groups())
    assert low <= 1.7 <= high  # the clock 70 % fast: the rate stated holds it
    assert "servos released" in err  # the servos let go before the error


def test_a_least_rate_is_forgotten_once_the_chip_is_configured_again():
    # fifo.py only ever raised rate_at_least: a full FIFO seen while a setting had changed
    # (SMPLRT_DIV lost to 0x03) pinned the poll at 0 s and max_poll_interval below zero for
    # the rest of the stream, though the chip was configured again at once
    from ebantenna.chips.mpu6050 import Register

    rig = SimulatedRig.quiet(seed=1)
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    nominal = mpu.max_poll_interval()
    stream = mpu.start_fifo()
    for _ in range(3):
        rig.clock.sleep(0.02)
        mpu.read_fifo()
    stream.rate_at_least = 6471.7  # what the reviewer's run showed: a FIFO full too soon
    assert mpu.max_poll_interval() < 0
    rig.mpu._corrupt(int(Register.SMPLRT_DIV), 3)
    rig.clock.sleep(0.02)
    mpu.read_fifo()  # the change is read back: the chip is configured again
    assert stream.faults[-1].action == "reconfigure" and stream.rate_at_least == 0.0
    assert mpu.max_poll_interval() == nominal and mpu.poll_wait(0.02) == 0.02


def test_a_least_rate_gives_way_to_the_bracket_once_the_stream_adapts():
    # a clock 45 % fast polled every 0.12 s at 400 kHz: the FIFO is found full first, then
    # counts bracket the rate
    rig, mpu, rec = _record(0.45, 400e3, 0.12)
    assert rec.metadata["fifo_overflows"] >= 1 and rec.metadata["clock_rate_adapted"]
    assert mpu.stream.rate_at_least == 0.0
    assert mpu.fastest_rate() == 1.0 / mpu.stream.estimator.prior[0]
