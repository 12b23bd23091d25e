"""The safety contract of ``acquire`` and ``record``: whenever the servos were not confirmed
released, every way out (an error, a signal, a full disk, a removed --out folder, a stall) ends
with exit code 3 and the instruction to cut the servo supply, last; the finished recording is
saved first, atomically, elsewhere when --out cannot be written; and ``session.json`` records it.
"""

from __future__ import annotations

import errno
import json
import os
import shutil
import signal
from pathlib import Path

import pytest

import ebantenna.device.pantilt as pantilt
from ebantenna.cli import Terminated, main
from ebantenna.device._cli import CUT_SUPPLY
from ebantenna.device.recording_session import CUT_SUPPLY as SESSION_CUT_SUPPLY
from ebantenna.device.recording_session import RecordingSession, read_manifest
from ebantenna.device.simulated import Faults, touches
from ebantenna.recording import Recording

ACQUIRE = ["acquire", "--simulated", "--seed", "1", "--duration", "0.3"]


def _last_line(err: str) -> str:
    return err.strip().splitlines()[-1]


@pytest.fixture
def in_tmp(tmp_path, monkeypatch):
    """Run in an empty folder, where the fallback recordings land."""
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _fallbacks(folder):
    return sorted(folder.glob("acquire-unreleased-*.npz"))


def _full_disk_at(folder, monkeypatch):
    """Make ``folder``, where saving a recording fails as on a full disk (ENOSPC)."""
    save = Recording.save

    def full(self, path):
        if Path(path).parent.name == folder.name:
            raise OSError(errno.ENOSPC, "No space left on device")
        return save(self, path)

    monkeypatch.setattr(Recording, "save", full)
    folder.mkdir()


def test_a_removed_out_folder_saves_elsewhere_and_still_says_cut_the_supply(in_tmp, monkeypatch,
                                                                            capsys):
    folder = in_tmp / "gone"
    folder.mkdir()
    result = pantilt._Search.result

    def remove_then_result(self, guard):  # the folder disappears while the rig runs
        shutil.rmtree(folder, ignore_errors=True)
        return result(self, guard)

    monkeypatch.setattr(pantilt._Search, "result", remove_then_result)
    code = main([*ACQUIRE, "--release-fails", "--out", str(folder / "rec.npz")])
    err = capsys.readouterr().err
    assert code == 3 and _last_line(err).endswith(CUT_SUPPLY)
    (saved,) = _fallbacks(in_tmp)
    assert f"could not write {folder / 'rec.npz'}" in err and str(saved) in err
    assert Recording.load(saved).n_samples + Recording.load(saved).metadata["samples_lost"] == 350


