"""Strikes on the touched rod through a contact that only pushes (``unilateral_contact``).

The linear model of :mod:`.modes` joins probe and rod by a spring that pulls as readily as it
pushes. Here the same two bodies, reduced by the same Craig-Bampton bases, strike each other
through :func:`.unilateral.unilateral_response`: the servo swings the probe onto the rod, drives on
by the overtravel that builds up the preload, and stops; whenever the contact force would turn
into a pull the probe separates, rings free, and strikes again.

The model of one strike (:func:`strike_model`):

- **Bases.** Each body keeps its fixed-interface modes below the scene's ``max_frequency`` and its
  interface coordinate, the deflection at the contact (a Craig-Bampton reduction with fewer
  modes; :func:`ebantenna.fem.coupling.craig_bampton`). The contact's gap closes by
  ``p = x_probe - x_rod + s``, ``s`` the servo's travel at the contact point.
- **Damping.** A time-domain model needs viscous damping where the frequency-domain one uses a
  loss factor: each body gets the modal viscous damping ``2 zeta_k omega_k`` with
  ``zeta_k = eta / 2`` on its own modes with its interface free, ``C = M Phi diag(eta omega)
  Phi^T M`` for mass-normalised ``Phi``; at each of the body's resonances this dissipates what
  the loss factor does (R. R. Craig and A. J. Kurdila, *Fundamentals of Structural Dynamics*,
  2nd ed., Wiley, 2006, section 10.3). **Assumption:** the contact spring's own loss (its
  compliance-weighted share, :meth:`~ebantenna.simulate.effects.ObjectModes.contact_loss_factor`) is
  left out: a dashpot in the contact would act in one state only.
- **The approach.** The probe swings rigidly about its hinge at the sweep speed, so the contact
  point approaches at ``sweep_speed x contact``; the servo's rigid motion per unit travel at the
  contact is that rotation projected on the probe's basis in the mass metric, as the linear
  model's initial modal velocities are (:func:`.modes.coupled_arrest_modes`).

**Chatter.** The contact opens and closes again and again, struck almost anywhere: the contact
mode has no loss in the spring (the assumption above) and little from the bodies, and the
contact opens as long as that mode's force amplitude exceeds the preload. Measured on the
``paper`` scene's strikes (its 3 kHz basis, the nominal preload of 0.5 N without scatter, 1 s
at 8 kHz, the five materials, every 25 mm from 0.02 m): from 0.02 to 0.37 m, 0 (aluminium at
0.045 m) to 102 (steel at 0.345 m) contact changes, the last at up to 348 ms (steel at
0.045 m); from 0.195 m on, 18 to 102, the last after 8 to 86 ms. At 0.395 m, 5 mm from the
tip, 46 (PVC) to 290 (brass), the last after 53 to 258 ms, on one machine with the NumPy
engine; there the count and the time of the last change depend on the last bits of the
arithmetic (:mod:`.unilateral`, "Reference and engine": another BLAS kernel gave brass 238
changes, the last after 271 ms, the compiled march 162). The bare probe (no tip
mass) chatters alike: 0 to 66 changes from 0.02 to 0.37 m, the last at up to 180 ms, and 78 to
112 at 0.395 m. A basis cut lower chatters longer: with the modes below 480 Hz, the bare probe
struck on steel at 0.36 m changes contact 838 times, the last after 431 ms. This is the model's
dynamics, not the event grid's: a grid four times finer finds the same events (the test suite
checks it on the bare probe struck on PVC at 0.3675 m).

The ``paper`` scene with this effect costs about 4.8 times as much as with a linear contact,
15.0 against 3.1 CPU seconds per thousand one-second recordings (one run, the two alternating,
on one machine; the theory page on the touched object gives it): most of it
in the events (dozens per strike, hundreds near the tip), each found within one step of a grid of 16
steps per period of the fastest mode (:mod:`.unilateral`).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
import weakref
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from .._validate import check_array, check_choice, check_int, check_nonnegative, check_positive
from ..fem.coupling import CraigBampton
from .contact import PiecewiseSpring
from .modes import sweep_velocity
from .structure import ContactModel, check_case
from .unilateral import MARCHES, unilateral_response

__all__ = [
    "StrikeModel",
    "strike_model",
    "strike_model_of",
    "strike_accelerations",
    "timed_rate",
    "batch_rate",
    "strike_axis",
    "reduced_body",
    "check_reduction",
]

#: Without the DLPF, strikes are computed at this multiple of ``fs`` and read at the sample times.
UNFILTERED_RATE = 8


@dataclass(frozen=True, eq=False)
class StrikeModel:
    """Probe and rod as one linear structure for :func:`.unilateral.unilateral_response`.

    Attributes
    ----------
    structure : ContactModel
        Mass, stiffness and damping of the two bodies side by side (no contact), the contact
        vector ``c`` (``p = c @ q + s``), the servo's motion ``base`` and the accelerometer
        ``output``, all in the stacked reduced coordinates.
    contact : float
        Contact position from the hinge, m (the approach speed is ``sweep_speed * contact``).
    contact_stiffness : float or PiecewiseSpring
        The contact spring, N/m; or, with ``hertz_contact``, the chords of its Hertz law.
    preload : float
        The static contact force once the servo has stopped, N.
    """

    structure: ContactModel
    contact: float
    contact_stiffness: float
    preload: float


#: Each reduction's truncated, damped matrices by ``max_frequency``: the many strikes on one
#: probe position or one rod (preloads and speeds differ) share them.
_BODIES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def check_reduction(name: str, reduction) -> None:
    """Raise a ``TypeError`` naming ``name`` unless ``reduction`` is a Craig-Bampton reduction
    (:func:`ebantenna.fem.coupling.craig_bampton`)."""
    if not isinstance(reduction, CraigBampton):
        raise TypeError(f"{name} must be a CraigBampton reduction (ebantenna.fem.coupling."
                        f"craig_bampton), got {type(reduction).__name__}")


def reduced_body(reduction, max_frequency: float):
    """One body of a strike: its Craig-Bampton reduction truncated at ``max_frequency``.

    Keeps the fixed-interface modes below ``max_frequency`` and the interface coordinate
    (last), damped by the reduction's loss factor (the modal viscous damping of the module
    docstring). The result is cached per reduction and ``max_frequency``: the many strikes on
    one probe position or one rod share it.

    Parameters
    ----------
    reduction : ebantenna.fem.coupling.CraigBampton
        The body reduced at its interface (the contact).
    max_frequency : float
        Fixed-interface modes at or above it are dropped, Hz.

    Returns
    -------
    tuple of ndarray
        ``K, M, T, C``: stiffness (N/m), mass (kg) and damping (N s/m) in the kept coordinates,
        and the basis ``T`` from them to the body's free DOFs.
    """
    check_reduction("reduction", reduction)
    max_frequency = check_positive("max_frequency", max_frequency)
    cached = _BODIES.setdefault(reduction, {})
    if max_frequency not in cached:
        keep = np.flatnonzero(reduction.fixed_interface_omega < 2 * math.pi * max_frequency)
        idx = np.append(keep, reduction.interface)
        K = reduction.stiffness[np.ix_(idx, idx)]
        M = reduction.mass[np.ix_(idx, idx)]
        C = _modal_viscous(K, M, reduction.loss_factor)
        cached[max_frequency] = K, M, reduction.basis[:, idx], C
    return cached[max_frequency]


def _side_by_side(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The block-diagonal matrix of ``a`` and ``b`` (``scipy.linalg.block_diag``'s general path
    costs more than the rest of a strike's set-up)."""
    out = np.zeros((a.shape[0] + b.shape[0],) * 2)
    out[: a.shape[0], : a.shape[0]] = a
    out[a.shape[0] :, a.shape[0] :] = b
    return out


