"""BLAS threads per step of the study: wall and CPU time of each step of the quick study, with
one BLAS thread and with two, side by side in one run (alternating, ``--repeats`` times each).

The study runs each step with :data:`ebantenna.study._common.BLAS_THREADS` threads; this script
sets it to 1 or 2 in a fresh process per run (the data set comes from the cache after the first
run, so the steps compared are the ones after it). CPU time is the study process's own (the
worker processes of the data set and the controls are not in it). Run from the repository:
``python benchmarks/study_blas_threads.py --repeats 2``.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile

ONE_RUN = """
import importlib, json, resource, sys
from ebantenna.study import _common
_common.BLAS_THREADS = int(sys.argv[1])
reproduce_module = importlib.import_module("ebantenna.study.reproduce")
cpu, timer_run = {}, reproduce_module._Timer.run

def run(self, name, fn, *args):
    before = resource.getrusage(resource.RUSAGE_SELF)
    out = timer_run(self, name, fn, *args)
    after = resource.getrusage(resource.RUSAGE_SELF)
    cpu[name] = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    return out

reproduce_module._Timer.run = run
result = reproduce_module.reproduce(sys.argv[2], quick=True, cache_dir=sys.argv[3],
                                    show_progress=False)
wall = result.summary["timings_s"]
print(json.dumps({step: [wall[step], cpu[step]] for step in wall}))
"""


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=2, help="runs of each setting (>= 1)")
    args = parser.parse_args(argv)
    if args.repeats < 1:
        parser.error(f"--repeats must be >= 1, got {args.repeats}")
    runs = {1: [], 2: []}
    with tempfile.TemporaryDirectory() as scratch:
        cache = os.path.join(scratch, "cache")
        for repeat in range(args.repeats + 1):  # the first pair warms the cache, not counted
            for threads in (1, 2):
                out = os.path.join(scratch, f"out-{threads}-{repeat}")
                child = subprocess.run([sys.executable, "-c", ONE_RUN, str(threads), out, cache],
                                       capture_output=True, text=True, check=True)
                if repeat:
                    runs[threads].append(json.loads(child.stdout.strip().splitlines()[-1]))
    print(f"{'step':<16}{'wall 1 / 2 threads (s)':>26}{'CPU 1 / 2 threads (s)':>26}"
          f"{'CPU ratio 2:1':>15}")
    for step in runs[1][0]:
        wall = [min(r[step][0] for r in runs[t]) for t in (1, 2)]
        cpu = [min(r[step][1] for r in runs[t]) for t in (1, 2)]
        ratio = f"{cpu[1] / cpu[0]:.2f}" if cpu[0] > 0.05 else "-"
        print(f"{step:<16}{wall[0]:>12.2f} / {wall[1]:<11.2f}{cpu[0]:>12.2f} / {cpu[1]:<11.2f}"
              f"{ratio:>15}")


if __name__ == "__main__":
    main()
