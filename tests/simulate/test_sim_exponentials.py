"""The uniform-grid engine of ``damped_exponentials`` against its reference, the direct sum."""

from __future__ import annotations

import functools

import numpy as np
import pytest

from ebantenna.simulate import builtin_scene, modal_terms
from ebantenna.simulate.modes import damped_exponentials, filtered_exponentials, modal_exponentials

EPS = np.finfo(float).eps


@functools.cache
def _paper_exponentials():
    """The exponentials the simulator sums for the ``paper`` scene: X's and Z's modes through
    the chip's low-pass filter (its poles are terms too)."""
    scene = builtin_scene("paper").with_(contact=0.2)
    dlpf = scene.effect("dlpf")
    out = []
    for terms in modal_terms(scene):
        coef, rate = modal_exponentials(terms.amplitude, terms.omega, terms.zeta)
        out.append(filtered_exponentials(coef, rate, dlpf.sos, dlpf.internal_rate))
    return out


@pytest.mark.parametrize("start", [0.0, 0.3])
def test_the_grid_engine_equals_the_direct_sum_to_the_rounding_of_the_arguments(start):
    t = start + np.arange(1001) / 1000.0
    for coef, rate in _paper_exponentials():
        grid = damped_exponentials(t, coef, rate)  # the default engine
        direct = damped_exponentials(t, coef, rate, engine="direct")
        # Each exponential's argument r t is rounded (relative eps, |r t| <= |r| t_max), and the
        # grid's instants t_0 + a B dt + b dt meet t to 8 eps t_max (its uniformity test): each
        # term e^(r t) moves by at most ~(8 + a few) eps |r| t_max (|e^(r t)| <= 1, Re r <= 0),
        # times |C|; summing the terms rounds by at most n_terms eps sum|C| more.
        assert np.all(rate.real <= 0)
        bound = 16 * EPS * (np.abs(rate).max() * t.max() + rate.shape[1]) * np.abs(coef).sum(1)
        assert np.all(np.abs(grid - direct).max(axis=1) <= bound)
        assert not np.array_equal(grid, direct)  # a different arithmetic, not the same bits


def test_where_the_grid_does_not_apply_the_engine_is_the_reference():
    coef, rate = _paper_exponentials()[0]
    rng = np.random.default_rng(1)
    short = np.arange(64) / 1000.0  # not longer than two blocks
    jittered = np.arange(500) / 1000.0 + rng.normal(0.0, 1e-6, (coef.shape[0], 500))
    uneven = np.sort(rng.uniform(0.0, 0.5, 500))
    for t in (short, jittered, uneven):
        assert np.array_equal(damped_exponentials(t, coef, rate),
                              damped_exponentials(t, coef, rate, engine="direct"))  # fmt: skip


def test_the_engine_is_named():
    with pytest.raises(ValueError, match="engine must be one of 'direct', 'grid'"):
        damped_exponentials(np.zeros(3), np.ones((1, 1), complex), -np.ones((1, 1)), engine="fast")
