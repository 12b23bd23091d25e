"""Calibrating the scene from recordings: hinge stiffness, tip mass and loss factor.

A handful of recordings at known contact distances fix the probe's unknown boundary parameters:
the hinge's rotational stiffness ``k_h`` (N m/rad), the tip mass ``m_t`` (kg) and the tube's loss
factor ``eta``. What follows fits them with **the scene's own model** and says, for each, whether
the recordings determine it.

The model
    The recordings are fitted with the model the scene simulates them with
    (:mod:`ebantenna.simulate.touched_object`): with the ``object_modes`` effect, the probe and
    the touched rod joined by the contact spring, each body damped as the simulator damps it;
    with ``unilateral_contact``, the strike's two bodies with the contact closed (the probe
    presses on the rod once the servo has stopped) and their modal viscous damping
    (:mod:`ebantenna.simulate.strikes`); without ``object_modes``, the probe arrested by a pin
    (or the ``contact_compliance`` spring). Leaving the rod out of the model, or damping the
    probe's arrested modes by ``eta`` when the simulator damps its free-interface modes, fits
    numbers the recordings do not contain: on the ``paper`` scene the decays then read 0.019 to
    0.024 for a tube of 0.03.

The mode fitted, by identity
    In every recording the mode fitted is the model's **lowest mode that shows at the sensor**
    (at least :data:`MIN_SHARE` of the largest modal displacement at the tip below ``fs / 2``):
    the probe's first arrested mode, not "the strongest peak", which in acceleration is often a
    higher mode or one of the rod's. Its frequency is measured where the model puts it: the
    recording is band-passed about the predicted frequency (+/- 25 %) and the mode's frequency
    read from the analytic signal's phase slope (:func:`loss_factor_of`). The fit starts from
    the hinge (a grid of decades) and the tip mass (a grid over the whole range searched, its
    neighbours' modes ``START_STEP`` apart) whose modes fall on the recordings' spectral
    peaks (a grid that stopped at half the range started a 12-15 g tip at 5 g, outside the
    band, and its recordings were refused), and alternates measuring at the prediction and
    fitting until the measured frequencies and the modes fitted no longer change (by
    ``SETTLED``). Each fit holds the mode at each position: the rule applied at every trial
    would switch to another mode where the lowest one's share crosses :data:`MIN_SHARE`, the
    misfit would jump there, and the fit could stop at the jump (a clamped probe without a tip
    mass once stopped at 27.7 N m/rad, its interval excluding the clamp).

Positions the estimator cannot read
    Every recording the fit does not use is in ``left_out`` with the reason: beyond ``region``;
    at a position where the model has no mode the recordings resolve, or where its other modes
    crowd the fitted one (below); or where the estimator reads nothing (the envelope first peaks
    too late in the record, or falls below 5 % within two periods) or a frequency outside the
    band (another mode). A position none of whose recordings is read is left out whole (a
    lightly damped tube's 5 cm position once left the fit so, ``left_out`` empty); recordings
    read at fewer than 3 positions are refused, each of the others named with its reason.

    A band of +/- 25 % with a second-order filter lets the model's other modes through. Where
    they move what the estimator reads of the fitted mode by more than :data:`CROWDING` (the
    model's modes within half to twice its frequency, each ringing beside it at its share of the
    acceleration and at the phase that moves the reading most), the position is left out of the
    fit, with the reason (``left_out``). On the ``paper`` scene without a tip mass, the touched
    rod's 91 Hz mode rings beside the probe's 84 Hz one at 30 cm and moves its reading by 6 %.
    What the check does not count is not
    modelled: a reading can be off the model's at the truth by more than the check allows (found
    at 30 cm on the ``paper`` scene with a light tip and a 60 N m/rad hinge, off by about 1e-3),
    and a hinge that moves the frequencies by less than that is located with a bias its interval
    does not include.

The measurement, modelled
    The estimator has a bias of its own on a short decay: a few parts in 10^4 of the frequency
    and 10 % of the loss factor for an 11 Hz mode over one second (it fits the band-passed
    signal's envelope and phase between the filter's transients), which is more than the time
    base's 10^-4 and would pass for a hinge softer than the truth. The model is therefore read
    through the same estimator (``as_measured``): the fitted mode rings alone over the
    recording's length, its envelope first peaking where the recording's does, and what the
    estimator reads from it is compared with what it reads from the recording, so the bias
    cancels.

Frequencies: hinge and tip mass
    The independent unit is the contact position (a material at a distance, or a distance alone
    where the model gives every material the same modes, as the pinned probe does): repetitions
    there share the model's error, so each position's frequency is the mean of its recordings'.
    ``(log10 k_h, m_t)`` are fitted by least squares to the relative misfit ``f_model / f - 1``
    over the ``n`` positions. The covariance is the residuals' scatter, ``s^2 (J^T J)^-1`` at the
    optimum (``s^2`` over ``n - 2`` degrees of freedom), plus the time base's: every frequency is
    measured against the host's clock, known to a relative ``time_base`` (default
    :data:`TIME_BASE`, a crystal's 100 ppm), which shifts the parameters by ``J^+ time_base``
    together. Intervals use Student's ``t`` with ``n - 2`` degrees of freedom (``s^2`` is
    estimated from few positions).

Identifiability
    The hinge is profiled: at each trial ``log10 k_h`` the tip mass is fitted again, and the trial
    is within the 95 % set while the sum of squared misfits exceeds the optimum's by at most
    ``t^2 (s^2 + time_base^2)`` (``t^2`` the 95 % quantile of ``F(1, n - 2)``); the hinge's
    interval is that set, not the linearised one. If the set reaches an end of
    ``stiffness_bounds`` the recordings cannot bound the stiffness on that side (stiffer than the
    set's lower end, a hinge is a clamp to them) and the hinge is reported **not identifiable**,
    with the one-sided interval and an :class:`IdentifiabilityWarning` that names it -- never the
    optimiser's bound as a value. The tip mass's interval then spans its fits over the whole set.
    A tip mass whose interval reaches an end of ``mass_bounds`` is reported not identifiable too,
    bounded on the other side only (recordings of a probe without a tip mass give "at most" a
    few tenths of a milligram, never the fit at 0 as a value).

Lack of fit
    Whether the model misses the recordings by more than they scatter is tested with the
    repetitions, the textbook lack-of-fit F test: each recording's relative residual
    ``f / f_model - 1`` splits into its position's mean residual (the lack of fit, ``n - 2`` degrees
    of freedom) and its scatter about that mean (the pure error, ``N - n``); their mean squares'
    ratio is ``F(n - 2, N - n)`` when the model is right and the repetitions independent. They
    are not: the repetitions at a position are near copies, measured against one clock, and
    share an error that their scatter does not show. Each position's frequency is therefore
    taken as uncertain by at least ``time_base`` (its square, times the repetitions per
    position, added to the pure error's mean square): without that floor the scene's own model,
    fitted to its own simulated recordings, was rejected in most scenes tried, by misfits of
    about 1e-4 where the repetitions agreed to 3e-5. A rejection at :data:`LACK_OF_FIT_LEVEL` is
    reported (:attr:`Calibration.fit_statement`, a :class:`ModelMisfitWarning`): the intervals
    above take the misfit between positions as random, which a misfit the model makes, or one
    the near-copy repetitions at a position share, is not. The test needs two recordings at some
    position.

Loss factor
    The decay of the fitted mode in each recording gives its loss factor as read: the band-passed
    Hilbert envelope falls as ``exp(-eta omega t / 2)``. The mode's loss factor that the
    estimator reads as that (``as_measured``, inverted by secant steps) is, in the model,
    affine in the tube's, ``a_i + b_i eta`` (the rod's and the contact's damping in ``a_i``;
    ``b_i`` the tube's share), so each recording gives one ``eta``; each position's are averaged.
    Only recordings whose fitted stretch spans at least :data:`MIN_CYCLES` periods are used, and
    whose mode the tube damps (``b_i`` at least :data:`MIN_SHARE`); the uncertainty is the
    positions' spread (their standard deviation), not its standard error, and the 95 % interval
    that spread times Student's quantile for the positions' number less one (at least as wide as
    the t interval of their mean, however few the positions). A scene without
    ``structural_damping`` has no tube loss to fit: the loss factor is then not identifiable.

Decays too slow to show
    A decay too slow to show within the record leaves the band envelope flat, wavering by a few
    per cent as the other modes beat through the band: its largest value then falls anywhere,
    often late, and read from there an undamped tube's recordings left nothing to read at most
    positions, which were refused (their frequency with them). Each recording is read from
    where its envelope first peaks (``_onset``: its largest value within ``RISE`` periods of
    first reaching ``ONSET`` of it), which for a decay that shows is its largest value. A
    reading of 0 or below (an envelope that does not fall, or the estimator's own bias on one
    that barely does) is inverted and averaged like any other: dropping it kept only the
    readings that happened to fall. Where the positions' interval then reaches 0 the loss
    factor is bounded from above, not estimated (the tests' modal rig, a 20 N m/rad hinge and a
    4 g tip, with an undamped tube: at most 6e-4, its hinge and tip mass recovered within their
    intervals).

Measured on the simulated rig (``ebantenna record --simulated --scene paper``, seed 0, brass at
5, 10, 15, 20, 25 and 30 cm, two repetitions, calibrated with ``--scene paper``): a tip mass of
2.499 g (95 % 2.490-2.507 g, truth 2.5 g), a loss factor of 0.0298 (0.0293-0.0304, truth 0.03)
and a hinge not identifiable, stiffer than about 840 N m/rad (a clamp); the same scene with a
5 N m/rad hinge gives 4.91 (4.75-5.08) N m/rad. ``tests/study/test_recorded_calibration.py``
checks, on five of these positions and another seed, that each interval holds the truth.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares
from scipy.signal import butter, hilbert, sosfiltfilt
from scipy.stats import f as fisher_f
from scipy.stats import t as student_t

from ..._validate import check_array, check_in_range, check_int, check_real, describe
from ...paper.protocol import DECAY_REGION
from ...probe import MAX_TIP_MASS_RATIO

__all__ = ["Calibration", "calibrate", "loss_factor_of", "IdentifiabilityWarning",
           "ModelMisfitWarning", "MIN_CYCLES", "MIN_SHARE", "TIME_BASE", "LACK_OF_FIT_LEVEL",
           "CROWDING", "plot_calibration"]

#: Fewest periods of the fitted mode a decay fit must span.
MIN_CYCLES = 8
#: Least share (of the largest modal tip displacement; of the mode's damping, for the tube's part)
#: for a mode to count as showing at the sensor, and for a decay to count as the tube's.
MIN_SHARE = 0.1
#: Relative uncertainty of the host's time base the frequencies are measured against.
TIME_BASE = 1e-4
#: Relative change of the measured frequencies below which measuring at the prediction and
#: fitting have settled: a tenth of the time base's uncertainty.
SETTLED = 1e-5
#: Half-width of the band about a mode's frequency (relative), as in :func:`loss_factor_of`.
BAND = 0.25
#: Hinge stiffnesses searched, relative to the tube's bending stiffness ``E I / L`` (N m/rad):
#: a hinge a million times stiffer than the tube is a clamp to the model's double precision
#: (its compliance changes a frequency by about 1e-6 relative, below the 1e-4 time base), and one
#: a thousandth of it lets the tube swing as a pendulum on the spring.
STIFFNESS_RANGE = (1e-3, 1e6)
#: Periods of a mode a recording must hold for the decay reading to see it: the band envelope
#: of a mode ringing from rest peaks 0.5 to 1.5 periods in (measured from 11 to 120 Hz at
#: 1000 Hz), and :func:`loss_factor_of` reads from two periods past the peak to two before the
#: end.
READ_PERIODS = 5.5
#: Ratio of the modes of neighbouring tip masses of the start's grid (``_mass_grid``): a mass
#: between two has modes within its square root, 14 %, of one of them's, inside the +/- 25 %
#: band (:data:`BAND`) the measurement reads about a prediction.
START_STEP = 1.3
#: Where a decay starts (``_onset``): at the band envelope's largest value within ``RISE``
#: periods of where it first reaches ``ONSET`` of its largest value. A mode ringing from rest
#: peaks 0.5 to 1.5 periods in (see :data:`READ_PERIODS`), having passed half its peak before.
ONSET, RISE = 0.5, 2.0
#: Largest relative change that the model's other modes, ringing beside the fitted one at any
#: phase, may make to what the estimator reads of it: the time base's uncertainty. A position
#: where they move it more is left out of the fit.
CROWDING = 1e-4
#: Level of the lack-of-fit test (module notes): the model is said to miss the recordings when
#: the test rejects at this level, the complement of the intervals' 95 %.
LACK_OF_FIT_LEVEL = 0.05


class IdentifiabilityWarning(UserWarning):
    """A calibrated parameter the recordings do not determine (its name is in the message)."""


class ModelMisfitWarning(UserWarning):
    """The scene's model misses the recordings by more than their repetitions scatter (the
    lack-of-fit test rejects it): the intervals then rest on the misfit being random between
    positions."""


@dataclass(frozen=True)
class Calibration:
    """Fitted hinge stiffness, tip mass and loss factor, with their 95 % intervals.

    Attributes
    ----------
    hinge_stiffness : float
        N m/rad: the best fit. For a hinge not identifiable it is where the optimiser stopped,
        not an estimate: :meth:`to_dict` gives None and the one-sided interval, and
        :meth:`scene` writes a clamp where the interval has no upper end.
    log10_stiffness_sd : float
        Standard uncertainty of ``log10(hinge_stiffness)`` from the linearised fit (inf when the
        hinge is not identifiable).
    tip_mass, tip_mass_sd : float
        kg.
    loss_factor, loss_factor_sd : float
        Dimensionless (NaN when not identifiable).
    contacts, measured_hz, fitted_hz : ndarray
        The contact positions fitted (m), and at each the measured frequency of the fitted mode
        (the mean over its recordings) and the model's (Hz).
    decay_used : int
        Recordings whose decay gave the loss factor.
    intervals : dict
        ``name -> (low, high)``, the 95 % interval of each parameter (an open end as 0 or inf).
    not_identifiable : dict
        ``name -> reason`` for each parameter the recordings do not determine.
    model : str
        What the fitted model contains.
    lack_of_fit : dict
        The lack-of-fit test (module notes): ``f``, ``df`` (lack of fit, pure error), ``p``
        (``f`` and ``p`` None where it cannot be tested) and ``largest`` (the contact, m, and
        the relative misfit of the position the model misses most).
    left_out : dict
        ``"contact m (material)" -> reason`` for each position left out of the fit: beyond
        ``region``, where the model's other modes ring beside the fitted one, where it has no
        mode the recordings resolve, or where none of its recordings could be read; and
        ``"contact m (material), recording r" -> reason`` for a recording (row ``r`` of the
        data set) not read at a position fitted from its others. Nothing recorded leaves the
        fit without an entry here.
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
    intervals: dict = field(default_factory=dict)
    not_identifiable: dict = field(default_factory=dict)
    model: str = ""
    lack_of_fit: dict = field(default_factory=dict)
    left_out: dict = field(default_factory=dict)

    def interval(self, name: str) -> tuple[float, float]:
        """The 95 % interval of ``"hinge_stiffness"``, ``"tip_mass"`` or ``"loss_factor"``
        (an end the recordings do not bound is 0 or inf)."""
        if not isinstance(name, str) or name not in self.intervals:
            raise ValueError(f"name must be one of {', '.join(PARAMETERS)}; got {name!r}")
        return self.intervals[name]

    def _value(self, name: str):
        """The fitted value for JSON: None where the recordings do not determine it (the fit
        is then a search bound or wherever the optimiser stopped, not an estimate)."""
        return None if name in self.not_identifiable else _json(getattr(self, name))

    def identifiable(self, name: str) -> bool:
        """Whether the recordings determine ``name``."""
        self.interval(name)
        return name not in self.not_identifiable

    @property
    def held_at_fit_stop(self) -> tuple[str, ...]:
        """The parameters that :meth:`scene` writes at the fit's stopping point, which the
        recordings do not determine (not estimates): those ``not_identifiable`` but a hinge
        not bounded from above (written as a clamp) and a loss factor (``base``'s is kept)."""
        return tuple(name for name in ("hinge_stiffness", "tip_mass")
                     if name in self.not_identifiable and not self._clamped(name))

    def _clamped(self, name: str) -> bool:
        """Whether :meth:`scene` writes ``name`` as a clamp: a hinge not bounded from above."""
        return name == "hinge_stiffness" and math.isinf(self.intervals[name][1])

    @property
    def misses_recordings(self) -> bool:
        """Whether the lack-of-fit test rejects the model at :data:`LACK_OF_FIT_LEVEL`."""
        p = self.lack_of_fit.get("p")
        return p is not None and p < LACK_OF_FIT_LEVEL

    @property
    def fit_statement(self) -> str:
        """What the lack-of-fit test says of the model, generated from its numbers."""
        test = self.lack_of_fit
        if test.get("p") is None:
            why = ("the repetitions and the model agree exactly" if min(test.get("df", [0]))
                   >= 1 else "no position was recorded twice, or there are no more positions "
                   "than parameters")
            size = ""
            if test.get("rms_misfit") is not None and test.get("clock"):
                size = (f" (the positions' misfit is {100 * test['rms_misfit']:.2g} % RMS, "
                        f"{test['rms_misfit'] / test['clock']:.2g} times the clock's "
                        "uncertainty: a model that misses by more than the recordings would "
                        "scatter is not caught)")
            return (f"the lack of fit is not tested: {why}; the intervals take the misfit "
                    f"between positions as random{size}")
        numbers = (f"lack-of-fit F = {test['f']:.3g} on {test['df'][0]} and {test['df'][1]} "
                   f"degrees of freedom, p = {test['p']:.2g}")
        scatter = ("the clock's uncertainty (larger here than the repetitions' scatter)"
                   if test.get("error_from") == "clock" else "the repetitions' scatter")
        if not self.misses_recordings:
            return f"the model fits within {scatter} ({numbers})"
        contact, misfit = test["largest"]
        return (f"the model misses the positions by more than {scatter} allows "
                f"({numbers}; the recordings differ most from it at {contact:g} m, by "
                f"{100 * misfit:+.2g} %): the intervals are set by the misfit between positions "
                "as if it were random, but part of it is the model's (a mode it places wrong, "
                "an effect the scene leaves out) or shared by the near-copy repetitions at a "
                "position, and a systematic part biases the parameters beyond their intervals")

    @property
    def rms_residual_hz(self) -> float:
        """Root-mean-square of fitted minus measured frequency, Hz."""
        return float(np.sqrt(np.mean((self.fitted_hz - self.measured_hz) ** 2)))

    def scene(self, base):
        """``base`` (an :class:`ebantenna.simulate.Scene`) with the fitted hinge, tip mass and
        loss factor; save it with :meth:`~ebantenna.simulate.Scene.save` for ``simulate`` and
        ``dataset``. A hinge not bounded from above is written as a clamp (what the recordings
        cannot tell it from); a loss factor not identifiable keeps ``base``'s. A scene must hold
        a value: any other parameter the recordings do not determine is written at the fit's
        stopping point, which is not an estimate (:attr:`Calibration.held_at_fit_stop` names
        them)."""
        from ...simulate.scene import Scene

        if not isinstance(base, Scene):
            raise TypeError(f"base must be a Scene (the one calibrated), got "
                            f"{type(base).__name__}")
        hinge = "clamped" if self._clamped("hinge_stiffness") else self.hinge_stiffness
        eta = base.probe.loss_factor if "loss_factor" in self.not_identifiable else (
            self.loss_factor)
        return _candidate(base, hinge, self.tip_mass, eta).with_(name=f"{base.name}-calibrated")

    def to_dict(self) -> dict:
        """JSON values: each parameter with its uncertainty, 95 % interval (an unbounded end as
        None) and identifiability (None, or the reason it is not identifiable); what was fitted:
        ``contact_materials``, the positions (a distance and a material, or a distance alone
        where the model does not tell the materials apart), each the mean of its recordings, at
        ``distances`` distinct distances."""
        out = {"contact_materials": int(self.contacts.size),
               "distances": len(set(self.contacts.tolist())),
               "decay_recordings": self.decay_used,
               "rms_residual_hz": self.rms_residual_hz, "model": self.model,
               "log10_hinge_stiffness_sd": _json(self.log10_stiffness_sd),
               "tip_mass_sd_kg": _json(self.tip_mass_sd),
               "loss_factor_sd": _json(self.loss_factor_sd),
               "hinge_stiffness_n_m_per_rad": self._value("hinge_stiffness"),
               "tip_mass_kg": self._value("tip_mass"),
               "loss_factor": self._value("loss_factor"),
               "left_out": dict(self.left_out),
               "lack_of_fit": {**self.lack_of_fit, "model_misses_recordings":
                               self.misses_recordings, "statement": self.fit_statement}}
        for name in PARAMETERS:
            # an end the recordings do not bound is None: infinite, or a stiffness of 0 (on the
            # log scale searched, no lower end); a mass or a loss factor of 0 is a real end
            out[f"{name}_interval95"] = [
                v if math.isfinite(v) and (v > 0 or name != "hinge_stiffness") else None
                for v in self.interval(name)]
        out["not_identifiable"] = dict(self.not_identifiable)
        return out


