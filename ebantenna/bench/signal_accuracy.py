"""Accuracy against cost of the signal-processing estimators, measured in one run.

Tables:

1. dominant frequency: plain bin against the interpolating estimators, with windows and zero
   padding, on one-second, 1 kHz noisy damped tones (error in Hz, time per call, time relative to
   the plain bin);
2. time-frequency: spectrogram (STFT) against the Morlet scalogram and the adaptive band-pass
   tracker (:class:`~ebantenna.signal.FrequencyTracker`), error of the ridge frequency on a chirp
   and time per map;
3. decay fit: the four fitting methods (:data:`~ebantenna.signal.DECAY_METHODS`) with no
   band-pass, the Table 1 band-pass and the band-pass as stated, error in tau;
4. contact distance from frequencies: error in cm along the whole probe, one mode against two and
   three, with FEM frequencies of the paper's probe as the calibration and test data.

:func:`run` returns the rows of every table; :func:`to_text` and :func:`plot` draw the tables and
the figure from those same rows. Run ``python benchmarks/signal_accuracy.py`` (add ``--quick`` for
fewer trials).

The timed cases of each table alternate round by round (three rounds: the first case, the
second, ..., then again), each a batch of calls, and each keeps its smallest round, so that a
load that comes and goes on a shared machine reaches all of them alike and the time ratios
compare; BLAS is held to one thread while they run.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from ebantenna._threads import limited_threads
from ebantenna._validate import check_bool, check_int
from ebantenna.bench._arguments import check_argv, check_count, check_generator, check_tables
from ebantenna.bench._timing import timed_rounds
from ebantenna.report import text_table
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

__all__ = ["frequency_rows", "timefreq_rows", "decay_rows", "distance_rows", "run", "to_text",
           "plot", "main"]

FS = 1000.0
T = np.arange(1000) / FS


#: Rounds in which the timed cases of a table alternate; each keeps its smallest.
_ROUNDS = 3


def _batch(fn, count: int):
    """A call of ``fn`` ``count`` times in a row, returning the last result."""

    def batch():
        for _ in range(count):
            result = fn()
        return result

    return batch


def _alternated(cases) -> list[tuple[float, object]]:
    """Time ``cases``, ``(fn, count)`` pairs, alternating over :data:`_ROUNDS` rounds (one batch
    of ``count`` calls of each case per round) with BLAS on one thread: for each, the smallest
    round's time per call (s) and the last result."""
    with limited_threads(1):
        timed = timed_rounds([_batch(fn, count) for fn, count in cases], _ROUNDS,
                             clock=time.perf_counter)
    return [(r["min"] / count, r["result"]) for r, (_, count) in zip(timed, cases, strict=True)]


def frequency_rows(n_trials, rng) -> list[dict]:
    """Dominant-frequency estimators on ``n_trials`` noisy damped tones.

    Returns
    -------
    list of dict
        ``method``, ``window``, ``pad`` (zero-padding factor), ``rms_hz`` and ``max_hz`` (error,
        Hz), ``seconds`` (per call, s) and ``ratio`` (time relative to the first row).
    """
    n_trials = check_count("n_trials", n_trials)
    check_generator("rng", rng)
    signals = []
    for _ in range(n_trials):
        f0 = rng.uniform(20.0, 450.0)
        x = np.exp(-T / 0.3) * np.sin(2 * np.pi * f0 * T + rng.uniform(0, 2 * np.pi))
        signals.append((f0, x + 0.02 * rng.standard_normal(T.size)))
    configs = [("bin", "hann", 1), ("bin", "hann", 4), ("bin", "hann", 16),
               ("parabolic", "hann", 1), ("parabolic", "hann", 4), ("parabolic", "blackman", 1),
               ("parabolic", "rectangular", 1), ("jacobsen", "hann", 1),
               ("jacobsen", "rectangular", 1), ("jacobsen", "hann", 4)]
    rows = []
    for method, window, pad in configs:
        errors = np.array([
            dominant_frequency(x, FS, method=method, window=window, zero_pad=pad) - f0
            for f0, x in signals
        ])
        rows.append({"method": method, "window": window, "pad": pad,
                     "rms_hz": float(np.sqrt(np.mean(errors**2))),
                     "max_hz": float(np.abs(errors).max())})
    timed = _alternated([(lambda m=method, w=window, p=pad: dominant_frequency(
        signals[0][1], FS, method=m, window=w, zero_pad=p), 50)
        for method, window, pad in configs])
    for row, (seconds, _) in zip(rows, timed, strict=True):
        row["seconds"] = seconds
    for row in rows:
        row["ratio"] = row["seconds"] / rows[0]["seconds"]
    return rows


