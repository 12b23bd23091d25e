"""The secular-equation sweep against the banded sweep, a dense solve of its own model, the Ritz
bounds of refinement and the exact solution."""

import itertools
import math

import numpy as np
import pytest
import scipy.linalg as sla

from ebantenna.fem import Supports, exact_frequencies, modal_analysis, natural_frequencies
from ebantenna.fem.assembly import assemble
from ebantenna.fem.elements import hermite
from ebantenna.fem.secular import secular_sweep
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


def _dense_constrained(n_elements, contact, n_modes):
    """The same model solved directly: the pin c(a)^T u = 0 by a null-space basis, then eigh."""
    nodes = np.linspace(0, PROBE.length, n_elements + 1)
    K, M = assemble(nodes, PROBE)
    M[-2, -2] += PROBE.tip_mass
    h = nodes[1] - nodes[0]
    e = min(int(contact // h), n_elements - 1)
    c = np.zeros(K.shape[0])
    c[2 * e : 2 * e + 4] = hermite((contact - nodes[e]) / h, h)
    free = np.arange(2, K.shape[0])  # clamped hinge
    Z = sla.null_space(c[free][None, :])
    Kz, Mz = Z.T @ K[np.ix_(free, free)] @ Z, Z.T @ M[np.ix_(free, free)] @ Z
    lam = sla.eigh(Kz, Mz, eigvals_only=True)
    return np.sqrt(lam[:n_modes]) / (2 * math.pi), lam[-1] / lam[0]


def test_inside_an_element_it_solves_its_model_as_a_dense_solve_does():
    # The dense generalized eigh is accurate to about n eps lambda_max absolute: relative to the
    # j-th eigenvalue n eps lambda_max / lambda_j; on 8 elements that is ~1e-9 for f1.
    n = 8
    contacts = np.array([0.037, 0.1234, 0.29, 0.3999])
    ours = natural_frequencies(PROBE, contacts, method="secular", n_elements=n, n_modes=3)
    for f, a in zip(ours, contacts, strict=True):
        witness, spread = _dense_constrained(n, a, 3)
        bound = (2 * n) * EPS * spread * (witness[0] / witness) ** 2
        assert np.all(np.abs(f / witness - 1) <= bound)


def test_refining_its_mesh_approaches_the_exact_solution_from_above():
    # Uniform meshes of 16, 32, 64 and 128 elements are nested, and so are their constrained
    # spaces: by Rayleigh-Ritz every frequency falls with refinement and stays above the exact
    # one (Probe() without tip mass, for which the exact solution exists), up to rounding.
    probe = Probe()
    contacts = np.array([0.0517, 0.171, 0.333])
    exact = np.array([exact_frequencies(probe, float(a), n_modes=3) for a in contacts])
    runs = [
        natural_frequencies(probe, contacts, method="secular", n_elements=n, n_modes=3)
        for n in (16, 32, 64, 128)
    ]
    slack = 1e-11  # the Rayleigh quotients' rounding, relative
    for coarse, fine in itertools.pairwise(runs):
        assert np.all(fine <= coarse * (1 + slack))
    assert np.all(runs[-1] >= exact * (1 - slack))
    assert np.abs(runs[-1] / exact - 1).max() < np.abs(runs[0] / exact - 1).max() / 100


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
