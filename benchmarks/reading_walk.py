"""Count the modules one recording passes, from ``Scene`` to a predicted material.

The walk is the path a student follows through the package: the ``paper`` scene with brass
touched at 0.25 m, simulated to a :class:`~ebantenna.recording.Recording`, turned into the
paper's FFT feature vector (:func:`ebantenna.signal.fft_features`) and classified by the
package's own RBF :class:`ebantenna.ml.SVC`. The SVC is trained beforehand on a small data set
of other recordings; its training is not part of the walk, its ``predict`` is.

Two walks are counted.

**As run.** The walk runs under :func:`sys.setprofile`. Each function of the package is
recorded at its *first* call only (later calls of a function already seen add nothing), and the
module it is defined in is noted. The validation and progress helpers are left out: the
modules named in :data:`LEFT_OUT` (argument checks that name the parameter and its range, the
memory budget's size check, the progress bar). Module-level code is not a call (every module
is imported before the walk starts), nor is code outside the package (NumPy, SciPy,
generated ``__init__`` methods of dataclasses). From the sequence of modules of those first
calls, with repeats in a row merged, the script counts

- the distinct modules entered, and
- the *returns*: switches from a module A to a module B where B was entered before.

**As read.** :data:`READING_ORDER` lists the files a student opens following the calls from
the public entry, in the order they open them: the run-time walk restricted to the public
modules and to the functions that do the work (a reader does not open a private engine to
follow the textbook step, nor the ``__init__`` that only re-exports a name). Its count is
the number of distinct files and the returns to a file already open, counted as above.
:func:`check_reading_order` holds the list to the run: every file in it is entered at run
time, in an order the run allows.

Run it (from the repository root)::

    PYTHONPATH=$PWD python benchmarks/reading_walk.py          # the walks, one module a line
    PYTHONPATH=$PWD python benchmarks/reading_walk.py --json   # the counts and sequences

With ``--hash`` it also prints SHA-256 digests of the recording's samples and of the SVC's
decision values, which must not change when the code is only moved between modules.

The compiled engines (numba) are switched off for the walk (``EBANTENNA_ENGINE=numpy``), so
that it is the one required path, the same on every machine.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import sys
from pathlib import Path

#: Modules left out of the run-time walk: the argument checks (which name a parameter, its range
#: and the value given; the finite-element model's guards of mesh, memory and contact), the
#: memory budget's size check done before a large allocation, and the progress bar. They are
#: called from everywhere and teach nothing of the path. So are the functions named as checks
#: anywhere in the package (:func:`is_check`), and whatever a left-out function calls.
LEFT_OUT = (
    "ebantenna._validate",
    "ebantenna._budget",
    "ebantenna._progress",
    "ebantenna.signal._checks",
    "ebantenna.fem.guards",
)

#: Code objects that are not functions a reader opens: a module's own code (every module is
#: imported before the walk), and comprehensions and generator expressions, which belong to the
#: function they are written in (Python 3.12 compiles comprehensions inline; so the count does
#: not depend on the Python version).
NOT_FUNCTIONS = frozenset({"<module>", "<listcomp>", "<dictcomp>", "<setcomp>", "<genexpr>"})

#: The files a student opens following the recording from the public entry, in order (the
#: run-time walk restricted to public modules and to the functions that do the work).
READING_ORDER = ()

#: The targets: at most this many files / returns as read, modules / returns as run.
TARGETS = {"read_files": 15, "read_returns": 5, "run_modules": 25, "run_returns": 40}

SCENE, MATERIAL, CONTACT, SEED = "paper", "brass", 0.25, 0

#: The small training set of the SVC (not part of the walk): every material of the paper at
#: two other contacts, two seeds each.
TRAIN_MATERIALS = ("aluminium", "brass", "wood", "steel", "pvc")
TRAIN_CONTACTS = (0.20, 0.30)
TRAIN_SEEDS = (1, 2)


def is_check(name: str) -> bool:
    """Whether a function is an argument check by the package's naming rule (``check_...``,
    ``_check_...``)."""
    return name.startswith(("check_", "_check_"))


def module_of(filename: str, root: Path) -> str | None:
    """Dotted name of the package module defined in ``filename``, or None outside the package."""
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


class FirstCalls:
    """A profile function that notes the module of each package function at its first call.

    A call made from inside a left-out function (:func:`left_out`), at any depth, is part of
    that check and is not noted; the function is noted at its first call from outside one.
    """

    def __init__(self, root: Path, left_out=LEFT_OUT):
        self.root = root
        self.left_out = frozenset(left_out)
        self.seen: set = set()  # code objects noted (or never to be noted)
        self.excluded: set = set()  # code objects of left-out functions
        self.calls: list[tuple[str, str]] = []  # (module, qualified function name)
        self._modules: dict[str, str | None] = {}

    def _module(self, code) -> str | None:
        module = self._modules.get(code.co_filename, ...)
        if module is ...:
            module = module_of(code.co_filename, self.root)
            self._modules[code.co_filename] = module
        return module

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
        self.calls.append((module, code.co_qualname))

    def __enter__(self):
        sys.setprofile(self)
        return self

    def __exit__(self, *exc):
        sys.setprofile(None)
        return False


def count_walk(sequence) -> dict:
    """Merge repeats in a row and count distinct entries and returns to an entry seen before."""
    path, seen, returns = [], set(), 0
    for item in sequence:
        if path and path[-1] == item:
            continue
        if item in seen:
            returns += 1
        seen.add(item)
        path.append(item)
    return {"path": path, "distinct": len(seen), "returns": returns}


def _training_set(builtin_scene, simulate, fft_features):
    import numpy as np

    scene = builtin_scene(SCENE)
    rows, labels = [], []
    for material in TRAIN_MATERIALS:
        for contact in TRAIN_CONTACTS:
            for seed in TRAIN_SEEDS:
                rec = simulate(scene.with_(contact=contact, material=material), seed=seed)
                rows.append(rec)
                labels.append(material)
    ax = np.stack([r.ax for r in rows])
    az = np.stack([r.az for r in rows])
    return fft_features(ax, az), np.array(labels)


def run_walk() -> dict:
    """Run the recording from ``Scene`` to a predicted material and count its walk as run.

    Returns
    -------
    dict
        ``calls`` (module, function) of every first call in order, ``run`` (the counts of
        :func:`count_walk` over their modules), ``prediction``, and the digests ``recording``
        and ``decision`` (SHA-256 of the samples and of the decision values).
    """
    os.environ["EBANTENNA_ENGINE"] = "numpy"
    import numpy as np

    import ebantenna
    from ebantenna.ml import SVC
    from ebantenna.signal import fft_features
    from ebantenna.simulate import Scene, builtin_scene, simulate

    root = Path(ebantenna.__file__).resolve().parent
    _import_all(root)
    recorder = FirstCalls(root)
    # the walk, part 1: the scene, its recording and its features
    with recorder:
        scene = builtin_scene(SCENE).with_(contact=CONTACT, material=MATERIAL)
        assert isinstance(scene, Scene)
        rec = simulate(scene, seed=SEED)
        x = fft_features(rec.ax[None, :], rec.az[None, :])
    # beforehand, outside the walk: the classifier's training
    X, y = _training_set(builtin_scene, simulate, fft_features)
    svc = SVC(kernel="rbf", C=1.0, gamma=2.0).fit(X, y)
    # the walk, part 2: the prediction
    with recorder:
        predicted = svc.predict(x)
    decision = svc.decision_function(x)
    samples = np.concatenate([rec.t, rec.ax, rec.az])
    return {
        "calls": recorder.calls,
        "run": count_walk(m for m, _ in recorder.calls),
        "prediction": str(predicted[0]),
        "recording": hashlib.sha256(np.ascontiguousarray(samples).tobytes()).hexdigest(),
        "decision": hashlib.sha256(np.ascontiguousarray(decision).tobytes()).hexdigest(),
    }


def _import_all(root: Path) -> None:
    # every module of the stages the walk passes is imported first: an import is not a call
    import importlib

    for stage in ("simulate", "signal", "ml", "fem"):
        for path in sorted((root / stage).rglob("*.py")):
            name = module_of(str(path), root)
            if name.rsplit(".", 1)[-1] in ("_cli",) or "numba" in name:
                continue
            importlib.import_module(name)


def read_walk(order=READING_ORDER) -> dict:
    """Count the walk as read: distinct files of ``order`` and returns to a file already open."""
    return count_walk(order)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("--hash", action="store_true", help="print the digests too")
    args = parser.parse_args(argv)
    walk = run_walk()
    read = read_walk()
    if args.json:
        print(json.dumps({"run": walk["run"], "read": read, "prediction": walk["prediction"],
                          "recording": walk["recording"], "decision": walk["decision"],
                          "calls": walk["calls"]}))
        return 0
    print("as run (first call of each function):")
    last = None
    for module, name in walk["calls"]:
        if module != last:
            print(f"  {module}")
            last = module
        print(f"      {name}")
    run = walk["run"]
    print(f"as run: {run['distinct']} modules, {run['returns']} returns, "
          f"{len(run['path'])} module entries")
    print("as read: " + " -> ".join(read["path"]))
    print(f"as read: {read['distinct']} files, {read['returns']} returns")
    print(f"prediction: {walk['prediction']}")
    if args.hash:
        print(f"recording sha256: {walk['recording']}")
        print(f"decision sha256: {walk['decision']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
