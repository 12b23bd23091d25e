"""Counts a command takes are bounded before any work: workers, seeds, and paths with a NUL.

``reproduce --jobs 100000`` spawned worker processes until it was killed; ``--seed 2**32 - 1``,
which an earlier ``--help`` allowed, failed inside scikit-learn. Each now ends, before any work,
in one line naming the flag.
"""

import os

import pytest

from ebantenna.cli import main

CORES = os.cpu_count() or 1


def _error(capsys, argv) -> str:
    with pytest.raises(SystemExit) as caught:
        main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert caught.value.code == 2 and err, err
    assert err[-1].startswith("ebantenna"), err
    return err[-1]


ROWS = {
    "cli:reproduce --jobs": [
        (["reproduce", "--jobs", "100000", "--out", "o"], "--jobs 100000"),
        (["reproduce", "--jobs", str(CORES + 1), "--out", "o"], "--force-jobs"),
        (["reproduce", "--jobs", "0"], "--jobs"),
        (["reproduce", "--jobs", "-2"], "--jobs"),
        (["reproduce", "--jobs", "2.5"], "--jobs"),
    ],
    "cli:dataset --jobs": [
        (["dataset", "--out", "o", "--jobs", "100000"], "--jobs 100000"),
        (["dataset", "--out", "o", "--jobs", "0"], "--jobs"),
    ],
    "cli:reproduce --seed": [
        (["reproduce", "--seed", str(2**32 - 1)], "--seed"),
        (["reproduce", "--seed", str(2**70)], "--seed"),
        (["reproduce", "--seed", "-1"], "--seed"),
    ],
    "cli:reproduce --out": [
        (["reproduce", "--out", "a\x00b"], "--out"),
    ],
    "cli:reproduce --force-jobs": [  # allowed: the error is then about --out, a file
        (["reproduce", "--jobs", str(CORES + 1), "--force-jobs", "--out", "f"], "--out"),
    ],
    "cli:dataset --force-jobs": [
        (["dataset", "--jobs", str(CORES + 1), "--force-jobs", "--out", "f"], "--out"),
    ],
}


@pytest.mark.parametrize(("argv", "word"), [row for rows in ROWS.values() for row in rows],
                         ids=lambda v: " ".join(v) if isinstance(v, list) else None)
def test_refused_before_any_work_naming_the_flag(tmp_path, monkeypatch, capsys, argv, word):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "f").write_text("a file, not a folder")
    assert word in _error(capsys, argv)
    assert sorted(os.listdir(tmp_path)) == ["f"]  # nothing was made


def contract_rows() -> dict[str, list[str]]:
    """The flags these rows cover (read by the inventory test)."""
    return {flag: [" ".join(argv) for argv, _ in rows] for flag, rows in ROWS.items()}
