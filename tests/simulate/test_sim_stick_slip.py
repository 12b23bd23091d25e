"""Coulomb friction along the rod: the exact stick-slip propagation and the ``coulomb_friction``
effect, against an analytic oscillator, the integrated witness and the pinned probe's modes."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg as sla

from ebantenna.fem import Supports, modal_analysis
from ebantenna.fem.coupling import craig_bampton, probe_substructure
from ebantenna.simulate import Scene, builtin_scene, simulate_batch
from ebantenna.simulate.effects import CoulombFriction
from ebantenna.simulate.friction_ode import coulomb_response
from ebantenna.simulate.stick_slip import friction_model, stick_slip_response
from ebantenna.simulate.unilateral import ChatterError

# A chain of three masses held by friction at the middle one: it slips, sticks, slips again.
K_CHAIN = 1000.0 * np.array([[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]])
M_CHAIN = np.diag([1.0, 0.5, 0.3])
C_CHAIN = 1e-3 * K_CHAIN  # proportional: the frictionless motion has a closed form
V_CHAIN = np.array([0.5, 1.0, 2.0])


def chain_exact(t):
    """Acceleration of the chain's last mass without friction (modal closed form)."""
    lam, phi = sla.eigh(K_CHAIN, M_CHAIN)  # mass-normalised
    w = np.sqrt(lam)
    zeta = 1e-3 * w / 2
    wd = w * np.sqrt(1 - zeta**2)
    p = phi.T @ M_CHAIN @ V_CHAIN
    decay = np.exp(-zeta * w * t[:, None])
    q = decay * np.sin(wd * t[:, None]) * p / wd
    qd = decay * (np.cos(wd * t[:, None]) - zeta * w / wd * np.sin(wd * t[:, None])) * p
    force = -(K_CHAIN @ (phi @ q.T)) - C_CHAIN @ (phi @ qd.T)
    return np.linalg.solve(M_CHAIN, force)[2]


