"""The strike's Hertz contact (``hertz_contact``): the chords' proven force bound, their exact
integration against scipy's event-driven DOP853, and a strike against the true law."""

import dataclasses
import math

import numpy as np
import pytest
import scipy.integrate as spi
import scipy.optimize as spo

from ebantenna.bench import BENCHMARKS, contact_cost
from ebantenna.fem.coupling import craig_bampton, probe_substructure, rod_substructure
from ebantenna.probe import MATERIALS, Probe, material
from ebantenna.simulate import Scene, builtin_scene, simulate_batch
from ebantenna.simulate.contact import (
    CrossedCylinders,
    HertzInSeries,
    PiecewiseSpring,
    tube_on_rod_law,
    tube_on_rod_stiffness,
)
from ebantenna.simulate.effects import HertzContact
from ebantenna.simulate.strikes import strike_model
from ebantenna.simulate.unilateral import (
    STEPS_PER_PERIOD,
    mass_inverse,
    segment_states,
    step_grid,
    unilateral_response,
)

EPS = np.finfo(float).eps
PROBE = Probe(tip_mass=2.5e-3)


@pytest.mark.parametrize("name", sorted(MATERIALS))
def test_the_chords_lie_above_the_law_within_their_bound(name):
    # The bound is proven for a convex law (contact.py notes); sampled densely, the chords'
    # error is never negative and never above it, up to the rounding of F(p) (~1e-15 N).
    law = tube_on_rod_law(Probe(), material(name), 0.012)
    spring = law.piecewise(0.01, 40.0, through=(0.5,))
    p = np.linspace(0.0, spring.approaches[-1], 200_001)
    error = spring.force(p) - law.force(p)
    assert error.min() >= -1e-12 and error.max() <= spring.bound <= 0.01
    assert error.max() > 0.3 * spring.bound  # the bound is not loose by orders of magnitude
    assert 0.5 in spring.forces  # exact at the preload

@pytest.mark.parametrize("preload", [0.05, 0.5, 3.0])
def test_the_placed_chords_carry_the_checked_laws_own_bounds_and_approaches(preload):
    # piecewise places its chords with the law's unchecked arithmetic: each chord's bound and
    # each node's approach are, bit for bit, those of the public (checked) methods
    law = tube_on_rod_law(Probe(), material("brass"), 0.012)
    spring = law.piecewise(0.01, 10.0, through=(preload,))
    F = spring.forces
    assert [law.chord_bound(a, b) for a, b in zip(F[:-1], F[1:], strict=True)] == list(
        spring.bounds)
    assert [law.approach(f) for f in F] == list(spring.approaches)
    assert [law.stiffness(f) for f in F] == list(law.stiffness(F))



def test_the_law_is_the_linearised_spring_at_the_preload_and_inverts_its_approach():
    law = tube_on_rod_law(Probe(), material("pvc"), 0.012)
    # dF/dp of the series law is the series of the two tangents (the linearised spring)
    k = tube_on_rod_stiffness(Probe(), material("pvc"), 0.012, 0.5).total
    assert law.stiffness(0.5) == pytest.approx(k, rel=1e-13)
    F = np.geomspace(1e-4, 40.0, 50)
    assert np.allclose(law.force(law.approach(F)), F, rtol=1e-12, atol=0)  # Newton to rounding
    assert law.stiffness(0.0) == 0.0  # Hertz starts soft


def test_the_chord_bound_is_the_tangents_meeting_point():
    # On F = p^2 over [0, 1] the chord is p and its largest gap is 1/4 at p = 1/2; the tangents
    # (0 and 2p - 1) meet the chord's bound (s - 0)(2 - s)(1)/(2 - 0) at s = 1: exactly 1/4.
    hz = CrossedCylinders(0.004, 0.004, 3.5e9)
    law = HertzInSeries(hz, math.inf)
    a, b = 0.1, 2.0
    pa, pb = law.approach(a), law.approach(b)
    p = np.linspace(pa, pb, 100_001)
    chord = a + (b - a) * (p - pa) / (pb - pa)
    assert (chord - law.force(p)).max() <= law.chord_bound(a, b) * (1 + 1e-9)


