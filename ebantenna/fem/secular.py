"""Contact sweeps by the secular equation: one modal analysis, then a few roots per position.

The probe without the contact is solved once, on one uniform mesh, for all of its modes
``(lambda_k, phi_k)``, mass-normalised. A contact at ``a`` touches the deflection there, which
inside an element is the Hermite interpolation ``c(a)^T u`` of the element's four DOFs. Pressing
a spring ``k_c`` on that point adds ``k_c c c^T`` to ``K``: a rank-one change, whose eigenvalues
``lambda`` solve the *secular equation* (G. H. Golub, "Some modified matrix eigenvalue problems",
SIAM Review 15, 1973)

    f(lambda) = 1/k_c + sum_k w_k / (lambda_k - lambda) = 0,    w_k = (c(a)^T phi_k)^2,

with ``1/k_c = 0`` for a rigid pin. ``f`` rises from minus to plus infinity between two poles, so
the ``j``-th root lies in ``(lambda_j, lambda_{j+1})`` (interlacing), one per interval. Each root
is found by the "middle way" rational iteration of R.-C. Li ("Solving secular equations stably and
efficiently", LAPACK Working Note 89, 1994; after J. R. Bunch, C. P. Nielsen and D. C. Sorensen,
Numer. Math. 31, 1978): the sums over the poles left and right of the root are each replaced by
one pole at the interval's end matching value and slope, and the quadratic solved; a step that
leaves the bracket falls back to bisection. A handful of iterations reach rounding. The mode is
then ``u = sum_k phi_k w_k^(1/2) / (lambda_k - lambda)``, and, as in :mod:`~ebantenna.fem.banded`,
the frequency is its Rayleigh quotient with the strain energy summed from the element curvatures:
the absolute accuracy ``eps lambda_max`` of the one dense solve does not reach the result.

Per position this costs ``O(n_modes x n)`` for the roots and one product with the modes for the
Rayleigh quotients, no factorisation: many times faster than a solve per position
(``ebantenna bench``).

**A pin inside a cubic element, and its static correction.** In
:func:`~ebantenna.fem.modal.modal_analysis` a node is put at the contact; here the mesh is fixed and
the contact falls inside an element, constraining the cubic interpolation there. That cannot make
the slope of the shear force jump at the contact, and the element is too stiff there: at 64
elements the frequencies are ~1e-4 too high. The error is almost all *static*. The flexibility of
the mesh at ``a``, ``c(a)^T K^-1 c(a) = sum_k w_k / lambda_k``, is smaller than the beam's
(Rayleigh-Ritz), by

    delta(a) = a^3 / (3 EI) - N(a)^T F_e N(a)  >= 0,

where ``a^3 / (3 EI)`` is the exact flexibility of the clamped probe at ``a`` and ``F_e`` the exact
flexibilities among the element's four nodal DOFs: for Hermite cubic beam elements the nodal
deflections of the finite element solution are exact under any load (P. Tong, "Exact solution of
certain problems by finite-element method", AIAA Journal 7(1), 1969, 178-180), so the mesh's
flexibility at ``a`` is the Hermite interpolation of the exact one between the nodes. A hinge
spring adds ``a^2 / k_h`` to both, so ``delta`` holds for every hinge; the tip mass does not enter
statics. ``delta`` is zero on the nodes. Added to ``1/k_c`` it is the missing compliance, a spring
in series with the contact (the static or "residual flexibility" correction of mode superposition,
R. H. MacNeal, "A hybrid method of component mode synthesis", Computers & Structures 1, 1971,
581-601): the secular function is shifted by a constant, the interlacing is kept, and the error
left is the dynamic part's, which falls like ``h^4`` as the banded sweep's does. At 64 elements
the corrected sweep is as accurate as the banded one against the exact solution; the uncorrected
one stays available (``secular_sweep(..., static=False)``) as the lesson. ``ebantenna bench``
shows both.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.linalg as sla

from .._validate import check_array, check_bool, check_int, check_positive
from ..probe import Probe
from ._parallel import map_on_cores
from .assembly import assemble
from .elements import hermite
from .guards import check_sweep, check_uniform_mesh
from .modal import bending_energy

__all__ = ["secular_sweep", "contact_weights", "static_correction"]

#: Most iterations of the rational root finder; bisection alone would need about 60.
MAX_ITERATIONS = 100
#: A root is taken as found when an iteration moves it by less than this, relative.
_STEP_TOLERANCE = 1e-13


def _unconstrained(probe: Probe, n_elements: int, hinge_stiffness: float):
    """Uniform mesh, free DOFs, ``K`` and ``M`` on them, and all the modes there."""
    nodes = np.linspace(0.0, probe.length, n_elements + 1)
    K, M = assemble(nodes, probe)
    M[-2, -2] += probe.tip_mass
    held = [0]  # the hinge never moves sideways
    if math.isinf(hinge_stiffness):
        held.append(1)
    else:
        K[1, 1] += hinge_stiffness
    free = np.setdiff1d(np.arange(K.shape[0]), held)
    K, M = K[np.ix_(free, free)], M[np.ix_(free, free)]
    lam, phi = sla.eigh(K, M)
    return nodes, free, M, np.maximum(lam, 0.0), phi


def _on_the_mesh(contacts, nodes) -> np.ndarray:
    """``contacts`` as a 1-D array of positions within the mesh ``nodes`` (0 to its length)."""
    contacts = check_array("contacts", contacts, ndim=1)
    if contacts.min() < 0 or contacts.max() > nodes[-1]:
        raise ValueError(f"contacts must lie on the mesh, from 0 to {nodes[-1]:g} m")
    return contacts


def contact_weights(nodes: np.ndarray, free: np.ndarray, phi: np.ndarray, contacts: np.ndarray):
    """``c(a)^T phi_k`` for every contact ``a``: each mode's deflection there, shape (B, n)."""
    nodes, h = check_uniform_mesh(nodes)
    free = np.asarray(free)
    if (free.ndim != 1 or free.dtype.kind not in "iu" or free.size == 0
            or free.min() < 0 or free.max() >= 2 * nodes.size
            or np.unique(free).size != free.size):
        raise ValueError(f"free must be distinct DOF indices of the mesh (0 to "
                         f"{2 * nodes.size - 1})")
    phi = check_array("phi", phi, ndim=2)
    if phi.shape[0] != free.size:
        raise ValueError(f"phi must have one row per free DOF ({free.size}), got shape "
                         f"{phi.shape}")
    contacts = _on_the_mesh(contacts, nodes)
    element = np.clip((contacts // h).astype(int), 0, nodes.size - 2)
    N = hermite((contacts - nodes[element]) / h, h)  # (B, 4)
    full = np.zeros((2 * nodes.size, phi.shape[1]))
    full[free] = phi
    return np.einsum("bj,bjk->bk", N, full[2 * element[:, None] + np.arange(4)])


def static_correction(nodes: np.ndarray, contacts: np.ndarray, flexural_rigidity: float):
    """The compliance a uniform mesh misses at each contact, ``delta(a) >= 0``, m/N, shape (B,).

    ``a^3 / (3 EI)``, the clamped beam's exact flexibility at ``a``, less the mesh's: the Hermite
    interpolation ``N^T F_e N`` of the exact flexibilities ``F_e`` among the four nodal DOFs of
    the element holding ``a`` (exact on the nodes, Tong 1969). Zero on the nodes; rounding below
    zero is clipped at zero (``delta >= 0`` by Rayleigh-Ritz).

    Examples
    --------
    >>> import numpy as np
    >>> nodes = np.linspace(0.0, 0.4, 5)
    >>> delta = static_correction(nodes, np.array([0.1, 0.15]), flexural_rigidity=1.0)
    >>> bool(delta[0] == 0.0), bool(delta[1] > 0)  # a node, then the middle of an element
    (True, True)
    """
    nodes, h = check_uniform_mesh(nodes)
    contacts = _on_the_mesh(contacts, nodes)
    flexural_rigidity = check_positive("flexural_rigidity", flexural_rigidity)
    element = np.clip((contacts // h).astype(int), 0, nodes.size - 2)
    N = hermite((contacts - nodes[element]) / h, h)  # (B, 4): v, theta at each end
    x = nodes[element[:, None] + np.array([0, 0, 1, 1])]  # (B, 4): where each DOF sits
    s, t = x[:, :, None], x[:, None, :]  # response at DOF i (s) to a unit load at DOF j (t)
    lo, hi = np.minimum(s, t), np.maximum(s, t)
    v_force = lo**2 * (3 * hi - lo) / 6  # deflection at s, force at t (Maxwell: symmetric)
    slope_force = np.where(s <= t, s * (2 * t - s) / 2, t**2 / 2)  # slope at s, force at t
    slope = np.array([False, True, False, True])
    F = np.where(
        slope[:, None] & slope[None, :],
        lo,  # slope at s, moment at t
        np.where(
            slope[:, None],
            slope_force,
            np.where(slope[None, :], np.swapaxes(slope_force, 1, 2), v_force),
        ),
    )
    interpolated = np.einsum("bi,bij,bj->b", N, F, N)
    return np.maximum(contacts**3 / 3 - interpolated, 0.0) / flexural_rigidity


def _roots(lam: np.ndarray, w: np.ndarray, n_modes: int, inv_k) -> np.ndarray:
    """The ``n_modes`` lowest roots of ``inv_k + sum_k w_k / (lam_k - x)``, shape (B, n_modes).

    ``inv_k`` is a compliance, m/N: a number, or one per position of shape (B, 1).
    """
    j = np.arange(n_modes)
    d0, d1 = np.broadcast_to(lam[j], (w.shape[0], n_modes)), lam[j + 1]
    width = d1 - d0
    lo, hi = d0.copy(), np.broadcast_to(d1, d0.shape).copy()
    x = d0 + 0.5 * width
    left = np.arange(lam.size) <= j[:, None]  # poles at or left of the interval, (n_modes, n)
    active = np.ones(x.shape, dtype=bool)
    for _ in range(MAX_ITERATIONS):
        with np.errstate(divide="ignore", invalid="ignore"):
            t = w[:, None, :] / (lam - x[..., None])  # (B, n_modes, n)
            t2 = t / (lam - x[..., None])
        psi, dpsi = np.where(left, t, 0.0).sum(-1), np.where(left, t2, 0.0).sum(-1)
        phi, dphi = np.where(left, 0.0, t).sum(-1), np.where(left, 0.0, t2).sum(-1)
        f = inv_k + psi + phi
        lo, hi = np.where(f < 0, x, lo), np.where(f > 0, x, hi)
        # one pole at each end of the interval, matching value and slope of each sum
        u0, u1 = d0 - x, d1 - x
        b0, b1 = dpsi * u0**2, dphi * u1**2
        A = inv_k + psi - b0 / u0 + phi - b1 / u1
        # A + b0/u + b1/(u + width) = 0 for u = d0 - x in (-width, 0): A u^2 + B u + C = 0
        B, C = A * width + b0 + b1, b0 * width
        q = -0.5 * (B + np.copysign(np.sqrt(np.maximum(B * B - 4 * A * C, 0.0)), B))
        with np.errstate(divide="ignore", invalid="ignore"):
            r0, r1 = C / q, q / A
        u = np.where((r0 > -width) & (r0 < 0), r0, r1)
        step = d0 - u
        done = np.abs(step - x) <= _STEP_TOLERANCE * x
        inside = (step >= lo) & (step <= hi) & np.isfinite(step)
        step = np.where(done, x, np.where(inside, step, 0.5 * (lo + hi)))
        x = np.where(active, step, x)
        active &= ~done
        if not active.any():
            return x
    raise np.linalg.LinAlgError(
        f"the secular iteration did not converge in {MAX_ITERATIONS} steps; use method='banded'"
    )


def secular_sweep(
    probe: Probe,
    contacts: np.ndarray,
    *,
    hinge_stiffness: float,
    contact_stiffness: float,
    n_elements: int,
    n_modes: int,
    chunk: int = 1024,
    static: bool = True,
) -> np.ndarray:
    """Lowest ``n_modes`` eigenvalues ``omega^2`` (1/s^2) for each contact, shape (B, n_modes).

    Inputs are trusted (the public entry is :func:`~ebantenna.fem.sweeps.natural_frequencies`
    with ``method="secular"``). ``hinge_stiffness`` is inf for a clamped hinge, 0 for a pinned
    one, N m/rad for a spring; ``contact_stiffness`` inf for a rigid contact, N/m for a spring.
    The modes without contact are solved once; the positions then go in batches of ``chunk``,
    side by side on the machine's cores. ``static=False`` leaves out the static correction
    (:func:`static_correction`): the pin inside an element as the mesh alone models it.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.probe import Probe
    >>> lam = secular_sweep(Probe(), np.array([0.1, 0.2]), hinge_stiffness=np.inf,
    ...                     contact_stiffness=np.inf, n_elements=64, n_modes=2)
    >>> (np.sqrt(lam) / (2 * np.pi)).round(2)  # the nodes at 0.1 and 0.2 m: modal_analysis's
    array([[ 21.35, 137.77],
           [ 38.97, 243.51]])
    """
    contacts, n_elements, n_modes = check_sweep(probe, contacts, hinge_stiffness,
                                                contact_stiffness, n_elements, n_modes)
    chunk = check_int("chunk", chunk, minimum=1)
    static = check_bool("static", static)
    nodes, free, M, lam, phi = _unconstrained(probe, n_elements, hinge_stiffness)
    inv_k = 0.0 if math.isinf(contact_stiffness) else 1.0 / contact_stiffness

    def solve(block):
        ct = contact_weights(nodes, free, phi, block)
        compliance = np.full(block.size, inv_k)  # the contact's, m/N, and the mesh's missing one
        if static:
            compliance += static_correction(nodes, block, probe.flexural_rigidity)
        x = _roots(lam, ct**2, n_modes, compliance[:, None])
        # the modes, u = Phi (ct / (lam - x)), and their Rayleigh quotients from the curvatures
        with np.errstate(divide="ignore", invalid="ignore"):
            eta = ct[:, None, :] / (lam - x[..., None])  # (B, n_modes, n)
        on_pole = ~np.all(np.isfinite(eta), axis=-1)  # a root on a pole: a mode the contact misses
        eta[on_pole] = 0.0
        u_free = phi @ eta.reshape(-1, lam.size).T  # (n, B n_modes)
        u = np.zeros((2 * nodes.size, u_free.shape[1]))
        u[free] = u_free
        h = np.full((n_elements, u.shape[1]), nodes[1] - nodes[0])
        energy = bending_energy(probe.flexural_rigidity, h, u).reshape(x.shape)
        if not math.isinf(hinge_stiffness):
            energy += hinge_stiffness * u[1].reshape(x.shape) ** 2
        # the contact spring's energy, (c^T u)^2 / compliance; none for a rigid pin (c^T u = 0)
        deflection = np.einsum("bk,bjk->bj", ct, eta)
        spring = compliance[:, None] > 0
        energy += np.where(spring, deflection**2 / np.where(spring, compliance[:, None], 1.0), 0)
        mass = np.einsum("db,db->b", u_free, M @ u_free).reshape(x.shape)
        with np.errstate(divide="ignore", invalid="ignore"):
            quotient = energy / mass
        return np.sort(np.where(on_pole, x, quotient), axis=1)

    blocks = [contacts[i : i + chunk] for i in range(0, contacts.size, chunk)]
    return np.concatenate(map_on_cores(solve, blocks))
