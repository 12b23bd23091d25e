"""Contact sweeps on banded matrices: a banded Cholesky and a few Lanczos steps per position.

A chain of beam elements couples each DOF only to its three neighbours on either side, so ``K`` and
``M`` are *banded* (half-bandwidth 3). A dense solve ignores this and pays ``O(n^3)`` per contact
position; here every position of a batch is handled at once, vectorised over the batch:

1. the band of ``A = K + s M`` is assembled (``s > 0``, the shift of :mod:`~ebantenna.fem.modal`),
   every held DOF (the hinge's deflection, its rotation when clamped, a rigid contact) decoupled
   instead of removed, so that all positions share one layout: its row and column of ``K``
   reduced to the diagonal, of ``M`` to zero, it carries the eigenvalue ``mu = 0`` and nothing
   else;
2. ``A = L L^T`` by a banded Cholesky factorisation, ``O(n)`` per position; ``L`` is block lower
   bidiagonal in the 2 x 2 blocks of the nodes, so the triangular solves go node by node;
3. Lanczos for the largest eigenvalues ``mu = 1 / (omega^2 + s)`` of ``C = L^-1 M L^-T`` (the
   lowest modes), each step two triangular solves and a banded product, ``O(n)``; the
   ``mu`` of a beam fall off like ``j^-4``, so about a dozen steps reach the residual bound
   ``1e-14`` (B. N. Parlett, *The Symmetric Eigenvalue Problem*, SIAM, 1998, ch. 13);
   A batch of one position (a root search sweeps one at a time) runs steps 2 and 3's node loops
   on Python floats instead: the same IEEE operations in the same order, bit for bit, without
   NumPy's cost per call on arrays of one element (about three times faster per sweep);
4. the frequencies are the Rayleigh quotients of the Ritz vectors, the strain energy summed from
   the element curvatures (:func:`~ebantenna.fem.modal.bending_energy`): good to about
   ``1e-12``, like :func:`~ebantenna.fem.modal.modal_analysis`, where ``1/mu - s`` alone carries
   a rounding bounded by ``eps omega_max^2 / omega^2`` (5e-7 at 64 elements with the contact at
   0.2 L; 6e-10 measured there).

:func:`~ebantenna.fem.sweeps.natural_frequencies` calls this by default.
"""

from __future__ import annotations

import math

import numpy as np

from ..probe import Probe
from ._assembly_engine import mass_polynomial, stiffness_polynomial
from .guards import check_sweep
from .modal import bending_energy

__all__ = ["banded_sweep", "sweep_meshes"]

_BAND = 3  # half-bandwidth of a chain of Hermite beam elements in the (v, theta) numbering
_TOLERANCE = 1e-14
#: Most Lanczos steps per batch, and the most modes the banded sweep is asked for (a quarter:
#: Ritz values converge in a few times n_modes steps).
MAX_LANCZOS_STEPS = 200
BANDED_MAX_MODES = MAX_LANCZOS_STEPS // 4


def sweep_meshes(length: float, contacts: np.ndarray, n_elements: int):
    """Node positions of :func:`~ebantenna.fem.assembly.beam_mesh` for many contacts at once.

    Returns ``(nodes, contact_node)``: arrays of shape ``(n, n_elements + 1)`` (m) and ``(n,)``.
    """
    from .._validate import check_array, check_positive
    from .guards import MIN_SPAN, check_resolvable

    length = check_positive("length", length)
    n_elements = check_resolvable(n_elements)
    contacts = check_array("contacts", contacts, ndim=1)
    if np.any((contacts < MIN_SPAN * length) | (contacts > (1 - MIN_SPAN) * length)):
        raise ValueError(f"contacts must lie in the probe, {MIN_SPAN:g} of its length from "
                         f"either end (0 < contact < {length:g} m)")
    n1 = np.clip(np.round(n_elements * contacts / length).astype(int), 1, n_elements - 1)
    k = np.arange(n_elements + 1)
    c = contacts[:, None]
    n1c = n1[:, None]
    span = k * (c / n1c)  # as np.linspace computes its points
    overhang = c + (k - n1c) * ((length - c) / (n_elements - n1c))
    nodes = np.where(k <= n1c, span, overhang)
    nodes[np.arange(contacts.size), n1] = contacts
    nodes[:, -1] = length
    return nodes, n1