def timefreq_rows() -> list[dict]:
    """Ridge error of STFT, Morlet scalogram and the adaptive tracker on a chirp.

    Returns
    -------
    list of dict
        ``view``, ``rms_hz`` (ridge error, Hz), ``seconds`` (per map, s) and ``ratio``.
    """
    truth = 80.0 + 60.0 * T  # chirp from 80 Hz to 140 Hz
    x = np.sin(2 * np.pi * (80.0 * T + 30.0 * T**2))
    interior = (T > 0.15) & (T < 0.85)
    freqs = np.arange(60.0, 160.0, 0.5)
    timed = _alternated(
        [(lambda n=n: spectrogram(x, FS, nperseg=n, noverlap=n - 8, n_fft=4 * n), 5)
         for n in (64, 128, 256)]
        + [(lambda b=b: morlet_scalogram(x, FS, freqs, bandwidth=b), 3) for b in (1.5, 4.0, 16.0)]
        + [(lambda: FrequencyTracker(FS).track(x), 3)]
    )
    rows = []
    for nperseg, (seconds, tf) in zip((64, 128, 256), timed[:3], strict=True):
        keep = (tf.t > 0.15) & (tf.t < 0.85)
        err = tf.ridge()[keep] - np.interp(tf.t[keep], T, truth)
        rows.append({"view": f"STFT nperseg={nperseg}",
                     "rms_hz": float(np.sqrt(np.mean(err**2))), "seconds": seconds})
    for bandwidth, (seconds, tf) in zip((1.5, 4.0, 16.0), timed[3:6], strict=True):
        err = tf.ridge()[interior] - truth[interior]
        rows.append({"view": f"Morlet B={bandwidth:g} (200 rows)",
                     "rms_hz": float(np.sqrt(np.mean(err**2))), "seconds": seconds})
    seconds, res = timed[6]
    err = res.frequency[interior] - truth[interior]
    rows.append({"view": "adaptive tracker", "rms_hz": float(np.sqrt(np.mean(err**2))),
                 "seconds": seconds})
    for row in rows:
        row["ratio"] = row["seconds"] / rows[0]["seconds"]
    return rows


def decay_rows(n_trials, rng) -> list[dict]:
    """The decay-fit methods, with and without the Table 1 band-pass, on damped tones.

    Returns
    -------
    list of dict
        ``tau`` (true time constant, s), ``method``, ``band_pass``, ``median_error`` and
        ``max_error`` (relative error of tau), ``seconds`` (per fit, s) and ``ratio``.
    """
    n_trials = check_count("n_trials", n_trials)
    check_generator("rng", rng)
    sos = paper_filter("chebyshev")
    stated = paper_filter("chebyshev", "stated")
    rows, cases = [], []
    for tau in (0.03, 0.1, 0.3):
        signals = [np.exp(-T / tau) * np.sin(2 * np.pi * rng.uniform(80, 140) * T)
                   + 0.01 * rng.standard_normal(T.size) for _ in range(n_trials)]
        for method in DECAY_METHODS:
            for label, pre in (("none", None), ("table 1 (13)", sos), ("stated (2)", stated)):
                def fit(x, m=method, p=pre):
                    return fit_decay(x if p is None else apply_filter(p, x), FS, method=m)
                rel = np.array([fit(x).tau / tau - 1 for x in signals])
                cases.append((lambda r=fit, x0=signals[0]: r(x0), 10))
                rows.append({"tau": tau, "method": method, "band_pass": label,
                             "median_error": float(np.median(rel)),
                             "max_error": float(np.abs(rel).max())})
    for row, (seconds, _) in zip(rows, _alternated(cases), strict=True):
        row["seconds"] = seconds
    for row in rows:
        row["ratio"] = row["seconds"] / rows[0]["seconds"]
    return rows


def distance_rows(rng) -> dict:
    """Contact distance from noisy FEM frequencies: one mode against two and three.

    Returns
    -------
    dict
        ``noise`` (relative frequency scatter), ``turning_point_m`` (where f1 turns, m),
        ``length_m`` (probe length, m), ``bands`` (list of (low, high) fractions of the length)
        and ``rows``: per estimator ``estimator``, ``max_error_cm`` (one value per band, NaN
        where no test contact falls in it) and ``us_per_contact``.
    """
    check_generator("rng", rng)
    from ebantenna.fem import natural_frequencies
    from ebantenna.paper.estimators import FrequencyDistanceEstimator, MultiModeDistanceEstimator
    from ebantenna.probe import Probe

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
    cases = [(lambda: single.predict(test_f[:, 0]), 5)]
    for k in (2, 3):
        est = MultiModeDistanceEstimator().fit(f[:, :k], d)
        errors[f"{k} modes"] = np.abs(est.predict(test_f[:, :k]) - test_d) * 100
        cases.append((lambda e=est, m=k: e.predict(test_f[:, :m]), 3))
    times = {name: seconds for name, (seconds, _) in zip(errors, _alternated(cases), strict=True)}
    edges = np.array([0.0, 0.25, 0.5, 0.75, single.limit_ / length, 0.9, 1.0])
    bands = [(float(a), float(b)) for a, b in zip(edges[:-1], edges[1:], strict=True)]
    rows = []
    for name, err in errors.items():
        worst = []
        for a, b in bands:
            sel = (test_d >= a * length) & (test_d < b * length)
            worst.append(float(err[sel].max()) if sel.any() else float("nan"))
        rows.append({"estimator": name, "max_error_cm": worst,
                     "us_per_contact": times[name] / test_d.size * 1e6})
    return {"noise": noise, "turning_point_m": float(single.limit_), "length_m": length,
            "bands": bands, "rows": rows}


