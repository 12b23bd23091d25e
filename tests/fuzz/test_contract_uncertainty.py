"""The input contract of the accuracy intervals, the intervals on clusters, the paired
differences, the folds of a split and the way every number is printed.

Each bad row gives one bad input, refused with a ValueError or TypeError naming the parameter
(never a silently truncated count, a NaN carried into a result, an OverflowError or an
IndexError). Each good row checks a result against a witness the surface does not compute: a
case worked by hand (a design effect, a Wilson interval, a bootstrap distribution enumerated,
a paired difference and its cluster-robust standard error), or the definition itself.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import norm
from scipy.stats import t as student_t

from ebantenna.ml.metrics import accuracy, accuracy_interval
from ebantenna.paper.controls import twin_seeds
from ebantenna.paper.experiments import ClassificationResult
from ebantenna.paper.splits import split_folds
from ebantenna.paper.uncertainty import (
    ClusteredAccuracy,
    FoldAccuracy,
    PairedDifference,
    SeedSpread,
    cluster_bootstrap,
    cluster_counts,
    cluster_labels,
    cluster_mean_interval,
    clustered_entries,
    design_effect,
    detectable_cell,
    detectable_text,
    format_clustered,
    format_difference,
    minimal_detectable_difference,
    percent,
    points,
    span,
    training_entries,
)

NAN = float("nan")
HUGE = 10**400


def _spread(correct=((True, False, True), (True, True, False))):
    """Two seeds whose test sets are the folds of six rows at three positions."""
    tested = [(np.array([0, 1, 2]), np.array(correct[0])),
              (np.array([3, 4, 5]), np.array(correct[1]))]
    s = SeedSpread([0, 1], [np.mean(c) for c in correct], [3, 3], tested)
    s.positions = np.array([0.1, 0.1, 0.2, 0.2, 0.3, 0.3])
    return s


SPREAD = _spread()
RESULT = ClassificationResult("svm", ("al", "pvc"), {"test": np.eye(2)}, 0.0,
                              tested={"test": (np.array([4, 7]), np.array([True, False]))})
ACC = ClusteredAccuracy([2, 1], [2, 2], "position")
FOLDS = FoldAccuracy([(np.array([1, 0], bool), np.array([0, 0])),
                      (np.array([1, 1], bool), np.array([1, 1]))], "position")
PAIR = PairedDifference([3, 3, 2, 3], [2, 1, 1, 2], [3] * 4, "position", resamples=400)
GOOD_FOLD = (np.array([1, 0], bool), np.array([0, 0]))

BAD = [  # (id, call, error, name)
    ("interval-fraction", lambda: accuracy_interval(3.7, 10), ValueError, "correct"),
    ("interval-n-fraction", lambda: accuracy_interval(3, 10.5), ValueError, "n"),
    ("interval-n-huge", lambda: accuracy_interval(3, HUGE), ValueError, "n"),
    ("interval-nan", lambda: accuracy_interval(NAN, 10), ValueError, "correct"),
    ("interval-bool", lambda: accuracy_interval(True, 3), TypeError, "correct"),
    ("interval-text", lambda: accuracy_interval("3", 10), TypeError, "correct"),
    ("interval-above-n", lambda: accuracy_interval(4, 3), ValueError, "correct"),
    ("accuracy-zeros", lambda: accuracy(np.zeros((3, 3))), ValueError, "matrix"),
    ("accuracy-empty", lambda: accuracy(np.array([])), ValueError, "matrix"),
    ("accuracy-not-square", lambda: accuracy(np.ones((2, 3))), ValueError, "matrix"),
    ("accuracy-nan", lambda: accuracy(np.array([[NAN, 1], [0, 1]])), ValueError, "matrix"),
    ("accuracy-negative", lambda: accuracy(np.array([[-1, 2], [0, 1]])), ValueError, "matrix"),
    # design effect and the counts of every cluster
    ("deff-empty", lambda: design_effect([], []), ValueError, "k and n"),
    ("deff-fraction", lambda: design_effect([1.5, 2], [3, 3]), ValueError, "k"),
    ("deff-k-above-n", lambda: design_effect([4, 2], [3, 3]), ValueError, "k_j"),
    ("deff-empty-cluster", lambda: design_effect([0, 0], [0, 3]), ValueError, "n_j"),
    ("deff-negative", lambda: design_effect([1, 1], [-2, 3]), ValueError, "n_j"),
    ("deff-nan", lambda: design_effect([NAN, 1], [3, 3]), ValueError, "k"),
    ("deff-huge-int", lambda: design_effect([HUGE], [HUGE]), ValueError, "k"),
    ("deff-huge-float", lambda: design_effect([1e300, 1], [1e300, 3]), ValueError, "k"),
    ("deff-mismatched", lambda: design_effect([1, 2], [3]), ValueError, "k and n"),
    ("deff-text", lambda: design_effect(["1", "2"], [3, 3]), ValueError, "k"),
    ("clustered-unit-empty", lambda: ClusteredAccuracy([1, 2], [3, 3], ""), TypeError, "unit"),
    ("clustered-mismatched", lambda: ClusteredAccuracy([1, 2], [3], "position"), ValueError,
     "k and n"),
    ("clustered-from-half", lambda: ClusteredAccuracy.from_recordings([0.5, 1], [0, 1], "p"),
     ValueError, "correct"),
    ("clustered-from-unit", lambda: ClusteredAccuracy.from_recordings([1, 0], [0, 1], None),
     TypeError, "unit"),
    ("clustered-from-nan-cluster", lambda: ClusteredAccuracy.from_recordings(
        [1, 0], [0.1, NAN], "position"), ValueError, "clusters"),
    ("entries-name-int", lambda: ACC.entries(3), TypeError, "name"),
    ("entries-name-empty", lambda: ACC.entries(""), TypeError, "name"),
    ("counts-empty", lambda: cluster_counts([], []), ValueError, "correct"),
    ("counts-not-bool", lambda: cluster_counts([1, 2], [0, 1]), ValueError, "correct"),
    ("counts-nan", lambda: cluster_counts([NAN, 1], [0, 1]), ValueError, "correct"),
    ("counts-mismatched", lambda: cluster_counts([1, 0], [0]), ValueError, "clusters"),
    ("counts-nan-cluster", lambda: cluster_counts([1, 0], [NAN, 1.0]), ValueError, "clusters"),
    ("labels-none", lambda: cluster_labels(), ValueError, "key"),
    ("labels-mismatched", lambda: cluster_labels([1, 2], [1]), ValueError, "keys"),
    ("labels-2d", lambda: cluster_labels(np.zeros((2, 2))), ValueError, "keys"),
    ("labels-nan", lambda: cluster_labels([0.1, NAN]), ValueError, "keys"),
    ("labels-empty", lambda: cluster_labels([]), ValueError, "keys"),
    ("bootstrap-resamples-zero", lambda: cluster_bootstrap([1, 2], [3, 3], resamples=0),
     ValueError, "resamples"),
    ("bootstrap-resamples-huge", lambda: cluster_bootstrap([1, 2], [3, 3], resamples=HUGE),
     ValueError, "resamples"),
    ("bootstrap-resamples-float", lambda: cluster_bootstrap([1, 2], [3, 3], resamples=100.0),
     TypeError, "resamples"),
    ("bootstrap-level", lambda: cluster_bootstrap([1, 2], [3, 3], level=1.5), ValueError,
     "level"),
    ("bootstrap-level-nan", lambda: cluster_bootstrap([1, 2], [3, 3], level=NAN), ValueError,
     "level"),
    ("bootstrap-seed", lambda: cluster_bootstrap([1, 2], [3, 3], seed=-1), ValueError, "seed"),
    ("bootstrap-counts", lambda: cluster_bootstrap([1, 2], [3, 0]), ValueError, "n_j"),
    # paired differences
    ("paired-one-cluster", lambda: PairedDifference([1], [1], [2], "position"), ValueError,
     "two clusters"),
    ("paired-unit", lambda: PairedDifference([1, 1], [1, 2], [2, 2], 5), TypeError, "unit"),
    ("paired-by-fold-not-bool", lambda: PairedDifference([1, 1], [1, 2], [2, 2], "fold",
                                                         by_fold=1), TypeError, "by_fold"),
    ("paired-from-mismatched", lambda: PairedDifference.from_recordings(
        [1, 0], [1], [0, 1], "position"), ValueError, "correct_a"),
    ("paired-from-clusters", lambda: PairedDifference.from_recordings(
        [1, 0], [1, 1], [0], "position"), ValueError, "clusters"),
    ("paired-from-not-bool", lambda: PairedDifference.from_recordings(
        [1, 0], [2, 1], [0, 1], "position"), ValueError, "correct"),
    ("mdd-power-one", lambda: minimal_detectable_difference([1, 2], [2, 2], [3, 3], power=1.0),
     ValueError, "power"),
    ("mdd-power-nan", lambda: minimal_detectable_difference([1, 2], [2, 2], [3, 3], power=NAN),
     ValueError, "power"),
    ("mdd-mismatched", lambda: minimal_detectable_difference([1, 2], [2], [3, 3]), ValueError,
     "k and n"),
    ("mdd-resamples-huge", lambda: minimal_detectable_difference(
        [1, 2], [2, 2], [3, 3], resamples=HUGE), ValueError, "resamples"),
    ("mdd-changes-unknown", lambda: minimal_detectable_difference(
        [1, 2], [2, 2], [3, 3], changes="positions"), ValueError, "changes"),
    ("mdd-changes-not-str", lambda: minimal_detectable_difference(
        [1, 2], [2, 2], [3, 3], changes=True), ValueError, "changes"),
    # folds
    ("folds-one", lambda: FoldAccuracy([(np.ones(3, bool), np.arange(3))], "position"),
     ValueError, "two folds"),
    ("folds-not-pairs", lambda: FoldAccuracy([np.ones(3), np.ones(3)], "position"), TypeError,
     "folds"),
    ("folds-not-sequence", lambda: FoldAccuracy(3, "position"), TypeError, "folds"),
    ("folds-half-right", lambda: FoldAccuracy([GOOD_FOLD, ([0.5, 1], [1, 1])], "position"),
     ValueError, "correct"),
    ("folds-nan-right", lambda: FoldAccuracy([GOOD_FOLD, ([NAN, 1], [1, 1])], "position"),
     ValueError, "correct"),
    ("folds-empty-fold", lambda: FoldAccuracy([GOOD_FOLD, ([], [])], "position"), ValueError,
     "correct"),
    ("folds-misaligned", lambda: FoldAccuracy([([1, 0, 1], [0, 0]), ([1, 1], [1, 1, 2])],
                                              "position"), ValueError, "clusters"),
    ("folds-unit", lambda: FoldAccuracy([GOOD_FOLD, GOOD_FOLD], ""), TypeError, "unit"),
    ("folds-by-fold-text", lambda: FoldAccuracy([GOOD_FOLD, GOOD_FOLD], "block", by_fold="no"),
     TypeError, "by_fold"),
    ("fold-entries-name", lambda: FOLDS.entries(None), TypeError, "name"),
    ("entries-name", lambda: clustered_entries(2, ACC), TypeError, "name"),
    ("entries-measured-float", lambda: clustered_entries("svm", 0.8), TypeError, "measured"),
    ("entries-measured-dict", lambda: clustered_entries("svm", {"a": 0.8}), TypeError,
     "measured"),
    ("training-accuracy-nan", lambda: training_entries("t", NAN, 10), ValueError, "accuracy"),
    ("training-accuracy-above", lambda: training_entries("t", 1.5, 10), ValueError, "accuracy"),
    ("training-accuracy-text", lambda: training_entries("t", "0.9", 10), TypeError, "accuracy"),
    ("training-n-zero", lambda: training_entries("t", 0.9, 0), ValueError, "n"),
    ("training-n-fraction", lambda: training_entries("t", 0.9, 10.5), TypeError, "n"),
    ("training-name", lambda: training_entries(None, 0.9, 10), TypeError, "name"),
    ("mean-interval-one-cluster", lambda: cluster_mean_interval([1.0, 2.0], [0, 0]), ValueError,
     "two clusters"),
    ("mean-interval-mismatched", lambda: cluster_mean_interval([1.0], [0, 1]), ValueError,
     "values and clusters"),
    ("mean-interval-nan", lambda: cluster_mean_interval([1.0, NAN], [0, 1]), ValueError,
     "values"),
    ("mean-interval-text", lambda: cluster_mean_interval(["1", "2"], [0, 1]), TypeError,
     "values"),
    ("mean-interval-empty", lambda: cluster_mean_interval([], []), ValueError, "values"),
    ("mean-interval-nan-cluster", lambda: cluster_mean_interval([1.0, 2.0], [0.1, NAN]),
     ValueError, "clusters"),
    # the seeds' spread as folds and as pairs
    ("by-row-zero", lambda: SPREAD.correct_by_row(0), ValueError, "n_rows"),
    ("by-row-fraction", lambda: SPREAD.correct_by_row(6.5), TypeError, "n_rows"),
    ("by-row-bool", lambda: SPREAD.correct_by_row(True), TypeError, "n_rows"),
    ("by-row-too-few", lambda: SPREAD.correct_by_row(4), ValueError, "n_rows"),
    ("spread-folds-clusters-short", lambda: SPREAD.folds([0, 1]), ValueError, "clusters"),
    ("spread-folds-clusters-nan", lambda: SPREAD.folds([NAN] * 6), ValueError, "clusters"),
    ("spread-folds-unit", lambda: SPREAD.folds(unit=""), TypeError, "unit"),
    ("spread-folds-by-fold", lambda: SPREAD.folds(by_fold="yes"), TypeError, "by_fold"),
    ("paired-with-other", lambda: SPREAD.paired_with("seeds"), TypeError, "other"),
    ("paired-with-unit", lambda: SPREAD.paired_with(_spread(), unit=3), TypeError, "unit"),
    ("paired-with-rows", lambda: SPREAD.paired_with(SeedSpread([0, 1], [0.5, 0.5], [2, 2])),
     ValueError, "positions"),
    # splits, twins and a result's rows
    ("folds-too-many", lambda: split_folds("grouped", [0, 1] * 3, [0.1, 0.2] * 3, folds=5),
     ValueError, "folds"),
    ("folds-one-fold", lambda: split_folds("grouped", [0] * 6, np.arange(6), folds=1),
     ValueError, "folds"),
    ("folds-fraction", lambda: split_folds("grouped", [0] * 6, np.arange(6), folds=2.5),
     TypeError, "folds"),
    ("split-kind", lambda: split_folds("sideways", [0] * 6, np.arange(6)), ValueError, "kind"),
    ("split-seed", lambda: split_folds("blocked", [0] * 6, np.arange(6), seed=-2), ValueError,
     "seed"),
    ("twin-negative", lambda: twin_seeds(-1), ValueError, "seed"),
    ("twin-fraction", lambda: twin_seeds(1.5), TypeError, "seed"),
    ("twin-bool", lambda: twin_seeds(True), TypeError, "seed"),
    ("twin-text", lambda: twin_seeds("3"), TypeError, "seed"),
    ("result-split-unknown", lambda: RESULT.correct("train"), ValueError, "split"),
    ("result-split-list", lambda: RESULT.correct(["test"]), TypeError, "split"),
    ("result-rows-none", lambda: RESULT.rows(None), TypeError, "split"),
    ("result-rows-unknown", lambda: RESULT.rows("all"), ValueError, "split"),
    # printing
    ("percent-nan", lambda: percent(NAN), ValueError, "x"),
    ("percent-huge", lambda: percent(HUGE), ValueError, "x"),
    ("percent-text", lambda: percent("0.5"), TypeError, "x"),
    ("percent-digits-negative", lambda: percent(0.5, -1), ValueError, "digits"),
    ("percent-digits-fraction", lambda: percent(0.5, 1.5), TypeError, "digits"),
    ("points-nan", lambda: points(NAN), ValueError, "x"),
    ("points-none", lambda: points(None), TypeError, "x"),
    ("points-digits-huge", lambda: points(0.1, 40), ValueError, "digits"),
    ("span-three", lambda: span((0.1, 0.2, 0.3)), TypeError, "ci"),
    ("span-number", lambda: span(0.5), TypeError, "ci"),
    ("span-nan", lambda: span((NAN, 0.2)), ValueError, "ci"),
    ("span-reversed", lambda: span((0.9, 0.2)), ValueError, "ci"),
    ("span-digits", lambda: span((0.1, 0.2), digits=-3), ValueError, "digits"),
    ("format-clustered-dict", lambda: format_clustered({"estimate": 0.5}), TypeError, "a"),
    ("format-difference-accuracy", lambda: format_difference(ACC), TypeError, "p"),
    ("detectable-text-nan", lambda: detectable_text(NAN, 0.1, "position"), ValueError,
     "spread"),
    ("detectable-text-str", lambda: detectable_text(0.1, "0.2", "position"), TypeError,
     "clustered"),
    ("detectable-text-unit", lambda: detectable_text(0.1, 0.2, 5), TypeError, "unit"),
    ("detectable-cell-nan", lambda: detectable_cell(0.1, NAN), ValueError, "clustered"),
    ("detectable-cell-str", lambda: detectable_cell("0.1", 0.2), TypeError, "spread"),
]


@pytest.mark.parametrize("call, error, name", [pytest.param(*r[1:], id=r[0]) for r in BAD])
def test_bad_input_is_refused_by_name(call, error, name):
    with pytest.raises(error, match=name):
        call()


def _wilson(k, n):
    """Wilson's score interval written out (Wilson 1927) with the normal quantile from SciPy."""
    z = norm.ppf(0.975)
    p = k / n
    centre, scale = p + z * z / (2 * n), 1 + z * z / n
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return (centre - half) / scale, (centre + half) / scale


