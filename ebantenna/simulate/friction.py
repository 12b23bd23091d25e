"""Coulomb friction at the contact, along the rod: stick and slip of a linear structure.

Where the probe presses on the rod with a normal force ``N``, its motion along the rod (the
tangential direction ``t``: ``u = t @ q'`` is the contact point's speed along the rod) is resisted
by dry friction (C. A. Coulomb's law, as in J. P. Den Hartog, *Mechanical Vibrations*, 4th ed.,
McGraw-Hill, 1956, section 8.3):

- **slip** (``u != v_s``, with ``v_s`` the surface's own speed, 0 for a rod at rest): the friction
  force is ``-mu_k N sign(u - v_s)``;
- **stick** (``u = v_s``): the friction force is whatever keeps ``t @ q'' = 0``,
  ``F = -(t M^-1 f) / (t M^-1 t)`` with ``f = -K q - C q'``, as long as ``|F| <= mu_s N``.

Each state is a smooth ODE integrated by :func:`scipy.integrate.solve_ivp` (DOP853) with terminal
events: slip ends when the relative speed ``u - v_s`` crosses zero, stick ends when ``|F|`` reaches
``mu_s N``. At the end of a slip the stick condition decides whether the contact sticks or slips
the other way. ``N`` is a constant or a function of time (for instance the contact force of
:func:`.unilateral.unilateral_response`; ``N = 0`` means no friction).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from .._validate import check_int, check_nonnegative, check_positive
from .structure import check_dof_vector, check_symmetric_matrix
from .unilateral import ChatterError

__all__ = ["FrictionEvent", "FrictionResponse", "coulomb_response", "check_coefficients"]


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


@dataclass(frozen=True)
class FrictionEvent:
    """One change of the friction state.

    Attributes
    ----------
    time : float
        When, s.
    kind : {"stick", "slip+", "slip-"}
        The state entered (``slip+``: sliding faster than the surface).
    position : float
        Tangential displacement of the contact point ``t @ q``, m.
    """

    time: float
    kind: str
    position: float


@dataclass(frozen=True, eq=False)
class FrictionResponse:
    """Time history of a structure with a Coulomb contact.

    Attributes
    ----------
    t : ndarray of shape (n_samples,)
        Sample times, s.
    acceleration : ndarray of shape (n_samples,)
        Acceleration at the output coordinate, m/s^2.
    friction_force : ndarray of shape (n_samples,)
        Friction force on the structure along ``t``, N.
    states : ndarray of shape (n_samples, 2 n)
        ``(q, q')`` at the samples.
    events : tuple of FrictionEvent
        The initial state and every change, in time order.
    """

    t: np.ndarray
    acceleration: np.ndarray
    friction_force: np.ndarray
    states: np.ndarray
    events: tuple


def coulomb_response(
    mass,
    stiffness,
    tangential,
    normal_force,
    *,
    static_friction: float,
    kinetic_friction: float,
    duration: float,
    fs: float,
    surface_speed: float = 0.0,
    displacement=None,
    velocity=None,
    damping=None,
    output=None,
    max_events: int = 1000,
    rtol: float = 1e-10,
) -> FrictionResponse:
    """Free motion of a linear structure with Coulomb friction at one contact point.

    Parameters
    ----------
    mass, stiffness : array of shape (n, n)
        Symmetric mass (positive definite) and stiffness matrices (kg, N/m).
    tangential : int or array of shape (n,)
        The contact point's displacement along the rod: a DOF index or a vector ``t``.
    normal_force : float or callable
        Normal force ``N`` (N, >= 0), or a function ``N(t)`` of time in s.
    static_friction, kinetic_friction : float
        Coefficients ``mu_s >= mu_k >= 0`` (dimensionless).
    duration, fs : float
        Record length (s) and output sample rate (Hz), both > 0.
    surface_speed : float
        Speed of the rod's surface along ``t`` (a belt), m/s; 0 for a rod at rest.
    displacement, velocity : array of shape (n,), optional
        Initial ``q`` (m) and ``q'`` (m/s); zero by default.
    damping : array of shape (n, n), optional
        Viscous damping matrix, N s/m.
    output : int or array of shape (n,), optional
        Where the acceleration is taken; default the contact point.
    max_events : int
        Most stick/slip changes handled (>= 1); more raise :class:`~.unilateral.ChatterError`.
    rtol : float
        Relative tolerance of the integrator (absolute: ``rtol`` times the initial state's size).

    Returns
    -------
    FrictionResponse

    Examples
    --------
    A 1 kg, 100 N/m oscillator released from 10 cm against mu N = 1 N loses 4 mu N / k = 4 cm of
    amplitude per cycle, every half period pi/10 s, and sticks at the first turning point within
    mu_s N / k = 1 cm of its rest position:

    >>> res = coulomb_response([[1.0]], [[100.0]], 0, 1.0, static_friction=1.0,
    ...                        kinetic_friction=1.0, duration=2.0, fs=100.0, displacement=[0.1])
    >>> [(e.kind, round(e.position, 6)) for e in res.events]  # doctest: +NORMALIZE_WHITESPACE
    [('slip-', 0.1), ('slip+', -0.08), ('slip-', 0.06), ('slip+', -0.04), ('slip-', 0.02),
     ('stick', 0.0)]
    """
    M = check_symmetric_matrix("mass", mass)
    n = M.shape[0]
    K = check_symmetric_matrix("stiffness", stiffness, n)
    C = np.zeros((n, n)) if damping is None else check_symmetric_matrix("damping", damping, n)
    tv = check_dof_vector("tangential", tangential, n)
    o = tv if output is None else check_dof_vector("output", output, n)
    mus, muk = check_coefficients(static_friction, kinetic_friction)
    if callable(normal_force):
        N = normal_force
    else:
        N0 = check_nonnegative("normal_force", normal_force)

        def N(t):
            return N0

    T = check_positive("duration", duration)
    fs = check_positive("fs", fs)
    vs = float(surface_speed)
    if not math.isfinite(vs):
        raise ValueError(f"surface_speed must be finite, got {surface_speed!r}")
    max_events = check_int("max_events", max_events, minimum=1)
    rtol = check_positive("rtol", rtol)
    q0 = np.zeros(n) if displacement is None else check_dof_vector("displacement", displacement, n)
    v0 = np.zeros(n) if velocity is None else check_dof_vector("velocity", velocity, n)
    try:
        np.linalg.cholesky(M)
    except np.linalg.LinAlgError:
        raise ValueError("mass must be positive definite") from None
    Minv = np.linalg.inv(M)
    Mt = Minv @ tv
    tMt = float(tv @ Mt)
    if not tMt > 0:
        raise ValueError("tangential must be a nonzero vector")

    def stick_force(t, y):
        f = -K @ y[:n] - C @ y[n:]
        return -float(tv @ (Minv @ f)) / tMt

    def friction(state, t, y):
        if state == "stick":
            return stick_force(t, y)
        return -muk * N(t) * (1.0 if state == "slip+" else -1.0)

    def rhs(state):
        def f(t, y):
            force = -K @ y[:n] - C @ y[n:] + friction(state, t, y) * tv
            return np.concatenate([y[n:], Minv @ force])

        return f

    def relative_speed(t, y):
        return float(tv @ y[n:]) - vs

    def stick_limit(t, y):
        return mus * N(t) - abs(stick_force(t, y))

    def entered(t, y, previous=None):
        """The state the contact takes at (t, y) with zero relative speed (or at the start)."""
        u = relative_speed(t, y)
        if previous is None and abs(u) > 0:
            return "slip+" if u > 0 else "slip-"
        F = stick_force(t, y)
        if abs(F) <= mus * N(t):
            return "stick"
        return "slip-" if F > 0 else "slip+"

    t_out = np.arange(int(math.floor(T * fs + 1e-9)) + 1) / fs
    scale = max(np.abs(np.concatenate([q0, v0])).max(), abs(vs), 1e-300)
    atol = rtol * scale
    y = np.concatenate([q0, v0])
    t = 0.0
    state = entered(t, y)
    events = [FrictionEvent(0.0, state, float(tv @ q0))]
    states = np.zeros((t_out.size, 2 * n))
    acc = np.zeros(t_out.size)
    fric = np.zeros(t_out.size)
    while t < t_out[-1]:
        if state == "stick":
            ev = stick_limit
            ev.direction = -1
        else:
            ev = relative_speed
            ev.direction = -1 if state == "slip+" else 1
        ev.terminal = True
        fun = rhs(state)
        mask = t_out >= t
        sol = solve_ivp(
            fun,
            (t, t_out[-1]),
            y,
            method="DOP853",
            events=ev,
            dense_output=True,
            rtol=rtol,
            atol=atol,
        )
        t_end = sol.t[-1]
        take = mask & (t_out <= t_end)
        Y = sol.sol(t_out[take]).T if take.any() else np.zeros((0, 2 * n))
        states[take] = Y
        for k, yy in zip(np.flatnonzero(take), Y, strict=True):
            a = fun(t_out[k], yy)[n:]
            acc[k] = o @ a
            fric[k] = friction(state, t_out[k], yy)
        if sol.status != 1:  # reached the end
            break
        t, y = t_end, sol.y[:, -1].copy()
        if state != "stick":
            y[n:] += Mt * ((vs - float(tv @ y[n:])) / tMt)  # land exactly on u = v_s
        if state == "stick":  # the static limit is reached: slip against the required force
            state = "slip-" if stick_force(t, y) > 0 else "slip+"
        else:
            new = entered(t, y, previous=state)
            if new == state:  # a grazing touch of u = v_s: keep slipping the other way
                new = "slip+" if state == "slip-" else "slip-"
            state = new
        events.append(FrictionEvent(float(t), state, float(tv @ y[:n])))
        if len(events) > max_events:
            raise ChatterError(
                f"more than max_events={max_events} stick/slip events by t={t:.6g} s; "
                "raise max_events or check the friction coefficients"
            )
    return FrictionResponse(t_out, acc, fric, states, tuple(events))
