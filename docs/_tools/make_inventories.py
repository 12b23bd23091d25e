"""Write the Sphinx inventories that let the docs link to Python, numpy, scipy, scikit-learn, sympy,
matplotlib, joblib and smbus2 without downloading their ``objects.inv``.

Each inventory lists only the objects these docs refer to, each with the page (and anchor) where
the project's own documentation describes it. The file follows Sphinx's documented inventory format,
version 2: four header lines, then zlib-compressed lines ``name domain:role priority uri dispname``
(``-`` as ``dispname`` means ``name``).

Every name is imported from the installed package (the built-in names from :mod:`builtins`) before
it is written, so an inventory never promises an object that does not exist; the version in the
header is the installed one (for Python, the running interpreter's ``major.minor``).

Run from the repository root after adding a reference to the docs::

    python docs/_tools/make_inventories.py
"""

from __future__ import annotations

import argparse
import builtins
import importlib
import importlib.metadata
import sys
import zlib
from pathlib import Path

#: project -> (display name, distribution, base URL, [(object, role, uri relative to base)]);
#: ``$`` in a uri stands for the object's name.
#: ``role`` is a Python-domain role: function, class, method, module, data.
#: ``distribution`` ``None`` stands for the Python standard library.
INVENTORIES: dict[str, tuple[str, str | None, str, list[tuple[str, str, str]]]] = {
    "python": (
        "Python",
        None,
        "https://docs.python.org/3/",
        [
            ("bool", "class", "library/functions.html#$"),
            ("int", "class", "library/functions.html#$"),
            ("float", "class", "library/functions.html#$"),
            ("complex", "class", "library/functions.html#$"),
            ("object", "class", "library/functions.html#$"),
            ("callable", "function", "library/functions.html#$"),
            ("format", "function", "library/functions.html#$"),
            ("str", "class", "library/stdtypes.html#$"),
            ("bytes", "class", "library/stdtypes.html#$"),
            ("list", "class", "library/stdtypes.html#$"),
            ("tuple", "class", "library/stdtypes.html#$"),
            ("dict", "class", "library/stdtypes.html#$"),
            ("None", "data", "library/constants.html#$"),
            ("abc.ABC", "class", "library/abc.html#$"),
            ("collections.abc.Sequence", "class", "library/collections.abc.html#$"),
            ("collections.abc.Iterable", "class", "library/collections.abc.html#$"),
            ("collections.abc.Callable", "class", "library/collections.abc.html#$"),
            ("enum.IntEnum", "class", "library/enum.html#$"),
            ("enum.IntFlag", "class", "library/enum.html#$"),
            ("fractions.Fraction", "class", "library/fractions.html#$"),
            ("os.PathLike", "class", "library/os.html#$"),
            ("pathlib.Path", "class", "library/pathlib.html#$"),
            ("time.monotonic", "function", "library/time.html#$"),
            ("time.sleep", "function", "library/time.html#$"),
            ("signal", "module", "library/signal.html#module-$"),
            ("types.ModuleType", "class", "library/types.html#$"),
        ],
    ),
    "numpy": (
        "NumPy",
        "numpy",
        "https://numpy.org/doc/stable/",
        [
            ("numpy", "module", "reference/index.html#module-$"),
            ("numpy.ndarray", "class", "reference/generated/$.html"),
            ("numpy.dtype", "class", "reference/generated/$.html"),
            ("numpy.int16", "class", "reference/arrays.scalars.html#$"),
            ("numpy.int32", "class", "reference/arrays.scalars.html#$"),
            ("numpy.int64", "class", "reference/arrays.scalars.html#$"),
            ("numpy.float32", "class", "reference/arrays.scalars.html#$"),
            ("numpy.float64", "class", "reference/arrays.scalars.html#$"),
            ("numpy.hypot", "function", "reference/generated/$.html"),
            ("numpy.typing.ArrayLike", "data", "reference/typing.html#$"),
            ("numpy.random.default_rng", "function", "reference/random/generator.html#$"),
            ("numpy.random.Generator", "class", "reference/random/generator.html#$"),
            ("numpy.random.RandomState", "class", "reference/random/legacy.html#$"),
            ("numpy.linalg.eigh", "function", "reference/generated/$.html"),
            ("numpy.linalg.cholesky", "function", "reference/generated/$.html"),
            ("numpy.linalg.solve", "function", "reference/generated/$.html"),
            ("numpy.fft.rfft", "function", "reference/generated/$.html"),
            ("numpy.polyfit", "function", "reference/generated/$.html"),
            ("numpy.savez_compressed", "function", "reference/generated/$.html"),
            ("numpy.load", "function", "reference/generated/$.html"),
        ],
    ),
    "scipy": (
        "SciPy",
        "scipy",
        "https://docs.scipy.org/doc/scipy/",
        [
            ("scipy.linalg.eigh", "function", "reference/generated/$.html"),
            ("scipy.linalg.cholesky", "function", "reference/generated/$.html"),
            ("scipy.linalg.solve_triangular", "function", "reference/generated/$.html"),
            ("scipy.sparse.linalg.eigsh", "function", "reference/generated/$.html"),
            ("scipy.sparse", "module", "reference/sparse.html#module-$"),
            ("scipy.sparse.csr_matrix", "class", "reference/generated/$.html"),
            ("scipy.integrate.solve_ivp", "function", "reference/generated/$.html"),
            ("scipy.optimize.brentq", "function", "reference/generated/$.html"),
            ("scipy.optimize.least_squares", "function", "reference/generated/$.html"),
            ("scipy.optimize.minimize_scalar", "function", "reference/generated/$.html"),
            ("scipy.optimize.minimize", "function", "reference/generated/$.html"),
            ("scipy.optimize.curve_fit", "function", "reference/generated/$.html"),
            ("scipy.signal.sosfiltfilt", "function", "reference/generated/$.html"),
            ("scipy.signal.sosfilt", "function", "reference/generated/$.html"),
            ("scipy.signal.lfilter", "function", "reference/generated/$.html"),
            ("scipy.signal.sosfreqz", "function", "reference/generated/$.html"),
            ("scipy.signal.cheby1", "function", "reference/generated/$.html"),
            ("scipy.signal.cheb1ord", "function", "reference/generated/$.html"),
            ("scipy.signal.ellip", "function", "reference/generated/$.html"),
            ("scipy.signal.ellipord", "function", "reference/generated/$.html"),
            ("scipy.signal.hilbert", "function", "reference/generated/$.html"),
            ("scipy.signal.spectrogram", "function", "reference/generated/$.html"),
        ],
    ),
    "sklearn": (
        "scikit-learn",
        "scikit-learn",
        "https://scikit-learn.org/stable/",
        [
            ("sklearn.svm.SVC", "class", "modules/generated/$.html"),
            ("sklearn.neural_network.MLPClassifier", "class", "modules/generated/$.html"),
            ("sklearn.neural_network.MLPRegressor", "class", "modules/generated/$.html"),
            ("sklearn.base.BaseEstimator", "class", "modules/generated/$.html"),
            ("sklearn.base.ClassifierMixin", "class", "modules/generated/$.html"),
            ("sklearn.base.RegressorMixin", "class", "modules/generated/$.html"),
            ("sklearn.utils.validation.validate_data", "function", "modules/generated/$.html"),
            ("sklearn.model_selection.train_test_split", "function", "modules/generated/$.html"),
            ("sklearn.preprocessing.StandardScaler", "class", "modules/generated/$.html"),
            ("sklearn.metrics", "module", "api/$.html"),
            ("sklearn.metrics.accuracy_score", "function", "modules/generated/$.html"),
            ("sklearn.metrics.confusion_matrix", "function", "modules/generated/$.html"),
        ],
    ),
    "sympy": (
        "SymPy",
        "sympy",
        "https://docs.sympy.org/latest/",
        [
            ("sympy.printing.latex.latex", "function", "modules/printing.html#$"),
            ("sympy.latex", "function", "modules/printing.html#sympy.printing.latex.latex"),
            ("sympy.utilities.lambdify.lambdify", "function", "modules/utilities/lambdify.html#$"),
            ("sympy.lambdify", "function",
             "modules/utilities/lambdify.html#sympy.utilities.lambdify.lambdify"),
            ("sympy.integrals.integrals.integrate", "function",
             "modules/integrals/integrals.html#$"),
            ("sympy.integrate", "function",
             "modules/integrals/integrals.html#sympy.integrals.integrals.integrate"),
            ("sympy.solvers.solvers.solve", "function", "modules/solvers/solvers.html#$"),
            ("sympy.solve", "function", "modules/solvers/solvers.html#sympy.solvers.solvers.solve"),
            ("sympy.Matrix", "class", "modules/matrices/matrices.html"),
        ],
    ),
    "matplotlib": (
        "Matplotlib",
        "matplotlib",
        "https://matplotlib.org/stable/",
        [
            ("matplotlib.axes.Axes", "class", "api/_as_gen/$.html"),
            ("matplotlib.axes.Axes.plot", "method", "api/_as_gen/$.html"),
            ("matplotlib.axes.Axes.pcolormesh", "method", "api/_as_gen/$.html"),
            ("matplotlib.figure.Figure", "class", "api/_as_gen/$.html"),
            ("matplotlib.pyplot.subplots", "function", "api/_as_gen/$.html"),
        ],
    ),
    "joblib": (
        "joblib",
        "joblib",
        "https://joblib.readthedocs.io/en/stable/",
        [
            ("joblib.Parallel", "class", "generated/$.html"),
            ("joblib.parallel_config", "class", "generated/$.html"),
        ],
    ),
    "smbus2": (
        "smbus2",
        "smbus2",
        "https://smbus2.readthedocs.io/en/latest/",
        [
            ("smbus2.SMBus", "class", "api.html#$"),
        ],
    ),
}


