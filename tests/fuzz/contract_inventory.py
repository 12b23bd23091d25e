"""The public surface of the package, generated from the code, and the contract rows that cover it.

The *inventory* (:func:`inventory`) is read from the code, never written by hand:

- every function and class named in the ``__all__`` of a public module (no ``_`` in its
  dotted path), once, under the name where it is defined (``ebantenna.signal.spectral.envelope``);
  a class's constructor is the class's entry; exceptions and constants take no input and are
  left out;
- every public method of those classes (own or inherited from a class of the package), under
  the class that defines it, and known also by every public class that has it
  (``SVC.fit``);
- every command of ``ebantenna`` (``cli:record``) and every flag of each (``cli:record --yes``);
- every file format the package reads (``file:plan``), from ``ebantenna._files.FILE_FORMATS``.

*Rows* come from any module ``tests/fuzz/test_*.py`` (``test_contract_*.py`` by convention) or
``tests/cli/test_*.py`` that defines ``contract_rows()`` (or assigns it, with its two tests, from
``contract_files_cases.row_tests``): a mapping from a surface's name (its
entry, or any unique ending of it or of one of its aliases, such as ``SVC.fit``) to the ids
of the rows that give it bad input. An engineer who adds a public name adds its rows in a file
of their own, and nothing else. A module may also define ``contract_exempt()``,
``{surface: reason}`` for a public name that takes no input from a user (a result type the
package builds, a function of no argument); exemptions are counted apart, with their reasons.

:data:`PENDING` (``contract_pending.txt``) lists the surfaces that were public before the
inventory existed and have no rows yet. It may only shrink: :func:`problems` reports a surface
with no rows that is not pending, a pending surface that has rows (take it off the list), and a
pending name that is no longer in the inventory.
"""

from __future__ import annotations

import importlib
import importlib.util
import inspect
import pkgutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
TESTS = HERE.parent
PENDING_FILE = HERE / "contract_pending.txt"


def _public_modules():
    import ebantenna

    yield ebantenna
    for info in pkgutil.walk_packages(ebantenna.__path__, "ebantenna."):
        if any(part.startswith("_") for part in info.name.split(".")[1:]):
            continue
        yield importlib.import_module(info.name)


def _own(obj) -> bool:
    return getattr(obj, "__module__", "").split(".")[0] == "ebantenna"


def _methods(cls):
    """``(name, function)`` of the public methods of ``cls`` defined in the package."""
    for name in dir(cls):
        if name.startswith("_"):
            continue
        raw = inspect.getattr_static(cls, name)
        if isinstance(raw, staticmethod | classmethod):
            raw = raw.__func__
        raw = getattr(raw, "fn", raw)  # scikit-learn's available_if wraps its function
        if inspect.isfunction(raw) and _own(raw):
            yield name, raw


def inventory() -> dict[str, set[str]]:
    """Every surface: its entry name mapped to its aliases (other names it is known by)."""
    entries: dict[str, set[str]] = {}
    for module in _public_modules():
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name, None)
            if not _own(obj) or not (inspect.isfunction(obj) or inspect.isclass(obj)):
                continue
            if inspect.isclass(obj) and issubclass(obj, BaseException):
                continue
            entry = f"{obj.__module__}.{obj.__qualname__}"
            entries.setdefault(entry, set()).add(f"{module.__name__}.{name}")
            if inspect.isclass(obj):
                for method, func in _methods(obj):
                    where = f"{func.__module__}.{func.__qualname__}"
                    entries.setdefault(where, set()).update(
                        {f"{entry}.{method}", f"{module.__name__}.{name}.{method}"})
    entries.update({name: set() for name in cli_surface()})
    entries.update({name: set() for name in file_surface()})
    return entries


def cli_surface() -> list[str]:
    """``cli:<command>`` and ``cli:<command> <flag>`` for every command and flag."""
    import argparse

    from ebantenna.cli import build_parser

    out = []
    parser = build_parser()
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for command, sub in action.choices.items():
                out.append(f"cli:{command}")
                for option in sub._actions:
                    flags = [s for s in option.option_strings if s.startswith("--")]
                    if flags and flags[0] != "--help":
                        out.append(f"cli:{command} {flags[0]}")
    return out


def file_surface() -> list[str]:
    """``file:<format>`` for every file format the package reads."""
    from ebantenna._files import FILE_FORMATS

    return [f"file:{name}" for name in FILE_FORMATS]


_INDEXES: dict[int, tuple[dict, dict[str, set[str]]]] = {}


