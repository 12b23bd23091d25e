"""Faults with no error on the bus (ebantenna.device.simulated.faults.SILENT_FAULTS), each
injected by name, judged against the simulated chip's ground truth: no wrong sample is kept
unflagged, kept + lost = asked, every unflagged timestamp lies within its stated uncertainty, and
what happened is said. Bit errors in the data are the exception the device guide documents:
I2C carries no checksum, and they are kept.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
from rig_truth import in_wrong_slot, record_ringing, ringing, true_times_of_values

from ebantenna.chips.mpu6050 import Register
from ebantenna.device import MPU6050, SimulatedRig
from ebantenna.device.fifo import (
    MIN_PARITY_READINGS,
    ODD_SHARE_LIMIT,
    PARITY_MIN_NOISE_LSB,
    sensor_check,
)
from ebantenna.device.i2c import SettingError
from ebantenna.device.simulated import Faults
from ebantenna.device.simulated.faults import SILENT_FAULTS
from ebantenna.device.watchdog import StreamStalledError
from ebantenna.recording import Recording

ASKED = 1000
#: Float round-off of a timestamp: sums of a few hundred periods of 1e-3 s.
ROUND_OFF = 1e-9


def _record(faults, bus_hz=100e3, seed=0):
    return record_ringing(faults, bus_hz, seed, ASKED)


def _judge(rig, mpu, rec, asked=ASKED):
    """The contract, for a run that kept something."""
    kept = mpu.stream.kept(0, asked)
    assert rec.n_samples + rec.metadata["samples_lost"] == asked
    assert not np.any(in_wrong_slot(rig, mpu, rec) & ~kept["suspect"])
    error = np.abs(kept["time"] - rig.true_times(mpu, rec))
    assert np.all((error <= kept["uncertainty"] + ROUND_OFF) | kept["suspect"])
    assert np.all(kept["uncertainty"] > 0)  # no timestamp claims to be exact
    assert rec.metadata["samples_timing_suspect"] == int(kept["suspect"].sum())


BUSES = [100e3, 400e3]


@pytest.mark.parametrize("bus_hz", BUSES)
def test_a_bit_flipped_in_a_setting_write_is_read_back_and_written_again(bus_hz):
    rig, mpu, rec = _record(Faults(flip_write=((Register.ACCEL_CONFIG, 0x08, 1),)), bus_hz)
    assert ("write bit flip" in {k for _, k in rig.bus.injector.log})
    assert rig.mpu.regs[Register.ACCEL_CONFIG] == mpu.config.accel_config
    _judge(rig, mpu, rec)
    assert rec.metadata["samples_lost"] == 0


@pytest.mark.parametrize("mask", [0x20, 0x40])
def test_the_write_that_starts_a_segment_is_read_back_whole(mask):
    # The USER_CTRL write that starts a segment (FIFO_EN, 0x40) is timed, so it is not retried;
    # its read-back decides whether the segment starts. It once checked FIFO_EN alone: with
    # I2C_MST_EN (0x20) flipped on as well the segment started, and only the next drain's
    # read-back saw USER_CTRL changed (20 samples discarded, 74 lost). Any stable bit read back
    # wrong now fails the restart, which is tried again: nothing read with the wrong setting.
    ax, az = ringing()
    rig = SimulatedRig.from_arrays(ax, az, fs=1000.0, obstacle=None, seed=0)
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    rig.touch()
    flipped, write = [], rig.bus._write

    def _write(address, register, data):
        if register == Register.USER_CTRL and list(data) == [0x40] and not flipped:
            flipped.append(rig.clock.monotonic())
            data = [0x40 ^ mask]
        return write(address, register, data)

    rig.bus._write = _write
    rec = mpu.record(ASKED / 1000.0)
    assert flipped
    causes = [f["cause"] for f in rec.metadata["faults"]]
    assert causes[0] == (f"restart failed (USER_CTRL (0x6A) reads back 0x{0x40 ^ mask:02X} "
                         "after 0x40 was written)")
    assert rec.metadata["samples_discarded"] == 0
    _judge(rig, mpu, rec)


def test_a_setting_that_never_lands_is_a_clear_error():
    ax, az = ringing()
    rig = SimulatedRig.from_arrays(ax, az, fs=1000.0, obstacle=None,
                                   faults=Faults(flip_write=((Register.ACCEL_CONFIG, 0x08, 9),)))
    with pytest.raises(SettingError, match=r"ACCEL_CONFIG \(0x1C\) .* reads back 0x10 after "
                                           r"0x18 was written twice"):
        MPU6050(rig.bus, clock=rig.clock).initialize()


@pytest.mark.parametrize("bus_hz", BUSES)
@pytest.mark.parametrize("lost", [
    ((0.4, Register.ACCEL_CONFIG, 0x00),),  # back to +/-2 g, awake, FIFO running
    ((0.4, Register.CONFIG, 0x00), (0.4, Register.SMPLRT_DIV, 0x00)),  # 8 kHz
    tuple((0.4, r, v) for r, v in ((Register.SMPLRT_DIV, 0), (Register.CONFIG, 0),
                                   (Register.ACCEL_CONFIG, 0), (Register.INT_ENABLE, 0),
                                   (Register.PWR_MGMT_1, 0x40))),  # everything, asleep
], ids=["accel_config", "rate", "all"])
def test_a_register_lost_mid_run_costs_one_drain_and_is_named(bus_hz, lost):
    rig, mpu, rec = _record(Faults(register_lost=lost), bus_hz)
    _judge(rig, mpu, rec)
    causes = " ".join(f["cause"] for f in rec.metadata["faults"])
    expected = mpu.expected_registers()
    for _, register, value in lost:  # every one that changed is named, from what to what
        if expected[register] != value:
            assert (f"{Register(register).name} (0x{int(register):02X}) changed from "
                    f"0x{expected[register]:02X} to 0x{value:02X}") in causes
    assert rig.mpu.regs[Register.ACCEL_CONFIG] == mpu.config.accel_config  # reconfigured
    assert rig.wrong_samples(mpu, rec) == 0  # counts and the range they were taken at
    # at most one drain's samples are discarded, and they are counted: a drain holds at most
    # the FIFO's samples
    assert 0 < rec.metadata["samples_discarded"] <= mpu.fifo_size // 6
    assert rec.metadata["fifo_restarts"] == 1


@pytest.mark.parametrize("bus_hz", BUSES)
@pytest.mark.parametrize("what", ["byte", "dump"])
def test_a_foreign_read_of_bytes_drops_the_drain_it_misaligned(bus_hz, what):
    for at in (0.4, 0.4123, 0.6071):
        rig, mpu, rec = _record(Faults(foreign_reads=((at, what),)), bus_hz)
        _judge(rig, mpu, rec)
        assert rec.metadata["foreign_reads_detected"] + rec.metadata["fifo_restarts"] >= 1
        assert rig.wrong_samples(mpu, rec) == 0


@pytest.mark.parametrize("bus_hz", BUSES)
def test_a_foreign_read_of_whole_samples_is_never_kept_unflagged(bus_hz):
    for seed, at in enumerate((0.4, 0.4123, 0.6071, 0.25)):
        rig, mpu, rec = _record(Faults(foreign_reads=((at, "sample"),)), bus_hz, seed)
        _judge(rig, mpu, rec)


@pytest.mark.parametrize("bus_hz", BUSES)
def test_an_under_reported_count_is_never_kept_unflagged(bus_hz):
    rig, mpu, rec = _record(Faults(undercount_at=(0.3, 0.5, 0.7)), bus_hz)
    assert sum(k == "undercount" for _, k in rig.bus.injector.log) == 3
    _judge(rig, mpu, rec)


@pytest.mark.parametrize("bus_hz", BUSES)
@pytest.mark.parametrize("drift", [-0.30, -0.10, -0.07, -0.06, 0.06, 0.07, 0.10, 0.30])
def test_a_clock_beyond_the_tolerance_is_measured_and_every_timestamp_holds(bus_hz, drift):
    """The stream adapts to the rate its counts show: it goes on recording, and every kept
    sample (flagged or not) lies within its stated uncertainty of the chip's true time."""
    rig, mpu, rec = _record(Faults(clock_drift=drift), bus_hz)
    assert isinstance(rec, Recording) and "stalled" not in rec.metadata
    _judge(rig, mpu, rec)
    kept = mpu.stream.kept(0, ASKED)
    error = np.abs(kept["time"] - rig.true_times(mpu, rec))
    assert np.all(error <= kept["uncertainty"] + ROUND_OFF)  # the flagged ones too
    assert rig.wrong_samples(mpu, rec) == 0
    est, true_period = mpu.stream.estimator, 1.0 / rig.mpu.true_rate()
    assert est.low <= true_period <= est.high  # the period's bracket holds the truth
    assert rec.metadata["clock_rate_adapted"] and rec.metadata["fifo_restarts"] <= 3
    assert rec.n_samples >= 0.819 * ASKED  # the device guide's figure (virtual time: exact)
    assert 1.0 / est.high <= rec.fs <= 1.0 / est.low
    side = "slow" if drift < 0 else "fast"
    adapted = [f.cause for f in mpu.stream.faults if f.action == "adapt"]
    assert adapted and all(f"% {side} (a rate between" in cause for cause in adapted)
    assert "produced" in adapted[0] and "since the FIFO was started" in adapted[0]
    wrong_side = "more than the chip can have" if drift < 0 else "fewer than the chip must"
    assert not any(wrong_side in f.cause for f in mpu.stream.faults)  # no message says false
    assert rec.metadata["foreign_reads_detected"] == 0  # the clock, not a reader, is named


