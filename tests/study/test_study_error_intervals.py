"""The error columns that had no interval (the full range's mean error beyond the region and
95th percentile, the distance networks' RMS) carry one on the test position, witnessed against
independent computations; and the sentences that typed a design's numbers or a model's property
read them from the data set or the model, and flip with them."""

import math

import numpy as np
import pytest
from scipy.stats import t as student_t

from ebantenna.fem.coupling import Rod
from ebantenna.paper.uncertainty import ClusteredAccuracy
from ebantenna.report import FigureSet, Report
from ebantenna.simulate.effects import ObjectModes
from ebantenna.study import full_range, material_splits, physics_controls, signals
from ebantenna.study._common import (
    BOOTSTRAP_MIN_UNITS,
    BOOTSTRAP_RESAMPLES,
    BOOTSTRAP_SEED,
    ERROR_STATISTICS,
    error_entry,
    format_error,
    format_mae,
    position_bootstrap,
)

RNG = np.random.default_rng(7)
#: 12 test positions of 1 to 6 recordings each, errors that differ between positions more than
#: within one (the design that makes the recording-level count too large)
POSITIONS = np.repeat(np.arange(12) * 0.01, RNG.integers(1, 7, 12))
ERRORS = np.abs(RNG.normal(0, 1, np.unique(POSITIONS).size))[
    np.unique(POSITIONS, return_inverse=True)[1].ravel()] + np.abs(
    RNG.normal(0, 0.1, POSITIONS.size))


def _brute_force(values, clusters, statistic, resamples, seed):
    """The cluster bootstrap written out: the same draws, each resample gathered position by
    position into a Python list."""
    labels = sorted(set(clusters.tolist()))
    draws = np.random.default_rng(seed).integers(0, len(labels), size=(resamples, len(labels)))
    stats = []
    for row in draws:
        drawn = []
        for i in row:
            drawn.extend(values[clusters == labels[i]].tolist())
        stats.append(statistic(np.array(drawn)))
    return tuple(np.quantile(stats, [0.025, 0.975]))


@pytest.mark.parametrize("name", sorted(ERROR_STATISTICS))
def test_the_position_bootstrap_is_the_brute_force_one(name):
    f = ERROR_STATISTICS[name]
    got = position_bootstrap(ERRORS, POSITIONS, f, resamples=400, seed=3)
    want = _brute_force(ERRORS, POSITIONS, f, 400, 3)
    # the same multisets; only the order of a sum differs (RMS): a few ulps of the values
    np.testing.assert_allclose(got, want, rtol=1e-12)


def test_one_recording_per_position_is_the_ordinary_bootstrap():
    e = np.abs(RNG.normal(1, 0.5, 30))
    pick = np.random.default_rng(5).integers(0, e.size, size=(500, e.size))
    want = np.quantile(np.percentile(e[pick], 95, axis=1), [0.025, 0.975])
    got = position_bootstrap(e, np.arange(e.size), ERROR_STATISTICS["p95"], resamples=500,
                             seed=5)
    np.testing.assert_allclose(got, want, rtol=1e-12)  # identical draws, vectorised


def test_near_copies_do_not_narrow_the_rms_interval():
    # every recording repeated five times at its position: the same RMS in every resample (each
    # position's weight scales alike), so the same interval; a recording-level bootstrap would
    # narrow by about sqrt(5)
    copies = np.repeat(ERRORS, 5)
    at = np.repeat(POSITIONS, 5)
    f = ERROR_STATISTICS["rms"]
    np.testing.assert_allclose(position_bootstrap(copies, at, f, resamples=300),
                               position_bootstrap(ERRORS, POSITIONS, f, resamples=300),
                               rtol=1e-12)


def test_an_error_entry_names_its_unit_and_method():
    e = error_entry(ERRORS, POSITIONS, "rms")
    assert e["rms_cm"] == pytest.approx(math.sqrt(np.mean(ERRORS**2)), rel=1e-12)
    assert e["rms_cm_n_units"] == 12 and e["rms_cm_n_test"] == ERRORS.size
    assert e["rms_cm_ci95"] == list(position_bootstrap(ERRORS, POSITIONS,
                                                       ERROR_STATISTICS["rms"]))
    assert "12 test positions" in e["rms_cm_method"]
    assert f"{BOOTSTRAP_RESAMPLES} resamples, seed {BOOTSTRAP_SEED}" in e["rms_cm_method"]
    one = error_entry([1.0, 2.0], [0.1, 0.1], "p95")
    assert one["p95_cm_ci95"] is None and format_error(one, "p95").endswith("no interval)")


@pytest.mark.parametrize("bad, error", [
    (dict(statistic="median"), ValueError), (dict(errors_cm=[1.0, 2.0]), ValueError)])
def test_bad_error_entries_are_refused(bad, error):
    args = dict(errors_cm=ERRORS, positions=POSITIONS, statistic="rms") | bad
    with pytest.raises(error):
        error_entry(**args)


