"""Effects of the sensor and the acquisition: they act on the sampled signals, in this order.

:class:`ClockJitter` (when the samples are taken), :class:`Gravity`, :class:`MainsHum`,
:class:`SensorNoise`, :class:`LowPassFilter` (the MPU6050's DLPF), :class:`SensorDrift` (offset
and sensitivity between sessions), :class:`Clipping`,
:class:`Quantisation`, :class:`SteadyStateKalman` (on the Raspberry Pi).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import scipy.signal as sps

from ..._validate import (
    check_array,
    check_choice,
    check_int,
    check_nonnegative,
    check_positive,
    real_array,
)
from ...chips.mpu6050 import ACCEL_NOISE_DENSITY, ACCEL_RANGES_G, DLPF, STANDARD_GRAVITY
from ._base import Effect, check_rng, check_samples


@dataclass(frozen=True)
class ClockJitter(Effect):
    """Jitter of the instants at which the samples are taken.

    **What it models.** Sample ``n`` is taken at ``n / fs + e_n`` instead of ``n / fs``, while
    the recording still assigns it the nominal time. The offsets ``e_n`` are independent, normal,
    with standard deviation ``rms``; the continuous signals (modal response, gravity, hum) are
    evaluated exactly at the jittered instants, a stepped one (a contact law's) by
    :func:`read_through_dlpf`. The MPU6050 takes its samples on its own clock: it writes its
    data registers at the Sample Rate (RM 25 and 59-64), so a moved sampling instant is jitter of
    the chip's sample clock (its oscillator and divider), which the register map does not
    specify. **Assumption:** that jitter, independent from sample to sample, of size ``rms``.
    Simplification: the sensor's own filter then runs on these samples as if they were regular.

    **What it does not model.** The host's timing: a Raspberry Pi whose user-space loop polls
    the data registers late or early does not move the sampling instant; each poll reads the
    last sample the chip wrote, so the host's jitter shows as a sample read twice (a repeat) or
    never (a skip). Repeats and skips are the device layer's concern (:mod:`ebantenna.device`),
    not this effect's.

    Parameters
    ----------
    rms : float
        Standard deviation of the sampling instants, s. Default 50 us: an assumption, no figure
        of the chip's; it is the order of the scheduling latency of a Linux user-space loop
        without real-time priority, a host's figure kept as the size of the jitter.

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
        return check_rng(rng).normal(0.0, self.rms, check_samples(n_samples))


def _sample_instants(jitter: ClockJitter, batch) -> None:
    """The chain's step ``clock_jitter``: each sample taken at ``n / fs + e_n``."""
    batch.when = batch.t + np.stack([jitter.offsets(r, batch.t.size) for r in batch.rngs(jitter)])


def _rest_before_arrest(jitter: ClockJitter, batch) -> None:
    """The chain's step ``clock_jitter`` after the responses: a sample taken before the arrest
    reads rigid rotation, no acceleration."""
    before = batch.when < 0
    batch.ax[before] = 0.0
    batch.az[before] = 0.0


@dataclass(frozen=True)
class Gravity(Effect):
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
        _real("ax", ax)
        _real("az", az)
        if np.shape(ax) != np.shape(az):
            raise ValueError(f"ax and az must have one shape, got {np.shape(ax)} and "
                             f"{np.shape(az)}")
        return ax, az + self.g


def _add_gravity(gravity: Gravity, batch) -> None:
    """The chain's step ``gravity``: a constant, which the settled filter passes unchanged; Z
    rests at ``g``."""
    batch.ax, batch.az = gravity.apply(batch.ax, batch.az)
    batch.levels_z = np.full(batch.n, gravity.g)


@dataclass(frozen=True)
class MainsHum(Effect):
    """Mains hum picked up by the sensor's supply and wiring.

    A sinusoid of the mains frequency with a fixed amplitude and a random phase per signal and
    axis. The paper's elliptic filter (Table 2: stop band below 48 Hz, pass band from 52 Hz) is
    placed to remove exactly such a 50 Hz hum.

    Parameters
    ----------
    frequency : float
        Mains frequency, Hz. Default 50 Hz: an assumption, read from the paper's Table 2 filter
        (stop band below 48 Hz, pass band above 52 Hz), which suits a 50 Hz grid; the paper does
        not say where the rig was built.
    amplitude : float
        Amplitude in each axis, m/s^2. Default 0.05 m/s^2 (about 5 mg): an assumption, about
        10 LSB at the +-16 g range.

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
        return check_rng(rng).uniform(0.0, 2 * math.pi, 2)

    def signal(self, t, phase) -> np.ndarray:
        """``amplitude * sin(2 pi f t + phase)``, m/s^2; ``t`` and ``phase`` broadcast."""
        _real("t", t)
        _real("phase", phase)
        return self.amplitude * np.sin(2 * math.pi * self.frequency * np.asarray(t) + phase)


def _add_hum(hum: MainsHum, batch) -> None:
    """The chain's step ``mains_hum``: a steady tone, which the chip's filter scales and
    delays."""
    dlpf = batch.chip_filter
    gain = complex(dlpf.frequency_response(hum.frequency)) if dlpf is not None else 1.0
    phases = np.stack([hum.phases(r) for r in batch.rngs(hum)]) + np.angle(gain)  # (n, 2)
    tt = batch.when if np.ndim(batch.when) == 2 else batch.when[None, :]
    batch.ax = batch.ax + abs(gain) * hum.signal(tt, phases[:, :1])
    batch.az = batch.az + abs(gain) * hum.signal(tt, phases[:, 1:])


@dataclass(frozen=True)
class SensorNoise(Effect):
    """White noise of the accelerometer.

    The MPU6050's accelerometer noise power spectral density is 400 ug/sqrt(Hz) (InvenSense,
    *MPU-6000 and MPU-6050 Product Specification*, rev. 3.4, 2013, table 6.2), given there at
    10 Hz, with ``AFS_SEL = 0`` (+-2 g) and a 1 kHz output rate. **Assumption:** the same density,
    white, at every frequency up to the internal rate's Nyquist frequency and at the +-16 g range
    the rig uses (the data sheet gives no other). White noise of that density sampled at ``fs``
    has the standard deviation ``density * sqrt(fs / 2)`` (about 0.088 m/s^2 at 1 kHz); the
    sensor's low-pass filter (:class:`LowPassFilter`), when listed, then shapes it. Independent
    in X and Z.

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
        return self.density * math.sqrt(check_positive("fs", fs) / 2)

    def draw(self, rng: np.random.Generator, n_samples: int, fs: float) -> np.ndarray:
        """Noise of one signal for X and Z, m/s^2, shape ``(2, n_samples)``."""
        return check_rng(rng).normal(0.0, self.std(fs), (2, check_samples(n_samples, 2)))

    def draw_signals(self, generators, n_samples: int, fs: float, dlpf=None) -> np.ndarray:
        """Noise of X and Z for every signal (one generator each), shape ``(n, 2, n_samples)``.

        Without the DLPF the noise is white at ``fs``. With it (a :class:`LowPassFilter`), the
        noise is drawn white at the internal rate (the datasheet's density), filtered and
        decimated as the chip does, from :data:`NOISE_WARM_UP` filter time constants before
        the first kept sample, so that the filter starts in its steady state.
        """
        if isinstance(generators, np.random.Generator) or not hasattr(generators, "__len__"):
            raise TypeError(f"generators must be a sequence of numpy.random.Generator, got "
                            f"{type(generators).__name__}")
        check_samples(n_samples, 2 * max(len(generators), 1))
        if dlpf is None:
            return np.stack([self.draw(r, n_samples, fs) for r in generators])
        step = dlpf.divider(fs)
        lead = math.ceil(NOISE_WARM_UP / (2 * math.pi * dlpf.bandwidth) * fs)  # output samples
        size = step * (lead + n_samples)  # internal samples drawn per signal and axis
        out = np.empty((len(generators), 2, n_samples))
        for start in range(0, len(generators), NOISE_BLOCK):
            block = generators[start : start + NOISE_BLOCK]
            raw = np.stack([self.draw(r, size, dlpf.internal_rate) for r in block])
            out[start : start + len(block)] = dlpf.apply_internal(raw, fs)[..., lead:]
        return out


