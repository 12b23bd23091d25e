"""Beyond the paper: material and contact distance fitted together from the modes' frequencies.

The touched rod is part of the vibrating system: its stiffness and mass move the coupled modes.
So each material draws its own curves ``f_j(d)`` of the mode frequencies against the contact
distance: one material's curve pair is not another's shifted along ``d``. A recording's two
strongest peaks ``(f_1, f_2)`` are then placed on every material's curves at once, and the
material whose curves pass closest, at the distance where they do, is the answer
(:class:`ModeCurveClassifier`). Two numbers per recording, each material's calibration curves
(median over repetitions, :class:`~ebantenna.paper.estimators.MultiModeDistanceEstimator`), no
spectrum and no learnt weights.

**Assumption.** Every material's misfit is measured with the same weights, equal for both modes,
``sum_j (log f_j - log f_j,m(d))^2``: the spread among repetitions differs from material to
material, and misfits compared across materials need one scale.

:func:`classify_materials_by_mode_curves` runs it on a train/test split; where a recording has
fewer than two separable peaks its dominant frequency alone is placed on one curve per material,
and one with no frequency at all gets the most common training material (a guess).
"""

from __future__ import annotations

import time

import numpy as np

from .._validate import check_array, check_per_row, check_split
from .estimators import MultiModeDistanceEstimator
from .experiments import ClassificationResult, confusions_and_tested, label_order

__all__ = ["ModeCurveClassifier", "classify_materials_by_mode_curves"]

#: Rows whose misfits are computed at once (memory about _CHUNK x n_grid x n_modes x 24 bytes).
_CHUNK = 256


class ModeCurveClassifier:
    """Material and contact distance from mode frequencies, by the closest calibration curves.

    Parameters
    ----------
    n_grid : int
        Points of each material's dense distance grid
        (:class:`~ebantenna.paper.estimators.MultiModeDistanceEstimator`), which spans the
        calibrated distances: 1000 points over the paper's 0.36 m is a step of about 0.4 mm,
        refined by a parabola for the distance. No distance is predicted outside them.

    Attributes
    ----------
    classes_ : ndarray of str
        The materials, sorted.
    curves_ : dict of str to MultiModeDistanceEstimator
        Each material's calibration curves.

    Examples
    --------
    Two materials whose curves differ: each recording is placed on both, and the nearer wins.

    >>> import numpy as np
    >>> d = np.tile(np.linspace(0.02, 0.38, 19), 2)
    >>> y = np.repeat(["al", "pvc"], 19)
    >>> f = np.column_stack([10 + 30 * d, 80 - 50 * d]) * np.where(y == "pvc", 0.95, 1.0)[:, None]
    >>> clf = ModeCurveClassifier().fit(f, y, d)
    >>> clf.predict([[16.0, 70.0], [0.95 * 16.0, 0.95 * 70.0]]).tolist()
    ['al', 'pvc']
    >>> np.round(clf.predict_distance([[16.0, 70.0]]), 4)
    array([0.2])
    """

    def __init__(self, n_grid: int = 1000):
        self.n_grid = n_grid

    def fit(self, X, y, distance):
        """Calibrate one set of curves per material.

        Parameters
        ----------
        X : array-like of shape (n, n_modes)
            Mode frequencies, Hz (> 0).
        y : array-like of shape (n,)
            Material of each row.
        distance : array-like of shape (n,)
            Contact distance of each row, m (at least 3 distinct values per material).

        Returns
        -------
        self
        """
        X = check_array("X", X, ndim=2)
        y = np.asarray(y)
        distance = check_array("distance", distance, ndim=1)
        check_per_row(X.shape[0], "X", y=y, distance=distance)
        self.classes_ = np.unique(y)
        if self.classes_.size < 2:
            raise ValueError(f"y must hold at least 2 materials, got {self.classes_.tolist()}")
        self.curves_ = {
            m: MultiModeDistanceEstimator(self.n_grid).fit(X[y == m], distance[y == m])
            for m in self.classes_
        }
        self.n_modes_ = X.shape[1]
        return self

    def misfit(self, X) -> np.ndarray:
        """Each material's smallest misfit over distance, shape ``(n, n_classes)``."""
        if not hasattr(self, "curves_"):
            from sklearn.exceptions import NotFittedError  # a ValueError, as scikit-learn's

            raise NotFittedError("this ModeCurveClassifier is not fitted yet: call fit first")
        X = check_array("X", X, ndim=2)
        weights = np.ones(self.n_modes_)
        out = np.empty((X.shape[0], self.classes_.size))
        for start in range(0, X.shape[0], _CHUNK):  # (rows, grid, modes) at a time
            rows = slice(start, start + _CHUNK)
            for j, curves in enumerate(self.curves_.values()):
                out[rows, j] = curves.cost(X[rows], weights).min(axis=1)
        return out

    def predict(self, X) -> np.ndarray:
        """The material whose curves pass closest to each row of ``X``."""
        best = np.argmin(self.misfit(X), axis=1)
        return self.classes_[best]

    def place(self, X) -> tuple[np.ndarray, np.ndarray]:
        """The material of each row and its contact distance (m) on that material's curves."""
        X = check_array("X", X, ndim=2)
        material = self.predict(X)
        distance = np.empty(X.shape[0])
        for m in np.unique(material):
            rows = material == m
            distance[rows] = self.curves_[m].predict(X[rows])
        return material, distance

    def predict_distance(self, X) -> np.ndarray:
        """The contact distance (m) of each row, on the curves of its predicted material."""
        return self.place(X)[1]


