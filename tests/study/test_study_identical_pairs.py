"""Two conditions that count as many right in every cluster (``PairedDifference.identical``)
are said to be alike, with no interval, verdict or detectable difference presented as a test
result, in the report's sentences and the documentation's tables alike."""

import sys
from pathlib import Path

import numpy as np
import pytest

from ebantenna.paper.uncertainty import ClusteredAccuracy, FoldAccuracy, PairedDifference
from ebantenna.study import ann_setup, contact_law, material_splits

N = np.full(16, 3)
SOME = np.array([3, 2] * 8)
ALIKE = PairedDifference(SOME, SOME, N, "position", resamples=200)
FLAT = PairedDifference(SOME, SOME[::-1], N, "position", resamples=200)

#: What a test result's wording would say: none of it belongs beside an identical pair.
VERDICT_WORDS = ("95 % CI", "detectable", "not resolved", "changes nothing this design")


def _says_alike(text: str, where: str) -> None:
    assert "as many" in where and "right" in where, text
    assert not any(w in where for w in VERDICT_WORDS), where


def test_the_fixtures_are_identical_and_not():
    assert ALIKE.identical and not FLAT.identical and not FLAT.resolved


def test_the_contact_law_says_alike_where_the_laws_classify_alike():
    r = contact_law.ContactLawResult("d", 1, {}, {}, {}, {}, 0.1,
                                     {"svm": FLAT, "mode_curves": ALIKE})
    text = contact_law._verdict(r)
    svm, curves = text.split("the mode-curve classifier", 1)
    assert "changes nothing this design resolves" in svm  # not identical: a test result
    _says_alike(text, curves)
    assert "16 positions" in curves and "no difference between the laws to resolve" in curves


def test_the_step_verdict_says_alike_where_the_steps_classify_alike():
    run = dict(stopped_by="epoch cap", epochs=1000, max_epochs=1000, lr=0.05,
               test=ClusteredAccuracy(SOME, N, "position"))
    runs = {"a": run, "b": {**run, "lr": 0.5}}
    text = ann_setup._verdict(ann_setup.AnnSetupResult(runs, 1, None, ALIKE))
    _says_alike(text, text.split("What ended each run")[1].split(". ", 1)[1])
    assert "not resolved" in ann_setup._verdict(ann_setup.AnnSetupResult(runs, 1, None, FLAT))


def _splits(pair):
    def folds(k):
        return FoldAccuracy([(np.arange(10) < k[i], np.full(10, i)) for i in range(5)],
                            "held-out block", by_fold=True)

    high = folds([6, 7, 6, 7, 6])
    return material_splits.MaterialSplitsResult(
        {"blocked": None}, {}, {}, {}, {}, {},
        {("svm", "blocked"): high, ("position_aware", "blocked"): high,
         ("mode_curves", "blocked"): high, ("svm", "grouped"): high,
         ("position_aware", "grouped"): high, ("mode_curves", "grouped"): high},
        {"blocked": {"position_aware": pair, "mode_curves": pair},
         "grouped": {"position_aware": pair, "mode_curves": pair}},
        flattery={"svm": pair})


def test_the_splits_sentences_say_alike_where_the_pairs_are_identical():
    r = _splits(ALIKE)
    for text in (material_splits._lift(r), material_splits._curves(r),
                 material_splits._flattery(r)):
        assert "as many" in text, text
        assert not any(w in text for w in ("95 % CI -0.0", "95 % CI 0.0 to 0.0", "detectable",
                                           "not resolved")), text
    flat = _splits(FLAT)
    assert "not resolved" in material_splits._lift(flat)
    assert "not resolved" in material_splits._flattery(flat)


@pytest.fixture
def study_tables():
    pytest.importorskip("sphinx")
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "docs" / "_ext"))
    import study_tables

    return study_tables


def _summary():
    alike, flat = ALIKE.to_dict(), FLAT.to_dict()
    alike["detectable_difference_80"] = 0.05  # whatever the design detects: not shown
    return {"materials": {"controls_paired": {"ablation:sensor_noise": alike,
                                              "ablation:gravity": flat}}}


def test_the_controls_table_says_alike_with_no_interval_or_detectable(study_tables):
    lines = study_tables.controls_lines(_summary())
    rows = "\n".join(lines).split("   * - ")[1:]
    noise = next(r for r in rows if r.startswith("switched off: sensor_noise"))
    gravity = next(r for r in rows if r.startswith("switched off: gravity"))
    assert "as many test recordings right under both in each of the 16 positions" in noise
    assert "nothing to resolve" in noise and "- no\n" not in noise and "5.0" not in noise
    assert "- no\n" in gravity  # the test result's verdict where there is one


