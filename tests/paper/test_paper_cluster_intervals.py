"""Intervals on the unit of replication: what the arithmetic and the resampling guarantee,
each against a witness written here independently of the module."""

import math

import numpy as np
import pytest
from scipy.stats import t as student_t

from ebantenna.ml.metrics import accuracy_interval
from ebantenna.paper.uncertainty import (
    ClusteredAccuracy,
    FoldAccuracy,
    PairedDifference,
    cluster_bootstrap,
    cluster_counts,
    cluster_labels,
    design_effect,
    minimal_detectable_difference,
    percent,
    points,
    span,
)


def _clustered(rng, clusters, size, p, rho):
    """Right/wrong per recording: each cluster draws its own rate from a beta of mean ``p``
    and intraclass correlation ``rho`` (beta-binomial), then its recordings from it."""
    a = p * (1 - rho) / rho
    b = (1 - p) * (1 - rho) / rho
    rates = rng.beta(a, b, clusters)
    correct = rng.random((clusters, size)) < rates[:, None]
    return correct.ravel(), np.repeat(np.arange(clusters), size)


@pytest.mark.parametrize("n", [1, 7, 80, 240, 2000])
def test_one_recording_per_cluster_is_wilson_exactly(n):
    rng = np.random.default_rng(n)
    for k in sorted({0, n, *rng.integers(0, n + 1, 5).tolist()}):
        correct = np.zeros(n, bool)
        correct[:k] = True
        a = ClusteredAccuracy.from_recordings(rng.permutation(correct), np.arange(n), "recording")
        assert a.design_effect == 1.0
        assert a.n_units == n
        # the same formula on the same numbers; rounding of a sqrt and a division: a few ulps
        assert a.ci95 == pytest.approx(accuracy_interval(k, n), abs=1e-15)
        assert a.recording_ci95 == accuracy_interval(k, n)


def test_design_effect_is_the_ratio_of_the_two_variances_written_out():
    rng = np.random.default_rng(3)
    correct, clusters = _clustered(rng, 60, 25, 0.8, 0.5)
    k, n = cluster_counts(correct, clusters)
    p = correct.mean()
    # witness: the cluster-level variance of the ratio over the binomial one, by loops
    between = sum((correct[clusters == j].sum() - p * (clusters == j).sum()) ** 2
                  for j in range(60))
    assert design_effect(k, n) == pytest.approx(between / (correct.size * p * (1 - p)),
                                                rel=1e-12)


def test_design_effect_tracks_kish_for_clusters_of_equal_size():
    """1 + (m - 1) rho for clusters of m with intraclass correlation rho (Kish 1965), within
    the sampling error of 400 clusters (about 10 % of the design effect)."""
    rng = np.random.default_rng(5)
    for m, rho in ((25, 0.76), (3, 0.79), (10, 0.1)):
        correct, clusters = _clustered(rng, 400, m, 0.75, rho)
        deff = design_effect(*cluster_counts(correct, clusters))
        assert deff == pytest.approx(1 + (m - 1) * rho, rel=0.2)


def test_whole_clusters_right_or_wrong_give_the_cluster_size():
    k, n = np.array([4, 0, 4, 4, 0]), np.full(5, 4)
    assert design_effect(k, n) == pytest.approx(4.0)
    a = ClusteredAccuracy(k, n, "position")
    # five units, each one observation: Wilson's interval of 3 of 5, with Student's quantile
    # on 4 degrees of freedom (the design effect is estimated from five clusters), written out
    q = student_t.ppf(0.975, 4)
    centre, scale = 0.6 + q * q / 10, 1 + q * q / 5
    half = q * np.sqrt(0.6 * 0.4 / 5 + q * q / 100)
    assert a.ci95 == pytest.approx(((centre - half) / scale, (centre + half) / scale), abs=1e-15)
    assert a.ci95[0] < accuracy_interval(3, 5)[0] and a.ci95[1] > accuracy_interval(3, 5)[1]


def test_few_clusters_widen_the_interval_as_the_t_interval_over_them_does():
    # four positions (a recorded quick design): the normal quantile gave 57.9-84.6 %, where the
    # t interval over the positions' own accuracies is 47.3-99.3 %; Student's quantile on three
    # degrees of freedom widens it towards that, and with many clusters it is the normal one
    def wilson(p, n, q):
        centre, scale = p + q * q / (2 * n), 1 + q * q / n
        half = q * np.sqrt(p * (1 - p) / n + q * q / (4 * n * n))
        return (centre - half) / scale, (centre + half) / scale

    k, n = np.array([9, 12, 14, 9]), np.full(4, 15)
    for g in (1, 50):
        a = ClusteredAccuracy(np.tile(k, g), np.tile(n, g), "position")
        q = student_t.ppf(0.975, 4 * g - 1)
        assert a.ci95 == pytest.approx(wilson(a.estimate, a.effective_n, q), abs=1e-14)
        normal = wilson(a.estimate, a.effective_n, 1.959963984540054)
        assert a.ci95[0] < normal[0] and a.ci95[1] > normal[1]
    assert (q - 1.96) / 1.96 < 0.01  # 200 positions: within 1 % of the normal quantile
    assert "Student's quantile" in a.method

