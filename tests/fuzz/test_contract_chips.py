"""The input contract of the chips' register maps: addresses, counts and bit fields.

Register numbers, channels, counts and field values must fit the chip's bytes and fields
(0-255, 12-bit counts, 0-15 channels, the field's width); each out-of-range or non-integer value
is refused naming the parameter, and a few encodings are checked by hand against the datasheets'
layouts. The register and bit enumerations and the chip tables (datasheet constants the package
defines) are exempt, held to being enumerations or dataclasses of the package.

Found by these rows and fixed: a register byte of 256 or 300 read and written into a bit
field, low and high count bytes beyond a byte joined into a count, and Python's "7 is not a
valid Led" for a register part.
"""

from __future__ import annotations

import dataclasses
import enum
import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, check_row  # noqa: E402

from ebantenna.chips import bitfield, mpu6050, pca9685  # noqa: E402

FIELD = bitfield.BitField(0x1A, 3, 2)  # bits 4..3 of register 0x1A
p, b = "ebantenna.chips.pca9685.", "ebantenna.chips.bitfield.BitField"
#: ``surface -> [(id, call, names or None, same)]``
ROWS = {
    p + "led_register": [
        ("channel-16", lambda: pca9685.led_register(16), ("channel",), None),
        ("channel-negative", lambda: pca9685.led_register(-1), ("channel",), None),
        ("channel-float", lambda: pca9685.led_register(1.5), ("channel",), None),
        ("part-7", lambda: pca9685.led_register(0, 7), ("part",), None),
        # DS 7.3.3: LEDn_ON_L at 0x06 + 4 n, then ON_H, OFF_L, OFF_H
        ("by-hand", lambda: (pca9685.led_register(0), pca9685.led_register(15, 3)), None,
         lambda r: r == (0x06, 0x06 + 60 + 3)),
    ],
    p + "all_led_register": [
        ("part-9", lambda: pca9685.all_led_register(9), ("part",), None),
        ("part-str", lambda: pca9685.all_led_register("x"), ("part",), None),
        ("by-hand", lambda: pca9685.all_led_register(0), None, lambda r: r == 0xFA),
    ],
    p + "split_count": [
        ("count-4096", lambda: pca9685.split_count(4096), ("count",), None),
        ("count-negative", lambda: pca9685.split_count(-1), ("count",), None),
        ("count-float", lambda: pca9685.split_count(1.5), ("count",), None),
        ("by-hand", lambda: pca9685.split_count(0xABC), None, lambda r: r == (0xBC, 0x0A)),
    ],
    p + "join_count": [
        ("low-256", lambda: pca9685.join_count(256, 0), ("low",), None),
        ("high-negative", lambda: pca9685.join_count(0, -1), ("high",), None),
        ("high-str", lambda: pca9685.join_count(0, "1"), ("high",), None),
        # the full ON/OFF bit (0x10 of the high byte) is not part of the count
        ("full-bit-ignored", lambda: pca9685.join_count(0xBC, 0x1A), None,
         lambda r: r == 0xABC),
    ],
    "ebantenna.chips.mpu6050.gyro_output_rate": [
        ("dlpf_cfg-8", lambda: mpu6050.gyro_output_rate(8), ("dlpf_cfg",), None),
        ("dlpf_cfg-negative", lambda: mpu6050.gyro_output_rate(-1), ("dlpf_cfg",), None),
        # RM 4.6: 8 kHz with the filter off (0 and 7), 1 kHz otherwise
        ("by-hand", lambda: [mpu6050.gyro_output_rate(c) for c in range(8)], None,
         lambda r: r == [8000.0] + [1000.0] * 6 + [8000.0]),
    ],
    b: [
        ("shift-8", lambda: bitfield.BitField(0x10, 8, 1), ("shift",), None),
        ("width-0", lambda: bitfield.BitField(0x10, 0, 0), ("width",), None),
        ("past-the-byte", lambda: bitfield.BitField(0x10, 6, 4), ("width",), None),
        ("register-256", lambda: bitfield.BitField(256, 0, 1), ("register",), None),
    ],
    b + ".get": [
        ("register_value-256", lambda: FIELD.get(256), ("register_value",), None),
        ("register_value-negative", lambda: FIELD.get(-1), ("register_value",), None),
        ("by-hand", lambda: FIELD.get(0b1101_0111), None, lambda r: r == 0b10),
    ],
    b + ".put": [
        ("value-4", lambda: FIELD.put(4), ("value",), None),
        ("register_value-300", lambda: FIELD.put(1, 300), ("register_value",), None),
        ("keeps-the-other-bits", lambda: FIELD.put(0b01, 0b1111_1111), None,
         lambda r: r == 0b1110_1111),
    ],
}
CASES = [(surface, *row) for surface, rows in ROWS.items() for row in rows]

#: Enumerations of registers and bits, and the datasheet tables.
ENUMS = [f"ebantenna.chips.mpu6050.{n}" for n in (
    "ClockSource", "FifoEnable", "Interrupt", "PowerManagement1", "Register", "UserControl")] + [
    f"ebantenna.chips.pca9685.{n}" for n in ("Led", "Mode1", "Mode2", "Register")]
TABLES = ["ebantenna.chips.mpu6050.ChipModel", "ebantenna.chips.mpu6050.DlpfSetting"]


def _find(dotted):
    module, name = dotted.rsplit(".", 1)
    return getattr(sys.modules.get(module) or __import__(module, fromlist=[name]), name)


@pytest.mark.parametrize(("surface", "id_", "call", "names", "same"), CASES,
                         ids=[f"{s.rsplit('.', 1)[-1]}:{i}" for s, i, *_ in CASES])
def test_every_row_ends_in_a_clear_error_or_the_right_answer(surface, id_, call, names, same):
    check_row(Row(surface, id_, call, names or (), same), id_, timeout=3.0)


@pytest.mark.parametrize("name", ENUMS)
def test_an_exempt_enumeration_is_one(name):
    assert issubclass(_find(name), enum.Enum)


@pytest.mark.parametrize("name", TABLES)
def test_an_exempt_table_is_a_dataclass_of_the_package(name):
    assert dataclasses.is_dataclass(_find(name)) and _find(name).__module__.startswith("ebantenna")


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    return {surface: [row[0] for row in rows] for surface, rows in ROWS.items()}


def contract_exempt() -> dict[str, str]:
    """Enumerations and datasheet tables (read by the inventory test)."""
    return {**{n: "an enumeration of a chip's registers or bits (datasheet constants)"
               for n in ENUMS},
            **{n: "a row of a chip's datasheet table, a constant the package defines"
               for n in TABLES}}
