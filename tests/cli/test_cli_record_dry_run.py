"""The input contract of ``ebantenna record --dry-run``: the plan, its time estimate and the
touches done and missing, with nothing recorded or written.

A bad input (a plan file that is none, a session folder of another plan) ends in a one-line
error naming it; a good one is checked against the session's own files: the touches its
manifest lists with their recording present are done, the others missing, and the folder is
left as it was.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import re
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "fuzz"))
from contract_files_cases import CliError, run_cli  # noqa: E402

from ebantenna.device.plan import Plan  # noqa: E402
from ebantenna.device.recording_session import MANIFEST, RecordingSession  # noqa: E402

PLAN = Plan("dry", ("brass",), (0.2, 0.3), 1)


def _dry_run(plan_path, out) -> dict:
    from ebantenna.cli import main

    text = io.StringIO()
    with contextlib.redirect_stdout(text):
        code = main(["record", "--simulated", "--plan", str(plan_path), "--out", str(out),
                     "--dry-run", "--json"])
    assert code == 0
    return json.loads(text.getvalue())


@pytest.fixture(scope="module")
def recorded(tmp_path_factory):
    """A session of :data:`PLAN` recorded, the file of its last touch then removed, and the
    plan's file."""
    from ebantenna.device.simulated.touches import simulated_connect
    from ebantenna.simulate import builtin_scene, simulate

    where = tmp_path_factory.mktemp("dry")
    plan_path = where / "plan.json"
    plan_path.write_text(json.dumps(PLAN.to_dict()), encoding="utf-8")
    manifest = RecordingSession(where / "s", PLAN, simulated_connect(
        builtin_scene("paper"), simulate, seed=0), rig={"simulated": True},
        show_progress=False).run()
    (where / "s" / manifest["recordings"][PLAN[-1].key]["file"]).unlink()
    return where, plan_path


def _snapshot(folder):
    return sorted((p.name, p.stat().st_size, p.stat().st_mtime_ns) for p in folder.iterdir())


def test_a_dry_run_of_a_new_folder_lists_every_touch_and_writes_nothing(recorded, tmp_path):
    _, plan_path = recorded
    out = tmp_path / "new"
    summary = _dry_run(plan_path, out)
    assert not out.exists()
    assert summary["dry_run"] is True and summary["touches"] == len(PLAN) == 2
    assert summary["done"] == 0 and summary["missing_touches"] == [t.key for t in PLAN]
    assert 0 < summary["estimate_s"] <= summary["estimate_worst_s"]


def test_a_dry_run_counts_what_the_manifest_lists_and_leaves_the_folder(recorded):
    where, plan_path = recorded
    folder = where / "s"
    manifest = json.loads((folder / MANIFEST).read_text(encoding="utf-8"))
    present = {k for k, e in manifest["recordings"].items() if (folder / e["file"]).exists()}
    before = _snapshot(folder)
    summary = _dry_run(plan_path, folder)
    assert _snapshot(folder) == before
    assert summary["done"] == len(present) == 1  # the last touch's file is gone
    assert summary["missing_touches"] == [t.key for t in PLAN if t.key not in present]


def test_a_dry_run_refuses_a_folder_of_another_plan(recorded, tmp_path):
    where, _ = recorded
    other = tmp_path / "other.json"
    other.write_text(json.dumps(Plan("other", ("brass",), (0.25,), 1).to_dict()),
                     encoding="utf-8")
    with pytest.raises(CliError, match=re.escape(str(where / "s"))) as err:
        run_cli(["record", "--simulated", "--plan", str(other), "--out", str(where / "s"),
                 "--dry-run"])
    # what differs is named (the plan's name, its contacts), so the user sees what to change
    assert "the name: 'dry' in the folder, 'other' given" in str(err.value)
    assert "the contacts (m): [0.2, 0.3] in the folder, [0.25] given" in str(err.value)


@pytest.mark.parametrize(("row", "text"), [("not-json", "{"), ("no-plan", "[]")])
def test_a_dry_run_refuses_a_plan_file_that_is_none(tmp_path, row, text):
    plan_path = tmp_path / "plan.json"
    plan_path.write_text(text, encoding="utf-8")
    with pytest.raises(CliError, match="plan"):
        run_cli(["record", "--simulated", "--plan", str(plan_path), "--out",
                 str(tmp_path / "s"), "--dry-run"])
    assert not (tmp_path / "s").exists()


def contract_rows() -> dict[str, list[str]]:
    """The surface these rows cover (read by the inventory test)."""
    return {"cli:record --dry-run": ["new-folder", "manifest-counted", "another-plan",
                                     "not-json", "no-plan"]}
