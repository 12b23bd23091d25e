"""The contact laws' engine (``method="blocks"``) against their reference (``"steps"``).

The reference takes every step in turn (:func:`ebantenna.simulate.linear_state.march_step_by_step`);
the engine reads each state a block of steps ahead and takes only the steps that hold an event.
Both propagate the same exact modal solution and locate events with the same root finder, so
they must find the same events, at times that differ by no more than the root finder's
resolution, and signals that differ only by what that shift and the propagation's rounding make.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from ebantenna.probe import Probe
from ebantenna.simulate.linear_state import step_grid
from ebantenna.simulate.stick_slip import stick_slip_response
from ebantenna.simulate.structure import check_dof_vector, mass_inverse, probe_contact_model
from ebantenna.simulate.unilateral import STEPS_PER_PERIOD, contact_states, unilateral_response

EPS = np.finfo(float).eps
K_CHAIN = 1000.0 * np.array([[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]])
M_CHAIN = np.diag([1.0, 0.5, 0.3])


def _chain(preload):
    return dict(mass=M_CHAIN, stiffness=K_CHAIN, contact=2, contact_stiffness=1e5,
                base=np.ones(3), approach_speed=0.3, duration=0.3, fs=2000.0,
                damping=1e-3 * K_CHAIN, output=0, preload=preload)  # fmt: skip


def _probe():
    m = probe_contact_model(Probe(tip_mass=2.5e-3), 0.05, n_elements=32, n_modes=5,
                            damping_ratio=0.01)  # fmt: skip
    return dict(mass=m.mass, stiffness=m.stiffness, contact=m.contact, contact_stiffness=2e5,
                base=m.base, approach_speed=0.025, duration=0.2, fs=4000.0, damping=m.damping,
                output=m.output, preload=0.3)  # fmt: skip


def _signal_tolerance(kw, time_tolerance=1e-12):
    """How far the two marches' signals may lie apart, per unit of the signal's peak.

    An event moved by ``dt <= 2 time_tolerance`` moves the motion after it by at most the
    signal's rate, a sum of modes bounded by ``|lambda|_max`` times its size, times ``dt``;
    the propagations round the state at about eps times the eigenvector matrix's condition
    at every step, and these roundings add up over the ``n_steps`` steps at most.
    """
    n = np.asarray(kw["mass"]).shape[0]
    free, closed, _ = contact_states(
        mass_inverse(np.asarray(kw["mass"], dtype=float)), np.asarray(kw["stiffness"]),
        kw["damping"], check_dof_vector("contact", kw["contact"], n), kw["contact_stiffness"],
        check_dof_vector("output", kw["output"], n),
    )  # fmt: skip
    n_steps = step_grid([free, closed], kw["fs"], kw["duration"], STEPS_PER_PERIOD)[3]
    lam = max(np.abs(st.lam).max() for st in (free, closed))
    cond = max(np.linalg.cond(st.V) for st in (free, closed))
    return lam * 2 * time_tolerance + n_steps * EPS * cond


@pytest.mark.parametrize(
    "kw",
    [_chain(0.0), _chain(0.5), _chain(2.0), _probe()],
    ids=["chain", "chain preloaded", "chain pressed", "probe"],
)
def test_the_strike_engine_finds_the_references_events_and_signals(kw):
    engine = unilateral_response(**kw, return_states=True)
    reference = unilateral_response(**kw, return_states=True, method="steps")
    assert [e.kind for e in engine.events] == [e.kind for e in reference.events]
    assert len(engine.events) >= 8  # the cases strike again and again
    # each event lies within time_tolerance after its root in both; the root itself moves
    # only by the propagation's rounding over the monitor's slope, far below that
    np.testing.assert_allclose([e.time for e in engine.events],
                               [e.time for e in reference.events], rtol=0, atol=2e-12)  # fmt: skip
    assert engine.stop_time == reference.stop_time  # the same arithmetic, before any step
    tol = _signal_tolerance(kw)
    for name in ("acceleration", "contact_force"):
        a, b = getattr(engine, name), getattr(reference, name)
        np.testing.assert_allclose(a, b, rtol=0, atol=tol * np.abs(b).max())
    scale = np.abs(reference.states).max(axis=0)
    assert np.all(np.abs(engine.states - reference.states) <= tol * scale)


def test_a_held_contact_is_held_from_the_same_event_in_both_marches():
    kw = dict(_chain(0.0), max_events=3, on_max_events="warn")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        engine = unilateral_response(**kw)
        reference = unilateral_response(**kw, method="steps")
    assert engine.bilateral_from is not None
    # the same event, located to within time_tolerance in each march (as above)
    assert abs(engine.bilateral_from - reference.bilateral_from) <= 2e-12
    tol = _signal_tolerance(kw) * np.abs(reference.acceleration).max()
    np.testing.assert_allclose(engine.acceleration, reference.acceleration, rtol=0, atol=tol)


@pytest.mark.parametrize(("mus", "muk", "normal"), [(0.5, 0.4, 3.0), (0.3, 0.3, 10.0),
                                                    (0.6, 0.4, 5.0), (0.6, 0.2, 0.0)])  # fmt: skip
def test_the_stick_slip_engine_finds_the_references_events_and_signals(mus, muk, normal):
    kw = dict(static_friction=mus, kinetic_friction=muk, duration=0.5, fs=1000.0,
              velocity=[0.5, 1.0, 2.0], damping=1e-3 * K_CHAIN, output=2)  # fmt: skip
    engine = stick_slip_response(M_CHAIN, K_CHAIN, 1, normal, **kw)
    reference = stick_slip_response(M_CHAIN, K_CHAIN, 1, normal, method="steps", **kw)
    assert [k for _, k in engine.events] == [k for _, k in reference.events]
    # as for the strike: each change within time_tolerance after its root in both
    np.testing.assert_allclose([t for t, _ in engine.events], [t for t, _ in reference.events],
                               rtol=0, atol=2e-12)  # fmt: skip
    # as for the strike: the fastest rate times the events' shift, plus the rounding of every
    # step. The free chain's highest frequency bounds every state's (held at the middle mass,
    # the chain's frequencies interlace below it); steps: 16 per shortest period or one per
    # output sample, over 0.5 s; the states' eigenvector matrices are conditioned near 1e2
    lam = np.sqrt(np.linalg.eigvalsh(np.linalg.solve(M_CHAIN, K_CHAIN)).max())
    n_steps = 0.5 * (16 * lam / (2 * np.pi) + 1000.0)
    tol = lam * 2e-12 + n_steps * EPS * 1e3  # (1e3: ten times the condition, for margin)
    for name in ("acceleration", "friction_force"):
        a, b = getattr(engine, name), getattr(reference, name)
        np.testing.assert_allclose(a, b, rtol=0, atol=tol * max(np.abs(b).max(), 1e-300))


def test_the_march_is_named():
    with pytest.raises(ValueError, match="method"):
        unilateral_response(**_chain(0.0), method="fast")
    with pytest.raises(ValueError, match="method"):
        stick_slip_response([[1.0]], [[1.0]], 0, 1.0, static_friction=0.1, kinetic_friction=0.1,
                            duration=0.1, fs=100.0, method="fast")  # fmt: skip
