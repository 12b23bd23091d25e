"""Driver for the NXP PCA9685 16-channel, 12-bit PWM controller that drives the pan-tilt servos.

Register numbers, bits and the procedures follow the *PCA9685 Product data sheet*, revision 4,
16 April 2015 (NXP), cited as "DS" with its section numbers.

PWM frequency (DS 7.3.5)
------------------------
    prescale = round(osc_clock / (4096 * update_rate)) - 1,

with the internal oscillator at 25 MHz: 121 for 50 Hz, which gives 25 MHz / (4096 * 122) = 50.03 Hz.
The internal oscillator is only nominally 25 MHz (DS table 11, "f_osc": 23-27 MHz over the
operating range), so a servo pulse computed for 25 MHz can be 8 % off. Adafruit's PCA9685 driver
lets the user give the measured oscillator frequency; here ``oscillator_hz`` takes it, and
:func:`oscillator_from_measurement` computes it from the PWM frequency measured on an output
(with a frequency counter or an oscilloscope) at a known prescale.
``PRE_SCALE`` can only be written while ``MODE1.SLEEP`` is 1, so the sequence is: sleep, write the
prescale, wake, wait 500 us for the oscillator (DS 7.3.1.1), then write ``RESTART``.

Pulse widths (DS 7.3.3)
-----------------------
Each channel has four registers ``LEDn_ON_L/H``, ``LEDn_OFF_L/H`` at ``0x06 + 4 n``: the output
goes high at count ON and low at count OFF of each 4096-count period. A servo pulse of width ``w``
seconds is ``ON = 0``, ``OFF = round(w * f * 4096)``. The four bytes are written in one
auto-incremented block transfer, and ``MODE2.OCH = 0`` makes the outputs change at the I2C STOP, so
a pulse is never half updated. The four bytes are then read back in one block (a bit flipped on the
wire would otherwise drive the servo into its end stop unseen); bytes that read back wrong are
written once more, then :class:`~ebantenna.device.i2c.SettingError` is raised. The read-back costs
one 4-byte block read per write (:data:`PULSE_READ_BACK_BITS` clocks: 0.71 ms at 100 kHz, 0.215 ms
at 400 kHz, the system call included). Bit 4 of ``LEDn_OFF_H`` (full OFF) switches a channel off;
``ALL_LED_OFF_H`` does so for all 16 channels at once, which is how the servos are released.
"""

from __future__ import annotations

import errno
import logging

from .._validate import check_int, check_nonnegative, check_positive
from ..chips.pca9685 import (
    COUNTS_PER_PERIOD,
    DEFAULT_ADDRESS,
    LED_FULL,
    N_CHANNELS,
    OSCILLATOR_HZ,
    OSCILLATOR_STARTUP,
    PRESCALE_MAX,
    PRESCALE_MIN,
    Led,
    Mode1,
    Mode2,
    Register,
    join_count,
    led_register,
    split_count,
)
from .clock import SystemClock
from .i2c import I2CDevice, RetryPolicy, SettingError, transfer_bits

__all__ = ["PCA9685", "prescale_for", "pwm_frequency", "oscillator_from_measurement",
           "OSCILLATOR_RANGE", "NotInitializedError", "PULSE_READ_BACK_BITS"]

#: The range of the internal oscillator, Hz (DS table 11, f_osc: 23 to 27 MHz); a calibration
#: outside it is refused as a measurement error.
OSCILLATOR_RANGE = (23e6, 27e6)

logger = logging.getLogger(__name__)

#: Bits of ``MODE1`` that read back as written (``RESTART`` reads the PWM's own state).
_MODE1_STABLE = 0xFF & ~int(Mode1.RESTART)

#: Bus clocks of the read-back that follows every write of a channel's four ``LEDn`` registers
#: (one register read of the four bytes).
PULSE_READ_BACK_BITS = transfer_bits(len(Led), read=True)


class NotInitializedError(RuntimeError):
    """A PCA9685 was asked for pulses before :meth:`PCA9685.initialize` set its frequency."""


