"""Section 6b': how much the material classifiers' numbers carry.

Every classifier on every split over all the split's folds, with the folds' spread beside the
spread binomial sampling would give, and the grouped split with fewer repetitions per position.
The two distance networks, each trained again from :data:`NETWORK_RUNS` seeds (split and
starting weights), with the runs' spread beside the spread one run's interval over its test
positions allows: a network is trained once in the study, and its interval holds the trained
network fixed.
The folds of all three classifiers run on the data set's first :data:`SUBSET_REPETITIONS`
repetitions (every position and material, a fifth of the recordings): the section fits each
classifier on every fold of every split, and a kernel on a fifth of the rows costs about a
twenty-fifth (its size grows with the square of the rows).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.stats import chi2

from ..paper import experiments
from ..paper.splits import SPLITS, split_folds
from ..paper.uncertainty import (
    UNITS,
    FoldAccuracy,
    PairedDifference,
    clustered_entries,
    correct_count,
    format_clustered,
    format_difference,
    percent,
)
from ._common import (
    MAX_SEED,
    check_instance,
    check_render,
    check_step,
    classifier_call,
    fits_in_parallel,
    listed,
    probe_length,
)
from .material_splits import answers_over_folds

__all__ = ["SPLIT_SEEDS", "SUBSET_REPETITIONS", "TRAINING_REPETITIONS", "CLASSIFIERS",
           "NETWORK_RUNS", "NETWORKS", "NetworkRuns", "SeedSpreadResult", "compute", "render"]

#: Folds per classifier and split (:func:`~ebantenna.paper.splits.split_folds`): every
#: recording tested once.
SPLIT_SEEDS = 5
#: Repetitions per position of the subset the seeds are repeated on.
SUBSET_REPETITIONS = 5
#: Repetitions per position kept for the grouped accuracy against the training size.
TRAINING_REPETITIONS = (1, 3, 5)
#: The classifiers repeated over the seeds, by the name the report gives them.
CLASSIFIERS = ("paper's SVM", "position-aware", "mode curves")
#: Each of :data:`CLASSIFIERS` by its name for :func:`~._common.classifier_call`.
FITTED = dict(zip(CLASSIFIERS, ("svm", "position_aware", "mode_curves"), strict=True))
#: Training runs of each distance network on the subset, from the seeds ``seed`` to
#: ``seed + NETWORK_RUNS - 1`` (each its own split and starting weights). Ten runs measure a
#: spread to within a factor of 1.5 below and 1.8 above (``ratio_interval``); five, to
#: within 1.7 and 2.9, left the full-length network's verdict open on one of the two strike
#: marches' data sets and resolved on the other.
NETWORK_RUNS = 10
#: The distance networks trained again, by the name the report gives them.
NETWORKS = ("full-length", "linear-region")


@dataclass(frozen=True, eq=False)
class NetworkRuns:
    """One distance network trained from several seeds on the same rows.

    Attributes
    ----------
    seeds : tuple of int
        The runs' seeds (split and starting weights).
    mae_cm : ndarray
        Per run, the mean over its test positions of their mean absolute errors (cm): the
        estimate its interval over the positions is on.
    se_cm : ndarray
        Per run, the standard error of that mean over its test positions (cm): the spread one
        run's interval allows, were the runs to differ only in the positions they test; NaN for
        a run that tests fewer than two positions (no spread to measure).
    """

    seeds: tuple
    mae_cm: np.ndarray
    se_cm: np.ndarray

    @classmethod
    def from_results(cls, seeds, results) -> NetworkRuns:
        """From the :class:`~ebantenna.paper.experiments.RegressionResult` of each run (at least
        two), made with the seeds ``seeds`` (one whole number each)."""
        if not isinstance(results, list | tuple) or len(results) < 2:
            raise ValueError(f"results must be a list of at least two runs' results (a spread "
                             f"needs two), got {results!r:.80}")
        for r in results:
            check_instance("results", r, experiments.RegressionResult)
        if isinstance(seeds, str | bytes) or not hasattr(seeds, "__len__") or len(seeds) != len(
                results) or not all(isinstance(v, int | np.integer) for v in seeds):
            raise ValueError(f"seeds must hold one whole number per run of results "
                             f"({len(results)}), got {seeds!r:.80}")
        means = [np.asarray(r.mean_error_cm, dtype=float) for r in results]
        return cls(tuple(int(v) for v in seeds), np.array([m.mean() for m in means]),
                   np.array([m.std(ddof=1) / np.sqrt(m.size) if m.size > 1 else np.nan
                             for m in means]))

    @property
    def spread(self) -> float:
        """The runs' standard deviation (cm)."""
        return float(np.std(self.mae_cm, ddof=1))

    @property
    def interval_std(self) -> float:
        """The standard error one run's interval allows, as the root mean square over the runs
        (cm)."""
        return float(np.sqrt(np.mean(np.square(self.se_cm))))

    @property
    def ratio(self) -> float | None:
        """:attr:`spread` over :attr:`interval_std` (None when the latter is 0 or not measured:
        a run tested fewer than two positions)."""
        return self.spread / self.interval_std if self.interval_std > 0 else None

    def to_dict(self) -> dict:
        ratio, measured = self.ratio, bool(np.all(np.isfinite(self.se_cm)))
        return {"seeds": list(self.seeds), "mae_cm": self.mae_cm.tolist(),
                "se_cm": [float(v) if np.isfinite(v) else None for v in self.se_cm],
                "runs_std_cm": self.spread,
                "interval_std_cm": self.interval_std if measured else None, "spread_ratio": ratio,
                "spread_ratio_ci95": None if ratio is None else
                list(ratio_interval(ratio, self.mae_cm.size))}


