"""Beyond the paper: the material from a spectrum read *at its contact distance*.

The probe's spectrum after a contact is dominated by the probe's own modes, whose frequencies
move with the contact distance; the touched object adds its own, smaller, signature. A classifier
fed the raw spectrum learns both at once, and at a contact position it never saw, the probe's
peaks sit in bins where it has no example: it guesses. Estimating the contact distance first
removes most of that: :class:`PositionAwareMaterialClassifier` standardises every spectral bin by
the mean and spread that all materials together show at that distance (learnt at the training
positions, interpolated linearly between them), so that what the probe does at a given distance
is subtracted and what is left is the object. An RBF SVM then classifies these residuals.

:func:`classify_materials_position_aware` runs the two steps on a train/test split: the distance
of each test recording comes from its two strongest spectral peaks through
:class:`~ebantenna.paper.estimators.MultiModeDistanceEstimator` calibrated on the training rows
(the dominant frequency through
:class:`~ebantenna.paper.estimators.FrequencyDistanceEstimator` where fewer than two peaks stand
out), never from the label.
"""

from __future__ import annotations

import time

import numpy as np
from sklearn.base import BaseEstimator, ClassifierMixin
from sklearn.utils.multiclass import check_classification_targets
from sklearn.utils.validation import check_is_fitted, validate_data

from .._validate import check_array, check_per_row, check_positive, check_split
from ._ovr_svm import OneVsRestSVC, whole_kernel_svc
from .estimators import FrequencyDistanceEstimator, MultiModeDistanceEstimator
from .experiments import ClassificationResult, confusions_and_tested, label_order
from .protocol import normalise_by_max

__all__ = ["PositionAwareMaterialClassifier", "classify_materials_position_aware"]

#: Floor of a bin's spread, as a fraction of the mean spread over all bins and positions: a bin
#: that is (nearly) empty at some distance must not turn rounding into a large residual.
SPREAD_FLOOR = 0.05


