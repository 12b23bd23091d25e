"""The input contract of the study's steps, of the controls that rebuild data sets, and of the
data set cache.

Every step of ``ebantenna reproduce`` is a ``compute`` and a ``render``. Each ``compute`` checks
its arguments with one shared check (``study._common.check_step``) before any work: a probe,
scene, data set or features that are not one, features of another data set, materials that are
not the data set's, a seed outside 0 ... 2**32 - 2, a ``quick`` that is not a bool (``"no"`` was
taken as true), a cache folder that cannot hold files, a count of workers that is not one.
Each ``render`` checks that its result is its step's, and the report and figures
(``check_render``). The controls refuse a design, a cache folder, workers or splits they cannot
use before building anything. The cache (``file:cache``, the data set files
:func:`~ebantenna.simulate.build_dataset` reuses) is reused when valid and rebuilt, never read
as data, when the file in its place is damaged, stale, a FIFO, a link to a device; a folder in
its place or a cache that is a file ends in an error naming the path.

Found by these rows and fixed: ``AttributeError`` from every step given a number for its data
set, scene, probe or result; ``hinge_fit.compute(probe, quick="no")`` and
``control_design("no")`` accepted as a quick run; ``signals.compute_frequency`` given no
materials ("'NoneType' object is not iterable"); ``ablation_accuracies(cache_dir=5)`` (a vague
``TypeError``), ``equivalent_pair_accuracy(design=5)`` ("replace() should be called on dataclass
instances") and a cache folder under ``/proc`` (a bare ``FileNotFoundError`` after the work).
"""

from __future__ import annotations

import atexit
import functools
import os
import shutil
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, check_row  # noqa: E402

from ebantenna.paper import controls  # noqa: E402
from ebantenna.paper.feature_table import signal_features  # noqa: E402
from ebantenna.paper.uncertainty import FoldAccuracy  # noqa: E402
from ebantenna.report import FigureSet, Report  # noqa: E402
from ebantenna.simulate import DatasetDesign, Scene, build_dataset, builtin_scene  # noqa: E402
from ebantenna.study import (  # noqa: E402
    ann_setup,
    contact_law,
    data_summary,
    full_range,
    hinge_fit,
    learning,
    material_splits,
    mode_zones,
    physics_controls,
    rod_geometry,
    seed_spread,
    signals,
    time_frequency,
)

SCENE = builtin_scene("paper")
PROBE = SCENE.probe
#: Two materials at three contacts, one repetition: six recordings, simulated in a fraction of a
#: second (the good-input rows and the cache's rows use it).
TINY = DatasetDesign("contract-tiny", ("brass", "pvc"), 0.1, 0.1, 1)
CACHE = Path(tempfile.mkdtemp(prefix="ebantenna-contract-steps-"))
atexit.register(shutil.rmtree, CACHE, ignore_errors=True)
PROC = "/proc/ebantenna-no-such-folder"  # a folder no file can be made in


@functools.cache
def tiny():
    """The tiny data set, its features and its materials."""
    ds = build_dataset(CACHE / "tiny", SCENE, TINY, seed=1, n_jobs=1, show_progress=False)
    return ds, signal_features(ds.ax, ds.az, ds.fs, n_jobs=1, show_progress=False), (
        "brass", "pvc")


def ds_():
    return tiny()[0]


def feats_():
    return tiny()[1]


def other_feats():
    """Features of two rows only: not those of the tiny data set's six."""
    ds = ds_()
    return signal_features(ds.ax[:2], ds.az[:2], ds.fs, n_jobs=1, show_progress=False)


def _six_folds():
    """The grouped SVM's accuracy over two folds of the tiny data set's six recordings, three
    right (what ``grouped_answers`` must agree with)."""
    right = np.array([True, False, True])
    return FoldAccuracy([(right, np.arange(3)), (~right, np.arange(3, 6))], "position")


def report_figures():
    return Report("contract"), FigureSet(CACHE)


def a_file() -> str:
    """A regular file where a cache folder is expected."""
    path = CACHE / "a-file"
    path.write_text("not a folder", encoding="utf-8")
    return str(path)


