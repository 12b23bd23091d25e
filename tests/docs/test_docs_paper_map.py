"""The paper -> code page: every item listed, every name real, every number read from a source."""

import json
import re
from pathlib import Path

import paper_map
import pytest

from ebantenna.paper.printed import NUMBERS

DOCS = Path(__file__).resolve().parents[2] / "docs"
ITEMS = {item.item: item for item in paper_map.PAPER_MAP}


def test_every_figure_table_and_equation_once():
    listed = [item.item for item in paper_map.PAPER_MAP]
    expected = paper_map.PAPER_FIGURES + paper_map.PAPER_TABLES + paper_map.PAPER_EQUATIONS
    assert sorted(listed) == sorted(expected) and len(set(listed)) == len(listed)


def test_the_papers_numbering_is_the_one_listed():
    # The paper, where it is at hand (beside the repository in CI), numbers exactly these.
    paper = Path(__file__).resolve().parents[3] / "shared" / "paper"
    texts = sorted(paper.glob("*.txt")) if paper.is_dir() else []
    if not texts:
        pytest.skip("the paper's text is not beside the repository")
    text = texts[0].read_text()
    figures = {int(k) for k in re.findall(r"^Fig\. (\d+) ", text, flags=re.M)}
    tables = {int(k) for k in re.findall(r"^Table (\d+) ", text, flags=re.M)}
    equations = {int(k) for k in re.findall(r"\\quad \((\d+)\)\$\$", text)}
    assert figures == set(range(1, len(paper_map.PAPER_FIGURES) + 1))
    assert tables == set(range(1, len(paper_map.PAPER_TABLES) + 1))
    assert equations == set(range(1, len(paper_map.PAPER_EQUATIONS) + 1))


@pytest.mark.parametrize("item", paper_map.PAPER_MAP, ids=lambda i: i.item)
def test_names_exist(item):
    for name in item.code:
        assert paper_map.resolve(name) is not None
    for stem in item.gallery:
        assert (DOCS / "examples" / f"{stem}.py").is_file(), stem
    if item.printed and not item.printed.startswith("order"):
        assert item.printed in NUMBERS


def test_links_point_where_a_name_is_defined():
    assert paper_map._defined_at("ebantenna.signal.norm_spectrum") == (
        "ebantenna.signal.features.norm_spectrum"
    )
    assert paper_map._defined_at("ebantenna.paper.printed.TABLE_1") == (
        "ebantenna.paper.printed.TABLE_1"
    )


def test_resolve_refuses_what_does_not_exist():
    assert paper_map.resolve("ebantenna.fem.modal_analysis").__name__ == "modal_analysis"
    with pytest.raises(LookupError):
        paper_map.resolve("ebantenna.fem.no_such_function")
    with pytest.raises(LookupError):
        paper_map.resolve("no_such_package.thing")


def test_every_item_is_reproduced_by_code_or_says_why_not():
    for item in paper_map.PAPER_MAP:
        assert item.code or item.status.startswith("not computed"), item.item


def test_every_status_is_one_of_the_kinds_and_gives_its_reason():
    for item in paper_map.PAPER_MAP:
        kind = item.status.split(":")[0]
        assert kind in paper_map.STATUSES, item.item
        if kind in ("differs", "not computed"):  # a difference or a gap always says why
            assert len(item.status.split(":", 1)[1].strip()) > 10, item.item
        assert item.here, item.item  # every "ebantenna" cell says what the package gives


RECORD = paper_map.load_summary()
VALUES = paper_map.build_values(RECORD["summary"])


def test_the_summary_has_every_key_the_map_reads():
    for item in paper_map.PAPER_MAP:
        for key in paper_map.keys_read(item):
            assert key in VALUES, (item.item, key)
        cells = paper_map._cells(item, VALUES)  # formats every value, checks every verdict
        assert not any("[[" in cell for cell in cells), item.item


def test_the_stored_summary_is_a_full_run_with_its_commit_and_date():
    made, summary = RECORD["made"], RECORD["summary"]
    assert re.fullmatch(r"[0-9a-f]{40}(\+dirty)?", made["commit"])
    assert re.fullmatch(r"\d{4}-\d\d-\d\d \d\d:\d\d UTC", made["date"])
    assert made["command"].startswith("ebantenna reproduce --json")
    assert summary["quick"] is False
    text = json.dumps(summary)
    assert "/tmp" not in text and str(Path.home()) not in text  # no path of the machine that ran it


def test_the_summary_keys_are_those_reproduce_writes():
    # The stored modes section is what the code computes now (a few seconds); every other key
    # is one that a section's to_dict or reproduce's summary writes (running the study takes
    # too long for this suite).
    from ebantenna.simulate import builtin_scene
    from ebantenna.study import mode_zones

    probe = builtin_scene("paper").probe
    assert RECORD["summary"]["modes"] == mode_zones.compute(probe, quick=False).to_dict()
    study = Path(paper_map.resolve("ebantenna.study").__file__).parent
    source = "\n".join(p.read_text() for p in study.glob("*.py"))
    for key in paper_map.flatten(RECORD["summary"]):
        section, name = key.split(".")[:2] if "." in key else (key, key)
        # an accuracy's count, unit, interval and method are named after it by paper.uncertainty
        # (clustered_entries, training_entries)
        name = re.sub(r"_(n_test|n_train|ci95|recording_ci95|unit|n_units|method|design_effect|"
                      r"folds|fold_std)$", "", name)
        assert f'"{section}"' in source, key
        if name not in ("figures", "report") and section not in ("figures", "report", "timings_s"):
            assert f'"{name}"' in source, key  # a key of its own, not a material or figure name


