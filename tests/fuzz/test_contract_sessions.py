"""The input contract of recording sessions: plan files, manifests, ``dataset --from-recordings``.

Each row is one bad input (or a good one, checked against what was written) to a surface of
the recording workflow: :func:`~ebantenna.device.plan.load_plan` and
:class:`~ebantenna.device.plan.Plan`, :func:`~ebantenna.device.recording_session.read_manifest`
and :meth:`~ebantenna.device.recording_session.RecordingSession.open`,
:func:`~ebantenna.study.recorded.assemble_dataset` (labels of the recordings included) and the
``record`` command. A row's setup runs when the row runs, from one recorded session made once,
so that :func:`contract_rows` lists the rows without making anything (the inventory test of
``test_contract_inventory`` reads it).

Outcomes are sorted by ``contract_files_cases.outcome``: a clear error must name the file or
parameter (the strings of ``names``); a traceback, a hang, a ``MemoryError``, an accepted bad
input or a wrong answer fails.

Run as a script (``PYTHONPATH=. python tests/fuzz/test_contract_sessions.py``) to print the
counts by surface and class, under an address-space limit of 4 GiB (``PYTHONPATH`` may name
another tree of the package: the rows use only what it has).
"""

from __future__ import annotations

import json
import os
import shutil
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import pytest

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import CLASSES, Case, outcome, run_cli  # noqa: E402

from ebantenna.device import plan as _plan_module  # noqa: E402
from ebantenna.device.plan import Plan, load_plan  # noqa: E402
from ebantenna.device.recording_session import (  # noqa: E402
    MANIFEST,
    RecordingSession,
    file_sha256,
    read_manifest,
)
from ebantenna.recording import Recording  # noqa: E402

#: (looked up so that the rows also run, and are counted, on a tree without it)
check_session_length = getattr(_plan_module, "check_session_length", None)
PLAN = Plan("fz", ("brass",), (0.1, 0.3), 2)
#: The rig the sessions are recorded with (a resume must name the same).
RIG = {"simulated": True}
ACCEPTED = {"error": {"clear"}, "equal": {"right"}, "either": {"clear", "right"}}


@dataclass
class Row:
    """One row: ``run(ctx)`` performs it, ``ctx`` holding the paths of a recorded session."""

    surface: str
    id: str
    expect: str
    names: tuple
    run: object
    same: object = None
    timeout: float = 5.0


class Context:
    """A finished session (``recorded``) and a scratch folder for each row."""

    def __init__(self, recorded: Path, scratch: Path):
        self.recorded, self.scratch = recorded, scratch
        self._n = 0

    def fresh(self) -> Path:
        """A scratch folder of its own for one row."""
        self._n += 1
        where = self.scratch / f"r{self._n}"
        where.mkdir()
        return where

    def session(self) -> Path:
        """A copy of the recorded session to spoil."""
        return Path(shutil.copytree(self.recorded, self.fresh() / "s"))

    def manifest_only(self) -> Path:
        """A folder holding a copy of the session's manifest alone."""
        folder = self.fresh() / "s"
        folder.mkdir()
        shutil.copy(self.recorded / MANIFEST, folder / MANIFEST)
        return folder


def record_session(where: Path) -> Path:
    """Record :data:`PLAN` on the simulated rig in ``where/s``."""
    from ebantenna.device.simulated.touches import simulated_connect
    from ebantenna.simulate import builtin_scene, simulate

    folder = where / "s"
    RecordingSession(folder, PLAN, simulated_connect(builtin_scene("paper"), simulate, seed=2),
                     rig=RIG, show_progress=False).run()
    return folder


# ------------------------------------------------------------------------- plan files
def _plan_file(ctx, data, suffix=".json", raw=None) -> Path:
    path = ctx.fresh() / f"plan{suffix}"
    path.write_text(raw if raw is not None else json.dumps(data), encoding="utf-8")
    return path


def _plan_with(**changes) -> dict:
    data = PLAN.to_dict()
    data.update(changes)
    return {k: v for k, v in data.items() if v is not None}


def _load_plan_row(id_, names, expect="error", **changes):
    return Row("ebantenna.device.plan.load_plan", id_, expect, names,
               lambda ctx: load_plan(_plan_file(ctx, _plan_with(**changes))))


