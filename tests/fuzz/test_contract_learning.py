"""The input contract of the learning building blocks and the paper's estimators.

The kernels, Platt's sigmoid and libsvm's generator, the MLP's backpropagation steps and
optimisers, the one-vs-one votes, the sparse helpers, the paper's estimators and its data
design and protocol plan: each gets bad inputs of the kinds it takes, and must refuse each with
a ``ValueError`` or ``TypeError`` naming the parameter before any work; a few good inputs are
checked against values worked by hand.

Found by these rows and fixed: an unknown activation name silently taken as the identity (in
the forward pass, its derivative and the output loss), ``l2_penalty`` dividing by zero samples,
Adam and momentum optimisers built with a negative learning rate or ``beta_1 = 1``, a Gram
matrix of NaN points returned, of 10**6 points allocating 7 TiB, NumPy's "einstein sum" message
for a 1-D ``squared_norms``, Platt's sigmoid trained on mismatched or NaN decision values,
``IndexError`` from the pairwise coupling and the votes, libsvm's generator taking a seed
string and a permutation of 10**12, ``protocol_plan(seed=-1)`` accepted, ``design("yes")``
taken as the quick design, and a ``RuntimeError`` (not scikit-learn's ``NotFittedError``, a
``ValueError``) from an unfitted mode-curve classifier.
"""

from __future__ import annotations

import math
import os
import sys

import numpy as np
import scipy.sparse as sp

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, row_tests  # noqa: E402

from ebantenna.fem import Rod  # noqa: E402
from ebantenna.ml import backprop, kernels, optimizers, platt, sparse_input  # noqa: E402
from ebantenna.paper import controls, estimators, mode_curves, position_aware  # noqa: E402
from ebantenna.paper import data as paper_data  # noqa: E402
from ebantenna.simulate import builtin_scene  # noqa: E402
from ebantenna.study import rod_geometry  # noqa: E402
from ebantenna.study.recorded import calibration, planning  # noqa: E402

NAN = math.nan
RNG = np.random.default_rng(0)
X = RNG.normal(size=(12, 3))
Y = np.array([0, 1] * 6)
NOT_REAL = {"nan": NAN, "inf": math.inf, "10**400": 10**400, "str": "1", "None": None,
            "bool": True}


def _numbers(surface, param, make, extra=()):
    return [Row(surface, f"{param}={label}", (lambda v=v: make(v)), (param,))
            for label, v in [*NOT_REAL.items(), *extra]]


