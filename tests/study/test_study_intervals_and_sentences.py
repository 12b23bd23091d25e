"""Distance errors on their unit of replication (the test position), the trainers' ranking
paired on the same test recordings, and sentences of the report read from their numbers (the
confusions, the full-range comparisons, the controls' damping share and chance baseline)."""

import numpy as np
import pytest
from scipy import stats

from ebantenna.paper.experiments import RegressionResult, regress_distance_linear_region
from ebantenna.study._common import format_mae, mae_entry, paired_mae
from ebantenna.study.full_range import _known_material_verdict
from ebantenna.study.material_splits import MaterialSplitsResult, _trainer_ranking

POSITIONS = np.repeat([0.05, 0.10, 0.15, 0.20, 0.25], 4)  # 5 positions x 4 repetitions


def _t_interval(values, positions):
    """Witness: Student's t interval over the positions' means, written out."""
    means = np.array([values[positions == p].mean() for p in np.unique(positions)])
    half = stats.t.ppf(0.975, means.size - 1) * means.std(ddof=1) / np.sqrt(means.size)
    return means.mean(), (means.mean() - half, means.mean() + half)


def test_a_mae_is_taken_on_the_positions_not_the_recordings():
    errors = np.random.default_rng(0).gamma(2.0, 1.0, POSITIONS.size)
    entry = mae_entry(errors, POSITIONS)
    centre, ci = _t_interval(errors, POSITIONS)
    assert entry["mae_cm"] == pytest.approx(errors.mean(), rel=1e-14)
    assert entry["mae_cm_estimate"] == pytest.approx(centre, rel=1e-14)
    # the same few operations on 20 numbers: a few eps of the interval's scale
    assert np.allclose(entry["mae_cm_ci95"], ci, rtol=1e-12)
    assert (entry["mae_cm_n_units"], entry["mae_cm_n_test"]) == (5, 20)
    assert "5 test positions" in format_mae(entry)


def test_one_test_position_gives_no_interval():
    entry = mae_entry([1.0, 2.0, 3.0], [0.1, 0.1, 0.1])
    assert entry["mae_cm_ci95"] is None and entry["mae_cm"] == 2.0
    assert "no interval" in format_mae(entry)
    assert paired_mae([1.0, 2.0], [0.0, 0.0], [0.1, 0.1])["resolved"] is False


@pytest.mark.parametrize("shift", [1.0, -1.0, 0.0])
def test_a_paired_difference_is_the_interval_of_the_differences_and_resolves_by_it(shift):
    rng = np.random.default_rng(1)
    base = rng.gamma(2.0, 1.0, POSITIONS.size)
    other = base + shift + rng.normal(0.0, 0.05, POSITIONS.size)
    d = paired_mae(other, base, POSITIONS)
    centre, ci = _t_interval(other - base, POSITIONS)
    assert d["difference_cm"] == pytest.approx(centre, abs=1e-12)
    assert np.allclose(d["ci95"], ci, rtol=0, atol=1e-12)
    assert d["resolved"] is (not ci[0] <= 0 <= ci[1])
    assert d["resolved"] is (shift != 0.0)  # a 1 cm shift against 0.05 cm noise resolves


def test_unpaired_errors_are_refused():
    with pytest.raises(ValueError, match="errors_a and errors_b"):
        paired_mae([1.0, 2.0], [1.0], [0.1, 0.2])


def _net(errors, rows):
    truth = POSITIONS[rows]
    return RegressionResult("net", truth, truth + np.asarray(errors) / 100.0, np.unique(truth),
                            np.zeros(np.unique(truth).size), 0.0, None, np.asarray(rows))


def test_the_ranking_pairs_networks_tested_on_the_same_rows_only():
    rng = np.random.default_rng(2)
    rows = np.arange(POSITIONS.size)
    base = rng.gamma(2.0, 0.2, rows.size)
    tie = np.repeat([0.1, -0.1, 0.05, -0.05, 0.001], 4)  # positions' means: +0.0002 cm
    distance = {"gd": _net(base + 1.0, rows), "scg": _net(base + tie, rows),
                "adam": _net(base, rows), "sgd": _net(base, rows[::-1])}
    result = MaterialSplitsResult({}, {}, {}, {}, {}, distance)
    smallest, against = result.distance_ranking
    assert smallest == "adam"
    assert against["gd"]["resolved"] and against["gd"]["difference_cm"] == pytest.approx(1.0)
    assert against["sgd"] is None  # other test rows: not compared
    assert not against["scg"]["resolved"]
    text = _trainer_ranking(smallest, against)
    assert "errs less than gradient descent (resolved)" in text
    assert "does not tell it apart from scaled conjugate gradient" in text
    assert "Stochastic gradient descent: tested on other rows" in text


