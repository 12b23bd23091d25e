"""A simulated I2C bus with an MPU-6050 and a PCA9685 on it, so that the drivers run unchanged
without the rig.

:class:`SimulatedBus` offers the subset of :class:`smbus2.SMBus` the drivers use. It runs in virtual
time (:class:`~ebantenna.device.clock.VirtualClock`): each transfer advances the clock by its
duration on a 400 kHz bus plus a fixed per-transfer overhead, and sleeping advances it instantly,
so a ten-second search takes a fraction of a second.

:class:`SimulatedPCA9685` keeps the chip's registers with the datasheet's rules (``PRE_SCALE`` only
writable asleep, auto-increment only with ``MODE1.AI``, ``ALL_LED`` registers, full-off bits) and
turns the channels' pulse widths into servo commands. The servos slew towards their commands at the
MG996R's rated speed, 60 degrees in 0.17 s at 4.8 V. When the pan angle reaches the
:class:`Obstacle` with the tilt inside its span, that is the contact: the probe stops there.

:class:`SimulatedMPU6050` keeps its registers, samples at the rate they set, quantises to the set
range and fills a 1024-byte FIFO that overflows (overwriting its oldest bytes and raising
``FIFO_OFLOW_INT``) when drained too slowly. Before the contact it reads the vibration's rest level
(:attr:`SimulatedRig.rest`) plus a little white noise; from the first sample at or after the contact
on it plays the vibration :class:`~ebantenna.recording.Recording`, sample for sample, so that what
the driver reads back matches it to within one LSB. The vibration comes either from given arrays or
from the scene simulator (:meth:`SimulatedRig.from_scene`, which is the only place in
:mod:`ebantenna.device` that imports :mod:`ebantenna.simulate`, and only when the accelerometer
first samples). The sensor reports what the simulator computes (with gravity if the scene includes
it) and does not model the chip's own low-pass filter.

:class:`Faults` injects transient ``OSError`` (errno 121) at a given rate, a wrong ``WHO_AM_I`` and
a host stall (the driver descheduled for a while, so the FIFO overflows).
"""

from __future__ import annotations

import errno
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .._validate import check_in_range, check_int, check_nonnegative, check_positive, check_real
from ..recording import Recording
from .clock import VirtualClock
from .mpu6050 import STANDARD_GRAVITY

__all__ = [
    "SimulatedBus",
    "SimulatedMPU6050",
    "SimulatedPCA9685",
    "SimulatedRig",
    "Obstacle",
    "Faults",
    "MG996R_SLEW_RATE",
]

#: MG996R speed at 4.8 V, no load: 0.17 s per 60 degrees (maker's data sheet), degrees/s.
MG996R_SLEW_RATE = 60.0 / 0.17


@dataclass(frozen=True)
class Faults:
    """Faults to inject into the simulated bus.

    Parameters
    ----------
    error_rate : float
        Probability that a transfer fails with ``OSError(121, "Remote I/O error")``, in [0, 1).
        A failed transfer has no effect on the chip.
    who_am_i : int
        What the MPU-6050's ``WHO_AM_I`` reads; 0x68 for a genuine chip.
    stall_at : float or None
        Virtual time (s) after which the host stalls once, for ``stall_duration``.
    stall_duration : float
        Length of that stall, s.

    Examples
    --------
    >>> from ebantenna.device.simbus import Faults
    >>> Faults(error_rate=0.05).error_rate
    0.05
    """

    error_rate: float = 0.0
    who_am_i: int = 0x68
    stall_at: float | None = None
    stall_duration: float = 0.0

    def __post_init__(self):
        check_in_range("error_rate", self.error_rate, 0.0, 1.0, low_inclusive=True)
        check_int("who_am_i", self.who_am_i, minimum=0, maximum=255)
        if self.stall_at is not None:
            check_nonnegative("stall_at", self.stall_at)
        check_nonnegative("stall_duration", self.stall_duration)


