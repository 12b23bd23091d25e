"""A session that stays one session: resuming with other settings is refused, a second writer is
refused by a lock that names its holder, one lost-sample limit is kept in the session and used by
both ``record`` and ``dataset --from-recordings``; and what the operator sees: ``record
--dry-run``, ``servos_released``, the exit codes in ``--help``, a warning on a half-done
session."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from ebantenna.cli import main
from ebantenna.device.plan import Plan
from ebantenna.device.recording_session import LOCK, MANIFEST, MAX_LOST, RecordingSession
from ebantenna.device.simulated.touches import simulated_connect
from ebantenna.simulate import builtin_scene, simulate
from ebantenna.study.recorded import assemble_dataset

PLAN = Plan("rules", ("brass",), (0.1, 0.2), 1)


def plan_file(where):
    path = where / "plan.json"
    path.write_text(json.dumps(PLAN.to_dict()))
    return str(path)


def session(where, *, rig=None, max_lost=0.02):
    return RecordingSession(where, PLAN, simulated_connect(builtin_scene("ideal"), simulate),
                            rig=rig or {"simulated": True, "seed": 0}, max_lost=max_lost,
                            show_progress=False)


@pytest.mark.parametrize("rig, max_lost, named", [
    ({"simulated": True, "seed": 1}, 0.02, "seed was 0, now 1"),
    ({"simulated": True, "seed": 0, "inject_faults": 0.01}, 0.02, "inject_faults was None"),
    ({"simulated": True, "seed": 0}, 0.1, "max_lost was 0.02, now 0.1"),
])
def test_resuming_with_other_settings_is_refused_by_name(tmp_path, rig, max_lost, named):
    session(tmp_path / "s").open()
    with pytest.raises(ValueError, match=named):
        session(tmp_path / "s", rig=rig, max_lost=max_lost).open()
    session(tmp_path / "s").open()  # the same settings resume


def test_a_second_writer_is_refused_naming_the_holder(tmp_path):
    where = tmp_path / "s"
    session(where).open()
    # alive until killed below, however long the machine takes to get there
    holder = subprocess.Popen([sys.executable, "-c", "import signal; signal.pause()"])
    try:
        (where / LOCK).write_text(f"{holder.pid}\n")  # another live process holds it
        with pytest.raises(ValueError, match=f"another process \\(pid {holder.pid}"):
            session(where).open()
    finally:
        holder.kill()
        holder.wait()
    session(where).open()  # its holder no longer runs: the lock is taken over
    assert (where / LOCK).read_text().strip() == str(os.getpid())


def test_the_lock_is_released_when_the_session_ends(tmp_path):
    s = session(tmp_path / "s")
    s.run()
    assert not (tmp_path / "s" / LOCK).exists()


def test_one_lost_sample_limit_kept_in_the_session(tmp_path):
    s = session(tmp_path / "s", max_lost=0.07)
    manifest = s.run()
    assert manifest["max_lost"] == 0.07
    data = assemble_dataset(tmp_path / "s", tmp_path)  # the session's limit, not a fixed one
    assert data.n_signals == 2


def test_record_cli_dry_run_exit_codes_and_servos_released(tmp_path, capsys):
    plan = plan_file(tmp_path)
    out = str(tmp_path / "s")
    assert main(["record", "--simulated", "--plan", plan, "--out", out, "--dry-run",
                 "--json"]) == 0
    dry = json.loads(capsys.readouterr().out)
    assert (dry["touches"], dry["done"], dry["missing"]) == (2, 0, 2)
    assert dry["estimate_s"] > 0 and not (tmp_path / "s").exists()  # nothing written
    assert main(["record", "--simulated", "--plan", plan, "--out", out, "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["servos_released"] is True and summary["saved"] == 2
    manifest = json.loads((tmp_path / "s" / MANIFEST).read_text())
    assert manifest["max_lost"] == 0.06  # record's default, kept in the session
    # the function's default is the command's: a session recorded through the API keeps the
    # same touches as one recorded by 'ebantenna record'
    api = RecordingSession(tmp_path / "api", PLAN, simulated_connect(builtin_scene("ideal"),
                                                                     simulate))
    assert api.max_lost == MAX_LOST == 0.06
    assert main(["record", "--simulated", "--plan", plan, "--out", out, "--dry-run",
                 "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["missing"] == 0
    with pytest.raises(SystemExit):
        main(["record", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    for code in ("0 every touch saved", "1 a search found no contact", "2 bad input",
                 "3 the servos may still be powered"):
        assert code in text


@pytest.mark.parametrize("argv", [["--bus", "-1"], ["--simulated", "--oe-gpio", "-3"]])
def test_record_refuses_negative_device_numbers(tmp_path, argv, capsys):
    with pytest.raises(SystemExit) as stop:
        main(["record", *argv, "--out", str(tmp_path / "s"), "--dry-run"])
    assert stop.value.code == 2
    assert "must be a whole number >= 0" in capsys.readouterr().err


def test_a_half_done_session_is_assembled_with_a_warning(tmp_path, capsys):
    s = session(tmp_path / "s", rig={"simulated": True})
    s.open()
    s._record(next(iter(PLAN)))  # one touch of two, then the session stops
    s.release()
    assert main(["dataset", "--from-recordings", str(tmp_path / "s"), "--out", str(tmp_path),
                 "--json"]) == 0
    captured = capsys.readouterr()
    assert "the session is not finished: 1 of 2 touches saved" in captured.err
    assert json.loads(captured.out)["complete"] is False


def test_every_failed_attempt_is_listed_in_retakes(tmp_path):
    # a session that loses too much on every attempt stops; the manifest lists all the attempts
    from ebantenna.device.recording_session import UnsafeRigError
    from ebantenna.device.simulated import Faults

    s = RecordingSession(tmp_path / "s", PLAN,
                         simulated_connect(builtin_scene("ideal"), simulate,
                                           faults=Faults.every_kind(0.05), seed=0),
                         rig={"simulated": True}, max_lost=0.0, attempts=2, show_progress=False)
    with pytest.raises(UnsafeRigError, match="every one of 2 attempts"):
        s.run()
    retakes = json.loads((tmp_path / "s" / MANIFEST).read_text())["retakes"]
    assert [r["attempt"] for r in retakes] == [1, 2]


def test_what_record_keeps_the_data_set_takes(tmp_path, capsys):
    # at 1 % faults some reads fail; one failure costs 4-7 % of the window at 100 kHz, within
    # record's default limit of 6 % of the samples (docs/user_guide/recording.rst) more often than
    # not: some kept recordings lost samples, and dataset --from-recordings holds the recordings
    # to the session's own limit, not another
    plan = Plan("faults", ("brass",), (0.1, 0.2, 0.3), 2)
    (tmp_path / "plan.json").write_text(json.dumps(plan.to_dict()))
    assert main(["record", "--simulated", "--scene", "ideal", "--inject-faults", "0.01",
                 "--plan", str(tmp_path / "plan.json"), "--out", str(tmp_path / "s"),
                 "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["saved"] == 6
    manifest = json.loads((tmp_path / "s" / MANIFEST).read_text())
    kept = [e["samples_lost"] for e in manifest["recordings"].values()]
    assert max(kept) > 0  # some kept recording did lose samples
    assert main(["dataset", "--from-recordings", str(tmp_path / "s"), "--out", str(tmp_path),
                 "--json"]) == 0
    assembled = json.loads(capsys.readouterr().out)
    assert assembled["signals"] == 6 and assembled["max_lost"] == 0.06
