"""Count the modules one recording passes, from ``Scene`` to a predicted material.

The walk is the path a student follows through the package: the ``paper`` scene with brass
touched at 0.25 m (:data:`SCENE`, :data:`MATERIAL`, :data:`CONTACT`), simulated to a
:class:`~ebantenna.recording.Recording`, turned into the paper's FFT feature vector
(:func:`ebantenna.signal.fft_features`) and classified by the package's own RBF
:class:`ebantenna.ml.SVC` (``gamma=2.0``, the paper's). The SVC is trained beforehand on a
small data set of other recordings (every material at the same contact, other seeds); its
training is not part of the walk, its ``predict`` is.

Two walks are counted.

**As run** (:func:`run_walk`). The recording runs under :func:`sys.setprofile`. Each function
of the package is noted at its *first* call only (later calls of a function already seen add
nothing), with the module it is defined in. Left out:

- the validation and progress helpers: every function of the modules in :data:`LEFT_OUT`, every
  function named as a check anywhere in the package (``check_...``, ``_check_...``,
  :func:`is_check`), and whatever these call, at any depth;
- code that is not a function a reader opens (:data:`NOT_FUNCTIONS`): a module's own code (every
  module of the stages is imported before the walk starts), comprehensions and generator
  expressions (they belong to the function they are written in; Python 3.12 compiles
  comprehensions inline, so leaving them out keeps the count the same on every version);
- code outside the package (NumPy, SciPy, scikit-learn, the ``__init__`` that
  :mod:`dataclasses` generates).

The compiled engines are switched off for the walk (``EBANTENNA_ENGINE=numpy``): it is the one
required path, the same on every machine. From the sequence of modules of the first calls, with
repeats in a row merged (:func:`count_walk`), the script counts the distinct modules entered and
the *returns*: switches from a module A to a module B where B was entered before.

**As read** (:func:`read_walk`). :data:`READING_ORDER` lists the files a student opens following
the recording from the public entry, in the order they open them. It is the walk as run
restricted (:func:`reading_order`) to the public modules (no private engine: the reader follows
the reference) and to the functions that do the work: not a special method (``__init__``,
``__post_init__``, ...), not a property, and not a function whose body is one statement besides
its checks of the input, which a reader takes from its name at the call (``Scene.has``,
``StructuralDamping.damping_ratio``).
Its count is the number of files and the returns to a file already read, as above.
:func:`check_reading_order` holds the list to the run.

Run it from the repository root::

    PYTHONPATH=$PWD python benchmarks/reading_walk.py            # both walks, one line a module
    PYTHONPATH=$PWD python benchmarks/reading_walk.py --json     # counts, sequences, digests

It also prints SHA-256 digests of the recording's samples and of the SVC's decision values:
code that is only moved between modules must leave both unchanged.
"""

from __future__ import annotations

import argparse
import ast
import contextlib
import difflib
import functools
import hashlib
import importlib
import importlib.util
import inspect
import json
import os
import sys
import textwrap
from pathlib import Path

#: Modules left out of the walk as run, with whatever they call: the argument checks (which name
#: a parameter, its range and the value given) of the package and of the signal stage, the
#: finite-element model's guards (mesh, memory and contact checks, and the floor of an
#: eigenvalue within its rounding, ``fem._rounding``), the memory budget's size
#: check before a large allocation, the progress bar (and the stop signal it raises again,
#: ``_signals``), and BLAS's thread limit around a batch of
#: small solves (``_threads``, which wraps the call to ``threadpoolctl`` that the package made
#: directly before, outside the walk as code outside the package). They are called from
#: everywhere and teach nothing of the path.
LEFT_OUT = (
    "ebantenna._validate",
    "ebantenna._budget",
    "ebantenna._progress",
    "ebantenna._signals",
    "ebantenna._threads",
    "ebantenna.signal._checks",
    "ebantenna.fem.guards",
    "ebantenna.fem._rounding",
)