@dataclass(frozen=True)
class Obstacle:
    """An upright post in the probe's reach.

    Parameters
    ----------
    pan : float
        Pan angle (servo degrees) at which the probe meets the post.
    tilt_low, tilt_high : float
        Tilt range (servo degrees) over which the post is there.

    Examples
    --------
    >>> from ebantenna.device.simbus import Obstacle
    >>> Obstacle().blocks(90.0), Obstacle().blocks(60.0)
    (True, False)
    """

    pan: float = 125.0
    tilt_low: float = 70.0
    tilt_high: float = 110.0

    def __post_init__(self):
        check_real("pan", self.pan)
        check_real("tilt_low", self.tilt_low)
        check_real("tilt_high", self.tilt_high)
        if not self.tilt_low < self.tilt_high:
            raise ValueError(
                f"tilt_low must be < tilt_high ({self.tilt_high!r}), got {self.tilt_low!r}")

    def blocks(self, tilt: float) -> bool:
        """Whether the post is there at this tilt."""
        return self.tilt_low <= tilt <= self.tilt_high


class _Servo:
    """A servo slewing at constant speed towards its command; None command: unpowered, stays."""

    def __init__(self, angle: float, rate: float):
        self.angle = angle
        self.target = None
        self.rate = rate

    def position(self, dt: float) -> float:
        if self.target is None:
            return self.angle
        step = self.rate * dt
        delta = self.target - self.angle
        return self.target if abs(delta) <= step else self.angle + math.copysign(step, delta)

    def arrival(self) -> float:
        return 0.0 if self.target is None else abs(self.target - self.angle) / self.rate


class _World:
    """Servo motion, the obstacle and the moment of contact, advanced lazily in virtual time."""

    def __init__(self, obstacle: Obstacle | None, rate: float):
        self.obstacle = obstacle
        self.pan = _Servo(90.0, rate)
        self.tilt = _Servo(90.0, rate)
        self.time = 0.0
        self.contact_time = None
        self.contact_tilt = None
        #: Furthest the pan was commanded past the post after the contact, degrees.
        self.max_push = 0.0
        self.blocked = False
        self.direction = 1.0
        self.commands: list[tuple[float, str, float | None]] = []

    def advance_to(self, now: float) -> None:
        while now > self.time:
            # Move in pieces that end where a servo arrives, so motion within a piece is linear.
            dt = now - self.time
            for servo in (self.pan, self.tilt):
                arrival = servo.arrival()
                if 0.0 < arrival < dt:
                    dt = arrival
            pan0 = self.pan.angle
            pan1 = self.pan.position(dt)
            if self.contact_time is None and self.obstacle is not None:
                lo, hi = sorted((pan0, pan1))
                if lo <= self.obstacle.pan <= hi and pan0 != pan1:
                    tau = abs(self.obstacle.pan - pan0) / self.pan.rate
                    tilt = self.tilt.position(tau)
                    if self.obstacle.blocks(tilt):
                        self.contact_time = self.time + tau
                        self.contact_tilt = tilt
                        self.direction = math.copysign(1.0, pan1 - pan0)
                        self.blocked = True
                        self.max_push = (self.pan.target - self.obstacle.pan) * self.direction
            if self.blocked:
                # The post stops the probe: the pan cannot pass it.
                if (pan1 - self.obstacle.pan) * self.direction > 0:
                    pan1 = self.obstacle.pan
            self.tilt.angle = self.tilt.position(dt)
            self.pan.angle = pan1
            self.time += dt
            if dt <= 0.0:  # pragma: no cover - guards against a zero step
                break

    def command(self, now: float, axis: str, angle: float | None) -> None:
        self.advance_to(now)
        servo = self.pan if axis == "pan" else self.tilt
        servo.target = angle
        self.commands.append((now, axis, angle))
        if axis == "pan" and angle is not None and self.blocked:
            push = (angle - self.obstacle.pan) * self.direction
            self.max_push = max(self.max_push, push)


