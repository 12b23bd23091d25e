"""The report's interpretive sentences of the spread, time-frequency, training-budget, decay,
contact-law and hinge sections are generated from their numbers: fed synthetic numbers whose
direction flips, the words flip with them; where nothing measured tests a claim, the words
describe the method instead."""

from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from ebantenna.fem.hinge import HingeFit
from ebantenna.paper.uncertainty import ClusteredAccuracy, PairedDifference
from ebantenna.report import FigureSet, Report
from ebantenna.signal.timefreq import TimeFrequency
from ebantenna.study import (
    ann_setup,
    contact_law,
    data_summary,
    hinge_fit,
    learning,
    seed_spread,
    signals,
    time_frequency,
)

G = 16
N = np.full(G, 3)


def _accuracy(k_each, n_each=3):
    return ClusteredAccuracy(np.full(G, k_each), np.full(G, n_each), "position")


# ---------------------------------------------------------------- folds against binomial
@pytest.mark.parametrize("ratio, words", [(3.0, "more than independent recordings"),
                                          (0.2, "less than independent recordings"),
                                          (1.0, "does not tell the recordings")])
def test_the_spread_sentence_follows_the_ratio(ratio, words):
    text = seed_spread.scatter_sentence([("the row", ratio, 5)])
    assert words in text
    others = {"more than independent", "less than independent", "does not tell"} - {
        w for w in ("more than independent", "less than independent", "does not tell")
        if w in words}
    assert not any(w in text for w in others)


def test_the_ratio_interval_is_the_chi_square_one():
    # s^2 (F-1) / sigma^2 ~ chi2(F-1): the ends are where the measured ratio sits at the
    # 2.5 % and 97.5 % quantiles; witnessed by simulating normal folds
    lo, hi = seed_spread.ratio_interval(1.0, 5)
    rng = np.random.default_rng(0)
    s = rng.standard_normal((200_000, 5)).std(axis=1, ddof=1)
    # 1/s covers the true ratio 1 within [lo, hi] 95 % of the time; 200 000 draws give the
    # share to within 0.002 (binomial standard error 0.0005, four of them)
    assert abs(np.mean((1 / s >= lo) & (1 / s <= hi)) - 0.95) < 0.002


def test_a_borderline_ratio_is_not_called_above_one():
    # 1.5 on five folds: above one, but within what five folds leave open
    text = seed_spread.scatter_sentence([("a", 1.5, 5), ("b", 3.0, 5)])
    assert "for b:" in text and "in the other 1 row" in text


@pytest.mark.parametrize("few, many, words", [
    (1, 3, "rises from"), (3, 1, "falls from"), (2, 2, "intervals overlap")])
def test_the_repetitions_sentence_follows_the_intervals(few, many, words):
    text = seed_spread.repetitions_sentence({1: _accuracy(few), 5: _accuracy(many)})
    assert words in text
    assert ("matters on whole held-out positions" in text) == (words != "intervals overlap")
    # the rows share their positions and folds: an overlap of their intervals is no test
    assert ("overlap is no test of the change" in text) == (words == "intervals overlap")
    assert "this design does not show" not in text


def test_the_narrowing_is_compared_with_the_count_of_recordings():
    # one recording per position against three: with every position alike the interval on
    # the position narrows as the recordings grow; with positions apart it narrows less
    alike = seed_spread.repetitions_sentence({
        1: ClusteredAccuracy([1, 0] * 8, [1] * G, "position"),
        3: ClusteredAccuracy([2, 1] * 8, [3] * G, "position")})
    apart = seed_spread.repetitions_sentence({
        1: ClusteredAccuracy([1, 0] * 8, [1] * G, "position"),
        3: ClusteredAccuracy([3, 0] * 8, [3] * G, "position")})
    assert "at least the precision their count suggests" in alike
    assert "less precision than their count suggests" in apart