def classify_materials_by_mode_curves(peaks, dominant, materials, positions, split, labels=None):
    """:class:`ModeCurveClassifier` on a split: curves from the training rows, test rows placed.

    Parameters
    ----------
    peaks : array-like of shape (n, 2)
        The two strongest spectral peaks, Hz; NaN where fewer than two stand out (where
        :func:`ebantenna.signal.peak_frequencies` raises its ValueError, as
        :func:`ebantenna.paper.feature_table.signal_features` stores it).
    dominant : array-like of shape (n,)
        Dominant frequency, Hz: alone on one curve per material where a row lacks two peaks.
    materials : array-like of shape (n,)
        Material of each row.
    positions : array-like of shape (n,)
        Nominal contact position of each row, m (only the training rows' are used).
    split : (ndarray, ndarray)
        Train and test row indices (:mod:`ebantenna.paper.splits`).
    labels : sequence of str, optional
        Row order of the confusion matrices (default: sorted); it must list every material
        of ``materials``: a row whose material it lacks would leave every matrix.

    Returns
    -------
    ClassificationResult
        Method ``'mode curves'``, confusion matrices for 'train' and 'test'; the model is the
        two-peak :class:`ModeCurveClassifier`. ``routes`` counts, per split, the rows placed
        by their two peaks, those placed by the dominant frequency alone, and those given the
        most common training material (no frequency at all, or no dominant-frequency curve to
        place them on): all of them count in the accuracy.
    """
    peaks = check_array("peaks", peaks, ndim=2, finite=False)
    dominant = check_array("dominant", dominant, ndim=1, finite=False)
    y = np.asarray(materials)
    d = check_array("positions", positions, ndim=1)
    check_per_row(peaks.shape[0], "peaks", dominant=dominant, materials=y, positions=d)
    train, test = check_split(split, peaks.shape[0])
    order = label_order(y, labels)
    two = np.all(np.isfinite(peaks), axis=1) & np.all(peaks > 0, axis=1)
    one = np.isfinite(dominant) & (dominant > 0)
    if not np.any(two[train]):
        raise ValueError("peaks: no training row has two peaks; the mode curves need them")
    start = time.perf_counter()
    fit_two = train[two[train]]
    model = ModeCurveClassifier().fit(peaks[fit_two], y[fit_two], d[fit_two])
    seconds = time.perf_counter() - start
    # a row lacking two peaks is placed on one curve per material by its dominant frequency,
    # from the training rows that have one; a row with no frequency at all (or with no training
    # row to learn one curve from) gets the most common training material: a guess, counted
    fit_one = train[one[train]]
    fallback = (ModeCurveClassifier().fit(dominant[fit_one, None], y[fit_one], d[fit_one])
                if np.any(one[~two]) and np.unique(y[fit_one]).size >= 2 else None)
    values, counts = np.unique(y[train], return_counts=True)
    guess = values[np.argmax(counts)]

    def predict(rows):
        out = np.full(rows.size, guess, dtype=object)
        out[two[rows]] = model.predict(peaks[rows[two[rows]]])
        alone = ~two[rows] & one[rows] & (fallback is not None)
        if np.any(alone):
            out[alone] = fallback.predict(dominant[rows[alone], None])
        routes = {"two peaks": int(two[rows].sum()), "dominant frequency": int(alone.sum())}
        routes["most common material"] = rows.size - sum(routes.values())
        return out, routes

    parts = {"train": train, "test": test}
    done = {k: predict(rows) for k, rows in parts.items()}
    predicted = {k: out for k, (out, _) in done.items()}
    confusions, tested = confusions_and_tested(y, predicted, parts, order)
    return ClassificationResult("mode curves", order, confusions, seconds, model, tested,
                                routes={k: r for k, (_, r) in done.items()})