def test_a_single_chord_is_the_linear_spring():
    # one chord, no node above: the same events and signals as the linear contact, bit for bit
    kw = dict(base=0, approach_speed=1.0, duration=0.05, fs=1000.0)
    lin = unilateral_response([[1.0]], [[0.0]], 0, 1e4, **kw)
    chord = unilateral_response([[1.0]], [[0.0]], 0, PiecewiseSpring.linear(1e4), **kw)
    assert lin.events == chord.events
    assert np.array_equal(lin.acceleration, chord.acceleration)


def _peak_of_the_law(law, m, v):
    """Peak force of a mass ``m`` at ``v`` stopped by the law: W(F*) = m v^2 / 2 with
    W(F) = F p(F) - int p dF = F p - 3/5 delta_H(1) F^(5/3) - F^2 / (2 k_ring)."""
    scale = law.hertz.approach(1.0)

    def work(F):
        return F * law.approach(F) - 0.6 * scale * F ** (5 / 3) - F**2 / (2 * law.ring)

    return spo.brentq(lambda F: work(F) - 0.5 * m * v**2, 1e-12, 1e3, xtol=1e-15, rtol=1e-15)


@pytest.mark.parametrize("name", ["steel", "wood"])
def test_a_mass_struck_on_the_chords_peaks_within_the_energy_bound_of_the_true_law(name):
    # A mass m at v on the contact: energy conservation bounds the chords' peak force by the
    # law's, |F~* - F*| <= eps F'(p*) p~* / F(p~*) (theory page), eps the chords' bound. The
    # true law's peak comes from scipy's solve_ivp with an event at zero speed, and checks the
    # work integral; the chords' strike is sampled at 2 MHz (error <= k F* dt^2 / 8 m).
    law = tube_on_rod_law(Probe(), material(name), 0.012)
    spring = law.piecewise(0.01, 40.0, through=(0.5,))
    m, v, fs = 0.02, 0.15, 2e6

    def rhs(t, y):
        return [y[1], -law.force(y[0]) / m]

    def turn(t, y):
        return y[1]

    turn.terminal, turn.direction = True, -1
    sol = spi.solve_ivp(rhs, (0, 1e-2), [0.0, v], events=turn, method="DOP853",
                        rtol=1e-12, atol=1e-18)  # fmt: skip
    peak = float(law.force(sol.y_events[0][0][0]))
    assert peak == pytest.approx(_peak_of_the_law(law, m, v), rel=1e-9)
    assert spring.forces[-2] > peak  # within the range where the bound holds
    res = unilateral_response([[m]], [[0.0]], 0, spring, base=0, approach_speed=v,
                              duration=1.5e-3, fs=fs)  # fmt: skip
    ours = float(res.contact_force.max())
    p_ours = spring.approach_at(ours)
    bound = spring.bound * law.stiffness(peak) * p_ours / float(law.force(p_ours))
    sampling = law.stiffness(spring.forces[-1]) * peak / (8 * m * fs**2)
    assert abs(ours - peak) <= bound + sampling
    # the linearised spring misses it by far more: the test can tell the laws apart
    k0 = tube_on_rod_stiffness(Probe(), material(name), 0.012, 0.5).total
    assert abs(v * math.sqrt(k0 * m) - peak) > 10 * (bound + sampling)


def _model(name, contact, spring_of):
    scene = builtin_scene("paper")
    effect = scene.effect("object_modes")
    rod = effect.rod(name)
    p_sub = probe_substructure(PROBE, contact, n_elements=40)
    r_sub = rod_substructure(rod, n_elements=24)
    p = craig_bampton(dataclasses.replace(p_sub, loss_factor=0.03), 40)
    r = craig_bampton(dataclasses.replace(r_sub, loss_factor=0.02), 20)
    return strike_model(p, r, contact, spring_of(rod.material), 0.5, 3000.0)


