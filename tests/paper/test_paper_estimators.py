import numpy as np
import pytest
from scipy.interpolate import PchipInterpolator

from ebantenna import fem  # the beam model is the witness of the calibration curves
from ebantenna.paper.estimators import (
    DecayMaterialClassifier,
    FrequencyDistanceEstimator,
    MultiModeDistanceEstimator,
)
from ebantenna.probe import Probe
from ebantenna.signal import apply_filter, fit_decay, paper_filter

PROBE = Probe()
L = PROBE.length
CAL_D = np.arange(0.01, 0.3951, 0.005)  # the paper's 5 mm calibration steps
REPS = 5
NOISE = 0.002  # 0.2 % frequency scatter between repeated contacts


@pytest.fixture(scope="module")
def calibration():
    rng = np.random.default_rng(0)
    f = fem.natural_frequencies(PROBE, CAL_D, n_modes=3)
    d = np.repeat(CAL_D, REPS)
    freqs = np.repeat(f, REPS, axis=0) * (1 + NOISE * rng.standard_normal((d.size, 3)))
    return freqs, d


@pytest.fixture(scope="module")
def test_contacts():
    rng = np.random.default_rng(1)
    d = np.linspace(0.0125, 0.39, 60)  # between calibration points, hinge to tip
    f = fem.natural_frequencies(PROBE, d, n_modes=3)
    return f * (1 + NOISE * rng.standard_normal(f.shape)), d


def test_first_mode_is_not_monotonic_and_the_limit_sits_near_80_percent(calibration):
    freqs, d = calibration
    est = FrequencyDistanceEstimator().fit(freqs[:, 0], d)
    # Witness: the turning point of the noise-free FEM curve on a fine grid.
    fine = np.linspace(0.2, 0.39, 400)
    f1 = fem.natural_frequencies(PROBE, fine, n_modes=1)[:, 0]
    turn = fine[np.argmax(f1)]
    assert 0.75 * L < turn < 0.82 * L
    assert est.limit_ == pytest.approx(turn, abs=0.0075)  # within the 5 mm calibration steps
    assert est.increasing_
    # Past the turning point f1 falls again: the same frequency belongs to two contacts.
    assert f1[-1] < f1.max() * 0.9


def test_single_mode_error_along_the_probe(calibration, test_contacts):
    freqs, d = calibration
    f_test, d_test = test_contacts
    est = FrequencyDistanceEstimator(out_of_range="clip").fit(freqs[:, 0], d)
    err_cm = np.abs(est.predict(f_test[:, 0]) - d_test) * 100
    inside = d_test <= est.limit_
    assert err_cm[inside].max() < 0.5  # the paper's 0.5 cm, met on the monotonic branch
    assert err_cm[~inside].max() > 5.0  # beyond the turning point it confuses the two branches


def test_single_mode_refuses_frequencies_it_cannot_place(calibration):
    freqs, d = calibration
    est = FrequencyDistanceEstimator().fit(freqs[:, 0], d)
    with pytest.raises(ValueError, match="calibrated range"):
        est.predict([est.frequency_range_[1] * 1.1])
    assert est.predict(est.frequency_range_[0]) == pytest.approx(d.min(), abs=1e-9)


@pytest.mark.parametrize("n_modes", [2, 3])
def test_multi_mode_covers_the_full_range(calibration, test_contacts, n_modes):
    freqs, d = calibration
    f_test, d_test = test_contacts
    est = MultiModeDistanceEstimator().fit(freqs[:, :n_modes], d)
    err_cm = np.abs(est.predict(f_test[:, :n_modes]) - d_test) * 100
    # Whole probe, hinge to tip, with 0.2 % frequency scatter: measured worst 0.08 cm.
    assert err_cm.max() < 0.2


def test_multi_mode_is_exact_on_noise_free_calibration_points():
    d = CAL_D[::4]
    f = fem.natural_frequencies(PROBE, d, n_modes=2)
    est = MultiModeDistanceEstimator(n_grid=20000).fit(f, d)
    np.testing.assert_allclose(est.predict(f), d, atol=2e-5)
    assert est.cost(f).shape == (d.size, 20000)


