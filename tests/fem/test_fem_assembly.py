"""The assembly loop (reference) and the parity scatter (engine) give the same matrices, and
hence the same modes."""

import numpy as np
import pytest

from ebantenna import Probe
from ebantenna.fem import Supports, modal_analysis
from ebantenna.fem._assembly_engine import (
    mass_polynomial,
    scatter,
    scatter_sparse,
    stiffness_polynomial,
)
from ebantenna.fem.assembly import assemble, assemble_elements, beam_mesh
from ebantenna.fem.elements import consistent_mass, element_stiffness


@pytest.mark.parametrize("n_elements", [1, 2, 3, 8, 65])
def test_scatter_engine_equals_the_assembly_loop_bit_for_bit(n_elements):
    # Each global entry sums at most two element entries (the two elements at a node), one from
    # each parity, and x + y == y + x in floating point: the order cannot change a bit.
    lengths = np.random.default_rng(n_elements).uniform(1e-3, 0.1, n_elements)
    for Ke in (element_stiffness(2.7, lengths), consistent_mass(0.05, lengths)):
        reference = assemble_elements(Ke)
        assert np.array_equal(scatter(Ke), reference)
        assert np.array_equal(scatter_sparse(Ke).toarray(), reference)


def test_assemble_engines_agree_on_a_probe_mesh():
    nodes = beam_mesh(0.4, 0.13, 33)
    K, M = assemble(nodes, Probe())
    K_loop, M_loop = assemble(nodes, Probe(), engine="loop")
    K_sparse, M_sparse = assemble(nodes, Probe(), sparse=True)
    assert np.array_equal(K, K_loop) and np.array_equal(M, M_loop)
    assert np.array_equal(K, K_sparse.toarray()) and np.array_equal(M, M_sparse.toarray())
    # the reference loop builds dense matrices: asked for sparse ones it says so by name
    with pytest.raises(ValueError, match="engine='loop' builds dense matrices"):
        assemble(nodes, Probe(), sparse=True, engine="loop")


def test_scatter_assembles_a_stack_of_meshes_as_one_loop_each():
    lengths = np.random.default_rng(0).uniform(1e-3, 0.1, (3, 7))
    Ke = element_stiffness(1.0, lengths)
    stacked = scatter(Ke)
    for b in range(3):
        assert np.array_equal(stacked[b], assemble_elements(Ke[b]))


def test_assembly_loop_shares_the_node_block_of_neighbours():
    K = assemble_elements(element_stiffness(1.0, np.array([1.0, 1.0])))
    # node 1 joins both elements: 12 + 12 in v, 4 + 4 in theta, and nothing reaches past it
    assert K[2, 2] == 24 and K[3, 3] == 8
    assert K[0, 4] == 0 and K[1, 5] == 0


def test_unknown_engine_is_refused():
    with pytest.raises(ValueError, match="engine"):
        assemble(beam_mesh(0.4, None, 4), Probe(), engine="fast")


@pytest.mark.parametrize("shape", [(), (7,), (3, 5)])
def test_polynomial_engine_equals_the_written_out_matrices_bit_for_bit(shape):
    # Every entry of K0 + K1 l + K2 l^2 is one term c l^k plus exact zeros, and the factor in
    # front is computed the same way, so the two forms round identically.
    rng = np.random.default_rng(len(shape))
    lengths = rng.uniform(1e-5, 2.0, shape)
    EI, rhoA = rng.uniform(1e-3, 1e3, shape), rng.uniform(1e-3, 1e3, shape)
    assert np.array_equal(stiffness_polynomial(EI, lengths), element_stiffness(EI, lengths))
    assert np.array_equal(mass_polynomial(rhoA, lengths), consistent_mass(rhoA, lengths))
    assert np.array_equal(stiffness_polynomial(2.5, lengths), element_stiffness(2.5, lengths))


@pytest.mark.parametrize("solver", ["auto", "dense", "naive"])
@pytest.mark.parametrize("supports", [Supports(0.13), Supports(0.29, 4.0, 300.0),
                                      Supports(None, "pinned")])
def test_modal_analysis_on_the_assembly_loop_gives_the_same_modes_bit_for_bit(solver, supports):
    # assemble gives the same K and M bit for bit with either engine (above), and everything
    # after it is the same arithmetic: the modes cannot differ by a bit.
    probe = Probe(tip_mass=0.002)
    kw = dict(n_elements=40, n_modes=4, solver=solver)
    engine = modal_analysis(probe, supports, **kw)
    loop = modal_analysis(probe, supports, assembly="loop", **kw)
    assert np.array_equal(loop.frequencies, engine.frequencies)
    assert np.array_equal(loop.shapes, engine.shapes)


def test_modal_analysis_refuses_an_unknown_assembly_or_a_sparse_loop():
    with pytest.raises(ValueError, match="assembly must be one of"):
        modal_analysis(Probe(), Supports(0.2), assembly="magic")
    with pytest.raises(ValueError, match=r"assembly='loop' builds dense matrices.*'sparse'"):
        modal_analysis(Probe(), Supports(0.2), n_elements=16, solver="sparse", assembly="loop")
    # clamped hinge and rigid contact fix 3 DOFs: 101 elements leave 201 free, above DENSE_LIMIT
    with pytest.raises(ValueError, match=r"assembly='loop' builds dense matrices.*'auto'"):
        modal_analysis(Probe(), Supports(0.2), n_elements=101, assembly="loop")
    # one element fewer (199 free DOFs) stays dense under solver="auto", and the loop is taken
    res = modal_analysis(Probe(), Supports(0.2), n_elements=100, assembly="loop")
    assert np.array_equal(res.frequencies,
                          modal_analysis(Probe(), Supports(0.2), n_elements=100).frequencies)
