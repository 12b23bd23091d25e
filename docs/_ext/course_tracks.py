"""The course as data: tracks of 4, 6 and 7 sessions of 90 minutes, and their pages.

One description serves the course page, the session sheets and the tests. A :class:`Session` says
what a student reads before it, what the teacher presents (with minutes), which gallery examples
are run and which exercises belong to it; a :class:`Track` is a list of sessions and, for each
exercise, its role in that track: **core** (done in class, counted in the session's budget),
**optional** (in class if time is left, otherwise at home), **homework** (before the next
session) or **further** (after the course, beyond its goals). The last session has no homework:
every goal is reached in class or before the last session. An exercise's minutes are read from
its page's ``:Time: about N minutes`` field, never written here; a gallery example's from its
source (:func:`example_minutes`).

When the build starts, :func:`write_sheets` writes one page per session into ``docs/course/``
(only pages whose text changed, so that a build stays incremental), and the ``course-tracks``
directive puts the three tracks on the course page as tables. The build stops if a session's
presentation, examples and core exercises do not fit its budget, or if the last session leaves
homework.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

__all__ = [
    "BUDGET", "ROLES", "Session", "Track", "TRACKS", "exercise_minutes", "example_minutes",
    "examples_minutes", "core_minutes", "class_minutes", "overloaded", "track_table",
    "session_sheet", "sheet_name", "write_sheets", "setup",
]  # fmt: skip

#: Length of a session, min.
BUDGET = 90
#: What an exercise can be in a track.
ROLES = ("core", "optional", "homework", "further")
#: Minutes to run a gallery example in class: each runs in 4 to 11 s on one core of a shared
#: machine (``python docs/examples/plot_NN_*.py``, measured for all thirteen), so a minute covers
#: starting it and reading its printed lines on a student's laptop.
RUN_MINUTES = 1
#: Minutes to read one figure of an example with the class: say what is plotted, point at what
#: the session is about in it.
FIGURE_MINUTES = 2
#: Where the pages are, relative to this file.
DOCS = Path(__file__).resolve().parents[1]
_TIME = re.compile(r"^:Time: about (\d+) minutes$", re.M)
_FIGURE = re.compile(r"\bplt\.(?:subplots|figure)\(")


@dataclass(frozen=True)
class Session:
    """One session of 90 minutes, independent of the track it is in.

    ``reading``, ``examples`` and ``exercises`` are Sphinx document names (``theory/element``);
    ``presented`` lists what the teacher shows in class as ``(topic, minutes)``.
    """

    title: str
    goals: tuple[str, ...]
    reading: tuple[str, ...]
    presented: tuple[tuple[str, int], ...]
    examples: tuple[str, ...]
    exercises: tuple[str, ...]

    @property
    def presented_minutes(self) -> int:
        """Minutes the teacher presents."""
        return sum(minutes for _, minutes in self.presented)


@dataclass(frozen=True)
class Track:
    """A course of ``len(sessions)`` sessions and the role of each exercise in it."""

    sessions: tuple[Session, ...]
    roles: dict

    @property
    def key(self) -> str:
        """Name of the track's pages: ``track7`` for seven sessions."""
        return f"track{len(self.sessions)}"


def _ex(name: str) -> str:
    return f"exercises/{name}"


def _run(name: str) -> str:
    return f"auto_examples/{name}"


RIG_INTRO = ("The rig: its parts, and the driver reading the FIFO on the simulated bus", 5)
RIG_GOAL = "name the rig's parts and see its driver read the accelerometer on the simulated bus"

