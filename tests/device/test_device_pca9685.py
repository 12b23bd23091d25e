"""PCA9685 and servos against the datasheet, through the simulated chip."""

import warnings

import pytest
from hypothesis import given
from hypothesis import strategies as st

from ebantenna.device import (
    PCA9685,
    Servo,
    ServoCalibration,
    ServoLimitWarning,
    SimulatedRig,
    prescale_for,
)
from ebantenna.device.pca9685 import pwm_frequency


def _pca():
    rig = SimulatedRig.quiet()
    pca = PCA9685(rig.bus, clock=rig.clock)
    pca.initialize()
    return rig, pca


def test_prescale_follows_equation_1():
    # prescale = round(25 MHz / (4096 * f)) - 1; 50 Hz -> round(122.07) - 1 = 121.
    assert prescale_for(50.0) == 121
    assert pwm_frequency(121) == pytest.approx(25e6 / (4096 * 122))
    # The register's ends: 3 (about 1526 Hz) and 255 (about 24 Hz).
    assert prescale_for(1526.0) == 3 and prescale_for(24.0) == 253
    with pytest.raises(ValueError, match="frequency must lie in"):
        prescale_for(2000.0)
    with pytest.raises(ValueError, match="frequency must lie in"):
        prescale_for(20.0)


def test_initialize_writes_sleep_prescale_wake_restart():
    rig, pca = _pca()
    writes = [(reg, data) for addr, reg, data in rig.bus.writes if addr == 0x40]
    assert writes == [
        (0xFD, (0x10,)),  # ALL_LED_OFF_H: full off, every channel
        (0x01, (0x04,)),  # MODE2: OUTDRV totem pole, OCH = 0 (change on STOP)
        (0x00, (0x11,)),  # MODE1: SLEEP (+ ALLCALL as at power-on), RESTART written 0
        (0xFE, (121,)),  # PRE_SCALE, accepted only while asleep
        (0x00, (0x21,)),  # MODE1: awake, AI
        (0x00, (0xA1,)),  # MODE1: RESTART (after the 500 us oscillator start-up)
    ]
    assert rig.pca.prescale_blocked == 0
    assert rig.pca.frequency() == pytest.approx(pca.frequency)
    assert not rig.pca.outputs_enabled()


def test_simulated_chip_blocks_prescale_while_awake():
    # The rule the driver obeys, checked on the simulated chip: PRE_SCALE writes are ignored awake.
    rig, _ = _pca()
    rig.bus.write_byte_data(0x40, 0xFE, 30)
    assert rig.pca.regs[0xFE] == 121 and rig.pca.prescale_blocked == 1


def test_pulse_is_one_block_write_and_reads_back():
    rig, pca = _pca()
    pca.set_pulse(3, 1.5e-3)
    counts = round(1.5e-3 * pca.frequency * 4096)
    assert counts == 307
    assert rig.bus.writes[-1] == (0x40, 0x06 + 4 * 3, (0, 0, counts & 0xFF, counts >> 8))
    assert rig.pca.pulse(3) == pytest.approx(counts / (4096 * pca.frequency))
    assert pca.pulse(3) == pytest.approx(rig.pca.pulse(3))
    assert abs(pca.pulse(3) - 1.5e-3) <= 0.5 / (4096 * pca.frequency)


def test_channel_and_all_off():
    rig, pca = _pca()
    pca.set_pulse(0, 1e-3)
    pca.set_pulse(1, 2e-3)
    pca.channel_off(0)
    assert rig.pca.pulse(0) == 0 and rig.pca.pulse(1) > 0 and pca.pulse(0) == 0
    pca.all_off()
    assert not rig.pca.outputs_enabled() and pca.pulse(1) == 0


@pytest.mark.parametrize("channel, pulse, match", [(16, 1e-3, "channel"), (0, 0.03, "pulse"),
                                                   (0, 0.0, "pulse"), (-1, 1e-3, "channel")])