# ------------------------------------------------------------------------------ good rows
def test_design_effect_by_hand():
    """Clusters of one: exactly 1; whole clusters right or wrong: the cluster size; and
    k = (2, 1, 0) of 2 each: p = 1/2, sum (k_j - p n_j)^2 / N^2 = 2/36 against p(1-p)/N = 1/24,
    a ratio of 4/3."""
    rng = np.random.default_rng(3)
    k = rng.integers(0, 2, 50)
    k[:2] = 0, 1
    assert design_effect(k, np.ones(50, int)) == 1.0
    assert design_effect([2, 0], [2, 2]) == 2.0
    assert design_effect([2, 1, 0], [2, 2, 2]) == pytest.approx(4 / 3, rel=4e-16)


def test_clustered_accuracy_on_clusters_of_one_is_wilson():
    """Clusters of one recording: the interval is Wilson's on the recordings (worked out)."""
    a = ClusteredAccuracy.from_recordings([1, 1, 0, 1], [0, 1, 2, 3], "position")
    lo, hi = _wilson(3, 4)
    assert a.ci95 == pytest.approx((lo, hi), abs=1e-12)  # two square roots: a few ulps
    assert a.recording_ci95 == pytest.approx(accuracy_interval(3, 4), abs=1e-12)
    assert (a.estimate, a.n_units, a.n_recordings) == (0.75, 4, 4)
    assert format_clustered(a) == (f"75.0 % (n = 4 in 4 positions, 95 % CI "
                                   f"{round(100 * lo, 1)}-{round(100 * hi, 1)})")
    e = a.entries("svm")
    assert (e["svm"], e["svm_n_units"], e["svm_unit"], e["svm_design_effect"]) == (
        0.75, 4, "position", 1.0)


