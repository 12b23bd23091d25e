"""``simulate(scene) -> Recording``, and the same for many signals at once.

The simulator is a chain of steps, applied in one loop over an ordered list, :data:`CHAIN`. Each
entry names the effect that switches the step on (None: the step always runs) and the step, a
function that takes the effect and the :class:`SignalBatch` it works on. A scene that does not
list an effect skips its step, and a new effect is one more entry in the list. In order:

1. ``preload_scatter``: each strike's preload. It sets the contact spring, so it comes before
   the modes.
2. *The touched object* (always): the modal parameters of X and Z, and the time-stepped models,
   from one physics model of the touched object (below).
3. ``clock_jitter``: when each sample is taken. The responses are evaluated at these instants.
4. *The responses* (always): X and Z after the arrest, each from its axis's time-stepped model
   if the scene lists one, otherwise the sum of its modes, through the chip's low-pass filter
   (``dlpf``) and its decimation.
5. ``clock_jitter`` again: a sample taken before the arrest reads no acceleration.
6. ``gravity``, 7. ``mains_hum``, 8. ``sensor_noise``: what the chip measures besides the
   vibration. The filter is linear, so it acts on each part as that part enters, which equals
   filtering the sum, where the chip puts it: on the modal exponentials exactly (step 4), on the
   hum by its gain and phase at the hum's frequency, on the noise draws; gravity, a constant,
   passes the settled filter unchanged.
9. ``sensor_drift``: the chip's offset and sensitivity, after its filter.
10. ``clipping`` and 11. ``quantisation``: the chip's range and its 16-bit output.
12. ``kalman``: the filter on the Raspberry Pi, about each axis's resting level.

The touched object is one of four physics models, each a named step. Without ``object_modes`` it
is rigid: ``_pinned_modes``, the probe arrested by a pin (or by the ``contact_compliance``
spring). With it, ``_object_modes`` reduces the probe and the rod once and builds, for each
distinct (contact, material, preload), the models of :data:`OBJECT_MODELS`: ``coupled`` (X's
modes: probe and rod joined by the contact spring), ``unilateral`` (X struck through a contact
that only pushes, with ``unilateral_contact``) and ``friction`` (Z held by dry friction along the
rod, with ``coulomb_friction``).

The work is vectorised over signals: modal parameters come from one FEM solve per distinct contact
position (and one for the Z axis), material physics is applied to whole arrays, and every effect
acts on ``(n_signals, n_samples)`` arrays. The only Python loops run over distinct contact
positions, over materials and, to give each signal its own reproducible random numbers, over
signals (one generator per signal and random effect) -- never over samples.

Inputs are checked once, where they enter (:class:`~ebantenna.simulate.Scene`, :func:`simulate`,
:func:`simulate_batch`); every step below takes checked values.
"""

from __future__ import annotations

import dataclasses
import logging
import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from threadpoolctl import threadpool_limits

from .._progress import progress
from .._validate import check_array, check_int, check_positive
from ..fem.coupling import craig_bampton, probe_substructure, rod_substructure
from ..probe import Probe
from ..probe import material as lookup_material
from ..recording import Recording
from .modes import (
    ArrestModes,
    arrest_modes,
    coupled_arrest_modes,
    damped_exponentials,
    modal_exponentials,
)
from .scene import Scene
from .stick_slip import friction_axis, friction_model
from .strikes import strike_model, unilateral_axis

__all__ = [
    "ModalTerms",
    "SignalBatch",
    "CHAIN",
    "OBJECT_MODELS",
    "ChainStep",
    "ObjectModel",
    "modal_terms",
    "simulate",
    "simulate_batch",
]

log = logging.getLogger(__name__)


