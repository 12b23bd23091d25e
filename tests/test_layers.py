"""The package's layers: which part may import which, and how long a function may grow.

``MAY_IMPORT`` below is the one written form of the import rules (``docs/architecture.rst`` shows
the same table, and a test here keeps the two equal). A part is a top-level module of the package
(``probe``, ``recording``, ...) or a subpackage (``fem``, ``signal``, ...); ``device.simulated``
is a part of its own, the one corner of ``device`` that may drive the simulator, and every
``_cli`` module belongs to the command layer ``cli`` wherever it sits. Every import
statement counts, those inside functions too (the command-line modules import lazily).

Below the parts, the modules: no two import each other (directly or round a longer circle), and no
module takes a private name (``_name``) from another. A private *module* (``ml/_smo_whole.py``)
is an engine behind its part's public interface: its own part may import its public names.

The unit a reader takes in is a function, so the budget is on functions: at most
``FUNCTION_BUDGET`` lines of code (the docstring is teaching and does not count); a longer one
is listed in ``LONG_FUNCTIONS`` with its reason. A module's length is only a warning.
"""

from __future__ import annotations

import ast
import functools
import re
from pathlib import Path

import pytest

#: The base: small modules every layer may use (data types, argument checks, the memory budget,
#: progress bars and the stop signal they raise again, BLAS's thread count, the chips' datasheet
#: facts, report writing).
BASE = frozenset(
    {"__init__", "_validate", "_budget", "_progress", "_signals", "_files", "_tempfiles",
     "_engines", "_threads", "probe", "recording", "chips", "report"}
)
STAGES = frozenset({"fem", "signal", "ml", "simulate", "device"})

