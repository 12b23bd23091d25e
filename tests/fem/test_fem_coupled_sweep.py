"""The coupled sweep over positions x rods equals one coupled_modes call per pair."""

import numpy as np
import pytest

from ebantenna import Probe
from ebantenna.fem.coupled_sweep import coupled_sweep
from ebantenna.fem.coupling import Rod, coupled_modes

PROBE = Probe(tip_mass=0.002)


#: The same reductions and the same small solve, batched differently (other BLAS blocking): they
#: differ by the rounding of the reduced eigenproblem. Its bound, n eps (omega_max / omega)^2 over
#: the ~60 retained modes, is about 1e-6 for the lowest mode; the Rayleigh-quotient refinement
#: keeps the real difference far below (measured up to 2e-11 over NumPy 1.24 and 2.4 and four
#: OpenBLAS kernels). 1e-9 sits between the two: 50 times the worst seen, and far below any error
#: of assembly or pairing, which moves a frequency by per cent.
BATCHING = 1e-9

def test_sweep_equals_one_pair_at_a_time():
    rods = [Rod("steel"), Rod("wood", contact_height=0.2), Rod("pvc")]
    contacts = np.array([0.05, 0.17, 0.33])
    k_c = np.array([3e5, 1e5, 5e4])  # per rod, as a Hertz stiffness per material would be
    sweep = coupled_sweep(PROBE, rods, contacts, k_c, hinge="pinned", n_modes=4)
    for i, rod in enumerate(rods):
        for j, c in enumerate(contacts):
            one = coupled_modes(PROBE, rod, float(c), float(k_c[i]), hinge="pinned", n_modes=4)
            np.testing.assert_allclose(sweep.frequencies[i, j], one.frequencies, rtol=BATCHING)
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
    np.testing.assert_allclose(sweep.frequencies[1, 0], one.frequencies, rtol=BATCHING)
    with pytest.raises(ValueError, match="contact_stiffness must be a number or of shape"):
        coupled_sweep(PROBE, rods, contacts, np.ones(3))
    with pytest.raises(ValueError, match="contact_stiffness"):
        coupled_sweep(PROBE, rods, contacts, -1.0)
    with pytest.raises(ValueError, match="rods must hold at least one Rod"):
        coupled_sweep(PROBE, [], contacts, 1e5)
    with pytest.raises(ValueError, match=r"contacts must lie in \(0, 0.4\)"):
        coupled_sweep(PROBE, rods, np.array([0.5]), 1e5)
