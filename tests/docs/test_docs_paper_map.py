"""The paper -> code page: every item of the paper listed, every name real, every key reproduced."""

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
        assert item.code or item.reproduced.startswith("not reproduced"), item.item


def test_build_values_are_reproduces_modes_section():
    # The page's numbers are the ``modes`` section of reproduce's summary and the filter orders.
    from ebantenna.signal import PAPER_FILTERS, filter_order
    from ebantenna.simulate import builtin_scene
    from ebantenna.study import mode_zones

    values = paper_map.build_values(quick=True)  # the page uses the full run; same code
    modes = mode_zones.compute(builtin_scene("paper").probe, quick=True).to_dict()
    page = {k.removeprefix("modes."): v for k, v in values.items() if k.startswith("modes.")}
    assert page == modes
    assert values["filter:chebyshev"] == filter_order(PAPER_FILTERS["chebyshev"]) == 13
    for item in paper_map.PAPER_MAP:
        if item.reproduced.startswith(("modes.", "filter:")):
            assert item.reproduced in values, item.item
    # the peak of the dominant frequency sits near the paper's 80 % (Fig. 16), on the quick run's
    # grid of 50 contacts (steps of 2 % of the length)
    assert values["modes.lowest_frequency_peak_ratio"] == pytest.approx(
        NUMBERS["mode_change_ratio"].value, abs=0.1
    )


SUMMARY_KEYS = sorted(
    {
        i.reproduced.removeprefix("summary:")
        for i in paper_map.PAPER_MAP
        if i.reproduced.startswith("summary:")
    }
)


def test_summary_keys_appear_where_reproduce_writes_them():
    # Each key's section is a key of reproduce's summary dict, and its name a key that a
    # section's to_dict writes (running reproduce itself takes too long for this suite).
    study = Path(paper_map.resolve("ebantenna.study").__file__).parent
    source = "\n".join(p.read_text() for p in study.glob("*.py"))
    summary_source = (study / "reproduce.py").read_text()
    for key in SUMMARY_KEYS:
        section, name = key.split(".")
        assert f'"{name}"' in source, key
        assert f'"{section}"' in summary_source or f'"{section}": {{' in source, key
