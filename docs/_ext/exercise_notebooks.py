"""Exercises in two editions: the pages' teacher blocks, the self-check section, and the notebooks.

The site builds in two editions. The **student edition** (the default) has every exercise's
statement, data, hints and self-check, and no solution, answer or teaching note anywhere in its
output: not in the pages, the search index, the copied sources, the downloads or the pickled
doctrees, because the teacher blocks are never parsed in it. The **teacher edition**
(``python -m sphinx -t teacher -b html docs docs/_build/teacher``) adds the expected answers and
the worked solutions.

The format of an exercise page ``docs/exercises/exNN_name.rst``, in this order:

1. The title ``Exercise N: ...`` underlined with ``=``, then ``*Theory:*`` and the pages to read
   (``:doc:`` roles become links in the notebooks).
2. ``.. rubric:: About this exercise`` and the fields ``:Objectives:``, ``:Difficulty:``
   (introductory, intermediate or advanced) and ``:Time: about N minutes``.
3. The statement: paragraphs, then the numbered steps ``1. ...``, ``2. ...`` (each step becomes a
   starting cell of the notebook).
4. When the exercise computes from data that are random or generated, ``.. rubric:: The data`` and
   a ``literalinclude`` of ``solutions/exNN_name.py`` with ``:start-after: # [data]`` and
   ``:end-before: # [/data]``: the solution script makes its data between these two marker lines,
   at its top, so that the page and the notebook show exactly the code (and seed) it uses. An
   exercise with graded variants (:data:`ebantenna.course.VARIANTS`) follows it with a paragraph
   that starts ``**A graded variant.**``; the notebook carries it, and its checks use the
   teacher's key when the data cell's ``STUDENT`` is set.
5. The hints, each a raw-HTML ``<details class="hint"><summary>Hint N</summary>`` ...
   ``</details>`` fold.
6. ``.. exercise-check:: exNN_name``: the self-check section (the names, tolerances and reasons
   of the expected answers, from :mod:`ebantenna.course`, the call that checks them, and the link
   to the notebook). Its content is a field list, ``:name: what exactly``, that defines every
   checked value for the student (which of several right values, its unit, its normalisation);
   the build stops if a checked value is not defined there.
7. ``.. teacher:: answers``: the expected answers, each number written ````name = value```` with
   ``name`` a key of the solution's ``ANSWERS``, to the digits the test suite checks.
8. ``.. teacher:: solution``: a ``literalinclude`` of the whole solution script, then any notes.

The solution script ``solutions/exNN_name.py`` runs under the test suite; it checks its own results
with ``assert``, prints a line with ``ok``, and ends with ``ANSWERS`` (name -> value) and
``TOLERANCES`` (name -> ``(kind, width, reason)``, see :class:`ebantenna.course.Tolerance`).
After changing one, run ``python docs/_tools/make_answer_key.py`` to update the package's key.

Every HTML build also writes the edition's notebooks next to the exercise pages
(``exercises/exNN_name.ipynb``, their links relative to that place) and all of them in one zip,
``exercises/ebantenna-exercises-<edition>.zip``, which the exercises index links with
``.. exercise-notebooks::``.
"""

from __future__ import annotations

import json
import posixpath
import re
import textwrap
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

from docutils import nodes
from docutils.parsers.rst import Directive
from docutils.statemachine import StringList

from ebantenna.course import VARIANTS, tolerances

__all__ = [
    "EDITIONS", "ExercisePage", "parse_page", "data_code", "markdown", "exercise_notebook",
    "write_notebooks", "zip_name", "TeacherDirective", "ExerciseCheckDirective",
    "ExerciseNotebooksDirective", "setup",
]

EDITIONS = ("student", "teacher")

_ROLE = re.compile(
    r":(func|class|meth|mod|data|attr|doc|obj|ref):`(~?)([^`<]*?)\s*(?:<([^>]*)>)?`"
)
_MATH = re.compile(r":math:`([^`]*)`")
_DATA = re.compile(r"^# \[data\]\n(.*?)^# \[/data\]\n", flags=re.S | re.M)