def prescale_for(frequency: float, oscillator_hz: float = OSCILLATOR_HZ) -> int:
    """``PRE_SCALE`` for a PWM ``frequency`` (Hz), DS equation 1.

    Raises
    ------
    ValueError
        When ``frequency`` lies outside the chip's range, the frequencies of ``PRE_SCALE`` 255
        and 3 with the data sheet's rounding to whole hertz (24-1526 Hz at 25 MHz, DS 7.3.5):
        it is refused, not silently clamped to the nearest frequency the chip can make.

    Examples
    --------
    >>> from ebantenna.device.pca9685 import prescale_for
    >>> prescale_for(50.0), prescale_for(200.0), prescale_for(1526.0)
    (121, 30, 3)
    >>> prescale_for(1600.0)
    Traceback (most recent call last):
    ...
    ValueError: frequency must lie in [24, 1526] Hz (the PCA9685's range at 25 MHz), got 1600.0
    """
    frequency = check_positive("frequency", frequency)
    oscillator_hz = _check_oscillator(oscillator_hz)
    low = round(oscillator_hz / (COUNTS_PER_PERIOD * (PRESCALE_MAX + 1)))
    high = round(oscillator_hz / (COUNTS_PER_PERIOD * (PRESCALE_MIN + 1)))
    if not low <= frequency <= high:
        raise ValueError(f"frequency must lie in [{low}, {high}] Hz (the PCA9685's range at "
                         f"{oscillator_hz / 1e6:g} MHz), got {frequency!r}")
    return min(max(round(oscillator_hz / (COUNTS_PER_PERIOD * frequency)) - 1, PRESCALE_MIN),
               PRESCALE_MAX)


def oscillator_from_measurement(measured_pwm_hz: float, prescale: int) -> float:
    """The oscillator frequency, Hz, from the PWM frequency measured on an output at ``prescale``.

    Inverts DS equation 1: ``osc_clock = f_pwm * 4096 * (prescale + 1)``.

    Examples
    --------
    >>> from ebantenna.device.pca9685 import oscillator_from_measurement
    >>> round(oscillator_from_measurement(51.2, 121) / 1e6, 4)  # MHz: a fast unit
    25.5853
    """
    prescale = check_int("prescale", prescale, minimum=PRESCALE_MIN, maximum=PRESCALE_MAX)
    return _check_oscillator(
        check_positive("measured_pwm_hz", measured_pwm_hz) * COUNTS_PER_PERIOD * (prescale + 1))


def _check_oscillator(oscillator_hz: float) -> float:
    low, high = OSCILLATOR_RANGE
    oscillator_hz = check_positive("oscillator_hz", oscillator_hz)
    if not low <= oscillator_hz <= high:
        raise ValueError(f"oscillator_hz must lie in [{low:g}, {high:g}] Hz (the PCA9685's "
                         f"oscillator range, DS table 11), got {oscillator_hz!r}")
    return oscillator_hz


def pwm_frequency(prescale: int, oscillator_hz: float = OSCILLATOR_HZ) -> float:
    """The PWM frequency that ``PRE_SCALE = prescale`` actually gives, Hz.

    Examples
    --------
    >>> from ebantenna.device.pca9685 import pwm_frequency
    >>> round(pwm_frequency(121), 3)
    50.029
    """
    prescale = check_int("prescale", prescale, minimum=PRESCALE_MIN, maximum=PRESCALE_MAX)
    return _check_oscillator(oscillator_hz) / (COUNTS_PER_PERIOD * (prescale + 1))


