"""The simulated chips follow their datasheets' register rules, register by register."""

import errno

import numpy as np
import pytest

from ebantenna.chips import mpu6050 as mpu_map
from ebantenna.chips import pca9685 as pca_map
from ebantenna.device.clock import VirtualClock
from ebantenna.device.simulated import (
    FaultInjector,
    Faults,
    SimulatedBus,
    SimulatedMPU6050,
    SimulatedPCA9685,
    World,
)

R = mpu_map.Register
P = pca_map.Register


def _mpu(clock=None):
    return SimulatedMPU6050(lambda t, fs: np.ones((t.size, 3)), clock or VirtualClock())


def test_mpu6050_power_on_and_device_reset():
    mpu = _mpu()
    assert mpu.read(R.PWR_MGMT_1, 1) == [0x40] and mpu.read(R.WHO_AM_I, 1) == [0x68]
    mpu.write(R.PWR_MGMT_1, [0])
    mpu.write(R.ACCEL_CONFIG, [0x18])
    assert mpu.lsb_per_g() == 2048
    mpu.write(R.PWR_MGMT_1, [mpu_map.PowerManagement1.DEVICE_RESET])
    assert mpu.read(R.PWR_MGMT_1, 1) == [0x40] and mpu.lsb_per_g() == 16384


def test_mpu6050_read_only_registers_ignore_writes_and_reset_bits_clear_themselves():
    mpu = _mpu()
    mpu.write(R.WHO_AM_I, [0x00])
    mpu.write(R.ACCEL_XOUT_H, [0x12])
    assert mpu.read(R.WHO_AM_I, 1) == [0x68]
    mpu.write(R.USER_CTRL, [0x40 | 0x04 | 0x02 | 0x01])
    assert mpu.read(R.USER_CTRL, 1) == [0x40]


def test_mpu6050_models_only_accelerometer_data_in_the_fifo():
    with pytest.raises(ValueError, match="FIFO_EN = 0x08\\); got FIFO_EN = 0x48"):
        _mpu().write(R.FIFO_EN, [0x48])


def test_mpu6050_rates_follow_the_filter_setting():
    # RM 25: 8 kHz with the filter off (DLPF_CFG 0 or 7), 1 kHz with it on, divided by 1 + div.
    mpu = _mpu()
    for cfg, div, rate in [(0, 7, 1000.0), (1, 0, 1000.0), (3, 1, 500.0), (7, 3, 2000.0)]:
        mpu.write(R.CONFIG, [cfg])
        mpu.write(R.SMPLRT_DIV, [div])
        assert mpu.sample_rate() == rate


def test_mpu6050_burst_read_of_the_data_registers_is_one_sample():
    clock = VirtualClock()
    mpu = _mpu(clock)
    mpu.write(R.PWR_MGMT_1, [0])
    clock.sleep(0.01)
    raw = bytes(mpu.read(R.ACCEL_XOUT_H, 6))
    counts = np.frombuffer(raw, dtype=">i2")
    # 1 m/s^2 at +/-2 g: 16384 / 9.80665 LSB, rounded.
    assert counts.tolist() == [1671, 1671, 1671]


def test_pca9685_all_led_registers_write_every_output():
    pca = SimulatedPCA9685(World(None, rate=300.0), VirtualClock())
    pca.write(P.ALL_LED_OFF_L, [0x34])
    assert all(pca.regs[pca_map.led_register(ch, pca_map.Led.OFF_L)] == 0x34 for ch in range(16))
    assert pca.read(P.ALL_LED_OFF_L, 1) == [0]


def test_pca9685_auto_increment_only_with_mode1_ai():
    pca = SimulatedPCA9685(World(None, rate=300.0), VirtualClock())
    pca.write(P.LED0_ON_L, [1, 2])  # AI off: both bytes land in LED0_ON_L
    assert pca.read(P.LED0_ON_L, 2) == [2, 2]
    pca.write(P.MODE1, [pca_map.Mode1.AI | pca_map.Mode1.RESTART])
    assert pca.read(P.MODE1, 1) == [0x20]  # RESTART clears itself
    pca.write(P.LED0_ON_L, [1, 2])
    assert pca.read(P.LED0_ON_L, 2) == [1, 2]