def _chords_witness(model, speed, t_out):
    """The strike by scipy's DOP853 on the same chords: the force ``F~(p)`` in the right-hand
    side, integration restarted at every node and at the servo's stop (events), so that no
    step straddles a kink."""
    s, spring = model.structure, model.contact_stiffness
    c, n = s.contact, s.mass.shape[0]
    Minv = np.linalg.inv(s.mass)
    v0 = speed * model.contact
    p0 = spring.approach_at(model.preload)
    stop = (p0 + model.preload * (c @ np.linalg.solve(s.stiffness, c))) / v0
    nodes = spring.approaches[:-1]

    def rhs(t, y):
        q, v = y[:n], y[n:]
        load = c * spring.force(c @ q + v0 * min(t, stop))
        return np.concatenate([v, -Minv @ (s.stiffness @ q + s.damping @ v + load)])

    events = []
    for node in nodes:
        def at_node(t, y, node=node):
            return c @ y[:n] + v0 * min(t, stop) - node
        at_node.terminal = True
        events.append(at_node)
    t, y, stopped, pieces = 0.0, np.zeros(2 * n), False, []
    while t < t_out[-1]:
        end = t_out[-1] if stopped else stop
        sol = spi.solve_ivp(rhs, (t, end), y, events=events, method="DOP853", rtol=1e-11,
                            atol=1e-16, dense_output=True, first_step=1e-9)  # fmt: skip
        pieces.append((t, sol.t[-1], sol.sol))
        t, y = sol.t[-1], sol.y[:, -1].copy()
        if sol.status == 1:  # a node: step just past it so that the event does not fire again
            nxt = spi.solve_ivp(rhs, (t, t + 1e-9), y, method="DOP853", rtol=1e-12, atol=1e-18)
            t, y = nxt.t[-1], nxt.y[:, -1].copy()
        elif not stopped:
            y[n:] += s.base * v0
            stopped = True
    acc = np.empty(t_out.size)
    for i, ti in enumerate(t_out):
        sol = next(p[2] for p in pieces if p[0] <= ti <= p[1])
        acc[i] = s.output @ rhs(ti, sol(ti))[n:]
    return acc


@pytest.mark.parametrize(("name", "contact"), [("steel", 0.1), ("pvc", 0.3)])
def test_the_hertz_strike_matches_an_event_driven_ode_solver_on_the_same_chords(name, contact):
    # The chords are integrated exactly between nodes (events to 1e-12 s); the witness, DOP853
    # restarted at every node (the short step past a node is integrated too) to rtol 1e-11,
    # differs by its tolerance and the event times: 5e-11 of the peak for steel at 0.1 m, 2e-7
    # for PVC at 0.3 m (1e-8 with the witness at rtol 1e-12); 1e-6 leaves room.
    def spring_of(obj):
        return HertzContact().spring(obj, PROBE, 0.012, 0.5)

    model = _model(name, contact, spring_of)
    s, rate, n_out = model.structure, 8000.0, 241
    res = unilateral_response(
        s.mass, s.stiffness, s.contact, model.contact_stiffness, base=s.base,
        approach_speed=0.5 * model.contact, duration=(n_out - 1) / rate, fs=rate,
        damping=s.damping, output=s.output, preload=model.preload, max_events=400,
    )  # fmt: skip
    witness = _chords_witness(model, 0.5, np.arange(n_out) / rate)
    assert res.n_impacts >= 2
    assert np.allclose(res.acceleration, witness, rtol=0, atol=1e-6 * np.abs(witness).max())


def test_the_reference_march_and_the_engine_agree_on_the_hertz_strike():
    def spring_of(obj):
        return HertzContact().spring(obj, PROBE, 0.012, 0.5)

    model = _model("brass", 0.25, spring_of)
    s = model.structure
    kw = dict(base=s.base, approach_speed=0.5 * model.contact, duration=0.05, fs=8000.0,
              damping=s.damping, output=s.output, preload=model.preload, max_events=400)
    a = unilateral_response(s.mass, s.stiffness, s.contact, model.contact_stiffness, **kw)
    b = unilateral_response(s.mass, s.stiffness, s.contact, model.contact_stiffness,
                            method="steps", **kw)  # fmt: skip
    assert [e.kind for e in a.events] == [e.kind for e in b.events]
    assert len(a.events) >= 2
    # each event lies within time_tolerance (1e-12 s) after its root in both marches
    np.testing.assert_allclose([e.time for e in a.events], [e.time for e in b.events], rtol=0,
                               atol=2e-12)  # fmt: skip
    # signals: the bound of test_sim_marches, over the free state and every chord's: an event
    # moved by 2 time_tolerance moves the motion by the fastest rate |lambda| times that, and
    # each of the n_steps steps rounds the state by eps times its eigenvectors' condition
    free, chords, _ = segment_states(mass_inverse(s.mass), s.stiffness, s.damping, s.contact,
                                     model.contact_stiffness, s.output)  # fmt: skip
    states = [free, *chords]
    n_steps = step_grid(states, kw["fs"], kw["duration"], STEPS_PER_PERIOD)[3]
    lam = max(np.abs(st.lam).max() for st in states)
    cond = max(np.linalg.cond(st.V) for st in states)
    tol = lam * 2e-12 + n_steps * EPS * cond
    for name in ("acceleration", "contact_force"):
        x, y = getattr(a, name), getattr(b, name)
        np.testing.assert_allclose(x, y, rtol=0, atol=tol * np.abs(y).max())


