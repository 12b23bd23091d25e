"""Fitting the hinge stiffness and the tip mass to where the dominant mode changes."""

import numpy as np
import pytest

from ebantenna import Probe
from ebantenna._validate import more_jobs_allowed
from ebantenna.fem import natural_frequencies
from ebantenna.fem.hinge import fit_hinge_and_tip, transition_position

PROBE = Probe()


def test_a_bare_clamped_tube_changes_at_one_fraction_of_any_length():
    # no length scale: the transition is the same fraction of 40 and of 50 cm, to its tolerance
    x40 = transition_position(PROBE, n_elements=24) / 0.4
    x50 = transition_position(Probe(length=0.5), n_elements=24) / 0.5
    assert abs(x40 - x50) < 1e-5


def test_the_peak_is_the_largest_lowest_frequency():
    x = transition_position(PROBE, n_elements=24)
    c = np.linspace(0.6, 0.95, 71) * PROBE.length
    f = natural_frequencies(PROBE, c, n_elements=24, n_modes=1)[:, 0]
    f_peak = natural_frequencies(PROBE, np.array([x]), n_elements=24, n_modes=1)[0, 0]
    assert f_peak >= f.max() * (1 - 1e-12)


def test_a_tip_mass_moves_the_change_outwards_and_a_soft_hinge_inwards():
    base = transition_position(PROBE, n_elements=24)
    assert transition_position(Probe(tip_mass=0.002), n_elements=24) > base
    assert transition_position(PROBE, hinge=0.3, n_elements=24) < base
    zone3 = transition_position(PROBE, criterion="zone3", n_elements=24)
    zone2 = transition_position(PROBE, criterion="zone2", n_elements=24)
    assert zone2 < zone3


def test_observations_made_by_a_known_model_are_fitted_back():
    truth = {"hinge": 2.0, "tip_mass": 0.001}
    lengths = np.array([0.4, 0.5])
    observed = np.array(
        [
            transition_position(
                Probe(length=length, tip_mass=truth["tip_mass"]),
                hinge=truth["hinge"],
                n_elements=24,
            )
            for length in lengths
        ]
    )
    fit = fit_hinge_and_tip(
        PROBE,
        lengths,
        observed,
        grid=4,
        n_elements=24,
        stiffness_bounds=(0.1, 100.0),
        mass_bounds=(0.0, 0.004),
    )
    # the located transitions carry ~1e-6 L of error; a consistent pair is fitted to that level
    assert fit.rms_residual < 2e-5
    assert fit.tip_mass == pytest.approx(truth["tip_mass"], rel=0.05)
    assert fit.hinge_stiffness == pytest.approx(truth["hinge"], rel=0.05)


def test_the_fit_is_the_same_on_two_worker_processes():
    # each point of the coarse search is computed alone, wherever it runs: the same lattice
    # costs, the same start, the same refinement, bit for bit
    args = dict(grid=3, n_elements=8, stiffness_bounds=(0.1, 100.0), mass_bounds=(0.0, 0.004))
    one = fit_hinge_and_tip(PROBE, [0.4], [0.3], n_jobs=1, **args)
    with more_jobs_allowed():  # two workers, on a machine of one core too
        two = fit_hinge_and_tip(PROBE, [0.4], [0.3], n_jobs=2, **args)
    assert (one.hinge_stiffness, one.tip_mass) == (two.hinge_stiffness, two.tip_mass)
    np.testing.assert_array_equal(one.predicted, two.predicted)
    for a, b in zip(one.lattice, two.lattice, strict=True):
        np.testing.assert_array_equal(a, b)


