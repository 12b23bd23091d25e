"""Modal analysis against the exact frequency equation, hard cases, and properties."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ebantenna import MemoryBudgetError, Probe
from ebantenna.fem import (
    Supports,
    dominant_mode_zones,
    exact_frequencies,
    modal_analysis,
    natural_frequencies,
)
from ebantenna.fem.assembly import apply_supports, assemble, beam_mesh
from ebantenna.fem.guards import MAX_ELEMENTS, MIN_SPAN, ROUNDOFF_RTOL, roundoff_error
from ebantenna.fem.modal import strain_energy

PROBE = Probe()
L = PROBE.length


def rel_error(res, hinge="clamped"):
    exact = exact_frequencies(PROBE, res.supports.contact, hinge=hinge, n_modes=res.n_modes)
    return res.frequencies / exact - 1


@pytest.mark.parametrize("hinge", ["clamped", "pinned"])
@pytest.mark.parametrize("ratio", [0.25, 0.5, 0.8])
def test_fem_converges_from_above_as_h4(ratio, hinge):
    errors = []
    for n in (4, 8, 16, 32):
        res = modal_analysis(PROBE, Supports(ratio * L, hinge), n_elements=n, n_modes=3)
        errors.append(rel_error(res, hinge))
    errors = np.array(errors)
    assert np.all(errors > 0), "consistent-mass elements bound the frequencies from above"
    # Halving h divides the error by 2^4 = 16 asymptotically; allow for the pre-asymptotic start.
    rates = np.log2(errors[-2] / errors[-1])
    assert np.all((rates > 3.7) & (rates < 4.3)), rates


@pytest.mark.parametrize("ratio", np.linspace(0.25, 0.9, 14))
def test_fine_meshes_match_the_exact_frequencies(ratio):
    # Cubic Hermite elements err by about (beta h)^4 / 1440 in frequency: at 64 elements that is
    # up to 6e-7 for the third mode, and 16 times less at 128 elements.
    e64 = rel_error(modal_analysis(PROBE, Supports(ratio * L), n_elements=64, n_modes=3))
    e128 = rel_error(modal_analysis(PROBE, Supports(ratio * L), n_elements=128, n_modes=3))
    assert np.all(np.abs(e64) < 1e-6), e64
    assert np.all(np.abs(e128) < 1e-7), e128


@pytest.mark.parametrize("hinge", ["clamped", "pinned"])
@pytest.mark.parametrize("contact", [MIN_SPAN * L, L - MIN_SPAN * L])
def test_contact_next_to_the_hinge_or_the_tip(contact, hinge):
    for n in (2, 64, 2048):
        res = modal_analysis(PROBE, Supports(contact, hinge), n_elements=n, n_modes=3)
        assert np.all(np.isfinite(res.frequencies)) and np.all(np.diff(res.frequencies) > 0)
    err = rel_error(res, hinge)
    assert np.all(np.abs(err) < 1e-8), err


def _spring_inside_an_element(probe, contact, stiffness, n_elements=64):
    """Lowest frequency (Hz) of the clamped probe with a contact spring placed inside an element
    of a uniform mesh by the cubic shape functions, no node at the contact: written out here,
    independently of the package's mesh, which puts a node there."""
    import scipy.linalg as sla

    h, EI, m = probe.length / n_elements, probe.flexural_rigidity, probe.mass_per_length
    k = EI / h**3 * np.array([[12, 6 * h, -12, 6 * h], [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                              [-12, -6 * h, 12, -6 * h], [6 * h, 2 * h * h, -6 * h, 4 * h * h]])
    me = m * h / 420 * np.array([[156, 22 * h, 54, -13 * h],
                                 [22 * h, 4 * h * h, 13 * h, -3 * h * h],
                                 [54, 13 * h, 156, -22 * h],
                                 [-13 * h, -3 * h * h, -22 * h, 4 * h * h]])
    size = 2 * (n_elements + 1)
    K, M = np.zeros((size, size)), np.zeros((size, size))
    for e in range(n_elements):
        K[2 * e:2 * e + 4, 2 * e:2 * e + 4] += k
        M[2 * e:2 * e + 4, 2 * e:2 * e + 4] += me
    e = min(int(contact / h), n_elements - 1)
    t = contact / h - e
    c = np.zeros(size)
    c[2 * e:2 * e + 4] = [1 - 3 * t**2 + 2 * t**3, h * (t - 2 * t**2 + t**3), 3 * t**2 - 2 * t**3,
                          h * (t**3 - t**2)]
    K, M = (K + stiffness * np.outer(c, c))[2:, 2:], M[2:, 2:]
    # the lowest mode as the largest of the inverted problem, eigh(M, K): eigh(K, M) would carry
    # the rounding eps w_max^2 / w_1^2 (the theory page on the eigenproblem), 1e-6 here
    factor = sla.cholesky(K, lower=True)
    inner = sla.solve_triangular(factor, sla.solve_triangular(factor, M, lower=True).T,
                                 lower=True)
    mu = sla.eigh((inner + inner.T) / 2, eigvals_only=True)[-1]
    return float(1 / np.sqrt(mu) / (2 * np.pi))


@pytest.mark.parametrize("stiffness", [0.01, 1.0, 1e2, 1e4, 1e8])
def test_a_spring_contact_at_the_shortest_span_from_the_tip(stiffness):
    # guards.MIN_SPAN: a soft contact next to the free tip leaves a short, nearly free end piece
    # (1 N/m at 1e-5 L was 3 % off, at 1e-6 L the factorisation failed). At MIN_SPAN the lowest
    # frequency agrees with the spring placed inside an element, whose own discretisation error
    # at 64 elements is below 1e-9 (the two meshes differ by the element cut at the contact):
    # 1e-8 is what the guard's comment promises
    contact = PROBE.length * (1 - MIN_SPAN)
    got = modal_analysis(PROBE, Supports(contact, contact_stiffness=stiffness), n_elements=64,
                         n_modes=1).frequencies[0]
    assert got == pytest.approx(_spring_inside_an_element(PROBE, contact, stiffness), rel=1e-8)


def test_2048_elements_stay_accurate_where_a_naive_eigh_does_not():
    sup = Supports(0.5 * L)
    good = modal_analysis(PROBE, sup, n_elements=2048, n_modes=3)
    assert np.all(np.abs(rel_error(good)) <= roundoff_error(2048))  # the a-priori bound, 4e-8
    # The textbook scipy.linalg.eigh(K, M) loses the low modes to rounding on this mesh: how much
    # is the luck of its rounding (6.6e-5 to 1.6e-3 under three OpenBLAS kernels on one or two
    # threads; its bound, eps w_max^2 / (2 w_1^2), is tested with the eigenproblem page), but
    # three orders of magnitude beyond what bounds the inverted solve on the same mesh (1.5e-10)
    naive = modal_analysis(PROBE, sup, n_elements=1024, n_modes=1, solver="naive")
    assert abs(rel_error(naive)[0]) > 1e3 * roundoff_error(1024)


@pytest.mark.parametrize(
    "contact, hinge", [(0.1 * L, "clamped"), (0.5 * L, "pinned"), (None, "clamped")]
)
def test_the_roundoff_estimate_bounds_the_error_at_the_finest_mesh_allowed(contact, hinge):
    # The discretisation error at this mesh is ~ (beta h)^4 < 1e-14: what is left is round-off,
    # which roundoff_error promises to bound.
    res = modal_analysis(PROBE, Supports(contact, hinge), n_elements=MAX_ELEMENTS, n_modes=1)
    err = abs(rel_error(res, hinge)[0])
    assert err <= roundoff_error(MAX_ELEMENTS) <= ROUNDOFF_RTOL, err


def test_a_mesh_finer_than_double_precision_resolves_is_refused_naming_the_limit():
    with pytest.raises(ValueError, match=f"n_elements must be <= {MAX_ELEMENTS}, got 16384"):
        modal_analysis(PROBE, Supports(0.5 * L), n_elements=16384)
    with pytest.raises(ValueError, match="condition number grows like N"):
        natural_frequencies(PROBE, [0.2], n_elements=MAX_ELEMENTS + 1)
    with pytest.raises(ValueError, match=f"<= {MAX_ELEMENTS}"):  # before any memory is spent
        beam_mesh(L, None, 10**9)
    # the estimate grows like N^8: a factor 2 in elements is a factor 256 in error
    assert roundoff_error(2 * MAX_ELEMENTS) == pytest.approx(256 * roundoff_error(MAX_ELEMENTS))


@pytest.mark.parametrize("n_modes", [0, 4, 50])
def test_n_modes_beyond_the_free_dofs_is_refused(n_modes):
    # 2 elements, clamped hinge, rigid contact: 3 free DOFs, so 3 modes at most
    with pytest.raises(ValueError, match="n_modes must be"):
        natural_frequencies(PROBE, [0.1], n_elements=2, n_modes=n_modes)
    with pytest.raises(ValueError, match="n_modes must be"):
        modal_analysis(PROBE, Supports(0.1), n_elements=2, n_modes=n_modes)


def test_sparse_and_dense_solvers_agree():
    sup = Supports(0.3)
    dense = modal_analysis(PROBE, sup, n_elements=100, n_modes=4, solver="dense")
    sparse = modal_analysis(PROBE, sup, n_elements=100, n_modes=4, solver="sparse")
    np.testing.assert_allclose(dense.frequencies, sparse.frequencies, rtol=1e-11)
    # shapes agree up to sign
    signs = np.sign(np.sum(dense.shapes * sparse.shapes, axis=0))
    np.testing.assert_allclose(
        dense.shapes, sparse.shapes * signs, atol=1e-7 * np.abs(dense.shapes).max()
    )


def test_very_stiff_hinge_spring_is_a_clamp():
    sup_spring = Supports(0.2, hinge=1e12)
    spring = modal_analysis(PROBE, sup_spring, n_elements=64, n_modes=3)
    clamped = modal_analysis(PROBE, Supports(0.2), n_elements=64, n_modes=3)
    np.testing.assert_allclose(spring.frequencies, clamped.frequencies, rtol=1e-9)


def test_soft_hinge_spring_lies_between_pinned_and_clamped():
    f = [
        modal_analysis(PROBE, Supports(0.2, hinge=h), n_elements=32, n_modes=1).frequencies[0]
        for h in ("pinned", 0.05, "clamped")
    ]
    assert f[0] < f[1] < f[2]


def test_stiff_contact_spring_is_a_pin_and_soft_one_frees_the_probe():
    pin = modal_analysis(PROBE, Supports(0.2), n_elements=32, n_modes=2).frequencies
    stiff = modal_analysis(PROBE, Supports(0.2, contact_stiffness=1e12), n_elements=32, n_modes=2)
    np.testing.assert_allclose(stiff.frequencies, pin, rtol=1e-8)
    soft = modal_analysis(PROBE, Supports(0.2, contact_stiffness=1e-9), n_elements=32, n_modes=2)
    free = exact_frequencies(PROBE, None, n_modes=2)
    np.testing.assert_allclose(soft.frequencies, free, rtol=1e-6)


def test_free_pinned_probe_has_a_zero_mode_not_a_nan():
    res = modal_analysis(PROBE, Supports(None, hinge="pinned"), n_elements=64, n_modes=3)
    assert np.all(np.isfinite(res.frequencies)) and np.all(np.isfinite(res.shapes))
    assert 0 <= res.frequencies[0] < 1e-6
    exact = exact_frequencies(PROBE, None, hinge="pinned", n_modes=3)
    assert exact[0] == 0
    np.testing.assert_allclose(res.frequencies[1:], exact[1:], rtol=1e-6)
    # the rigid rotation: deflection proportional to x
    x = np.linspace(0, L, 9)
    w = res.displacement(x)[:, 0]
    np.testing.assert_allclose(w, w[-1] * x / L, atol=1e-9 * abs(w[-1]))


def test_cantilever_matches_the_textbook_beta_l():
    res = modal_analysis(PROBE, Supports(None), n_elements=128, n_modes=3)
    beta_l = np.array([1.8751040687119611, 4.6940911329741745, 7.8547574382376126])
    f = (
        beta_l**2
        / L**2
        * math.sqrt(PROBE.flexural_rigidity / PROBE.mass_per_length)
        / (2 * math.pi)
    )
    np.testing.assert_allclose(res.frequencies, f, rtol=1e-7)
    np.testing.assert_allclose(exact_frequencies(PROBE, None, n_modes=3), f, rtol=1e-13)


def test_shapes_are_mass_normalised_and_stiffness_orthogonal():
    probe = Probe(tip_mass=0.003)
    sup = Supports(0.25, hinge=2.0)
    res = modal_analysis(probe, sup, n_elements=20, n_modes=4)
    nodes = beam_mesh(probe.length, 0.25, 20)
    K, M = assemble(nodes, probe)
    Kf, Mf, free = apply_supports(K, M, nodes, probe, sup)
    phi = res.shapes[free]
    np.testing.assert_allclose(phi.T @ Mf @ phi, np.eye(4), atol=1e-12)
    np.testing.assert_allclose(phi.T @ Kf @ phi, np.diag(res.omega**2), rtol=1e-9, atol=1e-6)
    # the curvature-based strain energy equals u^T K u
    u = res.shapes
    np.testing.assert_allclose(
        strain_energy(nodes, probe, sup, u), np.einsum("im,ij,jm->m", phi, Kf, phi), rtol=1e-9
    )


def test_deflection_between_nodes_uses_the_shape_functions():
    res = modal_analysis(PROBE, Supports(0.2), n_elements=8, n_modes=2)
    np.testing.assert_allclose(res.displacement(res.nodes), res.shapes[0::2], atol=1e-15)
    np.testing.assert_allclose(res.slope(res.nodes), res.shapes[1::2], atol=1e-12)
    # inside an element the deflection is a cubic, not the chord between the nodes
    mid = 0.5 * (res.nodes[-2] + res.nodes[-1])
    chord = 0.5 * (res.shapes[-4] + res.shapes[-2])
    assert not np.allclose(res.displacement(np.array([mid]))[0], chord)
    assert abs(res.displacement(np.array([0.2]))[0, 0]) < 1e-15  # the pin


def test_batched_sweep_equals_one_at_a_time():
    contacts = np.linspace(0.01, 0.39, 23)
    for hinge, probe in (("clamped", PROBE), ("pinned", Probe(tip_mass=0.003)), (5.0, PROBE)):
        batch = natural_frequencies(probe, contacts, hinge=hinge, n_elements=24, n_modes=3, chunk=7)
        single = natural_frequencies(probe, contacts, hinge=hinge, n_elements=24, n_modes=3,
                                     method="reference")
        np.testing.assert_allclose(batch, single, rtol=1e-10)
    soft = natural_frequencies(PROBE, contacts[:3], contact_stiffness=50.0, n_elements=24)
    one = natural_frequencies(PROBE, contacts[:3], contact_stiffness=50.0, n_elements=24,
                              method="reference")
    np.testing.assert_allclose(soft, one, rtol=1e-10)


@settings(max_examples=15, deadline=None)
@given(scale=st.floats(0.1, 10.0), ratio=st.floats(0.05, 0.95))
def test_frequencies_scale_with_the_square_root_of_e_over_rho(scale, ratio):
    base = modal_analysis(PROBE, Supports(ratio * L), n_elements=16, n_modes=3).frequencies
    stiffer = Probe(youngs_modulus=PROBE.youngs_modulus * scale)
    f = modal_analysis(stiffer, Supports(ratio * L), n_elements=16, n_modes=3).frequencies
    np.testing.assert_allclose(f, base * math.sqrt(scale), rtol=1e-10)


@settings(max_examples=15, deadline=None)
@given(ratio=st.floats(0.02, 0.98), tip=st.floats(1e-4, 0.05))
def test_a_tip_mass_lowers_every_frequency(ratio, tip):
    bare = modal_analysis(PROBE, Supports(ratio * L), n_elements=16, n_modes=3).frequencies
    loaded = modal_analysis(Probe(tip_mass=tip), Supports(ratio * L), n_elements=16, n_modes=3)
    assert np.all(loaded.frequencies < bare)


def test_zones_and_the_non_monotonic_dominant_frequency():
    contacts = np.linspace(0.02, 0.38, 37)
    z = dominant_mode_zones(PROBE, contacts)
    assert z.zone[0] == 1 and z.zone[-1] == 3
    assert np.all(np.diff(z.zone) >= 0), "zones follow each other from hinge to tip"
    start2, start3 = z.boundaries()
    assert 0.6 * L < start2 < start3 < 0.9 * L
    peak = contacts[np.argmax(z.frequency)]
    assert start2 <= peak <= start3 + 0.02, "the frequency peaks where the mode changes"
    assert z.frequency[-1] < z.frequency.max()


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"contact": 0.5}, "contact must lie in"),
        ({"contact": -0.1}, "contact must be > 0"),
        ({"contact": float("nan")}, "contact must be a finite number"),
        ({"n_elements": 1, "contact": 0.2}, "n_elements must be >= 2"),
        ({"n_elements": 0, "contact": None}, "n_elements must be >= 1"),
        ({"n_modes": 0}, "n_modes must be >= 1"),
        ({"hinge": "welded"}, "hinge must be one of"),
        ({"hinge": -3.0}, "hinge"),
        ({"solver": "magic"}, "solver must be one of"),
    ],
)
def test_bad_input_names_the_parameter(kwargs, message):
    contact = kwargs.pop("contact", 0.2)
    hinge = kwargs.pop("hinge", "clamped")
    with pytest.raises(ValueError, match=message):
        modal_analysis(PROBE, Supports(contact, hinge), **kwargs)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"inner_diameter": 0.008}, "inner_diameter must be < outer_diameter"),
        ({"youngs_modulus": 0.0}, "youngs_modulus must be > 0"),
        ({"density": float("inf")}, "density must be a finite number"),
        ({"length": -1.0}, "length must be > 0"),
        ({"tip_mass": -0.001}, "tip_mass must be >= 0"),
    ],
)
def test_bad_probe_names_the_parameter(kwargs, message):
    with pytest.raises(ValueError, match=message):
        Probe(**kwargs)