def test_the_pair_role_says_alike_with_no_interval(study_tables):
    s = _summary()
    alike = study_tables.value_text(s, "materials.controls_paired.ablation:sensor_noise|pair")
    flat = study_tables.value_text(s, "materials.controls_paired.ablation:gravity|pair")
    assert "no difference to resolve" in alike and "CI" not in alike and "unchanged" not in alike
    assert "95 % CI" in flat and "not resolved" in flat


def test_the_rod_table_says_alike_where_a_rod_classifies_alike(study_tables):
    row = {"diameter_mm": 6.0, "free_length_mm": 200.0, "closest_materials": ["a", "b"],
           "second_mode_gap_hz": 1.0, "svm_against_scene_rod": ALIKE.to_dict(),
           "svm_grouped_accuracy": 0.5, "svm_grouped_accuracy_n_test": 48,
           "svm_grouped_accuracy_unit": "position", "svm_grouped_accuracy_n_units": 16,
           "svm_grouped_accuracy_ci95": [0.4, 0.6], "mode_curve_grouped_accuracy": 0.5,
           "mode_curve_grouped_accuracy_n_test": 48,
           "mode_curve_grouped_accuracy_unit": "position",
           "mode_curve_grouped_accuracy_n_units": 16,
           "mode_curve_grouped_accuracy_ci95": [0.4, 0.6]}
    text = "\n".join(study_tables.sensitivity_lines({"materials": {"rod_geometry": [row]}}))
    assert "as many test recordings right under both" in text and "resolved" not in text


# The long run stops at the first checkpoint whose test accuracy reaches the paper's: that
# accuracy is picked on the test rows, so no sentence or table gives it a test interval.

def _long(reached_at_end: bool):
    final = ClusteredAccuracy(np.array([3] * 13 + [2] * 3), N, "position")  # 93.8 %
    epochs = [50, 100, 150]
    test = [0.5, 0.7, 0.938] if reached_at_end else [0.5, 0.7, 0.75]
    return dict(epochs=epochs, test=test, all=test, reached_test=150 if reached_at_end else None,
                reached_all=None, final=final, stopped_by="x", max_epochs=150,
                test_ci95=[(0.4, 0.6), (0.6, 0.8), (0.88, 0.97)], within_from=None)


def test_the_long_runs_selected_accuracy_has_no_test_interval():
    text = ann_setup._long_verdict(ann_setup.AnnSetupResult({}, 1, _long(True)))
    assert "93.8 % after 150, the checkpoint the run stopped at" in text
    assert "95 % CI" not in text and "no test interval" in text
    assert "first reaches the paper's 80.8 % after 150 epochs, as a point value" in text
    assert "does not show that plain gradient descent reaches" in text  # only the picked one
    unpicked = ann_setup._long_verdict(ann_setup.AnnSetupResult({}, 1, _long(False)))
    assert "95 % CI" in unpicked and "no test interval" not in unpicked  # a cap is no choice


def _budget(reached):
    long = {"lr": 0.5, "max_epochs": 3000, "stopped_by": "x", "epochs": [50, 1400],
            "paper_value": 0.808, "reached_paper_test_epoch": reached, "test_accuracy": 0.831,
            "test_accuracy_n_test": 296, "test_accuracy_unit": "position",
            "test_accuracy_n_units": 78, "test_accuracy_ci95": [0.775, 0.876]}
    return {"materials": {"ann_training_setup": {"recordings": 1, "long_run": long}}}


def test_the_budget_table_gives_the_selected_accuracy_no_interval(study_tables):
    picked = "\n".join(study_tables.ann_budget_lines(_budget(1400)))
    assert "first reaches the paper's 80.8 % at epoch 1400" in picked
    assert "83.1 % there, picked on the test rows: no test interval" in picked
    assert "77.5" not in picked and "n = 296" not in picked
    capped = "\n".join(study_tables.ann_budget_lines(_budget(None)))
    assert "83.1 % (n = 296 in 78 positions, 77.5-87.6)" in capped


def test_the_papers_split_is_named_an_assumption():
    import inspect

    source = inspect.getsource(material_splits)
    assert "The paper's 80/20 split draws recordings at random" not in source
    assert "the study assumes they were drawn at random" in source
    assert "at random \"\n        \"is the study's assumption" in source


def test_the_docstring_does_not_say_the_first_mode_estimator_stops_at_80_percent():
    import importlib

    module = importlib.import_module("ebantenna.study.reproduce")
    assert "stops at 80 %" not in " ".join(module.__doc__.split())
