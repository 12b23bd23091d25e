"""Checks of the sweeps' arguments, shared by the benchmark modules (private).

A sweep runs for minutes: its arguments are checked before the first measurement, and a table
handed to ``to_text`` or ``plot`` is checked to be what ``run`` returned before any of it is
formatted.
"""

from __future__ import annotations

import numpy as np

from .._validate import check_array, check_int, describe

__all__ = ["check_argv", "check_tables", "check_features", "check_callable",
           "check_generator", "check_count", "MAX_TRIALS"]

#: The most trials, repetitions or epochs a sweep takes: a count beyond this would run for days
#: (the full sweeps take 200 trials, 5 repetitions and 50 epochs).
MAX_TRIALS = 100_000


def check_argv(argv) -> list[str] | None:
    """``argv`` of a sweep's ``main``: None (the command line) or a list of strings.

    A single string would be read letter by letter by :mod:`argparse`.

    Examples
    --------
    >>> check_argv("--quick")
    Traceback (most recent call last):
    ...
    TypeError: argv must be None or a list of strings such as ['--quick'], got '--quick'
    """
    if argv is None:
        return None
    if not isinstance(argv, list | tuple) or not all(isinstance(a, str) for a in argv):
        raise TypeError(f"argv must be None or a list of strings such as ['--quick'], got "
                        f"{describe(argv)}")
    return list(argv)


def check_tables(tables, producer: str, **kinds) -> dict:
    """``tables`` as ``producer`` returns it: a dict holding each key of ``kinds``, its value of
    that type (a list of rows holds dicts).

    Examples
    --------
    >>> check_tables({"rows": []}, "run", rows=list, signals=int)
    Traceback (most recent call last):
    ...
    ValueError: tables must be what run() returns: it lacks 'signals'
    """
    if not isinstance(tables, dict):
        raise TypeError(f"tables must be the dict that {producer}() returns, got "
                        f"{type(tables).__name__}")
    for key, kind in kinds.items():
        if key not in tables:
            raise ValueError(f"tables must be what {producer}() returns: it lacks {key!r}")
        value = tables[key]
        if not isinstance(value, kind) or isinstance(value, bool):
            raise TypeError(f"tables[{key!r}] must be a {kind.__name__}, got "
                            f"{type(value).__name__}")
        if kind is list and not all(isinstance(row, dict) for row in value):
            raise TypeError(f"tables[{key!r}] must be a list of rows (dicts)")
    return tables


def check_features(X, y) -> tuple[np.ndarray, np.ndarray]:
    """``(X, y)`` of a timed fit: ``X`` a finite 2-D array, ``y`` one label per row of it and
    two classes at least (every estimator timed is a classifier)."""
    X = check_array("X", X, ndim=2)
    y = np.asarray(y)
    if y.shape != (X.shape[0],):
        raise ValueError(f"y must hold one label per row of X ({X.shape[0]}), got shape "
                         f"{y.shape}")
    if np.unique(y).size < 2:
        raise ValueError("y must hold two classes at least")
    return X, y


def check_callable(name: str, value) -> None:
    """Raise unless ``value`` can be called."""
    if not callable(value):
        raise TypeError(f"{name} must be a callable, got {type(value).__name__}")


def check_generator(name: str, rng) -> np.random.Generator:
    """``rng``, a :class:`numpy.random.Generator` (the sweeps draw from its stream)."""
    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"{name} must be a numpy.random.Generator (numpy.random.default_rng"
                        f"(seed)), got {type(rng).__name__}")
    return rng


def check_count(name: str, value, *, minimum: int = 1) -> int:
    """A count of trials, repetitions or epochs: an integer from ``minimum`` to
    :data:`MAX_TRIALS`."""
    return check_int(name, value, minimum=minimum, maximum=MAX_TRIALS)