def test_the_lattice_holds_each_points_own_residual():
    # the search's lattice, witnessed point by point: the transition located on the model with
    # that hinge and tip mass, the same computation as the fit's, so the same to the last bit
    fit = fit_hinge_and_tip(PROBE, [0.4, 0.5], [0.3, 0.4], grid=3, n_elements=8,
                            stiffness_bounds=(0.1, 100.0), mass_bounds=(0.0, 0.004))
    stiffness, mass, rms = fit.lattice
    np.testing.assert_allclose(stiffness, [0.1, 10**0.5, 100.0], rtol=4 * np.finfo(float).eps)
    np.testing.assert_array_equal(mass, np.linspace(0.0, 0.004, 3))
    for i, k in enumerate(stiffness):
        for j, m in enumerate(mass):
            located = [transition_position(Probe(length=length, tip_mass=float(m)),
                                           hinge=float(k), n_elements=8) for length in (0.4, 0.5)]
            expected = np.sqrt(np.mean((np.array(located) - [0.3, 0.4]) ** 2))
            assert rms[i, j] == expected, (k, m)
    # within a tolerance: the stiffnesses whose best mass misses by at most that much more than
    # the least misfit found. Here that is a lattice point's (100 N m/rad, no tip mass): the fit
    # weighs the 40 cm probe's residual by 1/0.4 and the 50 cm one's by 1/0.5, the RMS does not
    best = rms.min(axis=1)
    assert best.min() < fit.rms_residual
    least = best.min()
    for tol in (0.0, 1e-3, float(np.median(best - least)), 1.0):
        np.testing.assert_array_equal(fit.stiffness_within(tol), stiffness[best <= least + tol])
    np.testing.assert_array_equal(fit.stiffness_within(0.0), [100.0])
    np.testing.assert_array_equal(fit.stiffness_within(1.0), stiffness)


def test_a_fit_without_a_search_has_no_lattice_to_read():
    from ebantenna.fem.hinge import HingeFit

    one = np.ones(1)
    with pytest.raises(ValueError, match="lattice"):
        HingeFit(5.0, 0.002, one, one, one, "peak").stiffness_within(0.001)
    with pytest.raises(ValueError, match="tolerance"):
        HingeFit(5.0, 0.002, one, one, one, "peak").stiffness_within(-1.0)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"observed": [0.45]}, r"observed must lie in \(0, length\)"),
        ({"lengths": [0.4, 0.5]}, "lengths and observed must be 1-D of one size"),
        ({"criterion": "knee"}, "criterion must be one of"),
        ({"mass_bounds": (-0.001, 0.01)}, "mass_bounds"),
        ({"stiffness_bounds": (0.0, 1.0)}, r"stiffness_bounds\[0\] must be > 0"),
        ({"n_jobs": 0}, "n_jobs must be -1"),
    ],
)
def test_bad_input_names_the_parameter(kwargs, message):
    args = {"lengths": [0.4], "observed": [0.3]} | kwargs
    with pytest.raises(ValueError, match=message):
        fit_hinge_and_tip(PROBE, args.pop("lengths"), args.pop("observed"), **args)


def test_a_peak_at_the_edge_of_the_search_is_refused():
    # a heavy tip pushes the lowest mode's peak to the tip: there is no interior peak to locate
    with pytest.raises(ValueError, match="edge of the searched contacts"):
        transition_position(Probe(tip_mass=0.2))


def test_a_parameter_on_a_bound_of_its_search_is_said_to_be_there():
    from ebantenna.fem.hinge import HingeFit

    one = np.ones(1)
    inside = HingeFit(5.0, 0.002, one, one, one, "peak")
    assert inside.at_bound == {}
    edges = HingeFit(1e3, 0.02, one, one, one, "peak", (1e-2, 1e3), (0.0, 0.02))
    assert edges.at_bound == {"hinge_stiffness": "upper", "tip_mass": "upper"}
    # a millionth of the range from a bound is on it; a thousandth is not
    assert HingeFit(5.0, 2e-8, one, one, one, "peak").at_bound == {"tip_mass": "lower"}
    assert HingeFit(5.0, 2e-5, one, one, one, "peak").at_bound == {}
    assert HingeFit(1e-2 * 1.00001, 0.01, one, one, one, "peak").at_bound == {
        "hinge_stiffness": "lower"}
