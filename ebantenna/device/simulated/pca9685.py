"""The simulated PCA9685: its registers with the datasheet's rules, driving two simulated MG996R.

It keeps ``PRE_SCALE`` writable only while asleep, auto-increments the register address only with
``MODE1.AI``, spreads the ``ALL_LED`` registers to every output and honours the full-OFF and
full-ON bits (see :mod:`ebantenna.chips.pca9685` for the map and its source). Whenever a write
changes the pulse width on a servo's output it commands that servo of the :class:`World`.
"""

from __future__ import annotations

from ..._validate import check_bool, check_int, check_positive
from ...chips.pca9685 import (
    COUNTS_PER_PERIOD,
    LED_FULL,
    N_CHANNELS,
    OSCILLATOR_HZ,
    POWER_ON,
    PRESCALE_MIN,
    Led,
    Mode1,
    Register,
    join_count,
    led_register,
)
from .world import World, mg996r_angle

__all__ = ["SimulatedPCA9685", "SimulatedLine"]


class SimulatedLine:
    """A GPIO output line as gpiozero's ``DigitalOutputDevice`` offers it: ``on()``, ``off()``
    and ``value``; it calls ``drive(level)`` on every change.

    Examples
    --------
    >>> levels = []
    >>> line = SimulatedLine(levels.append)
    >>> line.on(); line.off(); levels, line.value
    ([True, False], 0)
    """

    def __init__(self, drive):
        if not callable(drive):
            raise TypeError(f"drive must be callable (high: bool) -> None, got "
                            f"{type(drive).__name__}")
        self._drive = drive
        self.value = 0

    def on(self) -> None:
        """Drive the line high."""
        self.value = 1
        self._drive(True)

    def off(self) -> None:
        """Drive the line low."""
        self.value = 0
        self._drive(False)

    def close(self) -> None:
        """Release the line: it floats, and the breakout's pull-down takes it low (on ``OE``:
        the outputs follow the registers again), as when the program that drove it exits."""
        self.value = 0
        self._drive(False)

#: Register addresses are one byte; with ``MODE1.AI`` set they roll over from 0xFF to 0x00.
_REGISTER_SPACE = 256