#: Names of code objects that are not functions a reader opens: a module's own code, and the
#: comprehensions and generator expressions that belong to the function they are written in.
NOT_FUNCTIONS = frozenset({"<module>", "<listcomp>", "<dictcomp>", "<setcomp>", "<genexpr>"})

#: The files a student opens following the recording from ``Scene`` to the predicted material,
#: in order (:func:`reading_order` of the walk as run; :func:`check_reading_order`).
READING_ORDER = (
    "ebantenna/simulate/scene.py",
    "ebantenna/probe.py",
    "ebantenna/simulate/simulator.py",
    "ebantenna/simulate/modes.py",
    "ebantenna/fem/modal.py",
    "ebantenna/fem/assembly.py",
    "ebantenna/fem/modal.py",
    "ebantenna/simulate/touched_object.py",
    "ebantenna/fem/coupling.py",
    "ebantenna/simulate/contact.py",
    "ebantenna/simulate/modes.py",
    "ebantenna/fem/coupling.py",
    "ebantenna/simulate/strikes.py",
    "ebantenna/simulate/modes.py",
    "ebantenna/simulate/strikes.py",
    "ebantenna/simulate/unilateral.py",
    "ebantenna/simulate/effects/sensor.py",
    "ebantenna/signal/features.py",
    "ebantenna/ml/svc.py",
    "ebantenna/ml/kernels.py",
)

#: The goals: at most this many files (modules) and returns as read (as run).
TARGETS = {"read_files": 15, "read_returns": 5, "run_modules": 25, "run_returns": 40}

#: The walk as it stands, which ``tests/test_reading_walk.py`` keeps it within so that it cannot
#: grow back unnoticed: lower these as the walk shrinks, down to :data:`TARGETS`.
CEILINGS = {"read_files": 15, "read_returns": 5, "run_modules": 25, "run_returns": 40}

SCENE, MATERIAL, CONTACT, SEED = "paper", "brass", 0.25, 0

#: The SVC's small training set (not part of the walk): every material of the paper at the
#: walk's contact, three other seeds each.
TRAIN_MATERIALS = ("aluminium", "brass", "wood", "steel", "pvc")
TRAIN_SEEDS = (1, 2, 3)

#: The stages whose modules are imported before the walk (an import is not a call).
_STAGES = ("fem", "simulate", "signal", "ml")


def is_check(name: str) -> bool:
    """Whether a function is an argument check by the package's naming rule (``check_...``,
    ``_check_...``)."""
    return name.startswith(("check_", "_check_"))


