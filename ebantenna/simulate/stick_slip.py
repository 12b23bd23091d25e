"""Coulomb friction along the rod, propagated exactly between stick and slip (``coulomb_friction``).

Across the sweep plane the probe presses on the rod with the normal force ``N`` and moves along
it (the Z axis: the rod stands across the sweep plane). Dry friction (C. A. Coulomb's law, as in
J. P. Den Hartog, *Mechanical Vibrations*, 4th ed., McGraw-Hill, 1956, section 8.3) resists that
motion at the contact coordinate ``q_b`` (its speed ``u = q_b'``):

- **slip** (``u != 0``): the friction force is ``-mu_k N sign(u)``, a constant load: the structure
  is linear, ``M q'' + C q' + K q = -mu_k N sign(u) e_b``;
- **stick** (``u = 0``): the rod holds the contact point, ``q_b'' = 0``, the other coordinates move
  as the structure pinned there, and the friction force is what holding takes,
  ``F = (M q'' + C q' + K q)_b``, as long as ``|F| <= mu_s N``.

Each of the three states is a linear system with a constant load, so it is propagated by its
closed-form modal solution (:class:`.unilateral.LinearState`, as the contact states of
:mod:`.unilateral` are), read in blocks of steps, and its end found inside a step by a bracketed
Newton iteration (:func:`.unilateral.crossing`): slip ends where ``u`` reaches zero, stick where
``|F|`` reaches ``mu_s N``. At a slip's end the contact sticks if holding takes at most
``mu_s N``; otherwise, as at a stick's end, it slips the way the structure pulls.
:func:`.friction_ode.coulomb_response` integrates the same law with
:func:`scipy.integrate.solve_ivp` and is this module's witness in the test suite.

**In the scene** (:class:`~ebantenna.simulate.effects.CoulombFriction`): the probe's Z axis is its
Craig-Bampton reduction at the contact (the same basis as the strikes', :mod:`.strikes`), damped by
the tube's loss factor where ``structural_damping`` is listed; the tilt servo's stop leaves it
moving with the rigid rotation ``tilt_ratio x sweep_speed`` about the hinge, as without friction
(:mod:`.modes`), so the contact point starts sliding along the rod at ``tilt_ratio x sweep_speed
x contact``. **Assumption:** ``N`` is the contact's static preload: the normal force's swing
during the strike, and its lift-offs with ``unilateral_contact``, are not fed into the friction.
The rod is rigid along its axis: its first axial mode, ``sqrt(E / rho) / (4 L)`` on the default
rod, lies at 1.5 kHz for PVC and 3.5 to 5.1 kHz for the others, above what the sensor reads at
1 kHz, though not above the probe's modes the scene keeps (up to 3 kHz).
"""

from __future__ import annotations

import logging
import weakref
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from .._validate import check_choice, check_int, check_nonnegative, check_positive
from .modes import sweep_velocity
from .strikes import batch_rate, check_reduction, reduced_body
from .structure import check_case, check_dof_vector, check_symmetric_matrix
from .unilateral import (
    MARCHES,
    STEPS_PER_PERIOD,
    ChatterError,
    LinearState,
    SwitchedSystem,
    check_grid,
    check_state,
    check_step,
    check_structure,
    crossing,
    mass_inverse,
    step_grid,
)

__all__ = ["StickSlipResponse", "check_coefficients", "stick_slip_response", "StickSlipLaw",
           "friction_states", "FrictionModel", "friction_model", "friction_model_of",
           "friction_accelerations", "friction_axis"]  # fmt: skip

log = logging.getLogger(__name__)


