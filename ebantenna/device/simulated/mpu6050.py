"""The simulated MPU-6050: its registers, sampling, quantisation and FIFO.

It samples at the rate ``CONFIG`` and ``SMPLRT_DIV`` set, quantises to the range ``ACCEL_CONFIG``
sets and fills a 1024-byte FIFO that overflows (overwriting its oldest bytes and raising
``FIFO_OFLOW_INT``) when drained too slowly; see :mod:`ebantenna.chips.mpu6050` for the register
map and its source. ``INT_STATUS`` clears when it is read, or on any read with ``INT_PIN_CFG``'s
``INT_RD_CLEAR`` bit (0x10) set. What it measures comes from a ``source``
callable; it does not model the chip's own low-pass filter.

Modelling assumption: the sample-rate divider starts counting when the FIFO starts filling (awake,
``USER_CTRL.FIFO_EN`` and ``FIFO_EN.ACCEL`` set), so the first sample of such an *epoch* lands one
sample period after it starts; with ``free_running_divider`` it runs on its own grid of ticks
instead, and the first sample lands at the next tick, anywhere within a period of the start. Which
of the two the real part does is a question for the hardware (see the HIL checklist of the user
guide); the driver assumes neither. The chip keeps the ground truth of every epoch
(``epochs`` and ``first_sample`` of :class:`SimulatedMPU6050`): its start time, the
time of its first sample and every sample it put into the FIFO, which is what a driver's kept
samples and timestamps are checked against.

A ``who_am_i`` of the MPU-6500 family (:data:`~ebantenna.chips.mpu6050.CHIP_MODELS`) makes it
one of those: a 512-byte FIFO, and ``SMPLRT_DIV`` applied only when ``0 < DLPF_CFG < 7``.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ..._validate import check_bool, check_int, check_nonnegative, check_real
from ...chips.mpu6050 import (
    ACCEL_LSB_PER_G,
    ACCEL_SAMPLE_BYTES,
    AFS_SEL,
    CHIP_MODELS,
    DATA_DTYPE,
    DLPF_CFG,
    GYRO_RATE_DLPF_OFF,
    GYRO_RATE_DLPF_ON,
    POWER_ON,
    READ_ONLY,
    STANDARD_GRAVITY,
    USER_CONTROL_SELF_CLEARING,
    WHO_AM_I_VALUE,
    FifoEnable,
    Interrupt,
    PowerManagement1,
    Register,
    UserControl,
    gyro_output_rate,
)

__all__ = ["SimulatedMPU6050"]

#: Largest sample-clock error accepted, relative: a few times the +/-1 % variation over temperature
#: of the gyro oscillators the MPU-6050's PLL locks to (PS rev. 3.4, section 7.15).
MAX_CLOCK_DRIFT = 0.05

#: Registers modelled: the 128 addresses 0x00-0x7F, which hold the whole map (RM section 3 ends at
#: 0x75); a burst read stops advancing at the last of them.
REGISTER_SPACE = 128
#: What a read of the empty FIFO returns in this model.
_EMPTY_FIFO_BYTE = 0xFF
#: ``INT_PIN_CFG``'s bit that makes any read clear ``INT_STATUS``, not only a read of it (RM 55).
INT_RD_CLEAR = 0x10
_COUNT_LIMITS = np.iinfo(np.int16)
#: The int16 range the counts saturate at, as floats (taken once: ``iinfo`` is slow to ask).
_COUNT_MIN, _COUNT_MAX = float(_COUNT_LIMITS.min), float(_COUNT_LIMITS.max)
#: The registers the chip reads at every sample block, as plain ints (an enum member is slower
#: to look up).
_CONFIG, _SMPLRT_DIV, _ACCEL_CONFIG = (int(Register.CONFIG), int(Register.SMPLRT_DIV),
                                      int(Register.ACCEL_CONFIG))
#: ``ACCEL_CONFIG`` byte -> sensitivity, LSB/g (:meth:`SimulatedMPU6050.lsb_per_g`, for all 256
#: bytes at once: the chip asks at every sample block it produces).
_LSB_PER_G = tuple(ACCEL_LSB_PER_G[AFS_SEL.get(value)] for value in range(256))


def _rate_set_by(config: int, smplrt_div: int, family_6500: bool) -> float:
    """Sample rate, Hz, that ``CONFIG`` and ``SMPLRT_DIV`` set (RM register 25; on the MPU-6500
    family, ``family_6500``, the divider applies only when ``0 < DLPF_CFG < 7``)."""
    dlpf_cfg = DLPF_CFG.get(config)
    if family_6500:
        if not 0 < dlpf_cfg < 7:
            return GYRO_RATE_DLPF_OFF
        return GYRO_RATE_DLPF_ON / (1 + smplrt_div)
    return gyro_output_rate(dlpf_cfg) / (1 + smplrt_div)


def _byte_list(data) -> list[int]:
    """``data`` (a sequence of bytes 0-255) as a list, or a clear error naming ``data``."""
    if isinstance(data, str) or not hasattr(data, "__iter__"):
        raise TypeError(f"data must be a sequence of bytes (0-255), got {type(data).__name__}")
    return [check_int("data", value, minimum=0, maximum=0xFF) for value in data]


class SimulatedMPU6050:
    """Register model of the MPU-6050: sleep, sample rate, range, FIFO with overflow.

    Parameters
    ----------
    source : callable
        ``source(times, fs)`` returns the (n, 3) accelerations in m/s^2 at the sample times
        ``times`` (s) for the sample rate ``fs`` (Hz) the registers set (the times themselves
        follow the chip's actual clock, :meth:`true_rate`).
    clock : VirtualClock
        The bus's clock.
    who_am_i : int
        What ``WHO_AM_I`` reads.
    clock_drift : float
        Relative error of the sample clock: the chip samples at ``(1 + clock_drift)`` times the
        rate its registers set.
    free_running_divider : bool
        The divider runs on its own grid instead of restarting with the FIFO (module notes).
    repeat_last_byte : bool
        A read of the empty FIFO repeats the last byte read (the real part); else 0xFF.

    Attributes
    ----------
    regs : bytearray
        The register file, by address.
    fifo : bytearray
        The bytes waiting in the FIFO, oldest first.
    overflowed_bytes : int
        Bytes overwritten by overflows.
    samples_pushed : int
        Samples written into the FIFO.
    epochs : list of (float, list of ndarray)
        Ground truth: for each time the FIFO started filling, that virtual time (s) and the
        blocks of (n, 3) int16 counts it produced from then on, in order.
    first_sample : list of float
        Ground truth: the virtual time of each epoch's first sample, s (its later samples follow
        at the true period, ``1 / true_rate()``).

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.chips.mpu6050 import Register, UserControl, FifoEnable
    >>> from ebantenna.device.clock import VirtualClock
    >>> from ebantenna.device.simulated import SimulatedMPU6050
    >>> clock = VirtualClock()
    >>> mpu = SimulatedMPU6050(lambda t, fs: np.zeros((t.size, 3)), clock)
    >>> mpu.sample_rate(), mpu.lsb_per_g()
    (8000.0, 16384)
    >>> mpu.write(Register.PWR_MGMT_1, [0]); mpu.write(Register.SMPLRT_DIV, [7])
    >>> mpu.write(Register.FIFO_EN, [FifoEnable.ACCEL])
    >>> mpu.write(Register.USER_CTRL, [UserControl.FIFO_EN])
    >>> clock.sleep(0.0105); mpu.read(Register.FIFO_COUNTH, 2)  # 10 samples of 6 bytes
    [0, 60]
    """

    def __init__(self, source: Callable, clock, *, who_am_i: int = WHO_AM_I_VALUE,
                 clock_drift: float = 0.0, free_running_divider: bool = False,
                 repeat_last_byte: bool = False, samples_like: int | None = None,
                 stuck_from: float | None = None):
        if not callable(source):
            raise TypeError(f"source must be callable (times, fs) -> accelerations, got "
                            f"{type(source).__name__}")
        if not callable(getattr(clock, "monotonic", None)):
            raise TypeError(f"clock must be a clock (with monotonic()), got "
                            f"{type(clock).__name__}")
        who_am_i = check_int("who_am_i", who_am_i, minimum=0, maximum=0xFF)
        clock_drift = check_real("clock_drift", clock_drift)
        if not -1.0 < clock_drift < 1.0:
            raise ValueError(f"clock_drift must lie in (-1, 1) (a rate (1 + clock_drift) times "
                             f"the set one), got {clock_drift!r}")
        for name, value in (("free_running_divider", free_running_divider),
                            ("repeat_last_byte", repeat_last_byte)):
            check_bool(name, value)
        if samples_like is not None and samples_like not in CHIP_MODELS:
            raise ValueError(f"samples_like must be a known WHO_AM_I value "
                             f"({sorted(CHIP_MODELS)}) or None, got {samples_like!r}")
        if stuck_from is not None:
            stuck_from = check_nonnegative("stuck_from", stuck_from)
        self.source = source
        self.clock = clock
        self.who_am_i = who_am_i
        self.model = CHIP_MODELS.get(who_am_i if samples_like is None else samples_like,
                                     CHIP_MODELS[WHO_AM_I_VALUE])
        #: From this virtual time on, every sample repeats the one before (a stuck sensor).
        self.stuck_from = stuck_from
        self._stuck_value = None
        #: FIFO size, bytes (512 for the MPU-6500 family).
        self.FIFO_SIZE = self.model.fifo_size
        self.clock_drift = float(clock_drift)
        self.free_running_divider = bool(free_running_divider)
        self.repeat_last_byte = bool(repeat_last_byte)
        self._last_byte = _EMPTY_FIFO_BYTE
        self.epochs: list[tuple[float, list[np.ndarray]]] = []
        #: Ground truth: for each epoch, the sensitivity (LSB/g) each of its samples was
        #: taken at, in blocks as ``epochs`` (a range changed mid-run by a fault shows here).
        self.epoch_scales: list[list[np.ndarray]] = []
        self.first_sample: list[float] = []
        self.regs = bytearray(REGISTER_SPACE)
        self.fifo = bytearray()
        self.overflowed_bytes = 0
        self.samples_pushed = 0
        #: :meth:`sample_rate` by (``CONFIG``, ``SMPLRT_DIV``, family): asked at every sample
        #: block; keyed by the register bytes, it follows a register changed in any way.
        self._rates: dict[tuple, float] = {}
        self.reset()

    def reset(self) -> None:
        """Power-on state (RM section 3): all zero but ``PWR_MGMT_1`` (asleep) and ``WHO_AM_I``."""
        self.regs[:] = bytes(REGISTER_SPACE)
        for register, value in POWER_ON.items():
            self.regs[register] = value
        self.regs[Register.WHO_AM_I] = self.who_am_i
        self.fifo.clear()
        self._since = None
        self._produced = 0
        # the rate samples are counted at, from when and from which sample (_anchor_rate)
        self._rate, self._rate_origin, self._rate_base = None, None, 0

    def brown_out(self) -> None:
        """Lose power for a moment: the samples due so far are produced, then the power-on state."""
        self._catch_up()
        self.reset()

    def _truth_scale(self, epoch: int) -> np.ndarray:
        """The sensitivity (LSB/g) each sample of epoch ``epoch`` was taken at."""
        blocks = self.epoch_scales[epoch]
        return np.concatenate(blocks) if blocks else np.empty(0, np.int32)

    def truth(self, epoch: int) -> np.ndarray:
        """Every sample (n, 3) int16 that epoch ``epoch`` put into the FIFO, in order."""
        if not self.epochs:
            raise ValueError(f"epoch must be an epoch begun, and none is yet; got {epoch!r}")
        epoch = check_int("epoch", epoch, minimum=0, maximum=len(self.epochs) - 1)
        blocks = self.epochs[epoch][1]
        return np.concatenate(blocks) if blocks else np.empty((0, 3), np.int16)

    def impossible_samples(self) -> int:
        """How many samples a FIFO count must add to what the FIFO holds to claim more than the
        chip can have produced since the FIFO was enabled, at the fastest clock the faults
        allow (``MAX_CLOCK_DRIFT``) and with its first
        sample as early as a free-running divider can put it: the ``"overcount"`` fault."""
        if self._since is None:
            return 0
        fastest = self.sample_rate() * (1.0 + MAX_CLOCK_DRIFT)
        possible = math.floor((self.clock.monotonic() - self._since) * fastest) + 1
        return max(possible - self._produced, 0) + 1

    def true_rate(self) -> float:
        """The rate at which the chip actually samples, Hz: :meth:`sample_rate` with the drift."""
        return self.sample_rate() * (1.0 + self.clock_drift)

    def sample_rate(self) -> float:
        """Sample rate set by CONFIG and SMPLRT_DIV, Hz (RM register 25; on the MPU-6500 family
        the divider applies only when ``0 < DLPF_CFG < 7``)."""
        regs = self.regs
        key = (regs[_CONFIG], regs[_SMPLRT_DIV], self.model.accel_config2)
        rate = self._rates.get(key)
        if rate is None:
            rate = self._rates[key] = _rate_set_by(*key)
        return rate

    def lsb_per_g(self) -> int:
        """Sensitivity from ACCEL_CONFIG.AFS_SEL, LSB/g."""
        return _LSB_PER_G[self.regs[_ACCEL_CONFIG]]

    def _producing(self) -> bool:
        regs = self.regs
        return (not regs[Register.PWR_MGMT_1] & PowerManagement1.SLEEP
                and bool(regs[Register.USER_CTRL] & UserControl.FIFO_EN)
                and bool(regs[Register.FIFO_EN] & FifoEnable.ACCEL))

    def _counts(self, times: np.ndarray) -> np.ndarray:
        acc = np.asarray(self.source(times, self.sample_rate()), dtype=np.float64)
        counts = np.rint(acc / STANDARD_GRAVITY * self.lsb_per_g())
        # saturated at the int16 range: np.clip's minimum(maximum(.)), without its wrapper
        np.maximum(counts, _COUNT_MIN, out=counts)
        counts = np.minimum(counts, _COUNT_MAX, out=counts).astype(DATA_DTYPE)
        if self.stuck_from is not None:
            stuck = times >= self.stuck_from
            if stuck.any():
                if self._stuck_value is None:
                    self._stuck_value = counts[np.argmax(stuck)].copy()
                counts[stuck] = self._stuck_value
        return counts

    def _corrupt(self, register: int, value: int) -> None:
        """A register takes ``value`` by itself (a fault): the samples due so far are produced
        with the old settings first."""
        self._catch_up()
        was = self._producing()
        self.regs[register] = value
        self._update_state(was)

    def _catch_up(self) -> None:
        """Produce the samples due by now at the current rate, counted from the rate's anchor
        (:meth:`_anchor_rate`: the FIFO's enable, or the last change of the rate)."""
        if self._since is None:
            return
        now = self.clock.monotonic()
        fs = self.true_rate()
        origin, base = self._rate_origin, self._rate_base
        if self.free_running_divider:
            target = base + int(math.floor((now - origin) * fs + 1e-9)) + 1
        else:
            target = base + int(math.floor((now - origin) * fs + 1e-9))
        if target <= self._produced:
            return
        n = target - self._produced
        k = np.arange(self._produced, target) - base
        if self.free_running_divider:  # sample k at origin + k / fs (origin: a tick)
            times = origin + k / fs
        else:  # sample k at origin + (k + 1) / fs
            times = origin + (k + 1) / fs
        counts = self._counts(times)
        self.epochs[-1][1].append(counts.astype(np.int16))
        scale = np.empty(n, np.int32)
        scale.fill(self.lsb_per_g())
        self.epoch_scales[-1].append(scale)
        self.fifo += counts.tobytes()
        self.samples_pushed += n
        self._produced = target
        excess = len(self.fifo) - self.FIFO_SIZE
        if excess > 0:
            # RM register 35 / PS 7.17: the oldest data are overwritten.
            del self.fifo[:excess]
            self.overflowed_bytes += excess
            if self.regs[Register.INT_ENABLE] & Interrupt.FIFO_OFLOW:
                self.regs[Register.INT_STATUS] |= Interrupt.FIFO_OFLOW

    def _update_state(self, was_producing: bool) -> None:
        producing = self._producing()
        if producing and not was_producing:
            self._since = self.clock.monotonic()
            self._produced = 0
            self.epochs.append((self._since, []))
            self.epoch_scales.append([])
            self._anchor_rate()
            self.first_sample.append(self._rate_origin if self.free_running_divider
                                     else self._since + 1.0 / self._rate)
        elif was_producing and not producing:
            self._since = None
        elif producing and self.true_rate() != self._rate:
            self._anchor_rate()  # the samples due were produced at the old rate (_catch_up)

    def _anchor_rate(self) -> None:
        """Count the samples from now at the current rate: the FIFO was just enabled, or the
        rate changed (a write of ``CONFIG`` or ``SMPLRT_DIV``), so that none is back-filled at
        the new rate. Without a free-running divider the next sample comes a period after now;
        with one, at the next tick of the chip's own grid."""
        now = self.clock.monotonic()
        self._rate = fs = self.true_rate()
        self._rate_base = self._produced
        self._rate_origin = ((math.floor(now * fs + 1e-9) + 1) / fs if self.free_running_divider
                             else now)

    def read(self, register: int, length: int) -> list[int]:
        """Read ``length`` bytes from ``register`` on, as one I2C read transfer does."""
        register = check_int("register", register, minimum=0, maximum=0xFF)
        length = check_int("length", length, minimum=0)
        self._catch_up()
        out = []
        reg = register
        for k in range(length):
            if reg == Register.FIFO_R_W:  # the address stays: every byte left is the FIFO's
                out += self._fifo_bytes(length - k)
                break
            if reg == Register.FIFO_COUNTH:
                value = len(self.fifo) >> 8
            elif reg == Register.FIFO_COUNTL:
                value = len(self.fifo) & 0xFF
            elif Register.ACCEL_XOUT_H <= reg <= Register.ACCEL_ZOUT_L:
                value = self._latest()[reg - Register.ACCEL_XOUT_H]
            elif reg >= REGISTER_SPACE:
                value = 0  # not modelled: reads as 0
            else:
                value = self.regs[reg]
                if reg == Register.INT_STATUS:
                    self.regs[reg] = 0  # cleared by reading it (INT_PIN_CFG.INT_RD_CLEAR = 0)
            out.append(value)
            reg = min(reg + 1, REGISTER_SPACE - 1) if reg < REGISTER_SPACE else reg
        if length and self.regs[Register.INT_PIN_CFG] & INT_RD_CLEAR:
            self.regs[Register.INT_STATUS] = 0  # cleared by any read (RM 55)
        return out

    def _fifo_bytes(self, n: int) -> list[int]:
        """``n`` bytes read at FIFO_R_W, taken from the FIFO in one slice; past its end the
        last byte again (``repeat_last_byte``) or the empty FIFO's byte."""
        taken = list(self.fifo[:n])
        del self.fifo[:n]
        if taken:
            self._last_byte = taken[-1]
        fill = self._last_byte if self.repeat_last_byte else _EMPTY_FIFO_BYTE
        return taken + [fill] * (n - len(taken))

    def _latest(self) -> bytes:
        if self.regs[Register.PWR_MGMT_1] & PowerManagement1.SLEEP:
            return bytes(ACCEL_SAMPLE_BYTES)
        fs = self.true_rate()
        tick = math.floor(self.clock.monotonic() * fs) / fs
        return self._counts(np.array([tick])).tobytes()

    def write(self, register: int, data) -> None:
        """Write ``data`` from ``register`` on, as one I2C write transfer does."""
        register = check_int("register", register, minimum=0, maximum=0xFF)
        data = _byte_list(data)
        self._catch_up()
        for k, value in enumerate(data):
            reg = (register + k) % 256
            if reg >= REGISTER_SPACE:
                continue  # not modelled: the write is ignored
            was = self._producing()
            if reg == Register.PWR_MGMT_1 and value & PowerManagement1.DEVICE_RESET:
                self.reset()
                continue
            if reg == Register.FIFO_EN and value & ~int(FifoEnable.ACCEL):
                raise ValueError(
                    "the simulated MPU-6050 models only accelerometer data in the FIFO "
                    f"(FIFO_EN = 0x{int(FifoEnable.ACCEL):02X}); got FIFO_EN = 0x{int(value):02X}")
            if reg in READ_ONLY:
                continue
            if reg == Register.USER_CTRL:
                if value & UserControl.FIFO_RESET and not value & UserControl.FIFO_EN:
                    self.fifo.clear()
                value &= ~int(USER_CONTROL_SELF_CLEARING) & 0xFF  # reset bits clear themselves
            self.regs[reg] = value
            self._update_state(was)