def _plan_rows() -> list[Row]:
    rows = [
        _load_plan_row("name-escapes", ("plan name",), name="x/../../escaped"),
        _load_plan_row("name-300-letters", ("plan name",), name="a" * 300),
        _load_plan_row("name-empty", ("plan name",), name=""),
        _load_plan_row("name-unicode", ("plan name",), name="plan\u00e9"),
        _load_plan_row("name-number", ("plan name",), name=5),
        _load_plan_row("materials-string", ("materials",), materials="brass"),
        _load_plan_row("materials-empty", ("materials",), materials=[]),
        _load_plan_row("materials-case-twice", ("materials", "brass"),
                       materials=["brass", "Brass"]),
        _load_plan_row("materials-number", ("material",), materials=[5]),
        _load_plan_row("materials-unknown", ("material",), materials=["gold"]),
        _load_plan_row("materials-table", ("materials",), materials={"a": "brass"}),
        _load_plan_row("contacts-twice", ("contacts_m",), contacts_m=[0.1, 0.1]),
        _load_plan_row("contacts-one-key", ("contacts_m",), contacts_m=[0.10001, 0.10004]),
        _load_plan_row("contacts-nan", ("contacts_m",), contacts_m=[float("nan")]),
        _load_plan_row("contacts-negative", ("contacts_m",), contacts_m=[-0.1]),
        _load_plan_row("contacts-5m", ("contacts_m",), contacts_m=[5.0]),
        _load_plan_row("contacts-string", ("contacts_m",), contacts_m="0.1"),
        _load_plan_row("contacts-10**6", ("contacts_m",), contacts_m=[0.1] * 10**6),
        _load_plan_row("repetitions-10**9", ("repetitions",), repetitions=10**9),
        _load_plan_row("repetitions-fraction", ("repetitions",), repetitions=1.5),
        _load_plan_row("repetitions-true", ("repetitions",), repetitions=True),
        _load_plan_row("repetitions-zero", ("repetitions",), repetitions=0),
        _load_plan_row("touches-over-max", ("touches",), contacts_m=[0.01 * i for i in
                                                                   range(1, 40)],
                       repetitions=5000),
        _load_plan_row("probe-length-nan", ("probe_length",), probe_length=float("nan")),
        _load_plan_row("search-duration-1e9", ("duration",), search={"duration": 1e9}),
        _load_plan_row("search-unknown", ("nope",), search={"nope": 1}),
        _load_plan_row("search-string", ("search",), search="fast"),
        _load_plan_row("simulation-string", ("simulation",), simulation="x"),
        _load_plan_row("unknown-key", ("colour",), colour="red"),
        _load_plan_row("missing-name", ("'name'",), name=None),
        _load_plan_row("missing-repetitions", ("'repetitions'",), repetitions=None),
    ]
    special = {
        "fifo": lambda p: os.mkfifo(p),
        "dev-zero-link": lambda p: os.symlink("/dev/zero", p),
        "directory": lambda p: os.mkdir(p),
        "deep-json": lambda p: p.write_text("[" * 100_000 + "]" * 100_000),
        "long-json": lambda p: p.write_text(" " * (2**24 + 1) + "{}"),
        "not-utf8": lambda p: p.write_bytes(b'{"name": "\xff"}'),
        "list": lambda p: p.write_text("[1, 2]"),
        "not-json": lambda p: p.write_text("name = 'x'"),
    }

    def special_row(make):
        def run(ctx):
            path = ctx.fresh() / "plan.json"
            make(path)
            return load_plan(path)
        return run

    rows += [Row("ebantenna.device.plan.load_plan", f"file-{k}", "error", ("plan.json",),
                 special_row(make)) for k, make in special.items()]
    rows += [
        Row("ebantenna.device.plan.load_plan", "toml-deep", "error", ("plan.toml",),
            lambda ctx: load_plan(_plan_file(ctx, None, ".toml",
                                             "a = " + "[" * 100_000 + "]" * 100_000))),
        Row("ebantenna.device.plan.load_plan", "toml-materials-string", "error", ("materials",),
            lambda ctx: load_plan(_plan_file(ctx, None, ".toml", 'name = "a"\nmaterials = '
                                             '"brass"\ncontacts_m = [0.1]\nrepetitions = 1\n'))),
        Row("ebantenna.device.plan.load_plan", "path-bytes", "error", ("plan",),
            lambda ctx: load_plan(b"plan.json")),
        Row("ebantenna.device.plan.load_plan", "path-nul", "error", ("plan",),
            lambda ctx: load_plan("pl\x00an.json")),
        Row("ebantenna.device.plan.load_plan", "round-trip", "equal", (),
            lambda ctx: load_plan(_plan_file(ctx, PLAN.to_dict())), same=lambda p: p == PLAN),
        Row("ebantenna.device.plan.Plan", "key-collision", "error", ("contacts_m",),
            lambda ctx: Plan("a", ("brass",), (0.10001, 0.10004), 1)),
        Row("ebantenna.device.plan.Plan", "materials-string", "error", ("materials",),
            lambda ctx: Plan("a", "brass", (0.1,), 1)),
        Row("ebantenna.device.plan.Plan", "contacts-10**6", "error", ("contacts_m",),
            lambda ctx: Plan("a", ("brass",), tuple(range(1, 10**6)), 1, probe_length=2e6)),
        Row("ebantenna.device.plan.Plan", "right-touches", "equal", (),
            lambda ctx: [t.key for t in Plan("a", ("pvc", "brass"), (0.2, 0.1), 1)],
            same=lambda keys: keys == ["pvc/0.2000/0", "pvc/0.1000/0", "brass/0.2000/0",
                                       "brass/0.1000/0"]),
        Row("ebantenna.device.plan.check_session_length", "hours-without-yes", "error",
            ("--yes",), lambda ctx: check_session_length(Plan("a", ("brass",), (0.1,), 5000))),
        Row("ebantenna.device.plan.check_session_length", "search-time-1e9", "error", ("--yes",),
            lambda ctx: check_session_length(
                Plan("a", ("brass",), (0.1,), 1, search={"max_search_time": 1e9}))),
        Row("ebantenna.device.plan.check_session_length", "agreed", "equal", (),
            lambda ctx: check_session_length(Plan("a", ("brass",), (0.1,), 5000), agreed=True),
            same=lambda t: t["touches"] == 5000),
        Row("ebantenna.device.plan.check_session_length", "not-a-plan", "error", ("plan",),
            lambda ctx: check_session_length({"name": "a"})),
    ]
    return rows


