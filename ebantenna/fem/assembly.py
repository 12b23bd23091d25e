"""Mesh of the probe and assembly of the global stiffness and mass matrices.

The global DOF vector is ``(v0, theta0, v1, theta1, ..., vN, thetaN)`` for nodes 0 (hinge) to N
(tip). Supports are applied by removing the DOFs they fix (a clamped hinge removes ``v0`` and
``theta0``, a rigid contact removes ``v`` at the contact node) and by adding spring stiffnesses and
the tip mass to the diagonal.

Round-off sets a limit to refinement. The assembled ``K`` is a discrete fourth derivative: its
entries grow like ``EI / h^3`` while ``K phi`` for the probe's low modes stays of the order of
``EI phi / L^4``, so its condition number grows like ``(L/h)^4 = N^4``. Every solve with it
(Cholesky, LU, shift-invert Lanczos) returns mode shapes carrying rounding noise of relative size
about ``eps N^4`` at the mesh's own wavelength, and that noise, stiff as it is, raises the
frequencies. Even refined by the curvature Rayleigh quotient (:mod:`~ebantenna.fem.modal`), the
lowest frequency is then off by about ``(c eps N^4)^2``, with ``c`` between 1e-4 and 0.02 for
the probe's hinges and contacts (measured against :mod:`~ebantenna.fem.exact` at 4096 and 8192
elements). :func:`roundoff_error` is that estimate with ``c = 0.05``, an upper bound, and
:data:`MAX_ELEMENTS` the finest mesh whose estimate stays within :data:`ROUNDOFF_RTOL`:
:func:`beam_mesh` refuses finer ones, where more elements buy no accuracy, only noise.
"""

from __future__ import annotations

import math
import os

import numpy as np
import scipy.sparse as sps

from .._validate import check_in_range, check_int
from ..probe import Probe
from .elements import consistent_mass, element_stiffness
from .supports import Supports

__all__ = [
    "beam_mesh",
    "roundoff_error",
    "check_resolvable",
    "check_memory",
    "ROUNDOFF_RTOL",
    "MAX_ELEMENTS",
    "MIN_SPAN",
    "check_contact",
    "assemble",
    "scatter",
    "support_diagonals",
    "apply_supports",
    "free_dofs",
    "contact_node",
]


#: Relative accuracy of the lowest frequency that a mesh must be able to hold in double precision.
ROUNDOFF_RTOL = 1e-6

#: The upper-bound constant ``c`` of :func:`roundoff_error` (measured: 1e-4 ... 0.02).
_ROUNDOFF_C = 0.05


def roundoff_error(n_elements: int) -> float:
    """A-priori estimate of the round-off error of the lowest frequency on ``n_elements``, relative.

    ``(c eps N^4)^2`` with ``c = 0.05`` (see the module's introduction): the condition number
    ``N^4`` of the assembled stiffness, times the machine epsilon, squared by the Rayleigh
    quotient. The discretisation error falls like ``N^-4``; the two cross at a few hundred
    elements below 1e-12, so a finer mesh than that buys nothing.

    Examples
    --------
    >>> from ebantenna.fem.assembly import roundoff_error
    >>> f"{roundoff_error(2048):.0e}", f"{roundoff_error(16384):.0e}"
    ('4e-08', '6e-01')
    """
    n_elements = check_int("n_elements", n_elements, minimum=1)
    return (_ROUNDOFF_C * np.finfo(float).eps * float(n_elements) ** 4) ** 2


#: The finest mesh whose :func:`roundoff_error` stays within :data:`ROUNDOFF_RTOL`.
MAX_ELEMENTS = int((math.sqrt(ROUNDOFF_RTOL) / (_ROUNDOFF_C * np.finfo(float).eps)) ** 0.25)


def check_resolvable(n_elements: int) -> int:
    """Return ``n_elements``; raise ``ValueError`` above :data:`MAX_ELEMENTS` (round-off limit)."""
    n_elements = check_int("n_elements", n_elements, minimum=1)
    if n_elements > MAX_ELEMENTS:
        raise ValueError(
            f"n_elements must be <= {MAX_ELEMENTS}, got {n_elements}: the stiffness matrix's "
            f"condition number grows like N^4 (here {float(n_elements) ** 4:.0e}), and in double "
            f"precision the lowest frequency would be off by about {roundoff_error(n_elements):.0e}"
            f" (relative), beyond {ROUNDOFF_RTOL:g}; at {MAX_ELEMENTS} elements the discretisation "
            "error is already far below that"
        )
    return n_elements


