"""``ebantenna calibrate``: every input it cannot calibrate from ends in exit code 2 and one line
naming the flag, the file or what is missing, before any fitting and with nothing written.

Records too short for the mode the model fits are refused with their length and the least the
calibration needs (:data:`~ebantenna.study.recorded.calibration.READ_PERIODS` periods of the
fitted mode at 3 positions, at the highest frequency the search allows), not with "0 of 10
positions show the mode".
"""

from __future__ import annotations

import math
import os

import pytest
from test_cli_data_option import _data_set

from ebantenna.cli import main
from ebantenna.simulate import builtin_scene
from ebantenna.study.recorded import calibration


def _needed() -> int:
    """The least record length the paper scene's calibration takes from :func:`_data_set`'s
    positions (brass and pvc, 5 to 25 cm), computed here from the model as the check does."""
    scene = builtin_scene("paper")
    contact = [c for m in ("brass", "pvc") for c in (0.05, 0.10, 0.15, 0.20, 0.25)]
    material = [m for m in ("brass", "pvc") for _ in range(5)]
    import numpy as np

    model = calibration._Model(scene, np.array(contact), np.array(material), 1000.0, 1)
    bounds = calibration._search_bounds(scene.probe, None, None)
    frequency = model.modes(bounds[1][0], bounds[0][1], 0.03)[0]
    need = sorted(math.ceil(calibration.READ_PERIODS * 1000.0 / f) + 3 for f in frequency
                  if np.isfinite(f))
    return need[2]


#: ``case -> (argv after "calibrate", made in tmp_path; words the error must hold)``
CASES = {
    "records-too-short": (lambda tmp: ["--data", _data_set(tmp / "s.npz", samples=100),
                                       "--out", str(tmp / "o")],
                          ["records of 100 samples", "needs", "samples at least"]),
    "records-one-short": (lambda tmp: ["--data", _data_set(tmp / "s.npz", samples=_needed() - 1),
                                       "--out", str(tmp / "o")],
                          [f"records of {_needed() - 1} samples", f"needs {_needed()} samples"]),
    "data-missing": (lambda tmp: ["--data", str(tmp / "none.npz"), "--out", str(tmp / "o")],
                     ["none.npz"]),
    "data-empty": (lambda tmp: ["--data", "", "--out", str(tmp / "o")], ["--data"]),
    "data-a-folder": (lambda tmp: ["--data", str(tmp), "--out", str(tmp / "o")],
                      ["is a directory"]),
    "data-not-npz": (lambda tmp: (tmp / "x.npz").write_text("hi") and [
        "--data", str(tmp / "x.npz"), "--out", str(tmp / "o")], ["is not an ebantenna data set"]),
    "scene-unknown": (lambda tmp: ["--data", _data_set(tmp / "s.npz"), "--scene", "nope",
                                   "--out", str(tmp / "o")], ["scene", "nope"]),
    # a scene's name becomes the calibrated scene's file name: it may not lead out of --out
    "scene-name-a-path": (lambda tmp: [
        "--data", _data_set(tmp / "s.npz"), "--scene", str(builtin_scene("paper").with_(
            name="x/../../escaped").save(tmp / "named.toml")), "--out", str(tmp / "o")],
        ["--out", "not a plain file name"]),
    "out-empty": (lambda tmp: ["--data", _data_set(tmp / "s.npz"), "--out", ""], ["--out"]),
    "out-a-file": (lambda tmp: ["--data", _data_set(tmp / "s.npz"), "--out",
                                str(tmp / "s.npz")], ["--out"]),
    # a folder where the summary goes is found before the fitting, not after it
    "out-a-directory-where-calibration.json-goes": (
        lambda tmp: (tmp / "o" / "calibration.json").mkdir(parents=True) or [
            "--data", _data_set(tmp / "s.npz"), "--out", str(tmp / "o")],
        ["--out", "calibration.json", "is a directory"]),
    "out-json-short": (lambda tmp: ["--data", _data_set(tmp / "s.npz", samples=64), "--json",
                                    "--out", str(tmp / "o")], ["records of 64 samples"]),
}


@pytest.mark.parametrize("case", CASES)
def test_calibrate_refuses_before_any_work(tmp_path, monkeypatch, capsys, case):
    monkeypatch.chdir(tmp_path)
    make, words = CASES[case]
    argv = ["calibrate", *make(tmp_path)]
    before = sorted(os.listdir(tmp_path))
    with pytest.raises(SystemExit) as end:
        main(argv)
    captured = capsys.readouterr()
    assert end.value.code == 2, captured.err
    assert captured.err.count("\n") == 1 and "Traceback" not in captured.err, captured.err
    for word in words:
        assert word in captured.err, (word, captured.err)
    assert sorted(os.listdir(tmp_path)) == before and captured.out == ""  # nothing written


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    return {"cli:calibrate": list(CASES),
            "cli:calibrate --data": [c for c in CASES if c.startswith(("records", "data"))],
            "cli:calibrate --scene": ["scene-unknown", "scene-name-a-path"],
            "cli:calibrate --out": ["out-empty", "out-a-file",
                                    "out-a-directory-where-calibration.json-goes"],
            "cli:calibrate --json": ["out-json-short"],
            "ebantenna.study.recorded.calibration.calibrate": ["records-too-short",
                                                               "records-one-short"]}
