"""What the command-line fuzz tests share: a working directory for a run, and command lines drawn
from a table of each command's options and the ones it requires."""

import contextlib
import os

from hypothesis import strategies as st


@contextlib.contextmanager
def working_directory(path):
    """Run the body in ``path`` (``contextlib.chdir`` arrives only with Python 3.11)."""
    before = os.getcwd()
    os.chdir(path)
    try:
        yield
    finally:
        os.chdir(before)


@st.composite
def command_lines(draw, commands, required):
    """An argv: a command of ``commands`` (command -> {option: values or None}), one option of
    each group ``required[command]`` lists, and up to three others."""
    command = draw(st.sampled_from(sorted(commands)))
    options = commands[command]
    chosen = [draw(st.sampled_from(group)) for group in required[command]]
    others = sorted(set(options) - set(chosen))
    chosen += draw(st.lists(st.sampled_from(others), max_size=3, unique=True))
    argv = [command]
    for name in chosen:
        argv.append(name)
        if options[name] is not None:
            argv.append(draw(st.sampled_from(options[name])))
    return argv
