"""Every accuracy of the study carries its test count and its Wilson interval; the repetitions
over split seeds are what they say."""

import json

import numpy as np
import pytest

from ebantenna.ml.metrics import accuracy_interval
from ebantenna.paper.controls import ABLATION_DESIGN
from ebantenna.paper.uncertainty import resolvable_difference
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


def _check(value, n, ci, where):
    """A count ``k`` out of ``n``, and the Wilson interval of ``k / n`` (to its four decimals)."""
    k = round(value * n)
    assert abs(value * n - k) < 1e-6, where  # an accuracy is k / n
    lo, hi = accuracy_interval(k, n)
    # summary.json rounds the ends to 4 decimals: within half a unit of the 4th
    assert ci == pytest.approx([lo, hi], abs=5e-5), where
    assert ci[0] - 5e-5 <= value <= ci[1] + 5e-5, where


def test_every_accuracy_in_the_summary_has_its_count_and_interval(quick_study):
    result, _ = quick_study
    summary = json.loads((result.out_dir / "summary.json").read_text())
    found = 0
    for where, name, value, parent in _accuracies(summary):
        if value is None:
            continue
        n, ci = parent[f"{name}_n_test"], parent[f"{name}_ci95"]
        if isinstance(value, dict):
            assert set(n) == set(value) == set(ci), where
            for key in value:
                _check(value[key], n[key], ci[key], f"{where}/{key}")
                found += 1
        else:
            _check(value, n, ci, where)
            found += 1
    assert found > 40  # every section's accuracies, not a few


def test_seed_spreads_hold_the_seed_zero_value_and_their_own_statistics(quick_study):
    result, _ = quick_study
    m = result.summary["materials"]
    spreads = [m["ablation_seed_spread"][k] for k in m["ablation"]]
    spreads += [m["seed_spread"][c][k] for c in CLASSIFIERS for k in ("random", "grouped")]
    for k, a in m["ablation"].items():
        assert m["ablation_seed_spread"][k]["values"][0] == a
        assert m["ablation_seed_spread"][k]["n_test"][0] == m["ablation_n_test"][k]
    for s in spreads:
        values = np.array(s["values"])
        assert len(set(s["seeds"])) == len(s["seeds"]) >= 5
        assert s["mean"] == pytest.approx(values.mean(), rel=1e-12)
        assert s["std"] == pytest.approx(values.std(ddof=1), rel=1e-12, abs=1e-15)
        for a, n, ci in zip(values, s["n_test"], s["ci95"], strict=True):
            _check(a, n, ci, "spread")


def test_five_grouped_seeds_hold_out_every_recording_once(quick_study):
    """The controls' split seeds draw different offsets: the five test sets are the five folds."""
    result, _ = quick_study
    m = result.summary["materials"]
    for s in m["ablation_seed_spread"].values():
        assert sum(s["n_test"]) == m["controls_design"]["recordings"]


def test_the_controls_design_resolves_a_ten_point_change():
    """Two accuracies on the controls' grouped test set, whatever they are (the variance is
    largest at 0.5), differ by two standard deviations of their difference at < 10 points."""
    positions = ABLATION_DESIGN.contacts(builtin_scene("paper").probe.length)
    held = len(positions) // 5  # the fewest positions any offset holds out
    n_test = held * len(ABLATION_DESIGN.materials) * ABLATION_DESIGN.repetitions
    assert resolvable_difference(0.5, n_test) < 0.10


def test_ann_runs_say_why_they_stopped(quick_study):
    result, _ = quick_study
    runs = result.summary["materials"]["ann_training_setup"]
    for name, (lr, epochs) in ann_setup.RUNS.items():
        r = runs[name]
        assert (r["lr"], r["max_epochs"]) == (lr, epochs)
        assert 1 <= r["epochs"] <= epochs
        assert (r["stopped_by"] == "epoch cap") == (r["epochs"] == epochs)


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