def test_fault_injector_draws_from_its_own_seed():
    a, b = (FaultInjector(Faults(error_rate=0.5), seed=3) for _ in range(2))
    draws = [(a.transfer_error() is None, b.transfer_error() is None) for _ in range(50)]
    assert all(x == y for x, y in draws) and a.errors_injected == 50 - sum(x for x, _ in draws)
    error = FaultInjector(Faults(error_rate=0.999), seed=0).transfer_error()
    assert isinstance(error, OSError) and error.errno == errno.EREMOTEIO
    with pytest.raises(TypeError, match="faults must be a Faults"):
        SimulatedBus(faults={"error_rate": 0.1})


def test_bus_time_per_transfer():
    # 50 us overhead plus, for a read of n = 2 data bytes, (9 (n + 3) + 3) clocks at 100 kHz
    # (S, address+W, register, Sr, address+R, data, P); a write of n bytes: 9 (n + 2) + 2
    bus = SimulatedBus(devices={0x68: _mpu()}, bus_hz=100e3)
    bus.read_i2c_block_data(0x68, R.FIFO_COUNTH, 2)
    assert bus.clock.monotonic() == pytest.approx(50e-6 + 48 / 100e3, rel=1e-12)  # float sums
    start = bus.clock.monotonic()
    bus.write_i2c_block_data(0x68, R.SMPLRT_DIV, [7, 0])
    assert bus.clock.monotonic() - start == pytest.approx(50e-6 + 38 / 100e3, rel=1e-9)  # a diff


def test_the_default_calibration_drives_the_simulated_servo_to_the_commanded_angle():
    from ebantenna.device.servo import ServoCalibration
    from ebantenna.device.simulated.world import mg996r_angle

    cal = ServoCalibration(channel=0)
    for angle in (0.0, 20.0, 90.0, 160.0, 180.0):
        assert mg996r_angle(cal.pulse(angle)) == pytest.approx(angle, abs=1e-9)


def test_pca9685_power_on_sub_addresses_and_the_prescale_floor():
    pca = SimulatedPCA9685(World(None, rate=300.0), VirtualClock())
    # DS table 4: the sub-addresses and the all-call address hold their 8-bit forms after reset
    assert pca.read(P.ALLCALLADR, 1) == [0xE0]
    assert [pca.read(r, 1)[0] for r in (P.SUBADR1, P.SUBADR2, P.SUBADR3)] == [0xE2, 0xE4, 0xE8]
    # DS 7.3.5: a PRE_SCALE below 3 (written while asleep) runs as 3
    pca.write(P.PRE_SCALE, [0])
    assert pca.frequency() == pca.oscillator_hz / (4096 * 4)


@pytest.mark.parametrize("who_am_i", [mpu_map.WHO_AM_I_VALUE, 0x70])
def test_mpu6050_rate_and_sensitivity_follow_every_register_value(who_am_i):
    # The chip looks both up by register byte; the witness is RM 25 and 28 written out here:
    # 8 kHz with the filter off (DLPF_CFG 0 or 7), else 1 kHz, divided by 1 + SMPLRT_DIV (on the
    # MPU-6500 family the divider applies only when 0 < DLPF_CFG < 7); 16384 LSB/g halved per
    # step of AFS_SEL. The registers are set behind the chip's back, as a fault sets them.
    mpu = SimulatedMPU6050(lambda t, fs: np.ones((t.size, 3)), VirtualClock(), who_am_i=who_am_i)
    family_6500 = who_am_i != mpu_map.WHO_AM_I_VALUE
    for config in range(256):
        dlpf = config & 0x07
        for div in (0, 1, 7, 99, 255) if config > 8 else range(256):
            mpu.regs[R.CONFIG], mpu.regs[R.SMPLRT_DIV] = config, div
            gyro = 8000.0 if dlpf in (0, 7) else 1000.0
            expected = gyro if family_6500 and dlpf in (0, 7) else gyro / (1 + div)
            assert mpu.sample_rate() == expected, (config, div)
    for value in range(256):
        mpu.regs[R.ACCEL_CONFIG] = value
        assert mpu.lsb_per_g() == 16384 >> ((value >> 3) & 0x03)


