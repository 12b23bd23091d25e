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

**Reference and engine.** :class:`StrikeLaw` is the law as the textbook writes it: the two
states (:func:`contact_states`), one step through any event (propagate, watch the sign of the
force or the gap, locate the root, :meth:`StrikeLaw.switch`), the servo's stop. Each state is a
:class:`LinearState` (the closed-form modal solution above), :func:`crossing` finds an event
inside a step, and the law is a :class:`SwitchedSystem`: it says which state holds and how one
step is taken through any event on the way. The friction law of :mod:`.stick_slip` is built of
the same pieces. The reference march, :func:`march_step_by_step` (``method="steps"``), takes
every step in turn, as an event-driven integration is written in a textbook. The default engine
``"blocks"`` (in the private module ``simulate/_block_march.py``, which imports this module and
the laws and registers itself in :data:`MARCHES` when the package is imported) reads each state
a block of steps ahead as described above and takes only the steps that hold an event, through
an adapter of each law that holds what only it needs. Nothing here imports the engine.

Away from the tip, both give the same events and the same signals up to the rounding of the
propagation: the test suite holds them together within the bound it derives, on the ``paper``
scene struck at 0.17 m among others. Near the tip, where a strike chatters longest, its event
sequence depends on the last bits of the arithmetic, and the two marches, which round
differently, can part. Measured on the ``paper`` scene's strikes (the five materials at the
nominal preload of 0.5 N, 1 s at 8 kHz, the NumPy engine, every 25 mm from 0.02 m and at 0.38
and 0.39 m): the same sequence of contact changes at every position up to 0.38 m, their times
within 2e-12 s of each other up to 0.245 m and within 1.4e-9 s up to 0.38 m; at 0.39 m
aluminium's counts differ (58 against 56); at 0.395 m those of three materials do (brass 290
against 318, its accelerations up to 554 m/s^2 apart; aluminium 198 against 222; steel 172
against 174). Through :func:`~ebantenna.simulate.simulate` (``paper``, aluminium at 0.395 m,
seed 0) the two give 117 and 100 re-strikes, X up to 25.6 m/s^2 apart. The reference is then
no more exact than the engine: the engine started one ulp away changes the count as well
(``simulate/_block_march.py``).

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

import abc
import copy
import logging
import math
import warnings
from dataclasses import dataclass

import numpy as np
import scipy.linalg as spl

from .._validate import (
    check_bool,
    check_choice,
    check_int,
    check_nonnegative,
    check_positive,
    check_real,
    describe,
    real_array,
)
from .contact import PiecewiseSpring
from .structure import check_dof_vector, check_symmetric_matrix

