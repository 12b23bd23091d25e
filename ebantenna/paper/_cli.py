"""``ebantenna dataset``: the paper's data set, simulated in the ``paper`` scene."""

from __future__ import annotations


def register(subparsers) -> None:
    """Add the ``dataset`` command."""
    from ..cli import jobs_argument, seed_argument
    from ..study.recorded._cli import add_from_recordings

    data = subparsers.add_parser(
        "dataset",
        help="build the paper's data set (5 materials x contacts x 25 repetitions)",
        description="Simulate the paper's data set with the paper scene and save it as a "
        ".npz (not compressed) with metadata and a checksum; an identical existing file is reused.",
    )
    data.add_argument("--out", required=True, metavar="DIR", help="output directory")
    data.add_argument(
        "--seed", type=seed_argument, default=0, metavar="S", help="seed, 0 ... 2**63 - 1 (0)"
    )
    data.add_argument("--quick", action="store_true", help="a small version for tests and docs")
    data.add_argument("--jobs", type=jobs_argument, default=1, metavar="N",
                      help="worker processes, at most the machine's cores (1; -1: all cores)")
    data.add_argument("--force-jobs", action="store_true",
                      help="allow --jobs above the number of cores")
    data.add_argument("--json", action="store_true", help="print one JSON object")
    add_from_recordings(data)
    data.set_defaults(func=run_dataset)


def run_dataset(args) -> int:
    """Run ``ebantenna dataset``."""
    import os
    import time

    import numpy as np

    from .._validate import output_dir
    from ..cli import check_jobs, interrupted, print_json
    from ..simulate import builtin_scene
    from ..simulate.dataset import dataset_path
    from ..study.recorded._cli import run_from_recordings
    from .data import build_paper_dataset, design

    check_jobs(args.jobs, args.force_jobs)
    output_dir("--out", args.out)  # refused before any work is done
    if args.from_recordings is not None:
        return run_from_recordings(args)
    # and the data set's own file in it (a directory in its place), before the simulation
    dataset_path(args.out, builtin_scene("paper"), design(args.quick), args.seed, parameter="--out")
    start = time.perf_counter()
    try:
        jobs = (os.cpu_count() or 1) if args.jobs == -1 else args.jobs
        data = build_paper_dataset(args.out, seed=args.seed, quick=args.quick, n_jobs=jobs)
    except KeyboardInterrupt as exc:
        # an unfinished data set is not kept: a partial file would pass for the whole one
        raise interrupted(
            exc,
            {
                "path": None,
                "seed": args.seed,
                "quick": bool(args.quick),
                "seconds": round(time.perf_counter() - start, 3),
            },
        ) from None
    summary = {
        "path": str(data.path),
        "signals": data.n_signals,
        "samples": data.n_samples,
        "fs": data.fs,
        "materials": sorted({str(m) for m in data.material}),
        "contacts": int(np.unique(data.contact).size),
        "repetitions": int(data.repetition.max()) + 1,
        "seed": args.seed,
        "quick": bool(args.quick),
        "checksum_sha256": data.metadata["checksum_sha256"],
        # the compiled and NumPy marches make different data sets (within a bound): say which
        "strike_march": data.metadata["config"].get("strike_march"),
        "seconds": round(time.perf_counter() - start, 3),
    }
    if args.json:
        print_json(summary)
        return 0
    print(
        f"{summary['signals']} signals ({len(summary['materials'])} materials x "
        f"{summary['contacts']} contacts x {summary['repetitions']} repetitions), "
        f"{summary['samples']} samples at {data.fs:g} Hz in {args.out} "
        f"({summary['seconds']:.1f} s)"
    )
    return 0