def test_cluster_counts_and_labels_by_hand():
    k, n = cluster_counts([True, False, True, True, False], ["b", "a", "b", "c", "a"])
    assert k.tolist() == [0, 2, 1] and n.tolist() == [2, 2, 1]
    labels = cluster_labels([0.2, 0.1, 0.2, 0.1], ["al", "al", "al", "pvc"])
    assert labels.tolist() == [2, 0, 2, 1]


def test_cluster_bootstrap_against_its_enumerated_distribution():
    """Three clusters of three, two all right and one all wrong: a resample's accuracy is
    B / 3 with B ~ Binomial(3, 2/3), so P(0) = 1/27, P(1/3) = 6/27, P(2/3) = 12/27,
    P(1) = 8/27. Its 10 % and 90 % quantiles are 1/3 and 1, each a jump away from the
    resampling noise (the cumulative 0.037 < 0.10 < 0.259 and 0.704 < 0.90)."""
    lo, hi = cluster_bootstrap([3, 0, 3], [3, 3, 3], level=0.8, resamples=4000, seed=5)
    assert (lo, hi) == (pytest.approx(1 / 3, rel=1e-15), 1.0)
    lo, hi = cluster_bootstrap([3, 0, 3], [3, 3, 3])
    assert (lo, hi) == (0.0, 1.0)  # P(0) = 3.7 % > 2.5 %, P(1) = 30 % > 2.5 %


