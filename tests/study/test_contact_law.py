"""The report section comparing the contact's Hertz law with its linearisation."""

import json

import numpy as np
import pytest

from ebantenna.paper.uncertainty import SeedSpread
from ebantenna.report import FigureSet, Report
from ebantenna.simulate import Scene, builtin_scene
from ebantenna.study import contact_law
from ebantenna.study.contact_law import ContactLawResult

#: Twelve rows at six positions (two repetitions each), tested in two folds of three positions.
POSITIONS = np.repeat([0.05, 0.10, 0.15, 0.20, 0.25, 0.30], 2)
FOLDS = (np.arange(6), np.arange(6, 12))


def _spread(correct) -> SeedSpread:
    """A classifier's grouped accuracy over the two folds, each row's result kept."""
    correct = np.asarray(correct, bool)
    tested = [(rows, correct[rows]) for rows in FOLDS]
    spread = SeedSpread([0, 1], [c.mean() for _, c in tested], [6, 6], tested)
    spread.positions = POSITIONS
    return spread


BASE = [1, 1, 0, 1, 1, 0, 1, 1, 1, 0, 1, 1]
SAME = [1, 0, 1, 1, 0, 1, 1, 1, 0, 1, 1, 1]  # as many right, at other rows
WORSE = [0] * 12


def _result(hertz_svm):
    svm = {"linearised": _spread(BASE), "hertz": _spread(hertz_svm)}
    curves = {"linearised": _spread(BASE), "hertz": _spread(BASE)}
    paired = {"svm": svm["linearised"].paired_with(svm["hertz"]),
              "mode_curves": curves["linearised"].paired_with(curves["hertz"])}
    return ContactLawResult(design="controls-test", recordings=12, svm=svm, mode_curves=curves,
                            restrikes={"linearised": 19.0, "hertz": 15.0},
                            chords={"steel": (10, 0.00999), "wood": (13, 0.00999)},
                            force_tolerance=0.01, paired=paired)


def test_the_result_is_json_ready_and_names_both_laws():
    d = json.loads(json.dumps(_result(SAME).to_dict()))
    assert set(d["svm_grouped"]) == set(contact_law.LAWS) == set(d["mode_curve_grouped"])
    assert d["hertz_chords"]["wood"]["chords"] == 13
    assert set(d["hertz_against_linearised"]) == {"svm", "mode_curves"}
    # each accuracy on its unit: 9 of 12 rows right, at 6 positions
    entry = d["svm_grouped"]["linearised"]
    assert entry["accuracy"] == pytest.approx(9 / 12)
    assert entry["accuracy_n_units"] == 6


@pytest.mark.parametrize(("hertz_svm", "words"), [
    (SAME, "changes nothing this design resolves"),  # the same count: no difference at all
    (WORSE, "lowers the accuracy"),  # every row wrong under the Hertz law: resolved, down
])
def test_the_verdict_follows_the_paired_difference(tmp_path, hertz_svm, words):
    report = Report("t")
    contact_law.render(_result(hertz_svm), report, FigureSet(tmp_path))
    text = report.markdown()
    svm_clause = text.split("For the SVM the Hertz law ")[1].split("; for the mode-curve")[0]
    assert words in svm_clause
    # the mode-curve classifier is the same under both laws here: said alike, with no interval
    assert ("the mode-curve classifier classifies as many test recordings right under both laws"
            in text)


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