@dataclass(frozen=True, eq=False)
class StickSlipResponse:
    """Time history of a structure with Coulomb friction at one coordinate.

    Attributes
    ----------
    t : ndarray of shape (n_samples,)
        Sample times, s.
    acceleration : ndarray of shape (n_samples,)
        Acceleration at the output, m/s^2.
    friction_force : ndarray of shape (n_samples,)
        Friction force on the structure along the contact coordinate, N.
    events : tuple of (float, str)
        ``(time in s, state entered)`` for the start and every change; states ``"stick"``,
        ``"slip+"`` (``u > 0``) and ``"slip-"``.
    """

    t: np.ndarray
    acceleration: np.ndarray
    friction_force: np.ndarray
    events: tuple


def check_coefficients(static_friction, kinetic_friction) -> tuple[float, float]:
    """``(mu_s, mu_k)`` as floats, checked: both >= 0 and ``mu_k <= mu_s``.

    Examples
    --------
    >>> check_coefficients(0.5, 0.4)
    (0.5, 0.4)
    """
    mus = check_nonnegative("static_friction", static_friction)
    muk = check_nonnegative("kinetic_friction", kinetic_friction)
    if muk > mus:
        raise ValueError(
            f"kinetic_friction must be <= static_friction ({mus!r}), got {kinetic_friction!r}"
        )
    return mus, muk


def stick_slip_response(
    mass,
    stiffness,
    contact: int,
    normal_force: float,
    *,
    static_friction: float,
    kinetic_friction: float,
    duration: float,
    fs: float,
    velocity=None,
    damping=None,
    output=None,
    max_events: int = 1000,
    time_tolerance: float = 1e-12,
    method: str = "blocks",
) -> StickSlipResponse:
    """Free motion, from ``q = 0``, of a linear structure with Coulomb friction at one coordinate.

    Parameters
    ----------
    mass, stiffness : array of shape (n, n)
        Symmetric mass (positive definite) and stiffness (positive semidefinite) matrices.
    contact : int
        Index of the coordinate along which friction acts (the contact point's displacement).
    normal_force : float
        ``N``, N (>= 0); 0 means no friction.
    static_friction, kinetic_friction : float
        ``mu_s >= mu_k >= 0`` (dimensionless).
    duration, fs : float
        Record length (s) and output sample rate (Hz).
    velocity : array of shape (n,), optional
        Initial ``q'``; zero by default.
    damping : array of shape (n, n), optional
        Viscous damping matrix.
    output : int or array of shape (n,), optional
        Where the acceleration is read; default the contact coordinate.
    max_events : int
        Most stick/slip changes (>= 1); more raise :class:`~.unilateral.ChatterError`.
    time_tolerance : float
        Each change is placed within this many seconds after the exact instant, s.
    method : {"blocks", "steps"}
        How the states are marched: ``"blocks"`` (the engine, fast) or ``"steps"`` (the
        reference, :func:`.unilateral.march_step_by_step`), as in
        :func:`.unilateral.unilateral_response`.

    Returns
    -------
    StickSlipResponse

    Examples
    --------
    A 1 kg, 100 N/m oscillator launched at 1 m/s against ``mu N = 1 N`` turns at 9.05 cm and
    loses ``2 mu N / k = 2 cm`` of amplitude every half period ``pi / 10 s``; from 1.05 cm the
    spring still overcomes ``mu_s N`` once, and at 0.95 cm (``0.02 m - 1.05 cm``) it no longer can:

    >>> r = stick_slip_response([[1.0]], [[100.0]], 0, 1.0, static_friction=1.0,
    ...                         kinetic_friction=1.0, duration=2.0, fs=100.0, velocity=[1.0])
    >>> [kind for _, kind in r.events]
    ['slip+', 'slip-', 'slip+', 'slip-', 'slip+', 'slip-', 'stick']
    >>> float(round(r.friction_force[-1], 6))  # holding the spring there: k x, N
    0.950124
    """
    M = check_symmetric_matrix("mass", mass)
    n = M.shape[0]
    K = check_symmetric_matrix("stiffness", stiffness, n)
    C = np.zeros((n, n)) if damping is None else check_symmetric_matrix("damping", damping, n)
    b = check_int("contact", contact, minimum=0)
    if b >= n:
        raise ValueError(f"contact must be a coordinate index below {n}, got {contact!r}")
    o = check_dof_vector("output", b if output is None else output, n)
    v0 = np.zeros(n) if velocity is None else check_dof_vector("velocity", velocity, n)
    N = check_nonnegative("normal_force", normal_force)
    mus, muk = check_coefficients(static_friction, kinetic_friction)
    T = check_positive("duration", duration)
    fs = check_positive("fs", fs)
    max_events = check_int("max_events", max_events, minimum=1)
    xtol = check_positive("time_tolerance", time_tolerance)
    check_choice("method", method, tuple(MARCHES))
    Minv = mass_inverse(M)

    states = friction_states(M, K, C, Minv, b, o, N * mus, N * muk)
    grid = step_grid(list(states.values()), fs, T, STEPS_PER_PERIOD)
    law = StickSlipLaw(states, b, grid, hold_limit=mus * N, max_events=max_events,
                       time_tolerance=xtol)  # fmt: skip
    x, name = law.start(v0)
    MARCHES[method](law, x, name, grid[3])
    log.debug("stick-slip: %d events, %d steps of %.3g s", len(law.events), grid[3], law.h)
    t_out = np.arange(grid[2]) / fs
    return StickSlipResponse(t_out, law.acc, law.force, tuple(law.events))


