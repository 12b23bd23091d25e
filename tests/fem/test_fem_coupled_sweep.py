"""The coupled sweep over positions x rods equals one coupled_modes call per pair."""

import numpy as np
import pytest

from ebantenna import Probe
from ebantenna.fem.coupled_sweep import coupled_sweep
from ebantenna.fem.coupling import Rod, coupled_modes

PROBE = Probe(tip_mass=0.002)


def test_sweep_equals_one_pair_at_a_time():
    rods = [Rod("steel"), Rod("wood", contact_height=0.2), Rod("pvc")]
    contacts = np.array([0.05, 0.17, 0.33])
    k_c = np.array([3e5, 1e5, 5e4])  # per rod, as a Hertz stiffness per material would be
    sweep = coupled_sweep(PROBE, rods, contacts, k_c, hinge="pinned", n_modes=4)
    for i, rod in enumerate(rods):
        for j, c in enumerate(contacts):
            one = coupled_modes(PROBE, rod, float(c), float(k_c[i]), hinge="pinned", n_modes=4)
            # the same reductions and the same small solve, batched differently (other BLAS
            # blocking): equal to the rounding of the Rayleigh-quotient refinement, about
            # n eps (omega_k / omega_1)^2 over the ~60 retained modes k that mix into the lowest
            # (measured up to 2e-12 across BLAS kernels and thread counts); 1e-10 bounds it
            np.testing.assert_allclose(sweep.frequencies[i, j], one.frequencies, rtol=1e-10)
            np.testing.assert_allclose(sweep.damping_ratio[i, j], one.damping_ratio, rtol=1e-10)
            np.testing.assert_allclose(
                np.abs(sweep.tip_displacement[i, j]), np.abs(one.tip_displacement), rtol=1e-9
            )


def test_stiffness_per_rod_and_position_and_bad_shapes():
    rods = [Rod("brass"), Rod("aluminium")]
    contacts = np.array([0.1, 0.3])
    grid = np.array([[1e5, 2e5], [3e5, 4e5]])
    sweep = coupled_sweep(PROBE, rods, contacts, grid, n_modes=2)
    one = coupled_modes(PROBE, rods[1], 0.1, 3e5, n_modes=2)
    np.testing.assert_allclose(sweep.frequencies[1, 0], one.frequencies, rtol=1e-12)
    with pytest.raises(ValueError, match="contact_stiffness must be a number or of shape"):
        coupled_sweep(PROBE, rods, contacts, np.ones(3))
    with pytest.raises(ValueError, match="contact_stiffness"):
        coupled_sweep(PROBE, rods, contacts, -1.0)
    with pytest.raises(ValueError, match="rods must hold at least one Rod"):
        coupled_sweep(PROBE, [], contacts, 1e5)
    with pytest.raises(ValueError, match=r"contact must lie in \(0, 0.4\)"):
        coupled_sweep(PROBE, rods, np.array([0.5]), 1e5)
