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

from ._validate import check_nonnegative, check_positive

__all__ = ["Probe", "Material", "MATERIALS", "material", "material_names"]


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
        Point mass at the free tip, kg (the accelerometer board). Default 0: none.
    loss_factor : float
        Structural loss factor eta of the tube (hysteretic damping, dimensionless), used by the
        simulator's structural-damping effect; the modal analysis ignores it. Default 0.03: PMMA,
        0.02-0.04 in L. Cremer, M. Heckl, B. A. T. Petersson, *Structure-Borne Sound*, 3rd ed.,
        Springer, 2005, table 2.4 ("Plexiglas").

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
        check_positive("length", self.length)
        check_positive("outer_diameter", self.outer_diameter)
        check_nonnegative("inner_diameter", self.inner_diameter)
        if not self.inner_diameter < self.outer_diameter:
            raise ValueError(
                "inner_diameter must be < outer_diameter "
                f"({self.outer_diameter!r} m), got {self.inner_diameter!r}"
            )
        check_positive("youngs_modulus", self.youngs_modulus)
        check_positive("density", self.density)
        check_nonnegative("tip_mass", self.tip_mass)
        check_nonnegative("loss_factor", self.loss_factor)

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
        Young's modulus E, Pa.
    density : float
        Density rho, kg/m^3.
    poisson_ratio : float
        Poisson's ratio nu (dimensionless).
    loss_factor : float
        Material loss factor eta (dimensionless): the fraction 2*pi*eta of the strain energy lost
        per cycle of vibration.
    source : str
        Where the numbers come from.
    """

    name: str
    youngs_modulus: float
    density: float
    poisson_ratio: float
    loss_factor: float
    source: str


_ASHBY = "M. F. Ashby, Materials Selection in Mechanical Design, 4th ed., 2011, appendix C"
_CREMER = "L. Cremer, M. Heckl, B. A. T. Petersson, Structure-Borne Sound, 3rd ed., 2005, table 2.4"
_FPL = "Wood Handbook, USDA FPL-GTR-190, 2010, tables 5-3a and 5-1 (red oak, 12 % moisture)"

#: The five materials of the paper's experiments. Mid values of the ranges the sources give.
MATERIALS: dict[str, Material] = {
    m.name: m
    for m in (
        Material("aluminium", 69e9, 2700.0, 0.33, 1e-4, f"6061 alloy; {_ASHBY}; eta: {_CREMER}"),
        Material(
            "brass", 105e9, 8500.0, 0.34, 1e-3, f"C26000 cartridge brass; {_ASHBY}; {_CREMER}"
        ),
        Material("wood", 12.5e9, 660.0, 0.35, 1e-2, f"red oak along the grain; {_FPL}; {_CREMER}"),
        Material("steel", 205e9, 7850.0, 0.29, 2e-4, f"low-carbon steel; {_ASHBY}; {_CREMER}"),
        Material(
            "pvc", 3.0e9, 1400.0, 0.38, 2e-2, f"rigid (unplasticised) PVC; {_ASHBY}; {_CREMER}"
        ),
    )
}


def material_names() -> tuple[str, ...]:
    """Names of the known touched materials, in the paper's order."""
    return tuple(MATERIALS)


def material(name: str) -> Material:
    """Look up a touched material by name (case-insensitive; 'aluminum' is accepted).

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
    key = {"aluminum": "aluminium"}.get(key, key)
    if key not in MATERIALS:
        raise ValueError(f"material must be one of {', '.join(MATERIALS)}; got {name!r}")
    return MATERIALS[key]