#: The calibrated parameters, in the order they are reported.
PARAMETERS = ("hinge_stiffness", "tip_mass", "loss_factor")


def _json(value: float):
    return float(value) if math.isfinite(value) else None


def loss_factor_of(x, fs: float, frequency: float) -> tuple[float, float, float]:
    """The decay of the mode near ``frequency`` (Hz) in the signal ``x`` sampled at ``fs`` (Hz).

    Returns ``(eta, f, periods)``: the loss factor from the envelope's slope, the mode's
    frequency from the analytic signal's phase slope (Hz; finer than a spectral peak's, whose
    bins are ``fs / n`` wide) and the periods the fit spans (see the module notes). The band
    ``frequency`` +/- 25 % must lie below ``fs / 2``.
    """
    fs = check_in_range("fs", fs, 0.0, math.inf)
    check_in_range(
        "frequency", frequency, 0.0, fs / 2 / (1 + BAND),
        reason=f"the band +/- {BAND:.0%} about it must lie below fs / 2 = {fs / 2:g} Hz")
    # the band filter runs forwards and backwards: longer than its 15 samples of edge padding
    return _decay(check_array("x", x, ndim=1, min_length=16), fs, frequency)[:3]


def _band(frequency, fs):
    """The estimator's band-pass filter about ``frequency`` (second-order sections)."""
    return butter(2, [(1 - BAND) * frequency, (1 + BAND) * frequency], btype="band", fs=fs,
                  output="sos")