def test_exact_solver_rejects_what_it_does_not_cover():
    with pytest.raises(ValueError, match="tip_mass must be 0"):
        exact_frequencies(Probe(tip_mass=0.01), 0.2)
    with pytest.raises(ValueError, match="contact must lie in"):
        exact_frequencies(PROBE, 0.4)
    with pytest.raises(ValueError, match="contacts must lie in"):
        natural_frequencies(PROBE, np.array([0.1, 0.5]))


def test_overhang_fraction_and_projection_work_on_sparse_meshes_too():
    dense = modal_analysis(PROBE, Supports(0.3), n_elements=100, n_modes=2, solver="dense")
    sparse = modal_analysis(PROBE, Supports(0.3), n_elements=100, n_modes=2, solver="sparse")
    np.testing.assert_allclose(
        dense.overhang_mass_fraction(), sparse.overhang_mass_fraction(), rtol=1e-8
    )
    u = np.zeros(dense.shapes.shape[0])
    u[0::2], u[1::2] = dense.nodes, 1.0  # rigid rotation about the hinge, 1 rad/s
    q_dense, q_sparse = dense.modal_coordinates(u), sparse.modal_coordinates(u)
    np.testing.assert_allclose(np.abs(q_dense), np.abs(q_sparse), rtol=1e-8)


@pytest.mark.parametrize("hinge", ["clamped", "pinned"])
@pytest.mark.parametrize("contact", [1e-100, 1e-300])
def test_exact_contact_at_the_hinge_tends_to_the_cantilever(contact, hinge):
    # A pin at the hinge itself leaves a cantilever (beta L = 1.8751, 4.6941, 7.8548) whatever
    # the hinge: the terms divided by u^3 are summed term by term, never 0 / 0.
    near = exact_frequencies(PROBE, contact, hinge=hinge, n_modes=3)
    cantilever = exact_frequencies(PROBE, None, hinge="clamped", n_modes=3)
    np.testing.assert_allclose(near, cantilever, rtol=1e-12)


def test_a_sweep_that_cannot_fit_in_memory_is_refused_before_allocating():
    # 10^6 positions x (2 x 3000)^2 x 32 bytes = 1.15e15 bytes = 1.02 PiB: over any budget
    contacts = np.linspace(0.01, 0.39, 10**6)
    with pytest.raises(MemoryBudgetError, match=r"^chunk asks for .*smaller chunk.* 1.02 PiB"):
        natural_frequencies(PROBE, contacts, n_elements=3000, method="dense", chunk=10**6)
