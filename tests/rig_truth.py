"""The ground truth a simulated rig knows of a recording's samples, found by their values, for the
tests of the driver and of the pages that state its numbers."""

import numpy as np

from ebantenna.device import MPU6050, SimulatedRig
from ebantenna.device.watchdog import StreamStalledError


def ringing(seed=0):
    """The X and Z the rig's chip samples: a 37 Hz ring decaying over 0.4 s, noisy on X (every
    sample its own value, so that a kept sample is found in the chip's truth by its counts)."""
    t = np.arange(3000) / 1000.0
    rng = np.random.default_rng(seed)
    ring = 30.0 * np.exp(-t / 0.4) * np.sin(2 * np.pi * 37.0 * t)
    return ring + rng.normal(0, 0.5, t.size), 0.5 * ring


def ringing_rig(faults, bus_hz=100e3, seed=0):
    """``(rig, mpu)``: a simulated rig whose chip samples :func:`ringing`, on a bus at
    ``bus_hz`` with ``faults``, its driver initialised and the probe touching."""
    ax, az = ringing(seed)
    rig = SimulatedRig.from_arrays(ax, az, fs=1000.0, obstacle=None, faults=faults, seed=seed)
    rig.bus.bus_hz = bus_hz
    mpu = MPU6050(rig.bus, clock=rig.clock)
    mpu.initialize()
    rig.touch()
    return rig, mpu


def record_ringing(faults, bus_hz=100e3, seed=0, asked=1000):
    """``(rig, mpu, rec)``: ``asked`` samples at 1 kHz of :func:`ringing` through the simulated
    bus at ``bus_hz`` with ``faults`` (what a stalled stream kept, if it stalls)."""
    rig, mpu = ringing_rig(faults, bus_hz, seed)
    try:
        rec = mpu.record(asked / 1000.0)
    except StreamStalledError as exc:
        rec = exc.recording
    return rig, mpu, rec


def in_wrong_slot(rig, mpu, rec) -> np.ndarray:
    """Per kept sample: not what the chip put at its place (the ground truth; a sample taken
    before it and not seen shifts it)."""
    raw = rec.metadata["raw"]
    epochs = {round(start, 12): k for k, (start, _) in enumerate(rig.mpu.epochs)}
    truths = {}  # each epoch's samples joined once (a join per sample made a long run quadratic)
    out = []
    for seg, pos, counts in zip(raw["segment"], raw["position"], raw["counts_xyz"],
                                strict=True):
        k = epochs.get(round(mpu.stream.starts[seg], 12))
        if k is not None and k not in truths:
            truths[k] = rig.mpu.truth(k)
        truth = None if k is None else truths[k]
        out.append(truth is None or not (pos < len(truth) and list(truth[pos]) == counts))
    return np.asarray(out, bool)


def true_times_of_values(rig, mpu, rec) -> np.ndarray:
    """The true time (s, from the stream's first segment start) of the chip's sample that each
    kept sample *is*, found by its counts near its position (a sample taken by another reader
    shifts the later ones of its segment); NaN where none matches (a wrong value)."""
    raw = rec.metadata["raw"]
    starts = mpu.stream.starts
    epochs = {round(start, 12): k for k, (start, _) in enumerate(rig.mpu.epochs)}
    period = 1.0 / rig.mpu.true_rate()
    out = np.full(len(raw["segment"]), np.nan)
    for i, (seg, pos, counts) in enumerate(zip(raw["segment"], raw["position"],
                                               raw["counts_xyz"], strict=True)):
        k = epochs.get(round(starts[seg], 12))
        if k is None:
            continue
        truth = rig.mpu.truth(k)
        low = max(pos - 2, 0)
        hits = low + np.flatnonzero(np.all(truth[low:pos + 64] == counts, axis=1))
        if hits.size:
            place = hits[np.argmin(np.abs(hits - pos))]
            out[i] = rig.mpu.first_sample[k] + place * period - starts[0]
    return out
