"""SIGINT or SIGTERM during the command's start-up imports ends in one line, exit 130 or 143.

How the moment is made certain, not hoped for: the child process puts a finder at the head of
``sys.meta_path`` that, when the import system looks for the target module, writes a marker file
and sends the signal to its own process with ``os.kill``. CPython runs a Python-level signal
handler at the next bytecode boundary of the main thread, and the next bytecodes are those of
the import machinery loading that very module: the signal lands *during that import*, every
time. The marker proves that the finder fired (a module imported before the finder was set would
not be looked up, and the test fails instead of passing unnoticed). Without handlers installed
before those imports, SIGINT prints a ``KeyboardInterrupt`` traceback and SIGTERM kills the
process with no message: both fail the assertions.
"""

import json
import signal
import sys
import textwrap

import pytest
from unloaded_time import run

CHILD = textwrap.dedent("""
    import os, signal, sys

    signal.signal(signal.SIGINT, signal.default_int_handler)  # as in a terminal
    SIG, TARGET, MARK, HOW = int(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4]

    class Trip:
        def find_spec(self, name, path=None, target=None):
            if name == TARGET:
                sys.meta_path.remove(self)
                open(MARK, "w").close()
                os.kill(os.getpid(), SIG)
            return None

    sys.meta_path.insert(0, Trip())
    sys.argv = ["ebantenna", *sys.argv[5:]]
    if HOW == "script":  # what the installed `ebantenna` script does
        from ebantenna.cli import main
        sys.exit(main())
    import runpy  # python -m ebantenna
    runpy.run_module("ebantenna", run_name="__main__", alter_sys=True)
""")

#: Modules imported during the start of ``ebantenna modes --json``: the first command module
#: (while the parser is built), NumPy (the first heavy import) and SciPy (inside the command).
TARGETS = ["ebantenna.fem._cli", "numpy", "scipy.linalg"]


@pytest.mark.parametrize("target", TARGETS)
@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_during_the_start_up_imports_ends_in_one_line(tmp_path, target, sig, code):
    mark = tmp_path / "fired"
    how = "script" if target != "numpy" else "module"
    # the child's work is the start-up imports, about a second of CPU: 120 s of its own time
    # (waits for a CPU left out, so a loaded machine does not count) is a hang
    proc = run(
        [sys.executable, "-c", CHILD, str(int(sig)), target, str(mark), how,
         "modes", "--ratio", "0.5", "--json"],
        120, capture_output=True, text=True,
    )
    assert mark.exists(), "the signal was never sent: the target was imported before"
    assert proc.returncode == code, proc.stderr
    assert proc.stderr in ("ebantenna: interrupted\n", "ebantenna modes: interrupted\n")
    assert json.loads(proc.stdout) == {"interrupted": sig.name}


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_stop_that_a_library_swallows_still_ends_the_command(monkeypatch, capsys, sig, code):
    # scikit-learn's MLP training catches KeyboardInterrupt (and so Terminated), warns and
    # returns; a command that went on from there must still end as stopped, not with success
    import os

    from ebantenna import _signals, cli
    from ebantenna._progress import progress
    from ebantenna.fem import _cli as fem_cli

    steps = []

    def swallowing(args):
        try:
            os.kill(os.getpid(), sig)  # the handler runs at the next bytecode, inside the try
            for _ in range(10_000_000):
                pass
        except KeyboardInterrupt:
            pass  # what a library that catches it does
        for i in progress(range(3), enabled=False):  # the next step of a bar raises it again
            steps.append(i)
        return 0

    monkeypatch.setattr(fem_cli, "run_modes", swallowing)
    # as in a terminal: a test worker may ignore Ctrl-C, and the command keeps an ignored SIGINT
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(SystemExit) as stop:
            cli.main(["modes", "--ratio", "0.5"])
    finally:
        signal.signal(signal.SIGINT, previous)
    assert stop.value.code == code and steps == []
    assert "interrupted" in capsys.readouterr().err
    assert _signals.pending() is None  # acted on, and forgotten


def test_a_stop_swallowed_after_the_last_step_still_ends_the_command(monkeypatch):
    import os

    from ebantenna import cli
    from ebantenna.fem import _cli as fem_cli

    def swallowing(args):
        try:
            os.kill(os.getpid(), signal.SIGTERM)
            for _ in range(10_000_000):
                pass
        except KeyboardInterrupt:
            pass
        return 0

    monkeypatch.setattr(fem_cli, "run_modes", swallowing)
    with pytest.raises(SystemExit) as stop:
        cli.main(["modes", "--ratio", "0.5"])
    assert stop.value.code == 143