def test_fewer_positions_than_a_95_percent_interval_needs_give_their_range():
    # A bootstrap over G positions stays inside the range of their values; that range misses
    # the median whenever all G draws fall on one side, probability 2 * 2**-G. The fewest G for
    # which it holds 95 % is BOOTSTRAP_MIN_UNITS; a simulation of the range agrees with it.
    coverage = {g: 1 - 2.0 ** (1 - g) for g in range(2, 9)}
    assert min(g for g, c in coverage.items() if c >= 0.95) == BOOTSTRAP_MIN_UNITS
    draws = np.random.default_rng(0).normal(size=(20000, 5))  # median 0; G = 5
    held = np.mean((draws.min(axis=1) < 0) & (draws.max(axis=1) > 0))
    # 20000 draws: binomial sd sqrt(c(1-c)/n) = 0.0017; four of them bound the check
    assert abs(held - coverage[5]) < 4 * np.sqrt(coverage[5] * (1 - coverage[5]) / 20000)
    errors, at = ERRORS[POSITIONS < 0.05], POSITIONS[POSITIONS < 0.05]  # five positions
    e = error_entry(errors, at, "rms")
    own = [np.sqrt(np.mean(errors[at == p] ** 2)) for p in np.unique(at)]
    assert e["rms_cm_ci95"] is None and e["rms_cm_range"] == [min(own), max(own)]
    assert "5 positions, too few for a 95 % interval" in format_error(e, "rms")
    six = POSITIONS < 0.06
    assert error_entry(ERRORS[six], POSITIONS[six], "rms")["rms_cm_ci95"] is not None


def test_position_bootstrap_refuses_what_it_cannot_resample():
    f = ERROR_STATISTICS["rms"]
    with pytest.raises(ValueError, match="two distinct"):
        position_bootstrap([1.0, 2.0], [0, 0], f)
    with pytest.raises(ValueError, match="finite"):
        position_bootstrap([1.0, np.nan], [0, 1], f)
    with pytest.raises(TypeError, match="statistic"):
        position_bootstrap([1.0, 2.0], [0, 1], "rms")
    with pytest.raises(ValueError, match="level"):
        position_bootstrap([1.0, 2.0], [0, 1], f, level=1.0)


# ----------------------------------------------------------------- the full range's columns
def _full_range(region=0.5):
    grid = np.linspace(0.02, 0.38, 10)
    contact = np.repeat(grid, 3)
    e = np.abs(np.random.default_rng(1).normal(1, 0.4, contact.size))
    return full_range.FullRangeResult(
        length=0.4, region=region, contact_two=contact, error_two_cm=e, contact_one=contact,
        error_one_cm=2 * e, error_known_material_cm=0.5 * e, error_joint_cm=1.5 * e,
        joint_material_accuracy=0.5, turning_point=0.3, without_two_peaks=0,
        recordings=contact.size,
        joint_material=ClusteredAccuracy.from_recordings(np.arange(contact.size) % 2 == 0,
                                                         contact, "position"),
        chance=0.2)


def test_the_mean_error_beyond_the_region_is_a_t_interval_over_its_positions():
    r = _full_range()
    d = r.to_dict()
    beyond = r.contact_two > r.region * r.length
    entry = d["full_range_beyond_80"]
    assert entry["mae_cm"] == d["full_range_mae_beyond_80_cm"]  # the stored value, unchanged
    means = [r.error_two_cm[r.contact_two == p].mean() for p in np.unique(r.contact_two[beyond])]
    half = student_t.ppf(0.975, len(means) - 1) * np.std(means, ddof=1) / math.sqrt(len(means))
    np.testing.assert_allclose(entry["mae_cm_ci95"], [np.mean(means) - half,
                                                      np.mean(means) + half], rtol=1e-12)
    assert entry["mae_cm_n_units"] == len(means)
    for key in ("first_mode_only", "full_range", "full_range_known_material",
                "full_range_joint"):
        assert d[f"{key}_p95"]["p95_cm_n_units"] == 10


def test_no_contact_beyond_the_region_gives_no_entry():
    d = _full_range(region=1.0).to_dict()
    assert d["full_range_beyond_80"] is None and d["full_range_mae_beyond_80_cm"] is None


def test_the_table_prints_what_the_summary_holds(tmp_path):
    r = _full_range()
    report = Report("t")
    full_range.render(r, report, FigureSet(tmp_path))
    text = report.markdown()
    d = r.to_dict()
    assert format_error(d["full_range_p95"], "p95") in text
    assert format_mae(d["first_mode_only_beyond_80"]) in text
    assert "95th percentile (cm, 95 % CI: bootstrap over the test positions)" in text


# ----------------------------------------------------------------- the random split's design
def test_the_design_facts_are_read_from_the_rows():
    materials = np.array(["a", "b"] * 12)
    positions = np.repeat([0.1, 0.15, 0.2, 0.25], 6)
    facts = material_splits._design_facts(materials, positions, [0, 1, 6, 7])
    assert facts["repetitions"] == [3, 3]
    assert facts["spacing_m"] == pytest.approx(0.05)
    assert facts["copies_in_training"] == 1.0  # each test row's material and position recur
    alone = material_splits._design_facts(["a", "a"], [0.1, 0.2], [0])
    assert alone["repetitions"] == [1, 1] and alone["copies_in_training"] == 0.0