@dataclass(frozen=True, eq=False)
class ModalTerms:
    """Modal parameters of many signals, zero-padded to a common number of modes.

    Attributes
    ----------
    omega : ndarray of shape (n_signals, n_modes)
        Undamped natural circular frequencies (with the contact compliance, if listed), rad/s.
    zeta : ndarray of shape (n_signals, n_modes)
        Damping ratios (dimensionless).
    amplitude : ndarray of shape (n_signals, n_modes)
        Tip velocity each mode starts with, ``phi_k(L) q_dot_k(0)``, m/s; 0 in padding.
    live : ndarray of bool, shape (n_signals, n_modes)
        True for a simulated mode, False for padding.
    contact_force : ndarray of shape (n_signals, n_modes) or None
        ``F_k q_dot_k(0)``: each mode's force in the contact spring per unit modal coordinate
        times its initial modal velocity, N/s (the dynamic contact force is
        ``sum_k F_k q_dot_k(0) / omega_dk e^(-a_k t) sin(omega_dk t)``); None without a contact
        spring (a rigid pin, or the Z axis).
    preload : ndarray of shape (n_signals,) or None
        Each strike's static contact force, N, with the ``object_modes`` effect; None otherwise.
    restrikes : ndarray of int, shape (n_signals,) or None
        With ``unilateral_contact``, once simulated: contacts after the first touch per strike.
    """

    omega: np.ndarray
    zeta: np.ndarray
    amplitude: np.ndarray
    live: np.ndarray
    contact_force: np.ndarray | None = None
    preload: np.ndarray | None = None
    restrikes: np.ndarray | None = None

    def frequencies(self, row: int = 0) -> np.ndarray:
        """Natural frequencies of signal ``row`` (padding dropped), Hz."""
        return self.omega[row, self.live[row]] / (2 * math.pi)

    def damping_ratios(self, row: int = 0) -> np.ndarray:
        """Damping ratios of signal ``row`` (padding dropped)."""
        return self.zeta[row, self.live[row]]

    def dynamic_contact_force(self, t) -> np.ndarray:
        """The contact spring's force about its static value at times ``t`` (s), N.

        Shape ``(n_signals, t.size)``; positive presses the probe on the object. The linear
        model lets it take either sign: a strike in which it falls below minus the preload
        would, on the rig, lift the probe off the object (see
        :func:`ebantenna.simulate.unilateral.unilateral_response`).
        """
        if self.contact_force is None:
            raise ValueError("these modal terms have no contact spring (contact_force is None)")
        # q_k(t) = q_dot_k(0) / omega_dk e^(-a_k t) sin(omega_dk t), on the modes' own rates
        _, rate = modal_exponentials(self.contact_force, self.omega, self.zeta)
        coef = (self.contact_force / rate.imag).astype(complex)
        return damped_exponentials(np.asarray(t, dtype=float), coef, rate)

    def lift_off_ratio(self, duration: float = 1.0, rate: float = 8000.0) -> np.ndarray:
        """Largest pull of the linear contact over its preload, per strike (dimensionless).

        ``max_t (-F_dyn(t)) / F0`` over ``duration`` seconds sampled at ``rate`` Hz: above 1 the
        linear (bilateral) model holds the probe to the object by a pull that a real contact
        cannot give; the probe would lift off and strike again.
        """
        if self.preload is None:
            raise ValueError("these modal terms have no preload (listed without object_modes)")
        t = np.arange(int(round(check_positive("duration", duration) * rate))) / rate
        return np.max(-self.dynamic_contact_force(t), axis=1) / self.preload


# -------------------------------------------------------------------------------------------------
# The physics models of the touched object
# -------------------------------------------------------------------------------------------------
def _pinned_modes(scene: Scene, contacts, materials, show_progress):
    """Arrest modes on a rigid object (a pin, or the ``contact_compliance`` spring).

    One FEM solve per distinct (contact, spring); takes checked values.
    """
    probe = scene.probe
    kw = dict(n_elements=scene.n_elements, n_modes=scene.n_modes, max_frequency=scene.max_frequency)
    compliance = scene.effect("contact_compliance")
    if compliance is not None:  # one FEM solve per (contact, material)
        stiffness = {m: compliance.stiffness(lookup_material(m), probe) for m in set(materials)}
        springs = np.array([stiffness[m] for m in materials])
    else:
        springs = np.full(contacts.size, math.inf)
    keys = np.stack([contacts, springs], axis=1)
    unique, inverse = np.unique(keys, axis=0, return_inverse=True)
    modes = [
        arrest_modes(probe, scene.hinge, float(c), contact_stiffness=float(k), **kw)
        for c, k in progress(unique, total=len(unique), desc="modes", enabled=show_progress)
    ]
    return modes, inverse.ravel()


@dataclass(frozen=True, eq=False)
class ContactCase:
    """One distinct (contact position, material, preload) of a batch on a rod (``object_modes``).

    What every model of the touched rod needs: the bodies, their Craig-Bampton reductions and
    the contact spring. Built by the simulator from checked values.

    Attributes
    ----------
    scene : Scene
        The scene simulated.
    probe : Probe
        The probe (without its loss factor unless ``structural_damping`` is listed).
    contact : float
        Contact position from the hinge, m.
    material : str
        Canonical name of the touched material.
    preload : float
        The contact's static force, N.
    rod : Rod
        The touched rod.
    probe_reduction, rod_reduction : Reduction
        The two bodies reduced at the contact (:func:`ebantenna.fem.coupling.craig_bampton`).
    stiffness : float
        The contact spring under ``preload``, N/m.
    loss_factor : float
        The contact's loss factor (dimensionless).
    """

    scene: Scene
    probe: Probe
    contact: float
    material: str
    preload: float
    rod: object
    probe_reduction: object
    rod_reduction: object
    stiffness: float
    loss_factor: float


