"""The input contract of the benchmark sweeps: their ``run``, row builders, ``to_text``, ``plot``,
``main`` and the report writer.

A sweep runs for minutes, so each refuses a bad argument before its first measurement: a flag
that is not True or False (``quick="no"`` would mean the full sweep), a count of trials,
repetitions or epochs that is not an integer from 1 to 100000, a seed below 0, a random
generator that is not one, a string ``argv`` (read letter by letter), a string ``only`` (read
as one benchmark per letter), a table that is not what ``run`` returned (a ``KeyError`` deep in
the formatting before). Good inputs are checked on the cheap parts: ``compare`` on a clock that
ticks by hand, the tables formatted from rows written by hand, the data sets' shapes.
"""

from __future__ import annotations

import functools
import math
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, row_tests  # noqa: E402

from ebantenna import bench  # noqa: E402
from ebantenna.bench import (  # noqa: E402
    contact_cost,
    fem_accuracy,
    ml_speed,
    signal_accuracy,
    simulate_cost,
)
from ebantenna.report import FigureSet, Report  # noqa: E402

NAN = math.nan
RNG = np.random.default_rng(0)
X = np.abs(RNG.normal(size=(12, 3)))
Y = np.array([0, 1] * 6)
B = "ebantenna.bench."


def _score(model):
    return 1.0


def _ticks():
    """A clock whose readings are 0, 1, 3, 6, 10, 15, 21, 28, ... (each step one longer)."""
    steps = iter(np.cumsum(np.arange(100.0)))
    return lambda: float(next(steps))


def _compare():
    return ml_speed.compare("t", lambda: None, lambda: None, _score, 2, clock=_ticks())


def _contact_tables(added):
    return {"signals": 40, "repeat": 1, "rows": [
        {"law": "linearised", "per_1000": 1.0, "ratio": 1.0, "ratio_median": 1.0,
         "restrikes": 0.0, "added_seconds": 0.0},
        {"law": "Hertz", "per_1000": 2.0, "ratio": 2.0, "ratio_median": 2.0, "restrikes": 1.0,
         "added_seconds": added}]}


def _fem_tables():
    accuracy = [{"N": 2, "blas_threads": 1, **{f"{s}_{k}": 1.0
                                               for s in fem_accuracy.SOLVER_MARKERS
                                               for k in ("error", "seconds", "median")}}]
    sweep = [{"method": m, "seconds": s, "median_seconds": s, "positions_per_second": 1.0,
              "max_error": 1e-6, "blas_threads": 1}
             for m, s in (("banded", 0.5), ("secular", 0.25), ("one at a time", 10.0))]
    return {"accuracy": accuracy, "sweep": sweep, "repeat": 1, "cores": 2}


def _ml_tables():
    row = {"task": "t", "data": "d", "engine": "numpy", "ours_seconds": 1.0,
           "sklearn_seconds": 2.0, "ratio_min": 0.5, "ratio_median": 0.5, "ours_accuracy": 1.0,
           "sklearn_accuracy": 1.0}
    return {"rows": [row], "parts": [{"part": "p", "seconds": 1.0, "share": 0.5, "note": ""}],
            "engine": [{"part": "import", "seconds": 1.0, "note": ""}]}


class _Sweep:
    """A sweep module of one table, for the report writer."""

    @staticmethod
    def to_text(rows):
        return "\n".join(f"{k} = {v}" for k, v in rows.items())


def _write_sweep():
    with tempfile.TemporaryDirectory() as tmp:
        report = Report("r")
        text = bench.write_sweep(report, FigureSet(tmp), "fem_accuracy", _Sweep, {"a": 1})
        md, _ = report.write(tmp, "r")
        return text, open(md, encoding="utf-8").read()


def _engine_kept():
    before = os.environ.get("EBANTENNA_ENGINE")
    with ml_speed.on_engine("numpy"):
        inside = os.environ["EBANTENNA_ENGINE"]
    return inside, os.environ.get("EBANTENNA_ENGINE") == before