@pytest.mark.parametrize("method", ["blocks", "steps"])
def test_one_oscillator_loses_two_mu_n_over_k_per_half_period_and_sticks(method):
    # m = 1 kg, k = 100 N/m, launched at 1 m/s against mu N = 1 N: each slip is half a period
    # about the shifted rest position -+mu N / k; it sticks at the first turning point whose
    # spring force k|x| is at most mu_s N (Den Hartog, section 8.3).
    k, mu_n, v0 = 100.0, 1.0, 1.0
    omega = math.sqrt(k)
    r = stick_slip_response([[1.0]], [[k]], 0, 1.0, static_friction=1.0, kinetic_friction=1.0,
                            duration=3.0, fs=100.0, velocity=[v0], method=method)  # fmt: skip
    shift = mu_n / k
    amplitude = math.hypot(shift, v0 / omega)
    first = (math.pi / 2 - math.asin(shift / amplitude)) / omega  # the first turning point
    x, times = -shift + amplitude, [first]
    while k * abs(x) > mu_n:  # the spring overcomes friction: half a period more
        x = -math.copysign(1.0, x) * (abs(x) - 2 * shift)  # the same side if |x| < 2 shift
        times.append(times[-1] + math.pi / omega)
    assert [kind for _, kind in r.events] == (
        ["slip+"] + ["slip-", "slip+"] * ((len(times) - 1) // 2) + ["slip-"] * (len(times) % 2 == 0)
        + ["stick"]
    )  # fmt: skip
    # each event lies within time_tolerance (1e-12 s) after its instant; ten times that per
    # event bounds the rounding of the phases as well
    assert np.allclose([t for t, _ in r.events[1:]], times, rtol=0, atol=1e-11 * len(times))
    stuck = r.t > times[-1] + 1e-9
    np.testing.assert_allclose(r.friction_force[stuck], k * x, rtol=1e-9)  # holds k x exactly
    assert np.all(np.abs(r.acceleration[stuck]) <= 1e-9 * k * abs(x))  # ... and rests


def test_frictionless_chain_is_the_modal_closed_form():
    r = stick_slip_response(M_CHAIN, K_CHAIN, 1, 0.0, static_friction=0.6, kinetic_friction=0.4,
                            duration=2.0, fs=1000.0, velocity=V_CHAIN, damping=C_CHAIN,
                            output=2)  # fmt: skip
    exact = chain_exact(r.t)
    # exact propagation restarted at every block of steps: some 400 restarts, each rounding
    # the state at a few eps times the eigenvector matrix's condition (~10)
    np.testing.assert_allclose(r.acceleration, exact, rtol=0, atol=1e-11 * np.abs(exact).max())
    assert [kind for _, kind in r.events] == ["slip+"]


@pytest.mark.parametrize("method", ["blocks", "steps"])
def test_chain_with_stick_and_slip_agrees_with_the_integrated_witness(method):
    kw = dict(static_friction=0.6, kinetic_friction=0.4, duration=2.0, fs=1000.0,
              velocity=V_CHAIN, damping=C_CHAIN, output=2)  # fmt: skip
    ours = stick_slip_response(M_CHAIN, K_CHAIN, 1, 5.0, method=method, **kw)
    witness = coulomb_response(M_CHAIN, K_CHAIN, 1, 5.0, rtol=1e-12, **kw)
    kinds = [kind for _, kind in ours.events]
    assert kinds == [e.kind for e in witness.events]
    assert "stick" in kinds and kinds.count("stick") >= 2  # the case exercises every state
    # event times: ours within 1e-12 s, the witness's within its integration error
    times = np.array([t for t, _ in ours.events])
    np.testing.assert_allclose(times, [e.time for e in witness.events], rtol=0, atol=1e-10)
    # the witness's own error, measured on the same chain without friction against the closed
    # form, bounds how far it may lie from the exact stick-slip motion (ten times: the events
    # restart its integration a dozen times)
    free = coulomb_response(M_CHAIN, K_CHAIN, 1, 0.0, rtol=1e-12, **kw)
    exact = chain_exact(free.t)
    own_error = np.abs(free.acceleration - exact).max() / np.abs(exact).max()
    peak = np.abs(witness.acceleration).max()
    assert np.abs(ours.acceleration - witness.acceleration).max() <= 10 * own_error * peak
    np.testing.assert_allclose(ours.friction_force, witness.friction_force, rtol=0,
                               atol=10 * own_error * peak * M_CHAIN.max())  # fmt: skip


def test_too_many_changes_raise_a_chatter_error():
    with pytest.raises(ChatterError, match="max_events=2"):
        stick_slip_response([[1.0]], [[100.0]], 0, 1.0, static_friction=1.0,
                            kinetic_friction=1.0, duration=2.0, fs=100.0, velocity=[1.0],
                            max_events=2)  # fmt: skip


def test_bad_input_is_named():
    kw = dict(static_friction=0.5, kinetic_friction=0.4, duration=1.0, fs=100.0)
    with pytest.raises(ValueError, match="contact must be a coordinate index below 1"):
        stick_slip_response([[1.0]], [[1.0]], 1, 1.0, **kw)
    with pytest.raises(ValueError, match="normal_force"):
        stick_slip_response([[1.0]], [[1.0]], 0, -1.0, **kw)
    with pytest.raises(ValueError, match="kinetic_friction must be <= static_friction"):
        stick_slip_response([[1.0]], [[1.0]], 0, 1.0, **{**kw, "kinetic_friction": 0.6})
    with pytest.raises(ValueError, match="kinetic_friction must be <= static_friction"):
        CoulombFriction(static_friction=0.2, kinetic_friction=0.3)
    with pytest.raises(ValueError, match="static_friction"):
        CoulombFriction(static_friction=-0.1)
    with pytest.raises(ValueError, match="'coulomb_friction' needs 'object_modes'"):
        Scene(effects=("coulomb_friction",))


def _friction_scene(mu):
    return Scene(
        effects=("object_modes", CoulombFriction(static_friction=mu, kinetic_friction=mu)),
        contact=0.25,
        material="steel",
    )


def test_probe_held_by_friction_rings_as_the_probe_pinned_at_the_contact():
    # Friction far above what the motion can overcome: the contact point stops sliding within
    # the first instants and Z rings at the frequencies of the probe pinned there (the X axis's
    # rigid-contact modes), not at the free probe's.
    scene = _friction_scene(50.0)
    t, _, az, _, z = simulate_batch(scene, show_progress=False)
    pinned = modal_analysis(scene.probe, Supports(contact=0.25), n_elements=scene.n_elements,
                            n_modes=4).frequencies  # fmt: skip
    spectrum = np.abs(np.fft.rfft(az[0] * np.hanning(t.size)))
    f = np.fft.rfftfreq(t.size, 1 / scene.fs)
    peak = f[np.argmax(spectrum)]
    # the FFT's bin is 1 Hz (one second); the peak lies within a bin of a pinned mode
    assert np.min(np.abs(pinned - peak)) <= 1.0
    assert np.min(np.abs(z.frequencies() - peak)) > 5.0  # and far from every free mode


def test_friction_changes_only_the_z_axis():
    base = Scene(effects=("object_modes",), contact=0.25, material="steel")
    _, ax0, az0, _, _ = simulate_batch(base, show_progress=False)
    _, ax1, az1, _, _ = simulate_batch(_friction_scene(0.45), show_progress=False)
    np.testing.assert_array_equal(ax1, ax0)  # X is the same computation
    assert np.abs(az1 - az0).max() > 0.1 * np.abs(az0).max()  # friction holds Z


def test_paper_scene_with_friction_runs_every_sensor_effect():
    scene = builtin_scene("paper")
    scene = scene.with_(effects=(*scene.effects, "coulomb_friction"), contact=0.3)
    t, ax, az, _, _ = simulate_batch(scene, material=["oak", "pvc"], seeds=[1, 2],
                                     show_progress=False)  # fmt: skip
    assert az.shape == (2, scene.n_samples) and np.all(np.isfinite(az))


def _paper_z_events(contact):
    scene = builtin_scene("paper")
    obj = scene.effect("object_modes")
    sub = probe_substructure(scene.probe, contact, hinge=scene.hinge, n_elements=scene.n_elements)
    m = friction_model(craig_bampton(sub, obj.probe_modes), obj.preload, scene.max_frequency)
    effect = CoulombFriction()
    return stick_slip_response(
        m.mass, m.stiffness, m.mass.shape[0] - 1, m.normal_force,
        static_friction=effect.static_friction, kinetic_friction=effect.kinetic_friction,
        duration=1.0, fs=8000.0, velocity=m.rotation * scene.tilt_ratio * scene.sweep_speed,
        damping=m.damping, output=m.output,
    ).events  # fmt: skip


@pytest.mark.parametrize("contact", [0.1, 0.2, 0.25, 0.3, 0.35, 0.39])
def test_paper_probe_sticks_within_20_ms_beyond_a_fifth_of_its_length(contact):
    # theory/touched_object.rst: "within the first 20 ms ... beyond a fifth of the probe"
    events = _paper_z_events(contact)
    assert events[-1][1] == "stick" and events[-1][0] <= 0.02 and len(events) <= 10


def test_paper_probe_near_the_hinge_slips_again_and_again():
    # ... "nearer the hinge ... it slips again and again: for about half a second with the
    # contact 2 cm from the hinge, and through the whole one-second recording at 1 cm"
    events = _paper_z_events(0.02)
    assert len(events) > 10 and 0.4 < events[-1][0] <= 0.6
    events = _paper_z_events(0.01)
    assert len(events) > 10 and events[-1][0] > 0.9
