"""The effects a scene may call for, each a small frozen dataclass with its physics and sources.

A scene lists the effects it wants; an effect that is not listed is not computed at all. The modal
response itself (superposition of the FEM modes after the arrest, see :mod:`.modes`) is not an
effect: it is always there. Effects fall in two groups:

*Physics of the probe and the contact*, which change the modal parameters:
:class:`StructuralDamping`, :class:`ContactCompliance`, :class:`ContactDamping`, :class:`TipMass`.

*The sensor and the acquisition*, which act on the sampled signals, in this order:
:class:`ClockJitter` (when the samples are taken), :class:`Gravity`, :class:`MainsHum`,
:class:`SensorNoise`, :class:`LowPassFilter` (the MPU6050's DLPF), :class:`Clipping`,
:class:`Quantisation`, :class:`KalmanFilter` (on the Raspberry Pi).

All arrays here have shape ``(n_signals, n_samples)``: every effect is vectorised over signals.
Random effects draw from a :class:`numpy.random.Generator` per signal that the simulator makes
from the signal's seed and the effect's own :attr:`stream` number, so that adding or removing one
effect never changes the random numbers of another.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields
from typing import ClassVar

import numpy as np
import scipy.signal as sps

from .._validate import check_choice, check_in_range, check_int, check_nonnegative, check_positive
from ..chips.mpu6050 import ACCEL_NOISE_DENSITY, ACCEL_RANGES_G, DLPF, STANDARD_GRAVITY
from ..probe import Material, Probe

__all__ = [
    "STANDARD_GRAVITY",
    "StructuralDamping",
    "ContactCompliance",
    "ContactDamping",
    "TipMass",
    "ClockJitter",
    "Gravity",
    "MainsHum",
    "SensorNoise",
    "LowPassFilter",
    "Clipping",
    "Quantisation",
    "KalmanFilter",
    "EFFECT_TYPES",
    "effect_names",
    "make_effect",
]

#: The accelerometer board at the tip: an MPU6050 breakout (GY-521), kg. Estimate: FR-4 board
#: 20 x 15.5 x 1.6 mm at 1850 kg/m^3 (0.9 g), 8-pin header (0.6 g), chip and parts (0.3 g), plus
#: 0.7 g of solder, glue and wire ends at the tip; 2.5 g, within the 2-3 g that hobby vendors list.
GY521_MASS = 2.5e-3


class _Effect:
    """Shared behaviour: a name, parameters as a dict, construction from a dict."""

    name: ClassVar[str]

    def parameters(self) -> dict:
        """The effect's parameters (for saving scenes and metadata)."""
        return asdict(self)

    @classmethod
    def from_parameters(cls, params: dict):
        """Build the effect from a dict of its parameters, rejecting unknown keys."""
        if not isinstance(params, dict):
            raise TypeError(
                f"parameters of effect {cls.name!r} must be a table/dict, got {params!r}"
            )
        valid = {f.name for f in fields(cls)}
        unknown = sorted(set(params) - valid)
        if unknown:
            allowed = ", ".join(sorted(valid)) or "none"
            raise ValueError(
                f"unknown parameter(s) {', '.join(unknown)} for effect {cls.name!r}; "
                f"allowed: {allowed}"
            )
        return cls(**params)


# --------------------------------------------------------------------------------------------------
# Physics of the probe and the contact


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
    The ring (ovalisation) compliance of the tube wall is neglected.

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


# --------------------------------------------------------------------------------------------------
# The sensor and the acquisition


@dataclass(frozen=True)
class ClockJitter(_Effect):
    """Sample-clock jitter of the acquisition loop.

    The Raspberry Pi polls the sensor from a user-space loop, so sample ``n`` is taken at
    ``n / fs + e_n`` instead of ``n / fs``, while the recording still assigns it the nominal time.
    The offsets ``e_n`` are independent, normal, with standard deviation ``rms``; the continuous
    signals (modal response, gravity, hum) are evaluated exactly at the jittered instants.
    Simplification: the sensor's own filter then runs on these samples as if they were regular.

    Parameters
    ----------
    rms : float
        Standard deviation of the sampling instants, s. Default 50 us: an assumption, the order of
        the scheduling latency of a Linux user-space loop without real-time priority.

    Examples
    --------
    >>> import numpy as np
    >>> e = ClockJitter(rms=1e-4).offsets(np.random.default_rng(0), 1000)
    >>> bool(abs(e.std() - 1e-4) < 1e-5)
    True
    """

    name: ClassVar[str] = "clock_jitter"
    stream: ClassVar[int] = 1
    rms: float = 50e-6

    def __post_init__(self):
        check_nonnegative("rms", self.rms)

    def offsets(self, rng: np.random.Generator, n_samples: int) -> np.ndarray:
        """Offsets ``e_n`` of one signal's sampling instants, s, shape ``(n_samples,)``."""
        return rng.normal(0.0, self.rms, n_samples)


