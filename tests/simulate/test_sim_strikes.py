"""The strike through a contact that only pushes (``unilateral_contact``), against witnesses:
the unreduced bodies' static flexibility, the damped eigenvalues, an ODE solver, the filter."""

import dataclasses
import math

import numpy as np
import pytest
import scipy.integrate as spi
import scipy.linalg as sla
import scipy.signal as sps

from ebantenna.fem.coupling import craig_bampton, probe_substructure, rod_substructure
from ebantenna.probe import Probe, material
from ebantenna.simulate import Scene, builtin_scene, simulate, simulate_batch
from ebantenna.simulate.strikes import UNFILTERED_RATE, strike_accelerations, strike_model
from ebantenna.simulate.unilateral import unilateral_response

EPS = np.finfo(float).eps
PROBE = Probe(tip_mass=2.5e-3)


def _model(name="brass", contact=0.2, preload=0.5, probe_loss=0.0, rod_loss=0.0):
    scene = builtin_scene("paper")
    effect = scene.effect("object_modes")
    rod = effect.rod(name)
    p_sub = probe_substructure(PROBE, contact, n_elements=40)
    r_sub = rod_substructure(rod, n_elements=24)
    p = craig_bampton(dataclasses.replace(p_sub, loss_factor=probe_loss), 40)
    r = craig_bampton(dataclasses.replace(r_sub, loss_factor=rod_loss), 20)
    k_c = effect.contact_stiffness(material(name), PROBE, preload)
    return strike_model(p, r, contact, k_c, preload, 3000.0), p_sub, r_sub


def _flexibility(sub):
    """Static deflection at the interface per unit force there, from the unreduced body."""
    e = np.zeros(sub.stiffness.shape[0])
    e[sub.interface] = 1.0
    return float(e @ np.linalg.solve(sub.stiffness, e)), float(np.linalg.cond(sub.stiffness))


@pytest.mark.parametrize("name", ["pvc", "steel"])
def test_the_truncated_bases_keep_each_bodys_static_flexibility_exactly(name):
    # The interface constraint mode is the static deflection shape, so however few modes are
    # kept, c K^-1 c is the two bodies' unreduced flexibilities in series (the preload's
    # overtravel rests on it). Both sides solve with K: rounding ~ n eps cond(K).
    model, p, r = _model(name)
    s = model.structure
    fp, cp = _flexibility(p)
    fr, cr = _flexibility(r)
    ours = float(s.contact @ np.linalg.solve(s.stiffness, s.contact))
    bound = 10 * p.stiffness.shape[0] * EPS * max(cp, cr)
    assert math.isclose(ours, fp + fr, rel_tol=bound)
    assert s.mass.shape[0] < p.stiffness.shape[0] // 4  # and it is a small model


def test_the_closed_strike_model_is_a_ritz_model_of_the_coupled_rod_and_probe():
    # Keeping fewer fixed-interface modes restricts the same coupled system to a subspace:
    # every Ritz frequency lies at or above the exact one of the same index (Rayleigh-Ritz),
    # here the 40/20-mode coupled system, itself within 1.3e-5 of the unreduced one.
    model, p, r = _model("aluminium")
    s = model.structure
    closed = s.stiffness + model.contact_stiffness * np.outer(s.contact, s.contact)
    ours = np.sqrt(sla.eigh(closed, s.mass, eigvals_only=True)) / (2 * math.pi)
    pc = craig_bampton(p, 40)
    rc = craig_bampton(r, 20)
    n_p = pc.stiffness.shape[0]
    K = sla.block_diag(pc.stiffness, rc.stiffness)
    K[n_p - 1, n_p - 1] += model.contact_stiffness
    K[-1, -1] += model.contact_stiffness
    K[n_p - 1, -1] = K[-1, n_p - 1] = -model.contact_stiffness
    full = np.sqrt(sla.eigh(K, sla.block_diag(pc.mass, rc.mass), eigvals_only=True))
    full = full[: ours.size] / (2 * math.pi)
    assert np.all(ours >= full * (1 - 1e-9))  # rounding of two eigh solves of cond ~1e9
    below = full < 1000.0  # well under the 3 kHz cut: the truncation error is small there
    assert np.allclose(ours[below], full[below], rtol=1e-2)


