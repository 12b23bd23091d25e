"""The main job: the whole study, the paper beside its reproduction, and one step beyond it.

:func:`reproduce` runs, in order,

1. the modal analysis of the probe: the dominant mode's zones along the probe and its mode shapes
   (Figs. 16 and 17), the paper's two-element model against fine meshes and the exact solution,
   and the errata of the printed matrices;
2. the simulated data set (built once, then reused from its cache);
3. the signal features of every recording (in parallel through :mod:`joblib`);
4. the dominant frequency against the contact distance per material and its spread (Figs. 9, 10);
5. the gain and time constant of the band-passed decay per material (Fig. 11);
6. the SVM and ANN material classifiers with their confusion matrices beside the paper's
   (Figs. 12 and 15) and the two distance networks (Figs. 13 and 14);
7. beyond the paper: the contact distance over the *whole* probe from two modes, tested on
   contact positions that the calibration never saw, against the first-mode-only estimator that
   stops at 80 %;
8. spectrograms and scalograms at 0.25 L ... 0.9 L (Figs. 18 and 19);

and writes every figure as PNG, a report in Markdown and HTML, and a JSON summary.
"""

from __future__ import annotations

import json
import logging
import os
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .._progress import progress
from .._validate import check_int
from ..paper import printed
from ..paper.protocol import TIME_FREQUENCY_RATIOS
from ..report import FigureSet, Report

__all__ = ["StudyResult", "reproduce", "default_cache_dir"]

log = logging.getLogger(__name__)

RATIOS = TIME_FREQUENCY_RATIOS


def default_cache_dir() -> Path:
    """Where data sets are cached: ``$EBANTENNA_CACHE``, else ``~/.cache/ebantenna``.

    Examples
    --------
    >>> isinstance(default_cache_dir(), Path)
    True
    """
    env = os.environ.get("EBANTENNA_CACHE")
    return Path(env) if env else Path.home() / ".cache" / "ebantenna"


@dataclass(frozen=True, eq=False)
class StudyResult:
    """Outcome of :func:`reproduce`.

    Attributes
    ----------
    summary : dict
        JSON-serialisable numbers (``svm.test_accuracy``, ``ann.test_accuracy``,
        ``distance.full_range_mae_cm``, ...).
    out_dir : Path
        Where the figures and the report were written.
    figures : dict of str to Path
        Every PNG written.
    report_markdown, report_html : Path
    """

    summary: dict
    out_dir: Path
    figures: dict
    report_markdown: Path
    report_html: Path


def _probe_length(ds) -> float:
    """Length (m) of the probe the data set was simulated with, from its own metadata."""
    return ds.metadata["config"]["scene"]["probe"]["length"]


def _pct(x: float) -> str:
    """A fraction as a percentage with one decimal.

    Examples
    --------
    >>> _pct(0.9917)
    '99.2 %'
    """
    return f"{100 * x:.1f} %"


