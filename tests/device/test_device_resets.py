"""Self-clearing reset bits are confirmed by what the reset leaves, not by reading the bit back.

``USER_CTRL.FIFO_RESET`` and ``PWR_MGMT_1.DEVICE_RESET`` clear themselves once the reset is done
(RM 106 and 107): they read back 0 whether or not the reset acted. ``Faults(reset_lost=...)``
makes a reset not act (the write lands without its reset bit); each case is judged against the
simulated chip's ground truth: what the FIFO held before the reset is never kept as a sample, and
the lost reset is said and counted."""

from __future__ import annotations

import logging

import numpy as np
import pytest
from rig_truth import in_wrong_slot, ringing_rig

from ebantenna.chips.mpu6050 import Register
from ebantenna.device import MPU6050
from ebantenna.device.fifo import FIFO_RESET_ATTEMPTS
from ebantenna.device.i2c import SettingError
from ebantenna.device.simulated import Faults
from ebantenna.device.watchdog import StreamStalledError

ASKED = 500
#: Virtual time from which the resets are lost: after the first stream's start (the rig is set up
#: and its stream started by about 0.14 s), before the second's.
LOST_AT = 0.3


def _one_sample_left(faults, bus_hz=400e3):
    """A rig whose chip's FIFO holds one sample of a stream that was stopped right after a drain
    that left one sample behind (at 400 kHz a drain of about 20 samples takes 2 to 3 ms and
    often leaves one; at 100 kHz it always leaves several)."""
    rig, mpu = ringing_rig(faults, bus_hz)
    mpu.start_fifo()
    rig.clock.sleep(0.02)
    for _ in range(20):
        mpu.read_fifo()
        high, low = rig.mpu.read(Register.FIFO_COUNTH, 2)  # the chip's own count: no bus
        if (high << 8) | low == 6:
            break
    mpu.stop_fifo()
    assert len(rig.mpu.fifo) == 6  # the case: one whole sample left from the stream before
    rig.clock.sleep(max(LOST_AT - rig.clock.monotonic(), 0.0) + 0.01)
    return rig, mpu


def _record(rig, mpu, asked=ASKED):
    try:
        return mpu.record(asked / 1000.0)
    except StreamStalledError as exc:
        return exc.recording


def _causes(rec) -> str:
    return " | ".join(f["cause"] for f in rec.metadata["faults"])


def test_a_lost_fifo_reset_is_seen_in_the_count_and_made_again():
    """The next stream's ``FIFO_RESET`` is lost with one sample of the stream before in the
    FIFO. Before, the count checks could not see it (one sample more is within the clock's
    tolerance): that stale sample became the new segment's first, and every one of the 500
    kept samples sat one slot late, unflagged, with no fault said. Now the count read before
    the FIFO is enabled again shows the 6 bytes; the reset is made again and nothing is lost."""
    rig, mpu = _one_sample_left(Faults(reset_lost=((LOST_AT, "fifo"),)))
    rec = _record(rig, mpu)
    assert [kind for _, kind in rig.bus.injector.log] == ["reset lost"]
    assert not np.any(in_wrong_slot(rig, mpu, rec))
    assert rec.n_samples == ASKED and rec.metadata["samples_lost"] == 0
    assert rec.metadata["fifo_resets_unconfirmed"] == 1
    assert "FIFO_COUNT reads 6 bytes after USER_CTRL.FIFO_RESET" in _causes(rec)
    assert rec.metadata["faults"][0]["action"] == "reset again"


def test_the_same_stream_without_the_fault_keeps_every_sample_in_its_slot():
    """The control: the reset acts, the stale sample goes with it, nothing is said."""
    rig, mpu = _one_sample_left(None)
    rec = _record(rig, mpu)
    assert not np.any(in_wrong_slot(rig, mpu, rec)) and rec.metadata["samples_lost"] == 0
    assert rec.metadata["fifo_resets_unconfirmed"] == 0 and not rec.metadata["faults"]


