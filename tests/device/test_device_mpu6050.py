"""The MPU-6050 driver against the datasheet's registers and the simulated chip."""

import logging

import numpy as np
import pytest

from ebantenna.device import (
    MPU6050,
    ChipIdentityError,
    Faults,
    MPU6050Config,
    SimulatedRig,
    sample_rate_divider,
)
from ebantenna.device.mpu6050 import STANDARD_GRAVITY, accel_bandwidth

LSB = STANDARD_GRAVITY / 2048  # one count at +/-16 g, m/s^2


def test_sample_rate_rule_of_register_25():
    # Every divider the register can hold, for every filter setting, inverts the datasheet's rule.
    for dlpf in range(7):
        gyro_rate = 8000.0 if dlpf == 0 else 1000.0
        for div in range(256):
            fs = gyro_rate / (1 + div)
            if fs <= 1000.0:
                assert sample_rate_divider(fs, dlpf) == div
    assert sample_rate_divider(1000.0, 0) == 7
    assert sample_rate_divider(1000.0, 1) == 0


@pytest.mark.parametrize("fs, dlpf, match", [(2000.0, 0, "1000 Hz"), (300.0, 1, "integer n"),
                                             (1000.0, 7, "dlpf_cfg"), (-1.0, 0, "fs")])
def test_sample_rate_rule_rejects_impossible_rates(fs, dlpf, match):
    with pytest.raises(ValueError, match=match):
        sample_rate_divider(fs, dlpf)


def test_table_2_pass_band_exceeds_the_accelerometer_bandwidth():
    # The paper's elliptic pass band reaches 325 Hz; the widest accelerometer bandwidth is 260 Hz.
    assert max(accel_bandwidth(d) for d in range(7)) == 260.0 < 325.0
    assert MPU6050Config().bandwidth == 260.0


def test_config_validation():
    with pytest.raises(ValueError, match="full_scale_g"):
        MPU6050Config(full_scale_g=12)
    with pytest.raises(ValueError, match="address"):
        MPU6050Config(address=0x70)


def test_initialize_writes_the_datasheet_sequence():
    rig = SimulatedRig.quiet()
    MPU6050(rig.bus, clock=rig.clock).initialize()
    writes = [(reg, data) for addr, reg, data in rig.bus.writes if addr == 0x68]
    assert writes == [
        (0x6B, (0x80,)),  # PWR_MGMT_1: DEVICE_RESET
        (0x6A, (0x00,)),  # USER_CTRL: FIFO off while the clock starts
        (0x6B, (0x01,)),  # PWR_MGMT_1: awake, CLKSEL = 1 (PLL, X gyro)
        (0x1A, (0x00,)),  # CONFIG: DLPF_CFG = 0 (260 Hz)
        (0x19, (0x07,)),  # SMPLRT_DIV: 8 kHz / (1 + 7) = 1 kHz
        (0x1C, (0x18,)),  # ACCEL_CONFIG: AFS_SEL = 3, +/-16 g
        (0x38, (0x10,)),  # INT_ENABLE: FIFO_OFLOW_EN
    ]
    # The simulated chip decodes the same registers independently.
    assert rig.mpu.sample_rate() == 1000.0
    assert rig.mpu.lsb_per_g() == 2048


def test_alternative_filter_setting_gives_the_same_rate():
    rig = SimulatedRig.quiet()
    MPU6050(rig.bus, MPU6050Config(dlpf_cfg=1), clock=rig.clock).initialize()
    assert rig.mpu.regs[0x19] == 0 and rig.mpu.regs[0x1A] == 1
    assert rig.mpu.sample_rate() == 1000.0


def test_wrong_chip_is_a_clear_error_and_nothing_is_written():
    rig = SimulatedRig.quiet(faults=Faults(who_am_i=0x72))
    mpu = MPU6050(rig.bus, clock=rig.clock)
    with pytest.raises(ChipIdentityError, match=r"0x68 is not an MPU-6050: WHO_AM_I reads 0x72"):
        mpu.initialize()
    assert rig.bus.writes == []


def _rig_with(ax, az, **kwargs):
    rig = SimulatedRig.from_arrays(ax, az, fs=1000.0, obstacle=None, **kwargs)
    rig.touch()
    return rig