class StickSlipLaw(SwitchedSystem):
    """Coulomb's law at one coordinate: the three states and when each ends.

    Built by :func:`stick_slip_response` from checked values; marched by
    :data:`.unilateral.MARCHES`. The state keys are ``"slip+"``, ``"slip-"`` and ``"stick"``.

    Parameters
    ----------
    states : dict of LinearState
        The slips, and the stick twice (``"stick"`` watches ``mu_s N - F``, ``"stick lower"``
        ``mu_s N + F``), from :func:`friction_states`.
    contact : int
        The coordinate ``b`` along which friction acts.
    grid : tuple
        :func:`.unilateral.step_grid` of the states.
    hold_limit : float
        ``mu_s N``, N: the most friction can hold; 0 means no friction.
    max_events, time_tolerance
        As in :func:`stick_slip_response`.
    """

    def __init__(self, states, contact, grid, *, hold_limit, max_events, time_tolerance):
        h, sub, n_samples, _ = check_grid(grid)
        names = ("slip+", "slip-", "stick", "stick lower")
        if not isinstance(states, dict) or sorted(states) != sorted(names) or not all(
                isinstance(st, LinearState) for st in states.values()):
            raise TypeError(f"states must map {names} to LinearState, as friction_states "
                            "builds them")
        contact = check_int("contact", contact, minimum=0, maximum=states["stick"].n - 1)
        hold_limit = check_nonnegative("hold_limit", hold_limit)
        max_events = check_int("max_events", max_events, minimum=1)
        time_tolerance = check_positive("time_tolerance", time_tolerance)
        super().__init__(h, sub, n_samples)
        self.linear, self.b = states, contact
        self.n = states["stick"].n
        self.stick, self.lower = states["stick"], states["stick lower"]
        self.hold_limit = hold_limit
        self.frictionless = hold_limit == 0  # one state, never left: the free structure
        self.max_events, self.xtol = max_events, time_tolerance
        self.events: list[tuple[float, str]] = []
        self.fresh = False  # the state was entered where the march now is

    def state(self, key):
        """The linear state called ``key``."""
        try:
            return self.linear[key]
        except (KeyError, TypeError):
            raise ValueError(f"key must be one of {sorted(self.linear)}, got {key!r}") from None

    def start(self, velocity):
        """The state at ``t = 0``: ``q = 0``, ``q' = velocity``, and the state it takes."""
        n = self.n
        velocity = check_dof_vector("velocity", velocity, n)
        x = np.zeros(2 * n + 2)
        x[n : 2 * n] = velocity
        x[2 * n] = 1.0  # the drive s = 1, s' = 0: each state's constant load f s at full size
        name = "slip+" if self.frictionless else self._entered(x)
        self.events.append((0.0, name))
        self._record(0, x, name)
        self.fresh = name != "stick" and x[n + self.b] == 0  # a slip from rest: on its boundary
        return x, name

    def _moved(self):
        """The march has left the point where the state was entered."""
        self.fresh = False

    def _entered(self, x):
        """The state taken at ``x`` where ``u = 0`` (or at the start): stick if holding takes
        at most ``mu_s N``, otherwise slip the way the structure pulls."""
        u = x[self.n + self.b]
        if u != 0 and not self.events:
            return "slip+" if u > 0 else "slip-"
        x[self.n + self.b] = 0.0  # exactly at rest on the rod (the event lies within xtol)
        F = float(self.stick.rows[2] @ x)
        if abs(F) <= self.hold_limit:
            return "stick"
        return "slip-" if F > 0 else "slip+"  # holding would take more: it slips the way it pulls

    def switch(self, name, x, t):
        """The switching law at an event at ``t``: a slip's end as ``_entered``; a stick's
        end slips against the force that holding took."""
        check_choice("name", name, ("slip+", "slip-", "stick"))
        check_state("x", x, 2 * self.n + 2)
        if name != "stick":
            new = self._entered(x)
        else:
            new = "slip-" if self.stick.rows[2] @ x > 0 else "slip+"
        self.events.append((t, new))
        if len(self.events) > self.max_events:
            raise ChatterError(
                f"more than max_events={self.max_events} stick/slip events by t={t:.6g} s; "
                "raise max_events or check the friction coefficients"
            )
        return new

    def _first_crossing(self, name, x, span, fresh):
        """Which monitor ends state ``name`` first within ``span`` after ``x``, and when
        (``None`` if neither does); ``fresh``: the state was entered at ``x``."""
        found = None
        for st in (self.stick, self.lower) if name == "stick" else (self.linear[name],):
            z = st._modal(x)  # the unchecked propagation: x is the march's own state
            curve = st._curve(x, z)
            end = curve(span)[0]
            start = float(st.monitor @ x)
            if end > 0:  # stays (a graze that rounding decides)
                continue
            if start <= 0 and not fresh:
                tau = 0.0
            else:  # a slip entered at u = 0 starts on its boundary and leaves it at once
                tau = crossing(curve, span, self.xtol, max(start, np.finfo(float).tiny), end)
            if found is None or tau < found[0]:
                found = (tau, st._at(x, z, tau))
        return found

    def advance(self, x, name, t0, t1, crosses=False):
        """Propagate from ``t0`` to ``t1`` (at most one step) through any events on the way
        (``crosses`` is not needed: every step looks for the first crossing)."""
        check_step(t0, t1)
        fresh = self.fresh
        while True:
            found = None if self.frictionless else self._first_crossing(name, x, t1 - t0, fresh)
            if found is None:
                return self.linear[name]._step(x, t1 - t0), name
            tau, x = found
            t0 += tau
            name, fresh = self.switch(name, x, t0), True