def test_each_body_is_damped_by_its_loss_factor_over_two_at_its_own_modes():
    # Witness: the complex eigenvalues of the first-order system of each body on its own
    # (interface free): zeta = eta / 2 at every mode, to rounding.
    eta_p, eta_r = 0.03, 0.02
    model, _, _ = _model("oak", probe_loss=eta_p, rod_loss=eta_r)
    s = model.structure
    n_p = int(np.flatnonzero(s.contact > 0)[0]) + 1
    for part, eta in ((slice(0, n_p), eta_p), (slice(n_p, None), eta_r)):
        M, K, C = s.mass[part, part], s.stiffness[part, part], s.damping[part, part]
        n = M.shape[0]
        A = np.block(
            [[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]]
        )
        lam = np.linalg.eigvals(A)
        lam = lam[lam.imag > 0]
        zeta = -lam.real / np.abs(lam)
        assert np.allclose(zeta, eta / 2, rtol=1e-8)  # eig of a 2n system with cond ~1e6


def _event_driven_witness(model, speed, t_out):
    """The strike by scipy's event-aware DOP853: the closed and the open state's ODEs, switched
    where the contact force falls to zero or the gap closes, the servo stopped at its time."""
    s = model.structure
    kc, c, n = model.contact_stiffness, s.contact, s.mass.shape[0]
    Minv = np.linalg.inv(s.mass)
    v0 = speed * model.contact
    stop = model.preload * (1 / kc + c @ np.linalg.solve(s.stiffness, c)) / v0

    def servo(t):
        return v0 * min(t, stop)

    def rhs(t, y, closed):
        q, v = y[:n], y[n:]
        load = kc * c * (c @ q + servo(t)) if closed else 0.0
        return np.concatenate([v, -Minv @ (s.stiffness @ q + s.damping @ v + load)])

    def force(t, y, closed):  # closed: falls through zero when the probe lifts off
        return c @ y[:n] + servo(t)

    force.terminal, force.direction = True, -1
    gap = force  # open: the penetration rises through zero when the gap closes
    t, y, closed, stopped = 0.0, np.zeros(2 * n), True, False
    pieces, restrikes = [], 0
    while t < t_out[-1]:
        end = t_out[-1] if stopped else stop
        event = force if closed else gap
        event.direction = -1 if closed else 1
        sol = spi.solve_ivp(
            rhs, (t, end), y, args=(closed,), events=event, method="DOP853", rtol=1e-11,
            atol=1e-16, dense_output=True,
        )  # fmt: skip
        pieces.append((t, sol.t[-1], closed, sol.sol))
        t, y = sol.t[-1], sol.y[:, -1].copy()
        if sol.status == 1:  # an event: switch state
            closed = not closed
            restrikes += closed
        elif not stopped:  # the servo stops: the structure keeps its velocity
            y[n:] += s.base * v0
            stopped = True
    acc = np.empty(t_out.size)
    for i, ti in enumerate(t_out):
        t0, t1, closed, sol = next(p for p in pieces if p[0] <= ti <= p[1])
        acc[i] = s.output @ rhs(ti, sol(ti), closed)[n:]
    return acc, restrikes


@pytest.mark.parametrize(("name", "contact"), [("steel", 0.1), ("pvc", 0.3)])
def test_the_strike_matches_an_event_driven_ode_solver(name, contact):
    # Lift-offs and re-strikes included: the modal propagator with brentq events against
    # solve_ivp with its own event location, over the first 0.1 s (a few re-strikes).
    model, _, _ = _model(name, contact=contact, probe_loss=0.03, rod_loss=0.02)
    rate, n_out = 8000.0, 801
    acc, restrikes = strike_accelerations(
        [model], [0], [0.5], rate=rate, n_samples=n_out, max_events=400
    )
    witness, n_witness = _event_driven_witness(model, 0.5, np.arange(n_out) / rate)
    assert restrikes[0] == n_witness >= 1
    # both locate events to ~1e-12 s and integrate to ~1e-11: far below 1e-6 of the peak
    assert np.allclose(acc[0], witness, rtol=0, atol=1e-6 * np.abs(witness).max())


