"""How much an accuracy can carry: its independent units, its 95 % interval on them, and its
spread over folds.

An accuracy measured on ``n`` test recordings is ``k`` of them right. Were the recordings
independent, ``k`` would be binomial and Wilson's interval
(:func:`ebantenna.ml.metrics.accuracy_interval`, :func:`interval`) would hold. They are not:
the recordings come in groups of near copies (the repetitions at one contact position), and a
split draws whole positions. The errors within a group go together, so an accuracy carries
about as much as ``n / deff`` independent recordings, where ``deff`` is the design effect
(:func:`design_effect`). Every interval the study states is taken on its unit of replication
(:data:`UNITS`):

* :class:`ClusteredAccuracy`: Wilson's interval at the design-effect sample size, the clusters
  named; it is Wilson's interval itself when every cluster holds one recording;
  :func:`cluster_bootstrap` resamples whole clusters instead, a check of it;
* :class:`FoldAccuracy`: an accuracy over every fold of a split (each recording tested once),
  with the spread of the folds, and Student's t over the folds when the fold is the unit;
* :class:`PairedDifference`: two conditions on the same recordings compared recording by
  recording, the difference's interval on the clusters, whether it is resolved, and the
  smallest difference the design detects at 80 % power, when the changed recordings are spread
  independently and when whole clusters change at once, the two ends of how a change can come
  (:func:`minimal_detectable_difference`, by simulating the design with that difference added
  as recordings that change outcome).

Every accuracy the study writes to ``summary.json`` goes through :func:`clustered_entries`
(training accuracies through :func:`training_entries`, which give no interval); every number
the report and the documentation print goes through :func:`percent`, :func:`points` and
:func:`span`. The recording-level helpers (:func:`accuracy_entries`, :func:`format_interval`,
:func:`resolvable_difference`) stay for teaching the contrast.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.stats import binom, norm
from scipy.stats import t as student_t

from .._validate import (
    check_array,
    check_bool,
    check_choice,
    check_in_range,
    check_int,
    check_real,
    describe,
)
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
    "UNITS",
    "cluster_labels",
    "cluster_counts",
    "design_effect",
    "ClusteredAccuracy",
    "FoldAccuracy",
    "clustered_entries",
    "training_entries",
    "cluster_bootstrap",
    "PairedDifference",
    "minimal_detectable_difference",
    "percent",
    "points",
    "span",
    "format_clustered",
    "format_difference",
    "detectable_text",
    "detectable_cell",
    "cluster_mean_interval",
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
    n = check_int("n", n, minimum=1, maximum=2**53)  # a count a float holds exactly
    accuracy = _accuracy("accuracy", accuracy)
    k = round(accuracy * n)
    if not 0 <= k <= n or abs(accuracy * n - k) > _COUNT_TOLERANCE:
        raise ValueError(f"accuracy {accuracy!r} is not a count out of n={n}")
    return int(k)


def _accuracy(name: str, value) -> float:
    """``value`` as a float in [0, 1] (an accuracy), else an error naming ``name``."""
    return check_in_range(name, value, 0.0, 1.0, low_inclusive=True, high_inclusive=True)


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
    name = _check_name(name)
    if accuracy is None:
        return {name: None, f"{name}_n_test": None, f"{name}_ci95": None}
    if isinstance(accuracy, dict):
        if not isinstance(n, dict) or set(n) != set(accuracy):
            raise ValueError(f"n must be a dict with the keys of accuracy "
                             f"({', '.join(map(str, accuracy))}), got {describe(n)}")
        return {
            name: dict(accuracy),
            f"{name}_n_test": {k: n[k] for k in accuracy},
            f"{name}_ci95": {k: _rounded(interval(a, n[k])) for k, a in accuracy.items()},
        }
    ci95 = _rounded(interval(accuracy, n))
    return {name: accuracy, f"{name}_n_test": check_int("n", n), f"{name}_ci95": ci95}


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
    tested : list of (ndarray, ndarray) or None
        Per seed, when recorded: the test rows and whether each was right.
    positions : ndarray or None
        The nominal contact position of every row of the data set measured, when the caller
        sets it: the cluster of each row (:meth:`folds`, :meth:`paired_with`).
    """

    def __init__(self, seeds, values, n_test, tested=None):
        self.seeds = tuple(check_int("seeds", s, minimum=0) for s in seeds)
        self.values = check_array("values", values, ndim=1)
        self.n_test = np.array([check_int("n_test", n, minimum=1) for n in np.ravel(n_test)])
        if not (len(self.seeds) == self.values.size == self.n_test.size >= 2):
            raise ValueError(f"seeds, values and n_test need at least two seeds, one value and "
                             f"one count per seed; got {len(self.seeds)}, {self.values.size} "
                             f"and {self.n_test.size}")
        if np.any((self.values < 0) | (self.values > 1)):
            raise ValueError("values must be accuracies, in [0, 1]")
        self.mean = float(self.values.mean())
        self.std = float(self.values.std(ddof=1))
        self.positions = None
        self.tested = None if tested is None else [
            (np.asarray(r, dtype=np.intp), np.asarray(c, dtype=bool)) for r, c in tested
        ]

    def correct_by_row(self, n_rows: int) -> np.ndarray:
        """Whether each row of the data set was classified right when it was tested, when the
        seeds' test sets are folds (every row tested exactly once).

        Raises ``ValueError`` when the seeds did not record their rows, or when a row was tested
        twice or never.
        """
        if self.tested is None:
            raise ValueError("the seeds' test rows were not recorded")
        n_rows = check_int("n_rows", n_rows, minimum=1)
        top = max(int(rows.max(initial=-1)) for rows, _ in self.tested)
        if top >= n_rows:
            raise ValueError(f"n_rows must exceed every tested row ({top}), got {n_rows}")
        out = np.zeros(n_rows, dtype=bool)
        seen = np.zeros(n_rows, dtype=int)
        for rows, correct in self.tested:
            out[rows] = correct
            np.add.at(seen, rows, 1)
        if np.any(seen != 1):
            raise ValueError("the seeds' test sets are not folds: some row was tested "
                             f"{int(seen.max())} times and some {int(seen.min())} times")
        return out

    def paired_with(self, other: SeedSpread, unit: str = "position", **kwargs):
        """``other`` against this one (the reference) on the same rows, over all the folds,
        paired within each row's position (``positions``, which must be the same for
        both): a :class:`PairedDifference`."""
        if not isinstance(other, SeedSpread):
            raise TypeError(f"other must be a SeedSpread, got {type(other).__name__}")
        if self.positions is None or other.positions is None:
            raise ValueError("both spreads need the positions of their rows")
        if not np.array_equal(self.positions, other.positions):
            raise ValueError("the two spreads were not measured on the same rows")
        n = self.positions.size
        return PairedDifference.from_recordings(self.correct_by_row(n), other.correct_by_row(n),
                                                self.positions, unit, **kwargs)

    def folds(self, clusters=None, unit: str = "position", *,
              by_fold: bool = False) -> FoldAccuracy:
        """The seeds as the folds of one split (:class:`FoldAccuracy`), each row's cluster
        from ``clusters`` (one label per row of the data set; default ``positions``)."""
        if self.tested is None:
            raise ValueError("the seeds' test rows were not recorded")
        g = _labels("clusters", self.positions if clusters is None else clusters)
        top = max(int(rows.max(initial=-1)) for rows, _ in self.tested)
        if g.size <= top:
            raise ValueError(f"clusters must hold one label per row of the data set (more than "
                             f"{top}), got {g.size}")
        return FoldAccuracy([(c, g[r]) for r, c in self.tested], unit, by_fold=by_fold)

    def to_dict(self) -> dict:
        """``mean``, ``std``, ``seeds``, ``values``, ``n_test`` and each value's Wilson 95 %
        interval counting every recording as independent, ``recording_ci95`` (too narrow when
        the recordings cluster: the spread of the values is the measure), as plain lists."""
        return {
            "mean": self.mean,
            "std": self.std,
            "seeds": list(self.seeds),
            "values": self.values.tolist(),
            "n_test": self.n_test.tolist(),
            "recording_ci95": [list(interval(a, n)) for a, n in zip(self.values, self.n_test,
                                                                   strict=True)],
        }

    def __str__(self) -> str:
        return f"{100 * self.mean:.1f} ± {100 * self.std:.1f} %"


