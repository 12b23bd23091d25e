"""The ``ebantenna`` command.

Each subcommand lives beside the code it drives, in a module with two functions:
``register(subparsers)`` adds its parser (and sets ``func`` to the function that runs it), and that
function takes the parsed arguments and returns an exit code. Modules import their heavy
dependencies inside the run function so that ``ebantenna --help`` stays fast.

With ``--json`` a command prints exactly one JSON object on stdout and nothing else.
"""

from __future__ import annotations

import argparse
import importlib
import json
import logging
import sys

from . import __version__

#: Modules that register subcommands, in the order ``--help`` lists them.
COMMAND_MODULES = (
    "ebantenna.fem._cli",
    "ebantenna.simulate._cli",
    "ebantenna.device._cli",
    "ebantenna.study._cli",
    "ebantenna.bench._cli",
)


def build_parser() -> argparse.ArgumentParser:
    """The argument parser with every subcommand registered."""
    parser = argparse.ArgumentParser(
        prog="ebantenna",
        description="A vibrating antenna probe: beam modes, simulated signals, features, "
        "classifiers and the real rig.",
    )
    parser.add_argument("--version", action="version", version=f"ebantenna {__version__}")
    parser.add_argument("-v", "--verbose", action="store_true", help="log progress to stderr")
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for name in COMMAND_MODULES:
        importlib.import_module(name).register(subparsers)
    return parser


def print_json(obj) -> None:
    """Print one JSON object on stdout (the ``--json`` contract)."""
    json.dump(obj, sys.stdout, indent=2, sort_keys=False)
    sys.stdout.write("\n")


def main(argv=None) -> int:
    """Run the ``ebantenna`` command line; returns the exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    logging.basicConfig(
        level=logging.INFO if args.verbose else logging.WARNING,
        format="%(levelname)s %(name)s: %(message)s",
        stream=sys.stderr,
    )
    try:
        return int(args.func(args) or 0)
    except (ValueError, TypeError, OSError) as exc:
        # Bad input and I/O problems end with one clear line, not a traceback.
        parser.exit(2, f"ebantenna {args.command}: error: {exc}\n")