#: part -> the parts it may import (besides itself).
MAY_IMPORT: dict[str, frozenset[str]] = {
    "_validate": frozenset({"_budget"}),
    "_budget": frozenset(),
    "_progress": frozenset({"_signals"}),
    "_signals": frozenset(),
    "_files": frozenset({"_validate"}),
    "_tempfiles": frozenset(),
    "_engines": frozenset(),
    "_threads": frozenset(),
    "probe": frozenset({"_validate"}),
    "recording": frozenset({"_validate"}),
    "chips": frozenset({"_validate"}),
    "__init__": frozenset({"probe", "recording", "_budget"}),
    "report": frozenset({"_validate"}),
    # the students' self-check and its answer key, generated from the exercises' solutions
    "course": frozenset(),
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

#: A module past this many lines is worth a look (a warning, never a failure: teaching content is
#: never cut to fit a number).
MODULE_LINES_HINT = 500

#: Lines of code a function may have, its docstring not counted: what a reader sees on one screen.
FUNCTION_BUDGET = 60

#: "module:qualified.name" -> why it stays longer than the budget.
LONG_FUNCTIONS: dict[str, str] = {
    "ebantenna.simulate._march_numba:march_strike": "one numba kernel: the block march's loop "
    "with its read-ahead, event step and servo stop inline, so that numba compiles one loop "
    "without calls across its hot path (the NumPy engine it reproduces is split into steps)",
}

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
        if part_of(target) in (here, "_validate", "_budget", "_progress", "_signals", "_files",
                               "_tempfiles", "_engines", "_threads"):
            continue  # a part's own private modules; the package-wide private helpers
        private = [n for n in names if n.startswith("_") and n != "__version__"]
        if private or any(p.startswith("_") for p in target.split(".")[1:]):
            wrong.append(f"line {line}: {target} {private}")
    assert not wrong, f"{module_name(path)} reaches into private names: {wrong}"


def long_modules() -> list[tuple[str, int]]:
    """Modules past ``MODULE_LINES_HINT`` lines, longest first (``conftest.py`` lists them after
    every run: a hint to look, never a failure)."""
    sizes = [(module_name(p), len(p.read_text().splitlines())) for p in MODULES]
    return sorted(((m, n) for m, n in sizes if n > MODULE_LINES_HINT), key=lambda r: -r[1])


def code_lines(node: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    """Lines of a function from ``def`` to its end, less its docstring."""
    n = node.end_lineno - node.lineno + 1
    first = node.body[0]
    if (isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant)
            and isinstance(first.value.value, str)):
        n -= first.end_lineno - first.lineno + 1
    return n


def functions(path: Path) -> dict[str, int]:
    """``{"module:qualified.name": code lines}`` of every function in ``path``."""
    found = {}

    def visit(node, prefix):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                name = f"{prefix}{child.name}"
                found[f"{module_name(path)}:{name}"] = code_lines(child)
                visit(child, f"{name}.<locals>.")
            elif isinstance(child, ast.ClassDef):
                visit(child, f"{prefix}{child.name}.")
    visit(ast.parse(path.read_text(), str(path)), "")
    return found


ALL_FUNCTIONS = {k: v for p in MODULES for k, v in functions(p).items()}


def test_functions_fit_the_budget():
    over = {k: n for k, n in ALL_FUNCTIONS.items()
            if n > FUNCTION_BUDGET and k not in LONG_FUNCTIONS}
    assert not over, (f"functions over {FUNCTION_BUDGET} lines of code: split them into named "
                      f"steps, or list them in LONG_FUNCTIONS with the reason: {over}")


def test_every_long_function_listed_is_still_long():
    stale = [k for k in LONG_FUNCTIONS if ALL_FUNCTIONS.get(k, 0) <= FUNCTION_BUDGET]
    assert not stale, f"LONG_FUNCTIONS entries that are gone or fit the budget now: {stale}"


def test_code_lines_leave_out_the_docstring():
    tree = ast.parse('def f():\n    """One.\n\n    Two.\n    """\n    a = 1\n    return a\n')
    assert code_lines(tree.body[0]) == 3  # def, a = 1, return a
    tree = ast.parse("def g():\n    return 1\n")
    assert code_lines(tree.body[0]) == 2


@functools.cache
def module_graph() -> dict[str, frozenset[str]]:
    """Module -> the package modules it imports (every statement, inside functions too).

    Built once per test process and read by every import test (parsing the whole package again
    for each was most of this file's time); the sets are frozen, so no test changes another's."""
    names = {module_name(p) for p in MODULES}
    return {module_name(p): frozenset(t for _, t, _ in imports(p)
                                      if t in names and t != module_name(p))
            for p in MODULES}


def circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components with more than one module (Tarjan, iteratively)."""
    index, low, on_stack, stack, found = {}, {}, set(), [], []
    for root in graph:
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph[child]))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    found.append(sorted(component))
    return found


def test_circles_are_found():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}, "e": set()}
    assert circles(graph) == [["a", "b", "c"]]
    assert circles({"a": {"b"}, "b": set()}) == []


def test_no_import_circle():
    found = circles(module_graph())
    assert not found, f"modules that import each other (directly or round a circle): {found}"


#: Each reference of the architecture page's "Reference and engine" table and the private
#: modules of its engines. The reference imports none of them, at any depth: its engines import
#: it (each that a public function dispatches to adds itself to the reference's registry,
#: :data:`ENGINE_OF`), never the reverse, as the README and DESIGN.md say.
SMO_ENGINES = {"ml._smo_state", "ml._smo_whole", "ml._smo_step", "ml._smo_compiled",
               "ml._smo_numba"}
MLP_ENGINES = {"ml._backprop_engine", "ml._mlp_optimizers", "ml._mlp_compiled", "ml._mlp_numba"}
MARCH_ENGINES = {"simulate._block_march", "simulate._march_numba"}
REFERENCE_ENGINES = {
    "ml.smo": SMO_ENGINES,
    "ml.backprop": MLP_ENGINES,
    "ml.optimizers": MLP_ENGINES,
    "fem.elements": {"fem._assembly_engine"},
    "fem.assembly": {"fem._assembly_engine"},
    "fem.modal": {"fem.sweeps", "fem.banded", "fem.secular"},
    "simulate.unilateral": MARCH_ENGINES,
    "simulate.stick_slip": MARCH_ENGINES,
    "simulate.modes": {"simulate._exponential_grid"},
}
#: Each engine and the reference it imports (and reuses, or registers itself with).
ENGINE_OF = {
    "ml._smo_state": "ml.smo",
    "ml._smo_compiled": "ml.smo",
    "ml._backprop_engine": "ml.backprop",
    "ml._mlp_optimizers": "ml.optimizers",
    "fem._assembly_engine": "fem.assembly",
    "fem.sweeps": "fem.modal",
    "simulate._block_march": "simulate.unilateral",
    "simulate._exponential_grid": "simulate.modes",
}


def reached(graph: dict[str, set[str]], start: str) -> set[str]:
    """Every module ``start`` imports, at any depth."""
    seen, todo = set(), [start]
    while todo:
        for nxt in graph.get(todo.pop(), ()):
            if nxt not in seen:
                seen.add(nxt)
                todo.append(nxt)
    return seen


def test_reached_follows_imports_at_any_depth():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert reached(graph, "a") == {"a", "b", "c"} and reached(graph, "c") == {"a", "b", "c"}
    assert reached({"a": set()}, "a") == set()


@pytest.mark.parametrize("reference", sorted(REFERENCE_ENGINES))
def test_a_reference_imports_none_of_its_engines(reference):
    graph = module_graph()
    full = f"ebantenna.{reference}"
    assert full in graph, f"{full} is no module of the package"
    engines = {f"ebantenna.{e}" for e in REFERENCE_ENGINES[reference]}
    assert engines <= set(graph), sorted(engines - set(graph))
    wrong = sorted(reached(graph, full) & engines)
    assert not wrong, f"{full} imports its engines {wrong} (the engine imports the reference)"


@pytest.mark.parametrize("engine", sorted(ENGINE_OF))
def test_an_engine_imports_its_reference(engine):
    graph = module_graph()
    assert f"ebantenna.{ENGINE_OF[engine]}" in graph[f"ebantenna.{engine}"]
    assert engine in REFERENCE_ENGINES[ENGINE_OF[engine]]


@pytest.mark.parametrize("path", MODULES, ids=lambda p: module_name(p))
def test_no_private_name_of_another_module(path):
    here = module_name(path)
    wrong = [f"line {line}: {target} {names}" for line, target, names in imports(path)
             if target != here and any(n.startswith("_") and n != "__version__" for n in names)]
    assert not wrong, f"{here} takes private names of another module: {wrong}"


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
