"""Hertz contact of crossed cylinders, tube wall and wood across the grain, against witnesses."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from ebantenna.probe import Probe, material
from ebantenna.simulate.contact import (
    CrossedCylinders,
    across_grain_modulus,
    contact_modulus,
    ring_stiffness,
    tube_on_rod_stiffness,
)
from ebantenna.simulate.effects import ContactCompliance

EPS = np.finfo(float).eps


def test_equal_radii_is_sphere_on_flat_and_todays_contact_compliance():
    # Crossed cylinders of equal radius R have the gap (x^2 + y^2)/(2R) of a sphere on a flat.
    probe, steel = Probe(), material("steel")
    today = ContactCompliance()
    Es = today.effective_modulus(steel, probe)
    R = probe.outer_diameter / 2
    hz = CrossedCylinders(R, R, Es)
    assert hz.axis_ratio == 1.0
    # Closed forms are cube roots of the same products: equal to a few ulps.
    assert hz.stiffness(0.5) == pytest.approx(today.stiffness(steel, probe), rel=16 * EPS)
    P = 0.7
    a = (3 * P * R / (4 * Es)) ** (1 / 3)  # Johnson eq. 4.22
    assert hz.semi_axes(P)[0] == pytest.approx(a, rel=16 * EPS)
    assert hz.approach(P) == pytest.approx(a * a / R, rel=16 * EPS)


def test_nearly_equal_radii_join_the_circular_case_continuously():
    # B/A = 1 + 2e-6: the ellipse's approach differs from the circle's at first order in the
    # curvature difference, so the two agree to about 1e-6 (and not better than rounding).
    R, Es = 0.004, 3.5e9
    near = CrossedCylinders(R, R * (1 + 2e-6), Es)
    exact = CrossedCylinders(R, R, Es)
    assert near.approach(0.5) == pytest.approx(exact.approach(0.5), rel=2e-6)


def test_hertz_pressure_reproduces_the_gap_boussinesq():
    # Independent witness: the surface displacement under p0 sqrt(1 - x^2/a^2 - y^2/b^2), summed
    # from Boussinesq's 1/r kernel along chords through the field point (no elliptic integrals),
    # must equal delta - A x^2 - B y^2 inside the contact.
    R1, R2, Es, P = 0.004, 0.006, 3.5e9, 0.5
    hz = CrossedCylinders(R1, R2, Es)
    a, b = hz.semi_axes(P)
    p0 = 3 * P / (2 * math.pi * a * b)
    A, B = 1 / (2 * R2), 1 / (2 * R1)

    def displacement(x, y):
        def chord(phi):
            c, s = math.cos(phi), math.sin(phi)
            alpha = 1 - x * x / a**2 - y * y / b**2
            beta = -2 * (x * c / a**2 + y * s / b**2)
            gamma = c * c / a**2 + s * s / b**2
            return (beta**2 + 4 * alpha * gamma) / gamma**1.5

        return p0 / (8 * Es) * quad(chord, 0, math.pi, epsabs=0, epsrel=1e-13)[0]

    delta = hz.approach(P)
    # quad's relative accuracy 1e-13 on a smooth periodic integrand; 1e-11 leaves margin.
    for x, y in ((0, 0), (0.5 * a, 0), (0, 0.6 * b), (0.3 * a, 0.4 * b)):
        assert displacement(x, y) == pytest.approx(delta - A * x * x - B * y * y, rel=1e-11)


def test_linearised_stiffness_is_the_derivative_of_the_nonlinear_law():
    hz = CrossedCylinders(0.004, 0.006, 3.5e9)
    F0 = 0.5
    d0 = hz.approach(F0)
    h = 1e-4 * d0
    fd = (hz.force(d0 + h) - hz.force(d0 - h)) / (2 * h)
    # Central difference of P ~ d^1.5: truncation (h/d)^2 * |P'''| d^2/6 / P' = 1e-8 / 24 relative,
    # rounding eps * P / h = 1e-12; 1e-8 covers both.
    assert fd == pytest.approx(hz.stiffness(F0), rel=1e-8)
    assert hz.force(-1e-9) == 0.0  # no tension


def test_stiffness_grows_without_bound_toward_a_cylinder_on_a_flat():
    radii = 0.004 * np.array([1, 1.5, 10, 100, 1e4])
    k = [CrossedCylinders(0.004, r, 3.5e9).stiffness(0.5) for r in radii]
    assert np.all(np.diff(k) > 0)
    # The growth is slow (roughly as (R2/R1)^(1/6) for a long ellipse) but unbounded: a line
    # contact is no point contact, and sphere-on-flat is not the flat-rod limit.
    assert k[-1] > 9 * k[0]


def test_stiffness_is_symmetric_in_the_two_radii():
    k12 = CrossedCylinders(0.004, 0.006, 3.5e9).stiffness(0.3)
    k21 = CrossedCylinders(0.006, 0.004, 3.5e9).stiffness(0.3)
    assert k12 == k21


def test_thin_ring_limit_is_roarks_pi_over_4_minus_2_over_pi():
    # A very thin wall: the hoop and shear corrections (~ (t/R)^2) vanish.
    Do, Di, E, w = 0.1, 0.1 - 2e-5, 1e9, 0.01
    t, Rm = (Do - Di) / 2, (Do + Di) / 4
    thin = E * (w * t**3 / 12) / (Rm**3 * (math.pi / 4 - 2 / math.pi))
    # Corrections are of order (t/Rm)^2 = 1.6e-7.
    assert ring_stiffness(Do, Di, E, 0.3, width=w) == pytest.approx(thin, rel=1e-6)


def test_wood_is_indented_across_the_grain():
    wood = material("wood")
    E_across = across_grain_modulus(wood.youngs_modulus)
    assert E_across == pytest.approx(wood.youngs_modulus * math.sqrt(0.154 * 0.082), rel=4 * EPS)
    across = tube_on_rod_stiffness(Probe(), wood, 0.012, 0.5, wall=False)
    along = tube_on_rod_stiffness(
        Probe(), wood, 0.012, 0.5, wall=False, object_modulus=wood.youngs_modulus
    )
    assert across.hertz < along.hertz
    assert across.contact_modulus == pytest.approx(
        contact_modulus(3.0e9, E_across, poisson_ratio1=0.39, poisson_ratio2=wood.poisson_ratio),
        rel=4 * EPS,
    )


def test_series_total_and_the_dominant_share():
    ks = tube_on_rod_stiffness(Probe(), material("steel"), 0.012, 0.5)
    assert 1 / ks.total == pytest.approx(1 / ks.hertz + 1 / ks.ring, rel=4 * EPS)
    assert ks.dominant == "ring"
    solid = tube_on_rod_stiffness(Probe(inner_diameter=0.0), material("pvc"), 0.012, 0.5)
    assert solid.ring == math.inf and solid.total == solid.hertz


@pytest.mark.parametrize(
    ("call", "word"),
    [
        (lambda: CrossedCylinders(0.0, 0.01, 1e9), "radius1"),
        (lambda: CrossedCylinders(0.01, -1.0, 1e9), "radius2"),
        (lambda: CrossedCylinders(0.01, 0.01, -1e9), "modulus"),
        (lambda: CrossedCylinders(0.01, 0.01, 1e9).stiffness(0.0), "preload"),
        (lambda: contact_modulus(1e9, 1e9, poisson_ratio1=0.5, poisson_ratio2=0.3), "Poisson"),
        (lambda: contact_modulus(1e9, 1e9, poisson_ratio1=0.3, poisson_ratio2=-1.0), "Poisson"),
        (lambda: ring_stiffness(0.008, 0.009, 3e9), "inner_diameter"),
        (lambda: tube_on_rod_stiffness(Probe(), material("steel"), 0.0, 0.5), "rod_diameter"),
        (lambda: tube_on_rod_stiffness(Probe(), material("steel"), 0.01, -0.1), "preload"),
    ],
)
def test_impossible_parameters_are_named(call, word):
    with pytest.raises(ValueError, match=word):
        call()
