"""Every exercise has a notebook per edition: the student's to work in, the teacher's to run.

The student notebook holds the statement, objectives and time, the data-making code, a starting
cell per step, the hints and the self-check; nothing of the answers or the worked solution. The
teacher notebook adds both. Executing them needs the ``teach`` extra (nbclient, ipykernel); the
tests that do so are skipped with that reason without it.
"""

import json
import re
import zipfile
from pathlib import Path

import exercise_notebooks
import pytest
from exercise_secrets import STEMS, answer_pairs, solution_lines

from ebantenna.course import VARIANTS, tolerances

DOCS = Path(__file__).resolve().parents[2] / "docs"
EXERCISES = DOCS / "exercises"
EDITIONS = ("student", "teacher")


def resolve(kind, target):
    """The links the build makes, for the pages that exist in the source tree."""
    if kind == "doc":
        path = (EXERCISES / f"{target}.rst").resolve()
        if path.is_file():
            return path.stem, f"{target}.html"
    return None


def notebook(stem, edition):
    page = (EXERCISES / f"{stem}.rst").read_text()
    solution = (EXERCISES / "solutions" / f"{stem}.py").read_text()
    made = exercise_notebooks.exercise_notebook(page, solution, stem, edition, resolve)
    return json.loads(json.dumps(made))  # as a file would hold it


def text_of(nb, kind=None):
    return "\n".join("".join(c["source"]) for c in nb["cells"] if kind in (None, c["cell_type"]))


def test_markdown_of_the_statements_constructs():
    text = "Title\n=====\n\nUse :func:`~ebantenna.signal.fit_decay` on :math:`x(t)`, ``n = 3``.\n"
    assert exercise_notebooks.markdown(text) == (
        "# Title\n\nUse `fit_decay` on $x(t)$, `n = 3`.\n"
    )
    linked = exercise_notebooks.markdown("See :doc:`../theory/decay`.", resolve)
    assert linked == "See [decay](../theory/decay.html)."


@pytest.mark.parametrize("edition", EDITIONS)
@pytest.mark.parametrize("stem", STEMS)
def test_notebook_of_each_exercise(stem, edition):
    nb = notebook(stem, edition)
    assert nb["nbformat"] == 4 and nb["nbformat_minor"] == 5
    assert nb["metadata"]["kernelspec"]["name"] == "python3"
    ids = [c["id"] for c in nb["cells"]]
    assert len(set(ids)) == len(ids) and all(re.fullmatch(r"[A-Za-z0-9_-]{1,64}", i) for i in ids)
    nbformat = pytest.importorskip("nbformat", reason="nbformat comes with the teach extra")
    nbformat.validate(nbformat.from_dict(nb))
    cells = nb["cells"]
    assert cells[0]["cell_type"] == "markdown" and "".join(cells[0]["source"]).startswith(
        "# Exercise "
    )
    first = "".join(cells[0]["source"])
    assert "**Objectives:**" in first and "**Time:** about" in first
    # theory references are links to the built pages, relative to the exercises' folder
    assert re.search(r"\]\(\.\./theory/\w+\.html\)", first) or "Theory:* the module" in first
    code = [c for c in cells if c["cell_type"] == "code"]
    assert all(c["outputs"] == [] and c["execution_count"] is None for c in code)
    page = (EXERCISES / f"{stem}.rst").read_text()
    n_steps = len(re.findall(r"^\d+\. ", page[: page.index(".. raw:: html")], flags=re.M))
    starts = [c for c in code if "".join(c["source"]).startswith("# Step ")]
    assert len(starts) == n_steps > 0
    assert text_of(nb, "markdown").count("<details><summary>Hint") == page.count('class="hint"')
    # the self-check names every expected answer with its tolerance
    for name, tol in tolerances(stem).items():
        assert f"| `{name}` | {tol.describe()} |" in text_of(nb, "markdown")
        assert f"    {name}=None,\n" in text_of(nb, "code")
    solution = (EXERCISES / "solutions" / f"{stem}.py").read_text()
    if "# [data]" in solution:
        data = solution.split("# [data]\n")[1].split("# [/data]\n")[0]
        assert data in text_of(nb, "code")
    secret = [s.replace("`", "") for s in solution_lines(stem) + answer_pairs(stem)]
    assert secret
    shown = text_of(nb).replace("`", "")  # Markdown's code spans, the pages' literals
    if edition == "student":
        assert [s for s in secret if s in shown] == []
    else:
        assert [s for s in secret if s not in shown] == []
        # the solution cells, put together, are the tested script itself
        at = next(i for i, c in enumerate(cells) if "".join(c["source"]).startswith("## Worked"))
        body = "".join("".join(c["source"]) for c in cells[at + 1 : -1])
        assert body.replace("\n", "") == solution.replace("\n", "")