def _add_noise(noise: SensorNoise, batch) -> None:
    """The chain's step ``sensor_noise``: white at the chip's rate, through its filter and
    decimation."""
    scene = batch.scene
    draws = noise.draw_signals(batch.rngs(noise), scene.n_samples, scene.fs, batch.chip_filter)
    batch.ax = batch.ax + draws[:, 0]  # draws: (n, 2, n_samples)
    batch.az = batch.az + draws[:, 1]


def _real(name: str, x) -> None:
    """Refuse ``x`` unless it is real, finite numeric data (checked, not converted: the
    simulator's arrays keep their type), naming it."""
    values = real_array(name, x)
    if not np.all(np.isfinite(values)):
        raise ValueError(f"{name} must contain only finite values (no NaN or inf)")


#: Signals whose internal-rate noise is drawn and filtered at once (bounds the memory).
NOISE_BLOCK = 128
#: Noise is drawn this many of the DLPF's time constants 1/(2 pi bandwidth) before the first
#: kept sample: the second-order Butterworth's poles have the real part -2 pi bandwidth / sqrt(2),
#: so its start-up transient then decays to about exp(-12 / sqrt(2)) = 2e-4 (on the filter itself,
#: 0.9e-4 to 2.4e-4 of the steady RMS over the DLPF settings).
NOISE_WARM_UP = 12


