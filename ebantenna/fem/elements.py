r"""Euler-Bernoulli beam element matrices and shape functions in NumPy.

These are the matrices derived in :mod:`ebantenna.fem.symbolic`, written out entry by entry as
a textbook prints them,

.. math::

   K_e = \frac{EI}{l^3} \begin{bmatrix} 12 & 6l & -12 & 6l \\ 6l & 4l^2 & -6l & 2l^2 \\
         -12 & -6l & 12 & -6l \\ 6l & 2l^2 & -6l & 4l^2 \end{bmatrix}, \qquad
   M_e = \frac{\rho A\, l}{420} \begin{bmatrix} 156 & 22l & 54 & -13l \\
         22l & 4l^2 & 13l & -3l^2 \\ 54 & 13l & 156 & -22l \\ -13l & -3l^2 & -22l & 4l^2
         \end{bmatrix}.

Each entry is an array, so one call builds the matrices of many elements at once (``l`` of shape
``(n,)`` gives ``(n, 4, 4)``), and on exact :class:`fractions.Fraction` inputs the arithmetic is
exact, which is how the tests prove them equal to the sympy result. DOF order per element:
``(v1, theta1, v2, theta2)``.

Filling sixteen entries one by one costs a few microseconds per call, which adds up when a sweep
builds the matrices of thousands of meshes; the fast paths (:func:`~ebantenna.fem.assembly.assemble`
by default, the sweeps) use an engine that writes the same matrices as ``K0 + K1 l + K2 l^2``,
equal to these bit for bit (``ebantenna.fem._assembly_engine``).
"""

from __future__ import annotations

import math
from numbers import Real

import numpy as np

__all__ = [
    "element_stiffness",
    "consistent_mass",
    "hermite",
    "hermite_slope",
]


def _checked(name: str, value, *, positive: bool = True):
    """``value`` as an array of finite real numbers (floats, integers, or exact
    :class:`fractions.Fraction` objects), all > 0 if ``positive``; else an error naming it."""
    a = np.asarray(value)
    if a.dtype.kind == "O":
        if not all(isinstance(v, Real) and not isinstance(v, bool) for v in a.flat):
            raise TypeError(f"{name} must hold real numbers, got {a.dtype} values")
        finite = all(_finite(v) for v in a.flat)
    elif a.dtype.kind in "fiu":
        finite = bool(np.all(np.isfinite(a)))
    else:
        raise TypeError(f"{name} must be a real number or an array of them, got dtype {a.dtype}")
    if a.size == 0 or not finite or (positive and not all(v > 0 for v in a.flat)):
        raise ValueError(f"{name} must be {'positive and ' if positive else ''}finite, got "
                         f"{a.ravel()[:4].tolist() if a.size else 'an empty array'}")
    return a


def _finite(v) -> bool:
    """Whether the real number ``v`` is finite (an int beyond the float range is not)."""
    try:
        return math.isfinite(v)
    except OverflowError:
        return False


#: How far outside [0, 1] a local coordinate may lie and count as on the element: a rounding's
#: worth, as ``(x - x_i) / h`` gives at a node.
_XI_SLACK = 1e-9


def _local(xi, l):
    """``xi`` and ``l`` checked and as float arrays (shape functions)."""
    xi = _checked("xi", xi, positive=False).astype(float)
    if np.any((xi < -_XI_SLACK) | (xi > 1 + _XI_SLACK)):
        raise ValueError(f"xi must lie in [0, 1] (x / l along the element), got values from "
                         f"{xi.min():g} to {xi.max():g}")
    return xi, _checked("l", l).astype(float)


def _matrix(rows, *scalars) -> np.ndarray:
    """Fill a 4 x 4 table of entries (numbers or arrays) into an array of shape (..., 4, 4).

    The entries broadcast against each other and against ``scalars`` (the factors in front); the
    result is floating point, or of objects for exact :class:`fractions.Fraction` inputs.
    """
    shape = np.broadcast_shapes(*(np.shape(s) for s in scalars))
    out = np.empty(shape + (4, 4), dtype=np.result_type(*scalars, float))
    for i, row in enumerate(rows):
        for j, entry in enumerate(row):
            out[..., i, j] = entry
    return out


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
    EI, l = _checked("EI", EI), _checked("l", l)
    K = _matrix(
        [
            [12, 6 * l, -12, 6 * l],
            [6 * l, 4 * l**2, -6 * l, 2 * l**2],
            [-12, -6 * l, 12, -6 * l],
            [6 * l, 2 * l**2, -6 * l, 4 * l**2],
        ],
        EI,
        l,
    )
    return np.asarray(EI / l**3)[..., None, None] * K


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
    rhoA, l = _checked("rhoA", rhoA), _checked("l", l)
    M = _matrix(
        [
            [156, 22 * l, 54, -13 * l],
            [22 * l, 4 * l**2, 13 * l, -3 * l**2],
            [54, 13 * l, 156, -22 * l],
            [-13 * l, -3 * l**2, -22 * l, 4 * l**2],
        ],
        rhoA,
        l,
    )
    return np.asarray(rhoA * l / 420)[..., None, None] * M


def hermite(xi, l):
    """Hermite cubic shape functions at ``xi = x/l`` in [0, 1] of an element of length ``l`` (m).

    Returns an array of shape ``(..., 4)``:
    deflection = ``hermite(xi, l) @ (v1, theta1, v2, theta2)``.
    """
    xi, l = _local(xi, l)
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
    xi, l = _local(xi, l)
    return np.stack(
        [
            (-6 * xi + 6 * xi**2) / l,
            1 - 4 * xi + 3 * xi**2,
            (6 * xi - 6 * xi**2) / l,
            -2 * xi + 3 * xi**2,
        ],
        axis=-1,
    )