def _played_as_masks(rig, times, fs, rng, own_noise=False):
    """The vibration played through boolean masks, whatever the block: the reference the rig's
    shortcut for a block that plays whole must equal, value for value."""
    rec, rest = rig.vibration, rig.rest
    acc = rest + rng.normal(0.0, rig.noise, (times.size, 3))
    after = times >= rig.world.contact_time - 1e-12
    if not after.any():
        return acc
    first = rig.contact_sample_time
    first = float(times[after][0]) if first is None else first
    j = np.rint((times - first) * rig.mpu.true_rate() * rec.fs / fs).astype(np.int64)
    play = after & (j >= 0) & (j < rec.n_samples)
    own = acc[play] - rest
    acc[play, 0] = rec.ax[j[play]]
    acc[play, 2] = rec.az[j[play]]
    if own_noise:
        acc[play, 0] += own[:, 0]
        acc[play, 2] += own[:, 2]
    return acc


def test_the_rig_plays_its_vibration_as_the_masked_reference_does():
    from ebantenna.device.simulated import SimulatedRig

    fs, n = 1000.0, 50
    ax, az = np.sin(np.arange(n) / 3.0), np.cos(np.arange(n) / 5.0)
    rig = SimulatedRig.from_arrays(ax, az, fs=fs, obstacle=None, seed=4)
    rig.mpu.write(R.PWR_MGMT_1, [0])
    rig.mpu.write(R.CONFIG, [1])  # 1 kHz, the vibration's rate
    rig.touch(at=0.0105)
    blocks = [np.array([0.009, 0.010]),  # before the contact: noise only
              0.0100 + np.arange(1, 4) / fs,  # the contact inside the block
              np.array([0.020, 0.021, 0.022]),  # all played
              np.array([0.030]),  # one sample
              0.0575 + np.arange(6) / fs,  # the vibration ends inside the block
              np.array([0.045, 0.025, 0.035]),  # not in order
              np.array([0.080, 0.081])]  # after its end: noise only
    for times in blocks:
        for own_noise, rng in ((False, rig._rng), (True, np.random.default_rng(9))):
            twin = np.random.default_rng()
            twin.bit_generator.state = rng.bit_generator.state
            expected = _played_as_masks(rig, times, fs, twin, own_noise)
            got = rig._acceleration(times, fs, rng, own_noise=own_noise)
            np.testing.assert_array_equal(got, expected)  # bit for bit: the same arithmetic
            assert rng.bit_generator.state == twin.bit_generator.state  # the same draws


@pytest.mark.parametrize("free_running", [False, True])
def test_a_rate_change_starts_counting_at_the_write_without_back_filling(free_running):
    # _catch_up counted (now - FIFO enable) x the NEW rate: SMPLRT_DIV set to 3 (2 kHz) after
    # 0.4 s at 1 kHz pushed 289 samples in 1 ms and overflowed the FIFO
    from ebantenna.chips.mpu6050 import Register
    from ebantenna.device import MPU6050
    from ebantenna.device.simulated import Faults, SimulatedRig

    rig = SimulatedRig.quiet(seed=1, faults=Faults(free_running_divider=free_running))
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    mpu.start_fifo()
    for _ in range(6):
        rig.clock.sleep(0.02)
        mpu.read_fifo()
    chip = rig.mpu
    pushed = chip.samples_pushed
    chip._corrupt(int(Register.SMPLRT_DIV), 3)  # 2 kHz from now on
    assert chip.samples_pushed == pushed  # the write itself produces nothing at the new rate
    rig.clock.sleep(0.001)
    chip.read(int(Register.FIFO_COUNTH), 2)  # the chip catches up when it is read
    # 1 ms at 2 kHz: two samples (one more on a free-running grid, whose tick may fall at 0)
    assert 2 <= chip.samples_pushed - pushed <= 3 and chip.overflowed_bytes == 0
    rig.clock.sleep(0.1)
    chip.read(int(Register.FIFO_COUNTH), 2)
    assert abs(chip.samples_pushed - pushed - 202) <= 1  # 101 ms at 2 kHz, to a sample
