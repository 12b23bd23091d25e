"""A Jupyter notebook for every exercise, made from its page and its worked solution.

Each notebook holds the exercise's statement (the page's text up to the first hint, in Markdown),
an empty cell to work in, and the worked solution, the same script the test suite runs, split at
its numbered steps. The notebooks are written into ``docs/exercises/notebooks/`` when the build
starts, and each exercise page offers its own for download.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

__all__ = ["markdown", "statement", "exercise_notebook", "write_notebooks", "setup"]

_ROLE = re.compile(r":(?:func|class|meth|mod|data|attr|doc|obj):`~?([^`<]*?)\s*(?:<[^>]*>)?`")
_MATH = re.compile(r":math:`([^`]*)`")


def markdown(rst: str) -> str:
    """The few reST constructs the statements use, in Markdown: roles, math, literals, titles."""
    text = _MATH.sub(r"$\1$", rst)
    text = _ROLE.sub(lambda m: f"`{m.group(1).removeprefix('../')}`", text)
    text = text.replace("``", "`")
    return re.sub(r"^(.+)\n=+\n", r"# \1\n", text, flags=re.M)


def statement(page_text: str) -> str:
    """The statement of an exercise page: its title and text up to the first hint, without the
    "About this exercise" field list (the teacher's)."""
    head = page_text.split(".. raw:: html", 1)[0]
    head = re.sub(r":download:`[^`]*`.*?\n\n", "", head, flags=re.S)  # this very notebook
    head = re.sub(
        r"\.\. rubric:: About this exercise\n\n(?::\w[^\n]*\n(?:   [^\n]*\n)*)+", "", head
    )
    return markdown(head).strip() + "\n"


def _cell(kind: str, source: str) -> dict:
    cell = {"cell_type": kind, "metadata": {}, "source": source.splitlines(keepends=True)}
    if kind == "code":
        cell.update(execution_count=None, outputs=[])
    return cell


def exercise_notebook(page: Path, solution: Path) -> dict:
    """The notebook (nbformat 4, as a dict) of one exercise."""
    code = solution.read_text()
    # the solution's numbered steps ("# 1. ...") start new cells
    steps = [s.strip("\n") + "\n" for s in re.split(r"\n(?=# \d+\. )", code) if s.strip()]
    cells = [
        _cell("markdown", statement(page.read_text())),
        _cell("markdown", "## Your work\n"),
        _cell("code", ""),
        _cell(
            "markdown", "## Worked solution\n\nTry first. Its checks (`assert`) pass when run.\n"
        ),
        *(_cell("code", step) for step in steps),
    ]
    return {
        "cells": cells,
        "metadata": {
            "kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
            "language_info": {"name": "python"},
        },
        "nbformat": 4,
        "nbformat_minor": 5,
    }


def write_notebooks(exercises: Path) -> list[Path]:
    """Write ``notebooks/<exercise>.ipynb`` for every ``ex*.rst`` page beside its solution."""
    out = exercises / "notebooks"
    out.mkdir(exist_ok=True)
    written = []
    for page in sorted(exercises.glob("ex*.rst")):
        notebook = exercise_notebook(page, exercises / "solutions" / f"{page.stem}.py")
        path = out / f"{page.stem}.ipynb"
        text = json.dumps(notebook, indent=1, ensure_ascii=False) + "\n"
        if not path.exists() or path.read_text() != text:  # unchanged files keep their time
            path.write_text(text)
        written.append(path)
    return written


def _on_builder_inited(app):
    write_notebooks(Path(app.srcdir) / "exercises")


def setup(app):
    app.connect("builder-inited", _on_builder_inited)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