def test_a_clock_within_the_tolerance_never_widens_the_bracket():
    rig, mpu, rec = _record(Faults(clock_drift=-0.045), 400e3)
    _judge(rig, mpu, rec)
    est = mpu.stream.estimator
    assert not rec.metadata["clock_rate_adapted"] and est.prior == (1e-3 / 1.05, 1e-3 / 0.95)
    assert rec.metadata["fifo_restarts"] == 0 and rec.metadata["samples_lost"] == 0


@pytest.mark.parametrize("bus_hz", [100e3, 400e3])
def test_a_clone_of_the_mpu6500_family_is_refused_at_once_and_named(bus_hz, caplog):
    # its FIFO is full at 512 bytes, not a whole number of samples: that count was taken for a
    # foreign read (40 of them), every overflow went uncounted, the rate named was 4.11 kHz
    # and the watchdog ended the run after a second
    ax, az = ringing()
    rig = SimulatedRig.from_arrays(ax, az, fs=1000.0, obstacle=None,
                                   faults=Faults(clone_6500=True))
    rig.bus.bus_hz = bus_hz
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    rig.touch()
    with pytest.raises(StreamStalledError, match="sample clock is refused.*MPU-6500-family "
                                                 "clone") as info:
        mpu.record(0.5)
    report = mpu.stream.report()
    assert report["clock_refused"] and report["foreign_reads_detected"] == 0
    assert report["fifo_overflows"] >= 1
    assert "FIFO count 512, the FIFO size of the MPU-6500 family: a full FIFO" in caplog.text
    # at once: well before the watchdog's second without a sample
    assert rig.clock.monotonic() - mpu.stream.starts[0] < 0.5
    # the rates the refusal states hold the clone's 8 kHz
    low, high = map(float, re.search(r"a rate between ([\d.]+) kHz and ([\d.]+) kHz",
                                     str(info.value)).groups())
    assert low <= 8.0 <= high


