"""Every accuracy of the study carries its unit of replication, the interval on it and its
method; every control is paired; the repetitions over folds are what they say."""

import json

import numpy as np
import pytest

from ebantenna.ml.metrics import accuracy_interval
from ebantenna.simulate import builtin_scene
from ebantenna.study import ann_setup, rod_geometry
from ebantenna.study.seed_spread import CLASSIFIERS


def _accuracies(node, path=""):
    """Every (path, name, value, parent) whose name ends in 'accuracy', and the by-name dicts
    ``materials.ann`` and ``materials.ablation``, anywhere in the summary."""
    if isinstance(node, dict):
        for k, v in node.items():
            here = f"{path}/{k}"
            if k.endswith("accuracy") or here in ("/materials/ann", "/materials/ablation"):
                yield here, k, v, node
            yield from _accuracies(v, here)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _accuracies(v, f"{path}[{i}]")


def _training(name: str) -> bool:
    return name.endswith("train_accuracy") or name == "all_accuracy"


def _check(value, n, ci, recording, unit, units, method, where):
    """A count ``k`` out of ``n``; the recording-level interval is Wilson's of ``k / n``; the
    interval on the unit holds the estimate and names its unit and method."""
    assert isinstance(unit, str) and unit and isinstance(method, str) and unit in method, where
    assert 1 <= units <= n, where
    if "folds" not in method:  # a pooled count (the blocked split's estimate is a fold mean)
        k = round(value * n)
        assert abs(value * n - k) < 1e-6, where
        assert recording == pytest.approx(list(accuracy_interval(k, n)), abs=1e-12), where
        # the design effect is at least one: never narrower than counting recordings
        assert ci[1] - ci[0] >= (recording[1] - recording[0]) * (1 - 1e-12), where
    assert ci[0] - 1e-12 <= value <= ci[1] + 1e-12, where


def test_every_accuracy_in_the_summary_has_its_unit_and_interval(quick_study):
    result, _ = quick_study
    summary = json.loads((result.out_dir / "summary.json").read_text())
    found = trained = 0
    for where, name, value, parent in _accuracies(summary):
        if value is None or where.endswith("_curve"):
            continue
        if _training(name):
            assert f"{name}_n_train" in parent and f"{name}_ci95" not in parent, where
            trained += 1
            continue
        keys = ("_n_test", "_ci95", "_recording_ci95", "_unit", "_n_units", "_method")
        fields = [parent[f"{name}{s}"] for s in keys]
        if isinstance(value, dict):
            assert all(set(f) == set(value) for f in fields), where
            for key in value:
                _check(value[key], *(f[key] for f in fields), f"{where}/{key}")
                found += 1
        else:
            _check(value, *fields, where)
            found += 1
    assert found > 40 and trained >= 4  # every section's accuracies, not a few


def test_every_control_is_paired_with_its_verdict_and_detectable_difference(quick_study):
    result, _ = quick_study
    m = result.summary["materials"]
    paired = m["controls_paired"]
    assert {f"ablation:{k}" for k in m["ablation"] if k != "none"} <= set(paired)
    assert {"mid_height", "friction", "contact_law"} <= set(paired)
    for name, p in paired.items():
        lo, hi = p["ci95"]
        assert lo <= p["difference"] <= hi, name
        assert p["resolved"] == (lo > 0 or hi < 0), name
        assert p["direction"] == ("unresolved" if not p["resolved"]
                                  else "higher" if p["difference"] > 0 else "lower"), name
        # positive even when the change left every count as it was (a sensor effect that the
        # features do not see): a change must bring changed recordings to be resolved
        assert p["detectable_difference_80"] > 0, name
        assert p["unit"] == "position", name
        assert p["difference"] == pytest.approx(p["estimate"] - p["reference_estimate"],
                                                abs=1e-12), name


def test_seed_spreads_hold_their_own_statistics(quick_study):
    result, _ = quick_study
    m = result.summary["materials"]
    for k, a in m["ablation"].items():
        s = m["ablation_seed_spread"][k]
        values = np.array(s["values"])
        assert len(set(s["seeds"])) == len(s["seeds"]) >= 5
        assert s["mean"] == pytest.approx(values.mean(), rel=1e-12)
        assert s["std"] == pytest.approx(values.std(ddof=1), rel=1e-12, abs=1e-15)
        # every recording tested once over the folds: the pooled estimate is the weighted mean
        assert a == pytest.approx(np.average(values, weights=s["n_test"]), rel=1e-12)
    for c in CLASSIFIERS:
        for kind in ("random", "grouped", "blocked"):
            f = m["seed_spread"][c][kind]
            assert len(f["accuracy_folds"]) == 5
            assert f["accuracy_fold_std"] == pytest.approx(
                np.std(f["accuracy_folds"], ddof=1), rel=1e-12, abs=1e-15)


