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
        "contact_cost, ml_speed",
    )
    bench.add_argument(
        "--json", action="store_true", help="print the measured rows as one JSON object"
    )
    bench.set_defaults(func=run_bench)


def json_ready(value):
    """``value`` with NumPy numbers and arrays as plain JSON values; NaN and inf as None.

    Examples
    --------
    >>> import numpy as np
    >>> json_ready({"n": np.int64(3), "err": [np.float64(1e-9), float("nan")]})
    {'n': 3, 'err': [1e-09, None]}
    """
    import math
    from pathlib import Path

    import numpy as np

    if isinstance(value, dict):
        return {str(k): json_ready(v) for k, v in value.items()}
    if isinstance(value, list | tuple | np.ndarray):
        return [json_ready(v) for v in value]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None  # JSON has no NaN or infinity
    if isinstance(value, Path):
        return str(value)
    return value


def run_bench(args) -> int:
    """Run ``ebantenna bench``."""
    from .._validate import output_dir
    from ..cli import print_json
    from . import run_benchmarks

    output_dir("--out", args.out)  # refused before any work is done
    results = run_benchmarks(
        args.out, quick=args.quick, only=args.only, show_progress=False if args.json else None
    )
    report = results.pop("report")
    if args.json:
        print_json(
            {
                "out": str(args.out),
                "quick": bool(args.quick),
                "report": report,
                "benchmarks": {
                    name: {"seconds": r["seconds"], "rows": json_ready(r["rows"])}
                    for name, r in results.items()
                },
            }
        )
        return 0
    for name, result in results.items():
        print(f"== {name} ({result['seconds']:.1f} s)")
        print(result["table"])
    print(f"report: {report['html']}")
    return 0
