"""Section 6b'': what in the paper's training setup its network's accuracy depends on.

The paper (section 4.2) trains its 53-tanh material network "using the MATLAB toolbox" (Beale,
Hagan & Demuth 2010) by gradient descent on a 70/15/15 split of max-normalised FFT magnitudes.
It states neither the number of epochs, nor the learning rate, nor the stopping rule. MATLAB's
``traingd`` defaults (Neural Network Toolbox user's guide, Beale et al. 2010) are 1000 epochs, a
learning rate of 0.01, and a stop after six validation checks failed in a row
(:data:`TRAINGD_DEFAULTS`). The study's run keeps the 1000 epochs and the six checks, with a
step of 0.05.

:func:`compute` trains the same network by the same full-batch gradient descent with the step
changed, on the first :data:`~.seed_spread.SUBSET_REPETITIONS` repetitions of every position (a
fifth of the data set: one epoch costs a fifth), and records for each run how many epochs it
ran, why it stopped, its final training loss and its accuracies.
"""

from __future__ import annotations

import inspect
import math
import warnings
from dataclasses import dataclass

import numpy as np
from sklearn.exceptions import ConvergenceWarning

from .._validate import check_bool
from ..ml import MLPClassifier
from ..paper import experiments, printed
from ..paper.protocol import MATERIAL_ANN, normalise_by_max, three_way_split
from ..paper.uncertainty import (
    UNITS,
    ClusteredAccuracy,
    PairedDifference,
    clustered_entries,
    format_clustered,
    percent,
    training_entries,
)
from ._common import (
    TRAINED_ONCE,
    check_instance,
    check_render,
    check_step,
    fits_in_parallel,
    listed,
)
from .learning import ANN_MAX_EPOCHS, stop_sentence
from .seed_spread import SUBSET_REPETITIONS

__all__ = ["TRAINGD_DEFAULTS", "RUNS", "LONG_RUN", "AnnSetupResult", "compute", "fit_calls",
           "from_fits", "render"]

#: MATLAB ``traingd``'s defaults: epochs, learning rate, validation checks (``max_fail``).
TRAINGD_DEFAULTS = {"epochs": 1000, "lr": 0.01, "max_fail": 6}
#: The runs: name -> (learning rate, largest number of epochs); validation patience six checks.
RUNS = {
    "the study's step": (0.05, TRAINGD_DEFAULTS["epochs"]),
    "a ten times larger step": (0.5, TRAINGD_DEFAULTS["epochs"]),
}
#: The long run: the larger step, up to three times MATLAB's epochs, no validation stop; the
#: test and 'all' accuracies recorded every ``every`` epochs, and the run ended once the test
#: accuracy reaches the paper's (what is asked of it is that epoch). One epoch of full-batch
#: gradient descent on the subset costs about 10 ms on one core: the cap bounds the cost.
LONG_RUN = {"lr": 0.5, "epochs": 3000, "every": 50}


@dataclass(frozen=True, eq=False)
class AnnSetupResult:
    """The gradient-descent runs of :data:`RUNS` and the long run of :data:`LONG_RUN`.

    Attributes
    ----------
    runs : dict of str to dict
        Per run: ``lr``, ``max_epochs``, ``epochs`` (run), ``stopped_by`` (``"epoch cap"`` or
        ``"validation"``), ``final_loss`` (training cross-entropy), ``guessing_loss``
        (``ln n_classes``), ``test`` (:class:`~ebantenna.paper.uncertainty.ClusteredAccuracy`),
        ``all`` and ``n_all`` (mostly training rows: no interval), ``result``.
    recordings : int
        Recordings of the subset trained on.
    long : dict
        ``epochs`` (the checkpoints), ``test`` and ``all`` (accuracy at each), ``reached_test``
        and ``reached_all`` (the first checkpoint at or above the paper's accuracy, or None),
        ``final`` (the last test accuracy on the position), ``stopped_by`` ("epoch cap").
    larger_step : PairedDifference
        The ten times larger step against the study's step, on the same test recordings.
    repetitions : int or None
        Repetitions of each position in the subset (None: not said).
    """

    runs: dict
    recordings: int
    long: dict = None
    larger_step: PairedDifference = None
    repetitions: int | None = None

    def to_dict(self) -> dict:
        """Under ``materials``: ``ann_training_setup``: each run with what stopped it, its test
        accuracy on the position and its 'all' accuracy with the count only, the long run's
        curve, and the paired difference of the two steps."""
        out = {"recordings": self.recordings}
        for name, r in self.runs.items():
            out[name] = {
                **{k: r[k] for k in ("lr", "max_epochs", "epochs", "stopped_by", "final_loss")},
                **clustered_entries("test_accuracy", r["test"]),
                **training_entries("all_accuracy", r["all"], r["n_all"]),
            }
        if self.long is not None:
            lg = self.long
            out["long_run"] = {
                "lr": LONG_RUN["lr"], "max_epochs": lg["max_epochs"],
                "stopped_by": lg["stopped_by"], "epochs": list(lg["epochs"]),
                "test_accuracy_curve": list(lg["test"]), "all_accuracy_curve": list(lg["all"]),
                "paper_value": printed.ANN_ACCURACY.value,
                "reached_paper_test_epoch": lg["reached_test"],
                "reached_paper_all_epoch": lg["reached_all"],
                "test_accuracy_ci95_curve": [list(c) for c in lg["test_ci95"]],
                "paper_within_test_ci95_from_epoch": lg["within_from"],
                **clustered_entries("test_accuracy", lg["final"]),
            }  # fmt: skip
        if self.larger_step is not None:
            out["larger_step_against_study_step"] = self.larger_step.to_dict()
        return {"ann_training_setup": out}


