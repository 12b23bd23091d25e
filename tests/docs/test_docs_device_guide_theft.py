"""user_guide/device.rst: what another program reading the MPU-6050 does to a recording ("What
the driver cannot detect": the theft table, single samples taken unseen, whole samples taken in a
drain with a failed transfer, an overflow while another program reads ``INT_STATUS``, registers
the driver never writes), the FIFO's size and the bus's share the page names. Each test measures
a part of what the page states again on the simulated rig, whose bus and clock are virtual: a
recording replays exactly from its seed, whatever the host.

The page's protocol, which the helpers below follow: one-second recordings at 1 kHz of a 37 Hz
ring (every sample its own value, so that a kept sample is found in the chip's ground truth by
its counts), seeds 0-19 (the table) or 0-39; a take at a random time (``Faults(foreign_reads=((t,
"sample"), ...))``) at times ``0.05 + 0.9 u`` of the rig's clock with ``u`` drawn from
``default_rng(1000 + seed)``; a take once, at once or mid-drain, at ``default_rng(2000 + seed)``
(the table), ``default_rng(seed)`` (the single takes) or ``default_rng(4000 + seed)`` (whole
samples taken in a drain with a failed transfer, or at 0.755 s). The whole table, 20 recordings
per row at 100 and 400 kHz, takes about a minute on two cores; the tests here take a few rows of
it.
"""

import re
from pathlib import Path

import numpy as np
import pytest
from rig_truth import in_wrong_slot, record_ringing, true_times_of_values

from ebantenna.chips.mpu6050 import ACCEL_SAMPLE_BYTES, FIFO_SIZE, Register
from ebantenna.device import MPU6050, SimulatedRig
from ebantenna.device.fifo import FIFO_CHUNK
from ebantenna.device.i2c import TRANSFER_OVERHEAD, transfer_bits, transfer_time
from ebantenna.device.mpu6050 import FIFO_MARGIN
from ebantenna.device.simulated import Faults

PAGE = Path(__file__).resolve().parents[2] / "docs" / "user_guide" / "device.rst"
ASKED = 1000
#: Float round-off of a timestamp: sums of a few hundred periods of 1e-3 s.
ROUND_OFF = 1e-9


def _page_text() -> str:
    return " ".join(PAGE.read_text().split())  # one space between words, lines joined


def _record(faults, bus_hz=100e3, seed=0):
    """A one-second recording of the ringing rig (``rig_truth.record_ringing``)."""
    rig, mpu, rec = record_ringing(faults, bus_hz, seed, ASKED)
    assert rec.n_samples + rec.metadata["samples_lost"] == ASKED
    return rig, mpu, rec


def _judge(rig, mpu, rec) -> dict:
    """What the page counts of a recording: unflagged samples outside the segment's own
    uncertainty (``sole``) and outside the stated one (``stated``), unflagged samples in a wrong
    slot (``late``), unflagged wrong values, and the worst timing error of an unflagged
    sample."""
    kept = mpu.stream.kept(0, ASKED)
    true = true_times_of_values(rig, mpu, rec)
    error = np.abs(kept["time"] - true)
    right = ~np.isnan(true)
    unflagged = ~kept["suspect"]
    return {
        "sole": int(np.sum(unflagged & right
                           & (error > kept["uncertainty_sole_reader"] + ROUND_OFF))),
        "stated": int(np.sum(unflagged & right & (error > kept["uncertainty"] + ROUND_OFF))),
        "late": int(np.sum(in_wrong_slot(rig, mpu, rec) & unflagged)),
        "wrong_values": int(np.sum(~right & unflagged)),
        "worst": float(error[right & unflagged].max()) if np.any(right & unflagged) else 0.0,
    }


def _u(base, seed):
    return 0.05 + 0.9 * np.random.default_rng(base + seed).random()


def _theft(row: str, seed: int):
    """The faults of a row of the page's table, for one seed."""
    if match := re.fullmatch(r"(\d+) samples? at (?:a random time|random times)", row):
        at = np.random.default_rng(1000 + seed).random(int(match[1]))
        return Faults(foreign_reads=tuple((t, "sample") for t in sorted(0.05 + 0.9 * at)))
    match = re.fullmatch(r"(\d+) (samples?|bytes?) (at once|mid-drain), once", row)
    n = int(match[1]) * (ACCEL_SAMPLE_BYTES if match[2].startswith("sample") else 1)
    take = ((_u(2000, seed), n),)
    return Faults(foreign_reads=take) if match[3] == "at once" else Faults(drain_reads=take)


