"""What each simulated effect costs: seconds per 1000 one-second signals, side by side.

Every row simulates the same 1000 signals (contacts drawn from the data set's 0.5 mm grid, the five
materials, 1 s at 1 kHz) with the ``ideal`` scene plus one effect, then with the whole ``paper``
scene; the ratio column compares each row with the ``ideal`` scene measured in the same run, the
rows alternating round by round (best of ``repeat`` rounds). Before every timed simulation the
process's cache of probe reductions is emptied
(``forget_probe_reductions`` in ``ebantenna.bench._timing``), so that every row with
``object_modes`` pays the reduction at each of its contacts, as in a fresh process, wherever it
stands in the table and in whichever round. Rows are timed in CPU seconds of this process
(``time.process_time``), which a busy machine disturbs less than wall time. The last lines build
the whole paper data set (9875 signals) in a temporary directory with one and with two worker
processes (the cache emptied before each) and print, for each, the wall time and the CPU time of
the main process (not its workers'); then the build's budget
(:data:`~ebantenna.bench.contact_cost.DATASET_BUDGET`, 60 s wall on
:data:`~ebantenna.bench.contact_cost.CORES` cores) with the wall time of the build on that many
processes against it, and the peak resident memory of this process (``ru_maxrss``: the
high-water mark of the whole run, the rows' simulations included, the workers' not).

:func:`run` returns the rows, :func:`to_text` prints them. ``march_engines`` times the strike
march alone, the NumPy block engine and the compiled one (the ``fast`` extra) side by side on the
same strikes of the paper scene and of its Hertz variant (``--march``).

Run: ``python benchmarks/simulate_cost.py [--signals N] [--repeat R] [--skip-dataset] [--quick]
[--march]``
"""

from __future__ import annotations

import argparse
import copy
import os
import resource
import tempfile
import time

import numpy as np

from ebantenna._validate import check_bool, more_jobs_allowed
from ebantenna.bench._arguments import check_argv, check_count, check_tables
from ebantenna.bench._timing import best_times, forget_probe_reductions, timed_rounds
from ebantenna.bench.contact_cost import CORES, DATASET_BUDGET
from ebantenna.paper.data import build_paper_dataset
from ebantenna.probe import Probe, material_names
from ebantenna.report import text_table
from ebantenna.simulate import builtin_scene, simulate_batch, unilateral
from ebantenna.simulate.effects import GY521_MASS, effect_names

__all__ = ["scenarios", "time_scene", "run", "to_text", "main"]


#: Effects that only make sense on top of others: measured together with them (a contact that
#: only pushes between undamped bodies chatters without end, so it gets the damping too).
PREREQUISITES = {
    "object_damping": ("object_modes",),
    "preload_scatter": ("object_modes",),
    "unilateral_contact": ("structural_damping", "object_modes", "object_damping"),
    "hertz_contact": ("structural_damping", "object_modes", "object_damping", "unilateral_contact"),
    "coulomb_friction": ("structural_damping", "object_modes"),
}


def scenarios():
    ideal = builtin_scene("ideal")
    yield "ideal (modal response only)", ideal
    for name in effect_names():
        if name in PREREQUISITES:
            base = PREREQUISITES[name]
            yield f"{name} (+ {', '.join(base)})", ideal.with_(effects=(*base, name))
        elif name == "tip_mass":
            yield name, ideal.with_(probe=Probe(tip_mass=GY521_MASS), effects=("tip_mass",))
        else:
            yield name, ideal.with_(effects=(name,))
    yield "paper (every effect)", builtin_scene("paper")


def time_scene(scene, contacts, materials, seeds, repeat):
    """Best CPU seconds of ``repeat`` simulations of the batch (``contacts``, ``materials`` and
    ``seeds`` as :func:`~ebantenna.simulate.simulate_batch` takes them), each with the cache of
    probe reductions emptied first (every one pays its own reductions, as in :func:`run`)."""
    from ebantenna.simulate import Scene

    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    repeat = check_count("repeat", repeat)
    return timed_rounds([_batch(scene, contacts, materials, seeds)], repeat,
                        clock=time.process_time, before=forget_probe_reductions)[0]["min"]


def _batch(scene, contacts, materials, seeds):
    """The simulation of the batch with ``scene``, as a call to time."""

    def batch():
        return simulate_batch(
            scene, contact=contacts, material=materials, seeds=seeds, show_progress=False
        )

    return batch