#: The MPU6050's accelerometer DLPF bandwidths, Hz, by DLPF_CFG 0..6 (see
#: :data:`ebantenna.chips.mpu6050.DLPF`).
DLPF_BANDWIDTHS = tuple(setting.accel_bandwidth for setting in DLPF)


@dataclass(frozen=True)
class LowPassFilter(Effect):
    """The MPU6050's digital low-pass filter (DLPF), run at the chip's internal rate.

    The chip samples the accelerometer internally faster than it outputs, filters the samples
    with its DLPF and hands out one sample in every ``internal_rate / fs`` (the accelerometer's
    output rate is 1 kHz, RM 25). Nothing but the DLPF stands between the sensor and the
    decimation, so whatever the DLPF lets through above ``fs / 2`` *aliases*: a mode at
    ``f > fs / 2`` appears at ``|f - m fs|`` with the DLPF's gain at ``f``.

    The register map gives each DLPF setting's bandwidth and delay (RM 26,
    :data:`ebantenna.chips.mpu6050.DLPF`), not the filter; it counts DLPF_CFG = 0 as the filter
    disabled (RM 25), yet lists 260 Hz and 0 ms for the accelerometer there. Assumptions, named
    here once: the filter is a second-order Butterworth low-pass with that -3 dB frequency,
    discretised at the internal rate (its zeros then lie at the internal Nyquist frequency, far
    above the band, not at ``fs / 2``); the internal rate is 8 kHz, the rate of the same chip's
    gyroscope path with the filter off (RM 25; the accelerometer's own internal rate is not
    published). The model matches each setting's bandwidth (its gain there is 1/sqrt(2)) but not
    its delay: its group delay at 0 Hz is 0.86, 1.22, 2.39, 5.11, 10.72, 22.51 and 45.02 ms for
    DLPF_CFG 0 to 6, against the register map's 0, 2.0, 3.0, 4.9, 8.5, 13.8 and 19.0 ms
    (``scipy.signal.group_delay`` of ``sos`` at the internal rate; the register map does not
    say how it defines its delay). The filter starts settled on the signal's level before the
    contact (gravity only), as the sensor was running before. Default bandwidth 260 Hz:
    DLPF_CFG = 0, the power-on value of register 26.

    The simulator does not sample the modal response at the internal rate and filter it: a sum
    of damped exponentials stays one through a linear filter, so the modal sum reads this
    filter's design (``sos``, ``internal_rate``) and gives the filtered and decimated signal
    in closed form (:func:`~ebantenna.simulate.modes.filtered_exponentials`; the witness,
    :func:`scipy.signal.sosfilt` at the internal rate followed by the decimation, agrees to
    rounding). Noise, which has no such form, is drawn at the internal rate and filtered
    (:meth:`apply_internal`).

    Parameters
    ----------
    bandwidth : float
        -3 dB frequency, Hz, one of :data:`DLPF_BANDWIDTHS`.
    internal_rate : float
        The rate the filter runs at, Hz: an integer multiple of the scene's sampling frequency.

    Attributes
    ----------
    sos : ndarray of shape (1, 6)
        The filter's design: its second-order sections at ``internal_rate``, computed once from
        the two parameters when the effect is made and shared by every use (not to be changed
        in place).

    Examples
    --------
    >>> import numpy as np
    >>> dlpf = LowPassFilter()
    >>> dlpf.sos.shape
    (1, 6)
    >>> dlpf.divider(1000.0)
    8
    >>> float(abs(dlpf.frequency_response(700.0)).round(3))  # a 700 Hz mode, seen at 300 Hz
    0.131
    """

    name: ClassVar[str] = "dlpf"
    bandwidth: float = DLPF[0].accel_bandwidth
    internal_rate: float = 8000.0

    def __post_init__(self):
        check_positive("bandwidth", self.bandwidth)
        if float(self.bandwidth) not in DLPF_BANDWIDTHS:
            valid = ", ".join(f"{b:g}" for b in DLPF_BANDWIDTHS)
            raise ValueError(
                f"bandwidth must be one of {valid} Hz (the MPU6050's DLPF); got {self.bandwidth!r}"
            )
        check_positive("internal_rate", self.internal_rate)
        if not self.bandwidth < self.internal_rate / 2:
            raise ValueError(
                f"internal_rate must exceed twice the bandwidth ({2 * self.bandwidth:g} Hz), "
                f"got {self.internal_rate!r} Hz"
            )
        # The design, once: whoever passes a signal through the filter (the modal sum's closed
        # form, the filtering at the internal rate, the gain) reads it as a value. Not a field:
        # the effect's parameters stay the two above.
        sos = sps.butter(2, self.bandwidth, btype="low", fs=self.internal_rate, output="sos")
        object.__setattr__(self, "sos", sos)

    def divider(self, fs: float) -> int:
        """How many internal samples make one output sample at ``fs`` (Hz); raise unless whole."""
        ratio = self.internal_rate / check_positive("fs", fs)
        whole = round(ratio)
        if whole < 1 or abs(ratio - whole) > 1e-9 * ratio:
            raise ValueError(
                f"the dlpf's internal_rate ({self.internal_rate:g} Hz) must be a whole multiple "
                f"of fs, got fs = {fs:g} Hz"
            )
        return int(whole)

    def _transfer(self):
        """``(b, a)`` of the filter, and its gain ``B(1/z) / A(1/z)`` as a function of ``z``."""
        b, a = sps.sos2tf(self.sos)
        return b, a, lambda z: np.polyval(b[::-1], 1 / z) / np.polyval(a[::-1], 1 / z)

    def frequency_response(self, frequency) -> np.ndarray:
        """Complex gain ``H(exp(2 pi i f / internal_rate))`` at ``frequency`` (Hz)."""
        frequency = real_array("frequency", frequency)
        if not np.all(np.isfinite(frequency)):
            raise ValueError("frequency must contain only finite values (no NaN or inf)")
        _, _, gain = self._transfer()
        return gain(np.exp(2j * math.pi * frequency / self.internal_rate))

    def apply_internal(self, a: np.ndarray, fs: float) -> np.ndarray:
        """Filter rows sampled at the internal rate (m/s^2) from rest; decimate them to ``fs``."""
        y = sps.sosfilt(self.sos, a, axis=-1)
        return y[..., :: self.divider(fs)]


