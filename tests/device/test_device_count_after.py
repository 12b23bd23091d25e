"""The count read after a drain confirms the drain or the drain is dropped: a count that cannot
be judged (one above the FIFO's size, a full FIFO) confirms nothing. Each case arranges the
fault at one moment of the transfers, by wrapping the simulated bus's read (the simulator's
own fault schedule has no hook at "the count after the data"), and is judged against the
simulated chip's ground truth; each has its control, the same run with the count after the
data left as the chip gives it."""

from __future__ import annotations

import numpy as np
import pytest
from rig_truth import in_wrong_slot, ringing_rig

from ebantenna.chips.mpu6050 import Register
from ebantenna.device.simulated import Faults
from ebantenna.device.watchdog import StreamStalledError

ASKED = 1000
ADDRESS = 0x68


def _rig(faults=None, seed=0):
    return ringing_rig(faults, 100e3, seed)


def _record(rig, mpu):
    try:
        return mpu.record(ASKED / 1000.0)
    except StreamStalledError as exc:
        return exc.recording


def _wrong_unflagged(rig, mpu, rec) -> int:
    kept = mpu.stream.kept(0, ASKED)
    assert rec.n_samples + rec.metadata["samples_lost"] == ASKED
    return int(np.sum(in_wrong_slot(rig, mpu, rec) & ~kept["suspect"]))


def _causes(rec) -> str:
    return " | ".join(f["cause"] for f in rec.metadata["faults"])


@pytest.mark.parametrize("second_stall", [0.0, 0.25])
def test_an_overflow_hidden_from_int_status_is_not_kept_when_the_count_after_reads_full(
        second_stall):
    """A host stall of 0.25 s between a drain's count and its data overflows the FIFO (its head
    moves by bytes that are not whole samples); another program reads ``INT_STATUS`` first (an
    ``i2cget`` of 0x3A), so the flag is gone. The count after the data catches the shift when
    it is not whole samples (no second stall: the control); after a second stall it reads a
    full FIFO, whole samples or not, and the drain is dropped all the same."""
    rig, mpu = _rig()
    chip, read = rig.mpu, rig.bus._read
    phase = {"n": 0, "after": None}

    def stalling_read(address, register, length, nbytes):
        if address == ADDRESS and register == Register.FIFO_R_W and phase["n"] == 0 \
                and rig.clock.monotonic() > 0.5:
            rig.clock.advance(0.25)  # between the drain's count and its data: an overflow
            phase["n"] = 1
        elif address == ADDRESS and register == Register.INT_ENABLE and phase["n"] == 1:
            chip.read(Register.INT_STATUS, 1)  # another program clears the overflow flag
            phase["n"] = 2
        elif address == ADDRESS and register == Register.FIFO_COUNTH and phase["n"] == 2:
            rig.clock.advance(second_stall)  # before the count after the data
            phase["n"] = 3
            data = read(address, register, length, nbytes)
            phase["after"] = (data[0] << 8) | data[1]
            return data
        return read(address, register, length, nbytes)

    rig.bus._read = stalling_read
    rec = _record(rig, mpu)
    assert phase["n"] == 3
    assert chip.overflowed_bytes % 6  # the overflow shifted the FIFO's head
    if second_stall:
        assert phase["after"] == 1024  # the case: full, which says nothing of the drain
        assert "the FIFO is full after the drain (1024 bytes)" in _causes(rec)
    assert rec.metadata["samples_discarded"] > 0
    assert _wrong_unflagged(rig, mpu, rec) == 0


@pytest.mark.parametrize("corrupted", [False, True])
def test_part_of_a_sample_taken_is_caught_even_when_the_count_after_reads_too_high(corrupted):
    """Another program takes 2 bytes between a drain's count and its data
    (``Faults(drain_reads=...)``): the count after the data is then not whole samples (the
    control). Read corrupted high, past the FIFO's 1024 bytes, it cannot be judged: the drain
    is dropped and the count counted as rejected, never kept on its word."""
    rig, mpu = _rig(Faults(drain_reads=((0.5, 2),)))
    read = rig.bus._read
    state = {"armed": False, "done": False}

    def reading(address, register, length, nbytes):
        data = read(address, register, length, nbytes)
        if register == Register.FIFO_R_W and rig.bus.injector._drain_done and not state["armed"]:
            state["armed"] = True  # the bytes were taken before this data read
        elif register == Register.FIFO_COUNTH and state["armed"] and not state["done"]:
            state["done"] = True  # the count after the data
            if corrupted:
                count = min(((data[0] << 8) | data[1]) + 6 * 171, 0xFFFF)
                data = [count >> 8, count & 0xFF]
        return data

    rig.bus._read = reading
    rec = _record(rig, mpu)
    assert state["done"]
    if corrupted:
        assert "exceeds the FIFO's 1024 bytes" in _causes(rec)
        assert rec.metadata["fifo_counts_rejected"] >= 1
    else:
        assert "is not a whole number of samples" in _causes(rec)
    assert rec.metadata["samples_discarded"] > 0
    assert _wrong_unflagged(rig, mpu, rec) == 0


@pytest.mark.parametrize("seed", range(6))
def test_int_rd_clear_set_behind_the_driver_keeps_no_wrong_sample(seed):
    """``INT_PIN_CFG``'s ``INT_RD_CLEAR`` (RM 55), set behind the driver's back
    (``register_lost``; the driver neither writes nor reads that register back), makes every
    read clear ``INT_STATUS``: the driver's own FIFO reads wipe the overflow flag before it reads
    it. With a slow host that overflows the FIFO, the counts still catch every shift (before
    the count after a full FIFO was taken on its word, seed 5 kept 2 shifted samples)."""
    faults = Faults(slow_host=(0.01, 0.3), register_lost=((0.01, Register.INT_PIN_CFG, 0x10),))
    rig, mpu = _rig(faults, seed)
    rec = _record(rig, mpu)
    assert rig.mpu.regs[Register.INT_PIN_CFG] & 0x10
    assert _wrong_unflagged(rig, mpu, rec) == 0

