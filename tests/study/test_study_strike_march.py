"""The data set says which strike march made it: the compiled and NumPy marches agree within a
bound, not bit for bit, so the summary and the report name the engine of the run's data set."""

from __future__ import annotations

import pytest

from ebantenna.report import FigureSet, Report
from ebantenna.simulate._block_march import march_engine
from ebantenna.study.data_summary import DatasetResult, render


def test_the_summary_names_the_march_that_made_the_data_set(quick_study):
    result, _ = quick_study
    assert result.summary["dataset"]["strike_march"] == march_engine()


@pytest.mark.parametrize("march, words", [("numpy", "marched by the NumPy block march"),
                                          ("compiled", "marched by the compiled march"),
                                          (None, None)])
def test_the_report_names_it_when_the_data_set_does(tmp_path, march, words):
    report = Report("t")
    render(DatasetResult("d.npz", 2, 10, 1000.0, ("brass",), 1, "abc", None, march), report,
           FigureSet(tmp_path))
    text = report.markdown()
    if words is None:  # a recorded data set, or one made before the key held the march
        assert "marched" not in text
    else:
        assert words in text and "not bit for bit" in text