class PCA9685:
    """The PWM controller.

    Parameters
    ----------
    bus : smbus2.SMBus or compatible
        The open I2C bus.
    address : int
        I2C address; 0x40 with all address pins low (default).
    frequency : float
        PWM frequency, Hz. Default 50 Hz, the servo frame rate.
    oscillator_hz : float
        The oscillator's actual frequency, Hz, if calibrated (given, or from
        :func:`oscillator_from_measurement`); default the nominal 25 MHz. Must lie in 23-27 MHz.
    retry : RetryPolicy, optional
        Retries of transient bus errors.
    clock : SystemClock or VirtualClock, optional
        ``sleep`` provider. Default the system clock.

    Examples
    --------
    >>> from ebantenna.device.simulated import SimulatedRig
    >>> from ebantenna.device.pca9685 import PCA9685
    >>> rig = SimulatedRig.quiet()
    >>> pca = PCA9685(rig.bus, clock=rig.clock)
    >>> pca.initialize()
    >>> pca.set_pulse(0, 1.5e-3)
    >>> round(pca.pulse(0) * 1e6, 1)  # microseconds, to the nearest 4.88 us count
    1498.2
    """

    def __init__(self, bus, address: int = DEFAULT_ADDRESS, *, frequency: float = 50.0,
                 oscillator_hz: float = OSCILLATOR_HZ, retry: RetryPolicy | None = None,
                 clock=None):
        self.oscillator_hz = _check_oscillator(oscillator_hz)
        self.prescale = prescale_for(frequency, oscillator_hz)
        self.frequency = pwm_frequency(self.prescale, oscillator_hz)
        self.clock = SystemClock() if clock is None else clock
        self.device = I2CDevice(bus, address, retry=retry, clock=self.clock)
        #: Whether :meth:`initialize` has set the frequency (pulses are refused before).
        self.initialized = False
        #: Channel writes that read back wrong and were written again, one sentence each.
        self.rewritten: list[str] = []

    def initialize(self) -> None:
        """Switch every output off, then set the PWM frequency.

        Register writes, in order: ``ALL_LED_OFF_H = 0x10`` (all outputs full off), ``MODE2 = 0x04``
        (totem-pole outputs, change on STOP), ``MODE1 = old | SLEEP`` (RESTART bit written as 0),
        ``PRE_SCALE``, ``MODE1 = old & ~SLEEP | AI`` (wake, register auto-increment), 500 us
        wait, ``MODE1 |= RESTART``. ``MODE2``, ``MODE1`` and ``PRE_SCALE`` are read back after
        each write (:meth:`write_verified`): a ``PRE_SCALE`` that did not land would give pulses
        of the wrong width, pinning the servos at an end stop. ``RESTART`` is not: it clears
        itself and reads 1 only while channels that ran before the sleep wait to be restarted (DS
        7.3.1.1), and every output was switched off before it, so its read-back could not tell
        whether it acted (the device guide's "What the driver cannot detect").
        """
        self.device.write_byte(Register.ALL_LED_OFF_H, LED_FULL)
        self.write_verified(Register.MODE2, Mode2.OUTDRV)
        old = self.device.read_byte(Register.MODE1) & ~int(Mode1.RESTART) & 0xFF
        self.write_verified(Register.MODE1, old | Mode1.SLEEP)
        self.write_verified(Register.PRE_SCALE, self.prescale)
        awake = (old & ~int(Mode1.SLEEP) & 0xFF) | Mode1.AI
        self.write_verified(Register.MODE1, awake)
        self.clock.sleep(OSCILLATOR_STARTUP)
        self.device.write_byte(Register.MODE1, awake | Mode1.RESTART)
        #: The settings :meth:`changed_settings` checks, as written.
        self.expected = {Register.MODE1: awake, Register.MODE2: int(Mode2.OUTDRV),
                         Register.PRE_SCALE: self.prescale}
        self.initialized = True
        logger.info("PCA9685 at 0x%02X: prescale %d, %.3f Hz", self.device.address, self.prescale,
                    self.frequency)

    def write_verified(self, register: int, value: int) -> None:
        """Write a setting and read it back (``MODE1``'s self-clearing ``RESTART`` bit aside);
        written once more if it reads back wrong, then :class:`SettingError`."""
        mask = _MODE1_STABLE if register == Register.MODE1 else 0xFF
        seen = self.device.write_read_back(register, value, mask,
                                           lambda: f"PCA9685 {Register(register).name}")
        if seen is None:
            return
        raise SettingError(errno.EIO, f"PCA9685 {Register(register).name} (0x{register:02X}) "
                           f"reads back 0x{seen:02X} after 0x{value:02X} was written twice")

    def changed_settings(self) -> list:
        """The settings of :meth:`initialize` that no longer read back as written (a brown-out
        puts the chip to sleep at 200 Hz with its writes still acknowledged):
        ``[(name, written, seen), ...]``, empty when all hold."""
        if not self.initialized:
            return []
        mode1, mode2 = self.device.read_block(Register.MODE1, 2)
        seen = {Register.MODE1: mode1, Register.MODE2: mode2,
                Register.PRE_SCALE: self.device.read_byte(Register.PRE_SCALE)}
        changed = []
        for register, value in self.expected.items():
            mask = _MODE1_STABLE if register == Register.MODE1 else 0xFF
            if seen[register] & mask != value & mask:
                changed.append((Register(register).name, value, seen[register]))
        return changed

    @staticmethod
    def _check_channel(channel) -> int:
        return check_int("channel", channel, minimum=0, maximum=N_CHANNELS - 1)

    def counts_for(self, pulse: float) -> int:
        """OFF count for a pulse of ``pulse`` seconds (rounded to the nearest count).

        The counts 1 to 4095 are pulses: a pulse rounds to one of them when it lies in
        ``(0.5 c, 4095.5 c)``, ``c`` being one count (``1 / (4096 f)``); anything else is
        refused with that range.

        Examples
        --------
        >>> from ebantenna.device.simulated import SimulatedRig
        >>> from ebantenna.device.pca9685 import PCA9685
        >>> pca = PCA9685(SimulatedRig.quiet().bus)
        >>> pca.counts_for(2e-6)
        Traceback (most recent call last):
        ...
        ValueError: pulse must lie in (2.440, 19986.0) us at 50.03 Hz (0.5 to 4095.5 counts...
        """
        pulse = check_nonnegative("pulse", pulse)
        count = 1.0 / (COUNTS_PER_PERIOD * self.frequency)  # one count, s
        counts = round(pulse / count)
        if not 1 <= counts <= COUNTS_PER_PERIOD - 1:
            raise ValueError(
                f"pulse must lie in ({0.5e6 * count:.3f}, "
                f"{(COUNTS_PER_PERIOD - 0.5) * 1e6 * count:.1f}) us at {self.frequency:.2f} Hz "
                f"(0.5 to {COUNTS_PER_PERIOD - 0.5:g} counts of {1e6 * count:.3f} us), got "
                f"{pulse!r}")
        return counts

    def set_pulse(self, channel: int, pulse: float) -> None:
        """Output pulses of ``pulse`` seconds on ``channel`` (one 4-byte block write, read back:
        :meth:`write_channel`).

        Raises
        ------
        NotInitializedError
            Before :meth:`initialize`: the chip's frequency, which the pulse width depends on,
            is not set yet (switching outputs off, :meth:`all_off`, works at any time).
        """
        channel = self._check_channel(channel)
        off = self.counts_for(pulse)
        if not self.initialized:
            raise NotInitializedError(
                f"PCA9685 at 0x{self.device.address:02X} is not initialized: call initialize() "
                "before set_pulse() (it sets the PWM frequency the pulse width depends on)")
        self.write_channel(channel, [0, 0, *split_count(off)])

    def write_channel(self, channel: int, data: list) -> None:
        """Write ``channel``'s four ``LEDn`` registers in one block and read them back; written
        once more if they read back wrong (noted in :attr:`rewritten` when the second write
        lands), then :class:`SettingError`. A chip that lost its register auto-increment (a
        brown-out) reads back wrong too: the block landed in one register."""
        channel = self._check_channel(channel)
        data = list(data)
        if len(data) != len(Led):
            raise ValueError(f"data must hold the {len(Led)} bytes ON_L, ON_H, OFF_L, OFF_H, "
                             f"got {len(data)}")
        register = led_register(channel)
        wrong = None
        for _ in range(2):
            self.device.write_block(register, data)
            seen = list(self.device.read_block(register, len(Led)))
            if seen == list(data):
                if wrong is not None:
                    self.rewritten.append(f"{wrong}: written again")
                return
            if wrong is None:
                wrong = (f"LED{channel} (0x{register:02X}) read back {_hex(seen)} after "
                         f"{_hex(data)} was written")
                logger.warning("PCA9685 %s; writing it again", wrong)
        raise SettingError(errno.EIO, f"PCA9685 LED{channel} (0x{register:02X}) reads back "
                           f"{_hex(seen)} after {_hex(data)} was written twice")

    def pulse(self, channel: int) -> float:
        """Read back the pulse width on ``channel``, s (0 when the channel is off)."""
        channel = self._check_channel(channel)
        on_l, on_h, off_l, off_h = self.device.read_block(led_register(channel), len(Led))
        on, off = join_count(on_l, on_h), join_count(off_l, off_h)
        if off_h & LED_FULL or (on_h & LED_FULL) == 0 and off == 0:
            return 0.0
        if on_h & LED_FULL:
            return 1.0 / self.frequency
        return ((off - on) % COUNTS_PER_PERIOD) / (COUNTS_PER_PERIOD * self.frequency)

    def channel_off(self, channel: int) -> None:
        """Switch one output off (full OFF bit)."""
        channel = self._check_channel(channel)
        self.write_channel(channel, [0, 0, 0, LED_FULL])

    def all_off(self) -> None:
        """Switch all 16 outputs off at once (``ALL_LED_OFF_H`` full OFF): the servos go limp."""
        self.device.write_byte(Register.ALL_LED_OFF_H, LED_FULL)


def _hex(data) -> str:
    return " ".join(f"{b:02X}" for b in data)
