"""Every command that writes checks its output before the work starts; errors name the flag."""

import importlib
import os

import pytest

import ebantenna.bench
import ebantenna.device.simulated
import ebantenna.paper.data
import ebantenna.simulate.simulator
from ebantenna.cli import main
from ebantenna.study import default_cache_dir


def _never(*args, **kwargs):
    raise AssertionError("the work started before the output was checked")


def _error(capsys, argv) -> str:
    with pytest.raises(SystemExit) as exc:
        main(argv)
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if not line.startswith(("usage:", " "))]
    assert exc.value.code == 2 and len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


@pytest.fixture
def no_work(monkeypatch):
    monkeypatch.setattr(ebantenna.device.simulated.SimulatedRig, "for_contact", _never)
    monkeypatch.setattr(ebantenna.simulate.simulator, "simulate", _never)
    monkeypatch.setattr(ebantenna.paper.data, "build_paper_dataset", _never)
    # the package exports the function reproduce under the module's name
    monkeypatch.setattr(importlib.import_module("ebantenna.study.reproduce"), "reproduce", _never)
    monkeypatch.setattr(ebantenna.bench, "run_benchmarks", _never)


@pytest.mark.parametrize("argv", [
    ["acquire", "--simulated", "--out", "{missing}/a.npz"],
    ["simulate", "--scene", "ideal", "--out", "{missing}/a.npz"],
    ["modes", "--ratio", "0.5", "--plot", "{missing}/modes.png"],
])
def test_a_file_in_a_missing_directory_fails_before_the_work(tmp_path, capsys, no_work, argv):
    argv = [a.format(missing=tmp_path / "missing_dir") for a in argv]
    err = _error(capsys, argv)
    flag = "--plot" if "--plot" in argv else "--out"
    assert f"error: {flag}: the directory {tmp_path / 'missing_dir'} does not exist" in err


@pytest.mark.parametrize("argv, flag", [
    (["dataset", "--quick", "--out", "{file}"], "--out"),
    (["reproduce", "--quick", "--out", "{file}"], "--out"),
    (["reproduce", "--quick", "--out", "{dir}", "--cache", "{file}"], "--cache"),
    (["bench", "--quick", "--out", "{file}"], "--out"),
    (["dataset", "--quick", "--out", "/proc/ebantenna-x"], "--out"),
])
def test_an_output_directory_that_cannot_be_used_fails_first(tmp_path, capsys, no_work, argv,
                                                               flag):
    afile = tmp_path / "a-file"
    afile.write_text("x")
    argv = [a.format(file=afile, dir=tmp_path / "d") for a in argv]
    err = _error(capsys, argv)
    assert f"error: {flag}" in err
    assert "must be a directory" in err or "does not accept new files" in err


def test_a_proc_output_says_why_it_cannot_be_written(capsys, no_work):
    err = _error(capsys, ["simulate", "--scene", "ideal", "--out", "/proc/x.npz"])
    assert "--out: cannot write in /proc: it does not accept new files" in err
    assert "No such file" not in err


@pytest.mark.parametrize("bus", ["-1", "x", "1.5"])
def test_a_bad_bus_number_names_the_flag_and_the_value(capsys, bus):
    err = _error(capsys, ["acquire", "--bus", bus])
    assert "argument --bus: must be a whole number >= 0" in err and bus in err
    assert "/dev/i2c--1" not in err


def test_a_missing_bus_names_the_flag(capsys):
    bus = next(n for n in range(90, 200) if not os.path.exists(f"/dev/i2c-{n}"))
    err = _error(capsys, ["acquire", "--bus", str(bus)])
    assert f"error: --bus {bus}: /dev/i2c-{bus} does not exist" in err


def test_a_multi_line_message_is_printed_on_one_line(tmp_path, capsys):
    scene = tmp_path / "s.json"
    scene.write_bytes(b"\xff\xfe")
    err = _error(capsys, ["simulate", "--scene", str(scene), "--out", str(tmp_path / "a")])
    assert f"{scene} is not a scene file: it is not UTF-8 text" in err


def test_a_relative_cache_directory_is_made_absolute(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("EBANTENNA_CACHE", "rel/dir")
    assert default_cache_dir() == tmp_path / "rel" / "dir"
    monkeypatch.setenv("EBANTENNA_CACHE", "~/c")
    assert default_cache_dir() == (tmp_path / "x").home() / "c"
