"""CPU time of the study's learning steps on a quiet machine and beside another job.

The ``ml`` step of ``ebantenna reproduce`` (the paper's classifiers and distance networks, with
the ``ann setup`` step's fits queued behind them, as the study runs them) is timed in a fresh
process per run, quiet and then with two busy-loop processes on the machine's cores (the other
job), in turn, ``--repeats`` times, on one and on two worker processes. A run's CPU time is the
process's own and that of its worker processes (reaped before it is read). Oversubscribed BLAS
threads spin while they wait for a core, so they show as CPU time that grows under load; one
BLAS thread per fit (``ebantenna.study._common.BLAS_THREADS``) keeps the loaded run's CPU near
the quiet one's. Run from the repository::

    PYTHONPATH=$PWD python benchmarks/ml_cpu_under_load.py --cache /tmp/cache
    PYTHONPATH=$PWD python benchmarks/ml_cpu_under_load.py --cache /tmp/cache --quick --json
    PYTHONPATH=$PWD python benchmarks/ml_cpu_under_load.py --cache /tmp/c --blas-threads 2 \
        --workers 1

The data set comes from ``--cache`` (built there first if absent, as ``reproduce`` builds it).
Prints, per number of workers, the quiet and loaded CPU and wall time (medians) and the ratio of
the CPU times.
"""

from __future__ import annotations

import argparse
import json
import os
import pickle
import statistics
import subprocess
import sys
import tempfile
import time

ONE_RUN = """
import pickle, resource, sys, time
from joblib.externals.loky import get_reusable_executor
from ebantenna.study.reproduce import _ml_with
from ebantenna.study import _common, ann_setup
if sys.argv[3] != "default":
    _common.BLAS_THREADS = int(sys.argv[3])
with open(sys.argv[1], "rb") as f:
    ds, feats, seed, quick = pickle.load(f)
workers = int(sys.argv[2])
calls = ann_setup.fit_calls(ds, feats, seed, quick, paper_ann_given=True)

def cpu():
    me = resource.getrusage(resource.RUSAGE_SELF)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    return me.ru_utime + me.ru_stime + kids.ru_utime + kids.ru_stime

c0, w0 = cpu(), time.perf_counter()
_ml_with(ds, feats, seed, calls, {}, workers)
get_reusable_executor().shutdown(wait=True)  # the workers reaped: their CPU counted
print(cpu() - c0, time.perf_counter() - w0)
"""

BUSY = "while True: pass"


def _inputs(cache: str, quick: bool, seed: int, path: str) -> None:
    from ebantenna.paper.data import build_paper_dataset
    from ebantenna.paper.feature_table import signal_features

    ds = build_paper_dataset(cache, seed=seed, quick=quick, show_progress=False)
    feats = signal_features(ds.ax, ds.az, ds.fs, show_progress=False)
    with open(path, "wb") as f:
        pickle.dump((ds, feats, seed, quick), f)


def one_run(inputs: str, workers: int, load: int, blas: str = "default") -> tuple[float, float]:
    """CPU and wall time (s) of one ``ml`` step in a fresh process, beside ``load`` busy loops,
    with ``blas`` threads per fit (``"default"``: the study's own number)."""
    busy = [subprocess.Popen([sys.executable, "-c", BUSY]) for _ in range(load)]
    try:
        time.sleep(0.5 if load else 0.0)  # the other job running before the step starts
        out = subprocess.run([sys.executable, "-c", ONE_RUN, inputs, str(workers), blas],
                             capture_output=True, text=True, check=True, env=os.environ)
    finally:
        for p in busy:
            p.kill()
            p.wait()
    cpu, wall = map(float, out.stdout.split())
    return cpu, wall


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cache", required=True, help="the data set's folder (as reproduce's)")
    parser.add_argument("--quick", action="store_true", help="the quick design's data set")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--repeats", type=int, default=1, help="runs of each kind, in turn")
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--blas-threads", default="default",
                        help="BLAS threads per fit instead of the study's own number (a control: "
                             "2 shows what oversubscription costs); with --workers 1 only, as the "
                             "worker processes read the study's own")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args(argv)
    if args.blas_threads != "default" and args.workers != [1]:
        parser.error("--blas-threads needs --workers 1: the worker processes use the study's "
                     "own number")
    load = os.cpu_count() or 1
    result = {"load_processes": load, "blas_threads": args.blas_threads}
    with tempfile.TemporaryDirectory() as tmp:
        inputs = os.path.join(tmp, "inputs.pkl")
        _inputs(args.cache, args.quick, args.seed, inputs)
        for workers in args.workers:
            runs = {"quiet": [], "loaded": []}
            for _ in range(args.repeats):
                runs["quiet"].append(one_run(inputs, workers, 0, args.blas_threads))
                runs["loaded"].append(one_run(inputs, workers, load, args.blas_threads))
            row = {kind: {"cpu_s": statistics.median(c for c, _ in r),
                          "wall_s": statistics.median(w for _, w in r)}
                   for kind, r in runs.items()}
            row["cpu_ratio"] = row["loaded"]["cpu_s"] / row["quiet"]["cpu_s"]
            result[f"workers_{workers}"] = row
    if args.json:
        print(json.dumps(result))
        return 0
    print(f"ml step (with the ann setup's fits), other job: {load} busy loops, BLAS threads per "
          f"fit: {args.blas_threads}")
    for workers in args.workers:
        row = result[f"workers_{workers}"]
        q, lo = row["quiet"], row["loaded"]
        print(f"{workers} worker(s): CPU {q['cpu_s']:.1f} s quiet, {lo['cpu_s']:.1f} s loaded "
              f"(ratio {row['cpu_ratio']:.2f}); wall {q['wall_s']:.1f} s and {lo['wall_s']:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
