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