def _coupled_model(case: ContactCase) -> ArrestModes:
    """The ``coupled`` model: the arrest modes of probe and rod joined by the contact spring."""
    return coupled_arrest_modes(
        case.probe,
        case.scene.hinge,
        case.contact,
        case.rod,
        probe_reduction=case.probe_reduction,
        rod_reduction=case.rod_reduction,
        contact_stiffness=case.stiffness,
        contact_loss_factor=case.loss_factor,
        max_frequency=case.scene.max_frequency,
    )


def _unilateral_model(case: ContactCase):
    """The ``unilateral`` model: the same reductions, struck through a contact that only pushes."""
    return strike_model(
        case.probe_reduction,
        case.rod_reduction,
        case.contact,
        case.stiffness,
        case.preload,
        case.scene.max_frequency,
    )


def _friction_model(case: ContactCase):
    """The ``friction`` model: Z along the rod, held by dry friction under the preload."""
    return friction_model(case.probe_reduction, case.preload, case.scene.max_frequency)


def _strike_axis(batch: SignalBatch, models) -> np.ndarray:
    """X from the ``unilateral`` strikes; records each strike's contacts after the first."""
    ax, restrikes = unilateral_axis(batch.scene, models, batch.inverse, batch.speeds, batch.when)
    batch.x = dataclasses.replace(batch.x, restrikes=restrikes)
    return ax


def _friction_axis(batch: SignalBatch, models) -> np.ndarray:
    """Z from the ``friction`` model: stick and slip along the rod, at the tilt rotation's speed."""
    return friction_axis(batch.scene, models, batch.inverse, batch.tilts * batch.speeds, batch.when)


@dataclass(frozen=True)
class ObjectModel:
    """One physics model of the touched rod, built for each distinct contact case.

    Attributes
    ----------
    name : str
        ``"coupled"``, ``"unilateral"`` or ``"friction"``.
    axis : {"x", "z"}
        The axis the model gives.
    effect : str or None
        The effect that asks for the model (None: every scene with ``object_modes``).
    build : callable
        ``build(case: ContactCase)``: the model of one contact case.
    respond : callable or None
        ``respond(batch, models) -> (n, n_samples) array``: the axis, for a model stepped in
        time; None for modes, which the modal sum reads (:data:`CHAIN`, the responses).
    unless : str or None
        An effect that gives the same axis in time: when it is listed and the caller asked for no
        X modes (``x_modes=False``, as a data set build does), the model is left out.
    """

    name: str
    axis: str
    effect: str | None
    build: Callable
    respond: Callable | None = None
    unless: str | None = None

    def wanted(self, scene: Scene, x_modes: bool) -> bool:
        """Whether ``scene`` needs this model (``x_modes`` as in :func:`simulate_batch`)."""
        if self.effect is not None and not scene.has(self.effect):
            return False
        return x_modes or self.unless is None or not scene.has(self.unless)


#: The models of the touched rod (``object_modes``), in the order they are built for each
#: contact case. A model stepped in time (``respond`` set) gives its axis instead of the modes.
OBJECT_MODELS = (
    ObjectModel("coupled", "x", None, _coupled_model, unless="unilateral_contact"),
    ObjectModel("unilateral", "x", "unilateral_contact", _unilateral_model, _strike_axis),
    ObjectModel("friction", "z", "coulomb_friction", _friction_model, _friction_axis),
)


def _reduced_rods(scene: Scene, materials, object_loss: bool) -> dict:
    """Each touched rod and its Craig-Bampton reduction, once per material."""
    obj = scene.effect("object_modes")
    rods = {}
    for name in sorted(set(materials)):
        rod = obj.rod(lookup_material(name))
        sub = rod_substructure(rod, n_elements=obj.rod_elements)
        if not object_loss:
            sub = dataclasses.replace(sub, loss_factor=0.0)
        rods[name] = (rod, craig_bampton(sub, obj.rod_modes))
    return rods


def _contact_cases(scene: Scene, probe: Probe, contact: float, rods: dict, pairs, object_loss):
    """The contact cases at one position: the probe reduced once, then each (material, preload).

    ``pairs`` lists the (material, preload) of the signals touching at ``contact``; yields one
    :class:`ContactCase` per distinct pair, in sorted order.
    """
    obj = scene.effect("object_modes")
    sub = probe_substructure(probe, contact, hinge=scene.hinge, n_elements=scene.n_elements)
    reduced = craig_bampton(sub, obj.probe_modes)
    for name, preload in sorted(set(pairs)):
        rod, rod_reduced = rods[name]
        yield ContactCase(
            scene=scene,
            probe=probe,
            contact=contact,
            material=name,
            preload=preload,
            rod=rod,
            probe_reduction=reduced,
            rod_reduction=rod_reduced,
            stiffness=obj.contact_stiffness(rod.material, probe, preload),
            loss_factor=obj.contact_loss_factor(
                rod.material, probe, object_loss=object_loss, preload=preload
            ),
        )