def test_the_ranking_sentence_flips_with_the_interval():
    near = {"difference_cm": 0.01, "ci95": [-0.02, 0.04], "n_units": 64, "resolved": False}
    far = {"difference_cm": 1.9, "ci95": [1.6, 2.2], "n_units": 64, "resolved": True}
    assert "does not rank" in _trainer_ranking("adam", {"scg": near})
    assert "does not rank" not in _trainer_ranking("adam", {"scg": far})
    alone = _trainer_ranking("adam", {"scg": near, "gd": near})
    assert "(resolved)" not in alone
    assert "this design does not tell it apart from scaled conjugate gradient and gradient" in alone


def test_the_known_material_sentence_follows_the_paired_difference():
    gain = {"difference_cm": 2.3, "ci95": [1.9, 2.7], "n_units": 39, "resolved": True}
    assert "must know what it touched" in _known_material_verdict(gain)
    unresolved = dict(gain, ci95=[-0.1, 0.4], resolved=False)
    assert "does not show" in _known_material_verdict(unresolved)
    worse = dict(gain, difference_cm=-2.3, ci95=[-2.7, -1.9])
    assert "worse" in _known_material_verdict(worse)
    assert "must know" not in _known_material_verdict(worse)


def test_the_tested_rows_are_numbered_among_the_rows_given():
    d = np.repeat(np.linspace(0.02, 0.40, 20), 6)  # the region keeps the first 80 % of 0.4 m
    X = np.column_stack([np.cos(8 * d), np.sin(8 * d)])
    res = regress_distance_linear_region(X, d, probe_length=0.4, max_iter=5)
    assert np.array_equal(d[res.test_rows], res.distance_test)
    assert np.all(d[res.test_rows] <= 0.8 * 0.4)


def test_the_confusion_sentence_is_read_from_the_matrix():
    from ebantenna.study.material_splits import _confusions_text

    labels = ["al", "pvc", "wood"]
    one = _confusions_text(np.array([[5, 3, 0], [0, 8, 0], [1, 0, 7]]), labels)
    other = _confusions_text(np.array([[5, 0, 3], [2, 6, 0], [0, 0, 8]]), labels)
    assert "al taken for pvc (3 of 8)" in one and "al taken for wood (3 of 8)" in other
    assert "pvc is never taken" in one and "wood is never taken" in other
    assert "no material for another" in _confusions_text(np.eye(3, dtype=int) * 4, labels)


def test_the_two_estimators_are_compared_only_on_the_same_recordings():
    from ebantenna.paper.uncertainty import ClusteredAccuracy
    from ebantenna.study.full_range import FullRangeResult, _joint_text, _two_against_one_text

    rng = np.random.default_rng(3)
    one = rng.gamma(2.0, 1.0, POSITIONS.size)
    joint = ClusteredAccuracy([4, 4, 4, 4, 4], [4] * 5, "position")

    def result(two, without=0, chance=0.2):
        return FullRangeResult(0.4, 0.8, POSITIONS, two, POSITIONS, one, one, one, 1.0, 0.395,
                               without, POSITIONS.size, joint, chance)

    worse = result(one + 1.0).two_against_one_mode
    assert worse["resolved"] and "more than the first mode alone" in _two_against_one_text(worse)
    better = result(one - 1.0).two_against_one_mode
    assert "less than the first mode alone" in _two_against_one_text(better)
    assert result(one, without=2).two_against_one_mode is None
    assert "not compared" in _two_against_one_text(None)
    assert "find the material too" in _joint_text(result(one))
    assert "reaches chance" in _joint_text(result(one, chance=0.99))


def _spread(correct_share, seed):
    """A SeedSpread over 2 folds of 16 positions x 3 repetitions, right in ``correct_share`` of
    the rows of each position (which rows, drawn with ``seed``)."""
    from ebantenna.paper.uncertainty import SeedSpread

    rng = np.random.default_rng(seed)
    positions = np.repeat(np.arange(16) / 40.0, 3)
    right = rng.random(positions.size) < correct_share
    folds = [np.arange(0, 48, 2), np.arange(1, 48, 2)]
    spread = SeedSpread([0, 1], [right[f].mean() for f in folds], [24, 24],
                        tested=[(f, right[f]) for f in folds])
    spread.positions = positions
    return spread


def test_the_damping_share_of_a_bundled_row_is_read_against_its_partner_alone():
    from ebantenna.study.physics_controls import verdict_from

    base = _spread(0.95, 0)
    contact_off = _spread(0.95, 1)
    spreads = {"none": base, "object_modes": _spread(0.05, 2), "unilateral_contact": contact_off}
    paired = {k: base.paired_with(v) for k, v in spreads.items() if k != "none"}
    for share, word in ((0.05, "lowers it too"), (0.95, "not resolved")):
        bundle = _spread(share, 3)
        spreads["object_damping+unilateral_contact"] = bundle
        paired["object_damping+unilateral_contact"] = base.paired_with(bundle)
        text = verdict_from(paired, base.folds(), 0.2, spreads)
        assert "Against 'unilateral_contact' switched off alone" in text
        assert word in text.split("switched off alone")[1]
    del spreads["unilateral_contact"], paired["unilateral_contact"]
    text = verdict_from(paired, base.folds(), 0.2, spreads)
    assert "own share is not separated" in text