def check_memory(nbytes: float, what: str) -> None:
    """Raise ``ValueError`` before ``what`` allocates more than half of the machine's memory.

    ``nbytes`` is the caller's a-priori estimate. Without a way to ask the machine (no
    ``os.sysconf``), nothing is checked.
    """
    try:
        total = os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (AttributeError, ValueError, OSError):
        return
    if nbytes > total / 2:
        raise ValueError(
            f"{what} needs about {nbytes / 1e9:.3g} GB, more than half of this machine's "
            f"{total / 1e9:.3g} GB of memory"
        )


#: The shortest span, as a fraction of the probe's length, between the contact and the hinge or
#: the tip. The element there has a stiffness growing like ``h^-3``: measured against
#: :mod:`~ebantenna.fem.exact` on 64 elements, a span of 2.5e-8 L still gives every frequency to
#: 1e-8, while 2.5e-10 L with a soft contact at the tip makes the Cholesky factor break down
#: (NaN) and 2.5e-12 L loses three digits; 1e-6 L keeps a margin of 25 below the last good one.
#: A contact that close (0.4 µm on the paper's probe) is at the end for every purpose.
MIN_SPAN = 1e-6


def check_contact(name: str, contact, length: float) -> float:
    """Return ``contact``; raise unless it lies in the probe, :data:`MIN_SPAN` from either end.

    Examples
    --------
    >>> from ebantenna.fem.assembly import check_contact
    >>> check_contact("contact", 0.2, 0.4)
    0.2
    >>> check_contact("contact", 1e-9, 0.4)
    Traceback (most recent call last):
    ...
    ValueError: contact must lie in [4e-07, 0.3999996] m (1e-06 of the length ...), got 1e-09
    """
    contact = check_in_range(name, contact, 0.0, length)
    low, high = MIN_SPAN * length, (1.0 - MIN_SPAN) * length
    if not low <= contact <= high:
        raise ValueError(
            f"{name} must lie in [{low:.7g}, {high:.7g}] m ({MIN_SPAN:g} of the length or more "
            f"from the hinge and from the tip), got {contact!r}"
        )
    return contact


def beam_mesh(length: float, contact: float | None, n_elements: int) -> np.ndarray:
    """Node positions from hinge (0) to tip (``length``), m, with a node exactly at ``contact``.

    The elements are shared between the two spans in proportion to their lengths (at least one each)
    and are uniform within a span. ``n_elements=2`` with a contact gives the paper's model; more
    than :data:`MAX_ELEMENTS` are refused (round-off, see :func:`roundoff_error`).

    Examples
    --------
    >>> from ebantenna.fem.assembly import beam_mesh
    >>> beam_mesh(0.4, 0.1, 4)
    array([0. , 0.1, 0.2, 0.3, 0.4])
    >>> beam_mesh(0.4, 0.3, 2)
    array([0. , 0.3, 0.4])
    """
    n_elements = check_resolvable(n_elements)
    if contact is None:
        return np.linspace(0.0, length, n_elements + 1)
    n_elements = check_int("n_elements", n_elements, minimum=2)
    contact = check_contact("contact", contact, length)
    n1 = min(max(1, round(n_elements * contact / length)), n_elements - 1)
    span = np.linspace(0.0, contact, n1 + 1)
    overhang = np.linspace(contact, length, n_elements - n1 + 1)
    return np.concatenate([span, overhang[1:]])


def contact_node(nodes: np.ndarray, contact: float | None) -> int | None:
    """Index of the node at the contact (None without contact)."""
    if contact is None:
        return None
    return int(np.argmin(np.abs(nodes - contact)))


def _element_dofs(n_elements: int) -> np.ndarray:
    return 2 * np.arange(n_elements)[:, None] + np.arange(4)