# ---------------------------------------------------------------- time-frequency
def _map(rows, t=None):
    rows = np.asarray(rows, dtype=float)
    t = np.arange(rows.shape[1]) * 0.1 if t is None else t
    return TimeFrequency(t, 10.0 * (1 + np.arange(rows.shape[0])), rows, "spectrogram")


def test_the_band_share_and_the_energy_time_read_the_map():
    one = _map([[1.0, 1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]])
    two = _map([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 1.0, 1.0]])
    assert time_frequency.band_share(one) == 1.0
    assert time_frequency.band_share(two) == 0.75
    assert time_frequency.energy_time(one) == pytest.approx(0.1)  # half arrives at each frame
    assert time_frequency.energy_time(two) == pytest.approx(0.3)


@pytest.mark.parametrize("shares, times, agree", [
    ((0.9, 0.4), (0.3, 0.1), 2), ((0.4, 0.9), (0.3, 0.1), 1), ((0.4, 0.9), (0.1, 0.3), 0)])
def test_the_time_frequency_sentence_follows_the_maps(shares, times, agree):
    text = time_frequency.profile_sentence((0.25, 0.9), shares, times)
    assert text.count("as the paper describes") == agree
    assert text.count("unlike the paper's description") == 2 - agree
    assert ("spreads over more frequencies" in text) == (shares[1] < shares[0])
    assert ("sooner" in text) == (times[1] < times[0])


# ---------------------------------------------------------------- the training budget
FLAT = PairedDifference(np.array([3, 2] * 8), np.array([2, 3] * 8), N, "position",
                        resamples=200)


def test_the_budget_heading_asks_and_learning_points_to_it():
    assert "lower" not in ann_setup.HEADING and "Why" not in ann_setup.HEADING
    source = Path(learning.__file__).read_text(encoding="utf-8")
    assert f"'{ann_setup.HEADING}'" in source


def test_an_unresolved_step_difference_is_not_read_as_no_effect():
    run = dict(stopped_by="epoch cap", epochs=1000, max_epochs=1000, lr=0.05,
               test=_accuracy(2))
    text = ann_setup._verdict(ann_setup.AnnSetupResult({"a": run, "b": {**run, "lr": 0.5}},
                                                       1, None, FLAT))
    assert "not resolved" in text and "does not show whether" in text
    assert "does not account" not in text


def test_the_long_run_does_not_speak_for_the_features():
    final = _accuracy(2)
    long = dict(epochs=[50, 100], test=[0.5, 0.9], all=[0.5, 0.95], reached_test=100,
                reached_all=100, final=final, stopped_by="x", max_epochs=200, within_from=None,
                test_ci95=[(0.4, 0.6), (0.85, 0.95)])
    text = ann_setup._long_verdict(ann_setup.AnnSetupResult({}, 1, long))
    assert "not the features" not in text and "not what this run tests" in text


# ---------------------------------------------------------------- decay and filter ringing
@pytest.mark.parametrize("taus, words", [
    ([0.13, 0.18], "every median here is shorter"), ([0.6, 0.7], "every median here is longer"),
    ([0.13, 0.7], "1 of the 2 medians here are shorter")])
def test_the_ringing_sentence_follows_the_time_constants(taus, words):
    text = signals.ringing_sentence(0.42, taus)
    assert words in text and "420 ms" in text


def test_the_decay_section_reads_the_filters_time_constant(tmp_path):
    row = dict(material="brass", grid=np.zeros(1), gain=np.ones(1), tau=np.ones(1),
               median_gain=1.0, median_tau=0.1, ok=1.0, n_ok=3, n=3)
    report = Report("t")
    signals.render_decay(signals.DecayResult((row,), 1.0, 0.25, {"ok": 3}), report,
                         FigureSet(tmp_path))
    text = report.markdown()
    assert "250 ms" in text and "every median here is shorter" in text and "0.4 s" not in text
    assert "Of the 3 fits, 3 are usable." in text and "| 3 of 3 |" in text
    # no usable fit: the table says so instead of printing NaN
    row = dict(row, median_gain=np.nan, median_tau=np.nan, ok=0.0, n_ok=0)
    report = Report("t")
    signals.render_decay(signals.DecayResult((row,), 0.0, 0.25, {"noise_limited": 3}), report,
                         FigureSet(tmp_path))
    text = report.markdown()
    assert "| n/a | n/a | 0 of 3 |" in text and "nan" not in text
    assert "none is usable, so the gains and time constants of Fig. 11 are not reproduced" in text


