"""One linear state of a structure on a moving base, propagated exactly, and the march through
the states.

:func:`.unilateral.unilateral_response` switches between two such states, the contact closed and
open. Within a state the motion is the closed-form modal solution (:class:`LinearState`), and
:func:`crossing` finds an event inside a step.

**Marching through the states.** A contact law (:class:`.unilateral.StrikeLaw`,
:class:`.stick_slip.StickSlipLaw`) is a :class:`SwitchedSystem`: it says which state holds and
how one step is taken through any event on the way. :func:`march_step_by_step` is the reference:
it takes every step in turn, as an event-driven integration is written in a textbook. The
engine ``"blocks"`` (the default, in the private module ``simulate/_block_march.py``, which
imports this module and the laws and registers itself in :data:`MARCHES` when the package is
imported) reads each state a block of steps ahead and takes only the steps that hold an event
one at a time, through an adapter of each law that holds what only it needs; both give the same
events, and the same signals up to the rounding of the propagation (the test suite holds them
together). Nothing here imports the engine.
"""

from __future__ import annotations

import abc
import copy
import math

import numpy as np
import scipy.linalg as spl

__all__ = ["LinearState", "crossing", "step_grid", "SwitchedSystem", "march_step_by_step",
           "MARCHES"]  # fmt: skip

#: Most iterations of the event root finder (bisection alone needs log2(step / tolerance)).
_MAX_ROOT_STEPS = 200


def step_grid(states, fs: float, duration: float, steps_per_period: int):
    """Lay out the steps on which ``states`` are propagated and watched.

    The step is at most a ``steps_per_period``-th of the fastest state's shortest period and
    divides the output sample interval ``1 / fs`` into ``sub`` whole steps. Returns ``(h, sub,
    n_samples, n_steps)``: the step (s), steps per output sample, output samples over
    ``duration`` (both ends included) and steps in all.
    """
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
        self.monitor = monitor
        self.rows = np.stack([monitor, accel, force])
        if self.eigen:
            m = 2 * self.n
            ry = self.rows[:, :m]
            self.row_modes = ry @ self.V  # (3, 2n): each row's weight on each mode
            self.row_s = self.rows[:, m] - ry @ self.G  # ... on the drive s(t)
            self.row_speed = self.rows[:, m + 1] - ry @ self.H  # ... on its speed s'

    def modal(self, x):
        """The modal coordinates ``z`` of ``x`` (None where the propagator is ``expm``)."""
        if not self.eigen:
            return None
        m = 2 * self.n
        return self.Vinv @ (x[:m] + self.G * x[m] + self.H * x[m + 1])

    def at(self, x, z, tau):
        """The state ``tau`` after ``x`` (``z``: its :meth:`modal`)."""
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

    def step(self, x, tau):
        """The state ``tau`` after ``x``."""
        return self.at(x, self.modal(x), tau)

    def curve(self, x, z):
        """The monitored quantity along the motion from ``x`` (``z``: its :meth:`modal`) and
        its rate, as a function of elapsed time."""
        if not self.eigen:

            def value_and_rate(tau):
                xt = self.step(x, tau)
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
    """
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


class SwitchedSystem(abc.ABC):
    """A structure that switches between linear states at events, as a march takes it.

    A contact law subclasses it and gives :meth:`state` (the :class:`LinearState` of a state's
    key) and :meth:`advance` (one step, through any event on the way); :meth:`interrupts`,
    :meth:`interrupted_step` and :meth:`moved` have defaults that suit a law with nothing but
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

    def interrupts(self, i: int) -> bool:
        """Whether something besides the states' own motion happens within step ``i``."""
        return False

    def interrupted_step(self, x, key, i: int):
        """Step ``i`` when :meth:`interrupts` says so; a law whose :meth:`interrupts` can be true
        gives its own (here, for a law with nothing but its states, an ordinary step)."""
        return self.advance(x, key, i * self.h, (i + 1) * self.h)

    def moved(self) -> None:  # noqa: B027 - a hook that most laws leave empty
        """Called once the march has moved on from where a state was entered."""

    def record(self, i: int, x, key) -> None:
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
    h = system.h
    for i in range(n_steps):
        if system.interrupts(i):
            x, key = system.interrupted_step(x, key, i)
        else:
            x, key = system.advance(x, key, i * h, (i + 1) * h)
        system.moved()
        system.record(i + 1, x, key)
    return x, key


#: The marches a contact law may take, by name: ``"steps"`` (the reference) and ``"blocks"``
#: (the engine, the default), which the private engine module adds when the package is imported.
MARCHES = {"steps": march_step_by_step}