def long_run(X, y, positions, *, lr: float, epochs: int, every: int, seed: int) -> dict:
    """The paper's network trained by full-batch gradient descent for up to ``epochs`` epochs
    with no validation stop (and no tolerance stop), on the same 70/15/15 split and scaling as
    :func:`~ebantenna.paper.experiments.classify_materials_ann`; its test and 'all' accuracies
    every ``every`` epochs, until the test accuracy reaches the paper's.

    Returns
    -------
    dict
        See :attr:`AnnSetupResult.long`.
    """
    y = np.asarray(y)
    train, val, test = three_way_split(X.shape[0], MATERIAL_ANN.fractions, seed, stratify=y)
    X = normalise_by_max(X, np.concatenate([train, val]))
    model = MLPClassifier(hidden_layer_sizes=MATERIAL_ANN.hidden_layer_sizes,
                          activation=MATERIAL_ANN.activation, solver="gd",
                          learning_rate_init=lr, max_iter=every, random_state=seed,
                          warm_start=True, alpha=0.0, tol=0.0, n_iter_no_change=epochs + 1)
    marks, on_test, on_all, test_ci = [], [], [], []
    at = np.asarray(positions)[test]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        paper, stopped = printed.ANN_ACCURACY.value, "epoch cap"
        for done in range(every, epochs + 1, every):
            model.fit(X[train], y[train])
            marks.append(done)
            scored = ClusteredAccuracy.from_recordings(model.predict(X[test]) == y[test], at,
                                                       UNITS["random"])
            on_test.append(scored.estimate)
            test_ci.append(tuple(scored.ci95))
            on_all.append(float(np.mean(model.predict(X) == y)))
            if on_test[-1] >= paper:
                stopped = "the paper's accuracy reached on the test rows"
                break
    correct = model.predict(X[test]) == y[test]
    return {
        "epochs": marks, "test": on_test, "all": on_all, "stopped_by": stopped,
        "max_epochs": epochs, "test_ci95": test_ci,
        "within_from": within_from(marks, test_ci, paper),
        "reached_test": next((e for e, a in zip(marks, on_test, strict=True) if a >= paper),
                             None),
        "reached_all": next((e for e, a in zip(marks, on_all, strict=True) if a >= paper),
                            None),
        "final": ClusteredAccuracy.from_recordings(correct, np.asarray(positions)[test],
                                                   UNITS["random"]),
    }  # fmt: skip


def within_from(epochs, intervals, value: float):
    """The first epoch from which ``value`` lies inside every later interval, or None.

    From that epoch to the run's end, the test set cannot tell the network's accuracy from
    ``value``: the epoch at which the accuracy first reaches ``value`` is one draw within that
    range, not a sharp crossing.

    Examples
    --------
    >>> within_from([50, 100, 150], [(0.5, 0.7), (0.7, 0.9), (0.6, 0.85)], 0.8)
    100
    >>> within_from([50, 100], [(0.5, 0.7), (0.6, 0.75)], 0.8) is None
    True
    """
    first = None
    for epoch, (lo, hi) in zip(epochs, intervals, strict=True):
        if lo <= value <= hi:
            first = epoch if first is None else first
        else:
            first = None
    return first