def test_five_grouped_seeds_hold_out_every_recording_once(quick_study):
    """The controls' split seeds draw different offsets: the five test sets are the five folds."""
    result, _ = quick_study
    m = result.summary["materials"]
    for s in m["ablation_seed_spread"].values():
        assert sum(s["n_test"]) == m["controls_design"]["recordings"]


def test_ann_runs_say_why_they_stopped(quick_study):
    result, _ = quick_study
    runs = result.summary["materials"]["ann_training_setup"]
    for name, (lr, epochs) in ann_setup.RUNS.items():
        r = runs[name]
        assert (r["lr"], r["max_epochs"]) == (lr, epochs)
        assert 1 <= r["epochs"] <= epochs
        assert (r["stopped_by"] == "epoch cap") == (r["epochs"] == epochs)
        assert r["stopped_by"] in ("epoch cap", "validation")
    main = result.summary["ann"]
    assert (main["stopped_by"] == "epoch cap") == (main["epochs"] == main["max_epochs"])
    long = runs["long_run"]
    assert long["epochs"][-1] <= long["max_epochs"] <= ann_setup.LONG_RUN["epochs"]
    reached = long["reached_paper_test_epoch"]
    assert (reached is None) == (max(long["test_accuracy_curve"]) < long["paper_value"])
    assert (long["stopped_by"] == "epoch cap") == (reached is None)


def test_rod_geometry_varies_diameter_and_length_three_ways(quick_study):
    result, _ = quick_study
    rows = result.summary["materials"]["rod_geometry"]
    scene = builtin_scene("paper").effect("object_modes")
    d0, l0 = 1e3 * scene.diameter, 1e3 * scene.free_length
    diameters = {round(r["diameter_mm"], 3) for r in rows if r["free_length_mm"] == l0}
    lengths = {round(r["free_length_mm"], 3) for r in rows if r["diameter_mm"] == d0}
    assert len(diameters) >= 3 and len(lengths) >= 3
    for r in rows:
        assert r["second_mode_gap_hz"] >= 0
        assert len(set(r["closest_materials"])) == 2
    assert "How much the accuracies owe to the assumed rod" in result.report_markdown.read_text()


def test_closest_materials_is_the_smallest_pairwise_gap():
    """The returned gap is no larger than the gap of any other pair (recomputed here)."""
    from itertools import combinations

    from ebantenna.fem.coupled_sweep import coupled_sweep
    from ebantenna.probe import material

    scene = builtin_scene("paper")
    a, b, gap = rod_geometry.closest_materials(scene, 0.012, 0.25, ("brass", "wood", "steel"))
    effect = scene.effect("object_modes")
    rods = [effect.rod(material(n)) for n in ("brass", "wood", "steel")]
    k = [effect.contact_stiffness(r.material, scene.probe) for r in rods]
    f = coupled_sweep(scene.probe, rods, rod_geometry.GAP_POSITIONS * scene.probe.length,
                      np.array(k), hinge=scene.hinge, n_modes=2).frequencies[:, :, 1]
    gaps = [np.median(np.abs(f[i] - f[j])) for i, j in combinations(range(3), 2)]
    assert gap == pytest.approx(min(gaps), rel=1e-12)
    assert {a, b} <= {"brass", "wood", "steel"}