# ------------------------------------------------------------------------- manifests
def _edit_manifest(folder: Path, edit) -> Path:
    path = folder / MANIFEST
    manifest = json.loads(path.read_text())
    result = edit(manifest)
    path.write_text(json.dumps(manifest if result is None else result))
    return folder


def _first_entry(m) -> dict:
    return next(iter(m["recordings"].values()))


def _drop(*keys):
    def edit(m):
        target = m
        for k in keys[:-1]:
            target = target[k]
        del target[keys[-1]]
    return edit


def _set_entry(**changes):
    def edit(m):
        _first_entry(m).update(changes)
    return edit


def _second_names_first(m):
    entries = list(m["recordings"].values())
    entries[1]["file"] = entries[0]["file"]
    entries[1]["sha256"] = entries[0]["sha256"]


def _extra_touch(m):
    entry = dict(_first_entry(m))
    entry.update(material="pvc")
    m["recordings"]["pvc/0.1000/0"] = entry


def _link_out(ctx, folder: Path) -> Path:
    """The first recording replaced by a link to a copy outside the session folder."""
    entry = _first_entry(json.loads((folder / MANIFEST).read_text()))
    outside = ctx.fresh() / "outside.npz"
    shutil.copy(folder / entry["file"], outside)
    (folder / entry["file"]).unlink()
    os.symlink(outside, folder / entry["file"])
    return folder