class PositionAwareMaterialClassifier(ClassifierMixin, BaseEstimator):
    """Material from a spectrum standardised by what all materials show at its contact distance.

    For every distinct training distance ``d_k`` the mean ``mu_k`` and standard deviation
    ``s_k`` of each feature over all training rows at ``d_k`` (all materials together) are
    kept, ``s_k`` floored at ``SPREAD_FLOOR`` times its mean. A row at distance ``d`` becomes
    ``z = (x - mu(d)) / S(d)``, with ``mu`` and ``S`` linear in ``d`` between training distances
    and constant beyond them. The scale ``S_k = sqrt(s_k^2 + m^2)`` adds to the spread at
    ``d_k`` the spread ``m`` of the mean over all training distances: a probe mode's peak moves
    from bin to bin with the distance, and between two training distances far apart the
    interpolated mean can miss it by up to that much. Features the distance moves are damped;
    those it leaves in place (the object's own lines) keep their contrast. A one-vs-rest RBF SVM
    (:class:`ebantenna.ml.SVC`) classifies ``z``: each machine holds the whole float64 kernel
    of the training rows when it fits the memory budget, and the machines share one test kernel
    per prediction.

    Parameters
    ----------
    C : float
        SVM penalty.
    gamma : float or {"scale", "auto"}
        RBF width on the standardised features.

    Attributes
    ----------
    classes_ : ndarray
        Labels, sorted.
    distances_ : ndarray of shape (n_distances,)
        Distinct training distances, m.
    means_, spreads_ : ndarray of shape (n_distances, n_features - 1)
        Mean ``mu_k`` and scale ``S_k`` of every feature at each of them.

    Examples
    --------
    Two materials whose line sits 2 bins apart, beside a resonance that moves with the distance;
    tested at distances between the training ones:

    >>> rng = np.random.default_rng(0)
    >>> bins = np.arange(40)
    >>> def rows(d, shift):
    ...     x = np.exp(-0.5 * ((bins - 60 * d[:, None]) / 2) ** 2)
    ...     x += 0.2 * np.exp(-0.5 * (bins - 30 - shift) ** 2)
    ...     return np.column_stack([d, x + 0.02 * rng.random(x.shape)])
    >>> d = np.repeat(np.linspace(0.02, 0.38, 10), 3)
    >>> X = np.vstack([rows(d, 0), rows(d, 2)])
    >>> y = np.repeat(["brass", "pvc"], d.size)
    >>> clf = PositionAwareMaterialClassifier().fit(X, y)
    >>> d_new = np.array([0.04, 0.16, 0.34])
    >>> clf.predict(np.vstack([rows(d_new, 0), rows(d_new, 2)])).tolist()
    ['brass', 'brass', 'brass', 'pvc', 'pvc', 'pvc']
    """

    def __init__(self, C: float = 1.0, gamma="scale"):
        self.C = C
        self.gamma = gamma

    def _split(self, X, reset):
        X = validate_data(self, X, reset=reset)
        if X.shape[1] < 2:
            raise ValueError(
                f"X must have the distance (m) in column 0 and features after it, got shape "
                f"{X.shape}"
            )
        return X[:, 0], X[:, 1:]

    def fit(self, X, y):
        """Learn the per-distance statistics and the SVM.

        Parameters
        ----------
        X : array-like of shape (n, 1 + n_features)
            Contact distance (m) in column 0, the features (e.g. spectrum magnitudes) after it.
        y : array-like of shape (n,)
            Material labels.

        Returns
        -------
        self
        """
        check_positive("C", self.C)
        X, y = validate_data(self, X, y)
        check_classification_targets(y)
        d, F = self._split(X, reset=False)
        self.classes_ = np.unique(y)
        if self.classes_.size < 2:
            raise ValueError("y must hold at least two materials, got 1 class")
        grid, inverse = np.unique(d, return_inverse=True)
        counts = np.bincount(inverse)
        if np.any(counts < 2):
            raise ValueError(
                "every training distance needs at least 2 rows to give a spread; "
                f"{int(np.sum(counts < 2))} distances have one"
            )
        means = np.array([F[inverse == k].mean(axis=0) for k in range(grid.size)])
        spreads = np.array([F[inverse == k].std(axis=0) for k in range(grid.size)])
        floor = SPREAD_FLOOR * spreads.mean()
        spreads = np.maximum(spreads, floor if floor > 0 else 1.0)
        # how much the distance moves each feature: what interpolating the mean may miss
        moved = means.std(axis=0)
        self.distances_ = grid
        self.means_ = means
        self.spreads_ = np.sqrt(spreads**2 + moved**2)
        self.svm_ = OneVsRestSVC(whole_kernel_svc(X.shape[0], C=self.C, gamma=self.gamma))
        self.svm_.fit(self.standardise(X), y)
        return self

    def standardise(self, X) -> np.ndarray:
        """The features standardised at their rows' distances, shape ``(n, n_features - 1)``.

        Parameters
        ----------
        X : array-like of shape (n, 1 + n_features)
            Distance (m) in column 0, features after it.
        """
        check_is_fitted(self, "distances_")
        d, F = self._split(X, reset=False)
        grid = self.distances_
        if grid.size == 1:
            return (F - self.means_[0]) / self.spreads_[0]
        x = np.clip(d, grid[0], grid[-1])
        hi = np.clip(np.searchsorted(grid, x), 1, grid.size - 1)
        w = ((x - grid[hi - 1]) / (grid[hi] - grid[hi - 1]))[:, None]
        mu = (1 - w) * self.means_[hi - 1] + w * self.means_[hi]
        s = (1 - w) * self.spreads_[hi - 1] + w * self.spreads_[hi]
        return (F - mu) / s

    def predict(self, X) -> np.ndarray:
        """Material of each row.

        Parameters
        ----------
        X : array-like of shape (n, 1 + n_features)
            Distance (m) in column 0, features after it.
        """
        check_is_fitted(self, "svm_")
        return self.svm_.predict(self.standardise(X))


