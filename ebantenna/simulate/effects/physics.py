"""Effects of the probe and the contact: they change the modal parameters.

:class:`StructuralDamping`, :class:`ContactCompliance`, :class:`ContactDamping`, :class:`TipMass`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..._validate import check_in_range, check_positive
from ...probe import Material, Probe
from ._base import _Effect

#: The accelerometer board at the tip: an MPU6050 breakout (GY-521), kg. Estimate: FR-4 board
#: 20 x 15.5 x 1.6 mm at 1850 kg/m^3 (0.9 g), 8-pin header (0.6 g), chip and parts (0.3 g), plus
#: 0.7 g of solder, glue and wire ends at the tip; 2.5 g, within the 2-3 g that hobby vendors list.
GY521_MASS = 2.5e-3



@dataclass(frozen=True)
class StructuralDamping(_Effect):
    """Hysteretic (material) damping of the tube, as modal damping.

    A material with loss factor ``eta`` loses ``2 pi eta`` of its strain energy per cycle. Near a
    resonance this equals viscous damping with ratio ``zeta = eta / 2`` (Cremer, Heckl and
    Petersson, *Structure-Borne Sound*, 3rd ed., 2005, section 3.3), applied to every mode. The
    loss factor is the probe's :attr:`~ebantenna.probe.Probe.loss_factor` (PMMA: 0.03).

    Examples
    --------
    >>> from ebantenna.probe import Probe
    >>> StructuralDamping().damping_ratio(Probe())
    0.015
    """

    name: ClassVar[str] = "structural_damping"

    def damping_ratio(self, probe: Probe) -> float:
        """Modal damping ratio ``eta / 2`` of every mode (dimensionless)."""
        return probe.loss_factor / 2


@dataclass(frozen=True)
class ContactCompliance(_Effect):
    """Compliance of the contact between the tube and the object (Hertz), by material.

    The tube's side touches the object in a point; with the crossed-cylinder approximation this is
    a sphere of the tube's outer radius ``R`` on a flat. Hertz's law ``F = 4/3 E* sqrt(R) d^(3/2)``
    linearised at the preload ``F0`` gives the contact stiffness

        k = dF/dd = (6 F0 E*^2 R)^(1/3),   1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2

    (K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, eqs. 4.22-4.23). The
    contact is much stiffer than the beam except right at the hinge (about 1e5-1e6 N/m), so it
    lowers the natural frequencies only slightly. The simulator puts this spring in place of the
    rigid pin in the FEM model (:class:`ebantenna.fem.Supports` ``contact_stiffness``), one solve
    per contact position and material.
    The ring (ovalisation) compliance of the tube wall is neglected here, and the object is taken
    as flat; :func:`ebantenna.simulate.contact.tube_on_rod_stiffness` models the tube crossing a
    round rod with the wall's ring compliance in series (for a 12 mm steel rod about 2.8 times
    softer than this sphere-on-flat value) and is the model the touched-rod physics builds on.

    Parameters
    ----------
    preload : float
        Contact force the linearisation is taken at, N. Default 0.5 N: an assumption (the stopped
        servo keeps the probe pressed on the object; the MG996R's stall torque, about 1 N m, could
        press up to several newtons at 0.2 m).
    probe_poisson_ratio : float
        Poisson's ratio of the tube, dimensionless. Default 0.39: PMMA, 0.38-0.40 in M. F. Ashby,
        *Materials Selection in Mechanical Design*, 4th ed., 2011, appendix C.

    Examples
    --------
    >>> from ebantenna.probe import Probe, material
    >>> k = ContactCompliance().stiffness(material("steel"), Probe())
    >>> round(k / 1e5, 2)  # N/m
    5.26
    """

    name: ClassVar[str] = "contact_compliance"
    preload: float = 0.5
    probe_poisson_ratio: float = 0.39

    def __post_init__(self):
        check_positive("preload", self.preload)
        check_in_range("probe_poisson_ratio", self.probe_poisson_ratio, -1.0, 0.5)

    def effective_modulus(self, obj: Material, probe: Probe) -> float:
        """Hertz's contact modulus ``E*`` of tube and object, Pa."""
        return 1.0 / (
            (1 - self.probe_poisson_ratio**2) / probe.youngs_modulus
            + (1 - obj.poisson_ratio**2) / obj.youngs_modulus
        )

    def stiffness(self, obj: Material, probe: Probe) -> float:
        """Linearised Hertz contact stiffness ``k``, N/m."""
        radius = probe.outer_diameter / 2
        return (6 * self.preload * self.effective_modulus(obj, probe) ** 2 * radius) ** (1 / 3)

    def loss_factor(self, obj: Material, probe: Probe) -> float:
        """Loss factor of the contact spring (dimensionless).

        The Hertz compliance is the sum of the two bodies' shares ``(1 - nu_i^2) / E_i``; each share
        loses energy with its own material loss factor, so the spring's loss factor is their
        compliance-weighted mean.
        """
        c_probe = (1 - self.probe_poisson_ratio**2) / probe.youngs_modulus
        c_obj = (1 - obj.poisson_ratio**2) / obj.youngs_modulus
        return (c_probe * probe.loss_factor + c_obj * obj.loss_factor) / (c_probe + c_obj)