# ---------------------------------------------------------------- the contact law
@pytest.mark.parametrize("median, words", [(15, "at least half"), (0.5, "exactly half"),
                                           (0, "fewer than half")])
def test_the_restrike_words_follow_the_median(median, words):
    assert contact_law.restrike_words(median).startswith(words)


def test_the_restrike_words_hold_for_the_counts_they_summarise():
    rng = np.random.default_rng(1)
    for _ in range(200):
        counts = rng.integers(0, 3, size=rng.integers(1, 12)) * rng.integers(0, 2)
        share = np.mean(counts > 0)
        words = contact_law.restrike_words(float(np.median(counts)))
        if words.startswith("at least half"):
            assert share >= 0.5
        elif words.startswith("exactly half"):
            assert share == 0.5
        else:
            assert share < 0.5


# ---------------------------------------------------------------- the hinge
def _hinge(observed, predicted):
    return hinge_fit.HingeResult(HingeFit(1.0, 1e-3, np.array([0.4, 0.5]), np.array(observed),
                                          np.array(predicted), "peak"))


def test_the_hinge_paragraph_reads_the_observations_and_the_resolution(tmp_path):
    report = Report("t")
    hinge_fit.render(_hinge([0.3, 0.45], [0.3, 0.45]), report, FigureSet(tmp_path))
    text = report.markdown()
    assert "0.75 L and 0.90 L" in text and "at 30 cm on a 40 cm probe" in text
    assert "explains both observations within their 2.5 mm" in text
    report = Report("t")
    hinge_fit.render(_hinge([0.3, 0.45], [0.3, 0.46]), report, FigureSet(tmp_path))
    text = report.markdown()
    assert "No single hinge-and-tip model" not in text  # the verdict rests on assumptions
    assert "Under two assumptions, no single hinge-and-tip model" in text
    assert "largest residual, 1.00 cm" in text
    assert "read to 2.5 mm, half its 5 mm contact step" in text
    assert "'deviation from the linear variation' is where the lowest frequency peaks" in text
    assert "cannot say which" in text


def _hinge_on_lattice(best_rms_cm):
    """A fit 1 cm RMS off, on a lattice of 1, 10, 100, 1000 N m/rad whose best masses miss by
    ``best_rms_cm`` (two masses each; the other mass misses by 5 cm more)."""
    best = np.asarray(best_rms_cm) / 100
    rms = np.stack([best, best + 0.05], axis=1)
    fit = HingeFit(10.0, 0.0, np.array([0.4, 0.5]), np.array([0.30, 0.40]),
                   np.array([0.31, 0.41]), "peak",
                   lattice=(10.0 ** np.arange(4), np.array([0.0, 0.01]), rms))
    return hinge_fit.HingeResult(fit)


