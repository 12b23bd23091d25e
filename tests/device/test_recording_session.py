"""Recording sessions on the simulated rig: plans, the manifest, resuming, and refusing an unsafe
rig (ebantenna.device.plan, ebantenna.device.recording_session, ``ebantenna record``)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from ebantenna._tempfiles import TEMPORARY_PREFIX
from ebantenna.device.oe import OE_ONLY, OutputEnable
from ebantenna.device.plan import Plan, load_plan
from ebantenna.device.recording_session import (
    MANIFEST,
    RecordingSession,
    UnsafeRigError,
    file_sha256,
    read_manifest,
)
from ebantenna.device.simulated import Faults
from ebantenna.device.simulated.touches import simulated_connect
from ebantenna.recording import Recording
from ebantenna.simulate import builtin_scene, simulate

SCENE = builtin_scene("paper")


def small_plan(**search) -> Plan:
    return Plan("small", ("brass", "pvc"), (0.1, 0.3), 2, 0.40, search)


def session(tmp_path, plan=None, connect=None, **kwargs) -> RecordingSession:
    return RecordingSession(tmp_path / "s", plan or small_plan(),
                            connect or simulated_connect(SCENE, simulate, seed=3),
                            rig={"simulated": True}, show_progress=False, **kwargs)


def test_plan_order_keys_and_file(tmp_path):
    plan = small_plan()
    assert len(plan) == 2 * 2 * 2
    keys = [t.key for t in plan]
    assert keys[:3] == ["brass/0.1000/0", "brass/0.1000/1", "brass/0.3000/0"]
    assert len(set(keys)) == len(plan)  # every touch named once
    path = tmp_path / "plan.toml"
    path.write_text('name = "small"\nmaterials = ["brass", "pvc"]\ncontacts_m = [0.1, 0.3]\n'
                    'repetitions = 2\nprobe_length = 0.40\n')
    assert load_plan(path) == plan
    back = tmp_path / "plan.json"
    back.write_text(json.dumps(plan.to_dict()))
    assert load_plan(back) == plan


@pytest.mark.parametrize("change, words", [
    ({"colour": "red"}, "unknown key(s) colour"),
    ({"materials": ["unobtainium"]}, "unobtainium"),
    ({"contacts_m": [0.5]}, "contacts_m"),
    ({"repetitions": 0}, "repetitions"),
    ({"search": {"speed": 3}}, "unknown search setting(s) speed"),
])
def test_plan_file_refused_by_name(tmp_path, change, words):
    data = {**small_plan().to_dict(), **change}
    path = tmp_path / "plan.json"
    path.write_text(json.dumps(data))
    with pytest.raises(ValueError, match=r"plan\.json") as err:
        load_plan(path)
    assert words in str(err.value)


def test_session_saves_every_touch_with_its_account(tmp_path):
    s = session(tmp_path)
    manifest = s.run()
    assert set(manifest["recordings"]) == {t.key for t in s.plan}
    for touch in s.plan:
        entry = manifest["recordings"][touch.key]
        path = s.directory / entry["file"]
        assert file_sha256(path) == entry["sha256"]
        meta = Recording.load(path).metadata
        assert (meta["material"], meta["contact"], meta["repetition"]) == (
            touch.material, touch.contact, touch.repetition)
        assert meta["release"]["servos_released"] is True
        assert meta["search"]["duration"] == 1.0
        assert {"i2c_retries", "fifo_restarts", "samples_lost"} <= set(meta["fault_counts"])
        assert meta["timestamp_uncertainty_s"] >= 0
        assert meta["sample_rate_hz"] == 1000.0
    assert not list(s.directory.rglob(f"{TEMPORARY_PREFIX}*"))


def test_a_recording_saved_but_not_entered_is_entered_on_resume(tmp_path):
    """The power failed between the rename and the manifest: the file is kept, not re-made."""
    s = session(tmp_path)
    s.run()
    manifest = read_manifest(s.manifest_path)
    key = small_plan()[5].key
    kept = manifest["recordings"].pop(key)
    (s.directory / MANIFEST).write_text(json.dumps(manifest))
    dead = _dead_pid()
    (s.directory / "recordings" / f"{TEMPORARY_PREFIX}{dead}-t00006.npz").write_bytes(b"half")
    again = session(tmp_path, connect=_never)
    again.open()
    assert again.manifest["recordings"][key]["sha256"] == kept["sha256"]
    assert again.remaining() == []
    assert not list(again.directory.rglob(f"{TEMPORARY_PREFIX}*"))


def _dead_pid() -> int:
    """The id of a process that has ended."""
    done = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True, check=True)
    return int(done.stdout)


def test_opening_a_session_removes_only_what_the_package_left(tmp_path):
    """A file the user made, whatever its name, survives; only a dead writer's own temporary
    file, in the folders the session writes, is removed."""
    s = session(tmp_path)
    s.run()
    dead = _dead_pid()
    users = [s.directory / ".bashrc.tmp-save", s.directory / "recordings" / ".draft.tmp.md",
             s.directory / "deep" / f"{TEMPORARY_PREFIX}{dead}-x.npz",
             s.directory / "recordings" / f"{TEMPORARY_PREFIX}{os.getppid()}-t00001.npz"]
    for path in users:
        path.parent.mkdir(exist_ok=True)
        path.write_text("the user's")
    left = s.directory / f"{TEMPORARY_PREFIX}{dead}-{MANIFEST}"
    left.write_text("half a manifest")
    session(tmp_path, connect=_never).open()
    assert not left.exists()
    assert all(path.read_text() == "the user's" for path in users)


def test_a_folder_of_other_files_is_not_taken_over(tmp_path):
    home = tmp_path / "home"
    (home / "projects").mkdir(parents=True)
    (home / ".bashrc.tmp-save").write_text("keep")
    with pytest.raises(FileExistsError, match="not a recording session"):
        RecordingSession(home, small_plan(), _never).open()
    assert (home / ".bashrc.tmp-save").read_text() == "keep"
    assert not (home / "recordings").exists() and not (home / MANIFEST).exists()


def test_an_empty_folder_name_is_refused():
    with pytest.raises(ValueError, match="directory must name"):
        RecordingSession("", small_plan(), _never)


def _never(touch, attempt):
    raise AssertionError("nothing should be recorded again")


def test_a_changed_file_is_refused_by_name(tmp_path):
    s = session(tmp_path)
    s.run()
    entry = next(iter(s.manifest["recordings"].values()))
    path = s.directory / entry["file"]
    path.write_bytes(path.read_bytes()[:-10])
    with pytest.raises(ValueError, match=f"{path.name}: checksum mismatch"):
        session(tmp_path).open()


def test_another_plan_in_the_same_folder_is_refused(tmp_path):
    session(tmp_path).open()
    other = Plan("other", ("wood",), (0.2,), 1)
    with pytest.raises(ValueError, match="another plan") as err:
        session(tmp_path, plan=other).open()
    assert "the materials:" in str(err.value) and "['wood'] given" in str(err.value)


def test_servos_not_released_stop_the_session_and_block_it_until_the_rig_checks_out(tmp_path):
    broken = simulated_connect(SCENE, simulate, seed=3, faults=Faults(release_fails=True))
    s = session(tmp_path, connect=broken)
    with pytest.raises(UnsafeRigError, match="could not be released") as err:
        s.run()
    assert err.value.servos_may_be_powered
    assert "switch off the servo supply" in str(err.value)
    manifest = read_manifest(s.manifest_path)
    assert manifest["unsafe"]["servos_may_be_powered"] is True
    # the finished recording is kept, marked
    (entry,) = manifest["recordings"].values()
    assert entry["servos_released"] is False
    # the next run checks the rig first: still broken, still refused
    with pytest.raises(UnsafeRigError):
        session(tmp_path, connect=broken).run()
    # repaired: it goes on, and makes the rest
    done = session(tmp_path).run()
    assert done["unsafe"] is None and len(done["recordings"]) == len(small_plan())


def test_the_oe_pin_alone_does_not_count_as_released(tmp_path):
    # the release over I2C fails; the OE pin switches the outputs off, but only while the
    # program runs: the session stops, marked unsafe, saying both
    broken = simulated_connect(SCENE, simulate, seed=3, faults=Faults(release_fails=True))
    held = []

    def with_oe(touch, attempt):
        conn = broken(touch, attempt)
        conn.output_enable = OutputEnable(conn.simulated.oe_line())
        held.append(conn)
        return conn

    s = session(tmp_path, connect=with_oe)
    with pytest.raises(UnsafeRigError, match="could not be released") as err:
        s.run()
    assert OE_ONLY in str(err.value) and "switch off the servo supply" in str(err.value)
    assert err.value.servos_may_be_powered
    manifest = read_manifest(s.manifest_path)
    assert manifest["unsafe"]["servos_may_be_powered"] is True
    (entry,) = manifest["recordings"].values()
    assert entry["servos_released"] is False
    rig = held[-1].simulated
    assert held[-1].output_enable.disabled and not rig.pca.outputs_enabled()  # kept high


def test_a_dead_bus_is_refused_saying_what_to_do(tmp_path):
    dead = simulated_connect(SCENE, simulate, faults=Faults(stuck_at=0.0, stuck_duration=1e6))
    with pytest.raises(UnsafeRigError, match="does not answer on the bus") as err:
        session(tmp_path, connect=dead).run()
    assert "i2cdetect" in str(err.value)
    assert read_manifest(tmp_path / "s" / MANIFEST)["recordings"] == {}


def test_a_missing_accelerometer_stops_with_the_servos_known_off(tmp_path):
    # the servo outputs read back off before the MPU-6050 is looked for: a stop, not a rig
    # whose servos may be powered (that is exit 3, and the dead bus above)
    inner = simulated_connect(SCENE, simulate)

    def without_mpu(touch, attempt):
        conn = inner(touch, attempt)
        conn.bus.devices.pop(0x68)
        return conn

    with pytest.raises(UnsafeRigError, match="accelerometer does not answer") as err:
        session(tmp_path, connect=without_mpu).run()
    assert not err.value.servos_may_be_powered and "i2cdetect" in str(err.value)
    assert read_manifest(tmp_path / "s" / MANIFEST)["unsafe"]["servos_may_be_powered"] is False


def test_a_touch_that_lost_too_much_is_made_again(tmp_path):
    s = session(tmp_path, plan=Plan("one", ("brass",), (0.2,), 3), max_lost=0.0,
                connect=simulated_connect(SCENE, simulate, seed=1, faults=Faults.every_kind(0.003)),
                attempts=10)
    manifest = s.run()
    assert manifest["retakes"]  # a failed FIFO read restarts the FIFO: its samples are lost
    for entry in manifest["recordings"].values():
        assert entry["samples_lost"] == 0


#: ``ebantenna record``, its simulated rig holding touch ``HOLD`` (0-based) at its first FIFO read
#: until a signal stops the command: "held" on stderr says the touch is mid-way, so a signal sent
#: then lands in it however late this process reads the line (a touch takes about 0.2 s).
HOLDING_RECORD = """
import sys, time
from ebantenna.cli import main
from ebantenna.device.simulated import touches

