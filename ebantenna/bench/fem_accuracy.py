"""What each digit of a frequency costs: FEM error against the exact solution and solve time.

Run:  python benchmarks/fem_accuracy.py [--quick] [--repeat R]

:func:`run` measures, for meshes of N = 2 ... 2048 elements, the largest relative error of the
first three frequencies against :func:`ebantenna.fem.exact_frequencies` and the time of each solver
(dense inverted Cholesky, sparse shift-invert Lanczos, and the textbook
``scipy.linalg.eigh(K, M)``), in one run; then the throughput and the error of a
contact sweep: the banded and the secular-equation sweeps (with and without the static correction)
against one position at a time, every row's error over the same 20 positions along the probe.

Every arm is timed with BLAS held to one thread (``ebantenna._threads.limited_threads``; the
table says how many threads BLAS ran on): on a shared machine BLAS's default threads wait for
each other (a dense solve of 256 elements once measured 4.4 s with OpenBLAS's default threads on
a shared two-core machine, 0.047 s on one thread). The arms of a table alternate round by round,
``repeat`` rounds (the solvers of one mesh; the sweeps and the loop), and each row gives the
smallest and the median of its times. The sweeps spread their batches over the cores
themselves (one thread per core, each on one BLAS thread); one position at a time runs on one
core. :func:`run` returns the rows; :func:`to_text` and :func:`plot` draw the table and the
figure from those rows.
"""

from __future__ import annotations

import argparse
import math
import os

import numpy as np

from ebantenna import Probe
from ebantenna._threads import limited_threads
from ebantenna._validate import check_bool
from ebantenna.bench._arguments import check_argv, check_count, check_tables
from ebantenna.bench._timing import blas_threads, timed_rounds
from ebantenna.fem import Supports, exact_frequencies, modal_analysis, natural_frequencies
from ebantenna.fem.secular import secular_sweep
from ebantenna.report import text_table

__all__ = ["SOLVER_MARKERS", "accuracy_rows", "sweep_rows", "run", "to_text", "plot", "main"]

#: The solvers compared, with their plot markers.
SOLVER_MARKERS = {"dense": "o", "sparse": "s", "naive": "x"}

#: One position in this many is solved one at a time (with the 20 positions of the error).
_LOOP_STRIDE = 50


def _skipped(solver: str, n: int, quick: bool) -> bool:
    """Whether ``solver`` is left out at ``n`` elements (too slow, or too few elements)."""
    if solver in ("dense", "naive"):
        return n > (256 if quick else 1024)
    return solver == "sparse" and n < 4


def accuracy_rows(quick: bool, repeat: int = 3) -> list[dict]:
    """Error and solve time of each solver against the mesh size, on one BLAS thread.

    Parameters
    ----------
    quick : bool
        Meshes up to 256 elements instead of 2048.
    repeat : int
        Rounds in which the solvers of a mesh alternate (one beyond 256 elements).

    Returns
    -------
    list of dict
        One row per mesh: ``N``, ``blas_threads`` (the threads BLAS ran on), and for each solver
        ``<solver>_error`` (largest relative error of f1..f3, NaN where the solver was not run),
        ``<solver>_seconds`` and ``<solver>_median`` (smallest and median wall time, s).
    """
    quick = check_bool("quick", quick)
    repeat = check_count("repeat", repeat)
    probe = Probe()
    contact = 0.8 * probe.length
    exact = exact_frequencies(probe, contact, n_modes=3)
    rows = []
    sizes = [2, 4, 8, 16, 32, 64, 128, 256] + ([] if quick else [512, 1024, 2048])
    with limited_threads(1):
        threads = blas_threads()
        for n in sizes:
            row = {"N": n, "blas_threads": threads}
            solvers = [s for s in SOLVER_MARKERS if not _skipped(s, n, quick)]
            for solver in (s for s in SOLVER_MARKERS if s not in solvers):
                row[f"{solver}_error"] = row[f"{solver}_seconds"] = float("nan")
                row[f"{solver}_median"] = float("nan")
            timed = timed_rounds(
                [lambda s=s, n=n: modal_analysis(
                    probe, Supports(contact), n_elements=n, n_modes=3, solver=s)
                 for s in solvers],
                repeat if n <= 256 else 1,
            )  # fmt: skip
            for solver, r in zip(solvers, timed, strict=True):
                row[f"{solver}_error"] = float(np.max(np.abs(r["result"].frequencies / exact - 1)))
                row[f"{solver}_seconds"], row[f"{solver}_median"] = r["min"], r["median"]
            rows.append(row)
    return rows


