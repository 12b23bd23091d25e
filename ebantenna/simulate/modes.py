"""The modal response of the probe after the object arrests it.

Before the contact the servo swings the probe rigidly about the hinge at the angular speed
``Omega``: every point moves with ``v = Omega x``, every section turns with ``theta = Omega``. At
the contact the servo stops and the object arrests the probe at the contact point: the supports take
the velocity of the DOFs they fix (an impulsive reaction), the rest keeps its velocity. The free
vibration that follows, with ``q(0) = 0``, is a sum of FEM modes with initial modal velocities
``q_dot(0) = Phi^T M u0`` (:meth:`ebantenna.fem.ModalResult.modal_coordinates`). With a compliant
contact (the ``contact_compliance`` effect) nothing is fixed at the contact: the contact spring
starts relaxed and stops the probe there within the first cycles. A mode ``k`` with
circular frequency ``omega_k``, damping ratio ``zeta_k`` and ``q_dot_k(0) = p_k`` moves as

    q_k(t) = p_k / omega_d e^(-a t) sin(omega_d t),   a = zeta_k omega_k,
    omega_d = omega_k sqrt(1 - zeta_k^2),

and the tip acceleration is ``sum_k phi_k(L) q_k''(t)`` with

    q_k''(t) = p_k e^(-a t) [ (a^2 - omega_d^2) / omega_d sin(omega_d t) - 2 a cos(omega_d t) ]
             = Im( C_k e^(s_k t) ),   s_k = -a + i omega_d,
             C_k = p_k ((a^2 - omega_d^2) / omega_d - 2 i a).

**X and Z.** The object touches the probe in the sweep plane, so it constrains the X motion only.
Across the sweep plane the probe slides along the object's surface (friction neglected), so in Z
it is a cantilever held only by the stopped servo. What drives Z is the tilt servo: the search
path is an ellipse (the paper's Fig. 7), so at the contact the probe also turns across the sweep
plane, at ``tilt_ratio * Omega``; the servos' stop arrests that rotation at the hinge. Z thus rings
at the free probe's frequencies, the same for every contact and material.

**In the simulator.** The module reads in the order the simulator uses it: the modes after the
arrest (:func:`arrest_modes`, :func:`coupled_arrest_modes`), laid out per signal
(:class:`ModalTerms`, :func:`x_terms`, :func:`z_terms`; a scene's free probe's,
:func:`free_probe_terms`), then their sum (:func:`modal_acceleration`): the exponentials, through
the chip's filter read as its design (:func:`filtered_exponentials`), summed
(:func:`damped_exponentials`). Two of the simulator's steps are at the end (``CHAIN_STEPS``): the
free probe's, before the touched object's, lays out Z's modes (the same for every contact and
material); the responses' sums every axis read from its modes and runs the models stepped in time
for the others.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.signal as sps

from .._validate import (
    check_array,
    check_choice,
    check_in_range,
    check_int,
    check_positive,
    real_array,
)
from ..fem import Supports, modal_analysis
from ..fem.assembly import assemble
from ..fem.coupling import coupled_modes
from ..probe import Probe
from .structure import check_case

__all__ = [
    "ArrestModes",
    "ModalTerms",
    "x_terms",
    "z_terms",
    "free_probe_terms",
    "arrest_modes",
    "coupled_arrest_modes",
    "coupled_modes_of",
    "modal_exponentials",
    "filtered_exponentials",
    "damped_exponentials",
    "direct_exponentials",
    "EXPONENTIAL_ENGINES",
    "modal_acceleration",
    "sweep_velocity",
]

#: Modes below this frequency (Hz) are rigid-body motions (a pinned hinge without contact): a
#: rotation at constant rate gives no transverse acceleration in the linear theory.
RIGID_BODY_HZ = 1e-6


@dataclass(frozen=True, eq=False)
class ArrestModes:
    """The modes that ring after the arrest, per unit sweep speed.

    Attributes
    ----------
    omega : ndarray of shape (n,)
        Undamped natural circular frequencies with the contact (pin or spring), rad/s.
    tip : ndarray of shape (n,)
        Tip deflection of each mass-normalised mode, 1/sqrt(kg).
    velocity : ndarray of shape (n,)
        Initial modal velocity per unit sweep speed, ``Phi^T M u0 / Omega``, sqrt(kg) m.
    contact_force : ndarray of shape (n,) or None
        Force in the contact in each mass-normalised mode per unit modal coordinate,
        N/(sqrt(kg) m): for a rigid pin its reaction ``[(K - omega^2 M) phi_k]`` at the contact
        DOF, for a spring ``k`` times the contact's deflection; None without contact.
    contact_stiffness : float
        Stiffness of the contact used, N/m (``inf``: rigid pin).
    damping_ratio : ndarray of shape (n,) or None
        Each mode's damping ratio where the model gives it (the probe coupled to a damped
        object, :func:`coupled_arrest_modes`); None where the scene's effects set it.
    """

    omega: np.ndarray
    tip: np.ndarray
    velocity: np.ndarray
    contact_force: np.ndarray | None
    contact_stiffness: float = math.inf
    damping_ratio: np.ndarray | None = None

    def strain_energy_share(self) -> np.ndarray:
        """Share of each mode's strain energy stored in the contact spring (0 for a rigid pin)."""
        if self.contact_force is None or math.isinf(self.contact_stiffness):
            return np.zeros_like(self.omega)
        return self.contact_force**2 / (self.contact_stiffness * self.omega**2)

    @property
    def frequencies(self) -> np.ndarray:
        """Natural frequencies, Hz."""
        return self.omega / (2 * math.pi)


