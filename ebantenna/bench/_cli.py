"""``ebantenna bench``."""

from __future__ import annotations


def register(subparsers) -> None:
    """Add the ``bench`` command."""
    bench = subparsers.add_parser(
        "bench",
        help="accuracy against time for every subpackage, as one report",
        description="Run the accuracy-versus-time sweeps and write bench.md / bench.html.",
    )
    bench.add_argument("--out", default="ebantenna-bench", metavar="DIR", help="output directory")
    bench.add_argument("--quick", action="store_true", help="the sweeps' quick versions")
    bench.add_argument(
        "--only",
        action="append",
        metavar="NAME",
        help="run only this sweep (repeatable): fem_accuracy, signal_accuracy, simulate_cost, "
        "ml_speed",
    )
    bench.set_defaults(func=run_bench)


def run_bench(args) -> int:
    """Run ``ebantenna bench``."""
    from . import run_benchmarks

    results = run_benchmarks(args.out, quick=args.quick, only=args.only)
    for name, result in results.items():
        if name != "report":
            print(f"== {name} ({result['seconds']:.1f} s)")
            print(result["table"])
    print(f"report: {results['report']['html']}")
    return 0