ELEMENT = Session(
    "The probe as a beam: the Euler–Bernoulli element, and the rig",
    ("derive the element's shape functions, stiffness and mass matrices with sympy",
     "check a mass matrix by the total mass, and tell the consistent from the lumped one",
     RIG_GOAL),
    ("theory/element", "user_guide/rig"),
    (("The Euler–Bernoulli equation and the cubic element", 15),
     ("Shape functions, stiffness and consistent mass, derived with sympy", 20),
     RIG_INTRO),
    (_run("plot_01_two_element_modes"), _run("plot_12_device_simulated_bus")),
    (_ex("ex01_element"),),
)
ASSEMBLY = Session(
    "Assembly, supports and the paper's two-element model",
    ("assemble elements into a beam and apply the hinge P and the contact Q",
     "find which of the paper's printed matrix entries are typos"),
    ("theory/assembly", "theory/errata"),
    (("Assembly: the DOFs of a shared node add", 15),
     ("Supports: the hinge P, the contact Q, the free tip R", 10),
     ("The paper's printed matrices and their errata", 10)),
    (_run("plot_05_errata"),),
    (_ex("ex02_assembly"),),
)
BEAM = Session(
    "The probe as a beam: element, assembly and the paper's model, and the rig",
    ELEMENT.goals[:2] + ASSEMBLY.goals + (RIG_GOAL,),
    ELEMENT.reading + ASSEMBLY.reading,
    (("The Euler–Bernoulli element and its matrices, derived with sympy", 25),
     ("Assembly and supports: P, Q and R", 10),
     ("The printed matrices and their errata", 5),
     RIG_INTRO),
    ELEMENT.examples + ASSEMBLY.examples,
    ELEMENT.exercises + ASSEMBLY.exercises,
)
MODES = Session(
    "Modes and their accuracy: the eigenproblem and convergence as h⁴",
    ("solve the generalized eigenproblem K φ = ω² M φ of a supported beam, and say why a plain "
     "scipy.linalg.eigh(K, M) loses the low modes on a fine mesh",
     "measure an order of convergence and say how many digits a frequency has and what the "
     "next digit costs"),
    ("theory/eigenproblem", "theory/convergence"),
    (("The generalized eigenproblem K φ = ω² M φ, solved stably", 15),
     ("Convergence to the exact solution, from above, as h⁴", 15)),
    (_run("plot_02_convergence"), _run("plot_03_naive_eigensolver")),
    (_ex("ex03_convergence"), _ex("ex09_mesh_budget")),
)
ZONES = Session(
    "Where the probe was touched: the three zones of the dominant mode",
    ("explain why the dominant frequency is not a monotonic function of the contact position",
     "say what the touched object adds to the probe's modes"),
    ("theory/zones", "theory/touched_object"),
    (("The zones of the lowest mode, and why the frequency turns over", 20),
     ("The touched object: its modes, the contact, the sensor chain", 15)),
    (_run("plot_04_zones"), _run("plot_13_stick_slip")),
    (_ex("ex04_peak"),),
)
MODES_AND_ZONES = Session(
    "Modes, their accuracy and the three zones",
    MODES.goals + ZONES.goals,
    MODES.reading + ZONES.reading,
    (("The generalized eigenproblem, solved stably", 5),
     ("Convergence to the exact solution as h⁴", 5),
     ("The zones of the lowest mode, and why the frequency turns over", 15),
     ("The touched object", 5)),
    MODES.examples + ZONES.examples,
    MODES.exercises + ZONES.exercises,
)
FEATURES = Session(
    "From vibration to features: spectra, filters and time–frequency pictures",
    ("choose a record length and a window for a frequency resolution",
     "design a band-pass to a specification, and say why it runs as second-order sections",
     "say why the repetitions of one position are not independent tests, and widen an "
     "accuracy's interval by the design effect"),
    ("theory/spectrum", "theory/filters", "theory/timefreq", "theory/uncertainty"),
    (("Bins, windows and the peak between two bins", 10),
     ("Band-pass filters to a specification, as second-order sections", 10),
     ("Spectrograms and wavelet scalograms", 10)),
    (_run("plot_06_paper_filters"), _run("plot_10_spectrogram_scalogram"),
     _run("plot_11_simulated_signals")),
    (_ex("ex08_filter_order"), _ex("ex13_mode_curves"), _ex("ex12_splits"),
     _ex("ex15_design_effect")),
)
DECAY = Session(
    "How fast the ringing dies: the decay fit and the Kalman filter",
    ("fit an exponential decay robustly and name what biases it",
     "track a slowly drifting level with a Kalman filter, and find its steady gain by hand"),
    ("theory/decay", "theory/kalman"),
    (("The decay a·eᵇᵗ, the time constant τ = −1/b, and what biases its fit", 10),
     ("The Kalman filter: predict, gain, update; the steady gain of the Riccati recursion", 20)),
    (_run("plot_07_decay_fit"),),
    (_ex("ex05_decay"), _ex("ex14_kalman")),
)
SIGNALS = Session(
    "Signals: spectra, filters, the decay and the Kalman filter",
    FEATURES.goals + DECAY.goals,
    FEATURES.reading + DECAY.reading,
    (("Bins, windows and the peak between two bins", 10),
     ("Band-pass filters as second-order sections", 10),
     ("Spectrograms and wavelet scalograms", 5),
     ("The decay fit and its time constant τ", 5),
     ("The Kalman filter and its steady gain", 10)),
    FEATURES.examples + DECAY.examples,
    FEATURES.exercises + DECAY.exercises,
)
CLASSIFIERS = Session(
    "Classifiers by hand: the SVM's dual, and a network that learns",
    ("write and solve the dual of a soft-margin SVM, and check it against SMO and the package",
     "watch a NumPy network learn and read its loss curve"),
    ("theory/svm", "theory/mlp"),
    (("The SVM dual and SMO", 15),
     ("A network of one hidden layer, trained by backpropagation", 5)),
    (_run("plot_08_svm_vs_sklearn"), _run("plot_09_mlp_training")),
    (_ex("ex06_svm_dual"), _ex("ex07_backprop"), _ex("ex10_fifo"),
     _ex("ex11_rbf_cancellation")),
)