def scatter(element_matrices: np.ndarray) -> np.ndarray:
    """Add the 4x4 matrices of a chain of elements into the dense global matrix.

    Works on stacks too: ``(..., n_elements, 4, 4)`` gives ``(..., 2 n + 2, 2 n + 2)``. Elements of
    the same parity share no node, so each parity is added with one fancy-indexed ``+=`` (fancy
    indexing does not accumulate repeated indices, and here there are none).
    """
    ne = element_matrices.shape[-3]
    n = 2 * (ne + 1)
    out = np.zeros(element_matrices.shape[:-3] + (n, n))
    for parity in (0, 1):
        e = np.arange(parity, ne, 2)
        d = _element_dofs(ne)[e]
        out[..., d[:, :, None], d[:, None, :]] += element_matrices[..., e, :, :]
    return out


def assemble(nodes: np.ndarray, probe: Probe, *, sparse: bool = False):
    """Global stiffness K (N/m...) and consistent mass M (kg...) of the bare beam, no supports.

    Parameters
    ----------
    nodes : array of shape (n_nodes,)
        Node positions, m, increasing.
    probe : Probe
        Beam properties (``EI``, ``rho A``); the tip mass is added by :func:`apply_supports`.
    sparse : bool
        Return ``scipy.sparse`` CSC matrices instead of dense arrays.
    """
    lengths = np.diff(nodes)
    Ke = element_stiffness(probe.flexural_rigidity, lengths)
    Me = consistent_mass(probe.mass_per_length, lengths)
    if not sparse:
        return scatter(Ke), scatter(Me)
    Ke, Me = Ke.reshape(-1), Me.reshape(-1)
    dofs = _element_dofs(lengths.size)
    rows = np.repeat(dofs, 4, axis=1).reshape(-1)
    cols = np.tile(dofs, (1, 4)).reshape(-1)
    n = 2 * nodes.size
    K = sps.coo_matrix((Ke, (rows, cols)), shape=(n, n))
    M = sps.coo_matrix((Me, (rows, cols)), shape=(n, n))
    return K.tocsc(), M.tocsc()


def free_dofs(nodes: np.ndarray, supports: Supports) -> np.ndarray:
    """Indices of the DOFs left free by the supports, increasing."""
    fixed = [0]  # the hinge never moves sideways
    if supports.hinge == "clamped":
        fixed.append(1)
    if supports.rigid_contact:
        fixed.append(2 * contact_node(nodes, supports.contact))
    return np.setdiff1d(np.arange(2 * nodes.size), fixed)


def support_diagonals(nodes: np.ndarray, probe: Probe, supports: Supports):
    """What the supports and the tip mass add to the diagonals of K and M (full DOF vectors).

    A rotational hinge spring adds to ``K[theta0, theta0]``, a compliant contact to ``K[v_c, v_c]``,
    the tip mass to ``M[v_tip, v_tip]``.
    """
    n = 2 * nodes.size
    k_diag = np.zeros(n)
    m_diag = np.zeros(n)
    if not isinstance(supports.hinge, str):
        k_diag[1] += supports.hinge_stiffness
    if supports.contact is not None and not math.isinf(supports.contact_stiffness):
        k_diag[2 * contact_node(nodes, supports.contact)] += supports.contact_stiffness
    m_diag[-2] += probe.tip_mass
    return k_diag, m_diag


def apply_supports(K, M, nodes: np.ndarray, probe: Probe, supports: Supports):
    """Add springs and the tip mass, then keep the free DOFs.

    Returns
    -------
    K_free, M_free : matrices (dense or sparse, as given)
        Restricted to the free DOFs.
    free : ndarray of int
        Their indices in the global DOF vector.
    """
    free = free_dofs(nodes, supports)
    k_diag, m_diag = support_diagonals(nodes, probe, supports)
    if sps.issparse(K):
        K = (K + sps.diags(k_diag)).tocsc()[free][:, free]
        M = (M + sps.diags(m_diag)).tocsc()[free][:, free]
    else:
        K = (K + np.diag(k_diag))[np.ix_(free, free)]
        M = (M + np.diag(m_diag))[np.ix_(free, free)]
    return K, M, free