def seed_spread(measure, seeds) -> SeedSpread:
    """``measure(seed)`` for every seed: each returns ``(accuracy, n_test)``, or
    ``(accuracy, n_test, rows, correct)`` to keep which rows it tested and whether each was
    right (:meth:`SeedSpread.correct_by_row`, :meth:`SeedSpread.folds`).

    Examples
    --------
    >>> s = seed_spread(lambda seed: ((seed + 1) / 4, 4), [0, 1, 2])
    >>> s.mean, s.std, str(s)
    (0.5, 0.25, '50.0 ± 25.0 %')
    """
    if not callable(measure):
        raise TypeError(f"measure must be a function of a seed, got {type(measure).__name__}")
    seeds = [check_int("seeds", s, minimum=0) for s in seeds]
    if len(seeds) < 2:
        raise ValueError(f"seeds must hold at least two seeds, got {len(seeds)}")
    pairs = [measure(s) for s in seeds]
    if not all(isinstance(p, tuple) and len(p) in (2, 4) for p in pairs):
        raise TypeError("measure must return (accuracy, n_test) or (accuracy, n_test, rows, "
                        "correct) for each seed")
    tested = [p[2:4] for p in pairs] if all(len(p) == 4 for p in pairs) else None
    return SeedSpread(seeds, [p[0] for p in pairs], [p[1] for p in pairs], tested)


def resolvable_difference(accuracy: float, n: int) -> float:
    """The smallest change two accuracies near ``accuracy``, each on ``n`` independent test
    recordings, must differ by to stand two standard deviations of their difference apart:
    ``2 sqrt(2 p (1 - p) / n)``.

    Examples
    --------
    >>> round(resolvable_difference(0.65, 80), 3), round(resolvable_difference(0.65, 240), 3)
    (0.151, 0.087)
    """
    n = check_int("n", n, minimum=1, maximum=2**53)
    accuracy = _accuracy("accuracy", accuracy)
    return 2 * math.sqrt(2 * accuracy * (1 - accuracy) / float(n))


def difference_resolved(a: float, b: float, n: int) -> bool:
    """Whether two accuracies on ``n`` test recordings each differ by more than two standard
    deviations of their difference (the binomial variance at their mean, ``2 p (1-p) / n``).

    It assumes two unpaired samples of independent recordings. The study's comparisons are
    neither: repetitions of one position go together and both conditions test the same
    recordings, so the study uses :class:`PairedDifference`, which is never less strict about
    the clusters and gains from the pairing. Here it is the textbook rule only.

    Examples
    --------
    >>> difference_resolved(0.65, 0.55, 240), difference_resolved(0.65, 0.55, 80)
    (True, False)
    """
    a, b = _accuracy("a", a), _accuracy("b", b)
    return bool(abs(a - b) > resolvable_difference((a + b) / 2, n))


def format_interval(accuracy: float, n: int) -> str:
    """An accuracy with its test count and Wilson 95 % interval, for the report.

    Examples
    --------
    >>> format_interval(0.65, 80)
    '65.0 % (n = 80, 95 % CI 54.1-74.5)'
    """
    low_high = interval(accuracy, n)  # checks both
    return f"{percent(accuracy)} (n = {n}, 95 % CI {span(low_high)})"


# ------------------------------------------------------------------ the unit of replication
#: What the study's intervals treat as one independent observation, by split or design. A split
#: draws whole nominal positions (grouped) or whole blocks of them (blocked), and the
#: repetitions at one position are near copies: the position, not the recording, is what is
#: replicated. The random split draws recordings, but its test recordings still come in groups
#: of near copies, so they are counted by position too.
UNITS = {
    "random": "position",
    "grouped": "position",
    "blocked": "held-out block",
}

#: Names of the interval methods, as ``summary.json`` and the report give them.
METHOD_DESIGN_EFFECT = ("Wilson at the design-effect sample size with Student's quantile on the "
                        "{unit}s less one, clustered by {unit}")
METHOD_FOLDS = "t interval over the {folds} folds (unit: {unit})"
METHOD_PAIRED = ("paired difference, cluster-robust interval with Student's quantile over "
                 "{unit}s")
METHOD_PAIRED_FOLDS = ("paired difference, the folds' mean, t interval over the {folds} folds "
                       "(unit: {unit})")

#: The standard normal's 97.5 % quantile: a two-sided 95 % interval.
Z95 = 1.959963984540054