def test_all_right_takes_the_largest_design_effect_the_design_allows():
    assert design_effect([3, 3, 3], [3, 3, 3]) == 3.0
    assert design_effect([0, 0], [1, 1]) == 1.0


def test_cluster_bootstrap_equals_a_brute_force_loop_on_the_same_draws():
    rng = np.random.default_rng(11)
    correct, clusters = _clustered(rng, 30, 7, 0.7, 0.4)
    k, n = cluster_counts(correct, clusters)
    lo, hi = cluster_bootstrap(k, n, resamples=500, seed=4)
    # witness: resample the cluster labels and recount from the recordings themselves
    draw = np.random.default_rng(4).integers(0, 30, size=(500, 30))
    stats = []
    for picks in draw:
        got = np.concatenate([correct[clusters == j] for j in picks])
        stats.append(got.mean())
    assert (lo, hi) == pytest.approx(tuple(np.quantile(stats, [0.025, 0.975])), abs=1e-12)


def test_cluster_bootstrap_and_design_effect_intervals_agree_on_many_clusters():
    """Two methods of one quantity: with 300 clusters both are near-normal, and their widths
    agree to the bootstrap's Monte Carlo error (a few per cent at 4000 resamples)."""
    rng = np.random.default_rng(2)
    correct, clusters = _clustered(rng, 300, 10, 0.7, 0.5)
    k, n = cluster_counts(correct, clusters)
    lo, hi = cluster_bootstrap(k, n, resamples=4000, seed=0)
    a = ClusteredAccuracy(k, n, "position")
    assert hi - lo == pytest.approx(a.ci95[1] - a.ci95[0], rel=0.1)
    assert a.ci95[1] - a.ci95[0] > 2 * (a.recording_ci95[1] - a.recording_ci95[0])


def test_the_clustered_interval_covers_the_true_rate_as_stated():
    """Coverage over 400 designs of 40 clusters of 10 at rho = 0.5: near 95 %, where the
    recording-level interval covers far less. 400 draws: the coverage's standard error is
    about 1.1 points."""
    rng = np.random.default_rng(8)
    hit = wilson = 0
    for _ in range(400):
        correct, clusters = _clustered(rng, 40, 10, 0.7, 0.5)
        a = ClusteredAccuracy.from_recordings(correct, clusters, "position")
        hit += a.ci95[0] <= 0.7 <= a.ci95[1]
        wilson += a.recording_ci95[0] <= 0.7 <= a.recording_ci95[1]
    assert 0.90 <= hit / 400 <= 0.99
    assert wilson / 400 < 0.75


def test_paired_difference_written_out_and_mirrored():
    rng = np.random.default_rng(1)
    g, m = 50, 6
    a = rng.random((g, m)) < 0.7
    b = a & (rng.random((g, m)) < 0.85)
    clusters = np.repeat(np.arange(g), m)
    p = PairedDifference.from_recordings(a.ravel(), b.ravel(), clusters, "position",
                                         resamples=200)
    d = (b.sum(1) - a.sum(1)).astype(float)
    diff = d.sum() / (g * m)
    se = math.sqrt(g / (g - 1) * np.sum((d - diff * m) ** 2)) / (g * m)
    q = student_t.ppf(0.975, g - 1)
    assert p.difference == pytest.approx(diff, rel=1e-12)
    assert p.se == pytest.approx(se, rel=1e-12)
    assert p.ci95 == pytest.approx((diff - q * se, diff + q * se), rel=1e-12)
    assert p.direction == "lower" and p.resolved
    back = PairedDifference.from_recordings(b.ravel(), a.ravel(), clusters, "position",
                                            resamples=200)
    assert back.difference == pytest.approx(-p.difference, rel=1e-12)
    assert back.direction == "higher"


def test_paired_by_fold_is_the_paired_t_interval_of_the_folds_accuracies():
    """With ``by_fold`` the folds weigh alike, as FoldAccuracy(by_fold=True) has them: the
    difference is the mean of the folds' differences and its interval scipy's paired t test's
    (ttest_rel), whatever the folds' sizes; the two accuracies are FoldAccuracy's."""
    from scipy.stats import ttest_rel

    rng = np.random.default_rng(3)
    sizes = [30, 30, 30, 15, 15]  # unequal folds: the fold mean is not the pooled accuracy
    a = [rng.random(m) < 0.3 for m in sizes]
    b = [x | (rng.random(x.size) < 0.2) for x in a]
    folds = np.concatenate([np.full(m, i) for i, m in enumerate(sizes)])
    p = PairedDifference.from_recordings(np.concatenate(a), np.concatenate(b), folds,
                                         "held-out block", by_fold=True, resamples=200)
    acc_a, acc_b = np.array([x.mean() for x in a]), np.array([x.mean() for x in b])
    witness = ttest_rel(acc_b, acc_a).confidence_interval(0.95)
    assert p.difference == pytest.approx(np.mean(acc_b - acc_a), rel=1e-12)
    assert p.ci95 == pytest.approx((witness.low, witness.high), rel=1e-12)
    for acc, x in ((p.accuracy_a, a), (p.accuracy_b, b)):
        assert acc == FoldAccuracy([(c, np.zeros(c.size)) for c in x], "held-out block",
                                   by_fold=True).estimate
    pooled = PairedDifference.from_recordings(np.concatenate(a), np.concatenate(b), folds,
                                              "held-out block", resamples=200)
    assert pooled.difference != pytest.approx(p.difference)  # the folds' sizes differ
    assert p.n_units == 5 and p.n_recordings == sum(sizes) and "5 folds" in p.method