@dataclass
class ExercisePage:
    """The parts of an exercise page (reST text each), as the format above lays them out."""

    name: str
    title: str
    theory: str
    about: dict[str, str]
    intro: str
    steps: list[str]
    hints: list[tuple[str, str]]
    answers: str
    solution_notes: str
    has_data: bool = field(default=False)
    asked: dict[str, str] = field(default_factory=dict)
    variant: str = ""


def _field_list(text: str) -> dict[str, str]:
    found = re.findall(r"^:(\w+): (.*(?:\n   .*)*)", text, flags=re.M)
    return {name: " ".join(value.split()) for name, value in found}


def asked_values(text: str, name: str) -> dict[str, str]:
    """What each checked value is, from the field list of the page's ``.. exercise-check::``.

    Every value the self-check checks is defined there, in the student's edition, with what makes
    it one value among several right ones (which meshes, which normalisation, which unit); raises
    ValueError when the list and the self-check's names differ.
    """
    match = re.search(rf"^\.\. exercise-check:: {name}\n\n((?:   .*\n|\n)*)", text + "\n",
                      flags=re.M)
    asked = _field_list(textwrap.dedent(match.group(1))) if match else {}
    checked = list(tolerances(name))
    if sorted(asked) != sorted(checked):
        raise ValueError(f"{name}: the exercise-check block must define every checked value "
                         f"{checked}, it defines {list(asked)}")
    return {n: asked[n] for n in checked}


def _teacher_block(text: str, kind: str) -> str:
    match = re.search(rf"^\.\. teacher:: {kind}\n\n((?:   .*\n|\n)*)", text + "\n", flags=re.M)
    if match is None:
        raise ValueError(f"the page has no '.. teacher:: {kind}' block")
    return textwrap.dedent(match.group(1)).strip() + "\n"


def _steps(body: str) -> tuple[str, list[str]]:
    """The paragraphs before the numbered list, and its items (continuation lines joined)."""
    first = re.search(r"^1\. ", body, flags=re.M)
    if first is None:
        return body.strip(), []
    items = re.split(r"^(?=\d+\. )", body[first.start():], flags=re.M)
    steps = [re.sub(r"^\d+\. ", "", textwrap.dedent(" " * 3 + i.strip())).strip() for i in items]
    return body[: first.start()].strip(), [re.sub(r"\n\s+", "\n", s) for s in steps if s]


def parse_page(text: str, name: str) -> ExercisePage:
    """Split an exercise page into its parts; raises ValueError when a part is missing."""
    title = text.split("\n", 1)[0]
    head, rest = text.split(".. rubric:: About this exercise\n", 1)
    fields = re.search(r"^(?::\w+: .*\n(?:   .*\n)*)+\n", rest, flags=re.M)
    if fields is None:
        raise ValueError(f"{name}: no field list after 'About this exercise'")
    about = _field_list(fields.group(0))
    body = re.split(r"^\.\. (?:rubric:: The data|raw:: html)\n", rest[fields.end():], maxsplit=1,
                    flags=re.M)[0]
    intro, steps = _steps(body)
    hints = re.findall(
        r'<details class="hint"><summary>(.*?)</summary>\n\n(.*?)\n\n\.\. raw:: html', text,
        flags=re.S,
    )
    notes = _teacher_block(text, "solution")
    notes = re.sub(r"^\.\. literalinclude::.*\n(?:   .*\n)*", "", notes, flags=re.M).strip()
    theory = re.search(r"^\*Theory:\*.*?(?=\n\n)", head, flags=re.M | re.S)
    variant = re.search(r"^\*\*A graded variant\.\*\*.*?(?=\n\n)", text, flags=re.M | re.S)
    return ExercisePage(
        name=name, title=title, theory=theory.group(0) if theory else "", about=about,
        intro=intro, steps=steps, hints=hints, answers=_teacher_block(text, "answers"),
        solution_notes=notes, has_data=".. rubric:: The data" in text,
        asked=asked_values(text, name), variant=variant.group(0) if variant else "",
    )


def data_code(solution: str) -> str | None:
    """The code between the ``# [data]`` and ``# [/data]`` lines of a solution, with its imports."""
    match = _DATA.search(solution)
    if match is None:
        return None
    head = solution[: match.start()]
    imports = re.findall(r"^(?:import |from ).*(?:\n    .*)*(?:\n\))?", head, flags=re.M)
    return "\n".join(imports) + "\n\n" + match.group(1).strip("\n") + "\n"


