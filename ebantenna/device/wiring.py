"""How the rig is wired: every connection the drivers' defaults expect, and a drawing of them.

The drivers choose nothing about the wiring at run time; they assume it. :data:`WIRES` lists the
connections those assumptions need, each derived from the default it serves:

- the MPU-6050 at the ``address`` of :class:`~ebantenna.device.mpu6050_config.MPU6050Config`
  (0x68, pin ``AD0`` low; MPU-6000/MPU-6050 Product Specification rev. 3.4, "PS", section 9.2);
- the PCA9685 at :data:`ebantenna.chips.pca9685.DEFAULT_ADDRESS` (0x40, address pins ``A0``-``A5``
  low; PCA9685 product data sheet rev. 4, "DS", section 7.1);
- both on I2C bus 1 of the Raspberry Pi (``--bus 1``, ``/dev/i2c-1``), whose SDA and SCL are
  GPIO 2 and GPIO 3 on header pins 3 and 5 (Raspberry Pi documentation, "GPIO and the 40-pin
  header");
- the pan servo on output 0 and the tilt servo on output 1
  (:class:`~ebantenna.device.pantilt.PanTilt`);
- optionally the PCA9685's active-low ``OE`` pin (DS 7.4) on GPIO 17, header pin 11, the line
  ``acquire --oe-gpio 17`` drives (:mod:`ebantenna.device.oe`);
- the servos' power from a separate supply on the PCA9685's ``V+`` terminal, its ground joined to
  the Raspberry Pi's through the board.

:func:`draw_wiring` draws exactly these connections.

Examples
--------
>>> from ebantenna.device.wiring import WIRES, draw_wiring
>>> [w.signal for w in WIRES if w.end == ("MPU-6050", "AD0")]
['AD0 low: address 0x68']
>>> fig = draw_wiring()
>>> wires = [line for line in fig.axes[0].lines if str(line.get_gid()).startswith("wire")]
>>> len(wires) == len(WIRES)
True
"""

from __future__ import annotations

from dataclasses import dataclass

from .._validate import check_bool, check_int
from ..chips import mg996r, mpu6050, pca9685
from ..chips.mpu6050 import ADDRESS_AD0_HIGH, ADDRESS_AD0_LOW
from ..chips.pca9685 import DEFAULT_ADDRESS as PCA9685_ADDRESS
from .mpu6050_config import MPU6050Config

__all__ = [
    "I2C_BUS", "SDA_GPIO", "SCL_GPIO", "OE_GPIO", "PAN_CHANNEL", "TILT_CHANNEL", "HEADER_PIN",
    "MPU6050_ADDRESS", "PCA9685_ADDRESS", "MPU6050_VDD", "PCA9685_VDD", "FAST_MODE_HZ",
    "SERVO_VOLTAGE", "SERVO_STALL_CURRENT", "SERVO_SUPPLY", "servo_supply_current", "Wire",
    "WIRES", "PARTS", "pin_positions", "draw_wiring",
]  # fmt: skip

#: The Raspberry Pi's I2C bus on its header (``/dev/i2c-1``).
I2C_BUS = 1
#: BCM GPIO numbers of bus 1's data and clock lines, and of the ``OE`` line of ``--oe-gpio 17``.
SDA_GPIO, SCL_GPIO, OE_GPIO = 2, 3, 17
#: Channels of the pan and tilt servos, as :class:`~ebantenna.device.pantilt.PanTilt` defaults them.
PAN_CHANNEL, TILT_CHANNEL = 0, 1
#: Physical header pin of each signal used (Raspberry Pi documentation, "GPIO and the 40-pin
#: header"): 3.3 V on pin 1, ground on pin 6.
HEADER_PIN = {"3.3 V": 1, f"GPIO {SDA_GPIO}": 3, f"GPIO {SCL_GPIO}": 5, "GND": 6,
              f"GPIO {OE_GPIO}": 11}
#: The accelerometer's address as the driver's default configuration has it.
MPU6050_ADDRESS = MPU6050Config().address

#: Supply voltage range of the MPU-6050, V (from :mod:`ebantenna.chips.mpu6050`); the Raspberry
#: Pi's 3.3 V pin lies inside it.
MPU6050_VDD = mpu6050.SUPPLY_VOLTAGE
#: Supply voltage range of the PCA9685, V (from :mod:`ebantenna.chips.pca9685`).
PCA9685_VDD = pca9685.SUPPLY_VOLTAGE
#: Fastest I2C clock both chips accept, Hz: the MPU-6050's fast mode, 400 kHz (the PCA9685
#: accepts Fast-mode Plus, 1 MHz).
FAST_MODE_HZ = min(mpu6050.MAX_I2C_CLOCK_HZ, pca9685.MAX_I2C_CLOCK_HZ)
#: Operating voltage of the MG996R, V (from :mod:`ebantenna.chips.mg996r`).
SERVO_VOLTAGE = mg996r.OPERATING_VOLTAGE
#: Stall current of one MG996R at 6 V, A (from :mod:`ebantenna.chips.mg996r`).
SERVO_STALL_CURRENT = mg996r.STALL_CURRENT
#: Servo supply voltage the rig uses, V: inside :data:`SERVO_VOLTAGE`, and the range the data
#: sheet's figures are given for (4.8 V and 6 V).
SERVO_SUPPLY = (5.0, 6.0)