def test_paired_difference_by_hand():
    """d = (-1, -2, -1, -1), D = -5/12; the residuals d_j - D n_j = (1, -3, 1, 1) / 4 give
    SE = sqrt(4/3 * 3/4) / 12 = 1/12, and the interval D ± t_{0.975, 3} SE."""
    se, q = 1 / 12, student_t.ppf(0.975, 3)
    assert PAIR.difference == pytest.approx(-5 / 12, rel=1e-15)
    assert PAIR.se == pytest.approx(se, rel=1e-14)
    assert PAIR.ci95 == pytest.approx((-5 / 12 - q * se, -5 / 12 + q * se), rel=1e-14)
    text = format_difference(PAIR)
    lo, hi = (round(100 * v, 1) for v in PAIR.ci95)
    assert text.startswith(f"-41.7 points (95 % CI {lo} to {hi}, 4 positions; ")
    both = detectable_text(PAIR.detectable, PAIR.detectable_clustered, "position")
    assert text.endswith(f"detectable at 80 % power: {both})")
    assert detectable_text(0.0065, math.inf, "block") == (
        "0.7 points spread over recordings, no change within reach by whole blocks")
    assert detectable_cell(0.0065, math.inf) == "0.7 / none within reach"
    assert detectable_text(math.inf, 0.3, "fold") == (
        "no change within reach spread over recordings, 30.0 points by whole folds")
    d = PAIR.to_dict()
    assert (d["direction"], d["resolved"], d["n_units"]) == ("lower", True, 4)
    p = PairedDifference.from_recordings([1, 1, 1, 1], [0, 1, 1, 1], [0, 0, 1, 1], "position",
                                         resamples=100)
    assert (p.difference, p.se) == (-0.25, 0.25)  # residuals (-1/2, 1/2): sqrt(2 * 1/2) / 4


