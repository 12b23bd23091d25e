"""Write ``ebantenna/course/_answer_key.py``: the key behind :func:`ebantenna.course.check`.

Every worked solution in ``docs/exercises/solutions/`` ends with two dictionaries: ``ANSWERS``
(name -> value) and ``TOLERANCES`` (name -> ``(kind, width, reason)``); a solution whose answers
count (recordings of a held-out set, restrikes, whole positions) adds ``STEPS`` (name -> the
answer's step): another machine's last-bit rounding may move such an answer by one step, so the
tests hold the key and the page to the solution within one step, and the step must lie within
the answer's ``"abs"`` tolerance, which grades the students' answers. This script runs each
solution and writes the tolerances and the *sealed* answers (:func:`ebantenna.course.seal`:
stretched, salted hashes of the cells within the answer's tolerance, never the value) into one
module of the package, so that a student's self-check needs neither the solutions nor the
documentation, and the installed package holds no answer in readable form. Next to the
solutions, in the repository only, it writes the same answers in plain form,
``docs/exercises/solutions/answers.json`` (the teacher's sheet of the published exercises, and
what the test of the wheel searches it for).
Run it after changing a solution::

    python docs/_tools/make_answer_key.py

``tests/docs/test_docs_exercises.py`` fails while the module differs from what the solutions
compute.
"""

from __future__ import annotations

import contextlib
import io
import json
import runpy
import sys
import textwrap
from pathlib import Path

from ebantenna.course import Tolerance, seal

ROOT = Path(__file__).resolve().parents[2]
SOLUTIONS = ROOT / "docs" / "exercises" / "solutions"
MODULE = ROOT / "ebantenna" / "course" / "_answer_key.py"
PLAIN = SOLUTIONS / "answers.json"

__all__ = ["entries", "sealed", "computed", "answer_key", "plain_text", "module_text", "main"]

HEADER = '''"""Sealed answers of the exercises and their tolerances: ebantenna.course's key.

Written by ``docs/_tools/make_answer_key.py`` from the worked solutions in
``docs/exercises/solutions/``; do not edit by hand. Each answer is held as the stretched, salted
hashes of the cells within its tolerance (see :func:`ebantenna.course.seal`), not as a value.
The test suite checks that it seals what the solutions compute.
"""

'''


def entries(answers: dict, tolerances: dict) -> dict[str, dict]:
    """One solution's answers and tolerances as ``{name: {value, kind, width, reason}}``."""
    if set(answers) != set(tolerances):
        raise ValueError(
            f"every answer needs a tolerance: answers {sorted(answers)}, "
            f"tolerances {sorted(tolerances)}"
        )
    out = {}
    for name in answers:
        kind, width, reason = tolerances[name]
        out[name] = {"value": float(answers[name]), "kind": kind, "width": float(width),
                     "reason": reason}
    return out


def sealed(exercise: str, entries_: dict[str, dict]) -> dict[str, dict]:
    """The key's form of one exercise's entries: the value replaced by its seal."""
    out = {}
    for name, entry in entries_.items():
        tolerance = Tolerance(entry["kind"], entry["width"], entry["reason"])
        out[name] = {"kind": entry["kind"], "width": entry["width"], "reason": entry["reason"],
                     **seal(entry["value"], tolerance, f"{exercise}/{name}")}
    return out


def _run(script: Path) -> dict:
    with contextlib.redirect_stdout(io.StringIO()):
        return runpy.run_path(str(script), run_name="__main__")


def computed(solutions: Path = SOLUTIONS, run=_run) -> dict[str, dict[str, dict]]:
    """The entries (values included) of every solution script ``ex*.py``, by exercise name."""
    out = {}
    for script in sorted(solutions.glob("ex*.py")):
        namespace = run(script)
        out[script.stem] = entries(namespace["ANSWERS"], namespace["TOLERANCES"])
    return out


def answer_key(solutions: Path = SOLUTIONS, run=_run) -> dict[str, dict[str, dict]]:
    """The sealed key of every solution script ``ex*.py`` in ``solutions``, by exercise name."""
    return {name: sealed(name, found) for name, found in computed(solutions, run).items()}


def plain_text(found: dict[str, dict[str, dict]]) -> str:
    """``answers.json``: every expected answer in plain form, ``{exercise: {name: value}}``."""
    plain = {name: {n: e["value"] for n, e in values.items()} for name, values in found.items()}
    return json.dumps(plain, indent=1) + "\n"


def module_text(key: dict) -> str:
    """The source of ``ebantenna/course/_answer_key.py`` holding the sealed ``key``."""
    lines = [HEADER, "ANSWER_KEY = {\n"]
    for exercise, answers in key.items():
        lines.append(f"    {exercise!r}: {{\n")
        for name, entry in answers.items():
            reason = textwrap.wrap(entry["reason"], 80, drop_whitespace=False)
            lines += [
                f"        {name!r}: {{\n",
                f"            'kind': {entry['kind']!r}, 'width': {entry['width']!r},\n",
                f"            'salt': {entry['salt']!r},\n",
                f"            'kdf': {entry['kdf']!r},\n",
                "            'cells': [\n",
                *(f"                {', '.join(repr(c) for c in entry['cells'][i:i + 4])},\n"
                  for i in range(0, len(entry['cells']), 4)),
                "            ],\n",
                "            'reason': (\n",
                *(f"                {part!r}\n" for part in reason),
                "            ),\n",
                "        },\n",
            ]
        lines.append("    },\n")
    lines.append("}\n")
    return "".join(lines)


def main() -> int:
    found = computed()
    MODULE.write_text(module_text({name: sealed(name, v) for name, v in found.items()}))
    PLAIN.write_text(plain_text(found))
    print(f"wrote {MODULE.relative_to(ROOT)} and {PLAIN.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