def servo_supply_current(n_servos: int = 2) -> float:
    """Current the servo supply must deliver when every servo stalls at once, A.

    >>> servo_supply_current()  # pan and tilt
    5.0
    """
    n_servos = check_int("n_servos", n_servos, minimum=0)
    return n_servos * SERVO_STALL_CURRENT


@dataclass(frozen=True)
class Wire:
    """One connection: from ``(part, pin)`` to ``(part, pin)``, with what it carries."""

    start: tuple[str, str]
    end: tuple[str, str]
    signal: str
    optional: bool = False

    def __post_init__(self):
        for name in ("start", "end"):
            value = getattr(self, name)
            if not (isinstance(value, tuple) and len(value) == 2
                    and all(isinstance(v, str) for v in value)):
                raise TypeError(f"{name} must be a (part, pin) pair of str, got {value!r}")
        if not isinstance(self.signal, str):
            raise TypeError(f"signal must be a str, got {type(self.signal).__name__}")
        check_bool("optional", self.optional)


def _pi(signal: str) -> tuple[str, str]:
    return ("Raspberry Pi", f"pin {HEADER_PIN[signal]}: {signal}")


def _ad0_level() -> str:
    if MPU6050_ADDRESS not in (ADDRESS_AD0_LOW, ADDRESS_AD0_HIGH):
        raise ValueError(f"no AD0 level gives address 0x{MPU6050_ADDRESS:02X}")
    return "GND" if MPU6050_ADDRESS == ADDRESS_AD0_LOW else "VCC"


#: Every connection of the rig.
WIRES = (
    Wire(_pi("3.3 V"), ("MPU-6050", "VCC"), "3.3 V"),
    Wire(_pi("GND"), ("MPU-6050", "GND"), "GND"),
    Wire(_pi(f"GPIO {SDA_GPIO}"), ("MPU-6050", "SDA"), "SDA"),
    Wire(_pi(f"GPIO {SCL_GPIO}"), ("MPU-6050", "SCL"), "SCL"),
    Wire(("MPU-6050", _ad0_level()), ("MPU-6050", "AD0"),
         f"AD0 {'low' if _ad0_level() == 'GND' else 'high'}: address 0x{MPU6050_ADDRESS:02X}"),
    Wire(_pi("3.3 V"), ("PCA9685", "VCC"), "3.3 V"),
    Wire(_pi("GND"), ("PCA9685", "GND"), "GND"),
    Wire(_pi(f"GPIO {SDA_GPIO}"), ("PCA9685", "SDA"), "SDA"),
    Wire(_pi(f"GPIO {SCL_GPIO}"), ("PCA9685", "SCL"), "SCL"),
    Wire(_pi(f"GPIO {OE_GPIO}"), ("PCA9685", "OE"), "OE (optional)", optional=True),
    Wire(("PCA9685", f"output {PAN_CHANNEL}"), ("pan servo", "plug"), "PWM, V+, GND"),
    Wire(("PCA9685", f"output {TILT_CHANNEL}"), ("tilt servo", "plug"), "PWM, V+, GND"),
    Wire(("PCA9685", "GND (V+)"), ("servo supply 5-6 V", "-"), "GND, common"),
    Wire(("PCA9685", "V+"), ("servo supply 5-6 V", "+"), "V+"),
)

#: Each part's box ``(x, y, width, height)`` in the drawing, and its pins as ``(name, side)``.
PARTS = {
    "Raspberry Pi": ((0.0, 0.6, 2.6, 5.0), [(p, "right") for p in (
        "pin 1: 3.3 V", f"pin 3: GPIO {SDA_GPIO}", f"pin 5: GPIO {SCL_GPIO}", "pin 6: GND",
        f"pin 11: GPIO {OE_GPIO}")]),
    "MPU-6050": ((6.2, 4.0, 2.0, 2.2), [(p, "left") for p in ("VCC", "GND", "SDA", "SCL",
                                                              "AD0")]),
    "PCA9685": ((6.2, 0.2, 2.0, 3.2), [(p, "left") for p in ("VCC", "GND", "SDA", "SCL", "OE")]
                + [(p, "right") for p in (f"output {PAN_CHANNEL}", f"output {TILT_CHANNEL}",
                                          "V+", "GND (V+)")]),
    "servo supply 5-6 V": ((10.4, 0.0, 1.8, 1.0), [("+", "left"), ("-", "left")]),
    "pan servo": ((10.4, 2.6, 1.8, 0.7), [("plug", "left")]),
    "tilt servo": ((10.4, 1.5, 1.8, 0.7), [("plug", "left")]),
}

