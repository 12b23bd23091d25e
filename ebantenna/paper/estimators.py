"""The paper's estimators from signal features: contact distance from frequencies, material from
the decay.

They learn from arrays (measured frequencies with the known contact distances; decay features with
the known materials) and are scikit-learn estimators: parameters in ``__init__`` and
``get_params``/``set_params``, input checked by :func:`sklearn.utils.validation.validate_data`,
``fit`` returns the estimator, fitted attributes end in ``_``, ``predict`` (and ``score``) map new
measurements, so they go into pipelines, ``clone`` and cross-validation. Which of scikit-learn's
own estimator checks each passes, and why the others do not apply, is tested in
``tests/paper/test_paper_estimators.py``.

**Why the paper stops at 80 %.** With the contact pinning the probe at a distance ``d`` from the
hinge, the lowest mode is first the overhang beyond the contact swinging as a cantilever (its
frequency rises as the overhang shortens), then the span between hinge and contact (its frequency
falls as the span grows). ``f1(d)`` therefore rises to a maximum near ``0.79 L`` for the paper's
probe and falls after it: one first-mode frequency belongs to two contact positions.
:class:`FrequencyDistanceEstimator` finds that turning point in its calibration data and refuses
(or, on request, clips) frequencies it cannot place; :class:`MultiModeDistanceEstimator` uses two or
more modes, whose combination is unique along the whole probe, and so covers the full range.
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import PchipInterpolator
from scipy.sparse import issparse
from sklearn.base import BaseEstimator, ClassifierMixin, RegressorMixin
from sklearn.utils.multiclass import check_classification_targets
from sklearn.utils.validation import check_is_fitted, validate_data

from .._validate import check_array, check_choice, check_int

__all__ = [
    "FrequencyDistanceEstimator",
    "MultiModeDistanceEstimator",
    "DecayMaterialClassifier",
]


def _positive(X, what="frequencies"):
    if np.any(X <= 0):
        raise ValueError(f"{what} must be > 0 Hz")
    return X


def _calibration_curve(frequencies: np.ndarray, distances: np.ndarray):
    """Median frequency (per column) at each distinct distance, and the spread of log f."""
    grid, inverse = np.unique(distances, return_inverse=True)
    if grid.shape[0] < 3:
        raise ValueError(f"distances must hold at least 3 distinct values, got {grid.shape[0]}")
    medians = np.empty((grid.shape[0], frequencies.shape[1]))
    for i in range(grid.shape[0]):
        medians[i] = np.median(frequencies[inverse == i], axis=0)
    residual = np.log(frequencies) - np.log(medians[inverse])
    replicates = frequencies.shape[0] - grid.shape[0]
    spread = np.sqrt((residual**2).sum(axis=0) / replicates) if replicates > 0 else None
    return grid, medians, spread


def _as_column(X):
    """A 1-D sequence of frequencies read as one column ``(n, 1)``; anything else unchanged."""
    if not hasattr(X, "shape") or (getattr(X, "ndim", None) == 1 and isinstance(X, np.ndarray)):
        arr = np.asarray(X)
        if arr.ndim == 1 and arr.dtype != object:
            return arr.reshape(-1, 1)
    return X


def _one_column(X) -> np.ndarray:
    """Check that validated ``X`` holds one frequency per row."""
    if X.shape[1] != 1:
        raise ValueError(f"X must hold one frequency per row (shape (n,) or (n, 1)), "
                         f"got shape {X.shape}")
    return X


def _same_length(X, y, message):
    """Our own message for a length mismatch, before scikit-learn's generic one."""
    if issparse(X):
        return  # scikit-learn's check below rejects it with its own message
    try:
        n_x, n_y = len(X), len(y)
    except TypeError:  # sparse input or no y: scikit-learn's checks below speak
        return
    if n_x != n_y:
        raise ValueError(message.format(n_x, n_y))