class SimulatedPCA9685:
    """Register model of the PCA9685 driving two simulated MG996R servos.

    Parameters
    ----------
    world : _World
        The servo motion model it commands.
    clock : VirtualClock
        The bus's clock.
    pan_channel, tilt_channel : int
        Outputs the two servos hang on.
    oscillator_hz : float
        The chip's oscillator, Hz.
    """

    def __init__(self, world, clock, *, pan_channel: int = 0, tilt_channel: int = 1,
                 oscillator_hz: float = 25e6):
        self.world = world
        self.clock = clock
        self.channels = {check_int("pan_channel", pan_channel, minimum=0, maximum=15): "pan",
                         check_int("tilt_channel", tilt_channel, minimum=0, maximum=15): "tilt"}
        self.oscillator_hz = oscillator_hz
        self.regs = bytearray(256)
        self.prescale_blocked = 0
        self.reset()

    def reset(self) -> None:
        """Power-on state (DS 7.3): MODE1 0x11 (asleep), MODE2 0x04, PRE_SCALE 0x1E, all off."""
        self.regs[:] = bytes(256)
        self.regs[0x00] = 0x11
        self.regs[0x01] = 0x04
        self.regs[0xFE] = 0x1E
        for ch in range(16):
            self.regs[0x06 + 4 * ch + 3] = 0x10
        self._apply()

    def frequency(self) -> float:
        """PWM frequency set by PRE_SCALE, Hz."""
        return self.oscillator_hz / (4096.0 * (self.regs[0xFE] + 1))

    def pulse(self, channel: int) -> float:
        """Pulse width now on ``channel``, s (0 when it is off or the chip sleeps)."""
        if self.regs[0x00] & 0x10:
            return 0.0
        on_l, on_h, off_l, off_h = self.regs[0x06 + 4 * channel: 0x0A + 4 * channel]
        if off_h & 0x10 or on_h & 0x10:
            return 0.0  # full off, or full on (no pulses: a servo ignores it)
        width = (((off_h & 0x0F) << 8 | off_l) - ((on_h & 0x0F) << 8 | on_l)) % 4096
        return width / (4096.0 * self.frequency())

    def outputs_enabled(self) -> bool:
        """Whether any servo channel is producing pulses."""
        return any(self.pulse(ch) > 0 for ch in self.channels)

    def _apply(self) -> None:
        now = self.clock.monotonic()
        for ch, axis in self.channels.items():
            width = self.pulse(ch)
            # The simulated MG996R: 0.5 ms -> 0 deg, 2.5 ms -> 180 deg, end stops beyond.
            angle = None if width == 0 else min(max((width - 0.5e-3) / 2e-3 * 180.0, 0.0), 180.0)
            servo = self.world.pan if axis == "pan" else self.world.tilt
            if angle != servo.target:
                self.world.command(now, axis, angle)

    def read(self, register: int, length: int) -> list[int]:
        step = 1 if self.regs[0x00] & 0x20 else 0
        return [self.regs[(register + k * step) & 0xFF] for k in range(length)]

    def write(self, register: int, data) -> None:
        step = 1 if self.regs[0x00] & 0x20 else 0
        for k, value in enumerate(data):
            reg = (register + k * step) & 0xFF
            if reg == 0xFE and not self.regs[0x00] & 0x10:
                self.prescale_blocked += 1  # DS 7.3.5: PRE_SCALE is blocked while awake
                continue
            if reg == 0x00:
                value &= 0x7F  # writing RESTART restarts the PWM and the bit clears itself
            if 0xFA <= reg <= 0xFD:
                for ch in range(16):
                    self.regs[0x06 + 4 * ch + (reg - 0xFA)] = value
                continue
            self.regs[reg] = value
        self._apply()


