"""The antenna probe and the materials of the objects it touches.

The probe of the paper (section 3) is an acrylic (PMMA) tube, 8 mm outside and 6 mm inside diameter,
40 cm long, hinged on a pan-tilt unit with an MPU6050 accelerometer board at its free tip. The paper
does not give the tube's Young's modulus or density; the values used here are mid-range handbook
values for cast PMMA, with their source.

Everything is in SI units: metres, kilograms, seconds, pascals.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

from ._validate import check_in_range, check_nonnegative, check_positive, check_range

__all__ = ["Probe", "Material", "MATERIALS", "ALIASES", "material", "material_names",
           "SIZE_RANGE", "MODULUS_RANGE", "DENSITY_RANGE", "MAX_LOSS_FACTOR", "MAX_TIP_MASS_RATIO"]


#: A beam's length or diameter, m, and why: a continuum beam from a micrometre to a kilometre;
#: there ``d**4`` and ``L**3`` of the stiffness and of the frequencies stay far inside the float
#: range (a diameter of 5e-324 m would make the second moment of area 0).
SIZE_RANGE = (1e-6, 1e3)
SIZE_REASON = "a continuum beam from 1 µm to 1 km; d**4 and L**3 stay inside the float range"
#: Young's modulus, Pa: from a soft gel (1 kPa) to 1e30 Pa, far beyond diamond (about 1.2e12 Pa)
#: but still a finite stand-in for a rigid body; ``E I`` and ``E / rho`` stay in the float range.
MODULUS_RANGE = (1e3, 1e30)
MODULUS_REASON = "from a soft gel, 1 kPa, to a rigid stand-in far beyond diamond's 1.2e12 Pa"
#: Density, kg/m^3: from an aerogel (a few kg/m^3) to beyond osmium (22 590 kg/m^3).
DENSITY_RANGE = (1.0, 1e5)
DENSITY_REASON = "from an aerogel to beyond osmium, 22 590 kg/m^3"
#: The largest structural loss factor: eta = 1 is a damping ratio of 0.5 per mode, far beyond
#: any solid (rubber reaches about 1); the hysteretic model describes light damping.
MAX_LOSS_FACTOR = 1.0
LOSS_REASON = "eta = 1 is a damping ratio of 0.5, beyond any solid; the model is for light damping"
#: The heaviest tip mass, as a multiple of the tube's mass. Beyond it the probe is a point mass
#: on a massless spring: its first frequency (about sqrt(3 EI / (M L^3)) / 2 pi) is all the
#: beam model could say, and the exact solution's root search no longer separates the modes.
MAX_TIP_MASS_RATIO = 1e4
TIP_MASS_REASON = "beyond, the probe is a point mass on a spring, not a beam"


@dataclass(frozen=True)
class Probe:
    """A hollow circular tube used as a vibrating antenna.

    Parameters
    ----------
    length : float
        Length from the hinge to the free tip, m. Default 0.40 m (paper, section 3).
    outer_diameter : float
        Outside diameter, m. Default 8 mm (paper, section 3).
    inner_diameter : float
        Inside diameter, m; 0 for a solid rod. Default 6 mm (paper, section 3).
    youngs_modulus : float
        Young's modulus E of the tube, Pa. Default 3.0 GPa: cast PMMA, 2.2-3.8 GPa in
        M. F. Ashby, *Materials Selection in Mechanical Design*, 4th ed., Butterworth-Heinemann,
        2011, ch. 4 charts and appendix C (mid value).
    density : float
        Mass density rho of the tube, kg/m^3. Default 1190 kg/m^3: PMMA, 1170-1200 kg/m^3
        (Ashby, ibid.).
    tip_mass : float
        Point mass at the free tip, kg (the accelerometer board). Default 0: none. At most
        :data:`MAX_TIP_MASS_RATIO` times the tube's mass.
    loss_factor : float
        Structural loss factor eta of the tube (hysteretic damping, dimensionless), used by the
        simulator's structural-damping effect; the modal analysis ignores it. Default 0.03, an
        assumption for PMMA: L. Cremer, M. Heckl, B. A. T. Petersson, *Structure-Borne Sound*, 3rd
        ed., Springer, 2005, list 2e-2 for Plexiglas in their table of material loss factors, and
        Ashby's loss-coefficient chart places glassy polymers at room temperature between 1e-2
        and 5e-2; 0.03 lies in that range. At most :data:`MAX_LOSS_FACTOR`.

    Each parameter has a range with its reason (:data:`SIZE_RANGE` for the length and the
    diameters, :data:`MODULUS_RANGE`, :data:`DENSITY_RANGE`); a value outside it raises a
    :class:`ValueError` that names the parameter, the range and the reason.

    Examples
    --------
    >>> from ebantenna.probe import Probe
    >>> probe = Probe()
    >>> round(probe.area * 1e6, 3)  # mm^2
    21.991
    >>> round(probe.flexural_rigidity, 4)  # EI in N m^2
    0.4123
    """

    length: float = 0.40
    outer_diameter: float = 0.008
    inner_diameter: float = 0.006
    youngs_modulus: float = 3.0e9
    density: float = 1190.0
    tip_mass: float = 0.0
    loss_factor: float = 0.03

    def __post_init__(self):
        for name in ("length", "outer_diameter"):
            check_range(name, getattr(self, name), SIZE_RANGE, SIZE_REASON)
        check_nonnegative("inner_diameter", self.inner_diameter)
        if not self.inner_diameter < self.outer_diameter:
            raise ValueError(
                "inner_diameter must be < outer_diameter "
                f"({self.outer_diameter!r} m), got {self.inner_diameter!r}"
            )
        if not self.outer_diameter - self.inner_diameter >= 2 * SIZE_RANGE[0] * 1e-3:
            raise ValueError(
                f"the wall (outer_diameter - inner_diameter)/2 must be at least 1 nm, got "
                f"{(self.outer_diameter - self.inner_diameter) / 2!r} m"
            )
        check_range("youngs_modulus", self.youngs_modulus, MODULUS_RANGE, MODULUS_REASON)
        check_range("density", self.density, DENSITY_RANGE, DENSITY_REASON)
        check_nonnegative("loss_factor", self.loss_factor)
        check_range("loss_factor", self.loss_factor, (0.0, MAX_LOSS_FACTOR), LOSS_REASON)
        check_nonnegative("tip_mass", self.tip_mass)
        check_range("tip_mass", self.tip_mass, (0.0, MAX_TIP_MASS_RATIO * self.mass),
                    f"{MAX_TIP_MASS_RATIO:g} times the tube's mass; {TIP_MASS_REASON}")

    @property
    def area(self) -> float:
        """Cross-section area A, m^2."""
        return math.pi / 4 * (self.outer_diameter**2 - self.inner_diameter**2)

    @property
    def second_moment(self) -> float:
        """Second moment of area I about a diameter, m^4."""
        return math.pi / 64 * (self.outer_diameter**4 - self.inner_diameter**4)

    @property
    def flexural_rigidity(self) -> float:
        """Bending stiffness EI, N m^2."""
        return self.youngs_modulus * self.second_moment

    @property
    def mass_per_length(self) -> float:
        """Mass per unit length rho*A, kg/m."""
        return self.density * self.area

    @property
    def mass(self) -> float:
        """Mass of the tube alone (without the tip mass), kg."""
        return self.mass_per_length * self.length

    def summary(self) -> dict:
        """The contract's JSON: ``L``, ``E``, ``rho``, ``A``, ``I``, ``tip_mass`` (SI units)."""
        return {
            "L": self.length,
            "E": self.youngs_modulus,
            "rho": self.density,
            "A": self.area,
            "I": self.second_moment,
            "tip_mass": self.tip_mass,
        }

    def to_dict(self) -> dict:
        """All constructor arguments, for saving in scenes and metadata."""
        return asdict(self)


