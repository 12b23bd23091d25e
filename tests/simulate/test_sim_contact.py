"""Contact stiffness (Hertz, tube wall, wood) and unilateral contact dynamics, against witnesses."""

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from ebantenna.fem import Supports, modal_analysis
from ebantenna.probe import Probe, material
from ebantenna.simulate.contact import (
    CrossedCylinders,
    contact_modulus,
    ring_stiffness,
    tube_on_rod_stiffness,
)
from ebantenna.simulate.effects import ContactCompliance
from ebantenna.simulate.friction_ode import coulomb_response
from ebantenna.simulate.stick_slip import stick_slip_response
from ebantenna.simulate.structure import probe_contact_model
from ebantenna.simulate.unilateral import ChatterError, mass_inverse, unilateral_response

EPS = np.finfo(float).eps


def test_equal_radii_is_sphere_on_flat_and_todays_contact_compliance():
    # Crossed cylinders of equal radius R have the gap (x^2 + y^2)/(2R) of a sphere on a flat.
    probe, steel = Probe(), material("steel")
    today = ContactCompliance()
    Es = today.effective_modulus(steel, probe)
    R = probe.outer_diameter / 2
    hz = CrossedCylinders(R, R, Es)
    assert hz.axis_ratio == 1.0
    # Closed forms are cube roots of the same products: equal to a few ulps.
    assert hz.stiffness(0.5) == pytest.approx(today.stiffness(steel, probe), rel=16 * EPS)
    P = 0.7
    a = (3 * P * R / (4 * Es)) ** (1 / 3)  # Johnson eq. 4.22
    assert hz.semi_axes(P)[0] == pytest.approx(a, rel=16 * EPS)
    assert hz.approach(P) == pytest.approx(a * a / R, rel=16 * EPS)


def test_nearly_equal_radii_join_the_circular_case_continuously():
    # B/A = 1 + 2e-6: the ellipse's approach differs from the circle's at first order in the
    # curvature difference, so the two agree to about 1e-6 (and not better than rounding).
    R, Es = 0.004, 3.5e9
    near = CrossedCylinders(R, R * (1 + 2e-6), Es)
    exact = CrossedCylinders(R, R, Es)
    assert near.approach(0.5) == pytest.approx(exact.approach(0.5), rel=2e-6)


def test_hertz_pressure_reproduces_the_gap_boussinesq():
    # Independent witness: the surface displacement under p0 sqrt(1 - x^2/a^2 - y^2/b^2), summed
    # from Boussinesq's 1/r kernel along chords through the field point (no elliptic integrals),
    # must equal delta - A x^2 - B y^2 inside the contact.
    R1, R2, Es, P = 0.004, 0.006, 3.5e9, 0.5
    hz = CrossedCylinders(R1, R2, Es)
    a, b = hz.semi_axes(P)
    p0 = 3 * P / (2 * math.pi * a * b)
    A, B = 1 / (2 * R2), 1 / (2 * R1)

    def displacement(x, y):
        def chord(phi):
            c, s = math.cos(phi), math.sin(phi)
            alpha = 1 - x * x / a**2 - y * y / b**2
            beta = -2 * (x * c / a**2 + y * s / b**2)
            gamma = c * c / a**2 + s * s / b**2
            return (beta**2 + 4 * alpha * gamma) / gamma**1.5

        return p0 / (8 * Es) * quad(chord, 0, math.pi, epsabs=0, epsrel=1e-13)[0]

    delta = hz.approach(P)
    # quad's relative accuracy 1e-13 on a smooth periodic integrand; 1e-11 leaves margin.
    for x, y in ((0, 0), (0.5 * a, 0), (0, 0.6 * b), (0.3 * a, 0.4 * b)):
        assert displacement(x, y) == pytest.approx(delta - A * x * x - B * y * y, rel=1e-11)


def test_linearised_stiffness_is_the_derivative_of_the_nonlinear_law():
    hz = CrossedCylinders(0.004, 0.006, 3.5e9)
    F0 = 0.5
    d0 = hz.approach(F0)
    h = 1e-4 * d0
    fd = (hz.force(d0 + h) - hz.force(d0 - h)) / (2 * h)
    # Central difference of P ~ d^1.5: truncation (h/d)^2 * |P'''| d^2/6 / P' = 1e-8 / 24 relative,
    # rounding eps * P / h = 1e-12; 1e-8 covers both.
    assert fd == pytest.approx(hz.stiffness(F0), rel=1e-8)
    assert hz.force(-1e-9) == 0.0  # no tension