def read_through_dlpf(dlpf, acc, rate, when) -> np.ndarray:
    """An axis stepped in time, through the chip's filter, read at the sample times.

    The contact laws (``unilateral_contact``, ``coulomb_friction``) give the acceleration at a
    fixed rate (:func:`~ebantenna.simulate.strikes.timed_rate`): the filter's internal rate
    when the chain has a :class:`LowPassFilter` (the ``chip_filter`` of
    :class:`~ebantenna.simulate.simulator.SignalBatch`). It is filtered there
    (:meth:`LowPassFilter.apply_internal`) and read at the sample times by linear interpolation
    between the internal samples. At whole internal samples (the nominal times, without
    :class:`ClockJitter`) this is exact; between them (jittered times) it is the chord between
    the two neighbouring filtered samples, an approximation of the filtered signal at that
    instant.

    Parameters
    ----------
    dlpf : LowPassFilter or None
        The chip's filter; None for none (the rows are only read at ``when``).
    acc : ndarray of shape (n, n_int)
        The accelerations from the first touch, sampled at ``rate``, m/s^2.
    rate : float
        Their sample rate, Hz: the filter's ``internal_rate`` when there is one.
    when : ndarray of shape (n_samples,) or (n, n_samples)
        The sample times, s (one row per signal with clock jitter).

    Returns
    -------
    ndarray of shape (n, n_samples)
        m/s^2.

    Examples
    --------
    >>> import numpy as np
    >>> ramp = np.arange(16.0)[None, :]  # 1 m/s^2 more at every sample of 8 kHz
    >>> read_through_dlpf(None, ramp, 8000.0, np.array([0.0, 0.001]))
    array([[0., 8.]])
    """
    if dlpf is not None and not isinstance(dlpf, LowPassFilter):
        raise TypeError(f"dlpf must be a LowPassFilter or None, got {type(dlpf).__name__}")
    acc = check_array("acc", acc, ndim=2)
    rate = check_positive("rate", rate)
    when = check_array("when", when, ndim=(1, 2))
    if when.ndim == 2 and when.shape[0] != acc.shape[0]:
        raise ValueError(f"when must have one row per row of acc ({acc.shape[0]}), got shape "
                         f"{when.shape}")
    if dlpf is not None:
        if rate != dlpf.internal_rate:
            raise ValueError(f"rate must be the dlpf's internal_rate ({dlpf.internal_rate:g} Hz), "
                             f"got {rate:g} Hz")
        acc = dlpf.apply_internal(acc, rate)  # filtered, at the internal rate
    grid = np.arange(acc.shape[1]) / rate
    rows = np.broadcast_to(when, acc.shape[:1] + np.shape(when)[-1:])
    return np.stack([np.interp(w, grid, a) for w, a in zip(rows, acc, strict=True)])