def test_a_full_disk_saves_elsewhere_and_exits_3_in_json_too(in_tmp, monkeypatch, capsys):
    _full_disk_at(in_tmp / "full", monkeypatch)
    code = main([*ACQUIRE, "--release-fails", "--out", str(in_tmp / "full" / "r.npz"), "--json"])
    captured = capsys.readouterr()
    data = json.loads(captured.out)
    assert code == 3 and data["action_required"] == CUT_SUPPLY and "No space" in data[
        "save_failed"]
    assert data["out"] == str(_fallbacks(in_tmp)[0]) and _last_line(captured.err).endswith(
        CUT_SUPPLY)
    assert not list((in_tmp / "full").iterdir())  # nothing half-written left at --out


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP, signal.SIGINT])
def test_a_signal_during_the_save_still_ends_with_the_instruction(in_tmp, monkeypatch, capsys,
                                                                    signum):
    save = Recording.save

    def interrupted_save(self, path):
        os.kill(os.getpid(), signum)
        return save(self, path)

    monkeypatch.setattr(Recording, "save", interrupted_save)
    out = in_tmp / "rec.npz"
    code = main([*ACQUIRE, "--release-fails", "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 3 and _last_line(err).endswith(CUT_SUPPLY)
    assert Recording.load(out).n_samples > 0  # whole: written under a temporary name


def test_a_signal_in_the_window_after_a_failed_release_keeps_what_was_recorded(in_tmp,
                                                                              monkeypatch,
                                                                              capsys):
    def terminated(self, guard):  # the signal lands before the result is made
        raise Terminated(signal.SIGTERM)

    monkeypatch.setattr(pantilt._Search, "result", terminated)
    code = main([*ACQUIRE, "--release-fails"])
    err = capsys.readouterr().err
    assert code == 3 and "interrupted by SIGTERM" in err and _last_line(err).endswith(CUT_SUPPLY)
    (saved,) = _fallbacks(in_tmp)
    assert Recording.load(saved).metadata["interrupted"] is True


@pytest.mark.parametrize("release_fails", [False, True])
def test_sighup_is_handled_like_sigterm(in_tmp, monkeypatch, capsys, release_fails):
    sweep = pantilt._Search.sweep
    calls = []

    def hang_up(self, elapsed):
        calls.append(elapsed)
        if len(calls) == 5:
            os.kill(os.getpid(), signal.SIGHUP)
        return sweep(self, elapsed)

    monkeypatch.setattr(pantilt._Search, "sweep", hang_up)
    args = [*ACQUIRE, *(["--release-fails"] if release_fails else [])]
    if release_fails:
        assert main(args) == 3
        assert _last_line(capsys.readouterr().err).endswith(CUT_SUPPLY)
    else:
        with pytest.raises(SystemExit) as info:
            main(args)
        assert info.value.code == 128 + signal.SIGHUP
        assert "interrupted" in capsys.readouterr().err


def test_an_error_after_the_search_with_the_servos_released_keeps_its_own_code(in_tmp,
                                                                              monkeypatch,
                                                                              capsys):
    # the counterpart: servos released, a full disk is an ordinary error (exit 2) naming where
    # the recording went instead
    _full_disk_at(in_tmp / "full", monkeypatch)
    with pytest.raises(SystemExit) as info:
        main([*ACQUIRE, "--out", str(in_tmp / "full" / "r.npz")])
    err = capsys.readouterr().err
    assert info.value.code == 2 and "No space" in err and CUT_SUPPLY not in err
    assert str(sorted(in_tmp.glob("acquire-unreleased-*.npz"))[0]) in err


# -- record ---------------------------------------------------------------------------------

def _broken_record(monkeypatch):
    """``record --simulated`` on a rig whose servos never release."""
    real = touches.simulated_connect

    def connect(scene, simulate, *, faults=None, seed=0):
        return real(scene, simulate, faults=Faults(release_fails=True), seed=seed)

    monkeypatch.setattr(touches, "simulated_connect", connect)


def _plan(tmp_path):
    path = tmp_path / "plan.json"
    path.write_text('{"name": "one", "materials": ["brass"], "contacts_m": [0.2], '
                    '"repetitions": 1, "probe_length": 0.4}')
    return path


@pytest.mark.parametrize("failure", ["full disk", "SIGTERM", "SIGHUP"])
def test_record_marks_the_session_unsafe_and_exits_3_whatever_else_fails(in_tmp, monkeypatch,
                                                                          capsys, failure):
    _broken_record(monkeypatch)
    save = RecordingSession._save

    def failing_save(self, touch, rec):
        if failure == "full disk":
            raise OSError(errno.ENOSPC, "No space left on device")
        os.kill(os.getpid(), getattr(signal, failure))
        return save(self, touch, rec)

    monkeypatch.setattr(RecordingSession, "_save", failing_save)
    out = in_tmp / "session"
    code = main(["record", "--simulated", "--plan", str(_plan(in_tmp)), "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 3 and SESSION_CUT_SUPPLY in _last_line(err)
    unsafe = read_manifest(out / "session.json")["unsafe"]
    assert unsafe["servos_may_be_powered"] is True
    if failure == "full disk":  # the finished recording went elsewhere, and the operator is told
        (saved,) = in_tmp.glob("record-*.npz")
        assert saved.name.startswith("record-brass_0.2000_0-")
        assert str(saved) in err and Recording.load(saved).n_samples > 0
    else:  # the signal is held until the recording is saved and the session marked
        (saved,) = (out / "recordings").glob("*.npz")
        assert Recording.load(saved).metadata["release"]["servos_released"] is False