class SimulatedMPU6050:
    """Register model of the MPU-6050: sleep, sample rate, range, FIFO with overflow.

    Parameters
    ----------
    source : callable
        ``source(times, fs)`` returns the (n, 3) accelerations in m/s^2 at the sample times
        ``times`` (s) for the sample rate ``fs`` (Hz).
    clock : VirtualClock
        The bus's clock.
    who_am_i : int
        What ``WHO_AM_I`` reads.
    """

    FIFO_SIZE = 1024

    def __init__(self, source: Callable, clock, *, who_am_i: int = 0x68):
        self.source = source
        self.clock = clock
        self.who_am_i = who_am_i
        self.regs = bytearray(128)
        self.fifo = bytearray()
        self.overflowed_bytes = 0
        self.samples_pushed = 0
        self.reset()

    def reset(self) -> None:
        """Power-on state (RM section 3): all zero but PWR_MGMT_1 = 0x40 (asleep) and WHO_AM_I."""
        self.regs[:] = bytes(128)
        self.regs[0x6B] = 0x40
        self.regs[0x75] = self.who_am_i
        self.fifo.clear()
        self._since = None
        self._produced = 0

    def sample_rate(self) -> float:
        """Sample rate set by CONFIG and SMPLRT_DIV, Hz (RM register 25)."""
        dlpf = self.regs[0x1A] & 0x07
        return (8000.0 if dlpf in (0, 7) else 1000.0) / (1 + self.regs[0x19])

    def lsb_per_g(self) -> int:
        """Sensitivity from ACCEL_CONFIG.AFS_SEL, LSB/g."""
        return 16384 >> ((self.regs[0x1C] >> 3) & 0x03)

    def _producing(self) -> bool:
        return (not self.regs[0x6B] & 0x40) and bool(self.regs[0x6A] & 0x40) and bool(
            self.regs[0x23] & 0x08)

    def _counts(self, times: np.ndarray) -> np.ndarray:
        acc = np.asarray(self.source(times, self.sample_rate()), dtype=np.float64)
        counts = np.rint(acc / STANDARD_GRAVITY * self.lsb_per_g())
        return np.clip(counts, -32768, 32767).astype(">i2")

    def _catch_up(self) -> None:
        if self._since is None:
            return
        now = self.clock.monotonic()
        fs = self.sample_rate()
        target = int(math.floor((now - self._since) * fs + 1e-9))
        if target <= self._produced:
            return
        k = np.arange(self._produced, target)
        times = self._since + (k + 1) / fs
        self.fifo += self._counts(times).tobytes()
        self.samples_pushed += k.size
        self._produced = target
        excess = len(self.fifo) - self.FIFO_SIZE
        if excess > 0:
            # RM register 35 / PS 7.17: the oldest data are overwritten.
            del self.fifo[:excess]
            self.overflowed_bytes += excess
            if self.regs[0x38] & 0x10:
                self.regs[0x3A] |= 0x10

    def _update_state(self, was_producing: bool) -> None:
        producing = self._producing()
        if producing and not was_producing:
            self._since = self.clock.monotonic()
            self._produced = 0
        elif was_producing and not producing:
            self._since = None

    def read(self, register: int, length: int) -> list[int]:
        self._catch_up()
        out = []
        reg = register
        for _ in range(length):
            if reg == 0x74:
                out.append(self.fifo.pop(0) if self.fifo else 0xFF)
                continue
            if reg == 0x72:
                value = len(self.fifo) >> 8
            elif reg == 0x73:
                value = len(self.fifo) & 0xFF
            elif 0x3B <= reg <= 0x40:
                value = self._latest()[reg - 0x3B]
            else:
                value = self.regs[reg]
                if reg == 0x3A:
                    self.regs[0x3A] = 0  # cleared by reading (INT_RD_CLEAR = 0)
            out.append(value)
            reg = min(reg + 1, 0x7F)
        return out

    def _latest(self) -> bytes:
        if self.regs[0x6B] & 0x40:
            return bytes(6)
        fs = self.sample_rate()
        tick = math.floor(self.clock.monotonic() * fs) / fs
        return self._counts(np.array([tick])).tobytes()

    def write(self, register: int, data) -> None:
        self._catch_up()
        for k, value in enumerate(data):
            reg = (register + k) & 0x7F
            was = self._producing()
            if reg == 0x6B and value & 0x80:
                self.reset()
                continue
            if reg == 0x23 and value & ~0x08:
                raise ValueError(
                    "the simulated MPU-6050 models only accelerometer data in the FIFO "
                    f"(FIFO_EN = 0x08); got FIFO_EN = 0x{value:02X}")
            if reg in (0x75, 0x3A, 0x72, 0x73) or 0x3B <= reg <= 0x48:
                continue  # read-only
            if reg == 0x6A:
                if value & 0x04 and not value & 0x40:
                    self.fifo.clear()
                value &= ~0x07 & 0xFF  # reset bits clear themselves
            self.regs[reg] = value
            self._update_state(was)


