"""The input contract of the simulated rig and of the driver's lower layers.

The simulated bus, its fault injector, the simulated chips, the world of servos and post, the
rig and its ground truth, the period estimator's counts, the I2C device, the MPU-6050's poll
and conversion helpers, the watchdog and the servo guard: each row gives a bad input, refused
with a ValueError or TypeError naming the parameter, or a good one whose answer is checked by
hand (register layouts from the datasheets, times from the bus's clock arithmetic).
"""

from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, check_row  # noqa: E402

from ebantenna.device import MPU6050, PCA9685  # noqa: E402
from ebantenna.device.clock import VirtualClock  # noqa: E402
from ebantenna.device.fifo import FifoBlock, StreamFault  # noqa: E402
from ebantenna.device.i2c import I2CDevice, transfer_bits, transfer_time  # noqa: E402
from ebantenna.device.mpu6050_config import accel_bandwidth  # noqa: E402
from ebantenna.device.oe import OutputEnable  # noqa: E402
from ebantenna.device.pantilt import PanTilt, servo_bus_time  # noqa: E402
from ebantenna.device.pca9685 import pwm_frequency  # noqa: E402
from ebantenna.device.plan import Plan, Touch, session_time  # noqa: E402
from ebantenna.device.recording_session import (  # noqa: E402
    Connection,
    file_sha256,
    write_atomic,
)
from ebantenna.device.safety import MAX_HELD_RETRY, ServoGuard  # noqa: E402
from ebantenna.device.servo import ServoCalibration  # noqa: E402
from ebantenna.device.simulated import Faults, SimulatedRig  # noqa: E402
from ebantenna.device.simulated.faults import FaultInjector  # noqa: E402
from ebantenna.device.simulated.mpu6050 import SimulatedMPU6050  # noqa: E402
from ebantenna.device.simulated.pca9685 import SimulatedLine, SimulatedPCA9685  # noqa: E402
from ebantenna.device.simulated.touches import simulated_connect  # noqa: E402
from ebantenna.device.simulated.world import (  # noqa: E402
    Obstacle,
    ServoMotion,
    World,
    mg996r_angle,
)
from ebantenna.device.timing import PeriodEstimator  # noqa: E402
from ebantenna.device.watchdog import check_watchdog, record_stream, stop_quietly  # noqa: E402
from ebantenna.device.wiring import Wire, draw_wiring, servo_supply_current  # noqa: E402

NAN, INF = math.nan, math.inf


def _rig():
    return SimulatedRig.quiet(seed=3)


def _mpu():
    rig = _rig()
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    return mpu


def _chip():
    return SimulatedMPU6050(lambda t, fs: np.zeros((t.size, 3)), VirtualClock())


def _pca():
    return SimulatedPCA9685(World(None, 300.0), VirtualClock())


def _injector(**faults):
    return FaultInjector(Faults(**faults), 0)


def _estimator():
    est = PeriodEstimator(1e-3)
    est.begin(before=0.0, after=3e-4)
    return est


def _device():
    return I2CDevice(_rig().bus, 0x68)


def _bus_clock(call):
    """The virtual time a call on a fresh simulated bus took, s."""
    bus = _rig().bus
    start = bus.clock.monotonic()
    call(bus)
    return bus.clock.monotonic() - start


B = "ebantenna.device.simulated.bus.SimulatedBus."
F = "ebantenna.device.simulated.faults.FaultInjector"
M = "ebantenna.device.simulated.mpu6050.SimulatedMPU6050"
P = "ebantenna.device.simulated.pca9685.SimulatedPCA9685"
R = "ebantenna.device.simulated.rig.SimulatedRig."
W = "ebantenna.device.simulated.world."
T = "ebantenna.device.timing.PeriodEstimator."
D = "ebantenna.device.i2c.I2CDevice."
U = "ebantenna.device.mpu6050.MPU6050."

