"""``simulate(scene) -> Recording``, and the same for many signals at once.

The work is vectorised over signals: modal parameters come from one FEM solve per distinct contact
position (and one for the Z axis), material physics is applied to whole arrays, and every effect
acts on ``(n_signals, n_samples)`` arrays. The only Python loops run over distinct contact
positions, over materials and, to give each signal its own reproducible random numbers, over
signals (one generator per signal and random effect) -- never over samples.
"""

from __future__ import annotations

import dataclasses
import logging
import math
from dataclasses import dataclass

import numpy as np
from threadpoolctl import threadpool_limits

from .._progress import progress
from .._validate import check_array, check_int, check_positive
from ..fem.coupling import craig_bampton, probe_substructure, rod_substructure
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

__all__ = ["ModalTerms", "modal_terms", "simulate", "simulate_batch"]

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


def _pinned_modes(scene: Scene, contacts, materials, show_progress):
    """Arrest modes on a rigid object (a pin, or the ``contact_compliance`` spring)."""
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


def _object_modes(scene: Scene, contacts, materials, preloads, show_progress, x_modes=True):
    """Arrest modes on the touched rod, coupled to the probe (the ``object_modes`` effect).

    Each rod is reduced once, the probe once per distinct contact position; what is left per
    (position, material, preload) is the small coupled eigenproblem, and the models of the
    time-stepped axes that the scene lists (``timed``: ``"strikes"``, ``"friction"``). Without
    ``x_modes`` the coupled eigenproblem is skipped where the strikes give the X axis.
    """
    obj = scene.effect("object_modes")
    probe = scene.probe
    if not scene.has("structural_damping"):
        probe = dataclasses.replace(probe, loss_factor=0.0)
    object_loss = scene.has("object_damping")
    rods = {}
    for name in sorted(set(materials)):
        rod = obj.rod(lookup_material(name))
        sub = rod_substructure(rod, n_elements=obj.rod_elements)
        if not object_loss:
            sub = dataclasses.replace(sub, loss_factor=0.0)
        rods[name] = (rod, craig_bampton(sub, obj.rod_modes))
    unique_c, inverse_c = np.unique(contacts, return_inverse=True)
    inverse_c = inverse_c.ravel()
    unilateral, friction = scene.has("unilateral_contact"), scene.has("coulomb_friction")
    key_of, modes, strikes, frictions = {}, [], [], []
    for i in progress(range(unique_c.size), desc="modes", enabled=show_progress):
        c = float(unique_c[i])
        sub = probe_substructure(probe, c, hinge=scene.hinge, n_elements=scene.n_elements)
        reduced = craig_bampton(sub, obj.probe_modes)
        here = inverse_c == i
        for name, preload in sorted(set(zip(materials[here], preloads[here], strict=True))):
            rod, rod_reduced = rods[name]
            k_c = obj.contact_stiffness(rod.material, probe, preload)
            eta_c = obj.contact_loss_factor(
                rod.material, probe, object_loss=object_loss, preload=preload
            )
            key_of[i, name, preload] = len(key_of)
            if x_modes or not unilateral:
                modes.append(
                    coupled_arrest_modes(
                        probe,
                        scene.hinge,
                        c,
                        rod,
                        probe_reduction=reduced,
                        rod_reduction=rod_reduced,
                        contact_stiffness=k_c,
                        contact_loss_factor=eta_c,
                        max_frequency=scene.max_frequency,
                    )
                )
            if unilateral:  # the same reductions, struck through a contact that only pushes
                model = strike_model(reduced, rod_reduced, c, k_c, preload, scene.max_frequency)
                strikes.append(model)
            if friction:  # Z along the rod, held by dry friction under the preload
                frictions.append(friction_model(reduced, preload, scene.max_frequency))
    inverse = np.array(
        [key_of[key] for key in zip(inverse_c, materials, preloads, strict=True)], dtype=int
    )
    timed = {"strikes": strikes, "friction": frictions}
    return modes, inverse, {name: models for name, models in timed.items() if models}