#: The section's heading: the question it asks, whatever its numbers answer.
HEADING = "What the paper's training budget changes"

#: The long run's cap in a quick run (its data set is tiny; the numbers only indicative).
QUICK_LONG_EPOCHS = 300


def _same_fit(paper_ann, lr: float, epochs: int, seed: int) -> bool:
    """Whether ``paper_ann`` (or None) is the fit that a run at step ``lr`` and cap ``epochs``
    with seed ``seed`` would make on the whole data set: the paper network's step, cap and
    patience, and a model trained by gradient descent at that step from that seed."""
    if paper_ann is None or (lr, epochs) != _paper_run():
        return False
    model = paper_ann.model
    return (getattr(model, "solver", None) == "gd" and model.learning_rate_init == lr
            and model.random_state == seed)


def _paper_run() -> tuple[float, int]:
    """The step and epoch cap of the study's paper network (its 'ml' step): the default step of
    :func:`~ebantenna.paper.experiments.classify_materials_ann` and
    ``learning.ANN_MAX_EPOCHS``; its patience is the default too (``max_fail``)."""
    defaults = inspect.signature(experiments.classify_materials_ann).parameters
    if defaults["n_iter_no_change"].default != TRAINGD_DEFAULTS["max_fail"]:
        return (math.nan, -1)  # another patience: no run of RUNS is that fit
    return defaults["learning_rate_init"].default, ANN_MAX_EPOCHS


def compute(ds, feats, seed: int, quick: bool = False, n_jobs: int = 1, *,
            paper_ann=None) -> AnnSetupResult:
    """Each run of :data:`RUNS` and the long run on the subset, seed ``seed`` for the split and
    the weights (the long run capped at ``QUICK_LONG_EPOCHS`` when ``quick``); each run on one
    of ``n_jobs`` worker processes (``_common.fits_in_parallel``): the same numbers whatever
    ``n_jobs``. The same as :func:`from_fits` of the fits of :func:`fit_calls`.

    ``paper_ann`` (optional) is the paper's network already trained on the whole data set with
    seed ``seed`` (the study's 'ml' step, ``learning.ANN_MAX_EPOCHS`` epochs, the default
    step and patience of :func:`~ebantenna.paper.experiments.classify_materials_ann`). When the
    subset is the whole data set (at most :data:`~.seed_spread.SUBSET_REPETITIONS` repetitions
    per position) the run of :data:`RUNS` with that step and cap is that same fit, and it is
    taken instead of being trained a second time."""
    check_step(ds=ds, feats=feats, seed=seed, quick=quick, n_jobs=n_jobs)
    if paper_ann is not None:
        check_instance("paper_ann", paper_ann, experiments.ClassificationResult)
    calls = fit_calls(ds, feats, seed, quick,
                      paper_ann_given=_same_fit(paper_ann, *_paper_run(), seed))
    fits = dict(zip(calls, fits_in_parallel(list(calls.values()), n_jobs), strict=True))
    return from_fits(ds, feats, seed, fits, paper_ann=paper_ann)


def fit_calls(ds, feats, seed: int, quick: bool = False, *,
              paper_ann_given: bool = False) -> dict:
    """The fits of :func:`compute` by name (each run of :data:`RUNS`, then ``"long"``), as calls
    ``(function, args, kwargs)`` for ``_common.fits_in_parallel``.

    With ``paper_ann_given``, the run that is the paper's network on the whole data set (see
    :func:`compute`; there is one only when the subset is the whole data set) is left out: the
    caller trains that network anyway and gives it to :func:`from_fits`."""
    check_step(ds=ds, feats=feats, seed=seed, quick=quick)
    paper_ann_given = check_bool("paper_ann_given", paper_ann_given)
    rows, whole = _subset(ds)
    X, y, d = feats.fft[rows], ds.material[rows], np.asarray(ds.contact)[rows]
    calls = {}
    for name, (lr, epochs) in RUNS.items():
        if paper_ann_given and whole and (lr, epochs) == _paper_run():
            continue
        calls[name] = (experiments.classify_materials_ann, (X, y),
                       {"learning_rate_init": lr, "max_iter": epochs, "seed": seed,
                        "n_iter_no_change": TRAINGD_DEFAULTS["max_fail"]})
    calls["long"] = (long_run, (X, y, d), {
        "lr": LONG_RUN["lr"], "epochs": QUICK_LONG_EPOCHS if quick else LONG_RUN["epochs"],
        "every": LONG_RUN["every"], "seed": seed})
    return calls


