"""The main job end to end on the quick data set, its report and its JSON summary."""

import dataclasses
import json

import numpy as np
import pytest

from ebantenna._validate import more_jobs_allowed
from ebantenna.cli import main
from ebantenna.paper.feature_table import mode_peaks, signal_features
from ebantenna.report import Report
from ebantenna.study.reproduce import STEPS


def test_quick_study_writes_every_figure_and_both_reports(quick_study):
    result, _ = quick_study
    expected = {
        "fig16_zones", "fig17_mode_shapes", "fig09_10_dominant_frequency",
        "fig11_gain_time_constant", "fig12_ann_confusion", "fig15_svm_confusion",
        "fig13_14_distance_networks", "beyond_full_range_distance", "fig18_19_time_frequency",
        "beyond_mode_curves",
    }
    assert set(result.figures) == expected
    for path in result.figures.values():
        assert path.stat().st_size > 5_000 and path.read_bytes()[:4] == b"\x89PNG"
    md = result.report_markdown.read_text()
    page = result.report_html.read_text()
    for name in expected:
        assert f"{name}.png" in md and f"{name}.png" in page
    # the paper's numbers stand beside the reproduction's
    assert "99.2 %" in md and "80.8 %" in md and "0.80 L" in md
    assert md.count("| K1 |") >= 1 and "common factor" in page


def test_summary_holds_the_contract_numbers(quick_study):
    result, _ = quick_study
    s = json.loads((result.out_dir / "summary.json").read_text())
    for key in ("svm", "ann"):
        assert 0.0 <= s[key]["test_accuracy"] <= 1.0
    assert s["distance"]["full_range_mae_cm"] > 0
    assert s["dataset"]["signals"] == 120 and s["modes"]["errata"] > 0
    # the zones are where the mode shapes put them: transition before the tip, after mid-probe
    assert 0.5 < s["modes"]["zone2_start_ratio"] < s["modes"]["zone3_start_ratio"] < 1.0


def test_a_second_run_reuses_the_cached_data_set(quick_study, tmp_path, capsys):
    result, cache = quick_study
    files = sorted(p.name for p in cache.iterdir())
    # the run-time paragraph counts the controls' and the contact law's data sets as they lie in
    # the cache (the rod's geometry counted apart)
    controls = sum("controls" in name and "-rod-" not in name for name in files)
    text = f"the controls and the contact law rebuild {controls} small data sets"
    assert text in result.report_markdown.read_text()
    code = main(["reproduce", "--quick", "--out", str(tmp_path), "--cache", str(cache),
                 "--jobs", "1", "--json"])
    assert code == 0
    printed = json.loads(capsys.readouterr().out)  # stdout is exactly one JSON object
    assert sorted(p.name for p in cache.iterdir()) == files
    assert printed["dataset"]["checksum_sha256"] == result.summary["dataset"]["checksum_sha256"]
    assert printed["svm"]["test_accuracy"] == result.summary["svm"]["test_accuracy"]


def test_features_do_not_depend_on_the_number_of_jobs():
    rng = np.random.default_rng(1)
    t = np.arange(1000) / 1000.0
    f1 = rng.uniform(15, 60, 7)[:, None]
    ax = np.exp(-t / 0.2) * (np.sin(2 * np.pi * f1 * t) + 0.5 * np.sin(2 * np.pi * 4.1 * f1 * t))
    az = 9.81 + 0.1 * ax + 0.01 * rng.standard_normal(ax.shape)
    one = signal_features(ax, az, 1000.0, n_jobs=1, chunk=3, show_progress=False)
    with more_jobs_allowed():  # two workers, on a machine of one core too
        two = signal_features(ax, az, 1000.0, n_jobs=2, chunk=2, show_progress=False)
    for name in ("dominant", "peaks", "tau", "gain", "decay_ok", "decay_status", "fft",
                 "fft_elliptic"):
        np.testing.assert_array_equal(getattr(one, name), getattr(two, name))
    np.testing.assert_allclose(one.dominant, f1[:, 0], atol=0.05)
    np.testing.assert_allclose(one.peaks[:, 1], 4.1 * f1[:, 0], rtol=2e-3)