def _object_modes(scene: Scene, contacts, materials, preloads, show_progress, x_modes=True):
    """The models of the touched rod (the ``object_modes`` effect), coupled to the probe.

    Each rod is reduced once, the probe once per distinct contact position; what is left per
    (position, material, preload) is each model of :data:`OBJECT_MODELS` the scene needs.
    Takes checked values. Returns the coupled modes (X), which case each signal uses, and the
    models stepped in time by name (``timed``, only those built).
    """
    probe = scene.probe
    if not scene.has("structural_damping"):
        probe = dataclasses.replace(probe, loss_factor=0.0)
    object_loss = scene.has("object_damping")
    rods = _reduced_rods(scene, materials, object_loss)
    models = [model for model in OBJECT_MODELS if model.wanted(scene, x_modes)]
    built = {model.name: [] for model in OBJECT_MODELS}
    unique_c, inverse_c = np.unique(contacts, return_inverse=True)
    inverse_c = inverse_c.ravel()
    key_of = {}
    for i in progress(range(unique_c.size), desc="modes", enabled=show_progress):
        here = inverse_c == i
        pairs = zip(materials[here], preloads[here], strict=True)
        for case in _contact_cases(scene, probe, float(unique_c[i]), rods, pairs, object_loss):
            key_of[i, case.material, case.preload] = len(key_of)
            for model in models:
                built[model.name].append(model.build(case))
    inverse = np.array(
        [key_of[key] for key in zip(inverse_c, materials, preloads, strict=True)], dtype=int
    )
    modes = built.pop("coupled")
    return modes, inverse, {name: got for name, got in built.items() if got}


# -------------------------------------------------------------------------------------------------
# Modal parameters per signal
# -------------------------------------------------------------------------------------------------
def _padded(modes) -> tuple[np.ndarray, ...]:
    """The distinct modes side by side, zero-padded to a common width.

    Returns ``omega`` (padding 1), ``zeta``, ``amplitude`` (``phi_k(L) q_dot_k(0)``),
    ``force`` (``F_k q_dot_k(0)``, 0 without a finite contact spring) and ``live``, each of shape
    ``(len(modes), width)``.
    """
    width = max(m.omega.size for m in modes)
    omega = np.ones((len(modes), width))
    amplitude = np.zeros((len(modes), width))
    force = np.zeros((len(modes), width))
    zeta = np.zeros((len(modes), width))
    live = np.zeros((len(modes), width), dtype=bool)
    for i, m in enumerate(modes):
        k = m.omega.size
        live[i, :k] = True
        omega[i, :k] = m.omega
        amplitude[i, :k] = m.tip * m.velocity
        if m.contact_force is not None and math.isfinite(m.contact_stiffness):
            force[i, :k] = m.contact_force * m.velocity
        if m.damping_ratio is not None:
            zeta[i, :k] = m.damping_ratio
    return omega, zeta, amplitude, force, live


def _x_terms(scene: Scene, modes, rows, speeds, preloads, zeta_s: float) -> ModalTerms:
    """X's modal parameters per signal: ``modes[rows[i]]`` scaled by signal ``i``'s speed.

    Without ``object_modes`` every mode takes the probe's structural damping ``zeta_s``; with
    it, the coupled modes carry every body's damping. Takes checked values.
    """
    n = speeds.size
    if not modes:  # X's modes not asked for (x_modes=False): none, for every signal
        rows, modes = np.zeros(n, dtype=int), [ArrestModes(*[np.empty(0)] * 3, None)]
    omega_u, zeta_u, amp_u, force_u, live_u = _padded(modes)
    amplitude = amp_u[rows] * speeds[:, None]
    if scene.has("object_modes"):  # the coupled model carries every body's damping
        zeta = zeta_u[rows]
    else:
        zeta = np.full((n, omega_u.shape[1]), zeta_s)
    if np.any(zeta >= 1):
        raise ValueError(f"a mode is overdamped (zeta up to {zeta.max():.3g}); not supported")
    spring = any(math.isfinite(m.contact_stiffness) for m in modes)
    force = force_u[rows] * speeds[:, None] if spring else None
    return ModalTerms(omega_u[rows], zeta, amplitude, live_u[rows], force, preloads)


