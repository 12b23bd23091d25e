"""The guide's walk-through (docs/user_guide/recording.rst, 'The operator's steps') run as written
on the simulated rig: its example plan file, every command of its steps with ``--simulated`` for
``--bus 1``, in order, ending in a report and a calibrated scene. The commands and the plan are
read from the page, so the page and the program cannot drift apart."""

from __future__ import annotations

import contextlib
import io
import json
import re
import shlex
from pathlib import Path

import pytest
from cli_fuzzing import working_directory

from ebantenna.cli import main

GUIDE = Path(__file__).resolve().parents[2] / "docs" / "user_guide" / "recording.rst"


def _section(text: str, title: str) -> str:
    start = text.index(f"{title}\n{'-' * len(title)}\n")
    rest = text[start + 2 * len(title) + 2:]
    following = re.search(r"\n[^\n]+\n-{3,}\n", rest)
    return rest[: following.start()] if following else rest


def guide_plan() -> str:
    """The example plan file of 'The plan file' section, as written."""
    block = _section(GUIDE.read_text(), "The plan file").split("::\n\n", 1)[1]
    lines = []
    for line in block.splitlines():
        if line and not line.startswith("    "):
            break
        lines.append(line[4:])
    return "\n".join(lines).strip() + "\n"


def guide_commands() -> list[list[str]]:
    """The commands of 'The operator's steps', in order, for the simulated rig."""
    steps = _section(GUIDE.read_text(), "The operator's steps")
    found = re.findall(r"^ {7}ebantenna (.+)$", steps, flags=re.MULTILINE)
    return [shlex.split(line.replace("--bus 1", "--simulated")) for line in found]


def run(argv) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(argv)
    return code, out.getvalue(), err.getvalue()


@pytest.fixture(scope="module")
def walked(tmp_path_factory):
    """The guide's plan written as plan.toml, and its commands up to the assembled data set."""
    where = tmp_path_factory.mktemp("guide")
    (where / "plan.toml").write_text(guide_plan())
    commands = guide_commands()
    outputs = {}
    with working_directory(where):
        for argv in commands[:4]:  # dry run, record, assemble, then the study on its own
            if argv[0] == "reproduce":
                break
            code, out, err = run(argv)
            assert code == 0, (argv, err)
            outputs[" ".join(argv)] = out
    return where, commands, outputs


def test_the_guide_lists_its_commands_in_order():
    names = [argv[0] for argv in guide_commands()]
    assert names == ["record", "record", "dataset", "reproduce", "calibrate"]
    assert "--dry-run" in guide_commands()[0]
    assert 'name = "bench-check"' in guide_plan()


def test_the_dry_run_and_the_session_as_written(walked):
    where, commands, outputs = walked
    dry = outputs[" ".join(commands[0])]
    assert "18 touches" in dry and "missing 18" in dry
    manifest = json.loads((where / "session" / "session.json").read_text())
    assert len(manifest["recordings"]) == 18
    # the file the guide names is the file the program wrote
    assert (where / commands[3][commands[3].index("--data") + 1]).is_file()


def test_the_study_as_written_ends_in_a_report(walked):
    where, commands, _ = walked
    with working_directory(where):
        code, _, err = run(commands[3])
    assert code == 0, err
    # the example design is too small for two sections: said before any work, listed in the report
    assert "splits: needs at least 5 positions (has 3)" in err.splitlines()[0]
    report = (where / "report" / "report.md").read_text()
    for section in ("splits", "full range", "seeds", "ann setup", "contact law", "rod geometry"):
        assert f"| {section} |" in report
    assert "How much the numbers carry" not in report
    assert "1 cm apart" not in report and "at least 10 cm apart" in report


def test_the_calibration_as_written_writes_the_scene(walked):
    where, commands, _ = walked
    with working_directory(where):
        code, out, err = run(commands[4])
    assert code == 0, err
    assert (where / "calibration" / "paper-calibrated.toml").is_file()
    # the paper scene's hinge is a clamp: reported as not identifiable, never as a bound
    assert "hinge_stiffness: not identifiable" in out
    assert "warning: hinge_stiffness is not identifiable" in err