def test_mode_peaks_are_the_features_dominant_frequency_and_peaks_bit_for_bit():
    # what the mode-curve classifier reads, without the decay fits: the same functions on the
    # same rows, in other chunks and on other workers
    rng = np.random.default_rng(4)
    t = np.arange(800) / 1000.0
    f1 = rng.uniform(15, 60, 9)[:, None]
    ax = np.exp(-t / 0.2) * (np.sin(2 * np.pi * f1 * t) + 0.5 * np.sin(2 * np.pi * 3.7 * f1 * t))
    az = 9.81 + 0.1 * ax
    feats = signal_features(ax, az, 1000.0, n_jobs=1, chunk=4, show_progress=False)
    with more_jobs_allowed():
        dominant, peaks = mode_peaks(ax, 1000.0, n_jobs=2, chunk=3, show_progress=False)
    np.testing.assert_array_equal(dominant, feats.dominant)
    np.testing.assert_array_equal(peaks, feats.peaks)
    # the second mode found: its interpolated peak within about a tenth of a bin (1.25 Hz) of
    # 3.7 f1 >= 55 Hz
    np.testing.assert_allclose(peaks[:, 1], 3.7 * f1[:, 0], rtol=3e-3)


@pytest.mark.parametrize("ax, fs, message", [
    (np.zeros(10), 1000.0, "ax and az must be 2-D"),
    (np.zeros((2, 10)), 0.0, "fs"),
    (np.zeros((2, 10)), "1000", "fs"),
])
def test_mode_peaks_refuse_what_they_cannot_read(ax, fs, message):
    with pytest.raises((ValueError, TypeError), match=message):
        mode_peaks(ax, fs, n_jobs=1)


def test_report_renders_the_same_blocks_twice():
    r = Report("T <&>")
    r.heading("A")
    r.paragraph("x < y")
    r.table(["a", "b"], [[1, "p|q"]])
    r.figure("f.png", "cap")
    r.preformatted("1 2\n3 4")
    md, page = r.markdown(), r.html()
    assert "| 1 | p\\|q |" in md and "<td>p|q</td>" in page
    assert "x &lt; y" in page and "<h1>T &lt;&amp;&gt;</h1>" in page
    assert md.index("## A") < md.index("![cap](f.png)") < md.index("```")


def test_sections_compute_without_drawing_and_render_from_their_result(tmp_path):
    """compute is pure (no figure, no report); render draws only from the result it is given."""
    import matplotlib.pyplot as plt

    from ebantenna.report import FigureSet
    from ebantenna.simulate import builtin_scene
    from ebantenna.study import mode_zones, time_frequency

    plt.close("all")
    scene = builtin_scene("paper")
    result = mode_zones.compute(scene.probe, quick=True)
    maps = time_frequency.compute(scene, seed=0)
    assert plt.get_fignums() == []
    with pytest.raises(dataclasses.FrozenInstanceError):
        result.peak = 0.0
    assert json.loads(json.dumps(result.to_dict())) == result.to_dict()
    report, figures = Report("t"), FigureSet(tmp_path)
    mode_zones.render(result, report, figures)
    time_frequency.render(maps, report, figures)
    assert list(figures.paths) == ["fig16_zones", "fig17_mode_shapes", "fig18_19_time_frequency"]
    assert plt.get_fignums() == []  # every figure saved and closed
    assert f"zone 3 from {result.to_dict()['zone3_start_ratio']:.2f} L" in report.markdown()