@pytest.mark.parametrize(("name", "contact"), [("steel", 0.1), ("pvc", 0.3)])
def test_the_reference_march_matches_the_event_driven_ode_solver(name, contact):
    # The same witness for the reference (every step in turn) as for the engine above.
    model, _, _ = _model(name, contact=contact, probe_loss=0.03, rod_loss=0.02)
    s, rate, n_out = model.structure, 8000.0, 801
    res = unilateral_response(
        s.mass, s.stiffness, s.contact, model.contact_stiffness, base=s.base,
        approach_speed=0.5 * model.contact, duration=(n_out - 1) / rate, fs=rate,
        damping=s.damping, output=s.output, preload=model.preload, max_events=400,
        method="steps",
    )  # fmt: skip
    witness, n_witness = _event_driven_witness(model, 0.5, np.arange(n_out) / rate)
    assert res.n_impacts - 1 == n_witness >= 1
    # both locate events to ~1e-12 s and integrate to ~1e-11: far below 1e-6 of the peak
    assert np.allclose(res.acceleration, witness, rtol=0, atol=1e-6 * np.abs(witness).max())


#: the rod and the contact, with the probe's and the rod's damping (undamped, they chatter on)
RIGID = {"structural_damping": {}, "object_modes": {}, "object_damping": {}, "tip_mass": {}}


def _bare(effects, **kw):
    kw.setdefault("fs", 8000.0)
    return Scene(
        probe=PROBE, effects={**RIGID, "unilateral_contact": {}, **effects},
        max_frequency=3000.0, n_modes=16, **kw,
    )  # fmt: skip


def test_the_simulator_reads_the_strike_at_its_sample_times():
    # Without the DLPF the strike is computed at UNFILTERED_RATE x fs and every such sample is
    # a reading: the simulator's X axis is the strike itself, sample for sample.
    scene = _bare({}, duration=0.2)
    _, ax, _, x, _ = simulate_batch(scene, contact=[0.12, 0.3], material=["pvc", "steel"])
    fine_rate = UNFILTERED_RATE * scene.fs
    for i, (c, name) in enumerate([(0.12, "pvc"), (0.3, "steel")]):
        model, _, _ = _model(name, contact=c, probe_loss=0.03, rod_loss=material(name).loss_factor)
        acc, n_re = strike_accelerations(
            [model], [0], [scene.sweep_speed], rate=fine_rate,
            n_samples=UNFILTERED_RATE * (scene.n_samples - 1) + 2, max_events=400,
        )  # fmt: skip
        assert x.restrikes[i] == n_re[0]
        # same arithmetic up to the reduction's rounding (two eigh solves of cond ~1e9)
        assert np.allclose(ax[i], acc[0, ::UNFILTERED_RATE][: scene.n_samples], atol=0, rtol=1e-6)


def test_with_the_dlpf_the_strike_is_filtered_at_the_internal_rate_then_decimated():
    # Witness: sosfilt of the strike at 8 kHz with the datasheet filter, every 8th sample.
    scene = _bare({"dlpf": {}}, fs=1000.0, duration=0.3)
    _, ax, _, _, _ = simulate_batch(scene, contact=0.2, material="oak")
    dlpf = scene.effect("dlpf")
    model, _, _ = _model("oak", probe_loss=0.03, rod_loss=material("oak").loss_factor)
    n_int = 8 * (scene.n_samples - 1) + 2
    acc, _ = strike_accelerations(
        [model], [0], [scene.sweep_speed], rate=8000.0, n_samples=n_int, max_events=400
    )
    sos = sps.butter(2, dlpf.bandwidth, fs=8000.0, output="sos")
    witness = sps.sosfilt(sos, acc[0])[::8][: scene.n_samples]
    assert np.allclose(ax[0], witness, atol=1e-6 * np.abs(witness).max(), rtol=0)


def test_the_contact_only_pushes_in_the_simulated_strikes():
    scene = _bare({}, duration=0.3)
    _, ax, _, x, _ = simulate_batch(scene, contact=[0.1, 0.38], material="brass")
    linear = simulate_batch(scene.with_(effects=RIGID),
                            contact=[0.1, 0.38], material="brass")[1]  # fmt: skip
    assert x.restrikes.shape == (2,) and np.all(x.restrikes >= 0)
    assert not np.allclose(ax, linear)  # the two contact laws give two different strikes
    rec = simulate(scene.with_(contact=0.1, material="brass"))
    assert rec.metadata["restrikes"] == x.restrikes[0]
    np.testing.assert_array_equal(rec.ax, ax[0])


