"""The engine of the contact laws' march: read each linear state a block of steps ahead.

:func:`.unilateral.march_step_by_step` takes every step in turn. Within one state the motion
is a sum of modes: each row read along it (the monitored quantity, the acceleration, the force)
is ``Re(sum_k w_k e^(lambda_k t)) + a (s + s' t) + b s'`` with ``w = row V * z`` for the modal
coordinates ``z`` (:class:`.unilateral.LinearState`), so a block of ``m`` steps costs one
``(m, 2n)`` by ``(2n, 3)`` product, not ``m`` state propagations (:func:`readings`). Whether an
event lies ahead is read from those values (:func:`read_ahead`); where a bound shows that no
event can happen over a longer span (a settled contact, :func:`stays_positive`), the span is
read at the output samples only (:func:`samples`). Only the step that holds an event is taken
through the law's ``advance``. Away from the tip it finds the same events as the reference and,
up to the rounding of the propagation, the same signals; near the tip, where a strike chatters,
the event sequence follows the last bits and the two marches can part (see
:mod:`~ebantenna.simulate.unilateral`, "Reference and engine"). It is the default because it
costs about one matrix product per block instead of a propagation per step.

Each state carries the engine's tables in its attribute ``blocks`` (:class:`BlockTables`, set by
:func:`prepare_blocks` when the march starts: the reference march needs none). What the engine
asks of a law beyond the reference's :class:`.unilateral.SwitchedSystem` is in the law's
adapter here (:class:`LawBlocks` and its subclasses, one per law): ``states`` (the states to
prepare), ``horizon`` (how far a state may be read ahead), ``quiet`` (no event within a span,
usually :func:`stays_positive`), ``ends`` (where a state ends, read on the block's values) and
``record_block`` (record the samples of a block). This module imports the laws; they import
nothing from it. Importing it adds ``"blocks"`` to :data:`.unilateral.MARCHES` (the package
does, when it is imported).

**The compiled march.** With the ``fast`` extra (numba), :func:`march_in_blocks` marches a strike
(:class:`.unilateral.StrikeLaw` or :class:`.unilateral.HertzStrikeLaw`, every state modal, no
states recorded: :func:`compiled_fits`) with :func:`march_compiled`, the same algorithm in
:mod:`ebantenna.simulate._march_numba` in one compiled call. The choice is that of the SVM and
the MLP (:mod:`ebantenna._engines`): ``EBANTENNA_ENGINE=auto`` (the default) takes it when
numba imports and passes :func:`compiled_status`'s check, says once why not (a logged INFO when
numba is not installed, a :class:`RuntimeWarning` when it fails), ``numpy`` never takes it,
``compiled`` requires it. It finds the same events, each within the root finder's tolerance of
this engine's, and the signals within the rounding of the propagation carried by the conditioning
(its sums run in another order); near the tip, where a strike chatters and the NumPy march started
one ulp away already moves the re-strikes and can change their number, it is held to what one
ulp makes. A strike that reaches ``max_events`` (or changes chord too often) is marched here
from the start, so that the law raises or warns as it says.
"""

from __future__ import annotations

import abc
import functools
import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as spl

from .stick_slip import StickSlipLaw
from .unilateral import MARCHES, HertzStrikeLaw, StrikeLaw

__all__ = ["LONG_BLOCKS", "BLOCK_ELEMENTS", "BlockTables", "prepare_blocks", "readings", "samples",
           "read_ahead", "swing", "stays_positive", "after", "LawBlocks", "StrikeBlocks",
           "HertzStrikeBlocks", "StickSlipBlocks", "adapter", "compiled_status", "compiled_fits",
           "march_compiled", "march_in_blocks"]  # fmt: skip

#: Where the contact provably keeps its state, up to this many blocks are read at once.
LONG_BLOCKS = 32
#: Most states propagated at once in one block (bounds the memory of the stacked powers).
BLOCK_ELEMENTS = 2_000_000


