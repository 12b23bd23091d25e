"""Natural frequencies for many contact positions at once: the contact sweeps.

A study of where the probe is touched asks for the lowest frequencies at hundreds of contact
positions. :func:`~ebantenna.fem.modal.modal_analysis` solves one position; looping it over the
positions is the reference, ``method="reference"``, the answer every engine is held to. The
engines solve a whole array of positions as a batch, with no Python loop per position:

- ``"banded"`` (default, :mod:`~ebantenna.fem.banded`): the matrices of a chain of beam elements
  are banded, so each position costs a banded Cholesky factorisation and a few Lanczos steps,
  ``O(n)``, then the Rayleigh quotients from the element curvatures; as accurate as
  :func:`~ebantenna.fem.modal.modal_analysis`;
- ``"dense"``: the dense inverted solve of :func:`~ebantenna.fem.modal.solve_modes` with batched
  LAPACK calls, ``O(n^3)`` per position (:func:`dense_sweep`), without the Rayleigh quotients'
  refinement: a mode far below the mesh's highest (a soft spring's on a fine mesh) is known
  only to the solve's rounding, of the order ``eps omega_max^2``;
- ``"secular"`` (:mod:`~ebantenna.fem.secular`): one modal analysis without the contact, then
  the roots of a secular equation per position.

Batches of ``chunk`` positions run side by side on the machine's cores. The inputs are checked
here, once; the engines take them as given.
"""

from __future__ import annotations

import math
import os

import numpy as np

from .._validate import check_array, check_choice, check_int
from ..probe import Probe
from ._assembly_engine import mass_polynomial, scatter, stiffness_polynomial
from ._parallel import map_on_cores
from ._rounding import floored, rounding
from .assembly import Supports, beam_mesh, free_dofs, support_diagonals
from .banded import BANDED_MAX_MODES, MAX_LANCZOS_STEPS, banded_sweep
from .guards import check_contact, check_memory, check_resolvable
from .modal import clip_eigenvalues, eigenvalue_shift, modal_analysis
from .secular import secular_sweep

__all__ = ["natural_frequencies", "SWEEP_METHODS", "reference_sweep", "dense_sweep"]

#: Methods of :func:`natural_frequencies`.
SWEEP_METHODS = ("banded", "dense", "secular", "reference")

#: Positions per batch by default: small enough for the cache, spread over the cores (the
#: reference solves one position at a time).
_DEFAULT_CHUNK = {"banded": 256, "dense": 125, "secular": 1024, "reference": 1}

#: Memory per position of a batch, bytes, as a function of ``(n_elements, n_modes)``.
_BYTES_PER_POSITION = {
    "dense": lambda n_elements, n_modes: 32 * (2 * n_elements) ** 2,
    "banded": lambda n_elements, n_modes: 600 * n_elements,
    "secular": lambda n_elements, n_modes: 100 * n_modes * n_elements,
}


