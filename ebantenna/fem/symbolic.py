"""The Euler-Bernoulli beam element, derived with sympy, and the errata of the paper's matrices.

The derivation follows any finite-element textbook (e.g. C. W. de Silva, *Vibration: Fundamentals
and Practice*, 2nd ed., CRC Press, 2007, ch. 11):

1. Approximate the deflection inside an element of length ``l`` by a cubic
   ``v(x) = c0 + c1 x + c2 x^2 + c3 x^3``.
2. Express the four coefficients through the nodal degrees of freedom ``(v1, theta1, v2, theta2)``
   (deflection and slope ``v'`` at both ends): ``v(x) = N(x) . d`` with the Hermite cubics ``N``.
3. Strain energy ``U = 1/2 int EI v''^2 dx = 1/2 d^T K d`` gives ``K = int EI N''^T N'' dx``;
   kinetic energy ``T = 1/2 int rho A vdot^2 dx = 1/2 ddot^T M ddot`` gives
   ``M = int rho A N^T N dx``.

Everything here is exact rational arithmetic in sympy. :mod:`ebantenna.fem.elements` holds the fast
NumPy versions, and the tests prove that both agree exactly.

DOF order is ``(v1, theta1, v2, theta2)`` per element and ``(v1, theta1, v2, theta2, v3, theta3)``
for the paper's two-element model (hinge P, contact Q, free end R). Rows and columns are 0-based in
code; the errata quote them 1-based, as printed.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

__all__ = [
    "x",
    "l",
    "l1",
    "l2",
    "EI",
    "rhoA",
    "shape_functions",
    "element_matrices",
    "two_element_matrices",
    "assemble_chain",
    "paper_matrices",
    "paper_errata",
    "Erratum",
    "PAPER_NOTES",
    "lambdify_element_matrices",
]

x, l, l1, l2 = sp.symbols("x l l1 l2", positive=True)
EI, rhoA = sp.symbols("EI rhoA", positive=True)


@cache
def shape_functions() -> sp.Matrix:
    """The Hermite cubic shape functions ``N(x)`` (a 1x4 row) on ``0 <= x <= l``.

    Found by solving for the cubic's coefficients from the nodal values, not typed in.

    Examples
    --------
    >>> from ebantenna.fem.symbolic import shape_functions, x, l
    >>> N = shape_functions()
    >>> [N[i].subs(x, 0) for i in range(4)]   # only v1 is felt at the left node
    [1, 0, 0, 0]
    """
    c = sp.symbols("c0:4")
    v = sum(c[k] * x**k for k in range(4))
    dv = sp.diff(v, x)
    d = sp.symbols("v1 theta1 v2 theta2")
    equations = [
        sp.Eq(v.subs(x, 0), d[0]),
        sp.Eq(dv.subs(x, 0), d[1]),
        sp.Eq(v.subs(x, l), d[2]),
        sp.Eq(dv.subs(x, l), d[3]),
    ]
    coefficients = sp.solve(equations, c, dict=True)[0]
    v_nodal = sp.expand(v.subs(coefficients))
    return sp.Matrix([[sp.factor(v_nodal.coeff(d[k])) for k in range(4)]])


@cache
def element_matrices() -> tuple[sp.Matrix, sp.Matrix]:
    """Element stiffness ``K = int EI N''^T N'' dx`` and consistent mass ``M = int rhoA N^T N dx``.

    Returns
    -------
    K, M : sympy.Matrix, 4x4
        In DOF order ``(v1, theta1, v2, theta2)``, symbols ``EI``, ``rhoA``, ``l``.

    Examples
    --------
    >>> from ebantenna.fem.symbolic import element_matrices, EI, l
    >>> K, M = element_matrices()
    >>> (K * l**3 / EI)[0, :]
    Matrix([[12, 6*l, -12, 6*l]])
    """
    N = shape_functions()
    B = sp.diff(N, x, 2)
    K = sp.simplify(EI * sp.integrate(B.T * B, (x, 0, l)))
    M = sp.simplify(rhoA * sp.integrate(N.T * N, (x, 0, l)))
    return K, M


def assemble_chain(element_list: list[sp.Matrix]) -> sp.Matrix:
    """Assemble the symbolic 4x4 matrices of a chain of elements (node k joins elements k-1, k).

    The sympy counterpart of :func:`~ebantenna.fem.assembly.assemble_elements`: element ``e``
    adds its block into rows and columns ``2e .. 2e + 3``.
    """
    if isinstance(element_list, sp.MatrixBase) or not isinstance(element_list, list | tuple):
        raise TypeError(f"element_list must be a list of 4x4 sympy matrices, got "
                        f"{type(element_list).__name__}")
    if not element_list:
        raise ValueError("element_list must hold at least one element matrix")
    for e, Ke in enumerate(element_list):
        if not isinstance(Ke, sp.MatrixBase) or Ke.shape != (4, 4):
            raise ValueError(f"element_list[{e}] must be a 4x4 sympy matrix, got "
                             f"{type(Ke).__name__} {getattr(Ke, 'shape', '')}")
    n = len(element_list)
    G = sp.zeros(2 * n + 2, 2 * n + 2)
    for e, Ke in enumerate(element_list):
        G[2 * e : 2 * e + 4, 2 * e : 2 * e + 4] += Ke
    return G


@cache
def two_element_matrices() -> tuple[sp.Matrix, sp.Matrix]:
    """The paper's 6-DOF model: hinge P, element 1 (``l1``), contact Q, element 2 (``l2``), tip R.

    The two elements have different lengths, so their factors ``EI/l1^3`` and ``EI/l2^3`` differ and
    cannot be pulled out of the assembled matrix as one common factor.

    Returns
    -------
    K1, M1 : sympy.Matrix, 6x6
        DOF order ``(v1, theta1, v2, theta2, v3, theta3)``; no supports applied yet.

    Examples
    --------
    >>> from ebantenna.fem.symbolic import two_element_matrices, EI, l1, l2
    >>> K1, M1 = two_element_matrices()
    >>> K1[2, 2]
    12*EI/l2**3 + 12*EI/l1**3
    """
    K, M = element_matrices()
    Ks = [K.subs(l, length) for length in (l1, l2)]
    Ms = [M.subs(l, length) for length in (l1, l2)]
    return assemble_chain(Ks), assemble_chain(Ms)


# --- The matrices as the paper prints them (section 2.2), transcribed entry by entry. -------------
# The printed factor in front of each matrix is written out: EI/l^3 for K, rhoA*l/420 for M. In the
# two-element matrices the printed "l" in the factor is not defined; see `paper_errata`.
_PAPER_K = [
    ["12", "6*l", "-12", "6*l"],
    ["6*l", "4*l**2", "-6*l", "2*l**2"],
    ["-12", "-6*l", "12", "6*l"],
    ["6*l", "2*l**2", "-6*l", "4*l**2"],
]
_PAPER_M = [
    ["156", "22*l", "54", "-13*l"],
    ["22*l", "4*l**2", "13*l", "-3*l**2"],
    ["54", "13*l", "156", "-22*l"],
    ["-13*l", "-3*l**2", "-22*l", "4*l**2"],
]
_PAPER_K1 = [
    ["12", "6*l1", "-12", "6*l1", "0", "0"],
    ["6*l1", "4*l1**2", "-6*l1", "2*l1**2", "0", "0"],
    ["-12", "-6*l1", "24", "6*(l2 - l1)", "-12", "6*l2"],
    ["-12", "-6*l1", "6*(l2 - l1)", "4*(l1**2 + l2**2)", "-6*l1**2", "2*l2**2"],
    ["0", "0", "-12", "6*l2", "12", "-6*l2"],
    ["0", "0", "6*l2", "2*l2**2", "-6*l2", "4*l2**2"],
]
_PAPER_M1 = [
    ["156", "22*l1", "54", "-13*l1", "0", "0"],
    ["22*l1", "4*l1**2", "13*l1", "-3*l1**2", "0", "0"],
    ["54", "13*l1", "312", "22*(l2 - l1)", "54", "-13*l2"],
    ["-13*l1", "-13*l1**2", "22*(l2 - l1)", "4*(l1**2 + l2**2)", "13*l2", "-3*l2**2"],
    ["0", "0", "54", "13*l2", "156", "-22*l2"],
    ["0", "0", "-13*l1", "-3*l1**2", "-22*l2", "4*l2**2"],
]

#: What the paper gets wrong besides single entries (quoted in the docs beside the errata table).
PAPER_NOTES = (
    "The text lists the element DOFs as [v1, v2, theta1, theta2], but the printed K and M are in "
    "the order (v1, theta1, v2, theta2).",
    "I is called the 'moment of inertia (kg/m^2)'; it is the second moment of area, in m^4.",
    "K1 and M1 carry one factor EI/l^3 and rhoA*l/420 with an undefined l; with l1 != l2 the two "
    "elements' factors differ and cannot be taken out in common.",
)


def paper_matrices() -> dict[str, sp.Matrix]:
    """The four matrices as printed, with their printed factors, as sympy matrices.

    Returns
    -------
    dict
        ``{"K": 4x4, "M": 4x4, "K1": 6x6, "M1": 6x6}``; the symbol ``l`` stands for the undefined
        length of the printed factor.
    """
    factor_k = EI / l**3
    factor_m = rhoA * l / 420
    symbols = {"l": l, "l1": l1, "l2": l2}

    def parse(rows):
        return sp.Matrix([[sp.sympify(entry, locals=symbols) for entry in row] for row in rows])

    return {
        "K": factor_k * parse(_PAPER_K),
        "M": factor_m * parse(_PAPER_M),
        "K1": factor_k * parse(_PAPER_K1),
        "M1": factor_m * parse(_PAPER_M1),
    }


@dataclass(frozen=True)
class Erratum:
    """One printed matrix entry that differs from the derivation.

    Attributes
    ----------
    matrix : str
        ``"K"``, ``"M"`` (element) or ``"K1"``, ``"M1"`` (two-element model).
    row, col : int
        1-based, as printed.
    printed, derived : str
        The entry as printed (with the printed factor) and as derived, both in sympy syntax.
    reason : str
        ``"typo"`` (wrong however the printed factor's ``l`` is read: as the length of the
        entry's own element, or with ``l1 == l2`` in an entry both elements share) or
        ``"common factor"`` (an entry both elements share, right only when ``l1 == l2``, because
        the printed factor cannot serve two element lengths).
    """

    matrix: str
    row: int
    col: int
    printed: str
    derived: str
    reason: str

    def __getitem__(self, key):
        # Records can be read like dicts too: ``erratum["row"]``.
        return getattr(self, key)


def _compare(name: str, printed: sp.Matrix, derived: sp.Matrix) -> list[Erratum]:
    records = []
    for i in range(printed.rows):
        for j in range(printed.cols):
            p, d = printed[i, j], derived[i, j]
            lengths = d.free_symbols & {l, l1, l2}
            if lengths <= {l}:
                own = l  # element matrices
            elif len(lengths) == 1:
                own = next(iter(lengths))  # an entry of one element only: its own length is "l"
            else:
                own = None  # a shared node: both elements contribute
            if own is not None:
                if sp.simplify(p.subs(l, own) - d) == 0:
                    continue
                reason = "typo"
            else:
                equal = {l1: l, l2: l}
                if sp.simplify(p.subs(equal) - d.subs(equal)) != 0:
                    reason = "typo"
                else:
                    reason = "common factor"
            records.append(Erratum(name, i + 1, j + 1, str(p), str(sp.factor(d)), reason))
    return records


def paper_errata() -> list[Erratum]:
    """Every printed entry of K, M, K1 and M1 that differs from the sympy derivation, and why.

    An entry of one element alone is compared with that element's length in the printed factor,
    and is a ``"typo"`` when it differs (a wrong subscript, ``l1`` where ``l2`` belongs, is one:
    it would go unseen with ``l1 == l2``). An entry at the shared node (contact Q) mixes both
    elements: it is a ``"typo"`` if it is wrong even for ``l1 == l2 == l``, and a
    ``"common factor"`` erratum if it is right only then.

    Returns
    -------
    list of Erratum
        Each with ``matrix``, ``row``, ``col`` (1-based), ``printed``, ``derived``, ``reason``.

    Examples
    --------
    >>> from ebantenna.fem.symbolic import paper_errata
    >>> [(e.matrix, e.row, e.col) for e in paper_errata() if e.reason == "typo"][:3]
    [('K', 3, 4), ('K1', 4, 1), ('K1', 4, 2)]
    """
    printed = paper_matrices()
    K, M = element_matrices()
    K1, M1 = two_element_matrices()
    derived = {"K": K, "M": M, "K1": K1, "M1": M1}
    records = []
    for name in ("K", "M", "K1", "M1"):
        records += _compare(name, printed[name], derived[name])
    return records


def lambdify_element_matrices():
    """NumPy functions ``K(EI, l)`` and ``M(rhoA, l)`` made by :func:`sympy.lambdify`.

    This is the direct route from the symbolic result to numbers; :mod:`ebantenna.fem.elements`
    has hand-vectorised versions, and the tests hold both to the sympy matrices.
    """
    K, M = element_matrices()
    return sp.lambdify((EI, l), K, "numpy"), sp.lambdify((rhoA, l), M, "numpy")
