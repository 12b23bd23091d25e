"""Section 1b: one hinge and one tip mass for both of the paper's probes?"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..fem.hinge import HingeFit, fit_hinge_and_tip
from ..paper import printed
from ._common import check_render, check_step

__all__ = ["HingeResult", "compute", "render"]

#: The paper's two observations: where the dominant frequency leaves the first mode's branch.
LENGTHS = (0.40, 0.50)


@dataclass(frozen=True, eq=False)
class HingeResult:
    """The least-squares hinge stiffness and tip mass for both observations.

    Attributes
    ----------
    fit : ebantenna.fem.hinge.HingeFit
    explains_both : bool
        Whether every residual is below half the paper's 5 mm contact step (the observations'
        own resolution).
    """

    fit: HingeFit

    #: Resolution of the observations: half the paper's 5 mm contact spacing, m.
    resolution = 2.5e-3

    @property
    def explains_both(self) -> bool:
        """Every residual within the observations' resolution."""
        return bool(np.all(np.abs(self.fit.residual) <= self.resolution))

    def to_dict(self) -> dict:
        """Best fit (N m/rad, g), which of its parameters sit on a bound of the search (there
        the bound, not the data, sets the value: ``at_bound``), observed and predicted
        transitions and residuals (cm), and the search lattice's hinge stiffnesses with those
        of them the observations cannot rank below the least misfit found
        (:meth:`~ebantenna.fem.hinge.HingeFit.stiffness_within` the resolution; None for a fit
        made without a search)."""
        f = self.fit
        return {
            "hinge_stiffness_n_m_per_rad": f.hinge_stiffness,
            "tip_mass_g": 1e3 * f.tip_mass,
            "at_bound": f.at_bound,
            "probe_lengths_cm": (100 * f.lengths).tolist(),
            "observed_cm": (100 * f.observed).tolist(),
            "predicted_cm": (100 * f.predicted).tolist(),
            "residual_cm": (100 * f.residual).tolist(),
            "rms_residual_cm": 100 * f.rms_residual,
            "explains_both": self.explains_both,
            "search_stiffness_n_m_per_rad":
                None if f.lattice is None else f.lattice[0].tolist(),
            "stiffness_within_resolution_n_m_per_rad":
                None if f.lattice is None else f.stiffness_within(self.resolution).tolist(),
        }


def compute(probe, quick: bool, n_jobs: int = 1) -> HingeResult:
    """Fit the hinge and the tip mass to the paper's 29.5 cm of 40 and 39.5 cm of 50 (the
    coarse search on ``n_jobs`` worker processes: the same fit whatever ``n_jobs``)."""
    check_step(probe=probe, quick=quick, n_jobs=n_jobs)
    observed = [printed.DEVIATION_CM.value / 100, printed.DEVIATION_50CM_PROBE_CM.value / 100]
    fit = fit_hinge_and_tip(
        probe, LENGTHS, observed, grid=3 if quick else 7, n_elements=16 if quick else 48,
        n_jobs=n_jobs,
    )
    return HingeResult(fit)


def render(result: HingeResult, report, figures) -> None:
    """The fit, its residuals and the verdict in plain words."""
    check_render(result, HingeResult, report, figures)
    f = result.fit
    report.heading("The hinge: one stiffness and one tip mass for both probes?")
    seen = " and ".join(f"at {100 * o:g} cm on a {100 * L:g} cm probe"
                        for L, o in zip(f.lengths, f.observed, strict=True))
    fractions = " and ".join(f"{o / L:.2f} L" for L, o in zip(f.lengths, f.observed, strict=True))
    report.paragraph(
        f"The paper saw the dominant frequency leave the first mode's branch {seen}: "
        f"{fractions}. A bare clamped tube "
        "puts it at the same fraction of any length; a rotational spring at the hinge and a "
        "point mass at the tip (sensor board, cable) can move it. Least squares over both: "
        f"{_fitted_words(f)} (transition located at the lowest frequency's peak)"
        + ("." if result.explains_both else
           ": the least-bad values of a model that misses the observations (below), not "
           "estimates of the rig's hinge and tip.")
    )
    report.table(
        ["probe (cm)", "paper (cm)", "fitted model (cm)", "residual (cm)"],
        [
            [f"{100 * L:g}", f"{100 * o:.1f}", f"{100 * p:.2f}", f"{100 * (p - o):+.2f}"]
            for L, o, p in zip(f.lengths, f.observed, f.predicted, strict=True)
        ],
    )
    if result.explains_both:
        verdict = (
            "One hinge-and-tip model explains both observations within their "
            f"{1000 * result.resolution:g} mm resolution."
        )
    else:
        verdict = (
            f"Under two assumptions, no single hinge-and-tip model explains both observations: "
            f"the best fit misses by {100 * f.rms_residual:.2f} cm RMS, and its largest "
            f"residual, {100 * np.max(np.abs(f.residual)):.2f} cm, is more than the "
            f"observations' {1000 * result.resolution:g} mm resolution. What else differs "
            "between the two probes, or in how the transition was located, lies outside this "
            "model's two parameters: the fit cannot say which."
        )
    report.paragraph(" ".join(filter(None, (verdict, _within_words(result),
                                            _assumptions(result)))))


