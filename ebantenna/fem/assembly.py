"""Mesh of the probe and assembly of the global stiffness and mass matrices.

The global DOF vector is ``(v0, theta0, v1, theta1, ..., vN, thetaN)`` for nodes 0 (hinge) to N
(tip). :class:`Supports` say how the probe is held: the hinge at x = 0, the touched object at
the contact, the free tip. They are applied by removing the DOFs they fix (a clamped hinge
removes ``v0`` and ``theta0``, a rigid contact removes ``v`` at the contact node) and by adding
spring stiffnesses and the tip mass to the diagonal.

The assembly itself is the *direct stiffness method*: every element adds its 4 x 4 matrix into the
rows and columns of its four DOFs, ``(v_e, theta_e, v_{e+1}, theta_{e+1})``, so that two
neighbouring elements overlap on the 2 x 2 block of their common node.
:func:`assemble_elements` is that loop, word for word, on the element matrices as
:mod:`~ebantenna.fem.elements` writes them out; :func:`assemble` runs a faster engine by default
that gives the same matrices bit for bit (``ebantenna.fem._assembly_engine`` explains how). This
module imports nothing of the engine: the engine imports it and adds itself to
:data:`ASSEMBLY_ENGINES` when the package is imported.

The guards that come before a mesh (round-off, memory, a contact the mesh can hold) are in
:mod:`~ebantenna.fem.guards`; the functions here take checked values.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sps

from .._validate import check_choice, check_int, check_positive
from ..probe import Probe
from .elements import consistent_mass, element_stiffness
from .guards import check_contact, check_resolvable

__all__ = [
    "Supports",
    "HINGES",
    "beam_mesh",
    "contact_node",
    "assemble_elements",
    "assemble",
    "ASSEMBLY_ENGINES",
    "apply_supports",
    "free_dofs",
]


def beam_mesh(length: float, contact: float | None, n_elements: int) -> np.ndarray:
    """Node positions from hinge (0) to tip (``length``), m, with a node exactly at ``contact``.

    The elements are shared between the two spans in proportion to their lengths (at least one each)
    and are uniform within a span. ``n_elements=2`` with a contact gives the paper's model; more
    than :data:`~ebantenna.fem.guards.MAX_ELEMENTS` are refused (round-off, see
    :func:`~ebantenna.fem.guards.roundoff_error`).

    ``contact`` is taken as checked: the public entry points (for example
    :func:`~ebantenna.fem.modal.modal_analysis`) pass it through
    :func:`~ebantenna.fem.guards.check_contact` first, which keeps it
    :data:`~ebantenna.fem.guards.MIN_SPAN` from either end.

    Examples
    --------
    >>> from ebantenna.fem.assembly import beam_mesh
    >>> beam_mesh(0.4, 0.1, 4)
    array([0. , 0.1, 0.2, 0.3, 0.4])
    >>> beam_mesh(0.4, 0.3, 2)
    array([0. , 0.3, 0.4])
    """
    n_elements = check_resolvable(n_elements)
    length = check_positive("length", length)
    if contact is None:
        return np.linspace(0.0, length, n_elements + 1)
    contact = check_contact("contact", contact, length)
    n_elements = check_int("n_elements", n_elements, minimum=2)
    n1 = min(max(1, round(n_elements * contact / length)), n_elements - 1)
    span = np.linspace(0.0, contact, n1 + 1)
    overhang = np.linspace(contact, length, n_elements - n1 + 1)
    return np.concatenate([span, overhang[1:]])


def contact_node(nodes: np.ndarray, contact: float | None) -> int | None:
    """Index of the node at the contact (None without contact)."""
    if contact is None:
        return None
    nodes = np.asarray(nodes, dtype=float)
    if nodes.ndim != 1 or nodes.size < 2:
        raise ValueError(f"nodes must be a 1-D mesh of 2 nodes at least, got shape {nodes.shape}")
    contact = check_contact("contact", contact, nodes[-1])
    return int(np.argmin(np.abs(nodes - contact)))


def assemble_elements(element_matrices: np.ndarray) -> np.ndarray:
    """Assemble the 4x4 matrices of a chain of elements: the direct stiffness method, as a loop.

    Element ``e`` joins nodes ``e`` and ``e + 1``; its local DOFs ``(v1, theta1, v2, theta2)`` are
    the global DOFs ``2e, 2e + 1, 2e + 2, 2e + 3``, that is ``(v_e, theta_e, v_{e+1},
    theta_{e+1})`` (the local 1 and 2 are the element's two ends, not nodes 1 and 2). Each of
    its 16 entries is added where its row and column DOFs meet.

    Parameters
    ----------
    element_matrices : array of shape (n_elements, 4, 4)

    Returns
    -------
    ndarray of shape (2 n_elements + 2, 2 n_elements + 2)

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.fem.assembly import assemble_elements
    >>> assemble_elements(np.ones((2, 4, 4)))   # node 1 is shared: its block adds up twice
    array([[1., 1., 1., 1., 0., 0.],
           [1., 1., 1., 1., 0., 0.],
           [1., 1., 2., 2., 1., 1.],
           [1., 1., 2., 2., 1., 1.],
           [0., 0., 1., 1., 1., 1.],
           [0., 0., 1., 1., 1., 1.]])
    """
    if np.ndim(element_matrices) != 3 or np.shape(element_matrices)[1:] != (4, 4):
        raise ValueError(f"element_matrices must have shape (n_elements, 4, 4), got "
                         f"{np.shape(element_matrices)}")
    n_elements = element_matrices.shape[0]
    n_dofs = 2 * n_elements + 2
    A = np.zeros((n_dofs, n_dofs))
    for e in range(n_elements):
        dofs = (2 * e, 2 * e + 1, 2 * e + 2, 2 * e + 3)  # v_e, theta_e, v_e+1, theta_e+1
        for a in range(4):
            for b in range(4):
                A[dofs[a], dofs[b]] += element_matrices[e, a, b]
    return A


def _with_loop(EI: float, rhoA: float, lengths: np.ndarray, sparse: bool):
    """K and M of elements of ``lengths`` (m), written out by :mod:`~ebantenna.fem.elements` and
    added by :func:`assemble_elements`: the reference of :func:`assemble` (dense: ``sparse`` is
    False, as ``assemble`` checks)."""
    Ke, Me = element_stiffness(EI, lengths), consistent_mass(rhoA, lengths)
    return assemble_elements(Ke), assemble_elements(Me)


#: The engines of :func:`assemble` by name, each ``(EI, rhoA, lengths, sparse) -> (K, M)``:
#: ``"loop"``, the reference (:func:`assemble_elements` on the written-out element matrices),
#: and ``"scatter"``, the default, which the private module ``fem/_assembly_engine.py`` adds
#: when the package is imported.
ASSEMBLY_ENGINES = {"loop": _with_loop}


def assemble(nodes: np.ndarray, probe: Probe, *, sparse: bool = False, engine: str = "scatter"):
    """Global stiffness K (N/m...) and consistent mass M (kg...) of the bare beam, no supports.

    Parameters
    ----------
    nodes : array of shape (n_nodes,)
        Node positions, m, increasing.
    probe : Probe
        Beam properties (``EI``, ``rho A``); the tip mass is added by :func:`apply_supports`.
    sparse : bool
        Return ``scipy.sparse`` CSC matrices instead of dense arrays.
    engine : {"scatter", "loop"}
        ``"loop"``: the reference, the element matrices written out
        (:func:`~ebantenna.fem.elements.element_stiffness`,
        :func:`~ebantenna.fem.elements.consistent_mass`) and added by :func:`assemble_elements`
        into dense matrices (with ``sparse=True`` a ``ValueError``: the loop is for reading, not
        for meshes too large to hold densely).
        ``"scatter"`` (default): the engines, the same matrices as polynomials in the element
        length added one parity of elements at a time, or into sparse matrices
        (``ebantenna.fem._assembly_engine``); the same result bit for bit.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna import Probe
    >>> from ebantenna.fem.assembly import assemble, beam_mesh
    >>> nodes = beam_mesh(0.4, 0.2, 8)
    >>> K, M = assemble(nodes, Probe())
    >>> K.shape
    (18, 18)
    >>> bool(np.array_equal(K, assemble(nodes, Probe(), engine="loop")[0]))
    True
    """
    check_choice("engine", engine, ASSEMBLY_ENGINES)
    if engine == "loop" and sparse:
        raise ValueError("engine='loop' builds dense matrices; use sparse=False with it, or "
                         "engine='scatter' for sparse ones")
    if not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
    nodes = _nodes(nodes)
    return ASSEMBLY_ENGINES[engine](probe.flexural_rigidity, probe.mass_per_length,
                                    np.diff(nodes), sparse)


#: Named hinge conditions; a positive number instead means a rotational spring (N m/rad).
HINGES = ("clamped", "pinned")


@dataclass(frozen=True)
class Supports:
    """How the probe is held and touched.

    Parameters
    ----------
    contact : float or None
        Distance of the contact point from the hinge, m, inside ``(0, L)``; ``None`` for a probe
        that touches nothing.
    hinge : {"clamped", "pinned"} or float
        The hinge at x = 0 (the servo shaft): clamped (no deflection, no rotation), pinned (no
        deflection, free rotation) or, as a positive number, a rotational spring in N m/rad.
    contact_stiffness : float
        Translational stiffness of the contact, N/m; ``math.inf`` (default) is a rigid pin.

    Examples
    --------
    >>> from ebantenna.fem import Supports
    >>> Supports(contact=0.2).hinge
    'clamped'
    >>> Supports(contact=0.2, hinge=50.0).hinge_stiffness
    50.0
    """

    contact: float | None = None
    hinge: str | float = "clamped"
    contact_stiffness: float = math.inf

    def __post_init__(self):
        if self.contact is not None:
            check_positive("contact", self.contact)
        if isinstance(self.hinge, str):
            check_choice("hinge", self.hinge, HINGES)
        else:
            object.__setattr__(
                self, "hinge", check_positive("hinge (rotational stiffness)", self.hinge)
            )
        object.__setattr__(
            self,
            "contact_stiffness",
            check_positive("contact_stiffness", self.contact_stiffness, allow_inf=True),
        )

    @property
    def hinge_stiffness(self) -> float:
        """Rotational stiffness of the hinge, N m/rad: inf if clamped, 0 if pinned."""
        if self.hinge == "clamped":
            return math.inf
        if self.hinge == "pinned":
            return 0.0
        return float(self.hinge)

    @property
    def rigid_contact(self) -> bool:
        """True when the contact is a rigid pin (and there is a contact)."""
        return self.contact is not None and math.isinf(self.contact_stiffness)

    def describe(self) -> str:
        """The hinge as the CLI's JSON reports it."""
        return self.hinge if isinstance(self.hinge, str) else f"spring {self.hinge:g} N m/rad"


def free_dofs(nodes: np.ndarray, supports: Supports) -> np.ndarray:
    """Indices of the DOFs left free by the supports, increasing."""
    if not isinstance(supports, Supports):
        raise TypeError(f"supports must be a Supports, got {type(supports).__name__}")
    nodes = _nodes(nodes)
    fixed = [0]  # the hinge never moves sideways
    if supports.hinge == "clamped":
        fixed.append(1)
    if supports.rigid_contact:
        fixed.append(2 * contact_node(nodes, supports.contact))
    return np.setdiff1d(np.arange(2 * nodes.size), fixed)


def _nodes(nodes) -> np.ndarray:
    """``nodes`` if they are a mesh: 1-D, 2 or more, finite and increasing (m)."""
    from .._validate import check_array

    nodes = check_array("nodes", nodes, ndim=1, min_length=2)
    if np.any(np.diff(nodes) <= 0):
        raise ValueError("nodes must increase from the hinge to the tip")
    return nodes


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
    for name, matrix in (("K", K), ("M", M)):
        if np.shape(matrix) != (2 * np.size(nodes),) * 2:
            raise ValueError(f"{name} must be the {2 * np.size(nodes)} x {2 * np.size(nodes)} "
                             f"matrix of these nodes, got shape {np.shape(matrix)}")
    if not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
    k_diag, m_diag = support_diagonals(nodes, probe, supports)
    if sps.issparse(K):
        K = (K + sps.diags(k_diag)).tocsc()[free][:, free]
        M = (M + sps.diags(m_diag)).tocsc()[free][:, free]
    else:
        K = (K + np.diag(k_diag))[np.ix_(free, free)]
        M = (M + np.diag(m_diag))[np.ix_(free, free)]
    return K, M, free