# ----------------------------------------------------------------------------- 1. modes
def _modes_section(report, figs, probe, quick):
    import matplotlib.pyplot as plt

    from ..fem import Supports, dominant_mode_zones, exact_frequencies, modal_analysis
    from ..fem.symbolic import PAPER_NOTES, paper_errata
    from ..probe import Probe

    L = probe.length
    contacts = np.linspace(0.01, 0.99, 50 if quick else 99) * L
    zones = dominant_mode_zones(probe, contacts)
    start2, start3 = zones.boundaries()
    peak = float(contacts[np.argmax(zones.frequency)])
    ax = zones.plot()
    ax.set_title("Dominant (lowest) frequency and its zones (cf. Fig. 16)")
    fig16 = figs.save(ax.figure, "fig16_zones")

    fig, axes = plt.subplots(1, 3, figsize=(13, 3.6), sharey=True)
    picks = {"a": 0.25 * L, "b": 0.5 * (start2 + start3), "c": 0.9 * L}
    for axis, (label, c) in zip(axes, picks.items(), strict=True):
        res = modal_analysis(probe, Supports(contact=float(c)), n_elements=64, n_modes=2)
        res.plot(ax=axis)
        axis.set_title(f"({label}) contact at {c / L:.2f} L")
    fig17 = figs.save(fig, "fig17_mode_shapes")

    bare = Probe(**{**probe.to_dict(), "tip_mass": 0.0})
    rows = []
    for r in RATIOS:
        two = modal_analysis(bare, Supports(r * L), n_elements=2, n_modes=2).frequencies
        fine = modal_analysis(bare, Supports(r * L), n_elements=64, n_modes=2).frequencies
        exact = exact_frequencies(bare, r * L, n_modes=2)
        rows.append(
            [
                f"{r:.2f} L",
                f"{two[0]:.2f}",
                f"{fine[0]:.4f}",
                f"{exact[0]:.4f}",
                f"{two[1]:.1f}",
                f"{exact[1]:.2f}",
            ]
        )

    report.heading("Modes of the probe and the three zones (Figs. 16, 17)")
    report.paragraph(
        f"Probe of the paper scene: L = {100 * L:g} cm acrylic tube with a "
        f"{1000 * probe.tip_mass:g} g sensor board at the tip, hinge clamped, contact a rigid "
        "pin. The zones are read off the mode shapes: zone 1 where the overhang holds at least "
        "90 % of the lowest mode's kinetic energy, zone 3 where it holds at most 10 %."
    )
    report.table(
        ["quantity", "paper", "this reproduction"],
        [
            [
                "mode change complete",
                f"{printed.MODE_CHANGE_RATIO.value:.2f} L",
                f"zone 3 from {start3 / L:.2f} L",
            ],
            ["transition (zone 2) begins", "-", f"{start2 / L:.2f} L"],
            ["lowest frequency peaks at", "-", f"{peak / L:.2f} L ({100 * peak:.1f} cm)"],
        ],
    )
    report.figure(fig16, "Dominant frequency against contact distance, zones shaded (cf. Fig. 16)")
    report.figure(
        fig17, "Mode shapes in zones 1, 2 and 3, drawn with the shape functions (cf. Fig. 17)"
    )
    report.paragraph(
        "The paper's two-element model against 64 elements and the exact frequency equation "
        "(bare tube, no tip mass, so that the exact solution applies):"
    )
    report.table(
        [
            "contact",
            "f1, 2 elements",
            "f1, 64 elements",
            "f1, exact",
            "f2, 2 elements",
            "f2, exact",
        ],
        rows,
    )
    errata = paper_errata()
    report.paragraph(
        f"Errata of the printed element and two-element matrices: {len(errata)} entries differ "
        "from the sympy derivation (typo: wrong even for equal element lengths; common factor: "
        "right only when l1 = l2)."
    )
    report.table(
        ["matrix", "row", "col", "printed", "derived", "why"],
        [[e.matrix, e.row, e.col, e.printed, e.derived, e.reason] for e in errata],
    )
    for note in PAPER_NOTES:
        report.paragraph(f"Note: {note}")
    return {
        "zone2_start_ratio": start2 / L,
        "zone3_start_ratio": start3 / L,
        "lowest_frequency_peak_ratio": peak / L,
        "errata": len(errata),
    }


# ----------------------------------------------------------------- 4-5. signal processing
def _per_contact(values, contact, mask=None):
    """Median and standard deviation of ``values`` at each distinct contact distance.

    Examples
    --------
    >>> grid, med, spread = _per_contact(np.array([1.0, 3.0, 5.0]), np.array([0.1, 0.1, 0.2]))
    >>> grid.tolist(), med.tolist(), spread.tolist()
    ([0.1, 0.2], [2.0, 5.0], [1.0, 0.0])
    """
    grid = np.unique(contact)
    med = np.full(grid.size, np.nan)
    spread = np.full(grid.size, np.nan)
    for i, g in enumerate(grid):
        sel = contact == g
        if mask is not None:
            sel &= mask
        if np.any(sel):
            med[i] = np.median(values[sel])
            spread[i] = np.std(values[sel])
    return grid, med, spread