def _within_words(result: HingeResult) -> str:
    """How closely the observations set the hinge: the search lattice's stiffnesses that come
    within the observations' resolution of the least misfit found, said from the lattice's
    numbers (nothing for a fit made without a search).

    Examples
    --------
    >>> from ebantenna.fem.hinge import HingeFit
    >>> one = np.ones(1)
    >>> rms = np.array([[0.03, 0.02], [0.011, 0.012], [0.012, 0.015]])
    >>> fit = HingeFit(10.0, 0.0, one, one, one + 0.011, "peak",
    ...                lattice=(np.array([1.0, 10.0, 100.0]), np.array([0.0, 0.01]), rms))
    >>> print(_within_words(HingeResult(fit)))  # doctest: +NORMALIZE_WHITESPACE
    Of the search's 3 hinge stiffnesses (1 to 100 N m/rad, each with the best of its 2 tip
    masses), those from 10 to 100 N m/rad come within the observations' 2.5 mm of the least
    misfit found (RMS), up to the top of the search: the observations cannot tell these hinges
    apart, and set no upper limit to the hinge within the search.
    """
    f = result.fit
    if f.lattice is None:  # a fit made without a search: no lattice to read
        return ""
    lattice, masses = f.lattice[0], f.lattice[1]
    within = f.stiffness_within(result.resolution)
    opening = (f"Of the search's {lattice.size} hinge stiffnesses ({_n(lattice[0])} to "
               f"{_n(lattice[-1])} N m/rad, each with the best of its {masses.size} tip masses)")
    near = (f"within the observations' {1000 * result.resolution:g} mm of the least misfit "
            "found (RMS)")
    if within.size == 0:
        return f"{opening}, none comes {near}."
    index = np.flatnonzero(np.isin(lattice, within))
    if within.size == 1:
        others = [_n(lattice[j]) for j in (index[0] - 1, index[0] + 1) if 0 <= j < lattice.size]
        miss = "its neighbour ({} N m/rad) misses" if len(others) == 1 else \
            "its neighbours ({} N m/rad) miss"
        return (f"{opening}, only {_n(within[0])} N m/rad comes {near}; "
                f"{miss.format(' and '.join(others))} by more: the observations set the hinge "
                "to within that step of the search.")
    if np.any(np.diff(index) != 1):
        listed = ", ".join(_n(k) for k in within)
        return (f"{opening}, {listed} N m/rad come {near}, and stiffnesses between them do "
                "not: the observations do not set the hinge to one range.")
    ends = [end for end, at in (("bottom", index[0] == 0), ("top", index[-1] == lattice.size - 1))
            if at]
    reach = "".join(f", {'down' if e == 'bottom' else 'up'} to the {e} of the search"
                    for e in ends)
    if len(ends) == 2:
        unset = ", and set neither a lower nor an upper limit"
    elif ends:
        unset = f", and set no {'lower' if ends[0] == 'bottom' else 'upper'} limit"
    else:
        unset = ""
    return (f"{opening}, those from {_n(within[0])} to {_n(within[-1])} N m/rad come {near}"
            f"{reach}: the observations cannot tell these hinges apart{unset}"
            + (" to the hinge within the search." if ends else "."))


def _n(x: float) -> str:
    """``x`` to three significant figures, without an exponent (1000, 147, 0.0681)."""
    return np.format_float_positional(x, precision=3, unique=False, fractional=False, trim="-")


def _assumptions(result: HingeResult) -> str:
    """The two assumptions the verdict rests on, which the paper leaves open."""
    return (
        f"The two assumptions, which the paper leaves open: that its points were read to "
        f"{1000 * result.resolution:g} mm, half its 5 mm contact step (the paper states no "
        "precision for them); and that its 'deviation from the linear variation' is where the "
        "lowest frequency peaks, which is where the model locates the transition."
    )


def _fitted_words(f) -> str:
    """The fitted hinge and tip mass, each at a bound of its search said to be the bound's
    value, which the observations did not set.

    Examples
    --------
    >>> from ebantenna.fem.hinge import HingeFit
    >>> _fitted_words(HingeFit(5.83, 6.7e-17, np.ones(1), np.ones(1), np.ones(1), "peak"))
    'hinge 5.83 N m/rad, tip mass at its lower bound, 0 g: the observations do not set it'
    """
    bound = f.at_bound
    parts = []
    for name, words, value, unit, scale, bounds in (
        ("hinge_stiffness", "hinge", f.hinge_stiffness, "N m/rad", 1.0, f.stiffness_bounds),
        ("tip_mass", "tip mass", f.tip_mass, "g", 1e3, f.mass_bounds),
    ):
        side = bound.get(name)
        if side is None:
            parts.append(f"{words} {scale * value:.3g} {unit}")
        else:
            at = bounds[0] if side == "lower" else bounds[1]
            parts.append(f"{words} at its {side} bound, {scale * at:g} {unit}: the observations "
                         "do not set it")
    return ", ".join(parts)
