"""The mode-curve classifier on curves whose answer is known, and on a split with gaps."""

import numpy as np
import pytest

from ebantenna.paper.mode_curves import ModeCurveClassifier, classify_materials_by_mode_curves

SCALE = {"al": 1.0, "brass": 0.97, "pvc": 0.9}  # each material's curves: the same shape, scaled


def _curves(d, names):
    """Two modes linear in the distance (PCHIP reproduces them exactly), scaled per material."""
    s = np.array([SCALE[n] for n in names])[:, None]
    return np.column_stack([20 + 30 * d, 120 - 60 * d]) * s


def _calibration(repeats=3):
    d = np.tile(np.repeat(np.linspace(0.02, 0.38, 19), repeats), len(SCALE))
    y = np.repeat(list(SCALE), d.size // len(SCALE))
    return _curves(d, y), y, d


def test_noiseless_recordings_between_the_calibration_points_are_placed_exactly():
    # Between calibration distances the curves are exact (linear data, PCHIP), so each true
    # material has zero misfit at the true distance and the others do not: the material is
    # right, and the distance within one step of the dense grid (refined by a parabola).
    f, y, d = _calibration()
    clf = ModeCurveClassifier().fit(f, y, d)
    d_new = np.linspace(0.03, 0.37, 35)
    y_new = np.resize(list(SCALE), d_new.size)
    f_new = _curves(d_new, y_new)
    assert clf.predict(f_new).tolist() == y_new.tolist()
    step = (0.38 - 0.02) / (clf.n_grid - 1)
    assert np.abs(clf.predict_distance(f_new) - d_new).max() <= step
    misfit = clf.misfit(f_new)
    truth = misfit[np.arange(d_new.size), np.searchsorted(clf.classes_, y_new)]
    # the grid point nearest the truth is at most half a step away: misfit <= sum_j (s_j step/2)^2
    # with s_j the largest slope of log f_j: 30/20.6 and 60/97.2 per metre
    bound = ((30 / 20.6) ** 2 + (60 / 97.2) ** 2) * (step / 2) ** 2
    assert np.all(truth <= bound) and np.all(np.sort(misfit, axis=1)[:, 1] > 100 * bound)


def test_a_split_with_rows_lacking_two_peaks_classifies_every_test_row():
    # Rows whose second peak is missing fall back to the dominant frequency on one curve per
    # material (one mode alone is ambiguous here: a scaled curve matches another material at
    # another distance); the two-peak rows are all right, and no test row is dropped.
    f, y, d = _calibration()
    peaks = f.copy()
    peaks[::7, 1] = np.nan
    test = np.flatnonzero(np.isin(d, np.unique(d)[1::4]))  # whole positions held out
    train = np.setdiff1d(np.arange(d.size), test)
    res = classify_materials_by_mode_curves(peaks, f[:, 0], y, d, (train, test))
    assert res.confusions["test"].sum() == test.size
    two = np.isfinite(peaks[test, 1])
    assert res.accuracies["test"] >= two.mean() > 0.8 and res.method == "mode curves"
    assert res.model.predict(peaks[test[two]]).tolist() == y[test[two]].tolist()


def test_bad_input_names_the_parameter():
    f, y, d = _calibration()
    with pytest.raises(ValueError, match="y and distance"):
        ModeCurveClassifier().fit(f, y[:-1], d)
    with pytest.raises(ValueError, match="at least 2 materials"):
        ModeCurveClassifier().fit(f, np.full(y.size, "al"), d)
    with pytest.raises(ValueError, match="not fitted"):
        ModeCurveClassifier().predict(f)
    clf = ModeCurveClassifier().fit(f, y, d)
    with pytest.raises(ValueError, match="weights"):
        clf.curves_["al"].cost(f, weights=[1.0])
    with pytest.raises(ValueError, match="materials and positions"):
        classify_materials_by_mode_curves(f, f[:, 0], y[:-1], d, (np.arange(3), np.arange(3)))


def test_every_row_is_counted_by_the_way_it_was_classified():
    # rows lacking two peaks take the dominant frequency; rows with no frequency at all take
    # the most common training material; routes counts each way, and every row is in the matrix
    f, y, d = _calibration()
    peaks, dominant = f.copy(), f[:, 0].copy()
    peaks[::5, 1] = np.nan
    dominant[::10] = np.nan  # every tenth row: no peak at all (a subset of the fifths)
    test = np.flatnonzero(np.isin(d, np.unique(d)[1::4]))
    train = np.setdiff1d(np.arange(d.size), test)
    res = classify_materials_by_mode_curves(peaks, dominant, y, d, (train, test))
    for split, rows in (("train", train), ("test", test)):
        routes = res.routes[split]
        two = np.isfinite(peaks[rows, 1])
        none = ~two & ~np.isfinite(dominant[rows])
        assert routes == {"two peaks": two.sum(), "dominant frequency": (~two & ~none).sum(),
                          "most common material": none.sum()}
        assert res.confusions[split].sum() == rows.size
    # no training row has a dominant frequency: the rows lacking two peaks are guesses, counted
    res = classify_materials_by_mode_curves(peaks, np.full(d.size, np.nan), y, d, (train, test))
    assert res.routes["test"]["dominant frequency"] == 0
    assert res.routes["test"]["most common material"] == np.isnan(peaks[test, 1]).sum()
    assert res.confusions["test"].sum() == test.size


def test_labels_must_list_every_material():
    # a label missing from labels would drop its rows from the matrices while the accuracy
    # still counted them tested (a one-letter typo turned 0.875 into 1.0)
    f, y, d = _calibration()
    test = np.flatnonzero(np.isin(d, np.unique(d)[1::4]))
    train = np.setdiff1d(np.arange(d.size), test)
    with pytest.raises(ValueError, match=r"labels must list every material; missing \['pvc'\]"):
        classify_materials_by_mode_curves(f, f[:, 0], y, d, (train, test),
                                          labels=["al", "brass", "PVC"])
    res = classify_materials_by_mode_curves(f, f[:, 0], y, d, (train, test),
                                            labels=["pvc", "brass", "al"])
    assert res.labels == ("pvc", "brass", "al") and res.confusions["test"].sum() == test.size
    with pytest.raises(ValueError, match="peaks: no training row has two peaks"):
        classify_materials_by_mode_curves(np.full_like(f, np.nan), f[:, 0], y, d, (train, test))
