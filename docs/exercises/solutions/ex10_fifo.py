"""Exercise 10: drain the accelerometer's FIFO by hand on the simulated bus, and lose samples."""

import numpy as np

from ebantenna.chips.mpu6050 import (
    ACCEL_SAMPLE_BYTES,
    DATA_DTYPE,
    FIFO_SIZE,
    FifoEnable,
    Interrupt,
    Register,
    UserControl,
)
from ebantenna.device import MPU6050, SimulatedRig

# [data]
rig = SimulatedRig.for_contact(scene="paper", material="steel", ratio=0.5, seed=11)
mpu = MPU6050(rig.bus, clock=rig.clock)
mpu.initialize()  # reset, wake, 1 kHz, +-16 g
address, fs = mpu.config.address, mpu.config.fs
rig.touch()  # the probe rings from now on
bus = rig.bus
# [/data]

# 1. Start the FIFO by hand: reset it (only while disabled), then let accelerometer samples in.
bus.write_byte_data(address, Register.FIFO_EN, 0)
bus.write_byte_data(address, Register.USER_CTRL, UserControl.FIFO_RESET)
# The reset bit clears itself: USER_CTRL reads back 0 whether the reset acted or not. What the
# reset leaves can be read instead: nothing enters the FIFO while it is disabled, so its count
# must be 0 now (the driver checks the same, and resets again when it is not).
high, low = bus.read_i2c_block_data(address, Register.FIFO_COUNTH, 2)
assert (high << 8) | low == 0
bus.read_byte_data(address, Register.INT_STATUS)  # clears a stale overflow flag
bus.write_byte_data(address, Register.FIFO_EN, FifoEnable.ACCEL)
bus.write_byte_data(address, Register.USER_CTRL, UserControl.FIFO_EN)

# 2. Wait 50 ms, then read how many bytes wait: FIFO_COUNTH and FIFO_COUNTL in one burst.
rig.clock.sleep(0.050)
high, low = bus.read_i2c_block_data(address, Register.FIFO_COUNTH, 2)
count = (high << 8) | low
print(f"after 50 ms: {count} bytes = {count / ACCEL_SAMPLE_BYTES:g} samples")
assert count % ACCEL_SAMPLE_BYTES == 0
assert abs(count // ACCEL_SAMPLE_BYTES - 0.050 * fs) <= 1  # one sample per ms, give or take one

# 3. Drain them: FIFO_R_W hands out the next byte at every read; 32 bytes per transfer at most.
raw = []
while len(raw) < count:
    raw += bus.read_i2c_block_data(address, Register.FIFO_R_W, min(32, count - len(raw)))
counts = np.frombuffer(bytes(raw), dtype=DATA_DTYPE).reshape(-1, 3)  # X, Y, Z, high byte first
acceleration = mpu.to_acceleration(counts)  # m/s^2: counts * g / 2048 at +-16 g
print("first samples (m/s^2):\n", acceleration[:3].round(2))
# Reading took time: 300 bytes at 100 kHz (a Raspberry Pi's default bus clock), 9 bits a byte,
# are 27 ms, and the chip kept sampling meanwhile. The FIFO holds those new samples, no more.
high, low = bus.read_i2c_block_data(address, Register.FIFO_COUNTH, 2)
arrived = ((high << 8) | low) // ACCEL_SAMPLE_BYTES
print(f"{arrived} samples arrived while we read")
assert bus.bus_hz == 100e3
assert 300 * 9 / bus.bus_hz * fs <= arrived + 1 and arrived <= 40  # plus addresses, overheads
# gravity: the mean of the samples is about 1 g in magnitude
assert abs(np.linalg.norm(acceleration.mean(axis=0)) / 9.81 - 1) < 0.2

# 4. Lose samples: leave the FIFO undrained longer than it can hold (1024 bytes = 170 samples).
rig.clock.sleep(0.300)
status = bus.read_byte_data(address, Register.INT_STATUS)
high, low = bus.read_i2c_block_data(address, Register.FIFO_COUNTH, 2)
count = (high << 8) | low
print(f"after 300 ms undrained: {count} bytes, overflow flag {bool(status & Interrupt.FIFO_OFLOW)}")
assert status & Interrupt.FIFO_OFLOW and count == FIFO_SIZE
# 1024 is not a whole number of 6-byte samples: the oldest bytes were overwritten one by one, so
# the content no longer starts on a sample. Decoding it anyway mixes the axes of two samples.
assert FIFO_SIZE % ACCEL_SAMPLE_BYTES != 0

# 5. The driver does the same, and counts what was lost instead of decoding garbage: it sees the
# full FIFO, discards it and restarts the FIFO; the next drain says how many samples the gap cost.
mpu.start_fifo()
rig.clock.sleep(0.300)
block = mpu.read_fifo()
assert len(block.index) == 0 and mpu.overflows == 1
rig.clock.sleep(0.020)
# the period the driver counts the gap with: taken before this drain, whose count read again
# after its data becomes the driver's first measurement of the rate
period_us = 1e6 * mpu.stream.estimator.period
block = mpu.read_fifo()
print(f"driver: {block.lost} samples lost, then {len(block.index)} returned")
# the 300 ms undrained, plus the few samples due while the driver read the count and restarted
assert 0.300 * fs <= block.lost <= 0.300 * fs + 5
# How the driver counts them: the time between the two starts of the FIFO over its period. Before
# any count it knows the rate only to within 5 %: the middle of [T / 1.05, T / 0.95], not T.
gap_ms = 1e3 * (mpu.stream.starts[1] - mpu.stream.starts[0])
print(f"{gap_ms:.1f} ms between the starts / {period_us:.2f} us = {1e3 * gap_ms / period_us:.2f}")
assert block.lost == round(1e3 * gap_ms / period_us)
assert abs(period_us - 1e6 / fs * (1 / 1.05 + 1 / 0.95) / 2) < 1e-9

# The expected answers on the exercise page, checked against these values by the test suite.
ANSWERS = {"samples_after_50ms": len(counts), "arrived_while_reading": arrived,
           "overflow_count": count, "lost": block.lost, "gap_ms": gap_ms, "period_us": period_us}
# The tolerance of each answer: how far two correct ways of working may differ, and why.
# Every transfer costs bus time on the virtual clock, so the transfers a student adds move the
# counts: the same drain in transfers of 6 bytes (one sample) lets 45 samples in instead of 31
# (each transfer costs 0.35 ms besides its data), an extra register read (0.44 ms) about half
# a sample. Step 3 fixes the transfers
# (32 bytes); the driver fixes its own in step 5.
TRANSFERS = "an extra register read or two (0.44 ms each) on the virtual clock"
TOLERANCES = {
    "samples_after_50ms": ("abs", 1, (
        "one sample more or less, as the wait starts between two samples"
    )),
    "arrived_while_reading": ("abs", 2, TRANSFERS + " move it by a sample or two"),
    "overflow_count": ("abs", 0, "a count of bytes, which no rounding moves"),
    "lost": ("abs", 1, TRANSFERS + " between the driver's calls move it by one sample"),
    "gap_ms": ("abs", 1, TRANSFERS + " between the driver's calls move it by under 1 ms"),
    "period_us": ("rel", 1e-9, "the middle of the bracket of a 5 % rate tolerance: rounding only"),
}
print("ok: the FIFO drained by hand; an overflow loses every sample since the last read")