@dataclass(frozen=True)
class Gravity(_Effect):
    """Gravity as the accelerometer sees it.

    An accelerometer measures specific force, so at rest it reads ``+g`` along the axis that points
    up. The probe lies horizontal and sweeps in the horizontal plane: X (in the sweep plane) is
    horizontal and reads no gravity, Z is vertical and reads ``+g``. The static sag of the probe is
    a constant deflection and does not change the (linear) vibration.

    Parameters
    ----------
    g : float
        Acceleration of gravity, m/s^2. Default: standard gravity 9.80665 m/s^2.

    Examples
    --------
    >>> import numpy as np
    >>> ax, az = Gravity().apply(np.zeros((1, 2)), np.zeros((1, 2)))
    >>> az
    array([[9.80665, 9.80665]])
    """

    name: ClassVar[str] = "gravity"
    g: float = STANDARD_GRAVITY

    def __post_init__(self):
        check_nonnegative("g", self.g)

    def apply(self, ax, az):
        """Add ``g`` to ``az``; ``ax`` is returned unchanged."""
        return ax, az + self.g


@dataclass(frozen=True)
class MainsHum(_Effect):
    """Mains hum picked up by the sensor's supply and wiring.

    A sinusoid of the mains frequency with a fixed amplitude and a random phase per signal and
    axis. The paper's elliptic filter (Table 2: stop band below 48 Hz, pass band from 52 Hz) is
    placed to remove exactly such a 50 Hz hum.

    Parameters
    ----------
    frequency : float
        Mains frequency, Hz. Default 50 Hz (the 230 V, 50 Hz grid where the rig was built).
    amplitude : float
        Amplitude in each axis, m/s^2. Default 0.05 m/s^2 (about 5 mg): an assumption, a few
        LSB at the +-16 g range.

    Examples
    --------
    >>> import numpy as np
    >>> hum = MainsHum().signal(np.arange(3) / 1000.0, np.array([[0.0]]))
    >>> hum.round(4)
    array([[0.    , 0.0155, 0.0294]])
    """

    name: ClassVar[str] = "mains_hum"
    stream: ClassVar[int] = 2
    frequency: float = 50.0
    amplitude: float = 0.05

    def __post_init__(self):
        check_positive("frequency", self.frequency)
        check_nonnegative("amplitude", self.amplitude)

    def phases(self, rng: np.random.Generator) -> np.ndarray:
        """Random phases (rad) for X and Z, shape ``(2,)``."""
        return rng.uniform(0.0, 2 * math.pi, 2)

    def signal(self, t, phase) -> np.ndarray:
        """``amplitude * sin(2 pi f t + phase)``, m/s^2; ``t`` and ``phase`` broadcast."""
        return self.amplitude * np.sin(2 * math.pi * self.frequency * np.asarray(t) + phase)


@dataclass(frozen=True)
class SensorNoise(_Effect):
    """White noise of the accelerometer.

    The MPU6050's accelerometer noise power spectral density is 400 ug/sqrt(Hz) (InvenSense,
    *MPU-6000 and MPU-6050 Product Specification*, rev. 3.4, 2013, table 6.2). White noise of that
    density sampled at ``fs`` has the standard deviation ``density * sqrt(fs / 2)`` (about 0.088
    m/s^2 at 1 kHz); the sensor's low-pass filter (:class:`LowPassFilter`), when listed, then
    shapes it. Independent in X and Z.

    Parameters
    ----------
    density : float
        Noise amplitude spectral density, (m/s^2)/sqrt(Hz). Default 400 ug/sqrt(Hz).

    Examples
    --------
    >>> round(SensorNoise().std(1000.0), 4)  # m/s^2
    0.0877
    """

    name: ClassVar[str] = "sensor_noise"
    stream: ClassVar[int] = 3
    density: float = ACCEL_NOISE_DENSITY * STANDARD_GRAVITY

    def __post_init__(self):
        check_nonnegative("density", self.density)

    def std(self, fs: float) -> float:
        """Standard deviation of the sampled noise, m/s^2."""
        return self.density * math.sqrt(fs / 2)

    def draw(self, rng: np.random.Generator, n_samples: int, fs: float) -> np.ndarray:
        """Noise of one signal for X and Z, m/s^2, shape ``(2, n_samples)``."""
        return rng.normal(0.0, self.std(fs), (2, n_samples))


