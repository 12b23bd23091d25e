"""A contact that only pushes: strike, rebound, free ringing and chatter of a linear structure.

The structure is linear, with ``n`` generalised coordinates ``q`` (physical DOFs or a reduced
basis, see :func:`.structure.probe_contact_model`), mass ``M``, stiffness ``K`` and viscous
damping ``C``.
It touches a rigid object at one point whose displacement toward the object is ``c @ q``
(for a compliant object coupled in, ``c`` is the difference of the two bodies' contact
displacements). The contact is a spring ``k_c`` (the linearised Hertz, wall and object
stiffness of :mod:`.contact`) that acts only in compression:

    contact state:  M q'' + C q' + K q = -k_c c p,   p = c @ q + s,   force F = k_c p >= 0
    free state:     M q'' + C q' + K q = 0,          gap g = -p >= 0

Both states are linear and time-invariant, so between events the motion is propagated exactly,
``x(t + tau) = expm(A tau) x(t)`` for the state ``x = (q, q', s, s')``: through the eigenvectors
of each state's system matrix (the closed-form modal solution, damping included), or through
the matrix exponential itself where a rigid-body motion makes that matrix defective. The
contact ends when its force falls to zero and starts when the gap closes; these events are
found within the step where the force or the gap changes sign, by Newton's method kept inside a
shrinking bracket, and placed on the far side of the root (within ``time_tolerance``) so that
the state entered starts admissible. The two states share the coordinates ``q``, so a switch
changes nothing but the equations: no energy is lost or gained by it.

**Cost.** Within a state, the force (or gap) and the acceleration are sums of the state's modes,
``Re(sum_k w_k e^(lambda_k t))`` plus the servo's linear part, so a block of steps costs one
small matrix product, not a propagation per step. Where a bound shows that the force (or gap)
cannot change sign over a long span, ``sum_k |w_k| |e^(lambda_k t)|`` below its steady part
(a settled strike pressed by its preload), only the output samples are computed there. A one-second
strike of the paper scene (probe and rod reduced to about 12 coordinates, a few dozen events,
8 kHz) costs about 8 ms on one core, most of it in the events.

**The pan-tilt's approach and the preload.** ``q`` are coordinates *relative to the servo*: the
absolute displacement is ``r s + q``, where ``s`` is the servo's travel measured at the contact
point and ``r`` the rigid motion the servo gives the structure per unit ``s`` (``base``). Before
the first contact the probe swings rigidly at ``s' = v0`` (no deformation, no acceleration).
The contact is first made at ``t = 0``. The servo does not stop at once: it drives on by an
overtravel ``s_stop`` and then stops, as the arrest in :mod:`.modes` (the structure keeps its
velocity, ``q' += r v0``). The overtravel is what presses the probe on the object: it is chosen
so that, once everything is at rest, the contact carries the preload ``F0``:

    s_stop = F0 (1/k_c + c @ K^-1 @ c),

the object pushing back through the contact spring in series with the structure's static
flexibility at the contact. ``F0 = 0`` stops the servo at the first touch. Gravity is left out
(it is the sensor chain's business).

**Limits.** A sign change of force or gap is looked for at steps of at most 1/16 of the shortest
natural period of either state (and at every output sample): a contact shorter than a step that
starts and ends inside it can be missed, as with any event detection on a time grid. A contact at
rest with zero preload can chatter without end; ``max_events`` bounds the work.
"""

from __future__ import annotations

import logging
import math
import warnings
from dataclasses import dataclass

import numpy as np

from .._validate import check_choice, check_int, check_nonnegative, check_positive
from .linear_state import LinearState, crossing, step_grid
from .structure import check_dof_vector, check_symmetric_matrix, mass_inverse

__all__ = [
    "ChatterError",
    "ContactEvent",
    "UnilateralResponse",
    "unilateral_response",
]

logger = logging.getLogger(__name__)

#: Steps per shortest natural period at which the sign of the force or the gap is checked.
STEPS_PER_PERIOD = 16


class ChatterError(RuntimeError):
    """More contact events than allowed: the probe chatters (or rests on the object unloaded)."""


@dataclass(frozen=True)
class ContactEvent:
    """One change of the contact state.

    Attributes
    ----------
    time : float
        When, s (0: the first touch).
    kind : {"contact", "separation"}
        The state entered.
    velocity : float
        Closing speed of the contact point on the object, ``dp/dt``, m/s (positive: pressing in).
    """

    time: float
    kind: str
    velocity: float


