"""The element matrices as polynomials in the element length: the engine behind the fast paths.

:mod:`~ebantenna.fem.elements` writes ``K_e`` and ``M_e`` out entry by entry, as the textbook does.
Every entry is a constant times a power of ``l`` (``12``, ``6 l``, ``4 l^2``, ...), so each matrix
is also a polynomial with constant 4 x 4 coefficient matrices,

    K_e = EI / l^3 (K0 + K1 l + K2 l^2),     M_e = rho A l / 420 (M0 + M1 l + M2 l^2),

three broadcast products instead of sixteen assignments: several times faster on the small arrays
of one mesh. It is the same arithmetic entry by entry: each entry of ``K0 + K1 l + K2 l^2`` is one
nonzero term plus exact zeros (``c l + 0 + 0 == c l``), so the matrices equal the written-out ones
bit for bit (``tests/fem`` holds them equal).
"""

from __future__ import annotations

import numpy as np

__all__ = ["stiffness_polynomial", "mass_polynomial"]

_K0 = np.array([[12, 0, -12, 0], [0, 0, 0, 0], [-12, 0, 12, 0], [0, 0, 0, 0]])
_K1 = np.array([[0, 6, 0, 6], [6, 0, -6, 0], [0, -6, 0, -6], [6, 0, -6, 0]])
_K2 = np.array([[0, 0, 0, 0], [0, 4, 0, 2], [0, 0, 0, 0], [0, 2, 0, 4]])
_M0 = np.array([[156, 0, 54, 0], [0, 0, 0, 0], [54, 0, 156, 0], [0, 0, 0, 0]])
_M1 = np.array([[0, 22, 0, -13], [22, 0, 13, 0], [0, 13, 0, -22], [-13, 0, -22, 0]])
_M2 = np.array([[0, 0, 0, 0], [0, 4, 0, -3], [0, 0, 0, 0], [0, -3, 0, 4]])


def _expand(value):
    return np.asarray(value)[..., None, None]


def stiffness_polynomial(EI, l) -> np.ndarray:
    """:func:`~ebantenna.fem.elements.element_stiffness`, bit for bit, as a polynomial in ``l``."""
    EI, l = _expand(EI), _expand(l)
    return EI / l**3 * (_K0 + _K1 * l + _K2 * l**2)


def mass_polynomial(rhoA, l) -> np.ndarray:
    """:func:`~ebantenna.fem.elements.consistent_mass`, bit for bit, as a polynomial in ``l``."""
    rhoA, l = _expand(rhoA), _expand(l)
    return rhoA * l / 420 * (_M0 + _M1 * l + _M2 * l**2)
