"""Every exercise solution runs, checks its own answer, and is shown on its exercise page."""

import contextlib
import functools
import io
import re
import runpy
import warnings
from decimal import Decimal
from pathlib import Path

import make_answer_key
import pytest

from ebantenna.course import ANSWER_KEY, check, tolerances, unseal

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
def test_page_has_statement_hints_answers_and_solution_in_order(page):
    text = page.read_text()
    # statement, hints (folded), the self-check, then what only the teacher edition shows: the
    # expected answers and the worked solution, the script the tests run, included verbatim
    marks = [
        text.index("====\n"),
        text.index('<details class="hint">'),
        text.index(f".. exercise-check:: {page.stem}\n"),
        text.index(".. teacher:: answers\n"),
        text.index(".. teacher:: solution\n"),
        text.index(f"   .. literalinclude:: solutions/{page.stem}.py\n      :language: python\n"),
    ]
    assert marks == sorted(marks), marks
    assert text.count(".. teacher:: answers\n") == text.count(".. teacher:: solution\n") == 1
    assert text.count("<details") == text.count("</details>")
    # nothing of the answers or the solution outside the teacher blocks (which students never get)
    assert "<details class=\"solution\">" not in text and "<details class=\"answers\">" not in text
    before_teacher = text[: marks[3]]
    assert f"solutions/{page.stem}.py\n   :language: python\n\n" not in before_teacher


#: what makes an exercise's data random or generated: a seed, a random generator, a simulated rig
GENERATED = re.compile(r"default_rng|seed=|build_dataset|SimulatedRig|linspace|meshes = ")


@pytest.mark.parametrize("script", SOLUTIONS, ids=lambda p: p.stem)
def test_generated_data_is_stated_on_the_page(script):
    source = script.read_text()
    page = (DOCS / "exercises" / f"{script.stem}.rst").read_text()
    start, end = source.find("# [data]\n"), source.find("# [/data]\n")
    if start == -1:
        assert not GENERATED.search(source), "the solution makes generated data: mark them"
        assert end == -1
        return
    # the data are made between the markers, at the top (before the first step)
    assert 0 < start < end
    data = source[start:end]
    assert not re.search(r"^# 1\. ", source[:start], flags=re.M)
    # every seed the solution uses is in the data block or stated on the page (seed=0 of a split)
    statement = page[: page.index(".. teacher::")]
    for call, seed in re.findall(r"(default_rng\(|seed=)(\d+)", source):
        assert f"{call}{seed}" in data or f"seed={seed}" in statement, f"{call}{seed} unstated"
    include = (f".. literalinclude:: solutions/{script.stem}.py\n   :language: python\n"
               "   :class: exercise-code\n   :start-after: # [data]\n   :end-before: # [/data]\n")
    assert include in page
    assert page.index(include) < page.index(".. teacher::")


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
    """``name = value`` pairs of the teacher's "Expected answers" block of an exercise page."""
    start = text.index(".. teacher:: answers\n")
    block = text[start : text.index(".. teacher:: solution\n", start)]
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
    stated_tolerances = tolerances(page.stem)
    for name, text in stated.items():
        value = float(answers[name])
        if stated_tolerances[name].kind == "factor":
            # a size of rounding error: its digits depend on the order of the operations (the
            # library versions, the BLAS kernel), so the page's value is held to the factor the
            # self-check allows between two right answers
            width = stated_tolerances[name].width
            assert value / width <= float(text) <= value * width, (name, text)
            continue
        # the page rounds to its last printed digit: the value is within half a unit of it
        half_unit = 0.5 * 10.0 ** Decimal(text).as_tuple().exponent
        assert abs(value - float(text)) <= half_unit * (1 + 1e-9), (name, text)


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


# --- the answer key behind ebantenna.course.check ------------------------------------------------


def _key_value(stem: str, name: str, near: float) -> float:
    """The key's sealed answer, opened with a value near it (the solution's own)."""
    value = unseal(ANSWER_KEY[stem][name], tolerances(stem)[name], near)
    assert value is not None, f"{stem}.{name}: run python docs/_tools/make_answer_key.py"
    return value


@pytest.mark.parametrize("script", SOLUTIONS, ids=lambda p: p.stem)
def test_answer_key_is_what_the_solution_computes(script):
    namespace = run_solution(script)[0]
    computed = make_answer_key.entries(namespace["ANSWERS"], namespace["TOLERANCES"])
    key = ANSWER_KEY[script.stem]
    assert list(key) == list(computed), "run python docs/_tools/make_answer_key.py"
    for name, entry in computed.items():
        stored = key[name]
        assert {k: stored[k] for k in ("kind", "width", "reason")} == {
            k: entry[k] for k in ("kind", "width", "reason")
        }, name
        assert "value" not in stored  # sealed: no answer in readable form
        # The key was written on one machine; another NumPy, SciPy or BLAS kernel rounds the
        # solution's arithmetic differently (an order of convergence from differences of small
        # errors moves in its seventh digit). A stale key moves by more than a hundredth of the
        # tolerance; a rounding error of size ("factor") is held to its factor.
        value, width = entry["value"], entry["width"]
        sealed = _key_value(script.stem, name, value)
        if entry["kind"] == "factor":
            assert value / width <= sealed <= value * width, name
        else:
            scale = width * abs(value) if entry["kind"] == "rel" else width
            assert abs(sealed - value) <= 0.01 * scale, name