def _vibration(n, seed=0, amplitude=60.0):
    rng = np.random.default_rng(seed)
    t = np.arange(n) / 1000.0
    ax = amplitude * np.exp(-t / 0.2) * np.sin(2 * np.pi * 37.0 * t) + rng.normal(0, 0.3, n)
    az = 0.4 * amplitude * np.exp(-t / 0.15) * np.cos(2 * np.pi * 91.0 * t)
    return ax, az


@pytest.mark.parametrize("use_rdwr", [False, True])
def test_fifo_recording_matches_the_source_to_within_one_lsb(use_rdwr):
    ax, az = _vibration(800)
    rig = _rig_with(ax, az)
    mpu = MPU6050(rig.bus, clock=rig.clock, use_rdwr=use_rdwr)
    mpu.initialize()
    rec = mpu.record(0.5)
    assert rec.n_samples == 500 and rec.metadata["samples_lost"] == 0
    # The estimated rate brackets the chip's exact 1 kHz; t is the slot grid at that period.
    assert abs(1 / rec.fs - 1e-3) <= rec.metadata["sample_period_uncertainty_s"]
    np.testing.assert_allclose(rec.t, np.arange(500) / rec.fs, rtol=0, atol=1e-12)
    # Quantisation to the nearest count: at most half an LSB off, so certainly within one.
    assert np.max(np.abs(rec.ax - ax[:500])) <= 0.5 * LSB + 1e-12
    assert np.max(np.abs(rec.az - az[:500])) <= 0.5 * LSB + 1e-12
    assert np.max(np.abs(rec.ax - ax[:500])) > 0.01 * LSB  # really quantised, not passed through


def test_fifo_reads_never_exceed_the_smbus_block_limit():
    ax, az = _vibration(300)
    rig = _rig_with(ax, az)
    sizes = []
    original = rig.bus.read_i2c_block_data

    def spy(addr, reg, length, force=None):
        sizes.append((reg, length))
        return original(addr, reg, length)

    rig.bus.read_i2c_block_data = spy
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    mpu.record(0.2, poll_interval=0.05)
    fifo_reads = [n for reg, n in sizes if reg == 0x74]
    assert fifo_reads and max(fifo_reads) <= 30 and all(n % 6 == 0 for n in fifo_reads)


def test_latest_sample_is_read_in_one_burst():
    ax, az = np.full(100, 3.0), np.full(100, -7.5)
    rig = _rig_with(ax, az, noise=0.0)
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    rig.clock.sleep(0.01)
    before = rig.bus.transfers
    acc = mpu.read_acceleration()
    assert rig.bus.transfers == before + 1
    np.testing.assert_allclose(acc, [3.0, 0.0, -7.5], atol=0.5 * LSB)


def test_polling_slower_than_the_fifo_holds_is_refused():
    rig = SimulatedRig.quiet()
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    # 170 samples, three kept free, at 1050 Hz (the clock's tolerance) while a 100 kHz bus
    # drains 5 samples per 300 clocks and 50 us: 167 (1 - 1050 * 0.61e-3) / 1050 s, less the
    # 3.36 ms of fixed transfers of a drain: the counts before and after (2 + 2 bytes) and the
    # settings read back (4, 1, 3 and 2 bytes), 50 us + 9 (n + 3) + 3 clocks each (a read sends
    # the address twice)
    with pytest.raises(ValueError, match=r"poll_interval must be < 0\.0538 s"):
        mpu.record(1.0, poll_interval=0.3)
    with pytest.raises(ValueError, match=r"poll_interval must be < 0\.0538 s"):
        mpu.record(1.0, poll_interval=0.1)  # it overflowed twice at 100 kHz: now refused


@pytest.mark.parametrize("bus_hz", [100e3, 400e3])
def test_the_poll_interval_limit_keeps_the_fifo_from_overflowing(bus_hz):
    # Just under the limit, with the clock 5 % fast (the tolerance the limit assumes): no
    # overflow, no sample lost.
    rig = SimulatedRig.quiet(faults=Faults(clock_drift=0.05))
    rig.bus.bus_hz = bus_hz
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    rec = mpu.record(1.0, poll_interval=0.999 * mpu.max_poll_interval())
    assert rec.metadata["fifo_overflows"] == 0 and rec.metadata["samples_lost"] == 0