def _z_terms(scene: Scene, speeds, tilts, zeta_s: float) -> ModalTerms:
    """Z's modal parameters per signal: the free probe, driven across the sweep plane."""
    kw = dict(n_elements=scene.n_elements, n_modes=scene.n_modes, max_frequency=scene.max_frequency)
    z_modes = arrest_modes(scene.probe, scene.hinge, None, **kw)
    z_amp = (z_modes.tip * z_modes.velocity)[None, :] * (tilts * speeds)[:, None]
    return ModalTerms(
        np.broadcast_to(z_modes.omega, z_amp.shape).copy(),
        np.full(z_amp.shape, zeta_s),
        z_amp,
        np.ones(z_amp.shape, dtype=bool),
    )


def _terms(
    scene: Scene, contacts, materials, speeds, tilts, preloads=None, show_progress=None,
    x_modes=True,
):  # fmt: skip
    """ModalTerms of X and Z per signal, the models stepped in time (``timed``, see
    ``_object_modes``) and which model each signal uses. Takes checked values.

    The touched object is a rod coupled to the probe with ``object_modes`` and rigid without.
    """
    n = contacts.size
    # Many small eigenproblems: BLAS threads only add overhead (and thrash on a busy machine).
    with threadpool_limits(limits=1):
        if scene.has("object_modes"):
            if preloads is None:
                preloads = np.full(n, scene.effect("object_modes").preload)
            modes, inverse, timed = _object_modes(
                scene, contacts, materials, preloads, show_progress, x_modes
            )
        else:
            (modes, inverse), timed = _pinned_modes(scene, contacts, materials, show_progress), {}
    damping = scene.effect("structural_damping")
    zeta_s = damping.damping_ratio(scene.probe) if damping is not None else 0.0
    x = _x_terms(scene, modes, inverse, speeds, preloads, zeta_s)
    return x, _z_terms(scene, speeds, tilts, zeta_s), timed, inverse


# -------------------------------------------------------------------------------------------------
# The chain
# -------------------------------------------------------------------------------------------------
@dataclass(eq=False)
class SignalBatch:
    """What the chain passes from step to step: ``n`` signals' checked inputs and results so far.

    Attributes
    ----------
    scene : Scene
        Everything the signals share.
    contacts, speeds, tilts : ndarray of shape (n,)
        Per-signal contact position (m), sweep speed (rad/s) and tilt ratio.
    materials : ndarray of str, shape (n,)
        Per-signal canonical material names.
    seeds : list of int
        Per-signal seeds of the random effects.
    show_progress : bool or None
        The progress bar over contact positions (None: on a terminal).
    x_modes : bool
        As in :func:`simulate_batch`.
    preloads : ndarray of shape (n,) or None
        Per-strike preloads, N, once ``preload_scatter`` drew them.
    x, z : ModalTerms or None
        The modal parameters, once the touched object's step ran.
    timed : dict
        The models stepped in time by name (:data:`OBJECT_MODELS`).
    inverse : ndarray of int or None
        Which contact case each signal uses.
    t : ndarray of shape (n_samples,)
        Nominal sample times, s.
    when : ndarray of shape (n_samples,) or (n, n_samples)
        When each sample is taken, s: ``t`` unless ``clock_jitter`` moves it.
    ax, az : ndarray of shape (n, n_samples) or None
        The signals, m/s^2, once the responses' step ran.
    levels_x, levels_z : ndarray of shape (n,)
        Each axis's resting reading, m/s^2 (gravity, the drift's offset), for the Kalman filter.
    """

    scene: Scene
    contacts: np.ndarray
    materials: np.ndarray
    speeds: np.ndarray
    tilts: np.ndarray
    seeds: list
    show_progress: bool | None = None
    x_modes: bool = True
    preloads: np.ndarray | None = None
    x: ModalTerms | None = None
    z: ModalTerms | None = None
    timed: dict = field(default_factory=dict)
    inverse: np.ndarray | None = None
    t: np.ndarray = field(init=False)
    when: np.ndarray = field(init=False)
    ax: np.ndarray | None = None
    az: np.ndarray | None = None
    levels_x: np.ndarray = field(init=False)
    levels_z: np.ndarray = field(init=False)

    def __post_init__(self):
        self.t = np.arange(self.scene.n_samples) / self.scene.fs
        self.when = self.t
        self.levels_x, self.levels_z = np.zeros(self.n), np.zeros(self.n)

    @property
    def n(self) -> int:
        """Number of signals."""
        return self.contacts.size

    def rngs(self, effect) -> list[np.random.Generator]:
        """One generator per signal for a random ``effect``: from its seed and the effect's stream.

        Adding or removing one effect never changes the random numbers of another.
        """
        return [np.random.default_rng([s, effect.stream]) for s in self.seeds]


