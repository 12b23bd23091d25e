"""The whole search loop on the simulated rig: sweep, contact, stop, record, release."""

import math

import numpy as np
import pytest

from ebantenna.device import (
    MPU6050,
    PCA9685,
    ContactDetector,
    EllipticalPath,
    Faults,
    Obstacle,
    PanTilt,
    SearchConfig,
    SimulatedRig,
    VirtualClock,
    search_and_record,
)
from ebantenna.device.mpu6050 import STANDARD_GRAVITY
from ebantenna.device.watchdog import StreamStalledError

LSB = STANDARD_GRAVITY / 2048


def _ring(n=1500, fs=1000.0):
    t = np.arange(n) / fs
    ax = 25.0 * np.exp(-t / 0.12) * np.sin(2 * np.pi * 43.0 * t)
    az = -10.0 * np.exp(-t / 0.08) * np.sin(2 * np.pi * 120.0 * t)
    return ax, az


def _run(rig, config=None, **kwargs):
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    unit = PanTilt(PCA9685(rig.bus, clock=rig.clock))
    unit.initialize()
    return mpu, search_and_record(mpu, unit, config, **kwargs)


def test_path_is_an_ellipse():
    path = EllipticalPath(pan_center=80, tilt_center=95, pan_amplitude=50, tilt_amplitude=10,
                          period=3.0)
    for t in np.linspace(0, 6, 37):
        pan, tilt = path.angles(t)
        assert ((pan - 80) / 50) ** 2 + ((tilt - 95) / 10) ** 2 == pytest.approx(1.0)
    assert path.angles(0.0) == pytest.approx((80.0, 105.0))
    assert path.angles(3.0) == pytest.approx(path.angles(0.0))
    assert path.peak_rate() == pytest.approx(2 * math.pi * 50 / 3.0)


def test_detector_needs_a_full_baseline_and_ignores_offsets():
    det = ContactDetector(threshold=1.0, window=5)
    assert det.update(np.full(3, 9.8), np.zeros(3)) is None  # window not yet full
    assert det.update(np.full(3, 9.8), np.zeros(3)) is None  # a constant offset is no contact
    assert det.update([9.8, 9.9, 9.8, 11.0], [0, 0, 0.5, 0]) == 3
    with pytest.raises(ValueError, match="threshold"):
        ContactDetector(threshold=0.0)


def test_search_finds_the_post_stops_records_and_releases():
    ax, az = _ring()
    rig = SimulatedRig.from_arrays(ax, az, fs=1000.0, seed=3)
    config = SearchConfig()
    mpu, result = _run(rig, config, labels={"material": "brass"})
    assert result.contact_detected and result.servos_stopped
    rec = result.recording
    assert result.samples == rec.n_samples == 1050 and result.samples_lost == 0
    assert rec.metadata["material"] == "brass" and rec.metadata["servos_stopped"]
    assert rec.metadata["trigger_time"] == pytest.approx(0.05)
    # The simulated probe met the post during the first quarter loop.
    assert 0.2 < rig.contact_time < 1.0
    # Every sample from the contact on is the vibration's, to within one LSB (stream positions
    # are counted from the FIFO start; sample k is taken at stream_start + (k + 1) / fs).
    k_contact = round((rig.contact_sample_time - mpu.stream.starts[0]) * 1000.0) - 1
    index = rec.metadata["first_index"] + np.rint(rec.t * 1000.0).astype(int)
    j = index - k_contact
    after = j >= 0
    assert after.sum() > 1000
    assert np.max(np.abs(rec.ax[after] - ax[j[after]])) <= LSB
    assert np.max(np.abs(rec.az[after] - az[j[after]])) <= LSB
    # Before the contact only sensor noise.
    assert np.max(np.abs(rec.ax[~after])) < 0.2
    # Detected within a few samples of the contact.
    trigger = rec.metadata["first_index"] + 50
    assert 0 <= trigger - k_contact <= 3
    # Stopped at once: the pan was never commanded more than one servo update past the post...
    # (the transfers of one loop take about 5 ms on top of the poll interval).
    # (one loop to drain the contact sample, one more at most before the stop; the transfers of
    # a loop take about 10 ms at 100 kHz on top of the poll interval) ...
    assert 0 < rig.world.max_push <= config.path.peak_rate() * 2 * (config.poll_interval + 0.01)
    # ... and then held at least back_off behind the post, where the probe touched it: the
    # hold never pushes further.
    pans = [a for t, axis, a in rig.world.commands if axis == "pan" and a is not None]
    assert (pans[-1] - Obstacle().pan) * rig.world.direction <= -config.back_off + 1e-9
    # ... no new angle was commanded after the contact was detected, and then the PWM went off.
    t_detect = rig.contact_time + config.poll_interval + 0.01
    late = [(axis, a) for t, axis, a in rig.world.commands if t > t_detect]
    held = {axis: a for axis, a in late if a is not None}
    assert late and late[-1][1] is None and late[-2][1] is None
    assert len({round(a, 9) for axis, a in late if axis == "pan" and a is not None}) <= 1
    assert set(held) <= {"pan", "tilt"}
    assert not rig.pca.outputs_enabled()
    # The servo went back to the hold, off the post, before the PWM went off.
    assert (rig.world.pan.angle - Obstacle().pan) * rig.world.direction <= -config.back_off + 1e-9


