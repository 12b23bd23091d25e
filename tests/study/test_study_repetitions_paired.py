"""The repetitions per position compared in pairs: the most repetitions against the fewest, on
the recordings both test (every position's first repetitions), clustered on the position.

The witness recomputes the fewest repetitions' answers with its own loop over the grouped
folds, and the paired difference and its cluster-robust standard error by hand (Liang & Zeger
1986); the sentence's verdict is checked to flip with the paired interval.
"""

from __future__ import annotations

import numpy as np
import pytest

from ebantenna.paper import experiments
from ebantenna.paper.feature_table import signal_features
from ebantenna.paper.splits import split_folds
from ebantenna.paper.uncertainty import ClusteredAccuracy, FoldAccuracy, PairedDifference
from ebantenna.simulate import DatasetDesign, build_dataset, builtin_scene
from ebantenna.study import seed_spread

G = 16


def _pair(k_a, k_b):
    return PairedDifference(k_a, k_b, [3] * G, "position", resamples=200)


FEW, MANY = ClusteredAccuracy([1] * G, [3] * G, "position"), ClusteredAccuracy(
    [2] * G, [3] * G, "position")


@pytest.mark.parametrize("pair, words, matters", [
    (_pair([1] * G, [3] * G), "the change is a rise of +66.7 points", True),
    (_pair([3] * G, [1] * G), "the change is a fall of -66.7 points", True),
    (_pair([1, 2] * 8, [2, 1] * 8), "not resolved: it is either smaller", False),
    (_pair([1, 2] * 8, [1, 2] * 8), "every position counts as many right with either", False),
])
def test_the_verdict_follows_the_paired_interval_not_the_rows_intervals(pair, words, matters):
    # the two rows' intervals are the same here: only the paired difference decides
    text = seed_spread.repetitions_sentence({1: FEW, 25: MANY}, pair)
    assert words in text
    assert ("matters on whole held-out positions" in text) == matters
    assert "overlap is no test" not in text and "does not make one" not in text
    assert f"On the {pair.n_recordings} recordings both rows test (the first repetition" in text


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    """Two materials at seven positions, three repetitions (42 recordings), and the grouped SVM's
    answers over all its folds."""
    design = DatasetDesign("paired-reps", ("brass", "pvc"), 0.05, 0.05, 3)
    ds = build_dataset(tmp_path_factory.mktemp("reps"), builtin_scene("paper"), design, seed=2,
                       n_jobs=1, show_progress=False)
    feats = signal_features(ds.ax, ds.az, ds.fs, n_jobs=1, show_progress=False)
    folds = [experiments.classify_materials_svm(feats.fft, ds.material, split=s)
             for s in split_folds("grouped", ds.material, ds.contact, seed=0)]
    answers = np.zeros(ds.material.size, bool)
    for r in folds:
        answers[r.rows()] = r.correct()
    full = FoldAccuracy([(r.correct(), ds.contact[r.rows()]) for r in folds], "position")
    return ds, feats, full, answers


def test_the_pairs_are_the_first_repetitions_tested_in_both(small):
    ds, feats, full, answers = small
    result = seed_spread.compute(ds, feats, 0, full, grouped_answers=answers)
    p = result.paired_repetitions
    # the witness: the fewest repetitions' own folds, one answer per first-repetition recording
    sub = np.flatnonzero(ds.repetition < 1)
    few = np.full(sub.size, -1)
    for s in split_folds("grouped", ds.material[sub], ds.contact[sub], seed=0):
        r = experiments.classify_materials_svm(feats.fft[sub], ds.material[sub], split=s)
        few[r.rows()] = r.correct()
    assert np.all(few >= 0)  # every first repetition tested once
    d = answers[sub].astype(float) - few
    positions, inverse = np.unique(ds.contact[sub], return_inverse=True)
    g, n = positions.size, d.size
    d_j = np.bincount(inverse.ravel(), weights=d)
    n_j = np.bincount(inverse.ravel())
    se = np.sqrt(g / (g - 1) * np.sum((d_j - d.mean() * n_j) ** 2)) / n
    # sums of at most 14 terms of +-1: exact; the standard error's few operations, to 1e-12
    assert p.difference == d.mean() and p.n_recordings == n and p.n_units == g == 7
    assert p.se == pytest.approx(se, rel=1e-12, abs=1e-15)
    entry = result.to_dict()["svm_grouped_repetitions_paired"]
    assert (entry["fewest"], entry["most"]) == (1, 3) and entry["difference"] == p.difference


def test_answers_of_another_run_are_refused(small):
    ds, feats, full, answers = small
    other = answers.copy()
    other[0] = not other[0]
    with pytest.raises(ValueError, match="grouped_answers and grouped_full describe different"):
        seed_spread.compute(ds, feats, 0, full, grouped_answers=other)
    # without them, no pairing and the sentence says none was made
    result = seed_spread.compute(ds, feats, 0, full)
    assert result.paired_repetitions is None
    assert "svm_grouped_repetitions_paired" not in result.to_dict()
