"""How a unilateral strike is stepped: the event root finder, and the block engine's no-event
bound and read-out."""

import math

import numpy as np
import pytest

from ebantenna.simulate._block_march import (
    LONG_BLOCKS,
    StrikeBlocks,
    after,
    prepare_blocks,
    read_ahead,
    readings,
    stays_positive,
)
from ebantenna.simulate.unilateral import LinearState, crossing, unilateral_response

EPS = np.finfo(float).eps


def _counted(g, rate):
    calls = []

    def curve(t):
        calls.append(t)
        return g(t), rate(t)

    return curve, calls


@pytest.mark.parametrize(
    ("g", "rate", "root"),
    [
        # a simple root, as a force through zero
        (lambda t: math.cos(3e4 * t) - 0.3, lambda t: -3e4 * math.sin(3e4 * t),
         math.acos(0.3) / 3e4),
        # a triple root: Newton crawls (each step 2/3 of the last), so bisection takes over
        (lambda t: (4e-5 - t) ** 3, lambda t: -3 * (4e-5 - t) ** 2, 4e-5),
        # a flat start (zero rate at 0): the first Newton step would leave the bracket
        (lambda t: 1e-9 - t**2, lambda t: -2 * t, math.sqrt(1e-9)),
    ],
)  # fmt: skip
def test_crossing_lands_just_past_the_root_within_the_bisection_budget(g, rate, root):
    span, xtol = 5e-5, 1e-12
    curve, calls = _counted(g, rate)
    b = crossing(curve, span, xtol, g(0.0), g(span))
    # The far end of a bracket [a, b] around the root with b - a <= xtol; the root itself is
    # known to rounding (eps of the time), which widens the window by a few ulps.
    assert g(b) <= 0
    assert root - 4 * EPS * span <= b <= root + xtol + 4 * EPS * span
    # Every non-Newton step halves the bracket and every Newton step must halve the last step,
    # so the work is bounded by two evaluations per halving of span down to xtol.
    assert len(calls) <= 2 * math.ceil(math.log2(span / xtol)) + 2


def _two_dof_closed_state():
    """The contact state of two masses on springs, damped, with the servo stopped."""
    M = np.diag([0.05, 0.02])
    K = np.array([[1.3e4, -9.0e3], [-9.0e3, 9.0e3]])
    C = 1e-4 * K
    kc, c = 5.0e4, np.array([0.0, 1.0])
    n = 2
    Minv = np.linalg.inv(M)
    A = np.zeros((2 * n + 2, 2 * n + 2))
    A[:n, n : 2 * n] = np.eye(n)
    A[n : 2 * n, :n] = -Minv @ (K + kc * np.outer(c, c))
    A[n : 2 * n, n : 2 * n] = -Minv @ C
    A[n : 2 * n, 2 * n] = -kc * (Minv @ c)
    A[2 * n, 2 * n + 1] = 1.0
    pen = np.concatenate([c, np.zeros(n), [1.0, 0.0]])  # p = c @ q + s
    st = LinearState(A, n, kc * pen, kc * pen, A[n])
    fastest = np.abs(st.lam).max()
    h = 2 * math.pi / (16 * fastest)
    assert prepare_blocks([st], h, 7, 10_000) == 256  # a full block
    return st