def _entered(engine):
    with ml_speed.on_engine(engine):
        pass


def _ideal():
    from ebantenna.simulate import builtin_scene

    return builtin_scene("ideal")


def _flags(surface, call, name="quick"):
    return [Row(surface, f"{name}-{label}", (lambda v=v: call(v)), (name,))
            for label, v in (("str", "no"), ("None", None), ("int", 1))]


@functools.cache
def all_rows():
    c, f, s, m = (B + "contact_cost.", B + "fem_accuracy.", B + "signal_accuracy.",
                  B + "ml_speed.")
    rows = []
    sc = B + "simulate_cost."
    for surface, module in ((c, contact_cost), (f, fem_accuracy), (s, signal_accuracy),
                            (m, ml_speed), (sc, simulate_cost)):
        rows += [Row(surface + "main", "argv-str", (lambda mod=module: mod.main("--quick")),
                     ("argv",)),
                 Row(surface + "main", "argv-ints", (lambda mod=module: mod.main([1, 2])),
                     ("argv",)),
                 Row(surface + "to_text", "tables-list", (lambda mod=module: mod.to_text([])),
                     ("tables",)),
                 Row(surface + "to_text", "tables-empty", (lambda mod=module: mod.to_text({})),
                     ("tables",)),
                 Row(surface + "run", "quick-str", (lambda mod=module: mod.run("no")),
                     ("quick",))]
    rows += [
        Row(c + "main", "signals-0", lambda: contact_cost.main(["--signals", "0"]),
            ("signals",)),
        Row(c + "run", "signals-str", lambda: contact_cost.run(False, "x"), ("signals",)),
        Row(c + "run", "signals-beyond-the-data-set",
            lambda: contact_cost.run(False, 10**6), ("signals",)),
        Row(c + "run", "repeat-0", lambda: contact_cost.run(False, 10, 0), ("repeat",)),
        Row(c + "run", "repeat-10**9", lambda: contact_cost.run(False, 10, 10**9), ("repeat",)),
        Row(c + "to_text", "rows-of-str",
            lambda: contact_cost.to_text({**_contact_tables(1.0), "rows": ["a"]}), ("rows",)),
        # the sentence is generated from the number: 10 s leaves 50 s of the 60 s budget for the
        # rest of the build (not "fits": the rest may not), 100 s alone exceeds it
        Row(c + "to_text", "sentence-from-the-number", lambda: (
            contact_cost.to_text(_contact_tables(10.0)).splitlines()[-1],
            contact_cost.to_text(_contact_tables(100.0)).splitlines()[-1]),
            same=lambda r: "adds 10 s: leaving 50 s for the rest of the build" in r[0]
            and "adds 100 s: more than the whole build's budget of 60 s" in r[1]),
        Row(sc + "run", "signals-0", lambda: simulate_cost.run(False, 0), ("signals",)),
        Row(sc + "run", "repeat-10**9", lambda: simulate_cost.run(False, 10, 10**9),
            ("repeat",)),
        Row(sc + "run", "skip_dataset-str", lambda: simulate_cost.run(False, 10, 1, "yes"),
            ("skip_dataset",)),
        Row(sc + "main", "signals-0", lambda: simulate_cost.main(["--signals", "0"]),
            ("signals",)),
        Row(sc + "to_text", "dataset-missing", lambda: simulate_cost.to_text(
            {"signals": 1, "repeat": 1, "rows": []}), ("dataset",)),
        Row(sc + "time_scene", "scene-str",
            lambda: simulate_cost.time_scene("ideal", [0.2], ["pvc"], [0], 1), ("scene",)),
        Row(sc + "time_scene", "repeat-0", lambda: simulate_cost.time_scene(
            _ideal(), [0.2], ["pvc"], [0], 0), ("repeat",)),
        Row(sc + "time_scene", "contacts-nan", lambda: simulate_cost.time_scene(
            _ideal(), [NAN], ["pvc"], [0], 1), ("contact",)),
        # CPU seconds of one simulation: positive, and under the row's 10 s limit
        Row(sc + "time_scene", "one-signal", lambda: simulate_cost.time_scene(
            _ideal(), [0.2], ["pvc"], [0], 1), same=lambda t: 0 < t < 10),
        *_flags(f + "accuracy_rows", fem_accuracy.accuracy_rows),
        *_flags(f + "sweep_rows", fem_accuracy.sweep_rows),
        Row(f + "plot", "tables-without-accuracy", lambda: fem_accuracy.plot({"sweep": []}),
            ("accuracy",)),
        Row(f + "plot", "accuracy-a-dict", lambda: fem_accuracy.plot({"accuracy": {}}),
            ("accuracy",)),
        Row(f + "plot", "one-point-per-solver",
            lambda: fem_accuracy.plot(_fem_tables()).axes[0].get_lines(),
            same=lambda lines: len(lines) == len(fem_accuracy.SOLVER_MARKERS)),
        # the speed-ups are ratios of the rows' seconds: 10 / 0.5 and 10 / 0.25; the word
        # follows the ratio (fem_accuracy._times_faster's doctest has the slower case)
        Row(f + "to_text", "speed-ups-from-the-rows",
            lambda: fem_accuracy.to_text(_fem_tables()).splitlines()[-1],
            same=lambda line: line.endswith("banded 20 times faster, secular 40 times faster")),
        Row(s + "run", "seed-negative", lambda: signal_accuracy.run(True, -1), ("seed",)),
        Row(s + "run", "seed-float", lambda: signal_accuracy.run(True, 0.5), ("seed",)),
        Row(s + "main", "seed-negative", lambda: signal_accuracy.main(["--seed", "-1"]),
            ("seed",)),
        Row(s + "frequency_rows", "n_trials-0",
            lambda: signal_accuracy.frequency_rows(0, RNG), ("n_trials",)),
        Row(s + "frequency_rows", "n_trials-10**9",
            lambda: signal_accuracy.frequency_rows(10**9, RNG), ("n_trials",)),
        Row(s + "frequency_rows", "rng-int", lambda: signal_accuracy.frequency_rows(2, 0),
            ("rng",)),
        Row(s + "decay_rows", "n_trials-float", lambda: signal_accuracy.decay_rows(2.5, RNG),
            ("n_trials",)),
        Row(s + "decay_rows", "rng-legacy",
            lambda: signal_accuracy.decay_rows(2, np.random.RandomState(0)), ("rng",)),
        Row(s + "distance_rows", "rng-None", lambda: signal_accuracy.distance_rows(None),
            ("rng",)),
        Row(s + "plot", "frequency-missing", lambda: signal_accuracy.plot({}), ("frequency",)),
        # one point per estimator row, where the row puts it (time in us, error in Hz)
        Row(s + "plot", "one-point-per-row", lambda: signal_accuracy.plot({"frequency": [
            {"method": "bin", "window": "hann", "pad": 1, "seconds": 2e-6, "rms_hz": 0.5}]})
            .axes[0].get_lines()[0].get_xydata().tolist(),
            same=lambda xy: np.allclose(xy, [[2.0, 0.5]], rtol=1e-12, atol=0)),
        Row(m + "run", "repeat-0", lambda: ml_speed.run(True, 0), ("repeat",)),
        Row(m + "main", "repeat-0", lambda: ml_speed.main(["--repeat", "0"]), ("repeat",)),
        Row(m + "to_text", "parts-missing",
            lambda: ml_speed.to_text({"rows": [], "engine": []}), ("parts",)),
        Row(m + "to_text", "the-rows", lambda: ml_speed.to_text(_ml_tables()),
            same=lambda text: "Where our time goes" in text and "numpy" in text),
        Row(m + "spectra_like", "n-0", lambda: ml_speed.spectra_like(0, 3, 2, 0), ("n",)),
        Row(m + "spectra_like", "k-beyond-n", lambda: ml_speed.spectra_like(3, 3, 5, 0), ("k",)),
        Row(m + "spectra_like", "seed-negative", lambda: ml_speed.spectra_like(3, 3, 2, -1),
            ("seed",)),
        Row(m + "spectra_like", "10**6-squared",
            lambda: ml_speed.spectra_like(10**6, 10**6, 2, 0), ("n and d",)),
        Row(m + "spectra_like", "non-negative-and-seeded",
            lambda: (ml_speed.spectra_like(50, 4, 3, 1), ml_speed.spectra_like(50, 4, 3, 1)),
            same=lambda r: r[0][0].shape == (50, 4) and np.all(r[0][0] >= 0)
            and np.array_equal(r[0][0], r[1][0]) and set(r[0][1].tolist()) <= {0, 1, 2}),
        Row(m + "small_set", "name-unknown", lambda: ml_speed.small_set("mnist"), ("name",)),
        Row(m + "small_set", "name-int", lambda: ml_speed.small_set(5), ("name",)),
        # iris: 150 samples, split three to one (112 and 38), standardised on all of them
        Row(m + "small_set", "iris", lambda: ml_speed.small_set("iris"),
            same=lambda r: r[0].shape == (112, 4) and r[2].shape == (38, 4)
            and np.allclose(np.vstack([r[0], r[2]]).mean(axis=0), 0, rtol=0, atol=1e-12)),
        Row(m + "on_engine", "engine-unknown", lambda: _entered("fast"), ("engine",)),
        Row(m + "on_engine", "engine-None", lambda: _entered(None), ("engine",)),
        Row(m + "on_engine", "set-then-restored", _engine_kept,
            same=lambda r: r == ("numpy", True)),
        Row(m + "compare", "ours-not-callable",
            lambda: ml_speed.compare("t", 5, lambda: None, _score, 2), ("ours",)),
        Row(m + "compare", "repeat-0",
            lambda: ml_speed.compare("t", lambda: None, lambda: None, _score, 0), ("repeat",)),
        Row(m + "compare", "task-int",
            lambda: ml_speed.compare(5, lambda: None, lambda: None, _score, 2), ("task",)),
        Row(m + "compare", "clock-float", lambda: ml_speed.compare(
            "t", lambda: None, lambda: None, _score, 2, clock=1.0), ("clock",)),
        # readings 0, 1 | 3, 6 | 10, 15 | 21, 28: ours 1 and 5 s, theirs 3 and 7 s, alternately;
        # the ratios within a repetition 1/3 and 5/7 (their median, the mean of the two, to
        # one rounding)
        Row(m + "compare", "by-a-ticking-clock", _compare,
            same=lambda r: (r["ours_seconds"], r["sklearn_seconds"], r["ratio"]) == (
                1.0, 3.0, 1 / 3) and r["ratio_min"] == 1 / 3
            and math.isclose(r["ratio_median"], (1 / 3 + 5 / 7) / 2, rel_tol=2e-16)),
        Row(m + "svc_rows", "y-one-class",
            lambda: ml_speed.svc_rows(X, np.zeros(12), _score, 1), ("y",)),
        Row(m + "svc_rows", "X-nan", lambda: ml_speed.svc_rows(X * NAN, Y, _score, 1), ("X",)),
        Row(m + "svc_rows", "score-None", lambda: ml_speed.svc_rows(X, Y, None, 1), ("score",)),
        Row(m + "mlp_rows", "epochs-0", lambda: ml_speed.mlp_rows(X, Y, _score, 1, 0),
            ("epochs",)),
        Row(m + "mlp_rows", "y-short", lambda: ml_speed.mlp_rows(X, Y[:3], _score, 1, 2),
            ("y",)),
        Row(m + "sklearn_adam", "epochs-10**9", lambda: ml_speed.sklearn_adam(X, Y, 10**9),
            ("epochs",)),
        Row(m + "sklearn_adam", "X-1-D", lambda: ml_speed.sklearn_adam(X[:, 0], Y, 2), ("X",)),
        Row(m + "sklearn_adam", "fits-the-row's-network",
            lambda: ml_speed.sklearn_adam(X, Y, 2)(),
            same=lambda model: model.hidden_layer_sizes == (53,) and model.n_iter_ == 2),
        Row(m + "where_time_goes", "svc_seconds-0",
            lambda: ml_speed.where_time_goes(X, Y, 0.0, 1.0, 2), ("svc_seconds",)),
        Row(m + "where_time_goes", "batch_size-0",
            lambda: ml_speed.where_time_goes(X, Y, 1.0, 1.0, 2, batch_size=0),
            ("batch_size",)),
        Row(m + "where_time_goes", "adam_fit-str",
            lambda: ml_speed.where_time_goes(X, Y, 1.0, 1.0, 2, adam_fit="x"), ("adam_fit",)),
        Row(m + "small_set_rows", "repeat-0", lambda: ml_speed.small_set_rows(0), ("repeat",)),
        Row(m + "small_set_rows", "batch_seconds-nan",
            lambda: ml_speed.small_set_rows(1, NAN), ("batch_seconds",)),
        Row(m + "small_set_parts", "rows-dict", lambda: ml_speed.small_set_parts({}),
            ("rows",)),
        Row(m + "small_set_parts", "rows-without-engine",
            lambda: ml_speed.small_set_parts([{"task": "t"}]), ("rows",)),
        Row(m + "small_set_parts", "repeat-0", lambda: ml_speed.small_set_parts([], 0),
            ("repeat",)),
        Row(m + "small_set_parts", "no-rows-no-parts", lambda: ml_speed.small_set_parts([]),
            same=lambda parts: parts == []),
        Row(B + "run_benchmarks", "only-a-string",
            lambda: bench.run_benchmarks(tempfile.gettempdir(), only="fem_accuracy"), ("only",)),
        Row(B + "run_benchmarks", "only-unknown",
            lambda: bench.run_benchmarks(tempfile.gettempdir(), only=["gpu"]), ("only",)),
        Row(B + "run_benchmarks", "quick-str",
            lambda: bench.run_benchmarks(tempfile.gettempdir(), quick="no"), ("quick",)),
        Row(B + "run_benchmarks", "show_progress-str",
            lambda: bench.run_benchmarks(tempfile.gettempdir(), show_progress="no"),
            ("show_progress",)),
        Row(B + "run_benchmarks", "out_dir-a-file",
            lambda: bench.run_benchmarks(__file__, only=[]), ("out_dir",)),
        Row(B + "write_sweep", "report-str", lambda: bench.write_sweep(
            "r", FigureSet(tempfile.gettempdir()), "fem_accuracy", _Sweep, {}), ("report",)),
        Row(B + "write_sweep", "name-unknown", lambda: bench.write_sweep(
            Report("r"), FigureSet(tempfile.gettempdir()), "x", _Sweep, {}), ("name",)),
        Row(B + "write_sweep", "module-without-to_text", lambda: bench.write_sweep(
            Report("r"), FigureSet(tempfile.gettempdir()), "fem_accuracy", object(), {}),
            ("module",)),
        # the module's text under the sweep's heading in the report
        Row(B + "write_sweep", "heading-and-text", _write_sweep,
            same=lambda r: r[0] == "a = 1" and bench.BENCHMARKS["fem_accuracy"] in r[1]
            and "a = 1" in r[1]),
    ]
    return rows


(IDS, test_the_rows_are_distinct, test_every_row_ends_in_a_clear_error_or_the_right_answer,
 contract_rows) = row_tests(all_rows, B)