def _kernel_rows():
    k = "ebantenna.ml.kernels."
    return [
        Row(k + "gram_matrix", "X-str", lambda: kernels.gram_matrix("abc"), ("X",)),
        Row(k + "gram_matrix", "X-nan", lambda: kernels.gram_matrix(X * NAN), ("X",)),
        Row(k + "gram_matrix", "X-1-D", lambda: kernels.gram_matrix(np.ones(3)), ("X",)),
        Row(k + "gram_matrix", "X-complex", lambda: kernels.gram_matrix(X + 1j), ("X",)),
        Row(k + "gram_matrix", "Y-other-features",
            lambda: kernels.gram_matrix(X, np.ones((2, 4))), ("Y",)),
        Row(k + "gram_matrix", "Y-inf", lambda: kernels.gram_matrix(X, X * math.inf), ("Y",)),
        Row(k + "gram_matrix", "10**6-points",
            lambda: kernels.gram_matrix(np.zeros((10**6, 1))), ("X",)),
        Row(k + "gram_matrix", "kernel-unknown", lambda: kernels.gram_matrix(X, kernel="x"),
            ("kernel",)),
        Row(k + "gram_matrix", "gamma-negative", lambda: kernels.gram_matrix(X, gamma=-1.0),
            ("gamma",)),
        Row(k + "gram_matrix", "sparse-nan",
            lambda: kernels.gram_matrix(sp.csr_matrix(np.array([[NAN, 1.0]]))), ("X",)),
        # rbf of points 1 apart at gamma 0.5: exp(-0.5) off the diagonal, exactly 1 on it
        Row(k + "gram_matrix", "rbf-by-hand",
            lambda: kernels.gram_matrix([[0.0], [1.0]], gamma=0.5),
            same=lambda K: K[0, 0] == K[1, 1] == 1.0
            and math.isclose(K[0, 1], math.exp(-0.5), rel_tol=4e-16)),
        Row(k + "Kernel", "name-unknown", lambda: kernels.Kernel("x"), ("kernel",)),
        Row(k + "Kernel", "degree-negative", lambda: kernels.Kernel("poly", degree=-1),
            ("degree",)),
        Row(k + "Kernel", "coef0-nan", lambda: kernels.Kernel("poly", coef0=NAN), ("coef0",)),
        Row(k + "Kernel.gram", "X-str", lambda: kernels.Kernel().gram("abc"), ("X",)),
        Row(k + "Kernel.gram", "Y-other-features",
            lambda: kernels.Kernel().gram(X, np.ones((2, 5))), ("Y",)),
        Row(k + "Kernel.gram", "10**6-points",
            lambda: kernels.Kernel("linear").gram(np.zeros((10**6, 1))), ("X",)),
        Row(k + "Kernel.diagonal", "X-1-D", lambda: kernels.Kernel().diagonal(np.ones(3)),
            ("X",)),
        Row(k + "Kernel.diagonal", "linear-by-hand",
            lambda: kernels.Kernel("linear").diagonal([[3.0, 4.0]]),
            same=lambda d: d.tolist() == [25.0]),
        Row(k + "resolve_gamma", "unknown", lambda: kernels.resolve_gamma("x", X), ("gamma",)),
        Row(k + "resolve_gamma", "negative", lambda: kernels.resolve_gamma(-1.0, X),
            ("gamma",)),
        # 'scale': 1 / (n_features * X.var()); X of variance 1/4 and 2 features: 2
        Row(k + "resolve_gamma", "scale-by-hand",
            lambda: kernels.resolve_gamma("scale", np.array([[0.0, 1.0], [1.0, 0.0]])),
            same=lambda g: g == 2.0),
        Row(k + "squared_norms", "X-str", lambda: kernels.squared_norms("abc"), ("X",)),
        Row(k + "squared_norms", "X-1-D", lambda: kernels.squared_norms(np.ones(3)), ("X",)),
        Row(k + "squared_norms", "by-hand", lambda: kernels.squared_norms([[3.0, 4.0]]),
            same=lambda n: n.tolist() == [25.0]),
    ]


