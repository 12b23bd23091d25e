"""The student edition holds no solution anywhere in its output; the teacher edition holds them.

Checked on the built sites: ``docs/_build/html`` (student, the default build) and
``docs/_build/teacher`` (``python -m sphinx -t teacher -b html docs docs/_build/teacher``). Every
file of the student output is searched, whatever its kind: the pages, the copied sources, the
downloads, the search index, the pickled doctrees, the notebooks and their zip. ``.ci/run`` builds
both editions before the documentation tests, so these tests are never skipped there.
"""

from __future__ import annotations

import json
import re
import zipfile
from pathlib import Path

import pytest
from exercise_secrets import STEMS, answer_pairs, solution_lines, visible_text

DOCS = Path(__file__).resolve().parents[2] / "docs"
BUILDS = {"student": DOCS / "_build" / "html", "teacher": DOCS / "_build" / "teacher"}
BANNER = {
    "student": "Student edition: exercises with self-checks, no solutions.",
    "teacher": "Teacher edition: expected answers and worked solutions shown.",
}


def needs(edition):
    build = BUILDS[edition]
    flag = "" if edition == "student" else "-t teacher "
    return pytest.mark.skipif(
        not (build / "exercises" / "index.html").is_file(),
        reason=f"{edition} edition not built (python -m sphinx {flag}-b html docs {build})",
    )


def _texts(build: Path):
    """(name, text) of every file of a build, zips opened, HTML as the text a reader sees."""
    for path in sorted(p for p in build.rglob("*") if p.is_file()):
        name = str(path.relative_to(build))
        data = path.read_bytes()
        if path.suffix == ".zip":
            with zipfile.ZipFile(path) as archive:
                for member in archive.namelist():
                    yield f"{name}:{member}", archive.read(member).decode("utf-8", "replace")
            continue
        text = data.decode("utf-8", "replace")
        if path.suffix == ".html":
            text = visible_text(text)
        elif path.suffix == ".ipynb":
            cells = json.loads(text)["cells"]
            text = "\n".join("".join(c["source"]) for c in cells)
        yield name, text


def _secrets() -> dict[str, list[str]]:
    return {stem: solution_lines(stem) + answer_pairs(stem) for stem in STEMS}


def _found(build: Path, secrets: dict[str, list[str]]) -> dict[str, set[str]]:
    wanted = {s for lines in secrets.values() for s in lines}
    found: dict[str, set[str]] = {}
    for name, text in _texts(build):
        text = text.replace("`", "")
        for secret in wanted:
            if secret.replace("`", "") in text:
                found.setdefault(secret, set()).add(name)
    return found


@needs("student")
def test_student_edition_holds_no_solution_text_anywhere():
    secrets = _secrets()
    assert all(secrets.values())  # every exercise has lines to look for
    found = _found(BUILDS["student"], secrets)
    assert not found, {s: sorted(where)[:3] for s, where in found.items()}
    # no copied reST (it holds the teacher blocks) in the student edition
    assert not [p for p in (BUILDS["student"] / "_sources").rglob("*") if p.is_file()]


@needs("teacher")
def test_teacher_edition_holds_every_solution_and_answer():
    secrets = _secrets()
    found = _found(BUILDS["teacher"], secrets)
    for stem, lines in secrets.items():
        page = visible_text((BUILDS["teacher"] / "exercises" / f"{stem}.html").read_text("utf-8"))
        missing = [s for s in lines if s.replace("`", "") not in page.replace("`", "")]
        assert not missing, (stem, missing[:3])
        notebook = f"exercises/{stem}.ipynb"
        assert all(notebook in found[s] for s in lines), stem


@pytest.mark.parametrize("edition", sorted(BUILDS))
def test_every_page_says_its_edition(edition):
    if not (BUILDS[edition] / "exercises" / "index.html").is_file():
        pytest.skip(f"{edition} edition not built")
    pages = sorted(BUILDS[edition].rglob("*.html"))
    assert len(pages) > 50
    missing = [str(p) for p in pages if BANNER[edition] not in p.read_text("utf-8")]
    assert not missing, missing[:5]


@pytest.mark.parametrize("edition", sorted(BUILDS))
def test_notebooks_and_their_zip_are_linked(edition):
    build = BUILDS[edition]
    if not (build / "exercises" / "index.html").is_file():
        pytest.skip(f"{edition} edition not built")
    index = (build / "exercises" / "index.html").read_text("utf-8")
    zip_name = f"ebantenna-exercises-{edition}.zip"
    assert f'href="{zip_name}"' in index
    with zipfile.ZipFile(build / "exercises" / zip_name) as archive:
        assert archive.namelist() == [f"exercises/{s}.ipynb" for s in STEMS]
    for stem in STEMS:
        page = (build / "exercises" / f"{stem}.html").read_text("utf-8")
        assert f'href="{stem}.ipynb"' in page
        notebook = json.loads((build / "exercises" / f"{stem}.ipynb").read_text())
        assert notebook["metadata"]["ebantenna"] == {"exercise": stem, "edition": edition}
        # every Markdown link of the notebook leads to a page of this build
        cells = notebook["cells"]
        markdown = "".join("".join(c["source"]) for c in cells if c["cell_type"] == "markdown")
        links = re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", markdown)
        assert links
        broken = [u for u in links if not (build / "exercises" / u).resolve().is_file()]
        assert not broken, (stem, broken)