def _sweeps(probe: Probe, contacts: np.ndarray) -> list[tuple[str, object]]:
    """The batched sweeps of :func:`sweep_rows`: ``(label, call)``."""

    def bare(n_elements):  # the secular sweep without the static correction
        lam = secular_sweep(
            probe, contacts, hinge_stiffness=math.inf, contact_stiffness=math.inf,
            n_elements=n_elements, n_modes=3, static=False,
        )  # fmt: skip
        return np.sqrt(lam) / (2 * math.pi)

    return [
        ("batched natural_frequencies, banded, 64 el.",
         lambda: natural_frequencies(probe, contacts, method="banded", n_elements=64)),
        ("secular equation, static correction, 64 el.",
         lambda: natural_frequencies(probe, contacts, method="secular", n_elements=64)),
        ("secular equation, no correction, 64 el.", lambda: bare(64)),
        ("secular equation, no correction, 256 el.", lambda: bare(256)),
    ]  # fmt: skip


def _one_at_a_time(probe: Probe, contacts: np.ndarray):
    """A call solving each of ``contacts`` with its own :func:`modal_analysis` (64 elements)."""
    return lambda: np.array(
        [modal_analysis(probe, Supports(c), n_elements=64).frequencies for c in contacts]
    )


def sweep_rows(quick: bool, repeat: int = 3) -> list[dict]:
    """Throughput and accuracy of a contact sweep: each method, in one run, on one BLAS thread.

    Every position is solved by the banded sweep and the secular sweep at 64 elements, and by
    the secular sweep without its static correction at 64 and 256 elements (it then models the
    contact as a pin inside an element, which needs finer elements for the same accuracy); one
    position in 50 and the 20 positions of the error one at a time, their time scaled to all
    positions. ``max_error`` is the largest relative error of f1..f3 against
    :func:`ebantenna.fem.exact_frequencies` over the same 20 positions, spread along the probe,
    in every row. The sweeps and the loop alternate, ``repeat`` rounds.

    Returns
    -------
    list of dict
        Rows with ``method``, ``seconds`` and ``median_seconds`` (smallest and median of the
        rounds, for the whole sweep, s), ``positions_per_second`` (from the smallest),
        ``max_error``, ``positions_timed`` and ``blas_threads``; the loop's row last.
    """
    quick = check_bool("quick", quick)
    repeat = check_count("repeat", repeat)
    probe = Probe()
    n = 2000 if quick else 10000
    contacts = np.linspace(0.01, 0.39, n)
    sample = np.linspace(0, n - 1, 20).astype(int)
    exact = np.array([exact_frequencies(probe, float(contacts[i]), n_modes=3) for i in sample])
    loop = np.union1d(np.arange(0, n, _LOOP_STRIDE), sample)  # sorted: holds the sample
    arms = [*_sweeps(probe, contacts),
            ("modal_analysis one at a time, 64 el.", _one_at_a_time(probe, contacts[loop]))]
    with limited_threads(1):
        threads = blas_threads()
        timed = timed_rounds([call for _, call in arms], repeat)
    banded, looped = timed[0]["result"], timed[-1]["result"]
    if not np.allclose(banded[loop], looped, rtol=1e-8):
        raise RuntimeError("the batched sweep and the single solves disagree beyond 1e-8")
    rows = [_sweep_row(f"{label}, {n} positions", r, n, n, r["result"][sample], exact, threads)
            for (label, _), r in zip(arms[:-1], timed[:-1], strict=True)]
    rows.append(_sweep_row(f"{arms[-1][0]}, {loop.size} of {n} positions, scaled", timed[-1],
                           n, loop.size, looped[np.searchsorted(loop, sample)], exact, threads))
    return rows


def _sweep_row(method: str, timing: dict, n: int, timed_positions: int, at_sample, exact,
               threads: int) -> dict:
    """A row of :func:`sweep_rows` from one arm's :func:`timed_rounds` entry: its times scaled
    from ``timed_positions`` to ``n`` positions, its error at the sample (``at_sample``, the
    frequencies there, against ``exact``)."""
    scale = n / timed_positions
    return {"method": method, "seconds": timing["min"] * scale,
            "median_seconds": timing["median"] * scale,
            "positions_per_second": timed_positions / timing["min"],
            "max_error": float(np.abs(at_sample / exact - 1).max()),
            "positions_timed": int(timed_positions), "blas_threads": int(threads)}