def _read_timed(_, batch) -> None:
    """The axes stepped in time (``batch.timed_acc``, at their models' rate): read by the chip
    at the sample instants, through its filter if listed (:func:`read_through_dlpf`)."""
    for axis, (acc, rate) in batch.timed_acc.items():
        # the batch's field ax or az
        setattr(batch, "a" + axis, read_through_dlpf(batch.chip_filter, acc, rate, batch.when))


#: MPU6050 zero-g level change over 0-70 degC, X and Y axes, g (PS rev. 3.4, table 6.2).
ZERO_G_DRIFT_XY = 35e-3
#: The same for the Z axis, g (PS rev. 3.4, table 6.2).
ZERO_G_DRIFT_Z = 60e-3
#: Span of temperature those drifts are specified over, degC (PS rev. 3.4, table 6.2).
DRIFT_SPAN = 70.0
#: MPU6050 sensitivity change with temperature, per degC (+-0.02 %/degC, PS rev. 3.4, table 6.2).
SENSITIVITY_DRIFT = 2e-4


@dataclass(frozen=True)
class SensorDrift(Effect):
    """The accelerometer's offset and gain differ between recording sessions.

    The MPU6050's zero-g level moves by up to 35 mg (X) and 60 mg (Z) over 0-70 degC and its
    sensitivity by 0.02 %/degC (product specification rev. 3.4, table 6.2). Taking the drifts
    as linear in temperature, a session at a room temperature ``delta`` away from another reads
    ``(1 + s_g delta) a + (o / 70 degC) delta`` instead of ``a``, per axis, with the datasheet's
    ``o`` and ``s_g``. Assumptions: the room's temperature varies between sessions with a standard
    deviation of ``temperature_std``; the paper does not say how the recordings were grouped in
    time, so each recording is taken as its own session (the drift is drawn per recording and
    axis, independent of the material, so it can never label one). Applied after the sensor's
    filter, before clipping.

    Parameters
    ----------
    temperature_std : float
        Standard deviation of the room's temperature between sessions, degC. Default 3 degC.

    Examples
    --------
    >>> import numpy as np
    >>> gain, offset = SensorDrift().draw(np.random.default_rng(0))
    >>> gain.shape, offset.shape
    ((2,), (2,))
    """

    name: ClassVar[str] = "sensor_drift"
    stream: ClassVar[int] = 5
    temperature_std: float = 3.0

    def __post_init__(self):
        check_nonnegative("temperature_std", self.temperature_std)

    def draw(self, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
        """One session's gain factors and offsets (m/s^2) for X and Z."""
        delta = check_rng(rng).normal(0.0, self.temperature_std, 2)
        gain = 1.0 + SENSITIVITY_DRIFT * delta
        offset = np.array([ZERO_G_DRIFT_XY, ZERO_G_DRIFT_Z]) / DRIFT_SPAN * delta
        return gain, offset * STANDARD_GRAVITY

    def offset_std(self) -> np.ndarray:
        """Standard deviation of the offsets of X and Z, m/s^2."""
        scale = self.temperature_std / DRIFT_SPAN * STANDARD_GRAVITY
        return np.array([ZERO_G_DRIFT_XY, ZERO_G_DRIFT_Z]) * scale

    def gain_std(self) -> float:
        """Standard deviation of the gain factor (dimensionless)."""
        return SENSITIVITY_DRIFT * self.temperature_std


def _drift(drift: SensorDrift, batch) -> None:
    """The chain's step ``sensor_drift``: after the filter, the chip's offset and sensitivity of
    this session; the axes' resting levels move with them."""
    draws = [drift.draw(r) for r in batch.rngs(drift)]
    gains = np.stack([g for g, _ in draws])
    offsets = np.stack([o for _, o in draws])
    batch.ax = gains[:, :1] * batch.ax + offsets[:, :1]
    batch.az = gains[:, 1:] * batch.az + offsets[:, 1:]
    batch.levels_x = offsets[:, 0].copy()
    batch.levels_z = gains[:, 1] * batch.levels_z + offsets[:, 1]


@dataclass(frozen=True)
class Clipping(Effect):
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
        """Cap ``a`` (m/s^2, finite) at the range."""
        _real("a", a)
        low, high = self.limits()
        return np.clip(a, low, high)


def _clip(clipping: Clipping, batch) -> None:
    """The chain's step ``clipping``: the chip's range, on both axes. The samples it moves to a
    rail are counted per signal (``batch.saturated``, X and Z together): a saturated recording is
    a fact of the data, which a study reports."""
    low, high = clipping.limits()
    batch.saturated = sum(np.count_nonzero((a < low) | (a > high), axis=-1)
                        for a in (batch.ax, batch.az))
    batch.ax, batch.az = clipping.apply(batch.ax), clipping.apply(batch.az)


@dataclass(frozen=True)
class Quantisation(Effect):
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
        """Round ``a`` (m/s^2, finite) to the nearest count."""
        _real("a", a)
        lsb = self.lsb()
        return np.round(a / lsb) * lsb


def _quantise(quantisation: Quantisation, batch) -> None:
    """The chain's step ``quantisation``: the chip's 16-bit output, on both axes."""
    batch.ax, batch.az = quantisation.apply(batch.ax), quantisation.apply(batch.az)


@dataclass(frozen=True)
class SteadyStateKalman(Effect):
    """The acquisition-side Kalman filter (the paper, section 3).

    A scalar Kalman filter per axis with a random-walk model ``x_n = x_(n-1) + w_n`` (variance
    ``q``) observed as ``z_n = x_n + v_n`` (variance ``r``), the usual choice for smoothing sensor
    readings. Run with its steady-state gain it is the first-order recursive filter
    ``y_n = y_(n-1) + K (z_n - y_(n-1))``, where ``K = s / (s + 1)``, ``s = (rho + sqrt(rho^2 +
    4 rho)) / 2`` and ``rho = q / r`` solve the Riccati equation. It starts settled on the level
    before the contact. The paper gives no tuning; ``rho = 1`` (``K = 0.618``, -3 dB at fs/6) is an
    assumption. Across its analysis band (60-160 Hz) at fs = 1 kHz it passes 0.936 of the
    amplitude (-0.57 dB) at 60 Hz and 0.720 (-2.85 dB) at 160 Hz, its -3 dB frequency being
    166.7 Hz (the magnitude of ``K / (1 - (1 - K) e^(-i w))``).

    Parameters
    ----------
    ratio : float
        ``rho = q / r``, process to measurement noise variance, dimensionless. Default 1.

    Examples
    --------
    >>> round(SteadyStateKalman().gain(), 6)
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
        _real("a", a)
        _real("level", level)
        if np.ndim(a) != 2 or np.shape(level) != np.shape(a)[:1]:
            raise ValueError(f"a must be 2-D and level hold one level per row of it, got shapes "
                             f"{np.shape(a)} and {np.shape(level)}")
        k = self.gain()
        zi = (1 - k) * np.asarray(level, dtype=float)[:, None]
        y, _ = sps.lfilter([k], [1.0, -(1.0 - k)], a, axis=-1, zi=zi)
        return y


def _kalman(kalman: SteadyStateKalman, batch) -> None:
    """The chain's step ``kalman``: the filter on the Raspberry Pi, about each axis's resting
    level."""
    batch.ax = kalman.apply(batch.ax, batch.levels_x)
    batch.az = kalman.apply(batch.az, batch.levels_z)


#: The chain's steps of the sensor and the acquisition, each ``step(effect, batch)`` beside the
#: effect whose physics it applies: it changes the simulator's
#: :class:`~ebantenna.simulate.simulator.SignalBatch` in place, with values the simulator
#: checked. :data:`ebantenna.simulate.simulator.CHAIN` puts them in order, and says why.
CHAIN_STEPS = {
    "sample_instants": _sample_instants,
    "read_timed": _read_timed,
    "rest_before_arrest": _rest_before_arrest,
    "gravity": _add_gravity,
    "mains_hum": _add_hum,
    "sensor_noise": _add_noise,
    "sensor_drift": _drift,
    "clipping": _clip,
    "quantisation": _quantise,
    "kalman": _kalman,
}