def from_fits(ds, feats, seed: int, fits: dict, *, paper_ann=None) -> AnnSetupResult:
    """The :class:`AnnSetupResult` of the results of :func:`fit_calls`' calls, by name; the run
    left out for ``paper_ann_given`` is ``paper_ann``, which must then be that same fit."""
    check_step(ds=ds, feats=feats, seed=seed)
    if paper_ann is not None:
        check_instance("paper_ann", paper_ann, experiments.ClassificationResult)
    rows, whole = _subset(ds)
    d = np.asarray(ds.contact)[rows]
    runs_given = set(fits) & set(RUNS) if isinstance(fits, dict) else set()
    if (not isinstance(fits, dict) or not isinstance(fits.get("long"), dict)
            or not set(fits) <= {*RUNS, "long"}
            or not all(isinstance(fits[k], experiments.ClassificationResult) for k in runs_given)):
        raise ValueError(f"fits must be the results of fit_calls' calls by name ({listed(RUNS)}"
                         f" and 'long'), got {fits!r:.80}")
    done = dict(fits)
    for name, (lr, epochs) in RUNS.items():
        if name not in done:
            if not (whole and _same_fit(paper_ann, lr, epochs, seed)):
                raise ValueError(f"fits lacks the run {name!r}, and paper_ann is not that fit "
                                 "(the paper's network on the whole data set with this seed)")
            done[name] = paper_ann
    results, long = [done[name] for name in RUNS], done["long"]
    runs = {}
    for (name, (lr, epochs)), result in zip(RUNS.items(), results, strict=True):
        curve = list(getattr(result.model, "loss_curve_", []))
        runs[name] = {
            "lr": lr,
            "max_epochs": epochs,
            "epochs": len(curve),
            "stopped_by": result.stopped_by,
            "final_loss": float(curve[-1]) if curve else float("nan"),
            "guessing_loss": float(np.log(len(result.labels))),
            "test": ClusteredAccuracy.from_recordings(result.correct(), d[result.rows()],
                                                      UNITS["random"]),
            "all": result.accuracies["all"],
            "n_all": result.counts["all"],
            "result": result,
        }
    first, larger = (runs[k]["result"] for k in RUNS)
    pair = PairedDifference.from_recordings(first.correct(), larger.correct(),
                                            d[first.rows()], UNITS["random"])
    depth = int(np.max(ds.repetition)) + 1
    return AnnSetupResult(runs, int(d.size), long, pair, min(SUBSET_REPETITIONS, depth))


def _subset_words(result: AnnSetupResult) -> str:
    """The subset the runs train on, in words."""
    if result.repetitions is None:
        return "a subset of every position's repetitions"
    if result.repetitions == 1:
        return "the first repetition of every position"
    return f"the first {result.repetitions} repetitions of every position"


def _subset(ds) -> tuple:
    """The subset's rows (the first :data:`~.seed_spread.SUBSET_REPETITIONS` repetitions of
    every position), and whether they are the whole data set."""
    rows = np.flatnonzero(np.asarray(ds.repetition) < SUBSET_REPETITIONS)
    return rows, rows.size == np.asarray(ds.repetition).size


def render(result: AnnSetupResult, report, figures) -> None:
    """The runs' table, the long run, and what they say about the gap to the paper's 80.8 %."""
    check_render(result, AnnSetupResult, report, figures)
    report.heading(HEADING)
    report.paragraph(
        "The paper trains its network by gradient descent in MATLAB but states neither the "
        "number of epochs, nor the learning rate, nor the stopping rule. MATLAB's traingd "
        f"stops after {TRAINGD_DEFAULTS['epochs']} epochs or {TRAINGD_DEFAULTS['max_fail']} "
        f"failed validation checks, with a step of {TRAINGD_DEFAULTS['lr']:g}, unless told "
        "otherwise. Full-batch gradient descent moves the weights by the step times the "
        "gradient, once per epoch. "
        f"Below, the same network on {_subset_words(result)} "
        f"({result.recordings} recordings, the same 70/15/15 split), two steps, each "
        "with what ended its training. " + TRAINED_ONCE.format(what="Each run is")
    )
    report.table(
        ["run", "step", "epochs run (cap)", "stopped by", "final loss (guessing)", "test",
         f"all, training rows included (paper: {printed.percent(printed.ANN_ACCURACY)})"],
        [
            [name, f"{r['lr']:g}", f"{r['epochs']} ({r['max_epochs']})", r["stopped_by"],
             f"{r['final_loss']:.3f} ({r['guessing_loss']:.3f})",
             format_clustered(r["test"]), percent(r["all"])]
            for name, r in result.runs.items()
        ],
    )
    report.paragraph(_verdict(result))
    if result.long is not None:
        report.paragraph(_long_verdict(result))


