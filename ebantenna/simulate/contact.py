"""Contact stiffness of the probe's tube on a round rod: Hertz, tube wall, wood across the grain.

The probe (a tube of outer radius ``R1``) crosses the touched rod (radius ``R2``) at right angles.
Three compliances act in series at the contact point:

1. **Hertz contact of crossed cylinders** (K. L. Johnson, *Contact Mechanics*, Cambridge University
   Press, 1985, section 4.2). The gap between two cylinders crossed at right angles is
   ``h = A x^2 + B y^2`` with ``A = 1/(2 max(R1, R2))`` and ``B = 1/(2 min(R1, R2))``; the contact
   area is an ellipse of semi-axes ``a >= b`` and eccentricity ``e = sqrt(1 - b^2/a^2)``, found from

       B/A = ((a/b)^2 E(e) - K(e)) / (K(e) - E(e))                            (Johnson 4.39)

   with ``K``, ``E`` the complete elliptic integrals. Then (Johnson 3.63-3.64, 4.38)

       a^3 (b/a)^2 = 3 P E(e) / (2 pi (A + B) E*),   delta = 3 P K(e) / (2 pi a E*),

   so the approach ``delta`` grows as ``P^(2/3)`` and the stiffness linearised at a preload ``F0``
   is ``k = dP/d delta = 3 F0 / (2 delta(F0))``. For equal radii (``A = B``) the contact is a
   circle and the law is exactly that of a sphere of radius ``R`` on a flat,
   ``P = 4/3 E* sqrt(R) delta^(3/2)``, ``k = (6 F0 E*^2 R)^(1/3)`` (Johnson 4.22-4.23).
   As ``R2`` grows the ellipse elongates without bound and the stiffness grows without bound
   too: a cylinder on a flat is a *line* contact, whose approach depends on the contact length,
   not a point contact. Sphere-on-flat is the equal-radius case, not the flat-rod limit.

2. **The tube wall** (ovalisation). The rod pinches the thin-walled tube locally. Modelled as a
   ring of the tube's mean radius ``Rm``, wall ``t`` and axial width ``w`` under two equal and
   opposite diametral point loads ``P`` (W. C. Young, R. G. Budynas, *Roark's Formulas for Stress
   and Strain*, 7th ed., McGraw-Hill, 2002, table 9.2 case 1, with its corrections for hoop
   stretch ``alpha = I/(A Rm^2)`` and shear ``beta = F E I/(G A Rm^2)``, ``F = 1.2``):

       Delta D = (P Rm^3 / (E I)) (K1 pi/4 - 2 K2^2 / pi),
       K1 = 1 - alpha + beta,  K2 = 1 - alpha,  I = w t^3 / 12.

   *Assumption*: the slice of tube that works as the ring is one outer diameter long
   (``w = 2 R1``), and the far side of the ring is held as by a second point load. The real tube
   spreads the load over a longer length and is held by shear around its whole circumference,
   so this is an upper estimate of the wall's compliance (a lower estimate of its stiffness).

3. **Wood across the grain.** A wooden rod (a dowel) has its grain along its axis, so the tube
   indents it *across* the grain. The contact modulus of this orthotropic body is approximated
   by the isotropic Hertz formula with the modulus across the grain, taken as the geometric mean
   of the radial and tangential moduli (the growth-ring orientation at the touched spot is
   random). Ratios for red oak at 12 % moisture: ``E_R/E_L = 0.154``, ``E_T/E_L = 0.082``
   (USDA Forest Products Laboratory, *Wood Handbook*, FPL-GTR-282, 2021, table 5-1; same values
   in FPL-GTR-190, 2010). The fibres lying in the surface stiffen the indentation somewhat, so
   this rule errs on the soft side; the longitudinal modulus would overestimate the stiffness
   about nine-fold.

All quantities are SI: m, N, Pa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from numbers import Real

import numpy as np
import scipy.optimize as spo
import scipy.special as spsp

from .._validate import check_in_range, check_positive

__all__ = [
    "RED_OAK_RADIAL_RATIO",
    "RED_OAK_TANGENTIAL_RATIO",
    "TUBE_POISSON_RATIO",
    "contact_modulus",
    "across_grain_modulus",
    "CrossedCylinders",
    "ring_stiffness",
    "ContactStiffness",
    "tube_on_rod_stiffness",
]

#: Red oak, 12 % moisture: E_R / E_L (Wood Handbook FPL-GTR-282, 2021, table 5-1).
RED_OAK_RADIAL_RATIO = 0.154
#: Red oak, 12 % moisture: E_T / E_L (Wood Handbook FPL-GTR-282, 2021, table 5-1).
RED_OAK_TANGENTIAL_RATIO = 0.082
#: Poisson's ratio of PMMA, 0.38-0.40 (M. F. Ashby, *Materials Selection in Mechanical Design*,
#: 4th ed., 2011, appendix C); the value the simulator's contact effect uses.
TUBE_POISSON_RATIO = 0.39
#: Shear correction factor of a rectangular section (Roark, 7th ed., table 9.2 notes).
_SHEAR_FACTOR = 1.2
#: Below this relative difference of the two curvatures the contact is treated as circular; the
#: approach then differs from the elliptical solution by less than its square (1e-18, relative).
_CIRCULAR = 1e-9


def _elastic(name: str, body, poisson_ratio) -> tuple[float, float]:
    """(E, nu) of a body given as a Material-like object or as E plus ``poisson_ratio``."""
    if isinstance(body, Real) and not isinstance(body, bool):
        if poisson_ratio is None:
            raise TypeError(f"{name}: give poisson_ratio with a plain Young's modulus")
        E, nu = body, poisson_ratio
    elif hasattr(body, "youngs_modulus") and hasattr(body, "poisson_ratio"):
        E, nu = body.youngs_modulus, body.poisson_ratio if poisson_ratio is None else poisson_ratio
    else:
        raise TypeError(
            f"{name} must be a Material (youngs_modulus, poisson_ratio) or a number, "
            f"got {type(body).__name__}"
        )
    E = check_positive(f"{name} Young's modulus", E)
    nu = check_in_range(f"{name} Poisson's ratio", nu, -1.0, 0.5)
    return E, nu


def contact_modulus(body1, body2, *, poisson_ratio1=None, poisson_ratio2=None) -> float:
    """Hertz's contact modulus ``E*`` of two bodies, Pa.

    ``1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2`` (Johnson, *Contact Mechanics*, 1985, eq. 4.22).

    Parameters
    ----------
    body1, body2 : Material or float
        Each a :class:`~ebantenna.probe.Material` (or anything with ``youngs_modulus`` and
        ``poisson_ratio``) or a Young's modulus in Pa (then give its Poisson's ratio).
    poisson_ratio1, poisson_ratio2 : float, optional
        Poisson's ratios in (-1, 0.5); override the body's own when given.

    Examples
    --------
    >>> round(contact_modulus(3.0e9, 205e9, poisson_ratio1=0.39, poisson_ratio2=0.29) / 1e9, 4)
    3.4831
    """
    E1, nu1 = _elastic("body1", body1, poisson_ratio1)
    E2, nu2 = _elastic("body2", body2, poisson_ratio2)
    return 1.0 / ((1 - nu1**2) / E1 + (1 - nu2**2) / E2)


def across_grain_modulus(
    longitudinal_modulus: float,
    *,
    radial_ratio: float = RED_OAK_RADIAL_RATIO,
    tangential_ratio: float = RED_OAK_TANGENTIAL_RATIO,
) -> float:
    """Modulus of wood across the grain for indentation of a dowel's side, Pa.

    The geometric mean ``E_L sqrt((E_R/E_L)(E_T/E_L))`` of the radial and tangential moduli
    (see the module notes for the rule and its source).

    Parameters
    ----------
    longitudinal_modulus : float
        ``E_L``, along the grain, Pa (> 0).
    radial_ratio, tangential_ratio : float
        ``E_R/E_L`` and ``E_T/E_L`` in (0, 1]; defaults: red oak, Wood Handbook table 5-1.

    Examples
    --------
    >>> round(across_grain_modulus(12.5e9) / 1e9, 3)  # red oak, GPa
    1.405
    """
    EL = check_positive("longitudinal_modulus", longitudinal_modulus)
    r = check_in_range("radial_ratio", radial_ratio, 0.0, 1.0, high_inclusive=True)
    s = check_in_range("tangential_ratio", tangential_ratio, 0.0, 1.0, high_inclusive=True)
    return EL * math.sqrt(r * s)


def _ratio_of_curvatures(p: float) -> float:
    """``B/A`` of an elliptical Hertz contact with axis ratio squared ``p = (b/a)^2``, 0 < p < 1."""
    m = 1.0 - p
    K, E = spsp.ellipkm1(p), spsp.ellipe(m)
    return (E / p - K) / (K - E)


@dataclass(frozen=True)
class CrossedCylinders:
    """Hertz contact of two cylinders crossed at right angles.

    Parameters
    ----------
    radius1, radius2 : float
        Radii of the two cylinders, m (> 0).
    modulus : float
        Contact modulus ``E*``, Pa (> 0); see :func:`contact_modulus`.

    Attributes
    ----------
    axis_ratio : float
        ``b/a`` of the contact ellipse (1 for equal radii); independent of the load.

    Examples
    --------
    >>> hz = CrossedCylinders(0.004, 0.006, 3.5e9)
    >>> round(hz.axis_ratio, 4)
    0.7633
    >>> round(hz.stiffness(0.5) / 1e5, 3)  # N/m at a 0.5 N preload
    5.659
    >>> round(hz.force(hz.approach(0.5)), 12)  # N
    0.5
    """

    radius1: float
    radius2: float
    modulus: float

    def __post_init__(self):
        check_positive("radius1", self.radius1)
        check_positive("radius2", self.radius2)
        check_positive("modulus", self.modulus)
        A = 1 / (2 * max(self.radius1, self.radius2))
        B = 1 / (2 * min(self.radius1, self.radius2))
        if B / A - 1 <= _CIRCULAR:
            p = 1.0
        else:
            # B/A rises from 1 (p -> 1) to infinity (p -> 0); solve in log p for a wide bracket.
            target = B / A
            p = math.exp(
                spo.brentq(
                    lambda s: _ratio_of_curvatures(math.exp(s)) - target,
                    -700.0,
                    math.log1p(-1e-12),
                    xtol=1e-15,
                    rtol=4 * np.finfo(float).eps,
                )
            )
        object.__setattr__(self, "_p", p)
        object.__setattr__(self, "_sum", A + B)

    @property
    def axis_ratio(self) -> float:
        """``b/a`` of the contact ellipse, dimensionless."""
        return math.sqrt(self._p)

    def semi_axes(self, force: float) -> tuple[float, float]:
        """Semi-axes ``(a, b)`` of the contact ellipse under the normal force ``force`` (N), m."""
        P = check_positive("force", force)
        E = float(spsp.ellipe(1.0 - self._p))
        a = (3 * P * E / (2 * math.pi * self._sum * self.modulus * self._p)) ** (1 / 3)
        return a, a * math.sqrt(self._p)

    def approach(self, force: float) -> float:
        """Approach ``delta`` of distant points of the two bodies under ``force`` (N), m."""
        a, _ = self.semi_axes(force)
        K = float(spsp.ellipkm1(self._p))
        return 3 * float(force) * K / (2 * math.pi * a * self.modulus)

    def force(self, approach) -> np.ndarray | float:
        """Normal force for an approach ``delta`` (m; 0 where ``delta <= 0``: no tension), N."""
        d = np.asarray(approach, dtype=float)
        scale = self.approach(1.0)  # delta at 1 N; P = (delta / scale)^(3/2)
        out = np.where(d > 0, np.abs(d) / scale, 0.0) ** 1.5
        return float(out) if out.ndim == 0 else out

    def stiffness(self, preload: float) -> float:
        """Contact stiffness ``dP/d delta`` linearised at the preload ``F0`` (N, > 0), N/m."""
        F0 = check_positive("preload", preload)
        return 1.5 * F0 / self.approach(F0)


def ring_stiffness(
    outer_diameter: float,
    inner_diameter: float,
    youngs_modulus: float,
    poisson_ratio: float = TUBE_POISSON_RATIO,
    *,
    width: float | None = None,
) -> float:
    """Stiffness of a tube wall pinched by two diametral point loads (ovalisation), N/m.

    Roark's ring under diametral point loads (7th ed., table 9.2 case 1), see the module notes:
    the stiffness returned is ``P / Delta D``.

    Parameters
    ----------
    outer_diameter, inner_diameter : float
        Tube diameters, m (``0 < inner < outer``).
    youngs_modulus : float
        Young's modulus of the tube, Pa.
    poisson_ratio : float
        Poisson's ratio of the tube in (-1, 0.5), for the shear correction. Default: PMMA.
    width : float, optional
        Axial width of the ring slice, m; default one outer diameter (the stated assumption).

    Examples
    --------
    >>> round(ring_stiffness(0.008, 0.006, 3.0e9) / 1e5, 3)  # the probe's tube, N/m
    2.746
    """
    Do = check_positive("outer_diameter", outer_diameter)
    Di = check_positive("inner_diameter", inner_diameter)
    if not Di < Do:
        raise ValueError(f"inner_diameter must be < outer_diameter ({Do!r} m), got {Di!r}")
    E = check_positive("youngs_modulus", youngs_modulus)
    nu = check_in_range("poisson_ratio", poisson_ratio, -1.0, 0.5)
    w = Do if width is None else check_positive("width", width)
    t = (Do - Di) / 2
    Rm = (Do + Di) / 4
    inertia = w * t**3 / 12
    area = w * t
    G = E / (2 * (1 + nu))
    alpha = inertia / (area * Rm**2)
    beta = _SHEAR_FACTOR * E * inertia / (G * area * Rm**2)
    K1, K2 = 1 - alpha + beta, 1 - alpha
    return E * inertia / (Rm**3 * (K1 * math.pi / 4 - 2 * K2**2 / math.pi))


@dataclass(frozen=True)
class ContactStiffness:
    """The contact's stiffnesses in series, N/m.

    Attributes
    ----------
    hertz : float
        Hertz stiffness of the crossed cylinders at the preload, N/m.
    ring : float
        Tube wall (ovalisation) stiffness, N/m (``inf`` when neglected).
    total : float
        Both in series, N/m.
    contact_modulus : float
        ``E*`` used, Pa.
    """

    hertz: float
    ring: float
    total: float
    contact_modulus: float

    @property
    def dominant(self) -> str:
        """``"hertz"`` or ``"ring"``: the softer of the two, which sets most of the compliance."""
        return "ring" if self.ring < self.hertz else "hertz"


def tube_on_rod_stiffness(
    probe,
    obj,
    rod_diameter: float,
    preload: float,
    *,
    probe_poisson_ratio: float = TUBE_POISSON_RATIO,
    object_modulus: float | None = None,
    wall: bool = True,
) -> ContactStiffness:
    """Linearised stiffness of the probe's tube pressed on a round rod.

    Parameters
    ----------
    probe : Probe
        The probe (its outer and inner diameter and Young's modulus are used).
    obj : Material
        The rod's material. Wood (``obj.name == "wood"``) is indented across the grain: its
        modulus becomes :func:`across_grain_modulus` of its ``youngs_modulus`` (along the grain).
    rod_diameter : float
        Diameter of the rod, m (> 0).
    preload : float
        Normal force the contact is linearised at, N (> 0).
    probe_poisson_ratio : float
        Poisson's ratio of the tube, in (-1, 0.5). Default: PMMA.
    object_modulus : float, optional
        Overrides the rod's modulus for the contact, Pa (e.g. a measured transverse modulus).
    wall : bool
        Put the tube wall's ring compliance in series (default True).

    Examples
    --------
    >>> from ebantenna.probe import Probe, material
    >>> ks = tube_on_rod_stiffness(Probe(), material("steel"), 0.012, 0.5)
    >>> round(ks.hertz / 1e5, 2), round(ks.ring / 1e5, 2), ks.dominant
    (5.64, 2.75, 'ring')
    """
    Ep = check_positive("probe.youngs_modulus", probe.youngs_modulus)
    if object_modulus is not None:
        Eo = check_positive("object_modulus", object_modulus)
    elif getattr(obj, "name", None) == "wood":
        Eo = across_grain_modulus(obj.youngs_modulus)
    else:
        Eo = obj.youngs_modulus
    _, nu_o = _elastic("obj", obj, None)
    Es = contact_modulus(Ep, Eo, poisson_ratio1=probe_poisson_ratio, poisson_ratio2=nu_o)
    R2 = check_positive("rod_diameter", rod_diameter) / 2
    k_h = CrossedCylinders(probe.outer_diameter / 2, R2, Es).stiffness(preload)
    if wall and probe.inner_diameter > 0:
        k_r = ring_stiffness(probe.outer_diameter, probe.inner_diameter, Ep, probe_poisson_ratio)
    else:
        k_r = math.inf
    total = 1.0 / (1.0 / k_h + 1.0 / k_r)
    return ContactStiffness(k_h, k_r, total, Es)