#: ``surface -> [(id, call, names or None, same)]``
ROWS = {
    B + "read_byte_data": [
        ("i2c_addr-128", lambda: _rig().bus.read_byte_data(128, 0), ("i2c_addr",), None),
        ("register-256", lambda: _rig().bus.read_byte_data(0x68, 256), ("register",), None),
        ("register-str", lambda: _rig().bus.read_byte_data(0x68, "0"), ("register",), None),
        # WHO_AM_I of the MPU-6050 (RM 4.32): 0x68
        ("who-am-i", lambda: _rig().bus.read_byte_data(0x68, 0x75), None, lambda r: r == 0x68),
    ],
    B + "write_byte_data": [
        ("value-256", lambda: _rig().bus.write_byte_data(0x68, 0x6B, 256), ("value",), None),
        ("value-float", lambda: _rig().bus.write_byte_data(0x68, 0x6B, 1.5), ("value",), None),
        ("i2c_addr-negative", lambda: _rig().bus.write_byte_data(-1, 0x6B, 0), ("i2c_addr",),
         None),
    ],
    B + "read_i2c_block_data": [
        ("length-33", lambda: _rig().bus.read_i2c_block_data(0x68, 0x3B, 33), ("length",),
         None),
        ("length-negative", lambda: _rig().bus.read_i2c_block_data(0x68, 0x3B, -1),
         ("length",), None),
        ("length-str", lambda: _rig().bus.read_i2c_block_data(0x68, 0x3B, "6"), ("length",),
         None),
        # 6 bytes of a quiet chip, asleep at power-on: the data registers read 0
        ("six-bytes", lambda: _rig().bus.read_i2c_block_data(0x68, 0x3B, 6), None,
         lambda r: len(r) == 6),
    ],
    B + "write_i2c_block_data": [
        ("data-300", lambda: _rig().bus.write_i2c_block_data(0x40, 0x06, [300]), ("data",),
         None),
        ("data-33-bytes", lambda: _rig().bus.write_i2c_block_data(0x40, 0x06, [0] * 33),
         ("data",), None),
        ("data-int", lambda: _rig().bus.write_i2c_block_data(0x40, 0x06, 5), ("data",), None),
        # a 4-byte write costs 50 us + (1 + 1 + 4 bytes + address) 9-bit frames at 100 kHz
        ("bus-time", lambda: _bus_clock(lambda b: b.write_i2c_block_data(0x40, 6, [0] * 4)),
         None, lambda r: math.isclose(r, 50e-6 + transfer_bits(4) / 100e3, rel_tol=1e-12)),
    ],
    B + "i2c_rdwr": [
        ("no-messages", lambda: _rig().bus.i2c_rdwr(), ("i2c_rdwr",), None),
        ("not-messages", lambda: _rig().bus.i2c_rdwr(1, 2), ("msgs",), None),
    ],
    F: [
        ("faults-dict", lambda: FaultInjector({}, 0), ("faults",), None),
        ("seed-negative", lambda: FaultInjector(Faults(), -1), ("seed",), None),
        ("seed-float", lambda: FaultInjector(Faults(), 1.5), ("seed",), None),
    ],
    F + ".chip_reset": [
        ("now-nan", lambda: _injector(chip_reset_at=1.0).chip_reset(NAN), ("now",), None),
        ("now-str", lambda: _injector(chip_reset_at=1.0).chip_reset("2"), ("now",), None),
        ("once", lambda: [(i := _injector(chip_reset_at=1.0)).chip_reset(0.5),
                          i.chip_reset(1.5), i.chip_reset(2.0)], None,
         lambda r: r == [False, True, False]),
    ],
    F + ".draw": [
        ("now-nan", lambda: _injector().draw(NAN), ("now",), None),
        ("none-at-rate-0", lambda: [_injector().draw(1.0) for _ in range(5)], None,
         lambda r: r == [None] * 5),
    ],
    F + ".early_error": [
        ("kind-unknown", lambda: _injector().early_error("late"), ("kind",), None),
        ("kind-int", lambda: _injector().early_error(5), ("kind",), None),
        ("nack-is-121", lambda: _injector().early_error("nack").errno, None,
         lambda r: r == 121),
    ],
    F + ".host_stall": [
        ("now-negative", lambda: _injector().host_stall(-1.0), ("now",), None),
        ("now-inf", lambda: _injector().host_stall(INF), ("now",), None),
        ("once", lambda: [(i := _injector(stall_at=1.0, stall_duration=0.5)).host_stall(0.9),
                          i.host_stall(1.2), i.host_stall(2.0)], None,
         lambda r: r == [0.0, 0.5, 0.0]),
    ],
    F + ".preemption": [
        ("now-nan", lambda: _injector(slow_host=(0.5, 0.1)).preemption(NAN), ("now",), None),
        ("never-without-it", lambda: [_injector().preemption(1.0) for _ in range(5)], None,
         lambda r: r == [0.0] * 5),
    ],
    F + ".short_length": [
        ("length-0", lambda: _injector().short_length(0), ("length",), None),
        ("length-float", lambda: _injector().short_length(2.5), ("length",), None),
        ("below-length", lambda: [_injector().short_length(4) for _ in range(20)], None,
         lambda r: all(0 <= v < 4 for v in r)),
    ],
    F + ".stuck": [
        ("now-nan", lambda: _injector(stuck_at=1.0, stuck_duration=1.0).stuck(NAN), ("now",),
         None),
        ("window", lambda: [_injector(stuck_at=1.0, stuck_duration=1.0).stuck(t) is None
                            for t in (0.5, 1.5, 2.5)], None,
         lambda r: r == [True, False, True]),
    ],
    F + ".timeout_wait": [
        ("error-int", lambda: _injector().timeout_wait(110), ("error",), None),
        ("timeout-only", lambda: [_injector(transfer_timeout=1.0).timeout_wait(OSError(e, ""))
                                  for e in (110, 5)], None, lambda r: r == [1.0, 0.0]),
    ],
    "ebantenna.device.simulated.faults.Faults.every_kind": [
        ("error_rate-1", lambda: Faults.every_kind(1.0), ("error_rate",), None),
        ("error_rate-nan", lambda: Faults.every_kind(NAN), ("error_rate",), None),
        ("kinds-twice", lambda: Faults.every_kind(0.1, kinds=("nack",)), ("kinds",), None),
        ("all-kinds", lambda: Faults.every_kind(0.1).kinds, None, lambda r: len(r) == 8),
    ],
    M: [
        ("source-not-callable", lambda: SimulatedMPU6050(3, VirtualClock()), ("source",), None),
        ("clock-none", lambda: SimulatedMPU6050(lambda t, fs: t, None), ("clock",), None),
        ("who_am_i-256", lambda: SimulatedMPU6050(lambda t, fs: t, VirtualClock(),
                                                  who_am_i=256), ("who_am_i",), None),
        ("clock_drift-nan", lambda: SimulatedMPU6050(lambda t, fs: t, VirtualClock(),
                                                     clock_drift=NAN), ("clock_drift",), None),
        ("clock_drift-minus-1", lambda: SimulatedMPU6050(lambda t, fs: t, VirtualClock(),
                                                         clock_drift=-1.0), ("clock_drift",),
         None),
    ],
    M + ".read": [
        ("register-256", lambda: _chip().read(256, 1), ("register",), None),
        ("length-negative", lambda: _chip().read(0x75, -1), ("length",), None),
        ("length-str", lambda: _chip().read(0x75, "1"), ("length",), None),
        ("who-am-i", lambda: _chip().read(0x75, 1), None, lambda r: r == [0x68]),
    ],
    M + ".write": [
        ("register-256", lambda: _chip().write(256, [0]), ("register",), None),
        ("data-256", lambda: _chip().write(0x6B, [256]), ("data",), None),
        ("data-int", lambda: _chip().write(0x6B, 0), ("data",), None),
        # PWR_MGMT_1 = 0 wakes the chip (RM 4.28): it reads back 0
        ("reads-back", lambda: [(c := _chip()).write(0x6B, [0]), c.read(0x6B, 1)][1], None,
         lambda r: r == [0]),
    ],
    M + ".truth": [
        ("epoch-negative", lambda: _chip().truth(-1), ("epoch",), None),
        ("epoch-none-begun", lambda: _chip().truth(0), ("epoch",), None),
        ("epoch-str", lambda: _chip().truth("0"), ("epoch",), None),
    ],
    "ebantenna.device.simulated.pca9685.SimulatedLine": [
        ("drive-not-callable", lambda: SimulatedLine(3), ("drive",), None),
    ],
    P: [
        ("world-none", lambda: SimulatedPCA9685(None, VirtualClock()), ("world",), None),
        ("pan_channel-16", lambda: SimulatedPCA9685(World(None, 300.0), VirtualClock(),
                                                    pan_channel=16), ("pan_channel",), None),
        ("same-channels", lambda: SimulatedPCA9685(World(None, 300.0), VirtualClock(),
                                                   pan_channel=1, tilt_channel=1),
         ("tilt_channel",), None),
        ("oscillator_hz-0", lambda: SimulatedPCA9685(World(None, 300.0), VirtualClock(),
                                                     oscillator_hz=0.0), ("oscillator_hz",),
         None),
    ],
    P + ".pulse": [
        ("channel-16", lambda: _pca().pulse(16), ("channel",), None),
        ("channel-float", lambda: _pca().pulse(1.5), ("channel",), None),
        ("off-at-power-on", lambda: _pca().pulse(0), None, lambda r: r == 0.0),
    ],
    P + ".read": [
        ("register-256", lambda: _pca().read(256, 1), ("register",), None),
        ("length-negative", lambda: _pca().read(0, -1), ("length",), None),
        # MODE1 at power-on: SLEEP and ALLCALL (DS 7.3.1, 0x11)
        ("mode1", lambda: _pca().read(0x00, 1), None, lambda r: r == [0x11]),
    ],
    P + ".set_oe": [
        ("high-int", lambda: _pca().set_oe(1), ("high",), None),
        ("high-str", lambda: _pca().set_oe("yes"), ("high",), None),
    ],
    P + ".write": [
        ("register-256", lambda: _pca().write(256, [0]), ("register",), None),
        ("data-300", lambda: _pca().write(0x00, [300]), ("data",), None),
        ("data-int", lambda: _pca().write(0x00, 0), ("data",), None),
    ],
    R + "for_contact": [
        ("ratio-1", lambda: SimulatedRig.for_contact(ratio=1.0), ("ratio",), None),
        ("material-unknown", lambda: SimulatedRig.for_contact(material="cheese"),
         ("material", "cheese"), None),
        ("scene-unknown", lambda: SimulatedRig.for_contact(scene="nope"), ("scene", "nope"),
         None),
        ("seed-negative", lambda: SimulatedRig.for_contact(seed=-1), ("seed",), None),
    ],
    R + "from_scene": [
        ("scene-str", lambda: SimulatedRig.from_scene("paper"), ("scene",), None),
        ("seed-float", lambda: SimulatedRig.from_scene(None, seed=1.5), ("seed", "scene"),
         None),
    ],
    R + "quiet": [
        ("seed-negative", lambda: SimulatedRig.quiet(seed=-1), ("seed",), None),
        ("faults-dict", lambda: SimulatedRig.quiet(faults={}), ("faults",), None),
        ("no-contact", lambda: SimulatedRig.quiet().contact_time, None, lambda r: r is None),
    ],
    R + "touch": [
        ("at-past", lambda: [(r := _rig()).clock.advance(1.0), r.touch(0.5)], ("at",), None),
        ("at-nan", lambda: _rig().touch(NAN), ("at",), None),
        ("twice", lambda: [(r := _rig()).touch(), r.touch()], ("contact",), None),
        ("at-now", lambda: [(r := _rig()).touch(), r.contact_time][1], None,
         lambda r: r == 0.0),
    ],
    R + "true_times": [
        ("mpu-none", lambda: _rig().true_times(None, None), ("mpu",), None),
        ("recording-none", lambda: (lambda r, m: [m.start_fifo(), r.true_times(m, None)])(
            *_rig_and_mpu()), ("recording",), None),
    ],
    R + "wrong_samples": [
        ("mpu-none", lambda: _rig().wrong_samples(None, None), ("mpu",), None),
        ("recording-none", lambda: (lambda r, m: [m.start_fifo(), r.wrong_samples(m, None)])(
            *_rig_and_mpu()), ("recording",), None),
    ],
    W + "Obstacle.blocks": [
        ("tilt-nan", lambda: Obstacle(pan=90.0, tilt_low=60.0, tilt_high=80.0).blocks(NAN),
         ("tilt",), None),
        ("tilt-str", lambda: Obstacle(pan=90.0, tilt_low=60.0, tilt_high=80.0).blocks("70"),
         ("tilt",), None),
        ("span", lambda: [Obstacle(pan=90.0, tilt_low=60.0, tilt_high=80.0).blocks(t)
                          for t in (50.0, 70.0, 90.0)], None,
         lambda r: r == [False, True, False]),
    ],
    W + "ServoMotion": [
        ("angle-nan", lambda: ServoMotion(NAN, 300.0), ("angle",), None),
        ("rate-0", lambda: ServoMotion(90.0, 0.0), ("rate",), None),
        ("rate-negative", lambda: ServoMotion(90.0, -1.0), ("rate",), None),
    ],
    W + "ServoMotion.position": [
        ("dt-negative", lambda: ServoMotion(90.0, 300.0).position(-1.0), ("dt",), None),
        ("dt-nan", lambda: ServoMotion(90.0, 300.0).position(NAN), ("dt",), None),
    ],
    W + "World": [
        ("obstacle-str", lambda: World("post", 300.0), ("obstacle",), None),
        ("rate-0", lambda: World(None, 0.0), ("rate",), None),
        ("rate-inf", lambda: World(None, INF), ("rate",), None),
    ],
    W + "World.advance_to": [
        ("now-nan", lambda: World(None, 300.0).advance_to(NAN), ("now",), None),
        # virtual time never goes back: a time already passed moves nothing
        ("now-back", lambda: [(w := World(None, 300.0)).advance_to(2.0), w.advance_to(1.0),
                              w.time][2], None, lambda r: r == 2.0),
    ],
    W + "World.command": [
        ("axis-roll", lambda: World(None, 300.0).command(0.0, "roll", 90.0), ("axis",), None),
        ("angle-nan", lambda: World(None, 300.0).command(0.0, "pan", NAN), ("angle",), None),
        ("now-nan", lambda: World(None, 300.0).command(NAN, "pan", 90.0), ("now",), None),
    ],
    W + "mg996r_angle": [
        ("width-nan", lambda: mg996r_angle(NAN), ("width",), None),
        ("width-str", lambda: mg996r_angle("1.5e-3"), ("width",), None),
        ("width-negative", lambda: mg996r_angle(-1e-3), ("width",), None),
    ],
    T + "add": [
        ("produced-negative", lambda: _estimator().add(produced=-1, before=0.1, after=0.2),
         ("produced",), None),
        ("before-nan", lambda: _estimator().add(produced=10, before=NAN, after=0.2),
         ("before",), None),
        ("after-below-before", lambda: _estimator().add(produced=10, before=0.2, after=0.1),
         ("after",), None),
        # 100 samples between 100.45 and 100.88 ms after an enable at 0-0.3 ms (the docstring)
        ("narrows", lambda: [(e := _estimator()).add(produced=100, before=0.10045,
                                                     after=0.10088), e.low, e.high], None,
         lambda r: r[0] and math.isclose(r[1], (0.10045 - 3e-4) / 101, rel_tol=1e-12)
         and math.isclose(r[2], 0.10088 / 99, rel_tol=1e-12)),
    ],
    T + "begin": [
        ("before-nan", lambda: PeriodEstimator(1e-3).begin(before=NAN, after=0.0), ("before",),
         None),
        ("after-below-before", lambda: PeriodEstimator(1e-3).begin(before=1.0, after=0.5),
         ("after",), None),
    ],
    T + "bounds": [
        ("produced-float", lambda: _estimator().bounds(1.5, 0.1, 0.2), ("produced",), None),
        ("after-inf", lambda: _estimator().bounds(10, 0.1, INF), ("after",), None),
        ("no-segment", lambda: PeriodEstimator(1e-3).bounds(10, 0.1, 0.2), ("segment",), None),
    ],
    T + "check": [
        ("produced-str", lambda: _estimator().check(produced="9", before=0.1, after=0.2),
         ("produced",), None),
        ("impossible", lambda: _estimator().check(produced=900, before=0.2, after=0.2004),
         None, lambda r: r is False),
    ],
    T + "sample_interval": [
        ("segment-1", lambda: _estimator().sample_interval(1, 0), ("segment",), None),
        ("j-negative", lambda: _estimator().sample_interval(0, -1), ("j",), None),
    ],
    T + "timestamps": [
        ("segment-negative", lambda: _estimator().timestamps(-1, 0), ("segment",), None),
        ("last-float", lambda: _estimator().timestamps(0, 1.5), ("last",), None),
    ],
    D + "read_byte": [
        ("register-256", lambda: _device().read_byte(256), ("register",), None),
        ("register-str", lambda: _device().read_byte("0x75"), ("register",), None),
        ("who-am-i", lambda: _device().read_byte(0x75), None, lambda r: r == 0x68),
    ],
    D + "write_byte": [
        ("value-256", lambda: _device().write_byte(0x6B, 256), ("value",), None),
        ("register-negative", lambda: _device().write_byte(-1, 0), ("register",), None),
    ],
    D + "read_block": [
        ("length-0", lambda: _device().read_block(0x3B, 0), ("length",), None),
        ("chunk-0", lambda: _device().read_block(0x3B, 6, chunk=0), ("chunk",), None),
        ("register-256", lambda: _device().read_block(256, 6), ("register",), None),
    ],
    D + "write_block": [
        ("data-300", lambda: _device().write_block(0x6B, [300]), ("data",), None),
        ("register-256", lambda: _device().write_block(256, [0]), ("register",), None),
    ],
    "ebantenna.device.i2c.transfer_bits": [
        ("nbytes-negative", lambda: transfer_bits(-1), ("nbytes",), None),
        ("nbytes-float", lambda: transfer_bits(1.5), ("nbytes",), None),
    ],
    "ebantenna.device.i2c.transfer_time": [
        ("bus_hz-0", lambda: transfer_time(4, 0.0), ("bus_hz",), None),
        ("overhead-negative", lambda: transfer_time(4, 100e3, -1.0), ("overhead",), None),
        ("nbytes-str", lambda: transfer_time("4"), ("nbytes",), None),
        ("by-hand", lambda: transfer_time(4, 100e3, 0.0), None,
         lambda r: math.isclose(r, transfer_bits(4) / 100e3, rel_tol=1e-12)),
    ],
    U + "check_poll_interval": [
        ("poll_interval-0", lambda: _mpu().check_poll_interval(0.0), ("poll_interval",), None),
        ("poll_interval-long", lambda: _mpu().check_poll_interval(1.0), ("poll_interval",),
         None),
        ("busy-negative", lambda: _mpu().check_poll_interval(0.02, -1.0), ("busy",), None),
    ],
    U + "max_poll_interval": [
        ("busy-nan", lambda: _mpu().max_poll_interval(NAN), ("busy",), None),
        ("busy-negative", lambda: _mpu().max_poll_interval(-1.0), ("busy",), None),
    ],
    U + "poll_wait": [
        ("poll_interval-0", lambda: _mpu().poll_wait(0.0), ("poll_interval",), None),
        ("busy-nan", lambda: _mpu().poll_wait(0.02, NAN), ("busy",), None),
        ("as-asked", lambda: _mpu().poll_wait(0.02), None, lambda r: r == 0.02),
    ],
    U + "fastest_rate": [
        # before any stream: the nominal rate 5 % fast
        ("tolerance", lambda: _mpu().fastest_rate(), None,
         lambda r: math.isclose(r, 1050.0, rel_tol=1e-12)),
    ],
    U + "to_acceleration": [
        ("counts-str", lambda: _mpu().to_acceleration("x"), ("counts",), None),
        ("counts-fraction", lambda: _mpu().to_acceleration(np.array([[1.5, 0, 0]])),
         ("counts",), None),
        # +/-16 g: 2048 LSB/g (RM 4.17)
        ("one-g", lambda: _mpu().to_acceleration(np.array([[2048, 0, -2048]], np.int16)),
         None, lambda r: np.allclose(r, [[9.80665, 0.0, -9.80665]], rtol=1e-12)),
    ],
    U + "configuration_lost": [
        ("streaming-str", lambda: _mpu().configuration_lost("yes"), ("streaming",), None),
        ("as-set", lambda: _mpu().configuration_lost(), None, lambda r: r is None),
    ],
    U + "to_recording": [
        ("no-stream", lambda: _mpu().to_recording(0, 10), ("stream", "start_fifo"), None),
    ],
    "ebantenna.device.pca9685.PCA9685.write_channel": [
        ("channel-16", lambda: _pca9685().write_channel(16, [0, 0, 0, 16]), ("channel",), None),
        ("data-3-bytes", lambda: _pca9685().write_channel(0, [0, 0, 1]), ("data",), None),
        ("data-300", lambda: _pca9685().write_channel(0, [0, 0, 300, 0]), ("data",), None),
        ("reads-back", lambda: _pca9685().write_channel(0, [0, 0, 51, 1]), None,
         lambda r: r is None),
    ],
    "ebantenna.device.pantilt.servo_bus_time": [
        ("bus_hz-0", lambda: servo_bus_time(0.0), ("bus_hz",), None),
        ("bus_hz-str", lambda: servo_bus_time("1e5"), ("bus_hz",), None),
        # two pulse writes and their read-backs, MODE1-MODE2 and PRE_SCALE read back
        ("by-hand", lambda: servo_bus_time(100e3), None, lambda r: math.isclose(
            r, 6 * 50e-6 + (2 * 56 + 2 * 66 + 48 + 39) / 100e3, rel_tol=1e-12)),
    ],
    "ebantenna.device.pca9685.PCA9685.channel_off": [
        ("channel-16", lambda: _pca9685().channel_off(16), ("channel",), None),
        ("channel-float", lambda: _pca9685().channel_off(1.5), ("channel",), None),
    ],
    # -- the FIFO stream's records and what it kept ------------------------------------------
    "ebantenna.device.fifo.FifoBlock": [
        ("lost-negative", lambda: FifoBlock(np.arange(2), np.zeros((2, 3), np.int16), -1),
         ("lost",), None),
        ("counts-shape", lambda: FifoBlock(np.arange(2), np.zeros((2, 2), np.int16), 0),
         ("counts",), None),
        ("index-length", lambda: FifoBlock(np.arange(3), np.zeros((2, 3), np.int16), 0),
         ("index",), None),
    ],
    "ebantenna.device.fifo.StreamFault": [
        ("time-nan", lambda: StreamFault(NAN, "bus error", "restart"), ("time",), None),
        ("cause-int", lambda: StreamFault(0.0, 5, "restart"), ("cause",), None),
        ("action-none", lambda: StreamFault(0.0, "bus error", None), ("action",), None),
        ("to-dict", lambda: StreamFault(1.0, "x", "restart").to_dict(), None,
         lambda r: r == {"time": 1.0, "cause": "x", "action": "restart"}),
    ],
    "ebantenna.device.fifo.FifoStream.host_time": [
        ("slot-negative", lambda: _streaming().stream.host_time(-1), ("slot",), None),
        ("slot-str", lambda: _streaming().stream.host_time("3"), ("slot",), None),
    ],
    "ebantenna.device.fifo.FifoStream.kept": [
        ("first-negative", lambda: _streaming().stream.kept(-1), ("first",), None),
        ("stop-below-first", lambda: _streaming().stream.kept(10, 5), ("stop",), None),
        ("stop-float", lambda: _streaming().stream.kept(0, 2.5), ("stop",), None),
        # 0.1 s at 1 kHz, drained: kept + lost = the slots asked for
        ("slots", lambda: _streaming().stream.kept(0, 50)["slot"], None,
         lambda r: r.size <= 50 and np.all(np.diff(r) > 0)),
    ],
    "ebantenna.device.fifo.FifoStream.recording": [
        ("first-str", lambda: _streaming().stream.recording("0", 10), ("first",), None),
        ("stop-below-first", lambda: _streaming().stream.recording(10, 5), ("stop",), None),
    ],
    "ebantenna.device.mpu6050_config.accel_bandwidth": [
        ("dlpf_cfg-7", lambda: accel_bandwidth(7), ("dlpf_cfg",), None),
        ("dlpf_cfg-float", lambda: accel_bandwidth(1.5), ("dlpf_cfg",), None),
        ("rm-table", lambda: accel_bandwidth(0), None, lambda r: r == 260.0),  # RM register 26
    ],
    "ebantenna.device.oe.OutputEnable": [
        ("line-none", lambda: OutputEnable(None), ("line",), None),
        ("line-int", lambda: OutputEnable(17), ("line",), None),
    ],
    "ebantenna.device.oe.OutputEnable.gpio": [
        ("pin-1", lambda: OutputEnable.gpio(1), ("pin",), None),
        ("pin-28", lambda: OutputEnable.gpio(28), ("pin",), None),
        ("pin-str", lambda: OutputEnable.gpio("17"), ("pin",), None),
    ],
    "ebantenna.device.pantilt.PanTilt.stop": [
        ("back_off-negative", lambda: _pantilt().stop(-1.0), ("back_off",), None),
        ("at-one-angle", lambda: _pantilt().stop(0.0, at=(90.0,)), ("at",), None),
        ("at-nan", lambda: _pantilt().stop(0.0, at=(90.0, NAN)), ("at",), None),
        ("holds", lambda: _pantilt().stop(2.0), None, lambda r: r is True),
    ],
    "ebantenna.device.pca9685.pwm_frequency": [
        ("prescale-2", lambda: pwm_frequency(2), ("prescale",), None),
        ("prescale-256", lambda: pwm_frequency(256), ("prescale",), None),
        ("oscillator_hz-0", lambda: pwm_frequency(121, 0.0), ("oscillator_hz",), None),
        # DS 7.3.5: 25 MHz / (4096 (121 + 1))
        ("by-hand", lambda: pwm_frequency(121), None,
         lambda r: math.isclose(r, 25e6 / (4096 * 122), rel_tol=1e-12)),
    ],
    "ebantenna.device.servo.ServoCalibration.angle": [
        ("pulse-nan", lambda: ServoCalibration(0).angle(NAN), ("pulse",), None),
        ("pulse-str", lambda: ServoCalibration(0).angle("1.5e-3"), ("pulse",), None),
        ("inverse", lambda: (c := ServoCalibration(0)).angle(c.pulse(60.0)), None,
         lambda r: math.isclose(r, 60.0, rel_tol=1e-12)),
    ],
    "ebantenna.device.servo.ServoCalibration.clamp": [
        ("angle-nan", lambda: ServoCalibration(0).clamp(NAN), ("angle",), None),
        ("angle-none", lambda: ServoCalibration(0).clamp(None), ("angle",), None),
        ("limits", lambda: [(c := ServoCalibration(0)).clamp(-1e3), c.clamp(1e3)], None,
         lambda r: r == [ServoCalibration(0).lower_limit, ServoCalibration(0).upper_limit]),
    ],
    "ebantenna.device.servo.ServoCalibration.pulse": [
        ("angle-nan", lambda: ServoCalibration(0).pulse(NAN), ("angle",), None),
        ("past-the-travel", lambda: ServoCalibration(0).pulse(1e4), ("angle", "pulse"), None),
    ],
    "ebantenna.device.simulated.touches.simulated_connect": [
        ("simulate-none", lambda: simulated_connect(None, None), ("simulate",), None),
        ("faults-dict", lambda: simulated_connect(None, len, faults={}), ("faults",), None),
        ("seed-negative", lambda: simulated_connect(None, len, seed=-1), ("seed",), None),
        ("scene-none", lambda: simulated_connect(None, len), ("scene",), None),
    ],
    "ebantenna.device.watchdog.check_watchdog": [
        ("mpu-none", lambda: check_watchdog(None, 1.0), ("mpu",), None),
        ("watchdog-0", lambda: check_watchdog(_streaming(), 0.0), ("watchdog",), None),
        ("window-reversed", lambda: check_watchdog(_streaming(), 1.0, window=(10, 5)),
         ("window",), None),
        ("quiet-when-alive", lambda: check_watchdog(_streaming(), 1.0), None,
         lambda r: r is None),
    ],
    "ebantenna.device.watchdog.record_stream": [
        ("mpu-none", lambda: record_stream(None, 1.0), ("mpu",), None),
        ("duration-0", lambda: record_stream(_mpu(), 0.0), ("duration",), None),
        ("watchdog-nan", lambda: record_stream(_mpu(), 0.1, watchdog=NAN), ("watchdog",),
         None),
        ("poll_interval-long", lambda: record_stream(_mpu(), 0.1, poll_interval=1.0),
         ("poll_interval",), None),
    ],
    "ebantenna.device.watchdog.stop_quietly": [
        ("mpu-none", lambda: stop_quietly(None), ("mpu",), None),
        # USER_CTRL.FIFO_EN (0x40, RM 4.29) read back cleared: the FIFO stopped
        ("stops", lambda: [stop_quietly(m := _streaming()), m.device.read_byte(0x6A)][1], None,
         lambda r: r & 0x40 == 0),
    ],
    "ebantenna.device.wiring.servo_supply_current": [
        ("n_servos-negative", lambda: servo_supply_current(-1), ("n_servos",), None),
        ("n_servos-float", lambda: servo_supply_current(1.5), ("n_servos",), None),
        ("two", lambda: servo_supply_current(2), None, lambda r: r == 5.0),
    ],
    "ebantenna.device.wiring.Wire": [
        ("start-str", lambda: Wire("pi", ("PCA9685", "SDA"), "SDA"), ("start",), None),
        ("signal-int", lambda: Wire(("a", "b"), ("c", "d"), 5), ("signal",), None),
        ("optional-str", lambda: Wire(("a", "b"), ("c", "d"), "SDA", "no"), ("optional",),
         None),
    ],
    "ebantenna.device.wiring.draw_wiring": [
        ("ax-str", lambda: draw_wiring("axes"), ("ax",), None),
    ],
    "ebantenna.device.recording_session.write_atomic": [
        ("write-none", lambda: write_atomic(os.devnull + ".x", None), ("write",), None),
        ("path-none", lambda: write_atomic(None, lambda tmp: None), ("path",), None),
    ],
    "ebantenna.device.recording_session.file_sha256": [
        ("path-none", lambda: file_sha256(None), ("path",), None),
        ("path-missing", lambda: file_sha256("/nonexistent/rec.npz"), ("rec.npz",), None),
        ("path-dir", lambda: file_sha256(os.path.dirname(__file__)), ("fuzz",), None),
    ],
    "ebantenna.device.recording_session.Connection": [
        ("bus-none", lambda: Connection(None, VirtualClock()), ("bus",), None),
        ("clock-none", lambda: Connection(_rig().bus, None), ("clock",), None),
    ],
    "ebantenna.device.plan.Touch": [
        ("index-negative", lambda: Touch(-1, "brass", 0.1, 0), ("index",), None),
        ("material-int", lambda: Touch(0, 5, 0.1, 0), ("material",), None),
        ("contact-nan", lambda: Touch(0, "brass", NAN, 0), ("contact",), None),
        ("repetition-float", lambda: Touch(0, "brass", 0.1, 1.5), ("repetition",), None),
    ],
    "ebantenna.device.plan.Touch.labels": [
        ("probe_length-0", lambda: Touch(0, "brass", 0.1, 0).labels(0.0), ("probe_length",),
         None),
        ("ratio", lambda: Touch(0, "brass", 0.1, 0).labels(0.4)["ratio"], None,
         lambda r: math.isclose(r, 0.25, rel_tol=1e-12)),
    ],
    "ebantenna.device.plan.Plan.from_dict": [
        ("data-list", lambda: Plan.from_dict([], "p.json"), ("p.json",), None),
        ("missing-name", lambda: Plan.from_dict({"materials": ["brass"], "contacts_m": [0.1],
                                                 "repetitions": 1}, "p.json"),
         ("p.json", "name"), None),
        ("where-int", lambda: Plan.from_dict({}, 5), ("where",), None),
    ],
    "ebantenna.device.plan.session_time": [
        ("plan-dict", lambda: session_time({}), ("plan",), None),
        ("move-negative", lambda: session_time(Plan("p", ("brass",), (0.1,), 1), move=-1.0),
         ("move",), None),
    ],
    "ebantenna.device.safety.ServoGuard": [
        ("held_retry-negative", lambda: ServoGuard(lambda: None, VirtualClock(), held_retry=-1.0),
         ("held_retry",), None),
        ("held_retry-past-the-limit", lambda: ServoGuard(lambda: None, VirtualClock(),
                                                         held_retry=MAX_HELD_RETRY + 1),
         ("held_retry",), None),
        ("held_interval-0", lambda: ServoGuard(lambda: None, VirtualClock(), held_interval=0.0),
         ("held_interval",), None),
        ("revive-int", lambda: ServoGuard(lambda: None, VirtualClock(), revive=3), ("revive",),
         None),
        # a release failing three times, then landing: retried while the fallback holds, and
        # released over I2C after three one-second waits
        ("retried-while-held", lambda: _held_release(fails=3), None,
         lambda r: r == (True, "i2c", 4.0)),
    ],
    "ebantenna.device.clock.VirtualClock.advance": [
        ("seconds-negative", lambda: VirtualClock().advance(-1.0), ("seconds",), None),
        ("seconds-nan", lambda: VirtualClock().advance(NAN), ("seconds",), None),
        ("adds", lambda: [(c := VirtualClock(1.0)).advance(0.5), c.monotonic()][1], None,
         lambda r: r == 1.5),
    ],
}


