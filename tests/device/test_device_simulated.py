"""The simulated bus: SMBus behaviour, chip rules, the scene simulator behind it, isolation."""

import ast
import errno
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from smbus2 import i2c_msg

import ebantenna.device as device
from ebantenna.chips.mpu6050 import ADDRESS_AD0_LOW, Interrupt, Register
from ebantenna.cli import main
from ebantenna.device import MPU6050, PCA9685, Faults, PanTilt, SimulatedRig, search_and_record
from ebantenna.device._cli import CUT_SUPPLY
from ebantenna.device.mpu6050 import STANDARD_GRAVITY
from ebantenna.recording import Recording

LSB = STANDARD_GRAVITY / 2048


def test_smbus_limits_and_missing_chips_behave_like_smbus2():
    rig = SimulatedRig.quiet()
    # the same kind of error as smbus2 (ValueError), naming the parameter
    with pytest.raises(ValueError, match="length must be <= 32"):
        rig.bus.read_i2c_block_data(0x68, 0x3B, 33)
    with pytest.raises(ValueError, match="32"):
        rig.bus.write_i2c_block_data(0x40, 0x06, [0] * 33)
    with pytest.raises(OSError) as info:
        rig.bus.read_byte_data(0x29, 0)
    assert info.value.errno == errno.EREMOTEIO
    rig.bus.close()
    with pytest.raises(OSError):
        rig.bus.read_byte_data(ADDRESS_AD0_LOW, Register.WHO_AM_I)


def test_i2c_rdwr_with_smbus2_messages():
    rig = SimulatedRig.quiet()
    write, read = i2c_msg.write(0x68, [0x75]), i2c_msg.read(0x68, 1)
    rig.bus.i2c_rdwr(write, read)
    assert list(read) == [0x68]


def test_fifo_overflow_sets_the_interrupt_flag_which_clears_on_read():
    rig = SimulatedRig.quiet()
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    mpu.start_fifo()
    rig.clock.sleep(0.1)
    status = (ADDRESS_AD0_LOW, Register.INT_STATUS)
    assert 590 <= mpu.fifo_count() <= 612 and rig.bus.read_byte_data(*status) == 0
    rig.clock.sleep(0.2)
    assert mpu.fifo_count() == 1024
    assert rig.bus.read_byte_data(*status) & Interrupt.FIFO_OFLOW
    # cleared by that read: read again at the same instant (over the bus, a sample landing in
    # the full FIFO during the transfer would set it again)
    assert rig.mpu.read(Register.INT_STATUS, 1) == [0]
    # The next drain notices (a full FIFO) and restarts; the one after counts the gap.
    block = mpu.read_fifo()
    assert block.index.size == 0 and mpu.overflows == 1
    rig.clock.sleep(0.02)
    block = mpu.read_fifo()
    assert block.index.size > 0 and block.lost >= 300


def test_error_injection_rate_is_what_was_asked():
    rig = SimulatedRig.quiet(faults=Faults(error_rate=0.2), seed=5)
    failures = 0
    for _ in range(2000):
        try:
            rig.bus.read_byte_data(ADDRESS_AD0_LOW, Register.WHO_AM_I)
        except OSError as exc:
            assert exc.errno == errno.EREMOTEIO
            failures += 1
    assert failures == rig.bus.errors_injected
    # Binomial(2000, 0.2): mean 400, standard deviation 17.9; five sigma either side.
    assert 310 < failures < 490


def test_same_seed_same_bytes():
    ax = 20.0 * np.sin(np.arange(800) / 7.0)
    results = []
    for _ in range(2):
        rig = SimulatedRig.from_arrays(ax, ax, fs=1000.0, seed=11,
                                       faults=Faults(error_rate=0.05))
        _, res = _search(rig)
        results.append(res.recording)
    np.testing.assert_array_equal(results[0].ax, results[1].ax)
    assert results[0].metadata == results[1].metadata


def _search(rig, **kwargs):
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    unit = PanTilt(PCA9685(rig.bus, clock=rig.clock))
    unit.initialize()
    return mpu, search_and_record(mpu, unit, **kwargs)


