"""Contact stiffness of the probe's tube on a round rod: Hertz, tube wall, wood across the grain.

The probe (a tube of outer radius ``R1``) crosses the touched rod (radius ``R2``) at right angles.
Three compliances act in series at the contact point:

1. **Hertz contact of crossed cylinders** (K. L. Johnson, *Contact Mechanics*, Cambridge University
   Press, 1985, section 4.2). The gap between two cylinders crossed at right angles is
   ``h = A x^2 + B y^2`` with ``A = 1/(2 max(R1, R2))`` and ``B = 1/(2 min(R1, R2))``; the contact
   area is an ellipse of semi-axes ``a >= b`` and eccentricity ``e = sqrt(1 - b^2/a^2)``, found from

       B/A = ((a/b)^2 Ee(e) - Ke(e)) / (Ke(e) - Ee(e))                        (Johnson 4.39)

   with ``Ke``, ``Ee`` the complete elliptic integrals of the first and second kind (Johnson
   writes them ``K`` and ``E``; here ``E`` is Young's modulus and ``E*`` the contact modulus).
   Then (Johnson 3.63-3.64, 4.38)

       a^3 (b/a)^2 = 3 P Ee(e) / (2 pi (A + B) E*),   delta = 3 P Ke(e) / (2 pi a E*),

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
   stretch ``alpha = I/(S Rm^2)`` and shear ``beta = F E I/(G S Rm^2)``, ``F = 1.2``; Roark's
   section area ``A`` is written ``S`` here, where ``A`` is a curvature):

       Delta D = (P Rm^3 / (E I)) (K1 pi/4 - 2 K2^2 / pi),
       K1 = 1 - alpha + beta,  K2 = 1 - alpha,  I = w t^3 / 12,  S = w t.

   *Assumption*: the slice of tube that works as the ring is one outer diameter long
   (``w = 2 R1``), and the far side of the ring is held as by a second point load. The real tube
   spreads the load over a longer length and is held by shear around its whole circumference,
   so this is an upper estimate of the wall's compliance (a lower estimate of its stiffness).

3. **Wood across the grain.** A wooden rod (a dowel) has its grain along its axis, so the tube
   indents it *across* the grain. The contact modulus of this orthotropic body is approximated
   by the isotropic Hertz formula with the modulus across the grain, the material's own
   ``transverse_modulus`` (:data:`ebantenna.probe.MATERIALS` states it, with its source: for red
   oak the mean of the radial and tangential moduli, 1.48 GPa). The fibres lying in the surface
   stiffen the indentation somewhat, so this rule errs on the soft side; the longitudinal
   modulus, 8.4 times larger, would raise the contact modulus 2.5-fold, the Hertz stiffness
   1.8-fold and the contact's in series with the tube wall 1.3-fold.

**The law, not only its slope.** The three compliances add in approach:
``p(F) = delta_H(F) + F / k_ring`` with ``delta_H = delta_H(1 N) F^(2/3)``. :class:`HertzInSeries`
is that law; :meth:`HertzInSeries.piecewise` replaces it by chords between nodes with a proven
bound on the force's error (the strike integrates the chords exactly,
:mod:`ebantenna.simulate.unilateral`). ``F(p)`` is convex (``dp/dF`` falls as ``F`` grows), so
on a chord ``[p_a, p_b]`` of slope ``s`` the law lies below the chord and above both tangents,

    0 <= chord(p) - F(p) <= (s - F'(p_a)) (F'(p_b) - s) (p_b - p_a) / (F'(p_b) - F'(p_a)),

the height at which the two tangents' bounds meet (each tangent lies below the convex law).

All quantities are SI: m, N, Pa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from numbers import Real

import numpy as np
import scipy.optimize as spo
import scipy.special as spsp

from .._validate import check_bool, check_in_range, check_nonnegative, check_positive, real_array

__all__ = [
    "TUBE_POISSON_RATIO",
    "PRELOAD",
    "contact_modulus",
    "CrossedCylinders",
    "ring_stiffness",
    "ContactStiffness",
    "tube_on_rod_stiffness",
    "tube_on_rod_spring",
    "HertzInSeries",
    "PiecewiseSpring",
    "tube_on_rod_law",
]

#: Poisson's ratio of PMMA, 0.38-0.40 (M. F. Ashby, *Materials Selection in Mechanical Design*,
#: 4th ed., 2011, appendix C); the value the simulator's contact effect uses.
TUBE_POISSON_RATIO = 0.39
#: Contact force the contact spring is linearised at, N: an assumption (the paper gives none;
#: the stopped servo keeps the probe pressed on the object, and the MG996R's stall torque,
#: 1.08 N m at 6 V (:data:`ebantenna.chips.mg996r.STALL_TORQUE_6V`), could press up to 5.4 N at
#: 0.2 m). The default of the ``contact_compliance``
#: and ``object_modes`` effects.
PRELOAD = 0.5
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


def _ratio_of_curvatures(q: float) -> float:
    """``B/A`` of an elliptical Hertz contact with axis ratio squared ``q = (b/a)^2``, 0 < q < 1
    (Johnson 4.39, with ``(a/b)^2 = 1/q``)."""
    m = 1.0 - q
    Ke, Ee = spsp.ellipkm1(q), spsp.ellipe(m)
    return (Ee / q - Ke) / (Ke - Ee)


@lru_cache(maxsize=256)
def _squared_axis_ratio(target: float) -> float:
    """``q = (b/a)^2`` of the contact ellipse whose ratio of curvatures ``B/A`` is ``target``
    (> 1), kept per process: every strike of a data set builds its contact from the same two
    radii, and the root search took about a quarter of a millisecond each time."""
    # B/A rises from 1 (q -> 1) to infinity (q -> 0); solve in log q for a wide bracket.
    return math.exp(
        spo.brentq(
            lambda s: _ratio_of_curvatures(math.exp(s)) - target,
            -700.0,
            math.log1p(-1e-12),
            xtol=1e-15,
            rtol=4 * np.finfo(float).eps,
        )
    )


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
        q = 1.0 if B / A - 1 <= _CIRCULAR else _squared_axis_ratio(B / A)
        object.__setattr__(self, "_q", q)  # (b/a)^2
        object.__setattr__(self, "_sum", A + B)

    @property
    def axis_ratio(self) -> float:
        """``b/a`` of the contact ellipse, dimensionless."""
        return math.sqrt(self._q)

    def semi_axes(self, force: float) -> tuple[float, float]:
        """Semi-axes ``(a, b)`` of the contact ellipse under the normal force ``force`` (N), m."""
        P = check_positive("force", force)
        Ee = float(spsp.ellipe(1.0 - self._q))
        a = (3 * P * Ee / (2 * math.pi * self._sum * self.modulus * self._q)) ** (1 / 3)
        return a, a * math.sqrt(self._q)

    def approach(self, force: float) -> float:
        """Approach ``delta`` of distant points of the two bodies under ``force`` (N), m."""
        a, _ = self.semi_axes(force)
        Ke = float(spsp.ellipkm1(self._q))
        return 3 * float(force) * Ke / (2 * math.pi * a * self.modulus)

    def force(self, approach) -> np.ndarray | float:
        """Normal force for an approach ``delta`` (m; 0 where ``delta <= 0``: no tension), N."""
        d = _finite("approach", approach)
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


def _chord_bound(pa, pb, fa, fb, da, db) -> float:
    """Most a chord of a convex law lies above it on ``[pa, pb]`` (module notes), N.

    ``fa, fb``: the law's values (N) at the ends; ``da, db``: its slopes there (N/m).
    """
    if pb <= pa or db <= da:
        return 0.0
    s = (fb - fa) / (pb - pa)
    return max(0.0, (s - da) * (db - s) * (pb - pa) / (db - da))


@dataclass(frozen=True)
class PiecewiseSpring:
    """A spring that only pushes, its force law given by chords between nodes.

    Segment ``j`` holds for ``approaches[j] <= p <= approaches[j+1]``, where the force is
    ``slopes[j] (p - offsets[j])``; the last chord continues beyond the last node, so a single
    chord is the linear spring ``k p``.

    Attributes
    ----------
    forces : ndarray of shape (n + 1,)
        Force at the nodes, N; ``forces[0] = 0``, increasing.
    approaches : ndarray of shape (n + 1,)
        Approach at the nodes, m; ``approaches[0] = 0``, increasing.
    bounds : ndarray of shape (n,)
        Most each chord's force differs from the law it replaces, N (0 for a linear spring).

    Examples
    --------
    >>> spring = PiecewiseSpring.linear(1e5)
    >>> spring.slopes, spring.offsets, spring.bound
    (array([100000.]), array([0.]), 0.0)
    """

    forces: np.ndarray
    approaches: np.ndarray
    bounds: np.ndarray

    def __post_init__(self):
        F, p = np.asarray(self.forces, float), np.asarray(self.approaches, float)
        if F.ndim != 1 or F.shape != p.shape or F.size < 2 or F[0] != 0 or p[0] != 0:
            raise ValueError("forces and approaches: equal 1-D arrays of >= 2 nodes from 0")
        if not (np.all(np.diff(F) > 0) and np.all(np.diff(p) > 0)):
            raise ValueError("forces and approaches must increase from node to node")
        object.__setattr__(self, "forces", F)
        object.__setattr__(self, "approaches", p)
        bounds = np.asarray(self.bounds, float)
        if bounds.shape != (F.size - 1,) or np.any(bounds < 0):
            raise ValueError("bounds: one non-negative bound per chord")
        object.__setattr__(self, "bounds", bounds)

    @classmethod
    def linear(cls, stiffness: float) -> PiecewiseSpring:
        """The linear spring ``k p`` (N/m): one chord, exact, continued without end."""
        k = check_positive("stiffness", stiffness)
        return cls(np.array([0.0, k]), np.array([0.0, 1.0]), np.zeros(1))

    @property
    def slopes(self) -> np.ndarray:
        """Each chord's slope, N/m."""
        return np.diff(self.forces) / np.diff(self.approaches)

    @property
    def offsets(self) -> np.ndarray:
        """Where each chord, extended, meets zero force, m (``p - F / k`` at its lower node)."""
        return self.approaches[:-1] - self.forces[:-1] / self.slopes

    @property
    def bound(self) -> float:
        """Most the chords' force differs from the law up to the last node, N."""
        return float(self.bounds.max())

    def force(self, approach):
        """Force of the chords at ``approach`` (m; 0 where ``p <= 0``), N."""
        p = _finite("approach", approach)
        j = np.clip(np.searchsorted(self.approaches, p, side="right") - 1, 0, self.slopes.size - 1)
        out = np.where(p > 0, self.slopes[j] * (p - self.offsets[j]), 0.0)
        return float(out) if out.ndim == 0 else out

    def approach_at(self, force: float) -> float:
        """Approach of the chords at ``force`` (N, >= 0), m."""
        force = check_nonnegative("force", force)
        j = int(np.clip(np.searchsorted(self.forces, force, side="right") - 1, 0,
                        self.slopes.size - 1))  # fmt: skip
        return float(self.offsets[j] + force / self.slopes[j])


