"""Which numbers of the study moved between two runs, and by how much.

Two runs of ``ebantenna reproduce --json`` on the same seed give the same ``summary.json`` when
they simulate the same data set. With another strike march (the compiled one of the ``fast``
extra) or other arithmetic (another BLAS kernel), a strike that chatters near the probe's tip
follows the last bits, the data set differs in those recordings, and every result learnt from it
may move. This script says which moved::

    python benchmarks/summary_moves.py A/summary.json B/summary.json
    python benchmarks/summary_moves.py A/summary.json B/summary.json --json

It prints, for each part of the summary, the entries that moved and the largest relative move
among them (with its entry), then every entry that is not a number and changed (a verdict such as
``resolved``, ``direction`` or ``identical``, an epoch that became ``null``): a changed verdict
is a changed statement of the report, not a changed digit. Wall times, file paths and checksums
are left out (:data:`NOT_RESULTS`); they differ between any two runs.

The stored summary of the documentation (``docs/_data/reproduce_summary.json``) holds the run
under ``"summary"``; the script reads either layout.
"""

from __future__ import annotations

import argparse
import json
import math
import sys

#: Entries that are not results of the study: they differ between any two runs.
NOT_RESULTS = ("timings_s", "seconds", "path", "figures", "report", "checksum", "dataset_cached",
               "strike_march")


def flatten(tree, prefix: str = "") -> dict:
    """The leaves of a nested dict/list, by dotted path (``a.b[2].c``).

    Examples
    --------
    >>> flatten({"a": {"b": [1, 2]}, "c": None})
    {'a.b[0]': 1, 'a.b[1]': 2, 'c': None}
    """
    if isinstance(tree, dict):
        out = {}
        for key, value in tree.items():
            out.update(flatten(value, f"{prefix}.{key}" if prefix else str(key)))
        return out
    if isinstance(tree, list):
        out = {}
        for i, value in enumerate(tree):
            out.update(flatten(value, f"{prefix}[{i}]"))
        return out
    return {prefix: tree}


def _is_number(value) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def relative_move(a: float, b: float) -> float:
    """``|b - a| / |a|``; ``inf`` when ``a`` is 0 and ``b`` is not.

    Examples
    --------
    >>> relative_move(2.0, 2.5), relative_move(0.0, 0.0), relative_move(0.0, 1e-3)
    (0.25, 0.0, inf)
    """
    if a == b:
        return 0.0
    return abs(b - a) / abs(a) if a != 0 else math.inf


def moves(a: dict, b: dict) -> dict:
    """Compare two summaries.

    Returns
    -------
    dict
        ``parts``: per top-level part, ``n`` entries compared, ``moved`` how many differ, and
        ``largest`` the entry with the largest relative move ``[path, a, b, relative]``;
        ``statements``: ``[path, a, b]`` of every entry that is not a number (or is missing on
        one side) and differs.

    Examples
    --------
    >>> m = moves({"x": {"acc": 0.80, "resolved": True}, "y": 1},
    ...           {"x": {"acc": 0.84, "resolved": False}, "y": 1})
    >>> m["parts"]["x"]["largest"][0], round(m["parts"]["x"]["largest"][3], 3), m["statements"]
    ('x.acc', 0.05, [['x.resolved', True, False]])
    """
    fa, fb = flatten(a), flatten(b)
    parts, statements = {}, []
    for path in sorted(set(fa) | set(fb)):
        if any(word in path for word in NOT_RESULTS):
            continue
        part = path.split(".")[0].split("[")[0]
        entry = parts.setdefault(part, {"n": 0, "moved": 0, "largest": None})
        entry["n"] += 1
        x, y = fa.get(path), fb.get(path)
        if x == y or (_is_number(x) and _is_number(y) and math.isnan(x) and math.isnan(y)):
            continue
        entry["moved"] += 1
        if _is_number(x) and _is_number(y):
            rel = relative_move(x, y)
            if entry["largest"] is None or rel > entry["largest"][3]:
                entry["largest"] = [path, x, y, rel]
        else:
            statements.append([path, x, y])
    return {"parts": parts, "statements": statements}


def _load(path: str) -> dict:
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    return data["summary"] if set(data) == {"made", "summary"} else data


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("a", help="the first run's summary.json")
    parser.add_argument("b", help="the second run's summary.json")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args(argv)
    result = moves(_load(args.a), _load(args.b))
    if args.json:
        print(json.dumps(result))
        return 0
    for part, entry in result["parts"].items():
        line = f"{part}: {entry['moved']} of {entry['n']} entries moved"
        if entry["largest"] is not None:
            path, x, y, rel = entry["largest"]
            line += f"; largest {rel:.3g} relative: {path} {x:.6g} -> {y:.6g}"
        print(line)
    print(f"statements changed: {len(result['statements'])}")
    for path, x, y in result["statements"]:
        print(f"  {path}: {x!r} -> {y!r}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
