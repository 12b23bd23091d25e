"""The assembly engine: the element matrices as polynomials in the element length, added by
parity, a whole chain in two NumPy operations.

**The element matrices.** :mod:`~ebantenna.fem.elements` writes ``K_e`` and ``M_e`` out entry by
entry, as the textbook does. Every entry is a constant times a power of ``l`` (``12``, ``6 l``,
``4 l^2``, ...), so each matrix is also a polynomial with constant 4 x 4 coefficient matrices,

    K_e = EI / l^3 (K0 + K1 l + K2 l^2),     M_e = rho A l / 420 (M0 + M1 l + M2 l^2),

three broadcast products instead of sixteen assignments: several times faster on the small arrays
of one mesh (:func:`stiffness_polynomial`, :func:`mass_polynomial`). It is the same arithmetic
entry by entry: each entry of ``K0 + K1 l + K2 l^2`` is one nonzero term plus exact zeros
(``c l + 0 + 0 == c l``), so the matrices equal the written-out ones bit for bit (``tests/fem``
holds them equal).

**Adding them up.** :func:`~ebantenna.fem.assembly.assemble_elements` is the reference: a loop
over the elements and their 16 entries, ``K[dofs[a], dofs[b]] += k_e[a, b]``, one Python step per
entry. That is ``16 n`` steps, slow on a fine mesh and slower still on a stack of meshes (a
contact sweep assembles hundreds at once). NumPy cannot simply do them all in one
``K[rows, cols] += k``: fancy indexing with repeated indices does *not* accumulate (the last write
wins), and neighbouring elements share the four entries of their common node.

The trick: elements ``0, 2, 4, ...`` share no node with each other, nor do ``1, 3, 5, ...``. So each
parity has no repeated indices, and is added with one fancy-indexed ``+=``; two of them assemble
the chain. Every global entry receives at most two contributions (from the two elements meeting at
a node), one from each parity, and a sum of two terms does not depend on its order in floating
point: the result equals the reference loop's **bit for bit** (``tests/fem`` holds them equal).

:func:`scatter_sparse` builds the same matrix in :mod:`scipy.sparse` coordinate format, where
repeated entries *are* summed on conversion (again two terms per entry).

This module imports the reference and adds ``"scatter"`` to
:data:`~ebantenna.fem.assembly.ASSEMBLY_ENGINES` (the package does, when it is imported); the
reference imports nothing from it.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sps

from .assembly import ASSEMBLY_ENGINES

__all__ = ["stiffness_polynomial", "mass_polynomial", "element_dofs", "scatter",
           "scatter_sparse", "assemble_by_parity"]

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


def element_dofs(n_elements: int) -> np.ndarray:
    """Global DOFs of each element, shape (n_elements, 4): element ``e`` holds ``2e .. 2e + 3``."""
    return 2 * np.arange(n_elements)[:, None] + np.arange(4)


def scatter(element_matrices: np.ndarray) -> np.ndarray:
    """Add the 4x4 matrices of a chain of elements into the dense global matrix.

    Works on stacks too: ``(..., n_elements, 4, 4)`` gives ``(..., 2 n + 2, 2 n + 2)``. Elements of
    the same parity share no node, so each parity is added with one fancy-indexed ``+=``.
    """
    ne = element_matrices.shape[-3]
    n = 2 * (ne + 1)
    out = np.zeros(element_matrices.shape[:-3] + (n, n))
    for parity in (0, 1):
        e = np.arange(parity, ne, 2)
        d = element_dofs(ne)[e]
        out[..., d[:, :, None], d[:, None, :]] += element_matrices[..., e, :, :]
    return out


def scatter_sparse(element_matrices: np.ndarray) -> sps.csc_matrix:
    """The same assembly into a :mod:`scipy.sparse` CSC matrix (duplicates summed by scipy)."""
    ne = element_matrices.shape[0]
    dofs = element_dofs(ne)
    rows = np.repeat(dofs, 4, axis=1).reshape(-1)
    cols = np.tile(dofs, (1, 4)).reshape(-1)
    n = 2 * ne + 2
    return sps.coo_matrix((element_matrices.reshape(-1), (rows, cols)), shape=(n, n)).tocsc()


def assemble_by_parity(EI: float, rhoA: float, lengths: np.ndarray, sparse: bool):
    """K and M of elements of ``lengths`` (m) as polynomials, added by :func:`scatter` (or
    :func:`scatter_sparse`): the default engine of :func:`~ebantenna.fem.assembly.assemble`."""
    Ke, Me = stiffness_polynomial(EI, lengths), mass_polynomial(rhoA, lengths)
    if sparse:
        return scatter_sparse(Ke), scatter_sparse(Me)
    return scatter(Ke), scatter(Me)


ASSEMBLY_ENGINES["scatter"] = assemble_by_parity