@dataclass(frozen=True, eq=False)
class UnilateralResponse:
    """Time history of a strike with a unilateral contact.

    Attributes
    ----------
    t : ndarray of shape (n_samples,)
        Sample times, s; 0 is the first touch.
    acceleration : ndarray of shape (n_samples,)
        Acceleration at the output coordinate (the accelerometer), m/s^2.
    contact_force : ndarray of shape (n_samples,)
        Contact force, N (0 while separated).
    events : tuple of ContactEvent
        Every contact and separation after the first touch, in time order.
    stop_time : float
        When the servo stopped, s.
    overtravel : float
        The servo's travel past the first touch, m.
    bilateral_from : float or None
        Time from which the contact was held (``on_max_events="warn"``), s; None otherwise.
    states : ndarray of shape (n_samples, 2 n + 2) or None
        With ``return_states=True``: the state ``(q, q', s, s')`` at every sample.
    """

    t: np.ndarray
    acceleration: np.ndarray
    contact_force: np.ndarray
    events: tuple
    stop_time: float
    overtravel: float
    bilateral_from: float | None = None
    states: np.ndarray | None = None

    @property
    def n_impacts(self) -> int:
        """Number of strikes, the first touch included."""
        return 1 + sum(e.kind == "contact" for e in self.events)


