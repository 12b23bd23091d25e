"""Counts, intervals and spreads: what the arithmetic guarantees."""

import numpy as np
import pytest

from ebantenna.ml.metrics import accuracy_interval
from ebantenna.paper.splits import distinct_split_seeds, split_rows
from ebantenna.paper.uncertainty import (
    accuracy_entries,
    correct_count,
    difference_resolved,
    interval,
    resolvable_difference,
    seed_spread,
)


@pytest.mark.parametrize("n", [1, 7, 80, 240, 2000])
def test_every_count_round_trips_and_its_interval_holds_it(n):
    for k in range(0, n + 1, max(1, n // 13)):
        a = k / n
        assert correct_count(a, n) == k
        lo, hi = interval(a, n)
        assert (lo, hi) == accuracy_interval(k, n)
        # the bounds carry the rounding of a square root and a division: a few ulps of 1
        assert lo - 4e-16 <= a <= hi + 4e-16


def test_an_accuracy_that_is_no_count_is_refused():
    with pytest.raises(ValueError, match="not a count"):
        correct_count(0.5, 7)


def test_entries_by_key_and_none():
    e = accuracy_entries("a", {"x": 0.25, "y": 1.0}, {"x": 4, "y": 3})
    assert e["a_n_test"] == {"x": 4, "y": 3}
    assert e["a_ci95"]["y"][1] == 1.0
    assert accuracy_entries("b", None, 10) == {"b": None, "b_n_test": None, "b_ci95": None}


def test_resolvable_difference_is_two_standard_deviations_of_the_difference():
    # Var(a - b) = 2 p (1 - p) / n for two independent binomial proportions at p
    p, n = 0.65, 240
    assert resolvable_difference(p, n) == pytest.approx(2 * np.sqrt(2 * p * (1 - p) / n))
    d = resolvable_difference(0.6, n)
    assert difference_resolved(0.6 + d / 2 + 1e-3, 0.6 - d / 2 - 1e-3, n)
    assert not difference_resolved(0.6 + d / 2 - 1e-3, 0.6 - d / 2 + 1e-3, n)


def test_seed_spread_is_mean_and_sample_deviation():
    s = seed_spread(lambda seed: ((seed % 3) / 4, 4), [0, 1, 2, 3])
    assert s.mean == pytest.approx(np.mean([0, 0.25, 0.5, 0]))
    assert s.std == pytest.approx(np.std([0, 0.25, 0.5, 0], ddof=1))
    with pytest.raises(ValueError):
        seed_spread(lambda seed: (0.5, 2), [0])


@pytest.mark.parametrize("kind", ["random", "grouped", "blocked"])
def test_distinct_split_seeds_give_distinct_test_sets(kind):
    pos = np.repeat(np.arange(1, 21) / 100, 3)
    y = np.tile(["al", "pvc", "steel"], 20)
    seeds = distinct_split_seeds(kind, y, pos, seed=3, count=5)
    assert seeds[0] == 3 and len(seeds) == 5
    tests = [tuple(split_rows(kind, y, pos, seed=s)[1]) for s in seeds]
    assert len(set(tests)) == 5
    if kind == "grouped":  # five offsets of one position in five: every row tested once
        assert sorted(np.concatenate(tests).tolist()) == list(range(60))


def test_too_few_distinct_splits_are_refused():
    pos = np.repeat(np.arange(1, 11) / 100, 2)
    y = np.tile(["al", "pvc"], 10)
    with pytest.raises(ValueError, match="distinct grouped splits"):
        distinct_split_seeds("grouped", y, pos, count=6, search=200)