def test_paired_se_matches_a_brute_force_cluster_bootstrap_of_the_difference():
    """The cluster-robust standard error against the spread of a bootstrap written here
    (2000 resamples: its standard deviation is within about 5 % of the truth)."""
    rng = np.random.default_rng(6)
    g, m = 120, 5
    shared = rng.random(g)[:, None]  # the position's difficulty, shared by both conditions
    a = rng.random((g, m)) < 0.4 + 0.5 * shared
    b = rng.random((g, m)) < 0.3 + 0.5 * shared
    p = PairedDifference(a.sum(1), b.sum(1), np.full(g, m), "position", resamples=100)
    draws = np.random.default_rng(0).integers(0, g, (2000, g))
    boot = [(b[i].sum() - a[i].sum()) / (g * m) for i in draws]
    assert p.se == pytest.approx(np.std(boot, ddof=1), rel=0.12)


def test_minimal_detectable_difference_has_its_power():
    """At the returned difference, a simulation written here (the design's clusters drawn
    again, the difference added as recordings that change outcome, each with the same chance)
    resolves it in about 80 % of draws, in the direction that needs the larger change (1000
    draws: a standard error of about 1.3 points)."""
    rng = np.random.default_rng(9)
    g, m = 80, 3
    a = rng.binomial(m, 0.65, g)
    b = np.clip(a + rng.integers(-1, 2, g), 0, m)
    n = np.full(g, m)
    mdd = minimal_detectable_difference(a, b, n, resamples=4000, seed=1)
    d = (b - a).astype(float)
    resid = d - d.sum() / n.sum() * n
    q = student_t.ppf(0.975, g - 1)
    share = []
    for sign, room in ((1, n - b), (-1, b)):  # a gain turns B's wrong right, a loss its right
        hits = 0
        sim = np.random.default_rng(2)
        for _ in range(1000):
            pick = sim.integers(0, g, g)
            r = sign * resid[pick] + sim.binomial(room[pick], mdd * n.sum() / room.sum())
            est = r.sum() / n[pick].sum()
            se = math.sqrt(g / (g - 1) * np.sum((r - est * n[pick]) ** 2)) / n[pick].sum()
            hits += est > q * se
        share.append(hits / 1000)
    assert 0.75 <= min(share) <= 0.85
    # and against the normal approximation: (z_0.975 + z_0.8) standard errors, about 2.8
    se = math.sqrt(g / (g - 1) * np.sum(resid**2)) / n.sum()
    assert mdd == pytest.approx(2.8 * se, rel=0.15)


def test_blocked_folds_take_students_t_over_the_folds():
    values = [0.1, 0.2, 0.45, 0.3, 0.25]
    folds = [(np.arange(20) < round(20 * v), np.full(20, i)) for i, v in enumerate(values)]
    f = FoldAccuracy(folds, "held-out block", by_fold=True)
    lo, hi = student_t.interval(0.95, 4, loc=np.mean(values),
                                scale=np.std(values, ddof=1) / math.sqrt(5))
    assert f.ci95 == pytest.approx((lo, hi), rel=1e-12)
    assert f.n_units == 5 and f.estimate == pytest.approx(np.mean(values))
    assert f.spread == pytest.approx(np.std(values, ddof=1))


def test_grouped_folds_pool_every_recording_once():
    rng = np.random.default_rng(0)
    folds = [(rng.random(12) < 0.6, np.repeat([i, i + 5, i + 10], 4)) for i in range(5)]
    f = FoldAccuracy(folds, "position")
    pooled = np.concatenate([c for c, _ in folds])
    assert f.estimate == pytest.approx(pooled.mean())
    assert f.n_units == 15 and f.n_recordings == 60


def test_cluster_labels_and_counts():
    labels = cluster_labels([0.1, 0.1, 0.2, 0.2, 0.1], ["a", "b", "a", "a", "a"])
    assert labels.tolist() == [0, 1, 2, 2, 0]
    k, n = cluster_counts([1, 0, 1, 1, 1], labels)
    assert k.tolist() == [2, 0, 2] and n.tolist() == [2, 1, 2]


def test_one_rounding_of_a_number_whatever_its_binary_form():
    # 0.8155 is stored a hair below 0.8155; 81.55 % must print 81.6 wherever it is printed
    assert percent(0.8155) == "81.6 %" and span([0.8155, 0.8482]) == "81.6-84.8"
    assert percent(0.81549) == "81.5 %"
    assert points(-0.104) == "-10.4 points" and points(0.0) == "+0.0 points"
