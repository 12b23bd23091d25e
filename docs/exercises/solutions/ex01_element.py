"""Exercise 1: derive the consistent mass matrix of the beam element with sympy."""

import sympy as sp

from ebantenna.fem.symbolic import element_matrices, l, rhoA, x

# 1. The cubic and its four nodal conditions.
c = sp.symbols("c0:4")
v = sum(c[k] * x**k for k in range(4))
d = sp.symbols("v1 theta1 v2 theta2")
conditions = [
    sp.Eq(v.subs(x, 0), d[0]),
    sp.Eq(sp.diff(v, x).subs(x, 0), d[1]),
    sp.Eq(v.subs(x, l), d[2]),
    sp.Eq(sp.diff(v, x).subs(x, l), d[3]),
]
coefficients = sp.solve(conditions, c, dict=True)[0]
v_nodal = sp.expand(v.subs(coefficients))

# 2. The shape functions: the coefficient of each DOF.
N = sp.Matrix([[v_nodal.coeff(dof) for dof in d]])

# 3. M = integral of rho A N^T N over the element.
M = (rhoA * (N.T * N)).applyfunc(lambda e: sp.integrate(e, (x, 0, l)))
M = M.applyfunc(sp.factor)
print(sp.pretty(M * 420 / (rhoA * l)))

# Checks -----------------------------------------------------------------------------------------
# The same matrix as the package's derivation, entry by entry.
assert sp.simplify(M - element_matrices()[1]) == sp.zeros(4, 4)
# The textbook numbers: 156, 22 l, 54, -13 l in the first row, times rho A l / 420.
first_row = sp.Matrix([[156, 22 * l, 54, -13 * l]])
assert sp.simplify(M[0, :] * 420 / (rhoA * l) - first_row) == sp.zeros(1, 4)
# A rigid translation d = (1, 0, 1, 0) carries the whole mass rho A l of the element.
t = sp.Matrix([1, 0, 1, 0])
assert sp.simplify((t.T * M * t)[0] - rhoA * l) == 0
# A lumped mass matrix (rho A l / 2 on each deflection) carries the same mass, but is not M.
lumped = sp.diag(rhoA * l / 2, 0, rhoA * l / 2, 0)
assert sp.simplify((t.T * lumped * t)[0] - rhoA * l) == 0 and lumped != M

# The expected answers on the exercise page, checked against these values by the test suite.
ANSWERS = {"M11": M[0, 0] * 420 / (rhoA * l), "M14": M[0, 3] * 420 / (rhoA * l**2)}
# The tolerance of each answer: how far two correct ways of working may differ, and why.
EXACT = "exact rational arithmetic gives an integer; 1e-6 admits a floating-point quadrature"
TOLERANCES = {"M11": ("abs", 1e-6, EXACT), "M14": ("abs", 1e-6, EXACT)}

print("ok: M derived, equal to element_matrices()[1], carries the mass rho A l")
