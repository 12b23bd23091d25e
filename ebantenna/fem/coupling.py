"""The touched object as a vibrating body, coupled to the probe through the contact spring.

The paper's objects are rods of five materials held in a stand (:class:`Rod`). Here such a rod is
a cantilever of Euler-Bernoulli beam elements (the same elements as the probe), clamped at its
foot, touched at ``contact_height`` above it. The probe and the rod are two *substructures*; the
contact joins the probe's deflection ``v(a)`` at the contact point and the rod's deflection
``w(h)`` at the contact height through a linear spring ``k_c`` (the linearised Hertz stiffness,
supplied by the caller).

Component-mode synthesis (Craig-Bampton)
----------------------------------------
Each substructure is reduced on its own, once, by the method of R. R. Craig and M. C. C. Bampton,
"Coupling of substructures for dynamic analyses", *AIAA Journal* 6(7):1313-1319, 1968. Split its
free DOFs into the interface DOF ``b`` (the deflection at the contact) and the interior DOFs ``i``.
The basis is

- the lowest ``k`` *fixed-interface normal modes* ``Phi`` (``K_ii Phi = M_ii Phi Lambda``, the
  interface held still), and
- the *constraint mode* ``Psi = -K_ii^-1 K_ib``: the static shape for a unit interface deflection.

With ``x = [x_i; x_b] = T [q; x_b]``, ``T = [[Phi, Psi], [0, 1]]``, the reduced stiffness is
``blockdiag(Lambda, K_bb + K_bi Psi)`` and the reduced mass ``T^T M T``. Keeping every
fixed-interface mode makes ``T`` square and the reduction exact; keeping ``k`` of them is exact for
the static response and, being a Rayleigh-Ritz subspace, converges from above in the low modes as
``k`` grows (errors in :func:`coupled_modes`). The two reduced substructures are then assembled
through the spring, ``k_c (x_b^probe - x_b^rod)^2 / 2`` of strain energy, or tied rigidly (infinite
``k_c``) by merging the two interface coordinates. The rod's reduction does not depend on the
probe's contact position, so a sweep reduces each rod once. :func:`monolithic_modes` assembles the
same system without reduction, the witness.

Damping (an assumption)
-----------------------
Each body's material loss factor ``eta`` enters as hysteretic (structural) damping proportional
to that body's stiffness, ``K (1 + i eta)`` (the contact spring carries ``contact_loss_factor``).
Every mode of a substructure on its own then has loss factor ``eta``, i.e. the equivalent viscous
modal damping ratio ``zeta = eta / 2`` at resonance. The coupled modes mix the bodies; their
damping comes from the complex eigenvalues ``lambda = omega^2 (1 + i eta_mode)`` of the coupled
system, ``zeta = Im(lambda) / (2 Re(lambda))``. To first order in ``eta`` this is the modal strain
energy average ``eta_mode = sum_s eta_s U_s / U`` (C. D. Johnson and D. A. Kienholz, *AIAA
Journal* 20(9):1284-1290, 1982); the frequencies returned are the undamped ones.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from .._validate import (
    check_array,
    check_choice,
    check_in_range,
    check_int,
    check_nonnegative,
    check_positive,
    check_range,
    describe,
)
from ..probe import MAX_LOSS_FACTOR, SIZE_RANGE, Material, Probe, material
from .assembly import Supports, apply_supports, assemble, beam_mesh
from .guards import check_contact, check_resolvable
from .modal import eigenvalue_shift, solve_modes

__all__ = [
    "ROD_DIAMETER",
    "ROD_FREE_LENGTH",
    "Rod",
    "Substructure",
    "CraigBampton",
    "CoupledModes",
    "probe_substructure",
    "rod_substructure",
    "craig_bampton",
    "coupled_modes",
    "monolithic_modes",
]


@dataclass(frozen=True, eq=False)
class Substructure:
    """A supported beam with one interface DOF, before reduction.

    Attributes
    ----------
    stiffness, mass : ndarray of shape (n, n)
        Stiffness (N/m, N, N m) and mass (kg, kg m, kg m^2) on the free DOFs, supports, springs and
        point masses included.
    interface : int
        Position of the interface DOF (the deflection at the contact) among the free DOFs.
    nodes : ndarray
        Node positions along the beam, m.
    free : ndarray of int
        The free DOFs' indices in the full DOF vector ``(v0, theta0, v1, ...)``.
    loss_factor : float
        Loss factor of the body (dimensionless), multiplying the whole stiffness.
    scale : float
        ``EI / (rho A l^4)`` of the beam, 1/s^2: the order of its lowest ``omega^2``, used as the
        eigen solver's shift.
    """

    stiffness: np.ndarray
    mass: np.ndarray
    interface: int
    nodes: np.ndarray
    free: np.ndarray
    loss_factor: float
    scale: float

    def __post_init__(self):
        stiffness = check_array("stiffness", self.stiffness, ndim=2)
        n = stiffness.shape[0]
        if stiffness.shape != (n, n):
            raise ValueError(f"stiffness must be a square matrix, got shape {stiffness.shape}")
        if check_array("mass", self.mass, ndim=2).shape != (n, n):
            raise ValueError(f"mass must have the shape of stiffness {(n, n)}, got "
                             f"{np.shape(self.mass)}")
        check_int("interface", self.interface, minimum=0, maximum=n - 1)
        nodes = check_array("nodes", self.nodes, ndim=1, min_length=2)
        if not np.all(np.diff(nodes) > 0):
            raise ValueError("nodes must be increasing positions along the beam")
        free = np.asarray(self.free)
        if (free.shape != (n,) or free.dtype.kind not in "iu" or free.min() < 0
                or free.max() >= 2 * nodes.size or np.unique(free).size != n):
            raise ValueError(f"free must hold the {n} distinct indices of the free DOFs among "
                             f"the {2 * nodes.size} of the nodes")
        check_in_range("loss_factor", self.loss_factor, 0.0, MAX_LOSS_FACTOR,
                       low_inclusive=True, high_inclusive=True)
        check_positive("scale", self.scale)

    def full(self, x: np.ndarray) -> np.ndarray:
        """Full DOF vectors (zeros at the fixed DOFs) from vectors on the free DOFs."""
        out = np.zeros((2 * self.nodes.size,) + x.shape[1:], dtype=x.dtype)
        out[self.free] = x
        return out


def probe_substructure(probe: Probe, contact: float, *, hinge="clamped", n_elements: int = 64):
    """The probe on its hinge, its interface the deflection at ``contact`` (m from the hinge).

    The hinge (clamped, pinned or a rotational spring in N m/rad) and the tip mass are included;
    the contact itself is not (it is the interface).
    """
    if not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
    contact = check_contact("contact", contact, probe.length)
    return _substructure(probe, hinge, contact, contact, n_elements)


#: The touched rod's diameter, m: an assumption (the paper gives no geometry of the touched
#: objects), the default of :class:`Rod` and of the simulator's ``object_modes`` effect.
ROD_DIAMETER = 0.012
#: The touched rod's length above the stand's clamp, m: an assumption, as :data:`ROD_DIAMETER`.
ROD_FREE_LENGTH = 0.25


@dataclass(frozen=True)
class Rod:
    """A solid round rod standing in a stand: the touched object.

    Parameters
    ----------
    material : Material or str
        What the rod is made of (a name is looked up with :func:`ebantenna.probe.material`); its
        ``youngs_modulus`` (along the rod's axis; for wood, along the grain), ``density`` and
        ``loss_factor`` are used.
    diameter : float
        Diameter, m. Default :data:`ROD_DIAMETER` (12 mm), an assumption.
    free_length : float
        Length above the clamp of the stand, m. Default :data:`ROD_FREE_LENGTH` (250 mm), an
        assumption.
    contact_height : float or None
        Height of the contact above the clamp, m, in ``(0, free_length]``; ``None`` (default)
        means the free end, ``free_length``.

    Examples
    --------
    >>> from ebantenna.fem.coupling import Rod
    >>> rod = Rod("steel")
    >>> rod.contact_height
    0.25
    >>> round(rod.cantilever_frequency(), 1)  # first bending mode in the stand, Hz
    137.3
    """

    material: Material | str
    diameter: float = ROD_DIAMETER
    free_length: float = ROD_FREE_LENGTH
    contact_height: float | None = None

    def __post_init__(self):
        mat = self.material if isinstance(self.material, Material) else material(self.material)
        object.__setattr__(self, "material", mat)
        for name in ("diameter", "free_length"):  # the probe's range for a beam, with its reason
            check_range(name, getattr(self, name), SIZE_RANGE, "a continuum beam from 1 µm to 1 km")
        height = self.free_length if self.contact_height is None else self.contact_height
        height = check_in_range(
            "contact_height (m above the clamp, within the rod's free length)",
            height,
            0.0,
            self.free_length,
            high_inclusive=True,
        )
        object.__setattr__(self, "contact_height", height)

    def as_beam(self) -> Probe:
        """The rod as a solid beam (a :class:`~ebantenna.probe.Probe` with no bore, no tip mass)."""
        m = self.material
        return Probe(
            length=self.free_length,
            outer_diameter=self.diameter,
            inner_diameter=0.0,
            youngs_modulus=m.youngs_modulus,
            density=m.density,
            loss_factor=m.loss_factor,
        )

    def cantilever_frequency(self) -> float:
        """First bending frequency of the rod clamped in its stand, Hz (beta L = 1.8751)."""
        beam = self.as_beam()
        beta_l = 1.8751040687119611
        return (
            beta_l**2
            / self.free_length**2
            * math.sqrt(beam.flexural_rigidity / beam.mass_per_length)
            / (2 * math.pi)
        )



def rod_substructure(rod: Rod, *, n_elements: int = 32) -> Substructure:
    """The rod clamped at its foot, its interface the deflection at ``rod.contact_height``."""
    if not isinstance(rod, Rod):
        raise TypeError(f"rod must be a Rod, got {type(rod).__name__}")
    node_at = None  # a contact at the free end is the last node of a uniform mesh
    if rod.contact_height < rod.free_length:
        node_at = check_contact("contact_height", rod.contact_height, rod.free_length)
    return _substructure(rod.as_beam(), "clamped", rod.contact_height, node_at, n_elements)


def _substructure(beam: Probe, hinge, interface_at: float, node_at, n_elements: int):
    """``beam`` on its hinge (with its tip mass, if any), its interface the deflection at
    ``interface_at`` (m from the hinge), meshed by :func:`~ebantenna.fem.assembly.beam_mesh`
    with a node at ``node_at`` (None: a uniform mesh); its loss factor the beam's."""
    nodes = beam_mesh(beam.length, node_at, n_elements)
    K, M = assemble(nodes, beam)
    K, M, free = apply_supports(K, M, nodes, beam, Supports(contact=None, hinge=hinge))
    v_contact = 2 * int(np.argmin(np.abs(nodes - interface_at)))
    interface = int(np.flatnonzero(free == v_contact)[0])
    return Substructure(K, M, interface, nodes, free, float(beam.loss_factor),
                        eigenvalue_shift(beam))


@dataclass(frozen=True, eq=False)
class CraigBampton:
    """A substructure reduced to fixed-interface modes plus the interface constraint mode.

    Attributes
    ----------
    stiffness, mass : ndarray of shape (k + 1, k + 1)
        Reduced matrices; coordinates ``(q_1, ..., q_k, x_b)``, the last one the interface
        deflection (m).
    basis : ndarray of shape (n, k + 1)
        ``T``: free DOFs of the substructure = ``T @ (q, x_b)``.
    fixed_interface_omega : ndarray of shape (k,)
        Circular frequencies of the retained fixed-interface modes, rad/s.
    substructure : Substructure
    """

    stiffness: np.ndarray
    mass: np.ndarray
    basis: np.ndarray
    fixed_interface_omega: np.ndarray
    substructure: Substructure

    @property
    def interface(self) -> int:
        """Index of the interface coordinate among the reduced ones (the last)."""
        return self.stiffness.shape[0] - 1

    @property
    def loss_factor(self) -> float:
        """Loss factor of the body."""
        return self.substructure.loss_factor


def craig_bampton(sub: Substructure, n_modes: int) -> CraigBampton:
    """Craig-Bampton reduction of a substructure to ``n_modes`` fixed-interface modes.

    Parameters
    ----------
    sub : Substructure
    n_modes : int
        Fixed-interface normal modes kept, 0 up to all interior DOFs (then the reduction is exact).

    Returns
    -------
    CraigBampton

    Examples
    --------
    >>> from ebantenna.fem.coupling import Rod, craig_bampton, rod_substructure
    >>> cb = craig_bampton(rod_substructure(Rod("brass"), n_elements=16), 4)
    >>> cb.stiffness.shape
    (5, 5)
    >>> round(cb.stiffness[-1, -1])  # static stiffness of the tip, 3 EI / l^3, N/m
    20520
    """
    if not isinstance(sub, Substructure):
        raise TypeError(f"sub must be a Substructure (probe_substructure, rod_substructure), "
                        f"got {type(sub).__name__}")
    n = sub.stiffness.shape[0]
    n_modes = check_int("n_modes", n_modes, minimum=0, maximum=n - 1)
    b = sub.interface
    inner = np.delete(np.arange(n), b)
    K_ii = sub.stiffness[np.ix_(inner, inner)]
    M_ii = sub.mass[np.ix_(inner, inner)]
    # Constraint mode: interior response to a unit interface deflection, no interior load.
    psi = -sla.solve(K_ii, sub.stiffness[inner, b], assume_a="pos")
    T = np.zeros((n, n_modes + 1))
    T[inner, n_modes] = psi
    T[b, n_modes] = 1.0
    lam = np.zeros(0)
    if n_modes:
        lam, phi = solve_modes(K_ii, M_ii, n_modes, shift=sub.scale, solver="dense")
        T[inner, :n_modes] = phi
    K_r = np.zeros((n_modes + 1, n_modes + 1))
    K_r[np.arange(n_modes), np.arange(n_modes)] = lam
    # Condensed (Guyan) stiffness, a Schur complement of a semi-definite K and so >= 0: where the
    # body is a mechanism without the interface (a pinned probe) it is 0 up to rounding.
    K_r[-1, -1] = max(sub.stiffness[b, b] + sub.stiffness[b, inner] @ psi, 0.0)
    M_r = T.T @ sub.mass @ T
    return CraigBampton(K_r, (M_r + M_r.T) / 2, T, np.sqrt(lam), sub)


@dataclass(frozen=True, eq=False)
class CoupledModes:
    """Modes of the probe and the touched rod joined by the contact spring.

    Attributes
    ----------
    omega : ndarray of shape (n_modes,)
        Undamped natural circular frequencies, rad/s, ascending.
    damping_ratio : ndarray of shape (n_modes,)
        Equivalent viscous damping ratio of each mode, ``Im(lambda) / (2 Re(lambda))``.
    eigenvalues : ndarray of complex, shape (n_modes,)
        The damped eigenvalues ``lambda = omega^2 (1 + i eta)``, 1/s^2.
    probe_nodes, rod_nodes : ndarray
        Node positions along the probe (from the hinge) and the rod (from the clamp), m.
    probe_shapes, rod_shapes : ndarray of shape (2 * n_nodes, n_modes)
        Undamped mode shapes of the two bodies as full DOF vectors ``(v0, theta0, ...)`` (m, rad
        per unit modal coordinate), mass-normalised over the coupled system.
    """

    omega: np.ndarray
    damping_ratio: np.ndarray
    eigenvalues: np.ndarray
    probe_nodes: np.ndarray
    rod_nodes: np.ndarray
    probe_shapes: np.ndarray
    rod_shapes: np.ndarray

    @property
    def frequencies(self) -> np.ndarray:
        """Undamped natural frequencies, Hz."""
        return self.omega / (2 * math.pi)

    @property
    def tip_displacement(self) -> np.ndarray:
        """Deflection of the probe's tip in each mode, m per unit modal coordinate."""
        return self.probe_shapes[-2]


def _check_coupling(contact_stiffness, contact_loss_factor, n_modes):
    k_c = check_nonnegative("contact_stiffness (N/m, 0 to inf)", contact_stiffness, allow_inf=True)
    check_nonnegative("contact_loss_factor", contact_loss_factor)
    eta_c = check_in_range("contact_loss_factor", contact_loss_factor, 0.0, MAX_LOSS_FACTOR,
                           low_inclusive=True, high_inclusive=True,
                           reason="a loss factor of 1 is a damping ratio of 0.5: the contact's "
                           "hysteretic model is for light damping")
    check_int("n_modes", n_modes, minimum=1)
    return k_c, eta_c


def _check_kept(name: str, kept, sub: Substructure, mesh: str) -> int:
    """The number of fixed-interface modes ``kept`` of ``sub``; the error names ``mesh`` too."""
    most = sub.stiffness.shape[0] - 1
    kept = check_int(name, kept, minimum=0)
    if kept > most:
        raise ValueError(
            f"{name} must be <= {most} (the interior degrees of freedom of {mesh}'s mesh), got "
            f"{describe(kept)}; lower {name} or refine {mesh}"
        )
    return kept


def _couple(parts, k_c, eta_c):
    """Assemble two bodies ``(K, M, interface, eta)`` through the spring; K = K_re + i K_im.

    Returns ``K_re, K_im, M, G`` with ``G`` the map from the coupled coordinates to the stacked
    coordinates of both bodies (identity unless the contact is rigid).
    """
    (Ka, Ma, ia, eta_a), (Kb, Mb, ib, eta_b) = parts
    na, nb = Ka.shape[0], Kb.shape[0]
    K = sla.block_diag(Ka, Kb)
    K_im = sla.block_diag(eta_a * Ka, eta_b * Kb)
    M = sla.block_diag(Ma, Mb)
    a, b = ia, na + ib
    if math.isinf(k_c):
        keep = np.delete(np.arange(na + nb), b)
        G = np.eye(na + nb)[:, keep]
        G[b, a] = 1.0  # the rod's interface deflection is the probe's
        return G.T @ K @ G, G.T @ K_im @ G, G.T @ M @ G, G
    spring = np.zeros((na + nb, na + nb))
    spring[np.ix_([a, b], [a, b])] = k_c * np.array([[1.0, -1.0], [-1.0, 1.0]])
    return K + spring, K_im + eta_c * spring, M, np.eye(na + nb)


#: The perturbation series is used while every coupling ``|D_kj|`` of a returned mode to another is
#: below this share of their eigenvalue gap; its third-order remainder is then below 1e-3 of the
#: second-order term.
_PERTURBATION_RATIO = 0.1


def _solve_coupled(K, K_im, M, n_modes, shift, damping="exact"):
    """Undamped modes of (K, M) and the damped eigenvalues of (K + i K_im, M), paired."""
    n = K.shape[0]
    if n_modes > n:
        raise ValueError(f"n_modes must be <= {n} (the coupled system's size), got {n_modes}")
    lam, phi = solve_modes(K, M, n, shift=shift, solver="dense")
    # Damped problem in the undamped modal basis (a full change of basis, so exact):
    # Lambda + i Phi^T K_im Phi; each damped mode is paired with the undamped one it is mostly.
    D = phi.T @ K_im @ phi
    D = (D + D.T) / 2
    eig = None
    if damping == "perturbation":
        eig = _perturbation(lam, D, n_modes)
    if eig is None:
        A = np.diag(lam) + 1j * D
        mu, Z = sla.eig(A)
        owner = np.argmax(np.abs(Z), axis=0)
        if np.unique(owner).size != n:  # near-degenerate pair mixed: first order, the diagonal
            eig = (lam + 1j * np.diag(D))[:n_modes]
        else:
            Z = Z[:, np.argsort(owner)][:, :n_modes]
            # eig is accurate to eps * max(lam) in absolute terms only, too little for the lowest
            # modes; the (unconjugated) Rayleigh quotient of the complex-symmetric A is stationary
            # at an eigenvector and sums lam_k z_k^2 term by term: relative accuracy again.
            eig = np.einsum("km,km->m", Z, A @ Z) / np.einsum("km,km->m", Z, Z)
    zeta = np.where(eig.real > 0, eig.imag / (2 * np.where(eig.real > 0, eig.real, 1.0)), 0.0)
    return lam[:n_modes], phi[:, :n_modes], eig, zeta


def _perturbation(lam, D, n_modes):
    """Eigenvalues of ``diag(lam) + i D`` to third order in ``D``, or None where it is unsafe.

    Rayleigh-Schrodinger perturbation with ``V = i D`` (``D`` real symmetric), ``g_kj = lam_k -
    lam_j`` and ``w_j = D_kj / g_kj`` (``w_k = 0``):

        mu_k = lam_k + i D_kk - sum_j D_kj w_j - i (w^T D w - D_kk w^T w) + O(D^4),

    the second-order term real, the third imaginary: the damping is right to third order. None
    when a returned mode couples to another more strongly than :data:`_PERTURBATION_RATIO` of
    their gap (a near-degenerate pair), where the series does not hold.
    """
    rows = D[:n_modes]
    gap = lam[:n_modes, None] - lam[None, :]
    np.fill_diagonal(gap[:, :n_modes], np.inf)
    w = rows / gap
    if not np.all(np.abs(w) < _PERTURBATION_RATIO):
        return None
    d = np.diag(D)[:n_modes]
    third = np.einsum("kj,jl,kl->k", w, D, w) - d * np.einsum("kj,kj->k", w, w)
    return lam[:n_modes] + 1j * d - np.einsum("kj,kj->k", rows, w) - 1j * third


def coupled_modes(
    probe: Probe,
    rod: Rod,
    contact: float,
    contact_stiffness: float,
    *,
    hinge="clamped",
    n_modes: int = 6,
    n_elements: int = 64,
    rod_elements: int = 32,
    probe_modes: int = 40,
    rod_modes: int = 20,
    contact_loss_factor: float = 0.0,
    rod_reduction: CraigBampton | None = None,
    probe_reduction: CraigBampton | None = None,
    damping: str = "exact",
) -> CoupledModes:
    """Coupled modes of probe and rod by Craig-Bampton component-mode synthesis.

    Parameters
    ----------
    probe : Probe
    rod : Rod
        The touched object; its material's loss factor damps it.
    contact : float
        Contact position along the probe, m from the hinge, in ``(0, L)``.
    contact_stiffness : float
        Contact spring ``k_c``, N/m, in ``[0, inf]``: 0 leaves the bodies apart, ``inf`` ties them.
    hinge : {"clamped", "pinned"} or float
        The probe's hinge, as in :class:`~ebantenna.fem.Supports`.
    n_modes : int
        Coupled modes returned (lowest first).
    n_elements, rod_elements : int
        Beam elements of the probe and the rod.
    probe_modes, rod_modes : int
        Fixed-interface modes kept per substructure (more: closer to :func:`monolithic_modes`).
        For the lowest six coupled modes of the five materials' default rods touched at 5, 20
        and 35 cm (k_c = 2e5 N/m), the largest relative error is 4.7e-6 with 24 / 12 modes,
        3.7e-7 with the default 40 / 20, 3.5e-8 with 64 / 32; the reduced problem has
        ``probe_modes + rod_modes + 2`` coordinates.
    contact_loss_factor : float
        Loss factor of the contact spring (dimensionless), default 0.
    rod_reduction, probe_reduction : CraigBampton, optional
        Reductions of this rod, and of this probe at this contact, made earlier by
        :func:`craig_bampton`, to reuse them in a sweep.
    damping : {"exact", "perturbation"}
        How the damped eigenvalues are found: ``"exact"``, from the complex eigenproblem of the
        reduced system; ``"perturbation"``, to second order in the loss factors (relative error
        of the damping ratios of order ``eta^2``; several times faster, for sweeps), falling back
        to the exact solution for near-degenerate modes.

    Returns
    -------
    CoupledModes

    Examples
    --------
    >>> from ebantenna import Probe
    >>> from ebantenna.fem.coupling import Rod, coupled_modes
    >>> res = coupled_modes(Probe(), Rod("pvc"), 0.2, 2e5, n_modes=3)
    >>> res.frequencies.round(1)
    array([ 23. ,  62.1, 213.2])
    >>> res.damping_ratio.round(4)
    array([0.012 , 0.0139, 0.0104])
    """
    k_c, eta_c = _check_coupling(contact_stiffness, contact_loss_factor, n_modes)
    check_choice("damping", damping, ("exact", "perturbation"))
    p = probe_reduction
    if p is None:
        sub = probe_substructure(probe, contact, hinge=hinge,
                                 n_elements=check_resolvable(n_elements))
        p = craig_bampton(sub, _check_kept("probe_modes", probe_modes, sub, "n_elements"))
    r = rod_reduction
    if r is None:
        sub = rod_substructure(rod, n_elements=check_resolvable(rod_elements, "rod_elements"))
        r = craig_bampton(sub, _check_kept("rod_modes", rod_modes, sub, "rod_elements"))
    parts = [(c.stiffness, c.mass, c.interface, c.loss_factor) for c in (p, r)]
    K, K_im, M, G = _couple(parts, k_c, eta_c)
    lam, z, eig, zeta = _solve_coupled(K, K_im, M, n_modes, eigenvalue_shift(probe), damping)
    x = G @ z
    n_p = p.stiffness.shape[0]
    return CoupledModes(
        np.sqrt(lam),
        zeta,
        eig,
        p.substructure.nodes,
        r.substructure.nodes,
        p.substructure.full(p.basis @ x[:n_p]),
        r.substructure.full(r.basis @ x[n_p:]),
    )


def monolithic_modes(
    probe: Probe,
    rod: Rod,
    contact: float,
    contact_stiffness: float,
    *,
    hinge="clamped",
    n_modes: int = 6,
    n_elements: int = 64,
    rod_elements: int = 32,
    contact_loss_factor: float = 0.0,
) -> CoupledModes:
    """The same coupled modes from one FEM system of probe, rod and spring, without reduction.

    The witness for :func:`coupled_modes`: both bodies' full matrices are assembled into one
    generalized eigenproblem and solved directly. Parameters as in :func:`coupled_modes`.

    Examples
    --------
    >>> from ebantenna import Probe
    >>> from ebantenna.fem.coupling import Rod, monolithic_modes
    >>> monolithic_modes(Probe(), Rod("pvc"), 0.2, 2e5, n_modes=3).frequencies.round(1)
    array([ 23. ,  62.1, 213.2])
    """
    k_c, eta_c = _check_coupling(contact_stiffness, contact_loss_factor, n_modes)
    p = probe_substructure(probe, contact, hinge=hinge, n_elements=n_elements)
    r = rod_substructure(rod, n_elements=rod_elements)
    parts = [(s.stiffness, s.mass, s.interface, s.loss_factor) for s in (p, r)]
    K, K_im, M, G = _couple(parts, k_c, eta_c)
    lam, z, eig, zeta = _solve_coupled(K, K_im, M, n_modes, eigenvalue_shift(probe))
    x = G @ z
    n_p = p.stiffness.shape[0]
    return CoupledModes(np.sqrt(lam), zeta, eig, p.nodes, r.nodes, p.full(x[:n_p]), r.full(x[n_p:]))