@dataclass(frozen=True, eq=False)
class SeedSpreadResult:
    """The classifiers over every fold of every split, and the grouped SVM against the
    repetitions.

    Attributes
    ----------
    spreads : dict of (str, str) to FoldAccuracy
        By (classifier of :data:`CLASSIFIERS`, split of :data:`SPLITS`): over the
        :data:`SPLIT_SEEDS` folds of the split (:func:`~ebantenna.paper.splits.split_folds`),
        on the subset.
    subset_recordings : int
        Recordings of the subset (its first :data:`SUBSET_REPETITIONS` repetitions).
    repetitions : dict of int to FoldAccuracy
        Grouped SVM over all folds on the first ``r`` repetitions of each position, for ``r`` in
        :data:`TRAINING_REPETITIONS` and the whole data set.
    subset_repetitions : int
        Repetitions of each position in the subset: :data:`SUBSET_REPETITIONS`, or all the data
        set holds when it holds fewer.
    paired_repetitions : PairedDifference or None
        The most repetitions (B) against the fewest (A) of ``repetitions``, paired on the
        recordings both test: the fewest repetitions' own (every position's first ones), each
        tested once in either; clustered on the position. None when the grouped SVM's answers
        per recording were not given.
    networks : dict of str to NetworkRuns
        By network of :data:`NETWORKS`: trained from :data:`NETWORK_RUNS` seeds on the subset.
    """

    spreads: dict
    subset_recordings: int
    repetitions: dict
    subset_repetitions: int
    paired_repetitions: PairedDifference | None = None
    networks: dict | None = None

    def to_dict(self) -> dict:
        """Under ``materials``: ``seed_spread`` (classifier -> split -> the accuracy over the
        folds, with ``binomial_std``, the spread the folds would show were the recordings
        independent, and ``spread_ratio``), ``svm_grouped_by_repetitions`` and, when measured,
        ``svm_grouped_repetitions_paired`` (the most repetitions against the fewest, paired,
        with ``fewest`` and ``most``) and ``distance_network_runs`` (network -> its runs, the
        runs' spread and the ratio to what one run's interval allows)."""
        spread = {c: {k: _spread_dict(self.spreads[c, k]) for k in SPLITS} for c in CLASSIFIERS}
        out = {
            "seed_spread": {"subset_recordings": self.subset_recordings, **spread},
            "svm_grouped_by_repetitions": {
                str(r): clustered_entries("accuracy", a) for r, a in self.repetitions.items()
            },
        }
        if self.paired_repetitions is not None:
            out["svm_grouped_repetitions_paired"] = {
                "fewest": min(self.repetitions), "most": max(self.repetitions),
                **self.paired_repetitions.to_dict()}
        if self.networks:
            out["distance_network_runs"] = {n: r.to_dict() for n, r in self.networks.items()}
        return out