MANIFEST_EDITS = {
    "missing-plan": (_drop("plan"), ("'plan'",)),
    "missing-recordings": (_drop("recordings"), ("'recordings'",)),
    "missing-search": (_drop("search"), ("'search'",)),
    "missing-rig": (_drop("rig"), ("'rig'",)),
    "missing-format": (_drop("format"), ("session.json",)),
    "plan-missing-name": (_drop("plan", "name"), ("'name'",)),
    "plan-missing-probe-length": (_drop("plan", "probe_length"), ("'probe_length'",)),
    "plan-missing-search": (_drop("plan", "search"), ("'search'",)),
    "plan-name-escapes": (lambda m: m["plan"].update(name="x/../../escaped"), ("plan name",)),
    "plan-materials-twice": (lambda m: m["plan"].update(materials=["brass", "Brass"]),
                             ("materials",)),
    "search-duration-1e9": (lambda m: m["search"].update(duration=1e9), ("search",)),
    "entry-parent-path": (_set_entry(file="../elsewhere/x.npz"), ("../elsewhere",)),
    "entry-absolute-path": (_set_entry(file="/etc/passwd"), ("/etc/passwd",)),
    "entry-missing-file": (lambda m: _first_entry(m).pop("file") and None, ("'file'",)),
    "entry-missing-sha": (lambda m: _first_entry(m).pop("sha256") and None, ("'sha256'",)),
    "entry-bad-sha": (_set_entry(sha256="zz"), ("sha256",)),
    "entry-contact-mismatch": (_set_entry(contact=0.2), ("contact",)),
    "entry-repetition-true": (_set_entry(repetition=True), ("repetition",)),
    "two-entries-one-file": (_second_names_first, ("names the file",)),
    "entry-for-no-touch": (_extra_touch, ("pvc/0.1000/0",)),
    "entry-not-a-table": (lambda m: m["recordings"].update({"brass/0.1000/0": 5}),
                          ("brass/0.1000/0",)),
    "recordings-list": (lambda m: m.update(recordings=[]), ("recordings",)),
    "top-level-list": (lambda m: [m], ("session.json",)),
    "unsafe-string": (lambda m: m.update(unsafe="yes"), ("unsafe",)),
}

#: The manifest rows also run through RecordingSession.open and assemble_dataset.
THROUGH = {"missing-plan", "missing-recordings", "missing-search", "plan-missing-name",
           "plan-missing-probe-length", "plan-name-escapes", "search-duration-1e9",
           "entry-parent-path", "entry-absolute-path", "two-entries-one-file",
           "entry-for-no-touch"}

MANIFEST_FILES = {
    "fifo": lambda p: (p.unlink(), os.mkfifo(p)),
    "dev-zero-link": lambda p: (p.unlink(), os.symlink("/dev/zero", p)),
    "deep-json": lambda p: p.write_text("[" * 100_000 + "]" * 100_000),
    "not-utf8": lambda p: p.write_bytes(b"\xff\xfe"),
    "empty": lambda p: p.write_text(""),
}


