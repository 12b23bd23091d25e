"""Graded variants: every student's own answers, for the teacher, and a sealed key, for them.

For an exercise with graded variants (:data:`ebantenna.course.VARIANTS`: ex04, ex05 and ex06, the
core exercises of the four-session track whose answers depend on data), this script runs the
worked solution once per student, with the data block's ``STUDENT = None`` replaced by the
student's id, so that :func:`ebantenna.course.parameters` draws that student's data. It writes

* ``exNN_answers.csv``: the teacher's answer sheet, one row per student (the id, the
  parameters, every expected answer to full precision);
* ``exNN_key.json``: the sealed key of every student's answers (no value in readable form,
  see :func:`ebantenna.course.seal`; each student named by a hash of the id, not the id),
  handed to the students with their ids. A student checks
  with ``check("ex05", student="s1234", key="ex05_key.json", tau_fit_ms=...)``.

Usage, from a clone of the repository::

    python docs/_tools/make_variant_key.py ex05 students.txt --out grading/

``students.txt`` holds one id a line (blank lines and ``#`` comments skipped).
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import io
import json
import secrets
import sys
from pathlib import Path

from ebantenna.course import (
    KEY_FORMAT,
    VARIANTS,
    Tolerance,
    parameters,
    seal,
    student_tag,
    tolerances,
)

ROOT = Path(__file__).resolve().parents[2]
SOLUTIONS = ROOT / "docs" / "exercises" / "solutions"
#: the line of a data block that a variant replaces
STUDENT_LINE = "STUDENT = None"

__all__ = ["read_ids", "solution_for", "answers_for", "variant_key", "main"]


def read_ids(text: str) -> list[str]:
    """The student ids of a list: one a line, blank lines and ``#`` comments skipped; raises
    ValueError on a repeated id."""
    ids = [line.split("#", 1)[0].strip() for line in text.splitlines()]
    ids = [i for i in ids if i]
    repeated = sorted({i for i in ids if ids.count(i) > 1})
    if repeated:
        raise ValueError(f"each student id once, repeated: {repeated}")
    if not ids:
        raise ValueError("the list of students is empty")
    return ids


def solution_for(exercise: str, student: str | None) -> str:
    """The worked solution's source with the data block's student set to ``student``."""
    (script,) = SOLUTIONS.glob(f"{exercise.split('_')[0]}_*.py")
    source = script.read_text(encoding="utf-8")
    if source.count(STUDENT_LINE) != 1:
        raise ValueError(f"{script.name} must set '{STUDENT_LINE}' once in its data block")
    return source.replace(STUDENT_LINE, f"STUDENT = {student!r}", 1)


def answers_for(exercise: str, student: str | None) -> dict[str, float]:
    """Run the worked solution for one student (its own checks included) and return ANSWERS."""
    namespace = {"__name__": "__main__"}
    with contextlib.redirect_stdout(io.StringIO()):
        exec(compile(solution_for(exercise, student), f"{exercise}:{student}", "exec"), namespace)
    return {name: float(value) for name, value in namespace["ANSWERS"].items()}


def variant_key(exercise: str, answers: dict[str, dict[str, float]],
                salt: str | None = None) -> dict:
    """The sealed key of every student's answers (``{student: {name: value}}``).

    Each student is named by :func:`ebantenna.course.student_tag` of the key's ``salt`` (a
    random one unless given) and their id; the id appears nowhere in the key.
    """
    stated: dict[str, Tolerance] = tolerances(exercise)
    salt = secrets.token_hex(8) if salt is None else salt
    students = {}
    for student, values in answers.items():
        tag = student_tag(salt, student)
        students[tag] = {name: seal(value, stated[name], f"{exercise}/{tag}/{name}")
                         for name, value in values.items()}
    return {"format": KEY_FORMAT, "exercise": exercise, "salt": salt, "students": students}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("exercise", help=f"one of {sorted(VARIANTS)} (or its exNN prefix)")
    parser.add_argument("students", type=Path, help="a text file of student ids, one a line")
    parser.add_argument("--out", type=Path, default=Path("."), help="folder to write into")
    args = parser.parse_args(argv)
    exercise = next((n for n in VARIANTS if args.exercise in (n, n.split("_")[0])), None)
    if exercise is None:
        parser.error(f"exercise must be one of {sorted(VARIANTS)}, got {args.exercise!r}")
    ids = read_ids(args.students.read_text(encoding="utf-8"))
    answers = {student: answers_for(exercise, student) for student in ids}
    args.out.mkdir(parents=True, exist_ok=True)
    short = exercise.split("_")[0]
    sheet = args.out / f"{short}_answers.csv"
    with sheet.open("w", newline="", encoding="utf-8") as stream:
        names = list(tolerances(exercise))
        keys = list(VARIANTS[exercise])
        writer = csv.writer(stream)
        writer.writerow(["student", *keys, *names])
        for student in ids:
            drawn = parameters(exercise, student=student)
            writer.writerow([student, *(drawn[k] for k in keys),
                             *(repr(answers[student][n]) for n in names)])
    key = args.out / f"{short}_key.json"
    key.write_text(json.dumps(variant_key(exercise, answers), indent=1), encoding="utf-8")
    print(f"wrote {sheet} (for the teacher) and {key} (for the students)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
