"""Fit the hinge's rotational stiffness and the tip mass to where the dominant mode changes.

The dominant (lowest) frequency rises as the contact moves from the hinge towards the tip, peaks,
and falls again once the lowest mode has become the span's own (zone 3 of
:mod:`~ebantenna.fem.zones`). *Where* this happens, as a fraction of the probe's length, is the
same for every length of a bare clamped tube (the problem has no length scale of its own). A
rotational spring at the hinge (``k_h``, N m/rad: stiffer relative to the tube as the tube gets
longer, ``k_h L / EI``) and a point mass at the tip (the sensor board: lighter relative to a
longer tube, ``m_t / (rho A L)``) give it one, so that two probes of different lengths can see the
change at different fractions of their lengths, as the paper did (29.5 cm of 40 cm and 39.5 cm of
50 cm). :func:`fit_hinge_and_tip` finds the ``(k_h, m_t)`` that come closest to such observations
in the least-squares sense and reports the residual: whether one hinge and one tip mass explain
them all is an outcome, not an assumption.

The transition is located by one of three criteria: ``"peak"``, the contact at which the lowest
frequency is largest (where it leaves its rising branch), or ``"zone2"`` / ``"zone3"``, where the
overhang's share of the lowest mode's kinetic energy falls below 0.9 / 0.1
(:func:`~ebantenna.fem.zones.dominant_mode_zones`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from joblib import Parallel, delayed
from scipy.optimize import brentq, least_squares, minimize_scalar

from .._validate import (
    check_array,
    check_choice,
    check_int,
    check_n_jobs,
    check_nonnegative,
    check_positive,
    check_real,
    describe,
)
from ..probe import Probe
from .assembly import Supports
from .modal import modal_analysis
from .sweeps import natural_frequencies

__all__ = ["CRITERIA", "HingeFit", "transition_position", "fit_hinge_and_tip"]

#: Ways of locating where the dominant frequency leaves the first mode's branch.
CRITERIA = ("peak", "zone2", "zone3")
_THRESHOLDS = {"zone2": 0.9, "zone3": 0.1}
#: The default search ranges of :func:`fit_hinge_and_tip` (and of a :class:`HingeFit` made
#: without them): hinge stiffness, N m/rad, and tip mass, kg.
_STIFFNESS_BOUNDS = (1e-2, 1e3)
_MASS_BOUNDS = (0.0, 0.02)


def transition_position(
    probe: Probe, *, hinge="clamped", criterion: str = "peak", n_elements: int = 64
) -> float:
    """Contact position (m from the hinge) where the dominant frequency leaves the first branch.

    Parameters
    ----------
    probe : Probe
        Tube and tip mass.
    hinge : {"clamped", "pinned"} or float
        As in :class:`~ebantenna.fem.Supports` (a float: rotational stiffness, N m/rad).
    criterion : {"peak", "zone2", "zone3"}
        See the module's description.
    n_elements : int
        Beam elements per contact position.

    Returns
    -------
    float
        The contact position, m, located to about ``1e-6 L``.

    Examples
    --------
    >>> from ebantenna import Probe
    >>> from ebantenna.fem.hinge import transition_position
    >>> round(transition_position(Probe()) / Probe().length, 3)  # a bare clamped tube
    0.783
    """
    if not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
    check_choice("criterion", criterion, CRITERIA)
    n_elements = check_int("n_elements", n_elements, minimum=4)
    L = probe.length
    grid = np.linspace(0.3, 0.99, 139) * L  # 5 mm steps on a 40 cm probe
    if criterion == "peak":
        f = natural_frequencies(probe, grid, hinge=hinge, n_elements=n_elements, n_modes=1)[:, 0]
        i = int(np.argmax(f))
        if i in (0, grid.size - 1):
            raise ValueError(
                f"the lowest frequency peaks at the edge of the searched contacts "
                f"({grid[i] / L:.2f} L of 0.30-0.99 L): no interior peak to locate for this "
                f"probe (tip_mass={probe.tip_mass!r} kg, hinge={hinge!r})"
            )
        best = minimize_scalar(
            lambda c: (
                -natural_frequencies(
                    probe, np.array([c]), hinge=hinge, n_elements=n_elements, n_modes=1
                )[0, 0]
            ),
            bounds=(grid[i - 1], grid[i + 1]),
            method="bounded",
            options={"xatol": 1e-6 * L},
        )
        return float(best.x)

    threshold = _THRESHOLDS[criterion]

    def excess(c):
        res = modal_analysis(
            probe, Supports(contact=float(c), hinge=hinge), n_elements=n_elements, n_modes=1
        )
        return res.overhang_mass_fraction()[0] - threshold

    coarse = grid[::6]
    values = np.array([excess(c) for c in coarse])
    below = np.flatnonzero(values < 0)
    if below.size == 0 or below[0] == 0:
        raise ValueError(
            f"criterion {criterion!r}: the overhang's energy share does not cross {threshold} "
            f"between {coarse[0]:.3g} and {coarse[-1]:.3g} m for this probe"
        )
    j = below[0]
    return float(brentq(excess, coarse[j - 1], coarse[j], xtol=1e-6 * L))


@dataclass(frozen=True)
class HingeFit:
    """The hinge stiffness and tip mass closest to observed transitions.

    Attributes
    ----------
    hinge_stiffness : float
        Rotational stiffness of the hinge, N m/rad.
    tip_mass : float
        Point mass at the tip, kg.
    lengths : ndarray
        Probe lengths of the observations, m.
    observed, predicted : ndarray
        Transition positions observed and given by the fitted model, m.
    criterion : str
        How the transition was located.
    stiffness_bounds, mass_bounds : (float, float)
        The bounds the fit searched within (N m/rad, kg).
    lattice : tuple of ndarray or None
        The coarse search's lattice, ``(stiffness, mass, rms)``: its hinge stiffnesses (N m/rad,
        shape ``(g,)``), its tip masses (kg, ``(g,)``) and the RMS residual at each pair (m,
        ``(g, g)``, stiffness by row); None for a fit made without a search. What
        :meth:`stiffness_within` reads.
    """

    hinge_stiffness: float
    tip_mass: float
    lengths: np.ndarray
    observed: np.ndarray
    predicted: np.ndarray
    criterion: str
    stiffness_bounds: tuple = _STIFFNESS_BOUNDS
    mass_bounds: tuple = _MASS_BOUNDS
    lattice: tuple | None = None

    @property
    def at_bound(self) -> dict:
        """Each fitted parameter that sits on a bound of its search, ``{"hinge_stiffness" or
        "tip_mass": "lower" or "upper"}``: there the data do not set the value, the bound does.
        On a bound means within a millionth of the range (the fit's ``xtol`` is 1e-10).

        Examples
        --------
        >>> f = HingeFit(5.0, 1e-16, np.ones(1), np.ones(1), np.ones(1), "peak")
        >>> f.at_bound
        {'tip_mass': 'lower'}
        """
        found = {}
        for name, value, (lo, hi) in (
            ("hinge_stiffness", math.log10(self.hinge_stiffness),
             tuple(math.log10(b) for b in self.stiffness_bounds)),
            ("tip_mass", self.tip_mass, self.mass_bounds),
        ):
            tol = 1e-6 * (hi - lo)
            if value <= lo + tol:
                found[name] = "lower"
            elif value >= hi - tol:
                found[name] = "upper"
        return found

    @property
    def residual(self) -> np.ndarray:
        """Predicted minus observed transition positions, m."""
        return self.predicted - self.observed

    @property
    def rms_residual(self) -> float:
        """Root-mean-square residual, m."""
        return float(np.sqrt(np.mean(self.residual**2)))

    def stiffness_within(self, tolerance: float) -> np.ndarray:
        """The lattice's hinge stiffnesses that come within ``tolerance`` of the least misfit.

        A stiffness of the coarse search's ``lattice`` comes within when its least RMS
        residual over the lattice's tip masses exceeds the least RMS residual found (the fit's
        :attr:`rms_residual`, or a lattice point's where that is smaller: the fit weighs each
        residual by its probe's length, the RMS does not) by at most ``tolerance``:
        observations read no finer than ``tolerance`` cannot rank it below the best. The
        lattice's masses are a sample of the range, so each stiffness's least residual is an
        upper bound of its best: the stiffnesses returned come within, and others of the range
        may too.

        Parameters
        ----------
        tolerance : float
            How much larger an RMS residual may be, m, >= 0.

        Returns
        -------
        ndarray
            Those stiffnesses, N m/rad, ascending.

        Raises
        ------
        ValueError
            For a fit made without a search (``lattice`` None).

        Examples
        --------
        >>> one = np.ones(1)
        >>> rms = np.array([[0.03, 0.02], [0.011, 0.012], [0.02, 0.015]])
        >>> fit = HingeFit(10.0, 0.0, one, one, one + 0.01, "peak",
        ...                lattice=(np.array([1.0, 10.0, 100.0]), np.array([0.0, 0.01]), rms))
        >>> fit.stiffness_within(0.005).tolist()
        [10.0, 100.0]
        """
        tolerance = check_nonnegative("tolerance", tolerance)
        if self.lattice is None:
            raise ValueError("stiffness_within needs the search's lattice: this fit has none "
                             "(lattice=None)")
        stiffness, _, rms = self.lattice
        best = np.min(rms, axis=1)
        least = min(self.rms_residual, float(best.min()))
        return np.sort(stiffness[best <= least + tolerance])


def fit_hinge_and_tip(
    probe: Probe,
    lengths,
    observed,
    *,
    criterion: str = "peak",
    stiffness_bounds: tuple[float, float] = _STIFFNESS_BOUNDS,
    mass_bounds: tuple[float, float] = _MASS_BOUNDS,
    grid: int = 7,
    n_elements: int = 48,
    n_jobs: int | None = 1,
) -> HingeFit:
    """Least-squares fit of hinge stiffness and tip mass to observed transition positions.

    A coarse ``grid x grid`` search (stiffness on a log scale) finds the basin, then
    :func:`scipy.optimize.least_squares` refines it inside the bounds.

    Parameters
    ----------
    probe : Probe
        The tube (its length and tip mass are replaced per observation and fit).
    lengths : array of shape (n,)
        Probe length of each observation, m.
    observed : array of shape (n,)
        Contact position of each observed transition, m from the hinge, inside ``(0, length)``.
    criterion : {"peak", "zone2", "zone3"}
        As in :func:`transition_position`.
    stiffness_bounds : (float, float)
        Range of the hinge's rotational stiffness, N m/rad, both > 0.
    mass_bounds : (float, float)
        Range of the tip mass, kg, ``0 <= low < high``.
    grid : int
        Points per parameter of the coarse search.
    n_elements : int
        Beam elements per contact position.
    n_jobs : int or None
        Worker processes for the coarse search (:class:`joblib.Parallel`; -1: every core; 1 or
        None: in this process). Each point is computed alone, so the fit is the same whatever
        ``n_jobs``.

    Returns
    -------
    HingeFit

    Examples
    --------
    >>> from ebantenna import Probe
    >>> from ebantenna.fem.hinge import fit_hinge_and_tip

    One observation leaves a family of exact fits; the search returns one of them:

    >>> fit = fit_hinge_and_tip(
    ...     Probe(), [0.4], [0.30], grid=2, mass_bounds=(0.0, 0.002), n_elements=16
    ... )
    >>> fit.rms_residual < 1e-6  # m
    True
    """
    if not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
    check_choice("criterion", criterion, CRITERIA)
    lengths, observed = _check_observations(lengths, observed)
    (k_lo, k_hi), (m_lo, m_hi) = _check_bounds(stiffness_bounds, mass_bounds)
    grid = check_int("grid", grid, minimum=2)
    n_jobs = check_n_jobs("n_jobs", n_jobs)

    def predict(log_k, mass):
        return np.array(
            [
                transition_position(
                    replace(probe, length=float(length), tip_mass=float(mass)),
                    hinge=float(10.0**log_k),
                    criterion=criterion,
                    n_elements=n_elements,
                )
                for length in lengths
            ]
        )

    def residual(p):
        return (predict(*p) - observed) / lengths

    bounds = ([math.log10(k_lo), m_lo], [math.log10(k_hi), m_hi])
    best, best_cost, lattice = _grid_search(residual, bounds, grid, n_jobs)
    start = np.clip(best, np.array(bounds[0]) + 1e-9, np.array(bounds[1]) - 1e-9)
    scale = np.array([0.1, 0.02 * (m_hi - m_lo)])
    fit = least_squares(residual, start, bounds=bounds, x_scale=scale, diff_step=1e-4, xtol=1e-10)
    log_k, mass = fit.x if 2 * fit.cost <= best_cost else np.asarray(best)  # cost = sum r^2 / 2
    return HingeFit(
        hinge_stiffness=float(10.0**log_k),
        tip_mass=float(mass),
        lengths=lengths,
        observed=observed,
        predicted=predict(log_k, mass),
        criterion=criterion,
        stiffness_bounds=(k_lo, k_hi),
        mass_bounds=(m_lo, m_hi),
        lattice=(lattice[0], lattice[1], np.sqrt(np.mean((lattice[2] * lengths) ** 2, axis=2))),
    )


def _check_observations(lengths, observed):
    """Both as 1-D arrays of one size >= 1, every observation inside its probe ``(0, length)``."""
    lengths = check_array("lengths", lengths, ndim=1)
    observed = check_array("observed", observed, ndim=1)
    if lengths.shape != observed.shape or lengths.size == 0:
        raise ValueError(
            f"lengths and observed must be 1-D of one size >= 1, got {lengths.shape} and "
            f"{observed.shape}"
        )
    for length, x in zip(lengths, observed, strict=True):
        check_positive("lengths", length)
        if not 0 < x < length:
            raise ValueError(f"observed must lie in (0, length) = (0, {length:g}) m, got {x!r}")
    return lengths, observed


def _check_bounds(stiffness_bounds, mass_bounds):
    """``(k_lo, k_hi), (m_lo, m_hi)`` with ``0 < k_lo < k_hi`` and ``0 <= m_lo < m_hi < inf``."""
    for name, pair in (("stiffness_bounds", stiffness_bounds), ("mass_bounds", mass_bounds)):
        if isinstance(pair, str | bytes) or not hasattr(pair, "__len__") or len(pair) != 2:
            raise TypeError(f"{name} must be a pair (low, high), got {describe(pair)}")
    k_lo = check_positive("stiffness_bounds[0]", stiffness_bounds[0])
    k_hi = check_positive("stiffness_bounds[1]", stiffness_bounds[1])
    m_lo = check_real("mass_bounds[0]", mass_bounds[0])
    m_hi = check_real("mass_bounds[1]", mass_bounds[1])
    if not (k_lo < k_hi and 0 <= m_lo < m_hi and math.isfinite(m_hi)):
        raise ValueError(
            "need 0 < stiffness_bounds[0] < stiffness_bounds[1] and "
            f"0 <= mass_bounds[0] < mass_bounds[1] < inf, got {stiffness_bounds}, {mass_bounds}"
        )
    return (k_lo, k_hi), (m_lo, m_hi)


def _grid_search(residual, bounds, grid: int, n_jobs=1):
    """The point of a ``grid x grid`` lattice inside ``bounds`` with the least squared residual
    (the first in lattice order on a tie), its points computed on ``n_jobs`` processes.

    Returns ``((log_k, mass), cost, (stiffness, mass, residuals))``: the lattice finds the basin
    that a local least-squares refinement then descends, and its stiffnesses (N m/rad), masses
    and residuals at each point (``(grid, grid, n)``) are kept for :attr:`HingeFit.lattice`.
    """
    log_ks = np.linspace(bounds[0][0], bounds[1][0], grid)
    masses = np.linspace(bounds[0][1], bounds[1][1], grid)
    lattice = [(log_k, mass) for log_k in log_ks for mass in masses]
    residuals = Parallel(n_jobs=n_jobs or 1)(delayed(residual)(point) for point in lattice)
    best, best_cost = None, math.inf
    for point, r in zip(lattice, residuals, strict=True):
        cost = float(np.sum(r**2))
        if cost < best_cost:
            best, best_cost = point, cost
    # each stiffness as the residual's model took it (a scalar power, which an array power may
    # round to another last bit: the lattice names the hinges its residuals were computed at)
    stiffness = np.array([10.0**log_k for log_k in log_ks])
    return best, best_cost, (stiffness, masses, np.reshape(residuals, (grid, grid, -1)))