def sweep_velocity(nodes: np.ndarray) -> np.ndarray:
    """DOF velocities of the probe swinging rigidly about the hinge, per unit sweep speed.

    A rigid rotation ``Omega`` about the hinge moves the node at ``x`` sideways at ``Omega x``
    and turns its section at ``Omega``; the beam's DOFs at each node are ``(v, theta)``.

    Parameters
    ----------
    nodes : ndarray of shape (n_nodes,)
        Node positions from the hinge, m.

    Returns
    -------
    ndarray of shape (2 n_nodes,)
        ``(v, theta)`` of every node per rad/s: m/s and rad/s.

    Examples
    --------
    >>> sweep_velocity(np.array([0.0, 0.1, 0.2]))
    array([0. , 1. , 0.1, 1. , 0.2, 1. ])
    """
    # (v, theta) = (Omega x, Omega) at every node, per unit Omega, node after node
    return np.stack(np.broadcast_arrays(check_array("nodes", nodes, ndim=1), 1.0), axis=-1).ravel()


def arrest_modes(
    probe: Probe,
    hinge,
    contact: float | None,
    *,
    n_elements: int,
    n_modes: int,
    max_frequency: float,
    contact_stiffness: float = math.inf,
) -> ArrestModes:
    """Modes below ``max_frequency`` of the arrested probe, with their excitation.

    Parameters
    ----------
    probe : Probe
        The probe (with its tip mass, if any).
    hinge : {"clamped", "pinned"} or float
        The hinge, as in :class:`ebantenna.fem.Supports`.
    contact : float or None
        Contact position from the hinge, m; None for the probe touching nothing (the Z axis).
    n_elements, n_modes : int
        FEM mesh size and number of modes computed.
    max_frequency : float
        Highest frequency simulated, Hz; modes at or above it are dropped.
    contact_stiffness : float
        Stiffness of the contact, N/m; ``inf`` (default) for a rigid pin. A rigid pin takes the
        velocity of the contact point away at the arrest; a spring stops it gradually, so the
        contact point keeps its velocity in the initial condition and the spring starts relaxed.

    Raises
    ------
    ValueError
        When the ``n_modes`` computed modes do not reach ``max_frequency`` (so some mode below it
        could be missing), unless they are all the modes of the FEM model.

    Examples
    --------
    >>> from ebantenna.probe import Probe
    >>> m = arrest_modes(Probe(), "clamped", 0.2, n_elements=40, n_modes=6, max_frequency=480.0)
    >>> m.frequencies.round(1)
    array([ 39. , 243.5, 350.7])
    """
    supports = Supports(contact=contact, hinge=hinge, contact_stiffness=contact_stiffness)
    # A coarse mesh may have fewer DOFs than n_modes: then take them all.
    n_free = 2 * (n_elements + 1) - 1 - (supports.hinge == "clamped") - supports.rigid_contact
    res = modal_analysis(probe, supports, n_elements=n_elements, n_modes=min(n_modes, n_free))
    freqs = res.frequencies
    if not freqs[-1] >= max_frequency and res.n_modes < res.free.size:
        raise ValueError(
            f"n_modes={n_modes} modes reach only {freqs[-1]:.1f} Hz, below max_frequency="
            f"{max_frequency:g} Hz; raise n_modes"
        )
    velocity = res.modal_coordinates(sweep_velocity(res.nodes))
    tip = res.shapes[-2]  # the tip is the mesh's last node: its deflection DOF
    keep = (freqs < max_frequency) & (freqs > RIGID_BODY_HZ)
    force = None
    if contact is not None:
        c = 2 * int(np.argmin(np.abs(res.nodes - contact)))
        if math.isinf(contact_stiffness):
            K, _ = assemble(res.nodes, probe)
            M_row = np.asarray(res.mass_matrix[c : c + 1] @ res.shapes).ravel()
            force = (K[c] @ res.shapes - res.omega**2 * M_row)[keep]
        else:
            force = contact_stiffness * res.shapes[c, keep]
    return ArrestModes(
        res.omega[keep], tip[keep], velocity[keep], force, float(supports.contact_stiffness)
    )


