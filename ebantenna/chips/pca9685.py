"""NXP PCA9685 16-channel, 12-bit PWM controller: register map, bit fields and constants.

Source, cited as "DS" with its section, table or equation: *PCA9685, 16-channel, 12-bit PWM Fm+
I2C-bus LED controller, Product data sheet*, revision 4, 16 April 2015, NXP Semiconductors.

Each output ``n`` has four registers from ``LED0_ON_L + 4 n`` on (:func:`led_register`), holding a
12-bit ON count and a 12-bit OFF count (:func:`split_count`, :func:`join_count`) and, in bit 4 of
each high byte, the "full ON" and "full OFF" bits (:data:`LED_FULL`). The four ``ALL_LED``
registers have the same layout and write all 16 outputs at once.

Examples
--------
>>> from ebantenna.chips.pca9685 import Led, Register, led_register, join_count
>>> hex(led_register(1, Led.OFF_H)), hex(Register.PRE_SCALE), join_count(0x33, 0x01)
('0xd', '0xfe', 307)
"""

from __future__ import annotations

from enum import IntEnum, IntFlag

from .._validate import check_int
from .bitfield import BitField

__all__ = [
    "DEFAULT_ADDRESS",
    "SUPPLY_VOLTAGE",
    "MAX_I2C_CLOCK_HZ",
    "N_CHANNELS",
    "COUNTS_PER_PERIOD",
    "Register",
    "Led",
    "led_register",
    "all_led_register",
    "Mode1",
    "Mode2",
    "OUTNE",
    "LED_FULL",
    "split_count",
    "join_count",
    "POWER_ON",
    "OSCILLATOR_HZ",
    "OSCILLATOR_STARTUP",
    "PRESCALE_MIN",
    "PRESCALE_MAX",
]

#: 7-bit I2C address with the address pins A5-A0 all low: ``1 A5 A4 A3 A2 A1 A0`` (DS 7.1).
DEFAULT_ADDRESS = 0x40
#: Supply voltage range, V (DS 1, "General description").
SUPPLY_VOLTAGE = (2.3, 5.5)
#: Fastest I2C clock, Hz: Fast-mode Plus, 1 MHz (DS 1).
MAX_I2C_CLOCK_HZ = 1_000_000
#: Number of PWM outputs, LED0-LED15 (DS 1).
N_CHANNELS = 16
#: Steps of the 12-bit counter in one PWM period (DS 7.3.3).
COUNTS_PER_PERIOD = 4096


class Register(IntEnum):
    """Register addresses (DS 7.3, table 4 "Register summary"); outputs: :func:`led_register`."""

    MODE1 = 0x00
    MODE2 = 0x01
    SUBADR1 = 0x02
    SUBADR2 = 0x03
    SUBADR3 = 0x04
    ALLCALLADR = 0x05
    LED0_ON_L = 0x06
    ALL_LED_ON_L = 0xFA
    ALL_LED_ON_H = 0xFB
    ALL_LED_OFF_L = 0xFC
    ALL_LED_OFF_H = 0xFD
    PRE_SCALE = 0xFE
    TEST_MODE = 0xFF


class Led(IntEnum):
    """Offset of each of an output's four registers from its first, ``LEDn_ON_L`` (DS table 4)."""

    ON_L = 0
    ON_H = 1
    OFF_L = 2
    OFF_H = 3


def led_register(channel: int, part: Led = Led.ON_L) -> int:
    """Address of register ``part`` of output ``channel`` (0-15): ``0x06 + 4 channel + part``.

    Examples
    --------
    >>> from ebantenna.chips.pca9685 import Led, led_register
    >>> led_register(0), led_register(15, Led.OFF_H)
    (6, 69)
    """
    channel = check_int("channel", channel, minimum=0, maximum=N_CHANNELS - 1)
    return Register.LED0_ON_L + len(Led) * channel + _led(part)


def all_led_register(part: Led) -> Register:
    """Address of the ``ALL_LED`` register that writes ``part`` of every output (DS 7.3.4)."""
    return Register(Register.ALL_LED_ON_L + _led(part))