def test_stiffness_grows_without_bound_toward_a_cylinder_on_a_flat():
    radii = 0.004 * np.array([1, 1.5, 10, 100, 1e4])
    k = [CrossedCylinders(0.004, r, 3.5e9).stiffness(0.5) for r in radii]
    assert np.all(np.diff(k) > 0)
    # The growth is slow (roughly as (R2/R1)^(1/6) for a long ellipse) but unbounded: a line
    # contact is no point contact, and sphere-on-flat is not the flat-rod limit.
    assert k[-1] > 9 * k[0]


def test_stiffness_is_symmetric_in_the_two_radii():
    k12 = CrossedCylinders(0.004, 0.006, 3.5e9).stiffness(0.3)
    k21 = CrossedCylinders(0.006, 0.004, 3.5e9).stiffness(0.3)
    assert k12 == k21


def test_thin_ring_limit_is_roarks_pi_over_4_minus_2_over_pi():
    # A very thin wall: the hoop and shear corrections (~ (t/R)^2) vanish.
    Do, Di, E, w = 0.1, 0.1 - 2e-5, 1e9, 0.01
    t, Rm = (Do - Di) / 2, (Do + Di) / 4
    thin = E * (w * t**3 / 12) / (Rm**3 * (math.pi / 4 - 2 / math.pi))
    # Corrections are of order (t/Rm)^2 = 1.6e-7.
    assert ring_stiffness(Do, Di, E, 0.3, width=w) == pytest.approx(thin, rel=1e-6)


def test_wood_is_indented_across_the_grain_with_the_tables_modulus():
    # One source: the material table's across-grain modulus (1.48 GPa), nothing recomputed.
    wood = material("wood")
    across = tube_on_rod_stiffness(Probe(), wood, 0.012, 0.5, wall=False)
    along = tube_on_rod_stiffness(
        Probe(), wood, 0.012, 0.5, wall=False, object_modulus=wood.youngs_modulus
    )
    assert across.hertz < along.hertz
    assert across.contact_modulus == pytest.approx(
        contact_modulus(
            3.0e9, wood.transverse_modulus, poisson_ratio1=0.39, poisson_ratio2=wood.poisson_ratio
        ),
        rel=4 * EPS,
    )
    assert wood.transverse_modulus == 1.48e9


def test_series_total_and_the_dominant_share():
    ks = tube_on_rod_stiffness(Probe(), material("steel"), 0.012, 0.5)
    assert 1 / ks.total == pytest.approx(1 / ks.hertz + 1 / ks.ring, rel=4 * EPS)
    assert ks.dominant == "ring"
    solid = tube_on_rod_stiffness(Probe(inner_diameter=0.0), material("pvc"), 0.012, 0.5)
    assert solid.ring == math.inf and solid.total == solid.hertz


@pytest.mark.parametrize(
    ("call", "word"),
    [
        (lambda: CrossedCylinders(0.0, 0.01, 1e9), "radius1"),
        (lambda: CrossedCylinders(0.01, -1.0, 1e9), "radius2"),
        (lambda: CrossedCylinders(0.01, 0.01, -1e9), "modulus"),
        (lambda: CrossedCylinders(0.01, 0.01, 1e9).stiffness(0.0), "preload"),
        (lambda: contact_modulus(1e9, 1e9, poisson_ratio1=0.5, poisson_ratio2=0.3), "Poisson"),
        (lambda: contact_modulus(1e9, 1e9, poisson_ratio1=0.3, poisson_ratio2=-1.0), "Poisson"),
        (lambda: ring_stiffness(0.008, 0.009, 3e9), "inner_diameter"),
        (lambda: tube_on_rod_stiffness(Probe(), material("steel"), 0.0, 0.5), "rod_diameter"),
        (lambda: tube_on_rod_stiffness(Probe(), material("steel"), 0.01, -0.1), "preload"),
    ],
)
def test_impossible_parameters_are_named(call, word):
    with pytest.raises(ValueError, match=word):
        call()


