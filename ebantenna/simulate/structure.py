"""A linear structure with one contact point, as the contact dynamics take it.

:class:`ContactCase` holds what every model of the touched rod starts from: the two bodies,
their reductions at the contact and the contact spring. :class:`ContactModel` holds the mass,
stiffness and damping matrices in some generalised coordinates and the three vectors that say
where the contact point, the servo's rigid motion and the accelerometer are in them;
:func:`probe_contact_model` builds it for the probe from the FEM.
:func:`.unilateral.unilateral_response` and :func:`.friction_ode.coulomb_response` take these
matrices and vectors (or any others of the same meaning).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as spl

from .._validate import check_int, check_nonnegative
from ..fem.guards import check_contact
from ..probe import Probe

__all__ = ["ContactModel", "ContactCase", "probe_contact_model", "check_dof_vector",
           "check_symmetric_matrix", "check_case"]


@dataclass(frozen=True, eq=False)
class ContactModel:
    """A linear structure with one contact point, ready for :func:`.unilateral.unilateral_response`.

    Attributes
    ----------
    mass, stiffness, damping : ndarray of shape (n, n)
        In the model's generalised coordinates (kg, N/m and N s/m for physical ones).
    contact : ndarray of shape (n,)
        Displacement of the contact point toward the object per unit coordinate.
    base : ndarray of shape (n,)
        The servo's rigid motion per metre of travel at the contact point.
    output : ndarray of shape (n,)
        Displacement at the accelerometer per unit coordinate.
    """

    mass: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    contact: np.ndarray
    base: np.ndarray
    output: np.ndarray


def check_dof_vector(name: str, value, n: int) -> np.ndarray:
    """A DOF index (as a unit vector) or a finite vector of length ``n``; raise otherwise."""
    if isinstance(value, int | np.integer) and not isinstance(value, bool):
        i = check_int(name, value, minimum=-n, maximum=n - 1)
        out = np.zeros(n)
        out[i] = 1.0
        return out
    out = np.asarray(value, dtype=float)
    if out.shape != (n,) or not np.all(np.isfinite(out)):
        raise ValueError(f"{name} must be a DOF index or a finite vector of length {n}")
    return out


def check_symmetric_matrix(name: str, value, n: int | None = None) -> np.ndarray:
    """A finite, symmetric square matrix (of size ``n`` when given); raise otherwise."""
    out = np.atleast_2d(np.asarray(value, dtype=float))
    if out.ndim != 2 or out.shape[0] != out.shape[1] or (n is not None and out.shape[0] != n):
        size = "square" if n is None else f"{n} x {n}"
        raise ValueError(f"{name} must be a {size} matrix, got shape {out.shape}")
    if not np.all(np.isfinite(out)):
        raise ValueError(f"{name} must be finite")
    # np.allclose(out, out.T, rtol=1e-10, atol=0) on a finite matrix, without its temporaries
    # (a quarter of the time): a strike's set-up checks six of its matrices
    if not np.all(np.abs(out - out.T) <= 1e-10 * np.abs(out.T)):
        raise ValueError(f"{name} must be symmetric")
    return out



@dataclass(frozen=True, eq=False)
class ContactCase:
    """One distinct (contact position, material, preload) of a batch on a rod (``object_modes``).

    What every model of the touched rod needs: the bodies, their Craig-Bampton reductions and
    the contact spring. Built by the simulator from checked values
    (:func:`ebantenna.simulate.touched_object.object_modes`), and handed to each model of
    :data:`~ebantenna.simulate.touched_object.OBJECT_MODELS`.

    Attributes
    ----------
    scene : ebantenna.simulate.Scene
        The scene simulated.
    probe : Probe
        The probe (without its loss factor unless ``structural_damping`` is listed).
    contact : float
        Contact position from the hinge, m.
    material : str
        Canonical name of the touched material.
    preload : float
        The contact's static force, N.
    rod : Rod
        The touched rod.
    probe_reduction, rod_reduction : ebantenna.fem.coupling.CraigBampton
        The two bodies reduced at the contact (:func:`ebantenna.fem.coupling.craig_bampton`).
    stiffness : float
        The contact spring under ``preload``, N/m.
    loss_factor : float
        The contact's loss factor (dimensionless).
    """

    scene: object
    probe: Probe
    contact: float
    material: str
    preload: float
    rod: object
    probe_reduction: object
    rod_reduction: object
    stiffness: float
    loss_factor: float


def check_case(case) -> None:
    """Raise a ``TypeError`` unless ``case`` is a :class:`ContactCase`."""
    if not isinstance(case, ContactCase):
        raise TypeError(f"case must be a ContactCase (the touched object's contact case), got "
                        f"{type(case).__name__}")


def probe_contact_model(
    probe,
    contact: float,
    *,
    hinge="clamped",
    n_elements: int = 64,
    n_modes: int = 8,
    damping_ratio: float = 0.0,
) -> ContactModel:
    """The probe reduced to its free modes and the attachment mode, for the contact dynamics.

    The basis is the probe's first ``n_modes`` modes without contact plus the static deflection
    under a unit force at the contact (the attachment mode, which carries the contact spring's
    local deformation: R. R. Craig and A. J. Kurdila, *Fundamentals of Structural Dynamics*, 2nd
    ed., Wiley, 2006, section 17.4). Both contact states use the same basis, so a switch loses
    nothing, and the static flexibility at the contact (hence the preload) is exact.

    Parameters
    ----------
    probe : Probe
        The probe (with its tip mass).
    contact : float
        Contact position from the hinge, m, in (0, L).
    hinge : {"clamped", "pinned"} or float
        As in :class:`ebantenna.fem.Supports`; "pinned" leaves a rigid rotation (then only
        ``preload=0`` is possible).
    n_elements, n_modes : int
        FEM mesh and number of free modes kept.
    damping_ratio : float
        Modal damping ratio of every mode of the reduced free probe, in [0, 1); e.g. the
        probe's ``loss_factor / 2``.

    Examples
    --------
    >>> from ebantenna.probe import Probe
    >>> model = probe_contact_model(Probe(), 0.2, n_elements=16, n_modes=4)
    >>> model.mass.shape
    (5, 5)
    >>> model.contact.shape, model.output.shape
    ((5,), (5,))
    """
    from ..probe import Probe

    if not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
    from ..fem import Supports
    from ..fem.assembly import apply_supports, assemble, beam_mesh, contact_node

    n_modes = check_int("n_modes", n_modes, minimum=1)
    zeta = check_nonnegative("damping_ratio", damping_ratio)
    if not zeta < 1:
        raise ValueError(f"damping_ratio must lie in [0, 1), got {damping_ratio!r}")
    contact = check_contact("contact", contact, probe.length)
    supports = Supports(contact=None, hinge=hinge)
    nodes = beam_mesh(probe.length, contact, n_elements)
    K, M = assemble(nodes, probe)
    Kf, Mf, free = apply_supports(K, M, nodes, probe, supports)
    nf = free.size
    # The free probe's modes on a mesh with a node at the contact (dense: a few hundred DOFs).
    _, phi = spl.eigh(Kf, Mf, subset_by_index=[0, min(n_modes, nf - 1) - 1])
    ci = int(np.searchsorted(free, 2 * contact_node(nodes, contact)))
    unit = np.zeros(nf)
    unit[ci] = 1.0
    if hinge == "pinned":
        # Attachment under a unit force with the rigid rotation removed: K is singular there.
        attach = np.linalg.lstsq(Kf, unit - Mf @ phi @ (phi.T @ unit), rcond=None)[0]
    else:
        attach = np.linalg.solve(Kf, unit)
    T = np.column_stack([phi, attach])
    # Orthonormalise the basis in the mass metric (keeps the reduced matrices well conditioned).
    Mr, Kr = T.T @ Mf @ T, T.T @ Kf @ T
    w2, Psi = spl.eigh(Kr, Mr)
    T = T @ Psi
    Mr = T.T @ Mf @ T
    Kr = T.T @ Kf @ T
    Mr, Kr = (Mr + Mr.T) / 2, (Kr + Kr.T) / 2
    omega = np.sqrt(np.clip(w2, 0, None))
    Cr = Mr @ np.diag(2 * zeta * omega) @ Mr  # mass-normalised basis: C = M Psi 2 zeta w Psi^T M
    x_free = nodes[free // 2]
    rigid = np.where(free % 2 == 0, x_free, 1.0) / contact  # rotation about the hinge
    base = np.linalg.solve(Mr, T.T @ Mf @ rigid)
    tip = int(np.searchsorted(free, 2 * (nodes.size - 1)))
    return ContactModel(Mr, Kr, (Cr + Cr.T) / 2, T[ci].copy(), base, T[tip].copy())
