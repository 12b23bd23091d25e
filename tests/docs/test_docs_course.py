"""The course tracks fit their sessions, cover every exercise and theory page, and point only at
pages that exist; the session sheets say what a student needs."""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import course_tracks as course
import pytest

DOCS = Path(__file__).resolve().parents[2] / "docs"
EXERCISES = sorted(f"exercises/{p.stem}" for p in (DOCS / "exercises").glob("ex*.rst"))
THEORY = sorted(f"theory/{p.stem}" for p in (DOCS / "theory").glob("*.rst") if p.stem != "index")
EXAMPLES = sorted(f"auto_examples/{p.stem}" for p in (DOCS / "examples").glob("plot_*.py"))
TRACKS = list(course.TRACKS.values())
IDS = [t.key for t in TRACKS]


def _assigned(track, field):
    return [d for s in track.sessions for d in getattr(s, field)]


def _source_of(docname: str) -> Path:
    """The file a document name comes from (gallery pages come from docs/examples)."""
    if docname.startswith("auto_examples/"):
        return DOCS / "examples" / f"{docname.split('/', 1)[1]}.py"
    return DOCS / f"{docname}.rst"


def test_the_three_tracks():
    assert sorted(course.TRACKS) == [4, 6, 7]
    assert all(len(t.sessions) == n for n, t in course.TRACKS.items())


@pytest.mark.parametrize("track", TRACKS, ids=IDS)
def test_work_in_class_of_every_session_fits_its_budget(track):
    for i, session in enumerate(track.sessions, 1):
        minutes = course.class_minutes(track, session)
        assert minutes == (session.presented_minutes + course.examples_minutes(session)
                           + course.core_minutes(track, session))
        assert minutes <= course.BUDGET, f"{track.key} session {i}: {minutes} min"
    assert course.overloaded({len(track.sessions): track}) == []


@pytest.mark.parametrize("track", TRACKS, ids=IDS)
def test_the_last_session_sets_no_homework(track):
    # every goal is reached in class or before the last session: after it come only the
    # "further" exercises, beyond the course's goals
    last = track.sessions[-1]
    assert all(track.roles[e] in ("core", "optional", "further") for e in last.exercises)
    assert any(track.roles[e] == "core" for e in last.exercises)


def test_an_overloaded_session_is_reported(monkeypatch):
    # one more core exercise, or one more example, in the fullest session must push it over
    track = course.TRACKS[7]
    fullest = max(track.sessions, key=lambda s: course.class_minutes(track, s))
    extra = "exercises/ex02_assembly"
    heavy = dataclasses.replace(fullest, exercises=fullest.exercises + (extra,))
    sessions = tuple(heavy if s is fullest else s for s in track.sessions)
    bad = course.Track(sessions, {**track.roles, extra: "core"})
    assert course.overloaded({7: bad}) and "session" in course.overloaded({7: bad})[0]
    slack = course.BUDGET - course.class_minutes(track, fullest)
    longest = "auto_examples/plot_01_two_element_modes"
    assert course.example_minutes(longest) > slack  # one more example does not fit either
    busy = dataclasses.replace(fullest, examples=fullest.examples + (longest,))
    bad = course.Track(tuple(busy if s is fullest else s for s in track.sessions), track.roles)
    assert course.overloaded({7: bad})
    # and homework after the last session is refused
    last = track.sessions[-1]
    further = next(e for e in last.exercises if track.roles[e] == "further")
    bad = course.Track(track.sessions, {**track.roles, further: "homework"})
    assert "homework after the course" in course.overloaded({7: bad})[0]
    # the build refuses it
    monkeypatch.setitem(course.TRACKS, 7, bad)
    with pytest.raises(ValueError, match="homework after the course"):
        course.write_sheets()  # refused before anything is written


def test_example_minutes_count_its_run_and_its_figures(tmp_path):
    # the cost of an example follows its source: a minute to run, two per figure it draws
    for docname in EXAMPLES:
        source = _source_of(docname).read_text()
        figures = source.count("plt.subplots(") + source.count("plt.figure(")
        assert figures >= 1, docname
        assert course.example_minutes(docname) == course.RUN_MINUTES + 2 * figures
    with pytest.raises(FileNotFoundError, match="plot_99"):
        course.example_minutes("auto_examples/plot_99", tmp_path)


def test_minutes_are_the_pages_own(tmp_path):
    for docname in EXERCISES:
        stated = re.search(r":Time: about (\d+) minutes", _source_of(docname).read_text())
        assert course.exercise_minutes(docname) == int(stated.group(1))
    (tmp_path / "exercises").mkdir()
    (tmp_path / "exercises" / "ex99.rst").write_text("Ex\n==\n\n:Time: a while\n")
    with pytest.raises(ValueError, match="Time"):
        course.exercise_minutes("exercises/ex99", tmp_path)


@pytest.mark.parametrize("track", TRACKS, ids=IDS)
def test_every_exercise_once_in_every_track_with_a_role(track):
    assigned = _assigned(track, "exercises")
    assert sorted(assigned) == EXERCISES  # each page once, none missing, none unknown
    assert sorted(track.roles) == EXERCISES
    assert set(track.roles.values()) <= set(course.ROLES)


@pytest.mark.parametrize("track", TRACKS, ids=IDS)
def test_every_theory_page_read_and_every_example_run(track):
    assert set(THEORY) <= set(_assigned(track, "reading"))
    assert sorted(_assigned(track, "examples")) == EXAMPLES


def test_every_referenced_page_exists():
    for track in TRACKS:
        for field in ("reading", "examples", "exercises"):
            for docname in _assigned(track, field):
                assert _source_of(docname).is_file(), f"{track.key}: {docname}"