def test_no_obstacle_no_contact_and_servos_released():
    rig = SimulatedRig.quiet(seed=1)
    _, result = _run(rig, SearchConfig(max_search_time=2.0))
    assert not result.contact_detected and result.recording is None
    assert result.summary()["samples"] == 0 and result.summary()["contact_detected"] is False
    assert not rig.pca.outputs_enabled()


def test_transient_errors_are_survived_and_counted():
    ax, az = _ring()
    rig = SimulatedRig.from_arrays(ax, az, fs=1000.0, seed=7, faults=Faults(error_rate=0.05))
    mpu, result = _run(rig)
    assert result.contact_detected
    assert result.samples + result.samples_lost == 1050
    assert rig.wrong_samples(mpu, result.recording) == 0
    assert result.i2c_retries + result.summary()["faults"] >= rig.bus.errors_injected > 10
    assert result.summary()["i2c_retries"] == result.i2c_retries


def test_a_stall_during_the_window_is_reported_not_hidden():
    ax, az = _ring()
    probe = SimulatedRig.from_arrays(ax, az, fs=1000.0, seed=3)
    _, first = _run(probe)
    contact = probe.contact_time
    rig = SimulatedRig.from_arrays(ax, az, fs=1000.0, seed=3,
                                   faults=Faults(stall_at=contact + 0.3, stall_duration=0.25))
    _, result = _run(rig)
    assert result.contact_detected
    assert result.samples_lost >= 250
    assert result.samples + result.samples_lost == first.samples == 1050
    assert result.recording.metadata["samples_lost"] == result.samples_lost
    assert result.stream_samples_lost >= result.samples_lost


class InterruptingClock(VirtualClock):
    """Raises KeyboardInterrupt (Ctrl-C) in the first sleep after ``at`` seconds."""

    def __init__(self, at):
        super().__init__()
        self.at = at

    def sleep(self, seconds):
        if self.monotonic() > self.at:
            raise KeyboardInterrupt
        super().sleep(seconds)


def test_ctrl_c_releases_the_servos():
    rig = SimulatedRig.quiet()
    clock = InterruptingClock(0.5)
    rig.bus.clock = clock
    rig.mpu.clock = rig.pca.clock = clock
    rig.clock = clock
    mpu = MPU6050(rig.bus, clock=clock)
    mpu.initialize()
    unit = PanTilt(PCA9685(rig.bus, clock=clock))
    unit.initialize()
    with pytest.raises(KeyboardInterrupt):
        search_and_record(mpu, unit)
    assert rig.world.commands[-1][2] is None
    assert not rig.pca.outputs_enabled()
    assert rig.mpu.regs[0x6A] & 0x40 == 0  # FIFO stopped too


def test_an_error_at_contact_releases_the_servos():
    t = np.arange(500) / 500.0
    rig = SimulatedRig.from_arrays(np.sin(t), np.cos(t), fs=500.0)  # not the sensor's 1 kHz
    with pytest.raises(ValueError, match="500 Hz but the simulated MPU-6050 is set to 1000 Hz"):
        _run(rig)
    assert not rig.pca.outputs_enabled()


def test_a_dead_bus_during_the_search_is_a_clear_error():
    ax, az = _ring()
    rig = SimulatedRig.from_arrays(ax, az, fs=1000.0, seed=2)
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    unit = PanTilt(PCA9685(rig.bus, clock=rig.clock))
    unit.initialize()
    rig.bus.devices.pop(0x68)  # the accelerometer's cable falls off
    with pytest.raises(StreamStalledError, match="0x68"):
        search_and_record(mpu, unit)
    assert not rig.pca.outputs_enabled()


def test_search_config_validation():
    with pytest.raises(ValueError, match="threshold"):
        SearchConfig(threshold=-1.0)
    with pytest.raises(TypeError, match="path"):
        SearchConfig(path=(1, 2))
    rig = SimulatedRig.quiet()
    with pytest.raises(ValueError, match="poll_interval"):
        _run(rig, SearchConfig(poll_interval=0.5))


@pytest.mark.parametrize("bus_hz, longest_step", [(100e3, 0.069), (400e3, 0.027)])
def test_the_default_back_off_exceeds_one_servo_update_along_the_default_path(bus_hz,
                                                                             longest_step):
    # SearchConfig's back_off was 3 deg, "peak 94 deg/s times 20 ms = 1.9 deg"; a step of the
    # search is the poll *and* the drain: 59-69 ms at 100 kHz, pan steps up to 6.4 deg
    from ebantenna.device.pantilt import SearchConfig, _Search

    rig = SimulatedRig(None, obstacle=None, seed=0)
    rig.bus.bus_hz = bus_hz
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    unit = PanTilt(PCA9685(rig.bus, clock=rig.clock))
    unit.initialize()
    config = SearchConfig(max_search_time=4.0)  # one loop of the path
    search = _Search(mpu, unit, config, None)
    search.run()
    c = np.array(search.commands)
    steps = np.diff(c[:, 0])
    moved = np.abs(np.diff(c[:, 1:], axis=0)).max()
    assert steps.max() <= longest_step  # the docstring's and the guide's step times
    peak = config.path.peak_rate()
    assert round(peak) == 94 and moved <= peak * longest_step
    assert round(peak * longest_step, 1) == {100e3: 6.5, 400e3: 2.5}[bus_hz]
    assert moved < config.back_off == 7.0
    if bus_hz == 100e3:  # the guide: the former 3 degrees "exceeded by 41 of 60 steps"
        per_step = np.abs(np.diff(c[:, 1:], axis=0)).max(axis=1)
        assert (int(np.sum(per_step > 3.0)), per_step.size) == (41, 60)
