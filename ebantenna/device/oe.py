"""A release of the servos that does not go through I2C: the PCA9685's ``OE`` pin on a GPIO line.

The PCA9685's ``OE`` input is active low (DS 7.4): while it is low the outputs follow the
registers; driven high, every output is switched off at once (with ``MODE2.OUTNE = 00``, as
:meth:`~ebantenna.device.pca9685.PCA9685.initialize` sets it, the outputs go low), whatever the
registers say and whatever the bus does. A servo that gets no pulses goes limp. When the I2C bus
is dead, this is the only way left to switch the servos off short of cutting their supply; but
it lasts only while the program drives the line (:data:`OE_ONLY`), so it is not a release: the
servos count as released only when their outputs are written full-off and read back so over
I2C, and a run that could only drive ``OE`` ends with the instruction to cut the servo supply.

Wiring (Raspberry Pi header): the PCA9685 breakout's ``OE`` pin to a free GPIO, e.g. GPIO 17
(header pin 11). Adafruit's breakout pulls ``OE`` low with a resistor, so the outputs stay enabled
while the line is not driven; the line is driven low (outputs enabled) when it is opened, and high
to release.

The GPIO library is an optional extra, ``pip install "ebantenna[gpio]"``: gpiozero with the
``lgpio`` pin factory, the default on current Raspberry Pi OS (Bookworm), which also drives the
Raspberry Pi 5's GPIO. The simulated rig offers the same kind of line
(:meth:`~ebantenna.device.simulated.SimulatedRig.oe_line`), wired to its simulated PCA9685.
"""

from __future__ import annotations

import logging

from .._validate import check_int

__all__ = ["OutputEnable", "GPIO_HINT", "OE_ONLY"]

logger = logging.getLogger(__name__)

#: What to install for :meth:`OutputEnable.gpio`.
GPIO_HINT = ('the OE release needs gpiozero: pip install "ebantenna[gpio]" (gpiozero and lgpio; '
             "on Raspberry Pi OS also 'sudo apt install python3-lgpio')")

#: Why ``OE`` alone is not a release: it holds the outputs off only while this process drives
#: the line. At exit the GPIO line is released (gpiozero closes its devices, the kernel frees
#: the line of a process that ends): it floats, the breakout's pull-down takes ``OE`` low, and
#: the outputs follow the registers again, which still hold the servos' pulses when the release
#: over I2C failed.
OE_ONLY = ("the OE pin holds the servo outputs off only while this program runs: at exit its "
           "GPIO line is released, the board's pull-down enables the outputs again and the "
           "servos get the pulses their registers still hold")

#: Highest BCM GPIO number of the Raspberry Pi's 40-pin header.
_LAST_GPIO = 27


class OutputEnable:
    """The PCA9685's ``OE`` pin, driven through a GPIO output line.

    Parameters
    ----------
    line : object
        A GPIO output with ``on()`` (drive high) and ``off()`` (drive low), such as gpiozero's
        ``DigitalOutputDevice`` or :class:`~ebantenna.device.simulated.pca9685.SimulatedLine`.
        It is driven low (outputs enabled) at once.

    Examples
    --------
    >>> from ebantenna.device import PCA9685, PanTilt
    >>> from ebantenna.device.oe import OutputEnable
    >>> from ebantenna.device.simulated import SimulatedRig
    >>> rig = SimulatedRig.quiet()
    >>> unit = PanTilt(PCA9685(rig.bus, clock=rig.clock)); unit.initialize()
    >>> oe = OutputEnable(rig.oe_line())
    >>> _ = unit.move(100.0, 80.0); rig.pca.outputs_enabled()
    True
    >>> oe.disable_outputs(); rig.pca.outputs_enabled()  # no I2C transfer involved
    False
    """

    def __init__(self, line):
        if not (callable(getattr(line, "on", None)) and callable(getattr(line, "off", None))):
            raise TypeError(f"line must be a GPIO output with on() and off(), got "
                            f"{type(line).__name__}")
        self.line = line
        self.line.off()
        #: Whether ``OE`` is driven high (every output off) by :meth:`disable_outputs`.
        self.disabled = False

    @classmethod
    def gpio(cls, pin: int) -> OutputEnable:
        """``OE`` wired to BCM GPIO ``pin`` (2-27), through gpiozero.

        Raises
        ------
        ImportError
            When gpiozero is not installed (the ``gpio`` extra).
        """
        pin = check_int("pin", pin, minimum=2, maximum=_LAST_GPIO)
        try:
            from gpiozero import DigitalOutputDevice
        except ImportError as exc:
            raise ImportError(GPIO_HINT) from exc
        return cls(DigitalOutputDevice(pin, active_high=True, initial_value=False))

    def disable_outputs(self) -> None:
        """Drive ``OE`` high: every output off, the servos limp (no I2C involved)."""
        self.line.on()
        self.disabled = True
        logger.warning("PCA9685 outputs switched off through the OE pin")

    def enable_outputs(self) -> None:
        """Drive ``OE`` low: the outputs follow the registers again."""
        self.line.off()
        self.disabled = False

    def close(self) -> None:
        """Release the GPIO line: it floats, and the breakout's pull-down takes ``OE`` low (the
        outputs follow the registers again, :data:`OE_ONLY`)."""
        close = getattr(self.line, "close", None)
        if callable(close):
            close()