def test_drivers_know_nothing_of_the_simulator():
    # Only device/simulated/rig.py imports ebantenna.simulate, and only inside a function.
    root = Path(device.__file__).parent
    for path in root.rglob("*.py"):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and "simulate" in (node.module or "").split("."):
                assert path.relative_to(root).as_posix() == "simulated/rig.py", path
        top = [n for n in tree.body if isinstance(n, ast.Import | ast.ImportFrom)]
        assert not any("simulate" in (getattr(n, "module", "") or "").split(".")
                       for n in top), path
    code = ("import sys, ebantenna.device, ebantenna.device._cli; "
            "print('ebantenna.simulate' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def _unnamed_hex_literals(path):
    """Hexadecimal integers in ``path`` other than the byte mask 0xFF and module-level constants."""
    text = path.read_text()
    tree = ast.parse(text)
    named = {id(node.value) for node in tree.body
             if isinstance(node, ast.Assign | ast.AnnAssign)
             and isinstance(node.value, ast.Constant)}
    for node in ast.walk(tree):
        if (isinstance(node, ast.Constant) and type(node.value) is int and id(node) not in named
                and node.value != 0xFF
                and ast.get_source_segment(text, node).lower().startswith("0x")):
            yield f"{path.name}:{node.lineno}: {ast.get_source_segment(text, node)}"


def test_register_numbers_come_from_the_chip_maps():
    # Drivers and simulated chips name every register and bit through ebantenna.chips.
    root = Path(device.__file__).parent
    paths = [root / "mpu6050.py", root / "pca9685.py", *sorted((root / "simulated").glob("*.py"))]
    found = [hit for path in paths for hit in _unnamed_hex_literals(path)]
    assert found == []


@pytest.mark.parametrize("material, ratio", [("brass", 0.3), ("wood", 0.7)])
def test_scene_vibration_is_read_back_to_within_one_lsb(material, ratio):
    from ebantenna import simulate

    scene = simulate.builtin_scene("paper")
    scene = scene.with_(contact=ratio * scene.probe.length, material=material)
    witness = simulate.simulate(scene, seed=5)
    rig = SimulatedRig.from_scene(scene, seed=5)
    mpu, result = _search(rig)
    assert result.contact_detected and result.servos_stopped and result.samples_lost == 0
    rec = result.recording
    assert isinstance(rec, Recording)
    assert abs(1 / rec.fs - 1 / witness.fs) <= rec.metadata["sample_period_uncertainty_s"]
    k_contact = round((rig.contact_sample_time - mpu.stream.starts[0]) * witness.fs) - 1
    j = rec.metadata["first_index"] + np.rint(rec.t * rec.fs).astype(int) - k_contact
    play = (j >= 0) & (j < witness.n_samples)
    assert play.sum() >= min(witness.n_samples, 1000)
    assert np.max(np.abs(rec.ax[play] - witness.ax[j[play]])) <= LSB
    assert np.max(np.abs(rec.az[play] - witness.az[j[play]])) <= LSB


def test_acquire_command_json(capsys, tmp_path):
    out = tmp_path / "rec.npz"
    code = main(["acquire", "--simulated", "--material", "pvc", "--ratio", "0.4", "--seed", "2",
                 "--inject-faults", "0.02", "--out", str(out), "--json"])
    captured = capsys.readouterr()
    data = json.loads(captured.out)
    assert code == 0
    assert data["contact_detected"] is True and data["servos_stopped"] is True
    assert data["samples"] + data["samples_lost"] == 1050 and data["samples_wrong"] == 0
    assert data["servos_released"] is True
    assert data["material"] == "pvc" and data["ratio"] == 0.4
    assert data["i2c_retries"] <= data["i2c_errors_injected"]
    saved = Recording.load(out)
    assert saved.n_samples == data["samples"] and saved.metadata["material"] == "pvc"
    assert len(saved.metadata["raw"]["counts_xyz"]) == data["samples"]  # raw counts, Y included


def test_acquire_without_the_bus_says_how_to_enable_i2c(capsys):
    with pytest.raises(SystemExit) as info:
        main(["acquire", "--bus", "97"])
    err = capsys.readouterr().err
    assert info.value.code == 2 and "/dev/i2c-97 does not exist" in err and "raspi-config" in err


def test_acquire_command_text_and_errors(capsys):
    assert main(["acquire", "--simulated", "--seed", "1"]) == 0
    assert "recorded 1050 samples" in capsys.readouterr().out
    for argv, match in [(["--ratio", "1.5"], "ratio"), (["--material", "gold"], "material")]:
        with pytest.raises(SystemExit) as info:
            main(["acquire", "--simulated", *argv])
        assert info.value.code == 2
        assert match in capsys.readouterr().err
    with pytest.raises(SystemExit) as info:
        main(["acquire", "--bus", "1", "--inject-faults", "0.1"])
    assert info.value.code == 2 and "--simulated" in capsys.readouterr().err


def test_acquire_with_every_fault_kind_reports_no_wrong_sample(capsys):
    code = main(["acquire", "--simulated", "--seed", "3", "--inject-faults", "0.2",
                 "--stuck-bus", "1.0", "0.2", "--clock-drift", "0.008", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0 and data["samples_wrong"] == 0 and data["servos_released"] is True
    assert data["samples"] + data["samples_lost"] == 1050 and data["fifo_restarts"] > 0
    assert {"late", "short", "stuck"} <= set(data["faults_injected"])
    # the chip runs 0.8 % fast: the estimated period's bracket holds the true one (loose here:
    # the faults cut the stream into short segments, each bounding the period weakly)
    period = 1 / data["sample_rate_estimated_hz"]
    assert abs(period - 1 / 1008.0) <= data["sample_period_uncertainty_s"] < 0.02 * period


def test_acquire_stalled_saves_the_partial_recording(capsys, tmp_path):
    # Stuck for 1.3 s: the 1 s watchdog fires, the release retries outlast the rest.
    out = tmp_path / "partial.npz"
    with pytest.raises(SystemExit) as info:
        main(["acquire", "--simulated", "--seed", "1", "--stuck-bus", "0.5", "1.3",
              "--out", str(out)])
    err = capsys.readouterr().err
    assert info.value.code == 2 and "watchdog" in err and "servos released" in err
    assert str(out) in err and Recording.load(out).n_samples > 0
    # Stuck for good: nothing can switch the servos off; the stall ends with exit 3 and the
    # instruction to cut the servo supply, last, the partial recording saved first.
    out.unlink()
    code = main(["acquire", "--simulated", "--seed", "1", "--stuck-bus", "0.5", "100",
                 "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 3 and "watchdog" in err and str(out) in err
    assert err.strip().splitlines()[-1].endswith(CUT_SUPPLY)
    assert Recording.load(out).metadata["stalled"]


def test_acquire_oscillator_calibration(capsys):
    main(["acquire", "--simulated", "--seed", "1", "--measured-pwm-hz", "51.2", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert data["pca9685_oscillator_hz"] == pytest.approx(51.2 * 4096 * 122)
    with pytest.raises(SystemExit):
        main(["acquire", "--simulated", "--oscillator-hz", "30e6"])
    assert "oscillator_hz must lie in" in capsys.readouterr().err