@pytest.mark.parametrize(("best_rms_cm", "words"), [
    # 2.5 mm of the least misfit (the fit's 1 cm): rows within 1.25 cm are indistinct
    ([1.2, 1.2, 1.1, 1.0], "those from 1 to 1000 N m/rad come within the observations' 2.5 mm "
     "of the least misfit found (RMS), down to the bottom of the search, up to the top of the "
     "search: the observations cannot tell these hinges apart, and set neither a lower nor an "
     "upper limit to the hinge within the search."),
    ([1.2, 1.1, 2.0, 2.0], "those from 1 to 10 N m/rad come within the observations' 2.5 mm "
     "of the least misfit found (RMS), down to the bottom of the search: the observations "
     "cannot tell these hinges apart, and set no lower limit to the hinge within the search."),
    ([3.0, 1.2, 1.1, 2.0], "those from 10 to 100 N m/rad come within the observations' 2.5 mm of "
     "the least misfit found (RMS): the observations cannot tell these hinges apart."),
    ([3.0, 1.1, 2.0, 2.0], "only 10 N m/rad comes within the observations' 2.5 mm of the least "
     "misfit found (RMS); its neighbours (1 and 100 N m/rad) miss by more: the observations set "
     "the hinge to within that step of the search."),
    ([2.0, 2.0, 2.0, 1.1], "only 1000 N m/rad comes within the observations' 2.5 mm of the "
     "least misfit found (RMS); its neighbour (100 N m/rad) misses by more"),
    ([1.1, 2.0, 1.2, 2.0], "1, 100 N m/rad come within the observations' 2.5 mm of the least "
     "misfit found (RMS), and stiffnesses between them do not: the observations do not set the "
     "hinge to one range."),
    ([2.0, 2.0, 2.0, 2.0], "none comes within the observations' 2.5 mm of the least misfit "
     "found (RMS)."),
])
def test_how_closely_the_hinge_is_set_is_read_from_the_lattice(tmp_path, best_rms_cm, words):
    result = _hinge_on_lattice(best_rms_cm)
    report = Report("t")
    hinge_fit.render(result, report, FigureSet(tmp_path))
    text = " ".join(report.markdown().split())
    assert ("Of the search's 4 hinge stiffnesses (1 to 1000 N m/rad, each with the best of its "
            "2 tip masses), " + words) in text
    within = result.to_dict()["stiffness_within_resolution_n_m_per_rad"]
    assert within == [k for k, r in zip(10.0 ** np.arange(4), best_rms_cm, strict=True)
                      if r <= 1.25 + 1e-12]


def test_an_interval_that_widens_is_said_to_widen():
    # the estimate moves from 0 towards one half: the interval on the position widens
    text = seed_spread.repetitions_sentence({
        1: ClusteredAccuracy([0] * G, [1] * G, "position"),
        3: ClusteredAccuracy([3, 0] * 8, [3] * G, "position")})
    assert "the interval on the position widens" in text and "narrows 0." not in text


def test_the_time_frequency_sentence_names_the_positions_that_go_each_way():
    # the report's quick run: the time falls at 0.50, 0.75 and 0.80 L, not at the tip-most 0.90 L
    ratios = (0.25, 0.5, 0.75, 0.8, 0.9)
    text = time_frequency.profile_sentence(ratios, (0.713, 0.486, 0.525, 0.283, 0.305),
                                           (0.704, 0.640, 0.320, 0.160, 0.672), step=0.032)
    assert "704, 640, 320, 160 and 672 ms" in text
    # 672 ms at 0.90 L is sooner than 704, but within one 32 ms step: the tolerance is said
    assert ("sooner than at 0.25 L by more than one time step (32 ms) at 0.50 L, 0.75 L and "
            "0.80 L, not so at 0.90 L" in text)
    assert text.endswith("; one simulated brass recording per position.")
    assert "less at every later position than at 0.25 L" in text
    mixed = time_frequency.profile_sentence(ratios, (0.5, 0.6, 0.4, 0.3, 0.5), (1, 1, 1, 1, 1))
    assert "less than at 0.25 L at 0.75 L and 0.80 L, not at 0.50 L and 0.90 L" in mixed
    # no step given: the equal times are as soon, and said so without a step
    assert "as soon at every later position as at 0.25 L, which does not show" in mixed