def _decay(x, fs, frequency, sos=None):
    """:func:`loss_factor_of` on checked values (``sos``: its band filter about ``frequency``,
    when already designed), and the index of the band envelope's first peak, where the decay
    read starts (``_onset``)."""
    x = np.asarray(x, dtype=float) - np.mean(x)
    sos = _band(frequency, fs) if sos is None else sos
    analytic = hilbert(sosfiltfilt(sos, x))
    envelope = np.abs(analytic)
    t = np.arange(x.size) / fs
    peak = _onset(envelope, fs / frequency)
    keep = ((t > t[peak] + 2.0 / frequency) & (t < t[-1] - 2.0 / frequency)
            & (envelope > 0.05 * envelope[peak]))
    if keep.sum() < 3:
        return math.nan, math.nan, 0.0, peak
    slope = np.polyfit(t[keep], np.log(envelope[keep]), 1)[0]
    phase = np.polyfit(t[keep], np.unwrap(np.angle(analytic))[keep], 1)[0]
    omega = abs(phase)
    return (float(-2.0 * slope / omega), float(omega / (2 * np.pi)),
            float(keep.sum() / fs * frequency), peak)


def _onset(envelope, period: float) -> int:
    """Where the decay starts: the largest value of the band envelope within ``RISE``
    periods (``period``, in samples) of where it first reaches ``ONSET`` of its largest
    value.

    A mode ringing from rest rises through half its peak and to the peak within a period or
    two, and falls from there, so for a decay that shows within the record this is the
    envelope's largest value. A decay too slow to show leaves the envelope flat, wavering by a
    few per cent as the model's other modes beat through the band: its largest value then falls
    anywhere, late in the record as often as not, where too little is left to read.

    Examples
    --------
    >>> _onset(np.array([0.1, 0.6, 1.0, 0.9, 0.8, 0.7]), 2.0)
    2
    >>> _onset(np.array([0.1, 0.6, 0.97, 0.95, 0.96, 0.96, 1.0]), 2.0)  # flat: not the late 1.0
    2
    """
    start = int(np.argmax(envelope >= ONSET * envelope.max()))
    return start + int(np.argmax(envelope[start:start + max(int(RISE * period), 1) + 1]))


def as_measured(frequency: float, loss: float, n: int, fs: float, peak: int, *, lag=None,
                band=None, sos=None):
    """What :func:`loss_factor_of` reads from one mode alone: ``(eta, f)`` (takes checked
    values: a band that lies below ``fs / 2``).

    The mode (damped frequency ``frequency`` Hz, loss factor ``loss``) rings from rest over ``n``
    samples at ``fs``, shifted so that its band envelope peaks at sample ``peak``, as the
    recording's does (``lag``, the shift, when already known), and is read with the band about
    ``band`` (Hz; default ``frequency``) the recording was read with (``sos``, that filter, when
    already designed). The estimator's own bias on a short decay -- a few parts in 10^4 of the
    frequency and 10 % of the loss factor for an 11 Hz mode over one second -- is then in the
    model as in the measurement, and cancels in their comparison.
    """
    band = frequency if band is None else band
    sos = _band(band, fs) if sos is None else sos
    x = _ringing(frequency, loss, n, fs)
    if lag is None:
        lag = peak - _decay(x, fs, band, sos)[3]
    x = np.concatenate([np.zeros(lag), x[: n - lag]]) if lag >= 0 else np.concatenate(
        [x[-lag:], np.zeros(-lag)])
    eta, f, _, _ = _decay(x, fs, band, sos)
    return eta, f


def _ringing(frequency, loss, n, fs, phase: float = 0.0):
    """One mode ringing from rest: damped frequency ``frequency`` (Hz), loss factor ``loss``
    (``phase``: its sine's phase at the start, rad)."""
    zeta = loss / 2
    omega_d = 2 * math.pi * frequency
    t = np.arange(n) / fs
    return np.exp(-zeta * omega_d / math.sqrt(1 - zeta**2) * t) * np.sin(omega_d * t + phase)


def _lag(frequency, loss, n, fs, peak, band, sos) -> int:
    """The shift that puts the ringing's band envelope peak at sample ``peak``."""
    return peak - _decay(_ringing(frequency, loss, n, fs), fs, band, sos)[3]


def _candidate(scene, hinge, tip_mass: float, loss_factor: float):
    """``scene`` with another hinge, tip mass and tube loss factor (the ``tip_mass`` effect
    listed exactly when the tip carries a mass, as a scene requires)."""
    from ...simulate.effects import TipMass

    probe = dataclasses.replace(scene.probe, tip_mass=float(tip_mass),
                                loss_factor=float(loss_factor))
    effects = tuple(e for e in scene.effects if e.name != "tip_mass")
    if tip_mass > 0:
        effects += (scene.effect("tip_mass") or TipMass(),)
    return scene.with_(probe=probe, hinge=hinge, effects=effects)


def _closed_contact_modes(strike):
    """Modes of a strike's two bodies with the contact closed: damped frequency (Hz), loss factor
    (``2 zeta``) and modal displacement at the sensor for the arrest, lowest first."""
    s = strike.structure
    n = s.mass.shape[0]
    stiffness = s.stiffness + float(strike.contact_stiffness) * np.outer(s.contact, s.contact)
    inv_mass = np.linalg.inv(s.mass)
    system = np.block([[np.zeros((n, n)), np.eye(n)],
                       [-inv_mass @ stiffness, -inv_mass @ s.damping]])
    lam, vectors = np.linalg.eig(system)
    weights = np.linalg.solve(vectors, np.concatenate([np.zeros(n), s.base]))
    up = lam.imag > 0
    lam, vectors, weights = lam[up], vectors[:, up], weights[up]
    order = np.argsort(lam.imag)
    lam, vectors, weights = lam[order], vectors[:, order], weights[order]
    shown = np.abs((s.output @ vectors[:n]) * weights)
    return lam.imag / (2 * math.pi), -2 * lam.real / np.abs(lam), shown


def scene_modes(scene, contacts, materials, *, rods=None) -> dict:
    """The modes the scene's model gives at each distinct (contact, material) (takes checked
    values: contacts inside the probe, materials the scene knows).

    Parameters
    ----------
    scene : ebantenna.simulate.Scene
        The scene (its hinge, tip mass, loss factor and effects are those modelled).
    contacts : array of float
        Contact distances, m.
    materials : array of str
        The touched material of each contact.
    rods : dict, optional
        The touched rods reduced once (:func:`touched_rods`): they do not depend on the probe,
        so a fit that varies the probe reduces them once.

    Returns
    -------
    dict
        ``(contact, material) -> (frequency_hz, loss_factor, tip_displacement)``, each an array
        over the modes, lowest first: the damped frequency, the loss factor ``2 zeta`` and the
        modal displacement at the tip after the arrest (see the module notes for the model). With
        ``object_modes`` each contact case is built as the simulator builds it
        (:class:`~ebantenna.simulate.structure.ContactCase`, its models of
        :data:`~ebantenna.simulate.touched_object.OBJECT_MODELS`).
    """
    from ...simulate.touched_object import pinned_modes

    keys = sorted(set(zip(np.asarray(contacts, float).tolist(),
                          np.asarray(materials).astype(str).tolist(), strict=True)))
    if scene.has("object_modes"):
        return _rod_modes(scene, keys, rods if rods is not None else touched_rods(
            scene, [m for _, m in keys]))
    out = {}
    where, what = np.array([c for c, _ in keys]), np.array([m for _, m in keys])
    modes, inverse = pinned_modes(scene, where, what, False)
    eta = scene.probe.loss_factor if scene.has("structural_damping") else 0.0
    for i, key in enumerate(keys):
        m = modes[inverse[i]]
        out[key] = (m.omega * math.sqrt(1 - eta**2 / 4) / (2 * math.pi),
                    np.full(m.omega.size, eta), np.abs(m.tip * m.velocity) / m.omega)
    return out