def _manifest_rows() -> list[Row]:
    rows = []
    readers = {
        "ebantenna.device.recording_session.read_manifest":
            lambda folder: read_manifest(folder / MANIFEST),  # (a copy of the manifest alone)
        "ebantenna.device.recording_session.RecordingSession.open":
            lambda folder: RecordingSession(folder, PLAN, _no_rig, rig=RIG,
                                            show_progress=False).open(),
        "ebantenna.study.recorded.assemble.assemble_dataset":
            lambda folder: _assemble(folder),
    }
    for surface, read in readers.items():
        # the session and assembly read the manifest through read_manifest: they get the kinds
        # the issue met on them, not every schema row again
        edits = (MANIFEST_EDITS if surface.endswith("read_manifest") else
                 {k: v for k, v in MANIFEST_EDITS.items() if k in THROUGH})
        for id_, (edit, names) in edits.items():
            only = surface.endswith("read_manifest")
            rows.append(Row(surface, f"manifest-{id_}", "error", names,
                            lambda ctx, e=edit, r=read, o=only: r(_edit_manifest(
                                ctx.manifest_only() if o else ctx.session(), e))))
        only_manifest = surface.endswith("read_manifest")
        for id_, make in MANIFEST_FILES.items():
            def run(ctx, make=make, read=read, only=only_manifest):
                folder = ctx.manifest_only() if only else ctx.session()
                make(folder / MANIFEST)
                return read(folder)
            rows.append(Row(surface, f"manifest-file-{id_}", "error", ("session.json",), run))
        if surface.endswith("read_manifest"):
            continue  # reads the file it is given; the folder's links are the session's
        rows.append(Row(surface, "recording-link-out", "error", ("outside",),
                        lambda ctx, r=read: r(_link_out(ctx, ctx.session()))))
        rows.append(Row(surface, "manifest-link-out", "error", ("session.json",),
                        lambda ctx, r=read: r(_manifest_link_out(ctx))))
    for id_, value in (("none", None), ("an-int", 5), ("a-tuple", ("bus", "clock"))):
        rows.append(Row("ebantenna.device.recording_session.RecordingSession.run",
                        f"connect-returns-{id_}", "error", ("connect",),
                        lambda ctx, v=value: RecordingSession(
                            ctx.fresh() / "s", PLAN, lambda touch, attempt: v,
                            show_progress=False).run()))
    for id_, kw in (("max-lost-1", {"max_lost": 1.0}), ("attempts-0", {"attempts": 0}),
                    ("directory-empty", {"directory": ""}), ("connect-none", {"connect": None}),
                    ("plan-dict", {"plan": PLAN.to_dict()})):
        def make(ctx, kw=kw):
            args = {"directory": ctx.fresh() / "s", "plan": PLAN, "connect": _no_rig, **kw}
            return RecordingSession(args.pop("directory"), args.pop("plan"),
                                    args.pop("connect"), **args)
        rows.append(Row("ebantenna.device.recording_session.RecordingSession", id_, "error",
                        (id_.split("-")[0].replace("max", "max_lost"),), make))
    rows.append(Row("ebantenna.device.recording_session.read_manifest", "right", "equal", (),
                    lambda ctx: read_manifest(ctx.recorded / MANIFEST),
                    same=lambda m: len(m["recordings"]) == len(PLAN)))
    rows.append(Row("ebantenna.device.recording_session.RecordingSession.open", "resume-right",
                    "equal", (), lambda ctx: RecordingSession(ctx.session(), PLAN, _no_rig,
                                                              rig=RIG, show_progress=False).open(),
                    same=lambda m: sorted(m["recordings"]) == sorted(t.key for t in PLAN)))
    return rows


def _manifest_link_out(ctx) -> Path:
    folder = ctx.session()
    outside = ctx.fresh() / "elsewhere.json"
    shutil.move(folder / MANIFEST, outside)
    os.symlink(outside, folder / MANIFEST)
    return folder


def _no_rig(touch, attempt):
    raise AssertionError("the rows only open sessions; none connects to a rig")


def _assembler():
    from ebantenna.study.recorded import assemble_dataset

    return assemble_dataset


def _assemble(folder: Path, **kw):
    out = folder.parent / "out"
    out.mkdir(exist_ok=True)
    return _assembler()(folder, out, **kw)


# ------------------------------------------------------------------- recordings' labels
def _relabel(folder: Path, **changes) -> Path:
    """The first recording's labels changed, its checksum in the manifest updated."""
    path = folder / MANIFEST
    manifest = json.loads(path.read_text())
    entry = _first_entry(manifest)
    rec_path = folder / entry["file"]
    rec = Recording.load(rec_path)
    meta = {**rec.metadata, **changes}
    Recording(rec.t, rec.ax, rec.az, rec.fs, meta).save(rec_path)
    entry["sha256"] = file_sha256(rec_path)
    path.write_text(json.dumps(manifest))
    return folder


LABELS = {
    "contact-nan": ({"contact": float("nan")}, "contact"),
    "contact-negative": ({"contact": -0.1}, "contact"),
    "contact-5m": ({"contact": 5.0}, "contact"),
    "contact-string": ({"contact": "0.1"}, "contact"),
    "repetition-fraction": ({"repetition": 1.5}, "repetition"),
    "repetition-true": ({"repetition": True}, "repetition"),
    "repetition-beyond-plan": ({"repetition": 7}, "repetition"),
    "material-number": ({"material": 5}, "material"),
    "material-unknown": ({"material": "gold"}, "material"),
    "material-other": ({"material": "pvc"}, "material"),
    "samples-lost-negative": ({"samples_lost": -1000}, "samples_lost"),
    "samples-lost-fraction": ({"samples_lost": 0.5}, "samples_lost"),
    "trigger-time-string": ({"trigger_time": "x"}, "trigger_time"),
    "trigger-time-nan": ({"trigger_time": float("nan")}, "trigger_time"),
    "sample-rate-negative": ({"sample_rate_hz": -1000.0}, "sample_rate_hz"),
    "sample-rate-string": ({"sample_rate_hz": "1k"}, "sample_rate_hz"),
}