def test_times_within_one_step_are_not_told_apart():
    told = time_frequency.profile_sentence((0.25, 0.9), (0.8, 0.4), (0.3, 0.1), step=0.032)
    near = time_frequency.profile_sentence((0.25, 0.9), (0.8, 0.4), (0.3, 0.29), step=0.032)
    assert "sooner at every later position" in told
    assert told.endswith("than at 0.25 L, as the paper describes; one simulated brass "
                         "recording per position.")
    assert "within one time step" not in told
    assert "within one time step" in near and "sooner" not in near
    # one whole step apart, as frame times give it (0.704 - 0.672 is a hair below 0.032)
    edge = time_frequency.profile_sentence((0.25, 0.9), (0.8, 0.4), (0.704, 0.672),
                                           step=float(np.median(np.diff(np.arange(5) * 0.032))))
    assert "within one time step" in edge


@pytest.mark.parametrize("k, words", [(1, "shortfall from the paper's"),
                                      (3, "the network's accuracy")])
def test_the_budget_is_said_to_close_a_shortfall_only_below_the_paper(k, words):
    up = PairedDifference(np.array([2, 1] * 8), np.full(G, 3), N, "position", resamples=200)
    run = dict(stopped_by="epoch cap", epochs=1000, max_epochs=1000, lr=0.05,
               test=_accuracy(k))
    text = ann_setup._verdict(ann_setup.AnnSetupResult({"a": run, "b": {**run, "lr": 0.5}},
                                                       1, None, up))
    assert "accounts for part of" in text and words in text
    assert ("shortfall" in text) == (k == 1)


@pytest.mark.parametrize("before, after, words", [
    (0.60, 0.70, "accounts for part of the network's shortfall"),
    (0.60, 0.85, "accounts for the network's shortfall"),
    (0.85, 0.95, "accounts for part of the network's accuracy")])
def test_the_budget_closes_the_shortfall_only_as_far_as_the_larger_step_reaches(
        before, after, words):
    """The larger step's accuracy decides how much of the shortfall the budget accounts for:
    part of it while it stays below the paper's 80.8 %, all of it (as a point estimate) once it
    reaches it."""
    text = ann_setup._budget_share(before, after)
    assert text.startswith(words)
    assert ("point estimate reaches it" in text) == (before < 0.808 <= after)


# ---------------------------------------------------------------- the chip's range
def _saturated_set(counts, materials, contacts):
    return SimpleNamespace(n_signals=len(counts), metadata={"samples_saturated": list(counts)},
                           material=np.array(materials), contact=np.array(contacts))


def test_the_saturation_sentence_reads_the_counts():
    materials, contacts = ["steel", "steel", "pvc", "brass"], [0.36, 0.39, 0.39, 0.38]
    none = data_summary.saturated_recordings(_saturated_set([0, 0, 0, 0], materials, contacts))
    assert none["recordings"] == 0 and none["contact_range_m"] is None
    assert data_summary.saturation_sentence(none) == "No recording reached the chip's range."
    some = data_summary.saturated_recordings(_saturated_set([2, 0, 0, 5], materials, contacts))
    assert some == {"recordings": 2, "samples": 7, "most": 5,
                    "by_material": {"steel": 1, "pvc": 0, "brass": 1},
                    "contact_range_m": [0.36, 0.38]}
    text = data_summary.saturation_sentence(some)
    assert text.startswith("2 recordings reached the chip's range (steel 1, brass 1; contacts "
                           "between 0.36 and 0.38 m): 7 samples in all, at most 5 in one")
    one = data_summary.saturated_recordings(_saturated_set([0, 1, 0, 0], materials, contacts))
    assert data_summary.saturation_sentence(one).startswith(
        "1 recording reached the chip's range (steel 1; contacts at 0.39 m): 1 sample in all")


def test_a_saturation_count_of_the_wrong_length_is_refused():
    short = _saturated_set([0, 1], ["a", "a", "a"], [0.1] * 3)  # two counts, three recordings
    short.n_signals = 3
    with pytest.raises(ValueError, match="samples_saturated must hold one count per recording"):
        data_summary.saturated_recordings(short)