def _classification():
    from ebantenna.paper import experiments

    rng = np.random.default_rng(0)
    return experiments.classify_materials_svm(rng.normal(size=(20, 3)),
                                              np.array(["a", "b"] * 10), seed=0)


S = "ebantenna.study."


def _scene_steps():
    """The three steps that rebuild data sets: every argument refused before any is built."""
    rows = []
    for name, step in (("physics_controls", physics_controls), ("contact_law", contact_law),
                       ("rod_geometry", rod_geometry)):
        compute = step.compute
        rows += [
            Row(f"{S}{name}.compute", "scene-int", lambda c=compute: c(5, 0, True, CACHE, 1),
                ("scene",)),
            Row(f"{S}{name}.compute", "quick-str", lambda c=compute: c(SCENE, 0, "no", CACHE, 1),
                ("quick",)),
            Row(f"{S}{name}.compute", "seed-negative",
                lambda c=compute: c(SCENE, -1, True, CACHE, 1), ("seed",)),
            Row(f"{S}{name}.compute", "seed-beyond-32-bits",
                lambda c=compute: c(SCENE, 2**32 - 1, True, CACHE, 1), ("seed",)),
            Row(f"{S}{name}.compute", "cache_dir-int", lambda c=compute: c(SCENE, 0, True, 5, 1),
                ("cache_dir",)),
            Row(f"{S}{name}.compute", "cache_dir-in-proc",
                lambda c=compute: c(SCENE, 0, True, PROC, 1), ("cache_dir",)),
            Row(f"{S}{name}.compute", "cache_dir-a-file",
                lambda c=compute: c(SCENE, 0, True, a_file(), 1), ("cache_dir",)),
            Row(f"{S}{name}.compute", "n_jobs-0", lambda c=compute: c(SCENE, 0, True, CACHE, 0),
                ("n_jobs",)),
            Row(f"{S}{name}.compute", "n_jobs-none",
                lambda c=compute: c(SCENE, 0, True, CACHE, None), ("n_jobs",)),
            Row(f"{S}{name}.compute", "n_jobs-beyond-the-cores",
                lambda c=compute: c(SCENE, 0, True, CACHE, 10**6), ("n_jobs",)),
        ]
    return rows


def _renders():
    """Every render: a result of another type, no report, figures that are not a FigureSet."""
    steps = [("ann_setup.render", ann_setup.render), ("contact_law.render", contact_law.render),
             ("data_summary.render", data_summary.render), ("full_range.render", full_range.render),
             ("hinge_fit.render", hinge_fit.render), ("learning.render", learning.render),
             ("material_splits.render", material_splits.render),
             ("mode_zones.render", mode_zones.render),
             ("physics_controls.render", physics_controls.render),
             ("rod_geometry.render", rod_geometry.render),
             ("seed_spread.render", seed_spread.render),
             ("signals.render_decay", signals.render_decay),
             ("signals.render_frequency", signals.render_frequency),
             ("time_frequency.render", time_frequency.render)]
    rows = []
    for name, render in steps:
        rows += [
            Row(S + name, "result-int", lambda r=render: r(5, *report_figures()), ("result",)),
            Row(S + name, "result-dict", lambda r=render: r({}, *report_figures()), ("result",)),
            Row(S + name, "report-none", lambda r=render: r(
                data_summary.compute(ds_()), None, FigureSet(CACHE)), ("result", "report")),
            Row(S + name, "figures-str", lambda r=render: r(
                data_summary.compute(ds_()), Report("t"), "out"), ("result", "figures")),
        ]
    summary = lambda: data_summary.compute(ds_())  # noqa: E731
    rows += [
        Row(S + "data_summary.render", "report-none-right-result",
            lambda: data_summary.render(summary(), None, FigureSet(CACHE)), ("report",)),
        Row(S + "data_summary.render", "figures-str-right-result",
            lambda: data_summary.render(summary(), Report("t"), "out"), ("figures",)),
        Row(S + "data_summary.render", "another-steps-result",
            lambda: data_summary.render(mode_zones.compute(PROBE, True), *report_figures()),
            ("result", "DatasetResult")),
        # the data set's own numbers, written as they are
        Row(S + "data_summary.render", "by-hand", lambda: _rendered(summary()), same=lambda md: (
            "6 simulated recordings of 1000 samples" in md and "2 materials x 3 contact" in md)),
        # a step that measured nothing (no rod in the scene) writes nothing
        Row(S + "contact_law.render", "none-writes-nothing",
            lambda: _rendered(None, contact_law.render), same=lambda md: "Hertz" not in md),
        Row(S + "rod_geometry.render", "none-writes-nothing",
            lambda: _rendered(None, rod_geometry.render), same=lambda md: "rod" not in md),
        Row(S + "learning.render", "simulated-str", lambda: learning.render(
            _learnt(), Report("t"), FigureSet(CACHE), simulated="no"), ("simulated",)),
        # checked before anything is drawn: a result of the right type, made by hand
        Row(S + "full_range.render", "simulated-str", lambda: full_range.render(
            full_range.FullRangeResult(0.4, 0.8, *[np.array([0.1, 0.2]), np.zeros(2)] * 2,
                                       np.zeros(2), np.zeros(2), 1.0, 0.395, 0, 2),
            Report("t"), FigureSet(CACHE), simulated="no"), ("simulated",)),
        Row(S + "material_splits.render", "simulated-str", lambda: material_splits.render(
            material_splits.MaterialSplitsResult({}, {}, {}, {}, {}, {}), Report("t"),
            FigureSet(CACHE), simulated=1), ("simulated",)),
    ]
    return rows


