"""One loader for the text files the package reads, and the rules every file read obeys.

Every file the package reads goes through :func:`ebantenna._validate.open_regular` (directly, or
through :func:`~ebantenna._validate.open_npz` for ``.npz`` archives): a regular file only (a
FIFO, a device such as ``/dev/zero``, a socket or a directory is refused before it is read, so
nothing hangs), its size bounded, archives' array sizes checked against the memory budget
before anything is allocated. This module adds, for the text documents (plan files, session
manifests, scene files):

- :func:`read_document`: JSON or TOML, its length bounded, its nesting depth measured before it
  is parsed (100,000 nested lists are refused by name, never a ``RecursionError``);
- :func:`require`: the keys a schema requires, a missing one named with its file;
- :func:`inside`: a file name read from a file, resolved inside the folder that owns it
  (absolute paths, ``..``, links that lead out and over-long names refused), so that a name
  written in a file never becomes a path component unchecked.

:data:`FILE_FORMATS` lists every file format the package reads and the function that reads it;
the input-contract tests hold a row of bad inputs for each.
"""

from __future__ import annotations

import os
from pathlib import Path, PurePosixPath

from ._validate import load_json, read_text

__all__ = ["FILE_FORMATS", "MAX_DOCUMENT_BYTES", "MAX_NAME_LENGTH", "read_document", "require",
           "inside", "toml_depth"]

#: Longest text document the package reads, bytes (a manifest of 100,000 touches is ~50 MB).
MAX_DOCUMENT_BYTES = 64 * 2**20
#: Longest file name (one path component) a file may give, characters.
MAX_NAME_LENGTH = 255

#: Every file format the package reads: its name and the public function that reads it.
FILE_FORMATS = {
    "recording": "ebantenna.recording.Recording.load",
    "dataset": "ebantenna.simulate.dataset.load_dataset",
    "model": "ebantenna.ml.persistence.load_model",
    "scene": "ebantenna.simulate.scene.load_scene",
    "plan": "ebantenna.device.plan.load_plan",
    "manifest": "ebantenna.device.recording_session.read_manifest",
    "cache": "ebantenna.simulate.dataset.build_dataset",  # reuses its file via load_dataset
}


def toml_depth(text: str) -> int:
    """How deep the arrays and inline tables of the TOML ``text`` nest, at most (an upper bound).

    Brackets inside strings are counted too, so a string full of ``[`` can only make the bound
    larger: the count errs on the side of refusing. Counted without parsing, like
    :func:`~ebantenna._validate.json_depth`.

    Examples
    --------
    >>> toml_depth('a = [[1, 2], {b = [3]}]')
    3
    """
    depth = deepest = 0
    for char in text:
        if char in "[{":
            depth += 1
            deepest = max(deepest, depth)
        elif char in "]}":
            depth = max(depth - 1, 0)
    return deepest


def read_document(path, what: str, *, max_bytes: int = MAX_DOCUMENT_BYTES, toml: bool = False):
    """The JSON (or, with ``toml=True``, TOML) document in the regular file ``path``.

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    ValueError
        Naming the file: not a regular file, longer than ``max_bytes``, not UTF-8, nested
        deeper than :data:`~ebantenna._validate.MAX_JSON_DEPTH`, or not valid JSON / TOML.
    """
    from ._validate import MAX_JSON_DEPTH

    text = read_text(path, what, max_bytes=max_bytes)
    path = Path(os.fspath(path))
    if not toml:
        return load_json(text, path, what)
    depth = toml_depth(text)
    if depth > MAX_JSON_DEPTH:
        raise ValueError(f"{path} is not {what}: its arrays nest {depth} levels deep, more than "
                         f"the {MAX_JSON_DEPTH} allowed")
    try:
        import tomllib  # novermin (guarded: Python 3.10 falls back to tomli below)
    except ModuleNotFoundError:  # Python 3.10: the same parser, from PyPI
        import tomli as tomllib
    try:
        return tomllib.loads(text)
    except (ValueError, RecursionError) as exc:  # TOMLDecodeError is a ValueError
        raise ValueError(f"{path} is not {what}: not valid TOML ({exc})") from None


def require(data, keys, where: str, *, kind: type | tuple = dict) -> None:
    """Raise unless ``data`` is a ``kind`` (a table) holding every one of ``keys``.

    ``where`` names the file (and the table inside it) in the message.

    Examples
    --------
    >>> require({"plan": {}}, ("plan", "recordings"), "s/session.json")
    Traceback (most recent call last):
    ...
    ValueError: s/session.json: missing key 'recordings'
    """
    if not isinstance(data, kind):
        raise ValueError(f"{where}: must be a table (a JSON object), got {type(data).__name__}")
    missing = [k for k in keys if k not in data]
    if missing:
        raise ValueError(f"{where}: missing key{'s' if len(missing) > 1 else ''} "
                         + ", ".join(repr(k) for k in missing))


def inside(folder, name, where: str) -> Path:
    """The path of ``name`` (a relative, '/'-separated name read from a file) inside ``folder``.

    Refused, with a ``ValueError`` naming ``where`` (the file that gave the name): a name that
    is not a non-empty string, holds a NUL or a backslash, is absolute, has a ``..``, ``.`` or
    empty component or one longer than :data:`MAX_NAME_LENGTH`, or resolves (through a link)
    outside ``folder``.

    Examples
    --------
    >>> inside("s", "recordings/t0.npz", "s/session.json").as_posix()
    's/recordings/t0.npz'
    >>> inside("s", "../elsewhere/x.npz", "s/session.json")
    Traceback (most recent call last):
    ...
    ValueError: s/session.json: the file name '../elsewhere/x.npz' leads outside s (a '..' part)
    """
    folder = Path(folder)
    if not isinstance(name, str) or not name:
        raise ValueError(f"{where}: a file name must be a non-empty string, got {name!r:.80}")
    shown = f"{name!r:.80}"
    if "\x00" in name or "\\" in name:
        raise ValueError(f"{where}: the file name {shown} holds a NUL or a backslash")
    pure = PurePosixPath(name)
    if pure.is_absolute() or os.path.isabs(name):
        raise ValueError(f"{where}: the file name {shown} is absolute; it must lie inside "
                         f"{folder}")
    parts = name.split("/")
    if any(p in ("", ".", "..") for p in parts):
        why = "a '..' part" if ".." in parts else "an empty or '.' part"
        raise ValueError(f"{where}: the file name {shown} leads outside {folder} ({why})")
    if any(len(p) > MAX_NAME_LENGTH for p in parts):
        raise ValueError(f"{where}: the file name {shown} has a part longer than "
                         f"{MAX_NAME_LENGTH} characters")
    path = folder.joinpath(*parts)
    real_folder = folder.resolve()
    real = path.resolve()
    if real != real_folder and real_folder not in real.parents:
        raise ValueError(f"{where}: the file name {shown} leads outside {folder} (through a "
                         f"link to {real})")
    return path
