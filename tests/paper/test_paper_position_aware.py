"""The position-aware material classifier: its standardisation against a direct computation,
and the distance it reads a recording at."""

import numpy as np
import pytest
from scipy.interpolate import interp1d

from ebantenna.paper.position_aware import (
    SPREAD_FLOOR,
    PositionAwareMaterialClassifier,
    classify_materials_position_aware,
    estimate_distances,
)
from ebantenna.paper.splits import grouped_split


def _data(seed=0):
    rng = np.random.default_rng(seed)
    d = np.tile(np.repeat(np.linspace(0.02, 0.38, 19), 3), 2)
    y = np.repeat(["al", "pvc"], d.size // 2)
    bins = np.arange(40)
    X = np.exp(-0.5 * ((bins - 60 * d[:, None]) / 2) ** 2)
    X += 0.2 * np.exp(-0.5 * (bins - 30 - 2 * (y == "pvc")[:, None]) ** 2)
    return d, y, X + 0.02 * rng.random(X.shape)


def test_standardisation_is_the_interpolated_mean_and_scale():
    d, y, X = _data()
    clf = PositionAwareMaterialClassifier().fit(np.column_stack([d, X]), y)
    grid = np.unique(d)
    mean = np.array([X[d == g].mean(axis=0) for g in grid])
    spread = np.array([X[d == g].std(axis=0) for g in grid])
    spread = np.maximum(spread, SPREAD_FLOOR * spread.mean())
    scale = np.sqrt(spread**2 + mean.std(axis=0) ** 2)
    at = np.array([0.0, 0.02, 0.111, 0.25, 0.38, 0.5])  # beyond both ends: held constant
    inside = np.clip(at, grid[0], grid[-1])
    mu = interp1d(grid, mean, axis=0)(inside)
    s = interp1d(grid, scale, axis=0)(inside)
    rows = X[:6]
    z = clf.standardise(np.column_stack([at, rows]))
    # the same sums in another order: a few roundings of values of order 1 over scales >= 0.01
    np.testing.assert_allclose(z, (rows - mu) / s, rtol=1e-12, atol=1e-12)


def test_distances_come_from_the_peaks_and_fall_back_to_the_dominant_frequency():
    d = np.repeat(np.linspace(0.05, 0.35, 7), 2)
    peaks = np.column_stack([10 + 30 * d, 80 - 50 * d])
    dominant = 10 + 30 * d
    peaks[1, :] = np.nan  # fewer than two peaks in this test row
    train, rows = np.arange(0, 14, 2), np.arange(1, 14, 2)
    est = estimate_distances(peaks, dominant, d, train, rows)
    # both curves are linear in d and the estimators interpolate monotone cubics through the
    # calibration medians: exact up to the two-mode grid's parabolic refinement
    np.testing.assert_allclose(est, d[rows], atol=1e-4)


def test_position_aware_classifier_on_held_out_positions():
    d, y, X = _data(1)
    peaks = np.column_stack([10 + 30 * d, 80 - 50 * d])
    split = grouped_split(d, every=4, seed=0)
    res = classify_materials_position_aware(X, y, d, peaks, peaks[:, 0], split)
    assert res.method == "position-aware" and res.labels == ("al", "pvc")
    assert res.confusions["test"].sum() == split[1].size
    assert res.accuracies["test"] >= 0.9  # the 2-bin line stands 10 noise levels high


def test_bad_input():
    d, y, X = _data()
    with pytest.raises(ValueError, match="column 0"):
        PositionAwareMaterialClassifier().fit(d[:, None], y)
    with pytest.raises(ValueError, match="at least 2 rows"):
        PositionAwareMaterialClassifier().fit(np.column_stack([np.arange(d.size), X]), y)
    with pytest.raises(ValueError, match="two materials"):
        PositionAwareMaterialClassifier().fit(np.column_stack([d, X]), np.full(d.size, "al"))
    with pytest.raises(ValueError, match="one entry per row"):
        classify_materials_position_aware(X, y[:-1], d, X[:, :2], X[:, 0], ([0], [1]))
    peaks = np.column_stack([10 + 30 * d, 80 - 50 * d])
    split = grouped_split(d, every=4, seed=0)
    # a material missing from labels would drop its rows from the matrices, not from the tested
    with pytest.raises(ValueError, match=r"labels must list every material; missing \['pvc'\]"):
        classify_materials_position_aware(X, y, d, peaks, peaks[:, 0], split,
                                          labels=["al", "PVC"])
