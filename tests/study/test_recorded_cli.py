"""Fuzzing ``ebantenna record``, ``calibrate``, ``dataset --from-recordings`` and ``reproduce
--data``: any arguments end in success or one clear error, never a traceback (as
tests/cli/test_cli_fuzz.py does for the other commands)."""

import contextlib
import io
import json
import os
import shutil
import tempfile

import pytest
from cli_fuzzing import command_lines, working_directory
from hypothesis import HealthCheck, example, given, settings

from ebantenna.cli import main
from ebantenna.device.plan import Plan

PATHS = ["", ".", "OUT", "OUT/s", "s", "plan.json"]
#: per command, its options and the values drawn (a flag's value is None)
COMMANDS = {
    "record": {
        "--simulated": None,
        "--bus": ["1", "x"],
        "--plan": ["plan.json", "nope.json", "OUT", "bad.json"],
        "--out": PATHS,
        "--inject-faults": ["0", "0.001", "-1", "nan", "2"],
        "--max-lost": ["0.02", "-1", "nan", "1"],
        "--attempts": ["1", "0", "x"],
        "--seed": ["0", "-1"],
        "--no-wait": None,
        "--dry-run": None,
        "--oe-gpio": ["17", "-1"],
        "--json": None,
    },
    "calibrate": {
        "--data": ["data.npz", "plan.json", "OUT", "nope.npz", ""],
        "--scene": ["paper", "nope"],
        "--out": PATHS,
        "--json": None,
    },
    "dataset": {"--from-recordings": ["session", "OUT", "nope", ""], "--out": PATHS,
                "--quick": None, "--json": None},
}
REQUIRED = {"record": [("--simulated", "--bus"), ("--plan",)], "calibrate": [("--data",)],
            "dataset": [("--from-recordings",)]}


@pytest.fixture(scope="module")
def scratch(tmp_path_factory):
    """A folder with a two-touch plan, a bad plan, a finished session and its data set."""
    where = tmp_path_factory.mktemp("fuzz")
    plan = Plan("fuzz", ("brass",), (0.1, 0.2, 0.3), 1)
    (where / "plan.json").write_text(json.dumps(plan.to_dict()))
    (where / "bad.json").write_text('{"name": "x", "materials": []}')
    with working_directory(where), contextlib.redirect_stderr(io.StringIO()), \
            contextlib.redirect_stdout(io.StringIO()):
        assert main(["record", "--simulated", "--plan", "plan.json", "--out", "session"]) == 0
        assert main(["dataset", "--from-recordings", "session", "--out", "."]) == 0
    shutil.move(where / "recorded-fuzz.npz", where / "data.npz")
    return where


def run(scratch, argv) -> int:
    """``main(argv)`` in a fresh copy of the scratch folder holding a folder ``OUT``."""
    with tempfile.TemporaryDirectory() as tmp:
        here = shutil.copytree(scratch, os.path.join(tmp, "w"))
        os.mkdir(os.path.join(here, "OUT"))
        err = io.StringIO()
        with working_directory(here), contextlib.redirect_stderr(err), \
                contextlib.redirect_stdout(io.StringIO()):
            try:
                code = main(argv)
            except SystemExit as exc:  # argparse and main's own error exits
                code = exc.code
    assert code in (0, 1, 2), (argv, code, err.getvalue())
    if code == 2:
        lines = err.getvalue().strip().splitlines()
        assert lines and lines[-1].startswith("ebantenna"), (argv, err.getvalue())
        assert "Traceback" not in err.getvalue()
    return code


def test_any_arguments_end_in_success_or_one_clear_error(scratch):
    outcomes = set()

    @settings(max_examples=40, derandomize=True, deadline=None, database=None,
              suppress_health_check=[HealthCheck.too_slow,
                                     HealthCheck.function_scoped_fixture])
    @given(argv=command_lines(COMMANDS, REQUIRED))
    # a refused value per command, whatever examples this hypothesis version draws
    @example(argv=["record", "--simulated", "--plan", "plan.json", "--attempts", "0"])
    @example(argv=["dataset", "--from-recordings", "nope"])
    def fuzz(argv):
        outcomes.add((argv[0], run(scratch, argv)))

    fuzz()
    assert ("record", 2) in outcomes and ("dataset", 2) in outcomes, sorted(outcomes)


def test_reproduce_data_refuses_what_is_not_a_data_set(scratch, capsys):
    with working_directory(scratch), pytest.raises(SystemExit) as stop:
        main(["reproduce", "--data", "plan.json", "--out", "OUT2"])
    assert stop.value.code == 2
    assert capsys.readouterr().err.strip().startswith("ebantenna reproduce: error: plan.json")