class FrequencyDistanceEstimator(RegressorMixin, BaseEstimator):
    """Contact distance from the dominant (first-mode) frequency, on the curve's monotonic part.

    Parameters
    ----------
    out_of_range : {"raise", "clip"}
        What :meth:`predict` does with a frequency outside the calibrated monotonic range: raise a
        ValueError (default), or return the nearest end of the range (an explicit, documented clip).

    Attributes
    ----------
    n_features_in_ : int
        Always 1: the dominant frequency.
    distances_ : ndarray
        Distinct calibration distances, m.
    frequencies_ : ndarray
        Median calibration frequency at each distance, Hz.
    limit_ : float
        End of the usable range: the distance where the frequency curve turns, m.
    frequency_range_ : tuple of float
        Frequencies the monotonic branch covers, Hz.
    increasing_ : bool
        Whether the frequency rises with distance on the usable branch.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.paper.estimators import FrequencyDistanceEstimator
    >>> d = np.linspace(0.0, 1.0, 11)
    >>> f = 10 + 20 * d - 10 * d**2 * (d > 0.8)     # rises, then bends down after 0.8
    >>> est = FrequencyDistanceEstimator().fit(f, d)
    >>> round(est.limit_, 2), np.round(est.predict([15.0, 20.0]), 3)
    (0.8, array([0.25, 0.5 ]))
    """

    def __init__(self, out_of_range: str = "raise"):
        self.out_of_range = out_of_range

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.input_tags.positive_only = True
        return tags

    def fit(self, X, y):
        """Learn the calibration curve.

        Parameters
        ----------
        X : array-like of shape (n,) or (n, 1)
            Dominant frequencies, Hz.
        y : array-like of shape (n,)
            Contact distances, m.

        Returns
        -------
        self
        """
        check_choice("out_of_range", self.out_of_range, ("raise", "clip"))
        X = _as_column(X)
        _same_length(X, y, "frequencies and distances must have the same shape, got ({},) and "
                           "({},)")
        f, d = validate_data(self, X, y, y_numeric=True)
        f = _positive(_one_column(f))[:, 0]
        grid, medians, _ = _calibration_curve(f[:, None], d)
        curve = medians[:, 0]
        increasing = bool(curve[min(2, curve.size - 1)] >= curve[0])
        signed = curve if increasing else -curve
        turn = int(np.argmax(signed))
        if turn < 2:
            raise ValueError("frequencies do not change monotonically with distance over the first "
                             "three calibration points; no calibration curve can be learnt")
        branch = np.maximum.accumulate(signed[: turn + 1])
        self.distances_ = grid
        self.frequencies_ = curve
        self.limit_ = float(grid[turn])
        self.increasing_ = increasing
        self._branch_d = grid[: turn + 1]
        self._branch_f = branch
        lo, hi = float(curve[: turn + 1].min()), float(curve[: turn + 1].max())
        self.frequency_range_ = (lo, hi)
        return self

    def predict(self, X):
        """Contact distances (m) for dominant frequencies (Hz).

        Parameters
        ----------
        X : float or array-like of shape (n,) or (n, 1)
            Dominant frequencies, Hz.

        Returns
        -------
        float or ndarray of shape (n,)
            Contact distances, m (a float for a scalar input).
        """
        check_is_fitted(self)
        scalar = np.ndim(X) == 0
        f = _one_column(validate_data(self, _as_column(np.atleast_1d(X)), reset=False))[:, 0]
        lo, hi = self.frequency_range_
        outside = (f < lo) | (f > hi)
        if np.any(outside) and self.out_of_range == "raise":
            bad = f[outside][0]
            raise ValueError(f"frequencies must lie in the calibrated range [{lo:g}, {hi:g}] Hz "
                             f"(contacts up to {self.limit_:g} m), got {bad:g}")
        signed = f if self.increasing_ else -f
        # np.interp needs increasing abscissae; flat stretches of the running maximum keep the
        # first distance, and values beyond the ends take the end distances (the "clip" mode).
        keep = np.concatenate([[True], np.diff(self._branch_f) > 0])
        out = np.interp(signed, self._branch_f[keep], self._branch_d[keep])
        return out[0] if scalar else out