@pytest.mark.parametrize("script", SOLUTIONS, ids=lambda p: p.stem)
def test_each_check_accepts_the_solution_and_rejects_just_outside(script):
    answers = run_solution(script)[0]["ANSWERS"]
    stated = tolerances(script.stem)
    assert check(script.stem, **{n: float(v) for n, v in answers.items()}).ok
    for name in answers:
        # around the key's value, which the check compares with (the solution's value on this
        # machine may differ from it by rounding, see the test above)
        value, tol = _key_value(script.stem, name, float(answers[name])), stated[name]
        assert tol.reason and len(tol.reason) < 140  # one line
        if tol.kind == "abs":
            outside = [value + tol.width + max(1e-6, 1e-3 * tol.width)]
            outside.append(value - tol.width - max(1e-6, 1e-3 * tol.width))
            inside = [value + tol.width * 0.999, value - tol.width * 0.999]
        elif tol.kind == "rel":
            outside = [value * (1 + 1.001 * tol.width), value * (1 - 1.001 * tol.width)]
            inside = [value * (1 + 0.999 * tol.width), value * (1 - 0.999 * tol.width)]
        else:
            outside, inside = [value * tol.width * 1.001, value / tol.width / 1.001], [
                value * tol.width * 0.999, value / tol.width * 1.001]
        if value == 0 and tol.kind != "abs":
            pytest.fail(f"{name}: a relative tolerance of a zero answer accepts nothing else")
        for v in outside:
            report = check(script.stem, **{name: v})
            assert not report.ok and "not yet" in str(report), (name, v)
        for v in inside:
            assert check(script.stem, **{name: v}).ok, (name, v)
        # the verdict never shows the answer
        shown = str(check(script.stem, **{name: outside[0]})).removeprefix(f"{name}: ")
        assert f"{value:.3g}" not in shown, shown


def test_ex13_linear_contact_numbers_as_stated(tmp_path):
    # ex13's answers quote what the same design gives with a linear contact (the paper scene
    # without unilateral_contact): the solution run on that scene, to the digits the page prints
    page = (DOCS / "exercises" / "ex13_mode_curves.rst").read_text()
    accuracy, distance = re.search(
        r"the same design gives about ([0-9.]+) and ([0-9.]+) cm", " ".join(page.split())
    ).groups()
    source = (DOCS / "exercises" / "solutions" / "ex13_mode_curves.py").read_text()
    scene = 'builtin_scene("paper")'
    assert source.count(scene) == 1
    linear = (f"{scene}.with_(effects=[e for e in {scene}.effects "
              'if e.name != "unilateral_contact"])')
    script = tmp_path / "ex13_linear.py"
    script.write_text(source.replace(scene, linear))
    answers = run_solution(script)[0]["ANSWERS"]
    for stated, value in ((accuracy, answers["curve_accuracy"]),
                          (distance, answers["distance_cm"])):
        half_unit = 0.5 * 10.0 ** Decimal(stated).as_tuple().exponent  # "about": printed digits
        assert abs(value - float(stated)) <= half_unit, (stated, value)


def test_answer_key_module_is_the_tools_output():
    # written by docs/_tools/make_answer_key.py, not by hand: its text is the tool's text of it
    text = make_answer_key.module_text(ANSWER_KEY)
    assert make_answer_key.MODULE.read_text() == text
    assert "'value'" not in text
    namespace = {}
    exec(compile(text, str(make_answer_key.MODULE), "exec"), namespace)
    assert namespace["ANSWER_KEY"] == ANSWER_KEY
    with pytest.raises(ValueError, match="every answer needs a tolerance"):
        make_answer_key.entries({"a": 1.0, "b": 2.0}, {"a": ("abs", 0, "a count")})


# --- what a student installs: the wheel and the sdist hold no answer and no solution ------------


