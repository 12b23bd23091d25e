"""The input contract of the driver's read-back and the recording session's safety steps.

Each row gives one bad input (refused with a ValueError or TypeError naming the parameter) or a
good one whose result is checked against a witness the surface does not compute: the simulated
chip's own registers for a write read back, a noise floor worked by hand, a bracket recomputed
from the observations kept, a recording read back from its file.
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from pathlib import Path

import numpy as np
import pytest

from ebantenna.chips.mpu6050 import Register
from ebantenna.chips.pca9685 import Register as PcaRegister
from ebantenna.device import MPU6050, PCA9685, SimulatedRig
from ebantenna.device.fifo import sensor_check
from ebantenna.device.plan import Plan
from ebantenna.device.recording_session import (
    MANIFEST,
    RecordingSession,
    fallback_paths,
    save_recording,
)
from ebantenna.device.timing import PeriodEstimator
from ebantenna.recording import Recording

BAD_BYTES = [  # (id, register, value, error, name)
    ("register-256", 256, 0, ValueError, "register"),
    ("register-text", "0x1A", 0, TypeError, "register"),
    ("register-bool", True, 0, TypeError, "register"),
    ("value-negative", None, -1, ValueError, "value"),
    ("value-float", None, 1.5, TypeError, "value"),
]


@pytest.fixture(scope="module")
def rig():
    return SimulatedRig.quiet()


@pytest.fixture(scope="module")
def mpu(rig):
    chip = MPU6050(rig.bus, clock=rig.clock)
    chip.initialize()
    return chip


@pytest.fixture(scope="module")
def pca(rig):
    chip = PCA9685(rig.bus, clock=rig.clock)
    chip.initialize()
    return chip


# ------------------------------------------------------------------ writes read back
@pytest.mark.parametrize(("row", "register", "value", "error", "name"), BAD_BYTES,
                         ids=[b[0] for b in BAD_BYTES])
def test_mpu6050_write_verified_refuses_a_bad_byte(mpu, row, register, value, error, name):
    with pytest.raises(error, match=name):
        mpu.write_verified(Register.CONFIG if register is None else register, value)


@pytest.mark.parametrize(("row", "register", "value", "error", "name"), BAD_BYTES,
                         ids=[b[0] for b in BAD_BYTES])
def test_pca9685_write_verified_refuses_a_bad_byte(pca, row, register, value, error, name):
    with pytest.raises(error, match=name):
        pca.write_verified(PcaRegister.MODE2 if register is None else register, value)


@pytest.mark.parametrize(("row", "register", "value", "error", "name"),
                         [*BAD_BYTES, ("mask-256", None, 0, ValueError, "mask")],
                         ids=[*(b[0] for b in BAD_BYTES), "mask-256"])
def test_a_device_write_read_back_refuses_a_bad_byte(mpu, row, register, value, error, name):
    mask = 256 if row == "mask-256" else 0xFF
    with pytest.raises(error, match=name):
        mpu.device.write_read_back(Register.CONFIG if register is None else register, value,
                                   mask, lambda: "CONFIG")


def test_a_device_write_read_back_says_none_when_it_landed(rig, mpu):
    before = rig.mpu.regs[Register.CONFIG]
    assert mpu.device.write_read_back(Register.CONFIG, 5, 0xFF, lambda: "CONFIG") is None
    assert rig.mpu.regs[Register.CONFIG] == 5  # the simulated chip's own register file
    mpu.device.write_read_back(Register.CONFIG, before, 0xFF, lambda: "CONFIG")


def test_a_verified_write_lands_in_the_chips_own_register(rig, mpu, pca):
    """The witness is the simulated chip's register file, not the driver's read."""
    before = rig.mpu.regs[Register.CONFIG]
    mpu.write_verified(Register.CONFIG, 3)
    assert rig.mpu.regs[Register.CONFIG] == 3
    mpu.write_verified(Register.CONFIG, before)
    mode2 = rig.pca.regs[PcaRegister.MODE2]
    pca.write_verified(PcaRegister.MODE2, mode2 ^ 0x10)
    assert rig.pca.regs[PcaRegister.MODE2] == mode2 ^ 0x10
    pca.write_verified(PcaRegister.MODE2, mode2)


@pytest.mark.parametrize("streaming", ["no", None, 1, np.array([True])])
def test_expected_registers_takes_a_bool(mpu, streaming):
    with pytest.raises(TypeError, match="streaming"):
        mpu.expected_registers(streaming)


def test_expected_registers_are_what_the_chip_holds_after_initialize(rig, mpu):
    expected = mpu.expected_registers(streaming=False)
    assert Register.FIFO_EN not in expected
    assert {int(r): v for r, v in expected.items()} == {
        int(r): rig.mpu.regs[r] for r in expected}
    assert mpu.expected_registers(streaming=True).keys() - expected.keys() == {
        Register.FIFO_EN, Register.USER_CTRL}


# ------------------------------------------------------------------ sensor check
@pytest.mark.parametrize(("row", "counts", "lsb", "error", "name"), [
    ("counts-list", [[0, 0, 0]] * 4, 2048, TypeError, "counts"),
    ("counts-float", np.zeros((4, 3)), 2048, TypeError, "counts"),
    ("counts-two-axes", np.zeros((4, 2), np.int16), 2048, TypeError, "counts"),
    ("lsb-text", np.zeros((4, 3), np.int16), "2048", TypeError, "lsb_per_g"),
    ("lsb-zero", np.zeros((4, 3), np.int16), 0, ValueError, "lsb_per_g"),
], ids=lambda v: v if isinstance(v, str) else "")
def test_sensor_check_refuses_bad_input(row, counts, lsb, error, name):
    with pytest.raises(error, match=name):
        sensor_check(counts, lsb)


def test_sensor_check_noise_is_the_rms_step_over_root_two():
    # x alternates 0, 2: every step is +-2 LSB, rms 2, noise 2 / sqrt(2); y ramps by 1: rms 1;
    # z never changes: a dead axis.
    n = 40
    counts = np.stack([2 * (np.arange(n) % 2), np.arange(n), np.full(n, 5)], axis=1)
    out = sensor_check(counts.astype(np.int16), 2048)
    assert out["noise_lsb"] == [round(2 / math.sqrt(2), 3), round(1 / math.sqrt(2), 3), 0.0]
    assert out["constant_axes"] == ["z"] and out["longest_repeat"] == 1
    assert any("never changes" in flag for flag in out["flags"])


# ------------------------------------------------------------------ period bracket
def _estimator(segments=1):
    est = PeriodEstimator(1e-3, 0.05)
    for k in range(segments):
        t0 = 10.0 * k
        est.begin(before=t0, after=t0 + 3e-4)
        est.add(produced=100, before=t0 + 0.10045, after=t0 + 0.10088)
    return est


@pytest.mark.parametrize(("row", "segments", "segment", "error"), [
    ("no-segment-yet", 0, 0, ValueError),
    ("beyond-the-last", 1, 1, ValueError),
    ("negative", 1, -1, ValueError),
    ("text", 1, "0", TypeError),
    ("float", 1, 0.0, TypeError),
], ids=lambda v: v if isinstance(v, str) else "")
def test_forget_names_a_segment_begun(row, segments, segment, error):
    est = _estimator(segments)
    with pytest.raises(error, match="segment"):
        est.forget(segment)


def test_forget_leaves_the_bracket_of_the_other_segments():
    est = _estimator(2)
    est.forget(1)
    alone = _estimator(1)  # the bracket of segment 0's observations alone
    assert (est.low, est.high) == (alone.low, alone.high)
    est.forget(0)  # nothing left: the rate's tolerance, nominal / (1 +- tolerance)
    assert (est.low, est.high) == (1e-3 / 1.05, 1e-3 / 0.95)


# ------------------------------------------------------------------ saving a recording
def _recording():
    t = np.arange(8) / 1000.0
    return Recording(t, np.sin(t * 1e3), np.cos(t * 1e3), fs=1000.0)


@pytest.mark.parametrize(("row", "name", "error"), [
    ("empty", "", ValueError), ("int", 3, TypeError), ("bytes", b"rec", TypeError),
    ("no-file-name", "/", ValueError), ("nul", "a\x00b", ValueError),
], ids=lambda v: v if isinstance(v, str) and v.isidentifier() or "-" in str(v) else "")
def test_fallback_paths_refuse_a_bad_name(row, name, error):
    with pytest.raises(error, match="name"):
        fallback_paths(name)


def test_fallback_paths_are_the_working_and_temporary_folders():
    unique = f"touch-{os.getpid()}.npz"
    assert fallback_paths("some/where/touch.npz") == [
        Path.cwd() / unique, Path(tempfile.gettempdir()) / unique]


@pytest.mark.parametrize(("row", "kwargs", "error", "name"), [
    ("recording-not-one", dict(recording="rec"), TypeError, "recording"),
    ("path-int", dict(path=3), TypeError, "path"),
    ("path-bytes", dict(path=b"x.npz"), TypeError, "path"),
    ("fallback-empty", dict(fallback_name=""), ValueError, "fallback_name"),
])
def test_save_recording_refuses_bad_input(tmp_path, row, kwargs, error, name):
    args = {"recording": _recording(), "path": tmp_path / "r.npz", "fallback_name": "r", **kwargs}
    with pytest.raises(error, match=name):
        save_recording(args.pop("recording"), args.pop("path"), **args)
    assert not list(tmp_path.iterdir())


def test_save_recording_writes_what_reads_back(tmp_path):
    rec = _recording()
    written, failures = save_recording(rec, tmp_path / "r", fallback_name="r")
    assert written == tmp_path / "r.npz" and failures == []
    back = Recording.load(written)
    np.testing.assert_array_equal(back.ax, rec.ax)
    np.testing.assert_array_equal(back.az, rec.az)


# ------------------------------------------------------------------ marking a rig unsafe
@pytest.fixture
def session(tmp_path):
    from ebantenna.device.simulated.touches import simulated_connect
    from ebantenna.simulate import builtin_scene, simulate

    connect = simulated_connect(builtin_scene("paper"), simulate, seed=0)
    out = RecordingSession(tmp_path / "s", Plan("u", ("brass",), (0.2,), 1), connect,
                           rig={"simulated": True}, show_progress=False)
    out.open()
    return out


@pytest.mark.parametrize(("row", "why", "powered", "error", "name"), [
    ("why-empty", "", True, ValueError, "why"),
    ("why-none", None, True, ValueError, "why"),
    ("why-blank", "  ", True, ValueError, "why"),
    ("powered-text", "servos", "no", TypeError, "powered"),
    ("powered-none", "servos", None, TypeError, "powered"),
])
def test_mark_unsafe_refuses_bad_input(session, row, why, powered, error, name):
    with pytest.raises(error, match=name):
        session.mark_unsafe(why, powered)
    assert json.loads(session.manifest_path.read_text())["unsafe"] in (None, {})


def test_mark_unsafe_is_read_from_the_manifest_file(session):
    assert session.mark_unsafe("servos not released", powered=False) is True
    unsafe = json.loads((session.directory / MANIFEST).read_text())["unsafe"]
    assert unsafe["reason"] == "servos not released" and unsafe["servos_may_be_powered"] is False


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    bytes_rows = [b[0] for b in BAD_BYTES] + ["lands-in-the-chip"]
    return {
        "MPU6050.write_verified": bytes_rows,
        "PCA9685.write_verified": bytes_rows,
        "I2CDevice.write_read_back": [b[0] for b in BAD_BYTES] + ["mask-256", "landed"],
        "MPU6050.expected_registers": ["streaming-not-bool", "what-the-chip-holds"],
        "ebantenna.device.fifo.sensor_check": ["counts-list", "counts-float", "counts-two-axes",
                                               "lsb-text", "lsb-zero", "noise-by-hand"],
        "PeriodEstimator.forget": ["no-segment-yet", "beyond-the-last", "negative", "text",
                                   "float", "bracket-of-the-others"],
        "recording_session.fallback_paths": ["empty", "int", "bytes", "no-file-name", "nul",
                                             "working-and-temporary"],
        "recording_session.save_recording": ["recording-not-one", "path-int", "path-bytes",
                                             "fallback-empty", "reads-back"],
        "RecordingSession.mark_unsafe": ["why-empty", "why-none", "why-blank", "powered-text",
                                         "powered-none", "read-from-the-manifest"],
    }


def contract_exempt() -> dict[str, str]:
    """Public names that take no input from a user."""
    return {
        "MPU6050.read_registers": "no argument",
        "PCA9685.changed_settings": "no argument",
        "AcquisitionResult.warnings": "no argument",
        "RecordingSession.release": "no argument",
        "ebantenna.device.safety.signals_held": "no argument",
    }
