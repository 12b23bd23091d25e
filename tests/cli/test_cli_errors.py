"""How every command ends: success, one clear line, or an interrupt; and the paths it reports."""

import json
import os
import signal
import subprocess
import sys
import textwrap

import numpy as np
import pytest
from unloaded_time import communicate, readline

from ebantenna import cli
from ebantenna.cli import main
from ebantenna.recording import Recording


def fails(capsys, argv, code=2):
    """Run ``argv``; return stderr after checking the exit code and that it is one line."""
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == code
    err = capsys.readouterr().err
    assert "Traceback" not in err and err.strip()
    return err


def test_simulate_reports_the_file_it_writes(tmp_path, capsys):
    out = tmp_path / "rec"  # no suffix: NumPy appends .npz, and so does the report
    assert (
        main(["simulate", "--scene", "ideal", "--ratio", "0.5", "--out", str(out), "--json"]) == 0
    )
    reported = json.loads(capsys.readouterr().out)["out"]
    assert reported == str(tmp_path / "rec.npz")
    assert Recording.load(reported).n_samples > 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rec.npz"]


@pytest.mark.parametrize("out", [".", "", "DIR", "DIR/"])
def test_an_output_that_is_a_directory_or_empty_is_refused(tmp_path, capsys, out, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "DIR").mkdir()
    err = fails(capsys, ["simulate", "--scene", "ideal", "--out", out])
    assert "--out must name a file" in err
    err = fails(capsys, ["acquire", "--simulated", "--out", out])
    assert "--out must name a file" in err
    err = fails(capsys, ["modes", "--ratio", "0.5", "--plot", out])
    assert "--plot must name a file" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["DIR"]  # nothing written, no ..npz


def test_modes_plot_without_a_suffix_says_where_the_png_went(tmp_path, capsys):
    assert main(["modes", "--ratio", "0.5", "--elements", "8", "--plot", str(tmp_path / "m")]) == 0
    assert f"saved to {tmp_path / 'm.png'}" in capsys.readouterr().out
    assert (tmp_path / "m.png").stat().st_size > 1000


def test_acquire_reports_the_file_it_writes(tmp_path, capsys):
    argv = ["acquire", "--simulated", "--seed", "1", "--out", str(tmp_path / "a"), "--json"]
    assert main(argv) == 0
    reported = json.loads(capsys.readouterr().out)["out"]
    assert reported == str(tmp_path / "a.npz") and Recording.load(reported).n_samples > 0


@pytest.mark.parametrize(
    "argv, message",
    [
        (["modes", "--ratio", "0.5", "--elements", "16384"], "n_elements must be <= 3080"),
        (["modes", "--ratio", "0.5", "--elements", "1000000"], "condition number grows like N^4"),
        (["modes", "--ratio", "0.5", "--elements", "2", "--modes", "50"], "n_modes must be <= 3"),
        (["modes", "--ratio", "0.5", "--modes", "0"], "n_modes must be >= 1"),
        (["acquire", "--simulated", "--duration", "10000"], "--duration must lie in (0, 60]"),
        (["simulate", "--scene", "ideal", "--seed", str(2**70), "--out", "x"], "2**63 - 1"),
        (["simulate", "--scene", "ideal", "--seed", "-1", "--out", "x"], "must lie in [0"),
        (["dataset", "--out", "d", "--seed", "1.5"], "must be an integer"),
    ],
)
def test_out_of_range_numbers_are_refused_by_name(capsys, argv, message):
    assert message in fails(capsys, argv)


def test_a_damaged_recording_is_one_clear_line(tmp_path):
    bad = tmp_path / "r.npz"
    Recording([0.0, 0.001], [0.0, 1.0], [0.0, 1.0], fs=1000.0).save(bad)
    os.truncate(bad, bad.stat().st_size - 10)
    with pytest.raises(ValueError, match="r.npz is not a recording") as exc:
        Recording.load(bad)
    assert "\n" not in str(exc.value)


@pytest.mark.parametrize(
    "kind, code, name", [(KeyboardInterrupt, 130, "SIGINT"), (cli.Terminated, 143, "SIGTERM")]
)
def test_an_interrupted_dataset_ends_in_one_line_and_json(
    tmp_path, capsys, monkeypatch, kind, code, name
):
    import ebantenna.paper.data

    def interrupted(*args, **kwargs):
        raise kind()

    monkeypatch.setattr(ebantenna.paper.data, "build_paper_dataset", interrupted)
    with pytest.raises(SystemExit) as exc:
        main(["dataset", "--out", str(tmp_path), "--quick", "--seed", "7", "--json"])
    assert exc.value.code == code
    captured = capsys.readouterr()
    assert captured.err == "ebantenna dataset: interrupted\n"
    report = json.loads(captured.out)
    assert report["interrupted"] == name and report["path"] is None and report["seed"] == 7