def test_summary_is_the_results_dicts_put_together(quick_study):
    result, _ = quick_study
    s = result.summary
    assert list(s) == ["quick", "seed", "modes", "dataset", "frequency", "decay", "svm", "ann",
                       "materials", "distance", "hinge", "contact_law", "timings_s",
                       "dataset_cached", "report", "figures"]
    joint = "full_range_joint_material_accuracy"
    assert list(s["distance"]) == [
        "full_range_mae_cm", "full_range_mae_beyond_80_cm", "first_mode_only_mae_cm",
        "full_range_known_material_mae_cm", "full_range_joint_mae_cm",
        "full_range", "first_mode_only", "full_range_known_material", "full_range_joint",
        "one_calibration_against_known_material", "two_modes_against_first_mode",
        joint, f"{joint}_n_test", f"{joint}_unit", f"{joint}_n_units",
        f"{joint}_design_effect", f"{joint}_ci95", f"{joint}_method",
        f"{joint}_recording_ci95", "first_mode_turning_point_cm", "first_mode_calibrated_to_cm",
        "recordings_without_two_peaks", "first_mode_only_beyond_80", "full_range_beyond_80",
        "full_range_known_material_beyond_80", "full_range_joint_beyond_80",
        "first_mode_only_p95", "full_range_p95", "full_range_known_material_p95",
        "full_range_joint_p95", "linear_region_mae_cm", "full_length_mae_cm",
        "full_length", "full_length_rms", "linear_region_mae_cm_by_trainer",
        "linear_region_by_trainer",
        "linear_region_smallest_error_trainer", "linear_region_against_smallest",
        "linear_region_random_split", "linear_region_rms_by_trainer",
        "linear_region_positions_held_out", "linear_region_held_out_against_random",
    ]
    assert list(s["timings_s"]) == list(STEPS)


def test_material_accuracies_are_fractions_on_every_split(quick_study):
    result, _ = quick_study
    m = json.loads((result.out_dir / "summary.json").read_text())["materials"]
    for key in ("svm_random_train_accuracy", "svm_random_test_accuracy",
                "svm_grouped_test_accuracy", "svm_blocked_test_accuracy"):
        assert 0.0 <= m[key] <= 1.0, key
    assert m["svm_random_test_accuracy"] == result.summary["svm"]["test_accuracy"]
    assert set(m["position_aware_test_accuracy"]) == {"random", "grouped", "blocked"}
    assert set(m["mode_curve_test_accuracy"]) == {"random", "grouped", "blocked"}
    assert set(m["ann"]) == {"gd", "scg", "adam"}
    assert m["ann"]["gd"] == result.summary["ann"]["test_accuracy"]
    assert m["ablation"]["none"] is not None and len(m["ablation"]) > 5
    values = [*m["position_aware_test_accuracy"].values(), *m["ann"].values(),
              *m["mode_curve_test_accuracy"].values(),
              m["mode_curve_grouped_linear_accuracy"], m["mode_curve_grouped_unilateral_accuracy"],
              *m["ablation"].values()]
    if m["equivalent_pair_accuracy"] is not None:
        values.append(m["equivalent_pair_accuracy"])
        values.append(m["equivalent_pair_mode_curve_accuracy"])
    # the paper scene has the rod's modes: lift-off, the unilateral rebuild, the moved contact
    values += [
        m[key]
        for key in (
            "contact_lift_off_share",
            "svm_grouped_unilateral_accuracy",
            "unilateral_restrike_share",
            "svm_grouped_mid_height_accuracy",
            "svm_grouped_friction_accuracy",
        )
    ]
    assert all(0.0 <= v <= 1.0 for v in values)
    assert m["unilateral_median_restrikes"] >= 0
    assert m["ablation_changed"].keys() == {"dlpf"}  # its modes above fs/2 go with it
    text = result.report_markdown.read_text()
    assert "A contact that only pushes" in text and "Where the rod is touched" in text
    assert "Friction along the rod" in text


