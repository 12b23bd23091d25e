"""The contact laws' engine (``method="blocks"``) against their reference (``"steps"``).

The reference takes every step in turn (:func:`ebantenna.simulate.unilateral.march_step_by_step`);
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
from ebantenna.simulate import builtin_scene, load_scene, simulate
from ebantenna.simulate.effects import CoulombFriction, UnilateralContact
from ebantenna.simulate.simulator import CHAIN, SignalBatch
from ebantenna.simulate.stick_slip import friction_states, stick_slip_response
from ebantenna.simulate.strikes import strike_accelerations, timed_rate
from ebantenna.simulate.structure import check_dof_vector, probe_contact_model
from ebantenna.simulate.unilateral import (
    STEPS_PER_PERIOD,
    contact_states,
    mass_inverse,
    step_grid,
    unilateral_response,
)

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
    return _march_tolerance([free, closed], kw["fs"], kw["duration"], time_tolerance)


def _march_tolerance(states, fs, duration, time_tolerance=1e-12):
    """:func:`_signal_tolerance` of a law's linear ``states``, marched at ``fs`` for
    ``duration``."""
    n_steps = step_grid(states, fs, duration, STEPS_PER_PERIOD)[3]
    lam = max(np.abs(st.lam).max() for st in states)
    cond = max(np.linalg.cond(st.V) for st in states)
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


def _paper_without_rounding(method, friction=None):
    """The ``paper`` scene, its strikes marched by ``method`` (and its Z axis held by Coulomb
    friction, marched by ``friction``, if given), without ``quantisation``: rounding to a count
    is not continuous (a difference of 1e-12 may move a reading by one count), so no bound on
    the march carries through it."""
    paper = builtin_scene("paper").with_(duration=0.4)
    effects = {name: params for name, params in paper.to_dict()["effects"].items()
               if name != "quantisation"}  # fmt: skip
    effects["unilateral_contact"] = dict(effects["unilateral_contact"], method=method)
    if friction is not None:
        effects["coulomb_friction"] = {"method": friction}
    return paper.with_(effects=effects)


def _up_to_the_march(scene, seed):
    """The one signal's batch as the chain has it when the marches start: the scattered preload,
    the touched object's models, the sample instants."""
    one = np.ones(1)
    batch = SignalBatch(scene, scene.contact * one, np.array([scene.material], dtype=object),
                        scene.sweep_speed * one, scene.tilt_ratio * one, [seed])  # fmt: skip
    for step in CHAIN[:3]:  # preload_scatter, the touched object, clock_jitter
        assert step.effect is None or scene.has(step.effect)
        step.apply(None if step.effect is None else scene.effect(step.effect), batch)
    return batch


def _chain_gain(scene, batch):
    """How much the steps after a march can enlarge a difference in it (max norm).

    The DLPF: the sum of its impulse response's magnitudes, ``||h||_1`` (a second-order
    Butterworth overshoots a little, so this is slightly above its largest ``|H|``, 1);
    decimation and reading at the jittered instants by linear interpolation (weights >= 0
    summing to 1): 1; gravity, hum and noise add the same values to both: 0 added; the drift:
    its gain factor; clipping: 1 (it is 1-Lipschitz); the Kalman filter ``y_n = (1 - K) y_(n-1)
    + K z_n``: its impulse response ``K (1 - K)^n`` is positive and sums to 1.
    """
    dlpf = scene.effect("dlpf")
    impulse = np.zeros(4096)  # its poles lie within 0.87 of the origin: 0.87^4096 is nothing
    impulse[0] = 1.0
    l1 = float(np.abs(dlpf.apply_internal(impulse[None, :], dlpf.internal_rate)).sum())
    drift = scene.effect("sensor_drift")
    gain, _ = drift.draw(batch.rngs(drift)[0])
    return l1 * float(np.abs(gain).max())