def _table() -> dict:
    """The page's theft table: ``{row: (100 kHz cell, 400 kHz cell)}``."""
    lines = PAGE.read_text().splitlines()
    top = next(i for i, line in enumerate(lines) if line.strip().startswith("====")
               and lines[i + 1].split()[:1] == ["theft"])
    rule = lines[top]
    starts = [m.start() for m in re.finditer(r"=+", rule)]
    rows = {}
    for line in lines[top + 3:]:
        if line.strip().startswith("===="):
            break
        cells = [line[a:b].strip() for a, b in zip(starts, [*starts[1:], None], strict=True)]
        rows[cells[0]] = (cells[1], cells[2])
    return rows


def _cell(runs) -> str:
    """A table cell: unflagged samples outside the segment's own uncertainty (the recordings
    that kept any), outside the stated one."""
    sole = sum(r["sole"] for r in runs)
    kept_them = sum(r["sole"] > 0 for r in runs)
    stated = sum(r["stated"] for r in runs)
    return f"{sole} ({kept_them}), {stated}" if sole else f"0, {stated}"


def test_the_page_states_the_theft_table_as_tested():
    table = _table()
    assert len(table) == 12
    # every recording kept every unflagged timestamp within the uncertainty it states, and at
    # 400 kHz within the segment's own too
    assert all(a.endswith(", 0") for a, _ in table.values())
    assert all(b == "0, 0" for _, b in table.values())
    page = _page_text()
    assert "The table was measured before the simulated bus" not in page  # the stale note


#: Rows measured again, and the unflagged samples in a wrong slot the page states for them.
ROWS = [("1 sample at once, once", 100e3, 1995), ("1 sample mid-drain, once", 100e3, 1377),
        ("3 samples at random times", 100e3, 3128), ("5 samples at random times", 100e3, 1296),
        ("3 samples at random times", 400e3, 0)]


@pytest.mark.parametrize("row, bus_hz, late", ROWS)
def test_a_row_of_the_theft_table_as_measured(row, bus_hz, late):
    # 20 one-second recordings, as the page says; about 2 s at 100 kHz
    runs = []
    for seed in range(20):
        runs.append(_judge(*_record(_theft(row, seed), bus_hz, seed)))
    assert _cell(runs) == _table()[row][0 if bus_hz == 100e3 else 1]
    assert sum(r["wrong_values"] for r in runs) == 0
    assert sum(r["late"] for r in runs) == late
    if late:
        page = _page_text()
        assert ("677, 1809, 3128, 1117 and 1296 samples in the rows of 1, 2, 3, 4 and 5 "
                "samples at random times at 100 kHz, 1995 and 1377 in the rows of 1 sample at "
                "once and mid-drain; none in any other row, nor at 400 kHz") in page


#: Recordings of the table in which the segment's own uncertainty missed at 100 kHz.
MISSED = [("1 sample at a random time", 0), ("2 samples at random times", 10),
          ("2 samples at random times", 17), ("4 samples at random times", 5),
          ("5 samples at random times", 9), ("5 samples at random times", 17),
          ("1 sample mid-drain, once", 18)]


def test_the_stated_uncertainty_holds_where_the_segments_own_missed():
    # the table's second numbers, on the recordings where the first is not 0 (at 100 kHz), and
    # the same recordings at 400 kHz, where neither misses
    for row, seed in MISSED:
        at_100 = _judge(*_record(_theft(row, seed), 100e3, seed))
        assert at_100["sole"] > 0 and at_100["stated"] == 0 == at_100["wrong_values"], row
        at_400 = _judge(*_record(_theft(row, seed), 400e3, seed))
        assert at_400["sole"] == at_400["stated"] == at_400["late"] == 0, row


def test_four_samples_taken_look_like_a_clock_a_third_of_a_percent_slow():
    # "four samples taken left every count of a segment that kept 923 samples outside its own
    # bound on one grid at a rate 0.34 % slow": the 4-sample row, seed 5, at 100 kHz
    page = _page_text()
    assert ("four samples taken left every count of a segment that kept 923 samples outside "
            "its own bound on one grid at a rate 0.34 % slow") in page
    rig, mpu, rec = _record(_theft("4 samples at random times", 5), 100e3, 5)
    meta = rec.metadata
    assert len(mpu.stream.starts) == 1  # one segment, never restarted
    assert meta["fifo_counts_rejected"] == meta["samples_timing_suspect"] == 0  # no count off
    assert _judge(rig, mpu, rec)["sole"] == 923
    slow = 1.0 - meta["sample_rate_estimated_hz"] / rig.mpu.true_rate()
    assert round(100 * slow, 2) == 0.34