def test_bad_pulses_are_refused(channel, pulse, match):
    _, pca = _pca()
    with pytest.raises(ValueError, match=match):
        pca.set_pulse(channel, pulse)


@given(st.floats(0.0, 180.0))
def test_calibration_round_trips(angle):
    cal = ServoCalibration(channel=2, min_pulse=0.6e-3, max_pulse=2.4e-3, min_angle=0.0,
                           max_angle=180.0)
    assert cal.angle(cal.pulse(angle)) == pytest.approx(angle, abs=1e-9)
    assert 0.6e-3 - 1e-15 <= cal.pulse(angle) <= 2.4e-3 + 1e-15


def test_reversed_servo_is_allowed():
    cal = ServoCalibration(channel=0, min_pulse=2.5e-3, max_pulse=0.5e-3, min_angle=0.0,
                           max_angle=180.0)
    assert cal.pulse(0.0) == 2.5e-3 and cal.pulse(180.0) == 0.5e-3


@pytest.mark.parametrize("kwargs, match", [
    ({"channel": 16}, "channel"), ({"channel": 0, "min_pulse": 0.0}, "min_pulse"),
    ({"channel": 0, "min_angle": 10.0, "max_angle": 10.0}, "min_angle"),
    ({"channel": 0, "lower_limit": 100.0, "upper_limit": 50.0}, "lower_limit"),
    ({"channel": 0, "upper_limit": 200.0}, "upper_limit"),
])
def test_calibration_validation(kwargs, match):
    with pytest.raises(ValueError, match=match):
        ServoCalibration(**kwargs)


def test_servo_clamps_with_a_warning_and_commands_the_limit():
    rig, pca = _pca()
    servo = Servo(pca, ServoCalibration(0, lower_limit=30.0, upper_limit=150.0), "pan")
    with pytest.warns(ServoLimitWarning, match=r"pan servo: 10\.00 deg .* clamped to 30"):
        assert servo.move(10.0) == 30.0
    # The simulated MG996R (0.5-2.5 ms for 0-180 deg) turns to the limit, to within one count.
    count_deg = 180.0 / 2e-3 / (4096 * pca.frequency)
    assert abs(rig.world.pan.target - 30.0) <= count_deg
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert servo.move(100.0) == 100.0  # inside the limits: no warning
    servo.release()
    assert rig.pca.pulse(0) == 0 and servo.angle is None


def _default_search(bus_hz, faults=None, seconds=4.0):
    """One loop of the default search's sweep (no obstacle): the rig, the PCA9685, the search."""
    from ebantenna.device import MPU6050, PanTilt
    from ebantenna.device.pantilt import SearchConfig, _Search
    from ebantenna.device.simulated import SimulatedRig

    rig = SimulatedRig(None, obstacle=None, seed=0, faults=faults)
    rig.bus.bus_hz = bus_hz
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    unit = PanTilt(PCA9685(rig.bus, clock=rig.clock))
    unit.initialize()
    return rig, unit, _Search(mpu, unit, SearchConfig(max_search_time=seconds), None)


def test_a_pulse_flipped_on_the_wire_is_read_back_and_written_again():
    # a bit of LED0_OFF_H flipped (+5 ms): the pan servo got 6.5 ms pulses and nothing said so
    import numpy as np

    from ebantenna.device import search_and_record
    from ebantenna.device.i2c import SettingError
    from ebantenna.device.simulated import Faults

    rig, unit, search = _default_search(100e3, Faults(pca_flip_write=((0x09, 0x04, 1),)),
                                        seconds=1.0)
    pulses = []
    write = rig.pca.write

    def spy(register, data):
        write(register, data)
        pulses.append(rig.pca.pulse(0))

    rig.pca.write = spy
    search.run()
    assert "write bit flip" in {k for _, k in rig.bus.injector.log}
    (fault,) = search.report["pca9685_faults"]
    assert fault.startswith("LED0 (0x06) read back") and fault.endswith("written again")
    # the wrong pulse lasted one transfer: every later write reads back right
    assert max(pulses[pulses.index(max(pulses)) + 1:]) < 2.5e-3 < max(pulses)
    assert np.all(np.isfinite(pulses))
    # flipped three times in a row (the write and its rewrite): the search ends, released
    rig, unit, search = _default_search(100e3, Faults(pca_flip_write=((0x09, 0x04, 3),)))
    with pytest.raises(SettingError, match=r"LED0 \(0x06\) reads back .* written twice") as info:
        search_and_record(search.mpu, unit)
    assert info.value.servos_released and rig.pca.pulse(0) == 0 == rig.pca.pulse(1)