def test_hinge_fit_and_run_time_table_are_reported(quick_study):
    result, _ = quick_study
    s = result.summary
    h = s["hinge"]
    assert h["observed_cm"] == [29.5, 39.5] and h["probe_lengths_cm"] == [40.0, 50.0]
    np.testing.assert_allclose(h["residual_cm"],
                               np.subtract(h["predicted_cm"], h["observed_cm"]), rtol=1e-12)
    assert h["rms_residual_cm"] == pytest.approx(np.sqrt(np.mean(np.square(h["residual_cm"]))))
    md = result.report_markdown.read_text()
    assert "hinge-and-tip model explains both" in md
    assert "| data set |" in md and "| total |" in md
    assert ("reused from its cache" in md) == s["dataset_cached"]
    assert "look better on such a split" in md
    assert "the random split flatters" in md or "does not show the random split flattering" in md


def test_report_sections_follow_the_recipe(quick_study):
    """reproduce computes and renders the sections in the order of its steps, and each render
    writes its own sections in its own order: the report's headings are the study's outline."""
    result, _ = quick_study
    headings = [line[3:] for line in result.report_markdown.read_text().splitlines()
                if line.startswith("## ")]
    assert headings == [
        "Modes of the probe and the three zones (Figs. 16, 17)",
        "The hinge: one stiffness and one tip mass for both probes?",
        "Data set",
        "Dominant frequency against contact distance (Figs. 9, 10)",
        "Gain and time constant by material (Fig. 11)",
        "Material classification: ANN and SVM (Figs. 12, 15)",
        "Distance networks (Figs. 13, 14)",
        "Random recordings against held-out positions",
        "Beyond the paper: distance first, then material",
        "Beyond the paper: material and distance from two frequencies",
        "The networks with other trainers",
        "How much the numbers carry: folds, clusters and repetitions",
        "What the paper's training budget changes",
        "What the classifier learns: one effect at a time switched off",
        "The equivalent pair: impedance or chemistry?",
        "A contact that only pushes",
        "Where the rod is touched: an assumption moved",
        "Friction along the rod",
        "The contact's Hertz law against its linearisation",
        "How much the accuracies owe to the assumed rod",
        "Beyond the paper: contact distance over the whole probe",
        "Spectrograms and scalograms (Figs. 18, 19)",
        "Run time",
    ]


def test_every_section_that_trains_a_network_says_what_its_interval_holds_fixed(quick_study):
    # a network's training is not convex: its test interval over positions holds the trained
    # network fixed, which the report must say wherever it gives one (and nowhere else)
    from ebantenna.study._common import TRAINED_ONCE

    result, _ = quick_study
    sections = {}
    for block in result.report_markdown.read_text().split("\n## ")[1:]:
        heading, _, text = block.partition("\n")
        sections[heading] = " ".join(text.split())
    tail = TRAINED_ONCE.split(" trained once", 1)[1]
    with_networks = {"Material classification: ANN and SVM (Figs. 12, 15)",
                     "Distance networks (Figs. 13, 14)", "The networks with other trainers",
                     "What the paper's training budget changes"}
    assert {h for h, text in sections.items() if tail in text} == with_networks


def test_every_step_of_a_study_runs_on_the_measured_number_of_blas_threads():
    # benchmarks/study_blas_threads.py measured one thread as never slower and cheaper in CPU
    from threadpoolctl import threadpool_info, threadpool_limits

    from ebantenna.study._common import BLAS_THREADS
    from ebantenna.study.reproduce import _Timer

    def blas_threads():
        return {p["num_threads"] for p in threadpool_info() if p["user_api"] == "blas"}

    timer = _Timer(show_progress=False)
    with threadpool_limits(limits=2, user_api="blas"):
        outside = blas_threads()
        inside = timer.run("modes", blas_threads)
        assert blas_threads() == outside  # the limit ends with the step
    timer.close()
    assert inside <= {BLAS_THREADS}  # empty if NumPy has no BLAS that threadpoolctl can see
