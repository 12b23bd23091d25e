"""The modal response and the physics effects, each against an independent witness."""

import numpy as np
import pytest
import scipy.linalg as sla

from ebantenna.fem import Supports, modal_analysis
from ebantenna.fem.assembly import apply_supports, assemble, beam_mesh
from ebantenna.probe import Probe, material
from ebantenna.simulate import builtin_scene, modal_terms, simulate, simulate_batch
from ebantenna.simulate.effects import ContactCompliance


def _analytic_undamped(probe, contact, omega_sweep, t, max_frequency, n_elements):
    """a(t) = -Omega sum_k phi_k(L) p_k omega_k sin(omega_k t), straight from the FEM result."""
    res = modal_analysis(probe, Supports(contact=contact), n_elements=n_elements, n_modes=8)
    u0 = np.zeros(2 * res.nodes.size)
    u0[0::2], u0[1::2] = res.nodes, 1.0
    p = res.modal_coordinates(u0)
    tip = res.displacement(np.array([probe.length]))[0]
    out = np.zeros_like(t)
    for k in range(res.n_modes):
        if res.frequencies[k] < max_frequency:
            out -= omega_sweep * tip[k] * p[k] * res.omega[k] * np.sin(res.omega[k] * t)
    return out


def test_ideal_scene_equals_analytic_modal_solution_and_ignores_seed():
    scene = builtin_scene("ideal").with_(contact=0.23, sweep_speed=0.7)
    rec = simulate(scene, seed=1)
    expected = _analytic_undamped(scene.probe, 0.23, 0.7, rec.t, 480.0, scene.n_elements)
    scale = np.abs(expected).max()
    assert scale > 1.0  # a real signal, m/s^2
    assert np.abs(rec.ax - expected).max() <= 1e-12 * scale
    assert np.array_equal(simulate(scene, seed=99).ax, rec.ax)


def test_full_modal_sum_equals_direct_time_integration():
    # Witness: the FEM equations of motion M u'' + K u = 0 solved by the matrix exponential, with
    # u(0) = 0 and u'(0) the rigid rotation minus the fixed DOFs; every mode is kept.
    probe = Probe()
    contact, omega_sweep, n_el = 0.15, 0.5, 4
    scene = builtin_scene("ideal").with_(
        contact=contact,
        sweep_speed=omega_sweep,
        n_elements=n_el,
        n_modes=8,
        max_frequency=2.0e5,
        fs=4.0e5,
        duration=2e-3,
    )
    nodes = beam_mesh(probe.length, contact, n_el)
    K, M = assemble(nodes, probe)
    Kf, Mf, free = apply_supports(K, M, nodes, probe, Supports(contact=contact))
    assert len(free) == 7  # all modes simulated
    v0 = np.zeros(2 * nodes.size)
    v0[0::2], v0[1::2] = nodes * omega_sweep, omega_sweep
    A = np.linalg.solve(Mf, Kf)
    n = len(free)
    system = np.block([[np.zeros((n, n)), np.eye(n)], [-A, np.zeros((n, n))]])
    rec = simulate(scene)
    tip = list(free).index(2 * (nodes.size - 1))
    state0 = np.concatenate([np.zeros(n), v0[free]])
    direct = np.array([-(A @ (sla.expm(system * t) @ state0)[:n])[tip] for t in rec.t[::40]])
    assert np.allclose(rec.ax[::40], direct, rtol=0, atol=1e-8 * np.abs(direct).max())


def test_damped_modal_sum_equals_time_integration_with_modal_damping():
    # Witness: state-space exponential with modal damping C = M Phi diag(2 zeta w) Phi^T M.
    probe = Probe()
    scene = builtin_scene("ideal").with_(
        contact=0.3,
        n_elements=3,
        n_modes=6,
        max_frequency=2.0e5,
        fs=4.0e5,
        duration=3e-3,
        effects=("structural_damping",),
    )
    res = modal_analysis(probe, Supports(contact=0.3), n_elements=3, n_modes=5)
    Mf = res.mass_matrix[np.ix_(res.free, res.free)]
    phi = res.shapes[res.free]
    Kf = Mf @ phi @ np.diag(res.omega**2) @ phi.T @ Mf
    C = Mf @ phi @ np.diag(2 * 0.015 * res.omega) @ phi.T @ Mf
    n = len(res.free)
    Minv = np.linalg.inv(Mf)
    system = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ Kf, -Minv @ C]])
    v0 = np.zeros(2 * res.nodes.size)
    v0[0::2], v0[1::2] = res.nodes * scene.sweep_speed, scene.sweep_speed
    state0 = np.concatenate([np.zeros(n), v0[res.free]])
    tip = list(res.free).index(2 * (res.nodes.size - 1))
    rec = simulate(scene)
    direct = []
    for t in rec.t[::60]:
        s = sla.expm(system * t) @ state0
        direct.append((system @ s)[n + tip])
    direct = np.array(direct)
    assert np.allclose(rec.ax[::60], direct, rtol=0, atol=1e-8 * np.abs(direct).max())