#: The MPU6050's accelerometer DLPF bandwidths, Hz, by DLPF_CFG 0..6 (see
#: :data:`ebantenna.chips.mpu6050.DLPF`).
DLPF_BANDWIDTHS = tuple(setting.accel_bandwidth for setting in DLPF)


@dataclass(frozen=True)
class LowPassFilter(_Effect):
    """The MPU6050's digital low-pass filter (DLPF).

    The register map gives only the bandwidth of each DLPF setting, not the filter. It is modelled
    as a second-order Butterworth low-pass with that -3 dB frequency, in second-order sections,
    run causally on the samples. Its state starts settled on the signal's level before the contact
    (gravity only), as the sensor was running before. Default 260 Hz: DLPF_CFG = 0, the power-on
    value of register 26.

    Parameters
    ----------
    bandwidth : float
        -3 dB frequency, Hz, one of :data:`DLPF_BANDWIDTHS`.

    Examples
    --------
    >>> import numpy as np
    >>> y = LowPassFilter().apply(np.ones((1, 50)), 1000.0, np.array([1.0]))
    >>> bool(np.allclose(y, 1.0))
    True
    """

    name: ClassVar[str] = "dlpf"
    bandwidth: float = DLPF[0].accel_bandwidth

    def __post_init__(self):
        check_positive("bandwidth", self.bandwidth)
        if float(self.bandwidth) not in DLPF_BANDWIDTHS:
            valid = ", ".join(f"{b:g}" for b in DLPF_BANDWIDTHS)
            raise ValueError(
                f"bandwidth must be one of {valid} Hz (the MPU6050's DLPF); got {self.bandwidth!r}"
            )

    def sos(self, fs: float) -> np.ndarray:
        """Second-order sections of the filter at sampling frequency ``fs`` (Hz)."""
        if not self.bandwidth < fs / 2:
            raise ValueError(
                f"dlpf bandwidth {self.bandwidth:g} Hz must be below fs/2 = {fs / 2:g} Hz"
            )
        return sps.butter(2, self.bandwidth, btype="low", fs=fs, output="sos")

    def apply(self, a: np.ndarray, fs: float, level) -> np.ndarray:
        """Filter every row of ``a`` (m/s^2); ``level`` (one per row): the settled initial value."""
        sos = self.sos(fs)
        zi = sps.sosfilt_zi(sos)[:, None, :] * np.asarray(level, dtype=float)[None, :, None]
        y, _ = sps.sosfilt(sos, a, axis=-1, zi=zi)
        return y


@dataclass(frozen=True)
class Clipping(_Effect):
    """The accelerometer's full-scale range.

    At AFS_SEL = 3 the MPU6050 measures +-16 g with 2048 LSB/g into a 16-bit two's-complement
    register, so readings saturate at ``-32768`` and ``+32767`` LSB: at ``-16 g`` and
    ``16 g (1 - 2^-15)`` (product specification rev. 3.4, table 6.2; the paper, section 3).

    Parameters
    ----------
    range_g : int
        Full scale, in g: 2, 4, 8 or 16. Default 16.

    Examples
    --------
    >>> import numpy as np
    >>> Clipping(range_g=2).apply(np.array([[-100.0, 0.0, 100.0]])).round(4)
    array([[-19.6133,   0.    ,  19.6127]])
    """

    name: ClassVar[str] = "clipping"
    range_g: int = 16

    def __post_init__(self):
        check_choice("range_g", check_int("range_g", self.range_g), ACCEL_RANGES_G)

    def limits(self) -> tuple[float, float]:
        """Lowest and highest reading, m/s^2."""
        full = self.range_g * STANDARD_GRAVITY
        return -full, full * (1 - 2.0**-15)

    def apply(self, a: np.ndarray) -> np.ndarray:
        """Cap ``a`` (m/s^2) at the range."""
        low, high = self.limits()
        return np.clip(a, low, high)