# --------------------------------------------------------------------------------------------------
# Unilateral contact dynamics

XTOL = 1e-12  # the default time_tolerance of unilateral_response, s


def test_mass_bouncing_on_a_spring():
    m, k, v0 = 0.3, 2.0e4, 0.7
    res = unilateral_response(
        [[m]],
        [[0.0]],
        0,
        k,
        base=0,
        approach_speed=v0,
        duration=0.02,
        fs=5000.0,
        return_states=True,
    )
    (sep,) = res.events
    Tc = math.pi * math.sqrt(m / k)
    assert sep.kind == "separation"
    # Each event is placed within 2 time_tolerance after the root; the root itself is exact up to
    # the rounding of F (eps * F_max) over its slope k v0: eps sqrt(m/k), far below XTOL.
    assert abs(sep.time - Tc) <= 2 * XTOL + 8 * EPS * Tc
    # At separation the force, hence the acceleration, is zero: the speed error is second order
    # in the time error, ~(omega 2 XTOL)^2; what remains is the propagator's rounding (few ulps
    # per step, ~100 steps).
    assert sep.velocity == pytest.approx(-v0, rel=1e3 * EPS)
    w = math.sqrt(k / m)
    inside = res.t < Tc
    expected = -v0 * w * np.sin(w * res.t[inside])  # a = -k x / m, x = v0/w sin(w t)
    # Rounding of the propagator and of sin (measured ~2 ulps of the peak); 100 ulps of margin.
    assert np.abs(res.acceleration[inside] - expected).max() <= 100 * EPS * v0 * w
    after = res.t > Tc + 1e-9
    assert np.all(res.contact_force[after] == 0) and np.all(res.acceleration[after] == 0)
    assert np.allclose(res.states[after, 1], -v0, rtol=1e3 * EPS, atol=0)  # flies off at -v0


def _two_dof(damping=0.0):
    m1, m2, k1, k2 = 0.05, 0.02, 4.0e3, 9.0e3
    M = np.diag([m1, m2])
    K = np.array([[k1 + k2, -k2], [-k2, k2]])
    C = damping * K
    return M, K, C


def _energy(res, M, K, kc):
    n = M.shape[0]
    X = res.states
    q, v, s = X[:, :n], X[:, n : 2 * n], X[:, 2 * n]
    p = q[:, -1] + s
    closed = res.contact_force > 0
    return (
        0.5 * np.einsum("ti,ij,tj->t", v, M, v)
        + 0.5 * np.einsum("ti,ij,tj->t", q, K, q)
        + 0.5 * kc * np.where(closed, p, 0.0) ** 2
    )


@pytest.mark.parametrize("preload", [0.0, 0.4])
def test_energy_is_conserved_across_switches_without_damping(preload):
    M, K, _ = _two_dof()
    kc = 5.0e4
    res = unilateral_response(
        M,
        K,
        1,
        kc,
        base=np.ones(2),
        approach_speed=0.3,
        duration=0.2,
        fs=2000.0,
        preload=preload,
        return_states=True,
        max_events=10_000,
    )
    assert len(res.events) >= 4  # the witness needs switches
    after = res.t > res.stop_time  # the servo does work until it stops
    E = _energy(res, M, K, kc)[after]
    # Within a state the propagator is exact up to rounding (a few ulps of the state per block,
    # cond(V) ~ 10; measured 2e-14 over ~40 switches); at a switch the spring holds
    # 1/2 kc (p_dot 2 XTOL)^2, ~1e-17 of E.
    assert np.abs(E - E[0]).max() <= 1e-12 * E[0]