def _rendered(result, render=data_summary.render) -> str:
    report, figures = report_figures()
    render(result, report, figures)
    return report.markdown()


@functools.cache
def _learnt():
    """A LearningResult whose parts are not checked before ``simulated`` is: not computed."""
    c = _classification()
    return learning.LearningResult(c, c, None, None, np.zeros(20))


def _computes():
    ds, feats = ds_, feats_
    rows = [
        Row(S + "data_summary.compute", "ds-int", lambda: data_summary.compute(5), ("ds",)),
        Row(S + "data_summary.compute", "ds-path", lambda: data_summary.compute("data.npz"),
            ("ds",)),
        Row(S + "data_summary.compute", "by-hand", lambda: data_summary.compute(ds()),
            same=lambda r: (r.signals, r.samples, r.materials, r.contacts) == (
                6, 1000, ("brass", "pvc"), 3)),
        Row(S + "signals.compute_frequency", "materials-none",
            lambda: signals.compute_frequency(ds(), feats(), None), ("materials",)),
        Row(S + "signals.compute_frequency", "materials-str",
            lambda: signals.compute_frequency(ds(), feats(), "brass"), ("materials",)),
        Row(S + "signals.compute_frequency", "materials-unknown",
            lambda: signals.compute_frequency(ds(), feats(), ["gold"]), ("materials", "gold")),
        Row(S + "signals.compute_frequency", "materials-twice",
            lambda: signals.compute_frequency(ds(), feats(), ["brass", "brass"]),
            ("materials",)),
        Row(S + "signals.compute_frequency", "feats-int",
            lambda: signals.compute_frequency(ds(), 5, ("brass",)), ("feats",)),
        Row(S + "signals.compute_frequency", "feats-of-other-rows",
            lambda: signals.compute_frequency(ds(), other_feats(), ("brass",)), ("feats",)),
        # each material's median per contact is read from its own rows
        Row(S + "signals.compute_frequency", "by-hand",
            lambda: signals.compute_frequency(ds(), feats(), ("pvc", "brass")),
            same=lambda r: [m for m, *_ in r.per_material] == ["pvc", "brass"] and all(
                np.array_equal(med, feats().dominant[ds().material == m][
                    np.argsort(ds().contact[ds().material == m])])
                for m, _, med in r.per_material)),
        Row(S + "signals.compute_decay", "materials-none",
            lambda: signals.compute_decay(ds(), feats(), None), ("materials",)),
        Row(S + "signals.compute_decay", "materials-numbers",
            lambda: signals.compute_decay(ds(), feats(), [1, 2]), ("materials",)),
        Row(S + "signals.compute_decay", "ds-none",
            lambda: signals.compute_decay(None, feats(), ("brass",)), ("ds",)),
        Row(S + "learning.compute", "ds-none", lambda: learning.compute(None, feats(), 0),
            ("ds",)),
        Row(S + "learning.compute", "seed-fraction", lambda: learning.compute(ds(), feats(), 1.5),
            ("seed",)),
        Row(S + "learning.compute", "feats-of-other-rows",
            lambda: learning.compute(ds(), other_feats(), 0), ("feats",)),
        Row(S + "learning.compute", "n_jobs-0", lambda: learning.compute(ds(), feats(), 0, 0),
            ("n_jobs",)),
        Row(S + "learning.compute", "n_jobs-beyond-the-cores",
            lambda: learning.compute(ds(), feats(), 0, n_jobs=10**6), ("n_jobs",)),
        Row(S + "learning.fit_calls", "ds-none", lambda: learning.fit_calls(None, feats(), 0),
            ("ds",)),
        Row(S + "learning.fit_calls", "seed-fraction",
            lambda: learning.fit_calls(ds(), feats(), 1.5), ("seed",)),
        Row(S + "learning.fit_calls", "feats-of-other-rows",
            lambda: learning.fit_calls(ds(), other_feats(), 0), ("feats",)),
        # the network's call first (the longest), then the SVM's and the two distance networks'
        Row(S + "learning.fit_calls", "by-hand", lambda: learning.fit_calls(ds(), feats(), 3),
            same=lambda calls: [f.__name__ for f, _, _ in calls] == [
                "classify_materials_ann", "classify_materials_svm",
                "regress_distance_linear_region", "regress_distance_full_length"]
            and all(kw["seed"] == 3 for _, _, kw in calls)),
        Row(S + "learning.from_fits", "fits-three",
            lambda: learning.from_fits(ds(), [_classification()] * 3), ("fits",)),
        Row(S + "learning.from_fits", "fits-none", lambda: learning.from_fits(ds(), None),
            ("fits",)),
        Row(S + "learning.from_fits", "ds-int",
            lambda: learning.from_fits(5, [_classification()] * 4), ("ds",)),
        Row(S + "full_range.compute", "ds-int", lambda: full_range.compute(5, feats()), ("ds",)),
        Row(S + "full_range.compute", "feats-none", lambda: full_range.compute(ds(), None),
            ("feats",)),
        Row(S + "ann_setup.compute", "quick-str",
            lambda: ann_setup.compute(ds(), feats(), 0, quick="no"), ("quick",)),
        Row(S + "ann_setup.compute", "seed-negative",
            lambda: ann_setup.compute(ds(), feats(), -1), ("seed",)),
        Row(S + "ann_setup.compute", "n_jobs-none",
            lambda: ann_setup.compute(ds(), feats(), 0, True, None), ("n_jobs",)),
        Row(S + "ann_setup.compute", "ds-dict", lambda: ann_setup.compute({}, feats(), 0),
            ("ds",)),
        Row(S + "ann_setup.compute", "paper_ann-dict",
            lambda: ann_setup.compute(ds(), feats(), 0, paper_ann={}), ("paper_ann",)),
        Row(S + "ann_setup.fit_calls", "paper_ann_given-str",
            lambda: ann_setup.fit_calls(ds(), feats(), 0, paper_ann_given="no"),
            ("paper_ann_given",)),
        Row(S + "ann_setup.fit_calls", "quick-str",
            lambda: ann_setup.fit_calls(ds(), feats(), 0, quick="no"), ("quick",)),
        Row(S + "ann_setup.fit_calls", "seed-negative",
            lambda: ann_setup.fit_calls(ds(), feats(), -1), ("seed",)),
        # every run and the long one; given the paper's network, its run on the whole data set
        # (this one has fewer repetitions than the subset keeps) is left out
        Row(S + "ann_setup.fit_calls", "by-hand", lambda: (
            ann_setup.fit_calls(ds(), feats(), 0),
            ann_setup.fit_calls(ds(), feats(), 0, paper_ann_given=True)),
            same=lambda pair: list(pair[0]) == [*ann_setup.RUNS, "long"]
            and list(pair[1]) == [name for name in pair[0] if name != "the study's step"]),
        Row(S + "ann_setup.from_fits", "fits-without-long",
            lambda: ann_setup.from_fits(ds(), feats(), 0, {}), ("fits",)),
        Row(S + "ann_setup.from_fits", "fits-list",
            lambda: ann_setup.from_fits(ds(), feats(), 0, [{}]), ("fits",)),
        Row(S + "ann_setup.from_fits", "fits-a-run-not-a-result",
            lambda: ann_setup.from_fits(ds(), feats(), 0, {"long": {}, "the study's step": 5}),
            ("fits",)),
        Row(S + "ann_setup.from_fits", "fits-lacking-a-run-without-paper_ann",
            lambda: ann_setup.from_fits(ds(), feats(), 0, {"long": {}}), ("fits", "paper_ann")),
        Row(S + "ann_setup.from_fits", "paper_ann-dict",
            lambda: ann_setup.from_fits(ds(), feats(), 0, {"long": {}}, paper_ann={}),
            ("paper_ann",)),
        Row(S + "material_splits.compute", "random_svm-int", lambda: material_splits.compute(
            ds(), feats(), 0, random_svm=5, paper_ann=_classification(), paper_distance=None),
            ("random_svm",)),
        Row(S + "material_splits.compute", "paper_distance-a-classification",
            lambda: material_splits.compute(
                ds(), feats(), 0, random_svm=_classification(), paper_ann=_classification(),
                paper_distance=_classification()), ("paper_distance",)),
        Row(S + "material_splits.compute", "n_jobs-0", lambda: material_splits.compute(
            ds(), feats(), 0, random_svm=_classification(), paper_ann=_classification(),
            paper_distance=None, n_jobs=0), ("n_jobs",)),
        Row(S + "material_splits.compute", "ds-int", lambda: material_splits.compute(
            5, feats(), 0, random_svm=None, paper_ann=None, paper_distance=None), ("ds",)),
        Row(S + "seed_spread.compute", "grouped_full-int",
            lambda: seed_spread.compute(ds(), feats(), 0, 5), ("grouped_full",)),
        Row(S + "seed_spread.compute", "n_jobs-none",
            lambda: seed_spread.compute(ds(), feats(), 0, None, n_jobs=None), ("n_jobs",)),
        Row(S + "seed_spread.compute", "seed-str",
            lambda: seed_spread.compute(ds(), feats(), "0", None), ("seed",)),
        Row(S + "seed_spread.compute", "grouped_answers-one-short",
            lambda: seed_spread.compute(ds(), feats(), 0, _six_folds(),
                                        grouped_answers=np.ones(5, bool)), ("grouped_answers",)),
        Row(S + "seed_spread.compute", "grouped_answers-floats",
            lambda: seed_spread.compute(ds(), feats(), 0, _six_folds(),
                                        grouped_answers=np.ones(6)), ("grouped_answers",)),
        Row(S + "seed_spread.compute", "grouped_answers-of-another-run",
            lambda: seed_spread.compute(ds(), feats(), 0, _six_folds(),
                                        grouped_answers=np.ones(6, bool)), ("grouped_answers",)),
        Row(S + "hinge_fit.compute", "probe-int", lambda: hinge_fit.compute(5, True), ("probe",)),
        Row(S + "hinge_fit.compute", "quick-str", lambda: hinge_fit.compute(PROBE, "no"),
            ("quick",)),
        Row(S + "hinge_fit.compute", "probe-a-scene", lambda: hinge_fit.compute(SCENE, True),
            ("probe",)),
        Row(S + "hinge_fit.compute", "n_jobs-zero", lambda: hinge_fit.compute(PROBE, True, 0),
            ("n_jobs",)),
        Row(S + "mode_zones.compute", "probe-a-scene", lambda: mode_zones.compute(SCENE, True),
            ("probe",)),
        Row(S + "mode_zones.compute", "quick-none", lambda: mode_zones.compute(PROBE, None),
            ("quick",)),
        # the quick run's 50 contacts, from 1 % to 99 % of the probe
        Row(S + "mode_zones.compute", "quick-by-hand", lambda: mode_zones.compute(PROBE, True),
            same=lambda r: r.length == PROBE.length and len(r.zones.frequency) == 50),
        Row(S + "time_frequency.compute", "scene-int", lambda: time_frequency.compute(5, 0),
            ("scene",)),
        Row(S + "time_frequency.compute", "seed-negative",
            lambda: time_frequency.compute(SCENE, -1), ("seed",)),
        Row(S + "time_frequency.compute", "scene-a-probe",
            lambda: time_frequency.compute(PROBE, 0), ("scene",)),
        Row(S + "physics_controls.control_design", "quick-str",
            lambda: physics_controls.control_design("no"), ("quick",)),
        Row(S + "physics_controls.control_design", "quick-none",
            lambda: physics_controls.control_design(None), ("quick",)),
        # a NumPy bool is a bool: the full design, three repetitions
        Row(S + "physics_controls.control_design", "numpy-false",
            lambda: physics_controls.control_design(np.bool_(False)),
            same=lambda d: d is controls.ABLATION_DESIGN and d.repetitions == 3),
        Row(S + "physics_controls.control_design", "quick-one-repetition",
            lambda: physics_controls.control_design(True), same=lambda d: d.repetitions == 1),
    ]
    return rows + _scene_steps()


