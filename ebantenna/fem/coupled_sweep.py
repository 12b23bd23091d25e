"""Coupled modes of probe and rod over contact positions x touched rods, reductions shared.

A data set with object modes asks for the coupled modes of every contact position with every
touched material. Component-mode synthesis (:mod:`~ebantenna.fem.coupling`) makes this cheap when
the reductions are shared: each rod is reduced once for all positions, the probe once per position
for all rods, and what is left per pair is the small coupled eigenproblem of the two reduced
bodies (``probe_modes + rod_modes + 2`` coordinates). Positions run side by side on the machine's
cores (LAPACK releases the GIL).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import check_array, check_int, real_array
from ..probe import Probe
from ._parallel import map_on_cores
from .coupling import Rod, coupled_modes, craig_bampton, probe_substructure, rod_substructure
from .guards import check_contact, check_resolvable

__all__ = ["CoupledSweep", "coupled_sweep"]


@dataclass(frozen=True, eq=False)
class CoupledSweep:
    """Coupled frequencies and damping for every rod and contact position.

    Attributes
    ----------
    rods : tuple of Rod
    contacts : ndarray of shape (n_contacts,)
        Contact positions along the probe, m from the hinge.
    frequencies : ndarray of shape (n_rods, n_contacts, n_modes)
        Undamped coupled natural frequencies, Hz.
    damping_ratio : ndarray of shape (n_rods, n_contacts, n_modes)
        Their equivalent viscous damping ratios (see :mod:`~ebantenna.fem.coupling`).
    tip_displacement : ndarray of shape (n_rods, n_contacts, n_modes)
        The probe tip's deflection in each mass-normalised mode, m per unit modal coordinate.
    """

    rods: tuple
    contacts: np.ndarray
    frequencies: np.ndarray
    damping_ratio: np.ndarray
    tip_displacement: np.ndarray


def coupled_sweep(
    probe: Probe,
    rods,
    contacts,
    contact_stiffness,
    *,
    hinge="clamped",
    n_modes: int = 6,
    n_elements: int = 64,
    rod_elements: int = 32,
    probe_modes: int = 40,
    rod_modes: int = 20,
    contact_loss_factor: float = 0.0,
) -> CoupledSweep:
    """Coupled modes of the probe touching each rod at each contact position.

    Parameters
    ----------
    probe : Probe
    rods : sequence of Rod
        The touched objects.
    contacts : array of shape (n_contacts,)
        Contact positions along the probe, m from the hinge, each in ``(0, L)``.
    contact_stiffness : float or array of shape (n_rods,) or (n_rods, n_contacts)
        Contact spring, N/m, in ``[0, inf]`` (per rod, e.g. each material's Hertz stiffness, or
        per rod and position).
    hinge, n_modes, n_elements, rod_elements, probe_modes, rod_modes, contact_loss_factor
        As in :func:`~ebantenna.fem.coupling.coupled_modes`.

    Returns
    -------
    CoupledSweep

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna import Probe
    >>> from ebantenna.fem.coupling import Rod
    >>> from ebantenna.fem.coupled_sweep import coupled_sweep
    >>> rods = [Rod("steel"), Rod("pvc")]
    >>> sweep = coupled_sweep(Probe(), rods, np.array([0.1, 0.2]), 2e5, n_modes=2)
    >>> sweep.frequencies.shape
    (2, 2, 2)
    >>> sweep.frequencies[1, 1].round(1)  # pvc rod, contact at 0.2 m
    array([23. , 62.1])
    """
    if not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
    rods = _check_rods(rods)
    contacts = check_array("contacts", contacts, ndim=1)
    for contact in contacts:  # checked here, so that the error names the caller's parameters
        check_contact("contacts", float(contact), probe.length)
    n_modes = check_int("n_modes", n_modes, minimum=1)
    k_c = _stiffness_table(contact_stiffness, len(rods), contacts.size)
    rod_elements = check_resolvable(rod_elements, "rod_elements")
    reduced_rods = [
        _reduced(rod_substructure(rod, n_elements=rod_elements), rod_modes, "rod_modes")
        for rod in rods
    ]

    def one_position(j):
        sub = probe_substructure(probe, float(contacts[j]), hinge=hinge, n_elements=n_elements)
        p = _reduced(sub, probe_modes, "probe_modes")
        out = []
        for i, (rod, r) in enumerate(zip(rods, reduced_rods, strict=True)):
            res = coupled_modes(
                probe,
                rod,
                float(contacts[j]),
                float(k_c[i, j]),
                n_modes=n_modes,
                contact_loss_factor=contact_loss_factor,
                rod_reduction=r,
                probe_reduction=p,
            )
            out.append((res.frequencies, res.damping_ratio, res.tip_displacement))
        return out

    results = map_on_cores(one_position, range(contacts.size))
    shape = (len(rods), contacts.size, n_modes)
    f, z, tip = (np.empty(shape) for _ in range(3))
    for j, per_rod in enumerate(results):
        for i, (fi, zi, ti) in enumerate(per_rod):
            f[i, j], z[i, j], tip[i, j] = fi, zi, ti
    return CoupledSweep(rods, contacts, f, z, tip)


def _reduced(sub, kept, name: str):
    """:func:`~ebantenna.fem.coupling.craig_bampton` of ``sub`` keeping ``kept`` modes, checked
    under the caller's ``name`` (at most the substructure's interior DOFs, its size less one)."""
    return craig_bampton(sub, check_int(name, kept, minimum=0, maximum=sub.stiffness.shape[0] - 1))


def _check_rods(rods) -> tuple:
    """The rods as a tuple of at least one :class:`~ebantenna.fem.coupling.Rod`."""
    if isinstance(rods, Rod) or not hasattr(rods, "__iter__"):
        raise TypeError(f"rods must be a sequence of Rod objects, got {type(rods).__name__}")
    rods = tuple(rods)
    for rod in rods:
        if not isinstance(rod, Rod):
            raise TypeError(f"rods must hold Rod objects, got {type(rod).__name__}")
    if not rods:
        raise ValueError("rods must hold at least one Rod, got none")
    return rods


def _stiffness_table(contact_stiffness, n_rods: int, n_contacts: int) -> np.ndarray:
    """The contact stiffness (N/m) per rod and position, shape ``(n_rods, n_contacts)``.

    A number holds for all, an array of shape ``(n_rods,)`` per rod, ``(n_rods, n_contacts)``
    per rod and position.
    """
    k_c = real_array("contact_stiffness", contact_stiffness)
    if k_c.ndim == 1:
        k_c = k_c[:, None]
    try:
        return np.broadcast_to(k_c, (n_rods, n_contacts))
    except ValueError:
        raise ValueError(
            f"contact_stiffness must be a number or of shape ({n_rods},) or "
            f"({n_rods}, {n_contacts}), got shape {np.shape(contact_stiffness)}"
        ) from None