def test_large_preload_never_separates_and_equals_the_bilateral_solution():
    # The force starts from zero at the first touch, so no preload can prevent a rebound of a stiff
    # contact; with a contact softer than the structure the servo's push closes it monotonically,
    # and the preload (ripple ~ v0 sqrt(m/kc) = 0.4 mm against 5 mm of overtravel) keeps it closed.
    M, K, C = _two_dof(damping=2e-5)
    kc, v0, F0 = 1.0e3, 0.05, 5.0
    res = unilateral_response(
        M,
        K,
        1,
        kc,
        base=np.ones(2),
        approach_speed=v0,
        duration=0.3,
        fs=4000.0,
        damping=C,
        preload=F0,
        output=0,
    )
    assert res.events == ()
    assert res.contact_force[1:].min() > 0  # zero only at the first touch
    # Independent witness: the bilateral system integrated by DOP853, base ramp then stop.
    c = np.array([0.0, 1.0])
    Kc = K + kc * np.outer(c, c)
    Minv = np.linalg.inv(M)

    def rhs(t, y, sdot):
        q, v, s = y[:2], y[2:4], y[4]
        a = -Minv @ (Kc @ q + C @ v + kc * c * s)
        return np.concatenate([v, a, [sdot]])

    tol = dict(method="DOP853", rtol=1e-12, atol=1e-15)
    first = solve_ivp(rhs, (0, res.stop_time), np.zeros(5), args=(v0,), **tol)
    y = first.y[:, -1].copy()
    y[2:4] += v0  # the servo stops: the structure keeps its velocity relative to it
    late = res.t > res.stop_time
    second = solve_ivp(rhs, (res.stop_time, res.t[-1]), y, args=(0.0,), t_eval=res.t[late], **tol)
    acc = np.array([rhs(0, yy, 0.0)[2] for yy in second.y.T])
    peak = np.abs(acc).max()
    # DOP853 at rtol 1e-12 keeps the global error near 1e-10 of the peak over these ~200 periods.
    assert np.abs(res.acceleration[late] - acc).max() <= 1e-8 * peak
    early = ~late
    bilateral = np.array(
        [
            rhs(0, yy, v0)[2]
            for yy in solve_ivp(
                rhs, (0, res.stop_time), np.zeros(5), args=(v0,), t_eval=res.t[early], **tol
            ).y.T
        ]
    )
    assert np.abs(res.acceleration[early] - bilateral).max() <= 1e-8 * peak


def test_chatter_beyond_max_events_is_named_or_held_closed():
    M, K, _ = _two_dof()
    kw = dict(base=np.ones(2), approach_speed=0.3, duration=0.2, fs=2000.0)
    with pytest.raises(ChatterError, match="max_events=3"):
        unilateral_response(M, K, 1, 5.0e4, max_events=3, **kw)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = unilateral_response(M, K, 1, 5.0e4, max_events=3, on_max_events="warn", **kw)
    assert any("max_events=3" in str(w.message) for w in caught)
    assert res.bilateral_from is not None
    held = res.t > res.bilateral_from
    assert np.all(res.contact_force[held] != 0)  # held closed: the force may even pull


def test_reduced_probe_model_matches_the_fem_modes():
    probe = Probe(tip_mass=2.5e-3)
    model = probe_contact_model(probe, 0.2, n_elements=32, n_modes=6)
    free = np.sqrt(np.linalg.eigvals(np.linalg.solve(model.mass, model.stiffness)).real)
    fem_free = modal_analysis(probe, Supports(), n_elements=32, n_modes=6).omega
    # The free modes are in the basis (on a mesh with a node at 0.2 m, here the same nodes):
    # eigh's relative accuracy, ~1e-12 for these conditioned pencils.
    assert np.sort(free)[:6] == pytest.approx(fem_free, rel=1e-9)
    kc = 2.0e5
    closed = np.sort(
        np.sqrt(
            np.linalg.eigvals(
                np.linalg.solve(
                    model.mass, model.stiffness + kc * np.outer(model.contact, model.contact)
                )
            ).real
        )
    )
    fem_closed = modal_analysis(
        probe, Supports(contact=0.2, contact_stiffness=kc), n_elements=32, n_modes=3
    ).omega
    # Rayleigh-Ritz from above; free modes + the attachment mode give the first three contact
    # modes within 0.5 % (measured 0.02-0.3 %), the truncated modes' share.
    assert np.all(closed[:3] >= fem_closed * (1 - 1e-12))
    assert closed[:3] == pytest.approx(fem_closed, rel=5e-3)


