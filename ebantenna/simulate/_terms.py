"""Modal parameters per signal, :class:`ModalTerms`, from the touched object's models.

The simulator's private helper: the distinct modes of :mod:`ebantenna.simulate.touched_object`
side by side, zero-padded, and each signal's row scaled by its sweep speed. Takes checked values.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from threadpoolctl import threadpool_limits

from .._validate import check_int, check_positive
from .modes import ArrestModes, arrest_modes, damped_exponentials, modal_exponentials
from .scene import Scene
from .touched_object import object_modes, pinned_modes

__all__ = ["ModalTerms", "signal_terms"]


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

    def _row(self, row) -> int:
        """``row`` checked: a signal's index, ``0 <= row < n_signals`` (no negative indexing)."""
        return check_int("row", row, minimum=0, maximum=self.omega.shape[0] - 1)

    def frequencies(self, row: int = 0) -> np.ndarray:
        """Natural frequencies of signal ``row`` (padding dropped), Hz."""
        row = self._row(row)
        return self.omega[row, self.live[row]] / (2 * math.pi)

    def damping_ratios(self, row: int = 0) -> np.ndarray:
        """Damping ratios of signal ``row`` (padding dropped)."""
        row = self._row(row)
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


def signal_terms(
    scene: Scene, contacts, materials, speeds, tilts, preloads=None, show_progress=None,
    x_modes=True,
):  # fmt: skip
    """ModalTerms of X and Z per signal, the models stepped in time (``timed``, see
    :func:`~ebantenna.simulate.touched_object.object_modes`) and which model each signal uses.

    Takes checked values.

    The touched object is a rod coupled to the probe with ``object_modes`` and rigid without.
    """
    n = contacts.size
    # Many small eigenproblems: BLAS threads only add overhead (and thrash on a busy machine).
    with threadpool_limits(limits=1):
        if scene.has("object_modes"):
            if preloads is None:
                preloads = np.full(n, scene.effect("object_modes").preload)
            modes, inverse, timed = object_modes(
                scene, contacts, materials, preloads, show_progress, x_modes
            )
        else:
            (modes, inverse), timed = pinned_modes(scene, contacts, materials, show_progress), {}
    damping = scene.effect("structural_damping")
    zeta_s = damping.damping_ratio(scene.probe) if damping is not None else 0.0
    x = _x_terms(scene, modes, inverse, speeds, preloads, zeta_s)
    return x, _z_terms(scene, speeds, tilts, zeta_s), timed, inverse