def test_minimal_detectable_difference_of_a_noiseless_design_is_not_zero():
    """The same count right under both in every cluster: no paired noise, yet a change must
    bring changed recordings before it is resolved, so the difference is positive (on three
    clusters of three, q = 4.30, no change within reach is resolved 80 % of the time: inf);
    with noise, about (z_0.975 + z_0.8) SE for many clusters."""
    assert minimal_detectable_difference([1, 2, 3], [1, 2, 3], [3, 3, 3]) == math.inf
    k = np.random.default_rng(1).binomial(5, 0.8, 100)
    assert 0 < minimal_detectable_difference(k, k, np.full(100, 5), resamples=500) < 0.05
    rng = np.random.default_rng(0)
    n = np.full(400, 3)
    k_a, k_b = rng.binomial(3, 0.6, 400), rng.binomial(3, 0.6, 400)
    se = PairedDifference(k_a, k_b, n, "position", resamples=10).se
    mdd = minimal_detectable_difference(k_a, k_b, n, resamples=2000)
    # the normal approximation at 400 clusters, and a bootstrap quantile of 2000 draws: 10 %
    assert mdd == pytest.approx((norm.ppf(0.975) + norm.ppf(0.8)) * se, rel=0.1)


def test_fold_accuracy_and_entries_by_hand():
    assert FOLDS.values.tolist() == [0.5, 1.0] and FOLDS.estimate == 0.75
    assert FOLDS.spread == pytest.approx(math.sqrt(0.125), rel=1e-15)
    e = FOLDS.entries("ann")
    assert e["ann_folds"] == [0.5, 1.0] and e["ann_n_units"] == 2
    both = clustered_entries("svm", {"a": ACC, "b": FOLDS})
    assert both["svm"] == {"a": 0.75, "b": 0.75} and both["svm_n_units"] == {"a": 2, "b": 2}
    assert training_entries("train", 0.9, 100) == {"train": 0.9, "train_n_train": 100}