class MultiModeDistanceEstimator(RegressorMixin, BaseEstimator):
    """Contact distance from the frequencies of several modes, along the whole probe.

    Each mode's calibration curve ``f_j(d)`` (median over replicates, monotone cubic interpolation
    between calibration distances) is sampled on a dense grid; a measurement ``(f_1, ..., f_k)`` is
    placed at the distance minimising ``sum_j w_j (log f_j - log f_j(d))^2``, found on the grid and
    refined by a parabola through the three best grid points. The weights ``w_j = 1 / s_j^2`` use
    the spread ``s_j`` of ``log f_j`` among calibration replicates; equal weights without
    replicates, and equal weights too when some mode's replicates all agree (a spread of zero
    would give that mode all the weight; ``weights_`` shows which was used).

    The grid spans the calibration distances only: every estimate lies in
    ``[distances_[0], distances_[-1]]``, and a measurement from beyond that range is placed at
    the nearer end (the best match the calibration holds), not extrapolated. Unlike
    :class:`FrequencyDistanceEstimator` it has no ``out_of_range`` option: several modes have no
    single frequency range to check a measurement against. An estimate at an end of the range
    may lie beyond it.

    Parameters
    ----------
    n_grid : int
        Points of the dense distance grid.

    Attributes
    ----------
    n_features_in_ : int
        Number of modes.
    distances_ : ndarray
        Distinct calibration distances, m.
    frequencies_ : ndarray of shape (n_distances, n_modes)
        Median calibration frequencies, Hz.
    weights_ : ndarray of shape (n_modes,)
        Weights of the modes in the distance cost.
    grid_ : ndarray of shape (n_grid,)
        The dense distance grid, m.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.paper.estimators import MultiModeDistanceEstimator
    >>> d = np.linspace(0.0, 1.0, 21)
    >>> f = np.column_stack([10 + 8 * np.sin(np.pi * d), 30 + 20 * d])  # f1 alone is ambiguous
    >>> est = MultiModeDistanceEstimator().fit(f, d)
    >>> f1 = 10 + 8 * np.sin(0.2 * np.pi)  # the first mode at d = 0.2 and at d = 0.8
    >>> np.round(est.predict([[f1, 34.0], [f1, 46.0]]), 3)
    array([0.2, 0.8])
    """

    def __init__(self, n_grid: int = 4000):
        self.n_grid = n_grid

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.input_tags.positive_only = True
        return tags

    def fit(self, X, y):
        """Learn the curves.

        Parameters
        ----------
        X : array-like of shape (n, n_modes)
            Mode frequencies, Hz.
        y : array-like of shape (n,)
            Contact distances, m.

        Returns
        -------
        self
        """
        n_grid = check_int("n_grid", self.n_grid, minimum=10)
        _same_length(X, y, "frequencies must have one row per distance, got {} rows for {} "
                           "distances")
        f, d = validate_data(self, X, y, y_numeric=True)
        _positive(f)
        grid, medians, spread = _calibration_curve(f, d)
        if spread is None or np.any(spread == 0):
            weights = np.ones(f.shape[1])
        else:
            weights = 1.0 / spread**2
            weights /= weights.max()
        self.distances_ = grid
        self.frequencies_ = medians
        self.weights_ = weights
        self.n_modes_ = f.shape[1]
        self.grid_ = np.linspace(grid[0], grid[-1], n_grid)
        self._log_curves = np.log(PchipInterpolator(grid, medians, axis=0)(self.grid_))
        return self

    def cost(self, X, weights=None) -> np.ndarray:
        """Weighted squared log-frequency misfit on the dense grid, shape ``(n, n_grid)``.

        Parameters
        ----------
        X : array-like of shape (n_modes,) or (n, n_modes)
            Mode frequencies, Hz.
        weights : array-like of shape (n_modes,), optional
            The modes' weights; default ``weights_``.
        """
        check_is_fitted(self)
        if np.ndim(X) == 1:
            X = np.atleast_2d(X)  # one measurement
        if np.ndim(X) == 2 and np.shape(X)[1] != self.n_modes_:
            raise ValueError(f"frequencies must have {self.n_modes_} columns (modes), "
                             f"got shape {np.shape(X)}")
        f = _positive(validate_data(self, X, reset=False))
        if weights is None:
            weights = self.weights_
        else:
            weights = check_array("weights", weights, ndim=1)
            if weights.size != self.n_modes_ or np.any(weights < 0):
                raise ValueError(
                    f"weights must be {self.n_modes_} non-negative numbers, one per mode, got "
                    f"{weights.tolist()}"
                )
        # sum_k w_k (log f_k - log curve_k)^2, one mode at a time: no (n, n_grid, n_modes)
        # temporaries, and for fewer than eight modes the same additions in the same order as
        # NumPy's sum over the last axis (which pairs terms only from eight on)
        log_f = np.log(f)
        out = np.zeros((f.shape[0], self._log_curves.shape[0]))
        for k in range(self.n_modes_):
            diff = log_f[:, k, None] - self._log_curves[None, :, k]
            diff *= diff
            diff *= weights[k]
            out += diff
        return out

    def predict(self, X) -> np.ndarray:
        """Contact distances (m) for rows of mode frequencies.

        Parameters
        ----------
        X : array-like of shape (n, n_modes)
            Mode frequencies, Hz.

        Returns
        -------
        ndarray of shape (n,)
            Contact distances, m.
        """
        cost = self.cost(X)
        grid = self.grid_
        best = np.argmin(cost, axis=1)
        inner = np.clip(best, 1, grid.shape[0] - 2)
        rows = np.arange(cost.shape[0])
        c0, c1, c2 = cost[rows, inner - 1], cost[rows, inner], cost[rows, inner + 1]
        curvature = c0 - 2 * c1 + c2
        with np.errstate(divide="ignore", invalid="ignore"):
            shift = np.where(curvature > 0, 0.5 * (c0 - c2) / curvature, 0.0)
        shift = np.where(best == inner, np.clip(shift, -1.0, 1.0), 0.0)
        step = grid[1] - grid[0]
        return grid[best] + shift * step


