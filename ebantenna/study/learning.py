"""Section 6: the SVM and ANN material classifiers beside the paper's confusion matrices
(Figs. 12, 15) and the two distance networks (Figs. 13, 14)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import check_bool
from ..paper import experiments, printed
from ..paper.plots import plot_confusion_comparison, plot_distance_errors
from ..paper.protocol import (
    DATASET,
    DISTANCE_FULL_LENGTH,
    DISTANCE_LINEAR_REGION,
    MATERIAL_ANN,
    MATERIAL_SVM,
)
from ..paper.uncertainty import (
    UNITS,
    ClusteredAccuracy,
    clustered_entries,
    format_clustered,
    percent,
    training_entries,
)
from ._common import (
    TRAINED_ONCE,
    check_render,
    check_step,
    error_entry,
    fits_in_parallel,
    format_error,
    format_mae,
    mae_entry,
    probe_length,
)

__all__ = ["LearningResult", "compute", "fit_calls", "from_fits", "render"]


@dataclass(frozen=True, eq=False)
class LearningResult:
    """The paper's four learning experiments on the study's features.

    Attributes
    ----------
    svm, ann : ebantenna.paper.experiments.ClassificationResult
        Material classifiers.
    linear_region, full_length : ebantenna.paper.experiments.RegressionResult
        Distance networks: 2 x 20 tanh on the first 80 %, 9 ReLU over the whole probe.
    positions : ndarray
        Nominal contact position of every recording (the unit of the intervals).
    """

    svm: experiments.ClassificationResult
    ann: experiments.ClassificationResult
    linear_region: experiments.RegressionResult
    full_length: experiments.RegressionResult
    positions: np.ndarray = None

    def to_dict(self) -> dict:
        """Accuracies and fit times of the classifiers, under ``svm`` and ``ann``: each test
        accuracy with its interval on the position
        (:func:`~ebantenna.paper.uncertainty.clustered_entries`), the training accuracies (and
        the network's 'all', mostly training rows) with their counts only; the network's
        ``epochs``, ``max_epochs`` and ``stopped_by``."""
        svm, ann = self.svm, self.ann
        return {
            "svm": {
                **training_entries("train_accuracy", svm.accuracies["train"],
                                   svm.counts["train"]),
                **clustered_entries("test_accuracy", held_out_accuracy(svm, self.positions)),
                "fit_seconds": svm.fit_seconds,
            },
            "ann": {
                **training_entries("train_accuracy", ann.accuracies["train"],
                                   ann.counts["train"]),
                **clustered_entries("test_accuracy", held_out_accuracy(ann, self.positions)),
                **training_entries("all_accuracy", ann.accuracies["all"], ann.counts["all"]),
                "epochs": epochs_run(ann),
                "max_epochs": ANN_MAX_EPOCHS,
                "stopped_by": ann.stopped_by,
                "fit_seconds": ann.fit_seconds,
            },
        }

    def distance_dict(self) -> dict:
        """Mean absolute errors of the two distance networks, cm; the full-length network's
        also with its interval over the test positions (``full_length``, ``mae_entry``), and
        its RMS error with a bootstrap over them (``full_length_rms``, ``error_entry``); the
        linear region's are under the splits."""
        full = self.full_length
        return {
            "linear_region_mae_cm": self.linear_region.mae_cm,
            "full_length_mae_cm": full.mae_cm,
            "full_length": mae_entry(full.errors_cm, full.distance_test),
            "full_length_rms": error_entry(full.errors_cm, full.distance_test, "rms"),
        }


def compute(ds, feats, seed: int, n_jobs: int = 1) -> LearningResult:
    """Train and test the two classifiers and the two distance networks, each fit on one of
    ``n_jobs`` worker processes (``_common.fits_in_parallel``): the same numbers whatever
    ``n_jobs``. The same as :func:`from_fits` of the fits of :func:`fit_calls`."""
    check_step(ds=ds, feats=feats, seed=seed, n_jobs=n_jobs)
    return from_fits(ds, fits_in_parallel(fit_calls(ds, feats, seed), n_jobs))


def fit_calls(ds, feats, seed: int) -> list:
    """The four fits of :func:`compute` as calls ``(function, args, kwargs)`` for
    ``_common.fits_in_parallel``, in the order :func:`from_fits` takes their results.

    The longest comes first (the network's 1000 epochs: about six times the SVM's CPU time on
    the full data set), so that the others share the second worker meanwhile; a caller may
    queue more fits behind them (the study queues the ANN setup's)."""
    check_step(ds=ds, feats=feats, seed=seed)
    return [
        (experiments.classify_materials_ann, (feats.fft, ds.material),
         {"seed": seed, "max_iter": ANN_MAX_EPOCHS}),
        (experiments.classify_materials_svm, (feats.fft, ds.material), {"seed": seed}),
        (experiments.regress_distance_linear_region, (feats.fft, ds.contact),
         {"probe_length": probe_length(ds), "seed": seed}),
        (experiments.regress_distance_full_length, (feats.fft_elliptic, ds.contact),
         {"seed": seed}),
    ]


def from_fits(ds, fits) -> LearningResult:
    """The :class:`LearningResult` of the results of :func:`fit_calls`' four calls, in order."""
    check_step(ds=ds)
    kinds = (experiments.ClassificationResult, experiments.ClassificationResult,
             experiments.RegressionResult, experiments.RegressionResult)
    if not isinstance(fits, list | tuple) or len(fits) != len(kinds) or not all(
            isinstance(f, k) for f, k in zip(fits, kinds, strict=True)):
        raise TypeError("fits must be the results of fit_calls' four calls, in order (the "
                        f"network's, the SVM's, the two distance networks'), got {fits!r:.80}")
    ann, svm, lin, full = fits
    return LearningResult(svm, ann, lin, full, np.asarray(ds.contact))


#: The largest number of epochs of the paper network's main run (MATLAB traingd's default).
ANN_MAX_EPOCHS = 1000


def held_out_accuracy(result, positions) -> ClusteredAccuracy:
    """A classifier's test accuracy with its interval on the nominal position."""
    p = np.asarray(positions)
    return ClusteredAccuracy.from_recordings(result.correct(), p[result.rows()],
                                             UNITS["random"])


def epochs_run(result) -> int:
    """Epochs a network trained (its loss curve's length, else its iteration count)."""
    return len(getattr(result.model, "loss_curve_", ())) or int(result.model.n_iter_)


def stop_sentence(stopped_by: str, epochs: int, max_epochs: int) -> str:
    """What ended a training run, in words, from what was recorded.

    Examples
    --------
    >>> stop_sentence("epoch cap", 1000, 1000)
    'the epoch cap ended the training (1000 of 1000 epochs), not the validation check'
    >>> stop_sentence("validation", 212, 1000)
    'the validation check ended the training after 212 of at most 1000 epochs'
    """
    if stopped_by == "epoch cap":
        return (f"the epoch cap ended the training ({epochs} of {max_epochs} epochs), not the "
                "validation check")
    if stopped_by == "validation":
        return (f"the validation check ended the training after {epochs} of at most "
                f"{max_epochs} epochs")
    return f"the {stopped_by} ended the training after {epochs} of at most {max_epochs} epochs"


def render(result: LearningResult, report, figures, *, simulated: bool = True) -> None:
    """Figs. 12-15, the accuracy and error tables and the confusion matrices as text
    (``simulated``: the data come from the simulator, and the report says how its materials
    differ)."""
    check_render(result, LearningResult, report, figures)
    check_bool("simulated", simulated)
    svm, ann, lin, full = result.svm, result.ann, result.linear_region, result.full_length
    fig12 = figures.save(plot_confusion_comparison(ann, printed.PAPER_ANN), "fig12_ann_confusion")
    fig15 = figures.save(plot_confusion_comparison(svm, printed.PAPER_SVM), "fig15_svm_confusion")
    fig1314 = figures.save(plot_distance_errors(lin, full), "fig13_14_distance_networks")
    _render_classifiers(svm, ann, result.positions, report, fig12, fig15, simulated)
    _render_distance_networks(lin, full, report, fig1314)


def _render_classifiers(svm, ann, positions, report, fig12: str, fig15: str,
                        simulated=True) -> None:
    """The material classifiers beside the paper's: features, accuracies, the ANN's training
    loss against guessing, the confusion matrices (Figs. 12, 15)."""
    report.heading("Material classification: ANN and SVM (Figs. 12, 15)")
    svm_split = _split((1 - MATERIAL_SVM.test_fraction, MATERIAL_SVM.test_fraction))
    report.paragraph(
        f"Features: the {DATASET.fft_bins} FFT magnitudes of X and Z, each vector divided by its "
        f"maximum. SVM: RBF kernel, gamma = {MATERIAL_SVM.gamma:g}, {MATERIAL_SVM.strategy}, "
        f"{svm_split} split (section 4.3). ANN: one hidden layer of "
        f"{MATERIAL_ANN.hidden_layer_sizes[0]} {MATERIAL_ANN.activation} neurons, gradient "
        f"descent, {_split(MATERIAL_ANN.fractions)} split with validation stopping "
        "(section 4.2). "
        + ("The simulated materials differ through the physics the scene lists (the ablation "
           "below measures what each effect carries); nothing was tuned towards the paper's "
           "accuracies." if simulated else
           "Nothing was tuned towards the paper's accuracies.")
    )
    report.table(
        ["model", "split", "paper", "this reproduction", "fit time (s)"],
        [
            ["SVM", "train", printed.percent(printed.SVM_TRAIN_ACCURACY), _train(svm, "train"),
             f"{svm.fit_seconds:.1f}"],
            ["SVM", "test", printed.percent(printed.SVM_TEST_ACCURACY),
             format_clustered(held_out_accuracy(svm, positions)), ""],
            ["ANN", "all", printed.percent(printed.ANN_ACCURACY), _train(ann, "all"),
             f"{ann.fit_seconds:.1f}"],
            ["ANN", "test", "-", format_clustered(held_out_accuracy(ann, positions)), ""],
        ],
    )
    report.paragraph(
        f"Training accuracies ('train', and the network's 'all', which is "
        f"{100 * MATERIAL_ANN.fractions[0]:.0f} % training rows) "
        "test nothing unseen and carry no interval. A test accuracy's interval is on the "
        "contact position, the design's independent unit: the repetitions at one position "
        "share its physics. " + TRAINED_ONCE.format(what="The ANN is")
    )
    curve = np.asarray(getattr(ann.model, "loss_curve_", [np.nan]))
    n = len(ann.labels)
    report.paragraph(
        f"The ANN's training cross-entropy went from {curve[0]:.3f} to {curve[-1]:.3f} in "
        f"{curve.size} epochs of full-batch gradient descent; guessing among {n} classes scores "
        f"ln {n} = {np.log(n):.3f}. "
        + stop_sentence(ann.stopped_by, epochs_run(ann), ANN_MAX_EPOCHS).capitalize()
        + ". 'What the paper's training budget changes' measures what more epochs give."
    )
    report.figure(fig12, "ANN confusion matrices beside the paper's Fig. 12")
    report.figure(fig15, "SVM confusion matrices beside the paper's Fig. 15")
    report.preformatted(svm.report() + "\n\n" + ann.report())


def _render_distance_networks(lin, full, report, fig1314: str) -> None:
    """The two distance networks, their errors and Figs. 13, 14."""
    report.heading("Distance networks (Figs. 13, 14)")
    lin_net, full_net = DISTANCE_LINEAR_REGION, DISTANCE_FULL_LENGTH
    sizes = lin_net.hidden_layer_sizes  # layers x neurons, as the paper counts them
    lin_name = f"{len(sizes)} x {sizes[0]} {lin_net.activation}"
    region = f"{100 * lin_net.region:g} %"
    report.paragraph(
        f"{lin_name} network on the first {region} of the probe (section 4.2), and the "
        f"{full_net.hidden_layer_sizes[0]}-neuron ReLU network trained by scaled conjugate "
        "gradient over the whole length on Table 2 elliptic-filtered spectra, min-max normalised."
    )
    report.table(
        ["network", "range", "MAE (cm, 95 % CI over the test positions)",
         "RMS (cm, 95 % CI: bootstrap over the test positions)", "fit time (s)"],
        [
            [name, where, format_mae(mae_entry(r.errors_cm, r.distance_test)),
             format_error(error_entry(r.errors_cm, r.distance_test, "rms"), "rms"),
             f"{r.fit_seconds:.1f}"]
            for name, where, r in (
                (f"{lin_name}, GD", f"0-{region} of L", lin),
                (f"{full_net.hidden_layer_sizes[0]} ReLU, SCG", "whole probe", full),
            )
        ],
    )
    report.paragraph(TRAINED_ONCE.format(what="Each network is"))
    report.figure(fig1314, "Mean absolute distance error along the probe (cf. Figs. 13, 14)")


def _train(result, split: str) -> str:
    """A training accuracy ('train', or 'all': mostly training rows) with its count and no
    interval."""
    rows = "training rows" if split == "train" else "all rows, mostly training"
    return f"{percent(result.accuracies[split])} (n = {result.counts[split]}, {rows})"


def _split(fractions) -> str:
    """Shares as the paper writes a split: ``(0.7, 0.15, 0.15)`` -> ``'70/15/15'``.

    Examples
    --------
    >>> _split((0.7, 0.15, 0.15)), _split((0.8, 0.2))
    ('70/15/15', '80/20')
    """
    return "/".join(f"{100 * f:.0f}" for f in fractions)