def _assemble_rows() -> list[Row]:
    surface = "ebantenna.study.recorded.assemble.assemble_dataset"
    rows = [Row(surface, f"label-{id_}", "error", (name,),
                lambda ctx, c=changes: _assemble(_relabel(ctx.session(), **c)))
            for id_, (changes, name) in LABELS.items()]
    # (None is the session's own limit, a valid value)
    for value in (1.5, float("nan"), "x", -0.1, True):
        rows.append(Row(surface, f"max_lost-{value!r}", "error", ("max_lost",),
                        lambda ctx, v=value: _assemble(ctx.session(), max_lost=v)))
    for value in (0.0, float("inf"), "x", 2.0):
        rows.append(Row(surface, f"rate_tolerance-{value!r}", "error", ("rate_tolerance",),
                        lambda ctx, v=value: _assemble(ctx.session(), rate_tolerance=v)))
    rows += [
        Row(surface, "directory-bytes", "error", ("directory",),
            lambda ctx: _assembler()(os.fsencode(ctx.session()))),
        Row(surface, "directory-missing", "error", ("session.json",),
            lambda ctx: _assemble(ctx.fresh() / "nope")),
        Row(surface, "out-nul", "error", ("out_dir",),
            lambda ctx: _assembler()(ctx.session(), "o\x00ut")),
        Row(surface, "out_dir-int", "error", ("out_dir",),
            lambda ctx: _assembler()(ctx.session(), 5)),
        Row(surface, "out_dir-a-file", "error", ("out_dir",),
            lambda ctx: _assembler()(ctx.session(), ctx.session() / MANIFEST)),
        # the place of the file is checked before any recording is read: a damaged label is
        # not what the refusal names
        Row(surface, "a-directory-where-the-file-goes", "error", ("out_dir",),
            lambda ctx: _assembler()(_relabel(ctx.session(), contact=-0.1),
                                     _holding_directory(ctx.fresh(), "recorded-fz.npz"))),
        Row(surface, "a-directory-where-the-file-goes-in-the-session", "error", ("directory",),
            lambda ctx: _assembler()(_holding_directory(ctx.session(), "recorded-fz.npz"))),
        Row(surface, "right", "equal", (), lambda ctx: _assemble(ctx.session()),
            same=lambda d: d.n_signals == len(PLAN) and d.path.name == "recorded-fz.npz"
            and d.path.parent.name == "out"),
    ]
    return rows


def _holding_directory(folder: Path, name: str) -> Path:
    """``folder``, with a directory named ``name`` in it."""
    (folder / name).mkdir()
    return folder


# ------------------------------------------------------------------------ the command
def _cli_rows() -> list[Row]:
    def record(ctx, argv_of):
        where = ctx.fresh()
        cwd = os.getcwd()
        os.chdir(where)
        try:
            return run_cli(argv_of(where))
        finally:
            os.chdir(cwd)

    def big_plan(where):
        (where / "big.json").write_text(json.dumps(Plan("big", ("brass",), (0.1, 0.2),
                                                        3000).to_dict()))
        return ["record", "--simulated", "--plan", "big.json", "--out", "s"]

    def escaping(where):
        (where / "p.json").write_text(json.dumps(_plan_with(name="x/../../escaped")))
        return ["record", "--simulated", "--plan", "p.json", "--out", "s"]

    return [
        Row("cli:record --out", "empty", "error", ("--out",),
            lambda ctx: record(ctx, lambda w: ["record", "--simulated", "--quick", "--out", ""])),
        Row("cli:record --yes", "hours-without-yes", "error", ("--yes",),
            lambda ctx: record(ctx, big_plan)),
        Row("cli:record --plan", "name-escapes", "error", ("plan name",),
            lambda ctx: record(ctx, escaping)),
        Row("cli:dataset --from-recordings", "a-directory-where-the-file-goes", "error",
            ("--out",), lambda ctx: run_cli([
                "dataset", "--from-recordings", str(ctx.session()), "--out",
                str(_holding_directory(ctx.fresh(), "recorded-fz.npz"))])),
        Row("cli:dataset --from-recordings", "entry-outside", "error", ("../elsewhere",),
            lambda ctx: run_cli(["dataset", "--from-recordings", str(_edit_manifest(
                ctx.session(), _set_entry(file="../elsewhere/x.npz"))), "--out",
                str(ctx.fresh())])),
    ]