def friction_states(M, K, C, Minv, b, o, hold, slide):
    """The linear states of ``x = (q, q', 1, 0)``: slipping either way, and sticking (twice:
    one copy watches the upper limit ``F <= mu_s N``, one the lower ``F >= -mu_s N``).

    Slip: ``M q'' + C q' + K q = -+mu_k N e_b`` (``slide`` is ``mu_k N``), watching the speed
    ``+-u``. Stick: ``q_b' = q_b'' = 0`` and the other coordinates move as the structure pinned
    at ``b``, watching ``mu_s N -+ F`` (``hold`` is ``mu_s N``) with
    ``F = (M q'' + C q' + K q)_b``. Every state records the acceleration at ``o`` and the
    friction force.

    Parameters
    ----------
    M, K, C : array of shape (n, n)
        Mass, stiffness and viscous damping, symmetric.
    Minv : array of shape (n, n)
        The inverse of ``M`` (:func:`.unilateral.mass_inverse`).
    b : int
        The coordinate along which friction acts.
    o : int or array of shape (n,)
        Where the acceleration is read.
    hold, slide : float
        ``mu_s N`` and ``mu_k N``, N (>= 0).
    """
    M = check_symmetric_matrix("M", M)
    n = M.shape[0]
    Minv, K, C, _, _ = check_structure(Minv, K, C, np.zeros(n), np.zeros(n))
    o = check_dof_vector("o", o, n)
    b = check_int("b", b, minimum=0, maximum=n - 1)
    hold = check_nonnegative("hold", hold)
    slide = check_nonnegative("slide", slide)
    size = 2 * n + 2

    def system(load, held):
        A = np.zeros((size, size))
        A[:n, n : 2 * n] = np.eye(n)
        A[n : 2 * n, :n] = -Minv @ K
        A[n : 2 * n, n : 2 * n] = -Minv @ C
        A[n : 2 * n, 2 * n] = load * Minv[:, b]
        if held:  # q_b' = q_b'' = 0; the others move as the structure pinned at b
            rest = np.delete(np.arange(n), b)
            A[b] = 0.0  # (q_b' is 0: dropping it keeps the held state's matrix diagonalisable)
            A[n : 2 * n] = 0.0
            Mr = M[np.ix_(rest, rest)]
            A[n + rest, :n] = -np.linalg.solve(Mr, K[rest])
            A[n + rest, n : 2 * n] = -np.linalg.solve(Mr, C[rest])
        return A

    states = {}
    for name, sign in (("slip+", 1.0), ("slip-", -1.0)):
        A = system(-sign * slide, held=False)
        monitor = np.zeros(size)
        monitor[n + b] = sign  # the speed along the rod, positive while slipping this way
        load = np.zeros(size)
        load[2 * n] = -sign * slide
        states[name] = LinearState(A, n, monitor, load, o @ A[n : 2 * n])
    A = system(0.0, held=True)
    F = np.zeros(size)  # (M q'' + C q' + K q)_b, with q'' from the held system
    F[: 2 * n] = M[b] @ A[n : 2 * n, : 2 * n] + np.concatenate([K[b], C[b]])
    limit = np.zeros(size)
    limit[2 * n] = hold
    accel = o @ A[n : 2 * n]
    states["stick"] = LinearState(A, n, limit - F, F, accel)
    states["stick lower"] = states["stick"].watching(limit + F, F, accel)
    return states


