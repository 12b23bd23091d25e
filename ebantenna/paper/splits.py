"""Train/test splits of a data set of recordings taken at a few contact positions.

The paper splits its recordings at random (80/20, section 4.3). Its recordings come in groups:
25 recordings at each of 79 nominal contact positions 5 mm apart, per material. Recordings at
one position are near copies of each other, and those at neighbouring positions differ only a
little. A random split therefore puts, for almost every test recording, a near copy of it in the
training set: the test then measures how well a classifier *recognises* a position it has seen,
not how well it tells the material at a position it has not. Any classifier looks better on
such a split than it will on the rig, where the next contact falls wherever it falls.

Three splits, from the most to the least flattering:

``random``
    Recordings at random, stratified by material (the paper's split).
``grouped``
    Whole nominal positions held out, interleaved: every ``every``-th distinct position (from an
    offset drawn from the seed) goes to the test set with all its recordings. The classifier must
    interpolate between positions it has seen on both sides.
``blocked``
    A contiguous range of positions held out (its start drawn from the seed): the classifier must
    bridge a stretch of the probe it never saw.

:func:`split_folds` gives every fold of a split (each recording tested exactly once): a result
is reported over all of them, never one fold as the result. Every split returns sorted row
indices ``(train, test)``; the grouped and blocked splits never
put one nominal position on both sides. Group by the *nominal* position (``Dataset.contact``),
not the realised one (``Dataset.contact_true``), which scatters around it.
"""

from __future__ import annotations

import math

import numpy as np
from sklearn.model_selection import train_test_split

from .._validate import check_array, check_choice, check_in_range, check_int

__all__ = [
    "SPLITS", "random_split", "grouped_split", "blocked_split", "split_rows",
    "distinct_split_seeds", "split_folds", "FOLDS",
]  # fmt: skip

#: Folds of every split reported over all its folds: five, the paper's 20 % test share.
FOLDS = 5

#: The splits, from the most to the least flattering.
SPLITS = ("random", "grouped", "blocked")

#: Largest seed of a split: scikit-learn's ``random_state`` takes 0 ... 2**32 - 1.
MAX_SPLIT_SEED = 2**32 - 1

#: Most seeds :func:`distinct_split_seeds` tries (a split takes about 0.1 ms: seconds at most).
MAX_SEARCH = 100_000


def _labels(labels, test_fraction=None, folds=None) -> np.ndarray:
    """``labels`` as a 1-D array of at least 2 rows, with rows enough for a stratified split of
    ``test_fraction`` (every class twice, and as many rows as classes on either side) or into
    ``folds`` (a class as large as ``folds``), else a ValueError naming it."""
    y = np.asarray(labels)
    if y.ndim != 1 or y.size < 2:
        raise ValueError(f"labels must be 1-D with at least 2 rows, got shape {y.shape}")
    if y.dtype.kind not in "iuUSO" or (y.dtype.kind == "O" and not all(
            isinstance(v, str | int | np.integer) and not isinstance(v, bool) for v in y)):
        raise TypeError(f"labels must be class names (str) or integers, got dtype {y.dtype}")
    classes, counts = np.unique(y, return_counts=True)
    if test_fraction is not None:
        n_test = math.ceil(test_fraction * y.size)
        if counts.min() < 2 or min(n_test, y.size - n_test) < classes.size:
            raise ValueError(
                f"labels: a stratified split of test_fraction={test_fraction:g} needs every "
                f"class twice and as many rows as classes ({classes.size}) on each side; "
                f"{y.size} rows, the rarest class {classes[counts.argmin()]!r} has "
                f"{counts.min()}, {y.size - n_test} would train and {n_test} test")
    if folds is not None and counts.max() < folds:  # (scikit-learn's own limit, in its words)
        raise ValueError(f"labels: {folds} stratified folds need a class with {folds} rows at "
                         f"least; the largest, {classes[counts.argmax()]!r}, has "
                         f"{counts.max()}")
    return y


def _positions(positions) -> tuple[np.ndarray, np.ndarray]:
    """The distinct nominal positions and each row's index among them."""
    p = check_array("positions", positions, ndim=1)
    grid, inverse = np.unique(p, return_inverse=True)
    if grid.size < 2:
        raise ValueError(
            f"positions must hold at least 2 distinct contact positions, got {grid.size}"
        )
    return grid, inverse