def _check_coupled_arrest(probe, probe_reduction, rod_reduction, max_frequency) -> float:
    """``max_frequency`` checked, once ``probe`` is a Probe and each reduction keeps its
    fixed-interface modes up to it (:func:`coupled_arrest_modes`)."""
    if not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
    max_frequency = check_positive("max_frequency", max_frequency)
    for label, red in (("probe_modes", probe_reduction), ("rod_modes", rod_reduction)):
        top = red.fixed_interface_omega[-1] / (2 * math.pi) if red.fixed_interface_omega.size else 0
        if not top >= max_frequency:
            raise ValueError(
                f"the {label.split('_')[0]}'s reduction keeps modes up to {top:.0f} Hz only, "
                f"below max_frequency={max_frequency:g} Hz; raise {label}"
            )
    return max_frequency


def coupled_arrest_modes(
    probe: Probe,
    hinge,
    contact: float,
    rod,
    *,
    probe_reduction,
    rod_reduction,
    contact_stiffness: float,
    contact_loss_factor: float,
    max_frequency: float,
) -> ArrestModes:
    """Modes below ``max_frequency`` of the probe arrested on a vibrating rod, and their excitation.

    The probe and the rod are joined by the contact spring
    (:func:`ebantenna.fem.coupling.coupled_modes`,
    from reductions made once per contact position and per rod). At the arrest
    the probe moves as in :func:`arrest_modes` (the hinge stopped, every other point keeping the
    sweep's velocity), the rod is at rest and the spring relaxed; the initial modal velocities are
    ``Phi^T M u0`` over the probe's DOFs (the rod's initial velocity is zero).

    Parameters
    ----------
    probe : Probe
        The probe, with the loss factor its modes should carry (0 for an undamped probe).
    hinge : {"clamped", "pinned"} or float
        The probe's hinge.
    contact : float
        Contact position from the hinge, m.
    rod : ebantenna.fem.coupling.Rod
        The touched rod.
    probe_reduction, rod_reduction : ebantenna.fem.coupling.CraigBampton
        The probe reduced at this contact, and the rod (with the loss factor it should carry).
    contact_stiffness, contact_loss_factor : float
        The contact spring, N/m, and its loss factor.
    max_frequency : float
        Highest frequency kept, Hz; each reduction must keep fixed-interface modes up to it.

    Examples
    --------
    >>> from ebantenna.probe import Probe
    >>> from ebantenna.fem.coupling import Rod, craig_bampton, probe_substructure, rod_substructure
    >>> p = craig_bampton(probe_substructure(Probe(), 0.2, n_elements=40), 16)
    >>> r = craig_bampton(rod_substructure(Rod("steel"), n_elements=16), 8)
    >>> m = coupled_arrest_modes(Probe(), "clamped", 0.2, Rod("steel"), probe_reduction=p,
    ...                          rod_reduction=r,
    ...                          contact_stiffness=1.8e5, contact_loss_factor=0.0,
    ...                          max_frequency=480.0)
    >>> m.frequencies.round(1)
    array([ 38.4, 133.9, 243.5, 347.6])
    """
    max_frequency = _check_coupled_arrest(probe, probe_reduction, rod_reduction, max_frequency)
    # Interlacing: joining the two fixed-interface systems through the two interface coordinates
    # adds at most two eigenvalues below any frequency, so this many coupled modes reach it.
    limit = 2 * math.pi * max_frequency
    n_modes = min(
        probe_reduction.stiffness.shape[0] + rod_reduction.stiffness.shape[0],
        int(np.sum(probe_reduction.fixed_interface_omega < limit))
        + int(np.sum(rod_reduction.fixed_interface_omega < limit))
        + 2,
    )
    # As in arrest_modes, the hinge takes the velocity of the DOFs it fixes: the modal velocities
    # are Phi^T M u0 over the probe's free DOFs only (its mass matrix there holds the tip mass).
    sub = probe_reduction.substructure
    momentum = sub.mass @ sweep_velocity(sub.nodes)[sub.free]
    res = coupled_modes(
        probe,
        rod,
        contact,
        contact_stiffness,
        hinge=hinge,
        n_modes=n_modes,
        contact_loss_factor=contact_loss_factor,
        rod_reduction=rod_reduction,
        probe_reduction=probe_reduction,
        damping="perturbation",
    )
    velocity = res.probe_shapes[sub.free].T @ momentum
    nodes = res.probe_nodes
    freqs = res.frequencies
    keep = (freqs < max_frequency) & (freqs > RIGID_BODY_HZ)
    ic = 2 * int(np.argmin(np.abs(nodes - contact)))
    ih = 2 * int(np.argmin(np.abs(res.rod_nodes - rod.contact_height)))
    force = contact_stiffness * (res.probe_shapes[ic] - res.rod_shapes[ih])
    return ArrestModes(
        res.omega[keep],
        res.tip_displacement[keep],
        velocity[keep],
        force[keep],
        float(contact_stiffness),
        res.damping_ratio[keep],
    )


