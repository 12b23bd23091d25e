"""The touched object as a beam: a solid round rod held in a stand."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .._validate import check_in_range, check_range
from ..probe import SIZE_RANGE, Material, Probe, material

__all__ = ["Rod"]


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
        Diameter, m. Default 12 mm: an assumption, the paper gives no geometry.
    free_length : float
        Length above the clamp of the stand, m. Default 250 mm: an assumption, as above.
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
    diameter: float = 0.012
    free_length: float = 0.25
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
