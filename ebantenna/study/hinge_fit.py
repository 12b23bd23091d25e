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
        transitions and residuals (cm)."""
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
    report.paragraph(verdict + " " + _assumptions(result))


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