def _modal_viscous(K: np.ndarray, M: np.ndarray, loss_factor: float) -> np.ndarray:
    """``M Phi diag(eta omega) Phi^T M``: viscous damping equal to ``eta`` at every mode."""
    if loss_factor == 0:
        return np.zeros_like(K)
    lam, phi = sla.eigh(K, M)  # mass-normalised: phi^T M phi = I
    omega = np.sqrt(np.clip(lam, 0.0, None))  # a mechanism's zero mode may come out as -eps
    Mphi = M @ phi
    C = (Mphi * (loss_factor * omega)) @ Mphi.T
    return (C + C.T) / 2


def strike_model(
    probe_reduction,
    rod_reduction,
    contact: float,
    contact_stiffness: float,
    preload: float,
    max_frequency: float,
) -> StrikeModel:
    """Probe and rod reduced for one strike (module docstring).

    Parameters
    ----------
    probe_reduction, rod_reduction : ebantenna.fem.coupling.CraigBampton
        The probe reduced at ``contact``, and the rod; each body is damped by its own
        substructure's loss factor (0 for none).
    contact : float
        Contact position from the hinge, m.
    contact_stiffness : float or PiecewiseSpring
        The contact spring (N/m), or the chords of its force law.
    preload : float
        The static contact force (N).
    max_frequency : float
        Fixed-interface modes at or above it are dropped, Hz.

    Examples
    --------
    >>> from ebantenna.fem.coupling import Rod, craig_bampton, probe_substructure, rod_substructure
    >>> from ebantenna.probe import Probe
    >>> p = craig_bampton(probe_substructure(Probe(), 0.2, n_elements=40), 16)
    >>> r = craig_bampton(rod_substructure(Rod("steel"), n_elements=16), 8)
    >>> m = strike_model(p, r, 0.2, contact_stiffness=1.8e5, preload=0.5, max_frequency=3000.0)
    >>> m.structure.mass.shape  # probe: 8 modes below 3 kHz + interface; rod: 2 + interface
    (12, 12)
    """
    check_reduction("probe_reduction", probe_reduction)
    check_reduction("rod_reduction", rod_reduction)
    contact = check_positive("contact", contact)
    if not isinstance(contact_stiffness, PiecewiseSpring):
        contact_stiffness = check_positive("contact_stiffness", contact_stiffness)
    preload = check_nonnegative("preload", preload)
    Kp, Mp, Tp, Cp = reduced_body(probe_reduction, max_frequency)
    Kr, Mr, _, Cr = reduced_body(rod_reduction, max_frequency)
    n_p, n_r = Kp.shape[0], Kr.shape[0]
    sub = probe_reduction.substructure
    # the servo's rigid rotation per metre of travel at the contact, projected on the basis
    rigid = sweep_velocity(sub.nodes)[sub.free] / contact
    base = np.zeros(n_p + n_r)
    base[:n_p] = sla.solve(Mp, Tp.T @ (sub.mass @ rigid), assume_a="pos")
    c = np.zeros(n_p + n_r)
    c[n_p - 1], c[-1] = 1.0, -1.0  # the probe's interface deflection minus the rod's
    tip = int(np.searchsorted(sub.free, 2 * (sub.nodes.size - 1)))
    output = np.zeros(n_p + n_r)
    output[:n_p] = Tp[tip]
    structure = ContactModel(
        _side_by_side(Mp, Mr), _side_by_side(Kp, Kr), _side_by_side(Cp, Cr), c, base, output
    )
    spring = contact_stiffness
    if not isinstance(spring, PiecewiseSpring):
        spring = float(spring)
    return StrikeModel(structure, float(contact), spring, float(preload))


