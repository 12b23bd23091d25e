"""Modal analysis of the probe: the generalized eigenproblem ``K phi = omega^2 M phi``.

Why not simply ``scipy.linalg.eigh(K, M)``? That routine reduces the problem to
``L^-1 K L^-T`` with ``M = L L^T`` and finds all eigenvalues to an *absolute* accuracy of about
``eps * omega_max^2``. On a fine mesh ``omega_max^2`` grows like ``(N/L)^4`` while the probe's
first ``omega^2`` stays put, so the low modes, the only ones that matter, lose their digits
(the bound on the first frequency's relative error, ``eps omega_max^2 / (2 omega_1^2)``, is 30 %
at 2048 elements with the contact at 0.2 L; how much a run loses depends on the BLAS kernel).
Here the problem is inverted instead, as in shift-invert Lanczos: with a small shift ``s > 0``
and ``K + s M = L L^T``,

    L^-1 M L^-T y = mu y,     omega^2 = 1/mu - s,     phi = L^-T y / sqrt(mu),

and the *largest* ``mu`` belong to the lowest modes, so they come out with full relative
accuracy. The shift keeps ``K + s M`` positive definite even for a free (unsupported) probe,
whose rigid-body mode then has ``omega = 0`` instead of a NaN. (Rounding moves a zero eigenvalue
by up to about ``eps * omega_max^2`` either way; one below zero by more than the solve can round
means ``K`` was not semi-definite, and is refused.) Small meshes are solved densely, large ones
with sparse shift-invert Lanczos (:func:`scipy.sparse.linalg.eigsh`), the same idea.

That is still not enough on very fine meshes: the assembled ``K`` itself is only known to
rounding, and ``K phi`` for a smooth mode is a fourth difference that cancels to a relative
``eps / (beta h)^4`` (about 1.6e-4 at 2048 elements with the contact at 0.2 L, where
``beta h = 1.1e-3``). So the eigenvalues are finally refined by the Rayleigh quotient
``omega^2 = U(phi) / T(phi)`` with the strain energy summed from the element *curvatures* (a
second difference, ``eps / (beta h)^2``, about 2e-10) instead of ``phi^T K phi``.
A Rayleigh quotient is stationary at an eigenvector, so the eigenvector's own error enters squared.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sps
import scipy.sparse.linalg as spla

from .._validate import (
    check_array,
    check_bool,
    check_choice,
    check_int,
    check_positive,
    real_array,
)
from ..probe import Probe
from ._rounding import floored as _floored
from ._rounding import rounding as _rounding
from .assembly import (
    ASSEMBLY_ENGINES,
    Supports,
    apply_supports,
    assemble,
    beam_mesh,
    contact_node,
    free_dofs,
    support_diagonals,
)
from .elements import consistent_mass, hermite, hermite_slope
from .guards import check_contact, check_memory

__all__ = [
    "ModalResult",
    "modal_analysis",
    "solve_modes",
    "eigenvalue_shift",
    "clip_eigenvalues",
    "EIGEN_SOLVERS",
    "DENSE_LIMIT",
    "strain_energy",
    "bending_energy",
]

#: Eigen-solvers of :func:`solve_modes`: the inverted dense solve, sparse shift-invert Lanczos,
#: and the textbook ``scipy.linalg.eigh(K, M)`` kept to show what it loses.
EIGEN_SOLVERS = ("auto", "dense", "sparse", "naive")

#: Above this many free DOFs (the size of ``K`` once the supports are applied), ``solver="auto"``
#: goes sparse, in :func:`solve_modes` and :func:`modal_analysis` alike (where shift-invert Lanczos
#: on the banded matrices overtakes the dense solve: about 100 elements, see
#: benchmarks/fem_accuracy.py).
DENSE_LIMIT = 200


def eigenvalue_shift(beam: Probe) -> float:
    """A positive shift ``s = EI / (rho A L^4)`` of the scale of a beam's own ``omega^2``, 1/s^2.

    Examples
    --------
    >>> from ebantenna import Probe
    >>> from ebantenna.fem.modal import eigenvalue_shift
    >>> p = Probe()
    >>> eigenvalue_shift(p) == p.flexural_rigidity / (p.mass_per_length * p.length**4)
    True
    """
    if not isinstance(beam, Probe):
        raise TypeError(f"beam must be a Probe (or Rod.as_beam()), got {type(beam).__name__}")
    return beam.flexural_rigidity / (beam.mass_per_length * beam.length**4)


def clip_eigenvalues(lam: np.ndarray, shift: float) -> np.ndarray:
    """Eigenvalues ``omega^2`` (1/s^2) floored at zero; raise below ``-1e-8 shift``.

    A guard for eigenvalues that cannot come out negative but by far less than ``1e-8 shift``:
    Rayleigh quotients of strain energies (never negative) and the secular equation's roots
    (above the eigenvalues without the contact, themselves such quotients). An inverted solve
    rounds a zero eigenvalue by up to about ``eps * omega_max^2`` instead, far more on a fine
    mesh; :func:`solve_modes` holds its eigenvalues to a bound from its own ``K`` and ``M``.
    """
    lam = real_array("lam", lam)
    return _floored(lam, 1e-8 * check_positive("shift", shift))


def solve_modes(K, M, n_modes: int, *, shift: float, solver: str = "auto"):
    """Lowest ``n_modes`` eigenpairs of ``K phi = lam M phi`` (``K`` semi-definite, ``M`` definite).

    Parameters
    ----------
    K, M : dense arrays or sparse matrices of shape (n, n)
        Stiffness and mass restricted to the free DOFs.
    n_modes : int
        How many of the lowest modes.
    shift : float
        Positive shift ``s`` (1/s^2), of the order of the lowest eigenvalue.
    solver : {"auto", "dense", "sparse", "naive"}
        See :data:`EIGEN_SOLVERS`.

    Returns
    -------
    lam : ndarray of shape (n_modes,)
        Eigenvalues ``omega^2``, 1/s^2, ascending, never negative.
    phi : ndarray of shape (n, n_modes)
        Mass-normalised eigenvectors (``phi.T @ M @ phi = I``).
    """
    check_choice("solver", solver, EIGEN_SOLVERS)
    shift = check_positive("shift", shift)
    if len(np.shape(K)) != 2 or np.shape(K)[0] != np.shape(K)[1] or np.shape(M) != np.shape(K):
        raise ValueError(f"K and M must be square matrices of one shape, got {np.shape(K)} and "
                         f"{np.shape(M)}")
    n = K.shape[0]
    n_modes = check_int("n_modes", n_modes, minimum=1, maximum=n)
    if solver == "auto":
        solver = "dense" if n <= DENSE_LIMIT else "sparse"
    if solver == "sparse" and n_modes >= n - 1:
        solver = "dense"  # ARPACK needs k < n - 1
    if solver in ("dense", "naive"):
        K = K.toarray() if hasattr(K, "toarray") else np.asarray(K)
        M = M.toarray() if hasattr(M, "toarray") else np.asarray(M)
    if solver == "naive":
        lam, phi = sla.eigh(K, M, subset_by_index=[0, n_modes - 1])
        return np.maximum(lam, 0.0), phi
    if solver == "dense":
        return _inverted_dense(K, M, n_modes, shift)
    # Sparse shift-invert Lanczos about -shift; a fixed start vector makes it deterministic.
    lam, phi = spla.eigsh(
        K.tocsc(), k=n_modes, M=M.tocsc(), sigma=-shift, which="LM", v0=np.ones(n), tol=0
    )
    order = np.argsort(lam)
    lam, phi = lam[order], phi[:, order]
    phi = phi / np.sqrt(np.einsum("ik,ik->k", phi, M @ phi))
    return _floored(lam, _rounding(K + shift * M, shift, lam, phi)), phi


def _inverted_dense(K: np.ndarray, M: np.ndarray, n_modes: int, shift: float):
    """The dense inverted solve of :func:`solve_modes`: ``(lam, phi)`` of the lowest modes."""
    n = K.shape[0]
    A = K + shift * M
    L = sla.cholesky(A, lower=True)
    X = sla.solve_triangular(L, M, lower=True)
    B = sla.solve_triangular(L, X.T, lower=True)
    mu, Y = sla.eigh((B + B.T) / 2, subset_by_index=[n - n_modes, n - 1])
    mu, Y = mu[::-1], Y[:, ::-1]
    # mu = 1 / (omega^2 + shift) is resolved only down to the rounding of the largest one,
    # n eps mu_max: below it (a mode stiffer than the arithmetic can see, e.g. a nearly rigid
    # substructure) it may even come out negative. Such modes are floored there: finite,
    # normalised, with omega^2 at least 1 / (n eps mu_max).
    mu = np.maximum(mu, n * np.finfo(float).eps * mu[0])
    phi = sla.solve_triangular(L, Y, lower=True, trans="T") / np.sqrt(mu)
    lam = 1.0 / mu - shift
    return _floored(lam, _rounding(A, shift, lam, phi)), phi


@dataclass(frozen=True, eq=False)
class ModalResult:
    """Natural frequencies and mass-normalised mode shapes of a supported probe.

    Attributes
    ----------
    probe : Probe
    supports : Supports
    nodes : ndarray of shape (n_nodes,)
        Node positions, m (a node sits at the contact).
    omega : ndarray of shape (n_modes,)
        Natural circular frequencies, rad/s, ascending.
    shapes : ndarray of shape (2 * n_nodes, n_modes)
        Mode shapes as full DOF vectors ``(v0, theta0, v1, ...)`` (m, rad per unit modal
        coordinate), zero at the fixed DOFs, normalised so that ``phi.T @ M @ phi = I``.
    free : ndarray of int
        Indices of the free DOFs.
    mass_matrix : ndarray or scipy.sparse matrix of shape (2 * n_nodes, 2 * n_nodes)
        Global consistent mass with the tip mass (kg, kg m, kg m^2), before removing fixed DOFs;
        sparse when the mesh was solved with the sparse solver.
    """

    probe: Probe
    supports: Supports
    nodes: np.ndarray
    omega: np.ndarray
    shapes: np.ndarray
    free: np.ndarray
    mass_matrix: object

    @property
    def frequencies(self) -> np.ndarray:
        """Natural frequencies, Hz."""
        return self.omega / (2 * math.pi)

    @property
    def n_modes(self) -> int:
        """Number of modes computed."""
        return int(self.omega.size)

    def _locate(self, x):
        x = check_array("x", x, ndim=(0, 1))
        if np.any((x < 0) | (x > self.probe.length)):
            raise ValueError(f"x must lie in [0, {self.probe.length:g}] m")
        element = np.clip(np.searchsorted(self.nodes, x, side="right") - 1, 0, self.nodes.size - 2)
        le = self.nodes[element + 1] - self.nodes[element]
        xi = (x - self.nodes[element]) / le
        dofs = 2 * element[..., None] + np.arange(4)
        return xi, le, self.shapes[dofs]  # shapes[dofs]: (..., 4, n_modes)

    def displacement(self, x) -> np.ndarray:
        """Deflection of every mode at positions ``x`` (m) by the Hermite shape functions.

        Returns an array of shape ``x.shape + (n_modes,)``, m per unit modal coordinate.
        """
        xi, le, local = self._locate(x)
        return np.einsum("...a,...am->...m", hermite(xi, le), local)

    def slope(self, x) -> np.ndarray:
        """Slope ``dv/dx`` of every mode at positions ``x`` (m), shape ``x.shape + (n_modes,)``."""
        xi, le, local = self._locate(x)
        return np.einsum("...a,...am->...m", hermite_slope(xi, le), local)

    def modal_coordinates(self, u) -> np.ndarray:
        """Modal coordinates ``q = Phi^T M u`` of a full DOF vector ``u`` (fixed DOFs ignored).

        For an initial velocity field this gives the initial modal velocities; the fixed DOFs are
        ignored because the supports take their motion away (an impulsive reaction).
        """
        u = check_array("u", u, ndim=(1, 2))
        if u.shape[0] != self.shapes.shape[0]:
            raise ValueError(f"u must have {self.shapes.shape[0]} rows (2 per node), got {u.shape}")
        masked = np.zeros_like(u)
        masked[self.free] = u[self.free]
        return self.shapes.T @ (self.mass_matrix @ masked)

    def overhang_mass_fraction(self) -> np.ndarray:
        """Share of each mode's kinetic energy in the overhang, from the contact to the tip.

        Close to 1 for a mode in which the overhang swings like a cantilever on the contact, close
        to 0 for one in which the span between hinge and contact vibrates (Fig. 17 of the paper).
        The energy is summed over the overhang's own elements and the tip mass: the global mass
        matrix's entries at the contact node also hold the span's last element.
        """
        if self.supports.contact is None:
            raise ValueError("overhang_mass_fraction needs a contact (supports.contact is None)")
        c = contact_node(self.nodes, self.supports.contact)
        overhang = np.arange(c, self.nodes.size - 1)  # the elements from the contact to the tip
        mass = consistent_mass(self.probe.mass_per_length, np.diff(self.nodes)[overhang])
        local = self.shapes[2 * overhang[:, None] + np.arange(4)]  # (elements, 4, n_modes)
        energy = np.einsum("eam,eab,ebm->m", local, mass, local)
        return energy + self.probe.tip_mass * self.shapes[-2] ** 2  # phi^T M phi = 1 in all

    @property
    def dominant_mode(self) -> int:
        """Index of the paper's "dominant (most flexible) mode": the lowest-frequency one, 0."""
        return 0

    def plot(self, ax=None, modes=None, n_points: int = 400, label: str = "mode"):
        """Draw mode shapes with the Hermite shape functions between nodes.

        See :func:`ebantenna.fem.plot.plot_modes`; returns the matplotlib Axes.
        """
        from .plot import plot_modes

        return plot_modes(self, ax=ax, modes=modes, n_points=n_points, label=label)


