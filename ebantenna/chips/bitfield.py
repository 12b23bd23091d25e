"""A bit field: a group of adjacent bits inside one 8-bit register."""

from __future__ import annotations

from dataclasses import dataclass

from .._validate import check_int

__all__ = ["BitField"]


@dataclass(frozen=True)
class BitField:
    """Bits ``shift + width - 1`` down to ``shift`` of the register at ``register``.

    Datasheets write such a field as ``NAME[msb:lsb]``; here ``shift = lsb`` and
    ``width = msb - lsb + 1``.

    Parameters
    ----------
    register : int
        Address of the register that holds the field, 0-255.
    shift : int
        Position of the field's lowest bit, 0-7.
    width : int
        Number of bits, 1-8; the field must fit inside the byte.

    Examples
    --------
    >>> from ebantenna.chips.bitfield import BitField
    >>> afs_sel = BitField(register=0x1C, shift=3, width=2)  # MPU-6050 ACCEL_CONFIG[4:3]
    >>> afs_sel.mask, afs_sel.get(0x18), afs_sel.put(1, 0x07)
    (24, 3, 15)
    """

    register: int
    shift: int
    width: int

    def __post_init__(self):
        check_int("register", self.register, minimum=0, maximum=255)
        check_int("shift", self.shift, minimum=0, maximum=7)
        check_int("width", self.width, minimum=1, maximum=8 - self.shift)

    @property
    def mask(self) -> int:
        """The field's bits set, all others clear."""
        return ((1 << self.width) - 1) << self.shift

    @property
    def maximum(self) -> int:
        """Largest value the field can hold."""
        return (1 << self.width) - 1

    def get(self, register_value: int) -> int:
        """The field's value inside the byte ``register_value``."""
        register_value = check_int("register_value", register_value, minimum=0, maximum=0xFF)
        return (register_value & self.mask) >> self.shift

    def put(self, value: int, register_value: int = 0) -> int:
        """``register_value`` with the field replaced by ``value``; the other bits are kept.

        Raises
        ------
        ValueError
            When ``value`` does not fit in the field.
        """
        value = check_int("value", value, minimum=0, maximum=self.maximum)
        register_value = check_int("register_value", register_value, minimum=0, maximum=0xFF)
        return (register_value & ~self.mask & 0xFF) | (value << self.shift)