def strike_model_of(case) -> StrikeModel:
    """The ``unilateral`` model of a contact case: :func:`strike_model` of its reductions,
    struck through a contact that only pushes (with ``hertz_contact`` listed, the spring is the
    chords of the Hertz law, not the linearised spring).

    Parameters
    ----------
    case : ebantenna.simulate.structure.ContactCase
        The contact case (its scene gives the effects and ``max_frequency``).
    """
    check_case(case)
    spring = case.stiffness
    hertz = case.scene.effect("hertz_contact")
    if hertz is not None:
        diameter = case.scene.effect("object_modes").diameter
        spring = hertz.spring(case.rod.material, case.probe, diameter, case.preload)
    return strike_model(
        case.probe_reduction,
        case.rod_reduction,
        case.contact,
        spring,
        case.preload,
        case.scene.max_frequency,
    )


def strike_accelerations(
    models, inverse, speeds, *, rate: float, n_samples: int, max_events: int,
    method: str = "blocks",
) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """The tip acceleration of every strike at ``rate``, and its number of re-strikes.

    Parameters
    ----------
    models : list of StrikeModel
        The distinct strike models.
    inverse : array of int, shape (n,)
        Which model each signal uses.
    speeds : array of shape (n,)
        Each signal's sweep speed, rad/s.
    rate : float
        Sample rate, Hz.
    n_samples : int
        Samples per signal from the first touch.
    max_events : int
        Most contact changes per strike before the contact is held closed (with a warning).
    method : {"blocks", "steps"}
        How each strike is marched: the engine (``"blocks"``) or the reference (``"steps"``),
        as in :func:`.unilateral.unilateral_response`.

    Returns
    -------
    acceleration : ndarray of shape (n, n_samples)
        m/s^2, 0 at the first touch.
    restrikes : ndarray of int, shape (n,)
        Contacts after the first touch: 0 where the probe never lifted off.

    Warns
    -----
    RuntimeWarning
        Once, naming how many strikes reached ``max_events`` (their contact is then held); once,
        naming how many pressed a Hertz contact beyond its chords' last node (sampled at
        ``rate``).
    """
    rate = check_positive("rate", rate)
    n_samples = check_int("n_samples", n_samples, minimum=2)
    max_events = check_int("max_events", max_events, minimum=1)
    check_choice("method", method, tuple(MARCHES))
    speeds = check_array("speeds", speeds, ndim=1)
    inverse = np.asarray(inverse)
    if inverse.shape != speeds.shape or inverse.dtype.kind not in "iu" or (
            inverse.size and not 0 <= inverse.min() <= inverse.max() < len(models)):
        raise ValueError(f"inverse must hold one index into models (0 to {len(models) - 1}) per "
                         f"speed ({speeds.size}), got {inverse!r}")
    if not all(isinstance(m, StrikeModel) for m in models):
        raise TypeError("models must be StrikeModel, as strike_model builds them")
    out = np.empty((len(inverse), n_samples))
    restrikes = np.zeros(len(inverse), dtype=int)
    held = np.zeros(len(inverse), dtype=bool)
    beyond = np.zeros(len(inverse), dtype=bool)
    duration = (n_samples - 1) / rate
    for i, (k, speed) in enumerate(zip(inverse, speeds, strict=True)):
        m = models[k]
        s = m.structure
        with warnings.catch_warnings():  # one warning for all strikes, below
            warnings.simplefilter("ignore", RuntimeWarning)
            res = unilateral_response(
                s.mass, s.stiffness, s.contact, m.contact_stiffness,
                base=s.base, approach_speed=float(speed) * m.contact, duration=duration, fs=rate,
                damping=s.damping, output=s.output, preload=m.preload,
                max_events=max_events, on_max_events="warn", method=method,
            )  # fmt: skip
        out[i] = res.acceleration[:n_samples]
        restrikes[i] = res.n_impacts - 1
        held[i] = res.bilateral_from is not None
        beyond[i] = isinstance(m.contact_stiffness, PiecewiseSpring) and bool(
            res.contact_force.max() > m.contact_stiffness.forces[-1]
        )
    if held.any():
        warnings.warn(
            f"{held.sum()} of {held.size} strikes chattered beyond max_events={max_events} "
            "contact changes; their contact was held closed from then on (undamped bodies "
            "chatter without end: list structural_damping and object_damping, or raise "
            "max_events)",
            RuntimeWarning,
            stacklevel=2,
        )
    if beyond.any():
        warnings.warn(
            f"{beyond.sum()} of {beyond.size} strikes pressed the contact beyond the Hertz "
            "chords' last node (hertz_contact's max_force), where their force bound does not "
            "hold; raise max_force",
            RuntimeWarning,
            stacklevel=2,
        )
    return out, restrikes


