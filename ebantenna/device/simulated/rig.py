"""The simulated rig: pan-tilt unit, probe, accelerometer and post behind a simulated bus.

Before the contact the accelerometer reads the vibration's rest level (:attr:`SimulatedRig.rest`)
plus a little white noise; from the first sample at or after the contact on it plays the vibration
:class:`~ebantenna.recording.Recording`, sample for sample, so that what the driver reads back
matches it to within one LSB. The vibration comes either from given arrays or from the scene
simulator (:meth:`SimulatedRig.from_scene`, :meth:`SimulatedRig.for_contact`). This module is the
only place in :mod:`ebantenna.device` that imports :mod:`ebantenna.simulate`, and only when the
accelerometer first samples. The sensor reports what the simulator computes (with gravity if the
scene includes it).
"""

from __future__ import annotations

import math

import numpy as np

from ..._validate import check_in_range, check_int, check_nonnegative, check_positive
from ...chips.mpu6050 import ADDRESS_AD0_LOW, CHIP_MODELS
from ...chips.pca9685 import DEFAULT_ADDRESS
from ...recording import Recording
from ..clock import VirtualClock
from .bus import SimulatedBus
from .faults import Faults
from .mpu6050 import SimulatedMPU6050
from .pca9685 import SimulatedPCA9685
from .world import DEFAULT_OBSTACLE, MG996R_SLEW_RATE, Obstacle, World

__all__ = ["SimulatedRig"]


#: The part a clone (``Faults.clone_6500``) samples like: the first of the MPU-6500 family.
CLONE_OF = next(value for value, model in CHIP_MODELS.items() if model.accel_config2)


class _SharedAddress:
    """Two chips answering at one address (``Faults.second_device``).

    Both acknowledge, both take every write, and both drive every read onto the open-drain bus,
    which carries a 0 wherever either of them pulls it low: a read returns the bitwise AND of
    their bytes (each chip shifts out its own bytes, so both FIFOs are popped together). The
    faults that act on the accelerometer as a board (a brown-out, a register written by another
    program, a foreign read) act on both.

    Parameters
    ----------
    first, second : object
        The two chips (``read(register, n)``, ``write(register, data)``, ``brown_out()``).

    Examples
    --------
    >>> from ebantenna.device.simulated.rig import _SharedAddress
    >>> class Chip:
    ...     def __init__(self, value): self.value = value
    ...     def read(self, register, n): return [self.value] * n
    >>> _SharedAddress(Chip(0b1011), Chip(0b0110)).read(0, 2)
    [2, 2]
    """

    def __init__(self, first, second):
        self.first, self.second = first, second

    def read(self, register: int, length: int) -> list[int]:
        """The AND of what both chips shift out for this read."""
        ours, theirs = self.first.read(register, length), self.second.read(register, length)
        return [a & b for a, b in zip(ours, theirs, strict=True)]

    def write(self, register: int, data) -> None:
        """Both chips take the write."""
        self.first.write(register, data)
        self.second.write(register, data)

    def brown_out(self) -> None:
        """Both lose power (they share the supply)."""
        self.first.brown_out()
        self.second.brown_out()

    def _corrupt(self, register: int, value: int) -> None:
        self.first._corrupt(register, value)
        self.second._corrupt(register, value)

    def impossible_samples(self) -> int:
        """Samples beyond what either chip can have produced (see the MPU-6050 model)."""
        return max(self.first.impossible_samples(), self.second.impossible_samples())


def _raw_of(mpu, recording) -> dict:
    """The raw record of ``recording``, made by ``mpu``'s stream (checked: a driver with a
    stream, a recording the FIFO stream made)."""
    if getattr(getattr(mpu, "stream", None), "starts", None) is None:
        raise TypeError(f"mpu must be the MPU6050 whose stream made the recording, got "
                        f"{type(mpu).__name__}")
    raw = getattr(recording, "metadata", {}).get("raw") if isinstance(
        getattr(recording, "metadata", None), dict) else None
    if not isinstance(raw, dict) or "segment" not in raw:
        raise TypeError(f"recording must be a Recording made by the FIFO stream (with its raw "
                        f"record), got {type(recording).__name__}")
    return raw