@pytest.mark.parametrize("bus_hz, step, blind_step, longest", [
    (100e3, 67.1, 63.7, 0.069), (400e3, 26.1, 25.7, 0.027)])
def test_the_pulse_read_back_costs_what_the_guide_says(bus_hz, step, blind_step, longest,
                                                       monkeypatch):
    import numpy as np

    from ebantenna.chips.pca9685 import led_register
    from ebantenna.device.i2c import TRANSFER_OVERHEAD
    from ebantenna.device.pca9685 import PULSE_READ_BACK_BITS

    # pca9685.py and the guide: one read-back 0.71 ms at 100 kHz, 0.215 ms at 400 kHz
    read_back = TRANSFER_OVERHEAD + PULSE_READ_BACK_BITS / bus_hz
    assert abs(1e3 * read_back - {100e3: 0.71, 400e3: 0.215}[bus_hz]) <= 1e-9  # float sum
    medians = []
    for blind in (False, True):
        if blind:  # the write without its read-back, as before
            monkeypatch.setattr(PCA9685, "write_channel", lambda self, channel, data:
                                self.device.write_block(led_register(channel), data))
        rig, unit, search = _default_search(bus_hz)
        search.run()
        steps = np.diff(np.array(search.commands)[:, 0])[5:]  # after the first drains
        medians.append(1e3 * np.median(steps))
        sizes = np.asarray(search.stream.drain_sizes)[5:]
        assert search.mpu.samples_lost == 0 and search.stream.overflows == 0
        if not blind:
            assert steps.max() <= longest and sizes.max() <= 68
    # the medians to the 0.1 ms printed
    assert abs(medians[0] - step) <= 0.05 and abs(medians[1] - blind_step) <= 0.05


@pytest.mark.parametrize("bus_hz, longest", [(100e3, 0.069), (400e3, 0.027)])
def test_a_brown_out_costs_at_most_one_step_of_dead_servos(bus_hz, longest):
    # pantilt.py said 0.2 s (10 steps of 20 ms): 0.505 s measured at 100 kHz; now the next
    # pulse reads back wrong, the chip is set up again at that step and the pulse commanded
    from ebantenna.device.simulated import Faults

    worst = 0.0
    for at in (1.0, 1.13, 1.29, 1.41):
        rig, unit, search = _default_search(bus_hz, Faults(pca_brown_out_at=at), seconds=2.5)
        again = []
        initialize = unit.initialize
        unit.initialize = lambda rig=rig, again=again, initialize=initialize: (
            again.append(rig.clock.monotonic()), initialize())
        search.run()
        (browned,) = [t for t, k in rig.bus.injector.log if k == "pca brown-out"]
        assert again and len(search.report["pca9685_faults"]) == 1
        # dead from the brown-out until the first pulse commanded after the set-up (which
        # switches every output off)
        pulsed = min(t for t, *_ in search.commands if t > again[0])
        worst = max(worst, pulsed - browned)
    assert worst <= longest
    assert f"{1e3 * worst:.0f}" == {100e3: "36", 400e3: "9"}[bus_hz]  # the guide's "measured"
