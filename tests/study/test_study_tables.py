"""The documentation's tables of the study's uncertainty are built from a summary as
``reproduce`` writes it: one row per classifier and split, per repetition count, per rod."""

import sys
from pathlib import Path

import pytest

pytest.importorskip("sphinx")
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "docs" / "_ext"))

import study_tables  # noqa: E402


def _rows(lines):
    """The list-table's rows after the header: each starts with '   * - '."""
    return [line for line in lines if line.startswith("   * - ")][1:]


def test_tables_have_a_row_per_measurement(quick_study):
    result, _ = quick_study
    s = result.summary
    m = s["materials"]
    assert len(_rows(study_tables.interval_lines(s))) == 9  # 3 classifiers x 3 splits
    assert len(_rows(study_tables.repetition_lines(s))) == len(m["svm_grouped_by_repetitions"]) + 1
    assert len(_rows(study_tables.sensitivity_lines(s))) == len(m["rod_geometry"])
    runs = [k for k, v in m["ann_training_setup"].items() if isinstance(v, dict)
            and "max_epochs" in v]
    assert len(_rows(study_tables.ann_budget_lines(s))) == len(runs)  # the long run among them
    assert len(_rows(study_tables.controls_lines(s))) == len(m["controls_paired"])


def test_a_cell_shows_what_the_report_shows(quick_study):
    """The docs' cell and the report's cell of one accuracy are one string: one formatter."""
    from ebantenna.paper.uncertainty import span

    result, _ = quick_study
    m = result.summary["materials"]
    n, units, ci = (m["svm_grouped_test_accuracy_n_test"],
                    m["svm_grouped_test_accuracy_n_units"], m["svm_grouped_test_accuracy_ci95"])
    cell = study_tables.cell(m, "svm_grouped_test_accuracy")
    assert f"n = {n} in {units} positions, {span(ci)})" in cell
    report = result.report_markdown.read_text()
    assert cell.replace(f", {span(ci)})", f", 95 % CI {span(ci)})") in report
    assert any(cell in line for line in study_tables.interval_lines(result.summary))


def test_the_paired_repetitions_line_follows_the_summary(quick_study):
    """The docs' line under the repetitions' table reads the paired entry: its difference as
    the report prints it, and a verdict that flips with ``resolved`` and ``identical``."""
    from ebantenna.paper.uncertainty import points

    result, _ = quick_study
    p = result.summary["materials"]["svm_grouped_repetitions_paired"]
    (line,) = study_tables.repetition_lines(result.summary)[-1:]
    assert f"{p['most']} repetitions against {p['fewest']}" in line
    if not p["identical"]:
        assert points(p["difference"]) in line
        report = result.report_markdown.read_text(encoding="utf-8")
        assert points(p["difference"]) in report  # the report's own string, one formatter
    flipped = {**p, "identical": False, "resolved": not p["resolved"], "direction": "higher",
               "ci95": [0.01, 0.02], "difference": 0.015}
    words = study_tables._paired_repetitions(flipped)[0]
    assert ("resolved, higher" in words) == (not p["resolved"])
    assert ("not resolved" in words) == p["resolved"]
    alike = study_tables._paired_repetitions({**p, "identical": True})[0]
    assert "as many test recordings right under both" in alike and "CI" not in alike
    # the same words as every paired comparison of the pages (the :study: role's ``pair``)
    assert words.endswith(study_tables.value_text({"x": flipped}, "x|pair") + ".")