def test_the_effect_needs_the_unilateral_contact_and_the_paper_scene_leaves_it_out():
    with pytest.raises(ValueError, match="needs 'unilateral_contact'"):
        Scene(effects={"object_modes": {}, "hertz_contact": {}})
    assert not builtin_scene("paper").has("hertz_contact")
    with pytest.raises(ValueError, match="force_tolerance"):
        HertzContact(force_tolerance=0.0)


def test_the_scene_with_hertz_contact_strikes_through_the_chords():
    effects = {"structural_damping": {}, "object_modes": {}, "object_damping": {},
               "unilateral_contact": {}}
    lin = Scene(effects=effects, max_frequency=3000.0, n_modes=16, duration=0.2, fs=8000.0)
    hz = lin.with_(effects=(*lin.effects, "hertz_contact"))
    kw = dict(contact=[0.15, 0.3], material=["oak", "steel"])
    _, a_lin, _, x_lin, _ = simulate_batch(lin, **kw)
    _, a_hz, _, x_hz, _ = simulate_batch(hz, **kw)
    assert np.all(np.isfinite(a_hz)) and not np.allclose(a_lin, a_hz)
    assert np.all(x_hz.restrikes >= 1)


def test_the_bench_times_both_laws_on_the_same_rows():
    # the rows' shape only: what the Hertz law costs is a measurement of the bench (ebantenna
    # bench --only contact_cost), which a unit test on a shared machine does not repeat; the
    # linearised row is the reference, so its ratio is 1 and it adds nothing by construction
    assert "contact_cost" in BENCHMARKS
    tables = contact_cost.run(signals=4, repeat=1)
    assert tables["signals"] == 4 and tables["repeat"] == 1
    assert [row["law"] for row in tables["rows"]] == [label for label, _ in contact_cost.scenes()]
    keys = {"law", "per_1000", "ratio", "ratio_median", "restrikes", "added_seconds"}
    for row in tables["rows"]:
        assert keys <= set(row)
        assert all(math.isfinite(row[key]) for key in keys - {"law"})
        assert row["per_1000"] >= 0 and row["restrikes"] >= 0
    linear = tables["rows"][0]
    assert linear["ratio"] == 1.0 and linear["ratio_median"] == 1.0
    assert linear["added_seconds"] == 0.0
    text = contact_cost.to_text(tables)
    assert "Hertz law" in text and "budget of 60 s" in text
    with pytest.raises(ValueError, match="signals must be >= 1"):
        contact_cost.run(signals=0)


def test_a_piecewise_spring_rejects_nodes_that_do_not_climb_from_zero():
    with pytest.raises(ValueError, match="from 0"):
        PiecewiseSpring(np.array([0.1, 1.0]), np.array([0.0, 1e-5]), np.zeros(1))
    with pytest.raises(ValueError, match="increase"):
        PiecewiseSpring(np.array([0.0, 1.0, 0.5]), np.array([0.0, 1e-5, 2e-5]), np.zeros(2))
    with pytest.raises(ValueError, match="one non-negative bound per chord"):
        PiecewiseSpring(np.array([0.0, 1.0]), np.array([0.0, 1e-5]), np.zeros(2))
    spring = PiecewiseSpring(np.array([0.0, 1.0, 3.0]), np.array([0.0, 1e-5, 2e-5]), np.zeros(2))
    # the chords' force and its inverse: exact at and between the nodes, continued beyond
    assert spring.force(1.5e-5) == pytest.approx(2.0, rel=4 * EPS)
    assert spring.approach_at(2.0) == pytest.approx(1.5e-5, rel=4 * EPS)
    assert spring.force(3e-5) == pytest.approx(5.0, rel=4 * EPS) and spring.force(-1e-6) == 0.0
