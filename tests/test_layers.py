"""The package's layers: which part may import which, and how long a module may grow.

``MAY_IMPORT`` below is the one written form of the import rules (``docs/architecture.rst`` shows
the same table, and a test here keeps the two equal). A part is a top-level module of the package
(``probe``, ``recording``, ...) or a subpackage (``fem``, ``signal``, ...); ``device.simulated``
is a part of its own, the one corner of ``device`` that may drive the simulator, and every
``_cli`` module belongs to the command layer ``cli`` wherever it sits. Every import
statement counts, those inside functions too (the command-line modules import lazily).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

#: The base: small modules every layer may use (data types, argument checks, progress bars, the
#: chips' datasheet facts, report writing).
BASE = frozenset({"__init__", "_validate", "_progress", "probe", "recording", "chips", "report"})
STAGES = frozenset({"fem", "signal", "ml", "simulate", "device"})

#: part -> the parts it may import (besides itself).
MAY_IMPORT: dict[str, frozenset[str]] = {
    "_validate": frozenset(),
    "_progress": frozenset(),
    "probe": frozenset({"_validate"}),
    "recording": frozenset({"_validate"}),
    "chips": frozenset({"_validate"}),
    "__init__": frozenset({"probe", "recording"}),
    "report": frozenset({"_validate"}),
    "fem": BASE,
    "signal": BASE,
    "ml": BASE,
    "simulate": BASE | {"fem"},
    # the package re-exports the simulated rig's names; only device.simulated imports simulate,
    # and only inside the functions that drive it (tests/device/test_device_simulated.py)
    "device": BASE | {"device.simulated"},
    "device.simulated": BASE | {"device", "simulate", "fem"},
    "paper": BASE | STAGES | {"device.simulated"},
    "study": BASE | STAGES | {"paper"},
    "bench": BASE | STAGES | {"paper"},
    "cli": BASE | STAGES | {"device.simulated", "paper", "study", "bench"},
    "__main__": frozenset({"cli"}),
}

#: A module past this many lines is split: a reader should find each concept in a short file.
MAX_LINES = 500

PACKAGE = Path(__file__).resolve().parent.parent / "ebantenna"
MODULES = sorted(PACKAGE.rglob("*.py"))


def part_of(module: str) -> str:
    """The part a dotted module name below ``ebantenna`` belongs to."""
    names = module.split(".")[1:]  # drop "ebantenna"
    if not names:
        return "__init__"
    if names[-1] == "_cli":  # each command sits beside the code it drives, in the command layer
        return "cli"
    if names[:2] == ["device", "simulated"]:
        return "device.simulated"
    return names[0]


def module_name(path: Path) -> str:
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _exists(module: str) -> bool:
    path = PACKAGE.parent / module.replace(".", "/")
    return path.with_suffix(".py").exists() or (path / "__init__.py").exists()


def imports(path: Path) -> list[tuple[int, str, list[str]]]:
    """Every import of an ``ebantenna`` module in ``path``: (line, module, names taken from it)."""
    name = module_name(path)
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    found = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            found += [(node.lineno, a.name, []) for a in node.names
                      if a.name.split(".")[0] == "ebantenna"]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] != "ebantenna":
                continue
            for alias in node.names:  # "from . import x": x may be a module of its own
                sub = f"{target}.{alias.name}"
                if _exists(sub):
                    found.append((node.lineno, sub, []))
                else:
                    found.append((node.lineno, target, [alias.name]))
    return found


def test_every_part_is_in_the_graph():
    parts = {part_of(module_name(p)) for p in MODULES}
    unknown = sorted(parts - set(MAY_IMPORT))
    assert not unknown, f"parts missing from MAY_IMPORT: {unknown}"


@pytest.mark.parametrize("path", MODULES, ids=lambda p: module_name(p))
def test_no_import_runs_up_the_layers(path):
    here = part_of(module_name(path))
    allowed = MAY_IMPORT.get(here, frozenset())
    wrong = [f"line {line}: {target} ({part_of(target)})"
             for line, target, _ in imports(path)
             if part_of(target) != here and part_of(target) not in allowed]
    assert not wrong, f"{module_name(path)} ({here}) imports above its layer: {wrong}"


@pytest.mark.parametrize("path", MODULES, ids=lambda p: module_name(p))
def test_no_private_name_of_another_part(path):
    here = part_of(module_name(path))
    wrong = []
    for line, target, names in imports(path):
        if part_of(target) in (here, "_validate", "_progress"):
            continue  # a part's own private modules; the package-wide private helpers
        private = [n for n in names if n.startswith("_") and n != "__version__"]
        if private or any(p.startswith("_") for p in target.split(".")[1:]):
            wrong.append(f"line {line}: {target} {private}")
    assert not wrong, f"{module_name(path)} reaches into private names: {wrong}"


@pytest.mark.parametrize("path", MODULES, ids=lambda p: module_name(p))
def test_no_module_grows_past_the_limit(path):
    n = len(path.read_text().splitlines())
    assert n <= MAX_LINES, f"{module_name(path)}: {n} lines (at most {MAX_LINES})"


#: File names that mean the same thing wherever they stand: the package conventions, and a chip's
#: name (its datasheet facts in ``chips``, its driver in ``device``, its model in
#: ``device.simulated``).
SAME_MEANING_MODULES = {"__init__", "_cli", "__main__", "mpu6050", "pca9685"}
#: Class names that mean the same thing in each chip's module: that chip's register map.
SAME_MEANING_CLASSES = {"Register"}


def test_no_two_modules_share_a_name_with_different_meanings():
    conventional = SAME_MEANING_MODULES
    seen: dict[str, str] = {}
    clashes = []
    for path in MODULES:
        if path.stem in conventional:
            continue
        name = module_name(path)
        if path.stem in seen and part_of(seen[path.stem]) != part_of(name):
            clashes.append((seen[path.stem], name))
        seen.setdefault(path.stem, name)
    assert not clashes, clashes


def test_no_two_public_classes_share_a_name():
    seen: dict[str, str] = {}
    clashes = []
    for path in MODULES:
        for node in ast.parse(path.read_text(), str(path)).body:
            if (isinstance(node, ast.ClassDef) and not node.name.startswith("_")
                    and node.name not in SAME_MEANING_CLASSES):
                where = module_name(path)
                if node.name in seen and seen[node.name] != where:
                    clashes.append((node.name, seen[node.name], where))
                seen.setdefault(node.name, where)
    assert not clashes, clashes


def test_architecture_page_shows_the_same_graph():
    page = (PACKAGE.parent / "docs" / "architecture.rst").read_text()
    rows = re.findall(r'^   "``([\w.]+)``", "[^"]*", "([^"]*)"$', page, re.M)
    assert rows, "docs/architecture.rst has no table of parts"
    groups = {"base": BASE, "stages": STAGES}
    shown = {}
    for part, may in rows:
        names = re.findall(r"``([\w.]+)``", may)
        shown[part] = frozenset().union(*(groups.get(n, {n}) for n in names))
    assert shown == MAY_IMPORT
