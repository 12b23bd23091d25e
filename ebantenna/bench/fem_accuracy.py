"""What each digit of a frequency costs: FEM error against the exact solution and solve time.

Run:  python benchmarks/fem_accuracy.py [--quick]

Prints, for meshes of N = 2 ... 2048 elements, the largest relative error of the first three
frequencies against :func:`ebantenna.fem.exact_frequencies` and the time of each solver (dense
inverted Cholesky, sparse shift-invert Lanczos, and the textbook ``scipy.linalg.eigh(K, M)``),
measured side by side in one run; then the throughput of a 1000-position contact sweep at 64
elements, batched against one position at a time.
"""

from __future__ import annotations

import argparse

import numpy as np

from ebantenna import Probe
from ebantenna.bench._timing import best_time
from ebantenna.fem import Supports, exact_frequencies, modal_analysis, natural_frequencies


def accuracy_table(quick: bool) -> list[dict]:
    probe = Probe()
    contact = 0.8 * probe.length
    exact = exact_frequencies(probe, contact, n_modes=3)
    rows = []
    sizes = [2, 4, 8, 16, 32, 64, 128, 256] + ([] if quick else [512, 1024, 2048])
    for n in sizes:
        row = {"N": n}
        for solver in ("dense", "sparse", "naive"):
            if solver in ("dense", "naive") and n > (256 if quick else 1024):
                row[solver] = (float("nan"), float("nan"))
                continue
            if solver == "sparse" and n < 4:
                row[solver] = (float("nan"), float("nan"))
                continue
            t, res = best_time(
                lambda s=solver, n=n: modal_analysis(
                    probe, Supports(contact), n_elements=n, n_modes=3, solver=s
                ),
                3 if n <= 256 else 1,
            )
            row[solver] = (float(np.max(np.abs(res.frequencies / exact - 1))), t)
        rows.append(row)
    return rows


def sweep_table(quick: bool) -> list[tuple[str, float, float]]:
    probe = Probe()
    n = 200 if quick else 1000
    contacts = np.linspace(0.01, 0.39, n)
    t_batch, f = best_time(lambda: natural_frequencies(probe, contacts, n_elements=64), 2)
    k = n // 10
    t_loop, g = best_time(
        lambda: np.array(
            [modal_analysis(probe, Supports(c), n_elements=64).frequencies for c in contacts[:k]]
        ),
        1,
    )
    assert np.allclose(f[:k], g, rtol=1e-8)
    return [
        (f"batched natural_frequencies, {n} positions", t_batch, n / t_batch),
        (f"modal_analysis one at a time (x{n // k} of {k})", t_loop * n / k, k / t_loop),
    ]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller meshes and sweep")
    args = parser.parse_args(argv)
    print("Contact at 0.8 L, clamped hinge: max relative error of f1..f3 | best time (s)")
    print(
        f"{'N':>6} | {'dense err':>10} {'time':>9} | {'sparse err':>10} {'time':>9} |"
        f" {'naive err':>10} {'time':>9}"
    )
    for row in accuracy_table(args.quick):
        cells = " | ".join(
            f"{row[s][0]:10.2e} {row[s][1]:9.5f}" for s in ("dense", "sparse", "naive")
        )
        print(f"{row['N']:>6} | {cells}")
    print()
    print("Contact sweep at 64 elements, 3 modes")
    rows = sweep_table(args.quick)
    for name, t, rate in rows:
        print(f"  {name:<48} {t:8.3f} s  {rate:9.0f} positions/s")
    print(f"  speed-up of the batched sweep: {rows[1][1] / rows[0][1]:.1f}x")


if __name__ == "__main__":
    main()