def _rod_modes(scene, keys, rods) -> dict:
    """:func:`scene_modes` with ``object_modes``: each (contact, material) a contact case as
    :func:`~ebantenna.simulate.touched_object.object_modes` builds it, the probe reduced once
    per contact."""
    from ...fem.coupling import craig_bampton, probe_substructure
    from ...simulate.structure import ContactCase
    from ...simulate.touched_object import OBJECT_MODELS

    effect = scene.effect("object_modes")
    probe = scene.probe
    if not scene.has("structural_damping"):
        probe = dataclasses.replace(probe, loss_factor=0.0)
    object_loss = scene.has("object_damping")
    build = {model.name: model.build for model in OBJECT_MODELS}
    out = {}
    for contact in sorted({c for c, _ in keys}):
        reduced = craig_bampton(probe_substructure(probe, contact, hinge=scene.hinge,
                                                   n_elements=scene.n_elements),
                                effect.probe_modes)
        for name in sorted(m for c, m in keys if c == contact):
            rod, rod_reduced = rods[name]
            case = ContactCase(
                scene=scene, probe=probe, contact=contact, material=name,
                preload=effect.preload, rod=rod, probe_reduction=reduced,
                rod_reduction=rod_reduced,
                stiffness=effect.contact_stiffness(rod.material, probe, effect.preload),
                loss_factor=effect.contact_loss_factor(rod.material, probe,
                                                       object_loss=object_loss,
                                                       preload=effect.preload))
            if scene.has("unilateral_contact"):
                out[contact, name] = _closed_contact_modes(build["unilateral"](case))
                continue
            m = build["coupled"](case)
            zeta = np.zeros(m.omega.size) if m.damping_ratio is None else m.damping_ratio
            out[contact, name] = (m.omega * np.sqrt(1 - zeta**2) / (2 * math.pi), 2 * zeta,
                                  np.abs(m.tip * m.velocity) / m.omega)
    return out


def touched_rods(scene, materials) -> dict | None:
    """The touched rods of ``scene`` (``object_modes``) reduced once per material, as the
    simulator reduces them: ``name -> (rod, reduction)``; None without ``object_modes``."""
    from ...fem.coupling import craig_bampton, rod_substructure
    from ...probe import material as lookup

    if not scene.has("object_modes"):
        return None
    effect = scene.effect("object_modes")
    rods = {}
    for name in sorted(set(materials)):
        rod = effect.rod(lookup(name))
        sub = rod_substructure(rod, n_elements=effect.rod_elements)
        if not scene.has("object_damping"):
            sub = dataclasses.replace(sub, loss_factor=0.0)
        rods[name] = (rod, craig_bampton(sub, effect.rod_modes))
    return rods


def fitted_mode(modes, fs: float) -> int:
    """Index of the mode fitted (by identity): the lowest of those the measurement can read (its
    band below ``fs / 2``) whose tip displacement is at least :data:`MIN_SHARE` of the largest
    of them; -1 if none. ``modes`` is one value of :func:`scene_modes`."""
    frequency, _, shown = modes
    below = np.flatnonzero(frequency < fs / 2 / (1 + BAND))
    if below.size == 0:
        return -1
    strong = below[shown[below] >= MIN_SHARE * shown[below].max()]
    return int(strong[0])


def _crowding(modes, j: int, n: int, fs: float) -> tuple[float, float]:
    """How far the model's other modes, ringing beside mode ``j``, move what the estimator
    reads of it: ``(shift, Hz)``, the largest relative change of the frequency read over eight
    relative phases, and the frequency of the strongest of them (0 and NaN when none rings
    near).

    ``modes`` is one value of :func:`scene_modes`; ``n`` samples at ``fs``. The modes counted
    lie between half and twice mode ``j``'s frequency (the band-pass of second order lets
    them through) and ring with at least 1e-3 of its acceleration at the sensor (the modal
    displacement times the frequency squared), which a mode weaker than that cannot move by
    1e-4. Each rings from rest with its loss factor, all at one phase relative to mode ``j``.
    """
    frequency, loss, shown = modes
    acceleration = shown * frequency**2 / (shown[j] * frequency[j] ** 2)
    near = [k for k in range(frequency.size) if k != j and acceleration[k] >= 1e-3
            and frequency[j] / 2 < frequency[k] < min(2 * frequency[j], fs / 2)]
    if not near:
        return 0.0, math.nan
    sos, alone = _band(frequency[j], fs), _ringing(frequency[j], loss[j], n, fs)
    read = _decay(alone, fs, frequency[j], sos)[1]
    shift = 0.0
    for phase in np.arange(8) * math.pi / 4:
        x = alone + sum(acceleration[k] * _ringing(frequency[k], loss[k], n, fs, phase)
                        for k in near)
        shift = max(shift, abs(_decay(x, fs, frequency[j], sos)[1] / read - 1))
    return shift, float(frequency[max(near, key=lambda k: acceleration[k])])


class _Model:
    """The scene's model at trial parameters, at the recordings' positions -- the design's
    independent unit -- and which position each recording is at (``index``).

    A position is a distinct (contact, material) pair where the model tells the materials apart
    (the touched rod's modes, a contact spring per material), and a distinct contact where it
    does not (a pinned probe): there, recordings of two materials at one distance are the same
    point of the model, repetitions of it, and counting them as two positions would fit two
    parameters to two distances exactly and test the fit on copies. ``keys`` holds one
    (contact, material) per position, ``labels`` its materials."""

    def __init__(self, scene, contacts, materials, fs, n):
        self.scene, self.fs, self.n = scene, fs, n
        self.evaluations = 0
        self._lags, self._filters = {}, {}
        self.rods = touched_rods(scene, materials.tolist())
        self.held, self.crowded, self.unread = None, {}, {}
        pairs = list(zip(contacts.tolist(), materials.tolist(), strict=True))
        same = _same_point(scene_modes(scene, contacts, materials, rods=self.rods))
        self.keys = sorted({same[pair] for pair in pairs})
        self.labels = ["+".join(sorted({pair[1] for pair, point in same.items() if point == key}))
                       for key in self.keys]
        self.index = np.array([self.keys.index(same[pair]) for pair in pairs])

    def _scene_modes(self, log10_k, tip_mass, eta) -> dict:
        self.evaluations += 1
        trial = _candidate(self.scene, float(10.0 ** log10_k), tip_mass, eta)
        return scene_modes(trial, [k[0] for k in self.keys], [k[1] for k in self.keys],
                           rods=self.rods)

    def identify(self, log10_k, tip_mass, eta) -> np.ndarray:
        """The mode the rule fits at each position (:func:`fitted_mode`), -1 where none, or
        where the model's other modes move its reading by more than :data:`CROWDING`
        (``_crowding``; those positions are kept in ``crowded``, ``index -> (shift, Hz of
        the other mode, Hz of the fitted one)``)."""
        by_key = self._scene_modes(log10_k, tip_mass, eta)
        identity, self.crowded = [], {}
        for i, key in enumerate(self.keys):
            j = fitted_mode(by_key[key], self.fs)
            shift, neighbour = _crowding(by_key[key], j, self.n, self.fs) if j >= 0 else (0, 0)
            if shift > CROWDING:
                self.crowded[i], j = (shift, neighbour, by_key[key][0][j]), -1
            identity.append(j)
        return np.array(identity)

    def hold(self, identity) -> None:
        """Fit the modes ``identity`` (one index per position) whatever the trial parameters,
        or (None) the mode the rule picks at each trial."""
        self.held = None if identity is None else np.array(identity)

    def modes(self, log10_k, tip_mass, eta):
        """Frequency (Hz) and loss factor of the fitted mode at each position: the mode held
        (:meth:`hold`), else the one the rule picks at these parameters."""
        by_key = self._scene_modes(log10_k, tip_mass, eta)
        frequency, loss = np.full(len(self.keys), np.nan), np.full(len(self.keys), np.nan)
        for i, key in enumerate(self.keys):
            j = fitted_mode(by_key[key], self.fs) if self.held is None else self.held[i]
            if 0 <= j < by_key[key][0].size:
                frequency[i], loss[i] = by_key[key][0][j], by_key[key][1][j]
        return frequency, loss

    def predicted(self, log10_k, tip_mass, eta, decays, valid):
        """What the measurement reads from the model (``as_measured``): each position's mean
        frequency over its ``valid`` recordings, and each recording's loss factor."""
        frequency, loss = self.modes(log10_k, tip_mass, eta)
        f_read = np.full(self.index.size, np.nan)
        eta_read = np.full(self.index.size, np.nan)
        for r in np.flatnonzero(valid):
            k = self.index[r]
            _, _, _, peak, band = decays[r]
            sos = self._filters.setdefault(r, _band(band, self.fs))  # the recording's filter
            known = self._lags.get(r)  # the envelope's peak moves little with the frequency
            if known is None or abs(known[0] / frequency[k] - 1) > 0.01:
                known = self._lags[r] = (frequency[k], _lag(frequency[k], loss[k], self.n,
                                                            self.fs, peak, band, sos))
            eta_read[r], f_read[r] = as_measured(frequency[k], loss[k], self.n, self.fs, peak,
                                                 lag=known[1], band=band, sos=sos)
        return self.per_position(f_read), eta_read

    def read(self, log10_k, tip_mass):
        """Each position's frequency as the measurement reads it from the model, at the loss
        factor and on the recordings set by :meth:`measured_on`."""
        return self.predicted(log10_k, tip_mass, self.eta, self.decays, self.valid)[0]

    def measured_on(self, decays, eta):
        """The recordings' decays (:func:`_measure`) the model is read against, and the tube's
        loss factor it is read at."""
        self.decays, self.eta, self._lags, self._filters = decays, eta, {}, {}
        self.valid = np.array([np.isfinite(d[1]) for d in decays])

    def per_position(self, values) -> np.ndarray:
        """The mean of the finite ``values`` (one per recording) at each position (NaN: none)."""
        out = np.full(len(self.keys), np.nan)
        for i in range(len(self.keys)):
            got = values[(self.index == i) & np.isfinite(values)]
            if got.size:
                out[i] = got.mean()
        return out