def markdown(rst: str, resolve=None) -> str:
    """The few reST constructs the exercise pages use, in Markdown.

    ``resolve(role, target)`` may return ``(text, url)`` to make a role a link; roles it does not
    resolve (or all, without it) become code, ``:doc:`` their target's path.
    """

    def role(m):
        kind, tilde, target, explicit = m.groups()
        target = (explicit or target).strip()
        found = resolve(kind, target) if resolve else None
        shown = target.rsplit(".", 1)[-1] if tilde else target
        if found is None:
            return f"`{target.removeprefix('../')}`" if kind == "doc" else f"`{shown}`"
        text, url = found
        text = (m.group(3).strip() if explicit else text) if kind == "doc" else f"`{shown}`"
        return f"[{text}]({url})"

    text = _MATH.sub(r"$\1$", rst)
    text = _ROLE.sub(role, text)
    text = text.replace("``", "`")
    return re.sub(r"^(.+)\n=+\n", r"# \1\n", text, flags=re.M)


def _cell(kind: str, source: str, index: int) -> dict:
    cell = {"cell_type": kind, "id": f"cell-{index:02d}", "metadata": {},
            "source": source.splitlines(keepends=True)}
    if kind == "code":
        cell.update(execution_count=None, outputs=[])
    return cell


def _check_call(name: str, names: list[str], values: str) -> str:
    args = "".join(f"    {n}={values.format(n=n)},\n" for n in names)
    return f'print(check(\n    "{name}",\n{args}))\n'


def _key_file(name: str) -> str:
    """The variant key's file name, as ``docs/_tools/make_variant_key.py`` writes it."""
    return f"{name.split('_')[0]}_key.json"


def _notebook_check(name: str, values: str) -> str:
    """The code of a notebook's check of ``values`` (a mapping): against the teacher's key of
    the student's variant when the data cell's ``STUDENT`` is set, else the published key."""
    if name not in VARIANTS:
        return f'print(check("{name}", **{values}))\n'
    return (f'if STUDENT is None:  # the published exercise\n'
            f'    print(check("{name}", **{values}))\n'
            "else:  # your graded variant: your teacher's key, next to this notebook\n"
            f'    print(check("{name}", student=STUDENT, key="{_key_file(name)}", **{values}))\n')


def _student_cells(page: ExercisePage, solution: str, names, md) -> list[tuple[str, str]]:
    about = "\n".join(f"**{k}:** {md(v)}  " for k, v in page.about.items())
    intro = md(page.intro) + "\n"
    if page.variant:
        intro += ("\n*These are the published exercise's numbers; a graded variant (see The data) "
                  "has its own.*\n")
    cells = [("markdown", md(f"{page.title}\n{'=' * len(page.title)}\n\n{page.theory}\n\n")
              + about + "\n"),
             ("markdown", intro)]
    data = data_code(solution)
    if data is not None:
        variant = f"\n{md(page.variant)}\n" if page.variant else ""
        cells += [("markdown", "## The data\n\nRun this cell first: it makes the exercise's data "
                   "with the seed of the expected answers.\n" + variant), ("code", data)]
    for k, step in enumerate(page.steps, 1):
        cells += [("markdown", f"## Step {k}\n\n{md(step)}\n"),
                  ("code", f"# Step {k}: your work here\n")]
    if page.hints:
        hints = "".join(f"<details><summary>{s}</summary>\n\n{md(h)}\n\n</details>\n\n"
                        for s, h in page.hints)
        cells.append(("markdown", "## Hints\n\nOpen one at a time.\n\n" + hints))
    table = "".join(f"| `{n}` | {t.describe()} | {md(page.asked[n])} | {t.reason} |\n"
                    for n, t in names.items())
    cells += [
        ("markdown", "## Check your answers\n\nPut your values in place of `None` and run the "
         "check: it says whether each is within its tolerance, without showing the answer.\n\n"
         "| value | tolerance | what exactly | why that much |\n| --- | --- | --- | --- |\n"
         + table),
        ("code", "from ebantenna.course import check\n\nanswers = dict(\n"
         + "".join(f"    {n}=None,\n" for n in names) + ")\n"),
        ("code", _notebook_check(page.name, "answers")),
    ]
    return cells