def binomial_std(f: FoldAccuracy) -> float:
    """The standard deviation the folds' accuracies would show were every recording an
    independent trial: ``sqrt(p (1 - p) / m)`` at the mean accuracy ``p`` and the folds' mean
    size ``m``.

    Examples
    --------
    >>> f = FoldAccuracy([(np.arange(100) < 50, np.arange(100)) for _ in range(2)], "position")
    >>> binomial_std(f)
    0.05
    """
    p, m = f.estimate, float(np.mean(f.n_test))
    return float(np.sqrt(p * (1 - p) / m))


def ratio_interval(ratio: float, folds: int) -> tuple[float, float]:
    """95 % interval of the true ratio of the folds' spread to the binomial one, from the ratio
    measured on ``folds`` folds.

    The folds' sample variance, were they independent normal draws, is ``sigma^2
    chi2_{F-1} / (F - 1)``, so the measured ratio is the true one times ``sqrt(chi2_{F-1} /
    (F - 1))``: five folds measure a spread only to within a factor of about two either way.

    Examples
    --------
    >>> [round(x, 3) for x in ratio_interval(1.0, 5)]
    [0.599, 2.874]
    """
    dof = folds - 1
    return (ratio * float(np.sqrt(dof / chi2.ppf(0.975, dof))),
            ratio * float(np.sqrt(dof / chi2.ppf(0.025, dof))))


def scatter_sentence(rows) -> str:
    """What the folds' spread against the binomial one shows, from each row's ratio.

    Parameters
    ----------
    rows : sequence of (str, float or None, int)
        Per row: its label, the ratio of the folds' standard deviation to the binomial one
        (None when the binomial one is zero) and the number of folds.

    Examples
    --------
    >>> scatter_sentence([("a", 3.0, 5), ("b", 1.1, 5)])[:56]
    'The folds scatter more than independent recordings would'
    >>> "less than" in scatter_sentence([("a", 0.2, 5)])
    True
    >>> scatter_sentence([("a", 1.1, 5), ("b", 0.9, 5)])[:30]
    'In every row the ratio is with'
    """
    above, below, open_ = [], [], []
    for label, ratio, folds in rows:
        if ratio is None:
            continue
        lo, hi = ratio_interval(ratio, folds)
        (above if lo > 1 else below if hi < 1 else open_).append(label)
    parts = []
    if above:
        parts.append("The folds scatter more than independent recordings would, beyond what "
                     f"the folds' number leaves open, for {listed(above)}: there the "
                     "recordings do not behave as independent trials")
    if below:
        parts.append(f"{'they' if parts else 'The folds'} scatter less than independent "
                     f"recordings would for {listed(below)}")
    n = len(open_)
    if n and parts:
        parts.append(f"in the other {n} row{'s' if n > 1 else ''} the ratio's 95 % interval "
                     "holds one: the folds cannot tell the spread from the binomial one")
    elif n:
        parts.append("In every row the ratio is within what the folds leave open (its 95 % "
                     "interval holds one): the folds' spread does not tell the recordings from "
                     "independent trials here, which does not show that they are")
    return "; ".join(parts) + "."