def test_unilateral_contact_needs_the_rod():
    with pytest.raises(ValueError, match="'unilateral_contact' needs 'object_modes'"):
        Scene(effects=["unilateral_contact"])
    with pytest.raises(ValueError, match="max_events"):
        Scene(effects={"object_modes": {}, "unilateral_contact": {"max_events": 0}})
    assert "unilateral_contact" in builtin_scene("paper").effect_names  # the rig's contact pushes


def test_undamped_bodies_chatter_on_and_say_so_once():
    # Without any damping the probe never comes to rest on the rod: max_events caps the work
    # and one warning (not one per strike) says how many strikes were held closed.
    scene = Scene(
        probe=PROBE,
        effects={"object_modes": {}, "unilateral_contact": {"max_events": 5}, "tip_mass": {}},
        fs=8000.0, max_frequency=3000.0, n_modes=16, duration=0.2,
    )  # fmt: skip
    with pytest.warns(RuntimeWarning, match=r"2 of 2 strikes chattered beyond max_events=5") as w:
        _, _, _, x, _ = simulate_batch(scene, contact=[0.15, 0.3], material="steel")
    assert len(w) == 1
    assert np.all(x.restrikes >= 2)  # five contact changes: at least two re-strikes


def test_the_chatter_near_the_tip_is_the_models_not_the_event_grids(monkeypatch):
    # Contacts near the bare probe's tip chatter for a long time: the contact mode (~3 kHz) is
    # lossless in the spring and lightly damped by the bodies, and the contact keeps opening
    # while its amplitude exceeds the preload's deflection F0 / k_c. Watching the force on a
    # grid four times finer finds the same events; the motions then differ only by the event
    # times' tolerance: each event within 2 time_tolerance, shifting what follows by at most
    # omega_max 2 time_tolerance relative, summed over the events.
    import ebantenna.simulate.unilateral as unilateral

    probe = Probe()
    scene = builtin_scene("paper")
    effect = scene.effect("object_modes")
    contact, preload = 0.3675, 0.5
    p = craig_bampton(probe_substructure(probe, contact, n_elements=40), 40)  # PMMA's loss
    r = craig_bampton(rod_substructure(effect.rod("pvc"), n_elements=24), 20)  # PVC's
    k_c = effect.contact_stiffness(material("pvc"), probe, preload)
    s = strike_model(p, r, contact, k_c, preload, 3000.0).structure
    runs = []
    for steps in (16, 64):
        monkeypatch.setattr(unilateral, "STEPS_PER_PERIOD", steps)
        runs.append(
            unilateral.unilateral_response(
                s.mass, s.stiffness, s.contact, k_c, base=s.base, approach_speed=0.5 * contact,
                duration=0.05, fs=8000.0, damping=s.damping, output=s.output, preload=preload,
                max_events=2000, time_tolerance=1e-12,
            )
        )  # fmt: skip
    coarse, fine = runs
    assert len(coarse.events) == len(fine.events) > 20
    assert [e.kind for e in coarse.events] == [e.kind for e in fine.events]
    closed = s.stiffness + k_c * np.outer(s.contact, s.contact)
    omega_max = math.sqrt(sla.eigvalsh(closed, s.mass).max())
    bound = len(fine.events) * omega_max * 2e-12 * 2
    assert (
        np.abs(coarse.acceleration - fine.acceleration).max()
        <= bound * np.abs(fine.acceleration).max()
    )


def test_without_x_modes_the_strikes_are_the_same_and_x_carries_no_modes():
    # A data set build skips the coupled eigenproblem per strike: the strikes never read it.
    scene = builtin_scene("paper")
    kw = dict(contact=[0.12, 0.3, 0.37], material=["pvc", "steel", "oak"], seeds=[4, 5, 6],
              show_progress=False)  # fmt: skip
    _, ax, az, x, _ = simulate_batch(scene, **kw)
    _, ax_, az_, x_, _ = simulate_batch(scene, x_modes=False, **kw)
    np.testing.assert_array_equal(ax_, ax)
    np.testing.assert_array_equal(az_, az)
    np.testing.assert_array_equal(x_.restrikes, x.restrikes)
    np.testing.assert_array_equal(x_.preload, x.preload)
    assert x.omega.shape[1] > 0 and x_.omega.shape == (3, 0) and x_.frequencies(0).size == 0