def _finite(name: str, value) -> np.ndarray:
    """``value`` as a float array of finite numbers, else an error naming ``name``."""
    a = real_array(name, value)
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must contain only finite values (no NaN or inf)")
    return a


def _forces(name: str, value) -> np.ndarray:
    """``value`` as a float array of finite forces >= 0 (N), else an error naming ``name``."""
    F = _finite(name, value)
    if np.any(F < 0):
        raise ValueError(f"{name} must be >= 0 N (the contact only pushes), got {F.min()!r}")
    return F


@dataclass(frozen=True)
class HertzInSeries:
    """The contact's law: crossed-cylinder Hertz in series with the tube wall's ring spring.

    ``p(F) = delta_H(1 N) F^(2/3) + F / k_ring``: the approach of the two compliances in series
    (module notes). ``F(p)`` is its inverse.

    Parameters
    ----------
    hertz : CrossedCylinders
        The Hertz contact.
    ring : float
        The tube wall's stiffness, N/m (``inf``: a solid probe).

    Examples
    --------
    >>> law = HertzInSeries(CrossedCylinders(0.004, 0.006, 3.5e9), 2.7e5)
    >>> round(float(law.force(law.approach(0.5))), 12)  # N
    0.5
    """

    hertz: CrossedCylinders
    ring: float

    def __post_init__(self):
        if not isinstance(self.hertz, CrossedCylinders):
            raise TypeError(f"hertz must be a CrossedCylinders, got {type(self.hertz).__name__}")
        check_positive("ring", self.ring, allow_inf=True)  # inf: the wall neglected

    def approach(self, force):
        """Approach under ``force`` (N, >= 0), m."""
        out = self._approach(_forces("force", force), self.hertz.approach(1.0))
        return float(out) if out.ndim == 0 else out

    def stiffness(self, force):
        """``dF/dp`` at ``force`` (N, >= 0), N/m: 0 at zero force, where Hertz starts soft."""
        out = self._stiffness(_forces("force", force), self.hertz.approach(1.0))
        return float(out) if out.ndim == 0 else out

    # the law at checked forces F >= 0 (N), ``unit`` the Hertz approach at 1 N (m): what the
    # chords' placement evaluates some hundred times per spring, without the checks
    def _approach(self, F, unit: float):
        return unit * np.cbrt(F) ** 2 + F / self.ring

    def _stiffness(self, F, unit: float):
        with np.errstate(divide="ignore"):
            compliance = 2 / 3 * unit / np.cbrt(F) + 1 / self.ring
        return 1 / compliance

    def _unchecked_chord_bound(self, fa: float, fb: float, unit: float) -> float:
        return _chord_bound(float(self._approach(fa, unit)), float(self._approach(fb, unit)),
                            fa, fb, float(self._stiffness(fa, unit)),
                            float(self._stiffness(fb, unit)))

    def force(self, approach):
        """Force at ``approach`` (m; 0 where ``p <= 0``), N: ``p(F)`` inverted by Newton's method.

        It starts above the root (either compliance alone gives a larger force); ``p(F)`` is
        concave, so a Newton step lands at or below the root and the iteration then climbs to it
        monotonically; a step is kept from falling below an eighth of the last iterate, which
        keeps ``F`` positive."""
        p = _finite("approach", approach)
        F = np.minimum((np.maximum(p, 0) / self.hertz.approach(1.0)) ** 1.5, p * self.ring)
        F = np.where(p > 0, np.maximum(F, 0.0), 0.0)
        for _ in range(40):
            step = np.where(p > 0, (self.approach(F) - p) * self.stiffness(F), 0.0)
            F = np.maximum(F - np.nan_to_num(step), F / 8)
        out = np.where(p > 0, F, 0.0)
        return float(out) if out.ndim == 0 else out

    def chord_bound(self, fa: float, fb: float) -> float:
        """Most the chord between the forces ``fa < fb`` (N) lies above the law, N."""
        fa = check_nonnegative("fa", fa)
        if not fa < check_nonnegative("fb", fb):
            raise ValueError(f"fa must be below fb, got fa = {fa!r}, fb = {fb!r}")
        return self._unchecked_chord_bound(fa, fb, self.hertz.approach(1.0))

    def piecewise(self, tolerance: float, max_force: float, through=()) -> PiecewiseSpring:
        """Chords of the law whose force is within ``tolerance`` (N) of it up to ``max_force``.

        Nodes are placed from zero force up, each chord as long as its bound allows; the forces
        in ``through`` (N, e.g. the preload, where the law is then exact) are nodes too.

        Examples
        --------
        >>> law = HertzInSeries(CrossedCylinders(0.004, 0.006, 3.5e9), 2.7e5)
        >>> spring = law.piecewise(0.01, 5.0, through=(0.5,))
        >>> spring.bound <= 0.01, bool(np.any(spring.forces == 0.5))
        (True, True)
        """
        tol = check_positive("tolerance", tolerance)
        top = check_positive("max_force", max_force)
        if tol < 1e-9 * top:  # the chords' ends are found to 1e-10 of the force
            raise ValueError(f"tolerance must be at least 1e-9 of max_force ({1e-9 * top:.3g} N), "
                             f"got {tol!r}")
        stops = sorted({top, *(float(f) for f in through if 0 < f < top)})
        unit = self.hertz.approach(1.0)
        nodes, bounds = [0.0], []
        for stop in stops:
            while nodes[-1] < stop:
                a = nodes[-1]
                if self._unchecked_chord_bound(a, stop, unit) <= tol:
                    b = stop
                else:
                    # aim a little inside the tolerance, so that the root's error keeps it
                    def excess(f, a=a):
                        return self._unchecked_chord_bound(a, f, unit) - tol * (1 - 1e-6)

                    b = spo.brentq(excess, a + (stop - a) * 1e-12, stop, xtol=1e-14, rtol=1e-10)
                bounds.append(self._unchecked_chord_bound(a, b, unit))
                nodes.append(b)
        F = np.array(nodes)
        return PiecewiseSpring(F, self.approach(F), np.array(bounds))


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
        The rod's material; its ``transverse_modulus`` (across the rod's axis: for wood, across
        the grain, as the material table states it) is the one the contact feels.
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
    law = tube_on_rod_law(
        probe, obj, rod_diameter, probe_poisson_ratio=probe_poisson_ratio,
        object_modulus=object_modulus, wall=wall,
    )  # fmt: skip
    k_h = law.hertz.stiffness(preload)
    k_r = law.ring
    total = 1.0 / (1.0 / k_h + 1.0 / k_r)
    return ContactStiffness(k_h, k_r, total, law.hertz.modulus)


