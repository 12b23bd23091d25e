"""Exercise 2: assemble the two-element model by hand and find the paper's errata."""

import numpy as np
import sympy as sp

from ebantenna.fem.assembly import assemble_elements
from ebantenna.fem.elements import consistent_mass, element_stiffness
from ebantenna.fem.symbolic import (
    EI,
    l,
    l1,
    l2,
    paper_errata,
    paper_matrices,
    rhoA,
    two_element_matrices,
)

# [data]
EI_value, rhoA_value = 0.4123, 0.02617  # N m^2, kg/m (the default probe, rounded)
a, b = 0.3, 0.1  # m: contact at 30 cm of a 40 cm probe
# [/data]

# 1. Assemble by hand: each element adds its 4x4 block to the rows/columns of its two nodes.
K = np.zeros((6, 6))
M = np.zeros((6, 6))
for e, length in enumerate((a, b)):
    dofs = slice(2 * e, 2 * e + 4)
    K[dofs, dofs] += element_stiffness(EI_value, length)
    M[dofs, dofs] += consistent_mass(rhoA_value, length)

# 2. Compare with the sympy assembly, evaluated at the same numbers.
values = {EI: EI_value, rhoA: rhoA_value, l1: a, l2: b}
K_sym, M_sym = (np.array(m.subs(values), dtype=float) for m in two_element_matrices())
assert np.allclose(K, K_sym, rtol=1e-13, atol=0)
assert np.allclose(M, M_sym, rtol=1e-13, atol=1e-18)
# The package's loop adds the same numbers in the same places: no entry sums more than two terms,
# and x + y == y + x in floating point, so it agrees bit for bit.
lengths = np.array([a, b])
assert np.array_equal(K, assemble_elements(element_stiffness(EI_value, lengths)))
assert np.array_equal(M, assemble_elements(consistent_mass(rhoA_value, lengths)))

# 3. The printed K1 with l = l1 = l2 (equal elements): which entries disagree with the derivation?
equal = {l1: l, l2: l}
printed = paper_matrices()["K1"].subs(equal)
derived = two_element_matrices()[0].subs(equal)
wrong = sorted(
    (i + 1, j + 1)
    for i in range(6)
    for j in range(6)
    if sp.simplify(printed[i, j] - derived[i, j]) != 0
)
print("entries of K1 wrong even for equal elements (1-based):", wrong)

# The package lists exactly these as typos of K1.
typos = sorted((e.row, e.col) for e in paper_errata() if e.matrix == "K1" and e.reason == "typo")
assert wrong == typos, (wrong, typos)
# The printed K1 is not even symmetric, which a stiffness matrix must be.
assert paper_matrices()["K1"] != paper_matrices()["K1"].T
assert np.allclose(K, K.T)

# The expected answers on the exercise page, checked against these values by the test suite.
ANSWERS = {"n_typos_K1": len(typos), "K33": K[2, 2], "M33": M[2, 2]}
# The tolerance of each answer: how far two correct ways of working may differ, and why.
SUMS = "the same two terms added in any order: only the last of 16 digits can differ"
TOLERANCES = {"n_typos_K1": ("abs", 0, "a count of matrix entries"),
              "K33": ("rel", 1e-9, SUMS), "M33": ("rel", 1e-9, SUMS)}

print("ok: hand assembly equals the sympy assembly; the typos of K1 are", typos)
