"""The secular-equation sweep against the banded sweep, a dense solve of its own model, the Ritz
bounds of refinement and the exact solution; its static correction against a direct solve."""

import itertools
import math

import numpy as np
import pytest
import scipy.linalg as sla

from ebantenna.fem import Supports, exact_frequencies, modal_analysis, natural_frequencies
from ebantenna.fem.assembly import assemble
from ebantenna.fem.elements import hermite
from ebantenna.fem.secular import secular_sweep, static_correction
from ebantenna.probe import Probe

EPS = np.finfo(float).eps
PROBE = Probe(tip_mass=2.5e-3)


@pytest.mark.parametrize(
    ("hinge", "contact_stiffness"), [("clamped", math.inf), ("pinned", math.inf), (3.0, 2e4)]
)
def test_on_the_nodes_of_its_mesh_it_is_the_banded_sweeps_model(hinge, contact_stiffness):
    # A contact on a node of the uniform mesh is what beam_mesh builds there: the same FEM model,
    # both refined by Rayleigh quotients from the curvatures (about 1e-12; 1e-10 is the claim).
    n = 32
    nodes = np.arange(1, n) * PROBE.length / n
    kw = dict(hinge=hinge, contact_stiffness=contact_stiffness, n_elements=n, n_modes=4)
    ours = natural_frequencies(PROBE, nodes, method="secular", **kw)
    theirs = natural_frequencies(PROBE, nodes, method="banded", **kw)
    np.testing.assert_allclose(ours, theirs, rtol=1e-10)


