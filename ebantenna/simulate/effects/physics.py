"""Effects of the probe and the contact: they change the modal parameters.

:class:`StructuralDamping`, :class:`ContactCompliance`, :class:`TipMass`. The touched object's own
modes and damping are in :mod:`.objects`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from ..._validate import check_in_range, check_positive
from ...probe import Material, Probe
from ..contact import PRELOAD, TUBE_POISSON_RATIO
from ._base import Effect, check_bodies

#: The accelerometer board at the tip: an MPU6050 breakout (GY-521), kg. Estimate: FR-4 board
#: 20 x 15.5 x 1.6 mm at 1850 kg/m^3 (0.9 g), 8-pin header (0.6 g), chip and parts (0.3 g), plus
#: 0.7 g of solder, glue and wire ends at the tip; 2.5 g, within the 2-3 g that hobby vendors list.
GY521_MASS = 2.5e-3


@dataclass(frozen=True)
class StructuralDamping(Effect):
    """Hysteretic (material) damping of the tube, as modal damping.

    A material with loss factor ``eta`` loses ``2 pi eta`` of its strain energy per cycle. Near a
    resonance this equals viscous damping with ratio ``zeta = eta / 2`` (Cremer, Heckl and
    Petersson, *Structure-Borne Sound*, 3rd ed., 2005, section 3.3), applied to every mode. The
    loss factor is the probe's ``loss_factor`` (:class:`~ebantenna.probe.Probe`) (PMMA: 0.03).

    Examples
    --------
    >>> from ebantenna.probe import Probe
    >>> StructuralDamping().damping_ratio(Probe())
    0.015
    """

    name: ClassVar[str] = "structural_damping"

    def damping_ratio(self, probe: Probe) -> float:
        """Modal damping ratio ``eta / 2`` of every mode (dimensionless)."""
        check_bodies(probe=probe)
        return probe.loss_factor / 2


@dataclass(frozen=True)
class ContactCompliance(Effect):
    """Compliance of the contact between the tube and the object (Hertz), by material.

    The tube's side touches the object in a point; with the crossed-cylinder approximation this is
    a sphere of the tube's outer radius ``R`` on a flat. Hertz's law ``F = 4/3 E* sqrt(R) d^(3/2)``
    linearised at the preload ``F0`` gives the contact stiffness

        k = dF/dd = (6 F0 E*^2 R)^(1/3),   1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2

    (K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, eqs. 4.22-4.23). The
    object's modulus ``E2`` is its material's ``transverse_modulus``, the modulus across the rod's
    axis: a wooden rod is indented across its grain (1.48 GPa for oak, not the 12.5 GPa along
    it), the assumption of :mod:`ebantenna.simulate.contact` and of :class:`~.objects.ObjectModes`,
    stated there with its source; for the isotropic materials it is their one modulus. The
    contact is much stiffer than the beam except right at the hinge (about 1e5-1e6 N/m), so it
    lowers the natural frequencies only slightly. The simulator puts this spring in place of the
    rigid pin in the FEM model (:class:`ebantenna.fem.Supports` ``contact_stiffness``), one solve
    per contact position and material.
    The ring (ovalisation) compliance of the tube wall is neglected here, and the object is taken
    as flat; :func:`ebantenna.simulate.contact.tube_on_rod_stiffness` models the tube crossing a
    round rod with the wall's ring compliance in series (for a 12 mm steel rod about 2.8 times
    softer than this sphere-on-flat value), the spring of :class:`~.objects.ObjectModes`.

    Parameters
    ----------
    preload : float
        Contact force the linearisation is taken at, N. Default
        :data:`~ebantenna.simulate.contact.PRELOAD` (0.5 N), an assumption.
    probe_poisson_ratio : float
        Poisson's ratio of the tube, dimensionless. Default
        :data:`~ebantenna.simulate.contact.TUBE_POISSON_RATIO` (0.39, PMMA).

    Examples
    --------
    >>> from ebantenna.probe import Probe, material
    >>> k = ContactCompliance().stiffness(material("steel"), Probe())
    >>> round(k / 1e5, 2)  # N/m
    5.26
    """

    name: ClassVar[str] = "contact_compliance"
    preload: float = PRELOAD
    probe_poisson_ratio: float = TUBE_POISSON_RATIO

    def __post_init__(self):
        check_positive("preload", self.preload)
        check_in_range("probe_poisson_ratio", self.probe_poisson_ratio, -1.0, 0.5)

    def effective_modulus(self, obj: Material, probe: Probe) -> float:
        """Hertz's contact modulus ``E*`` of tube and object (the object's modulus across the
        rod's axis, ``transverse_modulus``), Pa."""
        check_bodies(obj, probe)
        return 1.0 / (
            (1 - self.probe_poisson_ratio**2) / probe.youngs_modulus
            + (1 - obj.poisson_ratio**2) / obj.transverse_modulus
        )

    def stiffness(self, obj: Material, probe: Probe) -> float:
        """Linearised Hertz contact stiffness ``k``, N/m."""
        check_bodies(obj, probe)
        radius = probe.outer_diameter / 2
        return (6 * self.preload * self.effective_modulus(obj, probe) ** 2 * radius) ** (1 / 3)


@dataclass(frozen=True)
class TipMass(Effect):
    """The accelerometer board at the free tip, as a point mass in the FEM model.

    The mass itself is the probe's ``tip_mass`` (:class:`~ebantenna.probe.Probe`); a scene lists
    this effect exactly when its probe carries one, so that the list of effects says everything the
    simulator computes. The ``paper`` scene uses :data:`GY521_MASS` (2.5 g, an MPU6050 breakout
    with its pin header, solder and wire ends). Its rotary inertia and the wires along the tube
    are neglected.

    The tip mass moves the lowest mode's change of character (its zones,
    :func:`~ebantenna.fem.dominant_mode_zones`, clamped hinge, 64 elements, on a grid of 0.001 L)
    outwards: zone 2 begins at 0.741 L instead of the bare tube's 0.654 L, the lowest frequency
    peaks at 0.884 L instead of 0.783 L, and zone 3 begins at 0.911 L instead of 0.832 L. The
    paper finds the mode "entirely changed at the 80 % of the total antenna length" (its Fig. 16)
    and its distance data leave a straight line at 29.5 cm of the 40 cm probe (0.74 L): the bare
    tube's peak lies nearer both than the simulated probe's (35.4 cm), whose zone 2 begins near
    that 0.74 L.
    """

    name: ClassVar[str] = "tip_mass"