def coupled_modes_of(case) -> ArrestModes:
    """The ``coupled`` model of a contact case: :func:`coupled_arrest_modes` of its probe and rod
    joined by its contact spring, from its reductions.

    Parameters
    ----------
    case : ebantenna.simulate.structure.ContactCase
        The contact case (its scene gives the hinge and ``max_frequency``).
    """
    check_case(case)
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


# ------------------------------------------------------------- the terms of each signal
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

    def _check_row(self, row) -> None:
        """``row`` is a signal's index, an integer ``0 <= row < n_signals`` (no negative
        indexing)."""
        check_int("row", row, minimum=0, maximum=self.omega.shape[0] - 1)

    def frequencies(self, row: int = 0) -> np.ndarray:
        """Natural frequencies of signal ``row`` (padding dropped), Hz."""
        self._check_row(row)
        return self.omega[row, self.live[row]] / (2 * math.pi)

    def damping_ratios(self, row: int = 0) -> np.ndarray:
        """Damping ratios of signal ``row`` (padding dropped)."""
        self._check_row(row)
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
        t = check_array("t", t, ndim=1)
        # q_k(t) = q_dot_k(0) / omega_dk e^(-a_k t) sin(omega_dk t), on the modes' own rates
        _, rate = modal_exponentials(self.contact_force, self.omega, self.zeta)
        coef = (self.contact_force / rate.imag).astype(complex)
        return damped_exponentials(t, coef, rate)

    def lift_off_ratio(self, duration: float = 1.0, rate: float = 8000.0) -> np.ndarray:
        """Largest pull of the linear contact over its preload, per strike (dimensionless).

        ``max_t (-F_dyn(t)) / F0`` over ``duration`` seconds sampled at ``rate`` Hz: above 1 the
        linear (bilateral) model holds the probe to the object by a pull that a real contact
        cannot give; the probe would lift off and strike again.
        """
        if self.preload is None:
            raise ValueError("these modal terms have no preload (listed without object_modes)")
        duration = check_positive("duration", duration)
        rate = check_positive("rate", rate)
        t = np.arange(int(round(duration * rate))) / rate
        return np.max(-self.dynamic_contact_force(t), axis=1) / self.preload


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