def test_a_register_read_is_charged_the_address_twice():
    # S addr+W A reg A Sr addr+R A data... P: the model counted the address once, and the poll
    # limit (57.8 ms at 100 kHz) let a clock 5 % fast overflow at 57 ms (482 of 2000 lost)
    from ebantenna.device.i2c import TRANSFER_OVERHEAD, transfer_bits

    assert (transfer_bits(1), transfer_bits(1, read=True)) == (29, 39)
    rig = SimulatedRig.quiet()
    start = rig.clock.monotonic()
    rig.bus.read_i2c_block_data(0x68, 0x72, 2)  # FIFO_COUNT, as a drain reads it
    assert rig.clock.monotonic() - start == pytest.approx(
        TRANSFER_OVERHEAD + transfer_bits(2, read=True) / 100e3, rel=1e-12)  # float round-off
    mpu = MPU6050(rig.bus, clock=rig.clock)
    assert round(1e3 * mpu.max_poll_interval(), 1) == 53.8
    rig = SimulatedRig.quiet(faults=Faults(clock_drift=0.05))
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    with pytest.raises(ValueError, match="poll_interval"):
        mpu.record(2.0, poll_interval=0.057)  # accepted before, and it overflowed


@pytest.mark.parametrize("stall", [0.2, 0.45])
def test_a_stalled_host_loses_samples_and_says_how_many(stall):
    ax, az = _vibration(2000)
    rig = _rig_with(ax, az, faults=Faults(stall_at=0.4, stall_duration=stall))
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    rec = mpu.record(1.0)
    lost = rec.metadata["samples_lost"]
    assert mpu.overflows == 1
    # Lost: the stall, the drain interval and the restart around it (a few ms at 100 kHz).
    assert stall * 1000 <= lost <= (stall + 0.02) * 1000 + 80
    assert rec.n_samples + lost == 1000  # every slot accounted for
    assert rec.metadata["fifo_overflows"] == mpu.overflows
    assert rig.wrong_samples(mpu, rec) == 0  # the chip's own record of what it produced


def test_bus_errors_on_fifo_reads_cost_samples_never_right_ones():
    ax, az = _vibration(1200)
    rig = _rig_with(ax, az, faults=Faults(error_rate=0.05), seed=4)
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    rec = mpu.record(1.0)
    assert rig.bus.errors_injected > 0
    assert rec.n_samples + rec.metadata["samples_lost"] == 1000
    assert rig.wrong_samples(mpu, rec) == 0
    assert rec.metadata["i2c_retries"] + len(rec.metadata["faults"]) >= rig.bus.errors_injected


def test_saturation_is_counted_and_logged(caplog):
    ax = np.full(300, 200.0)  # beyond 16 g = 156.9 m/s^2
    rig = _rig_with(ax, np.zeros(300), noise=0.0)
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    with caplog.at_level(logging.WARNING, logger="ebantenna.device.mpu6050"):
        rec = mpu.record(0.1)
    assert rec.metadata["samples_saturated"] == 100
    assert rec.ax.max() == pytest.approx(32767 * LSB)
    assert "limit" in caplog.text


def test_read_fifo_before_start_is_an_error():
    rig = SimulatedRig.quiet()
    mpu = MPU6050(rig.bus, clock=rig.clock)
    with pytest.raises(ValueError, match="start_fifo"):
        mpu.read_fifo()


def test_a_compatible_chip_is_accepted_with_a_warning():
    from ebantenna.device import CompatibleChipWarning

    rig = SimulatedRig.quiet(faults=Faults(who_am_i=0x70))
    mpu = MPU6050(rig.bus, clock=rig.clock)
    with pytest.warns(CompatibleChipWarning, match="MPU-6500"):
        mpu.initialize()
    assert mpu.part == "MPU-6500" and mpu.metadata()["device"] == "MPU-6500"


def test_wake_waits_follow_the_datasheet():
    # 100 ms after the device reset, 30 ms (gyro start-up, PS 6.1) after waking on the PLL.
    rig = SimulatedRig.quiet()
    sleeps = []
    original = rig.clock.sleep
    rig.clock.sleep = lambda s: (sleeps.append(s), original(s))[1]
    MPU6050(rig.bus, clock=rig.clock).initialize()
    assert sleeps == [0.1, 0.03]