def _verdict(result: AnnSetupResult) -> str:
    """What the two steps show, from what stopped each run and their paired difference.

    Examples
    --------
    >>> from ebantenna.paper.uncertainty import ClusteredAccuracy, PairedDifference
    >>> acc = ClusteredAccuracy([3, 2], [5, 5], "position")
    >>> run = dict(stopped_by="epoch cap", epochs=1000, max_epochs=1000, lr=0.05, test=acc)
    >>> up = PairedDifference([1, 2, 1, 2], [3, 3, 3, 4], [4] * 4, "position")
    >>> r = AnnSetupResult({"a": run, "b": {**run, "lr": 0.5}}, 1975, None, up)
    >>> "accounts" in _verdict(r)
    True
    >>> r = AnnSetupResult({"a": run, "b": {**run, "lr": 0.5}}, 1975, None,
    ...                    PairedDifference([3, 3, 3, 4], [1, 2, 1, 2], [4] * 4, "position"))
    >>> "lower" in _verdict(r)
    True
    """
    runs = list(result.runs.values())
    stops = "; ".join(
        f"at step {r['lr']:g}, " + stop_sentence(r["stopped_by"], r["epochs"], r["max_epochs"])
        for r in runs
    )
    words = f"What ended each run: {stops}. "
    first, other = runs[0], runs[-1]
    pair = result.larger_step
    if pair is None:
        return words
    if pair.identical:
        return words + (
            f"The two steps count as many test recordings right in every one of the "
            f"{pair.n_units} {pair.unit}s: there is no difference between them to resolve."
        )
    if pair.direction == "higher":
        return words + (
            f"At step {other['lr']:g} the network's test accuracy is higher than at "
            f"{first['lr']:g} by {pair}: the training budget the paper leaves unstated (epochs "
            "times step) " + _budget_share(first["test"].estimate, other["test"].estimate)
            + " here."
        )
    if pair.direction == "lower":
        return words + (
            f"At step {other['lr']:g} the test accuracy is lower than at {first['lr']:g}, "
            f"{pair}: a larger step does not make up the budget here."
        )
    return words + (
        f"The two steps' test accuracies differ by {pair}, not resolved: on this subset at "
        "these steps, the design does not show whether the budget changes the accuracy (which "
        "is not to say that it does not)."
    )


def _crossing_sharpness(lg: dict, paper: str) -> str:
    """How sharply the test set places the epoch at which the paper's accuracy is reached (the
    checkpoints before it whose test interval already held the paper's value, ``test_ci95``),
    that the run's stop on the test rows biases the accuracy it stops at, and what the epoch
    depends on besides."""
    reached, value = lg["reached_test"], printed.ANN_ACCURACY.value
    k = lg["epochs"].index(reached)
    inside = [e for e, (lo, hi) in zip(lg["epochs"][:k], lg["test_ci95"][:k], strict=True)
              if lo <= value <= hi]
    if k == 0:
        placed = f"It is reached at the first checkpoint, within {reached} epochs."
    elif not inside:
        placed = ("At every checkpoint before, the paper's value lay above the test accuracy's "
                  "95 % interval, so the test set places the crossing within the last "
                  f"{reached - lg['epochs'][k - 1]} epochs.")
    else:
        placed = (f"That epoch is not sharp: the paper's {paper} already lay inside the test "
                  "accuracy's 95 % interval (on the position) at epoch"
                  f"{'s' if len(inside) > 1 else ''} {listed(str(e) for e in inside)}, so this "
                  "test set cannot tell at which epoch the network reaches it.")
    return placed + (" The run stops at the first checkpoint whose test accuracy reaches the "
                     "paper's: picked on these test rows, the accuracy it stops at is biased "
                     "upwards, and the run gives no accuracy at a checkpoint fixed in advance. "
                     "Gradient descent over this many epochs amplifies rounding: "
                     "arithmetic that differs in its last bits (another BLAS kernel or thread "
                     "count) follows another path and may reach it at another epoch.")