def resolve(name: str):
    """Import the object a dotted name refers to; ``LookupError`` if there is none.

    A name without a dot that is no module is looked up among the built-ins (``float``, ``None``).
    """
    parts = name.split(".")
    if len(parts) == 1 and hasattr(builtins, name):
        return getattr(builtins, name)
    for k in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:k]))
        except ImportError:
            continue
        for attr in parts[k:]:
            if not hasattr(obj, attr):
                raise LookupError(f"{name}: {'.'.join(parts[:k])} has no attribute {attr!r}")
            obj = getattr(obj, attr)
        return obj
    raise LookupError(f"{name}: no importable module")


def inventory_bytes(project: str, version: str, entries) -> bytes:
    """The bytes of an inventory file (format version 2) for ``entries``."""
    header = (
        "# Sphinx inventory version 2\n"
        f"# Project: {project}\n"
        f"# Version: {version}\n"
        "# The remainder of this file is compressed using zlib.\n"
    ).encode()
    # ``$`` in our table stands for the name anywhere in the URI; Sphinx only expands a trailing
    # ``$``, so the URIs are written out in full.
    lines = "".join(
        f"{name} py:{role} 1 {uri.replace('$', name)} -\n" for name, role, uri in sorted(entries)
    )
    return header + zlib.compress(lines.encode(), 9)


def write_inventories(out_dir: Path) -> list[Path]:
    """Write ``<key>.inv`` for each project of :data:`INVENTORIES` into ``out_dir``."""
    out_dir.mkdir(parents=True, exist_ok=True)
    written = []
    for key, (project, distribution, _base, entries) in INVENTORIES.items():
        for name, _role, _uri in entries:
            resolve(name)
        if distribution is None:
            version = f"{sys.version_info.major}.{sys.version_info.minor}"
        else:
            version = importlib.metadata.version(distribution)
        path = out_dir / f"{key}.inv"
        path.write_bytes(inventory_bytes(project, version, entries))
        written.append(path)
    return written


def intersphinx_mapping(inventory_dir: str = "_inventories") -> dict:
    """The ``intersphinx_mapping`` of ``conf.py``: each base URL with its local inventory."""
    return {
        key: (base, f"{inventory_dir}/{key}.inv")
        for key, (_project, _dist, base, _entries) in INVENTORIES.items()
    }


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    default = Path(__file__).resolve().parent.parent / "_inventories"
    parser.add_argument("--out", type=Path, default=default, help=f"output folder ({default})")
    args = parser.parse_args(argv)
    for path in write_inventories(args.out):
        print(path)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