def runs_sentence(networks: dict) -> str:
    """What the networks' runs show against one run's interval, from each network's ratio.

    Parameters
    ----------
    networks : dict of str to NetworkRuns
        By network name.

    Examples
    --------
    >>> def runs(maes, se):
    ...     return NetworkRuns((0, 1, 2, 3, 4), np.array(maes), np.full(5, se))
    >>> text = runs_sentence({"a": runs([2.0, 3.0, 2.5, 4.0, 2.2], 0.1)})
    >>> text[:66]
    "Trained again, the a network scatters more than one run's interval"
    >>> "within what" in runs_sentence({"a": runs([2.0, 2.1, 2.05, 1.95, 2.0], 0.05)})
    True
    """
    above, below, open_ = [], [], []
    for name, runs in networks.items():
        if runs.ratio is None:
            continue
        lo, hi = ratio_interval(runs.ratio, runs.mae_cm.size)
        (above if lo > 1 else below if hi < 1 else open_).append(f"the {name} network")
    parts = []
    if above:
        parts.append(f"Trained again, {listed(above)} scatter{'s' if len(above) == 1 else ''} "
                     "more than one run's interval over its test positions allows, beyond "
                     "what the runs' number leaves open: one run's interval does not carry "
                     "the training's own spread, and a single run's error says less than its "
                     "interval suggests")
    if below:
        parts.append(f"{'the runs of ' if parts else 'The runs of '}{listed(below)} scatter "
                     "less than one run's interval allows: the runs share most of their test "
                     "positions, and their training adds little spread of its own")
    if open_:
        lead = "for " if parts else "For "
        parts.append(f"{lead}{listed(open_)} the runs' spread is within what one run's "
                     "interval allows (the ratio's 95 % interval holds one): the runs cannot "
                     "tell the training's spread from the test positions'")
    return "; ".join(parts) + "." if parts else ""


def repetitions_sentence(repetitions: dict, paired: PairedDifference | None = None) -> str:
    """What the grouped accuracy against the repetitions per position shows: the change from the
    fewest to the most repetitions (from ``paired`` when given, else from the two intervals), and
    how much the interval on the position narrows against the one that counts every recording as
    independent.

    Parameters
    ----------
    repetitions : dict of int to ClusteredAccuracy or FoldAccuracy
        By repetitions per position.
    paired : PairedDifference, optional
        The most repetitions (B) against the fewest (A) on the recordings both test
        (``SeedSpreadResult.paired_repetitions``): the verdict then follows its interval.

    Examples
    --------
    >>> from ebantenna.paper.uncertainty import ClusteredAccuracy
    >>> few = ClusteredAccuracy([1, 0, 1, 0] * 4, [2] * 16, "position")
    >>> many = ClusteredAccuracy([9, 10, 9, 10] * 4, [10] * 16, "position")
    >>> repetitions_sentence({2: few, 10: many})[:60]
    'From 2 to 10 repetitions per position the grouped accuracy r'
    >>> "overlap is no test" in repetitions_sentence({2: few, 10: few})
    True
    """
    if len(repetitions) < 2:
        return ""
    (r0, a0), (r1, a1) = (min(repetitions.items()), max(repetitions.items()))
    moves = f"from {percent(a0.estimate)} to {percent(a1.estimate)}"
    head = f"From {r0} to {r1} repetitions per position the grouped accuracy "
    if paired is not None:
        text = head + f"goes {moves}. " + _paired_words(paired, r0)
    elif a1.ci95[0] > a0.ci95[1] or a1.ci95[1] < a0.ci95[0]:
        way = "rises" if a1.estimate > a0.estimate else "falls"
        text = (head + f"{way} {moves}, their 95 % intervals apart: the number of recordings "
                "of each position the SVM learns from matters on whole held-out positions. ")
    else:
        text = (head + f"goes {moves}, and their 95 % intervals overlap. Both rows test the "
                "same positions on the same grouped folds, so the two intervals are not "
                "independent and their overlap is no test of the change: only a comparison "
                "paired recording by recording could tell it, and this section does not make "
                "one. ")
    grow = a1.n_recordings / a0.n_recordings
    narrow = _width(a0.ci95) / _width(a1.ci95)
    independent = _width(a0.recording_ci95) / _width(a1.recording_ci95)
    # what the repetitions buy is their effective number (the recordings over the design
    # effect) against their count; the widths, printed beside it, also carry the quantile.
    # Accuracies over folds have no effective number: their widths are compared
    effective = all(hasattr(a, "effective_n") for a in (a0, a1))
    gain = a1.effective_n / a0.effective_n if effective else None
    less = gain < grow if effective else narrow < independent
    buys = ("less precision than their count suggests" if less else
            "at least the precision their count suggests")
    number = (f" and their effective number on the position (the recordings over the design "
              f"effect) {gain:.3g}-fold" if effective else "")
    return text + (
        f"The recordings grow {grow:.3g}-fold{number}; the interval counting every recording as "
        f"independent {_fold(independent)}, the interval on the position {_fold(narrow)}: on "
        f"whole held-out positions, these repetitions buy {buys}."
    )