def _band(element_matrices: np.ndarray, in_span: np.ndarray) -> np.ndarray:
    """Lower band of the assembled matrix, shape (B, 4, n): ``out[:, d, i] = A[i, i - d]``.

    ``element_matrices`` (B, 2, 4, 4) are those of the span's and of the overhang's elements,
    ``in_span`` (B, n_elements) says which elements belong to the span.
    """
    B, ne = in_span.shape
    out = np.zeros((B, _BAND + 1, 2 * ne + 2))
    for a in range(4):
        for b in range(a + 1):  # element e puts its (a, b) entry at row 2 e + a
            span, overhang = element_matrices[:, 0, a, b, None], element_matrices[:, 1, a, b, None]
            out[:, a - b, a : a + 2 * ne : 2] += np.where(in_span, span, overhang)
    return out


def _cholesky(A: np.ndarray) -> np.ndarray:
    """Banded Cholesky ``A = L L^T`` of a stack of bands (B, 4, n); returns L's band, same layout.

    Row ``i`` of ``L`` holds ``L[i, i-3 .. i]``; it needs only the three rows above it.
    """
    B, _, n = A.shape
    if B == 1:
        return _cholesky_one(A[0])[:, :, None]
    # rows padded by three rows of the identity above and three zero rows below
    L = np.zeros((n + 2 * _BAND, _BAND + 1, B))
    L[:_BAND, 0] = 1.0
    Ad = np.ascontiguousarray(np.transpose(A, (2, 1, 0)))  # (n, 4, B)
    for i in range(n):
        r = i + _BAND
        for d in range(_BAND, 0, -1):  # L[i, i-d], from the left
            j = r - d
            s = Ad[i, d].copy()
            for q in range(d + 1, _BAND + 1):  # k = i - q, shared by rows i and j = i - d
                s -= L[r, q] * L[j, q - d]
            L[r, d] = s / L[j, 0]
        s = Ad[i, 0] - L[r, 1] ** 2 - L[r, 2] ** 2 - L[r, 3] ** 2
        L[r, 0] = np.sqrt(s)
    return L


def _cholesky_one(A: np.ndarray) -> np.ndarray:
    """:func:`_cholesky` of one band (4, n), on Python floats: the same IEEE operations in the
    same order, so the same bits, without NumPy's cost per call on arrays of one element (a
    root search sweeps one position at a time). Returns L's band (n + 6, 4)."""
    n = A.shape[1]
    Ad = A.T.tolist()  # Ad[i][d] = A[i, i - d]
    L = [[1.0, 0.0, 0.0, 0.0] for _ in range(_BAND)]
    for i in range(n):
        row = [0.0] * (_BAND + 1)
        for d in range(_BAND, 0, -1):  # L[i, i-d], from the left
            above = L[i + _BAND - d]
            s = Ad[i][d]
            for q in range(d + 1, _BAND + 1):
                s -= row[q] * above[q - d]
            row[d] = s / above[0] if above[0] else float(np.float64(s) / above[0])
        # the squares as products, as NumPy's ``** 2`` computes them
        s = Ad[i][0] - row[1] * row[1] - row[2] * row[2] - row[3] * row[3]
        row[0] = math.sqrt(s) if not s < 0 else float(np.sqrt(np.float64(s)))
        L.append(row)
    return np.array(L + [[0.0] * (_BAND + 1)] * _BAND)


