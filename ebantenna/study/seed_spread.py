"""Section 6b': how much the material classifiers' numbers carry.

Every classifier on every split over all the split's folds, with the folds' spread beside the
spread binomial sampling would give, and the grouped split with fewer repetitions per position.
A fit of the paper's SVM on the whole data set's training rows takes tens of seconds, so the
folds of all three classifiers run on the data set's first :data:`SUBSET_REPETITIONS`
repetitions (every position and material, a fifth of the recordings).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..paper import experiments
from ..paper.splits import SPLITS, split_folds
from ..paper.uncertainty import UNITS, FoldAccuracy, clustered_entries, format_clustered, percent
from ._common import check_instance, check_render, check_step, classifier_call, fits_in_parallel

__all__ = ["SPLIT_SEEDS", "SUBSET_REPETITIONS", "TRAINING_REPETITIONS", "CLASSIFIERS",
           "SeedSpreadResult", "compute", "render"]

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
    """

    spreads: dict
    subset_recordings: int
    repetitions: dict

    def to_dict(self) -> dict:
        """Under ``materials``: ``seed_spread`` (classifier -> split -> the accuracy over the
        folds, with ``binomial_std``, the spread the folds would show were the recordings
        independent, and ``spread_ratio``) and ``svm_grouped_by_repetitions``."""
        spread = {c: {k: _spread_dict(self.spreads[c, k]) for k in SPLITS} for c in CLASSIFIERS}
        return {
            "seed_spread": {"subset_recordings": self.subset_recordings, **spread},
            "svm_grouped_by_repetitions": {
                str(r): clustered_entries("accuracy", a) for r, a in self.repetitions.items()
            },
        }


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


def _spread_dict(f: FoldAccuracy) -> dict:
    b = binomial_std(f)
    return {**clustered_entries("accuracy", f), "binomial_std": b,
            "spread_ratio": f.spread / b if b > 0 else None}


def _subset(ds, repetitions: int) -> np.ndarray:
    """Rows of the first ``repetitions`` repetitions of every position and material."""
    return np.flatnonzero(np.asarray(ds.repetition) < repetitions)


def compute(ds, feats, seed: int, grouped_full: FoldAccuracy, n_jobs: int = 1) -> SeedSpreadResult:
    """The three classifiers on every fold of the three splits (on the subset), and the grouped
    SVM over all folds on 1, 3, 5 repetitions; ``grouped_full`` is the whole data set's grouped
    SVM over its folds, already measured. Every fit runs on one of ``n_jobs`` worker processes
    (``_common.fits_in_parallel``): the same numbers whatever ``n_jobs``."""
    check_step(ds=ds, feats=feats, seed=seed, n_jobs=n_jobs)
    check_instance("grouped_full", grouped_full, FoldAccuracy)
    rows = _subset(ds, SUBSET_REPETITIONS)
    X, y, d = feats.fft[rows], ds.material[rows], ds.contact[rows]
    peaks, dominant = feats.peaks[rows], feats.dominant[rows]
    calls, tested = {}, {}  # every fit of the step, and the positions of its data's rows
    for c in CLASSIFIERS:
        for k in SPLITS:
            for i, split in enumerate(split_folds(k, y, d, folds=SPLIT_SEEDS, seed=seed)):
                calls[c, k, i] = classifier_call(FITTED[c], X, y, d, peaks, dominant, split)
                tested[c, k, i] = d
    depth = int(np.max(ds.repetition)) + 1
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

    def over_folds(head, unit, by_fold=False):
        keys = [key for key in calls if key[:2] == head]
        return FoldAccuracy([(done[key].correct(), tested[key][done[key].rows()]) for key in keys],
                            unit, by_fold=by_fold)

    spreads = {(c, k): over_folds((c, k), UNITS[k], by_fold=k == "blocked")
               for c in CLASSIFIERS for k in SPLITS}
    repetitions = {r: over_folds(("repetitions", r), UNITS["grouped"])
                   for r in TRAINING_REPETITIONS if r < depth}
    repetitions[depth] = grouped_full
    return SeedSpreadResult(spreads, int(rows.size), repetitions)


def render(result: SeedSpreadResult, report, figures) -> None:
    """The folds' spread against the binomial one, and the repetitions' table."""
    check_render(result, SeedSpreadResult, report, figures)
    report.heading("How much the numbers carry: folds, clusters and repetitions")
    report.paragraph(
        "Every recording is tested once over the folds of a split. Were the recordings "
        "independent trials, the folds' accuracies would scatter by the binomial standard "
        "deviation sqrt(p (1 - p) / m) of a fold of m recordings; they scatter more, because the "
        "repetitions at one position are near copies and the split draws whole positions. "
        "Below, every classifier on every split over its "
        f"{SPLIT_SEEDS} folds, on the first {SUBSET_REPETITIONS} repetitions of every position "
        f"({result.subset_recordings} recordings; a fit of the paper's SVM on the whole data "
        "set takes tens of seconds): the accuracy with its interval on the split's unit, the "
        "folds' standard deviation, and how many times the binomial one it is."
    )
    rows = []
    for c in CLASSIFIERS:
        for kind in SPLITS:
            f: FoldAccuracy = result.spreads[c, kind]
            b = binomial_std(f)
            ratio = f"{f.spread / b:.1f} x" if b > 0 else "-"
            rows.append([c, kind, format_clustered(f), percent(f.spread), percent(b), ratio])
    report.table(["classifier", "split", "over all folds (95 % CI on the unit)",
                  "folds' std", "binomial std", "ratio"], rows)
    report.paragraph(
        "How many recordings of each position the SVM learns from matters on whole held-out "
        "positions: below, the grouped split (all folds) of the main data set with only its "
        "first repetitions of every position. The controls' reduced design and the main data "
        "set differ in this, not in the physics: the controls' baseline sits where its number "
        "of repetitions puts it on this table. The interval is on the position: more "
        "repetitions add recordings, not positions, so it narrows far less than the count of "
        "recordings suggests."
    )
    report.table(
        ["repetitions per position", "grouped SVM test accuracy", "design effect"],
        [[str(r), format_clustered(a), f"{a.pooled.design_effect:.1f}"]
         for r, a in sorted(result.repetitions.items())],
    )