def _dense(n_elements, contact, n_modes, static):
    """The same model solved directly: the pin c(a)^T u = 0 by a null-space basis, or with the
    static correction a spring 1/delta(a) on c(a)^T u; then eigh."""
    nodes = np.linspace(0, PROBE.length, n_elements + 1)
    K, M = assemble(nodes, PROBE)
    M[-2, -2] += PROBE.tip_mass
    h = nodes[1] - nodes[0]
    e = min(int(contact // h), n_elements - 1)
    c = np.zeros(K.shape[0])
    c[2 * e : 2 * e + 4] = hermite((contact - nodes[e]) / h, h)
    free = np.arange(2, K.shape[0])  # clamped hinge
    K, M, c = K[np.ix_(free, free)], M[np.ix_(free, free)], c[free]
    if static:
        delta = static_correction(nodes, np.array([contact]), PROBE.flexural_rigidity)[0]
        lam = sla.eigh(K + np.outer(c, c) / delta, M, eigvals_only=True)
    else:
        Z = sla.null_space(c[None, :])
        lam = sla.eigh(Z.T @ K @ Z, Z.T @ M @ Z, eigvals_only=True)
    return np.sqrt(lam[:n_modes]) / (2 * math.pi), lam[-1] / lam[0]


@pytest.mark.parametrize("static", [False, True])
def test_inside_an_element_it_solves_its_model_as_a_dense_solve_does(static):
    # The dense generalized eigh is accurate to about n eps lambda_max absolute: relative to the
    # j-th eigenvalue n eps lambda_max / lambda_j; on 8 elements that is ~1e-9 for f1.
    n = 8
    contacts = np.array([0.037, 0.1234, 0.29, 0.3998])
    lam = secular_sweep(
        PROBE, contacts, hinge_stiffness=math.inf, contact_stiffness=math.inf, n_elements=n,
        n_modes=3, static=static,
    )  # fmt: skip
    ours = np.sqrt(lam) / (2 * math.pi)
    for f, a in zip(ours, contacts, strict=True):
        witness, spread = _dense(n, a, 3, static)
        bound = (2 * n) * EPS * spread * (witness[0] / witness) ** 2
        assert np.all(np.abs(f / witness - 1) <= bound)


def test_without_the_correction_refining_approaches_the_exact_solution_from_above():
    # Uniform meshes of 16, 32, 64 and 128 elements are nested, and so are their constrained
    # spaces: by Rayleigh-Ritz every frequency falls with refinement and stays above the exact
    # one (Probe() without tip mass, for which the exact solution exists), up to rounding.
    probe = Probe()
    contacts = np.array([0.0517, 0.171, 0.333])
    exact = np.array([exact_frequencies(probe, float(a), n_modes=3) for a in contacts])
    kw = dict(hinge_stiffness=math.inf, contact_stiffness=math.inf, n_modes=3, static=False)
    runs = [
        np.sqrt(secular_sweep(probe, contacts, n_elements=n, **kw)) / (2 * math.pi)
        for n in (16, 32, 64, 128)
    ]
    slack = 1e-11  # the Rayleigh quotients' rounding, relative
    for coarse, fine in itertools.pairwise(runs):
        assert np.all(fine <= coarse * (1 + slack))
    assert np.all(runs[-1] >= exact * (1 - slack))
    assert np.abs(runs[-1] / exact - 1).max() < np.abs(runs[0] / exact - 1).max() / 100


def test_the_static_correction_converges_like_the_elements_and_beats_the_bare_pin():
    # What is left after the correction is the dynamic part of the interpolation error, which
    # falls like h^4 for cubic elements (Strang and Fix, ch. 6): at least 8x per halving (h^3
    # with room for the pre-asymptotic meshes). And 64 corrected elements beat 128 bare ones.
    probe = Probe()
    contacts = np.array([0.0517, 0.171, 0.333])
    exact = np.array([exact_frequencies(probe, float(a), n_modes=3) for a in contacts])
    errors = [
        np.abs(natural_frequencies(probe, contacts, method="secular", n_elements=n) / exact - 1)
        for n in (16, 32, 64)
    ]
    for coarse, fine in itertools.pairwise(errors):
        assert np.all(fine <= coarse / 8)
    bare = secular_sweep(
        probe, contacts, hinge_stiffness=math.inf, contact_stiffness=math.inf, n_elements=128,
        n_modes=3, static=False,
    )  # fmt: skip
    assert errors[2].max() < np.abs(np.sqrt(bare) / (2 * math.pi) / exact - 1).max()


@pytest.mark.parametrize("hinge_stiffness", [math.inf, 3.0])
def test_the_static_correction_is_the_exact_flexibility_less_the_meshs(hinge_stiffness):
    # The mesh's flexibility at a, c^T K^-1 c, by a direct solve, against the exact a^3 / (3 EI)
    # (+ a^2 / k_h for a hinge spring, which the mesh carries exactly). The solve's rounding is
    # about n eps cond(K) relative to the flexibility.
    n = 8
    nodes = np.linspace(0, PROBE.length, n + 1)
    K, _ = assemble(nodes, PROBE)
    free = np.arange(1 if math.isfinite(hinge_stiffness) else 2, K.shape[0])
    if math.isfinite(hinge_stiffness):
        K[1, 1] += hinge_stiffness
    K = K[np.ix_(free, free)]
    contacts = np.array([0.037, 0.1234, 0.29, 0.3999, 0.05, 0.35])
    delta = static_correction(nodes, contacts, PROBE.flexural_rigidity)
    h = nodes[1] - nodes[0]
    EI = PROBE.flexural_rigidity
    for a, d in zip(contacts, delta, strict=True):
        e = min(int(a // h), n - 1)
        c = np.zeros(2 * n + 2)
        c[2 * e : 2 * e + 4] = hermite((a - nodes[e]) / h, h)
        exact = a**3 / (3 * EI) + (a**2 / hinge_stiffness if math.isfinite(hinge_stiffness) else 0)
        mesh = c[free] @ np.linalg.solve(K, c[free])
        assert d >= 0
        assert abs(d - (exact - mesh)) <= n * EPS * np.linalg.cond(K) * exact
    # 0.05 and 0.35 m are nodes: exact there (Tong 1969), up to the rounding of a^3 / 3
    assert np.all(delta[4:] <= 8 * EPS * contacts[4:] ** 3 / (3 * EI))


def test_a_stiffer_contact_spring_approaches_the_pin_and_interlaces():
    # The j-th root lies between the j-th and (j+1)-th frequencies without the contact, and
    # rises with the spring towards the pin's.
    contacts = np.array([0.15, 0.31])
    free_modes = modal_analysis(PROBE, Supports(None), n_elements=32, n_modes=5).frequencies
    lam = [
        secular_sweep(
            PROBE, contacts, hinge_stiffness=math.inf, contact_stiffness=k, n_elements=32,
            n_modes=3,
        )
        for k in (1e2, 1e4, 1e6, math.inf)
    ]  # fmt: skip
    f = [np.sqrt(x) / (2 * math.pi) for x in lam]
    for soft, stiff in itertools.pairwise(f):
        assert np.all(soft <= stiff * (1 + 1e-12))
    assert np.all(f[-1] > free_modes[:3]) and np.all(f[-1] < free_modes[1:4])