def _paired_words(p: PairedDifference, fewest: int) -> str:
    """The verdict on the repetitions from their paired difference ``p``, taken on the
    recordings of the ``fewest`` repetitions of every position (tested under both)."""
    on = (f"On the {p.n_recordings} recordings both rows test (the first "
          f"{'repetition' if fewest == 1 else f'{fewest} repetitions'} of each material at "
          f"each of the {p.n_units} positions, each tested once in either row)")
    if p.identical:
        return (on + ", every position counts as many right with either: the added repetitions "
                "change nothing there. ")
    if p.resolved:
        way = "rise" if p.direction == "higher" else "fall"
        return (on + f", paired, the change is a {way} of {format_difference(p)}, resolved: the "
                "number of recordings of each position the SVM learns from matters on whole "
                "held-out positions. ")
    return (on + f", paired, the change is {format_difference(p)}, not resolved: it is either "
            "smaller than what this design detects at 80 % power or missed. ")


def _fold(ratio: float) -> str:
    """``narrows 2-fold`` for a width ratio (before / after) of 2, ``widens 2-fold`` for 0.5."""
    return f"narrows {ratio:.3g}-fold" if ratio >= 1 else f"widens {1 / ratio:.3g}-fold"


def _width(ci) -> float:
    """Width of an interval (low, high)."""
    return ci[1] - ci[0]


def _spread_dict(f: FoldAccuracy) -> dict:
    b = binomial_std(f)
    return {**clustered_entries("accuracy", f), "binomial_std": b,
            "spread_ratio": f.spread / b if b > 0 else None}


def _subset(ds, repetitions: int) -> np.ndarray:
    """Rows of the first ``repetitions`` repetitions of every position and material."""
    return np.flatnonzero(np.asarray(ds.repetition) < repetitions)