def test_probe_strike_does_not_depend_on_the_detection_step(monkeypatch):
    # A contact missed between two checks would change the event list when the checks are four
    # times denser; the propagation itself is exact, so only the event times' placement differs.
    import ebantenna.simulate.unilateral as unilateral

    probe = Probe(tip_mass=2.5e-3)
    kc = tube_on_rod_stiffness(probe, material("steel"), 0.012, 0.5).total
    model = probe_contact_model(probe, 0.2, n_elements=32, n_modes=6, damping_ratio=0.015)

    def strike():
        return unilateral_response(
            model.mass,
            model.stiffness,
            model.contact,
            kc,
            base=model.base,
            damping=model.damping,
            output=model.output,
            approach_speed=0.1,
            duration=0.2,
            fs=1000.0,
            preload=0.5,
        )

    coarse = strike()
    monkeypatch.setattr(unilateral, "STEPS_PER_PERIOD", 4 * unilateral.STEPS_PER_PERIOD)
    fine = strike()
    assert len(coarse.events) >= 6  # the probe chatters: the witness has events to lose
    assert [e.kind for e in fine.events] == [e.kind for e in coarse.events]
    # Each event lies within 2 XTOL after its root; later roots inherit earlier offsets through
    # the motion (measured 1e-12 s), so 100 XTOL.
    times = np.array([[e.time for e in r.events] for r in (coarse, fine)])
    assert np.abs(times[0] - times[1]).max() <= 100 * XTOL
    peak = np.abs(coarse.acceleration).max()
    # An event time offset dt changes the motion after it by ~ omega_max dt of its size, with
    # omega_max ~ 3e4 rad/s: 3e-9 for 100 XTOL (measured 4e-11).
    assert np.abs(fine.acceleration - coarse.acceleration).max() <= 3e-9 * peak


@pytest.mark.parametrize(
    ("kwargs", "word"),
    [
        (dict(preload=-0.1), "preload"),
        (dict(contact_stiffness=0.0), "contact_stiffness"),
        (dict(approach_speed=-1.0), "approach_speed"),
        (dict(fs=0.0), "fs"),
        (dict(max_events=0), "max_events"),
        (dict(stiffness=[[-1.0]]), "stiffness"),
        (dict(mass=[[0.0]]), "mass"),
        (dict(preload=0.5), "preload > 0 needs"),  # a free mass cannot be pressed
    ],
)
def test_unilateral_bad_input_is_named(kwargs, word):
    args = dict(mass=[[1.0]], stiffness=[[0.0]], contact=0, contact_stiffness=1e4)
    args.update({k: kwargs.pop(k) for k in list(kwargs) if k in args})
    call = dict(base=0, approach_speed=1.0, duration=0.01, fs=1000.0)
    call.update(kwargs)
    with pytest.raises(ValueError, match=word):
        unilateral_response(**args, **call)


# --------------------------------------------------------------------------------------------------
# Coulomb friction


def test_free_vibration_with_dry_friction_decays_linearly():
    # Den Hartog, Mechanical Vibrations, 8.3: each half period pi/omega the amplitude drops by
    # 2 mu N / k (4 mu N / k per cycle); the motion stops at the first turning point inside
    # |x| <= mu N / k.
    m, k, muN, A0 = 1.0, 100.0, 1.0, 0.105
    res = coulomb_response(
        [[m]],
        [[k]],
        0,
        1.0,
        static_friction=muN,
        kinetic_friction=muN,
        duration=3.0,
        fs=200.0,
        displacement=[A0],
    )
    turns = res.events[1:]
    expected = [(-1) ** j * (A0 - 2 * j * muN / k) for j in range(1, 6)]
    assert [e.kind for e in turns] == ["slip+", "slip-", "slip+", "slip-", "stick"]
    # DOP853 at rtol 1e-10 (atol 1e-10 A0): the global error stays within a few rtol over three
    # periods (measured 2e-11 A0).
    assert [e.position for e in turns] == pytest.approx(expected, abs=1e-9 * A0)
    half = math.pi * math.sqrt(m / k)
    # The events are zeros of the velocity, whose slope there is omega^2 A: the time error is the
    # velocity error (~rtol omega A0) over it, ~rtol / omega per event, adding up (measured 3e-11).
    assert [e.time for e in turns] == pytest.approx(half * np.arange(1, 6), abs=1e-9)
    stuck = res.t > turns[-1].time
    assert np.allclose(res.states[stuck, 0], expected[-1], rtol=0, atol=1e-9 * A0)
    assert np.all(np.abs(res.friction_force[stuck]) <= muN)