def _budget_share(before: float, after: float) -> str:
    """What a higher accuracy at the larger step says of the shortfall from the paper's
    accuracy: the test accuracies at the study's step (``before``) and the larger (``after``).

    Examples
    --------
    >>> _budget_share(0.60, 0.70)
    "accounts for part of the network's shortfall from the paper's 80.8 %"
    >>> _budget_share(0.60, 0.85)[:60]
    "accounts for the network's shortfall from the paper's 80.8 %"
    """
    paper, value = printed.percent(printed.ANN_ACCURACY), printed.ANN_ACCURACY.value
    if before >= value:
        return "accounts for part of the network's accuracy"
    if after < value:
        return f"accounts for part of the network's shortfall from the paper's {paper}"
    return (f"accounts for the network's shortfall from the paper's {paper}: at the larger "
            "step the point estimate reaches it")


def _reached_words(lg: dict, paper: str) -> str:
    """What the long run shows of reaching the paper's accuracy: the checkpoint whose point
    value first reaches it, and whether a checkpoint fixed in advance (not the one the run
    stopped at, picked on the test rows) has its whole 95 % interval above it."""
    value = printed.ANN_ACCURACY.value
    k = lg["epochs"].index(lg["reached_test"])
    fixed = list(zip(lg["epochs"], lg["test_ci95"], strict=True))
    if _selected_on_test(lg):
        fixed = fixed[:k]
    above = [e for e, (lo, _) in fixed if lo > value]
    text = (f"Its test accuracy first reaches the paper's {paper} after {lg['reached_test']} "
            "epochs, as a point value. ")
    if above:
        text += (f"At epoch{'s' if len(above) > 1 else ''} {listed(str(e) for e in above)} its "
                 "95 % interval (on the position) lies above the paper's value: on this split "
                 f"of recordings (not of positions), plain gradient descent at step "
                 f"{LONG_RUN['lr']:g} gets there within {above[0]} epochs. ")
    else:
        text += ("No checkpoint fixed in advance has its 95 % interval (on the position) above "
                 "the paper's value, so this run does not show that plain gradient descent "
                 "reaches the paper's accuracy, only that its test accuracy comes within reach "
                 "of it. ")
    return text + ("Whether the features carry it as far on held-out positions is not what "
                   "this run tests. ")


def _selected_on_test(lg: dict) -> bool:
    """Whether the long run's last checkpoint is the first whose test accuracy reached the
    paper's (so that accuracy was picked on the test rows)."""
    return lg["reached_test"] is not None and lg["reached_test"] == lg["epochs"][-1]


def _long_verdict(result: AnnSetupResult) -> str:
    """The long run: the epoch at which it reaches the paper's accuracy, if it does.

    Examples
    --------
    >>> from ebantenna.paper.uncertainty import ClusteredAccuracy
    >>> final = ClusteredAccuracy([4, 5], [5, 5], "position")
    >>> long = dict(epochs=[100, 200], test=[0.5, 0.9], all=[0.5, 0.92], reached_test=200,
    ...             reached_all=200, final=final, stopped_by="epoch cap", max_epochs=300,
    ...             test_ci95=[(0.4, 0.6), (0.85, 0.95)])
    >>> "reaches the paper's" in _long_verdict(AnnSetupResult({}, 10, long))
    True
    >>> long.update(reached_test=None, reached_all=None, test=[0.5, 0.6], all=[0.5, 0.6])
    >>> "does not reach" in _long_verdict(AnnSetupResult({}, 10, long))
    True
    """
    lg = result.long
    paper = printed.percent(printed.ANN_ACCURACY)
    head = (
        f"The same network at step {LONG_RUN['lr']:g} trained with no validation stop, for at "
        f"most {lg['max_epochs']} epochs (what ended it: {lg['stopped_by']}): test accuracy "
        f"{percent(lg['test'][0])} after {lg['epochs'][0]} epochs and "
        + (f"{percent(lg['test'][-1])} after {lg['epochs'][-1]}, the checkpoint the run stopped "
           "at because its test accuracy reached the paper's: chosen on the test rows, that "
           "accuracy is no test result and has no test interval. "
           if _selected_on_test(lg) else f"{lg['final']} after {lg['epochs'][-1]}. ")
    )
    if lg["reached_test"] is not None:
        return head + _reached_words(lg, paper) + _crossing_sharpness(lg, paper)
    if lg["reached_all"] is not None:
        return head + (
            f"Its test accuracy does not reach the paper's {paper}; counting the training rows "
            f"too ('all', as the paper does) it does after {lg['reached_all']} epochs."
        )
    return head + (
        f"It does not reach the paper's {paper} within {lg['max_epochs']} epochs, on the test "
        "recordings nor counting the training rows."
    )