def _controls():
    """The controls that rebuild data sets: every argument refused before any is built."""
    p = "ebantenna.paper.controls."
    rows = [
        Row(p + "ablation_accuracies", "cache_dir-int",
            lambda: controls.ablation_accuracies(SCENE, cache_dir=5), ("cache_dir",)),
        Row(p + "ablation_accuracies", "cache_dir-in-proc",
            lambda: controls.ablation_accuracies(SCENE, cache_dir=PROC), ("cache_dir",)),
        Row(p + "ablation_accuracies", "cache_dir-a-file",
            lambda: controls.ablation_accuracies(SCENE, cache_dir=a_file()), ("cache_dir",)),
        Row(p + "ablation_accuracies", "design-int",
            lambda: controls.ablation_accuracies(SCENE, design=5, cache_dir=CACHE), ("design",)),
        Row(p + "ablation_accuracies", "splits-1",
            lambda: controls.ablation_accuracies(SCENE, cache_dir=CACHE, splits=1), ("splits",)),
        Row(p + "ablation_accuracies", "n_jobs-0",
            lambda: controls.ablation_accuracies(SCENE, cache_dir=CACHE, n_jobs=0), ("n_jobs",)),
        Row(p + "ablation_accuracies", "names-a-string",
            lambda: controls.ablation_accuracies(SCENE, "object_modes", cache_dir=CACHE),
            ("names",)),
        Row(p + "ablation_accuracies", "scene-int",
            lambda: controls.ablation_accuracies(5, cache_dir=CACHE), ("scene",)),
    ]
    for name in ("equivalent_pair_accuracy", "equivalent_pair_spread"):
        f = getattr(controls, name)
        rows += [
            Row(p + name, "design-int", lambda f=f: f(SCENE, design=5, cache_dir=CACHE),
                ("design",)),
            Row(p + name, "cache_dir-in-proc", lambda f=f: f(SCENE, cache_dir=PROC),
                ("cache_dir",)),
            Row(p + name, "cache_dir-int", lambda f=f: f(SCENE, cache_dir=5), ("cache_dir",)),
            Row(p + name, "n_jobs-0", lambda f=f: f(SCENE, cache_dir=CACHE, n_jobs=0),
                ("n_jobs",)),
            Row(p + name, "classifier-unknown",
                lambda f=f: f(SCENE, cache_dir=CACHE, classifier="knn"), ("classifier",)),
            Row(p + name, "reference-unknown",
                lambda f=f: f(SCENE, cache_dir=CACHE, reference="gold"), ("gold",)),
            Row(p + name, "scene-without-a-rod", lambda f=f: f(Scene(), cache_dir=CACHE),
                ("scene",)),
            Row(p + name, "seed-negative", lambda f=f: f(SCENE, cache_dir=CACHE, seed=-1),
                ("seed",)),
        ]
    rows.append(Row(p + "equivalent_pair_spread", "splits-1",
                    lambda: controls.equivalent_pair_spread(SCENE, cache_dir=CACHE, splits=1),
                    ("splits",)))
    return rows