def unilateral_response(
    mass,
    stiffness,
    contact,
    contact_stiffness: float,
    *,
    base,
    approach_speed: float,
    duration: float,
    fs: float,
    damping=None,
    output=None,
    preload: float = 0.0,
    max_events: int = 200,
    on_max_events: str = "raise",
    time_tolerance: float = 1e-12,
    return_states: bool = False,
) -> UnilateralResponse:
    """Strike of a linear structure on a rigid object through a contact that only pushes.

    Parameters
    ----------
    mass : array of shape (n, n)
        Mass matrix, symmetric positive definite (kg for physical coordinates).
    stiffness : array of shape (n, n)
        Stiffness matrix without the contact, symmetric positive semidefinite (N/m).
    contact : int or array of shape (n,)
        The contact point's displacement toward the object: a DOF index or a vector ``c``.
    contact_stiffness : float
        Contact spring ``k_c``, N/m (> 0).
    base : int or array of shape (n,)
        The servo's rigid motion per metre of its travel at the contact point, ``r``.
    approach_speed : float
        Speed of the contact point toward the object before the first touch, m/s (> 0).
    duration : float
        Length of the record from the first touch, s (> 0).
    fs : float
        Output sample rate, Hz (> 0).
    damping : array of shape (n, n), optional
        Viscous damping matrix, N s/m; default none.
    output : int or array of shape (n,), optional
        Where the accelerometer is; default the contact point.
    preload : float
        Static contact force once the servo has stopped, N (>= 0); enters as the overtravel
        ``F0 (1/k_c + c K^-1 c)``. A positive preload needs a nonsingular ``K``.
    max_events : int
        Most contact/separation events handled (>= 1).
    on_max_events : {"raise", "warn"}
        When they are exceeded: raise :class:`ChatterError`, or warn and hold the contact closed
        (bilateral) from the next contact on.
    time_tolerance : float
        Accuracy of each event time, s (> 0); events are placed no more than this late.
    return_states : bool
        Also return the state ``(q, q', s, s')`` at every sample.

    Returns
    -------
    UnilateralResponse

    Examples
    --------
    A 1 kg mass hits a 1e4 N/m spring at 1 m/s and leaves at 1 m/s after pi/100 s:

    >>> res = unilateral_response([[1.0]], [[0.0]], 0, 1e4, base=0, approach_speed=1.0,
    ...                           duration=0.05, fs=1000.0)
    >>> [(e.kind, round(e.time, 9), round(e.velocity, 9)) for e in res.events]
    [('separation', 0.031415927, -1.0)]
    >>> float(res.contact_force.max()) <= 100.0  # k v sqrt(m/k), N
    True
    """
    M = check_symmetric_matrix("mass", mass)
    n = M.shape[0]
    K = check_symmetric_matrix("stiffness", stiffness, n)
    C = np.zeros((n, n)) if damping is None else check_symmetric_matrix("damping", damping, n)
    c = check_dof_vector("contact", contact, n)
    r = check_dof_vector("base", base, n)
    o = c if output is None else check_dof_vector("output", output, n)
    kc = check_positive("contact_stiffness", contact_stiffness)
    v0 = check_positive("approach_speed", approach_speed)
    T = check_positive("duration", duration)
    fs = check_positive("fs", fs)
    F0 = check_nonnegative("preload", preload)
    max_events = check_int("max_events", max_events, minimum=1)
    check_choice("on_max_events", on_max_events, ("raise", "warn"))
    xtol = check_positive("time_tolerance", time_tolerance)
    Minv = mass_inverse(M)
    if np.linalg.eigvalsh(K).min() < -1e-10 * max(1.0, np.abs(K).max()):
        raise ValueError("stiffness must be positive semidefinite")

    overtravel = 0.0
    if F0 > 0:
        try:
            flex = float(c @ np.linalg.solve(K, c))
        except np.linalg.LinAlgError:
            flex = math.inf
        if not (math.isfinite(flex) and flex > 0):
            raise ValueError(
                "preload > 0 needs a structure that resists a static load at the contact "
                "(stiffness is singular there: a free rigid-body motion); give preload=0"
            )
        overtravel = F0 * (1 / kc + flex)
    t_stop = overtravel / v0

    # First-order systems of x = (q, q', s, s').
    N = 2 * n + 2
    pen = np.zeros(N)  # p = pen @ x
    pen[:n], pen[2 * n] = c, 1.0

    def system(closed):
        A = np.zeros((N, N))
        A[:n, n : 2 * n] = np.eye(n)
        Kc = K + kc * np.outer(c, c) if closed else K
        A[n : 2 * n, :n] = -Minv @ Kc
        A[n : 2 * n, n : 2 * n] = -Minv @ C
        if closed:
            A[n : 2 * n, 2 * n] = -kc * (Minv @ c)
        A[2 * n, 2 * n + 1] = 1.0
        return A

    A_free, A_closed = system(False), system(True)
    free = LinearState(A_free, n, -pen, np.zeros(N), o @ A_free[n : 2 * n])
    closed = LinearState(A_closed, n, kc * pen, kc * pen, o @ A_closed[n : 2 * n])
    h, sub, n_samples, n_steps, _ = step_grid([free, closed], fs, T, STEPS_PER_PERIOD)

    t_out = np.arange(n_samples) / fs
    acc = np.zeros(n_samples)
    force = np.zeros(n_samples)
    states = np.zeros((n_samples, N)) if return_states else None
    events: list[ContactEvent] = []
    bilateral_from = None
    frozen = False

    def record(i, x, st):
        if i % sub == 0:
            k = i // sub
            acc[k], force[k] = st.rows[1:] @ x
            if states is not None:
                states[k] = x

    def switch(st, x, t):
        """Enter the other state at time t; returns it."""
        nonlocal frozen, bilateral_from
        entering = free if st is closed else closed
        kind = "contact" if entering is closed else "separation"
        events.append(ContactEvent(t, kind, float(pen @ (st.A @ x))))
        if len(events) >= max_events and not frozen:
            if on_max_events == "raise":
                raise ChatterError(
                    f"more than max_events={max_events} contact events by t={t:.6g} s: the probe "
                    "chatters or rests on the object without preload; raise max_events, give a "
                    "preload, or use on_max_events='warn' to hold the contact from then on"
                )
            warnings.warn(
                f"max_events={max_events} reached at t={t:.6g} s (chatter); the contact is "
                "held closed from the next contact on",
                RuntimeWarning,
                stacklevel=3,
            )
            frozen = True
        if frozen and entering is closed and bilateral_from is None:
            bilateral_from = t
        return entering

    def watched(st):
        return not (frozen and st is closed)

    def advance(x, st, t0, t1, crosses=False):
        """Propagate from t0 to t1 (at most one step) through any events on the way;
        ``crosses``: the monitored quantity is known to reach zero by t1."""
        while True:
            if not crosses:
                x1 = st.step(x, t1 - t0)
                if not watched(st) or st.monitor @ x1 > 0:
                    return x1, st
            z = st.modal(x)
            g = st.curve(x, z)
            span = t1 - t0
            end = g(span)[0]
            if end > 0:  # a graze that rounding decides: the curve stays in this state
                return st.at(x, z, span), st
            crosses = False
            start = float(st.monitor @ x)
            if start <= 0:  # already at the boundary (a grazing touch): switch at once
                tau = 0.0
            else:
                tau = crossing(g, span, xtol, start, end)
            x = st.at(x, z, tau)
            t0 = t0 + tau
            st = switch(st, x, t0)

    # First touch at t = 0: contact closed, p = 0, closing at v0 through s' or through q'.
    x = np.zeros(N)
    x[2 * n + 1] = v0
    st = closed
    stopped = False
    if t_stop == 0.0:
        x[n : 2 * n] += r * v0
        x[2 * n + 1] = 0.0
        stopped = True
    record(0, x, st)
    i = 0
    while i < n_steps:
        t = i * h
        if not stopped and t_stop < (i + 1) * h:
            x, st = advance(x, st, t, t_stop)
            x = x.copy()
            x[n : 2 * n] += r * x[2 * n + 1]
            x[2 * n + 1] = 0.0
            stopped = True
            x, st = advance(x, st, t_stop, (i + 1) * h)
            i += 1
            record(i, x, st)
            continue
        limit = n_steps - i
        if not stopped:
            limit = min(limit, int(math.floor(t_stop / h)) - i)
        first = (-(i + 1)) % sub  # the first step from here that is an output sample
        z = st.modal(x)
        quiet = not watched(st) or st.stays_positive(x, z, min(st.span, limit))
        m, j, values, event = st.read_ahead(x, z, first, limit, quiet)
        # Record the output samples among the m steps taken.
        k = (i + 1 + j) // sub
        acc[k], force[k] = values[:, 1], values[:, 2]
        if states is not None:
            states[k] = [st.after(x, z, jj + 1) for jj in j]
        if m:
            x = st.after(x, z, m)
            i += m
        if event:
            x, st = advance(x, st, i * h, (i + 1) * h, crosses=True)
            i += 1
            record(i, x, st)
    logger.debug("unilateral strike: %d events, %d steps of %.3g s", len(events), n_steps, h)
    return UnilateralResponse(
        t_out, acc, force, tuple(events), t_stop, overtravel, bilateral_from, states
    )