def _roles(core=(), optional=(), homework=(), further=()) -> dict:
    return {
        **{_ex(n): "core" for n in core},
        **{_ex(n): "optional" for n in optional},
        **{_ex(n): "homework" for n in homework},
        **{_ex(n): "further" for n in further},
    }


#: after the course: the last session's exercises beyond its goals (backpropagation by hand, the
#: FIFO by hand, the RBF kernel's cancellation)
_AFTER = ("ex07_backprop", "ex10_fifo", "ex11_rbf_cancellation")

#: The three tracks, by number of sessions.
TRACKS = {
    7: Track(
        (ELEMENT, ASSEMBLY, MODES, ZONES, FEATURES, DECAY, CLASSIFIERS),
        _roles(core=("ex01_element", "ex02_assembly", "ex03_convergence", "ex04_peak",
                     "ex08_filter_order", "ex14_kalman", "ex06_svm_dual"),
               optional=("ex09_mesh_budget",),
               homework=("ex13_mode_curves", "ex12_splits", "ex15_design_effect", "ex05_decay"),
               further=_AFTER),
    ),
    6: Track(
        (BEAM, MODES, ZONES, FEATURES, DECAY, CLASSIFIERS),
        _roles(core=("ex01_element", "ex03_convergence", "ex04_peak", "ex08_filter_order",
                     "ex14_kalman", "ex06_svm_dual"),
               homework=("ex02_assembly", "ex09_mesh_budget", "ex13_mode_curves",
                         "ex12_splits", "ex15_design_effect", "ex05_decay"),
               further=_AFTER),
    ),
    4: Track(
        (BEAM, MODES_AND_ZONES, SIGNALS, CLASSIFIERS),
        _roles(core=("ex01_element", "ex04_peak", "ex05_decay", "ex06_svm_dual"),
               homework=("ex02_assembly", "ex03_convergence", "ex09_mesh_budget",
                         "ex08_filter_order", "ex14_kalman", "ex15_design_effect"),
               further=("ex13_mode_curves", "ex12_splits") + _AFTER),
    ),
}


def exercise_minutes(docname: str, docs: Path = DOCS) -> int:
    """The minutes an exercise page states in its ``:Time: about N minutes`` field."""
    page = docs / f"{docname}.rst"
    if not page.is_file():
        raise FileNotFoundError(f"the course assigns {docname}, but {page} does not exist")
    found = _TIME.findall(page.read_text(encoding="utf-8"))
    if len(found) != 1:
        raise ValueError(f"{page} must state its time once as ':Time: about N minutes', "
                         f"found {len(found)}")
    return int(found[0])