# --- the cache -------------------------------------------------------------------------------

def _built(folder: Path):
    return build_dataset(folder, SCENE, TINY, seed=1, n_jobs=1, show_progress=False)


def _cache_with(name: str, spoil) -> Path:
    """A cache folder holding the tiny data set's file, then ``spoil(path)`` done to it."""
    folder = CACHE / f"cache-{name}"
    spoil(_built(folder).path)
    return folder


def _same_as_simulated(ds) -> bool:
    """The data set equals the one simulated afresh, and its file is a valid data set again."""
    from ebantenna.simulate import load_dataset

    fresh = ds_()
    again = load_dataset(ds.path)
    return (np.array_equal(ds.ax, fresh.ax) and np.array_equal(ds.az, fresh.az)
            and np.array_equal(again.ax, fresh.ax)
            and not any(p.name.startswith(".") for p in ds.path.parent.iterdir()))


def _replace_with(make):
    def spoil(path: Path):
        path.unlink()
        make(path)
    return spoil


def _stale(path: Path):
    """The file of another seed under this one's name: a stale configuration."""
    other = build_dataset(path.parent / "other", SCENE, TINY, seed=2, n_jobs=1,
                          show_progress=False)
    os.replace(other.path, path)


def _cache_rows():
    spoils = {
        "truncated": lambda p: os.truncate(p, 100),
        "empty": lambda p: os.truncate(p, 0),
        "text": lambda p: p.write_text("t,ax,az\n", encoding="utf-8"),
        "fifo": _replace_with(os.mkfifo),
        "link-to-dev-zero": _replace_with(lambda p: os.symlink("/dev/zero", p)),
        "dangling-link": _replace_with(lambda p: os.symlink(p.parent / "missing.npz", p)),
        "stale-config": _stale,
    }
    rows = [Row("file:cache", f"{name}-rebuilt",
                lambda name=name, spoil=spoil: _built(_cache_with(name, spoil)),
                same=_same_as_simulated) for name, spoil in spoils.items()]
    rows += [
        # a valid file is reused as it is, not simulated again
        Row("file:cache", "valid-reused", _reused, same=lambda same_file: same_file),
        Row("file:cache", "a-folder-in-its-place", lambda: _built(_cache_with(
            "folder", _replace_with(lambda p: p.mkdir()))), ("paper-contract-tiny-seed1.npz",)),
        Row("file:cache", "cache-a-file", lambda: _built(Path(a_file())), ("a-file",)),
    ]
    return rows


def _reused() -> bool:
    folder = CACHE / "cache-reused"
    first = _built(folder).path
    stamp = first.stat().st_mtime_ns
    second = _built(folder)
    return second.path == first and first.stat().st_mtime_ns == stamp and np.array_equal(
        second.ax, ds_().ax)


ROWS = _computes() + _renders() + _controls() + _cache_rows()


@pytest.mark.parametrize("row", ROWS, ids=[f"{'.'.join(r.surface.rsplit('.', 2)[-2:])}:{r.id}"
                                           for r in ROWS])
def test_every_row_ends_in_a_clear_error_or_the_right_answer(row):
    check_row(row, row.id)


def test_the_row_ids_are_distinct_per_surface():
    keys = [(r.surface, r.id) for r in ROWS]
    assert len(set(keys)) == len(keys)


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    out: dict[str, list[str]] = {}
    for row in ROWS:
        out.setdefault(row.surface, []).append(row.id)
    return out