def run(
    quick: bool = False, signals: int = 1000, repeat: int = 3, skip_dataset: bool = False
) -> dict:
    """Cost of each effect, and (unless skipped) of building the whole paper data set.

    Parameters
    ----------
    quick : bool
        200 signals, one timing, no data-set build (overrides the other arguments).
    signals : int
        Signals simulated per scene.
    repeat : int
        Timings per scene; the best is kept.
    skip_dataset : bool
        Leave out the data-set build.

    Returns
    -------
    dict
        ``signals``, ``repeat``, ``rows`` (per scene ``scene``, ``per_1000`` CPU s per 1000
        signals and ``ratio`` against the ideal scene) and ``dataset`` (per worker count
        ``jobs``, ``signals``, ``wall_seconds``, ``cpu_seconds``; empty when skipped),
        ``peak_mb`` and ``load``.
    """
    check_bool("skip_dataset", skip_dataset)
    if check_bool("quick", quick):
        signals, repeat, skip_dataset = 200, 1, True
    signals = check_count("signals", signals)
    repeat = check_count("repeat", repeat)
    rng = np.random.default_rng(0)
    n = signals
    contacts = np.round(rng.uniform(0.005, 0.395, n) / 5e-4) * 5e-4
    materials = rng.choice(material_names(), n)
    seeds = rng.integers(0, 2**62, n)
    labelled = list(scenarios())
    timed = best_times([_batch(scene, contacts, materials, seeds) for _, scene in labelled],
                       repeat, clock=time.process_time, before=forget_probe_reductions)
    rows = [{"scene": label, "per_1000": seconds * 1000 / n}
            for (label, _), (seconds, _) in zip(labelled, timed, strict=True)]
    for row in rows:
        row["ratio"] = row["per_1000"] / rows[0]["per_1000"]
    dataset = []
    if not skip_dataset:
        for jobs in (1, 2):
            # two workers are measured on any machine, one core or more
            with tempfile.TemporaryDirectory() as tmp, more_jobs_allowed():
                forget_probe_reductions()  # the rows' contacts would be found made
                wall, cpu = time.perf_counter(), time.process_time()
                data = build_paper_dataset(tmp, seed=0, n_jobs=jobs, show_progress=False)
                wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
            dataset.append(
                {"jobs": jobs, "signals": data.n_signals, "wall_seconds": wall, "cpu_seconds": cpu}
            )
    return {
        "signals": n,
        "repeat": repeat,
        "rows": rows,
        "dataset": dataset,
        "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,  # kB -> MB (Linux)
        "load": os.getloadavg()[0],
    }


def to_text(tables: dict) -> str:
    """The tables of :func:`run` as text."""
    check_tables(tables, "run", signals=int, repeat=int, rows=list, dataset=list)
    lines = [
        f"{tables['signals']} one-second signals at 1 kHz, best of {tables['repeat']} alternating "
        "rounds, CPU seconds, each simulation paying its own probe reductions",
        text_table(
            [
                ("scene", "scene", "<42"),
                ("per_1000", "s / 1000 signals", "17.3f"),
                ("ratio", "x ideal", "8.2f"),
            ],
            tables["rows"],
        ),
    ]
    if tables["dataset"]:
        lines.append("")
        for r in tables["dataset"]:
            lines.append(
                f"whole paper data set, {r['jobs']} process(es): {r['signals']} signals, "
                f"{r['wall_seconds']:.2f} s wall, {r['cpu_seconds']:.2f} s CPU in the main "
                "process (incl. saving)"
            )
        lines += _budget_lines(tables["dataset"])
        lines.append(f"peak resident memory of this process over the whole run (ru_maxrss, the "
                     f"workers' not counted): {tables['peak_mb']:.0f} MB")
        lines.append(
            f"load average while measuring: {tables['load']:.2f} on {os.cpu_count()} cores"
        )
    return "\n".join(lines)


def _budget_lines(dataset: list[dict]) -> list[str]:
    """The build's budget, and the build on that many processes against it.

    >>> _budget_lines([{"jobs": 2, "wall_seconds": 75.0}])
    ["the build's budget: 60 s wall on 2 cores; the build on 2 processes took 75.0 s, over it"]
    """
    line = f"the build's budget: {DATASET_BUDGET:.0f} s wall on {CORES} cores"
    on_cores = [r for r in dataset if r["jobs"] == CORES]
    if on_cores:
        wall = on_cores[0]["wall_seconds"]
        line += (f"; the build on {CORES} processes took {wall:.1f} s, "
                 f"{'within' if wall <= DATASET_BUDGET else 'over'} it")
    return [line]


def strike_laws(scene, contacts, materials, seed: int = 0) -> list:
    """The strike laws the simulator builds for ``scene`` at ``contacts`` (m) on ``materials``
    (one signal each), each ``(law, x, key, n_steps)`` as its march receives it, copied."""

    got = []
    march = unilateral.MARCHES["blocks"]

    def spy(law, x, key, n_steps):
        got.append(copy.deepcopy((law, x, key, n_steps)))
        return march(law, x, key, n_steps)

    n = len(contacts)
    unilateral.MARCHES["blocks"] = spy
    try:
        simulate_batch(scene, contact=np.asarray(contacts, float),
                       material=np.asarray(materials, dtype=object),
                       sweep_speed=np.full(n, scene.sweep_speed),
                       tilt_ratio=np.full(n, scene.tilt_ratio), seeds=seed + np.arange(n),
                       show_progress=False, x_modes=False)  # fmt: skip
    finally:
        unilateral.MARCHES["blocks"] = march
    return got