def _wilson(p: float, n: float, z: float = Z95) -> tuple[float, float]:
    """Wilson's score interval of a proportion ``p`` on ``n`` observations; ``n`` may be a real
    number (an effective sample size). The same formula as
    :func:`ebantenna.ml.metrics.accuracy_interval`."""
    centre = p + z * z / (2 * n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    scale = 1 + z * z / n
    low = 0.0 if p <= 0 else (centre - half) / scale
    high = 1.0 if p >= 1 else (centre + half) / scale
    return max(0.0, low), min(1.0, high)


#: The most resamples a bootstrap draws: each is a row of ``G`` cluster indices held in memory.
MAX_RESAMPLES = 10**6


def _check_unit(unit) -> str:
    """``unit`` if it is a non-empty string: what one cluster is, named in the method."""
    if not isinstance(unit, str) or not unit:
        raise TypeError(f"unit must be a non-empty string, got {describe(unit)}")
    return unit


def _check_name(name) -> str:
    """``name`` if it is a non-empty string: the key of an entry of ``summary.json``."""
    if not isinstance(name, str) or not name:
        raise TypeError(f"name must be a non-empty string, got {describe(name)}")
    return name


def _labels(name: str, labels) -> np.ndarray:
    """``labels`` as a 1-D array of cluster labels; a NaN label (a missing value) is refused."""
    g = np.asarray(labels)
    if g.ndim != 1:
        raise ValueError(f"{name} must be a 1-D array of labels, got shape {g.shape}")
    if g.dtype.kind in "fc" and np.any(np.isnan(g)):
        raise ValueError(f"{name} must not hold NaN (a missing label)")
    return g


def _correct(name: str, correct) -> np.ndarray:
    """``correct`` as a non-empty 1-D bool array: booleans, or 0 and 1."""
    c = np.asarray(correct)
    if c.ndim != 1 or c.size == 0:
        raise ValueError(f"{name} must be a non-empty 1-D array, got shape {c.shape}")
    if c.dtype != bool:
        if c.dtype.kind not in "iuf" or not np.all((c == 0) | (c == 1)):
            raise ValueError(f"{name} must hold booleans (or 0 and 1)")
        c = c.astype(bool)
    return c


def cluster_labels(*keys) -> np.ndarray:
    """One integer per recording naming its cluster: the distinct combinations of ``keys``.

    Parameters
    ----------
    *keys : array-like of shape (n,)
        One value per recording each (a position, a material, a block ...).

    Returns
    -------
    ndarray of int of shape (n,)
        ``0 ... G - 1``, in the sorted order of the combinations.

    Examples
    --------
    >>> cluster_labels([0.1, 0.1, 0.2, 0.2], ["al", "pvc", "al", "al"]).tolist()
    [0, 1, 2, 2]
    """
    if not keys:
        raise ValueError("cluster_labels needs at least one key")
    keys = [_labels("keys", k) for k in keys]
    if keys[0].size == 0:
        raise ValueError("keys must hold at least one recording")
    columns = [np.unique(k, return_inverse=True)[1].ravel() for k in keys]
    sizes = {c.size for c in columns}
    if len(sizes) != 1:
        raise ValueError(f"keys must have one value per recording each, got sizes {sorted(sizes)}")
    rows = np.column_stack(columns)
    return np.unique(rows, axis=0, return_inverse=True)[1].ravel().astype(np.intp)


def cluster_counts(correct, clusters) -> tuple[np.ndarray, np.ndarray]:
    """Right answers ``k_j`` and recordings ``n_j`` of every cluster ``j``.

    Parameters
    ----------
    correct : array-like of bool of shape (n,)
        Whether each recording was classified right.
    clusters : array-like of shape (n,)
        Each recording's cluster (any labels).

    Returns
    -------
    k, n : ndarray of int
        Per cluster, in the sorted order of the labels.

    Examples
    --------
    >>> k, n = cluster_counts([True, False, True, True], ["a", "a", "b", "c"])
    >>> k.tolist(), n.tolist()
    ([1, 1, 1], [2, 1, 1])
    """
    c = _correct("correct", correct)
    g = np.asarray(clusters)
    if g.shape != c.shape:
        raise ValueError(f"clusters must have one label per recording ({c.size}), got {g.shape}")
    _labels("clusters", g)
    _, inverse = np.unique(g, return_inverse=True)
    inverse = inverse.ravel()
    n = np.bincount(inverse)
    k = np.bincount(inverse, weights=c.astype(float)).astype(np.int64)
    return k, n.astype(np.int64)


def _counts(k, n) -> tuple[np.ndarray, np.ndarray]:
    """Per-cluster counts checked: whole numbers, ``0 <= k_j <= n_j``, ``n_j >= 1``."""
    k = np.asarray(k)
    n = np.asarray(n)
    if k.ndim != 1 or k.shape != n.shape or k.size == 0:
        raise ValueError(f"k and n must be non-empty 1-D arrays of one shape, got {k.shape} "
                         f"and {n.shape}")
    for name, v in (("k", k), ("n", n)):
        if v.dtype.kind not in "iu" and not (v.dtype.kind == "f" and np.all(v == np.round(v))):
            raise ValueError(f"{name} must hold whole counts")
        if np.any(v > 2**53):  # whole in int64 and in float64 below it
            raise ValueError(f"{name} must hold counts at most 2**53, got {float(v.max()):g}")
    k, n = k.astype(np.int64), n.astype(np.int64)
    if np.any(n < 1) or np.any(k < 0) or np.any(k > n):
        raise ValueError("need 0 <= k_j <= n_j and n_j >= 1 in every cluster")
    return k, n


def design_effect(k, n) -> float:
    """How many times the variance of an accuracy exceeds the binomial one, given its clusters.

    With ``K = sum k_j`` right of ``N = sum n_j`` recordings and ``p = K / N``, the variance of
    the accuracy (a ratio estimator) counting each cluster as one observation is
    ``sum_j (k_j - p n_j)^2 / N^2``; the binomial variance, counting each recording as one, is
    ``p (1 - p) / N``. Their ratio is the design effect (Kish 1965, *Survey Sampling*, 8.2):
    for clusters of ``m`` recordings with intraclass correlation ``rho`` it is about
    ``1 + (m - 1) rho``. ``N / deff`` recordings would carry as much as the clustered ones.

    A ratio below one (errors anti-correlated within clusters) is taken as one: the interval on
    the cluster is never narrower than the recording-level one. When every recording is right
    (or every one wrong) the spread within the data says nothing; the design effect is then the
    largest the design allows, the mean cluster size ``N / G`` (every cluster one observation).
    Clusters of one recording give exactly 1.

    Examples
    --------
    >>> design_effect([1, 0, 1, 1], [1, 1, 1, 1])
    1.0
    >>> design_effect([5, 0, 5, 0], [5, 5, 5, 5])  # whole clusters right or wrong: m
    5.0
    """
    k, n = _counts(k, n)
    total, right = int(n.sum()), int(k.sum())
    if right in (0, total):
        return total / n.size
    # sum_j (k_j - p n_j)^2 / (N p (1 - p)) in whole numbers, exact: clusters of one
    # recording give 1 to the last bit
    kk, kn, nn = (int(np.dot(a.astype(object), b.astype(object)))
                  for a, b in ((k, k), (k, n), (n, n)))
    num = total * total * kk - 2 * total * right * kn + right * right * nn
    ratio = num / (total * right * (total - right))
    return max(1.0, ratio)


class ClusteredAccuracy:
    """An accuracy measured on clustered recordings, with its interval on the cluster.

    Parameters
    ----------
    k, n : array-like of int
        Right answers and recordings per cluster.
    unit : str
        What one cluster is (``"position"``, ``"twin pair"`` ...).

    Attributes
    ----------
    estimate : float
        ``sum k / sum n``.
    n_recordings, n_units : int
        Recordings, clusters.
    design_effect, effective_n : float
        :func:`design_effect` and ``n_recordings / design_effect``.
    ci95 : (float, float)
        Wilson's interval at the effective sample size, its normal quantile replaced by
        Student's on ``G - 1`` degrees of freedom (Korn & Graubard 1998, *Survey
        Methodology* 24:193): the design effect is estimated from ``G`` clusters, and a few of
        them (four positions) must widen the interval as the t interval over them does. Clusters
        of one recording each are independent recordings: the interval is then Wilson's itself.
        One cluster bounds nothing: (0, 1).
    recording_ci95 : (float, float)
        Wilson's interval counting every recording as independent, for comparison only.
    method : str

    Examples
    --------
    >>> a = ClusteredAccuracy([5, 0, 5, 3], [5, 5, 5, 5], "position")
    >>> a.estimate, a.n_units, round(a.design_effect, 2)
    (0.65, 4, 3.68)
    >>> [round(x, 3) for x in a.ci95], [round(x, 3) for x in a.recording_ci95]
    ([0.155, 0.949], [0.433, 0.819])
    """

    def __init__(self, k, n, unit: str):
        k, n = _counts(k, n)
        self.unit = _check_unit(unit)
        self.n_recordings = int(n.sum())
        self.n_units = int(n.size)
        self.correct = int(k.sum())
        self.estimate = self.correct / self.n_recordings
        self.design_effect = design_effect(k, n)
        self.effective_n = self.n_recordings / self.design_effect
        if self.n_units == self.n_recordings:  # independent recordings: Wilson's itself
            self.ci95 = _wilson(self.estimate, self.effective_n)
        elif self.n_units < 2:
            self.ci95 = (0.0, 1.0)
        else:
            self.ci95 = _wilson(self.estimate, self.effective_n, _quantile95(self.n_units))
        self.recording_ci95 = accuracy_interval(self.correct, self.n_recordings)
        self.method = METHOD_DESIGN_EFFECT.format(unit=unit)

    @classmethod
    def from_recordings(cls, correct, clusters, unit: str) -> ClusteredAccuracy:
        """From each recording's right/wrong and its cluster label (:func:`cluster_counts`)."""
        return cls(*cluster_counts(correct, clusters), unit)

    def entries(self, name: str) -> dict:
        """``summary.json``'s keys for this accuracy under ``name`` (see
        :func:`clustered_entries`)."""
        name = _check_name(name)
        return _shared_entries(self, name, self.design_effect)

    def __str__(self) -> str:
        return format_clustered(self)


def _shared_entries(measured, name: str, design_effect: float | None = None) -> dict:
    """The keys every measured accuracy gives under ``name`` (see :func:`clustered_entries`),
    in ``summary.json``'s order, with ``name_design_effect`` after the units when given."""
    entries = {
        name: measured.estimate,
        f"{name}_n_test": measured.n_recordings,
        f"{name}_unit": measured.unit,
        f"{name}_n_units": measured.n_units,
    }
    if design_effect is not None:
        entries[f"{name}_design_effect"] = design_effect
    return {
        **entries,
        f"{name}_ci95": list(measured.ci95),
        f"{name}_method": measured.method,
        f"{name}_recording_ci95": list(measured.recording_ci95),
    }


def clustered_entries(name: str, measured) -> dict:
    """``summary.json``'s keys of one accuracy, or of one accuracy per key.

    ``measured`` is a :class:`ClusteredAccuracy`, a :class:`FoldAccuracy`, a dict of them (the
    keys become dicts too), or None (not measured). The keys: ``name`` (the estimate),
    ``name_n_test`` (recordings), ``name_unit``, ``name_n_units``, ``name_ci95`` (the 95 %
    interval on the unit), ``name_method``, and ``name_recording_ci95`` (Wilson's interval
    counting every recording as independent: for comparison, too narrow when the recordings
    cluster); a :class:`ClusteredAccuracy` adds ``name_design_effect``, a :class:`FoldAccuracy`
    ``name_folds`` (each fold's accuracy) and ``name_fold_std``.

    Examples
    --------
    >>> e = clustered_entries("svm", ClusteredAccuracy([2, 1], [2, 2], "position"))
    >>> e["svm"], e["svm_n_units"], e["svm_unit"]
    (0.75, 2, 'position')
    >>> clustered_entries("x", None)["x_ci95"] is None
    True
    """
    keys = ("", "_n_test", "_unit", "_n_units", "_ci95", "_method", "_recording_ci95")
    name = _check_name(name)
    kinds = (ClusteredAccuracy, FoldAccuracy)
    if not (measured is None or isinstance(measured, kinds) or (
            isinstance(measured, dict) and all(isinstance(v, kinds) for v in measured.values()))):
        raise TypeError("measured must be a ClusteredAccuracy, a FoldAccuracy, a dict of them "
                        f"or None, got {type(measured).__name__}")
    if measured is None:
        return {f"{name}{s}": None for s in keys}
    if isinstance(measured, dict):
        parts = {k: v.entries(name) for k, v in measured.items()}
        fields = {f for p in parts.values() for f in p}
        return {f: {k: p.get(f) for k, p in parts.items()} for f in sorted(fields)}
    return measured.entries(name)


def training_entries(name: str, accuracy: float, n: int) -> dict:
    """A training-set accuracy and its count: no interval, since it tests nothing unseen.

    Examples
    --------
    >>> training_entries("train_accuracy", 0.9, 100)
    {'train_accuracy': 0.9, 'train_accuracy_n_train': 100}
    """
    name = _check_name(name)
    accuracy = check_in_range("accuracy", accuracy, 0.0, 1.0, low_inclusive=True,
                              high_inclusive=True)
    return {name: accuracy, f"{name}_n_train": check_int("n", n, minimum=1)}


# --------------------------------------------------------------------------- folds
class FoldAccuracy:
    """An accuracy measured over every fold of a split: each recording tested once.

    The estimate is the mean of the folds' accuracies; ``spread`` their sample standard
    deviation. When the split's unit is the fold itself (a contiguous block of positions), the
    interval is Student's t over the folds, ``mean ± t_{F-1} s / sqrt(F)``; otherwise
    (``clusters`` given) the folds are pooled and the interval is that of
    :class:`ClusteredAccuracy` on the clusters.

    Parameters
    ----------
    folds : sequence of (ndarray of bool, ndarray)
        Per fold: each test recording's right/wrong and its cluster label (labels shared
        across folds name the same cluster).
    unit : str
        What one independent unit is.
    by_fold : bool
        True: the fold is the unit (t interval); False: the clusters are.

    Examples
    --------
    >>> folds = [(np.array([1, 1, 0, 0], bool), np.array([0, 0, 1, 1])),
    ...          (np.array([1, 1, 1, 0], bool), np.array([2, 2, 3, 3]))]
    >>> f = FoldAccuracy(folds, "position")
    >>> f.estimate, f.values.tolist(), f.n_units
    (0.625, [0.5, 0.75], 4)
    >>> b = FoldAccuracy(folds, "held-out block", by_fold=True)
    >>> b.n_units, [round(x, 3) for x in b.ci95]
    (2, [0.0, 1.0])
    """

    def __init__(self, folds, unit: str, *, by_fold: bool = False):
        if isinstance(folds, str | np.ndarray) or not hasattr(folds, "__iter__"):
            raise TypeError(f"folds must be a sequence of (correct, clusters) pairs, got "
                            f"{type(folds).__name__}")
        folds = list(folds)
        for i, pair in enumerate(folds):
            if isinstance(pair, str) or not hasattr(pair, "__len__") or len(pair) != 2:
                raise TypeError(f"folds[{i}] must be a pair (correct, clusters), got "
                                f"{type(pair).__name__}")
        folds = [(_correct(f"folds[{i}]'s correct", c), _labels(f"folds[{i}]'s clusters", g))
                 for i, (c, g) in enumerate(folds)]
        if len(folds) < 2:
            raise ValueError(f"need at least two folds, got {len(folds)}")
        for i, (c, g) in enumerate(folds):
            if c.shape != g.shape:
                raise ValueError(f"folds[{i}]: clusters must have one label per recording "
                                 f"({c.size}), got shape {g.shape}")
        self.unit = _check_unit(unit)
        self.by_fold = check_bool("by_fold", by_fold)
        self.values = np.array([c.mean() for c, _ in folds])
        self.n_test = np.array([c.size for c, _ in folds])
        self.n_recordings = int(self.n_test.sum())
        self.spread = float(self.values.std(ddof=1))
        pooled_c = np.concatenate([c for c, _ in folds])
        pooled_g = np.concatenate([g for _, g in folds])
        self.pooled = ClusteredAccuracy.from_recordings(pooled_c, pooled_g, unit)
        self.recording_ci95 = self.pooled.recording_ci95
        if self.by_fold:
            f = self.values.size
            self.estimate = float(self.values.mean())
            half = float(student_t.ppf(0.975, f - 1)) * self.spread / math.sqrt(f)
            self.ci95 = (max(0.0, self.estimate - half), min(1.0, self.estimate + half))
            self.n_units = f
            self.method = METHOD_FOLDS.format(folds=f, unit=unit)
        else:
            self.estimate = self.pooled.estimate
            self.ci95 = self.pooled.ci95
            self.n_units = self.pooled.n_units
            self.method = self.pooled.method
            self.design_effect = self.pooled.design_effect

    def entries(self, name: str) -> dict:
        """As :meth:`ClusteredAccuracy.entries`, with ``name_folds`` and ``name_fold_std``."""
        name = _check_name(name)
        return {
            **_shared_entries(self, name),
            f"{name}_folds": self.values.tolist(),
            f"{name}_fold_std": self.spread,
            **({} if self.by_fold else {f"{name}_design_effect": self.design_effect}),
        }

    def __str__(self) -> str:
        return format_clustered(self) + f", {self.values.size} folds ± {percent(self.spread)}"


# ----------------------------------------------------------------- cluster bootstrap
def cluster_bootstrap(k, n, *, resamples: int = 2000, seed: int = 0, level: float = 0.95):
    """Percentile interval of ``sum k / sum n`` with whole clusters resampled.

    Each resample draws ``G`` clusters with replacement (Davison & Hinkley 1997, *Bootstrap
    Methods and their Application*, section 3.8) and takes the accuracy of what it drew; the
    draws are one ``(resamples, G)`` array of indices, so the cost is one gather and two sums.

    Parameters
    ----------
    k, n : array-like of int
        Right answers and recordings per cluster.
    resamples : int
        10 to ``10**6`` (each resample is a row of ``G`` indices held in memory).
    seed : int
        Seed of :func:`numpy.random.default_rng`; the indices are
        ``rng.integers(0, G, size=(resamples, G))``.
    level : float
        Coverage of the interval, in (0, 1).

    Returns
    -------
    (float, float)

    Examples
    --------
    >>> lo, hi = cluster_bootstrap([5, 0, 5, 3, 4, 2], [5] * 6, seed=1)
    >>> round(lo, 3), round(hi, 3)
    (0.333, 0.9)
    """
    k, n = _counts(k, n)
    resamples = check_int("resamples", resamples, minimum=10, maximum=MAX_RESAMPLES)
    check_in_range("level", level, 0.0, 1.0)
    rng = np.random.default_rng(check_int("seed", seed, minimum=0))
    pick = rng.integers(0, k.size, size=(resamples, k.size))
    stats = k[pick].sum(axis=1) / n[pick].sum(axis=1)
    tail = (1 - level) / 2
    lo, hi = np.quantile(stats, [tail, 1 - tail])
    return float(lo), float(hi)


# ----------------------------------------------------------------- paired comparisons
class PairedDifference:
    """Two classifiers' (or data sets') accuracies on the same recordings, compared in pairs.

    Every recording is tested under both conditions (the same fold, seed and position), so the
    difference is taken recording by recording and summed within each cluster:
    ``d_j = k_j^B - k_j^A``. The difference of accuracies is ``D = sum d_j / N``; its
    cluster-robust variance (Liang & Zeger 1986, *Biometrika* 73:13) is
    ``G / (G - 1) * sum_j (d_j - D n_j)^2 / N^2``, and its 95 % interval ``D ± q SE`` with
    ``q`` Student's 97.5 % quantile on ``G - 1`` degrees of freedom (1.96 for many clusters; a
    few clusters, such as five blocks, widen it as they should). The difference is *resolved*
    when that interval leaves out zero.

    ``detectable`` is the minimal detectable difference at 80 % power of this design
    (:func:`minimal_detectable_difference`): the smallest true change, simulated as recordings
    that change outcome in the resampled clusters, that this interval resolves in 80 % of
    repeats. It is positive even when both conditions classify every recording alike (a few
    recordings must change before a change is resolved), and it is a lower bound on what the
    design detects when real changes come clustered (the simulated ones are independent).
    ``detectable_clustered`` is the same for a change that comes as whole clusters, the most
    clustered (``changes="clusters"``): a real change needs a difference between the two.

    With ``by_fold`` the clusters are the folds of a split whose unit is the fold (the blocked
    split), and the accuracies are the folds' means, as :class:`FoldAccuracy` gives them with
    ``by_fold``: the difference is the mean of the folds' differences of accuracies,
    ``D = sum_f (k_f^B - k_f^A) / n_f / F``, its standard error their sample deviation over
    ``sqrt(F)``, the interval Student's on ``F - 1`` degrees of freedom. That is the formula
    above with each fold's accuracies in place of its counts and one in place of its size.

    Parameters
    ----------
    k_a, k_b, n : array-like of int
        Per cluster: right answers under A (the reference) and under B, recordings.
    unit : str
    by_fold : bool
        The clusters are folds, each weighing alike (see above).
    resamples, seed : int
        Of the power computation.

    Examples
    --------
    >>> p = PairedDifference([3, 3, 2, 3], [2, 1, 1, 2], [3, 3, 3, 3], "position")
    >>> round(p.difference, 4), p.resolved, p.direction
    (-0.4167, True, 'lower')
    """

    def __init__(self, k_a, k_b, n, unit: str, *, by_fold: bool = False, resamples: int = 4000,
                 seed: int = 0):
        k_a, n = _counts(k_a, n)
        k_b, _ = _counts(k_b, n)
        if k_a.size < 2:
            raise ValueError("a paired difference needs at least two clusters")
        self.unit = _check_unit(unit)
        self.by_fold = check_bool("by_fold", by_fold)
        resamples = check_int("resamples", resamples, minimum=10, maximum=MAX_RESAMPLES)
        seed = check_int("seed", seed, minimum=0)
        self.n_recordings = int(n.sum())
        self.n_units = int(n.size)
        # each cluster's right answers and weight: its counts, or (by fold) its accuracies
        a, b, w = (k_a / n, k_b / n, np.ones(n.size)) if self.by_fold else (k_a, k_b, n)
        self.accuracy_a = float(a.sum() / w.sum())
        self.accuracy_b = float(b.sum() / w.sum())
        d = (b - a).astype(float)
        self.difference = float(d.sum() / w.sum())
        self.se = _paired_se(d, w, self.difference)
        q = _quantile95(self.n_units)
        self.ci95 = (self.difference - q * self.se, self.difference + q * self.se)
        self.resolved = bool(self.ci95[0] > 0 or self.ci95[1] < 0)
        self.method = (METHOD_PAIRED_FOLDS.format(folds=self.n_units, unit=unit) if self.by_fold
                       else METHOD_PAIRED.format(unit=unit))
        self.detectable = _detectable(k_a, k_b, n, self.by_fold, 0.8, resamples, seed)
        self.detectable_clustered = _detectable(k_a, k_b, n, self.by_fold, 0.8, resamples,
                                                seed, whole=True)

    @property
    def identical(self) -> bool:
        """Whether every cluster has the same count right under both (nothing to resolve)."""
        return self.se == 0.0 and self.difference == 0.0

    @property
    def direction(self) -> str:
        """``"higher"``, ``"lower"`` (B against A) or ``"unresolved"``."""
        if not self.resolved:
            return "unresolved"
        return "higher" if self.difference > 0 else "lower"

    @classmethod
    def from_recordings(cls, correct_a, correct_b, clusters, unit: str, **kwargs):
        """From each recording's right/wrong under A and under B (the same recordings, in the
        same order) and its cluster (with ``by_fold``, its fold)."""
        correct_a, correct_b = np.asarray(correct_a), np.asarray(correct_b)
        if correct_a.shape != correct_b.shape:
            raise ValueError("correct_a and correct_b must hold the same recordings, got "
                             f"shapes {correct_a.shape} and {correct_b.shape}")
        k_a, n = cluster_counts(correct_a, clusters)
        k_b, _ = cluster_counts(correct_b, clusters)
        return cls(k_a, k_b, n, unit, **kwargs)

    def to_dict(self) -> dict:
        """``summary.json``'s entry: the two accuracies (``reference_estimate`` of A,
        ``estimate`` of B), the difference, its interval and method, the verdict
        (``resolved``, ``direction``) and the minimal detectable difference, and
        ``identical`` (every recording classified alike under both)."""
        return {
            "reference_estimate": self.accuracy_a,
            "estimate": self.accuracy_b,
            "difference": self.difference,
            "se": self.se,
            "ci95": list(self.ci95),
            "n_test": self.n_recordings,
            "unit": self.unit,
            "n_units": self.n_units,
            "method": self.method,
            "resolved": self.resolved,
            "direction": self.direction,
            "detectable_difference_80": self.detectable,
            "detectable_difference_80_clustered": self.detectable_clustered,
            "identical": self.identical,
        }

    def __str__(self) -> str:
        return format_difference(self)


def _quantile95(units: int) -> float:
    """Student's 97.5 % quantile on ``units - 1`` degrees of freedom."""
    return float(student_t.ppf(0.975, units - 1))


def _paired_se(d, n, difference) -> float:
    """Cluster-robust standard error of ``sum d / sum n`` (see :class:`PairedDifference`)."""
    g = d.size
    resid = d - difference * n
    return math.sqrt(g / (g - 1) * float(np.sum(resid**2))) / float(n.sum())


def minimal_detectable_difference(k_a, k_b, n, *, power: float = 0.8, resamples: int = 4000,
                                  seed: int = 0, by_fold: bool = False,
                                  changes: str = "recordings") -> float:
    """The smallest true paired difference this design resolves with probability ``power``.

    The power at a true difference ``delta`` is found by simulating the design under that
    alternative. Each resample draws whole clusters with replacement, as
    :func:`cluster_bootstrap` does, and keeps their paired noise, the centred differences
    ``r_j = d_j - D n_j``. The change itself is then added as recordings that change outcome:
    for a gain, each recording wrong under B turns right independently with probability
    ``p``, so a cluster gains ``f_j ~ Binomial(n_j - k_j^B, p)``; for a loss, each recording
    right under B turns wrong. ``p`` makes the expected change ``delta``, so ``delta`` runs
    over ``[0, 1 - accuracy_B]`` for a gain and ``[0, accuracy_B]`` for a loss. The resample is
    resolved when its difference clears ``q`` times its own cluster-robust standard error on
    the side of the change (``q`` and the standard error as in :class:`PairedDifference`). The
    smallest ``delta`` resolved in a ``power`` share of resamples is found by bisection to
    0.01 points, every step on the same draws (common random numbers), so the steps differ
    only by ``delta``; the larger of the gain's and the loss's is returned. A direction
    that cannot reach ``power`` even with every recording changed (B right on every recording
    leaves no gain) is left out; ``math.inf`` if neither can.

    Independent changes within a cluster are the most favourable way a change can come, the
    least clustered: if real changes come in groups (a whole position turning at once) the
    design detects less, so the result is a lower bound on the difference detected then.
    ``changes="clusters"`` simulates the other end, the most clustered change: each cluster
    turns whole (every recording wrong under B right, for a gain) with probability ``p``, and
    not at all otherwise; a real change between the two needs a difference between the two
    results. Even
    two conditions that classify every recording alike (every ``d_j = 0``) get a positive
    result: a handful of changed recordings is needed before any is resolved. For many
    clusters the result tends to ``(1.96 + 0.84) SE``, with ``SE`` the standard error under
    the alternative (the design's paired noise and the changed recordings' binomial spread).

    Parameters
    ----------
    k_a, k_b, n : array-like of int
        Per cluster, as in :class:`PairedDifference`.
    power : float
        In (0, 1).
    resamples, seed : int
        Of the resampling (:func:`numpy.random.default_rng`); ``resamples`` from 10 to
        ``10**6``.
    by_fold : bool
        The clusters are folds weighing alike, as in :class:`PairedDifference`: a fold's
        changed recordings count as a change of its accuracy, ``f_j / n_j``.
    changes : {"recordings", "clusters"}
        How the simulated change comes: recordings turning independently (the least
        clustered, a lower bound), or whole clusters turning at once (the most clustered).

    Returns
    -------
    float
        A difference of accuracies (a fraction).

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> n = np.full(200, 3)
    >>> k_a, k_b = rng.binomial(3, 0.6, 200), rng.binomial(3, 0.6, 200)
    >>> mdd = minimal_detectable_difference(k_a, k_b, n)
    >>> 0.05 < mdd < 0.15
    True

    Identical conditions still need changed recordings: a few, as a fraction of the 500
    (:class:`PairedDifference` resolves no fewer than four, each in its own position):

    >>> k = rng.binomial(5, 0.8, 100)
    >>> mdd = minimal_detectable_difference(k, k, np.full(100, 5))
    >>> round(500 * mdd, 1)  # recordings of the 500; four in four positions are resolved
    5.7

    The same change coming as whole positions needs many more recordings:

    >>> whole = minimal_detectable_difference(k, k, np.full(100, 5), changes="clusters")
    >>> whole > mdd
    True
    """
    k_a, n = _counts(k_a, n)
    k_b, _ = _counts(k_b, n)
    check_in_range("power", power, 0.0, 1.0)
    resamples = check_int("resamples", resamples, minimum=10, maximum=MAX_RESAMPLES)
    seed = check_int("seed", seed, minimum=0)
    whole = check_choice("changes", changes, ("recordings", "clusters")) == "clusters"
    return _detectable(k_a, k_b, n, check_bool("by_fold", by_fold), power, resamples, seed,
                       whole)


def _detectable(k_a, k_b, n, by_fold: bool, power: float, resamples: int, seed: int,
                whole: bool = False) -> float:
    """:func:`minimal_detectable_difference` of checked values (``whole``: the change comes
    as whole clusters)."""
    # a cluster's weight in the difference, and what one changed recording adds to it
    w = np.ones(n.size) if by_fold else n.astype(float)
    u = 1.0 / n if by_fold else np.ones(n.size)
    d = (k_b - k_a) * u
    resid = d - d.sum() / w.sum() * w
    resid[np.abs(resid) < 1e-12 * w.max()] = 0.0  # exactly 0 where d is proportional to w
    pick = np.random.default_rng(seed).integers(0, n.size, size=(resamples, n.size))
    design = _Resampled(resid, u, w, pick, whole)
    found = [design.detectable(sign, room, power, np.random.default_rng([seed, stream]))
             for sign, room, stream in ((1, n - k_b, 1), (-1, k_b, 2)) if room.sum() > 0]
    finite = [v for v in found if math.isfinite(v)]
    return max(finite) if finite else math.inf


class _Resampled:
    """The resamples of :func:`minimal_detectable_difference`: the clusters' paired noise
    ``r``, what one changed recording adds to a cluster's difference (``u``), the clusters'
    weights ``w``, each resample's cluster indices (``pick``, one row a resample), and the
    sums over each resample that its difference and standard error need."""

    #: The bisection stops when the bracket of the difference is this narrow (0.01 points).
    PRECISION = 1e-4

    def __init__(self, r, u, w, pick, whole: bool = False):
        self.r, self.u, self.w, self.pick, self.whole = r, u, w, pick, whole
        resamples, groups = pick.shape
        self.groups, self.q = groups, _quantile95(groups)
        times = np.bincount((pick + groups * np.arange(resamples)[:, None]).ravel(),
                            minlength=resamples * groups).reshape(resamples, groups) * 1.0
        # each resample's sums of r, r^2, r w, w^2 and w, from how often it drew each cluster
        *self.sums, self.total = (times @ np.stack([r, r * r, r * w, w * w, w], axis=1)).T

    def detectable(self, sign: int, room, power: float, rng) -> float:
        """The smallest change in direction ``sign`` (the recordings that can change: ``room``
        a cluster) resolved in a ``power`` share of resamples, ``math.inf`` if none is.

        Each resampled cluster (a cell) gets one uniform ``v``, and at probability ``p`` its
        changes are the ``v`` quantile of ``Binomial(room, p)``: exactly binomial, the same
        draws at every ``p`` and never fewer at a larger ``p`` (with ``whole``, its whole
        room when ``v > 1 - p``, none otherwise). The bisection keeps the cells'
        changes at both ends of its bracket and recomputes only the cells where they differ.
        """
        scale = float(np.sum(room * self.u)) / float(self.w.sum())  # the difference at p = 1
        p_hi = min(1.0, 1.25 * self._normal_guess(sign, room, scale, power) / scale)
        v = rng.random(self.pick.size)
        rooms, row = np.unique(room, return_inverse=True)
        cluster = self.pick.ravel()
        while True:
            none = 1 - p_hi if self.whole else binom.cdf(0, rooms, p_hi)[row[cluster]]
            live = np.flatnonzero(v > none)
            cells = _Cells(self, sign, cluster[live], live // self.groups, v[live], rooms, row)
            hi_changes = cells.changes(p_hi)
            if self._power(sign, cells.adds(hi_changes)) >= power:
                break
            if p_hi == 1.0:
                return math.inf
            p_hi = min(1.0, 2 * p_hi)
        lo, hi, base = 0.0, p_hi, np.zeros((3, self.total.size))  # base: the changes at lo
        lo_changes, act = np.zeros_like(hi_changes), np.arange(hi_changes.size)
        while (hi - lo) * scale > self.PRECISION:
            mid = (lo + hi) / 2
            mid_changes = cells.changes(mid, act)
            trial = base + cells.adds(mid_changes, act) - cells.adds(lo_changes[act], act)
            if self._power(sign, trial) >= power:
                hi, hi_changes[act] = mid, mid_changes
            else:
                lo, base, lo_changes[act] = mid, trial, mid_changes
            act = act[lo_changes[act] != hi_changes[act]]
        return hi * scale

    def _normal_guess(self, sign: int, room, scale: float, power: float) -> float:
        """Where to look: ``delta = k SE(delta)``, ``k = q + z_power``, ``SE(delta)^2`` the
        design's paired noise with the changes' expectation ``p room u`` added cluster by
        cluster, plus their binomial variance, a quadratic in ``delta`` (``scale`` if it has
        no root, where the changes' spread over clusters outgrows them)."""
        k2 = (self.q + float(norm.ppf(power))) ** 2
        g, total = self.groups, float(self.w.sum())
        spread = room * self.u / scale - self.w  # a cluster's expected change less its share
        a, b, c = (g / (g - 1) / total**2 * float(np.sum(x * y)) for x, y in
                   ((self.r, self.r), (2 * sign * self.r, spread), (spread, spread)))
        b += float(np.sum(room ** (2 if self.whole else 1) * self.u**2)) / (scale * total**2)
        if 1 - k2 * c <= 0:
            return scale
        return (k2 * b + math.sqrt((k2 * b) ** 2 + 4 * (1 - k2 * c) * k2 * a)) / (2 - 2 * k2 * c)

    def _power(self, sign: int, adds) -> float:
        """The share of resamples resolved with the changes ``adds`` (each resample's added
        difference, squares and cross products): its difference (noise signed so the change
        is positive) above ``q`` times its cluster-robust standard error."""
        s, ss, sw, sww = self.sums
        est = (sign * s + adds[0]) / self.total
        dev = (ss + adds[1]) - 2 * est * (sign * sw + adds[2]) + est * est * sww
        g = self.groups
        se = np.sqrt(np.maximum(dev, 0.0) * g / (g - 1)) / self.total
        return float(np.mean(est > self.q * se))


class _Cells:
    """The resampled clusters that change at all in one direction of
    :meth:`_Resampled.detectable`: each one's cluster, resample, uniform ``v``, and the row of
    its room in the distinct rooms ``rooms``."""

    def __init__(self, design: _Resampled, sign: int, cluster, resample, v, rooms, row):
        self.size, self.resample, self.v = design.total.size, resample, v
        self.whole = design.whole
        self.r, self.u, self.w = sign * design.r[cluster], design.u[cluster], design.w[cluster]
        self.rooms, self.row = rooms, row[cluster]

    def changes(self, p: float, at=slice(None)):
        """The cells' (those ``at``) changes at ``p``: ``v``'s quantile of
        ``Binomial(room, p)``, by one search in the rooms' distributions laid end to end (with
        ``whole``, the whole room when ``v > 1 - p``)."""
        if self.whole:
            return np.where(self.v[at] > 1 - p, self.rooms[self.row[at]], 0)
        top = int(self.rooms[-1])
        cdf = binom.cdf(np.arange(top + 1), self.rooms[:, None], p)  # [room, count]
        shift = 2 * np.arange(self.rooms.size)  # each room's above the last one's
        row = self.row[at]
        found = np.searchsorted((cdf + shift[:, None]).ravel(), shift[row] + self.v[at])
        return np.minimum(found - (top + 1) * row, self.rooms[row])

    def adds(self, changes, at=slice(None)):
        """What ``changes`` in the cells ``at`` add to each resample's difference, sum of
        squares and cross product with the weights: ``f u``, ``f u (2 r + f u)``, ``f u w``."""
        fu = changes * self.u[at]
        return np.stack([np.bincount(self.resample[at], weights=x, minlength=self.size)
                         for x in (fu, fu * (2 * self.r[at] + fu), fu * self.w[at])])


# ------------------------------------------------------------------------- formatting
def percent(x: float, digits: int = 1) -> str:
    """A fraction as a percentage: the one way every accuracy is printed.

    Rounds half away from zero on the decimal value of ``x`` (to 12 significant digits first,
    so that 0.8155 prints 81.6 whether it arrives as a float that is a hair below or above).

    Examples
    --------
    >>> percent(0.8155), percent(0.81549), percent(0.0)
    ('81.6 %', '81.5 %', '0.0 %')
    """
    x, digits = check_real("x", x), _check_digits(digits)
    return f"{_round_half_up(100 * x, digits):.{digits}f} %"


def points(x: float, digits: int = 1) -> str:
    """A difference of fractions in percentage points, signed.

    Examples
    --------
    >>> points(-0.104), points(0.05)
    ('-10.4 points', '+5.0 points')
    """
    x, digits = check_real("x", x), _check_digits(digits)
    v = _round_half_up(100 * x, digits)
    return f"{v:+.{digits}f} points"


def _check_digits(digits) -> int:
    """``digits`` if it is a whole number of decimals, 0 to 10 (the value is rounded from its
    twelve significant digits, so a percentage carries at most ten decimals)."""
    return check_int("digits", digits, minimum=0, maximum=10)


def _round_half_up(v: float, digits: int) -> float:
    """``v`` rounded to ``digits`` decimals, halves away from zero, on its 12-digit decimal."""
    from decimal import ROUND_HALF_UP, Decimal

    d = Decimal(f"{v:.12g}").quantize(Decimal(1).scaleb(-digits), rounding=ROUND_HALF_UP)
    return float(d)


def span(ci, digits: int = 1) -> str:
    """An interval's ends in percent without the unit: ``'76.0-90.5'``.

    Examples
    --------
    >>> span((0.7605, 0.905))
    '76.1-90.5'
    """
    if isinstance(ci, str) or not hasattr(ci, "__len__") or len(ci) != 2:
        raise TypeError(f"ci must be a pair (low, high), got {describe(ci)}")
    low, high = check_real("ci", ci[0]), check_real("ci", ci[1])
    if low > high:
        raise ValueError(f"ci must be (low, high) with low <= high, got {describe(ci)}")
    digits = _check_digits(digits)
    lo, hi = (f"{_round_half_up(100 * v, digits):.{digits}f}" for v in (low, high))
    return f"{lo}-{hi}"


def format_clustered(a) -> str:
    """An accuracy with its recordings, units and 95 % interval on the unit.

    Examples
    --------
    >>> format_clustered(ClusteredAccuracy([5, 0, 5, 3], [5, 5, 5, 5], "position"))
    '65.0 % (n = 20 in 4 positions, 95 % CI 15.5-94.9)'
    """
    if not isinstance(a, ClusteredAccuracy | FoldAccuracy):
        raise TypeError(f"a must be a ClusteredAccuracy or a FoldAccuracy, got {type(a).__name__}")
    unit = a.unit + ("s" if a.n_units != 1 and not a.unit.endswith("s") else "")
    return (f"{percent(a.estimate)} (n = {a.n_recordings} in {a.n_units} {unit}, "
            f"95 % CI {span(a.ci95)})")


def format_difference(p: PairedDifference) -> str:
    """A paired difference with its interval and the design's detectable differences
    (:func:`detectable_text`).

    Examples
    --------
    >>> p = PairedDifference([3, 3, 2, 3], [2, 1, 1, 2], [3] * 4, "position")
    >>> print(format_difference(p))  # doctest: +NORMALIZE_WHITESPACE
    -41.7 points (95 % CI -68.2 to -15.1, 4 positions; detectable at 80 % power:
    45.6 points spread over recordings, 46.5 by whole positions)
    """
    if not isinstance(p, PairedDifference):
        raise TypeError(f"p must be a PairedDifference, got {type(p).__name__}")
    lo, hi = (f"{_round_half_up(100 * v, 1):.1f}" for v in p.ci95)
    return (f"{points(p.difference)} (95 % CI {lo} to {hi}, {p.n_units} {p.unit}s; "
            f"detectable at 80 % power: "
            f"{detectable_text(p.detectable, p.detectable_clustered, p.unit)})")


def detectable_text(spread: float, clustered: float, unit: str) -> str:
    """The two detectable differences at 80 % power, a fraction each (``math.inf``: no change
    within reach): the change spread over recordings, the least clustered way, and coming as
    whole units, the most; a real change lies between.

    Examples
    --------
    >>> detectable_text(0.0065, 0.057, "position")
    '0.7 points spread over recordings, 5.7 by whole positions'
    """
    said = [f"{_round_half_up(100 * v, 1):.1f}" if math.isfinite(v) else "no change within reach"
            for v in (check_real("spread", spread, allow_inf=True),
                      check_real("clustered", clustered, allow_inf=True))]
    numbers = [i for i, s in enumerate(said) if s[0].isdigit()]
    if numbers:  # the unit once, after the first number
        said[numbers[0]] += " points"
    return f"{said[0]} spread over recordings, {said[1]} by whole {_check_unit(unit)}s"


def detectable_cell(spread: float, clustered: float) -> str:
    """The two detectable differences of :func:`detectable_text` as a table's cell, in points
    (the table's header names the unit and the two ends), ``math.inf`` as ``none within
    reach``.

    Examples
    --------
    >>> detectable_cell(0.067, 0.114), detectable_cell(0.01, math.inf)
    ('6.7 / 11.4', '1.0 / none within reach')
    """
    return " / ".join(f"{_round_half_up(100 * v, 1):.1f}" if math.isfinite(v)
                      else "none within reach"
                      for v in (check_real("spread", spread, allow_inf=True),
                                check_real("clustered", clustered, allow_inf=True)))


def cluster_mean_interval(values, clusters) -> dict:
    """The mean of a per-recording quantity (an error, cm) on its clusters: each cluster's
    mean, their mean, and Student's t interval over the clusters.

    Returns
    -------
    dict
        ``estimate``, ``ci95``, ``n_units``, ``n_test``, ``method``.

    Examples
    --------
    >>> r = cluster_mean_interval([1.0, 1.2, 3.0, 2.8, 2.0, 2.0], [0, 0, 1, 1, 2, 2])
    >>> round(r["estimate"], 3), r["n_units"], [round(x, 2) for x in r["ci95"]]
    (2.0, 3, [-0.24, 4.24])
    """
    v = check_array("values", values, ndim=1)
    g = _labels("clusters", clusters)
    if v.shape != g.shape:
        raise ValueError("values and clusters must be non-empty 1-D arrays of one shape, got "
                         f"{v.shape} and {g.shape}")
    _, inverse = np.unique(g, return_inverse=True)
    inverse = inverse.ravel()
    means = np.bincount(inverse, weights=v) / np.bincount(inverse)
    if means.size < 2:
        raise ValueError("need at least two clusters")
    centre = float(means.mean())
    half = _quantile95(means.size) * float(means.std(ddof=1)) / math.sqrt(means.size)
    return {"estimate": centre, "ci95": [centre - half, centre + half],
            "n_units": int(means.size), "n_test": int(v.size),
            "method": f"t interval over the {means.size} positions' mean errors"}