# ---------------------------------------------------------------- the decay fits' statuses
def test_the_decay_status_sentence_reads_the_counts():
    none = signals.status_sentence({"noise_limited": 60, "not_decaying": 55, "too_few_points": 5})
    assert none.startswith("Of the 120 fits, none is usable, so the gains and time constants of "
                           "Fig. 11 are not reproduced here; noise_limited: 60")
    some = signals.status_sentence({"ok": 54, "not_decaying": 39, "too_few_points": 27})
    assert some.startswith("Of the 120 fits, 54 are usable; not_decaying: 39")
    assert "not reproduced" not in some
    # one usable fit is not a median: the section says Fig. 11 is not reproduced
    assert signals.status_sentence({"ok": 1, "noise_limited": 7999}).startswith(
        "Of the 8000 fits, only 1 is usable, so the gains and time constants of Fig. 11 are not "
        "reproduced here")
    assert signals.status_sentence({"ok": 3}) == "Of the 3 fits, 3 are usable. "


def test_each_material_s_jump_is_read_on_its_own_median_not_on_the_pooled_one(tmp_path):
    """Two materials whose dominant frequency jumps at different contacts: the median over both
    jumps in between (the median of a mixture, no curve of Fig. 9). The section reads each
    material's own median: the largest rise where that material jumps, and its own peak."""
    from ebantenna.paper.feature_table import SignalFeatures
    from ebantenna.simulate import Dataset

    grid = np.round(np.arange(0.05, 0.40, 0.05), 3)
    jumps = {"brass": 0.20, "steel": 0.30}  # each material's first contact on the upper branch
    contact = np.tile(np.repeat(grid, 3), 2)
    material = np.repeat(list(jumps), grid.size * 3)
    dominant = np.where(contact >= np.vectorize(jumps.get)(material), 300.0, 100.0) + contact
    n = contact.size
    zeros = np.zeros((n, 8), np.float32)
    ds = Dataset(zeros, zeros, material, contact, contact, np.tile([0, 1, 2], n // 3),
                 np.ones(n), np.ones(n), np.arange(n), 1000.0,
                 {"config": {"scene": {"probe": {"length": 0.4}}}})
    feats = SignalFeatures(dominant, np.zeros((n, 2)), np.ones(n), np.ones(n), np.ones(n, bool),
                           np.full(n, "ok"), np.zeros((n, 256)), np.zeros((n, 256)))
    result = signals.compute_frequency(ds, feats, tuple(jumps))
    rises = result.steps["median"]
    for m, at in jumps.items():
        below = grid[grid < at].max()
        assert rises[m][:2] == pytest.approx((below, at))
    assert result.peaks == {"brass": grid[-1], "steel": grid[-1]}
    report = Report("t")
    signals.render_frequency(result, report, FigureSet(tmp_path))
    row = next(line for line in report.markdown().splitlines() if "linear trend" in line)
    assert "steel 100.2 to 300.3 Hz at 25.0 to 30.0 cm" in row
    assert "brass 100.2 to 300.2 Hz at 15.0 to 20.0 cm" in row
    assert "highest at the last position measured, 35.0 cm" in row


@pytest.mark.parametrize("miss_cm, least_bad", [(0.1, False), (1.2, True)])
def test_the_hinge_fit_is_called_least_bad_only_when_the_model_misses(tmp_path, miss_cm,
                                                                       least_bad):
    """The fitted hinge and tip are the model's least-bad values, not estimates of the rig,
    when the model misses the observations by more than their resolution (2.5 mm)."""
    from ebantenna.fem.hinge import HingeFit
    from ebantenna.report import FigureSet, Report
    from ebantenna.study import hinge_fit

    observed = np.array([0.295, 0.395])
    fit = HingeFit(5.82, 0.001, np.array([0.40, 0.50]), observed,
                   observed + np.array([1, -1]) * miss_cm / 100, "peak")
    report = Report("t")
    hinge_fit.render(hinge_fit.HingeResult(fit), report, FigureSet(tmp_path))
    text = report.markdown()
    assert ("the least-bad values of a model that misses the observations" in text) == least_bad
    assert "hinge 5.82 N m/rad" in text
