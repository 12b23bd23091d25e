"""Coulomb friction at the contact, along the rod, integrated as an ODE: the law's witness.

The law itself, propagated exactly between its events, is :mod:`.stick_slip`
(:func:`.stick_slip.stick_slip_response`, the ``coulomb_friction`` effect of a scene). This
module integrates the same law another way, with an ODE solver, to hold it against in the tests.

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

from .._validate import (
    check_array,
    check_choice,
    check_int,
    check_nonnegative,
    check_positive,
    check_real,
    real_array,
)
from .stick_slip import check_coefficients
from .structure import check_dof_vector, check_symmetric_matrix
from .unilateral import ChatterError

__all__ = ["FrictionEvent", "FrictionResponse", "coulomb_response", "CoulombLaw"]


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
    law = CoulombLaw(K, C, np.linalg.inv(M), tv, N, mus, muk, vs)
    t_out = np.arange(int(math.floor(T * fs + 1e-9)) + 1) / fs
    return law._respond(q0, v0, t_out, o, rtol=rtol, max_events=max_events)


#: The states of the contact: sticking, or slipping faster (``slip+``) or slower than the surface.
STATES = ("stick", "slip+", "slip-")


class CoulombLaw:
    """Coulomb's law at one contact point as the right-hand sides and events of an ODE.

    The witness's own arithmetic, independent of :mod:`.stick_slip`: each state is integrated
    by :func:`scipy.integrate.solve_ivp` (DOP853) up to its terminal event. Built by
    :func:`coulomb_response`. Every public method checks its input; the integration calls the
    same arithmetic unchecked.

    Parameters
    ----------
    K, C, Minv : array of shape (n, n)
        Stiffness and damping (symmetric), and the inverse mass (finite).
    tangential : int or array of shape (n,)
        ``t``: the contact point's displacement along the rod (a DOF index or a nonzero vector).
    normal_force : callable
        ``N(t)``, N.
    static_friction, kinetic_friction : float
        ``mu_s >= mu_k >= 0``.
    surface_speed : float
        ``v_s``, m/s (finite).

    Examples
    --------
    1 kg on 100 N/m, pressed by 1 N against mu = 1, held 5 cm out: the spring pulls back with
    5 N and the contact holds 1 N at most, so from rest the contact slips back at once:

    >>> law = CoulombLaw([[100.0]], [[0.0]], [[1.0]], 0, lambda t: 1.0, 1.0, 1.0, 0.0)
    >>> law.stick_force(0.0, [0.05, 0.0]), law.entered(0.0, [0.05, 0.0])
    (5.0, 'slip-')
    """

    def __init__(self, K, C, Minv, tangential, normal_force, static_friction, kinetic_friction,
                 surface_speed):  # fmt: skip
        K = check_symmetric_matrix("K", K)
        n = K.shape[0]
        C = check_symmetric_matrix("C", C, n)
        Minv = real_array("Minv", Minv)
        if Minv.shape != (n, n) or not np.all(np.isfinite(Minv)):
            raise ValueError(f"Minv must be a finite {n} x {n} matrix, got shape {Minv.shape}")
        tangential = check_dof_vector("tangential", tangential, n)
        if not callable(normal_force):
            raise TypeError(f"normal_force must be a function N(t) of time, N, got "
                            f"{type(normal_force).__name__}")
        static_friction, kinetic_friction = check_coefficients(static_friction, kinetic_friction)
        surface_speed = check_real("surface_speed", surface_speed)
        self.K, self.C, self.Minv, self.tv = K, C, Minv, tangential
        self.n = n
        self.N = normal_force
        self.mus, self.muk, self.vs = static_friction, kinetic_friction, surface_speed
        self.Mt = Minv @ tangential
        self.tMt = float(tangential @ self.Mt)
        if not self.tMt > 0:
            raise ValueError("tangential must be a nonzero vector (and Minv positive definite "
                             "along it)")

    # ------------------------------------------------------------ the checked public methods
    def stick_force(self, t, y):
        """The friction force that keeps ``t @ q'' = 0``: ``-(t M^-1 f) / (t M^-1 t)``, N.

        Parameters
        ----------
        t : float
            Time, s (finite).
        y : array of shape (2 n,)
            ``(q, q')``, finite.
        """
        return self._stick_force(*self._time_and_state(t, y))

    def friction(self, state, t, y):
        """The friction force in ``state`` (``"stick"``, ``"slip+"`` or ``"slip-"``) at time
        ``t`` and ``y = (q, q')``: the holding force, or ``-+mu_k N``."""
        state = check_choice("state", state, STATES)
        return self._friction(state, *self._time_and_state(t, y))

    def rhs(self, state):
        """``y' = (q', M^-1 (-K q - C q' + F t))`` in ``state`` (``"stick"``, ``"slip+"`` or
        ``"slip-"``), as a function ``f(t, y)`` for :func:`scipy.integrate.solve_ivp`."""
        return self._rhs(check_choice("state", state, STATES))

    def relative_speed(self, t, y):
        """``u - v_s`` at time ``t`` and ``y = (q, q')``: zero where a slip ends, m/s."""
        return self._relative_speed(*self._time_and_state(t, y))

    def stick_limit(self, t, y):
        """``mu_s N - |F|`` at time ``t`` and ``y = (q, q')``: zero where a stick ends, N."""
        return self._stick_limit(*self._time_and_state(t, y))

    def end_event(self, state):
        """The terminal event of ``state`` (``"stick"``, ``"slip+"`` or ``"slip-"``), as
        :func:`scipy.integrate.solve_ivp` takes it."""
        return self._end_event(check_choice("state", state, STATES))

    def entered(self, t, y, previous=None):
        """The state the contact takes at ``(t, y)`` with zero relative speed (``previous``:
        the state that ended there: ``"stick"``, ``"slip+"`` or ``"slip-"``) or at the start
        (None)."""
        if previous is not None:
            previous = check_choice("previous", previous, STATES)
        return self._entered(*self._time_and_state(t, y), previous)

    def next_state(self, state, t, y):
        """The state after ``state`` ended at ``(t, y)``; a slip's end lands ``y`` (in place:
        a float array of shape ``(2 n,)``) exactly on ``u = v_s``."""
        state = check_choice("state", state, STATES)
        t, checked = self._time_and_state(t, y)
        if not (isinstance(y, np.ndarray) and y.dtype == np.float64 and y.flags.writeable):
            raise TypeError("y must be a writable float64 array: a slip's end lands it on "
                            f"u = v_s in place, got {type(y).__name__}")
        return self._next_state(state, t, y)

    def respond(self, q0, v0, t_out, output, *, rtol, max_events) -> FrictionResponse:
        """The motion from ``(q0, v0)`` sampled at ``t_out``: one state after another, each
        integrated to its end.

        Parameters
        ----------
        q0, v0 : array of shape (n,)
            Initial ``q`` (m) and ``q'`` (m/s), finite.
        t_out : array of shape (n_samples,)
            Sample times from 0 on, s: finite, nondecreasing, ``t_out[0] >= 0``.
        output : int or array of shape (n,)
            Where the acceleration is taken.
        rtol : float
            Relative tolerance of the integrator (> 0); the absolute one is ``rtol`` times the
            initial state's size.
        max_events : int
            Most stick/slip changes (>= 1); more raise :class:`~.unilateral.ChatterError`.
        """
        n = self.n
        q0, v0 = self._vector("q0", q0), self._vector("v0", v0)
        t_out = self._times(t_out)
        output = check_dof_vector("output", output, n)
        rtol = check_positive("rtol", rtol)
        max_events = check_int("max_events", max_events, minimum=1)
        return self._respond(q0, v0, t_out, output, rtol=rtol, max_events=max_events)

    def integrate(self, state, t, y, t_out, output, record, *, rtol, atol):
        """Integrate ``state`` from ``(t, y)`` to its end or ``t_out[-1]``, filling ``record``
        (states, acceleration at ``output``, friction) at the samples ``t_out`` it covers;
        returns the :func:`scipy.integrate.solve_ivp` solution.

        ``record`` is three writable float arrays of shapes ``(n_samples, 2 n)``,
        ``(n_samples,)`` and ``(n_samples,)``; ``rtol`` and ``atol`` are > 0; the other
        parameters are as in :meth:`respond` and :meth:`stick_force`.
        """
        state = check_choice("state", state, STATES)
        t, y = self._time_and_state(t, y)
        t_out = self._times(t_out)
        output = check_dof_vector("output", output, self.n)
        shapes = ((t_out.size, 2 * self.n), (t_out.size,), (t_out.size,))
        if not (isinstance(record, tuple) and len(record) == 3 and all(
                isinstance(a, np.ndarray) and a.shape == shape and a.dtype == np.float64
                and a.flags.writeable for a, shape in zip(record, shapes, strict=True))):
            raise TypeError(f"record must be three writable float64 arrays of shapes "
                            f"{shapes[0]}, {shapes[1]} and {shapes[2]} (states, acceleration, "
                            f"friction)")
        rtol, atol = check_positive("rtol", rtol), check_positive("atol", atol)
        return self._integrate(state, t, y, t_out, output, record, rtol=rtol, atol=atol)

    def _vector(self, name, value) -> np.ndarray:
        """``value`` as a finite float vector of length ``n``; raise naming ``name``."""
        value = real_array(name, value)
        if value.shape != (self.n,) or not np.all(np.isfinite(value)):
            got = f"shape {value.shape}" if value.shape != (self.n,) else "NaN or inf in it"
            raise ValueError(f"{name} must be a finite vector of length {self.n}, got {got}")
        return value

    def _time_and_state(self, t, y) -> tuple:
        """``(t, y)`` checked: a finite time and a finite ``(q, q')`` of length ``2 n``."""
        t = check_real("t", t)
        y = real_array("y", y)
        if y.shape != (2 * self.n,) or not np.all(np.isfinite(y)):
            got = f"shape {y.shape}" if y.shape != (2 * self.n,) else "NaN or inf in it"
            raise ValueError(f"y must be a finite (q, q') of length {2 * self.n}, got {got}")
        return t, y

    @staticmethod
    def _times(t_out) -> np.ndarray:
        """``t_out`` checked: finite sample times from 0 on, nondecreasing."""
        t_out = check_array("t_out", t_out, ndim=1)
        if t_out[0] < 0 or np.any(np.diff(t_out) < 0):
            raise ValueError("t_out must be sample times from 0 on, in order (nondecreasing, "
                             f"t_out[0] >= 0), got {t_out[:3]}...")
        return t_out

    # --------------------------------------------------- the arithmetic, as the march calls it
    def _stick_force(self, t, y):
        n = self.n
        f = -self.K @ y[:n] - self.C @ y[n:]
        return -float(self.tv @ (self.Minv @ f)) / self.tMt

    def _friction(self, state, t, y):
        if state == "stick":
            return self._stick_force(t, y)
        return -self.muk * self.N(t) * (1.0 if state == "slip+" else -1.0)

    def _rhs(self, state):
        n = self.n

        def f(t, y):
            force = -self.K @ y[:n] - self.C @ y[n:] + self._friction(state, t, y) * self.tv
            return np.concatenate([y[n:], self.Minv @ force])

        return f

    def _relative_speed(self, t, y):
        return float(self.tv @ y[self.n :]) - self.vs

    def _stick_limit(self, t, y):
        return self.mus * self.N(t) - abs(self._stick_force(t, y))

    def _end_event(self, state):
        watched = self._stick_limit if state == "stick" else self._relative_speed

        def event(t, y):
            return watched(t, y)

        event.direction = -1 if state in ("stick", "slip+") else 1
        event.terminal = True
        return event

    def _entered(self, t, y, previous=None):
        u = self._relative_speed(t, y)
        if previous is None and abs(u) > 0:
            return "slip+" if u > 0 else "slip-"
        F = self._stick_force(t, y)
        if abs(F) <= self.mus * self.N(t):
            return "stick"
        return "slip-" if F > 0 else "slip+"

    def _next_state(self, state, t, y):
        n = self.n
        if state == "stick":  # the static limit is reached: slip against the required force
            return "slip-" if self._stick_force(t, y) > 0 else "slip+"
        y[n:] += self.Mt * ((self.vs - float(self.tv @ y[n:])) / self.tMt)  # land on u = v_s
        new = self._entered(t, y, previous=state)
        if new == state:  # a grazing touch of u = v_s: keep slipping the other way
            new = "slip+" if state == "slip-" else "slip-"
        return new

    def _respond(self, q0, v0, t_out, output, *, rtol, max_events) -> FrictionResponse:
        n, tv = self.n, self.tv
        scale = max(np.abs(np.concatenate([q0, v0])).max(), abs(self.vs), 1e-300)
        y = np.concatenate([q0, v0])
        t = 0.0
        state = self._entered(t, y)
        events = [FrictionEvent(0.0, state, float(tv @ q0))]
        record = np.zeros((t_out.size, 2 * n)), np.zeros(t_out.size), np.zeros(t_out.size)
        while t < t_out[-1]:
            sol = self._integrate(state, t, y, t_out, output, record, rtol=rtol,
                                  atol=rtol * scale)  # fmt: skip
            if sol.status != 1:  # reached the end
                break
            t, y = sol.t[-1], sol.y[:, -1].copy()
            state = self._next_state(state, t, y)
            events.append(FrictionEvent(float(t), state, float(tv @ y[:n])))
            if len(events) > max_events:
                raise ChatterError(
                    f"more than max_events={max_events} stick/slip events by t={t:.6g} s; "
                    "raise max_events or check the friction coefficients"
                )
        states, acc, fric = record
        return FrictionResponse(t_out, acc, fric, states, tuple(events))

    def _integrate(self, state, t, y, t_out, output, record, *, rtol, atol):
        n = self.n
        fun = self._rhs(state)
        mask = t_out >= t
        sol = solve_ivp(fun, (t, t_out[-1]), y, method="DOP853", events=self._end_event(state),
                        dense_output=True, rtol=rtol, atol=atol)  # fmt: skip
        take = mask & (t_out <= sol.t[-1])
        Y = sol.sol(t_out[take]).T if take.any() else np.zeros((0, 2 * n))
        states, acc, fric = record
        states[take] = Y
        for k, yy in zip(np.flatnonzero(take), Y, strict=True):
            acc[k] = output @ fun(t_out[k], yy)[n:]
            fric[k] = self._friction(state, t_out[k], yy)
        return sol