def all_rows() -> list[Row]:
    """Every row of this file."""
    return _plan_rows() + _manifest_rows() + _assemble_rows() + _cli_rows()


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover and the ids of their rows (read by the inventory test)."""
    rows: dict[str, list[str]] = {}
    for row in all_rows():
        rows.setdefault(row.surface, []).append(row.id)
    rows["file:plan"] = rows["ebantenna.device.plan.load_plan"]
    rows["file:manifest"] = rows["ebantenna.device.recording_session.read_manifest"]
    return rows


def classify(row: Row, ctx: Context) -> tuple[str, str]:
    """The class of ``row``'s outcome (see ``contract_files_cases.CLASSES``)."""
    case = Case(f"{row.surface}:{row.id}", lambda: row.run(ctx), row.expect, row.names,
                row.same, row.timeout)
    return outcome(case)


def count(ctx: Context) -> dict[str, dict[str, int]]:
    """Counts of outcome classes by surface."""
    table: dict[str, dict[str, int]] = {}
    for row in all_rows():
        kind, _ = classify(row, ctx)
        table.setdefault(row.surface, dict.fromkeys(CLASSES, 0))[kind] += 1
    return table


# ----------------------------------------------------------------------------- the tests
@pytest.fixture(scope="module")
def ctx(tmp_path_factory):
    root = tmp_path_factory.mktemp("sessions")
    return Context(record_session(root), root)


SURFACES = sorted({row.surface for row in all_rows()})


@pytest.mark.parametrize("surface", SURFACES)
def test_every_row_ends_in_a_clear_error_or_the_right_answer(ctx, surface):
    bad = []
    for row in all_rows():
        if row.surface != surface:
            continue
        kind, what = classify(row, ctx)
        if kind not in ACCEPTED[row.expect]:
            bad.append(f"{row.id}: {kind} ({what})")
    assert not bad, "\n".join(bad)


def test_the_rows_cover_the_kinds_of_the_workflow():
    ids = {r.id for r in all_rows()}
    assert len(all_rows()) >= 150 and len({(r.surface, r.id) for r in all_rows()}) == len(
        all_rows())
    assert {"manifest-entry-parent-path", "manifest-file-fifo", "manifest-file-deep-json",
            "label-contact-nan", "contacts-one-key", "materials-case-twice"} <= ids
    assert sum(r.expect == "equal" for r in all_rows()) >= 5  # right answers are checked too


def test_a_manifest_entry_never_reads_outside_and_assembly_writes_only_in_out(ctx):
    """The data-loss kind, by its effect: nothing appears outside ``--out``."""
    folder = _edit_manifest(ctx.session(), lambda m: m["plan"].update(name="x/../../escaped"))
    before = sorted(p for p in ctx.scratch.rglob("*"))
    with pytest.raises(ValueError, match="plan name"):
        _assemble(folder)
    after = sorted(p for p in ctx.scratch.rglob("*"))
    assert [p for p in after if p not in before] in ([], [folder.parent / "out"])


if __name__ == "__main__":
    import resource

    # as the review ran them: a bad row may not exhaust the machine (a MemoryError counts)
    resource.setrlimit(resource.RLIMIT_AS, (4 * 2**30, resource.RLIM_INFINITY))
    with tempfile.TemporaryDirectory() as tmp:
        context = Context(record_session(Path(tmp)), Path(tmp))
        total = dict.fromkeys(CLASSES, 0)
        for name, counts in count(context).items():
            print(f"{name}: " + ", ".join(f"{k} {v}" for k, v in counts.items() if v))
            for k, v in counts.items():
                total[k] += v
        print("all: " + ", ".join(f"{k} {v}" for k, v in total.items() if v))