def _decay_features(rng, materials, distances, reps):
    """Synthetic contacts: a damped first mode whose decay and gain depend on material and distance,
    band-passed by the Table 1 filter and fitted as in section 2.3."""
    fs = 1000.0
    t = np.arange(1000) / fs
    sos = paper_filter("chebyshev")
    rows, labels = [], []
    for name, (tau_scale, gain_scale) in materials.items():
        for dist in distances:
            for _ in range(reps):
                tau = 0.06 * tau_scale * (1 + 3 * dist) * (1 + 0.03 * rng.standard_normal())
                gain = gain_scale * (1 - 2.5 * dist) * (1 + 0.03 * rng.standard_normal())
                x = gain * np.exp(-t / tau) * np.sin(2 * np.pi * (90 + 150 * dist) * t)
                x = x + 0.002 * rng.standard_normal(t.size)
                fit = fit_decay(apply_filter(sos, x), fs)
                assert fit.ok
                rows.append([dist, fit.tau, fit.a])
                labels.append(name)
    return np.array(rows), np.array(labels)


def test_material_from_decay_after_band_pass():
    rng = np.random.default_rng(2)
    # Materials 15-30 % apart in tau or gain; both also change along the probe, by more than that.
    materials = {"aluminium": (1.0, 1.0), "brass": (1.15, 0.85), "pvc": (0.8, 0.85),
                 "steel": (1.3, 1.15), "wood": (0.85, 1.15)}
    X, y = _decay_features(rng, materials, np.linspace(0.05, 0.3, 6), 6)
    Xt, yt = _decay_features(rng, materials, np.linspace(0.07, 0.28, 4), 3)
    clf = DecayMaterialClassifier(degree=2).fit(X, y)
    assert list(clf.classes_) == sorted(materials)
    assert clf.score(Xt, yt) > 0.9
    np.testing.assert_allclose(clf.predict_proba(Xt).sum(axis=1), 1.0)
    # Without the distance model the materials overlap more (gain falls along the probe).
    assert DecayMaterialClassifier(degree=0).fit(X, y).score(Xt, yt) < 0.8


