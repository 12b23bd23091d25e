"""The ``ebantenna`` command.

Each subcommand lives beside the code it drives, in a module with two functions:
``register(subparsers)`` adds its parser (and sets ``func`` to the function that runs it), and that
function takes the parsed arguments and returns an exit code. Modules import their heavy
dependencies inside the run function so that ``ebantenna --help`` stays fast.

With ``--json`` a command prints exactly one JSON object on stdout and nothing else.

Every command ends in one of three ways: success (exit code 0, or 1 where the command says so),
one line on stderr naming what was wrong (exit code 2: bad input, a damaged file, too little
memory; exit code 3 from ``acquire``: the recording was saved but the servos could not be
released, and the servo supply must be cut by hand), or, on Ctrl-C, SIGTERM or SIGHUP, one line
saying so (exit codes 130, 143 and 129, as a shell reports a process killed by those signals). A
command that has partial results worth keeping (a recording) saves them before it stops; with
``--json`` it then prints what it kept, marked ``"interrupted"``.

The signal handlers are the first thing :func:`main` installs, before it imports any command
module (and ``import ebantenna`` imports nothing heavy), so an interrupt during the start-up
imports ends in the same one line as one during the work.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import json
import logging
import os
import signal
import sys
import threading

from . import __version__, _signals
from ._signals import Terminated

#: Modules that register subcommands, in the order ``--help`` lists them.
COMMAND_MODULES = (
    "ebantenna.fem._cli",
    "ebantenna.simulate._cli",
    "ebantenna.paper._cli",
    "ebantenna.device._cli",
    "ebantenna.study.recorded._cli",
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


#: Seeds the command line accepts: what a 64-bit signed integer holds, from 0.
MAX_SEED = 2**63 - 1


def seed_argument(text: str, maximum: int = MAX_SEED) -> int:
    """The ``--seed`` type: an integer in ``[0, maximum]`` (default :data:`MAX_SEED`)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be an integer, got {text!r}") from None
    if not 0 <= value <= maximum:
        shown = "2**63 - 1" if maximum == MAX_SEED else str(maximum)
        raise argparse.ArgumentTypeError(f"must lie in [0, {shown}], got {text:.40}")
    return value


def seeds_up_to(maximum: int):
    """A ``--seed`` type for a command whose seeds end at ``maximum`` (what its help says)."""
    def seed(text: str) -> int:
        return seed_argument(text, maximum)
    seed.__name__ = "seed"
    return seed


def jobs_argument(text: str) -> int:
    """The ``--jobs`` type: -1 (every core) or a count of workers >= 1."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be an integer, got {text!r:.40}") from None
    if value != -1 and value < 1:
        raise argparse.ArgumentTypeError(f"must be -1 (every core) or a count >= 1, got {text}")
    return value


def check_jobs(jobs: int, force: bool, flag: str = "--jobs") -> None:
    """Refuse more workers than the machine has cores, unless ``force`` (``--force-jobs``)."""
    cores = os.cpu_count() or 1
    if jobs > cores and not force:
        raise ValueError(f"{flag} {jobs} asks for more workers than this machine's {cores} "
                         f"core{'s' if cores > 1 else ''}; give at most {cores} (or -1), or add "
                         "--force-jobs")


def print_json(obj) -> None:
    """Print one JSON object on stdout (the ``--json`` contract)."""
    json.dump(obj, sys.stdout, indent=2, sort_keys=False)
    sys.stdout.write("\n")


def _raise_terminated(signum, frame):
    _signals.note(signum)
    raise Terminated(signum)


def _raise_interrupt(signum, frame):
    _signals.note(signum)
    raise KeyboardInterrupt


#: Signals that end a command like SIGTERM: terminate, and hang-up (the terminal closed, an SSH
#: session dropped), which would otherwise kill the process with no cleanup at all.
_TERMINATING = tuple(getattr(signal, name) for name in ("SIGTERM", "SIGHUP")
                     if hasattr(signal, name))


@contextlib.contextmanager
def _sigterm_as_interrupt():
    """SIGINT raises :class:`KeyboardInterrupt` and SIGTERM :class:`Terminated` inside.

    SIGINT gets Python's own handler back even if the caller changed it, unless it was ignored
    (a command started in the background by a shell ignores Ctrl-C, and keeps doing so).
    """
    if threading.current_thread() is not threading.main_thread():
        yield  # signal handlers can be set from the main thread only
        return
    previous_int = signal.getsignal(signal.SIGINT)
    if previous_int is not signal.SIG_IGN:
        signal.signal(signal.SIGINT, _raise_interrupt)
    previous = {signum: signal.signal(signum, _raise_terminated) for signum in _TERMINATING}
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)
        if previous_int is not None:
            signal.signal(signal.SIGINT, previous_int)


@contextlib.contextmanager
def signals_ignored():
    """While the last lines are written (and a command's safety ending runs): a second Ctrl-C,
    SIGTERM or SIGHUP must not cut it short."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = {signum: signal.signal(signum, signal.SIG_IGN)
                for signum in (signal.SIGINT, *_TERMINATING)}
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)