def compute(ds, feats, seed: int, grouped_full: FoldAccuracy, n_jobs: int = 1, *,
            grouped_answers=None) -> SeedSpreadResult:
    """The three classifiers on every fold of the three splits (on the subset), and the grouped
    SVM over all folds on 1, 3, 5 repetitions; ``grouped_full`` is the whole data set's grouped
    SVM over its folds, already measured, and ``grouped_answers`` (optional) its answer for
    each recording of ``ds`` (True where right; the splits' ``grouped_answers["svm"]``), with
    which the most repetitions are paired against the fewest. Every fit runs on one of
    ``n_jobs`` worker processes (``_common.fits_in_parallel``): the same numbers whatever
    ``n_jobs``."""
    check_step(ds=ds, feats=feats, seed=seed, n_jobs=n_jobs)
    check_instance("grouped_full", grouped_full, FoldAccuracy)
    answers = None if grouped_answers is None else _check_answers(grouped_answers, ds,
                                                                   grouped_full)
    depth = int(np.max(ds.repetition)) + 1
    rows = _subset(ds, SUBSET_REPETITIONS)
    X, y, d = feats.fft[rows], ds.material[rows], ds.contact[rows]
    peaks, dominant = feats.peaks[rows], feats.dominant[rows]
    calls, tested = {}, {}  # every fit of the step, and the positions of its data's rows
    seeds = [(seed + i) % (MAX_SEED + 1) for i in range(NETWORK_RUNS)]
    for i, s in enumerate(seeds):  # the study's calls of learning.fit_calls, on the subset;
        # queued first, as the longest fits of the step, so that the workers finish together
        calls["network", "full-length", i] = (experiments.regress_distance_full_length,
                                              (feats.fft_elliptic[rows], d), {"seed": s})
        calls["network", "linear-region", i] = (experiments.regress_distance_linear_region,
                                                (X, d), {"probe_length": probe_length(ds),
                                                         "seed": s})
    for c in CLASSIFIERS:
        for k in SPLITS:
            for i, split in enumerate(split_folds(k, y, d, folds=SPLIT_SEEDS, seed=seed)):
                calls[c, k, i] = classifier_call(FITTED[c], X, y, d, peaks, dominant, split)
                tested[c, k, i] = d
    for r in TRAINING_REPETITIONS:
        if r >= depth:
            continue
        sub = _subset(ds, r)
        d_sub = ds.contact[sub]
        for i, split in enumerate(split_folds("grouped", ds.material[sub], d_sub, seed=seed)):
            calls["repetitions", r, i] = (experiments.classify_materials_svm,
                                          (feats.fft[sub], ds.material[sub]), {"split": split})
            tested["repetitions", r, i] = d_sub
    done = dict(zip(calls, fits_in_parallel(list(calls.values()), n_jobs), strict=True))
    networks = {n: NetworkRuns.from_results(seeds, [done[key] for key in calls
                                                    if key[:2] == ("network", n)])
                for n in NETWORKS}

    def over_folds(head, unit, by_fold=False):
        keys = [key for key in calls if key[:2] == head]
        return FoldAccuracy([(done[key].correct(), tested[key][done[key].rows()]) for key in keys],
                            unit, by_fold=by_fold)

    spreads = {(c, k): over_folds((c, k), UNITS[k], by_fold=k == "blocked")
               for c in CLASSIFIERS for k in SPLITS}
    repetitions = {r: over_folds(("repetitions", r), UNITS["grouped"])
                   for r in TRAINING_REPETITIONS if r < depth}
    repetitions[depth] = grouped_full
    paired = None
    if answers is not None and len(repetitions) > 1:
        fewest = min(repetitions)
        sub = _subset(ds, fewest)
        few = answers_over_folds([done[key] for key in calls if key[:2] == ("repetitions",
                                                                             fewest)], sub.size)
        paired = PairedDifference.from_recordings(few, answers[sub], ds.contact[sub],
                                                  UNITS["grouped"], seed=seed)
    return SeedSpreadResult(spreads, int(rows.size), repetitions, min(SUBSET_REPETITIONS, depth),
                            paired, networks)


def _check_answers(answers, ds, grouped_full: FoldAccuracy) -> np.ndarray:
    """``answers`` as one bool per recording of ``ds``, agreeing with ``grouped_full``."""
    a = np.asarray(answers)
    if a.dtype != bool or a.shape != (len(ds.material),):
        raise ValueError(f"grouped_answers must hold one bool per recording of ds "
                         f"({len(ds.material)}), got dtype {a.dtype} and shape {a.shape}")
    n = grouped_full.n_recordings
    k = correct_count(grouped_full.pooled.estimate, n)
    if (a.size, int(a.sum())) != (n, k):
        raise ValueError(f"grouped_answers and grouped_full describe different runs: "
                         f"{int(a.sum())} of {a.size} right against {k} of {n}")
    return a