_COLOURS = {"3.3 V": "tab:red", "GND": "black", "SDA": "tab:blue", "SCL": "tab:orange",
            "OE": "tab:purple", "V+": "tab:red", "PWM": "tab:green", "AD0": "black"}


def pin_positions() -> dict:
    """Where each ``(part, pin)`` sits on its box's edge, in drawing units."""
    where = {}
    for part, ((x, y, w, h), pins) in PARTS.items():
        for side in ("left", "right"):
            names = [name for name, s in pins if s == side]
            for k, name in enumerate(names):
                yy = y + h - (k + 1) * h / (len(names) + 1)
                where[(part, name)] = (x if side == "left" else x + w, yy, side)
    return where


def _route(start, end, lane: float):
    """An orthogonal path from ``start`` to ``end`` through the vertical line ``x = lane``."""
    (x0, y0, _), (x1, y1, _) = start, end
    return [x0, lane, lane, x1], [y0, y0, y1, y1]


def _lanes(where: dict) -> list[float]:
    """One vertical lane per wire, so that no two wires share a segment."""
    lanes, left, right = [], 3.0, 9.0
    for wire in WIRES:
        x0, x1 = where[wire.start][0], where[wire.end][0]
        if x0 == x1:  # a jumper on one edge of a part, drawn outside it
            lanes.append(x0 - 0.5)
        elif max(x0, x1) <= 6.2:
            lanes.append(left)
            left += 0.28
        else:
            lanes.append(right)
            right += 0.25
    return lanes


def _draw_parts(ax, where: dict) -> None:
    from matplotlib.patches import Rectangle

    for part, ((x, y, w, h), _) in PARTS.items():
        ax.add_patch(Rectangle((x, y), w, h, facecolor="0.93", edgecolor="0.3", gid=f"part:{part}"))
        ax.text(x + w / 2, y + h + 0.08, part, ha="center", va="bottom", weight="bold")
    labels = {"Raspberry Pi": f"I2C bus {I2C_BUS}", "MPU-6050": f"address 0x{MPU6050_ADDRESS:02X}",
              "PCA9685": f"address 0x{PCA9685_ADDRESS:02X}"}
    for part, text in labels.items():
        (x, y, w, h), _ = PARTS[part]
        ax.text(x + w / 2, y + 0.12, text, ha="center", va="bottom", fontsize="small",
                style="italic", gid=f"address:{part}")
    for (_, name), (x, y, side) in where.items():
        inside = 0.08 if side == "left" else -0.08
        ax.text(x + inside, y, name, ha="left" if side == "left" else "right", va="center",
                fontsize="x-small")


def draw_wiring(ax=None):
    """Draw the rig's wiring: the parts as boxes, every connection of :data:`WIRES` as a line.

    Parameters
    ----------
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure of 11 x 6 inches when omitted.

    Returns
    -------
    matplotlib.figure.Figure
        The figure. Each wire is a line whose ``gid`` is ``"wire:<index into WIRES>"``; the
        optional ``OE`` wire is dashed.
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(11, 6))
    elif not callable(getattr(ax, "add_patch", None)):
        raise TypeError(f"ax must be a matplotlib Axes or None, got {type(ax).__name__}")
    where = pin_positions()
    _draw_parts(ax, where)
    for k, (wire, lane) in enumerate(zip(WIRES, _lanes(where), strict=True)):
        xs, ys = _route(where[wire.start], where[wire.end], lane)
        kind = next((c for c in _COLOURS if wire.signal.startswith(c)), "PWM")
        ax.plot(xs, ys, color=_COLOURS[kind], lw=1.6, ls="--" if wire.optional else "-",
                gid=f"wire:{k}", label=wire.signal)
        ax.plot([xs[0], xs[-1]], [ys[0], ys[-1]], "o", ms=3, color=_COLOURS[kind])
    ax.set_xlim(-0.2, 12.4)
    ax.set_ylim(-0.3, 6.7)
    ax.set_aspect("equal")
    ax.axis("off")
    ax.set_title("Wiring of the rig (the drivers' defaults); dashed: optional")
    return ax.figure