def tube_on_rod_spring(probe, obj, rod_diameter: float, preload: float, *,
                       object_loss: bool) -> tuple[float, float]:
    """The contact spring of the probe's tube on a round rod at ``preload``: its stiffness, N/m
    (:func:`tube_on_rod_stiffness`'s ``total``), and its loss factor (dimensionless).

    The spring's compliance is the sum of the tube's share (its Hertz share and the wall's ring
    compliance) and the rod's Hertz share; each share loses energy with its own body's loss
    factor, so the spring's loss factor is their compliance-weighted mean. With ``object_loss``
    False the rod's share is lossless (the ``object_damping`` effect not listed).

    Parameters
    ----------
    probe, obj, rod_diameter, preload
        As in :func:`tube_on_rod_stiffness`.
    object_loss : bool
        Whether the rod's share loses energy with the rod material's loss factor.

    Examples
    --------
    >>> from ebantenna.probe import Probe, material
    >>> k, eta = tube_on_rod_spring(Probe(), material("steel"), 0.012, 0.5, object_loss=True)
    >>> k == tube_on_rod_stiffness(Probe(), material("steel"), 0.012, 0.5).total
    True
    """
    object_loss = check_bool("object_loss", object_loss)
    ks = tube_on_rod_stiffness(probe, obj, rod_diameter, preload)
    e_probe = probe.youngs_modulus / (1 - TUBE_POISSON_RATIO**2)
    c_hertz = 1 / ks.hertz
    # Hertz compliance splits between the bodies as their (1 - nu^2)/E do: 1/E* = sum.
    probe_share = c_hertz * ks.contact_modulus / e_probe
    rod_share = c_hertz - probe_share
    ring = 0.0 if math.isinf(ks.ring) else 1 / ks.ring
    eta_rod = obj.loss_factor if object_loss else 0.0
    loss = (probe.loss_factor * (probe_share + ring) + eta_rod * rod_share) / (c_hertz + ring)
    return ks.total, loss


