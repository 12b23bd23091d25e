"""The paper's experiments on synthetic arrays, and the transcribed paper figures."""

import numpy as np
import pytest
from matplotlib.figure import Figure
from sklearn.multiclass import OneVsRestClassifier
from sklearn.svm import SVC as LibSVC

from ebantenna.ml.metrics import per_class_rates
from ebantenna.paper.experiments import (
    classify_materials_ann,
    classify_materials_svm,
    format_confusion,
    regress_distance_full_length,
    regress_distance_linear_region,
)
from ebantenna.paper.plots import plot_confusion_comparison, plot_distance_errors
from ebantenna.paper.printed import PAPER_ANN, PAPER_SVM
from ebantenna.paper.protocol import normalise_by_max

MATERIALS = ("aluminium", "brass", "pvc", "steel", "wood")


def _spectra(n_per=60, seed=0, n_bins=64, spread=1.0):
    """Synthetic magnitude spectra: a resonance that moves with the contact distance and a
    second one whose place depends on the material."""
    rng = np.random.default_rng(seed)
    labels = np.repeat(MATERIALS, n_per)
    distances = rng.choice(np.arange(0.02, 0.305, 0.02), labels.size)
    bins = np.arange(n_bins)

    def line(centre, width):
        return np.exp(-0.5 * ((bins[None, :] - centre[:, None]) / width) ** 2)

    X = line(4 + 40 * distances, 2.0 * spread)
    X += 0.6 * line(30.0 + 6 * np.searchsorted(MATERIALS, labels), 2.0)
    X += 0.05 * rng.random(X.shape)
    return 50.0 * X, labels, distances


def test_paper_figures_are_consistent_with_their_printed_percentages():
    # Fig. 12: counts add up to the printed 80.8 %, the printed recalls (bottom row) and
    # precisions (right column), which is what fixes the orientation of the printed table
    assert PAPER_ANN.accuracy("all") == pytest.approx(0.808, abs=5e-4)
    recall, precision = per_class_rates(PAPER_ANN.matrices["all"])
    np.testing.assert_allclose(100 * recall, [89.2, 75.6, 79.9, 74.7, 84.5], atol=0.05)
    np.testing.assert_allclose(100 * precision, [84.2, 80.9, 82.6, 76.1, 80.0], atol=0.05)
    # Fig. 15: an 80/20 split of 6000 samples and the printed 99.7 % / 99.2 %
    assert PAPER_SVM.matrices["train"].sum() == 4800
    assert PAPER_SVM.matrices["test"].sum() == 1200
    # 4783 / 4800 = 99.646 %: the paper prints 99.7 (rounded from 99.65), hence 6e-4
    assert PAPER_SVM.accuracy("train") == pytest.approx(0.997, abs=6e-4)
    assert PAPER_SVM.accuracy("test") == pytest.approx(0.992, abs=5e-4)


def test_svm_experiment_splits_and_matches_libsvm():
    X, y, _ = _spectra()
    res = classify_materials_svm(X, y, gamma="scale", C=10.0, seed=3)
    assert res.labels == MATERIALS
    assert res.confusions["train"].sum() == 240 and res.confusions["test"].sum() == 60
    # stratified: 12 test samples of each material
    np.testing.assert_array_equal(res.confusions["test"].sum(axis=1), [12] * 5)
    assert res.accuracies["test"] > 0.9
    # the same experiment with libsvm inside the same one-vs-rest wrapper
    from sklearn.model_selection import train_test_split

    Xn = normalise_by_max(X)
    train, test = train_test_split(np.arange(y.size), test_size=0.2, random_state=3, stratify=y)
    ref = OneVsRestClassifier(LibSVC(C=10.0, gamma="scale")).fit(Xn[train], y[train])
    agree = np.mean(ref.predict(Xn[test]) == res.model.predict(Xn[test]))
    assert agree >= 59 / 60
    assert "SVM test: accuracy" in res.report()


def test_ann_experiment_splits_70_15_15():
    X, y, _ = _spectra(n_per=40, seed=1)
    res = classify_materials_ann(X, y, hidden_layer_sizes=(12,), learning_rate_init=0.5,
                                 max_iter=300, seed=0)
    sizes = {k: int(m.sum()) for k, m in res.confusions.items()}
    assert sizes == {"train": 140, "validation": 30, "test": 30, "all": 200}
    np.testing.assert_array_equal(
        res.confusions["all"],
        res.confusions["train"] + res.confusions["validation"] + res.confusions["test"])
    assert res.accuracies["all"] > 0.9
    assert res.model.coefs_[0].shape == (64, 12)


def test_linear_region_regression_uses_only_the_first_80_percent():
    X, _, d = _spectra(n_per=40, seed=2, spread=3.0)
    res = regress_distance_linear_region(X, d, probe_length=0.30, hidden_layer_sizes=(20, 20),
                                         solver="scg", max_iter=300, seed=0)
    assert res.distance_test.max() <= 0.24 + 1e-12
    np.testing.assert_allclose(res.errors_cm, 100 * np.abs(res.predicted_test
                                                             - res.distance_test))
    # mean error per position is the mean of the per-sample errors at that position
    p = res.positions[0]
    assert res.mean_error_cm[0] == pytest.approx(res.errors_cm[res.distance_test == p].mean())
    assert res.mae_cm < 2.0  # the peak moves 40 bins per metre: distance is well encoded
    assert res.rmse_cm >= res.mae_cm
    assert "contact" in res.report()