def test_resets_lost_at_every_attempt_fail_the_restart_which_is_made_again_later():
    """:data:`FIFO_RESET_ATTEMPTS` resets lost in a row: the restart fails (no segment starts
    on a FIFO that is not empty) and is tried again at the next drain, whose reset acts."""
    lost = tuple((LOST_AT, "fifo") for _ in range(FIFO_RESET_ATTEMPTS))
    rig, mpu = _one_sample_left(Faults(reset_lost=lost))
    rec = _record(rig, mpu)
    assert [kind for _, kind in rig.bus.injector.log] == ["reset lost"] * FIFO_RESET_ATTEMPTS
    assert rec.metadata["fifo_resets_unconfirmed"] == FIFO_RESET_ATTEMPTS
    assert "restart failed (the FIFO still holds 6 bytes after USER_CTRL.FIFO_RESET" in (
        _causes(rec))
    assert not np.any(in_wrong_slot(rig, mpu, rec))
    assert rec.n_samples + rec.metadata["samples_lost"] == ASKED
    assert rec.metadata["samples_lost"] <= 30  # one poll's worth: the first restart was late


def test_a_chip_that_never_resets_its_fifo_ends_the_stream_with_the_reason():
    """Every reset lost: no segment ever starts, so no stale byte is read as a sample; the
    watchdog ends the stream, naming why."""
    lost = tuple((LOST_AT, "fifo") for _ in range(200))
    rig, mpu = _one_sample_left(Faults(reset_lost=lost))
    with pytest.raises(StreamStalledError, match="does not reset its FIFO") as caught:
        mpu.record(ASKED / 1000.0)
    assert caught.value.recording is None
    assert mpu.stream.samples_read == 0 and mpu.stream.resets_unconfirmed >= FIFO_RESET_ATTEMPTS


def test_a_lost_device_reset_is_seen_in_the_settings_it_leaves_and_made_again(caplog):
    """A second run initialises a chip the first one set up, and its ``DEVICE_RESET`` is lost.
    Before, nothing was said, and a register the driver never writes kept what another program
    had set (``INT_PIN_CFG.INT_RD_CLEAR``, which makes every read clear ``INT_STATUS``): the
    settings the reset must have cleared read as the first run left them, so it is made
    again, and the chip starts from its reset values. The first run's reset is lost too, on a
    chip just powered on: its settings read their reset values whether or not the reset acted,
    and nothing can be said (the device guide's "What the driver cannot detect")."""
    faults = Faults(reset_lost=((0.0, "device"), (LOST_AT, "device")),
                    register_lost=((0.2, Register.INT_PIN_CFG, 0x10),))
    with caplog.at_level(logging.WARNING, logger="ebantenna.device.mpu6050"):
        rig, first = ringing_rig(faults)
        assert [kind for _, kind in rig.bus.injector.log] == ["reset lost"]
        assert "did not act" not in caplog.text  # the fresh chip's lost reset: unseen
        first.record(0.05)
        rig.clock.sleep(max(LOST_AT - rig.clock.monotonic(), 0.0) + 0.01)
        MPU6050(rig.bus, clock=rig.clock).initialize()
    assert [kind for _, kind in rig.bus.injector.log] == [
        "reset lost", "register lost", "reset lost"]
    assert rig.mpu.regs[Register.INT_PIN_CFG] == 0
    assert caplog.text.count("did not act") == 1
    assert "INT_ENABLE (0x38) reads 0x10 after PWR_MGMT_1.DEVICE_RESET: the reset did not act; " \
           "resetting again" in caplog.text


def test_a_device_reset_lost_every_time_is_refused_by_name():
    faults = Faults(reset_lost=((LOST_AT, "device"), (LOST_AT, "device")))
    rig, first = ringing_rig(faults)
    first.record(0.05)
    rig.clock.sleep(max(LOST_AT - rig.clock.monotonic(), 0.0) + 0.01)
    with pytest.raises(SettingError, match=r"does not reset: SMPLRT_DIV \(0x19\) reads 0x07"):
        MPU6050(rig.bus, clock=rig.clock).initialize()


@pytest.mark.parametrize("bad, error, words", [
    (((0.1, "gyro"),), ValueError, "reset_lost which"),
    (((-0.1, "fifo"),), ValueError, "reset_lost time"),
    (((0.1,),), TypeError, "reset_lost must be a tuple"),
    ("fifo", TypeError, "reset_lost must be a tuple"),
])
def test_reset_lost_settings_are_checked(bad, error, words):
    with pytest.raises(error, match=words):
        Faults(reset_lost=bad)