def modal_analysis(
    probe: Probe,
    supports: Supports,
    *,
    n_elements: int = 64,
    n_modes: int = 3,
    solver: str = "auto",
    assembly: str = "scatter",
) -> ModalResult:
    """Natural frequencies and mode shapes of the probe on its supports.

    Parameters
    ----------
    probe : Probe
        Geometry and material of the tube, and the tip mass.
    supports : Supports
        Hinge, contact position (m) and stiffness.
    n_elements : int
        Number of beam elements; 2 with a contact is the paper's model.
    n_modes : int
        Number of lowest modes to return.
    solver : {"auto", "dense", "sparse", "naive"}
        Eigen solver; see :func:`solve_modes`.
    assembly : {"scatter", "loop"}
        How K and M are assembled, the ``engine`` of
        :func:`~ebantenna.fem.assembly.assemble`: ``"loop"`` the reference (the element matrices
        written out, added one by one), ``"scatter"`` (default) the engine; the same matrices,
        hence the same modes, bit for bit. The loop builds dense matrices, so it takes a dense
        solve: with ``solver="sparse"``, or ``"auto"`` on more than :data:`DENSE_LIMIT` free
        DOFs (101 elements or more; 100 when only the hinge's deflection is fixed, a hinge that
        is not clamped and no rigid contact), it is refused.

    Returns
    -------
    ModalResult

    Examples
    --------
    >>> from ebantenna import Probe
    >>> from ebantenna.fem import Supports, modal_analysis
    >>> res = modal_analysis(Probe(), Supports(contact=0.2), n_elements=2, n_modes=3)
    >>> res.frequencies.round(1)
    array([ 39.1, 293.9, 743.9])
    """
    if not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
    if not isinstance(supports, Supports):
        raise TypeError(f"supports must be a Supports, got {type(supports).__name__}")
    if supports.contact is not None:
        check_contact("contact", supports.contact, probe.length)
    check_choice("assembly", assembly, ASSEMBLY_ENGINES)
    nodes = beam_mesh(probe.length, supports.contact, n_elements)
    n_free = free_dofs(nodes, supports).size  # the size solve_modes compares with DENSE_LIMIT
    use_sparse = solver == "sparse" or (solver == "auto" and n_free > DENSE_LIMIT)
    if use_sparse and assembly == "loop":
        raise ValueError(
            f"assembly='loop' builds dense matrices, but solver={solver!r} solves {n_elements} "
            "elements as sparse ones; pass solver='dense' with it, or assembly='scatter'"
        )
    if not use_sparse:  # K, M, the factor and two products, (2 n_nodes)^2 doubles each
        check_memory(5 * 8 * (2 * nodes.size) ** 2, f"a dense solve of {n_elements} elements")
    K, M = assemble(nodes, probe, sparse=use_sparse, engine=assembly)
    K_free, M_free, free = apply_supports(K, M, nodes, probe, supports)
    lam, phi = solve_modes(K_free, M_free, n_modes, shift=eigenvalue_shift(probe), solver=solver)
    shapes = np.zeros((2 * nodes.size, lam.size))
    shapes[free] = phi
    _, m_diag = support_diagonals(nodes, probe, supports)  # the tip mass, as in apply_supports
    M_full = (M + sps.diags(m_diag)).tocsr() if use_sparse else M + np.diag(m_diag)
    if solver != "naive":
        lam = strain_energy(nodes, probe, supports, shapes, check_finite=False) / np.einsum(
            "im,im->m", shapes, M_full @ shapes
        )
        order = np.argsort(lam)
        lam, shapes = lam[order], shapes[:, order]
    return ModalResult(probe, supports, nodes, np.sqrt(np.maximum(lam, 0.0)), shapes, free, M_full)