def _platt_rows():
    p = "ebantenna.ml.platt."
    rows = [
        Row(p + "sigmoid_train", "labels-short", lambda: platt.sigmoid_train([1.0, 2.0], [1]),
            ("labels",)),
        Row(p + "sigmoid_train", "dec_values-nan",
            lambda: platt.sigmoid_train([NAN, 2.0], [1, 0]), ("dec_values",)),
        Row(p + "sigmoid_train", "dec_values-2-D",
            lambda: platt.sigmoid_train(np.ones((2, 2)), [1, 0]), ("dec_values",)),
        Row(p + "sigmoid_train", "labels-str", lambda: platt.sigmoid_train([1.0, 2.0], "ab"),
            ("labels",)),
        Row(p + "sigmoid_predict", "dec_values-str",
            lambda: platt.sigmoid_predict("ab", 1.0, 0.0), ("dec_values",)),
        # 1 / (1 + exp(A f + B)) at A f + B = 0 and at -1e3 (no overflow)
        Row(p + "sigmoid_predict", "by-hand",
            lambda: platt.sigmoid_predict(np.array([0.0, 1e3]), -1.0, 0.0),
            same=lambda r: r.tolist() == [0.5, 1.0]),
        Row(p + "LibsvmRandom", "seed-negative", lambda: platt.LibsvmRandom(-1), ("seed",)),
        Row(p + "LibsvmRandom", "seed-str", lambda: platt.LibsvmRandom("1"), ("seed",)),
        Row(p + "LibsvmRandom", "seed-2**32", lambda: platt.LibsvmRandom(2**32), ("seed",)),
        Row(p + "LibsvmRandom.bounded", "bound-0", lambda: platt.LibsvmRandom(1).bounded(0),
            ("bound",)),
        Row(p + "LibsvmRandom.bounded", "bound-2**33",
            lambda: platt.LibsvmRandom(1).bounded(2**33), ("bound",)),
        Row(p + "LibsvmRandom.permutation", "n-negative",
            lambda: platt.LibsvmRandom(1).permutation(-1), ("n",)),
        Row(p + "LibsvmRandom.permutation", "n-10**12",
            lambda: platt.LibsvmRandom(1).permutation(10**12), ("n",)),
        Row(p + "LibsvmRandom.permutation", "n-float",
            lambda: platt.LibsvmRandom(1).permutation(5.0), ("n",)),
        Row(p + "LibsvmRandom.permutation", "a-permutation",
            lambda: platt.LibsvmRandom(7).permutation(50),
            same=lambda r: sorted(r.tolist()) == list(range(50))),
        # std::mt19937 with its default seed 5489: the 10000th draw is fixed by the C++ standard
        Row(p + "LibsvmRandom.raw", "mt19937-10000th", lambda: [
            platt.LibsvmRandom(5489).raw() for _ in range(1)] and _ten_thousandth(),
            same=lambda r: r == 4123659995),
        Row(p + "LibsvmRandom.reseed", "back-to-the-first", lambda: _reseeded(),
            same=lambda r: r[0] == r[1]),
        Row(p + "multiclass_probability", "r-not-square",
            lambda: platt.multiclass_probability(np.ones((2, 2, 3))), ("r",)),
        Row(p + "multiclass_probability", "r-2-D",
            lambda: platt.multiclass_probability(np.ones((2, 2))), ("r",)),
        Row(p + "multiclass_probability", "r-nan",
            lambda: platt.multiclass_probability(np.full((1, 2, 2), NAN)), ("r",)),
        # two classes, P(0 | 0 or 1) = 0.8: the coupled probabilities are (0.8, 0.2), reached
        # to the iteration's documented stop (0.005 / k); they sum to 1 to rounding
        Row(p + "multiclass_probability", "two-classes-by-hand",
            lambda: platt.multiclass_probability(np.array([[[0, 0.8], [0.2, 0]]])),
            same=lambda r: np.allclose(r, [[0.8, 0.2]], rtol=0, atol=0.0025)
            and abs(r.sum() - 1) < 1e-15),
    ]
    return rows


def _ten_thousandth():
    g = platt.LibsvmRandom(5489)
    for _ in range(9999):
        g.raw()
    return g.raw()


def _reseeded():
    g = platt.LibsvmRandom(3)
    first = [g.raw() for _ in range(3)]
    g.reseed()
    return first, [g.raw() for _ in range(3)]