def test_cluster_mean_interval_by_hand():
    """Cluster means (1, 3, 2): mean 2, sample deviation 1, interval 2 ± t_{0.975, 2} / sqrt 3."""
    r = cluster_mean_interval([1.0, 1.0, 3.0, 3.0, 2.0], [0, 0, 1, 1, 2])
    half = student_t.ppf(0.975, 2) / math.sqrt(3)
    assert r["estimate"] == 2.0 and r["ci95"] == pytest.approx([2 - half, 2 + half], rel=1e-14)


def test_seed_spread_as_folds_and_pairs_by_hand():
    assert SPREAD.correct_by_row(6).tolist() == [True, False, True, True, True, False]
    f = SPREAD.folds()
    assert f.estimate == pytest.approx(4 / 6, rel=1e-15) and f.n_units == 3
    assert SPREAD.folds(clusters=np.arange(6)).n_units == 6
    # A: (T F | T T | T F) by position; B all right: d = (1, 0, 1) over 2 each, D = 2/6
    p = SPREAD.paired_with(_spread(((True,) * 3, (True,) * 3)), resamples=100)
    assert p.difference == pytest.approx(1 / 3, rel=1e-15) and p.n_units == 3


def test_printing_rounds_half_away_from_zero():
    """On the decimal value: 0.8155 and 0.8145 are a hair off their halves as doubles."""
    assert percent(0.8155) == "81.6 %" and percent(0.8145) == "81.5 %"
    assert percent(0.81549) == "81.5 %" and percent(0.5, 0) == "50 %"
    assert points(-0.1045) == "-10.5 points" and points(0.05) == "+5.0 points"
    assert span((0.7605, 0.905)) == "76.1-90.5" and span((0.0, 1.0), digits=0) == "0-100"


