"""The study on recorded data checks its design before any work (ebantenna.study.recorded.study):
each section's minimum, one message with what is missing and what still runs, and a data set too
small for every section refused before the features are computed."""

from __future__ import annotations

import pytest

from ebantenna.device.plan import Plan
from ebantenna.device.recording_session import RecordingSession
from ebantenna.device.simulated.touches import simulated_connect
from ebantenna.simulate import builtin_scene, simulate
from ebantenna.study.recorded import (
    MIN_SAMPLES,
    SECTION_MINIMUM,
    assemble_dataset,
    reproduce_recorded,
)
from ebantenna.study.recorded.study import check_design, design_message


def design(materials, positions, repetitions, in_region=None, samples=MIN_SAMPLES):
    return {"materials": materials, "positions": positions, "repetitions": repetitions,
            "in_region": materials * positions * repetitions if in_region is None else in_region,
            "spacing": 0.05, "samples": samples}


def test_a_section_the_data_do_not_allow_is_listed_and_the_others_go_on(tmp_path, monkeypatch):
    # a requirement only the data can show (here: the full-range calibration refuses them)
    from ebantenna.study import full_range

    def refuse(ds, feats):
        raise ValueError("frequencies do not change monotonically with distance")

    monkeypatch.setattr(full_range, "compute", refuse)
    plan = Plan("five", ("brass", "pvc"), (0.05, 0.1, 0.15, 0.2, 0.25), 1)
    RecordingSession(tmp_path / "s", plan, simulated_connect(builtin_scene("paper"), simulate),
                     show_progress=False).run()
    data = assemble_dataset(tmp_path / "s", tmp_path)
    heard = []
    summary = reproduce_recorded(data.path, tmp_path / "report", n_jobs=1, show_progress=False,
                                 say=heard.append)
    assert summary["not_applicable"]["full range"].startswith("did not run on this data set")
    assert "frequency" in summary and "full range: did not run" in " ".join(heard)
    report = (tmp_path / "report" / "report.md").read_text()
    assert "Sections the data themselves did not allow" in report


def test_the_quick_protocol_runs_every_section():
    runnable, missing = check_design(design(5, 8, 3, in_region=105))
    assert runnable == list(SECTION_MINIMUM) and not missing


def test_the_guides_example_plan_runs_what_it_can():
    runnable, missing = check_design(design(2, 3, 3))
    assert runnable == ["frequency", "decay", "ml"]
    assert set(missing) == {"splits", "full range"}
    assert "5 positions (has 3)" in missing["splits"]


def test_one_material_leaves_out_the_classifiers_and_what_reuses_them():
    runnable, missing = check_design(design(1, 8, 3))
    assert "ml" not in runnable and "splits" not in runnable
    assert "2 materials (has 1)" in missing["ml"]
    assert "the 'ml' section's results" in missing["splits"]
    message = design_message(design(1, 8, 3), runnable, missing)
    assert message.endswith("sections that run: frequency, decay")


def test_each_minimum_is_a_boundary():
    # one below any minimum removes the section; the minimum itself keeps it
    for section, need in SECTION_MINIMUM.items():
        at = design(need["materials"], need["positions"], need["repetitions"],
                    in_region=need.get("in_region", 0))
        if "after" not in need:
            assert section in check_design(at)[0], section
        for key in ("materials", "positions", "repetitions", "in_region", "samples"):
            if key in need or key == "samples":  # every section needs the features' records
                below = {**at, key: need.get(key, MIN_SAMPLES) - 1}
                assert section in check_design(below)[1], (section, key)


def test_a_data_set_too_small_for_every_section_is_refused_before_any_work(tmp_path):
    plan = Plan("one", ("brass",), (0.35,), 1)  # one position, beyond 0.8 L
    RecordingSession(tmp_path / "s", plan, simulated_connect(builtin_scene("ideal"), simulate),
                     show_progress=False).run()
    data = assemble_dataset(tmp_path / "s", tmp_path)
    heard = []
    with pytest.raises(ValueError, match="too small for any section") as error:
        reproduce_recorded(data.path, tmp_path / "report", say=heard.append)
    assert "frequency: needs at least 2 positions (has 1)" in str(error.value)
    assert "decay: needs at least 1 in region (has 0)" in str(error.value)
    assert not heard and not (tmp_path / "report").exists()  # no work started


def test_records_too_short_for_the_features_are_refused_by_the_option_that_named_them(
        tmp_path, capsys):
    # a data set file written by other means (here by hand, in the format load_dataset reads),
    # with a design every section accepts but records of 100 samples: shorter than one spectrum
    import json

    import numpy as np

    from ebantenna.cli import main
    from ebantenna.simulate.dataset import FORMAT, _checksum

    materials, positions, repetitions = ("brass", "pvc"), np.linspace(0.05, 0.25, 5), 2
    rows = [(m, c, r) for m in materials for c in positions for r in range(repetitions)]
    n, fs = len(rows), 1000.0
    rng = np.random.default_rng(0)
    arrays = {"ax": rng.normal(size=(n, 100)).astype(np.float32),
              "az": rng.normal(size=(n, 100)).astype(np.float32),
              "material": np.array([m for m, _, _ in rows]),
              "contact": np.array([c for _, c, _ in rows]),
              "contact_true": np.array([c for _, c, _ in rows]),
              "repetition": np.array([r for _, _, r in rows], dtype=np.int64),
              "sweep_speed": np.full(n, np.nan), "tilt_ratio": np.full(n, np.nan),
              "seed_row": np.full(n, -1, dtype=np.int64)}
    meta = {"config": {"format": FORMAT, "scene": {"probe": {"length": 0.4}}},
            "checksum_sha256": _checksum(arrays, fs)}
    path = tmp_path / "short.npz"
    np.savez(path, fs=np.float64(fs), metadata=np.array(json.dumps(meta)), **arrays)
    out = tmp_path / "report"
    with pytest.raises(SystemExit) as end:
        main(["reproduce", "--data", str(path), "--out", str(out), "--jobs", "1"])
    error = capsys.readouterr().err
    assert end.value.code == 2 and "too small for any section" in error
    assert f"records of {MIN_SAMPLES} samples at least (has 100)" in error
    assert not out.exists()  # refused before any work
    with pytest.raises(SystemExit) as end:
        main(["reproduce", "--data", "", "--out", str(out)])
    assert end.value.code == 2 and "--data must name a file" in capsys.readouterr().err
