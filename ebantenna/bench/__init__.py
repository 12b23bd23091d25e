"""Accuracy against time, for every subpackage: what each extra digit or percent costs.

Each module here is one sweep with a ``main(argv)`` that prints its tables; the scripts in the
repository's ``benchmarks/`` folder run them one at a time, and :func:`run_benchmarks` (the
``ebantenna bench`` command) runs them all and gathers their tables and plots into one report.

- :mod:`~ebantenna.bench.fem_accuracy`: FEM error against the exact frequencies and solve time,
  N = 2 ... 2048 elements, three solvers; the batched contact sweep.
- :mod:`~ebantenna.bench.signal_accuracy`: frequency estimators (window, zero padding,
  interpolation), STFT against wavelets, decay-fit methods, distance estimators.
- :mod:`~ebantenna.bench.simulate_cost`: seconds per 1000 signals for each simulated effect.
- :mod:`~ebantenna.bench.ml_speed`: the hand-written SVC and MLP against scikit-learn.

Timings are measured side by side in one run; on a shared machine read the ratios, not the seconds.
"""

from __future__ import annotations

import contextlib
import importlib
import io
import time
from pathlib import Path

import numpy as np

from .._progress import progress

__all__ = ["BENCHMARKS", "run_benchmarks"]

#: Module name and title of every sweep, in report order.
BENCHMARKS = {
    "fem_accuracy": "Finite elements: error against the exact solution, and solve time",
    "signal_accuracy": "Signal processing: estimator error against time",
    "simulate_cost": "Simulator: cost of each effect",
    "ml_speed": "Machine learning: hand-written estimators against scikit-learn",
}


def _fem_plot(quick: bool):
    import matplotlib.pyplot as plt

    from .fem_accuracy import accuracy_table

    rows = accuracy_table(quick)
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for solver, marker in (("dense", "o"), ("sparse", "s"), ("naive", "x")):
        err = np.array([r[solver][0] for r in rows])
        sec = np.array([r[solver][1] for r in rows])
        ok = np.isfinite(err) & (err > 0)
        ax.loglog(sec[ok], err[ok], marker + "-", label=solver)
        for r, e, s in zip(rows, err, sec, strict=True):
            if np.isfinite(e) and e > 0 and solver == "sparse":
                ax.annotate(
                    str(r["N"]), (s, e), fontsize=7, xytext=(3, 3), textcoords="offset points"
                )
    ax.set_xlabel("solve time (s)")
    ax.set_ylabel("max relative error of f1..f3")
    ax.set_title("What a digit costs: FEM at contact 0.8 L (labels: elements)")
    ax.legend()
    return fig


def _signal_plot(quick: bool):
    import matplotlib.pyplot as plt

    from .signal_accuracy import frequency_table

    with contextlib.redirect_stdout(io.StringIO()):
        rows = frequency_table(20 if quick else 200, np.random.default_rng(0))
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for method, window, pad, rms, _worst, seconds in rows:
        ax.loglog(seconds * 1e6, rms, "o")
        ax.annotate(
            f"{method}/{window}/x{pad}",
            (seconds * 1e6, rms),
            fontsize=7,
            xytext=(3, 3),
            textcoords="offset points",
        )
    ax.set_xlabel("time per estimate (us)")
    ax.set_ylabel("RMS frequency error (Hz)")
    ax.set_title("Dominant frequency: accuracy against time")
    return fig


PLOTS = {"fem_accuracy": _fem_plot, "signal_accuracy": _signal_plot}


def run_benchmarks(
    out_dir="ebantenna-bench", *, quick: bool = False, only=None, show_progress=None
) -> dict:
    """Run the sweeps and write ``bench.md``, ``bench.html`` and a PNG per plot into ``out_dir``.

    Parameters
    ----------
    out_dir : path
        Output directory (created).
    quick : bool
        Each sweep's ``--quick`` version: smaller meshes, fewer trials, smaller problems.
    only : iterable of str, optional
        Names from :data:`BENCHMARKS` to run; all by default.
    show_progress : bool, optional
        Progress bar (default: on a terminal).

    Returns
    -------
    dict
        ``{name: {"seconds": ..., "table": text}}`` and the report paths under ``"report"``.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..study.report import Report

    names = list(BENCHMARKS) if only is None else list(only)
    unknown = sorted(set(names) - set(BENCHMARKS))
    if unknown:
        raise ValueError(f"only must name benchmarks among {', '.join(BENCHMARKS)}; got {unknown}")
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    report = Report("ebantenna: accuracy against time" + (" (quick)" if quick else ""))
    report.paragraph(
        "Every table is measured side by side in one run; compare ratios, not seconds."
    )
    results: dict = {}
    for name in progress(names, desc="bench", enabled=show_progress):
        module = importlib.import_module(f"{__name__}.{name}")
        buffer = io.StringIO()
        start = time.perf_counter()
        with contextlib.redirect_stdout(buffer):
            module.main(["--quick"] if quick else [])
        seconds = time.perf_counter() - start
        results[name] = {"seconds": seconds, "table": buffer.getvalue()}
        report.heading(BENCHMARKS[name])
        report.preformatted(buffer.getvalue().strip())
        if name in PLOTS:
            fig = PLOTS[name](quick)
            fig.savefig(out_dir / f"{name}.png", dpi=120, bbox_inches="tight")
            plt.close(fig)
            report.figure(f"{name}.png", BENCHMARKS[name])
        report.paragraph(f"This sweep took {seconds:.1f} s.")
    md, page = report.write(out_dir, "bench")
    results["report"] = {"markdown": str(md), "html": str(page)}
    return results