def natural_frequencies(
    probe: Probe,
    contacts,
    *,
    hinge="clamped",
    contact_stiffness: float = math.inf,
    n_elements: int = 64,
    n_modes: int = 3,
    chunk: int | None = None,
    method: str = "banded",
) -> np.ndarray:
    """Natural frequencies for many contact positions at once, Hz.

    ``"reference"`` is the textbook: one :func:`~ebantenna.fem.modal.modal_analysis` per
    position (the generalized eigen-solve on the mesh with a node at the contact), in a plain
    loop. All positions share one mesh topology (``n_elements`` elements), so the engines solve
    them as a batch, with no Python loop per position, and are held to the reference by the
    tests (``"secular"`` where the contact is a node of its uniform mesh, see below):

    - ``"banded"`` (default): a banded Cholesky factorisation of ``K + s M`` per position, Lanczos
      for the lowest modes, then Rayleigh quotients from the element curvatures, all vectorised
      over the batch (:mod:`~ebantenna.fem.banded`); as accurate as
      :func:`~ebantenna.fem.modal.modal_analysis`;
    - ``"dense"``: the dense inverted solve of :func:`~ebantenna.fem.modal.solve_modes` with
      batched LAPACK calls, ``O(n^3)`` per position and without the final Rayleigh quotients
      (:func:`dense_sweep`);
    - ``"secular"``: one modal analysis without the contact on a *fixed* uniform mesh, then the
      roots of the secular equation of the rank-one contact per position
      (:mod:`~ebantenna.fem.secular`), several times faster. A different model: the contact
      falls inside an element instead of on a node put there, with the compliance the mesh
      misses there added in series (its static correction); the same model where the contact
      is a node of the uniform mesh, and as accurate elsewhere (``ebantenna bench`` shows both
      against the exact solution);
    - ``"reference"``: the loop of :func:`~ebantenna.fem.modal.modal_analysis`, which checks
      its own memory; slow (a Python loop and a full solve per position), for reading and for
      testing the engines.

    Parameters
    ----------
    probe : Probe
    contacts : array of shape (n,)
        Contact positions from the hinge, m, each in ``(0, L)``.
    hinge, contact_stiffness
        As in :class:`~ebantenna.fem.assembly.Supports`.
    n_elements, n_modes : int
        Mesh size and number of modes.
    chunk : int, optional
        Positions solved per batch: default 125 dense, 256 banded, 1024 secular (memory about
        ``chunk * (2 n_elements)^2 * 32`` bytes dense, ``chunk * n_elements * 600`` banded,
        ``chunk * n_modes * n_elements * 100`` secular); not used by ``"reference"``.
    method : {"banded", "dense", "secular", "reference"}
        See above.

    Returns
    -------
    ndarray of shape (n, n_modes)

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna import Probe
    >>> from ebantenna.fem import natural_frequencies
    >>> natural_frequencies(Probe(), np.array([0.1, 0.2]), n_modes=2).round(2)
    array([[ 21.35, 137.77],
           [ 38.97, 243.51]])
    """
    if not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
    contacts = check_array("contacts", contacts, ndim=1)
    check_choice("method", method, SWEEP_METHODS)
    chunk = check_int("chunk", _DEFAULT_CHUNK[method] if chunk is None else chunk, minimum=1)
    n_elements = check_resolvable(check_int("n_elements", n_elements, minimum=2))
    n_modes = _check_n_modes(n_modes, n_elements, method)
    if method != "reference":  # modal_analysis checks the memory of its own solve
        _check_batch_memory(method, contacts.size, chunk, n_elements, n_modes)
    supports = Supports(contact=None, hinge=hinge, contact_stiffness=contact_stiffness)
    for contact in (contacts.min(), contacts.max()):  # the two nearest the ends
        check_contact("contacts", contact, probe.length)
    if method == "reference":
        return reference_sweep(probe, contacts, supports, n_elements, n_modes)
    sweep = dict(
        hinge_stiffness=supports.hinge_stiffness,
        contact_stiffness=supports.contact_stiffness,
        n_elements=n_elements,
        n_modes=n_modes,
    )
    if method == "secular":  # one modal analysis, then every position side by side
        return _hertz(probe, secular_sweep(probe, contacts, chunk=chunk, **sweep))
    blocks = [contacts[i : i + chunk] for i in range(0, contacts.size, chunk)]
    if method == "banded":
        shift = eigenvalue_shift(probe)

        def solve(block):
            with np.errstate(invalid="ignore", divide="ignore"):  # NaN is refused below
                return _hertz(probe, banded_sweep(probe, block, shift=shift, **sweep))

    else:

        def solve(block):
            return dense_sweep(probe, block, supports, n_elements, n_modes)

    frequencies = np.concatenate(map_on_cores(solve, blocks))  # batches side by side
    _check_resolved(frequencies, probe, contacts, n_elements)
    return frequencies


def _check_n_modes(n_modes, n_elements: int, method: str) -> int:
    """``n_modes`` as an int the mesh has, and that Lanczos reaches with ``method="banded"``."""
    n_modes = check_int("n_modes", n_modes, minimum=1, maximum=2 * n_elements - 1)
    if method == "banded" and n_modes > BANDED_MAX_MODES:
        raise ValueError(
            f"n_modes must be <= {BANDED_MAX_MODES} with method='banded' (Lanczos converges in "
            f"a few times n_modes steps, at most {MAX_LANCZOS_STEPS}); got {n_modes}: use "
            "method='dense' for that many modes"
        )
    return n_modes