def strain_energy(nodes: np.ndarray, probe: Probe, supports: Supports, u: np.ndarray, *,
                  check_finite: bool = True) -> np.ndarray:
    """Twice the strain energy ``u^T K u`` of DOF vectors, summed from element curvatures (J).

    The beam's share is :func:`bending_energy`, ``EI l (k1^2 + k1 k2 +
    k2^2) / 3`` per element from its end curvatures ``k1``, ``k2``. Springs at the hinge and the
    contact add ``k theta0^2`` and ``k v_c^2``. Same value as ``u^T K u`` in exact arithmetic, far
    fewer cancellations in floating point.

    Parameters
    ----------
    u : array of shape (2 * n_nodes,) or (2 * n_nodes, m)
        Full DOF vectors (m, rad).
    check_finite : bool, default=True
        As in :func:`bending_energy`.
    """
    l = np.diff(nodes).reshape((-1,) + (1,) * (np.ndim(u) - 1))
    energy = bending_energy(probe.flexural_rigidity, l, u, check_finite=check_finite)
    u = np.asarray(u, dtype=float)  # checked by bending_energy
    if not isinstance(supports.hinge, str):
        energy = energy + supports.hinge_stiffness * u[1] ** 2
    if supports.contact is not None and not math.isinf(supports.contact_stiffness):
        energy = (
            energy + supports.contact_stiffness * u[2 * contact_node(nodes, supports.contact)] ** 2
        )
    return energy