def test_written_with_their_zip(tmp_path):
    exercises = tmp_path / "exercises"
    (exercises / "solutions").mkdir(parents=True)
    for stem in STEMS[:2]:
        (exercises / f"{stem}.rst").write_text((EXERCISES / f"{stem}.rst").read_text())
        solution = (EXERCISES / "solutions" / f"{stem}.py").read_text()
        (exercises / "solutions" / f"{stem}.py").write_text(solution)
    out = tmp_path / "site" / "exercises"
    written = exercise_notebooks.write_notebooks(exercises, out, "student")
    assert [p.name for p in written] == [f"{s}.ipynb" for s in STEMS[:2]]
    with zipfile.ZipFile(out / exercise_notebooks.zip_name("student")) as archive:
        assert archive.namelist() == [f"exercises/{s}.ipynb" for s in STEMS[:2]]
        assert archive.read(f"exercises/{STEMS[0]}.ipynb") == written[0].read_bytes()
    again = (out / exercise_notebooks.zip_name("student")).read_bytes()
    exercise_notebooks.write_notebooks(exercises, out, "student")
    assert (out / exercise_notebooks.zip_name("student")).read_bytes() == again  # reproducible


@pytest.mark.parametrize("edition", EDITIONS)
@pytest.mark.parametrize("stem", STEMS)
def test_notebook_executes(stem, edition, tmp_path):
    nbformat = pytest.importorskip("nbformat", reason="needs the teach extra (nbformat)")
    nbclient = pytest.importorskip("nbclient", reason="needs the teach extra (nbclient)")
    pytest.importorskip("ipykernel", reason="needs the teach extra (ipykernel)")
    nb = nbformat.reads(json.dumps(notebook(stem, edition)), as_version=4)  # as from a file
    # a hang guard per cell (nbclient's clock is the wall): the slowest notebook takes about
    # 13 s in all on a quiet core, so 600 s per cell leaves a slowdown of over forty
    client = nbclient.NotebookClient(
        nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}
    )
    client.execute()  # raises CellExecutionError on the first failing cell
    outputs = [
        "".join(o.get("text", "") for o in c.get("outputs", []))
        for c in nb.cells if c.cell_type == "code"
    ]
    errors = [o for c in nb.cells for o in c.get("outputs", []) if o.output_type == "error"]
    assert not errors
    names = list(tolerances(stem))
    student_check = next(o for o in outputs if o.startswith(f"{names[0]}: "))
    # with the starting cells left empty, every self-check says "not yet", and nothing raises
    assert student_check.count("not yet: no value given") == len(names), student_check
    if edition == "teacher":
        # the worked solution's own values pass its own check
        assert "ok" in "".join(outputs)
        last = outputs[-1].splitlines()
        assert len(last) == len(names) and not [line for line in last if "not yet" in line]


@pytest.mark.parametrize("stem", [s for s in STEMS if s in VARIANTS])
def test_a_variant_exercises_notebook_carries_the_variant(stem):
    # the page's "A graded variant" paragraph, a word that the statement's numbers are the
    # published ones, and a check that follows the data cell's STUDENT
    nb = notebook(stem, "student")
    assert "**A graded variant.**" in text_of(nb, "markdown")
    assert "published exercise's numbers" in text_of(nb, "markdown")
    check_cell = text_of(nb, "code").split("from ebantenna.course import check")[1]
    assert f'check("{stem}", student=STUDENT, key="{stem[:4]}_key.json", **answers)' in check_cell


def test_a_students_notebook_checks_their_own_variant(tmp_path):
    # STUDENT = "alice" in the data cell and the worked solution's answers for alice: the
    # notebook's own check says "within" for each (it checked the published key before)
    nbformat = pytest.importorskip("nbformat", reason="needs the teach extra (nbformat)")
    nbclient = pytest.importorskip("nbclient", reason="needs the teach extra (nbclient)")
    pytest.importorskip("ipykernel", reason="needs the teach extra (ipykernel)")
    import make_variant_key

    answers = make_variant_key.answers_for("ex05_decay", "alice")
    key = make_variant_key.variant_key("ex05_decay", {"alice": answers})
    (tmp_path / "ex05_key.json").write_text(json.dumps(key))
    nb = notebook("ex05_decay", "student")
    for cell in nb["cells"]:
        source = "".join(cell["source"])
        if cell["cell_type"] == "code" and "STUDENT = None" in source:
            cell["source"] = source.replace("STUDENT = None", 'STUDENT = "alice"', 1)
        elif cell["cell_type"] == "code" and source.startswith("from ebantenna.course import"):
            cell["source"] = source + f"answers = {answers!r}\n"
    nb = nbformat.reads(json.dumps(nb), as_version=4)
    nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()
    shown = "".join(o.get("text", "") for c in nb.cells if c.cell_type == "code"
                    for o in c.get("outputs", []))
    lines = [line for line in shown.splitlines() if line.split(":")[0] in answers]
    assert len(lines) == 3 and all(": within" in line for line in lines), shown