def _scatter_preloads(scatter, batch: SignalBatch) -> None:
    """``preload_scatter``: each strike's preload, the nominal one times a random factor."""
    nominal = batch.scene.effect("object_modes").preload
    batch.preloads = np.array([nominal * scatter.factor(r) for r in batch.rngs(scatter)])


def _touched_object(_, batch: SignalBatch) -> None:
    """The modal parameters of X and Z, and the models stepped in time (``_terms``)."""
    batch.x, batch.z, batch.timed, batch.inverse = _terms(
        batch.scene,
        batch.contacts,
        batch.materials,
        batch.speeds,
        batch.tilts,
        batch.preloads,
        batch.show_progress,
        batch.x_modes,
    )


def _jitter_instants(jitter, batch: SignalBatch) -> None:
    """``clock_jitter``: each sample taken at ``n / fs + e_n``."""
    batch.when = batch.t + np.stack([jitter.offsets(r, batch.t.size) for r in batch.rngs(jitter)])


def _modal_axis(terms: ModalTerms, batch: SignalBatch) -> np.ndarray:
    """The sum of ``terms``' modes read at ``batch.when``, through the chip's filter if listed."""
    coef, rate = modal_exponentials(terms.amplitude, terms.omega, terms.zeta)
    dlpf = batch.scene.effect("dlpf")
    if dlpf is not None:  # the chip's filter at its internal rate, then its decimation
        coef, rate = dlpf.filter_exponentials(coef, rate)
    return damped_exponentials(batch.when, coef, rate)


def _axis_response(batch: SignalBatch, axis: str) -> np.ndarray:
    """One axis: from its model stepped in time, if the scene built one, else its modes."""
    for model in OBJECT_MODELS:
        if model.axis == axis and model.respond is not None and model.name in batch.timed:
            return model.respond(batch, batch.timed[model.name])
    return _modal_axis(batch.x if axis == "x" else batch.z, batch)


def _respond(_, batch: SignalBatch) -> None:
    """X and Z after the arrest, read at the sample instants."""
    batch.ax = _axis_response(batch, "x")
    batch.az = _axis_response(batch, "z")


def _rest_before_arrest(_, batch: SignalBatch) -> None:
    """``clock_jitter``: a sample taken before the arrest reads rigid rotation, no acceleration."""
    before = batch.when < 0
    batch.ax[before] = 0.0
    batch.az[before] = 0.0


def _add_gravity(gravity, batch: SignalBatch) -> None:
    """``gravity``: a constant, which the settled filter passes unchanged; Z rests at ``g``."""
    batch.ax, batch.az = gravity.apply(batch.ax, batch.az)
    batch.levels_z = np.full(batch.n, gravity.g)


def _add_hum(hum, batch: SignalBatch) -> None:
    """``mains_hum``: a steady tone, which the filter scales and delays."""
    dlpf = batch.scene.effect("dlpf")
    gain = complex(dlpf.frequency_response(hum.frequency)) if dlpf is not None else 1.0
    phases = np.stack([hum.phases(r) for r in batch.rngs(hum)]) + np.angle(gain)  # (n, 2)
    tt = batch.when if np.ndim(batch.when) == 2 else batch.when[None, :]
    batch.ax = batch.ax + abs(gain) * hum.signal(tt, phases[:, :1])
    batch.az = batch.az + abs(gain) * hum.signal(tt, phases[:, 1:])


def _add_noise(noise, batch: SignalBatch) -> None:
    """``sensor_noise``: white at the chip's rate, through its filter and decimation."""
    scene = batch.scene
    draws = noise.draw_signals(batch.rngs(noise), scene.n_samples, scene.fs, scene.effect("dlpf"))
    batch.ax = batch.ax + draws[:, 0]  # draws: (n, 2, n_samples)
    batch.az = batch.az + draws[:, 1]


def _drift(drift, batch: SignalBatch) -> None:
    """``sensor_drift``: after the filter, the chip's offset and sensitivity of this session."""
    draws = [drift.draw(r) for r in batch.rngs(drift)]
    gains = np.stack([g for g, _ in draws])
    offsets = np.stack([o for _, o in draws])
    batch.ax = gains[:, :1] * batch.ax + offsets[:, :1]
    batch.az = gains[:, 1:] * batch.az + offsets[:, 1:]
    batch.levels_x = offsets[:, 0].copy()
    batch.levels_z = gains[:, 1] * batch.levels_z + offsets[:, 1]


def _clip(clipping, batch: SignalBatch) -> None:
    """``clipping``: the chip's range."""
    batch.ax, batch.az = clipping.apply(batch.ax), clipping.apply(batch.az)