@dataclass(eq=False)
class BlockTables:
    """What the engine reads a state with, on steps of ``h`` in blocks of ``block`` steps.

    Attributes
    ----------
    h : float
        The step, s.
    block : int
        Steps per block.
    sub : int
        Steps per output sample.
    span : int
        The longest span read at once, in steps.
    fine_real : ndarray or None
        ``e^(lambda t)`` at the steps ``1..block``, as ``[Re, -Im]`` for real products (None
        where the propagator is ``expm``).
    growing : bool
        Whether a mode grows (only by rounding, for a passive body).
    peak : ndarray or None
        ``|e^(lambda h)|``: the largest ``|e^(lambda t)|`` of a decaying mode over any span.
    powers : ndarray or None
        ``expm(A h)^j``, ``j = 1..block``, where the propagator is ``expm``.
    """

    h: float
    block: int
    sub: int
    span: int
    lam: np.ndarray
    fine_real: np.ndarray | None = None
    growing: bool = False
    peak: np.ndarray | None = None
    powers: np.ndarray | None = None

    @functools.cached_property
    def every_real(self):
        """``e^(lambda sub h k)``, ``k = 0, 1, ...`` over a span, as ``[Re, -Im]``: powers by
        repeated products (``k`` roundings); computed when a state first settles."""
        every = np.full(
            (-(-self.span // self.sub), self.lam.size), np.exp(self.lam * self.sub * self.h)
        )
        every[0] = 1.0
        every = np.cumprod(every, axis=0)
        return np.hstack([every.real, -every.imag])


def prepare_blocks(states, h: float, sub: int, n_steps: int) -> int:
    """Give each of ``states`` its :class:`BlockTables` for steps of ``h`` (``sub`` per output
    sample, ``n_steps`` in all); returns the steps per block."""
    size = states[0].A.shape[0]
    block = int(max(1, min(256, n_steps, BLOCK_ELEMENTS // (size * size))))
    for st in states:
        lam, A = st.lam, st.A
        if st.eigen:
            fine = np.exp(np.multiply.outer(h * np.arange(1, block + 1), lam))
            st.blocks = BlockTables(
                h, block, sub, block * LONG_BLOCKS, lam,
                fine_real=np.hstack([fine.real, -fine.imag]),
                growing=bool(np.any(lam.real > 0)), peak=np.abs(fine[0]),
            )  # fmt: skip
        else:
            Phi = spl.expm(A * h)
            powers = np.empty((block,) + A.shape)
            powers[0] = Phi
            for j in range(1, block):
                powers[j] = Phi @ powers[j - 1]
            st.blocks = BlockTables(h, block, sub, block, lam, powers=powers)
    return block


def _affine(st, out, x, steps):
    """Add the servo's part ``a (s + s' t) + b s'`` of the rows to ``out``."""
    m = 2 * st.n
    s, sigma = x[m], x[m + 1]
    if sigma == 0:  # the servo has stopped
        out += s * st.row_s
    else:
        out += np.multiply.outer(s + sigma * st.blocks.h * steps, st.row_s)
        out += sigma * st.row_speed
    return out


def readings(st, x, z, m):
    """The rows of state ``st`` at each of the ``m`` steps after ``x`` (at most ``block``),
    shape ``(m, 3)``; ``z`` is ``st.modal(x)``."""
    tables = st.blocks
    if not st.eigen:
        return (tables.powers[:m] @ x) @ st.rows.T
    w = st.row_modes * z  # (3, 2n)
    # Re(e w) = Re(e) Re(w) - Im(e) Im(w), as one real product
    out = tables.fine_real[:m] @ np.concatenate([w.real, w.imag], axis=1).T
    return _affine(st, out, x, np.arange(1, m + 1))


def samples(st, x, z, first, m):
    """The rows of ``st`` every ``sub`` steps from step ``first + 1`` after ``x`` up to step
    ``m`` (at most ``span``)."""
    tables = st.blocks
    steps = np.arange(first + 1, m + 1, tables.sub)
    if not st.eigen:
        return (tables.powers[steps - 1] @ x) @ st.rows.T
    w = st.row_modes * (z * np.exp(st.lam * (tables.h * (first + 1))))
    out = tables.every_real[: steps.size] @ np.concatenate([w.real, w.imag], axis=1).T
    return _affine(st, out, x, steps)


def read_ahead(st, x, z, first, limit, quiet, ends=None):
    """Read the rows of ``st`` from ``x`` on, up to the next event or ``limit`` steps.

    ``quiet`` (no event possible within ``min(span, limit)`` steps, e.g. from
    :func:`stays_positive`): all those steps are taken and only the output samples are read.
    Otherwise at most a ``block`` of steps is read, and the motion stops before the first
    step where ``ends(values)`` holds (default: the monitored row ``<= 0``). ``first`` is
    the first step from ``x`` that is an output sample.

    Returns
    -------
    tuple
        ``(m, j, values, event)``: the steps safely inside the state, the output samples among
        them (step indices from 0), the rows there, and whether an event lies in the next
        step.
    """
    tables = st.blocks
    if quiet:
        m = min(tables.span, limit)
        return m, np.arange(first, m, tables.sub), samples(st, x, z, first, m), False
    m = min(tables.block, limit)
    values = readings(st, x, z, m)
    bad = np.flatnonzero(values[:, 0] <= 0 if ends is None else ends(values))
    if len(bad):
        m = int(bad[0])
    j = np.arange(first, m, tables.sub)
    return m, j, values[j], bool(len(bad))


def swing(st, z, m):
    """How far the modal part of the monitored row of ``st`` (modal coordinates ``z``, an
    eigen state) can reach over the next ``m`` steps: ``sum_k |w_k| max|e^(lambda_k t)|``."""
    tables = st.blocks
    if tables.growing:
        rate = st.lam.real
        peak = np.exp(np.where(rate > 0, rate * m, rate) * tables.h)
    else:  # every mode decays: the largest |e^(lambda t)| is at the first step
        peak = tables.peak
    return np.abs(st.row_modes[0] * z) @ peak


def stays_positive(st, x, z, m):
    """Whether the monitored quantity of ``st`` provably stays positive over the next ``m``
    steps from ``x``: its modal part is at most :func:`swing` in size and the rest is linear
    in time, so the bound needs no step to be taken."""
    if not st.eigen:
        return False
    k = 2 * st.n
    s, sigma = x[k], x[k + 1]
    ends = (s * st.row_s[0], (s + sigma * st.blocks.h * m) * st.row_s[0])
    trend = min(ends) + sigma * st.row_speed[0]
    return bool(trend > swing(st, z, m))


def after(st, x, z, steps):
    """The state ``steps`` whole steps after ``x`` (``z``: ``st.modal(x)``)."""
    if not st.eigen:
        return st.blocks.powers[steps - 1] @ x
    return st._at(x, z, steps * st.blocks.h)


class LawBlocks(abc.ABC):
    """What the engine asks of a law besides the reference's interface: its adapter.

    The defaults suit a law with nothing but its states. A subclass per law gives the states
    to prepare (:meth:`states`) and whatever the law changes.

    Parameters
    ----------
    law : SwitchedSystem
        The contact law marched.
    """

    def __init__(self, law):
        self.law = law

    @abc.abstractmethod
    def states(self) -> list:
        """Every :class:`.unilateral.LinearState` the march may read."""

    def horizon(self, i: int, n_steps: int) -> int:
        """How many steps from step ``i`` on the current state may be read ahead."""
        return n_steps - i

    def quiet(self, key, x, z, m: int) -> bool:
        """Whether no event can happen within the next ``m`` steps (:func:`stays_positive`)."""
        return stays_positive(self.law.state(key), x, z, m)

    def ends(self, key):
        """Where the state ends, read on a block's rows (None: where the monitored row is
        ``<= 0``)."""
        return None

    def record_block(self, i: int, j, values, x, z, key) -> None:
        """Record the output samples ``j`` (steps after ``i``) of a block read ahead from ``x``
        (``z``: its modal coordinates), their rows ``values``, as the law's ``_record`` would."""
        law = self.law
        k = (i + 1 + j) // law.sub
        law.acc[k], law.force[k] = values[:, 1], values[:, 2]
        if law.trajectory is not None and len(j):  # (an empty list would not broadcast)
            st = law.state(key)
            law.trajectory[k] = [after(st, x, z, jj + 1) for jj in j]


class StrikeBlocks(LawBlocks):
    """The adapter of :class:`.unilateral.StrikeLaw`."""

    def states(self) -> list:
        """The contact open and closed."""
        return [self.law.free, self.law.closed]

    def horizon(self, i, n_steps):
        """Steps ahead before the record's end or the servo's stop."""
        law = self.law
        limit = n_steps - i
        if not law.stopped:
            limit = min(limit, int(math.floor(law.stop_time / law.h)) - i)
        return limit

    def quiet(self, st, x, z, m):
        """No event within ``m`` steps: the state is held or its monitor provably stays > 0."""
        return not self.law._watched(st) or stays_positive(st, x, z, m)


class HertzStrikeBlocks(StrikeBlocks):
    """The adapter of :class:`.unilateral.HertzStrikeLaw`: a chord's state ends at its nodes."""

    def states(self) -> list:
        """The contact open, and closed on each chord."""
        return [self.law.free, *self.law.segments]

    def ends(self, key):
        """A chord's state ends at either of its nodes; the free state where the gap closes."""
        if key is self.law.free:
            return None
        lower, upper = self.law._limits(key)
        return lambda values: (values[:, 0] <= lower) | (values[:, 0] >= upper)

    def quiet(self, key, x, z, m):
        """No event within ``m`` steps: the force provably stays between the chord's nodes (its
        modal part within :func:`swing`)."""
        law = self.law
        if key is law.free:
            return stays_positive(key, x, z, m)
        if not key.eigen:
            return False
        lower, upper = law._limits(key)
        k = 2 * law.base.size
        s, sigma = x[k], x[k + 1]
        a, b = key.row_s[0], key.row_speed[0]
        ends = (s * a, (s + sigma * law.h * m) * a)
        reach = float(swing(key, z, m))
        return bool(min(ends) + sigma * b - reach > lower and max(ends) + sigma * b + reach < upper)

    def record_block(self, i, j, values, x, z, key):
        """Record a block read ahead, the states in true coordinates (as the law's
        ``_record``)."""
        super().record_block(i, j, values, x, z, key)
        law = self.law
        if law.trajectory is not None and len(j):
            law.trajectory[(i + 1 + j) // law.sub, 2 * law.base.size] += law._shift(key)


class StickSlipBlocks(LawBlocks):
    """The adapter of :class:`.stick_slip.StickSlipLaw`: a stick ends at either limit."""

    def states(self) -> list:
        """The slips and the stick, watched at both limits."""
        return list(self.law.linear.values())

    def ends(self, name):
        """A stick ends at the upper limit, ``mu_s N - F <= 0`` (the monitored row), or at the
        lower, ``mu_s N + F = 2 mu_s N - (mu_s N - F) <= 0``; a slip where its speed reaches
        zero."""
        if name != "stick":
            return None
        hold = self.law.hold_limit
        return lambda values: (values[:, 0] <= 0) | (2 * hold - values[:, 0] <= 0)

    def quiet(self, name, x, z, m):
        """No event within ``m`` steps: there is no friction, or every monitor provably stays
        > 0."""
        law = self.law
        return law.frictionless or (
            stays_positive(law.linear[name], x, z, m)
            and (name != "stick" or stays_positive(law.lower, x, law.lower._modal(x), m))
        )


#: The adapter of each law, the most specific first.
ADAPTERS = ((HertzStrikeLaw, HertzStrikeBlocks), (StrikeLaw, StrikeBlocks),
            (StickSlipLaw, StickSlipBlocks))


def adapter(law) -> LawBlocks:
    """The engine's adapter of ``law`` (:data:`ADAPTERS`).

    Raises
    ------
    TypeError
        For a law the engine has no adapter of.
    """
    for cls, blocks in ADAPTERS:
        if isinstance(law, cls):
            return blocks(law)
    raise TypeError(f"the engine 'blocks' has no adapter of {type(law).__name__}; march it with "
                    "method='steps'")


@functools.cache
def compiled_status():
    """Compile the strike march once per process (or load it from numba's cache); say once
    why not (:func:`ebantenna._engines.load_compiled`)."""
    from .._engines import load_compiled

    return load_compiled(
        "compiled strike march",
        "strikes are marched by the NumPy block engine (the same events, slower)",
        "ebantenna.simulate._march_numba",
        _check_compiled,
    )


def march_engine(engine: str | None = None) -> str:
    """The march that simulates the strikes the compiled march takes (:func:`compiled_fits`):
    ``'compiled'`` when ``engine`` (None: ``EBANTENNA_ENGINE``) lets it and numba works
    (:func:`compiled_status`), else ``'numpy'``. The two agree within a bound, not bit for bit
    (a chattering strike near the tip follows the last bits), so a data set records which one
    made it (a strike the compiled march gives up is marched by NumPy in either case)."""
    from .._engines import use_compiled

    return ("compiled" if use_compiled(engine, compiled_status, "compiled strike march")
            else "numpy")


def _one_strike(march):
    """A mass of 1 kg on a 100 N/m spring strikes a 1e4 N/m contact at 1 m/s, marched by
    ``march``; its events."""
    from .unilateral import strike_law

    one, zero = np.ones((1, 1)), np.zeros((1, 1))
    options = dict(max_events=10, on_max_events="raise", time_tolerance=1e-12,
                   return_states=False)  # fmt: skip
    law, grid, _ = strike_law((one, 100 * one, zero, np.ones(1), np.ones(1), np.ones(1)),
                               1e4, 0.0, 1.0, 1000.0, 0.05, options)  # fmt: skip
    x, key = law.first_touch(1.0)
    march(law, x, key, grid[3])
    return law.events


def _check_compiled(loops) -> None:
    """The compiled march must find the NumPy engine's events on one strike (within the root
    tolerance), or it is not used."""
    numpy = _one_strike(lambda *args: march_in_blocks(*args, engine="numpy"))
    compiled = _one_strike(march_compiled)
    if len(numpy) != len(compiled) or any(
        abs(a.time - b.time) > 1e-9 or a.kind != b.kind
        for a, b in zip(numpy, compiled, strict=True)
    ):
        raise ArithmeticError(f"the compiled march found {compiled}, the NumPy one {numpy}")


def compiled_fits(system) -> bool:
    """Whether the compiled march takes ``system``: a strike law (linear or chords, not a
    subclass), every state with the modal propagator, no states recorded."""
    if type(system) not in (StrikeLaw, HertzStrikeLaw) or system.trajectory is not None:
        return False
    return all(st.eigen for st in adapter(system).states()) and not system.frozen


def march_compiled(system, x, key, n_steps: int):
    """March a strike law with :func:`ebantenna.simulate._march_numba.march_strike`: the
    block engine's algorithm compiled. Returns ``(x, key)``, or None when the compiled march
    gave up (``max_events`` reached, or too many changes of chord): then the law's events and
    state are as they were (the samples it recorded are partial), and the NumPy engine marches
    it from the start, recording every sample again."""
    from .._engines import interrupts_pass_through
    from . import _march_numba

    law = system
    hertz = isinstance(law, HertzStrikeLaw)
    states = [law.free, *law.segments] if hertz else [law.free, law.closed]
    h, sub = law.h, law.sub
    size = states[0].A.shape[0]
    block = int(max(1, min(256, n_steps, BLOCK_ELEMENTS // (size * size))))
    lam = np.stack([st.lam for st in states])
    fine = np.exp(np.multiply.outer(h * np.arange(1, block + 1), lam)).transpose(1, 0, 2)
    every = np.exp(lam * sub * h)
    if hertz:
        lower = np.array([0.0] + [law._limits(st)[0] for st in law.segments])
        upper = np.array([0.0] + [law._limits(st)[1] for st in law.segments])
        shift = np.array([law._shift(st) for st in states])
    else:
        lower = upper = shift = np.zeros(2)
    index = next(k for k, st in enumerate(states) if st is key)
    n_events = max(law.max_events, 1)
    ev_t, ev_kind, ev_v = np.zeros(n_events), np.zeros(n_events, np.int64), np.zeros(n_events)
    with interrupts_pass_through():
        x_end, st, ctl = _march_numba.march_strike(
            np.array(x, float), index, n_steps, h, sub, block, block * LONG_BLOCKS,
            float(law.stop_time), bool(law.stopped), np.asarray(law.base, float),
            np.stack([st.V for st in states]), np.stack([st.Vinv for st in states]), lam,
            np.stack([st.G for st in states]), np.stack([st.H for st in states]),
            np.stack([st.rows for st in states]), np.stack([st.row_modes for st in states]),
            np.stack([st.row_s for st in states]), np.stack([st.row_speed for st in states]),
            np.stack([law.pen @ st.A for st in states]), np.ascontiguousarray(fine.real),
            np.ascontiguousarray(fine.imag), every.real.copy(), every.imag.copy(),
            np.abs(fine[:, 0]), np.array([bool(np.any(st.lam.real > 0)) for st in states]),
            hertz, lower, upper, shift, float(law.xtol), int(law.max_events),
            int(getattr(law, "MAX_CHORD_CHANGES", 0)), law.acc, law.force, ev_t, ev_kind, ev_v,
        )  # fmt: skip
    if ctl[0]:
        return None
    from .unilateral import ContactEvent

    law.events.extend(
        ContactEvent(float(t), "contact" if kind else "separation", float(v))
        for t, kind, v in zip(ev_t[: ctl[1]], ev_kind[: ctl[1]], ev_v[: ctl[1]], strict=True)
    )
    law.stopped = bool(ctl[3])
    if hertz:
        law.chord_changes = int(ctl[2])
    return x_end, states[st]


def march_in_blocks(system, x, key, n_steps: int, engine: str | None = None):
    """March ``system`` (a :class:`.unilateral.SwitchedSystem`) ``n_steps`` steps from the
    state ``(x, key)`` at step 0, reading each state in blocks; returns ``(x, key)`` after the
    last step. Takes the checked values a contact law was built from.

    ``engine`` (None: the environment variable ``EBANTENNA_ENGINE``, default ``'auto'``)
    chooses, for a strike law that :func:`compiled_fits`, the compiled march
    (:func:`march_compiled`, the ``fast`` extra) or this NumPy one: ``'auto'`` takes the
    compiled march when numba works (:func:`compiled_status`), ``'numpy'`` never,
    ``'compiled'`` always (a :class:`RuntimeError` when numba is missing). Any other law, and a
    strike that reaches ``max_events``, is marched here.
    """
    from .._engines import use_compiled

    if compiled_fits(system) and use_compiled(engine, compiled_status, "compiled strike march"):
        done = march_compiled(system, x, key, n_steps)
        if done is not None:
            return done
    h, sub = system.h, system.sub
    blocks = adapter(system)
    prepare_blocks(blocks.states(), h, sub, n_steps)
    i = 0
    while i < n_steps:
        if system._interrupts(i):
            x, key = system._interrupted_step(x, key, i)
            i += 1
            system._record(i, x, key)
            continue
        st = system.state(key)
        z = st._modal(x)  # unchecked: the march's own state
        limit = blocks.horizon(i, n_steps)
        first = (-(i + 1)) % sub  # the first step from here that is an output sample
        quiet = blocks.quiet(key, x, z, min(st.blocks.span, limit))
        m, j, values, event = read_ahead(st, x, z, first, limit, quiet, blocks.ends(key))
        blocks.record_block(i, j, values, x, z, key)
        if m:
            x = after(st, x, z, m)
            i += m
            system._moved()
        if event:
            x, key = system.advance(x, key, i * h, (i + 1) * h, crosses=True)
            system._moved()
            i += 1
            system._record(i, x, key)
    return x, key


MARCHES["blocks"] = march_in_blocks