def interrupted(exc: KeyboardInterrupt, partial: dict) -> KeyboardInterrupt:
    """Attach what a command kept to the interrupt, for :func:`main` to print with ``--json``."""
    exc.partial = partial
    return exc


def _exit(code: int, message: str):
    """End the command with one line on stderr (what :meth:`argparse.ArgumentParser.exit` does)."""
    sys.stderr.write(message)
    sys.stderr.flush()
    raise SystemExit(code)


def _interrupted(exc: KeyboardInterrupt, args, argv) -> None:
    """End an interrupted command: one line, and with ``--json`` the JSON of what it kept."""
    signum = exc.signum if isinstance(exc, Terminated) else signal.SIGINT
    _signals.clear()
    partial = getattr(exc, "partial", None)
    # interrupted before its arguments were parsed, the command's --json is looked for by hand
    wants_json = getattr(args, "json", False) if args is not None else "--json" in argv
    where = "ebantenna" if args is None else f"ebantenna {args.command}"
    kept = f"; kept {partial['out']}" if partial and partial.get("out") else ""
    with signals_ignored():
        if wants_json:
            print_json({"interrupted": signal.Signals(signum).name, **(partial or {})})
            sys.stdout.flush()
        _exit(128 + signum, f"{where}: interrupted{kept}\n")


def main(argv=None) -> int:
    """Run the ``ebantenna`` command line; returns the exit code."""
    args = None
    argv = sys.argv[1:] if argv is None else list(argv)
    _signals.clear()
    try:
        with _sigterm_as_interrupt():  # first: every import below is interruptible cleanly
            parser = build_parser()
            args = parser.parse_args(argv)
            logging.basicConfig(
                level=logging.INFO if args.verbose else logging.WARNING,
                format="%(levelname)s %(name)s: %(message)s",
                stream=sys.stderr,
            )
            if os.environ.get("EBANTENNA_ENGINE") is not None:  # checked before any work
                from .ml import check_engine

                check_engine()
            from ._validate import more_jobs_allowed

            # --force-jobs (checked by check_jobs) lets the workers through to the functions
            with more_jobs_allowed(getattr(args, "force_jobs", False)):
                code = int(args.func(args) or 0)
            _signals.raise_pending()  # a signal a library caught and went on from
            return code
    except KeyboardInterrupt as exc:
        _interrupted(exc, args, argv)
    except (MemoryError, ValueError, TypeError, OSError) as exc:
        # Bad input, damaged files and I/O problems end with one clear line, not a traceback.
        where = "ebantenna" if args is None else f"ebantenna {args.command}"
        text = "not enough memory for this request" if isinstance(exc, MemoryError) else str(exc)
        _exit(2, f"{where}: error: {' '.join(text.splitlines())}\n")  # one line, always