def test_the_no_event_bound_never_promises_what_the_motion_breaks():
    st = _two_dof_closed_state()
    rng = np.random.default_rng(3)
    promised = 0
    s = 1e-5  # the servo's travel; the structure's static deflection, then a disturbance
    n, A = st.n, st.A
    q_static = -np.linalg.solve(A[n : 2 * n, :n], A[n : 2 * n, 2 * n] * s)
    for _ in range(200):
        size = s * 10 ** rng.uniform(-3, 0.5)
        dq, dv = rng.normal(size=n) * size, rng.normal(size=n) * size * 500.0
        x = np.concatenate([q_static + dq, dv, [s, 0.0]])
        z = st.modal(x)
        tables = st.blocks
        if not stays_positive(st, x, z, tables.span):
            continue
        promised += 1
        # every step of the span, read through the exact propagator one block at a time
        y = x
        for _ in range(tables.span // tables.block):
            yz = st.modal(y)
            assert readings(st, y, yz, tables.block)[:, 0].min() > 0
            y = after(st, y, yz, tables.block)
    assert promised >= 20  # the witness is not vacuous: the bound holds for many states


def test_settled_spans_read_the_same_samples_as_every_step(monkeypatch):
    M = np.diag([0.05, 0.02])
    K = np.array([[1.3e4, -9.0e3], [-9.0e3, 9.0e3]])
    kw = dict(
        base=np.ones(2), approach_speed=0.3, duration=0.5, fs=2000.0, damping=2e-4 * K,
        preload=2.0, max_events=10_000,
    )  # fmt: skip
    bound = unilateral_response(M, K, 1, 5.0e4, **kw)
    monkeypatch.setattr(StrikeBlocks, "quiet", lambda self, key, x, z, m: False)
    stepped = unilateral_response(M, K, 1, 5.0e4, **kw)
    assert [e.kind for e in bound.events] == [e.kind for e in stepped.events]
    assert len(bound.events) >= 2  # it rebounds before it settles
    # The two read the same exact motion with different roundings of the state (a few ulps),
    # which move an event by ulps of the force over its rate: far below the time tolerance.
    times = np.array([[e.time for e in r.events] for r in (bound, stepped)])
    assert np.abs(times[0] - times[1]).max() <= 1e-12
    peak = np.abs(stepped.acceleration).max()
    # The settled spans use powers e^(lambda sub h k) built by k repeated products, k below
    # span/sub; each carries k roundings of the modal amplitudes (sum |w| ~ peak).
    k = LONG_BLOCKS * 256
    assert np.abs(bound.acceleration - stepped.acceleration).max() <= 4 * k * EPS * peak
    np.testing.assert_allclose(bound.contact_force, stepped.contact_force, rtol=0,
                               atol=4 * k * EPS * np.abs(stepped.contact_force).max())  # fmt: skip


def test_a_state_watching_other_rows_shares_the_decomposition_and_reads_the_same():
    st = _two_dof_closed_state()
    n, A = st.n, st.A
    rng = np.random.default_rng(5)
    monitor, force, accel = (rng.normal(size=A.shape[0]) for _ in range(3))
    before = st.rows.copy(), st.row_modes.copy()
    twin = st.watching(monitor, force, accel)
    fresh = LinearState(A, n, monitor, force, accel)
    assert twin.V is st.V and twin.lam is st.lam  # not decomposed again
    np.testing.assert_array_equal(st.rows, before[0])  # the original reads what it read
    np.testing.assert_array_equal(st.row_modes, before[1])
    tables = st.blocks
    prepare_blocks([twin, fresh], tables.h, tables.sub, 10_000)
    x = np.concatenate([rng.normal(size=2 * n) * 1e-4, [1e-5, 2e-3]])
    # the same eigenvectors (LAPACK is deterministic on the same matrix), so the same numbers
    np.testing.assert_array_equal(readings(twin, x, twin.modal(x), tables.block),
                                  readings(fresh, x, fresh.modal(x), tables.block))


def test_read_ahead_stops_before_the_first_step_that_ends_the_state():
    st = _two_dof_closed_state()
    n = st.n
    x = np.concatenate([np.full(2 * n, 1e-6), [1e-5, 0.0]])
    z = st.modal(x)
    first = 3
    block, sub = st.blocks.block, st.blocks.sub
    never = lambda values: np.zeros(len(values), dtype=bool)  # noqa: E731
    m, j, values, event = read_ahead(st, x, z, first, block, False, never)
    assert m == block and not event
    np.testing.assert_array_equal(j, np.arange(first, block, sub))
    stop = block // 2
    at_stop = lambda values: np.arange(len(values)) >= stop  # noqa: E731
    m2, j2, values2, event2 = read_ahead(st, x, z, first, block, False, at_stop)
    assert event2 and m2 == stop
    np.testing.assert_array_equal(j2, j[j < stop])  # the samples up to the stop, the same numbers
    np.testing.assert_array_equal(values2, values[: len(j2)])
    # the limit bounds the steps read, quiet or not
    assert read_ahead(st, x, z, first, 5, False, never)[0] == 5
    assert read_ahead(st, x, z, first, 5, True)[0] == 5