def test_a_stuck_sensor_is_kept_and_flagged():
    rig, mpu, rec = _record(Faults(stuck_sensor_at=0.2))
    _judge(rig, mpu, rec)
    check = rec.metadata["sensor_check"]
    assert check["longest_repeat"] >= 790 and "identical samples in a row" in check["flags"][0]
    rig, mpu, rec = _record(Faults(stuck_sensor_at=0.0))
    assert rec.metadata["sensor_check"]["flags"] == [
        f"all {rec.n_samples} samples are identical: a stuck or dead sensor"]


def test_a_live_sensor_raises_no_flag():
    rig, mpu, rec = _record(Faults())
    _judge(rig, mpu, rec)
    assert rec.metadata["sensor_check"]["flags"] == []
    assert rec.metadata["samples_timing_suspect"] == 0


def test_the_sensor_check_sees_dead_axes_and_implausible_noise():
    rng = np.random.default_rng(0)
    live = rng.normal(0, 16, (500, 3)).round().astype(np.int16)
    assert sensor_check(live, 2048)["flags"] == []
    dead = live.copy()
    dead[:, 1] = 40
    assert sensor_check(dead, 2048)["flags"] == ["axis y never changes: a dead axis"]
    quiet = live.copy()
    quiet[:, 2] = 0
    quiet[::100, 2] = 1  # changes, but far less than any live sensor
    assert "implausibly quiet" in sensor_check(quiet, 2048)["flags"][0]