def _same_point(modes: dict) -> dict:
    """Each (contact, material) of ``modes`` (:func:`scene_modes`) mapped to the first pair at
    its contact whose modes are the same arrays, bit for bit: the model does not tell those
    materials apart there."""
    first, out = {}, {}
    for key in sorted(modes):
        for other in first.get(key[0], []):
            if all(np.array_equal(a, b) for a, b in zip(modes[key], modes[other], strict=True)):
                out[key] = other
                break
        else:
            first.setdefault(key[0], []).append(key)
            out[key] = key
    return out


def _check_bounds(name, bounds, low, high, unit, reason):
    """A pair ``(lo, hi)`` of finite reals with ``low <= lo < hi <= high``."""
    if isinstance(bounds, str | bytes) or not hasattr(bounds, "__len__") or len(bounds) != 2:
        raise TypeError(f"{name} must be a pair (low, high) in {unit}, got {describe(bounds)}")
    lo = check_real(f"{name}[0]", bounds[0])
    hi = check_real(f"{name}[1]", bounds[1])
    if not (low <= lo < hi <= high):
        raise ValueError(f"{name} must satisfy {low:g} <= low < high <= {high:g} {unit} "
                         f"({reason}), got ({lo!r}, {hi!r})")
    return lo, hi


def _check_dataset(ds):
    """The arrays ``calibrate`` reads from ``ds``, checked."""
    needed = ("contact", "material", "ax", "az", "fs")
    if not all(hasattr(ds, a) for a in needed):
        raise TypeError(f"ds must be a data set of recordings (ebantenna.simulate.Dataset, e.g. "
                        f"from ebantenna.simulate.load_dataset) with {', '.join(needed)}; got "
                        f"{type(ds).__name__}")
    fs = check_in_range("ds.fs", ds.fs, 0.0, math.inf)
    contact = np.asarray(ds.contact, dtype=float)
    ax = np.asarray(ds.ax, dtype=float)
    if ax.ndim != 2 or ax.shape[0] != contact.size or np.asarray(ds.material).size != contact.size:
        raise ValueError("ds must hold one contact, one material and one row of ax per recording")
    if not np.all(np.isfinite(contact)) or not np.all(np.isfinite(ax)):
        raise ValueError("ds.contact and ds.ax must be finite")
    return contact, np.asarray(ds.material).astype(str), ax, fs


def _peak_score(model, ax, fs):
    """``score(log10_k, m_t, eta)``: how well the model's fitted modes fall on the recordings'
    spectral peaks -- the mean over positions of the log of the position's mean amplitude
    spectrum within +/- 3 % of the mode (or half a bin, where that is wider: a 6 Hz mode's
    +/- 3 % holds no bin of a one-second record's, and scored as no mode, so heavy tips were
    never started from), over its median (a mode the model cannot show scores as the
    median)."""
    spectrum = np.abs(np.fft.rfft(ax - ax.mean(axis=1, keepdims=True), axis=1))
    f = np.fft.rfftfreq(ax.shape[1], 1.0 / fs)
    per_position = np.array([spectrum[model.index == k].mean(axis=0)
                             for k in range(len(model.keys))])
    band = (f > 0) & (f < fs / 2)
    with np.errstate(divide="ignore"):  # an empty bin (the mean's) is -inf: never a peak
        level = np.log(per_position / np.median(per_position[:, band], axis=1, keepdims=True))

    def score(log10_k, tip_mass, eta):
        total = 0.0
        for k, mode in enumerate(model.modes(log10_k, tip_mass, eta)[0]):
            near = np.abs(f - mode) <= max(0.03 * mode, 0.5 * f[1])
            total += level[k, near].max() if np.isfinite(mode) and near.any() else 0.0
        return total / len(model.keys)

    return score


def calibrate(ds, scene, *, stiffness_bounds=None, mass_bounds=None,
              region: float = DECAY_REGION, time_base: float = TIME_BASE,
              max_rounds: int = 4) -> Calibration:
    """Fit hinge stiffness, tip mass and loss factor to a data set's recordings, and say which the
    recordings determine (module notes).

    Parameters
    ----------
    ds : ebantenna.simulate.Dataset
        Recordings at known contact distances (e.g. assembled from a session).
    scene : ebantenna.simulate.Scene
        The scene the recordings are modelled with (e.g. ``builtin_scene("paper")``): its probe,
        rod and effects; its hinge, tip mass and loss factor are what is fitted.
    stiffness_bounds : (float, float), optional
        Range of the hinge stiffness searched, N m/rad, within ``STIFFNESS_RANGE`` times the
        tube's ``E I / L``. Default that whole range.
    mass_bounds : (float, float), optional
        Range of the tip mass, kg, ``0 <= low < high`` up to the probe's limit. Default 0 to
        20 g (eight times the ``paper`` scene's board).
    region : float
        Only contacts within this fraction of the probe's length are used (the lowest mode shows
        there). Default the paper's 0.8.
    time_base : float
        Relative uncertainty of the clock the frequencies were measured against, in [0, 0.01].
    max_rounds : int
        Most rounds of measuring at the model's prediction and fitting.

    Returns
    -------
    Calibration

    Warns
    -----
    IdentifiabilityWarning
        For each parameter the recordings do not determine, naming it and the reason.
    ModelMisfitWarning
        When the lack-of-fit test rejects the model (:attr:`Calibration.fit_statement`).

    Raises
    ------
    TypeError
        ``ds`` is not a data set, ``scene`` not a scene, a bound not a pair.
    ValueError
        A bound or setting out of its range (named), or too few usable recordings.
    """
    from ...simulate.scene import Scene

    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be an ebantenna.simulate.Scene (e.g. builtin_scene('paper') "
                        f"or load_scene(path)), got {type(scene).__name__}")
    contact, material, ax, fs = _check_dataset(ds)
    region = check_in_range("region", region, 0.0, 1.0, high_inclusive=True)
    time_base = check_in_range("time_base", time_base, 0.0, 0.01, low_inclusive=True,
                               high_inclusive=True)
    max_rounds = check_int("max_rounds", max_rounds, minimum=1, maximum=20)
    bounds = _search_bounds(scene.probe, stiffness_bounds, mass_bounds)
    use, beyond = _in_region(contact, material, region, scene.probe.length)
    contact, material, ax = contact[use], material[use], ax[use]
    model = _Model(scene, contact, material, fs, ax.shape[1])
    eta0 = scene.probe.loss_factor if scene.probe.loss_factor > 0 else 0.03
    _check_length(model, bounds, eta0)
    p = _start(model, ax, fs, bounds, eta0)
    fit, target, decays = _measure_and_fit(model, ax, fs, contact, p, bounds, eta0, max_rounds)
    p, ok = fit.x, np.isfinite(target)
    n = int(ok.sum())
    s2 = 2.0 * fit.cost / max(n - 2, 1)
    shift = np.linalg.lstsq(fit.jac, np.full(n, time_base), rcond=None)[0]
    cov = s2 * np.linalg.pinv(fit.jac.T @ fit.jac) + np.outer(shift, shift)
    quantile = float(student_t.ppf(0.975, max(n - 2, 1)))
    k_interval, masses = _profile_hinge(model, p, bounds, target, ok, eta0, 2.0 * fit.cost,
                                        quantile**2 * (s2 + time_base**2),
                                        quantile * math.sqrt(cov[0, 0]))
    missing = {}
    hinge = _hinge_interval(k_interval, bounds, missing)
    sd_m = math.sqrt(cov[1, 1])
    m_low, m_high = min(masses) - quantile * sd_m, max(masses) + quantile * sd_m
    missing.update(_mass_bounded(m_low, m_high, float(p[1]), bounds))
    eta, eta_sd, used, reason, eta_half = _loss_factor(model, p, decays, eta0)
    eta_interval, reason = _loss_interval(eta, eta_half, reason)
    if reason:
        missing["loss_factor"] = reason
    where = np.array([c for c, _ in model.keys])
    fitted = model.read(p[0], p[1])
    test = _lack_of_fit(np.array([d[1] for d in decays]) / fitted[model.index] - 1.0,
                        model.index, where, floor=time_base)
    return _warned(Calibration(
        float(10.0 ** p[0]),
        math.inf if "hinge_stiffness" in missing else math.sqrt(cov[0, 0]),
        float(p[1]), sd_m, eta, eta_sd, where[ok], target[ok], fitted[ok], used,
        intervals={"hinge_stiffness": hinge,
                   # a mass of 0 is a real end; the range searched is not: beyond it, open
                   "tip_mass": (max(m_low, bounds[0][1]),
                                math.inf if m_high >= bounds[1][1] else m_high),
                   "loss_factor": eta_interval},
        not_identifiable=missing, model=_describe_model(scene), lack_of_fit=test,
        left_out=_left_out(model, material, use, beyond)))


def _left_out(model, material, rows, beyond) -> dict:
    """Everything left out of the fit, with its reason, in order of distance: the distances
    ``beyond`` the region fitted (``_in_region``), each position that gave no frequency
    (``_not_fitted``), and each recording not read at a position that did, as
    ``"contact m (material), recording r"`` (``material`` its material, ``r`` its row of the
    data set, ``rows``)."""
    entries = list(beyond)
    for i, why in _not_fitted(model).items():
        entries.append((model.keys[i][0], _label(model, i), why))
    for r, why in model.unread.items():
        i = model.index[r]
        if any(np.isfinite(model.decays[q][1]) for q in np.flatnonzero(model.index == i)):
            entries.append((model.keys[i][0],
                            f"{model.keys[i][0]:g} m ({material[r]}), recording {rows[r]}", why))
    return {key: why for _, key, why in sorted(entries, key=lambda e: (e[0], e[1]))}