@pytest.mark.parametrize("reps, step, words, not_words", [
    ([3, 3], 0.05, ["3 at a time", "5 cm apart", "near copy"], ["25 at a time", "5 mm"]),
    ([25, 25], 0.005, ["25 at a time", "5 mm apart", "near copy"], ["3 at a time"]),
    ([1, 1], 0.005, ["1 at a time", "no other repetition"], ["near copy"]),
])
def test_the_random_split_sentence_reads_the_design(reps, step, words, not_words):
    text = material_splits._copies_text({"repetitions": reps, "spacing_m": step,
                                         "copies_in_training": 0.0 if reps[1] < 2 else 0.88})
    assert all(w in text for w in words), text
    assert not any(w in text for w in not_words), text


# ----------------------------------------------------------------- the rod's contact height
@pytest.mark.parametrize("name", ["steel", "pvc", "wood"])
def test_the_rods_static_compliance_is_the_cantilevers(name):
    # cubic Hermite beam elements are exact for a static point load: h^3 / (3 EI) at the
    # load, to the rounding of a 50-unknown solve
    effect = ObjectModes()
    c = physics_controls._contact_compliance(effect, name)
    ei = Rod(name, effect.diameter, effect.free_length).as_beam().flexural_rigidity
    for where in ("free_end", "mid_height"):
        h = c[where]["height_m"]
        assert c[where]["static_m_per_n"] == pytest.approx(h**3 / (3 * ei), rel=1e-9)
        # one mode's share of the static compliance: positive, and not more than all of it
        assert 0 < c[where]["first_mode_m_per_n"] <= c[where]["static_m_per_n"] * (1 + 1e-9)


def test_the_height_sentence_follows_the_compliances():
    end = {"height_m": 0.25, "static_m_per_n": 8.0, "first_mode_m_per_n": 7.0}
    mid = {"height_m": 0.125, "static_m_per_n": 1.0, "first_mode_m_per_n": 0.8}
    text = physics_controls._height_text({"a": {"free_end": end, "mid_height": mid}})
    assert "the free end is the softer" in text and "8 times" in text
    assert "moves the contact more at the free end" in text
    flipped = physics_controls._height_text({"a": {"free_end": mid, "mid_height": end}})
    assert "halfway up is the softer" in flipped and "more at halfway up" in flipped
    mixed = physics_controls._height_text({"a": {"free_end": end, "mid_height": mid},
                                           "b": {"free_end": mid, "mid_height": end}})
    assert "neither contact point is the softer" in mixed


def test_the_repetitions_clause_reads_both_designs():
    assert "3 repetitions of each material, against 25" in physics_controls._repetitions_text(
        (3, 25))
    assert "as many repetitions" in physics_controls._repetitions_text((3, 3))


# ----------------------------------------------------------------- gravity on the Z axis
@pytest.mark.parametrize("z, words, not_words", [
    (9.79, "carries a static 9.79 m/s^2 (1.00 g", "no static acceleration"),
    (-9.81, "carries a static -9.81 m/s^2 (1.00 g", "no static acceleration"),
    (0.03, "no static acceleration of the order of gravity", "carries a static"),
])
def test_the_resultant_sentence_reads_the_z_axis(z, words, not_words):
    text = signals._resultant_text(z)
    assert words in text and not_words not in text


# ----------------------------------------------------------------- the quick study
def test_the_quick_study_stores_and_prints_the_new_intervals(quick_study):
    import json

    result, _ = quick_study
    s = json.loads((result.out_dir / "summary.json").read_text())
    d = s["distance"]
    for key in ("first_mode_only_p95", "full_range_p95", "full_range_known_material_p95",
                "full_range_joint_p95"):
        entry = d[key]
        if entry["p95_cm_n_units"] >= BOOTSTRAP_MIN_UNITS:
            assert entry["p95_cm_method"].startswith("percentile interval of a bootstrap")
        else:  # the quick design tests 4 positions: a bootstrap over them cannot hold 95 %
            assert entry["p95_cm_ci95"] is None and "too few for a 95 % interval" in (
                entry["p95_cm_method"])
            lo, hi = entry["p95_cm_range"]
            assert lo <= entry["p95_cm"] <= hi
    rms = d["linear_region_rms_by_trainer"]
    assert set(rms) == set(d["linear_region_mae_cm_by_trainer"])
    design = s["materials"]["random_split_design"]
    assert design["repetitions"] == [3, 3] and design["spacing_m"] == pytest.approx(0.05)
    assert s["frequency"]["z_axis_static_m_s2"] == pytest.approx(9.8, abs=0.2)  # the gravity
    text = (result.out_dir / "report.md").read_text()
    assert "come 3 at a time" in text and "25 at a time" not in text
    assert "5 cm apart" in text
    compliance = s["materials"]["mid_height_contact_compliance"]
    assert all(c["free_end"]["static_m_per_n"] > c["mid_height"]["static_m_per_n"]
               for c in compliance.values())
    assert "the free end is the softer of the two contact points" in text