TWIN = "two devices answering at one address (the AND of their bits)? Check the AD0 pins."


@pytest.mark.parametrize("bus_hz", BUSES)
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_second_device_at_the_address_is_flagged_by_its_odd_share(bus_hz, seed):
    rig, mpu, rec = _record(Faults(second_device=True), bus_hz, seed)
    # the bus gives the AND of both chips' bytes: every kept sample is the AND of their truths
    both = rig.mpu.truth(0) & rig.second_mpu.truth(0)
    raw = rec.metadata["raw"]
    assert raw["counts_xyz"] == both[raw["position"]].tolist()
    # nothing else sees it: the settings read back as written, the counts agree
    assert not rec.metadata["faults"] and rec.metadata["samples_lost"] == 0
    check = rec.metadata["sensor_check"]
    # 3000 readings >= MIN_PARITY_READINGS: a share of two devices (1/4) reaches the limit
    # (3/8) with a probability below 1e-6 (the bound of sensor_check)
    assert check["parity_decided"] and check["flags"] == [check["flags"][0]]
    assert check["flags"][0].endswith(TWIN) and "of 1000 readings are odd" in check["flags"][0]
    assert max(check["odd_share"]) <= ODD_SHARE_LIMIT


def test_one_device_is_never_taken_for_two():
    # Each recording decides (2000 readings: X and Y pass the gate; Z plays the vibration
    # without noise, which its predictor explains) and flags a live sensor with a probability
    # below PARITY_FALSE_ALARM = 1e-6, so 30 recordings stay unflagged unless something of
    # probability below 3e-5 happens. The simulated noise (0.02 m/s^2, 4 LSB at +/-16 g) is a
    # quarter of the real part's: the gate is passed with less margin than on the rig.
    for seed in range(30):
        rig, mpu, rec = _record(Faults(), 100e3, seed)
        check = rec.metadata["sensor_check"]
        assert check["parity_decided"] and check["flags"] == []
        assert min(check["odd_share"]) > ODD_SHARE_LIMIT


def _noisy(rng, sigma, n=1000, rho=0.0):
    """(n, 3) counts of rounded Gaussian noise of sigma LSB (AR(1) with coefficient ``rho``)."""
    e = rng.normal(0.0, sigma * np.sqrt(1 - rho ** 2), (n, 3))
    x = np.empty_like(e)
    x[0] = rng.normal(0.0, sigma, 3)
    for k in range(1, n):
        x[k] = rho * x[k - 1] + e[k]
    return (300.0 + x).round().astype(np.int16)


def test_the_parity_test_flags_the_and_of_two_streams_and_not_one():
    for seed in range(20):
        rng = np.random.default_rng(seed)
        one, two = _noisy(rng, 16.0), _noisy(rng, 16.0)
        alone = sensor_check(one, 2048)
        assert alone["parity_decided"] and alone["flags"] == []
        anded = sensor_check(one & two, 2048)
        assert anded["parity_decided"] and anded["flags"][0].endswith(TWIN)
        witness = np.mean((one & two) & 1, axis=0)  # the share, counted independently
        assert anded["odd_share"] == [round(float(v), 4) for v in witness]


def test_neighbours_tied_by_a_filter_do_not_make_one_stream_look_like_two():
    # strongly low-passed noise (AR(1), rho = 0.9: ten samples of memory) with a sample-to-sample
    # noise just above the gate; the bound counts four readings as one, the test must hold here
    for seed in range(50):
        counts = _noisy(np.random.default_rng(seed), 7.0, rho=0.9)
        check = sensor_check(counts, 2048)
        assert min(check["unpredictable_lsb"]) >= PARITY_MIN_NOISE_LSB
        assert check["parity_decided"] and check["flags"] == []


