"""The report section comparing the contact's Hertz law with its linearisation."""

import json

import pytest

from ebantenna.ml.metrics import accuracy_interval
from ebantenna.report import FigureSet, Report
from ebantenna.simulate import Scene, builtin_scene
from ebantenna.study import contact_law
from ebantenna.study.contact_law import Accuracy, ContactLawResult


def _result(hertz_svm=(30, 80)):
    return ContactLawResult(
        design="controls-test",
        recordings=395,
        svm={"linearised": Accuracy(52, 80), "hertz": Accuracy(*hertz_svm)},
        mode_curves={"linearised": Accuracy(70, 80), "hertz": Accuracy(68, 80)},
        restrikes={"linearised": 19.0, "hertz": 15.0},
        chords={"steel": (10, 0.00999), "wood": (13, 0.00999)},
        force_tolerance=0.01,
    )


def test_each_accuracy_carries_its_count_and_wilson_interval():
    acc = Accuracy(52, 80)
    assert acc.value == 52 / 80
    assert acc.interval == accuracy_interval(52, 80)
    d = acc.to_dict()
    assert d["accuracy_n_test"] == 80
    assert d["accuracy_ci95"] == list(accuracy_interval(52, 80))
    assert "n = 80" in acc.text()


def test_the_result_is_json_ready_and_names_both_laws():
    d = json.loads(json.dumps(_result().to_dict()))
    assert set(d["svm_grouped"]) == set(contact_law.LAWS) == set(d["mode_curve_grouped"])
    assert d["hertz_chords"]["wood"]["chords"] == 13


@pytest.mark.parametrize(("hertz_svm", "word"), [((50, 80), "overlap"), ((10, 80), "do not")])
def test_the_verdict_follows_the_intervals(tmp_path, hertz_svm, word):
    # 52/80 against 50/80 overlap; against 10/80 the intervals are disjoint
    report = Report("t")
    contact_law.render(_result(hertz_svm), report, FigureSet(tmp_path))
    text = report.markdown()
    assert "95 % CI" in text and "n = 80" in text
    assert f"For the SVM the two laws' intervals {word}" in text


def test_the_two_scenes_differ_by_the_hertz_law_only():
    scenes = contact_law._scenes(builtin_scene("paper"))
    lin, hz = scenes["linearised"], scenes["hertz"]
    assert lin is not None and lin.has("unilateral_contact") and not lin.has("hertz_contact")
    assert hz.has("hertz_contact")
    assert {e.name for e in hz.effects} - {e.name for e in lin.effects} == {"hertz_contact"}


def test_without_a_rod_there_is_nothing_to_compare(tmp_path):
    assert contact_law.compute(Scene(), 0, True, tmp_path, 1) is None
    report = Report("t")
    contact_law.render(None, report, FigureSet(tmp_path))
    assert "Hertz" not in report.markdown()