def test_a_paper_recording_marched_step_by_step_equals_the_engines():
    seed = 3
    engine_scene, reference_scene = (_paper_without_rounding(m) for m in ("blocks", "steps"))
    engine = simulate(engine_scene, seed=seed)
    reference = simulate(reference_scene, seed=seed)
    s = engine_scene
    batch = _up_to_the_march(s, seed)
    model = batch.timed["unilateral"][0]
    rate, n_int = timed_rate(s, batch.when, batch.chip_filter)
    strike, _ = strike_accelerations([model], [0], batch.speeds, rate=rate, n_samples=n_int,
                                     max_events=s.effect("unilateral_contact").max_events)
    st = model.structure
    kw = dict(mass=st.mass, stiffness=st.stiffness, damping=st.damping, contact=st.contact,
              contact_stiffness=model.contact_stiffness, output=st.output, fs=rate,
              duration=(n_int - 1) / rate)  # fmt: skip
    # the march's bound (as in the tests above), times what the chain after it can enlarge
    bound = _signal_tolerance(kw) * np.abs(strike).max() * _chain_gain(s, batch)
    assert 0 < np.abs(engine.ax - reference.ax).max() <= bound  # not bit for bit: rounding
    assert np.array_equal(engine.az, reference.az)  # Z has no strike: the same arithmetic
    assert np.array_equal(engine.t, reference.t)


def test_a_paper_recording_with_friction_marched_step_by_step_equals_the_engines():
    seed = 4
    engine_scene, reference_scene = (_paper_without_rounding("blocks", friction=m)
                                     for m in ("blocks", "steps"))  # fmt: skip
    engine = simulate(engine_scene, seed=seed)
    reference = simulate(reference_scene, seed=seed)
    s = engine_scene
    batch = _up_to_the_march(s, seed)
    m = batch.timed["friction"][0]
    effect = s.effect("coulomb_friction")
    rate, n_int = timed_rate(s, batch.when, batch.chip_filter)
    b = m.mass.shape[0] - 1  # the contact's coordinate, last
    velocity = m.rotation * float(batch.tilts[0] * batch.speeds[0])
    z = stick_slip_response(
        m.mass, m.stiffness, b, m.normal_force, static_friction=effect.static_friction,
        kinetic_friction=effect.kinetic_friction, duration=(n_int - 1) / rate, fs=rate,
        velocity=velocity, damping=m.damping, output=m.output,
    )  # fmt: skip
    assert [k for _, k in z.events] == ["slip+", "stick"]  # the stop sets it sliding; it sticks
    states = friction_states(m.mass, m.stiffness, m.damping, mass_inverse(m.mass), b, m.output,
                             m.normal_force * effect.static_friction,
                             m.normal_force * effect.kinetic_friction).values()  # fmt: skip
    # as for the strike: the fastest rate times the events' shift, plus every step's rounding
    bound = (_march_tolerance(list(states), rate, (n_int - 1) / rate)
             * np.abs(z.acceleration).max() * _chain_gain(s, batch))  # fmt: skip
    assert 0 < np.abs(engine.az - reference.az).max() <= bound
    assert np.array_equal(engine.ax, reference.ax)  # the strikes: marched alike in both


def test_the_march_is_a_parameter_of_the_effects_and_of_a_scene_file(tmp_path):
    assert UnilateralContact().method == CoulombFriction().method == "blocks"
    scene = _paper_without_rounding("steps")
    for suffix in (".toml", ".json"):
        loaded = load_scene(scene.save(tmp_path / f"scene{suffix}"))
        assert loaded.effect("unilateral_contact").method == "steps"
        assert loaded == scene
    text = (tmp_path / "scene.toml").read_text(encoding="utf-8")
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace('method = "steps"', 'method = "fast"'), encoding="utf-8")
    with pytest.raises(ValueError, match="method must be one of 'steps', 'blocks'; got 'fast'"):
        load_scene(bad)
    with pytest.raises(ValueError, match="method must be one of"):
        CoulombFriction(method="fast")