def _check_batch_memory(method: str, n_positions: int, chunk: int, n_elements: int, n_modes: int):
    """Refuse a sweep whose batches, one per core at a time, would not fit in memory."""
    per_batch = min(chunk, n_positions)
    batch = per_batch * min(os.cpu_count() or 1, -(-n_positions // chunk))
    check_memory(
        batch * _BYTES_PER_POSITION[method](n_elements, n_modes),
        f"natural_frequencies(method={method!r}) with {n_elements} elements and batches of "
        f"{per_batch} positions (pass a smaller chunk, or method='banded')",
        "chunk",
    )


def _hertz(probe: Probe, lam: np.ndarray) -> np.ndarray:
    """Eigenvalues ``omega^2`` (1/s^2) as frequencies, Hz."""
    return np.sqrt(clip_eigenvalues(lam, eigenvalue_shift(probe))) / (2 * math.pi)


def _check_resolved(frequencies: np.ndarray, probe: Probe, contacts: np.ndarray, n_elements: int):
    """Raise if a frequency came out NaN: a mode the mesh cannot resolve at that position.

    A contact near an end on a coarse mesh leaves one tiny element beside long ones: its own
    modes lie some 1e16 (1 / eps) above the lowest, beyond what Lanczos resolves.
    """
    if np.all(np.isfinite(frequencies)):
        return
    i, k = np.argwhere(~np.isfinite(frequencies))[0]
    h = np.diff(beam_mesh(probe.length, float(contacts[i]), n_elements))
    raise ValueError(
        f"mode {k + 1} at contacts[{i}] = {float(contacts[i])!r} m cannot be resolved with "
        f"n_elements={n_elements}: the elements differ in length by a factor of "
        f"{h.max() / h.min():.1e}; use more elements or fewer modes"
    )


def reference_sweep(
    probe: Probe, contacts: np.ndarray, supports: Supports, n_elements: int, n_modes: int
) -> np.ndarray:
    """Lowest ``n_modes`` frequencies (Hz) at each contact, one modal analysis each, (n, n_modes).

    The reference of every sweep: for each position, the mesh with a node at the contact and the
    generalized eigen-solve of :func:`~ebantenna.fem.modal.modal_analysis`. Inputs are trusted
    (the public entry is :func:`natural_frequencies`); ``supports`` gives the hinge and the
    contact's stiffness, its ``contact`` is replaced by each of ``contacts``.
    """
    _check_bodies(probe, supports)
    hinge, stiffness = supports.hinge, supports.contact_stiffness
    return np.array([
        modal_analysis(probe, Supports(float(c), hinge=hinge, contact_stiffness=stiffness),
                       n_elements=n_elements, n_modes=n_modes).frequencies
        for c in contacts
    ])


def _check_bodies(probe, supports) -> None:
    """Refuse a ``probe`` that is not a Probe or ``supports`` that are not Supports."""
    if not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
    if not isinstance(supports, Supports):
        raise TypeError(f"supports must be a Supports, got {type(supports).__name__}")


def dense_sweep(
    probe: Probe, contacts: np.ndarray, supports: Supports, n_elements: int, n_modes: int
) -> np.ndarray:
    """Lowest ``n_modes`` frequencies (Hz) at each contact by batched dense solves, (n, n_modes).

    The inverted solve of :func:`~ebantenna.fem.modal.solve_modes`, one LAPACK call for the whole
    batch: ``K + s M = L L^T``, the eigenpairs of ``L^-1 M L^-T``, ``omega^2 = 1/mu - s``, floored
    at zero within the rounding bound of that solve (the eigenvectors give it).
    Inputs are trusted (the public entry is :func:`natural_frequencies`); ``supports`` gives the
    hinge and the contact's stiffness, its ``contact`` is replaced by each of ``contacts``.
    """
    _check_bodies(probe, supports)
    hinge, stiffness = supports.hinge, supports.contact_stiffness
    members = [Supports(float(c), hinge=hinge, contact_stiffness=stiffness) for c in contacts]
    meshes = np.stack([beam_mesh(probe.length, s.contact, n_elements) for s in members])
    pairs = list(zip(meshes, members, strict=True))
    K = scatter(stiffness_polynomial(probe.flexural_rigidity, np.diff(meshes, axis=1)))  # (B,n,n)
    M = scatter(mass_polynomial(probe.mass_per_length, np.diff(meshes, axis=1)))
    diagonals = [support_diagonals(m, probe, s) for m, s in pairs]
    d = np.arange(K.shape[-1])
    K[:, d, d] += np.array([k for k, _ in diagonals])
    M[:, d, d] += np.array([m for _, m in diagonals])
    # Every member has the same number of free DOFs; only which v is fixed at the contact moves.
    keep = np.array([free_dofs(m, s) for m, s in pairs])
    rows = np.arange(len(pairs))[:, None, None]
    K = K[rows, keep[:, :, None], keep[:, None, :]]
    M = M[rows, keep[:, :, None], keep[:, None, :]]
    shift = eigenvalue_shift(probe)
    A = K + shift * M
    L = np.linalg.cholesky(A)
    X = np.linalg.solve(L, M)
    Bm = np.linalg.solve(L, np.swapaxes(X, 1, 2))  # L^-1 M L^-T
    mu, Y = np.linalg.eigh((Bm + np.swapaxes(Bm, 1, 2)) / 2)
    mu, Y = mu[:, ::-1][:, :n_modes], Y[:, :, ::-1][:, :, :n_modes]
    phi = np.linalg.solve(np.swapaxes(L, 1, 2), Y) / np.sqrt(mu)[:, None, :]
    lam = 1.0 / mu - shift
    # floored where rounding may leave a (nearly) rigid mode below zero, the bound of the
    # single solve (``fem/_rounding.py``), member by member
    lam = np.stack([floored(lam[b], rounding(A[b], shift, lam[b], phi[b]))
                    for b in range(lam.shape[0])])
    return np.sqrt(lam) / (2 * math.pi)