SIGNAL_SCRIPT = textwrap.dedent("""
    import faulthandler, signal, sys, time
    import ebantenna.simulate.dataset as d
    from ebantenna.cli import main

    # Ctrl-C as a command in the foreground gets it, whatever launched this suite: a suite run
    # in the background of a shell without job control inherits SIGINT ignored, and keeps it
    # (the CLI leaves an ignored SIGINT ignored, as a background command should)
    signal.signal(signal.SIGINT, signal.default_int_handler)

    # a run that does not end: every thread's stack on stderr when the test asks (SIGUSR1)
    faulthandler.register(signal.SIGUSR1, all_threads=True)

    def slow(*args, **kwargs):
        print("ready", file=sys.stderr, flush=True)
        time.sleep(120)

    d._simulate_rows = slow
    sys.exit(main(["dataset", "--out", sys.argv[1], "--quick", "--json"]))
""")


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_real_signal_during_dataset_ends_cleanly(tmp_path, sig, code):
    proc = subprocess.Popen(
        [sys.executable, "-c", SIGNAL_SCRIPT, str(tmp_path / "d")],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    # before "ready": the imports and the build's set-up, a few seconds of the child's time
    def stacks(child):
        child.send_signal(signal.SIGUSR1)

    try:
        ready = readline(proc, proc.stderr, 120, before_kill=stacks)
    except subprocess.TimeoutExpired as exc:
        raise AssertionError(f"never ready; the child's stacks:\n{exc.stderr}") from None
    assert ready == "ready\n"  # inside the build, past every import
    proc.send_signal(sig)
    # What is left is milliseconds of work (unwind, remove the temporary file, print): 60 s of
    # the child's own time (waits for a CPU left out) is a hang, whatever the machine's load.
    try:
        out, err = communicate(proc, 60, before_kill=stacks)
    except subprocess.TimeoutExpired as exc:  # killed: never left behind for another test
        raise AssertionError(f"no end after the signal; the child's stacks:\n{exc.stderr}") \
            from None
    assert proc.returncode == code, err
    assert err == "ebantenna dataset: interrupted\n"
    report = json.loads(out)
    assert report["interrupted"] == sig.name and report["path"] is None
    assert list((tmp_path / "d").iterdir()) == []  # no partial data set, no temporary file


def test_bench_json_is_one_strict_json_object(tmp_path, capsys):
    argv = ["bench", "--quick", "--only", "fem_accuracy", "--out", str(tmp_path), "--json"]
    assert main(argv) == 0

    def no_nan(token):
        raise AssertionError(f"{token} is not JSON")

    report = json.loads(capsys.readouterr().out, parse_constant=no_nan)
    assert set(report) == {"out", "quick", "report", "benchmarks"}
    assert set(report["benchmarks"]) == {"fem_accuracy"}
    assert report["benchmarks"]["fem_accuracy"]["rows"]
    assert os.path.exists(report["report"]["html"])


@pytest.mark.parametrize(
    "module, function, argv, kept",
    [
        ("ebantenna.device.pantilt", "search_and_record", ["acquire", "--simulated"], "material"),
        ("ebantenna.study.reproduce", "reproduce", ["reproduce", "--quick"], "quick"),
    ],
)
def test_every_long_command_ends_an_interrupt_in_one_line_and_json(
    tmp_path, capsys, monkeypatch, module, function, argv, kept
):
    import importlib

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(importlib.import_module(module), function, interrupted)
    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit) as exc:
        main([*argv, "--json"])
    assert exc.value.code == 130
    captured = capsys.readouterr()
    assert captured.err == f"ebantenna {argv[0]}: interrupted\n"
    report = json.loads(captured.out)
    assert report["interrupted"] == "SIGINT" and kept in report and report["out"] is None


def test_a_hang_up_seen_by_the_servo_guard_ends_acquire_in_one_line(capsys, monkeypatch):
    import ebantenna.device.pantilt
    from ebantenna.device import SignalReceived

    def hung_up(*args, **kwargs):
        raise SignalReceived(signal.SIGHUP)

    monkeypatch.setattr(ebantenna.device.pantilt, "search_and_record", hung_up)
    with pytest.raises(SystemExit) as exc:
        main(["acquire", "--simulated", "--json"])
    assert exc.value.code == 128 + signal.SIGHUP
    captured = capsys.readouterr()
    assert captured.err == "ebantenna acquire: interrupted\n"
    assert json.loads(captured.out)["interrupted"] == "SIGHUP"


def test_acquire_keeps_the_window_recorded_before_an_interrupt(tmp_path, capsys, monkeypatch):
    import ebantenna.device.pantilt
    from ebantenna.recording import Recording

    part = Recording(np.arange(5) / 1000.0, np.ones(5), np.zeros(5), 1000.0, {"interrupted": True})

    def interrupted_after_contact(*args, **kwargs):
        exc = KeyboardInterrupt()
        exc.recording = part  # what search_and_record attaches after a contact
        raise exc

    monkeypatch.setattr(ebantenna.device.pantilt, "search_and_record", interrupted_after_contact)
    out = tmp_path / "strike"
    with pytest.raises(SystemExit) as exc:
        main(["acquire", "--simulated", "--out", str(out), "--json"])
    assert exc.value.code == 130
    report = json.loads(capsys.readouterr().out)
    assert report["out"] == str(out) + ".npz" and report["samples"] == 5
    assert Recording.load(report["out"]).metadata["interrupted"] is True
