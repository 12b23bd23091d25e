"""The sympy derivation against the NumPy element matrices, and the errata of the printed ones."""

from fractions import Fraction

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from ebantenna.fem import elements
from ebantenna.fem.symbolic import (
    EI,
    element_matrices,
    l,
    l1,
    l2,
    lambdify_element_matrices,
    paper_errata,
    rhoA,
    shape_functions,
    two_element_matrices,
    x,
)

positive_fractions = st.fractions(min_value=Fraction(1, 1000), max_value=Fraction(1000))


def test_shape_functions_interpolate_the_nodal_dofs():
    N = shape_functions()
    dN = sp.diff(N, x)
    assert [N[i].subs(x, 0) for i in range(4)] == [1, 0, 0, 0]
    assert [dN[i].subs(x, 0) for i in range(4)] == [0, 1, 0, 0]
    assert [N[i].subs(x, l) for i in range(4)] == [0, 0, 1, 0]
    assert [dN[i].subs(x, l) for i in range(4)] == [0, 0, 0, 1]


def test_element_matrices_are_the_textbook_ones():
    K, M = element_matrices()
    textbook_K = (
        EI
        / l**3
        * sp.Matrix(
            [
                [12, 6 * l, -12, 6 * l],
                [6 * l, 4 * l**2, -6 * l, 2 * l**2],
                [-12, -6 * l, 12, -6 * l],
                [6 * l, 2 * l**2, -6 * l, 4 * l**2],
            ]
        )
    )
    textbook_M = (
        rhoA
        * l
        / 420
        * sp.Matrix(
            [
                [156, 22 * l, 54, -13 * l],
                [22 * l, 4 * l**2, 13 * l, -3 * l**2],
                [54, 13 * l, 156, -22 * l],
                [-13 * l, -3 * l**2, -22 * l, 4 * l**2],
            ]
        )
    )
    assert sp.simplify(K - textbook_K) == sp.zeros(4, 4)
    assert sp.simplify(M - textbook_M) == sp.zeros(4, 4)


def test_rigid_body_motions_cost_no_strain_energy():
    K, _ = element_matrices()
    translation = sp.Matrix([1, 0, 1, 0])
    rotation = sp.Matrix([0, 1, l, 1])
    assert sp.simplify(K * translation) == sp.zeros(4, 1)
    assert sp.simplify(K * rotation) == sp.zeros(4, 1)


@settings(max_examples=25, deadline=None)
@given(ei=positive_fractions, rho_a=positive_fractions, length=positive_fractions)
def test_numpy_element_matrices_equal_sympy_exactly(ei, rho_a, length):
    # With Fraction inputs the NumPy polynomials are evaluated in exact rational arithmetic,
    # so "equal" means equal, not "close".
    K, M = element_matrices()
    subs = {EI: sp.Rational(ei), rhoA: sp.Rational(rho_a), l: sp.Rational(length)}
    K_num = elements.element_stiffness(np.array(ei, dtype=object), np.array(length, dtype=object))
    M_num = elements.consistent_mass(np.array(rho_a, dtype=object), np.array(length, dtype=object))
    for i in range(4):
        for j in range(4):
            assert sp.Rational(K_num[i, j]) == K.subs(subs)[i, j]
            assert sp.Rational(M_num[i, j]) == M.subs(subs)[i, j]


@settings(max_examples=25, deadline=None)
@given(ei=st.floats(1e-3, 1e3), rho_a=st.floats(1e-3, 1e3), length=st.floats(1e-4, 10.0))
def test_lambdified_and_hand_written_matrices_agree_in_floats(ei, rho_a, length):
    K_fun, M_fun = lambdify_element_matrices()
    # Both evaluate the same polynomials in a different order: a few ulps apart at most.
    np.testing.assert_allclose(
        elements.element_stiffness(ei, length), K_fun(ei, length), rtol=1e-14
    )
    np.testing.assert_allclose(
        elements.consistent_mass(rho_a, length), M_fun(rho_a, length), rtol=1e-14
    )


def test_two_element_model_is_the_assembly_of_two_elements():
    K1, M1 = two_element_matrices()
    K, M = element_matrices()
    assert K1[0:2, 0:2] == K.subs(l, l1)[0:2, 0:2]
    assert K1[4:6, 4:6] == K.subs(l, l2)[2:4, 2:4]
    assert sp.simplify(K1[2, 2] - 12 * EI * (1 / l1**3 + 1 / l2**3)) == 0
    assert sp.simplify(M1[3, 3] - rhoA * (l1**3 + l2**3) / 105) == 0
    assert K1[0, 4] == 0 and M1[1, 5] == 0


def test_errata_find_the_known_misprints():
    errata = paper_errata()
    typos = {(e.matrix, e.row, e.col) for e in errata if e.reason == "typo"}
    # Checked by hand against the paper's section 2.2: each is wrong even for l1 == l2, but for
    # M1(6,3) and M1(6,4), l1 printed where their own element's l2 belongs.
    assert typos == {
        ("K", 3, 4),
        ("K1", 4, 1),
        ("K1", 4, 2),
        ("K1", 4, 5),
        ("K1", 5, 4),
        ("M1", 4, 2),
        ("M1", 6, 3),
        ("M1", 6, 4),
    }
    common = {(e.matrix, e.row, e.col) for e in errata if e.reason == "common factor"}
    assert ("K1", 3, 3) in common and ("M1", 4, 4) in common
    assert all(e.matrix in {"K", "M", "K1", "M1"} for e in errata)
    assert not any(e.matrix == "M" for e in errata)  # the element mass matrix is printed right


def test_errata_records_read_like_dicts():
    e = paper_errata()[0]
    assert e["matrix"] == e.matrix and e["row"] >= 1 and e["col"] >= 1
    assert isinstance(e["printed"], str) and isinstance(e["derived"], str)


@pytest.mark.parametrize("matrix_name", ["K1", "M1"])
def test_every_unlisted_entry_really_agrees(matrix_name):
    from ebantenna.fem.symbolic import paper_matrices

    printed = paper_matrices()[matrix_name]
    derived = dict(zip(("K1", "M1"), two_element_matrices(), strict=True))[matrix_name]
    listed = {(e.row, e.col) for e in paper_errata() if e.matrix == matrix_name}
    for i in range(6):
        for j in range(6):
            if (i + 1, j + 1) in listed:
                continue
            # equal lengths make the printed factor well defined
            same = {l1: l, l2: l}
            assert sp.simplify(printed[i, j].subs(same) - derived[i, j].subs(same)) == 0


def test_one_element_has_the_two_frequencies_the_paper_says():
    # docs/theory/eigenproblem.rst: the paper's "two frequencies" of equation (2), one element, are
    # right: free, det(K - w^2 M) = 0 has a double root at zero (the rigid motions) and two
    # others, l^4 w^2 = 720 and 8400 (EI = rhoA = 1); clamped at one end, two DOFs, two roots
    w2 = sp.Symbol("w2")
    K, M = (m.subs({EI: 1, rhoA: 1}) for m in element_matrices())
    free = sp.Poly(sp.factor((K - w2 * M).det()), w2)
    roots = sp.roots(free)
    assert free.degree() == 4 and roots.get(sp.Integer(0)) == 2
    assert sorted(sp.simplify(r * l**4) for r in roots if r != 0) == [720, 8400]
    assert sp.Poly((K - w2 * M)[2:, 2:].det(), w2).degree() == 2
