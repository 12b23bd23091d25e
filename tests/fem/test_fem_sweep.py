"""The contact sweeps against their reference, one modal analysis per position."""

import math

import numpy as np
import pytest

from ebantenna import Probe
from ebantenna.fem import Supports, exact_frequencies, modal_analysis, natural_frequencies
from ebantenna.fem.assembly import beam_mesh
from ebantenna.fem.banded import sweep_meshes
from ebantenna.fem.guards import MIN_SPAN

PROBE = Probe()
L = PROBE.length
EPS = np.finfo(float).eps


def one_at_a_time(probe, contacts, hinge, k_c, n_elements, n_modes=3):
    """The reference sweep, ``method="reference"``."""
    return natural_frequencies(probe, np.asarray(contacts), hinge=hinge, contact_stiffness=k_c,
                               n_elements=n_elements, n_modes=n_modes, method="reference")


@pytest.mark.parametrize("hinge", ["clamped", "pinned", 5.0])
def test_the_reference_is_modal_analysis_at_each_contact(hinge):
    probe = Probe(tip_mass=0.003)
    contacts = np.array([1e-3 * L, 0.13, 0.31, L - 1e-3 * L])
    ref = natural_frequencies(probe, contacts, hinge=hinge, contact_stiffness=300.0,
                              n_elements=16, n_modes=4, method="reference")
    for row, c in zip(ref, contacts, strict=True):
        one = modal_analysis(probe, Supports(float(c), hinge, 300.0), n_elements=16, n_modes=4)
        # the same calls in the same order: the same bits
        np.testing.assert_array_equal(row, one.frequencies)


def test_the_batch_meshes_are_beam_mesh():
    contacts = np.concatenate([[MIN_SPAN * L, 0.5 * L / 64, L - MIN_SPAN * L],
                               np.linspace(0.01, 0.39, 77)])
    nodes, c_node = sweep_meshes(L, contacts, 64)
    for row, k, c in zip(nodes, c_node, contacts, strict=True):
        ref = beam_mesh(L, float(c), 64)
        # the same formula as np.linspace, which rounds its points to within an ulp of L
        np.testing.assert_allclose(row, ref, rtol=0, atol=2 * EPS * L)
        assert row[k] == c


@pytest.mark.parametrize("hinge", ["clamped", "pinned", 5.0])
@pytest.mark.parametrize("k_c", [math.inf, 300.0])
@pytest.mark.parametrize("tip_mass", [0.0, 0.003])
def test_banded_sweep_equals_modal_analysis(hinge, k_c, tip_mass):
    probe = Probe(tip_mass=tip_mass)
    contacts = np.concatenate([[1e-3 * L], np.linspace(0.02, 0.38, 9), [L - 1e-3 * L]])
    fast = natural_frequencies(probe, contacts, hinge=hinge, contact_stiffness=k_c, n_modes=4)
    ref = one_at_a_time(probe, contacts, hinge, k_c, 64, n_modes=4)
    # Both are Rayleigh quotients of eigenvectors from an inverted solve; a quotient errs by the
    # square of its vector's error, itself about sqrt(n eps kappa) with kappa = omega_max^2 /
    # omega^2 ~ 1e8 at 64 elements: ~1e-12 (seen: 3e-13), 1e-10 leaves margin for any BLAS.
    np.testing.assert_allclose(fast, ref, rtol=1e-10)


def test_banded_sweep_on_a_fine_mesh_converges_to_the_exact_frequencies():
    contacts = np.array([0.1, 0.25, 0.36])
    fast = natural_frequencies(PROBE, contacts, n_elements=1024, n_modes=3)
    exact = np.array([exact_frequencies(PROBE, float(c), n_modes=3) for c in contacts])
    # Hermite cubics: (beta h)^4 / 1440 ~ 1e-11 at 1024 elements; the quotients keep ~1e-11.
    np.testing.assert_allclose(fast, exact, rtol=1e-9)


def test_the_dense_batch_is_still_there_and_agrees():
    contacts = np.linspace(0.01, 0.39, 23)
    dense = natural_frequencies(PROBE, contacts, n_elements=24, method="dense", chunk=7)
    ref = one_at_a_time(PROBE, contacts, "clamped", math.inf, 24)
    # The dense batch reads omega^2 = 1/mu - s without the quotient: eps kappa, kappa ~ 1e5 at
    # 24 elements.
    np.testing.assert_allclose(dense, ref, rtol=1e-10)


def test_batches_of_any_size_give_the_same_answer():
    contacts = np.linspace(0.01, 0.39, 41)
    whole = natural_frequencies(PROBE, contacts, chunk=41)
    parts = natural_frequencies(PROBE, contacts, chunk=5)
    # a batch stops when its slowest member has converged: the others take a step more or less,
    # which moves their quotients by far less than their own 1e-12
    np.testing.assert_allclose(whole, parts, rtol=1e-12)
    again = natural_frequencies(PROBE, contacts, chunk=41)
    np.testing.assert_array_equal(whole, again)