def render(result: SeedSpreadResult, report, figures) -> None:
    """The folds' spread against the binomial one, and the repetitions' table."""
    check_render(result, SeedSpreadResult, report, figures)
    report.heading("How much the numbers carry: folds, clusters and repetitions")
    report.paragraph(
        "Every recording is tested once over the folds of a split. Were the recordings "
        "independent trials, the folds' accuracies would scatter by the binomial standard "
        "deviation sqrt(p (1 - p) / m) of a fold of m recordings; the ratio of the folds' "
        "standard deviation to it tests that, within what a spread measured on "
        f"{SPLIT_SEEDS} folds leaves open (a chi-square interval on {SPLIT_SEEDS - 1} degrees "
        "of freedom). Below, every classifier on every split over its "
        f"{SPLIT_SEEDS} folds, on the first {result.subset_repetitions} repetitions of every "
        "position "
        f"({result.subset_recordings} recordings, to keep the "
        f"{len(CLASSIFIERS) * len(SPLITS) * SPLIT_SEEDS} fits short): the accuracy with its "
        "interval on the split's unit, the folds' standard deviation, and how many times the "
        "binomial one it is."
    )
    rows, ratios = [], []
    for c in CLASSIFIERS:
        for kind in SPLITS:
            f: FoldAccuracy = result.spreads[c, kind]
            b = binomial_std(f)
            ratio = f"{f.spread / b:.1f} x" if b > 0 else "-"
            rows.append([c, kind, format_clustered(f), percent(f.spread), percent(b), ratio])
            ratios.append((f"the {c} on the {kind} split", f.spread / b if b > 0 else None,
                           f.values.size))
    report.table(["classifier", "split", "over all folds (95 % CI on the unit)",
                  "folds' std", "binomial std", "ratio"], rows)
    report.paragraph(scatter_sentence(ratios))
    if result.networks:
        _render_networks(result, report)
    report.paragraph(
        "Below, the grouped split (all folds) of the main data set with only its first "
        "repetitions of every position: what the number of recordings of each position the SVM "
        "learns from changes on whole held-out positions. The controls' reduced design carries "
        "fewer repetitions per position than the main data set: its baseline reads against the "
        "row of its own number of repetitions. The interval is on the position: more "
        "repetitions add recordings, not positions."
    )
    report.table(
        ["repetitions per position", "grouped SVM test accuracy", "design effect"],
        [[str(r), format_clustered(a), f"{a.pooled.design_effect:.1f}"]
         for r, a in sorted(result.repetitions.items())],
    )
    report.paragraph(repetitions_sentence(result.repetitions, result.paired_repetitions))


def _render_networks(result: SeedSpreadResult, report) -> None:
    """The distance networks trained again: their runs' spread against one run's interval."""
    runs = next(iter(result.networks.values()))
    report.paragraph(
        "The study trains each network once, and a network's interval over its test positions "
        "holds the trained network fixed. Below, the two distance networks trained again from "
        f"{runs.mae_cm.size} seeds (seeds {runs.seeds[0]} to {runs.seeds[-1]}, each its own "
        "split and starting weights) on the same subset: the mean error over the test "
        "positions (min to max over the runs), the runs' standard deviation, the standard "
        "error one run's interval allows (root mean square over the runs), and the ratio of "
        "the runs' spread to it, with its 95 % interval from the runs' number. The runs' "
        "random splits test mostly the same positions, so their spread leaves out most of what "
        "the interval counts (which positions happen to be tested): a ratio above one is "
        "training spread beyond all of the interval, and a ratio below one is what a training "
        "that adds little gives."
    )
    rows = []
    for name, r in result.networks.items():
        if r.ratio is None:
            ratio = "-"
        else:
            lo, hi = ratio_interval(r.ratio, r.mae_cm.size)
            ratio = f"{r.ratio:.1f} x ({lo:.1f} to {hi:.1f})"
        rows.append([name, f"{np.mean(r.mae_cm):.2f} ({np.min(r.mae_cm):.2f} to "
                     f"{np.max(r.mae_cm):.2f})", f"{r.spread:.2f}",
                     f"{r.interval_std:.2f}" if np.isfinite(r.interval_std) else "-",
                     ratio])
    report.table(["distance network", "mean error over runs (cm, min to max)", "runs' std (cm)",
                  "one run's standard error (cm)", "ratio"], rows)
    report.paragraph(runs_sentence(result.networks))