@dataclass(frozen=True)
class Material:
    """Elastic and damping properties of a touched object.

    Parameters
    ----------
    name : str
        Short name, as used on the command line.
    youngs_modulus : float
        Young's modulus E, Pa; for wood, along the grain (the rod's axis).
    density : float
        Density rho, kg/m^3.
    poisson_ratio : float
        Poisson's ratio nu (dimensionless), in (-1, 0.5).
    loss_factor : float
        Material loss factor eta (dimensionless, >= 0): the fraction 2*pi*eta of the strain energy
        lost per cycle of vibration.
    source : str
        Where the numbers come from.
    youngs_modulus_across : float or None
        Young's modulus across the rod's axis, Pa, for an anisotropic material (wood: across the
        grain); ``None`` (default) for an isotropic one, whose modulus is the same in every
        direction.
    ranges : tuple of (field, low, high)
        The spread the sources give for a field (same units as the field), where the value
        taken is one point of a range.

    Examples
    --------
    >>> from ebantenna.probe import material
    >>> oak = material("oak")
    >>> oak.youngs_modulus / oak.transverse_modulus > 5  # far stiffer along the grain
    True
    >>> material("steel").transverse_modulus == material("steel").youngs_modulus
    True
    """

    name: str
    youngs_modulus: float
    density: float
    poisson_ratio: float
    loss_factor: float
    source: str
    youngs_modulus_across: float | None = None
    ranges: tuple = ()

    def __post_init__(self):
        check_positive("youngs_modulus", self.youngs_modulus)
        check_positive("density", self.density)
        check_in_range("poisson_ratio", self.poisson_ratio, -1.0, 0.5)
        check_nonnegative("loss_factor", self.loss_factor)
        if self.youngs_modulus_across is not None:
            check_positive("youngs_modulus_across", self.youngs_modulus_across)
        for field, low, high in self.ranges:
            value = getattr(self, field)
            if not low <= value <= high:
                raise ValueError(
                    f"{field} must lie in its sources' range [{low:g}, {high:g}], got {value!r}"
                )

    @property
    def transverse_modulus(self) -> float:
        """Young's modulus across the rod's axis, Pa (the contact's); E for isotropic materials."""
        if self.youngs_modulus_across is None:
            return self.youngs_modulus
        return self.youngs_modulus_across