def test_sweep_rejects_bad_input():
    with pytest.raises(ValueError, match="method must be one of .*'reference'"):
        natural_frequencies(PROBE, np.array([0.1]), method="magic")
    with pytest.raises(ValueError, match="n_modes must be <="):
        natural_frequencies(PROBE, np.array([0.1]), n_elements=2, n_modes=4)
    for method in ("banded", "dense", "secular", "reference"):  # checked once, for every method
        with pytest.raises(ValueError, match=r"contacts must lie in \(0, 0.4\)"):
            natural_frequencies(PROBE, np.array([0.2, 0.0]), method=method)
        with pytest.raises(ValueError, match=r"contacts must lie in \[0.0002"):
            natural_frequencies(PROBE, np.array([0.2, 1e-9]), method=method)
        with pytest.raises(ValueError, match="n_modes must be <= 3"):
            natural_frequencies(PROBE, np.array([0.1]), n_elements=2, n_modes=4, method=method)


@pytest.mark.parametrize("n_elements", [2, 3, 4])
@pytest.mark.parametrize("hinge", ["clamped", "pinned", 3.0])
@pytest.mark.parametrize("k_c", [math.inf, 100.0])
def test_small_meshes_with_every_mode(n_elements, hinge, k_c):
    # Lanczos runs out of directions here (an invariant Krylov space): it must end cleanly.
    probe = Probe(tip_mass=0.002)
    n_modes = 2 * n_elements - 1
    fast = natural_frequencies(
        probe,
        np.array([0.1, 0.2]),
        hinge=hinge,
        contact_stiffness=k_c,
        n_elements=n_elements,
        n_modes=n_modes,
    )
    ref = one_at_a_time(probe, [0.1, 0.2], hinge, k_c, n_elements, n_modes)
    # tiny meshes, kappa <= 1e4: the quotients agree to a few eps kappa
    np.testing.assert_allclose(fast, ref, rtol=1e-10)


def test_banded_sweep_refuses_more_modes_than_lanczos_can_deliver():
    with pytest.raises(ValueError, match=r"n_modes must be <= 50 with method='banded'"):
        natural_frequencies(PROBE, np.array([0.2]), n_elements=200, n_modes=150)
    # the dense sweep takes that many; the banded one, up to its cap, agrees with one
    # modal_analysis (both refine by the Rayleigh quotient: relative agreement to a few hundred eps)
    dense = natural_frequencies(PROBE, np.array([0.2]), n_elements=200, n_modes=150,
                                method="dense")
    assert dense.shape == (1, 150) and np.all(np.diff(dense[0]) > 0)
    banded = natural_frequencies(PROBE, np.array([0.2]), n_elements=200, n_modes=50)
    single = modal_analysis(PROBE, Supports(0.2), n_elements=200, n_modes=50).frequencies
    np.testing.assert_allclose(banded[0], single, rtol=1e-12)


def test_one_position_solves_on_floats_are_the_batch_solves_bit_for_bit():
    """A batch of one position runs the banded Cholesky and the node-by-node triangular solves
    on Python floats; each column of a batch runs the same IEEE operations in the same order on
    arrays (a sum over a block's two columns from NumPy's identity, (0 + a) + b), so every bit
    agrees, signed zeros included."""
    from ebantenna.fem import banded

    rng = np.random.default_rng(7)
    n, B = 2 * 13, 3
    A = np.zeros((B, 4, n))
    A[:, 0] = 10 + rng.random((B, n))
    A[:, 1:] = 0.5 * rng.random((B, 3, n))
    A[:, 1:][rng.random((B, 3, n)) < 0.3] = -0.0  # entries of either sign of zero
    x = rng.standard_normal((n, B))
    x[rng.random((n, B)) < 0.2] = -0.0
    x[:, -1] = -0.0  # a sum of two negative zeros is +0 from NumPy's identity, -0 without it
    L = banded._cholesky(A)  # the array path (B > 1)
    blocks = banded._node_blocks(L)
    solves = banded._forward(blocks, x), banded._backward(blocks, x)
    for b in range(B):
        one = banded._cholesky(A[b : b + 1])  # the float path
        assert one.shape == (n + 6, 4, 1)
        assert np.array_equal(one[..., 0].view(np.int64), L[..., b].view(np.int64))
        one_blocks = banded._node_blocks(one)
        for solve, batch in zip((banded._forward, banded._backward), solves, strict=True):
            column = solve(one_blocks, x[:, b : b + 1])
            assert np.array_equal(column[:, 0].view(np.int64), batch[:, b].view(np.int64))
