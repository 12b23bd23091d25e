"""One recording followed from ``Scene`` to a predicted material (``benchmarks/reading_walk.py``):
the modules it passes at run time and the files a student reads, held within their ceilings."""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

import benchmark_scripts
import pytest
from unloaded_time import run

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = benchmark_scripts.FOLDER / "reading_walk.py"

walk_script = benchmark_scripts.load("reading_walk")


@pytest.fixture(scope="module")
def walk():
    # A fresh process: a function another test already ran behind a cache (the filter designs,
    # the block march's tables) would otherwise be skipped, and the walk would look shorter.
    path = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH", "")) if p)
    env = dict(os.environ, PYTHONPATH=path, OPENBLAS_NUM_THREADS="1")
    # a hang guard on the child's own time (waits for a CPU left out): the walk is about 3 s of
    # CPU on a quiet core, 300 s of its own time is no walk
    done = run([sys.executable, str(SCRIPT), "--json"], 300, capture_output=True, text=True,
               env=env)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_the_walk_as_run_stays_within_its_ceiling(walk):
    ceilings = walk_script.CEILINGS
    assert walk["run"]["distinct"] <= ceilings["run_modules"], walk["run"]["path"]
    assert walk["run"]["returns"] <= ceilings["run_returns"], walk["run"]["path"]
    assert walk["prediction"] in walk_script.TRAIN_MATERIALS


def test_the_walk_as_read_is_the_run_restricted_and_stays_within_its_ceiling(walk):
    assert walk["reading_order_matches_run"], "update READING_ORDER to the run's (see --help)"
    ceilings = walk_script.CEILINGS
    assert walk["read"]["distinct"] <= ceilings["read_files"]
    assert walk["read"]["returns"] <= ceilings["read_returns"]


def test_the_ceilings_never_exceed_the_walk_before_it_was_shortened():
    # The walk measured before the simulator's sensor steps moved beside their effects: 32
    # modules and 90 returns as run, 23 files and 44 returns as read.
    before = {"run_modules": 32, "run_returns": 90, "read_files": 23, "read_returns": 44}
    assert all(walk_script.CEILINGS[k] <= before[k] for k in before), walk_script.CEILINGS
    assert all(walk_script.TARGETS[k] <= walk_script.CEILINGS[k] for k in before)


def test_count_walk_merges_repeats_and_counts_returns():
    counted = walk_script.count_walk(["a", "a", "b", "c", "a", "b", "b", "d"])
    assert counted == {"path": ["a", "b", "c", "a", "b", "d"], "distinct": 4, "returns": 2}
    assert walk_script.count_walk([]) == {"path": [], "distinct": 0, "returns": 0}


def test_first_calls_leave_out_the_checks_and_what_they_call():
    import numpy as np

    import ebantenna
    from ebantenna.recording import Recording

    recorder = walk_script.FirstCalls(Path(ebantenna.__file__).resolve().parent)
    with recorder:
        for _ in range(2):  # the second time adds nothing: first calls only
            Recording(np.arange(3) / 10.0, np.zeros(3), np.zeros(3), 10.0)
    names = [name for _, name in recorder.calls]
    assert names == ["Recording.__post_init__"]  # _check_times, _check_metadata: checks
    assert {m for m, _ in recorder.calls} == {"ebantenna.recording"}


def test_the_architecture_page_states_the_ceilings():
    c = walk_script.CEILINGS
    page = " ".join((ROOT / "docs" / "architecture.rst").read_text(encoding="utf-8").split())
    assert (f"The ceilings today: {c['run_modules']} modules with {c['run_returns']} returns as "
            f"run, {c['read_files']} files with {c['read_returns']} returns as read.") in page


def test_partitions_are_every_split_once():
    # Bell's numbers: 1, 1, 2, 5, 15, 52 ways to split 0 ... 5 items
    for n, bell in enumerate([1, 1, 2, 5, 15, 52]):
        items = list(range(n))
        splits = [frozenset(frozenset(g) for g in p) for p in walk_script.partitions(items)]
        assert len(splits) == len(set(splits)) == bell
        assert all(sorted(x for g in p for x in g) == list(range(n)) for p in splits)


def test_fewest_returns_by_hand():
    order = ["p/a/x.py", "p/a/z.py", "p/a/x.py", "p/b/y.py", "p/a/z.py"]
    # apart: x z x b z, returns to x and to z; merged: one file, read again after b only
    assert walk_script.fewest_returns(order) == {"a": {1: 1, 2: 2}, "b": {1: 0}}
    assert walk_script.part_of("ebantenna/fem/modal.py") == "fem"
    assert walk_script.part_of("ebantenna/probe.py") == "probe.py"


@pytest.fixture(scope="module")
def fewest():
    """The fewest returns of the walk as read by any merge (Bell(10) merges of ``simulate``'s
    files, a few seconds): computed once for the tests below."""
    return walk_script.fewest_returns(walk_script.READING_ORDER)


def test_fewest_returns_meet_the_bounds_of_the_walk_as_read(fewest):
    # A part read in r separate runs (other parts between) returns r - 1 times as one file, at
    # least r - g times as g files (each run enters a file; g of them are new), and with every
    # file kept, as often as the walk itself returns to its files
    order = walk_script.READING_ORDER
    part_of = walk_script.part_of
    runs = {}
    for item in walk_script.count_walk(part_of(p) for p in order)["path"]:
        runs[item] = runs.get(item, 0) + 1
    seen, kept = set(), {}
    for path in walk_script.count_walk(order)["path"]:
        kept[part_of(path)] = kept.get(part_of(path), 0) + (path in seen)
        seen.add(path)
    assert set(fewest) == set(runs)
    for part, best in fewest.items():
        assert best[1] == runs[part] - 1
        assert all(returns >= runs[part] - g for g, returns in best.items())
        assert best[max(best)] == kept[part]
    assert sum(kept.values()) == walk_script.read_walk()["returns"]


def test_the_merges_option_prints_the_fewest_returns(capsys, monkeypatch, fewest):
    # the option prints what fewest_returns gives (computed once, in the fixture)
    monkeypatch.setattr(walk_script, "fewest_returns", lambda order=None: fewest)
    assert walk_script.main(["--merges"]) == 0
    out = capsys.readouterr().out
    least = sum(min(b.values()) for b in fewest.values())
    assert f"fewest returns as read by any merge within parts: {least} " in out


def test_the_architecture_page_states_the_fewest_returns_of_a_merge(fewest):
    least = {part: min(best.values()) for part, best in fewest.items()}
    page = " ".join((ROOT / "docs" / "architecture.rst").read_text(encoding="utf-8").split())
    assert (f"The fewest today: {sum(least.values())} returns, {least['fem']} in ``fem`` and "
            f"{least['simulate']} in ``simulate``") in page
    assert all(v == 0 for k, v in least.items() if k not in ("fem", "simulate"))