def _mlp_rows():
    b, o = "ebantenna.ml.backprop.", "ebantenna.ml.optimizers."
    z = np.array([[-1.0, 2.0]])
    rows = [
        Row(b + "activate", "name-unknown", lambda: backprop.activate("x", z), ("name",)),
        Row(b + "activate", "relu-by-hand", lambda: backprop.activate("relu", z),
            same=lambda r: r.tolist() == [[0.0, 2.0]]),
        Row(b + "activation_derivative", "name-unknown",
            lambda: backprop.activation_derivative("x", z, z), ("name",)),
        Row(b + "activation_derivative", "tanh-by-hand",
            lambda: backprop.activation_derivative("tanh", np.array([0.0, 0.5]), np.ones(2)),
            same=lambda r: r.tolist() == [1.0, 0.75]),
        Row(b + "output_loss", "out_activation-unknown",
            lambda: backprop.output_loss("x", z, z), ("out_activation",)),
        Row(b + "output_loss", "identity-by-hand", lambda: backprop.output_loss(
            "identity", np.array([[1.0], [3.0]]), np.array([[0.0], [3.0]])),
            same=lambda r: r[0] == 0.25 and r[1].tolist() == [[0.5], [0.0]]),
        Row(b + "glorot_uniform", "sizes-one", lambda: backprop.glorot_uniform(
            [3], "relu", np.random.default_rng(0)), ("sizes",)),
        Row(b + "glorot_uniform", "sizes-zero", lambda: backprop.glorot_uniform(
            [3, 0], "relu", np.random.default_rng(0)), ("sizes",)),
        Row(b + "glorot_uniform", "sizes-10**6-square", lambda: backprop.glorot_uniform(
            [10**6, 10**6], "relu", np.random.default_rng(0)), ("sizes",)),
        Row(b + "glorot_uniform", "rng-int", lambda: backprop.glorot_uniform([3, 2], "relu", 5),
            ("rng",)),
        Row(b + "glorot_uniform", "activation-unknown", lambda: backprop.glorot_uniform(
            [3, 2], "x", np.random.default_rng(0)), ("activation",)),
        # relu: bound sqrt(6 / (3 + 2)) = 1.0954...; every weight inside it
        Row(b + "glorot_uniform", "within-the-bound", lambda: backprop.glorot_uniform(
            [3, 2], "relu", np.random.default_rng(0)),
            same=lambda r: r[0][0].shape == (3, 2)
            and np.all(np.abs(r[0][0]) <= math.sqrt(6 / 5))),
        Row(b + "l2_penalty", "n_samples-0",
            lambda: backprop.l2_penalty([np.ones((2, 2))], 0.1, 0), ("n_samples",)),
        Row(b + "l2_penalty", "alpha-nan",
            lambda: backprop.l2_penalty([np.ones((2, 2))], NAN, 3), ("alpha",)),
        Row(b + "l2_penalty", "alpha-negative",
            lambda: backprop.l2_penalty([np.ones((2, 2))], -1.0, 3), ("alpha",)),
        Row(b + "l2_penalty", "by-hand",
            lambda: backprop.l2_penalty([np.full((2, 1), 3.0)], alpha=1.0, n_samples=9),
            same=lambda r: r == 1.0),
        Row(b + "pack", "intercepts-missing", lambda: backprop.pack([np.ones((2, 2))], []),
            ("intercepts",)),
        Row(b + "pack", "by-hand", lambda: backprop.pack([np.ones((2, 1))], [np.zeros(1)]),
            same=lambda r: r.tolist() == [1.0, 1.0, 0.0]),
        Row(b + "unpack", "w-short", lambda: backprop.unpack(np.ones(3), [(2, 2)]), ("w",)),
        Row(b + "unpack", "shapes-zero", lambda: backprop.unpack(np.ones(3), [(0, 2)]),
            ("shapes",)),
        Row(b + "unpack", "inverse-of-pack", lambda: backprop.unpack(np.arange(9.0), [(2, 3)]),
            same=lambda r: r[0][0].tolist() == [[0, 1, 2], [3, 4, 5]]
            and r[1][0].tolist() == [6, 7, 8]),
    ]
    one = [np.ones(2)]
    rows += _numbers(o + "Adam", "learning_rate", lambda v: optimizers.Adam(one, v),
                     [("0", 0.0), ("-1", -1.0)])
    rows += [
        Row(o + "Adam", "beta_1-1", lambda: optimizers.Adam(one, beta_1=1.0), ("beta_1",)),
        Row(o + "Adam", "beta_2-nan", lambda: optimizers.Adam(one, beta_2=NAN), ("beta_2",)),
        Row(o + "Adam", "epsilon-0", lambda: optimizers.Adam(one, epsilon=0.0), ("epsilon",)),
        Row(o + "Adam.update", "grads-other-shape",
            lambda: optimizers.Adam(one).update([np.ones(2)], [np.ones(3)]), ("grads",)),
        Row(o + "Adam.update", "params-missing",
            lambda: optimizers.Adam(one).update([], [np.ones(2)]), ("params",)),
        # the first step of Adam moves every weight by the learning rate, against the gradient;
        # epsilon = 1e-8 beside sqrt(v) = sqrt(1 - beta_2) |g| >= 0.09 shortens it by < 2e-7 of
        # itself (2e-8 here)
        Row(o + "Adam.update", "first-step-by-hand", lambda: _adam_step(),
            same=lambda w: np.allclose(w, [1.0 - 0.1, 1.0 + 0.1], rtol=0, atol=2e-8)),
    ]
    rows += _numbers(o + "Momentum", "learning_rate", lambda v: optimizers.Momentum(one, v),
                     [("0", 0.0)])
    rows += [
        Row(o + "Momentum", "momentum-2", lambda: optimizers.Momentum(one, 0.1, momentum=2.0),
            ("momentum",)),
        Row(o + "Momentum", "nesterov-str",
            lambda: optimizers.Momentum(one, 0.1, nesterov="no"), ("nesterov",)),
        Row(o + "Momentum.update", "grads-missing",
            lambda: optimizers.Momentum(one, 0.1).update([np.ones(2)], []), ("grads",)),
        # plain momentum, first step: w - lr g
        Row(o + "Momentum.update", "first-step-by-hand", lambda: _momentum_step(),
            same=lambda w: w.tolist() == [0.75, 1.25]),
    ]
    s = "ebantenna.ml.sparse_input."
    rows += [
        Row(s + "as_csr", "X-str", lambda: sparse_input.as_csr("abc"), ("X",)),
        Row(s + "as_csr", "X-3-D", lambda: sparse_input.as_csr(np.ones((2, 2, 2))), ("X",)),
        Row(s + "as_csr", "X-complex-sparse",
            lambda: sparse_input.as_csr(sp.csr_matrix(np.ones((2, 2)) * 1j)), ("X",)),
        Row(s + "as_csr", "summed-duplicates", lambda: sparse_input.as_csr(
            sp.csr_matrix((np.array([1.0, 2.0]), np.array([0, 0]), np.array([0, 2])),
                          shape=(1, 2))),
            same=lambda r: r.has_canonical_format and r.toarray().tolist() == [[3.0, 0.0]]),
        Row(s + "sparse_variance", "X-str", lambda: sparse_input.sparse_variance("abc"), ("X",)),
        Row(s + "sparse_variance", "equals-var", lambda: sparse_input.sparse_variance(
            sparse_input.as_csr([[0.0, 2.0], [0.0, 0.0]])), same=lambda r: r == 0.75),
        Row(s + "squared_norms_sparse", "X-dense",
            lambda: sparse_input.squared_norms_sparse(np.ones((2, 2))), ("X",)),
        Row(s + "squared_norms_sparse", "by-hand", lambda: sparse_input.squared_norms_sparse(
            sparse_input.as_csr([[3.0, 4.0], [0.0, 0.0]])), same=lambda r: r.tolist() == [25, 0]),
    ]
    return rows