def module_of(filename: str, root: Path) -> str | None:
    """Dotted name of the package module defined in ``filename``, or None outside the package
    (``root`` is the package's folder)."""
    try:
        rel = Path(filename).resolve().relative_to(root.parent)
    except ValueError:
        return None
    if rel.suffix != ".py" or rel.parts[0] != root.name:
        return None
    parts = list(rel.with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _code_names(module) -> dict:
    """Qualified name of every function and method defined in ``module``, by code object."""
    names, todo, classes = {}, [module], set()
    while todo:
        owner = todo.pop()
        for value in vars(owner).values():
            if inspect.isclass(value):
                if value.__module__ == module.__name__ and value not in classes:
                    classes.add(value)
                    todo.append(value)
                continue
            for f in (value, getattr(value, "__func__", None), getattr(value, "fget", None),
                      getattr(value, "func", None)):
                code = getattr(f, "__code__", None)
                if code is not None:
                    names[code] = f.__qualname__
    return names


@functools.cache
def _names_of(module_name: str) -> dict:
    return _code_names(importlib.import_module(module_name))


def qualified_name(code, module: str | None = None) -> str:
    """A code object's qualified name (``Class.method``): ``co_qualname`` from Python 3.11 on,
    before that looked up among the functions of its module (its bare name if not found)."""
    name = getattr(code, "co_qualname", None)
    if name is None and module is not None:
        name = _names_of(module).get(code)
    return name or code.co_name


class FirstCalls:
    """A profile function that notes the module of each package function at its first call.

    A call made from inside a left-out function (:data:`LEFT_OUT`, :func:`is_check`), at any
    depth, is part of that check and is not noted; the function is noted at its first call from
    outside one. Use it as a context manager around the calls to note.
    """

    def __init__(self, root: Path, left_out=LEFT_OUT):
        self.root = root
        self.left_out = frozenset(left_out)
        self.seen: set = set()  # code objects noted, or never to be noted
        self.excluded: set = set()  # code objects of left-out functions
        self.calls: list[tuple[str, str]] = []  # (module, qualified name), in order
        self._modules: dict[str, str | None] = {}

    def _module(self, code) -> str | None:
        if code.co_filename not in self._modules:
            self._modules[code.co_filename] = module_of(code.co_filename, self.root)
        return self._modules[code.co_filename]

    def __call__(self, frame, event, arg):
        if event != "call":
            return
        code = frame.f_code
        if code in self.seen or code in self.excluded:
            return
        module = self._module(code)
        if module is None or code.co_name in NOT_FUNCTIONS:
            self.seen.add(code)
            return
        if module in self.left_out or is_check(code.co_name):
            self.excluded.add(code)
            return
        caller = frame.f_back
        while caller is not None:
            if caller.f_code in self.excluded:
                return  # called by a check: part of it
            caller = caller.f_back
        self.seen.add(code)
        self.calls.append((module, qualified_name(code, module)))

    def __enter__(self):
        sys.setprofile(self)
        return self

    def __exit__(self, *exc):
        sys.setprofile(None)
        return False


def count_walk(sequence) -> dict:
    """Merge repeats in a row; count the distinct items and the returns to an item seen before.

    Examples
    --------
    >>> count_walk("aabcab")
    {'path': ['a', 'b', 'c', 'a', 'b'], 'distinct': 3, 'returns': 2}
    """
    path, seen, returns = [], set(), 0
    for item in sequence:
        if path and path[-1] == item:
            continue
        if item in seen:
            returns += 1
        seen.add(item)
        path.append(item)
    return {"path": path, "distinct": len(seen), "returns": returns}


@contextlib.contextmanager
def _numpy_engines():
    """``EBANTENNA_ENGINE=numpy`` inside, the caller's setting restored after."""
    before = os.environ.get("EBANTENNA_ENGINE")
    os.environ["EBANTENNA_ENGINE"] = "numpy"
    try:
        yield
    finally:
        if before is None:
            del os.environ["EBANTENNA_ENGINE"]
        else:
            os.environ["EBANTENNA_ENGINE"] = before


def _import_stages(root: Path) -> None:
    for stage in _STAGES:
        for path in sorted((root / stage).rglob("*.py")):
            name = module_of(str(path), root)
            if name.endswith("._cli") or "numba" in name:
                continue  # the command line's modules; the compiled engines (numba optional)
            importlib.import_module(name)


def _digest(array) -> str:
    import numpy as np

    return hashlib.sha256(np.ascontiguousarray(array, dtype=float).tobytes()).hexdigest()


def run_walk() -> dict:
    """Run the recording from ``Scene`` to a predicted material; note and count its walk.

    Returns
    -------
    dict
        ``calls``: ``(module, function)`` of every first call, in order; ``run``: the counts of
        :func:`count_walk` over their modules; ``prediction``: the material predicted;
        ``recording`` and ``decision``: SHA-256 digests of the recording's ``t``, ``ax``, ``az``
        and of the SVC's decision values.
    """
    import numpy as np

    import ebantenna
    from ebantenna.ml import SVC
    from ebantenna.signal import fft_features
    from ebantenna.simulate import Scene, builtin_scene, simulate, simulate_batch

    root = Path(ebantenna.__file__).resolve().parent
    _import_stages(root)
    recorder = FirstCalls(root)
    with _numpy_engines():
        with recorder:  # the walk: the scene, its recording, its features
            scene = builtin_scene(SCENE).with_(contact=CONTACT, material=MATERIAL)
            rec = simulate(scene, seed=SEED)
            features = fft_features(rec.ax[None, :], rec.az[None, :])
        # beforehand, outside the walk: the classifier's training
        rows = [(m, s) for m in TRAIN_MATERIALS for s in TRAIN_SEEDS]
        _, ax, az, _, _ = simulate_batch(scene, material=[m for m, _ in rows],
                                         seeds=[s for _, s in rows])
        svc = SVC(kernel="rbf", C=1.0, gamma=2.0).fit(fft_features(ax, az),
                                                      [m for m, _ in rows])
        with recorder:  # the walk: the prediction
            predicted = svc.predict(features)
        decision = svc.decision_function(features)
    assert isinstance(scene, Scene)
    return {
        "calls": recorder.calls,
        "run": count_walk(m for m, _ in recorder.calls),
        "prediction": str(predicted[0]),
        "recording": _digest(np.concatenate([rec.t, rec.ax, rec.az])),
        "decision": _digest(decision),
    }


def _statements(function) -> int:
    """The statements of a function's body, at any depth, its docstring and its checks of the
    input aside (:func:`_checks_only`): the checks are left out of the walk, as are the
    validation helpers they call."""
    node = ast.parse(textwrap.dedent(inspect.getsource(function))).body[0]
    body = node.body
    if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
        body = body[1:]
    body = [b for b in body if not _checks_only(b)]
    return sum(isinstance(n, ast.stmt) for b in body for n in ast.walk(b))


def _checks_only(statement) -> bool:
    """Whether a statement of a function's body only checks its input: a call of a ``check_*``
    helper whose value is dropped, or an ``if`` whose body only raises."""
    if isinstance(statement, ast.Expr) and isinstance(statement.value, ast.Call):
        f = statement.value.func
        name = f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", "")
        return name.startswith(("check_", "_check_"))
    return (isinstance(statement, ast.If) and not statement.orelse
            and all(isinstance(s, ast.Raise) for s in statement.body))


def does_work(module: str, qualname: str) -> bool:
    """Whether a reader opens ``module`` to read the function ``qualname``: it is not a special
    method, not a property, and its body holds more than one statement."""
    *owners, name = qualname.split(".")
    if name.startswith("__") or "<" in qualname:
        return False
    obj = importlib.import_module(module)
    try:
        for owner in owners:
            obj = getattr(obj, owner)
        attr = inspect.getattr_static(obj, name)
    except AttributeError:
        return False  # a function nested in another (Python 3.10 names it bare): part of it
    if isinstance(attr, property | functools.cached_property):
        return False
    return _statements(getattr(attr, "__func__", attr)) > 1


def _path_of(module: str) -> str:
    spec = importlib.util.find_spec(module)
    root = Path(importlib.import_module("ebantenna").__file__).resolve().parent.parent
    return Path(spec.origin).resolve().relative_to(root).as_posix()


def reading_order(calls) -> list[str]:
    """The files a student opens, in order: the walk as run restricted to the public modules
    and to the functions that :func:`does_work`, repeats in a row merged."""
    public = [(m, f) for m, f in calls if not any(p.startswith("_") for p in m.split("."))]
    return count_walk(_path_of(m) for m, f in public if does_work(m, f))["path"]


def read_walk(order=READING_ORDER) -> dict:
    """Count the walk as read: the files of ``order`` and the returns to a file already read."""
    return count_walk(order)


def check_reading_order(calls, order=READING_ORDER) -> list[str]:
    """Where ``order`` differs from :func:`reading_order` of the run, as the lines of a diff
    (empty: they agree)."""
    derived = reading_order(calls)
    if list(order) == derived:
        return []
    return list(difflib.unified_diff(list(order), derived, "READING_ORDER", "run", lineterm=""))


def part_of(path: str) -> str:
    """The part of the package a file of the walk belongs to: its folder below the package
    (``ebantenna/fem/modal.py``: ``fem``), or the file itself at the top (``probe.py``)."""
    parts = path.split("/")[1:]
    return parts[0]


def partitions(items):
    """Every way to split the list ``items`` into groups, each a list (Bell's number of them).

    Examples
    --------
    >>> sorted(sorted(map(sorted, p)) for p in partitions(["a", "b"]))
    [[['a'], ['b']], [['a', 'b']]]
    """
    if not items:
        yield []
        return
    first, rest = items[0], items[1:]
    for split in partitions(rest):
        for i in range(len(split)):
            yield split[:i] + [[first] + split[i]] + split[i + 1:]
        yield [[first]] + split


def fewest_returns(order=READING_ORDER) -> dict:
    """The fewest returns any merge of files could leave, with the walk's order kept: for each
    part (:func:`part_of`), every way to merge its files into fewer files, the fewest returns to
    them by the number of files left, ``{part: {files: returns}}``.

    Files are merged within a part only (a merge across parts would import up the layers). The
    files of other parts stay between a part's visits, so each part's returns do not depend on
    how the others are merged: the whole walk's fewest returns is the sum of the parts' fewest.

    Examples
    --------
    A part ``a`` read as x, then another part, then z and x again: merging x and z leaves one
    return (to the merged file, after ``b``), as keeping them apart does (to x).

    >>> fewest_returns(["p/a/x.py", "p/b/y.py", "p/a/z.py", "p/a/x.py"])
    {'a': {1: 1, 2: 1}, 'b': {1: 0}}
    """
    fewest = {}
    for part in sorted({part_of(p) for p in order}):
        files = sorted({p for p in order if part_of(p) == part})
        best = {}
        for split in partitions(files):
            merged = {f: i for i, group in enumerate(split) for f in group}
            walk = count_walk(merged[p] if part_of(p) == part else ("other", part_of(p))
                              for p in order)["path"]
            seen, returns = set(), 0
            for item in walk:
                if not isinstance(item, tuple):
                    returns += item in seen
                    seen.add(item)
            best[len(split)] = min(best.get(len(split), returns), returns)
        fewest[part] = dict(sorted(best.items()))
    return fewest


def _print_walk(title: str, sequence) -> None:
    print(title)
    last = None
    for module, name in sequence:
        if module != last:
            print(f"  {module}")
            last = module
        print(f"      {name}")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("--merges", action="store_true",
                        help="the fewest returns as read that merging files could leave "
                             "(fewest_returns), without running the walk")
    args = parser.parse_args(argv)
    if args.merges:
        fewest = fewest_returns()
        for part, best in fewest.items():
            print(f"{part}: {max(best)} files; fewest returns by files kept: {best}")
        print(f"fewest returns as read by any merge within parts: "
              f"{sum(min(b.values()) for b in fewest.values())} "
              f"(goal: at most {TARGETS['read_returns']})")
        return 0
    walk = run_walk()
    read = read_walk()
    mismatch = check_reading_order(walk["calls"])
    run = walk["run"]
    if args.json:
        print(json.dumps({"run": run, "read": read, "reading_order_matches_run": not mismatch,
                          "targets": TARGETS, "ceilings": CEILINGS,
                          "prediction": walk["prediction"],
                          "recording_sha256": walk["recording"],
                          "decision_sha256": walk["decision"], "calls": walk["calls"]}))
        return 0
    _print_walk("As run (first call of each function):", walk["calls"])
    print(f"as run: {run['distinct']} modules, {run['returns']} returns "
          f"(goal: at most {TARGETS['run_modules']} and {TARGETS['run_returns']})")
    print("As read:")
    for path in read["path"]:
        print(f"  {path}")
    print(f"as read: {read['distinct']} files, {read['returns']} returns "
          f"(goal: at most {TARGETS['read_files']} and {TARGETS['read_returns']})")
    if mismatch:
        print("READING_ORDER differs from the run:")
        print("\n".join(mismatch))
    print(f"predicted material: {walk['prediction']}")
    print(f"recording sha256: {walk['recording']}")
    print(f"decision values sha256: {walk['decision']}")
    return 1 if mismatch else 0


if __name__ == "__main__":
    sys.exit(main())