def _quantise(quantisation, batch: SignalBatch) -> None:
    """``quantisation``: the chip's 16-bit output."""
    batch.ax, batch.az = quantisation.apply(batch.ax), quantisation.apply(batch.az)


def _kalman(kalman, batch: SignalBatch) -> None:
    """``kalman``: the steady-state filter on the Raspberry Pi, about each axis's resting level."""
    batch.ax = kalman.apply(batch.ax, batch.levels_x)
    batch.az = kalman.apply(batch.az, batch.levels_z)


@dataclass(frozen=True)
class ChainStep:
    """One entry of :data:`CHAIN`.

    Attributes
    ----------
    effect : str or None
        The effect that switches the step on; None: the step always runs.
    apply : callable
        ``apply(effect, batch)``: changes the :class:`SignalBatch` in place (``effect`` is the
        scene's instance, or None for a step that always runs).
    """

    effect: str | None
    apply: Callable


#: The simulator's steps, in the order it applies them (see the module's docstring for why).
CHAIN = (
    ChainStep("preload_scatter", _scatter_preloads),
    ChainStep(None, _touched_object),
    ChainStep("clock_jitter", _jitter_instants),
    ChainStep(None, _respond),
    ChainStep("clock_jitter", _rest_before_arrest),
    ChainStep("gravity", _add_gravity),
    ChainStep("mains_hum", _add_hum),
    ChainStep("sensor_noise", _add_noise),
    ChainStep("sensor_drift", _drift),
    ChainStep("clipping", _clip),
    ChainStep("quantisation", _quantise),
    ChainStep("kalman", _kalman),
)


def _run_chain(batch: SignalBatch) -> SignalBatch:
    """Apply every step of :data:`CHAIN` that the scene asks for, in order."""
    for step in CHAIN:
        effect = None if step.effect is None else batch.scene.effect(step.effect)
        if step.effect is None or effect is not None:
            step.apply(effect, batch)
    log.debug("simulated %d signals of %d samples", batch.n, batch.scene.n_samples)
    return batch


# -------------------------------------------------------------------------------------------------
# The public entries: inputs are checked here, once
# -------------------------------------------------------------------------------------------------
def _per_signal(name, value, default, n):
    if value is None:
        value = default
    if isinstance(value, str):
        return np.array([value] * n, dtype=object)
    if np.ndim(value) == 0:
        return np.full(n, value, dtype=float)
    array = np.asarray(value)
    if array.shape != (n,):
        raise ValueError(f"{name} must be a scalar or have shape ({n},), got shape {array.shape}")
    return array


def _seeds(seeds, n: int) -> list[int]:
    """``n`` seeds as Python ints >= 0 (any size: they enter a SeedSequence), from one or ``n``."""
    if isinstance(seeds, int | np.integer) and not isinstance(seeds, bool):
        return [check_int("seeds", seeds, minimum=0)] * n
    values = list(np.asarray(seeds, dtype=object).ravel()) if np.ndim(seeds) == 1 else None
    if values is None or len(values) != n:
        raise ValueError(f"seeds must be an int or {n} ints, got {seeds!r}")
    return [check_int("seeds", v, minimum=0) for v in values]


def _checked_batch(scene, contact, material, sweep_speed, tilt_ratio, seeds, **options):
    """The :class:`SignalBatch` of :func:`simulate_batch`'s arguments, every one checked here.

    The scene's own values, the defaults, were checked when it was built.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    sizes = [np.size(v) for v in (contact, sweep_speed, tilt_ratio, seeds) if v is not None]
    if material is not None and not isinstance(material, str):
        sizes.append(len(material))
    n = max(sizes + [1])
    contacts = check_array("contact", _per_signal("contact", contact, scene.contact, n), ndim=1)
    bad = (contacts <= 0) | (contacts >= scene.probe.length)
    if np.any(bad):
        raise ValueError(
            f"contact must lie in (0, {scene.probe.length:g}) m, got {contacts[bad][0]!r}"
        )
    names = _per_signal("material", material, scene.material, n)
    materials = np.array([lookup_material(str(m)).name for m in names], dtype=object)
    speeds = check_array(
        "sweep_speed", _per_signal("sweep_speed", sweep_speed, scene.sweep_speed, n), ndim=1
    )
    tilts = check_array(
        "tilt_ratio", _per_signal("tilt_ratio", tilt_ratio, scene.tilt_ratio, n), ndim=1
    )
    if np.any(speeds <= 0) or np.any(tilts < 0):
        raise ValueError("sweep_speed must be > 0 and tilt_ratio >= 0 for every signal")
    return SignalBatch(scene, contacts, materials, speeds, tilts, _seeds(seeds, n), **options)


def _scene_batch(scene: Scene, seed: int) -> SignalBatch:
    """The one signal of a checked scene, with a checked seed."""
    one = np.ones(1)
    return SignalBatch(
        scene,
        np.array([scene.contact]),
        np.array([scene.material], dtype=object),
        scene.sweep_speed * one,
        scene.tilt_ratio * one,
        [seed],
    )


def modal_terms(scene: Scene) -> tuple[ModalTerms, ModalTerms]:
    """The X and Z modal parameters of one scene (one row each).

    Examples
    --------
    >>> from ebantenna.simulate import builtin_scene, modal_terms
    >>> x, z = modal_terms(builtin_scene("ideal").with_(contact=0.2))
    >>> x.frequencies().round(1), z.frequencies().round(1)
    (array([ 39. , 243.5, 350.7]), array([ 13.9,  87. , 243.6, 477.4]))
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    b = _scene_batch(scene, 0)
    return _terms(scene, b.contacts, b.materials, b.speeds, b.tilts)[:2]