def test_the_parity_test_says_nothing_when_it_cannot_tell():
    rng = np.random.default_rng(3)
    quiet = _noisy(rng, 0.4) & _noisy(rng, 0.4)  # two devices, but too quiet for parity
    check = sensor_check(quiet, 2048)
    assert max(check["unpredictable_lsb"]) < PARITY_MIN_NOISE_LSB
    assert not check["parity_decided"] and not any(f.endswith(TWIN) for f in check["flags"])
    short = _noisy(rng, 16.0, n=MIN_PARITY_READINGS // 3) & _noisy(rng, 16.0,
                                                                  n=MIN_PARITY_READINGS // 3)
    check = sensor_check(short, 2048)  # two devices, too few readings to bound a false alarm
    assert not check["parity_decided"] and check["flags"] == []
    one_axis = _noisy(rng, 16.0) & _noisy(rng, 16.0)
    one_axis[:, :2] = _noisy(rng, 0.4)[:, :2]  # 1000 readings of one noisy axis: too few
    assert not sensor_check(one_axis, 2048)["parity_decided"]
    assert sensor_check(np.zeros((0, 3), np.int16), 2048)["odd_share"] == [None, None, None]


@pytest.mark.parametrize("bus_hz", BUSES)
def test_bit_errors_in_the_data_cannot_be_detected(bus_hz):
    # What the device guide says the driver cannot detect: I2C carries no checksum, so a bit
    # flipped in a FIFO byte is kept as a wrong sample, with no fault.
    rig, mpu, rec = _record(Faults(bit_error_rate=1e-4), bus_hz)
    assert "bit error" in {k for _, k in rig.bus.injector.log}
    # 48 bits a sample: 1 - (1 - 1e-4)^48 = 0.48 % of 1000, about 4.8 wrong ("about five" in the
    # guide); 15 or more has a binomial probability below 1e-4
    assert 0 < rig.wrong_samples(mpu, rec) < 15 and not rec.metadata["faults"]
    assert abs(1 - (1 - 1e-4) ** 48 - 0.0048) < 0.00005


def test_every_silent_fault_is_exercised_by_name():
    exercised = {"write bit flip", "register lost", "foreign read", "undercount", "bit error",
                 "clone", "stuck sensor", "second device", "pca brown-out",
                 "reset lost"}  # the last in test_device_resets.py
    assert exercised == set(SILENT_FAULTS)


@pytest.mark.parametrize("bad, words", [
    ({"flip_write": ((0x1C, 0, 1),)}, "flip_write mask"),
    ({"register_lost": ((-1.0, 0x1C, 0),)}, "register_lost time"),
    ({"foreign_reads": ((0.1, "word"),)}, "foreign_reads must read"),
    ({"foreign_reads": ((0.1, 0),)}, "foreign_reads n"),
    ({"foreign_reads": ((0.1, True),)}, "foreign_reads must read"),
    ({"drain_reads": ((-0.1, 6),)}, "drain_reads time"),
    ({"drain_reads": ((0.1, 0),)}, "drain_reads n"),
    ({"undercount_at": (-0.5,)}, "undercount_at"),
    ({"bit_error_rate": 0.7}, "bit_error_rate"),
    ({"clock_drift": 0.95}, "clock_drift"),
    ({"stuck_sensor_at": -1.0}, "stuck_sensor_at"),
])
def test_silent_fault_settings_are_checked(bad, words):
    with pytest.raises(ValueError, match=words):
        Faults(**bad)
    with pytest.raises(TypeError, match="clone_6500"):
        Faults(clone_6500=1)
    with pytest.raises(TypeError, match="second_device"):
        Faults(second_device="yes")


def _search(faults, seed=1):
    from ebantenna.device import PCA9685, PanTilt, search_and_record

    rig = SimulatedRig.for_contact(seed=seed, faults=faults)
    unit = PanTilt(PCA9685(rig.bus, clock=rig.clock))
    unit.initialize()
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    return rig, search_and_record(mpu, unit)


def test_a_pca9685_brown_out_in_the_search_is_read_back_and_set_up_again():
    # asleep at 200 Hz with its writes acknowledged: the servos went dead and the search reported
    # "no contact" 12 s later
    rig, result = _search(Faults(pca_brown_out_at=0.2))
    assert "pca brown-out" in {k for _, k in rig.bus.injector.log}
    assert result.contact_detected and result.servos_released
    (fault,) = result.summary()["pca9685_faults"]
    assert "MODE1 changed from 0x21 to 0x11" in fault
    assert "PRE_SCALE changed from 0x79 to 0x1E" in fault


def test_a_pre_scale_that_does_not_land_is_written_again_or_refused():
    from ebantenna.chips.pca9685 import Register as PcaRegister
    from ebantenna.device import PCA9685

    once = Faults(pca_flip_write=((PcaRegister.PRE_SCALE, 0x80, 1),))
    rig, result = _search(once)
    assert result.contact_detected and rig.pca.frequency() == pytest.approx(50.0, rel=1e-3)
    always = SimulatedRig.for_contact(seed=1, faults=Faults(
        pca_flip_write=((PcaRegister.PRE_SCALE, 0x80, 9),)))
    with pytest.raises(SettingError, match=r"PRE_SCALE \(0xFE\) reads back 0xF9 after 0x79"):
        PCA9685(always.bus, clock=always.clock).initialize()


def test_a_drain_costs_the_same_and_a_sample_stays_within_its_memory_budget():
    # The period estimator keeps a bounded number of observations per segment: its work per
    # count does not grow with the recording. Memory per sample is measured against the
    # allocation check's figure.
    import tracemalloc

    from ebantenna.device import mpu6050 as module
    from ebantenna.device.timing import MAX_OBSERVATIONS

    t = np.arange(12_000) / 1000.0
    rig = SimulatedRig.from_arrays(np.sin(2 * np.pi * 37 * t), np.cos(2 * np.pi * 37 * t),
                                   fs=1000.0, obstacle=None)
    rig.bus.bus_hz = 400e3
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    rig.touch()
    tracemalloc.start()
    try:
        before = tracemalloc.get_traced_memory()[0]
        rec = mpu.record(10.0, poll_interval=0.02)
        used = tracemalloc.get_traced_memory()[0] - before
    finally:
        tracemalloc.stop()
    assert rec.metadata["fifo_restarts"] == 0
    assert max(len(obs) for obs in mpu.stream.estimator.segments) <= MAX_OBSERVATIONS
    assert used / 10_000 <= module.BYTES_PER_SAMPLE
    _judge(rig, mpu, rec, 10_000)  # pruning kept the timestamps within their (true) bound


@pytest.mark.parametrize("bad", [[[1, 2, 3]], np.zeros((4, 2), np.int16), np.zeros((4, 3)),
                                 np.zeros(3, np.int16)])
def test_the_sensor_check_refuses_what_is_not_counts(bad):
    with pytest.raises(TypeError, match="counts must be an"):
        sensor_check(bad, 2048)


def _within_stated_uncertainty(rig, mpu, rec):
    """The contract for a run another reader took single samples from: every kept value is a
    sample the chip took, and lies within its stated uncertainty of that sample's true time;
    returns the kept samples and each one's timing error."""
    kept = mpu.stream.kept(0, ASKED)
    assert rec.n_samples + rec.metadata["samples_lost"] == ASKED
    true = true_times_of_values(rig, mpu, rec)
    assert not np.any(np.isnan(true) & ~kept["suspect"])  # no wrong value kept unflagged
    error = np.abs(kept["time"] - true)
    assert np.all((error <= kept["uncertainty"] + ROUND_OFF) | np.isnan(true))
    return kept, error


def _judge_take(rig, mpu, rec) -> int:
    """:func:`_within_stated_uncertainty`, and the unflagged samples one slot late (an
    undetected take, which the device guide lists under "What the driver cannot detect")."""
    kept, _ = _within_stated_uncertainty(rig, mpu, rec)
    return int(np.sum(in_wrong_slot(rig, mpu, rec) & ~kept["suspect"]))


#: Per half of the forty recordings below: the seeds whose single take went undetected (its
#: samples one slot late), as the device guide states (6 of 40, 618 to 700 samples each).
UNDETECTED_SINGLE_TAKES = ({1, 6, 16}, {26, 38, 39})


@pytest.mark.parametrize("half", [0, 1])
def test_forty_recordings_with_a_sample_taken_keep_right_values_as_the_guide_says(half):
    # device guide: one sample taken at a random time in 40 one-second recordings at 100 kHz:
    # no wrong value and no timestamp outside its bound kept unflagged; 6 of 40 keep their
    # later samples one slot late (in two halves of 20, each a few seconds)
    late = {}
    for seed in range(20 * half, 20 * half + 20):
        at = 0.05 + 0.9 * np.random.default_rng(seed).random()
        rig, mpu, rec = _record(Faults(foreign_reads=((at, "sample"),)), 100e3, seed)
        shifted = _judge_take(rig, mpu, rec)
        if shifted:
            late[seed] = shifted
    assert set(late) == UNDETECTED_SINGLE_TAKES[half]
    assert all(618 <= n <= 700 for n in late.values())


def _family(kind, n, at):
    """Another reader's theft of ``n`` (whole samples or bytes, as ``kind`` says) at ``at``."""
    if kind == "samples at once":
        return Faults(foreign_reads=((at, 6 * n),))
    if kind == "bytes at once":
        return Faults(foreign_reads=((at, n),))
    return Faults(drain_reads=((at, 6 * n if kind == "samples mid-drain" else n),))


@pytest.mark.parametrize("bus_hz", BUSES)
@pytest.mark.parametrize("kind, n", [("samples at once", 2), ("samples at once", 3),
                                     ("samples at once", 8), ("bytes at once", 4),
                                     ("bytes at once", 13), ("samples mid-drain", 1),
                                     ("samples mid-drain", 3), ("bytes mid-drain", 4)])
def test_a_foreign_reader_taking_several_samples_or_part_of_one_is_never_kept_unflagged(
        bus_hz, kind, n):
    """The kinds of theft the device guide lists as detected: several whole samples at once
    between drains (the next count contradicts the tolerance within one drain), any number of
    bytes that is not whole samples (the count is not whole samples), and samples or bytes
    taken between a drain's count and its data (the count after the data). Judged against the
    chip's truth: no wrong sample and no timestamp outside its bound is kept unflagged."""
    for seed in range(3):
        at = 0.05 + 0.9 * np.random.default_rng(2000 + seed).random()
        rig, mpu, rec = _record(_family(kind, n, at), bus_hz, seed)
        assert sum(k == "foreign read" for _, k in rig.bus.injector.log) == 1
        _judge(rig, mpu, rec)
        assert rig.wrong_samples(mpu, rec) == int(
            (in_wrong_slot(rig, mpu, rec) & mpu.stream.kept(0, ASKED)["suspect"]).sum())


@pytest.mark.parametrize("kind", ["eio", "short", "late"])
def test_part_of_a_sample_taken_mid_drain_with_a_failed_transfer_is_never_kept(kind):
    # Another reader takes 2 bytes between a drain's count and its data, and a transfer of the
    # same drain fails: the count after the data cannot be placed in time (what the failed
    # transfer took is unknown), but it is not whole samples, so the chunks kept before the
    # failure, shifted by the theft, are dropped. They were kept, X read as Y, in 10 of 40 runs
    # at 10 % failures (5 to 25 wrong samples each).
    for seed in range(12):
        faults = Faults(drain_reads=((0.755, 2),), error_rate=0.1, kinds=(kind,))
        rig, mpu, rec = _record(faults, 100e3, seed)
        assert rig.wrong_samples(mpu, rec) == int(
            (in_wrong_slot(rig, mpu, rec) & mpu.stream.kept(0, ASKED)["suspect"]).sum()) == 0
        assert rec.n_samples + rec.metadata["samples_lost"] == ASKED


def test_every_count_that_is_not_whole_samples_is_counted_as_a_foreign_read():
    # the driver reads whole samples only: a count that is not whole samples before a drain is
    # another reader's doing (or a count read wrong), and it is counted as one; it was logged
    # as a rate only, and one byte taken at 400 kHz was counted in 3 runs of 20
    noticed = 0
    for seed in range(10):
        at = 0.05 + 0.9 * np.random.default_rng(seed).random()
        _, _, rec = _record(Faults(foreign_reads=((at, "byte"),)), 400e3, seed)
        partial = sum("not a whole number of samples" in f["cause"]
                      for f in rec.metadata["faults"])
        assert rec.metadata["foreign_reads_detected"] >= partial
        noticed += partial > 0
    assert noticed >= 8  # the byte lands on a FIFO that holds samples in nearly every run


def test_a_foreign_read_of_n_bytes_takes_them_from_the_fifo():
    # the injector's own witness: n bytes at once leave the FIFO n bytes shorter
    rig, _, _ = _record(Faults(foreign_reads=((0.5, 9),)), 400e3)
    assert [k for _, k in rig.bus.injector.log].count("foreign read") == 1
    assert Faults(foreign_reads=((0.2, "sample"), (0.1, 7))).foreign_reads == (
        (0.1, 7), (0.2, "sample"))


def _times(seed, k):
    return tuple(sorted(0.05 + 0.9 * np.random.default_rng(1000 + seed).random(k)))


@pytest.mark.parametrize("bus_hz", BUSES)
def test_single_samples_taken_unseen_stay_within_the_stated_uncertainty(bus_hz):
    """A reader taking single samples at random times (device guide, "What the driver cannot
    detect"): the counts cannot tell it from a slower clock, so it may go unseen; every kept
    sample's value is still the chip's, and its true time lies within the uncertainty it
    states (the hull with its drain's anchor), flagged or not. Seeds 10 and 14 with three
    takes and 5 with four are recordings in which the segment's own uncertainty (the one true
    when no other program reads the FIFO) missed the true times of hundreds of samples at
    100 kHz: there the test checks that it did, so that the check is not idle."""
    missed = 0
    for seed, takes in ((10, 3), (14, 3), (5, 4), (0, 3)):
        faults = Faults(foreign_reads=tuple((t, "sample") for t in _times(seed, takes)))
        rig, mpu, rec = _record(faults, bus_hz, seed)
        kept, error = _within_stated_uncertainty(rig, mpu, rec)
        assert np.all(kept["uncertainty_sole_reader"] <= kept["uncertainty"])
        assert rec.metadata["timestamp_uncertainty_sole_reader_s"] == (
            kept["uncertainty_sole_reader"].max())
        missed += int(np.sum(error > kept["uncertainty_sole_reader"] + ROUND_OFF))
    if bus_hz == 100e3:
        assert missed > 0


@pytest.mark.parametrize("bus_hz", BUSES)
@pytest.mark.parametrize("kind", ["two samples taken", "two counts read low", "one of each"])
def test_counts_contradicting_twice_on_one_side_leave_every_timestamp_within_its_bound(
        bus_hz, kind):
    """Samples taken by another reader, or counts read low, twice in a recording: the stream
    cannot tell a clock from them, so it flags the samples of the segments they touched (or
    all of them). Every kept timestamp, flagged or not, still lies within its stated
    uncertainty of the chip's true time: a flagged one's bound reaches the anchors that no
    stolen sample or false count can mislead (FifoStream._anchored). Before, with two samples
    taken at 100 kHz, 258 flagged samples in 20 recordings lay outside their bound (up to
    18 ms off against 16 ms stated)."""
    for seed in range(0, 20, 3):
        at = _times(seed, 2)
        faults = {"two samples taken": Faults(foreign_reads=tuple((t, "sample") for t in at)),
                  "two counts read low": Faults(undercount_at=at),
                  "one of each": Faults(foreign_reads=((at[0], "sample"),),
                                        undercount_at=(at[1],))}[kind]
        rig, mpu, rec = _record(faults, bus_hz, seed)
        if "taken" in kind or "each" in kind:
            # one take at 100 kHz (seed 12) goes unseen: 848 samples one slot late, right
            # values and timestamps (device guide, "What the driver cannot detect")
            late = _judge_take(rig, mpu, rec)
            assert late == (848 if (kind, bus_hz, seed) == ("two samples taken", 100e3, 12)
                            else 0)
            continue
        _judge(rig, mpu, rec)
        kept = mpu.stream.kept(0, ASKED)
        error = np.abs(kept["time"] - rig.true_times(mpu, rec))
        assert np.all(error <= kept["uncertainty"] + ROUND_OFF)  # the flagged ones too
        assert rec.metadata["timestamp_uncertainty_s"] == kept["uncertainty"].max()
        # the operator is told: the flagged samples are counted, and the counts that
        # contradicted are in the fault log, with what they showed
        assert rec.metadata["samples_timing_suspect"] == 0 or any(
            "fewer" in f["cause"] or "more" in f["cause"] for f in rec.metadata["faults"])
