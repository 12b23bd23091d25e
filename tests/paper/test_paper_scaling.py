"""The feature scale comes from the training rows only: what the test rows hold cannot change
what is learnt."""

import numpy as np
import pytest

from ebantenna.paper import experiments
from ebantenna.paper.position_aware import classify_materials_position_aware
from ebantenna.paper.protocol import normalise_by_max


def _data(seed=0):
    rng = np.random.default_rng(seed)
    y = np.repeat(["al", "pvc", "steel"], 30)
    d = np.tile(np.linspace(0.02, 0.30, 10).repeat(3), 3)
    X = rng.random((90, 12)) + 2.0 * (y[:, None] == ["al", "pvc", "steel"]).repeat(4, axis=1)
    return X, y, d


def test_normalise_by_max_takes_the_peak_of_the_given_rows():
    X, _, _ = _data()
    rows = np.arange(10)
    out = normalise_by_max(X, rows)
    assert np.abs(out[rows]).max() == pytest.approx(1.0, rel=1e-15)  # one division, one rounding
    np.testing.assert_array_equal(normalise_by_max(X), normalise_by_max(X, np.arange(90)))
    with pytest.raises(ValueError, match="at least one row"):
        normalise_by_max(X, [])


def _blown_up(X, test):
    """The same features with the test rows a thousand times larger."""
    X2 = X.copy()
    X2[test] *= 1e3
    return X2


def test_svm_learns_the_same_whatever_the_test_rows_hold():
    X, y, _ = _data()
    test = np.arange(0, 90, 5)
    split = (np.setdiff1d(np.arange(90), test), test)
    a = experiments.classify_materials_svm(X, y, split=split, gamma="scale")
    b = experiments.classify_materials_svm(_blown_up(X, test), y, split=split, gamma="scale")
    np.testing.assert_array_equal(a.confusions["train"], b.confusions["train"])


def test_ann_learns_the_same_whatever_the_test_rows_hold():
    X, y, _ = _data()
    from ebantenna.paper.protocol import three_way_split

    _, _, test = three_way_split(90, (0.7, 0.15, 0.15), 0, stratify=y)
    kw = dict(hidden_layer_sizes=(4,), max_iter=30, seed=0)
    a = experiments.classify_materials_ann(X, y, **kw)
    b = experiments.classify_materials_ann(_blown_up(X, test), y, **kw)
    for k in ("train", "validation"):
        np.testing.assert_array_equal(a.confusions[k], b.confusions[k])
    np.testing.assert_array_equal(a.model.coefs_[0], b.model.coefs_[0])


def test_position_aware_learns_the_same_whatever_the_test_rows_hold():
    X, y, d = _data()
    test = np.flatnonzero(np.isin(d, np.unique(d)[::4]))
    train = np.setdiff1d(np.arange(90), test)
    peaks = np.column_stack([10 + 30 * d, 80 - 50 * d])
    a = classify_materials_position_aware(X, y, d, peaks, peaks[:, 0], (train, test))
    b = classify_materials_position_aware(_blown_up(X, test), y, d, peaks, peaks[:, 0],
                                          (train, test))
    np.testing.assert_array_equal(a.confusions["train"], b.confusions["train"])