def test_degree_zero_is_quadratic_discriminant_analysis():
    """Witnesses: Gaussian densities from scipy with np.cov covariances give the same posteriors;
    scikit-learn's QDA (maximum-likelihood covariances, divided by n instead of n - 1) the same
    labels."""
    from scipy.stats import multivariate_normal
    from sklearn.discriminant_analysis import QuadraticDiscriminantAnalysis

    rng = np.random.default_rng(3)
    n = 60
    X = np.column_stack([rng.uniform(0.05, 0.3, 3 * n),
                         np.exp(rng.normal(np.repeat([-2.5, -2.0, -2.2], n), 0.2)),
                         np.exp(rng.normal(np.repeat([0.0, 0.3, -0.2], n), 0.25))])
    y = np.repeat(["a", "b", "c"], n)
    ours = DecayMaterialClassifier(degree=0).fit(X, y)
    z = np.log(X[:, 1:])
    dens = np.column_stack([
        multivariate_normal(z[y == c].mean(axis=0), np.cov(z[y == c].T)).pdf(z) for c in "abc"
    ])  # equal priors here: 60 samples per class
    np.testing.assert_allclose(ours.predict_proba(X), dens / dens.sum(axis=1, keepdims=True),
                               rtol=1e-9, atol=1e-14)
    qda = QuadraticDiscriminantAnalysis().fit(z, y)
    assert np.mean(ours.predict(X) == qda.predict(z)) > 0.98


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: FrequencyDistanceEstimator().fit([1.0, 2.0], [0.1, 0.2, 0.3]), "same shape"),
        (lambda: FrequencyDistanceEstimator().fit([1.0, 2.0], [0.1, 0.2]), "3 distinct"),
        (lambda: FrequencyDistanceEstimator().fit([1.0, -2.0, 3.0], [0.1, 0.2, 0.3]), "> 0"),
        (lambda: FrequencyDistanceEstimator().fit([3.0, 2.0, 3.0, 2.0], [0.1, 0.2, 0.3, 0.4]),
         "monotonically"),
        (lambda: FrequencyDistanceEstimator().predict([1.0]), "not fitted"),
        (lambda: FrequencyDistanceEstimator(out_of_range="nan").fit([1, 2, 3.0], [1, 2, 3.0]),
         "out_of_range"),
        (lambda: MultiModeDistanceEstimator().fit(np.ones(3), [0.1, 0.2, 0.3]), "2D array"),
        (lambda: MultiModeDistanceEstimator().fit(np.ones((2, 2)), [0.1, 0.2, 0.3]), "one row"),
        (lambda: MultiModeDistanceEstimator().fit(np.ones((3, 2)), [0.1, 0.2, 0.3]).predict(
            np.ones((1, 3))), "columns"),
        (lambda: MultiModeDistanceEstimator().predict(np.ones((1, 2))), "not fitted"),
        (lambda: DecayMaterialClassifier().fit(np.ones((10, 2)), np.zeros(10)), "3 columns"),
        (lambda: DecayMaterialClassifier().fit(np.ones((10, 3)), np.zeros(10)), "two materials"),
        (lambda: DecayMaterialClassifier().fit(-np.ones((10, 3)), np.arange(10) % 2), "> 0"),
        (lambda: DecayMaterialClassifier().fit(np.ones((10, 3)), np.arange(9) % 2), "one label"),
        (lambda: DecayMaterialClassifier(degree=9).fit(np.ones((10, 3)), np.arange(10) % 2),
         "degree"),
    ],
)
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_full_range_distance_from_signals_alone(calibration):
    """From vibration records to distances: two FEM modes ring, their peaks give the contact."""
    from ebantenna.signal import peak_frequencies

    freqs, d = calibration
    est = MultiModeDistanceEstimator().fit(freqs[:, :2], d)
    rng = np.random.default_rng(7)
    t = np.arange(1000) / 1000.0
    contacts = np.array([0.05, 0.15, 0.25, 0.30, 0.33, 0.36, 0.385])  # beyond 80 % included
    modes = fem.natural_frequencies(PROBE, contacts, n_modes=2)
    predicted = []
    for f1, f2 in modes:
        x = (np.exp(-t / 0.25) * np.sin(2 * np.pi * f1 * t + rng.uniform(0, 6))
             + 0.5 * np.exp(-t / 0.1) * np.sin(2 * np.pi * f2 * t + rng.uniform(0, 6))
             + 0.01 * rng.standard_normal(t.size))
        predicted.append(est.predict(peak_frequencies(x, 1000.0, 2)[None, :])[0])
    err_cm = np.abs(np.array(predicted) - contacts) * 100
    assert err_cm.max() < 0.3


@pytest.mark.parametrize("n_modes", [1, 2, 5, 7, 9])
def test_the_misfit_is_the_weighted_sum_of_squared_log_differences(n_modes):
    """``cost`` sums mode by mode; below eight modes the additions are those of NumPy's sum over
    the last axis, bit for bit; from eight on NumPy pairs its terms, and the two orders of the
    same non-negative terms agree within n_modes rounding errors of the total."""
    rng = np.random.default_rng(n_modes)
    d = np.repeat(np.linspace(0.02, 0.38, 12), 4)
    f = (100.0 * np.arange(1, n_modes + 1) * (1 + d[:, None])) * rng.uniform(0.98, 1.02,
                                                                              (d.size, n_modes))
    est = MultiModeDistanceEstimator(50).fit(f, d)
    X = f[::5] * 1.01
    w = rng.uniform(0.1, 1.0, n_modes)
    # the calibration curves on the dense grid, from the fitted medians (as fit builds them)
    log_curves = np.log(PchipInterpolator(est.distances_, est.frequencies_, axis=0)(est.grid_))
    reference = ((np.log(X)[:, None, :] - log_curves[None, :, :]) ** 2 * w).sum(axis=2)
    cost = est.cost(X, w)
    if n_modes < 8:
        assert cost.tobytes() == reference.tobytes()
    else:
        assert np.all(np.abs(cost - reference) <= n_modes * np.finfo(float).eps * reference)