def _in_region(contact, material, region: float, length: float):
    """The rows of the recordings within ``region`` of the probe's ``length`` from the hinge,
    and ``(contact, key, why)`` of ``left_out`` for each distance beyond; too few within are
    refused."""
    limit = region * length
    use = np.flatnonzero(contact <= limit)
    if use.size < 3 or np.unique(contact[use]).size < 2:
        raise ValueError(f"calibration needs at least 3 recordings at 2 or more distances within "
                         f"region={region:g} L of the hinge, got {use.size}")
    beyond = []
    for c in np.unique(contact[contact > limit]):
        here = contact == c
        beyond.append((float(c), f"{c:g} m ({'+'.join(sorted(set(material[here].tolist())))})",
                       f"beyond region = {region:g} of the probe's length ({limit:.3g} m from "
                       f"the hinge): its {int(here.sum())} recordings lie outside the region "
                       "fitted"))
    return use, beyond


def _warned(cal: Calibration) -> Calibration:
    """``cal``, once what it cannot determine and a rejected fit are warned of (for the caller
    of :func:`calibrate`)."""
    for name, why in cal.not_identifiable.items():
        warnings.warn(f"{name} is not identifiable from these recordings: {why}",
                      IdentifiabilityWarning, stacklevel=3)
    if cal.misses_recordings:
        warnings.warn(cal.fit_statement, ModelMisfitWarning, stacklevel=3)
    return cal


def _lack_of_fit(residuals, index, where, parameters: int = 2, floor: float = 0.0) -> dict:
    """The lack-of-fit F test with repetitions (module notes) on each recording's relative
    residual (NaN: not fitted) at its position ``index`` (contacts ``where``), the model having
    ``parameters`` fitted, each position's frequency uncertain by at least ``floor`` (relative)
    whatever its repetitions.

    The residuals' sum of squares splits into the pure error, their scatter about each
    position's mean (``N - n`` degrees of freedom), and the lack of fit, the positions' means
    weighted by their counts (``n - parameters``); ``F`` is the ratio of their mean squares.
    With a ``floor`` shared by a position's repetitions (they are near copies, measured against
    one clock), a mean of ``m`` of them varies by ``floor^2 + sigma^2 / m``: the lack of fit's
    mean square then expects ``m floor^2`` more than the pure error's, which the denominator
    adds (``m`` the mean count; the test then rejects less often than its level).

    Examples
    --------
    Four positions, two recordings each: the pure error is 0.06 on 4 degrees of freedom, the
    lack of fit 2 x 0.1^2 = 0.02 on 2, so ``F = 0.01 / 0.015``.

    >>> test = _lack_of_fit(np.array([0.1, -0.1, 0.2, 0.0, -0.1, 0.1, 0.0, 0.0]),
    ...                     np.repeat(np.arange(4), 2), np.array([1.0, 2.0, 3.0, 4.0]))
    >>> test["df"], round(test["f"], 6), test["largest"]
    ([2, 4], 0.666667, [2.0, 0.1])
    """
    ok = np.isfinite(residuals)
    positions, group = np.unique(index[ok], return_inverse=True)
    e, counts = residuals[ok], np.bincount(group)
    means = np.bincount(group, weights=e) / counts
    pure, lack = float(np.sum((e - means[group]) ** 2)), float(counts @ means**2)
    df = [int(positions.size - parameters), int(e.size - positions.size)]
    worst = int(np.argmax(np.abs(means))) if means.size else 0
    out = {"f": None, "df": df, "p": None,
           "largest": [float(where[positions[worst]]), float(means[worst])] if means.size
           else None}
    scatter, clock = pure / max(df[1], 1), e.size / max(positions.size, 1) * floor**2
    error = scatter + clock
    out["error_from"] = "clock" if clock > scatter else "repetitions"
    # the positions' misfit, relative, and the clock's uncertainty it is measured against
    out["rms_misfit"] = float(np.sqrt(np.mean(means**2))) if means.size else None
    out["clock"] = float(floor)
    if df[0] >= 1 and df[1] >= 1 and (error > 0 or lack > 0):
        out["f"] = (lack / df[0]) / error if error > 0 else math.inf
        out["p"] = float(fisher_f.sf(out["f"], *df))
    return out


def _mass_bounded(m_low: float, m_high: float, fit: float, bounds) -> dict:
    """``{"tip_mass": why}`` when the tip mass's 95 % interval reaches an end of the range
    searched: the recordings then bound it on one side at most, and the fit there is the
    optimiser's bound, not a value (its standard error comes from a Jacobian at an active
    bound); an empty dict when the interval lies inside the range.

    Examples
    --------
    >>> why = _mass_bounded(-1e-7, 1.2e-7, 1.8e-10, ([2.0, 0.0], [6.0, 0.02]))["tip_mass"]
    >>> why.split(": ")[1].split(" (")[0]
    'the recordings bound it only from above, at most 1.2e-07 kg'
    >>> _mass_bounded(0.00249, 0.00251, 0.0025, ([2.0, 0.0], [6.0, 0.02]))
    {}
    """
    lo, hi = bounds[0][1], bounds[1][1]
    if m_low <= lo and m_high >= hi:
        why = (f"its 95 % interval ({m_low:.3g}, {m_high:.3g}) kg covers the whole range searched "
               f"({lo:g}, {hi:g}) kg")
    elif m_low <= lo:
        why = (f"its 95 % interval reaches the lowest tip mass searched ({lo:g} kg): the "
               f"recordings bound it only from above, at most {m_high:.3g} kg (the fit, "
               f"{fit:.3g} kg, is the search bound, not a value)")
    elif m_high >= hi:
        why = (f"its 95 % interval reaches the highest tip mass searched ({hi:g} kg): the "
               f"recordings bound it only from below, at least {m_low:.3g} kg (the fit, "
               f"{fit:.3g} kg, is the search bound, not a value)")
    else:
        return {}
    return {"tip_mass": why}


def _search_bounds(probe, stiffness_bounds, mass_bounds):
    """``([log10 k_lo, m_lo], [log10 k_hi, m_hi])``, the bounds checked (module constants)."""
    ei_l = probe.flexural_rigidity / probe.length
    k_lo, k_hi = (STIFFNESS_RANGE[0] * ei_l, STIFFNESS_RANGE[1] * ei_l)
    if stiffness_bounds is not None:
        k_lo, k_hi = _check_bounds(
            "stiffness_bounds", stiffness_bounds, k_lo, k_hi, "N m/rad",
            f"{STIFFNESS_RANGE[0]:g} to {STIFFNESS_RANGE[1]:g} times the tube's E I / L = "
            f"{ei_l:.3g} N m/rad: softer swings the tube as a pendulum, stiffer is a clamp")
    m_max = min(MAX_TIP_MASS_RATIO * probe.mass, 1.0)
    m_lo, m_hi = 0.0, min(0.02, m_max)
    if mass_bounds is not None:
        m_lo, m_hi = _check_bounds("mass_bounds", mass_bounds, 0.0, m_max, "kg",
                                   "a mass is not negative, and the probe's limit")
    return [math.log10(k_lo), m_lo], [math.log10(k_hi), m_hi]


def _samples_needed(frequency, fs) -> np.ndarray:
    """The samples a recording needs to read the mode at each frequency (Hz), fewest first:
    :data:`READ_PERIODS` of its periods and the 3 samples of the stretch fitted."""
    return np.sort([math.ceil(READ_PERIODS * fs / f) + 3 for f in frequency
                    if np.isfinite(f) and f > 0])


def _check_length(model, bounds, eta0) -> None:
    """Refuse, before any fitting, recordings too short to read the fitted mode at 3 positions.

    The frequencies are the model's at the stiffest hinge and the lightest tip mass searched,
    the highest it can fit (a stiffer hinge and a lighter tip raise every mode), so recordings
    refused here are too short at any value the fit could reach.
    """
    need = _samples_needed(model.modes(bounds[1][0], bounds[0][1], eta0)[0], model.fs)
    if need.size >= 3 and model.n < need[2]:
        raise ValueError(
            f"records of {model.n} samples (ds.ax) are too short to calibrate from: at fs = "
            f"{model.fs:g} Hz reading the mode the model fits at 3 of the {len(model.keys)} "
            f"positions needs {int(need[2])} samples at least ({READ_PERIODS:g} periods of it, "
            "at the highest frequency the search allows); record longer")


def _mass_grid(effective: float, low: float, high: float) -> np.ndarray:
    """Tip masses (kg) from ``low`` to ``high`` whose modes lie within ``START_STEP`` of
    their neighbours': a tip mass lowers a mode about as ``1 / sqrt(m_e + m_t)``, ``m_e`` the
    ``effective`` mass (kg) the tip already carries, so the masses plus ``m_e`` are spaced by
    ``START_STEP**2`` (the last step shorter, to end at ``high``). Any mass in the range is then
    within half a step of one of them (a smaller ``m_e`` only makes the steps finer).

    Examples
    --------
    >>> np.round(1000 * _mass_grid(0.6e-3, 0.0, 0.02), 2)
    array([ 0.  ,  0.41,  1.11,  2.3 ,  4.29,  7.67, 13.38, 20.  ])
    """
    steps = math.ceil(math.log((effective + high) / (effective + low))
                      / (2 * math.log(START_STEP)))
    return np.array([*((effective + low) * START_STEP ** (2 * np.arange(steps)) - effective),
                     high])