class DecayMaterialClassifier(ClassifierMixin, BaseEstimator):
    """Material of the touched object from the decay time constant and gain (section 4.1.2).

    For each material the logarithms of ``tau`` and of the gain are modelled as polynomials of the
    contact distance (degree ``degree``) with Gaussian residuals (a full 2x2 covariance per
    material, unbiased). A new contact is given to the material with the largest posterior
    probability (priors: class frequencies). With ``degree=0`` the distance is ignored and this is
    quadratic discriminant analysis on ``(log tau, log gain)``. The features of a contact are
    ``tau`` and ``a`` of :func:`~ebantenna.signal.band_passed_decay`.

    Parameters
    ----------
    degree : int
        Polynomial degree of the distance dependence (0 to 5).

    Attributes
    ----------
    classes_ : ndarray
        Material labels, sorted.
    n_features_in_ : int
        Always 3: distance, tau and gain.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.paper.estimators import DecayMaterialClassifier
    >>> rng = np.random.default_rng(0)
    >>> d = np.tile(np.linspace(0.05, 0.3, 20), 2)
    >>> tau = np.r_[np.full(20, 0.05), np.full(20, 0.1)] * (1 + 0.05 * rng.standard_normal(40))
    >>> gain = np.r_[np.full(20, 2.0), np.full(20, 1.0)] * (1 + 0.05 * rng.standard_normal(40))
    >>> X = np.column_stack([d, tau, gain])
    >>> y = np.repeat(["steel", "wood"], 20)
    >>> clf = DecayMaterialClassifier(degree=1).fit(X, y)
    >>> clf.predict([[0.1, 0.052, 1.9], [0.2, 0.11, 0.9]])
    array(['steel', 'wood'], dtype='<U5')
    """

    def __init__(self, degree: int = 2):
        self.degree = degree

    def _features(self, X, reset):
        X = validate_data(self, X, reset=reset)
        if X.shape[1] != 3:
            raise ValueError(
                f"X must have 3 columns (distance m, tau s, gain), got shape {X.shape}"
            )
        if np.any(X[:, 1:] <= 0):
            raise ValueError("tau and gain (columns 2 and 3 of X) must be > 0")
        return X[:, 0], np.log(X[:, 1:])

    def _design(self, d):
        u = (d - self._d_mean) / self._d_scale
        return np.vander(u, self.degree + 1, increasing=True)

    def fit(self, X, y):
        """Learn the per-material models.

        Parameters
        ----------
        X : array-like of shape (n, 3)
            Contact distance (m), time constant tau (s) and gain (m/s^2) of each contact.
        y : array-like of shape (n,)
            Material labels.

        Returns
        -------
        self
        """
        degree = check_int("degree", self.degree, minimum=0, maximum=5)
        _same_length(X, y, "y must have one label per row of X ({}), got {}")
        X, y = validate_data(self, X, y)
        check_classification_targets(y)
        d, z = self._features(X, reset=False)
        self.classes_, inverse = np.unique(y, return_inverse=True)
        if self.classes_.shape[0] < 2:
            raise ValueError("y must hold at least two materials, got 1 class")
        self._d_mean = float(d.mean())
        self._d_scale = float(d.std()) or 1.0
        design = self._design(d)
        self._coef, self._cov_inv, self._log_norm, self._log_prior = [], [], [], []
        for k in range(self.classes_.shape[0]):
            rows = inverse == k
            if rows.sum() < degree + 4:
                raise ValueError(f"material {self.classes_[k]!r} needs at least {degree + 4} "
                                 f"samples for degree {degree}, got {rows.sum()}")
            coef, *_ = np.linalg.lstsq(design[rows], z[rows], rcond=None)
            resid = z[rows] - design[rows] @ coef
            cov = resid.T @ resid / (rows.sum() - (degree + 1))
            sign, logdet = np.linalg.slogdet(cov)
            if sign <= 0:
                raise ValueError(f"material {self.classes_[k]!r} has degenerate features "
                                 "(identical or collinear tau and gain)")
            self._coef.append(coef)
            self._cov_inv.append(np.linalg.inv(cov))
            self._log_norm.append(-0.5 * logdet - np.log(2 * np.pi))
            self._log_prior.append(np.log(rows.mean()))
        return self

    def _joint_log_likelihood(self, X):
        check_is_fitted(self)
        d, z = self._features(X, reset=False)
        design = self._design(d)
        out = np.empty((z.shape[0], self.classes_.shape[0]))
        for k in range(self.classes_.shape[0]):
            r = z - design @ self._coef[k]
            maha = np.einsum("ij,jk,ik->i", r, self._cov_inv[k], r)
            out[:, k] = self._log_prior[k] + self._log_norm[k] - 0.5 * maha
        return out

    def predict_proba(self, X) -> np.ndarray:
        """Posterior probabilities, shape ``(n, n_classes)``, columns in ``classes_`` order."""
        jll = self._joint_log_likelihood(X)
        jll -= jll.max(axis=1, keepdims=True)
        p = np.exp(jll)
        return p / p.sum(axis=1, keepdims=True)

    def predict(self, X) -> np.ndarray:
        """Most probable material for each row of ``X``."""
        best = np.argmax(self._joint_log_likelihood(X), axis=1)
        return self.classes_[best]
