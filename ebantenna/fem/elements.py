"""Euler-Bernoulli beam element matrices and shape functions in NumPy.

These are the matrices derived in :mod:`ebantenna.fem.symbolic`, written as polynomials in the
element length so that they vectorise over many elements at once (and so that they also work on
exact :class:`fractions.Fraction` inputs, which is how the tests prove them equal to the sympy
result). DOF order per element: ``(v1, theta1, v2, theta2)``.
"""

from __future__ import annotations

import numpy as np

__all__ = ["element_stiffness", "consistent_mass", "hermite", "hermite_slope"]

# K = EI/l^3 * (K0 + K1*l + K2*l^2), M = rhoA*l/420 * (M0 + M1*l + M2*l^2)
_K0 = np.array([[12, 0, -12, 0], [0, 0, 0, 0], [-12, 0, 12, 0], [0, 0, 0, 0]])
_K1 = np.array([[0, 6, 0, 6], [6, 0, -6, 0], [0, -6, 0, -6], [6, 0, -6, 0]])
_K2 = np.array([[0, 0, 0, 0], [0, 4, 0, 2], [0, 0, 0, 0], [0, 2, 0, 4]])
_M0 = np.array([[156, 0, 54, 0], [0, 0, 0, 0], [54, 0, 156, 0], [0, 0, 0, 0]])
_M1 = np.array([[0, 22, 0, -13], [22, 0, 13, 0], [0, 13, 0, -22], [-13, 0, -22, 0]])
_M2 = np.array([[0, 0, 0, 0], [0, 4, 0, -3], [0, 0, 0, 0], [0, -3, 0, 4]])


def _expand(value):
    value = np.asarray(value)
    return value[..., None, None]


def element_stiffness(EI, l):
    """Element stiffness matrix of an Euler-Bernoulli beam element.

    Parameters
    ----------
    EI : float or array
        Bending stiffness, N m^2.
    l : float or array
        Element length, m. Arrays broadcast with ``EI``.

    Returns
    -------
    ndarray of shape (..., 4, 4)
        Stiffness in N/m, N, N m per the DOF order ``(v1, theta1, v2, theta2)``.

    Examples
    --------
    >>> from ebantenna.fem.elements import element_stiffness
    >>> element_stiffness(1.0, 1.0)[0]
    array([ 12.,   6., -12.,   6.])
    """
    EI, l = _expand(EI), _expand(l)
    return EI / l**3 * (_K0 + _K1 * l + _K2 * l**2)


def consistent_mass(rhoA, l):
    """Consistent mass matrix of an Euler-Bernoulli beam element.

    Parameters
    ----------
    rhoA : float or array
        Mass per unit length, kg/m.
    l : float or array
        Element length, m.

    Returns
    -------
    ndarray of shape (..., 4, 4)
        Mass in kg, kg m, kg m^2 per the DOF order ``(v1, theta1, v2, theta2)``.

    Examples
    --------
    >>> from ebantenna.fem.elements import consistent_mass
    >>> M = consistent_mass(2.0, 0.5)          # rho A = 2 kg/m, l = 0.5 m
    >>> float(M[::2, ::2].sum())              # a rigid translation carries the whole mass rho A l
    1.0
    """
    rhoA, l = _expand(rhoA), _expand(l)
    return rhoA * l / 420 * (_M0 + _M1 * l + _M2 * l**2)


def hermite(xi, l):
    """Hermite cubic shape functions at ``xi = x/l`` in [0, 1] of an element of length ``l`` (m).

    Returns an array of shape ``(..., 4)``:
    deflection = ``hermite(xi, l) @ (v1, theta1, v2, theta2)``.
    """
    xi = np.asarray(xi, dtype=float)
    l = np.asarray(l, dtype=float)
    return np.stack(
        [
            1 - 3 * xi**2 + 2 * xi**3,
            l * (xi - 2 * xi**2 + xi**3),
            3 * xi**2 - 2 * xi**3,
            l * (-(xi**2) + xi**3),
        ],
        axis=-1,
    )


def hermite_slope(xi, l):
    """Derivatives ``dN/dx``, shape (..., 4): 1/m for the deflection DOFs, 1 for the slopes."""
    xi = np.asarray(xi, dtype=float)
    l = np.asarray(l, dtype=float)
    return np.stack(
        [
            (-6 * xi + 6 * xi**2) / l,
            1 - 4 * xi + 3 * xi**2,
            (6 * xi - 6 * xi**2) / l,
            -2 * xi + 3 * xi**2,
        ],
        axis=-1,
    )