def bending_energy(EI, l, u, *, check_finite: bool = True) -> np.ndarray:
    r"""Twice the bending strain energy ``u^T K u`` of a chain of elements, from curvatures, J.

    Inside an element the curvature ``v''`` is linear between its end values

    .. math:: \kappa_1 = \frac{6 (v_2 - v_1) - l (4 \theta_1 + 2 \theta_2)}{l^2}, \qquad
              \kappa_2 = \frac{6 (v_1 - v_2) + l (2 \theta_1 + 4 \theta_2)}{l^2},

    so ``int EI v''^2 dx = EI l (k1^2 + k1 k2 + k2^2) / 3``. The same value as ``u^T K u`` in
    exact arithmetic, with far fewer cancellations in floating point: a second difference of the
    deflections instead of the fourth difference ``K u``.

    Parameters
    ----------
    EI : float
        Bending stiffness, N m^2.
    l : array of shape (n_elements,) or (n_elements, m)
        Element lengths, m, broadcasting against ``u[:-2:2]``.
    u : array of shape (2 n_elements + 2,) or (2 n_elements + 2, m)
        DOF vectors ``(v0, theta0, v1, ...)`` (m, rad), one per column.
    check_finite : bool, default=True
        Refuse NaN or infinite entries of ``u``, as SciPy's linear algebra does. A solver that
        passes its own mode shapes turns it off: a shape it could not resolve then gives NaN,
        which the solver reports in its own words.

    Returns
    -------
    float or ndarray of shape (m,)

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.fem.elements import element_stiffness
    >>> from ebantenna.fem.modal import bending_energy
    >>> u = np.array([0.0, 0.0, 1e-3, 2e-2])           # one element, 0.1 m, EI = 2 N m^2
    >>> bool(np.isclose(bending_energy(2.0, 0.1, u), u @ element_stiffness(2.0, 0.1) @ u))
    True
    """
    EI = check_positive("EI", EI)
    l = check_array("l", l, ndim=(0, 1, 2))
    if not np.all(l > 0):
        raise ValueError(f"l must be positive and finite, got {l.ravel()[:4].tolist()}")
    u = check_array("u", u, ndim=(1, 2), finite=check_bool("check_finite", check_finite))
    if u.shape[0] < 4 or u.shape[0] % 2:
        raise ValueError(f"u must hold 2 n_elements + 2 DOFs (v, theta per node) along its first "
                         f"axis, n_elements >= 1, got shape {u.shape}")
    v1, t1, v2, t2 = u[0:-2:2], u[1:-2:2], u[2::2], u[3::2]
    k1 = (6 * (v2 - v1) - l * (4 * t1 + 2 * t2)) / l**2
    k2 = (6 * (v1 - v2) + l * (2 * t1 + 4 * t2)) / l**2
    return (EI * l / 3 * (k1 * k1 + k1 * k2 + k2 * k2)).sum(axis=0)
