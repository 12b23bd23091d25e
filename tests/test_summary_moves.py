"""Which numbers of the study moved between two runs (``benchmarks/summary_moves.py``)."""

from __future__ import annotations

import doctest
import json
import math

import benchmark_scripts

moves_script = benchmark_scripts.load("summary_moves")

STORED = benchmark_scripts.FOLDER.parent / "docs" / "_data" / "reproduce_summary.json"


def test_the_examples_print_what_they_promise():
    result = doctest.testmod(moves_script, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted >= 3 and result.failed == 0


def test_a_run_against_itself_moves_nothing():
    summary = json.loads(STORED.read_text(encoding="utf-8"))["summary"]
    result = moves_script.moves(summary, summary)
    assert result["statements"] == []
    assert all(p["moved"] == 0 and p["largest"] is None for p in result["parts"].values())
    # every leaf of the stored run is compared but the run's own bookkeeping
    compared = sum(p["n"] for p in result["parts"].values())
    leaves = moves_script.flatten(summary)
    assert compared == sum(not any(w in k for w in moves_script.NOT_RESULTS) for k in leaves)


def test_numbers_and_statements_are_told_apart_and_the_largest_move_named():
    a = {"svm": {"accuracy": 0.80, "ci95": [0.7, 0.9], "resolved": True},
         "distance": {"mae_cm": 2.0, "epoch": 1550}, "timings_s": {"svm": 1.0}}
    b = {"svm": {"accuracy": 0.81, "ci95": [0.7, 0.95], "resolved": False},
         "distance": {"mae_cm": 2.5, "epoch": None}, "timings_s": {"svm": 9.0}}
    result = moves_script.moves(a, b)
    assert set(result["parts"]) == {"svm", "distance"}  # wall times are not results
    svm, distance = result["parts"]["svm"], result["parts"]["distance"]
    assert (svm["n"], svm["moved"]) == (4, 3)
    # 0.05/0.9 = 0.056 beats 0.01/0.80 = 0.0125
    assert svm["largest"][0] == "svm.ci95[1]"
    assert math.isclose(svm["largest"][3], 0.05 / 0.9, rel_tol=1e-12)
    assert distance["largest"] == ["distance.mae_cm", 2.0, 2.5, 0.25]
    assert result["statements"] == [["distance.epoch", 1550, None],
                                    ["svm.resolved", True, False]]


def test_the_command_reads_the_stored_layout_and_a_plain_summary(tmp_path, capsys):
    plain = tmp_path / "summary.json"
    summary = json.loads(STORED.read_text(encoding="utf-8"))["summary"]
    summary["distance"]["full_length_mae_cm"] += 1.0
    plain.write_text(json.dumps(summary), encoding="utf-8")
    assert moves_script.main([str(STORED), str(plain), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["parts"]["distance"]["moved"] == 1
    assert result["parts"]["distance"]["largest"][0] == "distance.full_length_mae_cm"
    assert moves_script.main([str(STORED), str(plain)]) == 0
    assert "distance: 1 of" in capsys.readouterr().out
