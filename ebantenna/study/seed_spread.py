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
from ..paper.mode_curves import classify_materials_by_mode_curves
from ..paper.position_aware import classify_materials_position_aware
from ..paper.splits import SPLITS, split_folds
from ..paper.uncertainty import UNITS, FoldAccuracy, clustered_entries, format_clustered, percent

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


def compute(ds, feats, seed: int, grouped_full: FoldAccuracy) -> SeedSpreadResult:
    """The three classifiers on every fold of the three splits (on the subset), and the grouped
    SVM over all folds on 1, 3, 5 repetitions; ``grouped_full`` is the whole data set's grouped
    SVM over its folds, already measured."""
    rows = _subset(ds, SUBSET_REPETITIONS)
    X, y, d = feats.fft[rows], ds.material[rows], ds.contact[rows]
    peaks, dominant = feats.peaks[rows], feats.dominant[rows]

    def run(classifier, kind):
        results = []
        for split in split_folds(kind, y, d, folds=SPLIT_SEEDS, seed=seed):
            if classifier == CLASSIFIERS[0]:
                r = experiments.classify_materials_svm(X, y, split=split)
            elif classifier == CLASSIFIERS[1]:
                r = classify_materials_position_aware(X, y, d, peaks, dominant, split)
            else:
                r = classify_materials_by_mode_curves(peaks, dominant, y, d, split)
            results.append(r)
        return FoldAccuracy([(r.correct(), d[r.rows()]) for r in results], UNITS[kind],
                            by_fold=kind == "blocked")

    spreads = {(c, k): run(c, k) for c in CLASSIFIERS for k in SPLITS}
    repetitions = {}
    for r in TRAINING_REPETITIONS:
        if r >= int(np.max(ds.repetition)) + 1:
            continue
        sub = _subset(ds, r)
        d_sub = ds.contact[sub]
        results = [
            experiments.classify_materials_svm(feats.fft[sub], ds.material[sub], split=split)
            for split in split_folds("grouped", ds.material[sub], d_sub, seed=seed)
        ]
        repetitions[r] = FoldAccuracy([(x.correct(), d_sub[x.rows()]) for x in results],
                                      UNITS["grouped"])
    repetitions[int(np.max(ds.repetition)) + 1] = grouped_full
    return SeedSpreadResult(spreads, int(rows.size), repetitions)


def render(result: SeedSpreadResult, report, figures) -> None:
    """The folds' spread against the binomial one, and the repetitions' table."""
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
