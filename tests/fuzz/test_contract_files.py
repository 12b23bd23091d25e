"""The file contract, fuzzed: every generated input ends in a clear error or the right answer.

The inputs come from ``contract_files_cases`` (over 500: mutations of valid recordings, models,
data sets and scenes; special files; paths of every type; output paths that cannot be written;
command-line arguments). Each case states what is acceptable: only a clear error (an error that
names the file or the parameter), only the right answer (what was saved, compared exactly), or
either (a flipped bit may fall in a byte that no reader uses). A traceback from the internals, a
``MemoryError``, a timeout (a FIFO that blocks) or a silently wrong answer fails.
"""

import os
from pathlib import Path

import pytest
from contract_files_cases import (
    cli_cases,
    file_cases,
    outcome,
    saver_cases,
    scene_cases,
    valid_files,
)

ACCEPTED = {"error": {"clear"}, "equal": {"right"}, "either": {"clear", "right"}}


GROUPS = {
    "loaders": file_cases,
    "scenes": scene_cases,
    "savers": saver_cases,
    "command-line": cli_cases,
}


@pytest.fixture(scope="module")
def cases(tmp_path_factory):
    """Every group's cases, their files made once per worker."""
    root = tmp_path_factory.mktemp("contract")
    files = valid_files(root)
    made = {}
    for group, make in GROUPS.items():
        (root / group).mkdir()
        made[group] = make(root / group, files)
    return made


@pytest.mark.parametrize("group", GROUPS)
def test_every_input_ends_in_a_clear_error_or_the_right_answer(cases, group):
    bad = []
    for case in cases[group]:
        kind, what = outcome(case)
        if kind not in ACCEPTED[case.expect]:
            bad.append(f"{case.id}: {kind} ({what})")
    assert not bad, "\n".join(bad)


def test_the_suite_has_at_least_500_inputs_of_every_kind(cases):
    every = [case for group in cases.values() for case in group]
    assert len(every) >= 500
    tags = set().union(*(c.tags for c in every))
    # truncation, bit flips, header edits (2**40 values, oversized headers), version edits,
    # special files (FIFO, directories, symlinks, devices), deep/binary JSON, paths, CLI, saves
    assert {"truncate", "flip", "header", "version", "special", "json", "path", "scene",
            "save", "cli", "out"} <= tags
    assert len({c.id for c in every}) == len(every)
    assert sum(c.expect == "equal" for c in every) >= 10  # right answers are checked too


def test_the_classifier_tells_each_class_apart(tmp_path):
    """A classifier that called everything clear would make the tests above pass vacuously."""
    from contract_files_cases import Case

    def raise_(exc):
        raise exc

    path = str(tmp_path / "f.npz")
    samples = {
        "clear": Case("c", lambda: raise_(ValueError(f"{path} is damaged")), "error", (path,)),
        "vague": Case("v", lambda: raise_(ValueError("bad")), "error", (path,)),
        "traceback": Case("t", lambda: raise_(KeyError("x")), "error", (path,)),
        "memory/timeout": Case("m", lambda: raise_(MemoryError()), "error", (path,)),
        "wrong": Case("w", lambda: 1, "either", (path,), same=lambda r: r == 2),
        "right": Case("r", lambda: 2, "either", (path,), same=lambda r: r == 2),
    }
    for expected, case in samples.items():
        assert outcome(case)[0] == expected
    fifo = Path(tmp_path / "fifo")
    os.mkfifo(fifo)
    blocks = Case("b", lambda: open(fifo, "rb"), "error", (str(fifo),), timeout=0.2)
    assert outcome(blocks)[0] == "memory/timeout"
    unicode = Case("u", lambda: b"\xff".decode(), "error", ("",))
    assert outcome(unicode)[0] == "traceback"  # a ValueError, but one that names nothing


#: What each group's cases read or write, by the prefix of their ids.
SURFACES = {
    "file:recording": ("loaders", "recording/"),
    "Recording.load": ("loaders", "recording/"),
    "file:dataset": ("loaders", "dataset/"),
    "load_dataset": ("loaders", "dataset/"),
    "file:model": ("loaders", "svc/"),
    "load_model": ("loaders", "mlp/"),
    "file:scene": ("scenes", "scene/"),
    "load_scene": ("scenes", "scene/"),
    "Recording.save": ("savers", "save-recording/"),
}


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these cases cover (read by the inventory test; held true by the test below)."""
    return {surface: [f"{group}: {prefix}*"] for surface, (group, prefix) in SURFACES.items()}


def test_every_surface_named_has_cases(cases):
    for surface, (group, prefix) in SURFACES.items():
        assert any(c.id.startswith(prefix) for c in cases[group]), surface
