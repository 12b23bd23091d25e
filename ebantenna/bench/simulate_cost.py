"""What each simulated effect costs: seconds per 1000 one-second signals, side by side.

Every row simulates the same 1000 signals (contacts drawn from the data set's 0.5 mm grid, the five
materials, 1 s at 1 kHz) with the ``ideal`` scene plus one effect, then with the whole ``paper``
scene; the ratio column compares each row with the ``ideal`` scene measured in the same run. Rows
are timed in CPU seconds of this process (``time.process_time``), which a busy machine disturbs
less than wall time. The last lines build the whole paper data set (9875 signals) in a temporary
directory with one and with two worker processes and report wall and CPU time and the peak memory
(target: under 10 s and 1 GB on 2 cores).

Run: ``python benchmarks/simulate_cost.py [--signals N] [--repeat R] [--skip-dataset] [--quick]``
"""

from __future__ import annotations

import argparse
import os
import resource
import tempfile
import time

import numpy as np

from ebantenna.probe import Probe, material_names
from ebantenna.simulate import build_dataset, builtin_scene, simulate_batch
from ebantenna.simulate.effects import GY521_MASS, effect_names


def scenarios():
    ideal = builtin_scene("ideal")
    yield "ideal (modal response only)", ideal
    for name in effect_names():
        if name == "contact_damping":
            yield (
                name + " (+ contact_compliance)",
                ideal.with_(effects=("contact_compliance", "contact_damping")),
            )
        elif name == "tip_mass":
            yield name, ideal.with_(probe=Probe(tip_mass=GY521_MASS), effects=("tip_mass",))
        else:
            yield name, ideal.with_(effects=(name,))
    yield "paper (every effect)", builtin_scene("paper")


def time_scene(scene, contacts, materials, seeds, repeat):
    best = np.inf
    for _ in range(repeat):
        start = time.process_time()
        simulate_batch(
            scene, contact=contacts, material=materials, seeds=seeds, show_progress=False
        )
        best = min(best, time.process_time() - start)
    return best


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--signals", type=int, default=1000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--skip-dataset", action="store_true")
    parser.add_argument(
        "--quick", action="store_true", help="200 signals, one timing, no data set build"
    )
    args = parser.parse_args(argv)
    if args.quick:
        args.signals, args.repeat, args.skip_dataset = 200, 1, True

    rng = np.random.default_rng(0)
    n = args.signals
    contacts = np.round(rng.uniform(0.005, 0.395, n) / 5e-4) * 5e-4
    materials = rng.choice(material_names(), n)
    seeds = rng.integers(0, 2**62, n)
    rows = []
    for label, scene in scenarios():
        seconds = time_scene(scene, contacts, materials, seeds, args.repeat)
        rows.append((label, seconds * 1000 / n))
    base = rows[0][1]
    print(f"{n} one-second signals at 1 kHz, best of {args.repeat}, CPU seconds")
    print(f"{'scene':42s} {'s / 1000 signals':>17s} {'x ideal':>8s}")
    for label, per_1000 in rows:
        print(f"{label:42s} {per_1000:17.3f} {per_1000 / base:8.2f}")

    if not args.skip_dataset:
        print()
        for jobs in (1, 2):
            with tempfile.TemporaryDirectory() as tmp:
                wall, cpu = time.perf_counter(), time.process_time()
                data = build_dataset(tmp, seed=0, n_jobs=jobs, show_progress=False)
                wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
            print(
                f"whole paper data set, {jobs} process(es): {data.n_signals} signals, "
                f"{wall:.2f} s wall, {cpu:.2f} s CPU in the main process (incl. saving)"
            )
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # kB -> MB on Linux
        print(f"peak resident memory of the main process: {peak:.0f} MB")
        print(f"load average while measuring: {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")


if __name__ == "__main__":
    main()