class SimulatedBus:
    """The :class:`smbus2.SMBus` subset the drivers use, with simulated chips behind it.

    Parameters
    ----------
    clock : VirtualClock, optional
        Virtual time; a new one by default.
    devices : dict, optional
        Simulated chips by 7-bit address (objects with ``read(register, n)`` and
        ``write(register, data)``); an address with no chip does not acknowledge (errno 121).
    faults : Faults, optional
        What to inject.
    seed : int
        Seed of the fault injector.
    bus_hz : float
        I2C clock, Hz. Default 400 kHz (fast mode, the paper's rate).
    overhead : float
        Fixed cost of one transfer (system call, driver), s. Default 50 us.

    Attributes
    ----------
    devices : dict
        Chips by 7-bit address.
    writes : list of (address, register, tuple of int)
        Every completed write, in order.
    errors_injected : int
        Transfers failed on purpose.
    """

    def __init__(self, clock=None, *, devices: dict | None = None, faults: Faults | None = None,
                 seed: int = 0, bus_hz: float = 400e3, overhead: float = 50e-6):
        self.clock = VirtualClock() if clock is None else clock
        self.faults = Faults() if faults is None else faults
        if not isinstance(self.faults, Faults):
            raise TypeError(f"faults must be a Faults, got {type(faults).__name__}")
        self.bus_hz = check_positive("bus_hz", bus_hz)
        self.overhead = check_nonnegative("overhead", overhead)
        self._rng = np.random.default_rng(check_int("seed", seed, minimum=0))
        self.devices: dict[int, object] = dict(devices or {})
        self.writes: list[tuple[int, int, tuple[int, ...]]] = []
        self.transfers = 0
        self.errors_injected = 0
        self._stalled = False
        self.closed = False

    def _transfer(self, address: int, nbytes: int):
        if self.closed:
            raise OSError(errno.EBADF, "the simulated bus is closed")
        self.clock.advance(self.overhead + (9 * (nbytes + 2) + 2) / self.bus_hz)
        faults = self.faults
        if (faults.stall_at is not None and not self._stalled
                and self.clock.monotonic() >= faults.stall_at):
            self._stalled = True
            self.clock.advance(faults.stall_duration)
        self.transfers += 1
        if faults.error_rate and self._rng.random() < faults.error_rate:
            self.errors_injected += 1
            raise OSError(errno.EREMOTEIO, "Remote I/O error")
        if address not in self.devices:
            raise OSError(errno.EREMOTEIO, "Remote I/O error")
        return self.devices[address]

    def read_byte_data(self, i2c_addr: int, register: int, force=None) -> int:
        """Read one register."""
        return self._transfer(i2c_addr, 1).read(register, 1)[0]

    def write_byte_data(self, i2c_addr: int, register: int, value: int, force=None) -> None:
        """Write one register."""
        self._transfer(i2c_addr, 1).write(register, [value])
        self.writes.append((i2c_addr, register, (value,)))

    def read_i2c_block_data(self, i2c_addr: int, register: int, length: int, force=None):
        """Read ``length`` (at most 32) bytes from ``register`` on."""
        if length > 32:
            raise ValueError("Desired block length over 32 bytes")
        return self._transfer(i2c_addr, length).read(register, length)

    def write_i2c_block_data(self, i2c_addr: int, register: int, data, force=None) -> None:
        """Write up to 32 bytes from ``register`` on."""
        data = list(data)
        if len(data) > 32:
            raise ValueError("Data length cannot exceed 32 bytes")
        self._transfer(i2c_addr, len(data)).write(register, data)
        self.writes.append((i2c_addr, register, tuple(data)))

    def i2c_rdwr(self, *msgs) -> None:
        """Combined transfer: a one-byte register write followed by a read of any length."""
        if len(msgs) != 2 or msgs[0].flags & 1 or not msgs[1].flags & 1 or msgs[0].len != 1:
            raise ValueError("the simulated bus supports i2c_rdwr(write [register], read n) only")
        register = bytes(msgs[0])[0]
        device = self._transfer(msgs[0].addr, msgs[1].len + 1)
        data = bytes(device.read(register, msgs[1].len))
        for k, value in enumerate(data):
            msgs[1].buf[k] = bytes([value])

    def close(self) -> None:
        """Close the bus."""
        self.closed = True

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