def _teacher_cells(page: ExercisePage, solution: str, names, md) -> list[tuple[str, str]]:
    steps = [s.strip("\n") + "\n" for s in re.split(r"\n(?=# \d+\. )", solution) if s.strip()]
    cells = [("markdown", "## Expected answers (teacher edition)\n\n" + md(page.answers))]
    cells.append(("markdown", "## Worked solution (teacher edition)\n\nIts checks (`assert`) "
                  "pass when run; the last cell checks its own answers.\n"
                  + (f"\n{md(page.solution_notes)}\n" if page.solution_notes else "")))
    cells += [("code", step) for step in steps]
    cells.append(("code", _notebook_check(page.name, "ANSWERS") if page.name in VARIANTS
                  else _check_call(page.name, list(names), "ANSWERS[{n!r}]")))
    return cells


def exercise_notebook(page_text: str, solution: str, name: str, edition: str = "student",
                      resolve=None) -> dict:
    """The notebook (nbformat 4.5, as a dict) of one exercise in ``edition``."""
    if edition not in EDITIONS:
        raise ValueError(f"edition must be one of {EDITIONS}, got {edition!r}")
    page = parse_page(page_text, name)
    names = tolerances(name)

    def md(text):
        return markdown(text, resolve)

    cells = _student_cells(page, solution, names, md)
    if edition == "teacher":
        cells += _teacher_cells(page, solution, names, md)
    return {
        "cells": [_cell(kind, source, i) for i, (kind, source) in enumerate(cells)],
        "metadata": {
            "kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
            "language_info": {"name": "python"},
            "ebantenna": {"exercise": name, "edition": edition},
        },
        "nbformat": 4,
        "nbformat_minor": 5,
    }


def zip_name(edition: str) -> str:
    """The file name of the zip of all notebooks of ``edition``."""
    return f"ebantenna-exercises-{edition}.zip"


def write_notebooks(exercises: Path, out: Path, edition: str = "student",
                    resolve=None) -> list[Path]:
    """Write ``out/<exercise>.ipynb`` for every ``ex*.rst`` page in ``exercises``, and the zip."""
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for page in sorted(exercises.glob("ex*.rst")):
        solution = (exercises / "solutions" / f"{page.stem}.py").read_text()
        notebook = exercise_notebook(page.read_text(), solution, page.stem, edition, resolve)
        path = out / f"{page.stem}.ipynb"
        path.write_text(json.dumps(notebook, indent=1, ensure_ascii=False) + "\n")
        written.append(path)
    with zipfile.ZipFile(out / zip_name(edition), "w", zipfile.ZIP_DEFLATED) as archive:
        for path in written:  # a fixed date: the same notebooks give the same zip
            info = zipfile.ZipInfo(f"exercises/{path.name}", date_time=(2024, 1, 1, 0, 0, 0))
            archive.writestr(info, path.read_bytes(), zipfile.ZIP_DEFLATED)
    return written


def _edition(env) -> str:
    return env.config.exercise_edition


class TeacherDirective(Directive):
    """``.. teacher:: answers|solution|notes``: content parsed in the teacher edition only."""

    required_arguments = 1
    has_content = True
    TITLES = {"answers": "Expected answers", "solution": "Worked solution",
              "notes": "For the teacher"}

    def run(self):
        kind = self.arguments[0]
        if kind not in self.TITLES:
            raise self.error(f"teacher: the kind must be one of {sorted(self.TITLES)}, "
                             f"got {kind!r}")
        if _edition(self.state.document.settings.env) != "teacher":
            return []  # never parsed: nothing of it reaches the doctree, the index or a download
        box = nodes.container(classes=["teacher", f"teacher-{kind}"])
        box += nodes.rubric(text=f"{self.TITLES[kind]} (teacher edition)")
        self.state.nested_parse(self.content, self.content_offset, box)
        return [box]