# Sources. Every number of the table below is one of these, at the table or page given.
_ASHBY_JONES = (
    "M. F. Ashby, D. R. H. Jones, Engineering Materials 1, 4th ed., Butterworth-Heinemann, 2012, "
    "table 3.1 (Young's modulus) and table 5.1 (density)"
)
_ASHBY = (
    "M. F. Ashby, Materials Selection in Mechanical Design, 4th ed., Butterworth-Heinemann, 2011, "
    "ch. 4 (loss coefficient - modulus chart) and appendix C"
)
_CREMER = (
    "L. Cremer, M. Heckl, B. A. T. Petersson, Structure-Borne Sound, 3rd ed., Springer, 2005, "
    "ch. 3 (Damping), table of material loss factors"
)
_ASM = "ASM Handbook vol. 2, Properties and Selection: Nonferrous Alloys, ASM International, 1990"
_FPL = (
    "Forest Products Laboratory, Wood Handbook, FPL-GTR-282, USDA, 2021, ch. 5: table 5-1 "
    "(elastic ratios), table 5-2 (Poisson's ratios), table 5-3a (MOE, specific gravity at 12 % "
    "moisture); northern red oak"
)

#: The five materials of the paper's experiments (the paper names them, gives no grade or
#: geometry). Each value lies in the range its sources give (``ranges``), most of them mid
#: values; the wood's E is the handbook's bending MOE (the range's lower end, see below) and the
#: PVC's nu the lower end of Ashby's range. Where a range's bound comes from no source it says
#: so (an assumption):
#:
#: - aluminium, 6061-T6 (the common rod stock): E 68.9 GPa, rho 2700 kg/m^3, nu 0.33 (ASM vol. 2;
#:   Ashby & Jones table 3.1: 69 GPa; the range 68-71 GPa widens these by about 1 % for alloy
#:   and temper, an assumption); eta 1e-4, metals of construction 1e-5 to 1e-3 (Cremer et
#:   al.; Ashby's chart);
#: - brass: 97 GPa (C36000 free-cutting) to 110 GPa (C26000 cartridge), rho 8500 kg/m^3
#:   (8490-8530), nu 0.34 (ASM vol. 2; Ashby & Jones table 3.1: 103-124 GPa); eta 1e-3, "< 1e-3"
#:   in Cremer et al.; the range 2e-4 to 2e-3 about it is an assumption (no source here gives
#:   its bounds);
#: - wood: northern red oak at 12 % moisture (FPL table 5-3a): bending MOE 12.5 GPa along the grain
#:   (the handbook's MOE includes shear deflection and reads up to ~10 % below the true E_L);
#:   specific gravity 0.63 on oven-dry mass and volume at 12 % moisture, so rho = 0.63 * 1000 *
#:   1.12 = 706 kg/m^3; across the grain E_R / E_L = 0.154 and E_T / E_L = 0.082 (FPL table 5-1),
#:   E_R = 1.93 GPa, E_T = 1.03 GPa: the probe meets the rod's side at no particular angle to the
#:   growth rings, so the mean, 1.48 GPa, is taken; nu = mu_LR = 0.350 (FPL table 5-2); eta 1e-2,
#:   wood along the grain 5e-3 to 1.5e-2 (Cremer et al.; Ashby's chart);
#: - steel, low-carbon: E 200-210 GPa, rho 7850 kg/m^3, nu 0.29 (Ashby & Jones tables 3.1, 5.1:
#:   mild steel 200 GPa); eta 2e-4, 1e-4 to 6e-4 (Cremer et al.);
#: - pvc, rigid (unplasticised): E 2.4-4.1 GPa, rho 1300-1580 kg/m^3, nu 0.38-0.40 (Ashby
#:   appendix C); eta 2e-2, 1e-2 to 5e-2 at room temperature, well below the glass transition
#:   (Ashby's loss-coefficient chart; Cremer et al. give 2e-2 for the similar glassy Plexiglas).
MATERIALS: dict[str, Material] = {
    m.name: m
    for m in (
        Material(
            "aluminium", 68.9e9, 2700.0, 0.33, 1e-4,
            f"6061-T6; {_ASM}; {_ASHBY_JONES}; eta: {_CREMER}; {_ASHBY}",
            ranges=(("youngs_modulus", 68e9, 71e9), ("loss_factor", 1e-5, 1e-3)),
        ),
        Material(
            "brass", 105e9, 8500.0, 0.34, 1e-3,
            f"C36000-C26000; {_ASM}; {_ASHBY_JONES}; eta: {_CREMER}",
            ranges=(
                ("youngs_modulus", 97e9, 124e9),
                ("density", 8490.0, 8530.0),
                ("loss_factor", 2e-4, 2e-3),
            ),
        ),
        Material(
            "wood", 12.5e9, 706.0, 0.350, 1e-2,
            f"northern red oak; {_FPL}; eta: {_CREMER}; {_ASHBY}",
            youngs_modulus_across=1.48e9,
            ranges=(
                ("youngs_modulus", 12.5e9, 13.8e9),
                ("youngs_modulus_across", 1.03e9, 1.93e9),
                ("loss_factor", 5e-3, 1.5e-2),
            ),
        ),
        Material(
            "steel", 205e9, 7850.0, 0.29, 2e-4,
            f"low-carbon steel; {_ASHBY_JONES}; {_ASHBY}; eta: {_CREMER}",
            ranges=(("youngs_modulus", 200e9, 210e9), ("loss_factor", 1e-4, 6e-4)),
        ),
        Material(
            "pvc", 3.0e9, 1400.0, 0.38, 2e-2,
            f"rigid (unplasticised) PVC; {_ASHBY}; eta: {_CREMER}",
            ranges=(
                ("youngs_modulus", 2.4e9, 4.1e9),
                ("density", 1300.0, 1580.0),
                ("poisson_ratio", 0.38, 0.40),
                ("loss_factor", 1e-2, 5e-2),
            ),
        ),
    )
}

#: Other names accepted by :func:`material`.
ALIASES = {"aluminum": "aluminium", "oak": "wood", "red oak": "wood", "mild steel": "steel"}


def material_names() -> tuple[str, ...]:
    """Names of the known touched materials, in the paper's order."""
    return tuple(MATERIALS)


def material(name: str) -> Material:
    """Look up a touched material by name (case-insensitive; the :data:`ALIASES` are accepted).

    Raises
    ------
    ValueError
        For an unknown name, listing the valid ones.

    Examples
    --------
    >>> from ebantenna.probe import material
    >>> material("Brass").density
    8500.0
    """
    if not isinstance(name, str):
        raise TypeError(f"material must be a string, got {type(name).__name__}")
    key = name.strip().lower()
    key = ALIASES.get(key, key)
    if key not in MATERIALS:
        raise ValueError(f"material must be one of {', '.join(MATERIALS)}; got {name!r}")
    return MATERIALS[key]