def estimate_distances(peaks, dominant, positions, train, rows) -> np.ndarray:
    """Contact distances (m) of ``rows``, calibrated on the ``train`` rows only.

    Two strongest peaks through :class:`MultiModeDistanceEstimator`; the dominant frequency
    through :class:`FrequencyDistanceEstimator` (clipped at its turning point) where a row has
    fewer than two peaks.

    Parameters
    ----------
    peaks : array-like of shape (n, 2)
        The two strongest spectral peaks, Hz (NaN where fewer than two stand out).
    dominant : array-like of shape (n,)
        Dominant frequency, Hz.
    positions : array-like of shape (n,)
        Nominal contact positions, m (only the training rows' are used).
    train, rows : array of int
        Calibration rows and the rows to estimate.

    Returns
    -------
    ndarray of shape (len(rows),)

    Examples
    --------
    >>> d = np.repeat(np.linspace(0.05, 0.35, 7), 2)
    >>> peaks = np.column_stack([10 + 30 * d, 80 - 50 * d])
    >>> est = estimate_distances(peaks, peaks[:, 0], d, np.arange(0, 14, 2), np.arange(1, 14, 2))
    >>> bool(np.allclose(est, d[1::2], atol=1e-3))
    True
    """
    peaks = check_array("peaks", peaks, ndim=2, finite=False)
    dominant = check_array("dominant", dominant, ndim=1, finite=False)
    positions = check_array("positions", positions, ndim=1)
    train, rows = np.asarray(train, dtype=np.intp), np.asarray(rows, dtype=np.intp)
    ok = np.all(np.isfinite(peaks), axis=1) & np.all(peaks > 0, axis=1)
    out = np.empty(rows.size)
    two = ok[rows]
    if np.any(two):
        calib = train[ok[train]]
        multi = MultiModeDistanceEstimator().fit(peaks[calib], positions[calib])
        out[two] = multi.predict(peaks[rows[two]])
    if not np.all(two):
        calib = train[np.isfinite(dominant[train]) & (dominant[train] > 0)]
        single = FrequencyDistanceEstimator(out_of_range="clip")
        single.fit(dominant[calib], positions[calib])
        out[~two] = single.predict(dominant[rows[~two]])
    return out


def classify_materials_position_aware(
    X, materials, positions, peaks, dominant, split, *, C=1.0, gamma="scale", labels=None
):
    """Distance first, then material: :class:`PositionAwareMaterialClassifier` on a split.

    The classifier learns at the training rows' nominal distances; every test row is read at
    the distance estimated from its own spectrum (``estimate_distances``, calibrated on the
    training rows).

    Parameters
    ----------
    X : array-like of shape (n, n_features)
        Features (the paper's FFT magnitudes), divided by their largest magnitude on the
        training rows first.
    materials : array-like of shape (n,)
        Material label of each row.
    positions : array-like of shape (n,)
        Nominal contact position of each row, m.
    peaks, dominant
        Per-row frequencies for the distance estimate (see ``estimate_distances``).
    split : (ndarray, ndarray)
        Train and test row indices (:mod:`ebantenna.paper.splits`).
    C, gamma
        Of the SVM.
    labels : sequence of str, optional
        Row order of the confusion matrices (default: sorted); it must list every material
        of ``materials``: a row whose material it lacks would leave every matrix.

    Returns
    -------
    ClassificationResult
        Method ``'position-aware'``, confusion matrices for 'train' (at the nominal distances)
        and 'test' (at the estimated ones).

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> d = np.tile(np.repeat(np.linspace(0.02, 0.38, 19), 3), 2)
    >>> y = np.repeat(["al", "pvc"], d.size // 2)
    >>> bins = np.arange(40)
    >>> X = np.exp(-0.5 * ((bins - 60 * d[:, None]) / 2) ** 2) + 0.2 * np.exp(
    ...     -0.5 * (bins - 30 - 2 * (y == "pvc")[:, None]) ** 2) + 0.02 * rng.random((114, 40))
    >>> peaks = np.column_stack([10 + 30 * d, 80 - 50 * d])  # two modes that move with d
    >>> test = np.flatnonzero(np.isin(d, d[::15]))  # whole positions held out
    >>> train = np.setdiff1d(np.arange(114), test)
    >>> res = classify_materials_position_aware(X, y, d, peaks, peaks[:, 0], (train, test))
    >>> res.accuracies["test"] > 0.9
    True
    """
    X = check_array("X", X, ndim=2)
    y = np.asarray(materials)
    d = check_array("positions", positions, ndim=1)
    check_per_row(X.shape[0], "X", materials=y, positions=d)
    train, test = check_split(split, X.shape[0])
    X = normalise_by_max(X, train)  # the scale from the training rows only
    order = label_order(y, labels)
    start = time.perf_counter()
    clf = PositionAwareMaterialClassifier(C=C, gamma=gamma)
    clf.fit(np.column_stack([d[train], X[train]]), y[train])
    seconds = time.perf_counter() - start
    d_test = estimate_distances(peaks, dominant, d, train, test)
    predicted = {
        "train": clf.predict(np.column_stack([d[train], X[train]])),
        "test": clf.predict(np.column_stack([d_test, X[test]])),
    }
    confusions, tested = confusions_and_tested(y, predicted, {"train": train, "test": test}, order)
    return ClassificationResult("position-aware", order, confusions, seconds, clf, tested)