def _led(part) -> Led:
    """``part`` as a :class:`Led`, else an error naming it."""
    try:
        return Led(part)
    except (ValueError, TypeError):
        raise ValueError(f"part must be one of {', '.join(p.name for p in Led)} (0 to "
                         f"{len(Led) - 1}), got {part!r:.40}") from None


class Mode1(IntFlag):
    """Bits of ``MODE1`` (DS 7.3.1, table 5)."""

    RESTART = 0x80
    EXTCLK = 0x40
    AI = 0x20
    SLEEP = 0x10
    SUB1 = 0x08
    SUB2 = 0x04
    SUB3 = 0x02
    ALLCALL = 0x01


class Mode2(IntFlag):
    """Single bits of ``MODE2`` (DS 7.3.2, table 6); ``OUTNE`` is the field :data:`OUTNE`."""

    INVRT = 0x10
    OCH = 0x08
    OUTDRV = 0x04


#: ``MODE2[1:0]``: output state while ``OE`` is high (DS 7.3.2, table 6).
OUTNE = BitField(Register.MODE2, 0, 2)

#: Bit 4 of ``LEDn_ON_H`` (full ON) and of ``LEDn_OFF_H`` (full OFF, which wins) (DS 7.3.3,
#: tables 7 and 8).
LED_FULL = 0x10
#: Bits 3:0 of ``LEDn_ON_H``/``LEDn_OFF_H``: the upper four bits of the 12-bit count (DS 7.3.3).
_COUNT_HIGH_MASK = 0x0F


def split_count(count: int) -> tuple[int, int]:
    """A 12-bit count as its ``(low, high)`` register bytes, full ON/OFF bit clear.

    Examples
    --------
    >>> from ebantenna.chips.pca9685 import split_count
    >>> split_count(307)
    (51, 1)
    """
    count = check_int("count", count, minimum=0, maximum=COUNTS_PER_PERIOD - 1)
    return count & 0xFF, count >> 8


def join_count(low: int, high: int) -> int:
    """The 12-bit count held in a ``_L`` and an ``_H`` register (the full ON/OFF bit ignored)."""
    low = check_int("low", low, minimum=0, maximum=0xFF)  # register bytes
    high = check_int("high", high, minimum=0, maximum=0xFF)
    return (high & _COUNT_HIGH_MASK) << 8 | low


#: Power-on values that are not 0x00 (DS 7.3, table 4, and 7.3.1-7.3.5): ``MODE1`` 0x11 (asleep,
#: ALLCALL on), ``MODE2`` 0x04 (totem-pole outputs), the I2C sub-addresses ``SUBADR1..3`` 0xE2,
#: 0xE4, 0xE8 and ``ALLCALLADR`` 0xE0 (8-bit forms, DS 7.3.6-7.3.7), ``PRE_SCALE`` 0x1E (200 Hz),
#: and every ``LEDn_OFF_H`` 0x10 (full OFF).
POWER_ON = {
    Register.MODE1: Mode1.SLEEP | Mode1.ALLCALL,
    Register.MODE2: Mode2.OUTDRV,
    Register.SUBADR1: 0xE2,
    Register.SUBADR2: 0xE4,
    Register.SUBADR3: 0xE8,
    Register.ALLCALLADR: 0xE0,
    Register.PRE_SCALE: 0x1E,
    **{led_register(ch, Led.OFF_H): LED_FULL for ch in range(N_CHANNELS)},
}

#: Internal oscillator, Hz (DS 7.3.5: "osc_clock" of equation 1).
OSCILLATOR_HZ = 25e6
#: Wait for the oscillator after clearing ``MODE1.SLEEP``, s (DS 7.3.1.1: "500 us").
OSCILLATOR_STARTUP = 500e-6
#: Range of ``PRE_SCALE``: the chip forces a minimum of 3 (DS 7.3.5), a byte holds 255.
PRESCALE_MIN = 3
PRESCALE_MAX = 255