def _rows(test_mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return np.flatnonzero(~test_mask), np.flatnonzero(test_mask)


def random_split(labels, *, test_fraction: float = 0.2, seed: int = 0):
    """Recordings split at random, stratified by label (the paper's 80/20).

    Parameters
    ----------
    labels : array-like of shape (n,)
        Class of each recording (the strata).
    test_fraction : float
        Share of the recordings in the test set, in (0, 1).
    seed : int
        Seed of the split, 0 ... ``MAX_SPLIT_SEED`` (2**32 - 1).

    Returns
    -------
    train, test : ndarray of int
        Sorted row indices.

    Examples
    --------
    >>> train, test = random_split(["al", "pvc"] * 5, test_fraction=0.2, seed=0)
    >>> train.size, test.size
    (8, 2)
    """
    test_fraction = check_in_range("test_fraction", test_fraction, 0.0, 1.0)
    seed = check_int("seed", seed, minimum=0, maximum=MAX_SPLIT_SEED)
    y = _labels(labels, test_fraction=test_fraction)
    train, test = train_test_split(
        np.arange(y.size), test_size=test_fraction, random_state=seed, stratify=y
    )
    return np.sort(train), np.sort(test)


def grouped_split(positions, *, every: int = 5, seed: int = 0):
    """Whole nominal positions held out, interleaved: every ``every``-th one goes to the test.

    Parameters
    ----------
    positions : array-like of shape (n,)
        Nominal contact position of each recording, m.
    every : int
        One distinct position in ``every`` is held out (5: a fifth of the positions, the paper's
        test share).
    seed : int
        Picks the offset of the first held-out position, in ``[0, every)``.

    Returns
    -------
    train, test : ndarray of int
        Sorted row indices; no position has rows on both sides.

    Examples
    --------
    >>> pos = np.repeat([0.05, 0.10, 0.15, 0.20, 0.25, 0.30], 2)
    >>> train, test = grouped_split(pos, every=3, seed=0)
    >>> sorted(set(pos[test].tolist()))
    [0.05, 0.2]
    """
    grid, inverse = _positions(positions)
    every = check_int("every", every, minimum=2)
    if every > grid.size:
        raise ValueError(
            f"every must be at most the number of distinct positions ({grid.size}), got {every}"
        )
    seed = check_int("seed", seed, minimum=0)
    offset = int(np.random.default_rng([seed, 0x5917]).integers(every))
    held = np.zeros(grid.size, dtype=bool)
    held[offset::every] = True
    return _rows(held[inverse])


def blocked_split(positions, *, test_fraction: float = 0.2, seed: int = 0):
    """A contiguous range of nominal positions held out.

    Parameters
    ----------
    positions : array-like of shape (n,)
        Nominal contact position of each recording, m.
    test_fraction : float
        Share of the distinct positions held out, in (0, 1); rounded up to a whole number of
        positions, and at least one position stays for training.
    seed : int
        Picks where the held-out range starts (any start that fits, each equally likely).

    Returns
    -------
    train, test : ndarray of int
        Sorted row indices; the test positions are consecutive in the sorted grid.

    Examples
    --------
    >>> pos = np.repeat(np.arange(1, 11) / 100, 3)  # 1 ... 10 cm, 3 recordings each
    >>> train, test = blocked_split(pos, test_fraction=0.2, seed=0)
    >>> held = sorted(set(pos[test].tolist()))
    >>> len(held), round(held[1] - held[0], 9), test.size
    (2, 0.01, 6)
    """
    grid, inverse = _positions(positions)
    check_in_range("test_fraction", test_fraction, 0.0, 1.0)
    seed = check_int("seed", seed, minimum=0)
    width = min(math.ceil(test_fraction * grid.size), grid.size - 1)
    start = int(np.random.default_rng([seed, 0xB10C]).integers(grid.size - width + 1))
    held = np.zeros(grid.size, dtype=bool)
    held[start : start + width] = True
    return _rows(held[inverse])


def split_rows(kind: str, labels, positions, *, seed: int = 0, test_fraction: float = 0.2):
    """One of :data:`SPLITS` by name, with the test share the paper used.

    ``grouped`` holds out every ``round(1 / test_fraction)``-th position: the share held out is
    that of the rounded step (0.3 holds out every third position), and ``test_fraction`` above
    2/3 (a step of 1, every position) is refused.

    Parameters
    ----------
    kind : {"random", "grouped", "blocked"}
        Which split.
    labels : array-like of shape (n,)
        Class of each recording (the random split's strata).
    positions : array-like of shape (n,)
        Nominal contact position of each recording, m.
    seed : int
        Seed of the split.
    test_fraction : float
        Share of the recordings (random) or of the positions (grouped, blocked) held out.

    Returns
    -------
    train, test : ndarray of int

    Examples
    --------
    >>> pos = np.repeat(np.arange(1, 11) / 100, 2)
    >>> y = np.tile(["al", "pvc"], 10)
    >>> [split_rows(k, y, pos)[1].size for k in SPLITS]
    [4, 4, 4]
    """
    check_choice("kind", kind, SPLITS)
    if np.shape(labels)[:1] != np.shape(positions)[:1]:
        raise ValueError(f"labels and positions must have one entry per recording, got "
                         f"{np.shape(labels)[:1]} and {np.shape(positions)[:1]}")
    if kind == "random":
        return random_split(labels, test_fraction=test_fraction, seed=seed)
    if kind == "grouped":
        check_in_range("test_fraction", test_fraction, 0.0, 1.0)
        if round(1 / test_fraction) < 2:  # every position held out: nothing left to train on
            raise ValueError(f"test_fraction must be at most 2/3 for the grouped split (it holds "
                             f"out every round(1/test_fraction)-th position, at least every "
                             f"second), got {test_fraction!r}")
        return grouped_split(positions, every=round(1 / test_fraction), seed=seed)
    return blocked_split(positions, test_fraction=test_fraction, seed=seed)


def distinct_split_seeds(kind: str, labels, positions, *, seed: int = 0, count: int = 5,
                         search: int = 1000) -> tuple[int, ...]:
    """``count`` split seeds from ``seed`` upward whose test sets all differ.

    The grouped split draws only an offset among ``every`` (five) from its seed, and the
    blocked split a start among a few, so consecutive seeds can repeat a split. Repeating an
    accuracy over seeds measures its uncertainty only if the splits differ: the seeds are taken
    in order from ``seed`` (which always comes first), skipping any whose test set was seen.
    For the grouped split with ``count = every`` the test sets are the five interleaved folds:
    every recording is tested exactly once.

    Parameters
    ----------
    kind, labels, positions
        As in :func:`split_rows`.
    seed : int
        The first seed.
    count : int
        How many seeds.
    search : int
        How many seeds to try at most (up to ``MAX_SEARCH``, 100,000); fewer distinct splits than
        ``count`` raise.

    Returns
    -------
    tuple of int

    Examples
    --------
    >>> pos = np.repeat(np.arange(1, 11) / 100, 2)
    >>> y = np.tile(["al", "pvc"], 10)
    >>> seeds = distinct_split_seeds("grouped", y, pos, count=5)
    >>> seeds[0], len({tuple(split_rows("grouped", y, pos, seed=s)[1]) for s in seeds})
    (0, 5)
    """
    seed = check_int("seed", seed, minimum=0, maximum=MAX_SPLIT_SEED)
    search = check_int("search", search, minimum=1, maximum=MAX_SEARCH)
    count = check_int("count", count, minimum=1, maximum=search)
    seen, seeds = set(), []
    for s in range(seed, seed + search):
        test = tuple(split_rows(kind, labels, positions, seed=s)[1].tolist())
        if test not in seen:
            seen.add(test)
            seeds.append(s)
            if len(seeds) == count:
                return tuple(seeds)
    raise ValueError(
        f"only {len(seeds)} distinct {kind} splits among seeds {seed} ... {seed + search - 1}; "
        f"asked for count={count}"
    )


def split_folds(kind: str, labels, positions, *, folds: int = FOLDS, seed: int = 0) -> list:
    """Every fold of a split: ``folds`` test sets that together hold every recording once.

    ``grouped``
        Fold ``i`` holds out every ``folds``-th distinct position from offset ``i`` (the
        interleaved folds); the first fold is the one :func:`grouped_split` draws from
        ``seed`` with ``every=folds``, the others follow in order of their offset.
    ``blocked``
        The sorted distinct positions cut into ``folds`` contiguous blocks as equal as can be
        (``numpy.array_split``), from the hinge outwards.
    ``random``
        A stratified ``folds``-fold partition of the recordings, shuffled by ``seed``
        (scikit-learn's ``StratifiedKFold``).

    Parameters
    ----------
    kind : {"random", "grouped", "blocked"}
    labels, positions : array-like of shape (n,)
        As in :func:`split_rows`.
    folds : int
        How many folds (at least 2, at most the number of distinct positions).
    seed : int

    Returns
    -------
    list of (ndarray, ndarray)
        ``(train, test)`` sorted row indices per fold.

    Examples
    --------
    >>> pos = np.repeat(np.arange(1, 11) / 100, 2)
    >>> y = np.tile(["al", "pvc"], 10)
    >>> tests = [t for _, t in split_folds("blocked", y, pos, folds=3)]
    >>> [sorted(set((100 * pos[t]).round().astype(int).tolist())) for t in tests]
    [[1, 2, 3, 4], [5, 6, 7], [8, 9, 10]]
    >>> sorted(np.concatenate([t for _, t in split_folds("grouped", y, pos)]).tolist()) == list(
    ...     range(20))
    True
    """
    check_choice("kind", kind, SPLITS)
    seed = check_int("seed", seed, minimum=0, maximum=MAX_SPLIT_SEED)
    folds = check_int("folds", folds, minimum=2)
    if kind == "random":
        from sklearn.model_selection import StratifiedKFold

        y = _labels(labels, folds=folds)
        cv = StratifiedKFold(n_splits=folds, shuffle=True, random_state=seed)
        return [(np.sort(a), np.sort(b)) for a, b in cv.split(np.zeros(y.size), y)]
    grid, inverse = _positions(positions)
    if folds > grid.size:
        raise ValueError(
            f"folds must be at most the number of distinct positions ({grid.size}), got {folds}"
        )
    if kind == "grouped":
        first = int(np.random.default_rng([seed, 0x5917]).integers(folds))
        out = []
        for offset in [first, *(o for o in range(folds) if o != first)]:
            held = np.zeros(grid.size, dtype=bool)
            held[offset::folds] = True
            out.append(_rows(held[inverse]))
        return out
    out = []
    for block in np.array_split(np.arange(grid.size), folds):
        held = np.zeros(grid.size, dtype=bool)
        held[block] = True
        out.append(_rows(held[inverse]))
    return out