def _single_take(kind, n_bytes, bus_hz, seed):
    at = _u(0, seed)
    take = ((at, n_bytes),)
    faults = Faults(foreign_reads=take) if kind == "between drains" else Faults(
        drain_reads=take)
    rig, mpu, rec = _record(faults, bus_hz, seed)
    judged = _judge(rig, mpu, rec)
    judged["slow"] = 1.0 - rec.metadata["sample_rate_estimated_hz"] / rig.mpu.true_rate()
    judged["told"] = (rec.metadata["foreign_reads_detected"]
                      + rec.metadata["samples_timing_suspect"])
    return judged


#: Per half of the forty recordings: the seeds whose single sample, taken between a drain's count
#: and its data, went unseen at 100 kHz (tests/device/test_device_silent_faults.py holds the
#: forty with the sample taken between drains: seeds 1, 6, 16, 26, 38 and 39).
UNSEEN_MID_DRAIN = ({1, 6}, {26, 33, 38, 39})
UNSEEN_BETWEEN_DRAINS = (1, 6, 16, 26, 38, 39)


def _single_take_sentence(page):
    match = re.search(r"At 100 kHz the short count was never contradicted in (\d+) of each "
                      r"(\d+): every count of the segment agreed with a clock ([\d.]+) to "
                      r"([\d.]+) % slow, nothing was flagged or counted, and the samples after "
                      r"the take stayed one slot late \((\d+) to (\d+) per recording with the "
                      r"sample taken between drains, (\d+) to (\d+) between a count and its "
                      r"data\)\. Their values are right and their timestamps within the "
                      r"uncertainty they state \(up to ([\d.]+) ms off\), not within the "
                      r"segment's own", page)
    assert match, "the sentence on single samples taken at 100 kHz changed: update this test"
    return match


@pytest.mark.parametrize("half", [0, 1])
def test_a_single_sample_taken_mid_drain_at_100_khz_goes_unseen_as_stated(half):
    match = _single_take_sentence(_page_text())
    unseen_of, recordings = int(match[1]), int(match[2])
    slowest, fastest = float(match[3]), float(match[4])
    least, most, worst = int(match[7]), int(match[8]), float(match[9])
    assert recordings == 40 and unseen_of == len(set().union(*UNSEEN_MID_DRAIN))
    unseen = set()
    for seed in range(20 * half, 20 * half + 20):
        run = _single_take("mid-drain", ACCEL_SAMPLE_BYTES, 100e3, seed)
        assert run["stated"] == run["wrong_values"] == 0
        if run["late"]:
            unseen.add(seed)
            assert least <= run["late"] <= most and run["told"] == 0 and run["sole"] > 0
            assert slowest - 0.005 <= 100 * run["slow"] <= fastest + 0.005
            assert 1e3 * run["worst"] <= worst + 0.005
    assert unseen == UNSEEN_MID_DRAIN[half]


def test_the_single_takes_unseen_at_100_khz_are_caught_at_400_khz_and_two_at_100_khz():
    match = _single_take_sentence(_page_text())
    least, most, worst = int(match[5]), int(match[6]), float(match[9])
    seeds = sorted(set(UNSEEN_BETWEEN_DRAINS) | set().union(*UNSEEN_MID_DRAIN))
    for seed in UNSEEN_BETWEEN_DRAINS:  # the numbers the page gives for them
        run = _single_take("between drains", ACCEL_SAMPLE_BYTES, 100e3, seed)
        assert least <= run["late"] <= most and run["told"] == 0 and run["stated"] == 0
        assert 1e3 * run["worst"] <= worst + 0.005
    for seed in seeds:
        for kind in ("between drains", "mid-drain"):
            caught = _single_take(kind, ACCEL_SAMPLE_BYTES, 400e3, seed)
            two = _single_take(kind, 2 * ACCEL_SAMPLE_BYTES, 100e3, seed)
            for run in (caught, two):
                assert run["late"] == run["stated"] == run["wrong_values"] == 0, (seed, kind)
            assert caught["told"] > 0 and two["told"] > 0