def _raw_link(href: str, text: str) -> nodes.raw:
    return nodes.raw("", f'<a class="reference download" href="{href}" download>{text}</a>',
                     format="html")


class ExerciseCheckDirective(Directive):
    """``.. exercise-check:: exNN_name``: the self-check section of an exercise page."""

    required_arguments = 1
    has_content = True

    def run(self):
        name, edition = self.arguments[0], _edition(self.state.document.settings.env)
        asked = asked_values(f".. exercise-check:: {name}\n\n"
                             + "".join(f"   {line}\n" for line in self.content), name)
        rows = "".join(f"   * - ``{n}``\n     - {t.describe()}\n     - {asked[n]}\n"
                       f"     - {t.reason}\n" for n, t in tolerances(name).items())
        call = textwrap.indent(_check_call(name, list(tolerances(name)), "{n}"), "   ")
        text = (
            ".. rubric:: Check your answers\n\n"
            "Compute these values, then check them with :func:`ebantenna.course.check`: it says "
            "whether each is within its tolerance of the expected answer, without showing the "
            "answer. A tolerance is how far two correct ways of working may differ.\n\n"
            ".. list-table::\n   :header-rows: 1\n   :class: exercise-checks\n\n"
            "   * - value\n     - tolerance\n     - what exactly\n     - why that much\n"
            + rows +
            "\n.. code-block:: python\n\n   from ebantenna.course import check\n\n" + call
        )
        section = nodes.container(classes=["exercise-check"])
        self.state.nested_parse(StringList(text.splitlines(), source=name), 0, section)
        what = ("statement, data, a cell per step, hints and the self-check"
                if edition == "student" else "with the expected answers and the worked solution")
        para = nodes.paragraph()
        para += nodes.Text(f"The Jupyter notebook of this exercise ({edition} edition: {what}): ")
        para += _raw_link(f"{name}.ipynb", f"{name}.ipynb")
        para += nodes.Text(".")
        return [section, para]


class ExerciseNotebooksDirective(Directive):
    """``.. exercise-notebooks::``: the link to the zip of the edition's notebooks."""

    def run(self):
        edition = _edition(self.state.document.settings.env)
        para = nodes.paragraph()
        para += nodes.Text(f"All the exercises as Jupyter notebooks ({edition} edition), in one "
                           "zip: ")
        para += _raw_link(zip_name(edition), zip_name(edition))
        para += nodes.Text(". Unpack it next to the site's pages (its folder exercises/ beside "
                           "theory/) so that the notebooks' links to the theory pages work.")
        return [para]


def _resolver(env):
    """Links to the built pages, relative to ``exercises/``, from Sphinx's inventory of names."""
    objects = env.get_domain("py").objects

    def resolve(kind, target):
        if kind == "doc":
            docname = posixpath.normpath(posixpath.join("exercises", target))
            if docname not in env.titles:
                return None
            return env.titles[docname].astext(), f"../{docname}.html"
        found = objects.get(target.removeprefix("~"))
        if found is None:
            return None
        return target, f"../{found.docname}.html#{found.node_id}"

    return resolve


def _on_build_finished(app, exception):
    if exception is not None or app.builder.format != "html":
        return
    write_notebooks(Path(app.srcdir) / "exercises", Path(app.outdir) / "exercises",
                    _edition(app.env), _resolver(app.env))


def _on_config_inited(app, config):
    if config.exercise_edition is None:  # not set in conf.py: the tag decides
        config.exercise_edition = "teacher" if app.tags.has("teacher") else "student"
    if config.exercise_edition not in EDITIONS:
        raise ValueError(f"exercise_edition must be one of {EDITIONS}, "
                         f"got {config.exercise_edition!r}")


def setup(app):
    app.add_config_value("exercise_edition", None, "env", types=[str, type(None)])
    app.connect("config-inited", _on_config_inited)
    app.add_directive("teacher", TeacherDirective)
    app.add_directive("exercise-check", ExerciseCheckDirective)
    app.add_directive("exercise-notebooks", ExerciseNotebooksDirective)
    app.connect("build-finished", _on_build_finished)
    return {"version": "2.0", "parallel_read_safe": True, "parallel_write_safe": True}
