"""Every exercise solution runs, checks its own answer, and is shown on its exercise page."""

import contextlib
import functools
import io
import re
import runpy
import warnings
from decimal import Decimal
from pathlib import Path

import pytest

DOCS = Path(__file__).resolve().parents[2] / "docs"
SOLUTIONS = sorted((DOCS / "exercises" / "solutions").glob("ex*.py"))
PAGES = sorted((DOCS / "exercises").glob("ex*.rst"))


def test_at_least_six_exercises_each_with_a_page_and_a_solution():
    assert len(SOLUTIONS) >= 6
    assert [p.stem for p in PAGES] == [s.stem for s in SOLUTIONS]
    index = (DOCS / "exercises" / "index.rst").read_text()
    for page in PAGES:
        assert f"   {page.stem}\n" in index, f"{page.name} is missing from the exercises toctree"


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.stem)
def test_page_has_statement_hints_and_hidden_solution(page):
    text = page.read_text()
    # the solution is the script the tests run, included verbatim, inside a closed <details>
    assert f".. literalinclude:: solutions/{page.stem}.py" in text
    opened = re.findall(r"<details class=\"(hint|solution)\">", text)
    assert opened.count("solution") == 1 and opened.count("hint") >= 1
    assert text.count("<details") == text.count("</details>")
    solution_at = text.index('<details class="solution">')
    assert text.index(".. literalinclude::") > solution_at  # hidden until asked for
    assert text.index("<details") > text.index("====\n")  # a statement comes first


@functools.cache
def run_solution(script: Path) -> tuple[dict, str]:
    """The globals and the printed output of one solution script, warnings as errors."""
    out = io.StringIO()
    with warnings.catch_warnings(), contextlib.redirect_stdout(out):
        warnings.simplefilter("error")
        namespace = runpy.run_path(str(script), run_name="__main__")
    return namespace, out.getvalue()


@pytest.mark.parametrize("script", SOLUTIONS, ids=lambda p: p.stem)
def test_solution_runs_and_its_checks_pass(script):
    source = script.read_text()
    assert source.count("assert ") >= 3, "a solution must check its answer"
    assert "ok" in run_solution(script)[1]


def _page_answers(text: str) -> dict[str, str]:
    """``name = value`` pairs of the folded "Expected answers" block of an exercise page."""
    start = text.index('<details class="answers">')
    block = text[start : text.index("</details>", start)]
    return dict(re.findall(r"``(\w+) = ([-+0-9.eE]+)``", block))


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.stem)
def test_page_states_objectives_difficulty_time(page):
    text = page.read_text()
    assert re.search(r"^:Objectives: \S", text, flags=re.M)
    assert re.search(r"^:Difficulty: (introductory|intermediate|advanced)$", text, flags=re.M)
    assert re.search(r"^:Time: about \d+ minutes$", text, flags=re.M)


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.stem)
def test_expected_answers_on_the_page_are_the_solutions(page):
    stated = _page_answers(page.read_text())
    answers = run_solution(DOCS / "exercises" / "solutions" / f"{page.stem}.py")[0]["ANSWERS"]
    assert stated and set(stated) == set(answers), (sorted(stated), sorted(answers))
    for name, text in stated.items():
        # the page rounds to its last printed digit: the value is within half a unit of it
        half_unit = 0.5 * 10.0 ** Decimal(text).as_tuple().exponent
        assert abs(float(answers[name]) - float(text)) <= half_unit * (1 + 1e-9), (name, text)


def test_a_wrong_answer_fails(tmp_path):
    # The checks are real: the convergence solution rejects a second-order method.
    script = (DOCS / "exercises" / "solutions" / "ex03_convergence.py").read_text()
    broken = script.replace("orders = np.log2(errors[:-1] / errors[1:])",
                            "orders = np.log2(errors[:-1] / errors[1:]) / 2")
    assert broken != script
    path = tmp_path / "broken.py"
    path.write_text(broken)
    with pytest.raises(AssertionError):
        runpy.run_path(str(path), run_name="__main__")
