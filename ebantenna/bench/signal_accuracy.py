"""Accuracy against cost of the signal-processing estimators, measured side by side in one run.

Tables:

1. dominant frequency: plain bin against the interpolating estimators, with windows and zero
   padding, on one-second, 1 kHz noisy damped tones (error in Hz, time per call, time relative to
   the plain bin);
2. time-frequency: spectrogram (STFT) against the Morlet scalogram, error of the ridge frequency
   on a chirp and time per map;
3. decay fit: the three fitting methods, with and without the Table 1 band-pass, error in tau;
   (the adaptive band-pass tracker is timed on the same chirp);
4. contact distance from frequencies: error in cm along the whole probe, one mode against two and
   three, with FEM frequencies of the paper's probe as the calibration and test data.

Run ``python benchmarks/signal_accuracy.py`` (add ``--quick`` for fewer trials).
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from ebantenna.signal import (
    DECAY_METHODS,
    FrequencyTracker,
    apply_filter,
    dominant_frequency,
    fit_decay,
    morlet_scalogram,
    paper_filter,
    spectrogram,
)

FS = 1000.0
T = np.arange(1000) / FS


def _timed(fn, repeat):
    """Best-of-three mean time per call, s, and the last result."""
    best = np.inf
    result = None
    for _ in range(3):
        start = time.perf_counter()
        for _ in range(repeat):
            result = fn()
        best = min(best, (time.perf_counter() - start) / repeat)
    return best, result


def frequency_table(n_trials, rng):
    signals = []
    for _ in range(n_trials):
        f0 = rng.uniform(20.0, 450.0)
        x = np.exp(-T / 0.3) * np.sin(2 * np.pi * f0 * T + rng.uniform(0, 2 * np.pi))
        signals.append((f0, x + 0.02 * rng.standard_normal(T.size)))
    rows = []
    configs = [("bin", "hann", 1), ("bin", "hann", 4), ("bin", "hann", 16),
               ("parabolic", "hann", 1), ("parabolic", "hann", 4), ("parabolic", "blackman", 1),
               ("parabolic", "rectangular", 1), ("jacobsen", "hann", 1),
               ("jacobsen", "rectangular", 1), ("jacobsen", "hann", 4)]
    for method, window, pad in configs:
        errors = np.array([
            dominant_frequency(x, FS, method=method, window=window, zero_pad=pad) - f0
            for f0, x in signals
        ])
        seconds, _ = _timed(lambda m=method, w=window, p=pad: dominant_frequency(
            signals[0][1], FS, method=m, window=w, zero_pad=p), 50)
        rows.append((method, window, pad, np.sqrt(np.mean(errors**2)), np.abs(errors).max(),
                     seconds))
    base = rows[0][5]
    print("\n1. Dominant frequency: 1 s at 1 kHz, damped tone (tau 0.3 s), noise 0.02 "
          f"({n_trials} trials)")
    print(f"{'method':<10} {'window':<12} {'pad':>4} {'rms err Hz':>11} {'max err Hz':>11} "
          f"{'time us':>9} {'time ratio':>11}")
    for method, window, pad, rms, worst, seconds in rows:
        print(f"{method:<10} {window:<12} {pad:>4} {rms:>11.4f} {worst:>11.4f} "
              f"{seconds * 1e6:>9.1f} {seconds / base:>11.2f}")
    return rows


def timefreq_table():
    truth = 80.0 + 60.0 * T  # chirp from 80 Hz to 140 Hz
    x = np.sin(2 * np.pi * (80.0 * T + 30.0 * T**2))
    interior = (T > 0.15) & (T < 0.85)
    rows = []
    for nperseg in (64, 128, 256):
        seconds, tf = _timed(lambda n=nperseg: spectrogram(x, FS, nperseg=n, noverlap=n - 8,
                                                           n_fft=4 * n), 5)
        ridge = tf.ridge()
        keep = (tf.t > 0.15) & (tf.t < 0.85)
        err = ridge[keep] - np.interp(tf.t[keep], T, truth)
        rows.append((f"STFT nperseg={nperseg}", np.sqrt(np.mean(err**2)), seconds))
    freqs = np.arange(60.0, 160.0, 0.5)
    for bandwidth in (1.5, 4.0, 16.0):
        seconds, tf = _timed(lambda b=bandwidth: morlet_scalogram(x, FS, freqs, bandwidth=b), 3)
        err = tf.ridge()[interior] - truth[interior]
        rows.append((f"Morlet B={bandwidth:g} (200 rows)", np.sqrt(np.mean(err**2)), seconds))
    seconds, res = _timed(lambda: FrequencyTracker(FS).track(x), 3)
    err = res.frequency[interior] - truth[interior]
    rows.append(("adaptive tracker", np.sqrt(np.mean(err**2)), seconds))
    base = rows[0][2]
    print("\n2. Time-frequency ridge on a chirp 80 -> 140 Hz (1 s, 1 kHz), 0.15 s < t < 0.85 s")
    print(f"{'view':<28} {'rms ridge err Hz':>17} {'time ms':>9} {'time ratio':>11}")
    for name, rms, seconds in rows:
        print(f"{name:<28} {rms:>17.3f} {seconds * 1e3:>9.2f} {seconds / base:>11.2f}")


def decay_table(n_trials, rng):
    sos = paper_filter("chebyshev")
    stated = paper_filter("chebyshev", "stated")
    rows = []
    for tau in (0.03, 0.1, 0.3):
        signals = [np.exp(-T / tau) * np.sin(2 * np.pi * rng.uniform(80, 140) * T)
                   + 0.01 * rng.standard_normal(T.size) for _ in range(n_trials)]
        for method in DECAY_METHODS:
            for label, pre in (("none", None), ("table 1 (13)", sos), ("stated (2)", stated)):
                def run(x, m=method, p=pre):
                    return fit_decay(x if p is None else apply_filter(p, x), FS, method=m)
                fits = [run(x) for x in signals]
                rel = np.array([f.tau / tau - 1 for f in fits])
                seconds, _ = _timed(lambda r=run, x0=signals[0]: r(x0), 10)
                rows.append((tau, method, label, np.median(rel), np.abs(rel).max(), seconds))
    base = rows[0][5]
    print(f"\n3. Decay fit: 1 s, 1 kHz damped tone (80-140 Hz), noise 0.01 ({n_trials} trials)")
    print(f"{'tau s':>6} {'method':<10} {'band-pass':<13} {'median err':>11} {'max |err|':>10} "
          f"{'time ms':>8} {'time ratio':>11}")
    for tau, method, label, med, worst, seconds in rows:
        print(f"{tau:>6.2f} {method:<10} {label:<13} {med:>+11.2%} {worst:>10.2%} "
              f"{seconds * 1e3:>8.2f} {seconds / base:>11.2f}")


def distance_table(rng):
    from ebantenna.fem import natural_frequencies
    from ebantenna.probe import Probe
    from ebantenna.signal import FrequencyDistanceEstimator, MultiModeDistanceEstimator

    probe = Probe()
    length = probe.length
    noise = 0.002
    cal_d = np.arange(0.01, length - 0.0049, 0.005)
    cal_f = natural_frequencies(probe, cal_d, n_modes=3)
    d = np.repeat(cal_d, 5)
    f = np.repeat(cal_f, 5, axis=0) * (1 + noise * rng.standard_normal((d.size, 3)))
    test_d = rng.uniform(0.0125, length - 0.01, 400)
    test_f = natural_frequencies(probe, test_d, n_modes=3)
    test_f = test_f * (1 + noise * rng.standard_normal(test_f.shape))
    single = FrequencyDistanceEstimator(out_of_range="clip").fit(f[:, 0], d)
    errors = {"f1 only": np.abs(single.predict(test_f[:, 0]) - test_d) * 100}
    times = {"f1 only": _timed(lambda: single.predict(test_f[:, 0]), 5)[0]}
    for k in (2, 3):
        est = MultiModeDistanceEstimator().fit(f[:, :k], d)
        errors[f"{k} modes"] = np.abs(est.predict(test_f[:, :k]) - test_d) * 100
        times[f"{k} modes"] = _timed(lambda e=est, m=k: e.predict(test_f[:, :m]), 3)[0]
    edges = np.array([0.0, 0.25, 0.5, 0.75, single.limit_ / length, 0.9, 1.0])
    print(f"\n4. Contact distance from FEM frequencies with {noise:.1%} scatter; calibration every "
          f"5 mm; 400 random contacts. f1 turns at {single.limit_ * 100:.1f} cm "
          f"({single.limit_ / length:.1%} of L). Max error, cm:")
    bands = list(zip(edges[:-1], edges[1:], strict=True))
    header = " ".join(f"{f'{a:.0%}-{b:.0%}':>9}" for a, b in bands)
    print(f"{'estimator':<10} {header} {'us/contact':>11}")
    for name, err in errors.items():
        cells = []
        for a, b in bands:
            sel = (test_d >= a * length) & (test_d < b * length)
            cells.append(f"{err[sel].max():>9.3f}" if sel.any() else f"{'-':>9}")
        print(f"{name:<10} {' '.join(cells)} {times[name] / test_d.size * 1e6:>11.2f}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer trials")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    rng = np.random.default_rng(args.seed)
    n = 20 if args.quick else 200
    frequency_table(n, rng)
    timefreq_table()
    decay_table(5 if args.quick else 30, rng)
    distance_table(rng)


if __name__ == "__main__":
    main()
