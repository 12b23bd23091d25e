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
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..fem import Supports, modal_analysis
from ..fem.assembly import assemble
from ..probe import Probe

__all__ = ["ArrestModes", "arrest_modes", "modal_acceleration"]

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
    """

    omega: np.ndarray
    tip: np.ndarray
    velocity: np.ndarray
    contact_force: np.ndarray | None
    contact_stiffness: float = math.inf

    def strain_energy_share(self) -> np.ndarray:
        """Share of each mode's strain energy stored in the contact spring (0 for a rigid pin)."""
        if self.contact_force is None or math.isinf(self.contact_stiffness):
            return np.zeros_like(self.omega)
        return self.contact_force**2 / (self.contact_stiffness * self.omega**2)

    @property
    def frequencies(self) -> np.ndarray:
        """Natural frequencies, Hz."""
        return self.omega / (2 * math.pi)


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
    u0 = np.zeros(2 * res.nodes.size)
    u0[0::2] = res.nodes  # v = Omega x per unit Omega
    u0[1::2] = 1.0  # theta = Omega
    velocity = res.modal_coordinates(u0)
    tip = res.displacement(np.array([probe.length]))[0]
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


def modal_acceleration(t, amplitude, omega, zeta, *, max_elements: int = 500_000) -> np.ndarray:
    """Sum of damped modal accelerations ``sum_k Im(C_k e^(s_k t))`` for many signals at once.

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

    Returns
    -------
    ndarray of shape (n_signals, n_samples)
        Tip acceleration, m/s^2.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.array([0.0, 0.25])
    >>> modal_acceleration(t, np.array([[1.0]]), np.array([[2 * np.pi]]), np.zeros((1, 1))).round(6)
    array([[ 0.      , -6.283185]])
    """
    amplitude = np.asarray(amplitude, dtype=float)
    omega = np.asarray(omega, dtype=float)
    zeta = np.asarray(zeta, dtype=float)
    t = np.asarray(t, dtype=float)
    n_signals = amplitude.shape[0]
    n_samples = t.shape[-1]
    if np.any(zeta < 0) or np.any(zeta >= 1):
        raise ValueError("damping ratios must lie in [0, 1) (underdamped modes)")
    a = zeta * omega
    wd = omega * np.sqrt(1 - zeta**2)
    coef = amplitude * ((a * a - wd * wd) / wd - 2j * a)  # C_k
    rate = -a + 1j * wd  # s_k
    out = np.empty((n_signals, n_samples))
    block = max(1, max_elements // max(1, amplitude.shape[1] * n_samples))
    for start in range(0, n_signals, block):
        rows = slice(start, start + block)
        tt = t[rows] if t.ndim == 2 else t
        phase = rate[rows, :, None] * (tt[:, None, :] if t.ndim == 2 else tt[None, None, :])
        out[rows] = np.einsum("sk,skn->sn", coef[rows], np.exp(phase)).imag
    return out
