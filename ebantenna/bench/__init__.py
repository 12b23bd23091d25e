"""Accuracy against time, for every subpackage: what each extra digit or percent costs.

Each module here is one sweep: ``run(quick)`` measures and returns its rows (lists of dicts),
``to_text(rows)`` formats them as text tables, and, where the sweep has a figure,
``plot(rows)`` draws it from the same rows. ``main(argv)`` prints the tables; the scripts in the
repository's ``benchmarks/`` folder run them one at a time, and :func:`run_benchmarks` (the
``ebantenna bench`` command) runs them all, each once, and writes every table and figure into one
report through :func:`write_sweep`.

- :mod:`~ebantenna.bench.fem_accuracy`: FEM error against the exact frequencies and solve time,
  N = 2 ... 2048 elements, three solvers; the batched contact sweep.
- :mod:`~ebantenna.bench.signal_accuracy`: frequency estimators (window, zero padding,
  interpolation), STFT against wavelets, decay-fit methods, distance estimators.
- :mod:`~ebantenna.bench.simulate_cost`: seconds per 1000 signals for each simulated effect.
- :mod:`~ebantenna.bench.contact_cost`: the strike's Hertz contact against the linearised one.
- :mod:`~ebantenna.bench.ml_speed`: the hand-written SVC and MLP against scikit-learn.

Timings are measured in one run, the cases of a table alternating round by round where they are
compared (every sweep's timed tables); ``fem_accuracy``, ``signal_accuracy``, the ``SVC`` rows of
``ml_speed`` and the MLP rows marked so hold BLAS to one thread, whose default threads wait for
each other on a shared machine. The simulator's sweeps empty its cache of probe reductions
before every timed simulation, so that each pays its own. On a shared machine read the ratios,
not the seconds, and run twice to see how much they move.
"""

from __future__ import annotations

import importlib
import time

from .._progress import progress
from .._validate import check_bool, check_choice, output_dir
from ..report import FigureSet, Report

__all__ = ["BENCHMARKS", "run_benchmarks", "write_sweep"]

#: Module name and title of every sweep, in report order.
BENCHMARKS = {
    "fem_accuracy": "Finite elements: error against the exact solution, and solve time",
    "signal_accuracy": "Signal processing: estimator error against time",
    "simulate_cost": "Simulator: cost of each effect",
    "contact_cost": "Simulator: the Hertz contact's cost against the linearised one",
    "ml_speed": "Machine learning: hand-written estimators against scikit-learn",
}


def write_sweep(report: Report, figures: FigureSet, name: str, module, rows) -> str:
    """Write one sweep's tables and (if it has one) its figure, both from the same rows.

    Parameters
    ----------
    report : Report
        Receives a heading, the text tables and the figure.
    figures : FigureSet
        Saves the figure as ``name.png``.
    name : str
        Key of the sweep in :data:`BENCHMARKS`.
    module : module
        The sweep's module, with ``to_text(rows)`` and optionally ``plot(rows)``.
    rows : dict
        What the module's ``run`` returned.

    Returns
    -------
    str
        The tables as text.
    """
    if not isinstance(report, Report):
        raise TypeError(f"report must be a Report, got {type(report).__name__}")
    if not isinstance(figures, FigureSet):
        raise TypeError(f"figures must be a FigureSet, got {type(figures).__name__}")
    check_choice("name", name, BENCHMARKS)
    if not callable(getattr(module, "to_text", None)):
        raise TypeError(f"module must be a sweep's module, with to_text(rows); got "
                        f"{type(module).__name__}")
    text = module.to_text(rows)
    report.heading(BENCHMARKS[name])
    report.preformatted(text.strip())
    if hasattr(module, "plot"):
        report.figure(figures.save(module.plot(rows), name), BENCHMARKS[name])
    return text


def run_benchmarks(
    out_dir="ebantenna-bench", *, quick: bool = False, only=None, show_progress=None
) -> dict:
    """Run the sweeps and write ``bench.md``, ``bench.html`` and a PNG per plot into ``out_dir``.

    Parameters
    ----------
    out_dir : path
        Output directory (created).
    quick : bool
        Each sweep's quick version: smaller meshes, fewer trials, smaller problems.
    only : iterable of str, optional
        Names from :data:`BENCHMARKS` to run; all by default.
    show_progress : bool, optional
        Progress bar (default: on a terminal).

    Returns
    -------
    dict
        ``{name: {"seconds": ..., "table": text, "rows": ...}}`` and the report paths under
        ``"report"``.
    """
    import matplotlib

    matplotlib.use("Agg")

    quick = check_bool("quick", quick)
    if show_progress is not None:
        check_bool("show_progress", show_progress)
    if isinstance(only, str | bytes):  # a name would be read letter by letter
        raise TypeError(f"only must be a list of names such as [{only!r}], got a string")
    if only is not None and not hasattr(only, "__iter__"):
        raise TypeError(f"only must be an iterable of names, got {type(only).__name__}")
    names = list(BENCHMARKS) if only is None else list(only)
    if not all(isinstance(name, str) for name in names):
        raise TypeError("only must hold names (str) of the benchmarks")
    unknown = sorted(set(names) - set(BENCHMARKS))
    if unknown:
        raise ValueError(f"only must name benchmarks among {', '.join(BENCHMARKS)}; got {unknown}")
    out_dir = output_dir("out_dir", out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    figures = FigureSet(out_dir)
    report = Report("ebantenna: accuracy against time" + (" (quick)" if quick else ""))
    report.paragraph(
        "Every table is measured in one run; compare ratios, not seconds, and run twice to see "
        "how much they move."
    )
    results: dict = {}
    for name in progress(names, desc="bench", enabled=show_progress):
        module = importlib.import_module(f"{__name__}.{name}")
        start = time.perf_counter()
        rows = module.run(quick)
        seconds = time.perf_counter() - start
        text = write_sweep(report, figures, name, module, rows)
        results[name] = {"seconds": seconds, "table": text, "rows": rows}
        report.paragraph(f"This sweep took {seconds:.1f} s.")
    md, page = report.write(out_dir, "bench")
    results["report"] = {"markdown": str(md), "html": str(page)}
    return results