def test_a_baseline_at_chance_shows_no_carrier():
    from ebantenna.study.physics_controls import verdict_from

    base = _spread(0.2, 0)
    drop = base.paired_with(_spread(0.0, 1))
    text = verdict_from({"object_modes": drop}, base.folds(), 0.2)
    assert "cannot show what carries the material" in text and "costs the most" not in text


def _splits_result(random_k, grouped_k, pair_direction_k):
    """A MaterialSplitsResult whose three classifiers score ``random_k`` / ``grouped_k`` right of
    5 per position on 16 positions, with the position-aware classifier against the SVM on the
    grouped split paired from ``pair_direction_k`` (its own counts against the SVM's)."""
    from ebantenna.paper.uncertainty import ClusteredAccuracy, PairedDifference

    n = [5] * 16
    measured = {}
    for c in ("svm", "position_aware", "mode_curves"):
        measured[c, "random"] = ClusteredAccuracy(random_k, n, "position")
        measured[c, "grouped"] = ClusteredAccuracy(grouped_k, n, "position")
    paired = {"grouped": {"position_aware": PairedDifference(grouped_k, pair_direction_k, n,
                                                             "position", resamples=200)}}
    # the random split against the grouped one, paired on the same recordings
    flattery = {c: PairedDifference(grouped_k, random_k, n, "position", resamples=200)
                for c in ("svm", "position_aware", "mode_curves")}
    return MaterialSplitsResult({}, {}, {}, {}, {}, {}, measured, paired, flattery=flattery)


def test_the_random_split_flatters_only_where_the_paired_difference_shows_it():
    from ebantenna.study.material_splits import _flattery, _grouped_lift

    high, low = [5] * 8 + [4] * 8, [3, 2] * 8
    assert "flatters them here" in _flattery(_splits_result(high, low, low))
    # every position counts as many right under both: no difference, so no verdict on it
    alike = _flattery(_splits_result(high, high, high))
    assert "there is no difference to resolve" in alike and "not resolved" not in alike
    flipped = _flattery(_splits_result(low, high, low))  # the direction flips, the words too
    assert "scores lower than whole positions held out for" in flipped
    assert "flatters" not in flipped.replace("does not show the random split flattering", "")
    worse = _grouped_lift(_splits_result(high, high, [2] * 16))
    assert "lower than the raw spectrum, resolved" in worse
    assert "higher than the raw spectrum" in _grouped_lift(_splits_result(high, low, [5] * 16))
    assert "the two classify alike" in _grouped_lift(_splits_result(high, high, high))


def test_the_random_split_is_paired_with_the_folds_that_test_its_recordings_again():
    # every random-split test recording is tested once more by the grouped fold that holds its
    # position out: the paired difference is the mean, over those recordings, of (random right)
    # minus (held-out right), clustered on the position
    from ebantenna.paper.experiments import ClassificationResult, RegressionResult
    from ebantenna.study.material_splits import (
        answers_over_folds,
        held_out_against_random,
        random_against_grouped,
    )

    rng = np.random.default_rng(3)
    positions = np.repeat(np.arange(12) * 0.01, 4)
    right_held = rng.random(positions.size) < 0.6
    folds = [np.flatnonzero(np.isin(positions, np.unique(positions)[f::3])) for f in range(3)]
    grouped = [ClassificationResult("svm", ("a",), {}, 0.0, None,
                                    {"test": (rows, right_held[rows])}) for rows in folds]
    rows = np.sort(rng.choice(positions.size, 12, replace=False))
    right_random = rng.random(12) < 0.9
    random = ClassificationResult("svm", ("a",), {}, 0.0, None, {"test": (rows, right_random)})
    answers = answers_over_folds(grouped, positions.size)
    assert np.array_equal(answers, right_held)  # each recording's answer in its own fold
    p = random_against_grouped(random, answers, positions)
    assert p.difference == pytest.approx(np.mean(right_random.astype(float) - right_held[rows]),
                                         abs=1e-15)
    assert p.n_units == np.unique(positions[rows]).size
    # folds that leave recordings untested, or test one twice, give no answer to pair with
    with pytest.raises(ValueError, match="16 recordings never and 0 more than once"):
        answers_over_folds(grouped[:2], positions.size)
    with pytest.raises(ValueError, match="0 recordings never and 16 more than once"):
        answers_over_folds(grouped + grouped[:1], positions.size)
    # the distance network likewise, on errors (cm), from each result's own test rows
    truth = positions
    held = RegressionResult("held", truth, truth + 0.02, np.unique(truth), np.zeros(12), 0.0,
                            test_rows=np.arange(truth.size))
    rnd = RegressionResult("rnd", truth[rows], truth[rows] + 0.005, np.unique(truth[rows]),
                           np.zeros(1), 0.0, test_rows=rows)
    d = held_out_against_random(rnd, held)
    assert d["difference_cm"] == pytest.approx(1.5) and d["n_units"] == np.unique(truth[rows]).size
