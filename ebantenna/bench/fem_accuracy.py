"""What each digit of a frequency costs: FEM error against the exact solution and solve time.

Run:  python benchmarks/fem_accuracy.py [--quick]

:func:`run` measures, for meshes of N = 2 ... 2048 elements, the largest relative error of the
first three frequencies against :func:`ebantenna.fem.exact_frequencies` and the time of each solver
(dense inverted Cholesky, sparse shift-invert Lanczos, and the textbook
``scipy.linalg.eigh(K, M)``), in one run; then the throughput and the error of a
contact sweep: the banded and the secular-equation sweeps (with and without the static correction)
against one position at a time. It
returns the rows; :func:`to_text` and :func:`plot` draw the table and the figure from those rows.
"""

from __future__ import annotations

import argparse
import math

import numpy as np

from ebantenna import Probe
from ebantenna._validate import check_bool
from ebantenna.bench._arguments import check_argv, check_tables
from ebantenna.bench._timing import best_time
from ebantenna.fem import Supports, exact_frequencies, modal_analysis, natural_frequencies
from ebantenna.fem.secular import secular_sweep
from ebantenna.report import text_table

__all__ = ["SOLVER_MARKERS", "accuracy_rows", "sweep_rows", "run", "to_text", "plot", "main"]

#: The solvers compared, with their plot markers.
SOLVER_MARKERS = {"dense": "o", "sparse": "s", "naive": "x"}


def accuracy_rows(quick: bool) -> list[dict]:
    """Error and best solve time of each solver against the mesh size.

    Parameters
    ----------
    quick : bool
        Meshes up to 256 elements instead of 2048.

    Returns
    -------
    list of dict
        One row per mesh: ``N``, and for each solver ``<solver>_error`` (largest relative error of
        f1..f3, NaN where the solver was not run) and ``<solver>_seconds`` (best wall time, s).
    """
    quick = check_bool("quick", quick)
    probe = Probe()
    contact = 0.8 * probe.length
    exact = exact_frequencies(probe, contact, n_modes=3)
    rows = []
    sizes = [2, 4, 8, 16, 32, 64, 128, 256] + ([] if quick else [512, 1024, 2048])
    for n in sizes:
        row = {"N": n}
        for solver in SOLVER_MARKERS:
            skip = (solver in ("dense", "naive") and n > (256 if quick else 1024)) or (
                solver == "sparse" and n < 4
            )
            if skip:
                row[f"{solver}_error"] = row[f"{solver}_seconds"] = float("nan")
                continue
            t, res = best_time(
                lambda s=solver, n=n: modal_analysis(
                    probe, Supports(contact), n_elements=n, n_modes=3, solver=s
                ),
                3 if n <= 256 else 1,
            )
            row[f"{solver}_error"] = float(np.max(np.abs(res.frequencies / exact - 1)))
            row[f"{solver}_seconds"] = t
        rows.append(row)
    return rows


def sweep_rows(quick: bool) -> list[dict]:
    """Throughput and accuracy of a contact sweep: each method, in one run.

    Every position is solved by the banded sweep and the secular sweep at 64 elements, and by
    the secular sweep without its static correction at 64 and 256 elements (it then models the
    contact as a pin inside an element, which needs finer elements for the same accuracy); a
    fiftieth of them one at a time. ``max_error`` is the largest relative error of f1..f3
    against :func:`ebantenna.fem.exact_frequencies` over 20 of the positions.

    Returns
    -------
    list of dict
        Rows with ``method``, ``seconds`` (for the whole sweep, s), ``positions_per_second`` and
        ``max_error``.
    """
    quick = check_bool("quick", quick)
    probe = Probe()
    n = 2000 if quick else 10000
    contacts = np.linspace(0.01, 0.39, n)
    sample = np.linspace(0, n - 1, 20).astype(int)
    exact = np.array([exact_frequencies(probe, float(contacts[i]), n_modes=3) for i in sample])

    def bare(n_elements):  # the secular sweep without the static correction
        lam = secular_sweep(
            probe, contacts, hinge_stiffness=math.inf, contact_stiffness=math.inf,
            n_elements=n_elements, n_modes=3, static=False,
        )  # fmt: skip
        return np.sqrt(lam) / (2 * math.pi)

    rows, swept = [], {}
    for label, sweep in (
        ("batched natural_frequencies, banded, 64 el.",
         lambda: natural_frequencies(probe, contacts, method="banded", n_elements=64)),
        ("secular equation, static correction, 64 el.",
         lambda: natural_frequencies(probe, contacts, method="secular", n_elements=64)),
        ("secular equation, no correction, 64 el.", lambda: bare(64)),
        ("secular equation, no correction, 256 el.", lambda: bare(256)),
    ):  # fmt: skip
        t, f = best_time(sweep, 2)
        swept[label] = f
        rows.append(
            {
                "method": f"{label}, {n} positions",
                "seconds": t,
                "positions_per_second": n / t,
                "max_error": float(np.abs(f[sample] / exact - 1).max()),
            }
        )
    k = n // 50
    t_loop, g = best_time(
        lambda: np.array(
            [modal_analysis(probe, Supports(c), n_elements=64).frequencies for c in contacts[:k]]
        ),
        1,
    )
    banded = swept["batched natural_frequencies, banded, 64 el."][:k]
    if not np.allclose(banded, g, rtol=1e-8):
        raise RuntimeError("the batched sweep and the single solves disagree beyond 1e-8")
    exact_k = np.array([exact_frequencies(probe, float(c), n_modes=3) for c in contacts[:k:10]])
    rows.append(
        {
            "method": f"modal_analysis one at a time, 64 el. (x{n // k} of {k})",
            "seconds": t_loop * n / k,
            "positions_per_second": k / t_loop,
            "max_error": float(np.abs(g[::10] / exact_k - 1).max()),
        }
    )
    return rows


def run(quick: bool = False) -> dict:
    """Both sweeps: ``{"accuracy": accuracy_rows(quick), "sweep": sweep_rows(quick)}``."""
    check_bool("quick", quick)
    return {"accuracy": accuracy_rows(quick), "sweep": sweep_rows(quick)}


def to_text(tables: dict) -> str:
    """The tables of :func:`run` as text."""
    check_tables(tables, "run", accuracy=list, sweep=list)
    columns = [("N", "N", "6d")]
    for s in SOLVER_MARKERS:
        columns += [(f"{s}_error", f"{s} err", "10.2e"), (f"{s}_seconds", "time", "9.5f")]
    sweep = tables["sweep"]
    lines = [
        "Contact at 0.8 L, clamped hinge: max relative error of f1..f3 | best time (s)",
        text_table(columns, tables["accuracy"]),
        "",
        "Contact sweep, 3 modes: time, throughput and error against the exact solution",
        text_table(
            [
                ("method", "method", "<60"),
                ("seconds", "s", "8.3f"),
                ("positions_per_second", "positions/s", "11.0f"),
                ("max_error", "max error", "10.1e"),
            ],
            sweep,
        ),
        "against one position at a time (timed once on a fiftieth of the positions, the sweeps "
        "best of two): " + ", ".join(
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
    args = parser.parse_args(check_argv(argv))
    print(to_text(run(args.quick)))


if __name__ == "__main__":
    main()