@dataclass(frozen=True, eq=False)
class FrictionModel:
    """The probe's Z axis at one contact, ready for :func:`stick_slip_response`.

    Attributes
    ----------
    mass, stiffness, damping : ndarray of shape (n, n)
        The reduced probe (fixed-interface modes below ``max_frequency``, then the contact's
        deflection, last), kg, N/m, N s/m.
    rotation : ndarray of shape (n,)
        The reduced coordinates' velocity per rad/s of rigid rotation about the hinge.
    output : ndarray of shape (n,)
        The tip's deflection in the reduced coordinates.
    normal_force : float
        The contact's preload, N.
    """

    mass: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    rotation: np.ndarray
    output: np.ndarray
    normal_force: float


#: The Z model of each probe reduction by ``max_frequency`` (the preload only scales N).
_Z_BODIES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def friction_model(probe_reduction, preload: float, max_frequency: float) -> FrictionModel:
    """The probe's Z axis, reduced at its contact (module docstring), pressed with ``preload``.

    Parameters
    ----------
    probe_reduction : ebantenna.fem.coupling.CraigBampton
        The probe reduced at the contact, damped by its substructure's loss factor.
    preload : float
        The normal force, N (> 0).
    max_frequency : float
        Fixed-interface modes at or above it are dropped, Hz.
    """
    check_reduction("probe_reduction", probe_reduction)
    max_frequency = check_positive("max_frequency", max_frequency)
    cached = _Z_BODIES.setdefault(probe_reduction, {})
    if max_frequency not in cached:
        K, M, T, C = reduced_body(probe_reduction, max_frequency)
        sub = probe_reduction.substructure
        rigid = sweep_velocity(sub.nodes)[sub.free]  # per rad/s about the hinge
        rotation = sla.solve(M, T.T @ (sub.mass @ rigid), assume_a="pos")
        tip = int(np.searchsorted(sub.free, 2 * (sub.nodes.size - 1)))
        cached[max_frequency] = K, M, C, rotation, T[tip]
    K, M, C, rotation, output = cached[max_frequency]
    return FrictionModel(M, K, C, rotation, output, check_positive("preload", preload))