def _failed_transfer_take(n, bus_hz, seed, at=None):
    at = _u(4000, seed) if at is None else at
    faults = Faults(drain_reads=((at, ACCEL_SAMPLE_BYTES * n),), error_rate=0.1,
                    kinds=("eio",))
    rig, mpu, rec = _record(faults, bus_hz, seed)
    kept = mpu.stream.kept(0, ASKED)
    true = true_times_of_values(rig, mpu, rec)
    error = np.abs(kept["time"] - true)
    outside = ~kept["suspect"] & ~np.isnan(true) & (error > kept["uncertainty"] + ROUND_OFF)
    assert not np.any(np.isnan(true) & ~kept["suspect"])  # every unflagged value is right
    return int(outside.sum()), error[outside], kept["uncertainty"][outside]


def test_whole_samples_taken_in_a_drain_with_a_failed_transfer_as_stated():
    page = _page_text()
    assert ("3 to 10 of 30 runs kept 2 to 35 such samples each unflagged, up to 2.7 ms off (two "
            "taken) and 5.7 ms off (five taken) against 1.3 to 2.9 ms stated") in page
    # the runs that set the page's extremes, all with the take at 0.755 s: the worst errors
    # (seed 13, 100 kHz), the most samples and the largest stated bound (five taken, seed 2,
    # and seed 24, 100 kHz), the fewest samples (two taken, seed 24, 100 kHz), the least stated
    # bound (two taken, seed 15, 400 kHz)
    for n, stated_worst in ((2, 2.7), (5, 5.7)):
        count, error, bound = _failed_transfer_take(n, 100e3, 13, at=0.755)
        assert count == 5 and round(1e3 * error.max(), 1) == stated_worst
    count, _, bound = _failed_transfer_take(5, 100e3, 2, at=0.755)
    assert count == 35 and 1e3 * bound.max() <= 2.9
    count, _, bound = _failed_transfer_take(5, 100e3, 24, at=0.755)
    assert count == 20 and round(1e3 * bound.max(), 1) == 2.9
    count, _, bound = _failed_transfer_take(2, 100e3, 24, at=0.755)
    assert count == 2
    count, _, bound = _failed_transfer_take(2, 400e3, 15, at=0.755)
    assert count == 20 and round(1e3 * bound.min(), 1) == 1.3


@pytest.mark.parametrize("n, bus_hz, at, runs", [(2, 100e3, None, 3), (3, 400e3, 0.755, 10)])
def test_how_many_runs_of_thirty_keep_such_samples(n, bus_hz, at, runs):
    # the least and the most of the page's "3 to 10 of 30 runs": two taken at a time drawn from
    # the seed at 100 kHz, three taken at 0.755 s at 400 kHz
    counts = [_failed_transfer_take(n, bus_hz, seed, at=at)[0] for seed in range(30)]
    assert sum(c > 0 for c in counts) == runs
    assert all(2 <= c <= 35 for c in counts if c)


def _stalled(stall_at, bus_hz, other_reader):
    """A one-second recording with a 0.25 s host stall at ``stall_at`` (the FIFO overflows),
    and with ``other_reader`` another program reading ``INT_STATUS`` (clear on read) just before
    each of the driver's reads of it (the burst at ``INT_ENABLE``)."""
    t = np.arange(3000) / 1000.0
    ring = 30.0 * np.exp(-t / 0.4) * np.sin(2 * np.pi * 37.0 * t)
    x = ring + np.random.default_rng(0).normal(0, 0.5, t.size)
    rig = SimulatedRig.from_arrays(x, 0.5 * ring, fs=1000.0, obstacle=None, seed=0,
                                   faults=Faults(stall_at=stall_at, stall_duration=0.25))
    rig.bus.bus_hz = bus_hz
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    rig.touch()
    if other_reader:
        transfer = rig.bus._read  # the simulated bus's read transfer (no public hook for this)

        def _read(address, register, length, nbytes):
            if address == mpu.config.address and register == Register.INT_ENABLE and length == 3:
                rig.mpu.read(Register.INT_STATUS, 1)  # the other program's read clears it
            return transfer(address, register, length, nbytes)

        rig.bus._read = _read
    rec = mpu.record(1.0)
    assert rec.n_samples + rec.metadata["samples_lost"] == ASKED
    assert rig.wrong_samples(mpu, rec) == 0
    return rec.metadata