def timed_rate(scene, when, dlpf) -> tuple[float, int]:
    """The rate at which a time-stepped axis is computed, and how many samples reach past the
    last reading at ``when``: the internal rate of the chip's filter ``dlpf`` (the chain's,
    ``chip_filter`` of :class:`~ebantenna.simulate.simulator.SignalBatch`), or without it
    ``UNFILTERED_RATE`` times ``fs``.

    Examples
    --------
    >>> from ebantenna.simulate import builtin_scene
    >>> from ebantenna.simulate.effects import LowPassFilter
    >>> scene = builtin_scene("paper")  # 1000 samples at 1 kHz
    >>> timed_rate(scene, np.arange(1000) / 1000.0, LowPassFilter())  # the DLPF runs at 8 kHz
    (8000.0, 7994)
    """
    if not all(hasattr(scene, a) for a in ("fs", "n_samples")):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    when = check_array("when", when, ndim=(1, 2))
    if dlpf is not None and not hasattr(dlpf, "internal_rate"):
        raise TypeError(f"dlpf must be the scene's LowPassFilter or None, got "
                        f"{type(dlpf).__name__}")
    rate = dlpf.internal_rate if dlpf is not None else UNFILTERED_RATE * scene.fs
    span = float(np.max(when)) if np.ndim(when) == 2 else (scene.n_samples - 1) / scene.fs
    return rate, math.floor(span * rate) + 2