class SimulatedRig:
    """Pan-tilt unit, probe, accelerometer and obstacle, behind a :class:`SimulatedBus`.

    Parameters
    ----------
    vibration : Recording or callable or None
        The tip acceleration from the contact on: a recording, or ``vibration(fs)`` returning one
        for the sample rate the accelerometer is set to (called once, at the first sample); or None.
        Outside it the sensor reads :attr:`rest` plus noise.
    obstacle : Obstacle or None
        Where the post is (default
        :data:`~ebantenna.device.simulated.world.DEFAULT_OBSTACLE`); None for empty space (no
        contact ever).
    faults : Faults, optional
        Faults to inject.
    seed : int
        Seed of the sensor noise and of the fault injector.
    noise : float
        Standard deviation of the sensor noise outside the vibration, m/s^2. Default 0.02.
    slew_rate : float
        Servo speed, degrees/s. Default the MG996R's.

    Attributes
    ----------
    bus : SimulatedBus
    clock : VirtualClock
    world : World
        Servos, post and contact.
    mpu : SimulatedMPU6050
        The accelerometer, at address 0x68.
    second_mpu : SimulatedMPU6050 or None
        A second accelerometer at the same address (``Faults.second_device``), else None.
    pca : SimulatedPCA9685
        The servo controller, at address 0x40.

    Examples
    --------
    >>> from ebantenna.chips.mpu6050 import ADDRESS_AD0_LOW, Register, WHO_AM_I_VALUE
    >>> from ebantenna.device.simulated import SimulatedRig
    >>> rig = SimulatedRig.quiet(seed=2)
    >>> rig.bus.read_byte_data(ADDRESS_AD0_LOW, Register.WHO_AM_I) == WHO_AM_I_VALUE
    True
    >>> rig.contact_time is None
    True
    """

    def __init__(self, vibration=None, *, obstacle: Obstacle | None = DEFAULT_OBSTACLE,
                 faults: Faults | None = None, seed: int = 0, noise: float = 0.02,
                 slew_rate: float = MG996R_SLEW_RATE):
        if not (vibration is None or isinstance(vibration, Recording) or callable(vibration)):
            raise TypeError("vibration must be a Recording, a callable or None, got "
                            f"{type(vibration).__name__}")
        seed = check_int("seed", seed, minimum=0)
        self.noise = check_nonnegative("noise", noise)
        self._vibration = vibration
        self._recording = vibration if isinstance(vibration, Recording) else None
        self._rest_of = None  # (recording, its rest reading): see _rest
        noise_seed, bus_seed = np.random.SeedSequence(seed).spawn(2)
        self._rng = np.random.default_rng(noise_seed)
        self.clock = VirtualClock()
        self.bus = SimulatedBus(self.clock, faults=faults,
                                seed=int(bus_seed.generate_state(1)[0]))
        if not (obstacle is None or isinstance(obstacle, Obstacle)):
            raise TypeError(f"obstacle must be an Obstacle or None, got {type(obstacle).__name__}")
        self.world = World(obstacle, check_positive("slew_rate", slew_rate))
        self.mpu = self._chip(self._acceleration)
        self.pca = SimulatedPCA9685(self.world, self.clock)
        # a second MPU-6050 at the accelerometer's address: the same chip with noise of its
        # own, from a third stream of the seed (the first two stay as they were)
        self.second_mpu = None
        accelerometer = self.mpu
        if self.bus.faults.second_device:
            self._second_rng = np.random.default_rng(np.random.SeedSequence(seed,
                                                                             spawn_key=(2,)))
            self.second_mpu = self._chip(self._second_acceleration)
            accelerometer = _SharedAddress(self.mpu, self.second_mpu)
        self.bus.devices = {ADDRESS_AD0_LOW: accelerometer, DEFAULT_ADDRESS: self.pca}
        #: Time of the first sample at or after the contact, s.
        self.contact_sample_time = None

    def _chip(self, source) -> SimulatedMPU6050:
        """An MPU-6050 measuring ``source``, as the faults make it."""
        faults = self.bus.faults
        return SimulatedMPU6050(source, self.clock, who_am_i=faults.who_am_i,
                                clock_drift=faults.clock_drift,
                                free_running_divider=faults.free_running_divider,
                                repeat_last_byte=faults.repeat_last_byte,
                                samples_like=CLONE_OF if faults.clone_6500 else None,
                                stuck_from=faults.stuck_sensor_at)

    @classmethod
    def quiet(cls, *, seed: int = 0, faults: Faults | None = None) -> SimulatedRig:
        """A rig in empty space: noise only, never a contact."""
        return cls(None, obstacle=None, seed=seed, faults=faults)

    @classmethod
    def from_arrays(cls, ax, az, fs: float, **kwargs) -> SimulatedRig:
        """A rig whose contact plays the given accelerations (m/s^2) sampled at ``fs`` (Hz)."""
        ax = np.asarray(ax, dtype=np.float64)
        rec = Recording(np.arange(ax.size) / check_positive("fs", fs), ax, az, fs,
                        {"source": "arrays"})
        return cls(rec, **kwargs)

    @classmethod
    def from_scene(cls, scene, *, seed: int = 0, **kwargs) -> SimulatedRig:
        """A rig whose contact plays ``simulate(scene, seed=seed)`` (its contact and material).

        The simulator is imported and run only when the accelerometer first samples, at its
        configured sample rate.
        """
        if not (callable(getattr(scene, "with_", None)) and hasattr(scene, "fs")):
            raise TypeError(f"scene must be a Scene (ebantenna.simulate), got "
                            f"{type(scene).__name__}")

        def vibration(fs: float) -> Recording:
            from ...simulate import simulate

            run = scene if math.isclose(scene.fs, fs) else scene.with_(fs=fs)
            return simulate(run, seed=seed)

        return cls(vibration, seed=seed, **kwargs)

    @classmethod
    def for_contact(cls, *, scene: str = "paper", material: str = "brass", ratio: float = 0.5,
                    seed: int = 0, **kwargs) -> SimulatedRig:
        """A rig whose probe touches ``material`` at ``ratio`` of its length, in a built-in scene.

        Parameters
        ----------
        scene : str
            Name of a built-in scene of :mod:`ebantenna.simulate` ("paper" or "ideal").
        material : str
            Touched material (see :func:`ebantenna.probe.material_names`).
        ratio : float
            Contact distance from the hinge over the probe length, in (0, 1).
        seed : int
            Seed of the simulation, the sensor noise and the faults.
        """
        ratio = check_in_range("ratio", ratio, 0.0, 1.0)
        from ...simulate import builtin_scene

        base = builtin_scene(scene)
        chosen = base.with_(contact=ratio * base.probe.length, material=material)
        return cls.from_scene(chosen, seed=seed, **kwargs)

    def wrong_samples(self, mpu, recording) -> int:
        """How many samples of ``recording`` (made by ``mpu``'s stream on this rig) differ from
        what the simulated chip put into its FIFO: the ground truth.

        A kept sample is right when the chip's epoch that started when the driver's segment did
        holds, at the same position, the same counts on all three axes, taken at the range the
        driver converts them with (a range the chip lost makes right counts wrong m/s^2).
        """
        raw = _raw_of(mpu, recording)
        starts = mpu.stream.starts
        epochs = {round(start, 12): k for k, (start, _) in enumerate(self.mpu.epochs)}
        truths = {}
        wrong = 0
        for seg, pos, counts in zip(raw["segment"], raw["position"], raw["counts_xyz"],
                                    strict=True):
            k = epochs.get(round(starts[seg], 12))
            if k is None:
                wrong += 1
                continue
            if k not in truths:
                truths[k] = self.mpu.truth(k), self.mpu._truth_scale(k)
            truth, scale = truths[k]
            wrong += not (pos < len(truth) and list(truth[pos]) == list(counts)
                          and scale[pos] == mpu.config.lsb_per_g)
        return wrong

    def oe_line(self):
        """A GPIO line wired to the PCA9685's ``OE`` pin (for
        :class:`~ebantenna.device.oe.OutputEnable`): it switches the outputs off without I2C."""
        return self.pca.oe_line()

    def true_times(self, mpu, recording) -> np.ndarray:
        """The true host time (s, from the stream's first segment start) at which each sample of
        ``recording`` (made by ``mpu``'s stream on this rig) was taken: the ground truth of its
        timestamps. NaN for a sample of no epoch."""
        raw = _raw_of(mpu, recording)
        starts = mpu.stream.starts
        epochs = {round(start, 12): k for k, (start, _) in enumerate(self.mpu.epochs)}
        period = 1.0 / self.mpu.true_rate()
        out = np.full(len(raw["segment"]), np.nan)
        for i, (seg, pos) in enumerate(zip(raw["segment"], raw["position"], strict=True)):
            k = epochs.get(round(starts[seg], 12))
            if k is not None:
                out[i] = self.mpu.first_sample[k] + pos * period - starts[0]
        return out

    def touch(self, at: float | None = None) -> None:
        """Put the probe in contact from virtual time ``at`` (s; default now), whatever the servos.

        For exercising the accelerometer alone: from then on it plays the vibration.
        """
        now = self.clock.monotonic()
        at = now if at is None else check_nonnegative("at", at)
        if at < now:
            raise ValueError(f"at must be >= the current time {now!r} s, got {at!r}")
        if self.world.contact_time is not None:
            raise ValueError("the probe is already in contact")
        self.world.advance_to(now)
        self.world.contact_time = at

    @property
    def contact_time(self) -> float | None:
        """Virtual time at which the probe met the obstacle, s (None before that)."""
        self.world.advance_to(self.clock.monotonic())
        return self.world.contact_time

    @property
    def vibration(self) -> Recording | None:
        """The recording played from the contact on (None before it is needed)."""
        return self._recording

    @property
    def rest(self) -> np.ndarray:
        """The steady reading (X, Y, Z) outside the vibration, m/s^2: the mean of the last tenth
        of the vibration (where it has died away; gravity, if the simulator includes it), or 0."""
        return self._rest().copy()

    def _rest(self) -> np.ndarray:
        """:attr:`rest`, computed once per vibration (read at every sample the chip catches up
        on, it was a mean over a tenth of the vibration each time); not to be modified."""
        rec = self._recording
        if rec is None:
            return np.zeros(3)
        cached = self._rest_of
        if cached is None or cached[0] is not rec:
            tail = max(1, rec.n_samples // 10)
            cached = self._rest_of = (rec, np.array([rec.ax[-tail:].mean(), 0.0,
                                                     rec.az[-tail:].mean()]))
        return cached[1]

    def _second_acceleration(self, times: np.ndarray, fs: float) -> np.ndarray:
        """What the second device measures: the same acceleration with noise of its own (the
        played vibration carries the first device's noise; the second adds its own to it)."""
        return self._acceleration(times, fs, self._second_rng, own_noise=True)

    def _acceleration(self, times: np.ndarray, fs: float, rng=None, *,
                      own_noise: bool = False) -> np.ndarray:
        rng = self._rng if rng is None else rng
        self.world.advance_to(self.clock.monotonic())
        if self._vibration is not None and self._recording is None:
            self._recording = self._vibration(fs)
            if not isinstance(self._recording, Recording):
                raise TypeError("vibration(fs) must return a Recording")
        rec = self._recording
        faults = self.bus.faults
        if rec is not None and not math.isclose(rec.fs, fs) and not (
                faults.register_lost or faults.flip_write or faults.clone_6500):
            raise ValueError(f"the vibration is sampled at {rec.fs:g} Hz but the simulated "
                             f"MPU-6050 is set to {fs:g} Hz")
        rest = self._rest()
        acc = rest + rng.normal(0.0, self.noise, (times.size, 3))
        contact = self.world.contact_time
        if contact is None or rec is None:
            return acc
        after = times >= contact - 1e-12
        played = after.tolist()  # a few samples a call: Python's any/all are the faster
        if not any(played):
            return acc
        if self.contact_sample_time is None:
            self.contact_sample_time = float(times[after][0])
        # Played sample for sample at the chip's actual rate: with a drifting clock the
        # vibration runs that much faster or slower (a time scale within MAX_CLOCK_DRIFT, as
        # Faults checks). A chip whose rate a fault changed (a setting lost, a clone) plays it
        # in real time, each sample held until the next.
        rate = self.mpu.true_rate() * rec.fs / fs
        j = np.rint((times - self.contact_sample_time) * rate).astype(np.int64)
        index = j.tolist()
        if all(played) and min(index) >= 0 and max(index) < rec.n_samples:
            play = slice(None)  # the usual case, every sample plays: the same, without masks
        else:
            play = after & (j >= 0) & (j < rec.n_samples)
            j = j[play]
        # this draw's noise, for a device that adds its own to the played vibration
        own = acc[play] - rest if own_noise else None
        acc[play, 0] = rec.ax[j]  # Y keeps its rest reading and noise, as a live axis
        acc[play, 2] = rec.az[j]
        if own_noise:
            acc[play, 0] += own[:, 0]
            acc[play, 2] += own[:, 2]
        return acc