@pytest.mark.parametrize("bus_hz", [100e3, 400e3])
def test_an_overflow_while_another_program_reads_int_status_is_reported_as_stated(bus_hz):
    page = _page_text()
    match = re.search(r"at 40 times from 0.3 s on in one-second recordings: (\d+) of the 40 "
                      r"overflows at 100 kHz, and (\d+) of 40 at 400 kHz, were reported as "
                      r"foreign reads", page)
    assert match and ("not in ``fifo_overflows``, or which reads a full FIFO (reported as "
                      "one). The drain is dropped all the same") in page
    stated = int(match[1] if bus_hz == 100e3 else match[2])
    foreign = 0
    for k in range(40):
        meta = _stalled(0.3 + 0.0137 * k, bus_hz, other_reader=True)
        assert meta["fifo_overflows"] + meta["foreign_reads_detected"] == 1
        foreign += meta["foreign_reads_detected"]
        if k % 8 == 0:  # "none without the other program", on a few of the same stalls
            alone = _stalled(0.3 + 0.0137 * k, bus_hz, other_reader=False)
            assert alone["fifo_overflows"] == 1 and alone["foreign_reads_detected"] == 0
    assert foreign == stated


@pytest.mark.parametrize("register, value", [(Register.INT_PIN_CFG, 0x10),
                                             (Register.GYRO_CONFIG, 0x18)])
def test_a_register_the_driver_never_writes_is_not_checked(register, value):
    page = _page_text()
    assert ("a register it leaves at its reset value is never checked, and a change to one, "
            "``INT_PIN_CFG`` (0x37) or ``GYRO_CONFIG`` (0x1B) say, is not seen") in page
    assert f"(0x{int(register):02X})" in page
    rig, mpu, rec = _record(Faults(register_lost=((0.4, register, value),)))
    assert register not in mpu.expected_registers()
    assert rig.mpu.regs[register] == value  # the change landed
    assert rec.metadata["faults"] == [] and rec.metadata["fifo_restarts"] == 0


def test_the_fifo_size_the_page_names_is_the_chips():
    page = _page_text()
    assert "drains of at most 68 of the 170 samples the FIFO holds" in page
    assert FIFO_SIZE // ACCEL_SAMPLE_BYTES == 170
    assert "FIFO's 167" not in page  # 167 is what the poll interval leaves room for
    assert FIFO_SIZE // ACCEL_SAMPLE_BYTES - FIFO_MARGIN == 167


def test_the_bus_share_of_the_stream_as_stated():
    page = _page_text()
    match = re.search(r"twice \(:func:`~ebantenna.device.i2c.transfer_bits`: 9 \((\d+) \+ 3\) "
                      r"\+ 3 = (\d+) clocks\), and the simulated bus charges every transfer "
                      r"(\d+) us more \(:data:`~ebantenna.device.i2c.TRANSFER_OVERHEAD`\): a "
                      r"sample then costs ([\d.]+) ms at 100 kHz, (\d+) % of the bus \(([\d.]+) "
                      r"ms, (\d+) % at 400 kHz\)", page)
    assert match, "the sentence on the bus share changed: update this test"
    assert "54 clocks: at 100 kHz the 1 kHz stream alone takes 54 % of the bus" in page
    block, clocks, overhead_us = int(match[1]), int(match[2]), int(match[3])
    assert block == FIFO_CHUNK == 5 * ACCEL_SAMPLE_BYTES
    assert clocks == transfer_bits(FIFO_CHUNK, read=True)
    assert overhead_us == round(1e6 * TRANSFER_OVERHEAD, 9)
    for bus_hz, cost_ms, share in ((100e3, match[4], match[5]), (400e3, match[6], match[7])):
        per_sample = transfer_time(FIFO_CHUNK, bus_hz, read=True) / (FIFO_CHUNK // 6)
        assert round(1e3 * per_sample, 2) == float(cost_ms)
        assert round(100 * per_sample * 1e3) == int(share)  # a 1 kHz stream
        # what the simulated bus charges for one block of the FIFO's data
        rig = SimulatedRig.quiet()
        rig.bus.bus_hz = bus_hz
        mpu = MPU6050(rig.bus, clock=rig.clock)
        mpu.initialize()
        before = rig.clock.monotonic()
        mpu.device.read_block(Register.FIFO_R_W, FIFO_CHUNK, increment=False, retry=False)
        assert rig.clock.monotonic() - before == pytest.approx(5 * per_sample, rel=1e-9)