def test_the_held_out_distance_holds_out_every_region_position_once():
    """Every recording of the linear region is tested exactly once, in the fold that holds its
    position out; the pooled errors are those of the folds' own networks."""
    from ebantenna.paper import experiments
    from ebantenna.paper.splits import split_folds
    from ebantenna.study.material_splits import _pooled_distance, _region_folds

    d = np.repeat(np.linspace(0.02, 0.38, 19), 3)
    y = np.tile(["brass", "steel", "pvc"], 19)
    X = np.column_stack([np.cos(8 * d), np.sin(8 * d)])
    X = X + np.random.default_rng(0).normal(0, 0.01, X.shape)
    folds = _region_folds(split_folds("grouped", y, d, seed=0), d, 0.4)
    pooled = _pooled_distance([experiments.regress_distance_linear_region(
        X, d, probe_length=0.4, seed=0, split=f) for f in folds])
    region = d[d <= 0.8 * 0.4]
    assert np.array_equal(np.sort(pooled.distance_test), np.sort(region))
    assert np.array_equal(pooled.positions, np.unique(region))
    train, test = split_folds("grouped", y, d, seed=0)[1]
    one = experiments.regress_distance_linear_region(X, d, probe_length=0.4, seed=0,
                                                     split=(train, test))
    at = np.isin(pooled.distance_test, one.distance_test)
    # the same network on the same rows: its predictions, bit for bit
    assert np.array_equal(np.sort(pooled.predicted_test[at]), np.sort(one.predicted_test))


def test_fits_in_parallel_are_the_fits_in_turn():
    """Worker processes change where a fit runs, not its numbers: the SVM's decision values
    and the network's predictions are bit for bit those of the calls made in turn."""
    from ebantenna.paper import experiments
    from ebantenna.paper.splits import split_folds
    from ebantenna.study._common import fits_in_parallel

    rng = np.random.default_rng(1)
    d = np.repeat(np.linspace(0.02, 0.38, 10), 6)
    y = np.tile(["brass", "steel", "pvc"], 20)
    X = rng.normal(size=(60, 6)) + (y[:, None] == "steel")
    calls = [(experiments.classify_materials_svm, (X, y), {"split": f, "gamma": "scale"})
             for f in split_folds("grouped", y, d, seed=0)[:2]]
    calls.append((experiments.regress_distance_linear_region, (X, d),
                  {"probe_length": 0.4, "max_iter": 50}))
    turn, pool = fits_in_parallel(calls, 1), fits_in_parallel(calls, 2)
    for a, b in zip(turn[:2], pool[:2], strict=True):
        assert np.array_equal(a.model.decision_function(X), b.model.decision_function(X))
        assert np.array_equal(a.confusions["test"], b.confusions["test"])
    assert np.array_equal(turn[2].predicted_test, pool[2].predicted_test)


def _without_times(entry):
    """A summary's entry as JSON holds it, its fit times left out."""
    entry = json.loads(json.dumps(entry))
    if isinstance(entry, dict):
        return {k: _without_times(v) for k, v in entry.items() if k != "fit_seconds"}
    return entry


def test_the_learning_steps_give_the_same_numbers_on_two_workers(quick_study):
    """The study's 'ml' and 'ann setup' steps fit on worker processes, the setup's networks in
    the ml step's pool, the paper network's run taken from the ml step: each step computed
    alone on two workers (the setup training that run itself) gives the numbers the quick
    study reported from its fits made in turn (one worker)."""
    from ebantenna.paper.data import build_paper_dataset
    from ebantenna.paper.feature_table import signal_features
    from ebantenna.study import learning

    study, cache = quick_study
    summary = _without_times(study.summary)
    ds = build_paper_dataset(cache, seed=0, quick=True, n_jobs=1, show_progress=False)
    feats = signal_features(ds.ax, ds.az, ds.fs, n_jobs=1, show_progress=False)
    learnt = learning.compute(ds, feats, 0, n_jobs=2)
    assert _without_times(learnt.to_dict()) == {k: summary[k] for k in ("svm", "ann")}
    distance = _without_times(learnt.distance_dict())
    assert distance == {k: summary["distance"][k] for k in distance}
    setup = _without_times(ann_setup.compute(ds, feats, 0, quick=True, n_jobs=2).to_dict())
    assert setup == {k: summary["materials"][k] for k in setup}


def _regression(seed, positions=15):
    """A real distance network's result on a small synthetic problem (the docstring's)."""
    from ebantenna.paper.experiments import regress_distance_full_length

    d = np.repeat(np.linspace(0.02, 0.30, positions), 8)
    X = np.column_stack([np.cos(8 * d), np.sin(8 * d)])
    X = X + np.random.default_rng(seed).normal(0, 0.01, X.shape)
    return regress_distance_full_length(X, d, max_iter=60, seed=seed)


