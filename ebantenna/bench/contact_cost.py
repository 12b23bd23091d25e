"""What the strike's Hertz contact costs against the contact linearised at the preload.

The same signals (a seeded sample of the paper data set's rows: contacts, materials, speeds, tilts)
are simulated with the ``paper`` scene, whose strike pushes through the spring linearised at the
preload, and with the same scene plus ``hertz_contact`` (the Hertz law in series with the tube
wall, as chords within 0.01 N, :class:`~ebantenna.simulate.effects.HertzContact`). Each is timed in
CPU seconds of this process (``repeat`` rounds, the two laws alternating); the table gives
seconds per 1000 signals (the best round), the ratio of the best rounds and the median of the
ratios within a round, the median re-strikes and what each law adds to the linearised one's time
for the whole paper data set (9875 signals) on two cores, perfectly parallel, against the budget
of 60 s for the whole build. The process caches the probe's reduction at each contact for later
simulations; the cache is emptied before every timed simulation
(``forget_probe_reductions`` in ``ebantenna.bench._timing``), so that each law, in each round, pays
the reductions of its own signals, whichever runs first. (The sample's signals touch nearly as
many positions as there are signals, 171 for the default 200, so each pays nearly one
reduction, which the data set's 25 repetitions share: the per-signal cost here is an upper one;
the difference between the laws, the strikes themselves, is not.)

:func:`run` returns the rows, :func:`to_text` prints them.

Run: ``python -m ebantenna.bench.contact_cost [--signals N] [--repeat R] [--quick]``
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from ebantenna._validate import check_bool, check_int
from ebantenna.bench._arguments import check_argv, check_count, check_tables
from ebantenna.bench._timing import forget_probe_reductions, timed_rounds
from ebantenna.paper.data import paper_dataset_plan
from ebantenna.report import text_table
from ebantenna.simulate import builtin_scene, simulate_batch

__all__ = ["DATASET_BUDGET", "DATASET_SIGNALS", "CORES", "scenes", "run", "to_text", "main"]

#: The main data set's build must stay under this many seconds (wall) ...
DATASET_BUDGET = 60.0
#: ... on this many cores ...
CORES = 2
#: ... for this many signals (the paper data set).
DATASET_SIGNALS = 9875


def scenes():
    """The two contact laws: ``(label, scene)``, the linearised first."""
    paper = builtin_scene("paper")
    yield "linearised at the preload (paper)", paper
    yield "Hertz law (paper + hertz_contact)", paper.with_(
        name="paper-hertz_contact", effects=(*paper.effects, "hertz_contact")
    )


def _batch(scene, rows):
    """The simulation of ``rows`` with ``scene``, as a call to time."""

    def batch():
        return simulate_batch(
            scene, contact=rows["contact_true"], material=rows["material"],
            sweep_speed=rows["sweep_speed"], tilt_ratio=rows["tilt_ratio"],
            seeds=rows["seed_row"], show_progress=False, x_modes=False,
        )  # fmt: skip

    return batch


def run(quick: bool = False, signals: int = 200, repeat: int = 2) -> dict:
    """The cost of the two contact laws on the same signals.

    Parameters
    ----------
    quick : bool
        40 signals, one timing (overrides the other arguments).
    signals : int
        Signals drawn from the paper data set's rows (>= 1).
    repeat : int
        Timings per law; the best is kept (>= 1).

    Returns
    -------
    dict
        ``signals``, ``repeat`` and ``rows``: per law ``law``, ``per_1000`` (CPU s per 1000
        signals, the best round), ``ratio`` (against the linearised law's best round),
        ``ratio_median`` (the median of the ratios within a round), ``restrikes`` (median per
        strike) and
        ``added_seconds`` (what the law adds to the linearised one's build of the paper data set
        on :data:`CORES` cores, s).
    """
    if check_bool("quick", quick):
        signals, repeat = 40, 1
    repeat = check_count("repeat", repeat)
    plan = paper_dataset_plan(seed=0)
    signals = check_int("signals", signals, minimum=1, maximum=plan["contact"].size)
    pick = np.sort(np.random.default_rng(0).choice(plan["contact"].size, signals, replace=False))
    rows = {key: np.asarray(plan[key])[pick] for key in
            ("contact_true", "material", "sweep_speed", "tilt_ratio", "seed_row")}  # fmt: skip
    laws = list(scenes())
    timed = timed_rounds([_batch(scene, rows) for _, scene in laws], repeat,
                         clock=time.process_time, before=forget_probe_reductions)
    out = []
    for (label, _), r in zip(laws, timed, strict=True):
        out.append({
            "law": label, "per_1000": 1000 * r["min"] / signals,
            "restrikes": float(np.median(np.asarray(r["result"][3].restrikes))),
            "ratio_median": float(np.median(np.divide(r["times"], timed[0]["times"]))),
        })  # fmt: skip
    for row in out:
        row["ratio"] = row["per_1000"] / out[0]["per_1000"]
        extra = (row["per_1000"] - out[0]["per_1000"]) / 1000  # CPU s per signal
        row["added_seconds"] = extra * DATASET_SIGNALS / CORES
    return {"signals": signals, "repeat": repeat, "rows": out}


def to_text(tables: dict) -> str:
    """The table of :func:`run` as text, with the data set's budget."""
    check_tables(tables, "run", signals=int, repeat=int, rows=list)
    hertz = tables["rows"][-1]
    added = hertz["added_seconds"]
    if added > DATASET_BUDGET:
        verdict = "more than the whole build's budget of"
    else:  # the rest of the build would have to fit in what is left
        verdict = (f"leaving {DATASET_BUDGET - added:.0f} s for the rest of the build, of a "
                   "budget of")
    return "\n".join([
        f"{tables['signals']} signals of the paper data set, best of {tables['repeat']} "
        "alternating rounds (median x: the median of the rounds' ratios), CPU seconds, each "
        "simulation paying its own probe reductions",
        text_table(
            [
                ("law", "contact law", "<36"),
                ("per_1000", "s / 1000 signals", "17.2f"),
                ("ratio", "x linearised", "13.2f"),
                ("ratio_median", "median x", "9.2f"),
                ("restrikes", "median re-strikes", "18.0f"),
                ("added_seconds", f"added to the data set ({CORES} cores), s", "32.0f"),
            ],
            tables["rows"],
        ),
        f"the Hertz law alone adds {added:.0f} s: {verdict} {DATASET_BUDGET:.0f} s on "
        f"{CORES} cores",
    ])  # fmt: skip


def main(argv=None):
    """Command-line entry: print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--signals", type=int, default=200)
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--quick", action="store_true", help="40 signals, one timing")
    args = parser.parse_args(check_argv(argv))
    print(to_text(run(args.quick, args.signals, args.repeat)))


if __name__ == "__main__":
    main()