def simulate_batch(
    scene: Scene,
    *,
    contact=None,
    material=None,
    sweep_speed=None,
    tilt_ratio=None,
    seeds=0,
    show_progress=None,
    x_modes=True,
):
    """Simulate many signals of one scene, each with its own contact, material, speed and seed.

    Row ``i`` equals ``simulate(scene.with_(contact=contact[i], material=material[i],
    sweep_speed=sweep_speed[i], tilt_ratio=tilt_ratio[i]), seed=seeds[i])``.

    Parameters
    ----------
    scene : Scene
        Everything that is shared.
    contact, sweep_speed, tilt_ratio : float or array of shape (n,), optional
        Per-signal values (m, rad/s, dimensionless); the scene's by default.
    material : str or array of str of shape (n,), optional
        Per-signal touched materials; the scene's by default.
    seeds : int or array of int of shape (n,)
        Seeds of the signals' random effects.
    show_progress : bool, optional
        Force the progress bar over contact positions on or off (default: on a terminal).
    x_modes : bool
        Whether ``x`` carries the coupled modes even where the strikes of ``unilateral_contact``
        give the X axis (one eigenproblem per strike); False leaves them out there (``x`` then
        has no modes, only ``preload`` and ``restrikes``), as a data set build does.

    Returns
    -------
    t : ndarray of shape (n_samples,)
        Nominal sample times, s.
    ax, az : ndarray of shape (n, n_samples)
        Tip accelerations, m/s^2.
    x, z : ModalTerms
        The modal parameters used.
    """
    batch = _checked_batch(
        scene, contact, material, sweep_speed, tilt_ratio, seeds,
        show_progress=show_progress, x_modes=x_modes,
    )  # fmt: skip
    _run_chain(batch)
    return batch.t, batch.ax, batch.az, batch.x, batch.z


def simulate(scene: Scene, seed: int = 0) -> Recording:
    """Simulate the tip accelerations of one scene.

    Parameters
    ----------
    scene : Scene
        What to simulate (:func:`~ebantenna.simulate.builtin_scene` or your own).
    seed : int
        Seed of the random effects (noise, jitter, hum phase); a scene without random effects does
        not depend on it.

    Returns
    -------
    Recording
        ``t`` (s), ``ax``, ``az`` (m/s^2), ``fs`` (Hz) and metadata: the scene, the seed and the
        simulated modes of X and Z (frequencies in Hz, damping ratios); with the
        ``unilateral_contact`` effect also ``restrikes``, the contacts after the first touch.

    Examples
    --------
    >>> from ebantenna.simulate import builtin_scene, simulate
    >>> rec = simulate(builtin_scene("paper").with_(contact=0.25, material="brass"), seed=3)
    >>> rec.n_samples, rec.fs
    (1000, 1000.0)
    >>> rec.metadata["modes_x_hz"][:4]  # the probe's and the brass rod's coupled modes
    [32.82, 92.58, 185.89, 372.96]
    """
    seed = check_int("seed", seed, minimum=0)
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    batch = _run_chain(_scene_batch(scene, seed))
    x, z = batch.x, batch.z
    metadata = {
        "source": "ebantenna.simulate",
        "scene": scene.to_dict(),
        "seed": seed,
        "modes_x_hz": [round(float(f), 2) for f in x.frequencies()],
        "zeta_x": [float(v) for v in x.damping_ratios()],
        "modes_z_hz": [round(float(f), 2) for f in z.frequencies()],
        "zeta_z": [float(v) for v in z.damping_ratios()],
    }
    if x.restrikes is not None:  # the unilateral contact: strikes after the first touch
        metadata["restrikes"] = int(x.restrikes[0])
    return Recording(batch.t, batch.ax[0], batch.az[0], scene.fs, metadata)