def _start(model, ax, fs, bounds, eta0) -> np.ndarray:
    """The hinge (a grid of decades), then the tip mass (a grid over the whole range searched,
    ``_mass_grid``), then the hinge again, whose modes fall on the recordings' spectral peaks."""
    score = _peak_score(model, ax, fs)
    (k_lo, m_lo), (k_hi, m_hi) = bounds
    probe = model.scene.probe
    m_start = min(max(probe.tip_mass, m_lo), m_hi)
    grid = np.unique(np.clip(np.arange(math.floor(k_lo), math.ceil(k_hi) + 1), k_lo, k_hi))
    # the tube beyond the farthest contact swings with the tip there (33/140 of its mass,
    # Rayleigh's cantilever): the least effective mass, where a tip mass moves the modes most
    effective = 33 / 140 * probe.mass_per_length * (probe.length - max(c for c, _ in model.keys))
    masses = np.unique([m_start, *_mass_grid(effective, m_lo, m_hi)])
    k_start = grid[int(np.argmax([score(g, m_start, eta0) for g in grid]))]
    m_start = masses[int(np.argmax([score(k_start, m, eta0) for m in masses]))]
    k_start = grid[int(np.argmax([score(g, m_start, eta0) for g in grid]))]
    return np.array([k_start, m_start])


def _measure_and_fit(model, ax, fs, contact, p, bounds, eta0, max_rounds):
    """Measure at the model's prediction and fit, until the measured frequencies settle:
    ``(fit, target, decays)``, the positions' frequencies and each recording's decay."""
    target, fit, held = np.full(len(model.keys), np.nan), None, None
    for _ in range(max_rounds):
        # the mode fitted at each position is the rule's at the current parameters, held
        # through the fit: a rule applied at every trial would switch modes within the fit, and
        # the misfit would jump there (a clamped probe's fit once stopped at such a switch, at
        # 27.7 N m/rad, its interval excluding the clamp)
        identity = model.identify(p[0], p[1], eta0)
        model.hold(identity)
        predicted, _ = model.modes(p[0], p[1], eta0)
        decays, model.unread = _measure(ax, fs, predicted[model.index], contact)
        new = model.per_position(np.array([d[1] for d in decays]))
        settled = np.array_equal(identity, held) and np.array_equal(
            np.isfinite(new), np.isfinite(target)) and np.allclose(
            new[np.isfinite(new)], target[np.isfinite(target)], rtol=SETTLED, atol=0.0)
        target, held = new, identity
        model.measured_on(decays, eta0)
        ok = np.isfinite(target)
        if ok.sum() < 3:
            raise ValueError(_refusal(model, predicted, ok))
        if settled and fit is not None:
            break
        fit = _fit(model, p, bounds, target, ok, eta0)
        p = fit.x
    return fit, target, decays


def _refusal(model, predicted, ok) -> str:
    """Why the calibration cannot go on with ``ok.sum()`` (under 3) positions that show the mode
    the model predicts (``predicted``, Hz): each of the others with its reason
    (``_not_fitted``, positions of one reason together), and records too short for the modes
    predicted."""
    if ok.size < 3:
        return (f"the recordings hold {ok.size} distinct contact positions in the region fitted "
                "(a distance each, and a material where the model tells the materials apart); 3 "
                "are needed: record more distances")
    together = {}
    for i, reason in _not_fitted(model).items():
        together.setdefault(reason, []).append(_label(model, i))
    why = "".join(f"; at {', '.join(where)}: {reason}" for reason, where in together.items())
    need = _samples_needed(predicted, model.fs)
    if need.size >= 3 and model.n < need[2]:
        why += (f"; records of {model.n} samples are too short for the modes predicted: reading "
                f"3 positions needs {int(need[2])} samples at least ({READ_PERIODS:g} periods)")
    if any(NO_MODE in reason or ANOTHER in reason for reason in together):
        why += ("; check that the scene describes these recordings (--scene: the probe, the "
                "material)")
    return (f"only {int(ok.sum())} of {ok.size} distinct contact positions show the mode the "
            f"model predicts (3 are needed){why}")


#: What ``_not_fitted`` says of a position where the model has no mode the recordings resolve,
#: and ``_unread`` of a band that holds another mode than the one predicted.
NO_MODE, ANOTHER = "the model has no mode below", "not the mode predicted"


def _label(model, i: int) -> str:
    """Position ``i`` as ``left_out`` names it: ``"contact m (materials)"``."""
    return f"{model.keys[i][0]:g} m ({model.labels[i]})"


def _not_fitted(model) -> dict:
    """``{position: why}`` for each position none of whose recordings gave a frequency: the
    model's other modes ring beside the fitted one there (:data:`CROWDING`), it has no mode the
    recordings resolve, or each recording's reading failed (``_unread``)."""
    out = {}
    for i in range(len(model.keys)):
        mine = np.flatnonzero(model.index == i)
        if any(np.isfinite(model.decays[r][1]) for r in mine):
            continue
        whys = list(dict.fromkeys(model.unread[r] for r in mine if r in model.unread))
        if i in model.crowded:
            shift, other, fitted = model.crowded[i]
            out[i] = (f"the model's mode at {other:.1f} Hz rings beside the fitted one "
                      f"({fitted:.1f} Hz) and moves what the estimator reads of it by up to "
                      f"{shift:.2%}, more than {CROWDING:g}")
        elif whys:
            out[i] = f"none of its {mine.size} recordings is read: {'; '.join(whys)}"
        else:
            out[i] = (f"{NO_MODE} {model.fs / 2 / (1 + BAND):.4g} Hz, the highest whose band "
                      f"recordings at fs = {model.fs:g} Hz resolve")
    return out


def _loss_interval(eta: float, half: float, reason: str) -> tuple[tuple[float, float], str]:
    """The loss factor's 95 % interval and why it is not identifiable ("" if it is): none
    (``(0, inf)``) with a ``reason`` already; bounded only from above when ``eta - half``
    reaches 0, a real end (the interval is then ``(0, eta + half)``); bounded on neither side
    when ``eta + half`` lies below 0 too, where no loss factor is.

    Examples
    --------
    >>> _loss_interval(0.03, 0.002, "")[1] == ""
    True
    >>> interval, why = _loss_interval(0.06, 0.063, "")
    >>> interval[0], why.split(", and ")[1]
    (0.0, 'bound it only from above, at most 0.123')
    >>> _loss_interval(-0.002, 0.001, "")[0]
    (0.0, inf)
    """
    if reason:
        return (0.0, math.inf), reason
    low, high = eta - half, eta + half
    if low > 0:
        return (low, high), ""
    if high <= 0:
        return (0.0, math.inf), (
            f"its 95 % interval ({low:.3g}, {high:.3g}) lies below 0, where no loss factor is: "
            "the envelopes rise where the model's decays fall, and the recordings bound it on "
            "neither side (a decay too slow to measure within these records, read with a bias "
            "the model does not have)")
    return (0.0, high), (f"its 95 % interval ({low:.3g}, {high:.3g}) reaches 0: the decays "
                         "cannot be told from none within their spread, and bound it only from "
                         f"above, at most {high:.3g}")


def _hinge_interval(k_interval, bounds, missing) -> tuple[float, float]:
    """The hinge's 95 % interval (N m/rad) from its profile set in log10; an end at the
    search's bound is open, and the hinge then not identifiable (its reason put in
    ``missing``)."""
    lo_open = k_interval[0] <= bounds[0][0] + 1e-9
    hi_open = k_interval[1] >= bounds[1][0] - 1e-9
    low = 0.0 if lo_open else 10.0 ** k_interval[0]
    high = math.inf if hi_open else 10.0 ** k_interval[1]
    if hi_open and lo_open:
        missing["hinge_stiffness"] = (
            f"the frequencies change by less than their uncertainty over the whole range "
            f"searched, {10.0 ** bounds[0][0]:.3g} to {10.0 ** bounds[1][0]:.3g} N m/rad: the "
            "recordings bound the hinge on neither side")
    elif hi_open or lo_open:
        where = "stiffer than" if hi_open else "softer than"
        edge = low if hi_open else high
        missing["hinge_stiffness"] = (
            f"the frequencies change by less than their uncertainty for any hinge {where} "
            f"{edge:.3g} N m/rad, up to the search's bound "
            f"{10.0 ** (bounds[1][0] if hi_open else bounds[0][0]):.3g} N m/rad: the recordings "
            f"{'cannot tell the hinge from a clamp' if hi_open else 'set no lower limit'}")
    return low, high


def _describe_model(scene) -> str:
    if scene.has("object_modes"):
        how = ("the contact closed, each body's modal viscous damping (the strike's)"
               if scene.has("unilateral_contact") else "a linear contact spring")
        return f"probe and touched rod ({how})"
    return "probe arrested by a pin" + (" or spring" if scene.has("contact_compliance") else "")


def _measure(ax, fs, predicted, contact):
    """Each recording's decay of the mode at its prediction: ``(eta, f, periods, peak, band)``
    (f NaN where no mode is predicted, or the band holds another; band: the prediction the
    band-pass was centred on), and ``{recording: why}`` for each whose predicted mode gave no
    frequency (``_unread``)."""
    out, unread = [], {}
    for r, (x, f, c) in enumerate(zip(ax, predicted, contact, strict=True)):
        if not np.isfinite(f):
            out.append((math.nan, math.nan, 0.0, 0, math.nan))
            continue
        if not f < fs / 2 / (1 + BAND):
            raise ValueError(
                f"the mode fitted at contact {c:g} m is predicted at {f:.1f} Hz, above what "
                f"recordings at fs = {fs:g} Hz resolve (its band +/- {BAND:.0%} must lie below "
                f"fs / 2); lower region or record at a higher rate")
        eta, measured, cycles, peak = _decay(x, fs, f)
        if not abs(measured / f - 1) < BAND:  # nothing read, or not the predicted mode
            unread[r] = _unread(x.size, fs, f, peak, measured)
            measured = math.nan
        out.append((eta, measured, cycles, peak, f))
    return out, unread


