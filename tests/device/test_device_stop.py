"""Stopping the FIFO is a setting like any other: both enables are read back.

A write of ``FIFO_EN = 0`` that lands with the accelerometer's bit still set (``Faults``'s
``flip_write``, switched on after the stream started, so that only the stop's writes are hit)
leaves the chip filling its FIFO behind a recording said to be over. Each case is judged against
the simulated chip's own registers."""

from __future__ import annotations

import dataclasses

import pytest
from rig_truth import ringing_rig

from ebantenna.chips.mpu6050 import FifoEnable, Register, UserControl
from ebantenna.device.i2c import SettingError
from ebantenna.device.simulated import Faults


def _streaming_then_flipped(register: int, mask: int, n: int):
    """A rig streaming at 100 kHz whose next ``n`` writes of ``register`` arrive with ``mask``
    XOR-ed in."""
    rig, mpu = ringing_rig(Faults())
    mpu.start_fifo()
    rig.clock.sleep(0.02)
    mpu.read_fifo()
    faults = dataclasses.replace(rig.bus.faults, flip_write=((register, mask, n),))
    rig.bus.faults = rig.bus.injector.faults = faults  # the bus and its injector read the same
    return rig, mpu


@pytest.mark.parametrize(("register", "mask"), [(Register.FIFO_EN, int(FifoEnable.ACCEL)),
                                                (Register.USER_CTRL, int(UserControl.FIFO_EN))])
def test_a_stop_that_lands_wrong_once_is_written_again(register, mask):
    rig, mpu = _streaming_then_flipped(register, mask, 1)
    mpu.stop_fifo()
    assert [kind for _, kind in rig.bus.injector.log] == ["write bit flip"]
    # the chip's own registers (no bus): both enables off, so the FIFO fills no more
    assert rig.mpu.read(Register.FIFO_EN, 1) == [0]
    assert rig.mpu.read(Register.USER_CTRL, 1)[0] & int(UserControl.FIFO_EN) == 0
    before = len(rig.mpu.fifo)
    rig.clock.sleep(0.05)  # 50 samples' time at 1 kHz
    assert len(rig.mpu.fifo) == before


def test_a_stop_that_lands_wrong_twice_is_an_error_naming_the_register():
    rig, mpu = _streaming_then_flipped(Register.FIFO_EN, int(FifoEnable.ACCEL), 2)
    with pytest.raises(SettingError, match=r"FIFO_EN \(0x23\).* reads back 0x08 after 0x00"):
        mpu.stop_fifo()