def run(quick: bool = False, repeat: int = 3) -> dict:
    """Both sweeps: ``{"accuracy": accuracy_rows(quick, repeat), "sweep": sweep_rows(quick,
    repeat), "repeat": repeat, "cores": os.cpu_count()}`` (the cores the sweeps' batches
    spread over)."""
    check_bool("quick", quick)
    repeat = check_count("repeat", repeat)
    return {"accuracy": accuracy_rows(quick, repeat), "sweep": sweep_rows(quick, repeat),
            "repeat": repeat, "cores": os.cpu_count() or 1}


def _threads_used(rows: list[dict]) -> str:
    """The BLAS threads the rows were timed on, as text (``"1"``, or ``"1, 2"`` if they differ).

    >>> _threads_used([{"blas_threads": 1}, {"blas_threads": 1}])
    '1'
    """
    return ", ".join(str(t) for t in sorted({r["blas_threads"] for r in rows}))


def to_text(tables: dict) -> str:
    """The tables of :func:`run` as text."""
    check_tables(tables, "run", accuracy=list, sweep=list, repeat=int, cores=int)
    repeat, sweep = tables["repeat"], tables["sweep"]
    columns = [("N", "N", "6d")]
    for s in SOLVER_MARKERS:
        columns += [(f"{s}_error", f"{s} err", "10.2e"), (f"{s}_seconds", "min s", "9.5f"),
                    (f"{s}_median", "median", "9.5f")]
    lines = [
        f"Wall time on {_threads_used(tables['accuracy'] + sweep)} BLAS thread(s); the arms of "
        f"each table alternate over {repeat} rounds (one beyond 256 elements): min and median",
        "Contact at 0.8 L, clamped hinge: max relative error of f1..f3 | solve time (s)",
        text_table(columns, tables["accuracy"]),
        "",
        "Contact sweep, 3 modes: time, throughput and error against the exact solution (every "
        "row at the same 20 positions)",
        text_table(
            [
                ("method", "method", "<72"),
                ("seconds", "min s", "8.3f"),
                ("median_seconds", "median s", "9.3f"),
                ("positions_per_second", "positions/s", "11.0f"),
                ("max_error", "max error", "10.1e"),
            ],
            sweep,
        ),
        f"the sweeps spread their batches over {tables['cores']} core(s), one position at a "
        "time runs on one; the loop's time is scaled from the positions it solved to all",
        f"against one position at a time (min of {repeat} alternating rounds): " + ", ".join(
            _times_faster(name, sweep[-1]["seconds"] / sweep[i]["seconds"])
            for i, name in ((0, "banded"), (1, "secular"))),
    ]
    return "\n".join(lines)


def _times_faster(name: str, ratio: float) -> str:
    """``"banded 12 times faster"`` or ``"... 2 times slower"``, from the ratio of the times.

    >>> _times_faster("banded", 12.3), _times_faster("secular", 0.5)
    ('banded 12 times faster', 'secular 2 times slower')
    """
    if ratio >= 1:
        return f"{name} {ratio:.0f} times faster"
    return f"{name} {1 / ratio:.0f} times slower"


def plot(tables: dict):
    """Error against solve time of each solver, from the rows of :func:`run`.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    rows = check_tables(tables, "run", accuracy=list)["accuracy"]
    fig = Figure(figsize=(7, 4.2))
    ax = fig.subplots()
    for solver, marker in SOLVER_MARKERS.items():
        err = np.array([r[f"{solver}_error"] for r in rows])
        sec = np.array([r[f"{solver}_seconds"] for r in rows])
        ok = np.isfinite(err) & (err > 0)
        ax.loglog(sec[ok], err[ok], marker + "-", label=solver)
        if solver == "sparse":
            for r, e, s in zip(rows, err, sec, strict=True):
                if np.isfinite(e) and e > 0:
                    ax.annotate(
                        str(r["N"]), (s, e), fontsize=7, xytext=(3, 3),
                        textcoords="offset points",
                    )
    ax.set_xlabel("solve time (s)")
    ax.set_ylabel("max relative error of f1..f3")
    ax.set_title("What a digit costs: FEM at contact 0.8 L (labels: elements)")
    ax.legend()
    return fig


def main(argv=None):
    """Command-line entry: print the tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller meshes and sweep")
    parser.add_argument("--repeat", type=int, default=3,
                        help="alternating rounds of every timing (min and median)")
    args = parser.parse_args(check_argv(argv))
    print(to_text(run(args.quick, args.repeat)))


if __name__ == "__main__":
    main()