def _frequency_section(report, figs, ds, feats, materials):
    import matplotlib.pyplot as plt

    L = _probe_length(ds)
    fig, (a9, a10) = plt.subplots(1, 2, figsize=(12, 4))
    for m in materials:
        sel = ds.material == m
        grid, med, _ = _per_contact(feats.dominant[sel], ds.contact[sel])
        a9.semilogy(100 * grid, med, ".-", label=m, ms=3)
    a9.set_xlabel("contact distance (cm)")
    a9.set_ylabel("dominant frequency (Hz, log scale)")
    a9.set_title("cf. Fig. 9")
    a9.legend(fontsize="small")
    grid, med, spread = _per_contact(feats.dominant, ds.contact)
    a10.plot(100 * grid, spread, ".-")
    a10.set_xlabel("contact distance (cm)")
    a10.set_ylabel("std of the dominant frequency (Hz)")
    a10.set_title("cf. Fig. 10 (a)")
    name = figs.save(fig, "fig09_10_dominant_frequency")
    peak = float(grid[np.nanargmax(med)])
    first = int(np.argmax(spread > 3 * np.nanmedian(spread[: max(3, grid.size // 2)])))
    report.heading("Dominant frequency against contact distance (Figs. 9, 10)")
    report.paragraph(
        "Dominant frequency of the sweep-plane (X) acceleration of every recording, median over "
        "repetitions per material, and its standard deviation over all recordings at a contact. "
        "The resultant of eq. 1 is not used here: the Z axis carries gravity, so the square root "
        "mixes the static 1 g with the vibration and moves the spectral peak."
    )
    report.table(
        ["quantity", "paper", "this reproduction"],
        [
            [
                "deviation from the linear trend",
                f"{printed.DEVIATION_CM.value} cm ({printed.PROBE_LENGTH_CM.value:g} cm probe)",
                f"dominant frequency peaks at {100 * peak:.1f} cm ({peak / L:.2f} L)",
            ],
            [
                "spread grows near",
                f"about 30 cm ({printed.percent(printed.SPREAD_RATIO)} of L)",
                f"{100 * grid[first]:.1f} cm ({grid[first] / L:.2f} L)",
            ],
        ],
    )
    report.figure(name, "Dominant frequency per material (log scale) and its spread")
    return {
        "dominant_frequency_peak_cm": 100 * peak,
        "spread_rises_at_cm": 100 * float(grid[first]),
    }


def _decay_section(report, figs, ds, feats, materials):
    import matplotlib.pyplot as plt

    L = _probe_length(ds)
    region = ds.contact <= 0.8 * L
    fig, (ag, at) = plt.subplots(1, 2, figsize=(12, 4))
    rows = []
    for m in materials:
        sel = (ds.material == m) & region
        ok = feats.decay_ok[sel]
        grid, gain, _ = _per_contact(feats.gain[sel], ds.contact[sel], ok)
        _, tau, _ = _per_contact(feats.tau[sel], ds.contact[sel], ok)
        ag.plot(100 * grid, gain, ".-", ms=3, label=m)
        at.plot(100 * grid, 1000 * tau, ".-", ms=3, label=m)
        rows.append(
            [
                m,
                f"{np.nanmedian(feats.gain[sel][ok]):.3g}",
                f"{1000 * np.nanmedian(feats.tau[sel][ok]):.1f}",
                f"{ok.mean():.0%}",
            ]
        )
    for axis, label in ((ag, "gain a (m/s^2)"), (at, "time constant tau (ms)")):
        axis.set_xlabel("contact distance (cm)")
        axis.set_ylabel(label)
        axis.legend(fontsize="small")
    ag.set_title("cf. Fig. 11 (a)")
    at.set_title("cf. Fig. 11 (b)")
    name = figs.save(fig, "fig11_gain_time_constant")
    report.heading("Gain and time constant by material (Fig. 11)")
    report.paragraph(
        "Resultant acceleration band-passed by the Table 1 Chebyshev filter at the order its "
        "specification needs (zero phase), then a*exp(b t) fitted to the envelope (tau = -1/b), on "
        "the first 80 % of the probe. The filter itself rings for about 0.4 s (see "
        "ebantenna.signal.filters), which lengthens short time constants; recordings whose fit "
        "finds no decay are left out and counted."
    )
    report.table(["material", "median gain (m/s^2)", "median tau (ms)", "fits with a decay"], rows)
    report.figure(name, "Gain and time constant along the probe per material")
    return {"decay_fit_ok_fraction": float(feats.decay_ok[region].mean())}


# ------------------------------------------------------------------------------ 6. ML
def _ml_section(report, figs, ds, feats, seed):
    from ..paper import experiments as ex
    from ..paper.plots import plot_confusion_comparison, plot_distance_errors
    from ..paper.printed import PAPER_ANN, PAPER_SVM

    L = _probe_length(ds)
    svm = ex.classify_materials_svm(feats.fft, ds.material, seed=seed)
    ann = ex.classify_materials_ann(feats.fft, ds.material, seed=seed)
    fig12 = figs.save(plot_confusion_comparison(ann, PAPER_ANN), "fig12_ann_confusion")
    fig15 = figs.save(plot_confusion_comparison(svm, PAPER_SVM), "fig15_svm_confusion")
    lin = ex.regress_distance_linear_region(feats.fft, ds.contact, probe_length=L, seed=seed)
    full = ex.regress_distance_full_length(feats.fft_elliptic, ds.contact, seed=seed)
    fig1314 = figs.save(plot_distance_errors(lin, full), "fig13_14_distance_networks")

    sa, aa = svm.accuracies, ann.accuracies
    report.heading("Material classification: ANN and SVM (Figs. 12, 15)")
    report.paragraph(
        "Features: the 256 FFT magnitudes of X and Z, each vector divided by its maximum. "
        "SVM: RBF kernel, gamma = 2, one-vs-rest, 80/20 split (section 4.3). ANN: one hidden "
        "layer of 53 tanh neurons, gradient descent, 70/15/15 split with validation stopping "
        "(section 4.2). "
        "The simulator's materials differ only through contact damping and compliance; nothing "
        "was tuned towards the paper's accuracies."
    )
    report.table(
        ["model", "split", "paper", "this reproduction", "fit time (s)"],
        [
            [
                "SVM",
                "train",
                printed.percent(printed.SVM_TRAIN_ACCURACY),
                _pct(sa["train"]),
                f"{svm.fit_seconds:.1f}",
            ],
            ["SVM", "test", printed.percent(printed.SVM_TEST_ACCURACY), _pct(sa["test"]), ""],
            ["ANN", "all", printed.percent(printed.ANN_ACCURACY), _pct(aa["all"]),
             f"{ann.fit_seconds:.1f}"],
            ["ANN", "test", "-", _pct(aa["test"]), ""],
        ],
    )
    curve = np.asarray(getattr(ann.model, "loss_curve_", [np.nan]))
    report.paragraph(
        f"The ANN's training cross-entropy went from {curve[0]:.3f} to {curve[-1]:.3f} in "
        f"{curve.size} epochs of full-batch gradient descent; guessing among {len(ann.labels)} "
        f"classes scores ln {len(ann.labels)} = {np.log(len(ann.labels)):.3f}. Where the two are "
        "close, the network has learnt little before validation stopping ended the training: "
        "plain gradient descent is slow on these features, not a sign that they hold nothing "
        "(the SVM's accuracy above chance shows they do)."
    )
    report.figure(fig12, "ANN confusion matrices beside the paper's Fig. 12")
    report.figure(fig15, "SVM confusion matrices beside the paper's Fig. 15")
    report.preformatted(svm.report() + "\n\n" + ann.report())
    report.heading("Distance networks (Figs. 13, 14)")
    report.paragraph(
        "2 x 20 tanh network on the first 80 % of the probe (section 4.2), and the 9-neuron ReLU "
        "network trained by scaled conjugate gradient over the whole length on Table 2 "
        "elliptic-filtered spectra, min-max normalised."
    )
    report.table(
        ["network", "range", "MAE (cm)", "RMS (cm)", "fit time (s)"],
        [
            [
                "2 x 20 tanh, GD",
                "0-80 % of L",
                f"{lin.mae_cm:.2f}",
                f"{lin.rmse_cm:.2f}",
                f"{lin.fit_seconds:.1f}",
            ],
            [
                "9 ReLU, SCG",
                "whole probe",
                f"{full.mae_cm:.2f}",
                f"{full.rmse_cm:.2f}",
                f"{full.fit_seconds:.1f}",
            ],
        ],
    )
    report.figure(fig1314, "Mean absolute distance error along the probe (cf. Figs. 13, 14)")
    return {
        "svm": {
            "train_accuracy": sa["train"],
            "test_accuracy": sa["test"],
            "fit_seconds": svm.fit_seconds,
        },
        "ann": {
            "train_accuracy": aa["train"],
            "test_accuracy": aa["test"],
            "all_accuracy": aa["all"],
            "fit_seconds": ann.fit_seconds,
        },
        "networks": {"linear_region_mae_cm": lin.mae_cm, "full_length_mae_cm": full.mae_cm},
    }


# ----------------------------------------------------------------- 7. beyond the paper
def _full_range_section(report, figs, ds, feats):
    import matplotlib.pyplot as plt

    from ..paper.estimators import FrequencyDistanceEstimator, MultiModeDistanceEstimator

    L = _probe_length(ds)
    grid = np.unique(ds.contact)
    # Calibrate on every other contact position and test on the ones in between: the estimate
    # must interpolate, it cannot just recognise a position it has seen.
    calibration = np.isin(ds.contact, grid[::2])
    ok = np.all(np.isfinite(feats.peaks), axis=1)
    multi = MultiModeDistanceEstimator().fit(
        feats.peaks[calibration & ok], ds.contact[calibration & ok]
    )
    test = ~calibration & ok
    estimate = multi.predict(feats.peaks[test])
    error_cm = 100 * np.abs(estimate - ds.contact[test])
    beyond = ds.contact[test] > 0.8 * L

    single = FrequencyDistanceEstimator(out_of_range="clip").fit(
        feats.dominant[calibration], ds.contact[calibration]
    )
    test1 = ~calibration
    error1_cm = 100 * np.abs(single.predict(feats.dominant[test1]) - ds.contact[test1])

    pos, mae, _ = _per_contact(error_cm, ds.contact[test])
    pos1, mae1, _ = _per_contact(error1_cm, ds.contact[test1])
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.semilogy(100 * pos1, mae1, ".-", label="first mode only (the paper's feature)")
    ax.semilogy(100 * pos, mae, ".-", label="two modes (full range)")
    ax.axvline(100 * single.limit_, color="0.5", ls="--", lw=1, label="turning point of f1")
    ax.set_xlabel("contact distance (cm)")
    ax.set_ylabel("mean absolute error (cm)")
    ax.legend(fontsize="small")
    ax.set_title("Contact distance along the whole probe")
    name = figs.save(fig, "beyond_full_range_distance")

    report.heading("Beyond the paper: contact distance over the whole probe")
    report.paragraph(
        "The first mode's frequency rises and then falls along the probe, so it cannot place a "
        "contact beyond its turning point. The two strongest spectral peaks together are unique "
        "along the whole length: each is calibrated against distance (median over recordings) and "
        "a new recording is placed where both fit best. Calibration uses every other contact "
        "position (1 cm apart), the test the positions in between, which the calibration never saw."
    )
    report.table(
        ["estimator", "range", "MAE (cm)", "MAE beyond 0.8 L (cm)", "95th percentile (cm)"],
        [
            [
                "first mode only",
                "whole probe",
                f"{error1_cm.mean():.2f}",
                f"{error1_cm[ds.contact[test1] > 0.8 * L].mean():.2f}",
                f"{np.percentile(error1_cm, 95):.2f}",
            ],
            [
                "two modes",
                "whole probe",
                f"{error_cm.mean():.2f}",
                f"{error_cm[beyond].mean():.2f}" if np.any(beyond) else "-",
                f"{np.percentile(error_cm, 95):.2f}",
            ],
        ],
    )
    report.paragraph(
        f"Paper: the earlier ANN reached about {printed.PRIOR_DISTANCE_ACCURACY_CM.value} cm on "
        "the first 75-80 % of the probe. Recordings without two separable peaks: "
        f"{int((~ok).sum())} of {ok.size} (left out of the two-mode estimate and counted here)."
    )
    report.figure(name, "Mean absolute error along the probe: one mode against two")
    return {
        "full_range_mae_cm": float(error_cm.mean()),
        "full_range_mae_beyond_80_cm": float(error_cm[beyond].mean()) if np.any(beyond) else None,
        "first_mode_only_mae_cm": float(error1_cm.mean()),
        "first_mode_turning_point_cm": 100 * single.limit_,
        "recordings_without_two_peaks": int((~ok).sum()),
    }


# ---------------------------------------------------------------- 8. time-frequency
def _time_frequency_section(report, figs, scene, seed):
    import matplotlib.pyplot as plt

    from ..signal import morlet_scalogram, spectrogram
    from ..simulate import simulate

    L = scene.probe.length
    fig, axes = plt.subplots(2, len(RATIOS), figsize=(3.2 * len(RATIOS), 6), sharey=True)
    frequencies = np.linspace(5, 450, 120)
    for j, r in enumerate(RATIOS):
        rec = simulate(scene.with_(contact=r * L, material="brass"), seed=seed)
        x = rec.ax - rec.ax.mean()
        spectrogram(x, rec.fs, nperseg=64).plot(ax=axes[0, j])
        morlet_scalogram(x, rec.fs, frequencies).plot(ax=axes[1, j])
        axes[0, j].set_ylim(0, frequencies[-1])
        axes[0, j].set_title(f"spectrogram, {r:.2f} L")
        axes[1, j].set_title(f"scalogram, {r:.2f} L")
    fig.tight_layout()
    name = figs.save(fig, "fig18_19_time_frequency")
    report.heading("Spectrograms and scalograms (Figs. 18, 19)")
    report.paragraph(
        "Sweep-plane acceleration after contact with brass at 0.25 L ... 0.9 L: short-time FFT "
        "(64-sample frames) above, Morlet scalogram below. Near the hinge one long-lived component "
        "dominates; towards the tip several modes start strong and die out quickly, as the paper "
        "describes."
    )
    report.figure(name, "Spectrograms (top) and scalograms (bottom) at five contact positions")


# ------------------------------------------------------------------------------ driver
def reproduce(
    out_dir="ebantenna-output",
    *,
    quick: bool = False,
    seed: int = 0,
    n_jobs: int | None = -1,
    cache_dir=None,
    show_progress=None,
) -> StudyResult:
    """Run the whole study and write its figures and report.

    Parameters
    ----------
    out_dir : path
        Where the PNG figures, ``report.md``, ``report.html`` and ``summary.json`` go.
    quick : bool
        The small data set (contacts every 5 cm, 3 repetitions) and coarser sweeps: well under a
        minute, for tests and the documentation. Its numbers are not the study's.
    seed : int
        Seed of the data set and of every split and initialisation.
    n_jobs : int or None
        joblib workers for the data set and the features (``-1``: all cores).
    cache_dir : path, optional
        Data set cache; default :func:`default_cache_dir`.
    show_progress : bool, optional
        Progress bars (default: on a terminal).

    Returns
    -------
    StudyResult
    """
    import matplotlib

    matplotlib.use("Agg")
    from ..simulate import build_dataset, builtin_scene

    seed = check_int("seed", seed, minimum=0)
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    cache_dir = Path(cache_dir) if cache_dir is not None else default_cache_dir()
    figs = FigureSet(out_dir)
    report = Report("ebantenna: the study reproduced" + (" (quick run)" if quick else ""))
    report.paragraph(
        "Every number below comes from the simulated probe (scene 'paper'), not from the paper's "
        "recordings; the paper's value stands beside each one. "
        + ("This is the quick run: a small data set, numbers only indicative." if quick else "")
    )
    scene = builtin_scene("paper")
    summary: dict = {"quick": quick, "seed": seed}
    timings: dict = {}
    steps = [
        "modes",
        "data set",
        "features",
        "frequency",
        "decay",
        "ml",
        "full range",
        "time-frequency",
    ]
    bar = progress(total=len(steps), desc="study", enabled=show_progress)

    def step(name):
        bar.set_postfix_str(name)
        timings[name] = time.perf_counter()

    def done(name):
        timings[name] = time.perf_counter() - timings[name]
        bar.update()
        log.info("%s done in %.1f s", name, timings[name])

    step("modes")
    summary["modes"] = _modes_section(report, figs, scene.probe, quick)
    done("modes")

    step("data set")
    workers = (os.cpu_count() or 1) if n_jobs is None or n_jobs < 0 else n_jobs
    ds = build_dataset(
        cache_dir, seed=seed, quick=quick, n_jobs=workers, show_progress=show_progress
    )
    materials = list(dict.fromkeys(ds.material.tolist()))
    summary["dataset"] = {
        "path": str(ds.path) if ds.path else None,
        "signals": ds.n_signals,
        "samples": ds.n_samples,
        "materials": materials,
        "contacts": int(np.unique(ds.contact).size),
        "checksum_sha256": ds.metadata.get("checksum_sha256"),
    }
    done("data set")

    step("features")
    from ..paper.features import signal_features

    feats = signal_features(ds.ax, ds.az, ds.fs, n_jobs=n_jobs, show_progress=show_progress)
    done("features")
    report.heading("Data set")
    report.paragraph(
        f"{ds.n_signals} simulated recordings of {ds.n_samples} samples at {ds.fs:g} Hz: "
        f"{len(materials)} materials x {summary['dataset']['contacts']} contact positions x "
        f"repetitions, from {ds.path} (SHA-256 {summary['dataset']['checksum_sha256']})."
    )

    step("frequency")
    summary["frequency"] = _frequency_section(report, figs, ds, feats, materials)
    done("frequency")
    step("decay")
    summary["decay"] = _decay_section(report, figs, ds, feats, materials)
    done("decay")
    step("ml")
    summary.update(_ml_section(report, figs, ds, feats, seed))
    done("ml")
    step("full range")
    summary["distance"] = _full_range_section(report, figs, ds, feats)
    summary["distance"].update(summary.pop("networks"))
    done("full range")
    step("time-frequency")
    _time_frequency_section(report, figs, scene, seed)
    done("time-frequency")
    bar.close()

    report.heading("Run time")
    report.table(["step", "seconds"], [[k, f"{v:.1f}"] for k, v in timings.items()])
    summary["timings_s"] = timings
    md, page = report.write(out_dir)
    summary["report"] = {"markdown": str(md), "html": str(page)}
    summary["figures"] = {k: str(v) for k, v in figs.paths.items()}
    (out_dir / "summary.json").write_text(json.dumps(summary, indent=2), encoding="utf-8")
    return StudyResult(summary, out_dir, dict(figs.paths), md, page)
