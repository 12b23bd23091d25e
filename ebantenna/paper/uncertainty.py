"""How much an accuracy can carry: its test count, its 95 % interval, and its spread over seeds.

An accuracy measured on ``n`` test recordings is a binomial proportion: ``k`` of them right. Its
95 % interval here is Wilson's (:func:`ebantenna.ml.metrics.accuracy_interval`). A split's
seed decides which recordings are tested, so a second, independent measure of the uncertainty is
the spread of the accuracy over several split seeds (:func:`seed_spread`).

Every accuracy the study writes to ``summary.json`` goes through :func:`accuracy_entries`, which
puts the test count and the interval beside it:
``{"x_accuracy": a, "x_accuracy_n_test": n, "x_accuracy_ci95": [lo, hi]}``.
"""

from __future__ import annotations

import math

import numpy as np

from .._validate import check_int
from ..ml.metrics import accuracy_interval

__all__ = [
    "correct_count",
    "interval",
    "accuracy_entries",
    "SeedSpread",
    "seed_spread",
    "difference_resolved",
    "resolvable_difference",
    "format_interval",
]

#: How far ``accuracy * n`` may sit from a whole number and still count as ``k`` right out of
#: ``n``: an accuracy is ``k / n`` rounded to a double, so ``k / n * n`` is within a few ulps.
_COUNT_TOLERANCE = 1e-6


def correct_count(accuracy: float, n: int) -> int:
    """The number right, ``k``, of an accuracy ``k / n`` measured on ``n`` test recordings.

    Raises ``ValueError`` when ``accuracy * n`` is not a whole number: the accuracy was not
    measured on ``n`` recordings.

    Examples
    --------
    >>> correct_count(0.8325, 400)
    333
    """
    n = check_int("n", n, minimum=1)
    accuracy = float(accuracy)
    k = round(accuracy * n)
    if not 0 <= k <= n or abs(accuracy * n - k) > _COUNT_TOLERANCE:
        raise ValueError(f"accuracy {accuracy!r} is not a count out of n={n}")
    return int(k)


def interval(accuracy: float, n: int) -> tuple[float, float]:
    """Wilson 95 % interval of an accuracy ``k / n`` measured on ``n`` test recordings.

    Examples
    --------
    >>> lo, hi = interval(0.65, 80)
    >>> round(lo, 3), round(hi, 3)
    (0.541, 0.745)
    """
    return accuracy_interval(correct_count(accuracy, n), n)


def accuracy_entries(name: str, accuracy, n) -> dict:
    """``{name: accuracy, name_n_test: n, name_ci95: [lo, hi]}`` for ``summary.json``.

    ``accuracy`` and ``n`` may be one number each, or dicts with the same keys (one accuracy
    per split, trainer, ...), and the two added entries are then dicts as well. ``None`` (not
    measured) stays None.

    Examples
    --------
    >>> accuracy_entries("svm", 0.75, 8)
    {'svm': 0.75, 'svm_n_test': 8, 'svm_ci95': [0.4093, 0.9285]}
    >>> accuracy_entries("by", {"a": 0.5}, {"a": 4})["by_n_test"]
    {'a': 4}
    """
    if accuracy is None:
        return {name: None, f"{name}_n_test": None, f"{name}_ci95": None}
    if isinstance(accuracy, dict):
        return {
            name: dict(accuracy),
            f"{name}_n_test": {k: n[k] for k in accuracy},
            f"{name}_ci95": {k: _rounded(interval(a, n[k])) for k, a in accuracy.items()},
        }
    ci95 = _rounded(interval(accuracy, n))
    return {name: accuracy, f"{name}_n_test": int(n), f"{name}_ci95": ci95}


def _rounded(pair) -> list:
    """An interval's ends to four decimals (a hundredth of a percentage point)."""
    return [round(pair[0], 4), round(pair[1], 4)]


class SeedSpread:
    """An accuracy over several split seeds: the values, their mean and sample deviation.

    Attributes
    ----------
    seeds : tuple of int
    values : ndarray
        One accuracy per seed.
    n_test : ndarray of int
        Test recordings of each seed's split.
    mean, std : float
        Mean and sample standard deviation (``ddof=1``) of ``values``.
    """

    def __init__(self, seeds, values, n_test):
        self.seeds = tuple(int(s) for s in seeds)
        self.values = np.asarray(values, dtype=float)
        self.n_test = np.asarray(n_test, dtype=int)
        if not (len(self.seeds) == self.values.size == self.n_test.size >= 2):
            raise ValueError("need at least two seeds, one value and one count per seed")
        self.mean = float(self.values.mean())
        self.std = float(self.values.std(ddof=1))

    def to_dict(self) -> dict:
        """``mean``, ``std``, ``seeds``, ``values``, ``n_test`` and each value's Wilson 95 %
        interval ``ci95``, as plain lists."""
        return {
            "mean": self.mean,
            "std": self.std,
            "seeds": list(self.seeds),
            "values": self.values.tolist(),
            "n_test": self.n_test.tolist(),
            "ci95": [_rounded(interval(a, n)) for a, n in zip(self.values, self.n_test,
                                                              strict=True)],
        }

    def __str__(self) -> str:
        return f"{100 * self.mean:.1f} ± {100 * self.std:.1f} %"


def seed_spread(measure, seeds) -> SeedSpread:
    """``measure(seed)`` for every seed: each returns ``(accuracy, n_test)``.

    Examples
    --------
    >>> s = seed_spread(lambda seed: ((seed + 1) / 4, 4), [0, 1, 2])
    >>> s.mean, s.std, str(s)
    (0.5, 0.25, '50.0 ± 25.0 %')
    """
    pairs = [measure(int(s)) for s in seeds]
    return SeedSpread(seeds, [p[0] for p in pairs], [p[1] for p in pairs])


def resolvable_difference(accuracy: float, n: int) -> float:
    """The smallest change two accuracies near ``accuracy``, each on ``n`` independent test
    recordings, must differ by to stand two standard deviations of their difference apart:
    ``2 sqrt(2 p (1 - p) / n)``.

    Examples
    --------
    >>> round(resolvable_difference(0.65, 80), 3), round(resolvable_difference(0.65, 240), 3)
    (0.151, 0.087)
    """
    n = check_int("n", n, minimum=1)
    return 2 * math.sqrt(2 * accuracy * (1 - accuracy) / n)


def difference_resolved(a: float, b: float, n: int) -> bool:
    """Whether two accuracies on ``n`` test recordings each differ by more than two standard
    deviations of their difference (the binomial variance at their mean, ``2 p (1-p) / n``).

    Examples
    --------
    >>> difference_resolved(0.65, 0.55, 240), difference_resolved(0.65, 0.55, 80)
    (True, False)
    """
    return bool(abs(a - b) > resolvable_difference((a + b) / 2, n))


def format_interval(accuracy: float, n: int) -> str:
    """An accuracy with its test count and Wilson 95 % interval, for the report.

    Examples
    --------
    >>> format_interval(0.65, 80)
    '65.0 % (n = 80, 95 % CI 54.1-74.5)'
    """
    lo, hi = interval(accuracy, n)
    return f"{100 * accuracy:.1f} % (n = {n}, 95 % CI {100 * lo:.1f}-{100 * hi:.1f})"