def _index(entries: dict[str, set[str]]) -> dict[str, set[str]]:
    """Every dotted ending of every entry's name and alias, mapped to the entries it names."""
    cached = _INDEXES.get(id(entries))
    if cached is not None and cached[0] is entries:
        return cached[1]
    index: dict[str, set[str]] = {}
    for entry, aliases in entries.items():
        for name in (entry, *aliases):
            parts = name.split(".")
            for i in range(len(parts)):
                index.setdefault(".".join(parts[i:]), set()).add(entry)
    _INDEXES[id(entries)] = (entries, index)
    return index


def resolve(name: str, entries: dict[str, set[str]]) -> str:
    """The entry a row's surface name means: the entry itself, or the one entry whose name or
    alias ends with ``.name``; KeyError if none or several."""
    if name in entries:
        return name
    found = _index(entries).get(name, set())
    if len(found) != 1:
        raise KeyError(f"{name!r} names {sorted(found) or 'no surface'}")
    return next(iter(found))


def row_modules() -> list[Path]:
    """The files that may hold rows."""
    return sorted(HERE.glob("test_*.py")) + sorted((TESTS / "cli").glob("test_*.py"))


def collect_rows() -> dict[str, dict[str, list[str]]]:
    """``{file name: {surface name: row ids}}`` from every row module with ``contract_rows``.

    An exemption of ``contract_exempt`` is a row whose id begins with ``exempt:``.
    """
    out = {}
    for folder in (str(TESTS), str(HERE)):
        if folder not in sys.path:
            sys.path.insert(0, folder)
    for path in row_modules():
        if "contract_rows" not in path.read_text(encoding="utf-8"):
            continue  # no rows (defined, or assigned from contract_files_cases.row_tests)
        name = path.stem
        if name in sys.modules and getattr(sys.modules[name], "__file__", None) and Path(
                sys.modules[name].__file__).resolve() == path:
            module = sys.modules[name]
        else:
            if str(path.parent) not in sys.path:
                sys.path.insert(0, str(path.parent))
            module = importlib.import_module(name)
        rows = getattr(module, "contract_rows", None)
        table = {surface: list(ids) for surface, ids in rows().items()} if rows else {}
        exempt = getattr(module, "contract_exempt", None)
        for surface, why in (exempt() if exempt else {}).items():
            table.setdefault(surface, []).append(f"exempt: {why}")
        out[path.name] = table
    return out


def read_pending() -> set[str]:
    """The surfaces listed in :data:`PENDING_FILE` (one a line, ``#`` comments)."""
    lines = PENDING_FILE.read_text(encoding="utf-8").splitlines()
    return {line.strip() for line in lines if line.strip() and not line.startswith("#")}


def covered(entries, rows) -> tuple[set[str], list[str]]:
    """The entries with at least one row, and the row names that resolve to no single entry."""
    done, unknown = set(), []
    for file, table in rows.items():
        for name, ids in table.items():
            if not ids:
                continue
            try:
                done.add(resolve(name, entries))
            except KeyError as exc:
                if not all(i.startswith("exempt:") for i in ids):  # exceptions are not listed
                    unknown.append(f"{file}: {exc.args[0]}")
    return done, unknown


def problems(entries, rows, pending) -> list[str]:
    """What keeps the contract from covering the inventory (empty when it covers it)."""
    done, unknown = covered(entries, rows)
    out = [f"row for an unknown surface: {u}" for u in unknown]
    out += [f"{e}: public, and no contract rows (add them in a tests/fuzz/test_contract_*.py "
            "contract_rows())" for e in sorted(set(entries) - done - pending)]
    out += [f"{e}: has rows now; take it off {PENDING_FILE.name}" for e in sorted(pending & done)]
    out += [f"{e}: listed in {PENDING_FILE.name} but no longer public" for e in
            sorted(pending - set(entries))]
    return out


def write_pending() -> None:
    """Rewrite :data:`PENDING_FILE` with the surfaces that have no rows now (maintainers only)."""
    entries = inventory()
    done, _ = covered(entries, collect_rows())
    missing = sorted(set(entries) - done)
    PENDING_FILE.write_text(
        "# Public surfaces that had no input-contract rows when the inventory was made.\n"
        "# This list may only shrink: give a surface rows, then remove it here.\n"
        + "".join(f"{m}\n" for m in missing), encoding="utf-8")


if __name__ == "__main__":
    if sys.argv[1:] == ["--write-pending"]:
        write_pending()
    entries = inventory()
    done, unknown = covered(entries, collect_rows())
    kinds = {"api": lambda e: not e.startswith(("cli:", "file:")),
             "cli": lambda e: e.startswith("cli:"), "file": lambda e: e.startswith("file:")}
    for kind, test in kinds.items():
        mine = [e for e in entries if test(e)]
        print(f"{kind}: {len(mine)} surfaces, {sum(e in done for e in mine)} with rows")
    print("\n".join(unknown))
