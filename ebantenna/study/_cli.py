"""``ebantenna reproduce``."""

from __future__ import annotations


def register(subparsers) -> None:
    """Add the ``reproduce`` command."""
    from ..cli import jobs_argument, seeds_up_to
    from .recorded._cli import add_data
    from .reproduce import MAX_SEED

    rep = subparsers.add_parser(
        "reproduce",
        help="the whole study: figures and a report, the paper beside its reproduction",
        description="Build (or reuse) the simulated data set and run the whole study.",
    )
    rep.add_argument("--out", default="ebantenna-output", metavar="DIR", help="output directory")
    rep.add_argument("--quick", action="store_true", help="a reduced run for tests and docs")
    rep.add_argument(
        "--seed",
        type=seeds_up_to(MAX_SEED),
        default=0,
        help="seed of the data set and the models, 0 ... 2**32 - 2 (0)",
    )
    rep.add_argument("--jobs", type=jobs_argument, default=-1,
                     help="parallel workers, at most the machine's cores (-1: all cores)")
    rep.add_argument("--force-jobs", action="store_true",
                     help="allow --jobs above the number of cores")
    rep.add_argument("--cache", metavar="DIR", help="data set cache (default ~/.cache/ebantenna)")
    rep.add_argument("--json", action="store_true", help="print the summary as one JSON object")
    add_data(rep)
    rep.set_defaults(func=run_reproduce)


def run_reproduce(args) -> int:
    """Run ``ebantenna reproduce``."""
    from .._validate import output_dir, output_file_in
    from ..cli import check_jobs, interrupted, print_json
    from ..paper import printed
    from .recorded._cli import run_data
    from .reproduce import REPORT_FILES, reproduce

    check_jobs(args.jobs, args.force_jobs)
    if args.cache is not None:
        output_dir("--cache", args.cache)
    for name in REPORT_FILES:  # the folder and what goes in it, refused before any work
        output_file_in("--out", args.out, name)
    if args.data is not None:
        return run_data(args)
    try:
        result = reproduce(
            args.out,
            quick=args.quick,
            seed=args.seed,
            n_jobs=args.jobs,
            cache_dir=args.cache,
            show_progress=None if not args.json else False,
        )
    except KeyboardInterrupt as exc:
        # what is complete stays: the cached data set (written whole or not at all), the figures
        # written so far; the report and summary.json are not written
        partial = {"out": None, "quick": bool(args.quick), "seed": args.seed}
        raise interrupted(exc, partial) from None
    s = result.summary
    if args.json:
        print_json(s)
        return 0
    print(f"Study written to {result.out_dir}/ ({len(result.figures)} figures)")
    print(f"  report: {result.report_html}")
    print(
        f"  SVM material accuracy: train {s['svm']['train_accuracy']:.1%}, "
        f"test {s['svm']['test_accuracy']:.1%}   (paper "
        f"{printed.percent(printed.SVM_TRAIN_ACCURACY)} / "
        f"{printed.percent(printed.SVM_TEST_ACCURACY)})"
    )
    print(
        f"  ANN material accuracy: all {s['ann']['all_accuracy']:.1%}, "
        f"test {s['ann']['test_accuracy']:.1%}   (paper {printed.percent(printed.ANN_ACCURACY)})"
    )
    print(
        f"  contact distance over the whole probe: MAE "
        f"{s['distance']['full_range_mae_cm']:.2f} cm (first mode only: "
        f"{s['distance']['first_mode_only_mae_cm']:.2f} cm)"
    )
    return 0
