"""The wiring figure draws exactly the connections the drivers' defaults need."""

from __future__ import annotations

import matplotlib.pyplot as plt
import pytest

from ebantenna.chips.mpu6050 import ADDRESS_AD0_LOW
from ebantenna.chips.pca9685 import DEFAULT_ADDRESS
from ebantenna.device import PCA9685, MPU6050Config, PanTilt, wiring
from ebantenna.device.simulated import SimulatedRig


@pytest.fixture(scope="module")
def drawn():
    fig = wiring.draw_wiring()
    ax = fig.axes[0]
    lines = {line.get_gid(): line for line in ax.lines if str(line.get_gid()).startswith("wire")}
    texts = {t.get_gid(): t.get_text() for t in ax.texts if t.get_gid()}
    yield lines, texts
    plt.close(fig)


def _ends(wire):
    return {wire.start, wire.end}


def test_every_wire_drawn_once_between_its_two_pins(drawn):
    lines, _ = drawn
    assert sorted(lines) == sorted(f"wire:{k}" for k in range(len(wiring.WIRES)))
    where = wiring.pin_positions()
    for k, wire in enumerate(wiring.WIRES):
        xs, ys = lines[f"wire:{k}"].get_data()
        assert (xs[0], ys[0]) == where[wire.start][:2]
        assert (xs[-1], ys[-1]) == where[wire.end][:2]
        assert (lines[f"wire:{k}"].get_linestyle() == "--") == wire.optional


def test_every_pin_drawn_belongs_to_a_part():
    where = wiring.pin_positions()
    for wire in wiring.WIRES:
        assert wire.start in where and wire.end in where


def test_addresses_are_the_drivers_defaults(drawn):
    _, texts = drawn
    assert wiring.MPU6050_ADDRESS == MPU6050Config().address == ADDRESS_AD0_LOW == 0x68
    assert wiring.PCA9685_ADDRESS == DEFAULT_ADDRESS == 0x40
    assert texts["address:MPU-6050"] == "address 0x68"
    assert texts["address:PCA9685"] == "address 0x40"
    # AD0 low is what gives 0x68 (PS 9.2): the AD0 pin is wired to the chip's ground
    ad0 = [w for w in wiring.WIRES if ("MPU-6050", "AD0") in _ends(w)]
    assert len(ad0) == 1 and ("MPU-6050", "GND") in _ends(ad0[0])


def test_both_chips_share_bus_1_on_its_header_pins():
    for chip in ("MPU-6050", "PCA9685"):
        for signal, gpio, pin in (("SDA", 2, 3), ("SCL", 3, 5)):
            wires = [w for w in wiring.WIRES if (chip, signal) in _ends(w)]
            assert len(wires) == 1
            assert ("Raspberry Pi", f"pin {pin}: GPIO {gpio}") in _ends(wires[0])
        for supply, pin in (("VCC", "pin 1: 3.3 V"), ("GND", "pin 6: GND")):
            wires = [w for w in wiring.WIRES if (chip, supply) in _ends(w)
                     and w.start[0] == "Raspberry Pi"]
            assert [w.start for w in wires] == [("Raspberry Pi", pin)]


def test_servo_channels_are_pantilts_defaults():
    rig = SimulatedRig.quiet()
    unit = PanTilt(PCA9685(rig.bus, clock=rig.clock))
    channels = {"pan servo": unit.pan.calibration.channel,
                "tilt servo": unit.tilt.calibration.channel}
    for servo, channel in channels.items():
        wires = [w for w in wiring.WIRES if (servo, "plug") in _ends(w)]
        assert [w.start for w in wires] == [("PCA9685", f"output {channel}")]


def test_oe_wire_is_optional_on_gpio_17_and_servo_power_is_separate():
    oe = [w for w in wiring.WIRES if ("PCA9685", "OE") in _ends(w)]
    assert len(oe) == 1 and oe[0].optional
    assert ("Raspberry Pi", "pin 11: GPIO 17") in _ends(oe[0])
    # V+ comes from the servo supply, never from the Raspberry Pi
    vplus = [w for w in wiring.WIRES if ("PCA9685", "V+") in _ends(w)]
    assert [w.end[0] for w in vplus] == ["servo supply 5-6 V"]
    assert any(("servo supply 5-6 V", "-") in _ends(w) for w in wiring.WIRES)
