"""Splits by contact position: no position on both sides, the same rows for the same seed."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ebantenna.paper.splits import SPLITS, blocked_split, grouped_split, random_split, split_rows


@st.composite
def recordings(draw):
    """Nominal positions on a grid (some repeated), with labels, in a shuffled row order."""
    n_positions = draw(st.integers(10, 40))
    step = draw(st.sampled_from([0.005, 0.01, 0.05]))
    reps = draw(st.integers(1, 4))
    seed = draw(st.integers(0, 2**16))
    rng = np.random.default_rng(seed)
    positions = np.repeat(step * np.arange(1, n_positions + 1), reps)
    labels = np.tile(["al", "pvc"], positions.size)[: positions.size]
    order = rng.permutation(positions.size)
    return positions[order], labels[order], draw(st.integers(0, 1000))


@settings(max_examples=40, deadline=None)
@given(recordings())
def test_grouped_and_blocked_never_share_a_position(data):
    positions, _, seed = data
    n = positions.size
    for train, test in (
        grouped_split(positions, every=5, seed=seed),
        blocked_split(positions, test_fraction=0.2, seed=seed),
    ):
        # a partition of the rows ...
        np.testing.assert_array_equal(np.sort(np.concatenate([train, test])), np.arange(n))
        assert train.size > 0 and test.size > 0
        # ... with no nominal position on both sides
        assert not set(positions[train].tolist()) & set(positions[test].tolist())


@settings(max_examples=40, deadline=None)
@given(recordings())
def test_blocked_holds_out_consecutive_positions_and_grouped_every_fifth(data):
    positions, _, seed = data
    grid = np.unique(positions)
    _, test = blocked_split(positions, test_fraction=0.2, seed=seed)
    held = np.flatnonzero(np.isin(grid, positions[test]))
    np.testing.assert_array_equal(held, np.arange(held[0], held[0] + held.size))
    assert held.size == min(int(np.ceil(0.2 * grid.size)), grid.size - 1)
    _, test = grouped_split(positions, every=5, seed=seed)
    held = np.flatnonzero(np.isin(grid, positions[test]))
    assert np.all(np.diff(held) == 5) and held[0] < 5


@settings(max_examples=20, deadline=None)
@given(recordings())
def test_every_split_is_deterministic_per_seed(data):
    positions, labels, seed = data
    for kind in SPLITS:
        a = split_rows(kind, labels, positions, seed=seed)
        b = split_rows(kind, labels, positions, seed=seed)
        for x, y in zip(a, b, strict=True):
            np.testing.assert_array_equal(x, y)


def test_the_seed_moves_the_held_out_positions():
    positions = np.repeat(np.arange(1, 41) / 100, 2)
    held = {tuple(np.unique(positions[blocked_split(positions, seed=s)[1]])) for s in range(20)}
    assert len(held) > 1
    held = {tuple(np.unique(positions[grouped_split(positions, seed=s)[1]])) for s in range(20)}
    assert len(held) > 1


def test_random_split_is_the_papers_stratified_80_20():
    labels = np.repeat(["al", "brass", "pvc", "steel", "wood"], 20)
    train, test = random_split(labels, seed=0)
    assert test.size == 20
    assert all(np.sum(labels[test] == m) == 4 for m in np.unique(labels))


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: grouped_split([0.1, 0.1, 0.1]), "at least 2 distinct"),
        (lambda: grouped_split([0.1, 0.2, 0.3], every=4), "every must be at most"),
        (lambda: grouped_split([0.1, 0.2, 0.3], every=1), "every"),
        (lambda: blocked_split([0.1, 0.2], test_fraction=1.5), "test_fraction"),
        (lambda: split_rows("shuffled", [0, 1], [0.1, 0.2]), "kind"),
        (lambda: grouped_split([0.1, np.nan, 0.3]), "positions"),
        # above 2/3 the rounded step is 1: every position would be held out (it gave 0.5)
        (lambda: split_rows("grouped", np.zeros(6), np.arange(6.0), test_fraction=0.7),
         "test_fraction must be at most 2/3"),
    ],
)
def test_bad_input_names_the_parameter(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_the_grouped_split_holds_out_the_share_of_its_rounded_step():
    positions = np.repeat(np.arange(12.0), 2)
    for fraction, every in ((0.2, 5), (0.3, 3), (0.5, 2), (2 / 3, 2)):
        test = split_rows("grouped", np.zeros(24), positions, test_fraction=fraction)[1]
        assert np.unique(positions[test]).size in (12 // every, -(-12 // every)), fraction


@pytest.mark.parametrize("kind", ["random", "grouped", "blocked"])
def test_the_folds_test_every_recording_exactly_once(kind):
    from ebantenna.paper.splits import split_folds

    pos = np.repeat(np.arange(1, 24) / 100, 3)  # 23 positions, 3 recordings each
    y = np.tile(["al", "pvc", "steel"], 23)
    folds = split_folds(kind, y, pos, seed=3)
    tested = np.concatenate([test for _, test in folds])
    assert len(folds) == 5 and np.array_equal(np.sort(tested), np.arange(pos.size))
    for train, test in folds:
        assert np.array_equal(np.union1d(train, test), np.arange(pos.size))
        if kind != "random":  # whole positions, never on both sides
            assert not set(pos[train]) & set(pos[test])
        if kind == "blocked":  # one contiguous run of the sorted grid
            grid = np.unique(pos)
            held = np.flatnonzero(np.isin(grid, pos[test]))
            assert np.array_equal(held, np.arange(held[0], held[-1] + 1))


def test_the_first_grouped_fold_is_the_split_seed_own():
    from ebantenna.paper.splits import grouped_split, split_folds

    pos = np.repeat(np.arange(1, 24) / 100, 2)
    y = np.tile(["al", "pvc"], 23)
    for seed in range(4):
        first = split_folds("grouped", y, pos, seed=seed)[0]
        assert np.array_equal(first[1], grouped_split(pos, every=5, seed=seed)[1])