def _node_blocks(L: np.ndarray):
    """The band of ``L`` regrouped by node: ``L`` is block lower bidiagonal in 2 x 2 blocks.

    Row ``2k`` (the deflection of node ``k``) and ``2k + 1`` (its rotation) reach back to node
    ``k - 1`` only (``L[2k, 2k - 3]`` belongs to node ``k - 2`` and is zero: those nodes share no
    element, and a banded Cholesky fills nothing outside the band). Returns the inverses of the
    diagonal blocks and the blocks below them, each (n_nodes, 2, 2, B); for a batch of one, each
    as nested lists (n_nodes, 2, 2) of floats, read by the float path of the solves.
    """
    Lr = L[_BAND:-_BAND]  # (n, 4, B): Lr[i, d] = L[i, i - d]
    v, t = Lr[0::2], Lr[1::2]  # rows of deflections and of rotations, (n_nodes, 4, B)
    a, c, b = v[:, 0], t[:, 1], t[:, 0]  # diagonal block [[a, 0], [c, b]]
    inv = np.zeros((v.shape[0], 2, 2) + v.shape[2:])
    inv[:, 0, 0], inv[:, 1, 1], inv[:, 1, 0] = 1 / a, 1 / b, -c / (a * b)
    below = np.zeros_like(inv)  # columns 2k - 2, 2k - 1
    below[:, 0, 0], below[:, 0, 1], below[:, 1, 0], below[:, 1, 1] = (
        v[:, 2],
        v[:, 1],
        t[:, 3],
        t[:, 2],
    )
    if inv.shape[-1] == 1:  # a batch of one: the blocks as the float path reads them, once
        return inv[..., 0].tolist(), below[..., 0].tolist()
    return inv, below


def _forward(L, x: np.ndarray) -> np.ndarray:
    """``L^-1 x`` for x of shape (n, B): forward substitution, node by node."""
    inv, below = L
    if isinstance(inv, list):  # a batch of one (see _node_blocks)
        return _forward_one(inv, below, x[:, 0].tolist())
    x = x.reshape(inv.shape[0], 2, -1)
    z = np.empty_like(x)
    z[0] = (inv[0] * x[0]).sum(1)
    for k in range(1, x.shape[0]):
        z[k] = (inv[k] * (x[k] - (below[k] * z[k - 1]).sum(1))).sum(1)
    return z.reshape(-1, x.shape[-1])


def _backward(L, x: np.ndarray) -> np.ndarray:
    """``L^-T x`` for x of shape (n, B): back substitution, node by node."""
    inv, below = L
    if isinstance(inv, list):  # a batch of one (see _node_blocks)
        return _backward_one(inv, below, x[:, 0].tolist())
    x = x.reshape(inv.shape[0], 2, -1)
    z = np.empty_like(x)
    z[-1] = (inv[-1] * x[-1][:, None]).sum(0)
    for k in range(x.shape[0] - 2, -1, -1):
        z[k] = (inv[k] * (x[k] - (below[k + 1] * z[k + 1][:, None]).sum(0))[:, None]).sum(0)
    return z.reshape(-1, x.shape[-1])


def _forward_one(inv, below, x) -> np.ndarray:
    """:func:`_forward` of a batch of one, on Python floats (``inv``, ``below``: the node
    blocks as nested lists, ``x`` a list), the same operations in the same order: a sum over
    the block's two columns is ``(0 + a) + b``, as NumPy's reduction starts from its identity.
    Only products, sums and differences: IEEE arithmetic, bit for bit."""
    z = []
    (a, b), (c, d) = inv[0]
    z0, z1 = 0.0 + a * x[0] + b * x[1], 0.0 + c * x[0] + d * x[1]
    z += [z0, z1]
    for k in range(1, len(inv)):
        (a, b), (c, d) = inv[k]
        (e, f), (g, h) = below[k]
        r0 = x[2 * k] - (0.0 + e * z0 + f * z1)
        r1 = x[2 * k + 1] - (0.0 + g * z0 + h * z1)
        z0, z1 = 0.0 + a * r0 + b * r1, 0.0 + c * r0 + d * r1
        z += [z0, z1]
    return np.array(z)[:, None]


def _backward_one(inv, below, x) -> np.ndarray:
    """:func:`_backward` of a batch of one, on Python floats, as :func:`_forward_one`."""
    n = len(inv)
    z = [0.0] * (2 * n)
    (a, b), (c, d) = inv[-1]
    z0, z1 = 0.0 + a * x[-2] + c * x[-1], 0.0 + b * x[-2] + d * x[-1]
    z[-2:] = z0, z1
    for k in range(n - 2, -1, -1):
        (a, b), (c, d) = inv[k]
        (e, f), (g, h) = below[k + 1]
        r0 = x[2 * k] - (0.0 + e * z0 + g * z1)
        r1 = x[2 * k + 1] - (0.0 + f * z0 + h * z1)
        z0, z1 = 0.0 + a * r0 + c * r1, 0.0 + b * r0 + d * r1
        z[2 * k], z[2 * k + 1] = z0, z1
    return np.array(z)[:, None]