def batch_rate(batch, *needs: str) -> tuple[float, int]:
    """:func:`timed_rate` of the chain's batch (its scene, sample instants and chip filter), for
    a model stepped in time that also reads the batch's fields ``needs``; a TypeError unless
    ``batch`` holds them all.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> from ebantenna.simulate import builtin_scene
    >>> batch = SimpleNamespace(scene=builtin_scene("paper"), when=np.arange(1000) / 1000.0,
    ...                         chip_filter=None)
    >>> batch_rate(batch)  # no filter: UNFILTERED_RATE times fs
    (8000.0, 7994)
    """
    if not all(hasattr(batch, a) for a in ("scene", "when", "chip_filter", *needs)):
        raise TypeError(f"batch must be the simulator's SignalBatch, got {type(batch).__name__}")
    return timed_rate(batch.scene, batch.when, batch.chip_filter)


def strike_axis(batch, models) -> tuple[np.ndarray, float]:
    """The ``unilateral`` model's axis (X) in the simulator's responses step: every strike
    marched by the effect's ``method``, at :func:`timed_rate` (:func:`batch_rate`).

    The acceleration is left at that rate for the chip to read at the sample instants, through
    its filter (:func:`~ebantenna.simulate.effects.sensor.read_through_dlpf`, the sensor's step
    after the responses). Records each strike's contacts after the first in ``batch.x``
    (``restrikes``).

    Parameters
    ----------
    batch : ebantenna.simulate.simulator.SignalBatch
        The chain's batch, once its sample instants are set.
    models : list of StrikeModel
        The distinct strike models (``batch.timed["unilateral"]``).

    Returns
    -------
    acceleration : ndarray of shape (n, n_int)
        m/s^2, from the first touch, at ``rate``.
    rate : float
        Its sample rate, Hz.
    """
    rate, n_int = batch_rate(batch, "inverse", "speeds")
    effect = batch.scene.effect("unilateral_contact")
    acc, restrikes = strike_accelerations(
        models, batch.inverse, batch.speeds, rate=rate, n_samples=n_int,
        max_events=effect.max_events, method=effect.method,
    )  # fmt: skip
    batch.x = dataclasses.replace(batch.x, restrikes=restrikes)
    return acc, rate