def x_terms(modes, rows, speeds, *, zeta=None, preloads=None) -> ModalTerms:
    """X's modal parameters per signal: ``modes[rows[i]]`` scaled by signal ``i``'s speed.

    The distinct modes are laid side by side, zero-padded to a common width (:class:`ModalTerms`).

    Parameters
    ----------
    modes : list of ArrestModes
        The distinct modes of X; empty when none were asked for (each signal then has none).
    rows : array of int, shape (n,)
        Which of them each signal uses.
    speeds : array of shape (n,)
        Each signal's sweep speed, rad/s.
    zeta : float or None
        One damping ratio for every mode (the probe's structural damping, on a rigid object);
        None: each mode's own (the coupled model carries every body's damping).
    preloads : array of shape (n,) or None
        Each strike's preload, N (with the ``object_modes`` effect).

    Examples
    --------
    >>> m = ArrestModes(np.array([100.0]), np.array([2.0]), np.array([0.5]), None)
    >>> x_terms([m], np.array([0, 0]), np.array([1.0, 3.0]), zeta=0.01).amplitude
    array([[1.],
           [3.]])
    """
    speeds = check_array("speeds", speeds, ndim=1)
    n = speeds.size
    if not isinstance(modes, list | tuple) or not all(isinstance(m, ArrestModes) for m in modes):
        raise TypeError("modes must be a list of ArrestModes")
    rows = np.asarray(rows)
    if rows.shape != (n,) or rows.dtype.kind not in "iu" or (
            n and modes and not 0 <= rows.min() <= rows.max() < len(modes)):
        raise ValueError(f"rows must hold one index into modes per speed ({n}), got {rows!r}")
    if zeta is not None:
        zeta = check_in_range("zeta", zeta, 0.0, 1.0, low_inclusive=True)
    if preloads is not None and check_array("preloads", preloads, ndim=1).shape != (n,):
        raise ValueError(f"preloads must hold one preload per speed ({n}), got shape "
                         f"{np.shape(preloads)}")
    if not modes:  # X's modes not asked for (x_modes=False): none, for every signal
        rows, modes = np.zeros(n, dtype=int), [ArrestModes(*[np.empty(0)] * 3, None)]
    omega_u, zeta_u, amp_u, force_u, live_u = _padded(modes)
    amplitude = amp_u[rows] * speeds[:, None]
    if zeta is None:  # the coupled model carries every body's damping
        zeta = zeta_u[rows]
    else:
        zeta = np.full((n, omega_u.shape[1]), zeta)
    if np.any(zeta >= 1):
        raise ValueError(f"a mode is overdamped (zeta up to {zeta.max():.3g}); not supported")
    spring = any(math.isfinite(m.contact_stiffness) for m in modes)
    force = force_u[rows] * speeds[:, None] if spring else None
    return ModalTerms(omega_u[rows], zeta, amplitude, live_u[rows], force, preloads)


def z_terms(probe: Probe, hinge, speeds, tilts, zeta: float, *, n_elements: int, n_modes: int,
            max_frequency: float) -> ModalTerms:
    """Z's modal parameters per signal: the free probe (:func:`arrest_modes` with no contact),
    driven across the sweep plane at ``tilts * speeds``.

    Parameters
    ----------
    probe, hinge, n_elements, n_modes, max_frequency
        As in :func:`arrest_modes`.
    speeds, tilts : arrays of shape (n,)
        Each signal's sweep speed (rad/s) and tilt ratio.
    zeta : float
        The damping ratio of every mode (the probe's structural damping).

    Examples
    --------
    >>> from ebantenna.probe import Probe
    >>> z = z_terms(Probe(), "clamped", np.array([1.0]), np.array([0.5]), 0.0, n_elements=40,
    ...             n_modes=6, max_frequency=480.0)
    >>> z.frequencies().round(1)
    array([ 13.9,  87. , 243.6, 477.4])
    """
    speeds = check_array("speeds", speeds, ndim=1)
    if check_array("tilts", tilts, ndim=1).shape != speeds.shape:
        raise ValueError(f"tilts must hold one tilt ratio per speed ({speeds.size}), got shape "
                         f"{np.shape(tilts)}")
    zeta = check_in_range("zeta", zeta, 0.0, 1.0, low_inclusive=True)
    kw = dict(n_elements=n_elements, n_modes=n_modes, max_frequency=max_frequency)
    z_modes = arrest_modes(probe, hinge, None, **kw)
    z_amp = (z_modes.tip * z_modes.velocity)[None, :] * (tilts * speeds)[:, None]
    return ModalTerms(
        np.broadcast_to(z_modes.omega, z_amp.shape).copy(),
        np.full(z_amp.shape, zeta),
        z_amp,
        np.ones(z_amp.shape, dtype=bool),
    )


def free_probe_terms(scene, speeds, tilts) -> ModalTerms:
    """Z's modal parameters per signal of a scene's free probe: :func:`z_terms` with the scene's
    probe, hinge, mesh and band, every mode damped by the probe's structural damping
    (:attr:`~ebantenna.simulate.Scene.probe_damping_ratio`). The simulator's free-probe step
    reads Z here, and so does :func:`~ebantenna.simulate.touched_object.signal_terms`.

    Parameters
    ----------
    scene : ebantenna.simulate.Scene
    speeds, tilts : arrays of shape (n,)
        As in :func:`z_terms`.

    Examples
    --------
    >>> from ebantenna.simulate import builtin_scene
    >>> z = free_probe_terms(builtin_scene("ideal"), np.array([1.0]), np.array([0.5]))
    >>> z.frequencies().round(1)
    array([ 13.9,  87. , 243.6, 477.4])
    """
    # known by the Probe it holds: scene.py imports this module (through its effects), so this
    # module cannot import Scene without a circle
    if not isinstance(getattr(scene, "probe", None), Probe):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    return z_terms(scene.probe, scene.hinge, speeds, tilts, scene.probe_damping_ratio,
                   n_elements=scene.n_elements, n_modes=scene.n_modes,
                   max_frequency=scene.max_frequency)


