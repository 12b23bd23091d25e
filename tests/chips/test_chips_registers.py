"""The chips' register maps: consistent in themselves and with what the datasheets derive."""

import re

import pytest

from ebantenna.chips import BitField
from ebantenna.chips import mpu6050 as mpu
from ebantenna.chips import pca9685 as pca


@pytest.mark.parametrize("enum", [mpu.Register, pca.Register])
def test_no_two_register_names_share_an_address(enum):
    # An IntEnum silently turns a repeated value into an alias; a typo would hide that way.
    assert len(enum.__members__) == len(list(enum)), [
        name for name, member in enum.__members__.items() if member.name != name]


def test_bit_field_round_trip_and_bounds():
    field = BitField(register=0x10, shift=2, width=3)
    for value in range(8):
        byte = field.put(value, 0b1110_0011)
        assert field.get(byte) == value and byte & ~field.mask & 0xFF == 0b1110_0011
    with pytest.raises(ValueError, match="value must be <= 7, got 8"):
        field.put(8)
    with pytest.raises(ValueError, match="width must be <= 3, got 4"):
        BitField(register=0, shift=5, width=4)
    with pytest.raises(ValueError, match="register must be <= 255"):
        BitField(register=256, shift=0, width=1)


def test_mpu6050_sensitivity_is_the_16_bit_span_over_the_range():
    # PS table 6.2 lists the sensitivities; a signed 16-bit count spans 2^15 per full scale.
    for afs_sel, (g, lsb) in enumerate(zip(mpu.ACCEL_RANGES_G, mpu.ACCEL_LSB_PER_G, strict=True)):
        assert lsb * g == 2**15
        assert mpu.AFS_SEL.put(afs_sel) == afs_sel << 3


def test_mpu6050_filter_table_and_rates():
    bandwidths = [s.accel_bandwidth for s in mpu.DLPF]
    assert bandwidths == sorted(bandwidths, reverse=True) and len(mpu.DLPF) == mpu.DLPF_CFG.maximum
    delays = [s.accel_delay for s in mpu.DLPF]
    assert delays == sorted(delays)
    for cfg, setting in enumerate(mpu.DLPF):
        assert mpu.gyro_output_rate(cfg) == setting.gyro_rate
    with pytest.raises(ValueError, match="dlpf_cfg must be <= 7, got 8"):
        mpu.gyro_output_rate(8)


def test_mpu6050_fields_sit_in_their_registers_and_power_on_state():
    assert mpu.DLPF_CFG.mask | mpu.EXT_SYNC_SET.mask == 0b0011_1111
    assert mpu.CLKSEL.put(mpu.ClockSource.PLL_X_GYRO) == 0x01
    assert mpu.POWER_ON[mpu.Register.PWR_MGMT_1] == mpu.PowerManagement1.SLEEP
    assert mpu.POWER_ON[mpu.Register.WHO_AM_I] == mpu.WHO_AM_I_VALUE == mpu.ADDRESS_AD0_LOW
    assert mpu.READ_ONLY >= {mpu.Register.FIFO_COUNTH, mpu.Register.ACCEL_XOUT_H}
    assert mpu.Register.FIFO_EN not in mpu.READ_ONLY
    # A FIFO sample with only the accelerometer enabled is the block ACCEL_XOUT_H..ACCEL_ZOUT_L.
    assert mpu.ACCEL_SAMPLE_BYTES == mpu.Register.ACCEL_ZOUT_L - mpu.Register.ACCEL_XOUT_H + 1


def test_pca9685_output_registers_fill_the_gap_before_all_led():
    first = pca.led_register(0)
    last = pca.led_register(pca.N_CHANNELS - 1, pca.Led.OFF_H)
    assert first == pca.Register.LED0_ON_L and last == 0x45
    assert last < pca.Register.ALL_LED_ON_L
    assert [pca.all_led_register(p) for p in pca.Led] == [
        pca.Register.ALL_LED_ON_L, pca.Register.ALL_LED_ON_H, pca.Register.ALL_LED_OFF_L,
        pca.Register.ALL_LED_OFF_H]
    with pytest.raises(ValueError, match="channel must be <= 15, got 16"):
        pca.led_register(16)


def test_pca9685_counts_split_and_join():
    for count in (0, 1, 255, 256, 307, 4095):
        low, high = pca.split_count(count)
        assert pca.join_count(low, high) == count
        assert pca.join_count(low, high | pca.LED_FULL) == count  # the full bit is not a count
    with pytest.raises(ValueError, match="count must be <= 4095, got 4096"):
        pca.split_count(4096)


def test_pca9685_prescale_range_matches_the_frequency_range_of_the_datasheet():
    # DS 1 "General description": 24 Hz to 1526 Hz with the 25 MHz oscillator.
    per_period = pca.COUNTS_PER_PERIOD
    assert round(pca.OSCILLATOR_HZ / (per_period * (pca.PRESCALE_MAX + 1))) == 24
    assert round(pca.OSCILLATOR_HZ / (per_period * (pca.PRESCALE_MIN + 1))) == 1526
    assert pca.POWER_ON[pca.Register.MODE1] == 0x11 and pca.POWER_ON[pca.Register.MODE2] == 0x04


def test_the_compatible_parts_not_modelled_are_refused_as_their_doc_says():
    # the doc of COMPATIBLE_WHO_AM_I said "accepted with a warning only", while WHO_AM_I 0x98
    # (ICM-20689) raises ChipIdentityError, as the driver and the device guide say
    import inspect
    import warnings

    from ebantenna.device.mpu6050 import MPU6050, ChipIdentityError
    from ebantenna.device.simulated import Faults, SimulatedRig

    source = inspect.getsource(mpu)
    doc = source[:source.index("COMPATIBLE_WHO_AM_I = {")].rsplit("\n\n", 1)[-1]
    assert "accepted with a warning only" not in doc and "refused by name" in doc
    for who_am_i, name in mpu.COMPATIBLE_WHO_AM_I.items():
        rig = SimulatedRig.quiet(faults=Faults(who_am_i=who_am_i))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            if who_am_i in mpu.CHIP_MODELS:
                MPU6050(rig.bus, clock=rig.clock).initialize()  # driven as what it is
                continue
            with pytest.raises(ChipIdentityError, match=f"{name}.*not supported"):
                MPU6050(rig.bus, clock=rig.clock).initialize()


def test_a_pulse_refused_by_the_pca9685_is_told_the_range_it_can_make():
    # 2 us was refused with "pulse must lie in (0, 0.019984] s", a range holding 2 us; the
    # counts 1 to 4095 are pulses from half a count on
    from ebantenna.device.pca9685 import PCA9685
    from ebantenna.device.simulated import SimulatedRig

    p = PCA9685(SimulatedRig.quiet().bus)
    count = 1.0 / (pca.COUNTS_PER_PERIOD * p.frequency)
    for pulse in (2e-6, 0.49 * count, (pca.COUNTS_PER_PERIOD - 0.49) * count, 0.02):
        with pytest.raises(ValueError, match="pulse") as info:
            p.counts_for(pulse)
        low, high = map(float, re.search(r"in \(([\d.]+), ([\d.]+)\) us", str(info.value))
                        .groups())
        assert not low <= pulse * 1e6 < high  # the range stated does not hold it
        assert low == pytest.approx(0.5e6 * count, abs=1e-3)  # printed to 1 ns
    assert p.counts_for(0.51 * count) == 1
    assert p.counts_for((pca.COUNTS_PER_PERIOD - 0.51) * count) == pca.COUNTS_PER_PERIOD - 1
