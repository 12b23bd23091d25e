"""Section 6b': how much the material classifiers' numbers carry.

Every split's accuracy is measured once more over five split seeds, and the grouped split with
fewer repetitions per position. A fit of the paper's SVM on the whole data set's training rows
takes tens of seconds, so the repetitions over seeds run on the data set's first
:data:`SUBSET_REPETITIONS` repetitions (every position and material, a fifth of the recordings):
its grouped test set still holds about 400 recordings, two standard deviations of about 4.5
points at 70 %.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..paper import experiments
from ..paper.mode_curves import classify_materials_by_mode_curves
from ..paper.position_aware import classify_materials_position_aware
from ..paper.splits import SPLITS, distinct_split_seeds, grouped_split, split_rows
from ..paper.uncertainty import SeedSpread, accuracy_entries, format_interval, seed_spread

__all__ = ["SPLIT_SEEDS", "SUBSET_REPETITIONS", "TRAINING_REPETITIONS", "CLASSIFIERS",
           "SeedSpreadResult", "compute", "render"]

#: Split seeds per classifier and split, from ``seed`` up, each holding out other recordings
#: (:func:`~ebantenna.paper.splits.distinct_split_seeds`).
SPLIT_SEEDS = 5
#: Repetitions per position of the subset the seeds are repeated on.
SUBSET_REPETITIONS = 5
#: Repetitions per position kept for the grouped accuracy against the training size.
TRAINING_REPETITIONS = (1, 3, 5)
#: The classifiers repeated over the seeds, by the name the report gives them.
CLASSIFIERS = ("paper's SVM", "position-aware", "mode curves")


@dataclass(frozen=True, eq=False)
class SeedSpreadResult:
    """The classifiers over the split seeds, and the grouped SVM against the repetitions.

    Attributes
    ----------
    spreads : dict of (str, str) to SeedSpread
        By (classifier of :data:`CLASSIFIERS`, split of :data:`SPLITS`).
    subset_recordings : int
        Recordings of the subset (its first :data:`SUBSET_REPETITIONS` repetitions).
    repetitions : dict of int to (float, int)
        Grouped SVM accuracy and test count (split seed ``seed``) on the first ``r``
        repetitions of each position, for ``r`` in :data:`TRAINING_REPETITIONS` and the whole
        data set.
    """

    spreads: dict
    subset_recordings: int
    repetitions: dict

    def to_dict(self) -> dict:
        """Under ``materials``: ``seed_spread`` (classifier -> split -> spread) and
        ``svm_grouped_by_repetitions``."""
        spread = {c: {k: self.spreads[c, k].to_dict() for k in SPLITS} for c in CLASSIFIERS}
        return {
            "seed_spread": {"subset_recordings": self.subset_recordings, **spread},
            "svm_grouped_by_repetitions": {
                str(r): accuracy_entries("accuracy", a, n) for r, (a, n) in self.repetitions.items()
            },
        }


def _subset(ds, repetitions: int) -> np.ndarray:
    """Rows of the first ``repetitions`` repetitions of every position and material."""
    return np.flatnonzero(np.asarray(ds.repetition) < repetitions)


def compute(ds, feats, seed: int, grouped_full: tuple[float, int]) -> SeedSpreadResult:
    """The three classifiers on the three splits over the split seeds (on the subset), and the
    grouped SVM on 1, 3, 5 repetitions; ``grouped_full`` is the whole data set's grouped SVM
    (accuracy, test count), already measured."""
    rows = _subset(ds, SUBSET_REPETITIONS)
    X, y, d = feats.fft[rows], ds.material[rows], ds.contact[rows]
    peaks, dominant = feats.peaks[rows], feats.dominant[rows]

    def run(classifier, kind):
        def measure(s):
            split = split_rows(kind, y, d, seed=s)
            if classifier == CLASSIFIERS[0]:
                r = experiments.classify_materials_svm(X, y, split=split)
            elif classifier == CLASSIFIERS[1]:
                r = classify_materials_position_aware(X, y, d, peaks, dominant, split)
            else:
                r = classify_materials_by_mode_curves(peaks, dominant, y, d, split)
            return r.accuracies["test"], r.counts["test"]
        return seed_spread(
            measure, distinct_split_seeds(kind, y, d, seed=seed, count=SPLIT_SEEDS)
        )

    spreads = {(c, k): run(c, k) for c in CLASSIFIERS for k in SPLITS}
    repetitions = {}
    for r in TRAINING_REPETITIONS:
        if r >= int(np.max(ds.repetition)) + 1:
            continue
        sub = _subset(ds, r)
        result = experiments.classify_materials_svm(
            feats.fft[sub], ds.material[sub], split=grouped_split(ds.contact[sub], seed=seed)
        )
        repetitions[r] = (result.accuracies["test"], result.counts["test"])
    repetitions[int(np.max(ds.repetition)) + 1] = tuple(grouped_full)
    return SeedSpreadResult(spreads, int(rows.size), repetitions)


def render(result: SeedSpreadResult, report, figures) -> None:
    """The spread over the seeds beside the seed-0 values, and the repetitions' table."""
    report.heading("How much the numbers carry: split seeds and repetitions")
    report.paragraph(
        f"Each accuracy above was measured on one split (seed 0), with its Wilson 95 % "
        "interval. A second measure of its uncertainty is its spread when the split is drawn "
        f"again: below, every classifier on every split over {SPLIT_SEEDS} split seeds (mean ± "
        "sample standard deviation). A fit of the paper's SVM on the whole data set takes tens "
        "of seconds, so the seeds are repeated on its first "
        f"{SUBSET_REPETITIONS} repetitions of every position ({result.subset_recordings} "
        "recordings); the column 'seed 0' is that subset's own seed-0 value. The seeds are "
        "taken from 0 upwards, skipping any that would repeat a split: the grouped split's "
        "five seeds then hold out each position once."
    )
    rows = []
    for c in CLASSIFIERS:
        for kind in SPLITS:
            s: SeedSpread = result.spreads[c, kind]
            rows.append([c, kind, format_interval(float(s.values[0]), int(s.n_test[0])), str(s)])
    report.table(["classifier", "split", "seed 0 (subset)", f"over {SPLIT_SEEDS} split seeds"],
                 rows)
    report.paragraph(
        "How many recordings of each position the SVM learns from matters on whole held-out "
        "positions: below, the grouped split (seed 0) of the main data set with only its first "
        "repetitions of every position. The controls' reduced design and the main data set "
        "differ in this, not in the physics: the controls' baseline sits where its number of "
        "repetitions puts it on this table."
    )
    report.table(
        ["repetitions per position", "grouped SVM test accuracy"],
        [[str(r), format_interval(a, n)] for r, (a, n) in sorted(result.repetitions.items())],
    )