def _distributions(tmp: Path) -> dict[str, str]:
    """The text of every file of the sdist and of the wheel (or, without the ``wheel`` package,
    of what its pure-Python build copies: ``build_py``'s output), by name."""
    import shutil
    import subprocess
    import sys
    import tarfile
    import zipfile

    root = DOCS.parent
    project = tmp / "project"
    project.mkdir()
    for name in ("pyproject.toml", "README.md", "MANIFEST.in", "setup.py", "setup.cfg", "LICENSE"):
        if (root / name).is_file():
            shutil.copy(root / name, project / name)
    shutil.copytree(root / "ebantenna", project / "ebantenna",
                    ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    out = tmp / "dist"
    build = ("import sys, setuptools.build_meta as b\n"
             "out = sys.argv[1]\n"  # build_meta resets sys.argv
             "b.build_sdist(out)\n"
             "try:\n    import wheel  # noqa: F401\nexcept ImportError:\n"
             "    sys.argv[1:] = ['build_py', '--build-lib', out + '/purelib']\n"
             "    import setuptools; setuptools.setup()\n"
             "else:\n    b.build_wheel(out)\n")
    subprocess.run([sys.executable, "-c", build, str(out)], cwd=project, check=True,
                   capture_output=True)
    texts = {}
    for path in out.rglob("*"):
        if path.suffix == ".gz":
            with tarfile.open(path) as archive:
                for member in archive.getmembers():
                    if member.isfile():
                        data = archive.extractfile(member).read()
                        texts[f"sdist:{member.name}"] = data.decode("utf-8", "replace")
        elif path.suffix == ".whl":
            with zipfile.ZipFile(path) as archive:
                for member in archive.namelist():
                    texts[f"wheel:{member}"] = archive.read(member).decode("utf-8", "replace")
        elif path.is_file():
            texts[f"wheel:{path.relative_to(out)}"] = path.read_text("utf-8", "replace")
    assert any(n.startswith("sdist:") for n in texts) and any(n.startswith("wheel:") for n in texts)
    return texts


def _searched_forms(value: float) -> set[str]:
    """How a student would search for an answer: its repr and its roundings to 3 to 8
    significant digits, as ``%g`` and fixed-point. Forms of fewer than three significant digits
    ("0.2", "13", "1024") are left out: they are everywhere in any source and give nothing away
    that a few tries of the self-check would not."""
    forms = {repr(value), repr(float(value))}
    for digits in range(3, 9):
        forms.add(f"{value:.{digits}g}")
        forms.add(f"{value:.{digits - 1}e}")
    return {f for f in forms if len(re.sub(r"[^1-9]", "", f.split("e")[0])) >= 3}


def test_wheel_and_sdist_hold_no_answer_and_no_solution(tmp_path):
    from exercise_secrets import answer_pairs, solution_lines

    texts = _distributions(tmp_path)
    assert any(name.endswith("course/_answer_key.py") for name in texts)  # the sealed key ships
    assert not any("solutions/" in name or name.endswith(".rst") for name in texts)
    # every number-like token and every stripped line of every file, searched once
    tokens, lines = {}, {}
    for name, text in texts.items():
        for token in re.findall(r"\d[\d.]*(?:[eE][-+]?\d+)?", text):
            tokens.setdefault(token.rstrip("."), set()).add(name)
        for line in text.splitlines():
            lines.setdefault(line.strip(), set()).add(name)
    found = []
    for script in SOLUTIONS:
        answers = run_solution(script)[0]["ANSWERS"]
        pairs = answer_pairs(script.stem)
        if script.stem == "ex01_element":
            # the exercise derives the element's mass matrix and checks it against the package's
            # (ebantenna.fem.symbolic), so its answers are the package's own textbook matrix;
            # its solution's lines are still searched
            answers, pairs = {}, []
        numbers = {f.lstrip("-") for v in answers.values() for f in _searched_forms(float(v))}
        numbers |= {pair.split(" = ")[1].lstrip("-") for pair in pairs
                    if len(re.sub(r"[^1-9]", "", pair.split(" = ")[1])) >= 3}
        found += [(script.stem, n, sorted(tokens[n])[:3]) for n in numbers if n in tokens]
        found += [(script.stem, line, sorted(lines[line])[:3])
                  for line in solution_lines(script.stem) if line in lines]
    assert not found, found


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.stem)
def test_every_checked_value_is_defined_in_the_students_statement(page):
    # a value the self-check checks but the statement never asks, or asks without saying which of
    # several right values (which meshes, which normalisation, which unit), rejects right answers
    import exercise_notebooks

    text = page.read_text()
    asked = exercise_notebooks.asked_values(text, page.stem)
    assert list(asked) == list(tolerances(page.stem))
    for name, definition in asked.items():
        assert len(definition.split()) >= 4, (name, definition)
    statement = text[: text.index(".. teacher::")]
    assert all(f":{name}: " in statement for name in asked)
    with pytest.raises(ValueError, match="must define every checked value"):
        exercise_notebooks.asked_values(text.replace(f"   :{next(iter(asked))}: ", "   :x: "),
                                        page.stem)