__all__ = [
    "ChatterError",
    "ContactEvent",
    "StrikeLaw",
    "HertzStrikeLaw",
    "contact_states",
    "check_structure",
    "check_step",
    "check_grid",
    "check_state",
    "segment_states",
    "preload_overtravel",
    "UnilateralResponse",
    "unilateral_response",
    "mass_inverse",
    "LinearState",
    "crossing",
    "step_grid",
    "SwitchedSystem",
    "march_step_by_step",
    "MARCHES",
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
    method: str = "blocks",
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
    contact_stiffness : float or PiecewiseSpring
        Contact spring ``k_c``, N/m (> 0); or a spring whose force law is chords
        (:class:`.contact.PiecewiseSpring`, e.g. the Hertz law of
        :meth:`.contact.HertzInSeries.piecewise`), marched by :class:`HertzStrikeLaw`.
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
    method : {"blocks", "steps"}
        How the states are marched: ``"blocks"`` reads each state a block of steps ahead (the
        engine, fast); ``"steps"`` takes every step in turn (the reference,
        :func:`march_step_by_step`). The same events and, up to the rounding of the
        propagation, the same signals away from the tip; in the long chatter near the tip the
        two can find different events (the module's "Reference and engine").

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

    The reference march finds the same event, within ``time_tolerance``:

    >>> ref = unilateral_response([[1.0]], [[0.0]], 0, 1e4, base=0, approach_speed=1.0,
    ...                           duration=0.05, fs=1000.0, method="steps")
    >>> abs(ref.events[0].time - res.events[0].time) <= 2e-12
    True
    """
    M = check_symmetric_matrix("mass", mass)
    n = M.shape[0]
    K = check_symmetric_matrix("stiffness", stiffness, n)
    C = np.zeros((n, n)) if damping is None else check_symmetric_matrix("damping", damping, n)
    c = check_dof_vector("contact", contact, n)
    r = check_dof_vector("base", base, n)
    o = c if output is None else check_dof_vector("output", output, n)
    spring = contact_stiffness if isinstance(contact_stiffness, PiecewiseSpring) else None
    kc = spring.slopes[0] if spring else check_positive("contact_stiffness", contact_stiffness)
    v0 = check_positive("approach_speed", approach_speed)
    T = check_positive("duration", duration)
    fs = check_positive("fs", fs)
    F0 = check_nonnegative("preload", preload)
    max_events = check_int("max_events", max_events, minimum=1)
    check_choice("on_max_events", on_max_events, ("raise", "warn"))
    xtol = check_positive("time_tolerance", time_tolerance)
    check_choice("method", method, tuple(MARCHES))
    Minv = mass_inverse(M)
    if np.linalg.eigvalsh(K).min() < -1e-10 * max(1.0, np.abs(K).max()):
        raise ValueError("stiffness must be positive semidefinite")

    options = dict(max_events=max_events, on_max_events=on_max_events, time_tolerance=xtol,
                   return_states=return_states)  # fmt: skip
    law, grid, overtravel = strike_law((Minv, K, C, c, r, o), spring or kc, F0, v0, fs, T,
                                        options)  # fmt: skip
    x, state = law.first_touch(v0)
    MARCHES[method](law, x, state, grid[3])
    logger.debug("unilateral strike: %d events, %d steps of %.3g s", len(law.events), grid[3],
                 law.h)  # fmt: skip
    return UnilateralResponse(
        np.arange(grid[2]) / fs, law.acc, law.force, tuple(law.events), law.stop_time,
        overtravel, law.bilateral_from, law.trajectory,
    )  # fmt: skip


def mass_inverse(mass: np.ndarray) -> np.ndarray:
    """:math:`M^{-1}` of a symmetric mass matrix, through its Cholesky factor; raise a
    ``ValueError`` naming ``mass`` when it is not positive definite.

    Examples
    --------
    >>> mass_inverse(np.array([[2.0, 0.0], [0.0, 4.0]]))
    array([[0.5 , 0.  ],
           [0.  , 0.25]])
    """
    try:
        L = np.linalg.cholesky(mass)
    except np.linalg.LinAlgError:
        raise ValueError("mass must be positive definite") from None
    return spl.cho_solve((L, True), np.eye(mass.shape[0]))


def strike_law(structure, spring, F0, v0, fs, T, options):
    """The law of a strike, its step grid and the overtravel, for a linear spring (a float) or
    chords (:class:`.contact.PiecewiseSpring`). Takes checked values."""
    Minv, K, C, c, r, o = structure
    if not isinstance(spring, PiecewiseSpring):
        overtravel = preload_overtravel(K, c, spring, F0)
        free, closed, pen = contact_states(Minv, K, C, c, spring, o)
        grid = step_grid([free, closed], fs, T, STEPS_PER_PERIOD)
        return StrikeLaw(free, closed, pen, r, overtravel / v0, grid, **options), grid, overtravel
    # the overtravel from the chords' own p(F0) (a node: the law's, exactly)
    secant = F0 / spring.approach_at(F0) if F0 > 0 else float(spring.slopes[0])
    overtravel = preload_overtravel(K, c, secant, F0)
    free, segments, pen = segment_states(Minv, K, C, c, spring, o)
    grid = step_grid([free, *segments], fs, T, STEPS_PER_PERIOD)
    law = HertzStrikeLaw(free, segments, pen, r, overtravel / v0, grid, spring, **options)
    return law, grid, overtravel


def preload_overtravel(K, c, contact_stiffness: float, preload: float) -> float:
    """The servo's travel past the first touch that leaves the contact carrying ``preload``.

    ``s_stop = F0 (1/k_c + c @ K^-1 @ c)``: the contact spring in series with the structure's
    static flexibility at the contact.

    Parameters
    ----------
    K : array of shape (n, n)
        The structure's stiffness without the contact, symmetric.
    c : array of shape (n,)
        The contact point's displacement toward the object per unit coordinate.
    contact_stiffness : float
        ``k_c``, N/m (> 0).
    preload : float
        ``F0``, N (>= 0); 0 stops the servo at the first touch.

    Examples
    --------
    >>> preload_overtravel(np.array([[100.0]]), np.array([1.0]), 100.0, 1.0)  # 1 N on 50 N/m, m
    0.02
    """
    K = check_symmetric_matrix("K", K)
    c = check_dof_vector("c", c, K.shape[0])
    contact_stiffness = check_positive("contact_stiffness", contact_stiffness)
    preload = check_nonnegative("preload", preload)
    if preload == 0:
        return 0.0
    try:
        flex = float(c @ np.linalg.solve(K, c))
    except np.linalg.LinAlgError:
        flex = math.inf
    if not (math.isfinite(flex) and flex > 0):
        raise ValueError(
            "preload > 0 needs a structure that resists a static load at the contact "
            "(stiffness is singular there: a free rigid-body motion); give preload=0"
        )
    return preload * (1 / contact_stiffness + flex)


def state_matrix(Minv, K, C, c, contact_stiffness: float, closed: bool) -> np.ndarray:
    """The first-order system of ``x = (q, q', s, s')`` with the contact open or closed.

    ``q' = q'``, ``M q'' = -(K + k_c c c^T) q - C q' - k_c c s`` when closed (without the
    ``k_c`` terms when open), ``s' = s'`` and ``s'' = 0`` (the servo at constant speed; its
    stop is an event). Takes checked values.

    Examples
    --------
    One mass of 1 kg on a 100 N/m spring and a 2 N s/m dashpot, touching a 300 N/m contact:

    >>> state_matrix(np.eye(1), np.array([[100.0]]), np.array([[2.0]]), np.ones(1), 300.0, True)
    array([[   0.,    1.,    0.,    0.],
           [-400.,   -2., -300.,    0.],
           [   0.,    0.,    0.,    1.],
           [   0.,    0.,    0.,    0.]])
    """
    n = K.shape[0]
    A = np.zeros((2 * n + 2, 2 * n + 2))
    A[:n, n : 2 * n] = np.eye(n)
    Kc = K + contact_stiffness * np.outer(c, c) if closed else K
    A[n : 2 * n, :n] = -Minv @ Kc
    A[n : 2 * n, n : 2 * n] = -Minv @ C
    if closed:
        A[n : 2 * n, 2 * n] = -contact_stiffness * (Minv @ c)
    A[2 * n, 2 * n + 1] = 1.0
    return A


def check_structure(Minv, K, C, c, output):
    """``(Minv, K, C, c, output)`` of a contact's states, checked: ``K`` and ``C`` symmetric,
    ``Minv`` finite of the same size, ``c`` and ``output`` vectors of that length (or DOF
    indices); raise a ``ValueError`` naming the first that is not."""
    K = check_symmetric_matrix("K", K)
    n = K.shape[0]
    C = check_symmetric_matrix("C", C, n)
    Minv = np.asarray(Minv, dtype=float)
    if Minv.shape != (n, n) or not np.all(np.isfinite(Minv)):
        raise ValueError(f"Minv must be a finite {n} x {n} matrix, got shape {Minv.shape}")
    return Minv, K, C, check_dof_vector("c", c, n), check_dof_vector("output", output, n)


def contact_states(Minv, K, C, c, contact_stiffness: float, output):
    """The two linear states, ``(free, closed, pen)``, with what each watches and records.

    The free state watches the gap ``-p`` and records zero force; the closed state watches and
    records the contact force ``k_c p``. Both record the acceleration at ``output``. ``pen``
    reads the penetration ``p = pen @ x``.

    Parameters
    ----------
    Minv : array of shape (n, n)
        The inverse of the mass matrix (:func:`mass_inverse`).
    K, C : array of shape (n, n)
        Stiffness and viscous damping without the contact, symmetric.
    c, output : array of shape (n,)
        The contact point's displacement toward the object, and the accelerometer's, per unit
        coordinate.
    contact_stiffness : float
        ``k_c``, N/m (> 0).
    """
    Minv, K, C, c, output = check_structure(Minv, K, C, c, output)
    contact_stiffness = check_positive("contact_stiffness", contact_stiffness)
    n = K.shape[0]
    pen = np.zeros(2 * n + 2)  # p = pen @ x
    pen[:n], pen[2 * n] = c, 1.0
    A_free = state_matrix(Minv, K, C, c, contact_stiffness, closed=False)
    A_closed = state_matrix(Minv, K, C, c, contact_stiffness, closed=True)
    kp = contact_stiffness * pen
    free = LinearState(A_free, n, -pen, np.zeros(2 * n + 2), output @ A_free[n : 2 * n])
    closed = LinearState(A_closed, n, kp, kp, output @ A_closed[n : 2 * n])
    return free, closed, pen


# ---------------------------------------- one linear state, and the march through the states
#: Most iterations of the event root finder (bisection alone needs log2(step / tolerance)).
_MAX_ROOT_STEPS = 200


def step_grid(states, fs: float, duration: float, steps_per_period: int):
    """Lay out the steps on which ``states`` are propagated and watched.

    The step is at most a ``steps_per_period``-th of the fastest state's shortest period and
    divides the output sample interval ``1 / fs`` into ``sub`` whole steps. Returns ``(h, sub,
    n_samples, n_steps)``: the step (s), steps per output sample, output samples over
    ``duration`` (both ends included) and steps in all.

    Examples
    --------
    One mass of 1 kg on 100 N/m pressed by a 300 N/m contact rings at 20 rad/s: 16 steps of its
    period, ``pi / 160`` s, are longer than the sample interval of 1 ms, which is the step.

    >>> free, closed, _ = contact_states(np.eye(1), np.array([[100.0]]), np.zeros((1, 1)),
    ...                                  np.ones(1), 300.0, np.ones(1))
    >>> step_grid([free, closed], fs=1000.0, duration=0.05, steps_per_period=16)
    (0.001, 1, 51, 50)
    """
    states = list(states)
    if not states or not all(isinstance(st, LinearState) for st in states):
        raise TypeError("states must be a non-empty sequence of LinearState")
    fs = check_positive("fs", fs)
    duration = check_positive("duration", duration)
    steps_per_period = check_int("steps_per_period", steps_per_period, minimum=1)
    fastest = max(float(np.abs(st.lam).max()) for st in states)
    h_max = 2 * math.pi / (steps_per_period * fastest) if fastest > 0 else 1 / fs
    sub = max(1, math.ceil(1 / (fs * h_max)))
    h = 1 / (fs * sub)
    n_samples = int(math.floor(duration * fs + 1e-9)) + 1
    n_steps = (n_samples - 1) * sub
    return h, sub, n_samples, n_steps


class LinearState:
    """One of the two linear states: exact propagator, and what is monitored and recorded in it.

    The state ``x = (y, s, s')`` with ``y = (q, q')`` obeys ``y' = A y + f s``: ``s(t) = s + s' t``
    is the drive, a load or base motion along ``f`` that grows linearly in time (a strike: the
    servo's travel at its speed ``s'``; stick-slip: the friction's constant load, ``s = 1``,
    ``s' = 0``). With ``G = A^-1 f``
    and ``H = A^-1 G`` the motion is ``y(t) = e^(At) (y + G s + H s') - G s(t) - H s'``, and
    ``e^(At) = V e^(Lambda t) V^-1`` from the eigenvectors of ``A``. Where ``A`` is defective or
    singular with a load on it (a rigid-body motion), the matrix exponential is used instead.

    Three linear functions of the state are read along the motion (``rows``: the monitored
    quantity, the acceleration and the contact force). In modal coordinates ``z = V^-1 (y + G s
    + H s')`` each of them is ``Re(sum_k w_k e^(lambda_k t)) + a (s + s' t) + b s'``
    (:meth:`curve` for the monitored one).
    """

    def __init__(self, A, n, monitor, force, accel):
        n = check_int("n", n, minimum=1)
        if np.shape(A) != (2 * n + 2, 2 * n + 2) or not np.all(np.isfinite(A)):
            raise ValueError(f"A must be a finite {2 * n + 2} x {2 * n + 2} matrix (n = {n}), "
                             f"got shape {np.shape(A)}")
        self.A, self.n = A, n
        Ay, f = A[: 2 * n, : 2 * n], A[: 2 * n, 2 * n]
        self.eigen = False
        with np.errstate(all="ignore"):
            lam, V = np.linalg.eig(Ay)
            self.lam = lam  # the state's eigenvalues, whichever propagator it uses
            if np.linalg.cond(V) < 1e8:
                Vinv = np.linalg.inv(V)
                G = H = np.zeros(2 * n)
                ok = True
                if np.any(f):
                    try:
                        G = np.linalg.solve(Ay, f)
                        H = np.linalg.solve(Ay, G)
                    except np.linalg.LinAlgError:
                        ok = False
                if ok and np.all(np.isfinite(G)) and np.all(np.isfinite(H)):
                    self.eigen = True
                    self.V, self.Vinv, self.G, self.H = V, Vinv, G, H
        self._read(monitor, force, accel)

    def watching(self, monitor, force, accel) -> LinearState:
        """The same state with other rows read along the motion; the decomposition of ``A`` is
        shared, not computed again."""
        twin = copy.copy(self)
        twin._read(monitor, force, accel)
        return twin

    def _read(self, monitor, force, accel):
        """Set the rows read along the motion, and their weights on the modes."""
        for name, row in (("monitor", monitor), ("force", force), ("accel", accel)):
            if np.shape(row) != (2 * self.n + 2,) or not np.all(np.isfinite(row)):
                raise ValueError(f"{name} must be a finite row of length {2 * self.n + 2}, got "
                                 f"shape {np.shape(row)}")
        self.monitor = monitor
        self.rows = np.stack([monitor, accel, force])
        if self.eigen:
            m = 2 * self.n
            ry = self.rows[:, :m]
            self.row_modes = ry @ self.V  # (3, 2n): each row's weight on each mode
            self.row_s = self.rows[:, m] - ry @ self.G  # ... on the drive s(t)
            self.row_speed = self.rows[:, m + 1] - ry @ self.H  # ... on its speed s'

    def modal(self, x):
        """The modal coordinates ``z`` of the state ``x`` (None where the propagator is
        ``expm``).

        Parameters
        ----------
        x : array of shape (2 n + 2,)
            A state ``(q, q', s, s')``, finite.

        Examples
        --------
        >>> free, closed, _ = contact_states(np.eye(1), np.array([[100.0]]), np.zeros((1, 1)),
        ...                                  np.ones(1), 300.0, np.ones(1))
        >>> closed.modal([0.0, 1.0, 0.0, 0.0]).shape
        (2,)
        """
        return self._modal(self._checked(x))

    def at(self, x, z, tau):
        """The state ``tau`` after ``x`` (``z``: its :meth:`modal`).

        Parameters
        ----------
        x : array of shape (2 n + 2,)
            The state at the start, finite.
        z : ndarray of shape (2 n,) or None
            ``modal(x)``, computed once for several ``tau`` (None for a state propagated by
            ``expm``).
        tau : float
            Elapsed time, s (>= 0: a state is propagated forward).
        """
        x = self._checked(x)
        return self._at(x, self._checked_modal(z), check_nonnegative("tau", tau))

    def step(self, x, tau):
        """The state ``tau`` (s, >= 0) after the state ``x`` (finite, of length ``2 n + 2``).

        Examples
        --------
        1 kg on 100 N/m pressed by a 300 N/m contact, released at 1 m/s: a quarter period of
        its 20 rad/s later it is at rest, 1/20 m in:

        >>> free, closed, _ = contact_states(np.eye(1), np.array([[100.0]]), np.zeros((1, 1)),
        ...                                  np.ones(1), 300.0, np.ones(1))
        >>> np.round(closed.step([0.0, 1.0, 0.0, 0.0], np.pi / 40), 12) + 0.0
        array([0.05, 0.  , 0.  , 0.  ])
        """
        return self._step(self._checked(x), check_nonnegative("tau", tau))

    def curve(self, x, z):
        """The monitored quantity along the motion from ``x`` (``z``: its :meth:`modal`) and
        its rate, as a function of elapsed time (its argument is not checked: the function is
        what :func:`crossing` evaluates)."""
        x = self._checked(x)
        return self._curve(x, self._checked_modal(z))

    def _checked(self, x) -> np.ndarray:
        """``x`` as a float state vector of this state's size; raise naming ``x`` otherwise."""
        x = real_array("x", x)
        check_state("x", x, 2 * self.n + 2)
        return x

    def _checked_modal(self, z):
        """``z`` as :meth:`modal` gives it; raise naming ``z`` otherwise."""
        if not self.eigen:
            if z is not None:
                raise ValueError("z must be None for a state propagated by expm (its modal(x) "
                                 f"is None), got {type(z).__name__}")
            return None
        shape = np.shape(z) if isinstance(z, np.ndarray) else None
        if shape != (2 * self.n,) or z.dtype.kind not in "fc" or not np.all(np.isfinite(z)):
            raise ValueError(f"z must be modal(x): a finite vector of length {2 * self.n}, got "
                             f"{describe(z) if shape is None else f'shape {shape}'}")
        return z

    # the unchecked propagation, which the marches call on states they built
    def _modal(self, x):
        if not self.eigen:
            return None
        m = 2 * self.n
        return self.Vinv @ (x[:m] + self.G * x[m] + self.H * x[m + 1])

    def _at(self, x, z, tau):
        if tau == 0:
            return x
        if not self.eigen:
            return spl.expm(self.A * tau) @ x
        m = 2 * self.n
        s, sigma = x[m], x[m + 1]
        out = np.empty_like(x)
        out[:m] = (self.V @ (np.exp(self.lam * tau) * z)).real - self.G * (s + sigma * tau)
        out[:m] -= self.H * sigma
        out[m], out[m + 1] = s + sigma * tau, sigma
        return out

    def _step(self, x, tau):
        return self._at(x, self._modal(x), tau)

    def _curve(self, x, z):
        if not self.eigen:

            def value_and_rate(tau):
                xt = self._step(x, tau)
                return float(self.monitor @ xt), float(self.monitor @ (self.A @ xt))

            return value_and_rate
        m = 2 * self.n
        s, sigma = x[m], x[m + 1]
        w, lam = self.row_modes[0] * z, self.lam
        a, b = self.row_s[0], self.row_speed[0]

        def value_and_rate(tau):
            e = w * np.exp(lam * tau)
            return float(e.sum().real + a * (s + sigma * tau) + b * sigma), float(
                (e @ lam).real + a * sigma
            )

        return value_and_rate


def crossing(curve, span: float, xtol: float, ga: float, gb: float) -> float:
    """When the monitored quantity ``g``, ``ga > 0`` at 0 and ``gb <= 0`` at ``span``, reaches
    zero: the far end ``b`` of a bracket ``[a, b]`` with ``g(a) > 0 >= g(b)`` and ``b - a <=
    xtol``, so that the state entered starts admissible.

    Newton's method on ``g`` and its rate, kept inside the bracket by bisection where a Newton
    step would leave it or does not halve the last one (the safeguarded iteration ``rtsafe``,
    W. H. Press et al., *Numerical Recipes*, 3rd ed., Cambridge University Press, 2007, section
    9.4). Near the root a step just past it closes the bracket from the other side.

    Parameters
    ----------
    curve : callable
        ``curve(tau) -> (g, dg/dtau)``, as :meth:`LinearState.curve` gives it.
    span : float
        The step's length, s (> 0).
    xtol : float
        Width of the final bracket, s (> 0).
    ga, gb : float
        ``g(0) > 0`` and ``g(span) <= 0``, finite.

    Examples
    --------
    ``g = 1 - tau`` reaches zero at 1; the root is bracketed from above within ``xtol``:

    >>> b = crossing(lambda tau: (1.0 - tau, -1.0), 2.0, 1e-9, 1.0, -1.0)
    >>> 1.0 <= b <= 1.0 + 1e-9
    True
    """
    if not callable(curve):
        raise TypeError(f"curve must be a function of elapsed time (LinearState.curve's), got "
                        f"{type(curve).__name__}")
    span = check_positive("span", span)
    xtol = check_positive("xtol", xtol)
    if not check_real("ga", ga) > 0:
        raise ValueError(f"ga must be > 0 (the monitored quantity at the step's start), got {ga!r}")
    if not check_real("gb", gb) <= 0:
        raise ValueError(f"gb must be <= 0 (the monitored quantity at the step's end), got {gb!r}")
    return _crossing(curve, span, xtol, float(ga), float(gb))


def _crossing(curve, span, xtol, ga, gb):
    """:func:`crossing` of checked values, as the marches call it."""
    a, b = 0.0, span
    t = a + ga * (b - a) / (ga - gb)  # the secant through the ends
    last = span
    for _ in range(_MAX_ROOT_STEPS):
        g, rate = curve(t)
        if g > 0:
            a = t
        else:
            b = t
        if b - a <= xtol:
            return b
        step = g / rate if rate != 0 else math.inf
        new = t - step
        if not (a < new < b) or abs(step) > last / 2:
            new = (a + b) / 2  # bisection: the bracket halves
        elif abs(step) < xtol / 2:  # at the root: step just past it, to the other side
            new += math.copysign(xtol / 2, -step)
            if not a < new < b:
                new = (a + b) / 2
        last = abs(new - t)
        t = new
    return b


def check_step(t0, t1) -> None:
    """Raise a ``ValueError`` naming ``t1`` unless ``t0 <= t1``, both finite: a step of a march
    goes forward in time (or nowhere, at an event on its start)."""
    if not (math.isfinite(t0) and math.isfinite(t1) and t0 <= t1):
        raise ValueError(f"t1 must be finite and not before t0, got t0={t0!r}, t1={t1!r}")


def check_grid(grid) -> tuple:
    """``grid`` as :func:`step_grid` lays it out, ``(h, sub, n_samples, n_steps)``; raise a
    ``TypeError`` naming ``grid`` otherwise (the values are checked where they are used)."""
    if not isinstance(grid, tuple) or len(grid) != 4:
        raise TypeError(f"grid must be step_grid's (h, sub, n_samples, n_steps), got {grid!r}")
    return grid


def check_state(name: str, x, size: int) -> None:
    """Raise a ``ValueError`` naming ``name`` unless ``x`` is a finite state vector of ``size``."""
    x = real_array(name, x)
    if x.shape != (size,) or not np.all(np.isfinite(x)):
        got = f"shape {x.shape}" if x.shape != (size,) else "NaN or inf in it"
        raise ValueError(f"{name} must be a finite state vector of length {size}, got {got}")


class SwitchedSystem(abc.ABC):
    """A structure that switches between linear states at events, as a march takes it.

    A contact law subclasses it and gives :meth:`state` (the :class:`LinearState` of a state's
    key) and :meth:`advance` (one step, through any event on the way); ``_interrupts``,
    ``_interrupted_step`` and ``_moved`` have defaults that suit a law with nothing but
    its states. Along the march it records the acceleration and the force (rows 1 and 2 of each
    state) at every ``sub``-th step, and with ``n_states`` the whole state there too. What the
    engine ``"blocks"`` needs besides is in its adapters, not here.

    Parameters
    ----------
    h : float
        The step, s.
    sub : int
        Steps per output sample.
    n_samples : int
        Output samples.
    n_states : int, optional
        Size of the state vector, to record the state at every output sample.
    """

    def __init__(self, h: float, sub: int, n_samples: int, n_states: int | None = None):
        h = check_positive("h", h)
        sub = check_int("sub", sub, minimum=1)
        n_samples = check_int("n_samples", n_samples, minimum=1)
        if n_states is not None:
            n_states = check_int("n_states", n_states, minimum=1)
        self.h, self.sub = h, sub
        self.acc = np.zeros(n_samples)
        self.force = np.zeros(n_samples)
        self.trajectory = None if n_states is None else np.zeros((n_samples, n_states))

    @abc.abstractmethod
    def state(self, key) -> LinearState:
        """The linear state called ``key``."""

    @abc.abstractmethod
    def advance(self, x, key, t0: float, t1: float, crosses: bool = False):
        """The state ``(x, key)`` at ``t1`` from ``t0`` (at most one step), through any event;
        ``crosses``: an event is known to lie before ``t1``."""

    def _interrupts(self, i: int) -> bool:
        """Whether something besides the states' own motion happens within step ``i``."""
        return False

    def _interrupted_step(self, x, key, i: int):
        """Step ``i`` when ``_interrupts`` says so; a law whose ``_interrupts`` can be true
        gives its own (here, for a law with nothing but its states, an ordinary step)."""
        return self.advance(x, key, i * self.h, (i + 1) * self.h)

    def _moved(self) -> None:  # noqa: B027 - a hook that most laws leave empty
        """Called once the march has moved on from where a state was entered."""

    def _record(self, i: int, x, key) -> None:
        """Record step ``i`` if it is an output sample."""
        if i % self.sub == 0:
            k = i // self.sub
            self.acc[k], self.force[k] = self.state(key).rows[1:] @ x
            if self.trajectory is not None:
                self.trajectory[k] = x


def march_step_by_step(system: SwitchedSystem, x, key, n_steps: int):
    """The reference march: every step in turn, each through any event on the way.

    Parameters
    ----------
    system : SwitchedSystem
        The contact law; it records the output samples.
    x : ndarray
        The state vector at step 0 (already recorded).
    key
        The state that holds there.
    n_steps : int
        Steps to take.

    Returns
    -------
    tuple
        ``(x, key)`` after the last step.
    """
    if not isinstance(system, SwitchedSystem):
        raise TypeError(f"system must be a SwitchedSystem (a contact law), got "
                        f"{type(system).__name__}")
    n_steps = check_int("n_steps", n_steps, minimum=0)
    h = system.h
    for i in range(n_steps):
        if system._interrupts(i):
            x, key = system._interrupted_step(x, key, i)
        else:
            x, key = system.advance(x, key, i * h, (i + 1) * h)
        system._moved()
        system._record(i + 1, x, key)
    return x, key


#: The marches a contact law may take, by name: ``"steps"`` (the reference) and ``"blocks"``
#: (the engine, the default), which the private engine module adds when the package is imported.
MARCHES = {"steps": march_step_by_step}


class StrikeLaw(SwitchedSystem):
    """The unilateral contact's law: two states, the switching conditions, the servo's stop.

    Built by :func:`unilateral_response` from checked values; marched by
    :data:`MARCHES`. The state keys are the two :class:`LinearState`
    themselves.

    Parameters
    ----------
    free, closed : LinearState
        The contact open (watching the gap) and closed (watching the force).
    pen : ndarray of shape (2 n + 2,)
        The penetration ``p = pen @ x``.
    base : ndarray of shape (n,)
        The servo's rigid motion per metre of travel, ``r``.
    stop_time : float
        When the servo stops, s.
    grid : tuple
        :func:`step_grid` of the two states.
    max_events, on_max_events, time_tolerance, return_states
        As in :func:`unilateral_response`.
    """

    def __init__(self, free, closed, pen, base, stop_time, grid, *, max_events, on_max_events,
                 time_tolerance, return_states):  # fmt: skip
        h, sub, n_samples, _ = check_grid(grid)
        if np.ndim(base) != 1 or not np.all(np.isfinite(base)):
            raise ValueError(f"base must be a finite vector, got shape {np.shape(base)}")
        n = base.size
        for name, st in (("free", free), ("closed", closed)):
            if not isinstance(st, LinearState) or st.n != n:
                raise TypeError(f"{name} must be a LinearState of {n} coordinates (base's), got "
                                f"{type(st).__name__}")
        check_state("pen", pen, 2 * n + 2)
        stop_time = check_nonnegative("stop_time", stop_time)
        max_events = check_int("max_events", max_events, minimum=1)
        check_choice("on_max_events", on_max_events, ("raise", "warn"))
        time_tolerance = check_positive("time_tolerance", time_tolerance)
        return_states = check_bool("return_states", return_states)
        super().__init__(h, sub, n_samples, 2 * n + 2 if return_states else None)
        self.free, self.closed, self.base, self.stop_time = free, closed, base, stop_time
        self.max_events, self.on_max_events = max_events, on_max_events
        self.xtol = time_tolerance
        self.pen = pen
        self.events: list[ContactEvent] = []
        self.bilateral_from = None
        self.frozen = False  # held closed after max_events (on_max_events="warn")
        self.stopped = False

    def state(self, key):
        """The state itself (the keys are the states)."""
        return key

    def first_touch(self, approach_speed: float):
        """The state at ``t = 0``: the contact just closed, ``p = 0``, closing at ``v0``."""
        approach_speed = check_positive("approach_speed", approach_speed)
        n = self.base.size
        x = np.zeros(2 * n + 2)
        x[2 * n + 1] = approach_speed
        if self.stop_time == 0.0:
            x = self.stop_servo(x)
        self._record(0, x, self.closed)
        return x, self.closed

    def stop_servo(self, x):
        """The servo stops: its speed passes to the structure (``q' += r s'``, ``s' = 0``)."""
        n = self.base.size
        check_state("x", x, 2 * n + 2)
        x = x.copy()
        x[n : 2 * n] += self.base * x[2 * n + 1]
        x[2 * n + 1] = 0.0
        self.stopped = True
        return x

    def _interrupts(self, i):
        """The servo stops within step ``i``."""
        return not self.stopped and self.stop_time < (i + 1) * self.h

    def _interrupted_step(self, x, st, i):
        """Step ``i`` with the servo's stop inside: up to it, stop, and on to the step's end."""
        x, st = self.advance(x, st, i * self.h, self.stop_time)
        x = self.stop_servo(x)
        return self.advance(x, st, self.stop_time, (i + 1) * self.h)

    def _watched(self, st) -> bool:
        """Whether ``st`` can end (not a contact held closed after ``max_events``)."""
        return not (self.frozen and st is self.closed)

    def switch(self, st, x, t):
        """The switching law at an event at time ``t``: enter the other state, and count."""
        if st is not self.free and st is not self.closed:
            raise ValueError("st must be the law's free or closed state (its attribute free or "
                             "closed)")
        entering = self.free if st is self.closed else self.closed
        kind = "contact" if entering is self.closed else "separation"
        self.events.append(ContactEvent(t, kind, float(self.pen @ (st.A @ x))))
        if len(self.events) >= self.max_events and not self.frozen:
            self._too_many_events(t)
        if self.frozen and entering is self.closed and self.bilateral_from is None:
            self.bilateral_from = t
        return entering

    def _too_many_events(self, t):
        """``max_events`` reached at ``t``: raise, or warn and hold the next contact closed."""
        if self.on_max_events == "raise":
            raise ChatterError(
                f"more than max_events={self.max_events} contact events by t={t:.6g} s: the "
                "probe chatters or rests on the object without preload; raise max_events, give "
                "a preload, or use on_max_events='warn' to hold the contact from then on"
            )
        warnings.warn(
            f"max_events={self.max_events} reached at t={t:.6g} s (chatter); the contact is "
            "held closed from the next contact on",
            RuntimeWarning,
            stacklevel=2,
        )
        self.frozen = True

    def advance(self, x, st, t0, t1, crosses=False):
        """Propagate from ``t0`` to ``t1`` (at most one step) through any events on the way.

        The state's monitor (the force when closed, the gap when open) is watched: where it
        falls to zero, :func:`crossing` finds when, and :meth:`switch` enters the
        other state there. ``crosses``: the monitor is known to reach zero by ``t1``.
        """
        check_step(t0, t1)
        while True:
            if not crosses:
                x1 = st._step(x, t1 - t0)
                if not self._watched(st) or st.monitor @ x1 > 0:
                    return x1, st
            z = st._modal(x)
            g = st._curve(x, z)
            span = t1 - t0
            end = g(span)[0]
            if end > 0:  # a graze that rounding decides: the curve stays in this state
                return st._at(x, z, span), st
            crosses = False
            start = float(st.monitor @ x)
            if start <= 0:  # already at the boundary (a grazing touch): switch at once
                tau = 0.0
            else:
                tau = _crossing(g, span, self.xtol, start, end)
            x = st._at(x, z, tau)
            t0 = t0 + tau
            st = self.switch(st, x, t0)


def segment_states(Minv, K, C, c, spring, output):
    """The free state and one closed state per chord of ``spring``, ``(free, segments, pen)``.

    In the closed state of chord ``j`` the force is ``k_j (p - e_j)`` (slope ``k_j``, offset
    ``e_j``): the linear contact's state with the spring ``k_j`` and the servo's coordinate
    shifted by ``e_j``. :class:`HertzStrikeLaw` keeps ``x`` in the coordinates of the state
    that holds (``s - e_j``), so each state watches and records the true force ``k_j p~``.
    The other parameters are those of :func:`contact_states`.
    """
    if not isinstance(spring, PiecewiseSpring):
        raise TypeError(f"spring must be a PiecewiseSpring, got {type(spring).__name__}")
    Minv, K, C, c, output = check_structure(Minv, K, C, c, output)
    n = K.shape[0]
    free, _, pen = contact_states(Minv, K, C, c, float(spring.slopes[0]), output)
    segments = []
    for k in spring.slopes:
        A = state_matrix(Minv, K, C, c, float(k), closed=True)
        kp = float(k) * pen
        segments.append(LinearState(A, n, kp, kp, output @ A[n : 2 * n]))
    return free, segments, pen


class HertzStrikeLaw(StrikeLaw):
    """The strike through a contact whose force law is chords (:class:`.contact.PiecewiseSpring`).

    Each chord is a linear state (:func:`segment_states`), propagated exactly as the linear
    contact's; the state also ends where the force reaches the chord's upper node (the next
    chord takes over) or, above the first chord, its lower node (the previous one does). The
    force is continuous at a node, so a change of chord changes the equations only. Contact and
    separation are the first chord's lower end and the gap's closing, as in :class:`StrikeLaw`;
    only they count toward ``max_events``. The error of the force law is the spring's
    ``bound`` (up to its last node); the integration of the chords adds only the event
    tolerance and rounding.

    Parameters
    ----------
    free : LinearState
        The contact open.
    segments : list of LinearState
        The contact closed on each chord.
    pen, base, stop_time, grid
        As in :class:`StrikeLaw`.
    spring : PiecewiseSpring
        The chords.
    max_events, on_max_events, time_tolerance, return_states
        As in :func:`unilateral_response`.
    """

    #: Most changes of chord in one step before the march gives up (a node grazed by rounding).
    MAX_CHORD_CHANGES = 10_000

    def __init__(self, free, segments, pen, base, stop_time, grid, spring, **options):
        if not isinstance(spring, PiecewiseSpring):
            raise TypeError(f"spring must be a PiecewiseSpring, got {type(spring).__name__}")
        if not isinstance(segments, list | tuple) or len(segments) != len(spring.slopes) or not all(
                isinstance(st, LinearState) for st in segments):
            raise TypeError(f"segments must be a list of LinearState, one per chord of spring "
                            f"({len(spring.slopes)})")
        super().__init__(free, segments[0], pen, base, stop_time, grid, **options)
        self.segments = segments
        self.index = {id(st): j for j, st in enumerate(segments)}
        self.offsets = np.asarray(spring.offsets, float)
        self.nodes = np.append(spring.forces[:-1], math.inf)  # the last chord continues
        self.chord_changes = 0

    def _limits(self, st):
        """The forces ``(lower, upper)`` between which the chord of ``st`` holds, N."""
        j = self.index[id(st)]
        lower = -math.inf if (j == 0 and self.frozen) else float(self.nodes[j])
        return lower, float(self.nodes[j + 1])

    def _shift(self, st) -> float:
        """The offset ``e_j`` of the state's coordinates, m (0 when free)."""
        return 0.0 if st is self.free else float(self.offsets[self.index[id(st)]])

    def _first_exit(self, st, x, z, span, fresh):
        """The first node (or the gap's closing) reached within ``span`` after ``x`` (``z``:
        ``st.modal(x)``): ``(tau, x there, "up" or "down")``, or None. ``fresh``: ``st`` was
        entered at ``x``."""
        curve = st._curve(x, z)
        if st is self.free:
            sides = (("up", 0.0, 1.0),)  # the gap, watched as it is
        else:
            lower, upper = self._limits(st)
            sides = (("down", lower, 1.0), ("up", upper, -1.0))
        found = None
        ends = {}  # the curve at the step's start and end, read once for both sides

        def read(tau):
            if tau not in ends:
                ends[tau] = curve(tau)[0]
            return ends[tau]

        for which, node, sign in sides:
            if math.isinf(node):
                continue

            def g(tau, node=node, sign=sign):
                value, rate = curve(tau)
                return sign * (value - node), sign * rate

            end = sign * (read(span) - node)
            if end > 0:
                continue
            start = sign * (read(0.0) - node)
            if start <= 0 and not fresh:
                tau = 0.0
            else:
                tau = _crossing(g, span, self.xtol, max(start, np.finfo(float).tiny), end)
            if found is None or tau < found[0]:
                found = (tau, which)
        return None if found is None else (found[0], st._at(x, z, found[0]), found[1])

    def _change(self, st, x, t, which):
        """Enter the next state at an event at ``t``: ``(state, x)``, another chord (``x``
        shifted to its coordinates) or contact and separation (:meth:`StrikeLaw.switch`)."""
        j = self.index.get(id(st))
        if st is self.free or (j == 0 and which == "down"):
            return self.switch(st, x, t), x
        self.chord_changes += 1
        if self.chord_changes > self.MAX_CHORD_CHANGES * (len(self.events) + 1):
            raise ChatterError(f"the force keeps crossing a node of the contact law at t={t:.6g} s")
        new = self.segments[j + 1 if which == "up" else j - 1]
        x = x.copy()
        x[2 * self.base.size] += self._shift(st) - self._shift(new)
        return new, x

    def advance(self, x, st, t0, t1, crosses=False):
        """Propagate from ``t0`` to ``t1`` (at most one step) through any events on the way:
        the first node or gap reached (``_first_exit``), then the state it enters."""
        check_step(t0, t1)
        fresh = False
        while True:
            z = st._modal(x)
            found = self._first_exit(st, x, z, t1 - t0, fresh)
            if found is None:
                return st._at(x, z, t1 - t0), st
            tau, x, which = found
            t0 += tau
            st, x = self._change(st, x, t0, which)
            fresh = True

    def _record(self, i, x, key):
        """Record step ``i`` as :class:`StrikeLaw` does, the state in true coordinates."""
        super()._record(i, x, key)
        if self.trajectory is not None and i % self.sub == 0:
            self.trajectory[i // self.sub, 2 * self.base.size] += self._shift(key)