def test_split_folds_hold_every_row_once():
    pos = np.repeat(np.arange(1, 7) / 100, 2)
    y = np.tile(["al", "pvc"], 6)
    tests = [t for _, t in split_folds("grouped", y, pos, folds=3)]
    assert sorted(np.concatenate(tests).tolist()) == list(range(12))
    for t in tests:  # whole positions
        assert not set(pos[t]) & set(np.delete(pos, t))


def test_twin_seeds_differ():
    assert twin_seeds(7) == (7, 8) and twin_seeds(2**32 - 2) == (2**32 - 2, 2**32 - 3)


def test_result_rows_and_correct():
    assert RESULT.rows().tolist() == [4, 7] and RESULT.correct("test").tolist() == [True, False]


def _ids(*prefixes):
    return [r[0] for r in BAD if r[0].startswith(prefixes)]


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    u = "ebantenna.paper.uncertainty."
    return {
        "ebantenna.ml.metrics.accuracy_interval": _ids("interval-")
        + ["test_clustered_accuracy_on_clusters_of_one_is_wilson"],
        "ebantenna.ml.metrics.accuracy": _ids("accuracy-"),
        u + "design_effect": _ids("deff-") + ["test_design_effect_by_hand"],
        u + "ClusteredAccuracy": _ids("clustered-unit", "clustered-mismatched")
        + ["test_clustered_accuracy_on_clusters_of_one_is_wilson"],
        u + "ClusteredAccuracy.from_recordings": _ids("clustered-from-")
        + ["test_clustered_accuracy_on_clusters_of_one_is_wilson"],
        u + "ClusteredAccuracy.entries": _ids("entries-name-")
        + ["test_clustered_accuracy_on_clusters_of_one_is_wilson"],
        u + "cluster_counts": _ids("counts-") + ["test_cluster_counts_and_labels_by_hand"],
        u + "cluster_labels": _ids("labels-") + ["test_cluster_counts_and_labels_by_hand"],
        u + "cluster_bootstrap": _ids("bootstrap-")
        + ["test_cluster_bootstrap_against_its_enumerated_distribution"],
        u + "PairedDifference": _ids("paired-one", "paired-unit")
        + ["test_paired_difference_by_hand"],
        u + "PairedDifference.from_recordings": _ids("paired-from-")
        + ["test_paired_difference_by_hand"],
        u + "minimal_detectable_difference": _ids("mdd-")
        + ["test_minimal_detectable_difference_of_a_noiseless_design_is_not_zero"],
        u + "FoldAccuracy": _ids("folds-one", "folds-not", "folds-half", "folds-nan",
                                 "folds-empty", "folds-misaligned", "folds-unit", "folds-by")
        + ["test_fold_accuracy_and_entries_by_hand"],
        u + "FoldAccuracy.entries": _ids("fold-entries-")
        + ["test_fold_accuracy_and_entries_by_hand"],
        u + "clustered_entries": _ids("entries-name", "entries-measured")
        + ["test_fold_accuracy_and_entries_by_hand"],
        u + "training_entries": _ids("training-") + ["test_fold_accuracy_and_entries_by_hand"],
        u + "cluster_mean_interval": _ids("mean-interval-")
        + ["test_cluster_mean_interval_by_hand"],
        u + "SeedSpread.correct_by_row": _ids("by-row-")
        + ["test_seed_spread_as_folds_and_pairs_by_hand"],
        u + "SeedSpread.folds": _ids("spread-folds-")
        + ["test_seed_spread_as_folds_and_pairs_by_hand"],
        u + "SeedSpread.paired_with": _ids("paired-with-")
        + ["test_seed_spread_as_folds_and_pairs_by_hand"],
        u + "percent": _ids("percent-") + ["test_printing_rounds_half_away_from_zero"],
        u + "points": _ids("points-") + ["test_printing_rounds_half_away_from_zero"],
        u + "span": _ids("span-") + ["test_printing_rounds_half_away_from_zero"],
        u + "format_clustered": _ids("format-clustered-")
        + ["test_clustered_accuracy_on_clusters_of_one_is_wilson"],
        u + "format_difference": _ids("format-difference-") + ["test_paired_difference_by_hand"],
        u + "detectable_text": _ids("detectable-text-") + ["test_paired_difference_by_hand"],
        u + "detectable_cell": _ids("detectable-cell-") + ["test_paired_difference_by_hand"],
        "ebantenna.paper.splits.split_folds": _ids("folds-too", "folds-one-fold",
                                                   "folds-fraction", "split-")
        + ["test_split_folds_hold_every_row_once"],
        "ebantenna.paper.controls.twin_seeds": _ids("twin-") + ["test_twin_seeds_differ"],
        "ClassificationResult.correct": _ids("result-split-") + ["test_result_rows_and_correct"],
        "ClassificationResult.rows": _ids("result-rows-") + ["test_result_rows_and_correct"],
    }


def contract_exempt() -> dict[str, str]:
    """Public names that take no input from a user."""
    return {
        "ebantenna.paper.uncertainty.PairedDifference.to_dict": "no argument",
        "ebantenna.study.rod_geometry.GeometryResult.gap_correlation": "no argument",
    }


def test_every_mapped_row_exists():
    """A row id of contract_rows() names a bad row above or a test of this module."""
    names = {r[0] for r in BAD} | {n for n in globals() if n.startswith("test_")}
    for surface, ids in contract_rows().items():
        assert ids and set(ids) <= names, surface