class SimulatedPCA9685:
    """Register model of the PCA9685 driving two simulated MG996R servos.

    Parameters
    ----------
    world : World
        The servo motion model it commands.
    clock : VirtualClock
        The bus's clock.
    pan_channel, tilt_channel : int
        Outputs the two servos hang on.
    oscillator_hz : float
        The chip's oscillator, Hz.

    Attributes
    ----------
    regs : bytearray
        The register file, by address.
    prescale_blocked : int
        Writes to ``PRE_SCALE`` ignored because the chip was awake (DS 7.3.5).
    output_disabled : bool
        The level of the ``OE`` pin: True (high) switches every output off whatever the
        registers say (DS 7.4, "Active LOW output enable input"); see :meth:`oe_line`.

    Examples
    --------
    >>> from ebantenna.chips.pca9685 import Mode1, Register
    >>> from ebantenna.device.clock import VirtualClock
    >>> from ebantenna.device.simulated import SimulatedPCA9685, World
    >>> pca = SimulatedPCA9685(World(None, rate=300.0), VirtualClock())
    >>> pca.write(Register.PRE_SCALE, [121]); round(pca.frequency(), 2)
    50.03
    >>> pca.write(Register.MODE1, [Mode1.AI]); pca.write(Register.PRE_SCALE, [3])
    >>> pca.prescale_blocked, pca.read(Register.PRE_SCALE, 1)
    (1, [121])
    """

    def __init__(self, world: World, clock, *, pan_channel: int = 0, tilt_channel: int = 1,
                 oscillator_hz: float = OSCILLATOR_HZ):
        if not isinstance(world, World):
            raise TypeError(f"world must be a World, got {type(world).__name__}")
        if not callable(getattr(clock, "monotonic", None)):
            raise TypeError(f"clock must be a clock (with monotonic()), got "
                            f"{type(clock).__name__}")
        self.world = world
        self.clock = clock
        last = N_CHANNELS - 1
        pan_channel = check_int("pan_channel", pan_channel, minimum=0, maximum=last)
        tilt_channel = check_int("tilt_channel", tilt_channel, minimum=0, maximum=last)
        if tilt_channel == pan_channel:
            raise ValueError(f"tilt_channel must differ from pan_channel ({pan_channel}), got "
                             f"{tilt_channel!r}")
        self.channels = {pan_channel: "pan", tilt_channel: "tilt"}
        self.oscillator_hz = check_positive("oscillator_hz", oscillator_hz)
        self.regs = bytearray(_REGISTER_SPACE)
        self.prescale_blocked = 0
        self.output_disabled = False
        self.reset()

    def reset(self) -> None:
        """Power-on state (DS 7.3): asleep, every output full off, 200 Hz."""
        self.regs[:] = bytes(_REGISTER_SPACE)
        for register, value in POWER_ON.items():
            self.regs[register] = value
        self._apply()

    def frequency(self) -> float:
        """PWM frequency set by PRE_SCALE, Hz (the chip reads a value below 3 as 3, DS 7.3.5)."""
        prescale = max(self.regs[Register.PRE_SCALE], PRESCALE_MIN)
        return self.oscillator_hz / (COUNTS_PER_PERIOD * (prescale + 1))

    def pulse(self, channel: int) -> float:
        """Pulse width now on ``channel``, s (0 when it is off, the chip sleeps or OE is high)."""
        channel = check_int("channel", channel, minimum=0, maximum=N_CHANNELS - 1)
        if self.regs[Register.MODE1] & Mode1.SLEEP or self.output_disabled:
            return 0.0
        first = led_register(channel)
        on_l, on_h, off_l, off_h = self.regs[first:first + len(Led)]
        if off_h & LED_FULL or on_h & LED_FULL:
            return 0.0  # full off, or full on (no pulses: a servo ignores it)
        width = (join_count(off_l, off_h) - join_count(on_l, on_h)) % COUNTS_PER_PERIOD
        return width / (COUNTS_PER_PERIOD * self.frequency())

    def outputs_enabled(self) -> bool:
        """Whether any servo channel is producing pulses."""
        return any(self.pulse(ch) > 0 for ch in self.channels)

    def set_oe(self, high: bool) -> None:
        """Drive the ``OE`` pin: high switches every output off at once, low lets the registers
        rule again (no I2C involved)."""
        self.output_disabled = check_bool("high", high)
        self._apply()

    def oe_line(self) -> SimulatedLine:
        """A GPIO line wired to ``OE``, with gpiozero's ``on``/``off`` (on = high = outputs off)."""
        return SimulatedLine(self.set_oe)

    def _apply(self) -> None:
        now = self.clock.monotonic()
        for ch, axis in self.channels.items():
            angle = mg996r_angle(self.pulse(ch))
            servo = self.world.pan if axis == "pan" else self.world.tilt
            if angle != servo.target:
                self.world.command(now, axis, angle)

    def _step(self) -> int:
        return 1 if self.regs[Register.MODE1] & Mode1.AI else 0

    def read(self, register: int, length: int) -> list[int]:
        """Read ``length`` bytes from ``register`` on, as one I2C read transfer does."""
        register = check_int("register", register, minimum=0, maximum=0xFF)
        length = check_int("length", length, minimum=0)
        step = self._step()
        return [self.regs[(register + k * step) % _REGISTER_SPACE] for k in range(length)]

    def write(self, register: int, data) -> None:
        """Write ``data`` from ``register`` on, as one I2C write transfer does."""
        register = check_int("register", register, minimum=0, maximum=0xFF)
        if isinstance(data, str) or not hasattr(data, "__iter__"):
            raise TypeError(f"data must be a sequence of bytes (0-255), got "
                            f"{type(data).__name__}")
        data = [check_int("data", value, minimum=0, maximum=0xFF) for value in data]
        step = self._step()
        for k, value in enumerate(data):
            reg = (register + k * step) % _REGISTER_SPACE
            if reg == Register.PRE_SCALE and not self.regs[Register.MODE1] & Mode1.SLEEP:
                self.prescale_blocked += 1  # DS 7.3.5: PRE_SCALE is blocked while awake
                continue
            if reg == Register.MODE1:
                value &= ~int(Mode1.RESTART) & 0xFF  # RESTART restarts the PWM and clears itself
            if Register.ALL_LED_ON_L <= reg <= Register.ALL_LED_OFF_H:
                part = Led(reg - Register.ALL_LED_ON_L)
                for ch in range(N_CHANNELS):
                    self.regs[led_register(ch, part)] = value
                continue
            self.regs[reg] = value
        self._apply()
