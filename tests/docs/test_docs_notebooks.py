"""Every exercise has a notebook: its statement, a cell to work in, and the tested solution."""

import json
from pathlib import Path

import exercise_notebooks
import pytest

DOCS = Path(__file__).resolve().parents[2] / "docs"
PAGES = sorted((DOCS / "exercises").glob("ex*.rst"))


def test_markdown_of_the_statements_constructs():
    text = "Title\n=====\n\nUse :func:`~ebantenna.signal.fit_decay` on :math:`x(t)`, ``n = 3``.\n"
    assert exercise_notebooks.markdown(text) == (
        "# Title\n\nUse `ebantenna.signal.fit_decay` on $x(t)$, `n = 3`.\n"
    )


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.stem)
def test_notebook_of_each_exercise(page, tmp_path):
    assert f"<notebooks/{page.stem}.ipynb>`" in page.read_text()  # the page offers it
    solution = DOCS / "exercises" / "solutions" / f"{page.stem}.py"
    notebook = exercise_notebooks.exercise_notebook(page, solution)
    # a valid nbformat-4 document, as JSON
    notebook = json.loads(json.dumps(notebook))
    assert notebook["nbformat"] == 4 and notebook["metadata"]["kernelspec"]["language"] == "python"
    cells = notebook["cells"]
    statement = "".join(cells[0]["source"])
    assert cells[0]["cell_type"] == "markdown" and statement.startswith("# Exercise ")
    # the teacher's notes and the expected answers stay out of the student's statement
    assert ":Objectives:" not in statement and "Expected answers" not in statement
    assert ":download:" not in statement and ".. " not in statement
    code = [c for c in cells if c["cell_type"] == "code"]
    assert all(c["outputs"] == [] and c["execution_count"] is None for c in code)
    # the solution cells, put together, are the tested script itself
    assert "".join("".join(c["source"]) for c in code[1:]).replace("\n", "") == (
        solution.read_text().replace("\n", "")
    )


def test_written_where_the_pages_link(tmp_path):
    exercises = tmp_path / "exercises"
    (exercises / "solutions").mkdir(parents=True)
    for page in PAGES[:2]:
        (exercises / page.name).write_text(page.read_text())
        solution = DOCS / "exercises" / "solutions" / f"{page.stem}.py"
        (exercises / "solutions" / solution.name).write_text(solution.read_text())
    written = exercise_notebooks.write_notebooks(exercises)
    assert [p.name for p in written] == [f"{p.stem}.ipynb" for p in PAGES[:2]]
    assert all(json.loads(p.read_text())["nbformat"] == 4 for p in written)