def test_stick_slip_of_a_block_on_a_moving_belt():
    # Block (m, k to the ground) on a belt at speed v, mu_s > mu_k: it sticks until k x = mu_s N,
    # slips on a circle about x_k = mu_k N / k in the phase plane for (pi + 2 atan(v/(omega d)))
    # / omega, d = x_s - x_k, and sticks again at 2 x_k - x_s for 2 d / v.
    m, k, N, mus, muk, v = 1.0, 100.0, 1.0, 0.6, 0.4, 0.05
    w = math.sqrt(k / m)
    xs, xk = mus * N / k, muk * N / k
    d = xs - xk
    slip = (math.pi + 2 * math.atan(v / (w * d))) / w
    stick = 2 * d / v
    res = coulomb_response(
        [[m]],
        [[k]],
        0,
        N,
        static_friction=mus,
        kinetic_friction=muk,
        duration=1.5,
        fs=1000.0,
        surface_speed=v,
        velocity=[v],
    )
    kinds = [e.kind for e in res.events]
    assert kinds[:5] == ["stick", "slip-", "stick", "slip-", "stick"]
    times = np.array([e.time for e in res.events[:5]])
    expected = np.array(
        [0, xs / v, xs / v + slip, xs / v + slip + stick, xs / v + 2 * slip + stick]
    )
    # Event times from DOP853's event root finder at rtol 1e-10: ~rtol / omega = 1e-11 s each,
    # adding up over four events (measured 4e-11 s).
    assert times == pytest.approx(expected, abs=1e-9)
    # Position at the sticking event: rtol times the state's size (v0 = 0.05).
    assert res.events[2].position == pytest.approx(2 * xk - xs, abs=1e-11)


def test_friction_bad_input_is_named():
    kw = dict(duration=0.1, fs=100.0)
    with pytest.raises(ValueError, match="kinetic_friction must be <= static_friction"):
        coulomb_response([[1.0]], [[1.0]], 0, 1.0, static_friction=0.2, kinetic_friction=0.3, **kw)
    with pytest.raises(ValueError, match="normal_force"):
        coulomb_response([[1.0]], [[1.0]], 0, -1.0, static_friction=0.2, kinetic_friction=0.1, **kw)


def test_friction_follows_a_normal_force_in_time():
    # No normal force, no friction: the oscillator rings as if frictionless, x0 cos(omega t).
    res = coulomb_response(
        [[1.0]],
        [[100.0]],
        0,
        lambda t: 0.0,
        static_friction=0.5,
        kinetic_friction=0.4,
        duration=1.0,
        fs=100.0,
        displacement=[0.01],
    )
    # DOP853 at rtol 1e-10 over 1.6 periods: global error a few rtol of the amplitude.
    assert np.abs(res.states[:, 0] - 0.01 * np.cos(10 * res.t)).max() <= 1e-9 * 0.01
    assert np.all(res.friction_force == 0)


def test_probe_model_rejects_a_contact_off_the_probe():
    with pytest.raises(ValueError, match="contact must lie in"):
        probe_contact_model(Probe(), 0.45)
    with pytest.raises(ValueError, match="damping_ratio"):
        probe_contact_model(Probe(), 0.2, damping_ratio=1.0)


def test_mass_inverse_inverts_and_names_a_mass_that_is_not_positive_definite():
    rng = np.random.default_rng(2)
    A = rng.normal(size=(4, 4))
    M = A @ A.T + 4 * np.eye(4)
    # a backward-stable inverse: residual within a few n eps cond(M)
    bound = 10 * 4 * np.finfo(float).eps * np.linalg.cond(M)
    assert np.abs(mass_inverse(M) @ M - np.eye(4)).max() < bound
    singular = [[1.0, 1.0], [1.0, 1.0]]
    with pytest.raises(ValueError, match="mass must be positive definite"):
        mass_inverse(np.array(singular))
    with pytest.raises(ValueError, match="mass must be positive definite"):
        unilateral_response(singular, np.eye(2), 0, 1e3, base=0, approach_speed=0.1,
                            duration=0.01, fs=1000.0)
    with pytest.raises(ValueError, match="mass must be positive definite"):
        stick_slip_response(singular, np.eye(2), 0, 1.0, static_friction=0.5,
                            kinetic_friction=0.5, duration=0.01, fs=1000.0)