def _adam_step():
    w = np.ones(2)
    optimizers.Adam([w], learning_rate=0.1).update([w], [np.array([3.0, -5.0])])
    return w


def _momentum_step():
    w = np.ones(2)
    optimizers.Momentum([w], 0.25, nesterov=False).update([w], [np.array([1.0, -1.0])])
    return w


def _paper_rows():
    p, e = "ebantenna.paper.", "ebantenna.paper.estimators."
    feats = np.abs(X[:, :2]) + 0.1
    decay = np.column_stack([np.linspace(0.05, 0.3, 12), RNG.uniform(0.02, 0.08, 12),
                             RNG.uniform(1.0, 3.0, 12)])
    modes = np.abs(X) + 1.0
    rows = [
        Row(p + "data.design", "quick-str", lambda: paper_data.design("yes"), ("quick",)),
        Row(p + "data.design", "by-hand", lambda: (paper_data.design().repetitions,
                                                   paper_data.design(True).contact_step),
            same=lambda r: r == (25, 0.05)),
        Row(p + "data.paper_dataset_plan", "seed-negative",
            lambda: paper_data.paper_dataset_plan(seed=-1), ("seed",)),
        Row(p + "data.paper_dataset_plan", "scene-int",
            lambda: paper_data.paper_dataset_plan(scene=5), ("scene",)),
        Row(p + "data.paper_dataset_plan", "quick-None",
            lambda: paper_data.paper_dataset_plan(quick=None), ("quick",)),
        Row(p + "controls.equivalent_rod", "other-int",
            lambda: controls.equivalent_rod(Rod("pvc"), 5), ("other",)),
        Row(p + "controls.equivalent_rod", "reference-str",
            lambda: controls.equivalent_rod("pvc", "steel"), ("reference",)),
        Row(p + "controls.equivalent_rod", "other-unknown",
            lambda: controls.equivalent_rod(Rod("pvc"), "gold"), ("gold",)),
        Row(p + "controls.equivalent_rod", "same-cantilever-frequency", lambda: (lambda a: (
            controls.equivalent_rod(a, "steel").cantilever_frequency()
            / a.cantilever_frequency()))(Rod("aluminium", diameter=0.012, free_length=0.25)),
            same=lambda r: math.isclose(r, 1.0, rel_tol=1e-12)),
        Row(p + "controls.equivalent_pair_scenes", "reference-unknown",
            lambda: controls.equivalent_pair_scenes(builtin_scene("paper"), reference="gold"),
            ("gold",)),
        Row(p + "controls.equivalent_pair_scenes", "scene-str",
            lambda: controls.equivalent_pair_scenes("paper"), ("scene",)),
        Row(e + "DecayMaterialClassifier", "degree-6",
            lambda: estimators.DecayMaterialClassifier(6).fit(decay, Y), ("degree",)),
        Row(e + "DecayMaterialClassifier", "degree-1.5",
            lambda: estimators.DecayMaterialClassifier(1.5).fit(decay, Y), ("degree",)),
        Row(e + "DecayMaterialClassifier.fit", "X-two-columns",
            lambda: estimators.DecayMaterialClassifier().fit(decay[:, :2], Y), ("X",)),
        Row(e + "DecayMaterialClassifier.fit", "tau-negative",
            lambda: estimators.DecayMaterialClassifier().fit(decay * [1, -1, 1], Y), ("tau",)),
        Row(e + "DecayMaterialClassifier.predict", "unfitted",
            lambda: estimators.DecayMaterialClassifier().predict(decay), ("fit",)),
        Row(e + "DecayMaterialClassifier.predict_proba", "unfitted",
            lambda: estimators.DecayMaterialClassifier().predict_proba(decay), ("fit",)),
        Row(e + "DecayMaterialClassifier.predict", "X-other-columns",
            lambda: estimators.DecayMaterialClassifier().fit(decay, Y).predict(X[:, :2]),
            ("X",)),
        Row(e + "FrequencyDistanceEstimator", "out_of_range-unknown",
            lambda: estimators.FrequencyDistanceEstimator("x").fit(feats[:, :1], Y + 0.1),
            ("out_of_range",)),
        Row(e + "FrequencyDistanceEstimator.fit", "X-nan",
            lambda: estimators.FrequencyDistanceEstimator().fit(feats[:, :1] * NAN, Y + 0.1),
            ("X",)),
        Row(e + "FrequencyDistanceEstimator.predict", "unfitted",
            lambda: estimators.FrequencyDistanceEstimator().predict(feats[:, :1]), ("fit",)),
        Row(e + "MultiModeDistanceEstimator", "n_grid-0",
            lambda: estimators.MultiModeDistanceEstimator(0).fit(modes, np.arange(12) / 50),
            ("n_grid",)),
        Row(e + "MultiModeDistanceEstimator.fit", "y-two-distances",
            lambda: estimators.MultiModeDistanceEstimator().fit(modes, Y + 0.1), ("distances",)),
        Row(e + "MultiModeDistanceEstimator.predict", "unfitted",
            lambda: estimators.MultiModeDistanceEstimator().predict(modes), ("fit",)),
        Row(e + "MultiModeDistanceEstimator.cost", "unfitted",
            lambda: estimators.MultiModeDistanceEstimator().cost(modes), ("fit",)),
    ]
    m = p + "mode_curves.ModeCurveClassifier"
    rows += [
        Row(m, "n_grid-0", lambda: mode_curves.ModeCurveClassifier(0).fit(
            modes, Y, np.abs(X[:, 0])), ("n_grid",)),
        Row(m + ".fit", "distance-short", lambda: mode_curves.ModeCurveClassifier().fit(
            modes, Y, [0.1]), ("distance",)),
        *[Row(f"{m}.{method}", "unfitted",
              (lambda method=method: getattr(mode_curves.ModeCurveClassifier(), method)(modes)),
              ("fit",)) for method in ("predict", "misfit", "place", "predict_distance")],
    ]
    a = p + "position_aware.PositionAwareMaterialClassifier"
    rows += [
        Row(a, "C-negative", lambda: position_aware.PositionAwareMaterialClassifier(C=-1).fit(
            X, Y), ("C",)),
        Row(a + ".fit", "X-nan", lambda: position_aware.PositionAwareMaterialClassifier().fit(
            X * NAN, Y), ("X",)),
        Row(a + ".predict", "unfitted",
            lambda: position_aware.PositionAwareMaterialClassifier().predict(X), ("fit",)),
        Row(a + ".standardise", "unfitted",
            lambda: position_aware.PositionAwareMaterialClassifier().standardise(X), ("fit",)),
    ]
    r = "ebantenna.study."
    rows += [
        Row(r + "recorded.planning.protocol_plan", "quick-str",
            lambda: planning.protocol_plan(quick="no"), ("quick",)),
        Row(r + "recorded.planning.protocol_plan", "seed-negative",
            lambda: planning.protocol_plan(seed=-1), ("seed",)),
        Row(r + "recorded.planning.protocol_plan", "scene-int",
            lambda: planning.protocol_plan(scene=5), ("scene",)),
        Row(r + "recorded.planning.protocol_plan", "quick-by-hand",
            lambda: planning.protocol_plan(quick=True),
            same=lambda plan: plan.repetitions == 3 and plan.contacts[:2] == (0.025, 0.075)),
        Row(r + "recorded.calibration.loss_factor_of", "x-str",
            lambda: calibration.loss_factor_of("abc", 1000.0, 10.0), ("x",)),
        Row(r + "recorded.calibration.loss_factor_of", "x-short",
            lambda: calibration.loss_factor_of(np.ones(10), 1000.0, 10.0), ("x",)),
        Row(r + "recorded.calibration.loss_factor_of", "fs-0",
            lambda: calibration.loss_factor_of(np.ones(100), 0.0, 10.0), ("fs",)),
        Row(r + "recorded.calibration.loss_factor_of", "frequency-above-the-band",
            lambda: calibration.loss_factor_of(np.ones(1000), 1000.0, 450.0), ("frequency",)),
        Row(r + "recorded.calibration.loss_factor_of", "ringing-by-hand", lambda: _ringing(),
            same=lambda r: abs(r[0] / 0.02 - 1) < 0.05 and abs(r[1] / 40.0 - 1) < 1e-3),
        Row(r + "rod_geometry.closest_materials", "diameter-negative",
            lambda: rod_geometry.closest_materials(builtin_scene("paper"), -1, 0.1),
            ("diameter",)),
        Row(r + "rod_geometry.closest_materials", "materials-unknown",
            lambda: rod_geometry.closest_materials(builtin_scene("paper"), 0.01, 0.1,
                                                   materials=["gold"]), ("gold",)),
    ]
    return rows


def _ringing():
    """A 40 Hz mode of loss factor 0.02 ringing over 2 s at 1000 Hz: the estimator reads both
    (its bias on a decay this long is under 5 % of the loss factor, 1e-3 of the frequency)."""
    t = np.arange(2000) / 1000.0
    omega = 2 * np.pi * 40.0
    return calibration.loss_factor_of(np.exp(-0.02 * omega * t / 2) * np.sin(omega * t),
                                      1000.0, 40.0)


def all_rows():
    return _kernel_rows() + _platt_rows() + _mlp_rows() + _paper_rows()


(IDS, test_the_rows_are_distinct, test_every_row_ends_in_a_clear_error_or_the_right_answer,
 contract_rows) = row_tests(all_rows, 'ebantenna.')
