"""The contact's force law in the strike: crossed-cylinder Hertz in series with the tube wall.

:class:`HertzContact` replaces the strike's contact spring, linearised at the preload, by the
whole law ``p(F) = delta_H(1 N) F^(2/3) + F / k_ring``
(:class:`~ebantenna.simulate.contact.HertzInSeries`; K. L. Johnson, *Contact Mechanics*, 1985,
section 4.2, and Roark's ring, as in :mod:`ebantenna.simulate.contact`), replaced by chords
within a proven force bound and integrated exactly between the chords' nodes
(:class:`~ebantenna.simulate.unilateral.HertzStrikeLaw`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from ..._validate import check_positive
from ..contact import PiecewiseSpring, tube_on_rod_law
from ._base import Effect, check_bodies


@dataclass(frozen=True)
class HertzContact(Effect):
    """The strike's contact follows the Hertz law, not its tangent at the preload.

    Without this effect the strike (``unilateral_contact``) pushes through the spring linearised
    at the preload. A strike that lifts off and strikes again takes the force through zero, away
    from the preload, where the Hertz contact is softer (near zero force its stiffness falls to
    zero as ``F^(1/3)``) and stiffer (above the preload) than the tangent. With it, the force
    law is the crossed cylinders' Hertz law in series with the tube wall's ring spring, as chords
    that differ from it by at most ``force_tolerance`` up to ``max_force`` (and are exact at the
    preload, so the static contact is the linear one's). Requires ``unilateral_contact``.

    Parameters
    ----------
    force_tolerance : float
        Most the chords' force may differ from the law, N (> 0). The default, 0.01 N, is 2 % of
        the ``paper`` scene's preload.
    max_force : float
        The force up to which the bound holds, N (> 0); above it the last chord continues (a
        strike that goes beyond is counted and warned of). The default, 20 times the ``paper``
        scene's preload, lies above its strikes' peaks (0.6 to 4.3 N over the five materials
        and the probe's length, the metals' highest near the tip); the stiffest chord sets the
        time step, so a higher one costs time.

    Examples
    --------
    >>> from ebantenna.probe import Probe, material
    >>> spring = HertzContact().spring(material("steel"), Probe(), 0.012, 0.5)
    >>> spring.bound <= 0.01, spring.slopes.size
    (True, 10)
    """

    name: ClassVar[str] = "hertz_contact"
    force_tolerance: float = 0.01
    max_force: float = 10.0

    def __post_init__(self):
        check_positive("force_tolerance", self.force_tolerance)
        check_positive("max_force", self.max_force)

    def spring(self, obj, probe, diameter: float, preload: float) -> PiecewiseSpring:
        """The chords of the tube's contact on a rod of ``obj`` and ``diameter`` (m), with a
        node at ``preload`` (N)."""
        check_bodies(obj, probe)
        preload = check_positive("preload", preload)
        law = tube_on_rod_law(probe, obj, diameter)
        return law.piecewise(self.force_tolerance, self.max_force, through=(preload,))
