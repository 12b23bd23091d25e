"""Section 6b: the material classifier on three splits, a position-aware classifier, and the
networks with other trainers."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import check_bool
from ..paper import experiments, printed
from ..paper.protocol import DISTANCE_LINEAR_REGION
from ..paper.splits import FOLDS, SPLITS, split_folds, split_rows
from ..paper.uncertainty import (
    UNITS,
    ClusteredAccuracy,
    FoldAccuracy,
    PairedDifference,
    cluster_labels,
    clustered_entries,
    format_difference,
    percent,
    training_entries,
)
from ._common import (
    TRAINED_ONCE,
    check_instance,
    check_render,
    check_step,
    classifier_call,
    error_entry,
    fits_in_parallel,
    format_error,
    format_mae,
    format_paired_mae,
    listed,
    mae_entry,
    paired_mae,
    probe_length,
)

__all__ = ["MaterialSplitsResult", "TRAINERS", "STEP_SIZES", "CLASSIFIERS", "compute", "render"]

#: The trainers compared: the paper's gradient descent, scaled conjugate gradient and Adam.
TRAINERS = ("gd", "scg", "adam")
#: Step of each first-order trainer, at its textbook default and never tuned on this data:
#: gradient descent keeps the step the paper experiments use, Adam the 0.001 of Kingma & Ba
#: (2015, section 2); SCG chooses its own steps.
STEP_SIZES = {"ann": {"gd": 0.05, "adam": 0.001}, "distance": {"gd": 0.01, "adam": 0.001}}


@dataclass(frozen=True, eq=False)
class MaterialSplitsResult:
    """Classifiers on the three splits and the networks by trainer.

    Attributes
    ----------
    svm, position_aware, mode_curves : dict of str to ClassificationResult
        The paper's SVM, the position-aware classifier and the mode-curve classifier, per split
        of :data:`SPLITS`: the random split's one result, and for the grouped and blocked
        splits the first fold's (that of the split seed).
    held_out : dict of str to ndarray
        The nominal positions (m) the first fold of each split holds out (random: none).
    ann : dict of str to ClassificationResult
        The paper's 53-tanh network per trainer of :data:`TRAINERS`.
    distance : dict of str to RegressionResult
        The 2 x 20 tanh distance network on the first 80 % per trainer.
    measured : dict of (str, str) to ClusteredAccuracy or FoldAccuracy
        By (classifier of :data:`CLASSIFIERS`, split): the test accuracy with its interval on
        the split's unit (:data:`~ebantenna.paper.uncertainty.UNITS`); the grouped and blocked
        splits over all their folds. ``("ann", trainer)`` likewise for the networks.
    paired : dict of str to PairedDifference
        Per split held out (``"grouped"``, ``"blocked"``): the position-aware and the mode-curve
        classifiers against the paper's SVM on the same folds (``"position_aware"``,
        ``"mode_curves"``).
    distance_held_out : RegressionResult or None
        The paper's distance network (gradient descent) trained with whole positions held out,
        over every fold of the grouped split (``_region_folds``), beside its random
        split.
    grouped_answers : dict of str to ndarray or None
        Per classifier of :data:`CLASSIFIERS`: each recording of the data set right (True) or
        wrong on the grouped split, over its folds, which test every recording once
        (``answers_over_folds``): what a comparison paired on the same recordings reads.
    flattery : dict of str to PairedDifference or None
        Per classifier of :data:`CLASSIFIERS`: its random split (B) against whole positions held
        out (A), paired on the random split's own test recordings, each of which the grouped
        split tests once more in the fold that holds its position out
        (``random_against_grouped``).
    design : dict or None
        What the data set's design makes of a random split, read from the data set
        (``_design_facts``): ``repetitions`` (the fewest and the most recordings of one
        material at one contact position), ``spacing_m`` (the smallest distance between two
        distinct contact positions) and ``copies_in_training`` (the share of the random split's
        test recordings whose material and position have a recording in its training set).
    """

    svm: dict
    position_aware: dict
    mode_curves: dict
    held_out: dict
    ann: dict
    distance: dict
    measured: dict = None
    paired: dict = None
    distance_held_out: object = None
    design: dict | None = None
    flattery: dict | None = None
    grouped_answers: dict | None = None

    @property
    def distance_ranking(self) -> tuple[str, dict]:
        """The trainer with the smallest distance error, and each other trainer's errors against
        its, paired on the same test recordings and taken on the test positions
        (``paired_mae``; None for a network tested on other rows).
        The smallest is a ranking of this run, not a finding, unless every difference is
        resolved."""
        smallest = min(self.distance, key=lambda k: self.distance[k].mae_cm)
        base = self.distance[smallest]
        against = {}
        for k, r in self.distance.items():
            same = (r.test_rows is not None and base.test_rows is not None
                    and np.array_equal(r.test_rows, base.test_rows))
            if k != smallest:
                against[k] = (paired_mae(r.errors_cm, base.errors_cm, r.distance_test) if same
                              else None)
        return smallest, against

    def to_dict(self) -> dict:
        """``materials`` (accuracies, fractions, each with its test count ``*_n_test``, unit,
        number of units, 95 % interval on the unit ``*_ci95`` and its method, and the
        recording-level Wilson interval ``*_recording_ci95``; the training accuracy with its
        count only) and ``distance`` (MAE by trainer, cm)."""
        svm, m = self.svm, self.measured
        train = svm["random"]
        materials = {
            **training_entries("svm_random_train_accuracy", train.accuracies["train"],
                               train.counts["train"]),
        }
        for kind in SPLITS:
            materials.update(clustered_entries(SVM_KEYS[kind], m["svm", kind]))
        for name, key in (("position_aware_test_accuracy", "position_aware"),
                          ("mode_curve_test_accuracy", "mode_curves")):
            materials.update(clustered_entries(name, {k: m[key, k] for k in SPLITS}))
        materials.update(clustered_entries("ann", {k: m["ann", k] for k in self.ann}))
        materials["splits_against_svm"] = {
            kind: {k: p.to_dict() for k, p in pairs.items()}
            for kind, pairs in (self.paired or {}).items()
        }
        if self.flattery is not None:
            materials["random_against_grouped"] = {c: p.to_dict()
                                                   for c, p in self.flattery.items()}
        for name, first in (("svm_grouped_test_confusion", svm["grouped"]),
                            ("mode_curve_grouped_test_confusion", self.mode_curves["grouped"])):
            materials[name] = {"labels": list(first.labels),
                               "counts": first.confusions["test"].astype(int).tolist(),
                               "fold": 0}
        smallest, against = self.distance_ranking
        distance = {
            "linear_region_mae_cm_by_trainer": {k: r.mae_cm for k, r in self.distance.items()},
            "linear_region_by_trainer": {k: _distance_entry(r) for k, r in self.distance.items()},
            "linear_region_smallest_error_trainer": smallest,
            "linear_region_against_smallest": against,
            "linear_region_random_split": _distance_entry(self.distance["gd"]),
            # the table's RMS column, with its interval on the test position (a bootstrap)
            "linear_region_rms_by_trainer": {k: error_entry(r.errors_cm, r.distance_test, "rms")
                                             for k, r in self.distance.items()},
        }
        if self.distance_held_out is not None:
            distance["linear_region_positions_held_out"] = _distance_entry(
                self.distance_held_out)
            distance["linear_region_held_out_against_random"] = held_out_against_random(
                self.distance["gd"], self.distance_held_out)
        if self.design is not None:
            materials["random_split_design"] = dict(self.design)
        return {"materials": materials, "distance": distance}


def _distance_entry(r) -> dict:
    """A distance network's mean absolute error (cm) with its interval over the test
    positions (``mae_entry``)."""
    return mae_entry(r.errors_cm, r.distance_test)


def _design_facts(materials, positions, test_rows) -> dict:
    """What a random split of a data set's design holds, read from its rows: ``repetitions``
    (``[fewest, most]`` recordings of one material at one contact position), ``spacing_m`` (the
    smallest step between two distinct contact positions, m; None with one position) and
    ``copies_in_training`` (the share of the test rows ``test_rows`` whose material and
    position have a recording among the other rows, the training set).

    Examples
    --------
    >>> facts = _design_facts(["a", "a", "a", "b", "b", "b"], [0.1, 0.1, 0.2, 0.1, 0.2, 0.2],
    ...                      [2, 3])
    >>> facts["repetitions"], facts["spacing_m"], facts["copies_in_training"]
    ([1, 2], 0.1, 0.0)
    """
    groups = cluster_labels(materials, positions)
    counts = np.bincount(groups)
    grid = np.unique(np.asarray(positions, dtype=float))
    test = np.zeros(groups.size, dtype=bool)
    test[np.asarray(test_rows, dtype=int)] = True
    in_training = np.isin(groups[test], groups[~test])
    return {"repetitions": [int(counts.min()), int(counts.max())],
            "spacing_m": float(np.diff(grid).min()) if grid.size > 1 else None,
            "copies_in_training": float(in_training.mean()) if in_training.size else None}


#: The paper SVM's test accuracy on each split, by its key in ``summary.json``.
SVM_KEYS = {"random": "svm_random_test_accuracy", "grouped": "svm_grouped_test_accuracy",
            "blocked": "svm_blocked_test_accuracy"}

#: The classifiers of this section, by the key of ``MaterialSplitsResult.measured``.
CLASSIFIERS = ("svm", "position_aware", "mode_curves")
#: Each classifier's column heading in the report.
_HEADINGS = {"svm": "paper's SVM", "position_aware": "position-aware",
             "mode_curves": "mode curves"}


def measured_over_folds(results, positions, kind: str):
    """A classifier's results on the folds of split ``kind`` as one accuracy on the split's
    unit: :class:`~ebantenna.paper.uncertainty.ClusteredAccuracy` for one result (the random
    split), :class:`~ebantenna.paper.uncertainty.FoldAccuracy` for the folds (the blocked
    split's unit is the fold itself)."""
    unit = UNITS[kind]
    positions = np.asarray(positions)
    if len(results) == 1:
        r = results[0]
        return ClusteredAccuracy.from_recordings(r.correct(), positions[r.rows()], unit)
    return FoldAccuracy([(r.correct(), positions[r.rows()]) for r in results], unit,
                        by_fold=kind == "blocked")


def paired_over_folds(reference, other, positions, kind: str) -> PairedDifference:
    """``other`` against ``reference``, the same recordings of the same folds of ``kind``,
    paired within the split's unit (a fold of the blocked split, a position otherwise); on the
    blocked split the accuracies are the folds' means, as :func:`measured_over_folds` gives
    them there."""
    positions = np.asarray(positions)
    a, b, clusters = [], [], []
    for i, (ra, rb) in enumerate(zip(reference, other, strict=True)):
        if not np.array_equal(ra.rows(), rb.rows()):
            raise ValueError("the two classifiers were not tested on the same recordings")
        a.append(ra.correct())
        b.append(rb.correct())
        clusters.append(np.full(ra.rows().size, i) if kind == "blocked"
                        else positions[ra.rows()])
    return PairedDifference.from_recordings(np.concatenate(a), np.concatenate(b),
                                            np.concatenate(clusters), UNITS[kind],
                                            by_fold=kind == "blocked")


def compute(ds, feats, seed: int, *, random_svm, paper_ann, paper_distance,
            n_jobs: int = 1) -> MaterialSplitsResult:
    """Train and test on the three splits and with the three trainers.

    ``random_svm``, ``paper_ann`` and ``paper_distance`` are the paper's experiments already run
    by :mod:`.learning` (random split, gradient descent): they are reused, not run again. The
    grouped and blocked splits run over all their folds
    (:func:`~ebantenna.paper.splits.split_folds`). Every fit is independent of the others and
    runs on one of ``n_jobs`` worker processes (``_common.fits_in_parallel``): the same
    numbers whatever ``n_jobs``.
    """
    check_step(ds=ds, feats=feats, seed=seed, n_jobs=n_jobs)
    check_instance("random_svm", random_svm, experiments.ClassificationResult)
    check_instance("paper_ann", paper_ann, experiments.ClassificationResult)
    check_instance("paper_distance", paper_distance, experiments.RegressionResult)
    X, y, positions = feats.fft, ds.material, ds.contact
    length = probe_length(ds)
    folds = {kind: ([split_rows(kind, y, positions, seed=seed)] if kind == "random"
                    else split_folds(kind, y, positions, seed=seed)) for kind in SPLITS}
    held = {kind: np.array([]) if kind == "random" else np.unique(positions[f[0][1]])
            for kind, f in folds.items()}
    regions = _region_folds(folds["grouped"], positions, length)
    calls = {}  # key -> (function, args, kwargs), every fit of the step
    for kind in SPLITS:
        for c in CLASSIFIERS:
            if not (c == "svm" and kind == "random"):  # the paper's, run by .learning
                for i, split in enumerate(folds[kind]):
                    calls[c, kind, i] = classifier_call(c, X, y, positions, feats.peaks,
                                                        feats.dominant, split)
    for trainer in TRAINERS[1:]:
        calls["ann", trainer] = (experiments.classify_materials_ann, (X, y), dict(
            solver=trainer, seed=seed,
            learning_rate_init=STEP_SIZES["ann"].get(trainer, 0.001)))
        calls["distance", trainer] = (experiments.regress_distance_linear_region, (X, positions),
                                      dict(probe_length=length, solver=trainer, seed=seed,
                                           learning_rate_init=STEP_SIZES["distance"].get(
                                               trainer, 0.001)))
    for i, split in enumerate(regions):
        calls["held_out", i] = (experiments.regress_distance_linear_region, (X, positions),
                                dict(probe_length=length, seed=seed, split=split))
    done = dict(zip(calls, fits_in_parallel(list(calls.values()), n_jobs), strict=True))
    by_fold = {(c, kind): [random_svm] if (c, kind) == ("svm", "random") else
               [done[c, kind, i] for i in range(len(folds[kind]))]
               for kind in SPLITS for c in CLASSIFIERS}
    measured = {key: measured_over_folds(r, positions, key[1]) for key, r in by_fold.items()}
    paired = {kind: {c: paired_over_folds(by_fold["svm", kind], by_fold[c, kind], positions, kind)
                     for c in CLASSIFIERS[1:]} for kind in ("grouped", "blocked")}
    ann = {"gd": paper_ann, **{t: done["ann", t] for t in TRAINERS[1:]}}
    distance = {"gd": paper_distance, **{t: done["distance", t] for t in TRAINERS[1:]}}
    for trainer, a in ann.items():
        measured["ann", trainer] = ClusteredAccuracy.from_recordings(
            a.correct(), positions[a.rows()], UNITS["random"])
    held_out = _pooled_distance([done["held_out", i] for i in range(len(regions))])
    first = {key: r[0] for key, r in by_fold.items()}
    answers = {c: answers_over_folds(by_fold[c, "grouped"], y.size) for c in CLASSIFIERS}
    flattery = {c: random_against_grouped(by_fold[c, "random"][0], answers[c], positions)
                for c in CLASSIFIERS}
    return MaterialSplitsResult(
        {k: first["svm", k] for k in SPLITS}, {k: first["position_aware", k] for k in SPLITS},
        {k: first["mode_curves", k] for k in SPLITS}, held, ann, distance, measured, paired,
        held_out, _design_facts(y, positions, random_svm.rows()), flattery, answers)


def answers_over_folds(folds, n_rows: int) -> np.ndarray:
    """Each of ``n_rows`` recordings right (True) or wrong over ``folds``, results of folds
    that test every recording once (the grouped split's)."""
    answer = np.zeros(n_rows, dtype=bool)
    times = np.zeros(n_rows, dtype=int)
    for fold in folds:
        answer[fold.rows()] = fold.correct()
        times[fold.rows()] += 1
    if np.any(times != 1):
        raise ValueError(f"the folds test {np.count_nonzero(times == 0)} recordings never and "
                         f"{np.count_nonzero(times > 1)} more than once: they do not test every "
                         "recording once")
    return answer


def random_against_grouped(random, grouped, positions) -> PairedDifference:
    """A classifier's random split (B) against its grouped split (A), paired on the random
    split's test recordings: the grouped split's folds test every recording once (``grouped``,
    each recording's answer there, ``answers_over_folds``), so each of them has an answer from
    a network that saw other repetitions of its position (B) and one from a network that saw
    none (A). Clustered on the position."""
    rows = random.rows()
    return PairedDifference.from_recordings(np.asarray(grouped)[rows], random.correct(),
                                            np.asarray(positions)[rows], UNITS["grouped"])


def _region_folds(folds, positions, probe_length: float) -> list:
    """Those of the grouped split's ``folds`` that hold out a position of the distance network's
    linear region. A fold whose held-out positions all lie beyond the region has nothing to
    test and is left out (it happens only on designs with few positions)."""
    positions = np.asarray(positions)
    region = DISTANCE_LINEAR_REGION.region * probe_length
    return [(tr, te) for tr, te in folds if np.any(positions[te] <= region)]


def _pooled_distance(runs):
    """The distance networks of :func:`_region_folds`, their test predictions pooled into one
    :class:`~ebantenna.paper.experiments.RegressionResult`: every position of the region held
    out in exactly one fold. Its interval is taken over the test positions
    (:func:`_distance_entry`)."""
    truth = np.concatenate([r.distance_test for r in runs])
    predicted = np.concatenate([r.predicted_test for r in runs])
    at = np.unique(truth)
    errors = 100.0 * np.abs(predicted - truth)
    rows = (None if any(r.test_rows is None for r in runs)
            else np.concatenate([r.test_rows for r in runs]))
    return experiments.RegressionResult(
        f"{runs[0].name}, {len(runs)} folds of whole positions held out", truth, predicted, at,
        np.array([errors[truth == p].mean() for p in at]), sum(r.fit_seconds for r in runs),
        test_rows=rows)


def held_out_against_random(random, held_out) -> dict | None:
    """How much more the distance network errs with its test positions held out than on the
    random split, paired on the random split's own test recordings (each is tested once more
    by the fold that holds its position out) and taken on their positions
    (:func:`~ebantenna.study._common.paired_mae`); None where the two share no test recording
    or a result does not name its test rows."""
    if random.test_rows is None or held_out.test_rows is None:
        return None
    common, in_random, in_held = np.intersect1d(random.test_rows, held_out.test_rows,
                                                return_indices=True)
    if common.size == 0:
        return None
    return paired_mae(held_out.errors_cm[in_held], random.errors_cm[in_random],
                      random.distance_test[in_random])


def _positions_cm(p) -> str:
    return ", ".join(f"{100 * v:g}" for v in p) if p.size else "none as a whole"


def render(result: MaterialSplitsResult, report, figures, *, simulated: bool = True) -> None:
    """The three splits side by side, the position-aware classifier, the mode-curve classifier
    and the trainers, each a section of the report (``simulated``: the data come from the
    simulator, and the report names the simulator's assumptions it reads them through)."""
    check_render(result, MaterialSplitsResult, report, figures)
    check_bool("simulated", simulated)
    _render_splits(result, report)
    _render_position_aware(result, report)
    _render_mode_curves(result, report, figures, simulated)
    _render_trainers(result, report)


def _render_splits(r: MaterialSplitsResult, report) -> None:
    """Why a random split can flatter, and the classifiers on the three splits."""
    report.heading("Random recordings against held-out positions")
    report.paragraph(
        "The paper's 80/20 split (section 4.3) does not say how its test recordings were "
        "chosen; the study assumes they were drawn at random, as recordings. "
        + _copies_text(r.design)
        + " A classifier can then score by recognising the position and its recordings instead "
        "of the material, and look better on such a split than it will at a contact it has "
        "never seen. Holding out whole positions, interleaved (one position in "
        f"{FOLDS}, so the classifier interpolates between neighbours it has seen) or as one "
        "contiguous range (it must bridge a stretch of the probe it never saw), measures what "
        "the rig needs."
    )
    rows = []
    for kind in SPLITS:
        rows.append([kind, _folds_text(r, kind)]
                    + [str(r.measured[c, kind]) for c in CLASSIFIERS])
    report.table(
        ["split", "tested", *(_HEADINGS[c] for c in CLASSIFIERS)],
        rows,
    )
    report.paragraph(
        f"Paper, random split: {printed.percent(printed.SVM_TEST_ACCURACY)}. Chance: "
        f"{percent(1 / len(r.svm['random'].labels))}. " + _flattery(r) + " " + _units_text(r)
    )
    grouped = r.svm["grouped"]
    report.paragraph(
        "The paper's SVM on whole held-out positions (grouped split, its first fold): its "
        "confusion matrix, rows the true material, columns the predicted one. "
        + _confusions_text(grouped.confusions["test"], grouped.labels)
    )
    report.preformatted(
        experiments.format_confusion(grouped.confusions["test"], grouped.labels)
    )


def _copies_text(design: dict | None) -> str:
    """How the data set's recordings come and what a random split therefore leaves in its
    training set, read from ``_design_facts``.

    Examples
    --------
    >>> text = _copies_text({"repetitions": [3, 3], "spacing_m": 0.05,
    ...                      "copies_in_training": 0.9})
    >>> text.split(", and ")[0]
    'Here its recordings come 3 at a time from one material at one nominal contact position'
    >>> text.split(", and ")[1].split(":")[0]
    'neighbouring positions are 5 cm apart'
    >>> text.split(": ")[1][:6]
    '90.0 %'
    >>> "no other repetition" in _copies_text({"repetitions": [1, 1], "spacing_m": 0.005,
    ...                                        "copies_in_training": 0.0})
    True
    """
    if design is None:
        return ("Where a data set holds several recordings of one material at one contact "
                "position, a test recording can have a near copy of itself in the training set.")
    few, most = design["repetitions"]
    count = f"{few}" if few == most else f"{few} to {most}"
    step = design["spacing_m"]
    apart = ("" if step is None else
             f", and neighbouring positions are {_length_text(step)} apart")
    text = (f"Here its recordings come {count} at a time from one material at one nominal "
            f"contact position{apart}")
    share = design["copies_in_training"]
    if most < 2:
        return text + (": a test recording has no other repetition of its own position to "
                       "find in the training set, only its neighbours.")
    return text + (f": {percent(share)} of the random split's test recordings have a "
                   "recording of their own material and position (another repetition, a near "
                   "copy) in its training set.")


def _length_text(metres: float) -> str:
    """A distance in mm below 1 cm, else in cm.

    Examples
    --------
    >>> _length_text(0.005), _length_text(0.05)
    ('5 mm', '5 cm')
    """
    return f"{1e3 * metres:.3g} mm" if metres < 0.01 else f"{1e2 * metres:.3g} cm"


def _flattery(r: MaterialSplitsResult) -> str:
    """Which classifiers the random split flatters: its accuracy against whole positions held
    out, paired on its own test recordings (:func:`random_against_grouped`); a difference
    whose interval leaves out zero is resolved."""
    names = {"svm": "the paper's SVM", "position_aware": "the position-aware classifier",
             "mode_curves": "the mode curves"}
    pairs = r.flattery or {}
    above = [c for c in CLASSIFIERS if c in pairs and pairs[c].direction == "higher"]
    below = [c for c in CLASSIFIERS if c in pairs and pairs[c].direction == "lower"]
    alike = [c for c in CLASSIFIERS if c in pairs and pairs[c].identical]
    even = [c for c in CLASSIFIERS if c in pairs and c not in above + below + alike]

    def they(group, one, many):
        return one if len(group) == 1 else many

    def named(group):
        return listed(f"{names[c]}, by {format_difference(pairs[c])}" for c in group)

    words = []
    if above:
        words.append("Paired on the random split's own test recordings (each tested again by "
                     "the grouped fold that holds its position out), the random split scores "
                     "higher for " + named(above) + ": resolved, it flatters "
                     + they(above, "it", "them") + " here.")
    if below:
        words.append("The random split scores lower than whole positions held out for "
                     + named(below) + ": resolved.")
    if even:
        words.append("The paired difference is not resolved for " + named(even)
                     + ": this design does not show the random split flattering "
                     + they(even, "it.", "them."))
    if alike:
        words.append("For " + listed(names[c] for c in alike) + ", the random split and whole "
                     "positions held out count as many of its test recordings right in every "
                     "position: there is no difference to resolve.")
    return " ".join(words)


def _paired_text(pair) -> str:
    """A paired difference with its interval, or, where both count as many right in every
    cluster (``identical``), that: then there is no interval or verdict to give.

    Examples
    --------
    >>> from ebantenna.paper.uncertainty import PairedDifference
    >>> _paired_text(PairedDifference([2, 1], [2, 1], [3, 3], "position"))[:40]
    'as many right under both in each of the '
    """
    if pair.identical:
        return (f"as many right under both in each of the {pair.n_units} {pair.unit}s, so no "
                "difference to resolve")
    return format_difference(pair)


def _confusions_text(matrix, labels) -> str:
    """Each material's most frequent wrong answer, read from a confusion matrix (rows the true
    material): counts of one fold, not a finding about the materials.

    Examples
    --------
    >>> text = _confusions_text(np.array([[5, 3, 0], [0, 8, 0], [1, 0, 7]]), ["al", "pvc", "wood"])
    >>> text.split(": ")[1].split(";")[0]
    'al taken for pvc (3 of 8), wood taken for al (1 of 8)'
    >>> text.split("; ")[1].split(".")[0]
    'pvc is never taken for another'
    >>> _confusions_text(np.array([[0, 3, 3], [0, 6, 0], [0, 0, 6]]), ["st", "al", "pvc"])[46:]
    'st taken for al or pvc (3 of 6 each); al and pvc are never taken for another. Counts of \
one fold, not a finding about the materials.'
    """
    m = np.asarray(matrix)
    wrong, right = [], []
    for i, name in enumerate(labels):
        errors = m[i].copy()
        errors[i] = 0
        if errors.sum() == 0:
            right.append(str(name))
            continue
        most = [str(labels[j]) for j in np.flatnonzero(errors == errors.max())]  # ties: all
        wrong.append(f"{name} taken for {' or '.join(most)} ({errors.max()} of {m[i].sum()}"
                     + (" each)" if len(most) > 1 else ")"))
    if not wrong:
        return "It takes no material for another in this fold."
    text = "Its most frequent wrong answers in this fold: " + ", ".join(wrong)
    if right:
        text += (f"; {' and '.join(right)} {'is' if len(right) == 1 else 'are'} never taken for "
                 "another")
    return text + ". Counts of one fold, not a finding about the materials."


def _folds_text(r: MaterialSplitsResult, kind: str) -> str:
    """What a split's row of the table was tested on."""
    m = r.measured["svm", kind]
    if kind == "random":
        return "one 80/20 split of the recordings (the paper's)"
    per_fold = f"{r.held_out[kind].size} positions" if r.held_out[kind].size else "positions"
    return (f"all {m.values.size} folds, each recording once (first fold: {per_fold}, "
            f"{_positions_cm(r.held_out[kind])} cm)")


def _units_text(r: MaterialSplitsResult) -> str:
    """What each cell of the table gives, from the measured accuracies' own units and methods.

    Examples
    --------
    >>> from ebantenna.paper.uncertainty import ClusteredAccuracy
    >>> a = ClusteredAccuracy([5, 0, 5, 3], [5, 5, 5, 5], "position")
    >>> r = MaterialSplitsResult({}, {}, {}, {}, {}, {}, {("svm", "random"): a})
    >>> _units_text(r).split(": ")[1]
    'random split'
    """
    parts = []
    for (c, kind), m in r.measured.items():
        if c == "svm":
            effects = [f"{r.measured[k, kind].design_effect:.1f} ({_HEADINGS[k]})"
                       for k in CLASSIFIERS if hasattr(r.measured.get((k, kind)), "design_effect")]
            parts.append(f"{kind} split: {m.method}" + (
                f", design effect {listed(effects)}" if effects else ""))
    return (
        "Each accuracy is followed by its test recordings n, the independent units they come in "
        "and its 95 % interval on those units: " + "; ".join(parts) + ". The repetitions at "
        "one position share its physics (the design effects say how alike they are here), so "
        "the units, not the recordings, are what is replicated; the recording-level Wilson "
        "interval, which counts every recording as independent, is in summary.json only, "
        "labelled as such. The grouped and blocked rows "
        "are over all their folds, each recording tested once: the grouped split's accuracy "
        "pools the folds' recordings, the blocked split's is the mean of its folds' accuracies "
        "(its unit); after the interval, the folds' standard deviation."
    )


def _render_position_aware(r: MaterialSplitsResult, report) -> None:
    """The classifier that estimates the contact distance first, and what it gains."""
    report.heading("Beyond the paper: distance first, then material")
    report.paragraph(
        "The position-aware classifier first estimates the contact distance of a recording from "
        "its two strongest spectral peaks (the two-mode estimator of the full-range section, "
        "calibrated on the training positions only), then standardises every spectral bin by "
        "the mean and spread that all materials together show at that distance, and classifies "
        "what is left with the same RBF SVM. The standardisation is meant to subtract the "
        "probe's own modes, which move with the distance, and to keep what stays in place from "
        "one distance to the next, the touched object's own signature; whether it does is "
        "measured against the raw spectrum below, on the same folds."
    )
    report.paragraph(_lift(r))


def _render_mode_curves(r: MaterialSplitsResult, report, figures, simulated: bool) -> None:
    """Material and distance from the two strongest peaks, with the calibration curves."""
    name = _plot_mode_curves(r.mode_curves["random"].model, figures)
    report.heading("Beyond the paper: material and distance from two frequencies")
    report.paragraph(
        ("In the simulator the touched rod is part of the vibrating system (by assumption, the "
           "'object_modes' effect), so each material can draw its own curves"
           if simulated else "The touched object can move the probe's modes, so each material "
           "can draw its own curves")
        + " of the two strongest modes' frequencies against the contact distance. The mode-curve "
        "classifier calibrates these curves per material on the training positions (median over "
        "repetitions) and places each test recording's two peaks on every material's curves "
        "at once: the material whose curves pass closest, at the distance where they do, is the "
        "answer. Two numbers per recording instead of the spectrum's 256, and nothing learnt "
        "but the curves. " + _curves(r, simulated)
    )
    report.figure(
        name,
        "Each material's calibration curves (median over repetitions): the two strongest peaks "
        "against the contact distance. Where another mode becomes one of the two strongest ("
        + ("in the simulator, a coupled mode the rod brings" if simulated else
           "a mode of the probe or of what it touches")
        + "), a curve jumps to that mode's branch.",
    )


def _render_trainers(r: MaterialSplitsResult, report) -> None:
    """The paper's networks trained by gradient descent, scaled conjugate gradient and Adam."""
    report.heading("The networks with other trainers")
    report.paragraph(
        "The same 53-tanh network trained by the paper's full-batch gradient descent (with its "
        "validation check), by scaled conjugate gradient and by Adam (each in one run with "
        "early stopping on the same validation share). Steps: gradient descent "
        f"{STEP_SIZES['ann']['gd']:g}, Adam {STEP_SIZES['ann']['adam']:g} (its textbook "
        "default); nothing was tuned toward the paper's numbers, which are references only. "
        + TRAINED_ONCE.format(what="Each network is")
    )
    report.table(
        ["network", "trainer", "epochs", "test", "paper"],
        [
            [
                f"{len(a.labels)} materials, 53 tanh",
                k,
                str(len(getattr(a.model, "loss_curve_", ())) or a.model.n_iter_),
                str(r.measured["ann", k]),
                printed.percent(printed.ANN_ACCURACY) + " (all)",
            ]
            for k, a in r.ann.items()
        ],
    )
    smallest, against = r.distance_ranking
    report.table(
        ["distance network", "trainer", "MAE (cm)", "against the smallest (cm, paired)",
         "RMS (cm, 95 % CI: bootstrap over the test positions)", "fit time (s)"],
        [
            [
                "2 x 20 tanh, 0-80 % of L",
                k,
                format_mae(_distance_entry(d)),
                "smallest" if k == smallest else _paired_cm(against[k]),
                format_error(error_entry(d.errors_cm, d.distance_test, "rms"), "rms"),
                f"{d.fit_seconds:.1f}",
            ]
            for k, d in r.distance.items()
        ],
    )
    report.paragraph(_trainer_ranking(smallest, against))
    if r.distance_held_out is not None:
        report.paragraph(_distance_held_out(r))


def _paired_cm(d) -> str:
    """A ``paired_mae`` difference as the table prints it."""
    if d is None:
        return "not paired (other test rows)"
    if d["ci95"] is None:
        return f"{d['difference_cm']:+.2f} (one test position, no interval)"
    lo, hi = d["ci95"]
    return f"{d['difference_cm']:+.2f} (95 % CI {lo:+.2f} to {hi:+.2f}, {d['n_units']} positions)"


def _trainer_ranking(smallest: str, against: dict) -> str:
    """Which trainer's distance network errs least, and whether this design tells it from the
    others: generated from the paired differences.

    Examples
    --------
    >>> near = {"difference_cm": 0.02, "ci95": [-0.01, 0.05], "n_units": 64, "resolved": False}
    >>> far = {"difference_cm": 1.9, "ci95": [1.6, 2.2], "n_units": 64, "resolved": True}
    >>> text = _trainer_ranking("adam", {"gd": far, "scg": near})
    >>> text.split(". ")[0]
    'Adam has the smallest mean error in this run'
    >>> "errs less than gradient descent (resolved)" in text, "does not rank" in text
    (True, True)
    >>> "does not rank" in _trainer_ranking("adam", {"gd": far, "scg": far})
    False
    """
    names = {"gd": "gradient descent", "scg": "scaled conjugate gradient", "adam": "Adam",
             "sgd": "stochastic gradient descent"}

    def named(keys):
        return listed(names.get(k, k) for k in keys)

    resolved = [k for k, d in against.items() if d is not None and d["resolved"]]
    tied = [k for k, d in against.items() if d is not None and not d["resolved"]]
    unpaired = [k for k, d in against.items() if d is None]
    first = names.get(smallest, smallest)
    text = f"{first[0].upper()}{first[1:]} has the smallest mean error in this run."
    if resolved or tied:
        text += " Paired on the same test recordings and taken on the test positions, "
    if resolved:
        text += f"it errs less than {named(resolved)} (resolved)"
        text += "; " if tied else "."
    if tied:
        text += (f"this design does not tell it apart from {named(tied)} (the interval "
                 f"includes 0), so this run does not rank "
                 f"{'the two' if len(tied) == 1 else 'them'}.")
    if unpaired:
        text += f" {named(unpaired).capitalize()}: tested on other rows, not compared."
    return text


def _distance_held_out(r: MaterialSplitsResult) -> str:
    """The distance network on the random split against whole positions held out, each with
    its interval over the test positions."""
    rnd, held = (_distance_entry(x) for x in (r.distance["gd"], r.distance_held_out))
    return (
        "The paper's distance network (gradient descent) is scored on a random split (the "
        "paper's 70/15/15 split, section 4.2, does not say how its rows were drawn: at random "
        "is the study's assumption), where "
        "nearly every test recording has a repetition of its own position in the training "
        f"set: {format_mae(rnd)}. Trained with whole positions held out (every fold of the "
        f"grouped split, each position of the region held out once) it errs by "
        f"{format_mae(held)}. "
        + flattery_sentence(held_out_against_random(r.distance["gd"], r.distance_held_out))
        + f" The earlier ANN the paper cites reached about "
          f"{printed.PRIOR_DISTANCE_ACCURACY_CM.value} cm."
    )


def flattery_sentence(d: dict | None) -> str:
    """Whether the random split flatters the distance network, from the paired difference of
    :func:`held_out_against_random`.

    Examples
    --------
    >>> d = {"difference_cm": 2.7, "ci95": [0.4, 5.0], "n_units": 6, "resolved": True}
    >>> flattery_sentence(d).split(": ")[1]
    'resolved, the random split flatters the network.'
    >>> flattery_sentence({**d, "difference_cm": 0.3, "ci95": [-0.2, 0.8],
    ...                    "resolved": False}).split(": ", 1)[1]
    'not resolved: this design does not show the random split flattering the network.'
    >>> flattery_sentence({**d, "difference_cm": -0.9, "ci95": [-1.5, -0.3]}).split(": ")[1]
    'resolved, the network errs less with its positions held out.'
    """
    if d is None:
        return "The two splits share no test recording to compare them on."
    head = ("On the random split's own test recordings, holding their positions out errs by "
            + format_paired_mae(d) + ": ")
    if d["ci95"] is None or not d["resolved"]:
        return head + ("not resolved: this design does not show the random split flattering "
                       "the network.")
    if d["difference_cm"] > 0:
        return head + "resolved, the random split flatters the network."
    return head + "resolved, the network errs less with its positions held out."


def _lift(r: MaterialSplitsResult) -> str:
    """What the position-aware classifier does on the blocked split, from its interval and its
    paired difference with the paper's SVM on the same folds.

    Examples
    --------
    >>> from ebantenna.paper.uncertainty import FoldAccuracy, PairedDifference
    >>> def folds(k):
    ...     return FoldAccuracy([(np.arange(10) < k[i], np.full(10, i)) for i in range(5)],
    ...                         "held-out block", by_fold=True)
    >>> low, high = folds([2, 3, 2, 2, 3]), folds([6, 7, 6, 7, 6])
    >>> up = PairedDifference([2, 3, 2, 2, 3], [6, 7, 6, 7, 6], [10] * 5, "held-out block")
    >>> down = PairedDifference([6, 7, 6, 7, 6], [2, 3, 2, 2, 3], [10] * 5, "held-out block")
    >>> r = MaterialSplitsResult({"blocked": None}, {}, {}, {}, {}, {},
    ...     {("svm", "blocked"): low, ("position_aware", "blocked"): high},
    ...     {"blocked": {"position_aware": up}})
    >>> "lifts the classifier above chance" in _lift(r)
    True
    >>> r.measured["svm", "blocked"], r.measured["position_aware", "blocked"] = high, low
    >>> r.paired["blocked"]["position_aware"] = down
    >>> "not above chance" in _lift(r), "lower than the raw spectrum" in _lift(r)
    (True, True)
    """
    svm, aware = r.measured["svm", "blocked"], r.measured["position_aware", "blocked"]
    pair = r.paired["blocked"]["position_aware"]
    chance = 1 / _classes(r)
    words = _grouped_lift(r) + (
        f"On the blocked split (all folds) it reaches {aware} against the paper's SVM's "
        f"{svm}; chance {percent(chance)}. Paired on the same folds, the difference is "
        f"{_paired_text(pair)}: "
    )
    above = aware.ci95[0] > chance
    if above and pair.direction == "higher":
        return words + "reading the spectrum at its distance lifts the classifier above chance."
    if above:
        return words + ("above chance, and as many right as the raw spectrum." if pair.identical
                        else "above chance, and not resolved as better than the raw spectrum.")
    compare = ("as many right as" if pair.identical else
               {"higher": "higher than", "lower": "lower than",
                "unresolved": "not resolved from"}[pair.direction])
    return words + (
        f"not above chance, and {compare} the raw spectrum: what tells the materials apart at "
        "the positions it learnt from is not shown to carry over to an unseen stretch of the "
        "probe."
    )


def _grouped_lift(r: MaterialSplitsResult) -> str:
    """The position-aware classifier against the paper's SVM on whole held-out positions,
    worded from their paired difference (empty where the grouped split was not paired)."""
    pair = (r.paired or {}).get("grouped", {}).get("position_aware")
    if pair is None:
        return ""
    aware, svm = r.measured["position_aware", "grouped"], r.measured["svm", "grouped"]
    verdict = {"higher": "higher than the raw spectrum, resolved",
               "lower": "lower than the raw spectrum, resolved: on positions between those it "
                        "learnt from, the standardisation costs more than it gives",
               "unresolved": "not resolved from the raw spectrum"}[pair.direction]
    if pair.identical:
        verdict = "the two classify alike"
    return (f"On whole held-out positions (grouped split, all folds) it reaches {aware} against "
            f"the paper's SVM's {svm}; paired on the same folds, {_paired_text(pair)}: "
            f"{verdict}. ")


def _classes(r: MaterialSplitsResult) -> int:
    """Number of materials (from any stored result)."""
    for res in (*r.svm.values(), *r.mode_curves.values()):
        if res is not None:
            return len(res.labels)
    return 5


def _curves(r: MaterialSplitsResult, simulated: bool = True) -> str:
    """What the mode curves do on the held-out positions, against the paper's SVM, paired on
    the same folds; what the curves read is named as the data set's source makes it
    (``simulated``: the rod's effect on the probe's modes is the simulator's assumption).

    Examples
    --------
    >>> from ebantenna.paper.uncertainty import FoldAccuracy, PairedDifference
    >>> def folds(k):
    ...     return FoldAccuracy([(np.arange(10) < k[i], np.full(10, i)) for i in range(5)],
    ...                         "held-out block", by_fold=True)
    >>> high, low = folds([6, 7, 6, 7, 6]), folds([2, 3, 2, 2, 3])
    >>> up = PairedDifference([2, 3, 2, 2, 3], [6, 7, 6, 7, 6], [10] * 5, "held-out block")
    >>> r = MaterialSplitsResult({"blocked": None}, {}, {}, {}, {}, {},
    ...     {("svm", "blocked"): low, ("mode_curves", "blocked"): high,
    ...      ("mode_curves", "grouped"): high},
    ...     {"blocked": {"mode_curves": up}, "grouped": {"mode_curves": up}})
    >>> "carries over" in _curves(r), "by assumption" in _curves(r)
    (True, True)
    >>> "by assumption" in _curves(r, simulated=False)
    False
    >>> r.measured["mode_curves", "blocked"] = low
    >>> "not shown to carry over" in _curves(r)
    True
    """
    words = []
    for kind in ("grouped", "blocked"):
        pair = r.paired[kind]["mode_curves"]
        words.append(f"{r.measured['mode_curves', kind]} on the {kind} split, "
                     f"{_paired_text(pair)} against the SVM on the same folds")
    blocked = r.measured["mode_curves", "blocked"]
    carried = blocked.ci95[0] > 1 / _classes(r)
    if carried:
        read = ("the two strongest peaks' frequencies against the distance, which the touched "
                "rod moves in the simulator by assumption (the 'object_modes' effect)"
                if simulated else "the two strongest peaks' frequencies against the distance")
        why = (
            f"Its interval on the blocked split lies above chance: what it reads, {read}, "
            "carries over to a stretch of the probe it never saw"
        )
        better = r.paired["blocked"]["mode_curves"].direction == "higher"
        svm_at_chance = not r.measured["svm", "blocked"].ci95[0] > 1 / _classes(r)
        why += (", where the spectrum's bins are not shown to." if better and svm_at_chance
                else ", better than the spectrum's bins on the same folds." if better else ".")
    else:
        why = ("Its interval on the blocked split reaches chance: it is not shown to carry "
               "over to a stretch of the probe it never saw.")
    return f"It reaches {'; and '.join(words)}. {why}"


def _plot_mode_curves(model, figures) -> str:
    """Each material's calibration curves: its two strongest peaks against the distance."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(12, 4), sharex=True)
    for m, curves in model.curves_.items():
        for j, ax in enumerate(axes):
            ax.semilogy(100 * curves.distances_, curves.frequencies_[:, j], label=m)
    for j, ax in enumerate(axes):
        ax.set_xlabel("contact distance (cm)")
        ax.set_ylabel(f"{('lower', 'upper')[j]} of the two strongest peaks (Hz)")
    axes[0].legend(fontsize="small")
    fig.suptitle("Each material's two strongest peaks against the contact distance")
    return figures.save(fig, "beyond_mode_curves")