def _unread(n: int, fs: float, band: float, peak: int, measured: float) -> str:
    """Why a recording of ``n`` samples gave no frequency of the mode predicted at ``band``
    (Hz): its band envelope first peaking at sample ``peak``, ``measured`` what
    :func:`loss_factor_of` read (NaN: nothing, the stretch it reads holding under 3 samples).

    Examples
    --------
    >>> _unread(1000, 1000.0, 10.0, 700, math.nan).split(":")[0]
    'its band envelope about 10.0 Hz first peaks at 0.7 s of the 1 s record, too late to read'
    >>> _unread(1000, 1000.0, 10.0, 100, 14.0).split(": ")[1]
    'what rings there is not the mode predicted'
    """
    if np.isfinite(measured):
        return (f"the band about the predicted {band:.1f} Hz reads {measured:.1f} Hz, more than "
                f"{BAND:.0%} off: what rings there is {ANOTHER}")
    t = np.arange(n) / fs
    if np.count_nonzero((t > t[peak] + 2.0 / band) & (t < t[-1] - 2.0 / band)) < 3:
        return (f"its band envelope about {band:.1f} Hz first peaks at {peak / fs:.3g} s of the "
                f"{n / fs:.3g} s record, too late to read: a reading spans from 2 periods past "
                "the peak to 2 before the end")
    return (f"its band envelope about {band:.1f} Hz falls below 5 % of its peak within 2 periods "
            "of it: a decay too fast to read")


#: The parameters' typical sizes (``log10 k_h``, ``m_t`` in kg): least squares' ``x_scale``.
SCALES = np.array([0.5, 0.002])
#: Steps of the forward differences of the misfit's Jacobian: a millionth of :data:`SCALES`,
#: whatever the value (SciPy's ``diff_step`` is relative to it, so at a tip mass near its lower
#: bound of 0 its step sank below 1e-20 kg and the derivative was rounding: -3.7e7 against about
#: -300 per kg).
STEPS = 1e-6 * SCALES


def _fit(model, start, bounds, target, ok, eta):
    """Least squares of ``(log10 k_h, m_t)`` to the positions' frequencies (relative misfit)."""
    start = np.clip(start, bounds[0], bounds[1])
    return least_squares(lambda p: _misfit(model, p[0], p[1], target, ok), start,
                         jac=lambda p: _jacobian(model, p, target, ok, bounds), bounds=bounds,
                         x_scale=SCALES, xtol=1e-8, ftol=1e-10)


def _jacobian(model, p, target, ok, bounds):
    """The misfit's Jacobian by one-sided differences of :data:`STEPS`, towards the side with
    more room inside ``bounds`` (a step never leaves them)."""
    r0 = _misfit(model, p[0], p[1], target, ok)
    jac = np.empty((r0.size, 2))
    for j in range(2):
        up, down = bounds[1][j] - p[j], p[j] - bounds[0][j]
        h = min(STEPS[j], up) if up >= down else -min(STEPS[j], down)
        q = np.array(p, dtype=float)
        q[j] += h
        jac[:, j] = (_misfit(model, q[0], q[1], target, ok) - r0) / h
    return jac


def _profile_point(model, log10_k, m, slope, bounds, target, ok, eta, steps: int = 1):
    """The tip mass that best fits at a fixed hinge, ``steps`` Gauss-Newton steps from ``m``
    along the misfit's derivative ``slope`` (per kg), and the sum of squared misfits there."""
    r = _misfit(model, log10_k, m, target, ok)
    for _ in range(steps if slope @ slope > 0 else 0):
        m = float(np.clip(m - (slope @ r) / (slope @ slope), bounds[0][1], bounds[1][1]))
        r = _misfit(model, log10_k, m, target, ok)
    return m, float(r @ r)


def _profile_hinge(model, p, bounds, target, ok, eta, best, allowed, half_width):
    """The 95 % profile set of ``log10 k_h`` (module notes) and the tip masses fitted in it.

    Each end: if the profile at the search's bound is within the threshold the set reaches it;
    otherwise the crossing is found by bisection between the optimum (or the linearised end, if
    that is inside) and the bound, to 1/256 of the distance.
    """
    threshold = best + allowed
    h = 1e-6 if p[1] + 1e-6 <= bounds[1][1] else -1e-6
    slope = (_misfit(model, p[0], p[1] + h, target, ok)
             - _misfit(model, p[0], p[1], target, ok)) / h
    masses = [float(p[1])]
    ends = []
    for side, bound in ((-1, bounds[0][0]), (1, bounds[1][0])):
        inside, m_in = float(p[0]), float(p[1])
        if abs(bound - inside) < 1e-9:
            ends.append(bound)
            continue
        m_b, ssr = _profile_point(model, bound, m_in, slope, bounds, target, ok, eta, steps=2)
        if ssr <= threshold:
            masses.append(m_b)
            ends.append(bound)
            continue
        outside = bound
        guess = inside + side * 1.5 * half_width  # bisect from near the linearised end
        if np.isfinite(guess) and (guess - bound) * side < 0:
            m_g, ssr_g = _profile_point(model, guess, m_in, slope, bounds, target, ok, eta, steps=2)
            if ssr_g > threshold:
                outside = guess
            else:
                inside, m_in = guess, m_g
                masses.append(m_g)
        for _ in range(8):
            mid = 0.5 * (inside + outside)
            m_mid, ssr_mid = _profile_point(model, mid, m_in, slope, bounds, target, ok, eta)
            if ssr_mid <= threshold:
                inside, m_in = mid, m_mid
                masses.append(m_mid)
            else:
                outside = mid
        ends.append(inside)
    return (ends[0], ends[1]), masses


def _misfit(model, log10_k, tip_mass, target, ok):
    """Relative misfit of the model as read to the positions' frequencies; a position where the
    model shows no mode the measurement can read counts as a misfit of 1 (100 %)."""
    r = model.read(log10_k, tip_mass)[ok] / target[ok] - 1.0
    return np.where(np.isfinite(r), r, 1.0)


def _loss_factor(model, p, decays, eta1):
    """The tube's loss factor from the decays (module notes): ``(eta, sd, used, reason,
    half)``, the reason not empty when the recordings do not determine it, ``half`` the 95 %
    interval's half-width. Each position's estimates are averaged; the spread is over
    positions."""
    if not model.scene.has("structural_damping"):
        return (math.nan, math.nan, 0,
                "the scene does not list structural_damping: its model has no tube loss for the "
                "decays to measure", math.inf)
    frequency, a = model.modes(p[0], p[1], 0.0)
    _, at = model.modes(p[0], p[1], eta1)
    b = (at - a) / eta1
    estimates = np.full(len(decays), np.nan)
    for r, (eta, f, cycles, peak, band) in enumerate(decays):
        k = model.index[r]
        if cycles >= MIN_CYCLES and b[k] >= MIN_SHARE and np.isfinite(eta) and np.isfinite(f):
            mode = _as_read_inverse(eta, frequency[k], model.n, model.fs, peak, band)
            estimates[r] = (mode - a[k]) / b[k]
    used = int(np.isfinite(estimates).sum())
    per_position = model.per_position(estimates)
    per_position = per_position[np.isfinite(per_position)]
    if per_position.size < 2:
        return (math.nan, math.nan, used,
                f"fewer than 2 contact positions ({per_position.size}) have a decay of the "
                f"fitted mode that spans {MIN_CYCLES} periods and is at least {MIN_SHARE:.0%} "
                "the tube's", math.inf)
    sd = float(per_position.std(ddof=1))
    # the interval is the positions' spread times Student's quantile for their number: at least
    # as wide as the t interval of their mean, for two positions as for twenty
    half = float(student_t.ppf(0.975, per_position.size - 1)) * sd
    return float(per_position.mean()), sd, used, "", half


def _as_read_inverse(eta_read: float, frequency: float, n: int, fs: float, peak: int,
                     band: float) -> float:
    """The mode's loss factor whose decay ``as_measured`` reads as ``eta_read`` (secant
    steps from ``eta_read``: the reading is within a few per cent of linear in it). A reading
    of 0 or below -- an envelope that does not fall over the record -- is inverted as any other:
    the mode's loss factor is then about as small, and below 0 where the estimator reads the
    ringing's own bias."""
    sos = _band(band, fs)
    x0, x1 = eta_read, eta_read + max(0.1 * abs(eta_read), 1e-5)
    g0 = as_measured(frequency, x0, n, fs, peak, band=band, sos=sos)[0] - eta_read
    for _ in range(4):
        g1 = as_measured(frequency, x1, n, fs, peak, band=band, sos=sos)[0] - eta_read
        if g1 == g0:
            break
        x0, x1, g0 = x1, x1 - g1 * (x1 - x0) / (g1 - g0), g1
        if abs(x1 - x0) < 1e-6 * abs(x1):
            break
    return float(x1)


def plot_calibration(cal: Calibration, scene):
    """Measured against modelled frequency of the fitted mode versus contact distance.

    ``cal`` is a :class:`Calibration` and ``scene`` the :class:`ebantenna.simulate.Scene` it
    calibrated; anything else is refused, naming the parameter, before a figure is made.
    """
    import matplotlib.pyplot as plt

    from ...simulate.scene import Scene

    if not isinstance(cal, Calibration):
        raise TypeError(f"cal must be a Calibration, got {type(cal).__name__}")
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be an ebantenna.simulate.Scene, got {type(scene).__name__}")
    grid = np.linspace(cal.contacts.min(), cal.contacts.max(), 24)
    fitted = cal.scene(scene)
    material = np.full(grid.size, scene.material)
    by_key = scene_modes(fitted, grid, material)
    fs = scene.fs
    curve = [by_key[(float(c), str(m))][0][fitted_mode(by_key[(float(c), str(m))], fs)]
             for c, m in zip(grid, material, strict=True)]
    hinge = fitted.hinge if isinstance(fitted.hinge, str) else f"{fitted.hinge:.3g} N m/rad"
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(100 * cal.contacts, cal.measured_hz, "o", label="measured (recordings)")
    unknown = cal.held_at_fit_stop
    ax.plot(100 * grid, curve, "-", label=f"model ({scene.material}): hinge {hinge}, "
            f"m_t = {1000 * cal.tip_mass:.2f} g"
            + (f"\n(drawn at the fit's stop: {' and '.join(unknown)} not identifiable)"
               if unknown else ""))
    ax.set_xlabel("contact distance from the hinge (cm)")
    ax.set_ylabel("frequency of the fitted mode (Hz)")
    ax.legend(fontsize="small")
    fig.tight_layout()
    return fig