def test_full_length_regression_with_scg_relu():
    X, _, d = _spectra(n_per=40, seed=4, spread=3.0)
    res = regress_distance_full_length(X, d, max_iter=400, seed=0)
    assert res.model.hidden_layer_sizes == (9,)
    assert res.model.solver == "scg" and res.model.activation == "relu"
    assert res.distance_test.size == 30
    assert res.mae_cm < 3.0


def test_figures_put_results_beside_the_paper():
    X, y, d = _spectra(n_per=20, seed=5)
    svm = classify_materials_svm(X, y, gamma="scale")
    fig = plot_confusion_comparison(svm)
    assert isinstance(fig, Figure)
    assert len(fig.axes) == 4  # this run and the paper, training and test
    titles = [ax.get_title() for ax in fig.axes]
    assert any("paper Fig. 15, test (printed 99.2 %)" in t for t in titles)
    # the paper's matrix is drawn in this run's class order
    paper_ax = fig.axes[3]
    assert [t.get_text() for t in paper_ax.get_yticklabels()] == list(MATERIALS)
    reg = regress_distance_full_length(X, d, max_iter=50)
    fig2 = plot_distance_errors(reg)
    assert isinstance(fig2, Figure) and fig2.axes[0].get_legend() is not None


def test_format_confusion_lists_rows_as_true_classes():
    text = format_confusion(PAPER_SVM.matrices["test"], PAPER_SVM.labels)
    lines = text.splitlines()
    assert lines[1].split() == ["aluminium", "217", "2", "1", "1", "1"]


@pytest.mark.parametrize("call, match", [
    (lambda X, y, d: classify_materials_svm(X, y[:-1]), "materials"),
    (lambda X, y, d: classify_materials_svm(X, np.full(y.size, "pvc")), "two classes"),
    (lambda X, y, d: classify_materials_svm(X, y, test_fraction=1.5), "test_fraction"),
    (lambda X, y, d: classify_materials_ann(X, y, fractions=(0.5, 0.2, 0.2)), "add up"),
    (lambda X, y, d: classify_materials_svm(X, y, labels=["pvc"]), "labels"),
    (lambda X, y, d: regress_distance_full_length(X, -d), "distances"),
    (lambda X, y, d: regress_distance_linear_region(X, d, probe_length=0.0), "probe_length"),
    (lambda X, y, d: classify_materials_svm(X * np.nan, y), "X"),
])
def test_bad_input_is_named(call, match):
    X, y, d = _spectra(n_per=5)
    with pytest.raises(ValueError, match=match):
        call(X, y, d)


def test_svm_on_a_given_split_trains_and_tests_on_those_rows():
    X, y, d = _spectra(n_per=30)
    test = np.flatnonzero(np.isin(np.round(d, 3), [0.06, 0.16, 0.26]))
    train = np.setdiff1d(np.arange(y.size), test)
    res = classify_materials_svm(X, y, gamma="scale", split=(train, test))
    assert res.confusions["train"].sum() == train.size
    assert res.confusions["test"].sum() == test.size
    lib = OneVsRestClassifier(LibSVC(kernel="rbf", gamma="scale")).fit(
        normalise_by_max(X)[train], y[train])
    ours = res.model.predict(normalise_by_max(X)[test])
    # two SMO solvers to tol 1e-3: they may part on a sample at the margin, not on more
    assert np.mean(ours == lib.predict(normalise_by_max(X)[test])) >= 0.97
    with pytest.raises(ValueError, match="both train and test"):
        classify_materials_svm(X, y, split=(train, np.r_[test, train[:1]]))


@pytest.mark.parametrize("solver", ["scg", "adam"])
def test_stateful_trainers_run_in_one_call(solver):
    """SCG's directions and Adam's moments must survive from epoch to epoch: the experiment is
    one fit of the estimator with early stopping, the same as calling it directly."""
    from ebantenna.ml import MLPClassifier
    from ebantenna.paper.protocol import three_way_split

    X, y, _ = _spectra(n_per=30)
    res = classify_materials_ann(X, y, hidden_layer_sizes=(8,), solver=solver,
                                 learning_rate_init=0.01, max_iter=200, seed=2)
    assert "validation" not in res.confusions and res.model.n_iter_ > 1
    train, val, test = three_way_split(y.size, (0.7, 0.15, 0.15), 2, stratify=y)
    rows = np.concatenate([train, val])
    direct = MLPClassifier((8,), activation="tanh", solver=solver, learning_rate_init=0.01,
                           max_iter=200, random_state=2, alpha=0.0, early_stopping=True,
                           validation_fraction=val.size / rows.size, n_iter_no_change=6)
    Xn = normalise_by_max(X)
    direct.fit(Xn[rows], y[rows])
    np.testing.assert_array_equal(res.model.predict(Xn[test]), direct.predict(Xn[test]))
    assert res.model.n_iter_ == direct.n_iter_
    assert res.confusions["test"].sum() == test.size