def test_ideal_spectral_peaks_are_the_fem_natural_frequencies():
    scene = builtin_scene("ideal").with_(contact=0.12, duration=8.0)
    rec = simulate(scene)
    fem = modal_analysis(scene.probe, Supports(contact=0.12), n_elements=40, n_modes=8)
    expected = fem.frequencies[fem.frequencies < 480.0]
    spectrum = np.abs(np.fft.rfft(rec.ax * np.hanning(rec.n_samples)))
    freqs = np.fft.rfftfreq(rec.n_samples, 1 / rec.fs)
    peaks = [
        i
        for i in range(1, spectrum.size - 1)
        if spectrum[i] > spectrum[i - 1]
        and spectrum[i] > spectrum[i + 1]
        and spectrum[i] > 1e-3 * spectrum.max()
    ]
    assert len(peaks) == expected.size
    # Hann-window peaks fall within one bin (0.125 Hz) of the true frequency.
    assert np.abs(freqs[peaks] - expected).max() <= 0.125


def test_energy_decays_under_damping_only():
    base = builtin_scene("ideal").with_(contact=0.2, duration=2.0)
    windows = lambda a: (a.reshape(20, -1) ** 2).mean(axis=1)  # noqa: E731
    undamped = windows(simulate(base).ax)
    damped = windows(simulate(base.with_(effects=("structural_damping",))).ax)
    assert np.all(np.diff(damped) < 0)
    assert undamped[-1] > 0.5 * undamped[0]  # no decay without damping
    assert damped[-1] < 0.01 * damped[0]


def test_contact_compliance_equals_fem_with_a_spring_and_lowers_frequencies():
    scene = builtin_scene("ideal").with_(contact=0.2, effects=("contact_compliance",))
    probe = scene.probe
    rigid = modal_terms(builtin_scene("ideal").with_(contact=0.2))[0].frequencies()
    for name in ("steel", "pvc"):
        x, _ = modal_terms(scene.with_(material=name))
        k = ContactCompliance().stiffness(material(name), probe)
        fem = modal_analysis(
            probe, Supports(contact=0.2, contact_stiffness=k), n_elements=40, n_modes=8
        )
        assert np.allclose(x.frequencies(), fem.frequencies[: x.frequencies().size], rtol=1e-12)
        assert np.all(x.frequencies() < rigid)
    # Hertz: softer objects, softer contact (wood indented across its grain, 1.48 GPa, softer
    # than PVC's 3 GPa).
    stiff = [ContactCompliance().stiffness(material(m), probe) for m in ("steel", "pvc", "wood")]
    assert stiff[0] > stiff[1] > stiff[2]
    # Johnson (1985) by hand, steel: 1/E* = (1-0.39^2)/3e9 + (1-0.29^2)/205e9, R = 4 mm, F = 0.5 N.
    e_star = 1 / ((1 - 0.39**2) / 3e9 + (1 - 0.29**2) / 205e9)
    assert stiff[0] == pytest.approx((6 * 0.5 * e_star**2 * 0.004) ** (1 / 3), rel=1e-12)


def test_material_matters_only_through_contact_effects():
    no_contact = builtin_scene("paper").with_(
        effects=[
            e
            for e in builtin_scene("paper").effects
            if e.name
            not in ("object_modes", "object_damping", "preload_scatter", "unilateral_contact")
        ]
    )
    a = simulate(no_contact.with_(material="steel"), seed=5)
    b = simulate(no_contact.with_(material="pvc"), seed=5)
    assert np.array_equal(a.ax, b.ax) and np.array_equal(a.az, b.az)
    paper = builtin_scene("paper")
    assert not np.array_equal(
        simulate(paper.with_(material="steel"), seed=5).ax,
        simulate(paper.with_(material="pvc"), seed=5).ax,
    )