def modal_exponentials(amplitude, omega, zeta):
    """The modes' tip acceleration as complex exponentials: ``C_k`` and ``s_k`` (module docstring).

    Parameters
    ----------
    amplitude, omega, zeta : arrays of shape (n_signals, n_modes)
        As in :func:`modal_acceleration`.

    Returns
    -------
    coef, rate : complex ndarrays of shape (n_signals, n_modes)
        ``C_k`` (m/s^2) and ``s_k`` (1/s): the acceleration is ``Im(sum_k C_k exp(s_k t))``.
    """
    amplitude = np.asarray(amplitude, dtype=float)
    omega = np.asarray(omega, dtype=float)
    zeta = np.asarray(zeta, dtype=float)
    if np.any(zeta < 0) or np.any(zeta >= 1):
        raise ValueError("zeta, the damping ratios, must lie in [0, 1) (underdamped modes)")
    a = zeta * omega
    wd = omega * np.sqrt(1 - zeta**2)
    return amplitude * ((a * a - wd * wd) / wd - 2j * a), -a + 1j * wd


def filtered_exponentials(coef, rate, sos, internal_rate: float):
    """A digital filter's output for an input ``Im(sum_k coef_k exp(rate_k t))`` sampled from t = 0.

    The filter is given by its design, as values: its second-order sections ``sos`` and the
    rate it runs at (for the chip's low-pass filter, the ``sos`` and ``internal_rate`` of
    :class:`~ebantenna.simulate.effects.LowPassFilter`). Input sample ``n`` is
    ``u_n = Im(sum_k C_k z_k^n)`` with ``z_k = exp(rate_k / f_i)`` and ``f_i`` the internal
    rate; the filter ``H(z) = B(1/z) / A(1/z)``, with ``B`` and ``A`` polynomials in
    ``w = z^-1`` (the difference equation's coefficients), starts at rest. For one exponential
    the output's z-transform ``B(w) / (A(w) (1 - z_k w))`` splits into partial fractions over
    the input's pole and the filter's poles ``p_j``:

        y_n = Im( sum_k C_k [ H(z_k) z_k^n + sum_j R_jk p_j^n ] ),
        R_jk = B(1/p_j) / ( (1 - z_k / p_j) prod_(i != j) (1 - p_i / p_j) ),

    a sum of damped exponentials again: the input's, scaled by the filter's gain, and the
    filter's own transient at its poles (rates ``f_i log p_j``). Evaluated at ``t = n / f_i``
    it is the filter's output exactly; at every ``divider``-th sample, the decimated one. The
    poles must be distinct (a Butterworth pair is).

    Parameters
    ----------
    coef, rate : complex arrays of shape (n_signals, n_terms)
        ``C_k`` and ``rate_k`` (1/s) of each signal's exponentials.
    sos : ndarray of shape (n_sections, 6)
        The filter's second-order sections at ``internal_rate``.
    internal_rate : float
        The rate the filter runs at, Hz.

    Returns
    -------
    coef, rate : complex arrays of shape (n_signals, n_terms + 2 n_sections)
        The output's exponentials, the filter's transient terms last, one per pole (two per
        section of second order, as the chip's filter has).

    Examples
    --------
    >>> import numpy as np
    >>> import scipy.signal as sps
    >>> sos = sps.butter(2, 260.0, fs=8000.0, output="sos")
    >>> coef, rate = filtered_exponentials(np.array([[1.0 + 0j]]), np.array([[-5.0 + 100j]]),
    ...                                    sos, 8000.0)
    >>> coef.shape, bool(np.all(rate[0, 1:].real < 0))  # the input's term, two filter transients
    ((1, 3), True)
    """
    coef, rate = np.asarray(coef), np.asarray(rate)
    for name, value in (("coef", coef), ("rate", rate)):
        if value.ndim != 2 or value.dtype.kind not in "fc" or not np.all(np.isfinite(value)):
            raise ValueError(f"{name} must be a finite real or complex array of shape "
                             f"(n_signals, n_terms), got {value.dtype} of shape {value.shape}")
    if rate.shape != coef.shape:
        raise ValueError(f"rate must have the shape of coef {coef.shape}, got {rate.shape}")
    sos = np.asarray(sos)
    if sos.ndim != 2 or sos.shape[1] != 6 or sos.dtype.kind not in "fi" \
            or not np.all(np.isfinite(sos)):
        raise ValueError(f"sos must be a finite real array of second-order sections, shape "
                         f"(n_sections, 6), got {sos.dtype} of shape {sos.shape}")
    fi = check_positive("internal_rate", internal_rate)
    b, a = sps.sos2tf(sos)
    poles = np.roots(a)
    z = np.exp(np.asarray(rate) / fi)
    gain = np.polyval(b[::-1], 1 / z) / np.polyval(a[::-1], 1 / z)  # H(z_k) = B(1/z) / A(1/z)
    out_coef = [coef * gain]
    for j, p in enumerate(poles):
        others = np.prod([1 - q / p for i, q in enumerate(poles) if i != j])
        residue = np.polyval(b[::-1], 1 / p) / ((1 - z / p) * others)
        out_coef.append(np.sum(coef * residue, axis=-1, keepdims=True))
    n = coef.shape[0]
    pole_rates = np.broadcast_to(fi * np.log(poles.astype(complex)), (n, poles.size))
    return np.concatenate(out_coef, axis=-1), np.concatenate([rate, pole_rates], axis=-1)