def _copy(strike):
    """A copy of a strike to march (a Hertz law finds its chords by identity: renewed)."""
    from ebantenna.simulate.unilateral import HertzStrikeLaw

    law, x, key, n_steps = copy.deepcopy(strike)
    if isinstance(law, HertzStrikeLaw):
        law.index = {id(st): j for j, st in enumerate(law.segments)}
    return law, x, key, n_steps


def _march_all(strikes, engine: str) -> float:
    """March a copy of every strike with ``engine`` ('numpy' or 'compiled'); the CPU seconds
    of the marches (the copies not counted)."""
    march = unilateral.MARCHES["blocks"]
    seconds = 0.0
    for strike in strikes:
        law, x, key, n_steps = _copy(strike)
        start = time.process_time()
        march(law, x, key, n_steps, engine=engine)
        seconds += time.process_time() - start
    return seconds


def _compiled_status(strike) -> tuple[str, float]:
    """Why the compiled march cannot run here ('' when it can), and the seconds its first
    strike took with loading (compiling, or reading numba's cache) included."""
    start = time.perf_counter()
    try:
        unilateral.MARCHES["blocks"](*_copy(strike), engine="compiled")
    except RuntimeError as exc:  # asked for 'compiled' where it is not available: says why
        return str(exc), np.nan
    return "", time.perf_counter() - start


def march_engines(n_paper: int = 50, n_hertz: int = 20, repeat: int = 3, seed: int = 0) -> dict:
    """The strike march's CPU time per strike, NumPy block engine and compiled, side by side.

    ``n_paper`` strikes of the ``paper`` scene and ``n_hertz`` of its Hertz variant (one second
    each), at contacts drawn from the data set's 0.5 mm grid along the rod (2 mm to 0.397 m) and
    the five materials, seeded; each engine marches copies of the same laws, best of ``repeat``
    rounds in which the engines alternate, in CPU seconds of this process. The set-up of a
    strike (reduction, states) is not timed. The compiled engine is loaded (compiled or read
    from numba's cache) before the timing; without it its column is NaN and ``reason`` says
    why.
    """
    rng = np.random.default_rng(seed)
    paper = builtin_scene("paper")
    hertz = paper.with_(name="paper-hertz_contact", effects=(*paper.effects, "hertz_contact"))
    grid = np.round(np.arange(0.002, 0.3975, 0.0005), 4)
    rows = []
    for label, scene, n in (("paper (linearised contact)", paper, n_paper),
                            ("paper + hertz_contact", hertz, n_hertz)):  # fmt: skip
        contacts = rng.choice(grid, n)
        materials = rng.choice(material_names(), n)
        strikes = strike_laws(scene, contacts, materials, seed)
        row = {"strikes": label, "n": len(strikes)}
        if not rows:
            reason, load_seconds = _compiled_status(strikes[0])
        engines = ("numpy",) if reason else ("numpy", "compiled")
        seconds = dict.fromkeys(engines, np.inf)
        for _ in range(repeat):  # the engines alternate, so that the load reaches both alike
            for engine in engines:
                seconds[engine] = min(seconds[engine], _march_all(strikes, engine))
        for engine in ("numpy", "compiled"):
            row[engine] = 1e3 * seconds[engine] / len(strikes) if engine in seconds else np.nan
        row["ratio"] = row["numpy"] / row["compiled"]
        rows.append(row)
    return {"rows": rows, "repeat": repeat, "reason": reason,
            "load_seconds": load_seconds}  # fmt: skip


def march_text(tables: dict) -> str:
    """The table of ``march_engines`` as text."""
    lines = [
        f"the strike march alone, ms of CPU per one-second strike, best of {tables['repeat']}",
        text_table(
            [
                ("strikes", "strikes", "<28"),
                ("n", "n", "4d"),
                ("numpy", "NumPy blocks", "13.3f"),
                ("compiled", "compiled", "9.3f"),
                ("ratio", "ratio", "6.1f"),
            ],
            tables["rows"],
        ),
    ]
    if tables["reason"]:
        lines.append(tables["reason"])
    else:
        lines.append("compiled engine loaded and its first strike marched in "
                     f"{tables['load_seconds']:.1f} s (not timed)")
    return "\n".join(lines)


def main(argv=None):
    """Command-line entry: print the tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--signals", type=int, default=1000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--skip-dataset", action="store_true")
    parser.add_argument(
        "--quick", action="store_true", help="200 signals, one timing, no data set build"
    )
    parser.add_argument(
        "--march", action="store_true",
        help="time only the strike march, NumPy against compiled (50 + 20 strikes)",
    )  # fmt: skip
    args = parser.parse_args(check_argv(argv))
    if args.march:
        print(march_text(march_engines(repeat=args.repeat)))
        return
    print(to_text(run(args.quick, args.signals, args.repeat, args.skip_dataset)))


if __name__ == "__main__":
    main()