def test_the_kalman_page_has_its_exercise_in_its_session():
    for track in TRACKS:
        session = next(s for s in track.sessions if "theory/kalman" in s.reading)
        assert "exercises/ex14_kalman" in session.exercises, track.key


def test_sheet_has_goals_reading_exercises_and_what_to_prepare():
    track = course.TRACKS[7]
    for number, session in enumerate(track.sessions, 1):
        sheet = course.session_sheet(track, number)
        for heading in ("Goals", "Read before the session", "Presented in class",
                        "Run in class", "Exercises", "Prepare for next time"):
            assert f"\n{heading}\n" in sheet
        for docname in session.reading + session.examples:
            assert f":doc:`/{docname}`" in sheet
        for docname in session.exercises:
            line = f":doc:`/{docname}` ({track.roles[docname]}, "
            assert line + f"{course.exercise_minutes(docname)} min)" in sheet
        if number < len(track.sessions):  # the next session's reading is announced
            for docname in track.sessions[number].reading:
                assert f"read :doc:`/{docname}`" in sheet


def test_table_and_sheets_show_the_minutes_of_every_session():
    for track in TRACKS:
        table = "\n".join(course.track_table(track))
        for number, session in enumerate(track.sessions, 1):
            line = (f"{session.presented_minutes} presented + {course.examples_minutes(session)} "
                    f"examples + {course.core_minutes(track, session)} core = "
                    f"{course.class_minutes(track, session)} of {course.BUDGET}")
            assert line in table and line in course.session_sheet(track, number)


def test_sheets_are_written_and_left_alone_when_unchanged(tmp_path):
    # the exercise pages and examples are read from a copy of docs/, so the sheets land in
    # tmp_path
    (tmp_path / "exercises").mkdir()
    (tmp_path / "examples").mkdir()
    for docname in EXERCISES + EXAMPLES:
        (tmp_path / _source_of(docname).relative_to(DOCS)).write_text(
            _source_of(docname).read_text())
    written = course.write_sheets(docs=tmp_path)
    assert len(written) == sum(len(t.sessions) for t in TRACKS)
    stamps = [p.stat().st_mtime_ns for p in written]
    assert course.write_sheets(docs=tmp_path) == written
    assert [p.stat().st_mtime_ns for p in written] == stamps


def test_course_page_has_every_track_and_no_ascii_powers():
    text = (DOCS / "course.rst").read_text()
    for n in course.TRACKS:
        assert f".. course-track:: {n}\n" in text
    sheets = [course.session_sheet(t, i) for t in TRACKS for i in range(1, len(t.sessions) + 1)]
    for page in [text, *sheets]:
        assert not re.search(r"\w\^\d", page), "write h⁴ or :math:`h^4`, not h^4"
    assert "   course\n" in (DOCS / "index.rst").read_text()  # in the site's toctree


def test_the_course_page_says_what_the_tracks_hold():
    from collections import Counter

    text = " ".join((DOCS / "course.rst").read_text().split())
    roles = Counter(course.TRACKS[4].roles.values())
    words = dict(enumerate(["no", "one", "two", "three", "four", "five", "six", "seven"]))
    assert (f"{words[roles['core']]} exercises are done in class and {words[roles['homework']]} "
            "are homework") in text.lower()
    splits = "exercises/ex12_splits"
    assert course.TRACKS[4].roles[splits] == "further"
    where = {n: next(i for i, s in enumerate(t.sessions, 1) if splits in s.exercises)
             for n, t in course.TRACKS.items()}
    assert all(course.TRACKS[n].roles[splits] == "homework" for n in (6, 7))
    assert f"(session {where[7]} of seven, {where[6]} of six)" in text
    design = "exercises/ex15_design_effect"
    assert all(t.roles[design] == "homework" for t in course.TRACKS.values())


#: how a symbol of the notation table is written in a page's source
_WRITTEN = {"ρ": (r"\rho", "ρ"), "α": (r"\alpha", "α"), "η": (r"\eta", "η"),
            "β": (r"\beta", "β"), "λ": (r"\lambda", "λ"), "γ": (r"\gamma", "γ")}


def _notation_rows() -> list[tuple[str, str, list[str]]]:
    text = (DOCS / "glossary.rst").read_text()
    table = text.split("Symbols with more than one meaning", 1)[1].split("\nGlossary\n", 1)[0]
    rows = re.findall(r"   \* - (\S+)\n     - (.*)\n     - (.*)\n", table)
    return [(s, m, re.findall(r":doc:`([^`]+)`", pages)) for s, m, pages in rows[1:]]


def test_the_notation_lists_every_symbol_that_changes_meaning_with_its_pages():
    rows = _notation_rows()
    meanings = {}
    for symbol, meaning, pages in rows:
        meanings.setdefault(symbol, []).append(meaning)
        assert pages, (symbol, meaning)
        for page in pages:  # each page named for a meaning uses the symbol
            source = (DOCS / f"{page}.rst").read_text()
            forms = _WRITTEN.get(symbol, ())
            found = any(f in source for f in forms) or re.search(
                rf"(?<![A-Za-z\\]){symbol}(?![A-Za-z])", source)
            assert found, (symbol, page)
    # the symbols a reader of the course meets with more than one meaning, each with two or more
    # (η is the loss factor only: the MLP page writes its learning rate lr)
    assert {"P", "Q", "K", "b", "a", "L", "ρ", "α", "β", "λ", "C"} <= set(meanings)
    assert "η" not in meanings
    assert all(len(m) >= 2 for m in meanings.values()), meanings
