"""The ground truth a simulated rig knows of a recording's samples, found by their values, for the
tests of the driver and of the pages that state its numbers."""

import numpy as np


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