class SimulatedRig:
    """Pan-tilt unit, probe, accelerometer and obstacle, behind a :class:`SimulatedBus`.

    Parameters
    ----------
    vibration : Recording or callable or None
        The tip acceleration from the contact on: a recording, or ``vibration(fs)`` returning one
        for the sample rate the accelerometer is set to (called once, at the first sample); or None.
        Outside it the sensor reads :attr:`rest` plus noise.
    obstacle : Obstacle or None
        Where the post is (default :class:`Obstacle()`); None for empty space (no contact ever).
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
    mpu : SimulatedMPU6050 at 0x68
    pca : SimulatedPCA9685 at 0x40

    Examples
    --------
    >>> from ebantenna.device.simbus import SimulatedRig
    >>> rig = SimulatedRig.quiet(seed=2)
    >>> rig.bus.read_byte_data(0x68, 0x75) == 0x68, rig.contact_time is None
    (True, True)
    """

    def __init__(self, vibration=None, *, obstacle: Obstacle | None = Obstacle(),
                 faults: Faults | None = None, seed: int = 0, noise: float = 0.02,
                 slew_rate: float = MG996R_SLEW_RATE):
        if not (vibration is None or isinstance(vibration, Recording) or callable(vibration)):
            raise TypeError("vibration must be a Recording, a callable or None, got "
                            f"{type(vibration).__name__}")
        seed = check_int("seed", seed, minimum=0)
        self.noise = check_nonnegative("noise", noise)
        self._vibration = vibration
        self._recording = vibration if isinstance(vibration, Recording) else None
        noise_seed, bus_seed = np.random.SeedSequence(seed).spawn(2)
        self._rng = np.random.default_rng(noise_seed)
        self.clock = VirtualClock()
        self.bus = SimulatedBus(self.clock, faults=faults,
                                seed=int(bus_seed.generate_state(1)[0]))
        if not (obstacle is None or isinstance(obstacle, Obstacle)):
            raise TypeError(f"obstacle must be an Obstacle or None, got {type(obstacle).__name__}")
        self.world = _World(obstacle, check_positive("slew_rate", slew_rate))
        self.mpu = SimulatedMPU6050(self._acceleration, self.clock,
                                    who_am_i=self.bus.faults.who_am_i)
        self.pca = SimulatedPCA9685(self.world, self.clock)
        self.bus.devices = {0x68: self.mpu, 0x40: self.pca}
        #: Time of the first sample at or after the contact, s.
        self.contact_sample_time = None

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
        def vibration(fs: float) -> Recording:
            from ..simulate import simulate

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
        from ..simulate import builtin_scene

        base = builtin_scene(scene)
        chosen = base.with_(contact=ratio * base.probe.length, material=material)
        return cls.from_scene(chosen, seed=seed, **kwargs)

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
        rec = self._recording
        if rec is None:
            return np.zeros(3)
        tail = max(1, rec.n_samples // 10)
        return np.array([rec.ax[-tail:].mean(), 0.0, rec.az[-tail:].mean()])

    def _acceleration(self, times: np.ndarray, fs: float) -> np.ndarray:
        self.world.advance_to(self.clock.monotonic())
        if self._vibration is not None and self._recording is None:
            self._recording = self._vibration(fs)
            if not isinstance(self._recording, Recording):
                raise TypeError("vibration(fs) must return a Recording")
        rec = self._recording
        if rec is not None and not math.isclose(rec.fs, fs):
            raise ValueError(f"the vibration is sampled at {rec.fs:g} Hz but the simulated "
                             f"MPU-6050 is set to {fs:g} Hz")
        acc = self.rest + self._rng.normal(0.0, self.noise, (times.size, 3))
        contact = self.world.contact_time
        if contact is None or rec is None:
            return acc
        after = times >= contact - 1e-12
        if not after.any():
            return acc
        if self.contact_sample_time is None:
            self.contact_sample_time = float(times[after][0])
        j = np.rint((times - self.contact_sample_time) * fs).astype(np.int64)
        play = after & (j >= 0) & (j < rec.n_samples)
        acc[play, 0] = rec.ax[j[play]]
        acc[play, 1] = 0.0
        acc[play, 2] = rec.az[j[play]]
        return acc
