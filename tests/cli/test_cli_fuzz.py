"""Fuzzing the command line: any arguments end in success or one clear error, never a traceback.

Hypothesis draws argument lists for every command from values a hostile new user would type:
valid ones, edge numbers (0, negative, NaN, infinity, 1e-300, 1e300, 2**70), junk and paths
that are directories. The property: ``main`` returns an exit code or exits through argparse
with one line on stderr; any other exception escaping it is a traceback the user would see. The
run is derandomized (the same examples every time) and small, so it stays a fast unit test.
"""

import contextlib
import io
import os
import tempfile

from cli_fuzzing import command_lines, working_directory
from hypothesis import HealthCheck, example, given, settings

from ebantenna.cli import main

NUMBERS = [
    "0",
    "-1",
    "0.5",
    "1",
    "2",
    "nan",
    "inf",
    "-inf",
    "1e-300",
    "1e300",
    str(2**70),
    "0.999999",
    "1e-12",
    "abc",
    "",
]
INTEGERS = ["0", "-1", "1", "2", "3", "64", "3080", "3081", "1000000", str(2**70), "2.5", "x", ""]
PATHS = ["", ".", "..", "OUT", "OUT/", "OUT/rec", "rec", "rec.npz", "rec.png", "rec.xyz"]

#: per command, its options and the values drawn for each (a flag's value is None)
COMMANDS = {
    "modes": {
        "--ratio": NUMBERS,
        "--contact": NUMBERS,
        "--no-contact": None,
        "--hinge": ["clamped", "pinned", "free", ""],
        "--modes": INTEGERS,
        "--tip-mass": NUMBERS,
        "--elements": INTEGERS,
        "--plot": PATHS,
        "--json": None,
    },
    "exact": {
        "--ratio": NUMBERS,
        "--contact": NUMBERS,
        "--no-contact": None,
        "--hinge": ["clamped", "pinned", "5"],
        "--modes": INTEGERS[:6],
        "--tip-mass": NUMBERS,
        "--json": None,
    },
    "simulate": {
        "--scene": ["ideal", "paper", "nope", "", "OUT"],
        "--ratio": NUMBERS,
        "--contact": NUMBERS,
        "--hinge": ["clamped", "pinned", "50", "-3", "nan", "x"],
        "--material": ["brass", "pvc", "gold", ""],
        "--seed": INTEGERS,
        "--out": PATHS,
        "--json": None,
    },
    "acquire": {
        "--simulated": None,
        "--bus": ["x", "-1"],
        "--material": ["oak", "gold"],
        "--ratio": NUMBERS,
        "--scene": ["paper", "nope"],
        "--seed": INTEGERS,
        "--inject-faults": ["0", "0.01", "-1", "2", "nan"],
        "--threshold": NUMBERS,
        "--duration": ["0.2", "0", "-1", "nan", "1e9"],
        "--out": PATHS,
        "--json": None,
    },
    # the long commands: only with a value that must be refused before any work starts
    "dataset": {
        "--seed": ["-1", "x", "1.5", str(2**70)],
        "--out": PATHS,
        "--jobs": INTEGERS,
        "--json": None,
    },
    "reproduce": {"--seed": ["-1", "x", str(2**70)], "--jobs": INTEGERS, "--json": None},
}
MUST_FAIL = {"dataset", "reproduce"}


#: per command, groups of options of which one is always given (so that valid runs happen too)
REQUIRED = {
    "modes": [("--ratio", "--contact", "--no-contact")],
    "exact": [("--ratio", "--contact", "--no-contact")],
    "simulate": [("--scene",), ("--out",)],
    "acquire": [("--simulated", "--simulated", "--bus")],
    "dataset": [("--seed",)],
    "reproduce": [("--seed",)],
}


def run(argv) -> int:
    """``main(argv)`` in a scratch directory holding a folder ``OUT``; its exit code."""
    with tempfile.TemporaryDirectory() as tmp, working_directory(tmp):
        os.mkdir("OUT")
        err = io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            try:
                code = main(argv)
            except SystemExit as exc:  # argparse and main's own error exits
                code = exc.code
    # any other exception propagates: the traceback a user would have seen
    assert code in (0, 1, 2), (argv, code, err.getvalue())
    if code == 2:
        lines = err.getvalue().strip().splitlines()
        assert lines and lines[-1].startswith("ebantenna"), (argv, err.getvalue())
        assert "Traceback" not in err.getvalue()
    if argv[0] in MUST_FAIL:
        assert code == 2, argv
    return code


def test_any_arguments_end_in_success_or_one_clear_error():
    outcomes = set()

    @settings(
        max_examples=150,
        derandomize=True,
        deadline=None,
        database=None,
        suppress_health_check=[HealthCheck.too_slow],
    )
    @given(argv=command_lines(COMMANDS, REQUIRED))
    # one valid run and one refused value per command, whatever examples this hypothesis draws
    @example(argv=["modes", "--no-contact"])
    @example(argv=["modes", "--ratio", "nan"])
    @example(argv=["exact", "--ratio", "0.5"])
    @example(argv=["exact", "--contact", "x"])
    @example(argv=["simulate", "--scene", "ideal", "--out", "rec.npz"])
    @example(argv=["simulate", "--scene", "nope", "--out", "rec.npz"])
    @example(argv=["acquire", "--simulated"])
    @example(argv=["acquire", "--simulated", "--duration", "-1"])
    def fuzz(argv):
        outcomes.add((argv[0], run(argv)))

    fuzz()
    # a fuzz whose examples all fail at parsing would test nothing of the commands themselves
    # (the explicit examples above make sure both outcomes are tried, under any hypothesis)
    for command in ("modes", "exact", "simulate", "acquire"):
        assert {(command, 0), (command, 2)} <= outcomes, sorted(outcomes)


def test_the_fuzz_table_covers_every_command():
    from ebantenna.cli import build_parser

    parser = build_parser()
    commands = set(parser._subparsers._group_actions[0].choices)
    # bench runs minutes whatever its arguments; its --json has a test of its own; record and
    # calibrate are fuzzed in tests/study/test_recorded_cli.py
    assert commands - set(COMMANDS) == {"bench", "record", "calibrate"}


def contract_rows() -> dict[str, list[str]]:
    """``cli:<command> <flag>`` for every flag the fuzz draws (read by the inventory test)."""
    rows = {}
    for command, flags in COMMANDS.items():
        rows[f"cli:{command}"] = [f"{command}: drawn with {len(flags)} flags"]
        for flag, values in flags.items():
            rows[f"cli:{command} {flag}"] = [f"{command} {flag} {v}" for v in (values or [""])]
    return rows