@dataclass(frozen=True)
class Quantisation(_Effect):
    """16-bit quantisation of the readings.

    The register holds an integer count of LSB, ``LSB = 2 range / 2^16`` (``g/2048`` at +-16 g);
    the reading is rounded to the nearest count. Saturation is :class:`Clipping`'s business.

    Parameters
    ----------
    range_g : int
        Full scale, in g: 2, 4, 8 or 16. Default 16 (must match :class:`Clipping` when both are
        listed).

    Examples
    --------
    >>> import numpy as np
    >>> q = Quantisation()
    >>> float(q.apply(np.array([[0.01]]))[0, 0] / q.lsb())
    2.0
    """

    name: ClassVar[str] = "quantisation"
    range_g: int = 16

    def __post_init__(self):
        check_choice("range_g", check_int("range_g", self.range_g), ACCEL_RANGES_G)

    def lsb(self) -> float:
        """One count, m/s^2."""
        return 2 * self.range_g * STANDARD_GRAVITY / 2**16

    def apply(self, a: np.ndarray) -> np.ndarray:
        """Round ``a`` (m/s^2) to the nearest count."""
        lsb = self.lsb()
        return np.round(a / lsb) * lsb


@dataclass(frozen=True)
class KalmanFilter(_Effect):
    """The acquisition-side Kalman filter (the paper, section 3).

    A scalar Kalman filter per axis with a random-walk model ``x_n = x_(n-1) + w_n`` (variance
    ``q``) observed as ``z_n = x_n + v_n`` (variance ``r``), the usual choice for smoothing sensor
    readings. Run with its steady-state gain it is the first-order recursive filter
    ``y_n = y_(n-1) + K (z_n - y_(n-1))``, where ``K = s / (s + 1)``, ``s = (rho + sqrt(rho^2 +
    4 rho)) / 2`` and ``rho = q / r`` solve the Riccati equation. It starts settled on the level
    before the contact. The paper gives no tuning; ``rho = 1`` (``K = 0.618``, -3 dB at fs/6) is an
    assumption that keeps its analysis band (60-160 Hz) mostly intact.

    Parameters
    ----------
    ratio : float
        ``rho = q / r``, process to measurement noise variance, dimensionless. Default 1.

    Examples
    --------
    >>> round(KalmanFilter().gain(), 6)
    0.618034
    """

    name: ClassVar[str] = "kalman"
    ratio: float = 1.0

    def __post_init__(self):
        check_positive("ratio", self.ratio)

    def gain(self) -> float:
        """Steady-state Kalman gain ``K`` (dimensionless)."""
        rho = self.ratio
        s = (rho + math.sqrt(rho * rho + 4 * rho)) / 2
        return s / (s + 1)

    def apply(self, a: np.ndarray, level) -> np.ndarray:
        """Filter every row of ``a`` (m/s^2) starting from the settled ``level`` (one per row)."""
        k = self.gain()
        zi = (1 - k) * np.asarray(level, dtype=float)[:, None]
        y, _ = sps.lfilter([k], [1.0, -(1.0 - k)], a, axis=-1, zi=zi)
        return y


#: Every effect type, in the order the simulator applies them.
EFFECT_TYPES = (
    StructuralDamping,
    ContactCompliance,
    ContactDamping,
    TipMass,
    ClockJitter,
    Gravity,
    MainsHum,
    SensorNoise,
    LowPassFilter,
    Clipping,
    Quantisation,
    KalmanFilter,
)

_BY_NAME = {cls.name: cls for cls in EFFECT_TYPES}


def effect_names() -> tuple[str, ...]:
    """Names of every effect, in the order the simulator applies them.

    Examples
    --------
    >>> effect_names()[:2]
    ('structural_damping', 'contact_compliance')
    """
    return tuple(_BY_NAME)


def make_effect(effect, params: dict | None = None):
    """An effect instance from a name (with optional parameters) or an instance.

    Raises
    ------
    ValueError
        For an unknown name, listing the valid ones.

    Examples
    --------
    >>> make_effect("sensor_noise", {"density": 0.01})
    SensorNoise(density=0.01)
    """
    if isinstance(effect, EFFECT_TYPES):
        if params:
            raise TypeError("parameters can only be given with an effect's name, not an instance")
        return effect
    if not isinstance(effect, str):
        raise TypeError(f"an effect must be a name or an effect instance, got {effect!r}")
    if effect not in _BY_NAME:
        raise ValueError(f"unknown effect {effect!r}; valid effects: {', '.join(_BY_NAME)}")
    return _BY_NAME[effect].from_parameters(params or {})