def example_minutes(docname: str, docs: Path = DOCS) -> int:
    """Minutes a gallery example takes in class: :data:`RUN_MINUTES` to run it, plus
    :data:`FIGURE_MINUTES` for each figure it draws (its ``plt.subplots(``/``plt.figure(`` calls,
    counted in its source ``docs/examples/plot_NN_*.py``)."""
    name = docname.split("/", 1)[1]
    source = docs / "examples" / f"{name}.py"
    if not source.is_file():
        raise FileNotFoundError(f"the course runs {docname}, but {source} does not exist")
    figures = len(_FIGURE.findall(source.read_text(encoding="utf-8")))
    return RUN_MINUTES + FIGURE_MINUTES * figures


def examples_minutes(session: Session, docs: Path = DOCS) -> int:
    """Minutes of the gallery examples a session runs in class."""
    return sum(example_minutes(d, docs) for d in session.examples)


def core_minutes(track: Track, session: Session, docs: Path = DOCS) -> int:
    """Minutes of the session's core exercises in ``track``."""
    core = [e for e in session.exercises if track.roles[e] == "core"]
    return sum(exercise_minutes(e, docs) for e in core)


def class_minutes(track: Track, session: Session, docs: Path = DOCS) -> int:
    """Minutes in class: presented + examples run + core exercises."""
    return (session.presented_minutes + examples_minutes(session, docs)
            + core_minutes(track, session, docs))


def overloaded(tracks: dict = TRACKS, docs: Path = DOCS) -> list[str]:
    """Every session over :data:`BUDGET` in class, and every last session that sets homework,
    as readable lines (none: ``[]``)."""
    late = [
        f"{track.key}, session {i}: {class_minutes(track, s, docs)} min in class"
        for track in tracks.values()
        for i, s in enumerate(track.sessions, 1)
        if class_minutes(track, s, docs) > BUDGET
    ]
    for track in tracks.values():
        last = track.sessions[-1]
        homework = [e for e in last.exercises if track.roles[e] == "homework"]
        if homework:
            late.append(f"{track.key}, last session: homework after the course ({homework})")
    return late


def _minutes_line(track: Track, session: Session, docs: Path) -> str:
    return (f"{session.presented_minutes} presented + {examples_minutes(session, docs)} examples + "
            f"{core_minutes(track, session, docs)} core = {class_minutes(track, session, docs)} "
            f"of {BUDGET}")


def sheet_name(track: Track, number: int) -> str:
    """Document name of a session's sheet: ``course/track7/session3``."""
    return f"course/{track.key}/session{number}"


def _exercise_line(track: Track, docname: str, docs: Path) -> str:
    return f":doc:`/{docname}` ({track.roles[docname]}, {exercise_minutes(docname, docs)} min)"


def track_table(track: Track, docs: Path = DOCS) -> list[str]:
    """The track as a reST list-table: one row per session, with its minute budget."""
    lines = [
        f".. list-table:: {len(track.sessions)} sessions of {BUDGET} minutes",
        "   :header-rows: 1", "   :widths: 3 24 22 27 12", "",
        "   * - #", "     - session", "     - read before", "     - exercises (role, time)",
        "     - in class, min: presented + examples + core",
    ]  # fmt: skip
    for i, s in enumerate(track.sessions, 1):
        lines += [
            f"   * - {i}",
            f"     - :doc:`{s.title} </{sheet_name(track, i)}>`",
            "     - " + ", ".join(f":doc:`/{d}`" for d in s.reading),
            "     - " + "; ".join(_exercise_line(track, e, docs) for e in s.exercises),
            f"     - {_minutes_line(track, s, docs)}",
        ]
    return lines


def _bullets(items) -> list[str]:
    return [f"* {item}" for item in items] + [""]


def _section(title: str) -> list[str]:
    return [title, "-" * len(title), ""]