def friction_model_of(case) -> FrictionModel:
    """The ``friction`` model of a contact case: :func:`friction_model` of its probe's reduction,
    Z held along the rod by dry friction under its preload.

    Parameters
    ----------
    case : ebantenna.simulate.structure.ContactCase
        The contact case (its scene gives ``max_frequency``).
    """
    check_case(case)
    return friction_model(case.probe_reduction, case.preload, case.scene.max_frequency)


def friction_accelerations(scene, models, inverse, rotation_speeds, *, rate: float,
                           n_samples: int) -> np.ndarray:
    """The tip acceleration along Z of every signal with ``coulomb_friction``, at ``rate``.

    Parameters
    ----------
    scene : Scene
        Lists ``coulomb_friction`` (its coefficients and its march, ``method``).
    models : list of FrictionModel
        The distinct Z models.
    inverse : array of int, shape (n,)
        Which model each signal uses.
    rotation_speeds : array of shape (n,)
        Each signal's tilt rotation at the stop, ``tilt_ratio x sweep_speed``, rad/s.
    rate : float
        Sample rate, Hz (:func:`~ebantenna.simulate.strikes.timed_rate`).
    n_samples : int
        Samples per signal from the servo's stop.

    Returns
    -------
    ndarray of shape (n, n_samples)
        m/s^2, 0 at the stop.
    """
    rate = check_positive("rate", rate)
    n_int = check_int("n_samples", n_samples, minimum=2)
    effect = scene.effect("coulomb_friction")
    if effect is None:
        raise ValueError("scene must list coulomb_friction (its coefficients and its march)")
    acc = np.empty((len(inverse), n_int))
    for i, (k, speed) in enumerate(zip(inverse, rotation_speeds, strict=True)):
        m = models[k]
        acc[i] = stick_slip_response(
            m.mass, m.stiffness, m.mass.shape[0] - 1, m.normal_force,
            static_friction=effect.static_friction, kinetic_friction=effect.kinetic_friction,
            duration=(n_int - 1) / rate, fs=rate, velocity=m.rotation * float(speed),
            damping=m.damping, output=m.output, max_events=effect.max_events, method=effect.method,
        ).acceleration[:n_int]  # fmt: skip
    return acc


def friction_axis(batch, models) -> tuple[np.ndarray, float]:
    """The ``friction`` model's axis (Z) in the simulator's responses step: stick and slip along
    the rod at the tilt rotation's speed, computed at
    :func:`~ebantenna.simulate.strikes.timed_rate` and left there for the chip to read, as the
    strikes are (:func:`~ebantenna.simulate.strikes.strike_axis`).

    Parameters
    ----------
    batch : ebantenna.simulate.simulator.SignalBatch
        The chain's batch, once its sample instants are set.
    models : list of FrictionModel
        The distinct Z models (``batch.timed["friction"]``).

    Returns
    -------
    acceleration : ndarray of shape (n, n_int)
        m/s^2, from the servo's stop, at ``rate``.
    rate : float
        Its sample rate, Hz.
    """
    rate, n_int = batch_rate(batch, "inverse", "speeds", "tilts")
    acc = friction_accelerations(batch.scene, models, batch.inverse, batch.tilts * batch.speeds,
                                 rate=rate, n_samples=n_int)
    return acc, rate