def _rig_and_mpu():
    rig = _rig()
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    return rig, mpu


def _streaming():
    """A driver whose FIFO has run 0.1 s and been drained once."""
    rig, mpu = _rig_and_mpu()
    mpu.start_fifo()
    rig.clock.advance(0.1)
    mpu.read_fifo()
    return mpu


def _pantilt():
    rig = _rig()
    unit = PanTilt(PCA9685(rig.bus, clock=rig.clock))
    unit.initialize()
    unit.move(100.0, 80.0)
    unit.move(105.0, 85.0)
    return unit


def _held_release(fails: int):
    """A guard whose release fails ``fails`` times in a row past its first round, with a
    fallback: (released, released_by, time spent after the first round, s)."""
    from ebantenna.device.i2c import I2CError

    clock = VirtualClock()
    calls = {"n": 0, "first_round_end": None}

    def release():
        calls["n"] += 1
        if calls["n"] <= 1 + fails:  # the first round has one attempt (attempts=1)
            raise I2CError(5, "release refused")

    def fallback():
        calls["first_round_end"] = clock.monotonic()

    guard = ServoGuard(release, clock, attempts=1, fallback=fallback)
    guard.release_with_retries()
    return guard.released, guard.released_by, clock.monotonic() - calls["first_round_end"]


def _pca9685():
    rig = _rig()
    pca = PCA9685(rig.bus, clock=rig.clock)
    pca.initialize()
    return pca


CASES = [(surface, *row) for surface, rows in ROWS.items() for row in rows]


@pytest.mark.parametrize(("surface", "id_", "call", "names", "same"), CASES,
                         ids=[f"{s.rsplit('.', 1)[-1]}:{i}" for s, i, *_ in CASES])
def test_every_row_ends_in_a_clear_error_or_the_right_answer(surface, id_, call, names, same):
    check_row(Row(surface, id_, call, names or (), same), id_, timeout=10.0)


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    return {surface: [row[0] for row in rows] for surface, rows in ROWS.items()}