def test_each_verdict_is_the_one_the_numbers_give():
    checked = [item for item in paper_map.PAPER_MAP if item.check]
    assert {i.item for i in checked} >= {"Fig. 9", "Fig. 12", "Fig. 15", "Fig. 16"}
    for item in checked:
        assert item.printed in NUMBERS, item.item
        assert item.status.startswith(paper_map.verdict(item, VALUES)), item.item
    wrong = paper_map.Item("Fig. 12", "x", printed="ann_accuracy", here="y",
                           status="agrees", check=("summary:ann.all_accuracy", 0.02))
    with pytest.raises(paper_map.ExtensionError):
        paper_map._cells(wrong, VALUES)


def test_an_estimate_with_an_interval_is_judged_by_its_interval():
    """Where the summary gives a 95 % interval, the verdict is whether it holds the printed
    number: a point farther than the tolerance agrees when its interval holds the paper's
    number, and a point within it differs when the interval excludes it."""
    item = paper_map.Item("Fig. 15", "x", printed="svm_test_accuracy", here="y",
                          status="agrees", check=("summary:svm.test_accuracy", 0.02))
    printed = NUMBERS["svm_test_accuracy"].value
    wide = {"summary:svm.test_accuracy": printed - 0.05,
            "summary:svm.test_accuracy_ci95": [printed - 0.1, printed + 0.01]}
    narrow = {"summary:svm.test_accuracy": printed - 0.01,
              "summary:svm.test_accuracy_ci95": [printed - 0.015, printed - 0.005]}
    assert paper_map.verdict(item, wide) == "agrees"
    assert paper_map.verdict(item, narrow) == "differs"
    assert paper_map.verdict(item, {"summary:svm.test_accuracy": printed - 0.01}) == "agrees"


def test_fill_formats_and_refuses_an_unknown_key():
    text = paper_map.fill("[[a|pct]] and [[b|.1f]] cm", {"a": 0.5, "b": 2.25})
    assert text == "50.0 % and 2.2 cm"
    with pytest.raises(KeyError, match="nothing"):
        paper_map.fill("[[nothing|g]]", {})


def test_refresh_stores_a_full_run_without_its_paths(tmp_path):
    summary = json.loads(json.dumps(RECORD["summary"]))
    summary["dataset"]["path"] = "/somewhere/cache/" + summary["dataset"]["path"]
    summary["figures"] = {k: f"/somewhere/out/{v}" for k, v in summary["figures"].items()}
    source = tmp_path / "summary.json"
    source.write_text(json.dumps(summary))
    record = paper_map.refresh(source, tmp_path / "stored.json", commit="0" * 40)
    assert record == json.loads((tmp_path / "stored.json").read_text())
    assert record["summary"]["figures"] == RECORD["summary"]["figures"]
    assert record["summary"]["dataset"] == RECORD["summary"]["dataset"]
    assert record["made"]["commit"] == "0" * 40
    summary["quick"] = True
    source.write_text(json.dumps(summary))
    with pytest.raises(ValueError, match="quick"):
        paper_map.refresh(source, tmp_path / "stored.json", commit="0" * 40)


def test_the_pages_numbers_on_the_peak():
    # paper_to_code.rst, "Where the dominant frequency peaks": each number it states
    assert VALUES["peak:bare-clamped"] == pytest.approx(0.783, abs=5e-4)
    assert VALUES["peak:board-clamped"] == pytest.approx(0.88, abs=0.005)
    assert VALUES["scene:tip_mass_g"] == pytest.approx(2.5)
    board = [VALUES[f"peak:board-{h}"] for h in ("clamped", "fitted", "pinned")]
    assert min(board) == VALUES["peak:board-pinned"] and round(min(board), 2) == 0.84
    assert VALUES["peak:bare-pinned"] < VALUES["peak:bare-fitted"] < VALUES["peak:bare-clamped"]
    hinge = RECORD["summary"]["hinge"]
    assert hinge["tip_mass_g"] < 1e-3 and hinge["explains_both"] is False  # "no tip mass at all"
    assert NUMBERS["deviation_cm"].value / 40 == pytest.approx(0.74, abs=0.005)
    assert NUMBERS["deviation_50cm_probe_cm"].value / 50 == pytest.approx(0.79, abs=0.005)
    assert RECORD["summary"]["modes"]["lowest_frequency_peak_ratio"] == pytest.approx(0.88)
    # "on the report's grid of 99 contacts": the full run's zone sweep
    from ebantenna.simulate import builtin_scene
    from ebantenna.study import mode_zones

    zones = mode_zones.compute(builtin_scene("paper").probe, quick=False).zones
    assert len(zones.contacts) == 99


def test_the_long_runs_picked_accuracy_is_no_test_result():
    # the long run stops at the first checkpoint whose test accuracy reaches the paper's: the
    # row gives that epoch, and no accuracy picked on the test rows as if it were a test result
    status = paper_map.fill(ITEMS["Fig. 12"].status, VALUES)
    long = RECORD["summary"]["materials"]["ann_training_setup"]["long_run"]
    assert f"first reaches the paper's value at epoch {long['reached_paper_test_epoch']}" in status
    assert "picked on the test rows" in status and "no test interval" in status
    assert paper_map._formatted(long["test_accuracy"], "pct") not in status