def direct_exponentials(t: np.ndarray, coef, rate, max_elements: int) -> np.ndarray:
    """The reference of :func:`damped_exponentials`: the sum as it reads, one complex
    exponential per term and sample, summed over the terms, in blocks of signals of at most
    ``max_elements`` complex numbers. Takes checked values (``t`` a float array).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(4) / 4.0
    >>> direct_exponentials(t, np.array([[1.0 + 0j]]), np.array([[2j * np.pi]]), 100).round(12)
    array([[ 0.,  1.,  0., -1.]])
    """
    for name, value in (("t", t), ("coef", coef), ("rate", rate)):
        if not isinstance(value, np.ndarray) or value.dtype.kind not in "fc":
            raise TypeError(f"{name} must be a float or complex ndarray, got "
                            f"{type(value).__name__} {getattr(value, 'dtype', '')}")
    if coef.ndim != 2 or rate.shape != coef.shape:
        raise ValueError(f"coef and rate must be 2-D arrays of one shape (signals, terms), got "
                         f"{coef.shape} and {rate.shape}")
    if t.ndim not in (1, 2) or (t.ndim == 2 and t.shape[0] != coef.shape[0]):
        raise ValueError(f"t must be 1-D, or 2-D with one row per signal ({coef.shape[0]}), got "
                         f"shape {t.shape}")
    check_int("max_elements", max_elements, minimum=1)
    n_signals, n_terms = coef.shape
    n_samples = t.shape[-1]
    out = np.empty((n_signals, n_samples))
    block = max(1, max_elements // max(1, n_terms * n_samples))
    for start in range(0, n_signals, block):
        rows = slice(start, start + block)
        tt = t[rows][:, None, :] if t.ndim == 2 else t[None, None, :]
        out[rows] = np.einsum("sk,skn->sn", coef[rows], np.exp(rate[rows, :, None] * tt)).imag
    return out


#: The evaluations of :func:`damped_exponentials` by name: ``"direct"`` (the reference,
#: :func:`direct_exponentials`) and ``"grid"`` (the engine, the default), which the private
#: module ``simulate/_exponential_grid.py`` adds when the package is imported.
EXPONENTIAL_ENGINES = {"direct": direct_exponentials}


def damped_exponentials(
    t, coef, rate, *, max_elements: int = 500_000, engine: str = "grid"
) -> np.ndarray:
    """``Im(sum_k coef_k exp(rate_k t))`` for many signals at once.

    The reference (``engine="direct"``, :func:`direct_exponentials`) evaluates the sum as it
    reads: one complex exponential per term and sample, summed over the terms. The engine
    ``"grid"``, the default, takes most
    of the exponentials of a uniform time grid longer than 64 samples as products instead (a
    private module; with ``t_n = t_0 + n dt`` and ``n = a B + b``, ``exp(r t_n) = exp(r (t_0 +
    a B dt)) exp(r b dt)``), and evaluates any other ``t`` as the reference does; times given
    per signal (a jittered clock) go to the reference here, whatever ``engine`` says. The two agree
    to a few ulps of ``|rate| t_max sum_k |coef_k|``: both round the arguments ``rate t``.

    Parameters
    ----------
    t : array of shape (n_samples,) or (n_signals, n_samples)
        Times, s (one row per signal when the sampling is jittered).
    coef, rate : complex arrays of shape (n_signals, n_terms)
        Amplitudes and rates (1/s) of each signal's exponentials.
    max_elements : int
        Work in blocks of signals so that no temporary exceeds this many complex numbers.
    engine : {"grid", "direct"}
        How the sum is evaluated (above).

    Returns
    -------
    ndarray of shape (n_signals, n_samples)

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(4) / 4.0
    >>> damped_exponentials(t, np.array([[1.0 + 0j]]), np.array([[2j * np.pi]])).round(12)
    array([[ 0.,  1.,  0., -1.]])
    """
    check_choice("engine", engine, tuple(EXPONENTIAL_ENGINES))
    t = real_array("t", t)
    if t.ndim == 2:  # each signal its own times (a jittered clock): no grid an engine could share
        return direct_exponentials(t, coef, rate, max_elements)
    return EXPONENTIAL_ENGINES[engine](t, coef, rate, max_elements)


def modal_acceleration(
    t, amplitude, omega, zeta, *, max_elements: int = 500_000, low_pass=None
) -> np.ndarray:
    """Sum of damped modal accelerations ``sum_k Im(C_k e^(s_k t))`` for many signals at once.

    The exponentials (:func:`modal_exponentials`) are summed by :func:`damped_exponentials`;
    with ``low_pass`` they first pass through the chip's filter, read as its design (its
    ``sos`` and ``internal_rate``; :func:`filtered_exponentials`: the filter's output, exactly,
    at its internal rate, then read at ``t``).

    Parameters
    ----------
    t : array of shape (n_samples,) or (n_signals, n_samples)
        Times since the arrest, s (one row per signal when the sampling is jittered).
    amplitude : array of shape (n_signals, n_modes)
        ``phi_k(L) * q_dot_k(0)``: the tip velocity each mode starts with, m/s.
    omega : array of shape (n_signals, n_modes)
        Undamped natural circular frequencies, rad/s (> 0).
    zeta : array of shape (n_signals, n_modes)
        Damping ratios, in ``[0, 1)``.
    max_elements : int
        Work in blocks of signals so that no temporary exceeds this many complex numbers.
    low_pass : ebantenna.simulate.effects.LowPassFilter or None
        The chip's low-pass filter (the scene's ``dlpf``) the acceleration is read through;
        None: the acceleration itself.

    Returns
    -------
    ndarray of shape (n_signals, n_samples)
        Tip acceleration, m/s^2 (as read through ``low_pass``, if given).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.array([0.0, 0.25])
    >>> modal_acceleration(t, np.array([[1.0]]), np.array([[2 * np.pi]]), np.zeros((1, 1))).round(6)
    array([[ 0.      , -6.283185]])
    """
    if low_pass is not None and not isinstance(getattr(low_pass, "sos", None), np.ndarray):
        raise TypeError(f"low_pass must be a LowPassFilter (the scene's dlpf) or None, got "
                        f"{type(low_pass).__name__}")
    coef, rate = modal_exponentials(amplitude, omega, zeta)
    if low_pass is not None:  # the chip's filter at its internal rate, then its decimation
        coef, rate = filtered_exponentials(coef, rate, low_pass.sos, low_pass.internal_rate)
    return damped_exponentials(t, coef, rate, max_elements=max_elements)


# ------------------------------------------------------------- the simulator's steps
def _free_probe(_, batch) -> None:
    """The free probe: Z's modal parameters (:func:`free_probe_terms`). Across the sweep plane
    the probe swings free, touching nothing, whatever the object; its modes carry the probe's
    structural damping (:attr:`~ebantenna.simulate.Scene.probe_damping_ratio`)."""
    batch.z = free_probe_terms(batch.scene, batch.speeds, batch.tilts)


def _respond(_, batch) -> None:
    """The responses: X and Z after the arrest. Each axis read from its modes is their sum at
    the sample instants, through the chip's filter if listed (:func:`modal_acceleration`); then
    each axis a model stepped in time gives (``batch.responders``, set by the touched object's
    step) is computed at that model's rate, for the chip to read (the sensor's next step)."""
    for axis, terms in (("x", batch.x), ("z", batch.z)):
        if axis not in batch.responders:  # the batch's field ax or az
            setattr(batch, "a" + axis, modal_acceleration(
                batch.when, terms.amplitude, terms.omega, terms.zeta, low_pass=batch.chip_filter))
    for axis, (respond, models) in batch.responders.items():
        batch.timed_acc[axis] = respond(batch, models)


#: The simulator's steps written beside the modes they read, the free probe's and the
#: responses': each takes ``(effect, batch)`` and changes the simulator's
#: :class:`~ebantenna.simulate.simulator.SignalBatch` in place, with values the simulator
#: checked. :data:`ebantenna.simulate.simulator.CHAIN` puts them in order, and says why.
CHAIN_STEPS = {"free_probe": _free_probe, "responses": _respond}