@dataclass(frozen=True)
class ContactDamping(_Effect):
    """Energy the vibrating probe loses into the touched object, by material.

    The object is modelled as a large plate of thickness ``h`` touched normal to its face. The
    drive-point impedance of an infinite thin plate is real, a pure dashpot
    ``Z = 8 sqrt(B' m'')`` with bending stiffness ``B' = E h^3 / (12 (1 - nu^2))`` and mass per area
    ``m'' = rho h`` (Cremer, Heckl and Petersson, *Structure-Borne Sound*, 3rd ed., 2005, section
    5.3.1): bending waves carry the energy away. In series with it sits the Hertz spring of
    :class:`ContactCompliance` with its hysteretic loss factor. The contact's complex compliance at
    circular frequency ``omega`` is ``C = 1 / (k (1 + i eta_c)) + 1 / (i omega Z)``. A
    mass-normalised
    mode whose contact force per unit modal coordinate is ``F_k`` loses ``pi F_k^2 (-Im C)`` per
    cycle of its energy ``omega_k^2 / 2``, hence the damping ratio (modal strain energy method,
    valid while the contact holds a small share of the mode's energy, a few per cent here)

        zeta_k = F_k^2 (-Im C(omega_k)) / (2 omega_k^2).

    Soft, light objects (wood, PVC) have a low impedance and take more energy than metals. The
    plate's own loss factor does not enter (an infinite plate radiates everything). Requires
    :class:`ContactCompliance`, the element through which the energy flows.

    Parameters
    ----------
    object_thickness : float
        Thickness ``h`` of the touched object, m. Default 10 mm: an assumption (the paper does not
        describe the objects).

    Examples
    --------
    >>> from ebantenna.probe import material
    >>> round(ContactDamping().plate_impedance(material("steel")))  # N s/m
    9680
    """

    name: ClassVar[str] = "contact_damping"
    object_thickness: float = 0.01

    def __post_init__(self):
        check_positive("object_thickness", self.object_thickness)

    def plate_impedance(self, obj: Material) -> float:
        """Drive-point impedance ``Z = 8 sqrt(B' m'')`` of the object (infinite plate), N s/m."""
        h = self.object_thickness
        bending = obj.youngs_modulus * h**3 / (12 * (1 - obj.poisson_ratio**2))
        return 8 * math.sqrt(bending * obj.density * h)

    def loss_compliance(self, omega, obj: Material, probe: Probe, compliance: ContactCompliance):
        """``-Im C(omega)``, the dissipative part of the contact compliance, m/N.

        ``omega`` (rad/s) may be an array.
        """
        k = compliance.stiffness(obj, probe)
        eta = compliance.loss_factor(obj, probe)
        omega = np.asarray(omega, dtype=float)
        return eta / (k * (1 + eta**2)) + 1.0 / (omega * self.plate_impedance(obj))


@dataclass(frozen=True)
class TipMass(_Effect):
    """The accelerometer board at the free tip, as a point mass in the FEM model.

    The mass itself is the probe's :attr:`~ebantenna.probe.Probe.tip_mass`; a scene lists this
    effect exactly when its probe carries one, so that the list of effects says everything the
    simulator computes. The ``paper`` scene uses :data:`GY521_MASS` (2.5 g, an MPU6050 breakout
    with its pin header, solder and wire ends). With it, the lowest mode changes character near
    0.8 L (the paper's Fig. 16). Its rotary inertia and the wires along the tube are neglected.
    """

    name: ClassVar[str] = "tip_mass"