HOLD, real = int(sys.argv[1]), touches.simulated_connect

class HoldingBus:
    def __init__(self, bus):
        self._bus = bus
    def __getattr__(self, name):
        if name != "read_i2c_block_data":
            return getattr(self._bus, name)
        def read(*args, **kwargs):
            print("held", file=sys.stderr, flush=True)
            while True:  # until the signal's handler raises
                time.sleep(0.01)
        return read

def holding(*args, **kwargs):
    connect = real(*args, **kwargs)
    def at(touch, attempt):
        conn = connect(touch, attempt)
        if touch.index == HOLD:
            conn.bus = HoldingBus(conn.bus)
        return conn
    return at

touches.simulated_connect = holding
raise SystemExit(main(sys.argv[2:]))
"""


def _run_record(out: Path, plan: Path, hold: int | None = None) -> subprocess.Popen:
    args = ["record", "--simulated", "--plan", str(plan), "--out", str(out), "--seed", "5"]
    start = ["-m", "ebantenna"] if hold is None else ["-c", HOLDING_RECORD, str(hold)]
    return subprocess.Popen([sys.executable, "-u", *start, *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env={**os.environ, "PYTHONUNBUFFERED": "1"})


def test_sigterm_mid_touch_then_resume_loses_nothing_and_repeats_nothing(tmp_path):
    """Killed with SIGTERM while touch 3 is searching: touches 1-2 stay saved and unchanged,
    touch 3 is not kept half made, and the resumed session makes 3 onwards, each once."""
    plan = tmp_path / "plan.json"
    plan.write_text(json.dumps(small_plan(duration=3.0).to_dict()))
    out = tmp_path / "session"
    proc = _run_record(out, plan, hold=2)  # touch 3 held mid-way until the signal
    seen = []
    for line in proc.stderr:
        seen.append(line)
        if line.strip() == "held":
            assert "touch 3/8" in seen[-2] and "searching" in seen[-2], "".join(seen)
            proc.send_signal(signal.SIGTERM)
            break
    rest = proc.stderr.read()
    code = proc.wait(timeout=60)
    proc.stdout.close()
    proc.stderr.close()
    assert code == 128 + signal.SIGTERM, "".join(seen) + rest
    assert "interrupted" in rest
    assert "touch 3/8" in "".join(seen) and "brass/0.3000/0: saved" not in rest  # mid-touch
    before = read_manifest(out / MANIFEST)["recordings"]
    assert sorted(e["touch"] for e in before.values()) == [0, 1]
    assert not list(out.rglob(f"{TEMPORARY_PREFIX}*"))
    resumed = _run_record(out, plan)
    _, err = resumed.communicate(timeout=120)
    assert resumed.returncode == 0, err
    assert "resuming: 2 of 8 touches already saved" in err
    after = read_manifest(out / MANIFEST)["recordings"]
    assert sorted(e["touch"] for e in after.values()) == list(range(8))
    for key, entry in before.items():  # nothing saved was lost or made again
        assert after[key]["sha256"] == entry["sha256"] == file_sha256(out / entry["file"])
    files = sorted(p.name for p in (out / "recordings").iterdir())
    assert len(files) == 8 and files == sorted(Path(e["file"]).name for e in after.values())
    searched = err.count("searching")
    assert searched - err.count("again") == 6  # touches 3-8 made once each (retakes aside)
    assert np.all([Recording.load(out / e["file"]).metadata["release"]["servos_released"]
                   for e in after.values()])