def tube_on_rod_law(
    probe,
    obj,
    rod_diameter: float,
    *,
    probe_poisson_ratio: float = TUBE_POISSON_RATIO,
    object_modulus: float | None = None,
    wall: bool = True,
) -> HertzInSeries:
    """The contact's whole force law: crossed-cylinder Hertz in series with the tube wall.

    Parameters as :func:`tube_on_rod_stiffness` (without the preload: the law holds at every
    force). The rod's modulus is its material's ``transverse_modulus``.

    Examples
    --------
    >>> from ebantenna.probe import Probe, material
    >>> law = tube_on_rod_law(Probe(), material("steel"), 0.012)
    >>> round(law.stiffness(0.5) / 1e5, 2)  # N/m, the linearised spring at 0.5 N
    1.85
    """
    from ..probe import Probe

    if not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
    if not hasattr(obj, "youngs_modulus"):
        raise TypeError(f"obj must be a Material (ebantenna.probe.material(name)), got "
                        f"{type(obj).__name__}")
    Ep = check_positive("probe.youngs_modulus", probe.youngs_modulus)
    if object_modulus is not None:
        Eo = check_positive("object_modulus", object_modulus)
    else:
        Eo = getattr(obj, "transverse_modulus", None) or obj.youngs_modulus
    _, nu_o = _elastic("obj", obj, None)
    Es = contact_modulus(Ep, Eo, poisson_ratio1=probe_poisson_ratio, poisson_ratio2=nu_o)
    R2 = check_positive("rod_diameter", rod_diameter) / 2
    hertz = CrossedCylinders(probe.outer_diameter / 2, R2, Es)
    if wall and probe.inner_diameter > 0:
        k_r = ring_stiffness(probe.outer_diameter, probe.inner_diameter, Ep, probe_poisson_ratio)
    else:
        k_r = math.inf
    return HertzInSeries(hertz, k_r)