def test_tip_mass_lowers_the_modes():
    bare = modal_terms(builtin_scene("ideal").with_(contact=0.3))[0].frequencies()
    scene = builtin_scene("ideal").with_(
        contact=0.3, probe=Probe(tip_mass=2.5e-3), effects=("tip_mass",)
    )
    loaded = modal_terms(scene)[0].frequencies()
    assert loaded[0] < bare[0]
    # The overhang (0.3 m to the tip) carries the board: its cantilever mode drops most.
    fem = modal_analysis(Probe(tip_mass=2.5e-3), Supports(contact=0.3), n_elements=40, n_modes=8)
    assert np.allclose(loaded, fem.frequencies[: loaded.size], rtol=1e-12)


def test_z_axis_rings_at_the_free_probe_frequencies_scaled_by_tilt():
    scene = builtin_scene("ideal").with_(contact=0.2)
    _, z = modal_terms(scene)
    free = modal_analysis(scene.probe, Supports(contact=None), n_elements=40, n_modes=8)
    assert np.allclose(z.frequencies(), free.frequencies[free.frequencies < 480.0], rtol=1e-12)
    half = simulate(scene.with_(tilt_ratio=scene.tilt_ratio / 2))
    full = simulate(scene)
    assert np.allclose(half.az, full.az / 2, rtol=0, atol=1e-12 * np.abs(full.az).max())
    assert np.array_equal(half.ax, full.ax)
    # Z is the same whatever the contact.
    assert np.array_equal(simulate(scene.with_(contact=0.33)).az, full.az)
    # Without tilt Z is silent, and the modes are still reported.
    still = simulate(scene.with_(tilt_ratio=0.0))
    assert np.all(still.az == 0) and still.metadata["modes_z_hz"] == full.metadata["modes_z_hz"]


def test_batch_rows_equal_single_simulations():
    paper = builtin_scene("paper")
    contacts = np.array([0.05, 0.2, 0.2, 0.37])
    materials = ["steel", "pvc", "wood", "brass"]
    speeds = np.array([0.4, 0.5, 0.6, 0.55])
    tilts = np.array([0.1, 0.2, 0.3, 0.25])
    seeds = np.array([3, 4, 5, 6])
    t, ax, az, _, _ = simulate_batch(
        paper,
        contact=contacts,
        material=materials,
        sweep_speed=speeds,
        tilt_ratio=tilts,
        seeds=seeds,
    )
    for i in range(4):
        one = simulate(
            paper.with_(
                contact=contacts[i],
                material=materials[i],
                sweep_speed=speeds[i],
                tilt_ratio=tilts[i],
            ),
            seed=int(seeds[i]),
        )
        # The same numbers, not merely close: no step of the chain mixes rows or changes its
        # arithmetic with the batch (each row has its own generators, its strike marched alone,
        # its filters and modal sums taken row by row; the modes of a contact position are
        # computed once, as for a single signal). A tolerance would not help: past the quantiser
        # a difference is a whole count (about 5e-3 m/s^2) or nothing.
        np.testing.assert_array_equal(one.ax, ax[i])
        np.testing.assert_array_equal(one.az, az[i])


def test_with_the_board_the_lowest_mode_changes_character_near_0_8_l():
    # The paper's Fig. 16: the overhang's cantilever mode gives way to the span's mode. Witness:
    # the share of the lowest mode's kinetic energy in the overhang falls through 1/2.
    probe = builtin_scene("paper").probe
    ratios = np.arange(0.70, 0.951, 0.01)
    share = np.array(
        [
            modal_analysis(
                probe, Supports(contact=r * probe.length), n_elements=40, n_modes=3
            ).overhang_mass_fraction()[0]
            for r in ratios
        ]
    )
    assert np.all(np.diff(share) < 0)
    crossing = ratios[np.argmax(share < 0.5)]
    assert 0.78 <= crossing <= 0.88
    # Without the board the change comes earlier: the tip mass moves it towards the tip.
    bare = np.array(
        [
            modal_analysis(
                Probe(), Supports(contact=r * 0.4), n_elements=40, n_modes=3
            ).overhang_mass_fraction()[0]
            for r in ratios
        ]
    )
    assert ratios[np.argmax(bare < 0.5)] < crossing