def run(quick: bool = False, seed: int = 0) -> dict:
    """Every table of this sweep, as rows.

    Parameters
    ----------
    quick : bool
        Fewer trials.
    seed : int
        Seed of the noise and of the test contacts.

    Returns
    -------
    dict
        ``n_trials`` and the rows of ``frequency``, ``timefreq``, ``decay`` (with
        ``decay_trials``) and ``distance``.
    """
    quick = check_bool("quick", quick)
    rng = np.random.default_rng(check_int("seed", seed, minimum=0))
    n = 20 if quick else 200
    n_decay = 5 if quick else 30
    return {
        "n_trials": n,
        "frequency": frequency_rows(n, rng),
        "timefreq": timefreq_rows(),
        "decay_trials": n_decay,
        "decay": decay_rows(n_decay, rng),
        "distance": distance_rows(rng),
    }


def to_text(tables: dict) -> str:
    """The tables of :func:`run` as text."""
    check_tables(tables, "run", n_trials=int, frequency=list, timefreq=list, decay_trials=int,
                 decay=list, distance=dict)
    frequency = text_table(
        [("method", "method", "<10"), ("window", "window", "<12"), ("pad", "pad", "4d"),
         ("rms_hz", "rms err Hz", "11.4f"), ("max_hz", "max err Hz", "11.4f"),
         ("us", "time us", "9.1f"), ("ratio", "time ratio", "11.2f")],
        [{**r, "us": r["seconds"] * 1e6} for r in tables["frequency"]],
    )
    timefreq = text_table(
        [("view", "view", "<28"), ("rms_hz", "rms ridge err Hz", "17.3f"),
         ("ms", "time ms", "9.2f"), ("ratio", "time ratio", "11.2f")],
        [{**r, "ms": r["seconds"] * 1e3} for r in tables["timefreq"]],
    )
    decay = text_table(
        [("tau", "tau s", "6.2f"), ("method", "method", "<10"), ("band_pass", "band-pass", "<13"),
         ("median_error", "median err", "+11.2%"), ("max_error", "max |err|", "10.2%"),
         ("ms", "time ms", "8.2f"), ("ratio", "time ratio", "11.2f")],
        [{**r, "ms": r["seconds"] * 1e3} for r in tables["decay"]],
    )
    dist = tables["distance"]
    band_names = [f"{a:.0%}-{b:.0%}" for a, b in dist["bands"]]
    distance_columns = [("estimator", "estimator", "<10")]
    distance_columns += [(name, name, "9.3f") for name in band_names]
    distance_columns.append(("us_per_contact", "us/contact", "11.2f"))
    distance = text_table(
        distance_columns,
        [{**r, **dict(zip(band_names, r["max_error_cm"], strict=True))} for r in dist["rows"]],
    )
    turn = dist["turning_point_m"]
    return "\n".join([
        f"Times per call: the best of {_ROUNDS} rounds in which the cases of a table alternate, "
        "BLAS on one thread; time ratio: against the table's first row",
        "",
        "1. Dominant frequency: 1 s at 1 kHz, damped tone (tau 0.3 s), noise 0.02 "
        f"({tables['n_trials']} trials)",
        frequency,
        "",
        "2. Time-frequency ridge on a chirp 80 -> 140 Hz (1 s, 1 kHz), 0.15 s < t < 0.85 s",
        timefreq,
        "",
        f"3. Decay fit: 1 s, 1 kHz damped tone (80-140 Hz), noise 0.01 "
        f"({tables['decay_trials']} trials)",
        decay,
        "",
        f"4. Contact distance from FEM frequencies with {dist['noise']:.1%} scatter; calibration "
        f"every 5 mm; 400 random contacts. f1 turns at {turn * 100:.1f} cm "
        f"({turn / dist['length_m']:.1%} of L). Max error, cm:",
        distance,
    ])


def plot(tables: dict):
    """Error against time of the dominant-frequency estimators, from the rows of :func:`run`.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    check_tables(tables, "run", frequency=list)
    fig = Figure(figsize=(7, 4.2))
    ax = fig.subplots()
    for r in tables["frequency"]:
        us = r["seconds"] * 1e6
        ax.loglog(us, r["rms_hz"], "o")
        ax.annotate(f"{r['method']}/{r['window']}/x{r['pad']}", (us, r["rms_hz"]), fontsize=7,
                    xytext=(3, 3), textcoords="offset points")
    ax.set_xlabel("time per estimate (us)")
    ax.set_ylabel("RMS frequency error (Hz)")
    ax.set_title("Dominant frequency: accuracy against time")
    return fig


def main(argv=None):
    """Command-line entry: print the tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer trials")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(check_argv(argv))
    print(to_text(run(args.quick, args.seed)))


if __name__ == "__main__":
    main()