def _seeds(seeds, n: int) -> list[int]:
    """``n`` seeds as Python ints >= 0 (any size: they enter a SeedSequence), from one or ``n``."""
    if isinstance(seeds, int | np.integer) and not isinstance(seeds, bool):
        return [check_int("seeds", seeds, minimum=0)] * n
    values = list(np.asarray(seeds, dtype=object).ravel()) if np.ndim(seeds) == 1 else None
    if values is None or len(values) != n:
        raise ValueError(f"seeds must be an int or {n} ints, got {seeds!r}")
    return [check_int("seeds", v, minimum=0) for v in values]


def _terms(
    scene: Scene, contacts, materials, speeds, tilts, preloads=None, show_progress=None,
    x_modes=True,
):  # fmt: skip
    """ModalTerms of X and Z per signal, the models of the time-stepped axes (``timed``, see
    :func:`_object_modes`) and which model each signal uses."""
    probe = scene.probe
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
    rows = inverse  # each signal's modes
    if not modes:  # X's modes not asked for (x_modes=False): none, for every signal
        rows, modes = np.zeros(n, dtype=int), [ArrestModes(*[np.empty(0)] * 3, None)]
    width = max(m.omega.size for m in modes)
    omega_u = np.ones((len(modes), width))
    amp_u = np.zeros((len(modes), width))
    force_u = np.zeros((len(modes), width))
    zeta_u = np.zeros((len(modes), width))
    live_u = np.zeros((len(modes), width), dtype=bool)
    for i, m in enumerate(modes):
        k = m.omega.size
        live_u[i, :k] = True
        omega_u[i, :k] = m.omega
        amp_u[i, :k] = m.tip * m.velocity
        if m.contact_force is not None and math.isfinite(m.contact_stiffness):
            force_u[i, :k] = m.contact_force * m.velocity
        if m.damping_ratio is not None:
            zeta_u[i, :k] = m.damping_ratio
    omega = omega_u[rows]
    amplitude = amp_u[rows] * speeds[:, None]
    zeta_s = (
        scene.effect("structural_damping").damping_ratio(probe)
        if scene.has("structural_damping")
        else 0.0
    )
    if scene.has("object_modes"):  # the coupled model carries every body's damping
        zeta = zeta_u[rows]
    else:
        zeta = np.full((n, width), zeta_s)
    if np.any(zeta >= 1):
        raise ValueError(f"a mode is overdamped (zeta up to {zeta.max():.3g}); not supported")
    spring = any(math.isfinite(m.contact_stiffness) for m in modes)
    force = force_u[rows] * speeds[:, None] if spring else None
    x = ModalTerms(omega, zeta, amplitude, live_u[rows], force, preloads)

    kw = dict(n_elements=scene.n_elements, n_modes=scene.n_modes, max_frequency=scene.max_frequency)
    z_modes = arrest_modes(probe, scene.hinge, None, **kw)
    z_amp = (z_modes.tip * z_modes.velocity)[None, :] * (tilts * speeds)[:, None]
    z = ModalTerms(
        np.broadcast_to(z_modes.omega, z_amp.shape).copy(),
        np.full(z_amp.shape, zeta_s),
        z_amp,
        np.ones(z_amp.shape, dtype=bool),
    )
    return x, z, timed, inverse


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
    one = np.ones(1)
    return _terms(
        scene,
        np.array([scene.contact]),
        np.array([scene.material], dtype=object),
        scene.sweep_speed * one,
        scene.tilt_ratio * one,
    )[:2]


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
    materials = np.array(
        [
            lookup_material(str(m)).name
            for m in _per_signal("material", material, scene.material, n)
        ],
        dtype=object,
    )
    speeds = check_array(
        "sweep_speed", _per_signal("sweep_speed", sweep_speed, scene.sweep_speed, n), ndim=1
    )
    tilts = check_array(
        "tilt_ratio", _per_signal("tilt_ratio", tilt_ratio, scene.tilt_ratio, n), ndim=1
    )
    if np.any(speeds <= 0) or np.any(tilts < 0):
        raise ValueError("sweep_speed must be > 0 and tilt_ratio >= 0 for every signal")
    seed_list = _seeds(seeds, n)

    def rngs(effect):
        return [np.random.default_rng([s, effect.stream]) for s in seed_list]

    preloads = None
    scatter = scene.effect("preload_scatter")
    if scatter is not None:
        nominal = scene.effect("object_modes").preload
        preloads = np.array([nominal * scatter.factor(r) for r in rngs(scatter)])
    x, z, timed, inverse = _terms(
        scene, contacts, materials, speeds, tilts, preloads, show_progress, x_modes
    )
    fs, ns = scene.fs, scene.n_samples
    t = np.arange(ns) / fs

    jitter = scene.effect("clock_jitter")
    if jitter is not None:
        when = t + np.stack([jitter.offsets(r, ns) for r in rngs(jitter)])
    else:
        when = t
    dlpf = scene.effect("dlpf")

    def modal_axis(terms):
        coef, rate = modal_exponentials(terms.amplitude, terms.omega, terms.zeta)
        if dlpf is not None:  # the chip's filter at its internal rate, then its decimation
            coef, rate = dlpf.filter_exponentials(coef, rate)
        return damped_exponentials(when, coef, rate)

    if "strikes" in timed:  # X is the strike through a contact that only pushes
        ax, restrikes = unilateral_axis(scene, timed["strikes"], inverse, speeds, when)
        x = dataclasses.replace(x, restrikes=restrikes)
    else:
        ax = modal_axis(x)
    if "friction" in timed:  # Z sticks to the rod and slips along it
        az = friction_axis(scene, timed["friction"], inverse, tilts * speeds, when)
    else:
        az = modal_axis(z)
    if jitter is not None:
        before = when < 0  # a sample taken before the arrest: rigid rotation, no acceleration
        ax[before] = 0.0
        az[before] = 0.0

    level_z = 0.0
    gravity = scene.effect("gravity")
    if gravity is not None:  # a constant: the settled filter passes it unchanged
        ax, az = gravity.apply(ax, az)
        level_z = gravity.g
    hum = scene.effect("mains_hum")
    if hum is not None:  # a steady tone: the filter scales and delays it
        gain = complex(dlpf.frequency_response(hum.frequency)) if dlpf is not None else 1.0
        phases = np.stack([hum.phases(r) for r in rngs(hum)]) + np.angle(gain)  # (n, 2)
        tt = when if np.ndim(when) == 2 else when[None, :]
        ax = ax + abs(gain) * hum.signal(tt, phases[:, :1])
        az = az + abs(gain) * hum.signal(tt, phases[:, 1:])
    noise = scene.effect("sensor_noise")
    if noise is not None:
        draws = noise.draw_signals(rngs(noise), ns, fs, dlpf)  # (n, 2, ns)
        ax = ax + draws[:, 0]
        az = az + draws[:, 1]
    levels_x, levels_z = np.zeros(n), np.full(n, level_z)
    drift = scene.effect("sensor_drift")
    if drift is not None:  # after the filter: the chip's offset and sensitivity
        draws = [drift.draw(r) for r in rngs(drift)]
        gains = np.stack([g for g, _ in draws])
        offsets = np.stack([o for _, o in draws])
        ax = gains[:, :1] * ax + offsets[:, :1]
        az = gains[:, 1:] * az + offsets[:, 1:]
        levels_x = offsets[:, 0].copy()
        levels_z = gains[:, 1] * levels_z + offsets[:, 1]
    clipping = scene.effect("clipping")
    if clipping is not None:
        ax, az = clipping.apply(ax), clipping.apply(az)
    quantisation = scene.effect("quantisation")
    if quantisation is not None:
        ax, az = quantisation.apply(ax), quantisation.apply(az)
    kalman = scene.effect("kalman")
    if kalman is not None:
        ax, az = kalman.apply(ax, levels_x), kalman.apply(az, levels_z)
    log.debug("simulated %d signals of %d samples", n, ns)
    return t, ax, az, x, z


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
    t, ax, az, x, z = simulate_batch(scene, seeds=seed)
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
    return Recording(t, ax[0], az[0], scene.fs, metadata)
