"""``reproduce --data FILE``: every file it cannot run on ends in exit code 2 and one line that
names ``--data`` or the file, before any work (no report folder written)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from ebantenna.cli import main
from ebantenna.simulate.dataset import FORMAT, _checksum
from ebantenna.study.recorded import MIN_SAMPLES


def _data_set(path, samples=MIN_SAMPLES, scene=None):
    """A data set file in load_dataset's format, written by hand: 2 materials x 5 positions x 2
    repetitions (a design every section accepts) with records of ``samples`` samples."""
    materials, positions = ("brass", "pvc"), np.linspace(0.05, 0.25, 5)
    rows = [(m, c, r) for m in materials for c in positions for r in range(2)]
    n, fs = len(rows), 1000.0
    rng = np.random.default_rng(0)
    arrays = {"ax": rng.normal(size=(n, samples)).astype(np.float32),
              "az": rng.normal(size=(n, samples)).astype(np.float32),
              "material": np.array([m for m, _, _ in rows]),
              "contact": np.array([c for _, c, _ in rows]),
              "contact_true": np.array([c for _, c, _ in rows]),
              "repetition": np.array([r for _, _, r in rows], dtype=np.int64),
              "sweep_speed": np.full(n, np.nan), "tilt_ratio": np.full(n, np.nan),
              "seed_row": np.full(n, -1, dtype=np.int64)}
    config = {"format": FORMAT, "scene": {"probe": {"length": 0.4}} if scene is None else scene}
    meta = {"config": config, "checksum_sha256": _checksum(arrays, fs)}
    np.savez(path, fs=np.float64(fs), metadata=np.array(json.dumps(meta)), **arrays)
    return str(path)


#: ``case -> (make the --data argument in tmp_path, words the error must hold)``
CASES = {
    "empty": (lambda tmp: "", "--data must name a file"),
    "missing": (lambda tmp: str(tmp / "none.npz"), "none.npz"),
    "a-folder": (lambda tmp: str(tmp), "is a directory"),
    "not-npz": (lambda tmp: (tmp / "x.npz").write_text("hi") and str(tmp / "x.npz"),
                "is not an ebantenna data set"),
    "records-too-short": (lambda tmp: _data_set(tmp / "short.npz", samples=100),
                          f"records of {MIN_SAMPLES} samples at least (has 100)"),
    "no-probe-length": (lambda tmp: _data_set(tmp / "s.npz", scene={"name": "x"}),
                        "probe's length"),
}


@pytest.mark.parametrize("case", CASES)
def test_a_file_reproduce_cannot_run_on_is_refused_before_any_work(tmp_path, capsys, case):
    make, words = CASES[case]
    data, out = make(tmp_path), tmp_path / "report"
    with pytest.raises(SystemExit) as end:
        main(["reproduce", "--data", data, "--out", str(out), "--jobs", "1"])
    error = capsys.readouterr().err
    assert end.value.code == 2 and words in error, error
    assert error.count("\n") == 1 and not out.exists()


def contract_rows() -> dict[str, list[str]]:
    """The surface these rows cover (read by the inventory test)."""
    return {"cli:reproduce --data": list(CASES)}
