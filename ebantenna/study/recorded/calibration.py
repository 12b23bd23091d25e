"""Calibrating the scene from recordings: hinge stiffness, tip mass and loss factor.

A handful of recordings at known contact distances fix the probe's two unknown boundary
parameters. The dominant frequency of a touch in the first part of the probe is its lowest mode
(:mod:`ebantenna.fem.hinge`), and that depends on the hinge's rotational stiffness ``k_h``
(N m/rad) and the tip mass ``m_t`` (kg): a soft hinge lowers it most for contacts near the hinge,
a heavy tip most for contacts far from it, so recordings spread over the distances separate the
two. :func:`calibrate` fits ``(log10 k_h, m_t)`` by least squares to the measured frequencies with
:func:`~ebantenna.fem.sweeps.natural_frequencies`, and states the fit's uncertainty as the sum of
two covariances: the residuals' scatter, ``s^2 (J^T J)^-1`` of the linearised problem at the
optimum (``s^2`` the residuals' variance over ``n - 2`` degrees of freedom), and the time base's:
every frequency is measured against the host's clock, known to a relative ``time_base``
(default :data:`TIME_BASE`, a crystal's 100 ppm), which shifts the parameters by
``dp = J^+ (time_base f)`` together (covariance ``dp dp^T``). The scatter alone understates it: a
common scale error of all frequencies does not show in the residuals.

The loss factor comes from the decay of the same mode: band-passed about the dominant frequency
(+/- 25 %), its Hilbert envelope falls as ``exp(-eta omega t / 2)`` (hysteretic damping, damping
ratio ``eta / 2``), so the slope ``b`` of the envelope's logarithm gives ``eta = -2 b / omega``.
Only recordings whose fitted stretch spans at least :data:`MIN_CYCLES` periods are used (a band
filter smears a decay of fewer, and the estimate falls short of the truth by a few per cent); the
uncertainty stated is the estimates' spread (their standard deviation), which holds that bias,
not their standard error, which would not.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import least_squares
from scipy.signal import butter, hilbert, sosfiltfilt

from ...fem.sweeps import natural_frequencies
from ...paper.protocol import DECAY_REGION

__all__ = ["Calibration", "calibrate", "loss_factor_of", "MIN_CYCLES", "TIME_BASE",
           "plot_calibration"]

#: Fewest periods of the dominant mode a decay fit must span.
MIN_CYCLES = 8
#: Relative uncertainty of the host's time base the frequencies are measured against.
TIME_BASE = 1e-4
#: Two-sided 95 % quantile of the standard normal.
Z95 = 1.959963984540054


@dataclass(frozen=True)
class Calibration:
    """Fitted hinge stiffness, tip mass and loss factor, with their standard uncertainties.

    Attributes
    ----------
    hinge_stiffness : float
        N m/rad.
    log10_stiffness_sd : float
        Standard uncertainty of ``log10(hinge_stiffness)``.
    tip_mass, tip_mass_sd : float
        kg.
    loss_factor, loss_factor_sd : float
        Dimensionless.
    contacts, measured_hz, fitted_hz : ndarray
        The recordings used for the fit: contact distance (m), measured and fitted dominant
        frequency (Hz).
    decay_used : int
        Recordings whose decay gave the loss factor.
    """

    hinge_stiffness: float
    log10_stiffness_sd: float
    tip_mass: float
    tip_mass_sd: float
    loss_factor: float
    loss_factor_sd: float
    contacts: np.ndarray
    measured_hz: np.ndarray
    fitted_hz: np.ndarray
    decay_used: int

    def interval(self, name: str) -> tuple[float, float]:
        """The 95 % interval of ``"hinge_stiffness"``, ``"tip_mass"`` or ``"loss_factor"``
        (``(0, inf)`` for a stiffness the recordings do not determine, e.g. a hinge stiffer than
        the tube can feel)."""
        if name == "hinge_stiffness":
            exponent = Z95 * self.log10_stiffness_sd
            if not exponent < 300:  # the recordings do not pin the stiffness down
                return 0.0, math.inf
            spread = 10.0 ** exponent
            return self.hinge_stiffness / spread, self.hinge_stiffness * spread
        value, sd = getattr(self, name), getattr(self, f"{name}_sd")
        return value - Z95 * sd, value + Z95 * sd

    @property
    def rms_residual_hz(self) -> float:
        """Root-mean-square of fitted minus measured frequency, Hz."""
        return float(np.sqrt(np.mean((self.fitted_hz - self.measured_hz) ** 2)))

    def scene(self, base):
        """``base`` (an :class:`ebantenna.simulate.Scene`) with the fitted hinge, tip mass and
        loss factor; save it with :meth:`~ebantenna.simulate.Scene.save` for ``simulate`` and
        ``dataset``. The ``tip_mass`` effect must be in ``base``."""
        probe = replace(base.probe, tip_mass=self.tip_mass, loss_factor=self.loss_factor)
        return base.with_(name=f"{base.name}-calibrated", probe=probe,
                          hinge=self.hinge_stiffness)

    def to_dict(self) -> dict:
        """JSON values: each parameter with its uncertainty and 95 % interval (an unbounded end
        as None)."""
        out = {"recordings": int(self.contacts.size), "decay_recordings": self.decay_used,
               "rms_residual_hz": self.rms_residual_hz,
               "log10_hinge_stiffness_sd": self.log10_stiffness_sd,
               "tip_mass_sd_kg": self.tip_mass_sd, "loss_factor_sd": self.loss_factor_sd,
               "hinge_stiffness_n_m_per_rad": self.hinge_stiffness, "tip_mass_kg": self.tip_mass,
               "loss_factor": self.loss_factor}
        for name in ("hinge_stiffness", "tip_mass", "loss_factor"):
            out[f"{name}_interval95"] = [v if math.isfinite(v) else None
                                         for v in self.interval(name)]
        return out


def loss_factor_of(x, fs: float, frequency: float) -> tuple[float, float, float]:
    """The decay of the mode near ``frequency`` (Hz) in the signal ``x`` sampled at ``fs`` (Hz).

    Returns ``(eta, f, periods)``: the loss factor from the envelope's slope, the mode's
    frequency from the analytic signal's phase slope (Hz; finer than a spectral peak's, whose
    bins are ``fs / n`` wide) and the periods the fit spans (see the module notes).
    """
    x = np.asarray(x, dtype=float) - np.mean(x)
    sos = butter(2, [0.75 * frequency, 1.25 * frequency], btype="band", fs=fs, output="sos")
    analytic = hilbert(sosfiltfilt(sos, x))
    envelope = np.abs(analytic)
    t = np.arange(x.size) / fs
    peak = int(envelope.argmax())
    keep = ((t > t[peak] + 2.0 / frequency) & (t < t[-1] - 2.0 / frequency)
            & (envelope > 0.05 * envelope[peak]))
    if keep.sum() < 3:
        return math.nan, math.nan, 0.0
    slope = np.polyfit(t[keep], np.log(envelope[keep]), 1)[0]
    phase = np.polyfit(t[keep], np.unwrap(np.angle(analytic))[keep], 1)[0]
    omega = abs(phase)
    return float(-2.0 * slope / omega), float(omega / (2 * np.pi)), float(
        keep.sum() / fs * frequency)


def calibrate(ds, probe, *, stiffness_bounds=(1e-1, 1e4), mass_bounds=(0.0, 0.02),
              region: float = DECAY_REGION, n_elements: int = 48,
              time_base: float = TIME_BASE) -> Calibration:
    """Fit hinge stiffness, tip mass and loss factor to a data set's recordings.

    Parameters
    ----------
    ds : ebantenna.simulate.Dataset
        Recordings at known contact distances (e.g. assembled from a session).
    probe : ebantenna.Probe
        The tube (length, section, material); its tip mass and loss factor are fitted.
    stiffness_bounds : (float, float)
        Range of the hinge stiffness, N m/rad.
    mass_bounds : (float, float)
        Range of the tip mass, kg.
    region : float
        Only contacts within this fraction of the probe's length are used (the lowest mode
        dominates there). Default the paper's 0.8.
    n_elements : int
        Beam elements of the model.
    time_base : float
        Relative uncertainty of the clock the frequencies were measured against.

    Returns
    -------
    Calibration
    """
    from ...paper.feature_table import signal_features

    use = np.flatnonzero(ds.contact <= region * probe.length)
    if use.size < 3 or np.unique(ds.contact[use]).size < 2:
        raise ValueError(f"calibration needs at least 3 recordings at 2 or more distances within "
                         f"{region:g} L of the hinge, got {use.size}")
    feats = signal_features(ds.ax[use], ds.az[use], ds.fs, n_jobs=1, show_progress=False)
    contacts = np.asarray(ds.contact[use], float)
    decays = [loss_factor_of(x, ds.fs, f) for x, f in zip(ds.ax[use], feats.dominant,
                                                          strict=True)]
    measured = np.array([f if cycles >= MIN_CYCLES else dominant
                         for (_, f, cycles), dominant in zip(decays, feats.dominant, strict=True)])

    def model(p):
        tube = replace(probe, tip_mass=float(p[1]))
        return natural_frequencies(tube, contacts, hinge=float(10.0 ** p[0]),
                                   n_elements=n_elements, n_modes=1)[:, 0]

    bounds = ([math.log10(stiffness_bounds[0]), mass_bounds[0]],
              [math.log10(stiffness_bounds[1]), mass_bounds[1]])
    start = [0.5 * (bounds[0][0] + bounds[1][0]), 0.5 * (mass_bounds[0] + mass_bounds[1])]
    fit = least_squares(lambda p: model(p) - measured, start, bounds=bounds,
                        x_scale=[0.5, 0.002], diff_step=1e-6)
    dof = max(contacts.size - 2, 1)
    s2 = 2.0 * fit.cost / dof
    shift = np.linalg.lstsq(fit.jac, time_base * measured, rcond=None)[0]
    cov = s2 * np.linalg.pinv(fit.jac.T @ fit.jac) + np.outer(shift, shift)
    eta, sd, used = _loss_factor(decays)
    return Calibration(float(10.0 ** fit.x[0]), float(np.sqrt(cov[0, 0])), float(fit.x[1]),
                       float(np.sqrt(cov[1, 1])), eta, sd, contacts, measured, model(fit.x), used)


def _loss_factor(decays) -> tuple[float, float, int]:
    """Mean loss factor of the decays that span :data:`MIN_CYCLES`, and their spread."""
    etas = np.array([eta for eta, _, cycles in decays if cycles >= MIN_CYCLES and eta > 0])
    if etas.size < 2:
        raise ValueError(f"the loss factor needs 2 or more recordings whose decay spans "
                         f"{MIN_CYCLES} periods; got {etas.size}")
    return float(etas.mean()), float(etas.std(ddof=1)), int(etas.size)


def plot_calibration(cal: Calibration, probe, *, n_elements: int = 48):
    """Measured against simulated (fitted) dominant frequency versus contact distance."""
    import matplotlib.pyplot as plt

    grid = np.linspace(cal.contacts.min(), cal.contacts.max(), 60)
    tube = replace(probe, tip_mass=cal.tip_mass)
    curve = natural_frequencies(tube, grid, hinge=cal.hinge_stiffness, n_elements=n_elements,
                                n_modes=1)[:, 0]
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(100 * cal.contacts, cal.measured_hz, "o", label="measured (recordings)")
    ax.plot(100 * grid, curve, "-", label=f"simulated: k_h = {cal.hinge_stiffness:.3g} N m/rad, "
            f"m_t = {1000 * cal.tip_mass:.2f} g")
    ax.set_xlabel("contact distance from the hinge (cm)")
    ax.set_ylabel("dominant frequency (Hz)")
    ax.legend()
    fig.tight_layout()
    return fig