def _prepare(track: Track, number: int, docs: Path) -> list[str]:
    """What to do before the next session: this session's homework and the next reading."""
    session = track.sessions[number - 1]
    todo = [f"do the homework :doc:`/{e}` ({exercise_minutes(e, docs)} min)"
            for e in session.exercises if track.roles[e] == "homework"]
    todo += [f"finish :doc:`/{e}` if there was no time for it in class"
             for e in session.exercises if track.roles[e] == "optional"]
    if number < len(track.sessions):
        todo += [f"read :doc:`/{d}`" for d in track.sessions[number].reading]
    else:
        todo.append("the course ends here: every goal above was reached in class")
        todo += [f"after the course, beyond its goals: :doc:`/{e}` ({exercise_minutes(e, docs)} "
                 "min)" for e in track.sessions[-1].exercises if track.roles[e] == "further"]
    return _bullets(todo)


def session_sheet(track: Track, number: int, docs: Path = DOCS) -> str:
    """The sheet of session ``number`` (1-based) of ``track``, as reST."""
    s = track.sessions[number - 1]
    title = f"Session {number} of {len(track.sessions)}: {s.title}"
    lines = [
        title, "=" * len(title), "",
        f":Track: {len(track.sessions)} sessions of {BUDGET} minutes (all tracks: :doc:`/course`)",
        f":In class, min: {_minutes_line(track, s, docs)}", "",
        *_section("Goals"), *_bullets(s.goals),
        *_section("Read before the session"), *_bullets(f":doc:`/{d}`" for d in s.reading),
        *_section("Presented in class"),
        *_bullets(f"{topic} ({minutes} min)" for topic, minutes in s.presented),
        *_section("Run in class"),
        *_bullets(f":doc:`/{d}` ({example_minutes(d, docs)} min)" for d in s.examples),
        *_section("Exercises"),
        "Core exercises are done in class; optional ones too if time is left, otherwise at home;",
        "homework is done before the next session; further ones are for after the course, beyond",
        "its goals.", "",
        *_bullets(_exercise_line(track, e, docs) for e in s.exercises),
        *_section("Prepare for next time"), *_prepare(track, number, docs),
    ]  # fmt: skip
    return "\n".join(lines)


def write_sheets(app=None, docs: Path = DOCS) -> list[Path]:
    """Write every session's sheet into ``docs/course/`` (unchanged pages are left alone).

    Raises ``ValueError`` naming each session whose work in class does not fit its budget, and
    each last session that sets homework.
    """
    late = overloaded(TRACKS, docs)
    if late:
        raise ValueError(f"a session over the {BUDGET}-minute budget or homework after the "
                         "course: " + "; ".join(late))
    written = []
    for track in TRACKS.values():
        for i in range(1, len(track.sessions) + 1):
            path = docs / f"{sheet_name(track, i)}.rst"
            text = session_sheet(track, i, docs)
            if not path.is_file() or path.read_text(encoding="utf-8") != text:
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_text(text, encoding="utf-8")
            written.append(path)
    return written


def _directive():
    from docutils import nodes
    from docutils.parsers.rst import directives
    from docutils.statemachine import StringList
    from sphinx.util.docutils import SphinxDirective

    class CourseTrack(SphinxDirective):
        """``.. course-track:: N``: the table of the track of N sessions."""

        required_arguments = 1

        def run(self):
            track = TRACKS[directives.positive_int(self.arguments[0])]
            for session in track.sessions:
                for docname in session.exercises:
                    self.env.note_dependency(str(DOCS / f"{docname}.rst"))
                for docname in session.examples:
                    self.env.note_dependency(str(DOCS / "examples" / f"{docname[14:]}.py"))
            self.env.note_dependency(__file__)
            return self._parse(track_table(track))

        def _parse(self, lines):
            box = nodes.container()
            self.state.nested_parse(StringList(lines, source=__file__), self.content_offset, box)
            return box.children

    return CourseTrack


def setup(app):
    app.connect("builder-inited", write_sheets)
    app.add_directive("course-track", _directive())
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
