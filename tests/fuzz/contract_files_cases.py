"""Generated inputs for the loaders, the savers and the command line, and a classifier of outcomes.

Each case is one input a user (or a damaged disk, or an attacker) can hand the package: a valid
file mutated (truncated, bits flipped, an array header or the format version edited, a header
declaring 2**40 values, an oversized header), a special file (FIFO, directory, symlink, device,
``/proc``), a path of the wrong type, a binary or deeply nested scene, an output path that cannot
be written, a command-line argument. Running a case ends in one of these classes:

- ``clear``: a ``ValueError``, ``TypeError`` or ``OSError`` (for the command line: exit code 2
  and one line) whose message names the file or the parameter;
- ``right``: the call returned, and what it returned equals what was saved;
- ``vague``: a clear kind of error that does not name the file or the parameter;
- ``traceback``: any other exception (``KeyError``, ``RecursionError``, ``UnicodeDecodeError``,
  ``BadZipFile``, ...): the user would see a traceback from the package's internals;
- ``memory/timeout``: ``MemoryError``, or no answer within the time limit (a FIFO that blocks);
- ``wrong``: the call returned something other than what was saved, or returned where only an
  error is right (a tampered model that loads).

The cases use only the public functions that the package has had since before this contract, so
the same list runs on an older checkout: ``PYTHONPATH=<checkout> python
tests/fuzz/contract_files_cases.py`` prints the counts by class (``--list`` prints each case).
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import sys
import tempfile
import time
import warnings
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

# tests/ (for ``unloaded_time``), also when this file runs as a script
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from unloaded_time import time_limit  # noqa: E402

CLASSES = ("clear", "right", "vague", "traceback", "memory/timeout", "wrong")

class Timeout(BaseException):
    """No answer in time: raised by the timer, never caught as a clear error."""


@dataclass
class Case:
    """One input: ``run()`` performs it; ``expect`` says which outcomes are acceptable."""

    id: str
    run: object
    expect: str  # "error": only a clear error; "equal": only the right answer; "either"
    names: tuple = ()  # a clear error's message must contain one of these
    same: object = None  # same(result) -> bool: the answer equals what was saved
    timeout: float = 3.0
    tags: set = field(default_factory=set)


class CliError(ValueError):
    """The command ended with exit code 2 and one line on stderr (the message)."""


class CliTraceback(Exception):
    """The command printed more than one line on stderr, or ended in an unexpected way."""


# --- the classifier -------------------------------------------------------------------------


@dataclass
class Row:
    """One row of a contract table: ``call()`` must refuse naming one of ``names``, or return
    what ``same`` checks (``same(result) -> bool``, for a good input)."""

    surface: str
    id: str
    call: object
    names: tuple = ()
    same: object = None

    @property
    def expect(self) -> str:
        return "equal" if self.same is not None else "error"


def check_row(row: Row, row_id: str, timeout: float = 10.0) -> None:
    """Run ``row`` and assert its outcome: a clear error for a bad input, the right answer for a
    good one, within ``timeout`` seconds."""
    kind, what = outcome(Case(row_id, row.call, row.expect, row.names, row.same,
                              timeout=timeout))
    assert kind == ("right" if row.same is not None else "clear"), what


def rows_by_surface(rows) -> dict[str, list[str]]:
    """The surfaces ``rows`` cover, each with its row ids (what ``contract_rows()`` returns to
    the inventory test)."""
    out: dict[str, list[str]] = {}
    for row in rows:
        out.setdefault(row.surface, []).append(row.id)
    return out


def row_tests(all_rows, prefix: str = "") -> tuple:
    """What every row file defines, for the rows ``all_rows()`` returns: ``(IDS,
    test_the_rows_are_distinct, test_every_row_ends_in_a_clear_error_or_the_right_answer,
    contract_rows)``, each row's id its surface without ``prefix``, then the row's own id.

    A row file assigns them to those names, so that pytest collects the two tests and the
    inventory test reads ``contract_rows``.
    """
    import pytest

    ids = [f"{row.surface.removeprefix(prefix)}:{row.id}" for row in all_rows()]

    def test_the_rows_are_distinct():
        assert len(set(ids)) == len(ids)

    @pytest.mark.parametrize("index", range(len(ids)), ids=ids)
    def test_every_row_ends_in_a_clear_error_or_the_right_answer(index):
        check_row(all_rows()[index], ids[index])

    def contract_rows() -> dict[str, list[str]]:
        """The surfaces these rows cover (read by the inventory test)."""
        return rows_by_surface(all_rows())

    return ids, test_the_rows_are_distinct, \
        test_every_row_ends_in_a_clear_error_or_the_right_answer, contract_rows


def outcome(case: Case) -> tuple[str, str]:
    """Run ``case`` and return its class and a short description of what happened.

    The time limit is on the clock of ``unloaded_time``: time spent waiting for a CPU (a busy
    machine) does not count, computing and blocking (a FIFO) do.
    """
    try:
        with warnings.catch_warnings(), time_limit(case.timeout, Timeout):
            warnings.simplefilter("ignore")
            result = case.run()
    except Timeout:
        return "memory/timeout", f"no answer within {case.timeout} s"
    except MemoryError as exc:
        return "memory/timeout", f"MemoryError {exc}"
    except UnicodeError as exc:  # a ValueError, but NumPy's or the codec's, naming nothing
        return "traceback", f"{type(exc).__name__}: {exc}"[:300]
    except (ValueError, TypeError, OSError) as exc:
        message = str(exc)
        what = f"{type(exc).__name__}: {message}"[:300]
        if case.expect == "equal":
            return "wrong", f"refused a valid input: {what}"
        if any(name in message for name in case.names):
            return "clear", what
        return "vague", what
    except Exception as exc:  # noqa: BLE001 - every other kind is a traceback to the user
        return "traceback", f"{type(exc).__name__}: {exc}"[:300]
    if case.expect == "error":
        return "wrong", f"accepted: returned {type(result).__name__}"
    try:
        same = case.same(result)
    except Exception as exc:  # noqa: BLE001
        return "wrong", f"returned something unusable ({type(exc).__name__}: {exc})"
    return ("right", "equal to what was saved") if same else ("wrong", "differs from the saved")


# --- valid files -----------------------------------------------------------------------------

PROBE_X = np.random.default_rng(3).normal(size=(16, 3))


def _models():
    from ebantenna.ml import SVC, MLPClassifier

    rng = np.random.default_rng(0)
    X = rng.normal(size=(40, 3))
    y = (X[:, 0] + X[:, 1] > 0).astype(int) + (X[:, 2] > 0.8)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        svc = SVC(C=2.0).fit(X, y)
        mlp = MLPClassifier((4,), max_iter=30, random_state=0).fit(X, y)
    return svc, mlp


def _same_model(reference):
    def same(model):
        if type(model) is not type(reference):
            return False
        ok = np.array_equal(model.predict(PROBE_X), reference.predict(PROBE_X))
        for method in ("decision_function", "predict_proba"):
            if hasattr(reference, method):
                a, b = getattr(model, method)(PROBE_X), getattr(reference, method)(PROBE_X)
                ok = ok and np.array_equal(a, b)
        return bool(ok)

    return same


def _same_recording(reference):
    def same(rec):
        return (
            all(np.array_equal(getattr(rec, k), getattr(reference, k)) for k in ("t", "ax", "az"))
            and rec.fs == reference.fs
            and rec.metadata == reference.metadata
        )

    return same


def _same_dataset(reference):
    def same(data):
        return data.checksum() == reference.checksum() and data.metadata == reference.metadata

    return same


def _same_scene(reference):
    return lambda scene: scene.to_dict() == reference.to_dict()


@dataclass
class Valid:
    """A valid file, how to load one like it, and how to tell that a load gave it back."""

    kind: str
    path: Path
    load: object
    same: object


def valid_files(root: Path) -> dict[str, Valid]:
    """One valid file of each kind in ``root``: recording, two models, data set, two scenes."""
    from ebantenna import Recording
    from ebantenna.ml import load_model, save_model
    from ebantenna.simulate import builtin_scene
    from ebantenna.simulate.dataset import DatasetDesign, build_dataset, load_dataset
    from ebantenna.simulate.scene import load_scene

    rng = np.random.default_rng(1)
    rec = Recording(np.arange(64) / 1000.0, rng.normal(size=64), rng.normal(size=64), 1000.0,
                    {"scene": "paper", "seed": 4, "lost": [1, 2]})
    files = {"recording": Valid("recording", rec.save(root / "rec.npz"), Recording.load,
                                _same_recording(rec))}
    svc, mlp = _models()
    for name, model in (("svc", svc), ("mlp", mlp)):
        files[name] = Valid(name, save_model(model, root / f"{name}.npz"), load_model,
                            _same_model(model))
    design = DatasetDesign("tiny", ("brass", "pvc"), 0.1, 0.1, 1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        data = build_dataset(root / "ds", builtin_scene("ideal"), design, seed=1,
                             show_progress=False)
    files["dataset"] = Valid("dataset", data.path, load_dataset, _same_dataset(data))
    scene = builtin_scene("paper")
    for suffix in ("json", "toml"):
        path = root / f"scene.{suffix}"
        scene.save(path)
        files[f"scene-{suffix}"] = Valid(f"scene-{suffix}", path, load_scene, _same_scene(scene))
    return files


# --- mutations ---------------------------------------------------------------------------------


def _members(path: Path) -> dict:
    with zipfile.ZipFile(path) as archive:
        return {i.filename: (archive.read(i), i.compress_type) for i in archive.infolist()}


def _write_members(path: Path, members: dict) -> None:
    with zipfile.ZipFile(path, "w") as archive:
        for name, (data, compress) in members.items():
            archive.writestr(zipfile.ZipInfo(name, (2020, 1, 1, 0, 0, 0)), data,
                             compress_type=compress)


def _npy(header: str, body: bytes, *, declared_length: int | None = None) -> bytes:
    """An .npy member with the header dict ``header`` (padded as NumPy pads it) and ``body``."""
    text = header + " " * ((64 - (10 + len(header) + 1) % 64) % 64) + "\n"
    length = len(text) if declared_length is None else declared_length
    if length < 2**16:
        return b"\x93NUMPY\x01\x00" + length.to_bytes(2, "little") + text.encode("latin1") + body
    return b"\x93NUMPY\x02\x00" + length.to_bytes(4, "little") + text.encode("latin1") + body


def _largest_array(members: dict) -> str:
    return max((n for n in members if n.endswith(".npy")), key=lambda n: len(members[n][0]))


HEADER_EDITS = {
    "2**40-values": "{'descr': '<f8', 'fortran_order': False, 'shape': (1099511627776,), }",
    "2**62-values": "{'descr': '<f8', 'fortran_order': False, 'shape': (4611686018427387904,), }",
    "2**21-squared": "{'descr': '<f8', 'fortran_order': False, 'shape': (2097152, 2097152), }",
    "negative-shape": "{'descr': '<f8', 'fortran_order': False, 'shape': (-5,), }",
    "object-dtype": "{'descr': '|O', 'fortran_order': False, 'shape': (3,), }",
    "complex-dtype": "{'descr': '<c16', 'fortran_order': False, 'shape': (4,), }",
    "fortran-2d": "{'descr': '<f8', 'fortran_order': True, 'shape': (2, 2), }",
    "not-a-dict": "[1, 2, 3]",
}


def _header_edit(src: Path, dst: Path, edit: str) -> None:
    members = _members(src)
    name = _largest_array(members)
    _, compress = members[name]
    if edit == "oversized-header":
        data = _npy("{'descr': '<f8', 'fortran_order': False, 'shape': (1,), }" + " " * 60000,
                    b"\0" * 8)
    else:
        data = _npy(HEADER_EDITS[edit], b"\0" * 64)
    members[name] = (data, compress)
    _write_members(dst, members)


def _bit_flip(src: Path, dst: Path, seed: int) -> None:
    raw = bytearray(src.read_bytes())
    rng = np.random.default_rng(seed)
    position = int(rng.integers(len(raw)))
    raw[position] ^= 1 << int(rng.integers(8))
    dst.write_bytes(bytes(raw))


def _model_edit(src: Path, dst: Path, version, *, tamper: bool, drop_checksum: bool) -> None:
    """Edit a model file as someone who knows the format would, without recomputing the
    checksum: the version set to ``version``, the weights negated if ``tamper``."""
    with np.load(src, allow_pickle=False) as data:
        arrays = {k: data[k] for k in data.files}
    meta = json.loads(str(arrays.pop("__meta__")))
    meta["format_version"] = version
    if drop_checksum:
        meta.pop("checksum_sha256", None)
    if tamper:
        key = "dual_coef_" if "dual_coef_" in arrays else "coefs_1"
        arrays[key] = -arrays[key]
    np.savez(dst, __meta__=np.array(json.dumps(meta)), **arrays)


def _json_edit(src: Path, dst: Path, member: str, text: str) -> None:
    members = _members(src)
    _, compress = members[member]
    body = text.encode("utf-32-le")
    header = f"{{'descr': '<U{len(text)}', 'fortran_order': False, 'shape': (), }}"
    members[member] = (_npy(header, body), compress)
    _write_members(dst, members)


def _fifo(path: Path) -> Path:
    os.mkfifo(path)
    return path


class _PathLike:
    def __init__(self, value):
        self.value = value

    def __fspath__(self):
        return self.value


# --- the cases -------------------------------------------------------------------------------


def _loads(valid: Valid, path, expect="error", names=None, **kw) -> dict:
    names = (Path(path).name,) if names is None else names
    return dict(run=lambda: valid.load(path), expect=expect, names=names, same=valid.same, **kw)


def file_cases(root: Path, files: dict[str, Valid]) -> list[Case]:
    """Mutations of the valid files, and special files, for every loader."""
    out = []
    npz = [v for v in files.values() if not v.kind.startswith("scene")]
    for v in npz:
        size = v.path.stat().st_size
        for cut in sorted({0, 1, 4, 30, size // 10, size // 3, size // 2, size - 22, size - 1}):
            dst = root / f"{v.kind}-cut{cut}.npz"
            dst.write_bytes(v.path.read_bytes()[:cut])
            out.append(Case(f"{v.kind}/truncated-{cut}", **_loads(v, dst), tags={"truncate"}))
        for seed in range(50):
            dst = root / f"{v.kind}-flip{seed}.npz"
            _bit_flip(v.path, dst, seed)
            out.append(Case(f"{v.kind}/bit-flip-{seed}", **_loads(v, dst, "either"),
                            tags={"flip"}))
        for edit in (*HEADER_EDITS, "oversized-header"):
            dst = root / f"{v.kind}-header-{edit}.npz"
            _header_edit(v.path, dst, edit)
            out.append(Case(f"{v.kind}/header-{edit}", **_loads(v, dst), tags={"header"}))
        out += _special_cases(root, v)
        out += _path_cases(v)
    for v in (files["svc"], files["mlp"]):
        for version in (1, 2, 3, 4, 5, 99, True, False, "3", 3.0, None, [3]):
            for tamper, drop in ((False, False), (True, False), (True, True)):
                dst = root / f"{v.kind}-v{version!r}-{tamper}-{drop}.npz"
                _model_edit(v.path, dst, version, tamper=tamper, drop_checksum=drop)
                expect = "error" if tamper else "either"
                out.append(Case(f"{v.kind}/version-{version!r}-tamper{tamper}-nosum{drop}",
                                **_loads(v, dst, expect), tags={"version"}))
        for label, text in (("deep-json", "[" * 200_000 + "]" * 200_000),
                            ("json-list", "[1, 2]"), ("bad-json", "{'a': 1")):
            dst = root / f"{v.kind}-{label}.npz"
            _json_edit(v.path, dst, "__meta__.npy", text)
            out.append(Case(f"{v.kind}/meta-{label}", **_loads(v, dst), tags={"json"}))
    rec = files["recording"]
    for label, text in (("deep-json", "[" * 200_000 + "]" * 200_000),
                        ("deep-object", '{"a":' * 100_000 + "1" + "}" * 100_000),
                        ("json-list", "[1, 2]"), ("bad-json", "{'a': 1"),
                        ("int-keys", '{"1": "a"}')):
        dst = root / f"rec-meta-{label}.npz"
        _json_edit(rec.path, dst, "metadata.npy", text)
        expect = "either" if label == "int-keys" else "error"
        same = (lambda r: r.metadata == {"1": "a"}) if label == "int-keys" else rec.same
        case = _loads(rec, dst, expect)
        case["same"] = same
        out.append(Case(f"recording/metadata-{label}", **case, tags={"json"}))
    out += _dataset_format_cases(root, files["dataset"])
    return out


def _dataset_format_cases(root: Path, v: Valid) -> list[Case]:
    out = []
    with np.load(v.path, allow_pickle=False) as data:
        arrays = {k: data[k] for k in data.files}
    for label, fmt in (("format-2", 2), ("format-true", True), ("format-none", None)):
        meta = json.loads(str(arrays["metadata"]))
        meta["config"]["format"] = fmt
        dst = root / f"dataset-{label}.npz"
        np.savez_compressed(dst, **{**arrays, "metadata": np.array(json.dumps(meta))})
        out.append(Case(f"dataset/{label}", **_loads(v, dst), tags={"version"}))
    tampered = dict(arrays, ax=-arrays["ax"])
    dst = root / "dataset-tampered.npz"
    np.savez_compressed(dst, **tampered)
    out.append(Case("dataset/tampered-ax", **_loads(v, dst), tags={"version"}))
    return out


def _special_cases(root: Path, v: Valid) -> list[Case]:
    """A FIFO, directories, symlinks, devices and foreign files given to the loader of ``v``."""
    base = root / f"special-{v.kind}"
    base.mkdir()
    suffix = v.path.suffix
    fifo = _fifo(base / f"fifo{suffix}")
    (base / f"dir{suffix}").mkdir()
    links = {"link-valid": v.path, "link-dangling": base / "nothing", "link-dir": base,
             "link-fifo": fifo, "link-loop": base / f"link-loop{suffix}"}
    for name, target in links.items():
        os.symlink(target, base / f"{name}{suffix}")
    (base / f"empty{suffix}").write_bytes(b"")
    (base / f"junk{suffix}").write_bytes(np.random.default_rng(7).bytes(3000))
    (base / f"zeros{suffix}").write_bytes(bytes(4096))
    (base / f"png{suffix}").write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(100))
    out = [Case(f"{v.kind}/{p.stem}", **_loads(v, p), tags={"special"})
           for p in sorted(base.iterdir()) if p.stem != "link-valid"]
    out.append(Case(f"{v.kind}/link-valid", **_loads(v, base / f"link-valid{suffix}", "equal"),
                    tags={"special"}))
    for p in ("/dev/null", "/dev/zero", "/proc/self/status", "/proc", "/proc/self/fd/0"):
        if os.path.exists(p):
            out.append(Case(f"{v.kind}/{p}", **_loads(v, p, names=(p,)), tags={"special"}))
    return out


def _path_cases(v: Valid) -> list[Case]:
    """Paths of every wrong type, and right ones of unusual types, for the loader of ``v``."""
    text = str(v.path)
    wrong = {
        "bytes": text.encode(), "bytearray": bytearray(text.encode()), "nul": text + "\0x",
        "nul-inside": text[:5] + "\0" + text[5:], "empty": "", "int": 3, "none": None,
        "float": 1.5, "list": [text], "pathlike-bytes": _PathLike(text.encode()),
        "missing": text + ".missing", "through-a-file": os.path.join(text, "inner"),
    }
    out = [Case(f"{v.kind}/path-{label}", **_loads(v, p, names=("path", "missing", "inner")),
                tags={"path"}) for label, p in wrong.items()]
    for label, p in (("pathlib", Path(text)), ("pathlike", _PathLike(text))):
        out.append(Case(f"{v.kind}/path-{label}", **_loads(v, p, "equal"), tags={"path"}))
    return out


def scene_cases(root: Path, files: dict[str, Valid]) -> list[Case]:
    """Scene files that are binary, not UTF-8, deeply nested, huge or of the wrong shape."""
    v = files["scene-json"]
    t = files["scene-toml"]
    contents = {
        "binary.json": b"\x89PNG\r\n\x1a\n\x00\xff\xfe" + bytes(range(256)),
        "latin1.json": '{"name": "caf\xe9"}'.encode("latin-1"),
        "deep.json": b"[" * 200_000 + b"]" * 200_000,
        "deep-object.json": b'{"a":' * 100_000 + b"1" + b"}" * 100_000,
        "list.json": b"[1, 2, 3]",
        "string.json": b'"paper"',
        "huge.json": b'{"name": "' + b"x" * (3 * 2**20) + b'"}',
        "bom.json": b"\xef\xbb\xbf{}",
        "bad.json": b"{name: paper}",
        "nan-field.json": b'{"fs": NaN}',
        "deep.toml": b"a = " + b"[" * 5000 + b"]" * 5000 + b"\n",
        "binary.toml": b"\x00\xff\xfe\xfd" * 50,
        "bad.toml": b"[probe\nlength = 1",
        "inline-deep.toml": b"a = " + b"{b = " * 3000 + b"1" + b"}" * 3000 + b"\n",
    }
    out = []
    for name, raw in contents.items():
        path = root / name
        path.write_bytes(raw)
        loader = t if name.endswith(".toml") else v
        out.append(Case(f"scene/{name}", **_loads(loader, path), tags={"scene"}))
    return out


def saver_cases(root: Path, files: dict[str, Valid]) -> list[Case]:
    """Output paths for the savers: missing directory, /proc, a FIFO, a directory, bad types."""
    from ebantenna import Recording
    from ebantenna.ml import load_model, save_model
    from ebantenna.simulate.scene import load_scene

    rec = Recording.load(files["recording"].path)
    model = load_model(files["svc"].path)
    scene = load_scene(files["scene-json"].path)
    savers = {"recording": rec.save, "svc": lambda p: save_model(model, p), "scene": scene.save}
    fifo = _fifo(root / "out-fifo.npz")
    targets = {"missing-dir": root / "no-such-dir" / "x.npz", "proc": "/proc/ebantenna-x.npz",
               "fifo": fifo, "directory": root, "bytes": str(root / "b.npz").encode(),
               "nul": str(root / "a\0b.npz"), "through-a-file": files["svc"].path / "x.npz",
               "sys": "/sys/ebantenna-x.npz", "empty": ""}
    out = []
    for kind, save in savers.items():
        for label, target in targets.items():
            names = ("path", "no-such-dir", str(fifo), "/proc", "/sys")
            out.append(Case(f"save-{kind}/{label}", run=lambda s=save, t=target: s(t),
                            expect="error", names=names, tags={"save"}))
    return out


# --- the command line --------------------------------------------------------------------------


def run_cli(argv: list[str]):
    """Run ``ebantenna`` in-process: the exit code, or ``CliError`` with its one line."""
    from ebantenna.cli import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(argv)
        except SystemExit as exc:
            code = exc.code
    lines = [line for line in err.getvalue().splitlines() if line.strip()]
    if code == 2 and lines and lines[-1].startswith(("ebantenna", "usage:")) and (
        len(lines) == 1 or lines[0].startswith("usage:")
    ):
        raise CliError(lines[-1])
    if code not in (0, 1):
        raise CliTraceback(f"exit code {code}: {err.getvalue()[-300:]}")
    return code


def cli_cases(root: Path, files: dict[str, Valid]) -> list[Case]:
    """Arguments naming outputs that cannot be written, bad devices and bad scene files."""
    fifo = _fifo(root / "cli-fifo.npz")
    _fifo(root / "cli-fifo.png")
    afile = files["svc"].path
    bad_outs = {"missing-dir": str(root / "no-such-dir" / "a.npz"), "proc": "/proc/eb-x.npz",
                "fifo": str(fifo), "through-a-file": str(afile / "a.npz"),
                "sys": "/sys/eb-x.npz"}
    out = []
    for label, target in bad_outs.items():
        for argv in (["simulate", "--scene", "ideal", "--out", target],
                     ["acquire", "--simulated", "--out", target],
                     ["modes", "--ratio", "0.5", "--plot", target.replace(".npz", ".png")]):
            flag = "--plot" if "--plot" in argv else "--out"
            out.append(Case(f"cli/{argv[0]}-{label}", run=lambda a=argv: run_cli(a),
                            expect="error", names=(flag,), timeout=60, tags={"cli", "out"}))
    bad_dirs = {"a-file": str(afile), "proc": "/proc/eb-dir", "sys": "/sys/eb-dir",
                "under-a-file": str(afile / "sub"), "fifo": str(fifo)}
    for label, target in bad_dirs.items():
        for argv in (["dataset", "--quick", "--out", target],
                     ["reproduce", "--quick", "--out", target],
                     ["reproduce", "--quick", "--out", str(root / "rep"), "--cache", target],
                     ["bench", "--quick", "--only", "fem_accuracy", "--out", target]):
            flag = "--cache" if "--cache" in argv else "--out"
            out.append(Case(f"cli/{argv[0]}{flag}-{label}", run=lambda a=argv: run_cli(a),
                            expect="error", names=(flag,), timeout=60, tags={"cli", "out"}))
    for bus in ("-1", "-7", "x", "99", "1.5", str(2**70)):
        out.append(Case(f"cli/acquire-bus-{bus}", run=lambda b=bus: run_cli(
            ["acquire", "--bus", b]), expect="error", names=("--bus",), tags={"cli"}))
    for pin in ("-1", "x"):
        out.append(Case(f"cli/acquire-oe-gpio-{pin}", run=lambda p=pin: run_cli(
            ["acquire", "--simulated", "--oe-gpio", p]), expect="error", names=("--oe-gpio",),
            tags={"cli"}))
    for name in ("binary.json", "deep.json", "latin1.json", "deep.toml", "huge.json"):
        path = str(root / name)
        out.append(Case(f"cli/simulate-scene-{name}", run=lambda p=path: run_cli(
            ["simulate", "--scene", p, "--out", str(root / "s.npz")]), expect="error",
            names=(name,), tags={"cli"}))
    out.append(Case("cli/simulate-scene-fifo", run=lambda: run_cli(
        ["simulate", "--scene", str(fifo), "--out", str(root / "s.npz")]), expect="error",
        names=("cli-fifo", "--scene", "scene"), tags={"cli"}))
    return out


def all_cases(root: Path) -> list[Case]:
    """Every case, its files made in ``root`` (a fresh directory)."""
    files = valid_files(root)
    return (file_cases(root, files) + scene_cases(root, files) + saver_cases(root, files)
            + cli_cases(root, files))


def classify(root: Path, *, show: bool = False) -> dict[str, int]:
    """Run every case; return the counts by class (and print each case if ``show``)."""
    counts = dict.fromkeys(CLASSES, 0)
    for case in all_cases(root):
        kind, what = outcome(case)
        counts[kind] += 1
        if show:
            print(f"{kind:15s} {case.id}: {what}", flush=True)
    return counts


if __name__ == "__main__":
    os.environ.setdefault("MPLBACKEND", "Agg")
    start = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        counts = classify(Path(tmp), show="--list" in sys.argv)
    import ebantenna

    print(json.dumps({"ebantenna": os.path.dirname(ebantenna.__file__), "cases": sum(
        counts.values()), **counts, "seconds": round(time.perf_counter() - start, 1)}))