def test_a_network_run_carries_the_spread_its_interval_over_positions_allows():
    # witness: the study's own interval over the test positions (mae_entry, a t interval on the
    # positions' mean errors); its half-width is the standard error times Student's quantile
    from scipy.stats import t

    from ebantenna.study._common import mae_entry
    from ebantenna.study.seed_spread import NetworkRuns

    results = [_regression(s) for s in (0, 1, 2)]
    runs = NetworkRuns.from_results((0, 1, 2), results)
    for r, mae, se in zip(results, runs.mae_cm, runs.se_cm, strict=True):
        e = mae_entry(r.errors_cm, r.distance_test)
        lo, hi = e["mae_cm_ci95"]
        # both are a few sums over at most 15 positions: rounding far below 1e-12
        assert mae == pytest.approx(e["mae_cm_estimate"], rel=1e-12)
        assert (hi - lo) / 2 == pytest.approx(se * t.ppf(0.975, e["mae_cm_n_units"] - 1),
                                              rel=1e-12)
    assert runs.spread == pytest.approx(np.std(runs.mae_cm, ddof=1), rel=1e-12)
    assert runs.interval_std == pytest.approx(np.sqrt(np.mean(runs.se_cm ** 2)), rel=1e-12)
    d = runs.to_dict()
    assert d["spread_ratio"] == pytest.approx(runs.spread / runs.interval_std, rel=1e-12)
    lo, hi = d["spread_ratio_ci95"]
    assert lo < d["spread_ratio"] < hi
    json.dumps(d, allow_nan=False)


def test_a_run_that_tests_one_position_has_no_interval_and_no_ratio():
    from ebantenna.paper.experiments import RegressionResult
    from ebantenna.study import seed_spread

    one = RegressionResult("one", np.full(4, 0.1), np.full(4, 0.12), np.array([0.1]),
                           np.array([2.0]), 0.0)
    runs = seed_spread.NetworkRuns.from_results((0, 1), [one, _regression(1)])
    assert np.isnan(runs.se_cm[0]) and runs.ratio is None
    d = runs.to_dict()
    assert d["se_cm"][0] is None and d["interval_std_cm"] is None
    assert d["spread_ratio"] is None and d["spread_ratio_ci95"] is None
    json.dumps(d, allow_nan=False)
    assert seed_spread.runs_sentence({"x": runs}) == ""


@pytest.mark.parametrize("maes, se, words", [
    ([2.0, 3.0, 2.5, 4.0, 2.2], 0.1, "scatters more than one run's interval"),
    ([2.0, 2.001, 2.002, 1.999, 2.0], 1.0, "scatter less than one run's interval"),
    ([2.0, 2.2, 2.1, 1.9, 2.0], 0.15, "the runs' spread is within what one run's interval"),
])
def test_the_runs_sentence_follows_the_ratio_and_its_interval(maes, se, words):
    from ebantenna.study.seed_spread import NetworkRuns, ratio_interval, runs_sentence

    runs = NetworkRuns((0, 1, 2, 3, 4), np.array(maes), np.full(5, se))
    lo, hi = ratio_interval(runs.ratio, 5)
    text = runs_sentence({"a": runs})
    assert words in text
    assert ("scatters more than" in text) == (lo > 1)
    assert ("scatter less than" in text) == (hi < 1)


def test_two_networks_on_either_side_are_both_named():
    from ebantenna.study.seed_spread import NetworkRuns, runs_sentence

    wide = NetworkRuns((0, 1, 2, 3, 4), np.array([2.0, 3.0, 2.5, 4.0, 2.2]), np.full(5, 0.1))
    open_ = NetworkRuns((0, 1, 2, 3, 4), np.array([2.0, 2.2, 2.1, 1.9, 2.0]), np.full(5, 0.15))
    text = runs_sentence({"full-length": wide, "linear-region": open_})
    assert text.startswith("Trained again, the full-length network scatters more")
    assert "; for the linear-region network the runs' spread is within" in text


def test_the_distance_networks_trained_again_hold_their_own_statistics(quick_study):
    from ebantenna.study.seed_spread import NETWORK_RUNS, NETWORKS

    result, _ = quick_study
    runs = result.summary["materials"]["distance_network_runs"]
    assert set(runs) == set(NETWORKS)
    for r in runs.values():
        assert r["seeds"] == list(range(result.summary["seed"],
                                        result.summary["seed"] + NETWORK_RUNS))
        assert len(r["mae_cm"]) == len(r["se_cm"]) == NETWORK_RUNS
        assert r["runs_std_cm"] == pytest.approx(np.std(r["mae_cm"], ddof=1), rel=1e-12)
    md = result.report_markdown.read_text()
    assert f"the two distance networks trained again from {NETWORK_RUNS} seeds" in md