def _matvec(band: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Symmetric band (4, n, B), ``band[d, i] = A[i, i - d]``, times vectors x (n, B)."""
    y = band[0] * x
    for d in range(1, _BAND + 1):
        y[d:] += band[d, d:] * x[:-d]
        y[:-d] += band[d, d:] * x[d:]
    return y


def banded_sweep(
    probe: Probe,
    contacts: np.ndarray,
    *,
    hinge_stiffness: float,
    contact_stiffness: float,
    n_elements: int,
    n_modes: int,
    shift: float,
) -> np.ndarray:
    """Lowest ``n_modes`` eigenvalues ``omega^2`` (1/s^2) for each contact, shape (n, n_modes).

    Inputs are trusted (the public entry is :func:`~ebantenna.fem.sweeps.natural_frequencies`).
    ``hinge_stiffness`` is inf for a clamped hinge, 0 for a pinned one, N m/rad for a spring;
    ``contact_stiffness`` inf for a rigid contact, N/m for a spring.
    """
    contacts, n_elements, n_modes = check_sweep(probe, contacts, hinge_stiffness,
                                                contact_stiffness, n_elements, n_modes, shift)
    B = contacts.size
    # Two uniform spans per position (see sweep_meshes): two element lengths, two matrices.
    _, c_node = sweep_meshes(probe.length, contacts, n_elements)
    lengths = np.stack([contacts / c_node, (probe.length - contacts) / (n_elements - c_node)], 1)
    in_span = np.arange(n_elements) < c_node[:, None]
    h = np.where(in_span, lengths[:, :1], lengths[:, 1:])  # (B, n_elements)
    K = _band(stiffness_polynomial(probe.flexural_rigidity, lengths), in_span)
    M = _band(mass_polynomial(probe.mass_per_length, lengths), in_span)
    rows = np.arange(B)
    v_c = 2 * c_node
    held = [np.zeros(B, dtype=int)]  # the hinge never moves sideways
    if math.isinf(hinge_stiffness):
        held.append(np.ones(B, dtype=int))
    else:
        K[:, 0, 1] += hinge_stiffness
    if math.isinf(contact_stiffness):
        held.append(v_c)
    else:
        K[rows, 0, v_c] += contact_stiffness
    M[:, 0, -2] += probe.tip_mass
    for dof in held:  # decouple each held DOF: mu = 0 there, nothing else
        size = K.shape[2]
        for A in (K, M):
            A[rows, 1:, dof] = 0.0  # its row: A[dof, dof - d]
            for d in range(1, _BAND + 1):  # its column: A[dof + d, dof]
                A[rows, d, np.minimum(dof + d, size - 1)] *= dof + d >= size
        M[rows, 0, dof] = 0.0  # K keeps its diagonal there, so A stays definite
    free = np.ones((B, K.shape[2]))
    for dof in held:
        free[rows, dof] = 0.0
    A = K + shift * M
    L = _node_blocks(_cholesky(A))
    Mb = np.ascontiguousarray(np.transpose(M, (1, 2, 0)))  # (4, n, B): one diagonal each
    _, y = _lanczos(L, Mb, n_modes, free)
    # Rayleigh quotients of the mode shapes phi = L^-T y, the strain energy summed from element
    # curvatures (modal.bending_energy): the Ritz values themselves carry the rounding of
    # 1 / mu - s and of K phi, about eps * omega_max^2 / omega^2; the quotient, stationary at an
    # eigenvector, does not.
    lam = np.empty((B, n_modes))
    for j in range(n_modes):
        phi = _backward(L, y[j]) * free.T  # held DOFs exactly still
        mass = np.einsum("nb,nb->b", phi, _matvec(Mb, phi))
        lam[:, j] = bending_energy(probe.flexural_rigidity, h.T, phi, check_finite=False) / mass
        if not math.isinf(hinge_stiffness):
            lam[:, j] += hinge_stiffness * phi[1] ** 2 / mass
        if not math.isinf(contact_stiffness):
            lam[:, j] += contact_stiffness * phi[v_c, rows] ** 2 / mass
    return np.sort(lam, axis=1)


def _lanczos(L, Mb, n_modes, free):
    """Largest ``n_modes`` eigenpairs of ``C = L^-1 M L^-T`` for each band of a batch.

    Returns the Ritz values, shape (B, n_modes), and Ritz vectors, shape (n_modes, n, B).

    Lanczos with full reorthogonalisation (one Gram-Schmidt pass per step) from one fixed start
    vector. The error of a Ritz value
    ``theta_j`` is bounded by its residual ``r_j = beta_k |s_kj|`` (``s_kj`` the last component
    of its eigenvector of the tridiagonal ``T_k``), and by ``r_j^2 / gap_j`` once the residual is
    below the gap to the other eigenvalues (Kato-Temple; the gap estimated from the next Ritz
    value): the loop stops once that bound is below ``1e-14 theta_j`` for every retained value of
    every position. The Lanczos vectors are stored step by step, ``(step, n, B)``, so that every
    operation runs over the whole batch at once and the memory grows with the steps taken.
    """
    n, B = Mb.shape[1], Mb.shape[2]
    steps = min(n, MAX_LANCZOS_STEPS)
    first_check = min(2 * n_modes + 2, steps)  # Ritz values seldom converge sooner
    basis = np.empty((min(steps, 4 * first_check) + 1, n, B))  # grown below if need be
    q = np.random.default_rng(0).standard_normal(n)[:, None] * free.T  # nothing on a held DOF
    basis[0] = q / np.linalg.norm(q, axis=0)
    alpha = np.zeros((B, steps))
    beta = np.zeros((B, steps))
    for k in range(steps):
        if k + 1 == basis.shape[0]:
            basis = np.concatenate([basis, np.empty_like(basis)])[: steps + 1]
        w = _forward(L, _matvec(Mb, _backward(L, basis[k])))
        alpha[:, k] = np.einsum("nb,nb->b", basis[k], w)
        done = basis[: k + 1]  # reorthogonalise against every earlier vector, batch-wide
        before = np.linalg.norm(w, axis=0)
        w -= np.einsum("kb,knb->nb", np.einsum("knb,nb->kb", done, w), done)
        norm = np.linalg.norm(w, axis=0)
        if np.any(norm < 0.7 * before):
            # Much of w cancelled: one Gram-Schmidt pass leaves components along the basis of
            # about eps |w_before| / |w|, so a second pass follows ("twice is enough": Kahan's
            # criterion, B. N. Parlett, The Symmetric Eigenvalue Problem, 1998, section 6.9).
            w -= np.einsum("kb,knb->nb", np.einsum("knb,nb->kb", done, w), done)
            norm = np.linalg.norm(w, axis=0)
        # A Krylov space that is already invariant (a small mesh) ends here: beta = 0 and the
        # next vector is zero, which adds nothing to the tridiagonal matrix.
        alive = norm > 1e-13 * np.abs(alpha[:, : k + 1]).max(axis=1)
        beta[:, k] = np.where(alive, norm, 0.0)
        basis[k + 1] = np.where(alive, w / np.where(alive, norm, 1.0), 0.0)
        m = k + 1
        if m < steps and (m < first_check or (m - first_check) % 2):  # check every other step
            continue
        T = np.zeros((B, m, m))
        idx = np.arange(m)
        T[:, idx, idx] = alpha[:, :m]
        T[:, idx[:-1], idx[1:]] = T[:, idx[1:], idx[:-1]] = beta[:, : m - 1]
        theta, S = np.linalg.eigh(T)
        theta, S = theta[:, ::-1], S[:, :, ::-1]
        r = beta[:, k, None] * np.abs(S[:, -1, :n_modes])
        gap = np.abs(theta[:, :n_modes] - theta[:, 1 : n_modes + 1])
        bound = np.where(r < gap, np.minimum(r, r**2 / np.where(r < gap, gap, 1.0)), r)
        # converged, or the whole space spanned (then the Ritz pairs are the eigenpairs)
        if np.all(bound <= _TOLERANCE * theta[:, :n_modes]) or m == n:
            ritz = np.einsum("bkj,knb->jnb", S[:, :, :n_modes], basis[:m])  # (j, n, B)
            return theta[:, :n_modes], ritz
    raise np.linalg.LinAlgError(
        f"Lanczos did not converge to {n_modes} modes in {steps} steps; "
        "ask for fewer modes or use method='dense'"
    )
