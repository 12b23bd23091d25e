"""The input contract of the learning engines' parts: the network's passes, SCG, the SMO steps,
the kernel rows, the one-vs-one layout, Platt's folds and coupling, and the estimators'
prediction and incremental-training methods.

Each part refuses a bad input of the kinds it takes (a list where an array is changed in place,
layers that do not chain, a row index outside the problem, labels outside the declared classes,
NaN samples, another number of features) with a ``ValueError`` or ``TypeError`` naming the
parameter, before any work; a good input is checked against a value worked by hand or against
the estimator's own other method.

Found by these rows and fixed: ``KernelRows.row(-1)`` silently answered the last row; the SMO
steps, ``forward``, ``backprop`` and ``rbf_in_place`` answered NumPy's broadcast or index
messages for arrays of the wrong shape; ``partial_fit(X, y, classes=[0, 1])`` with a label 2 in
``y`` trained, its rows binarised to no class at all (so did a warm-started ``fit`` on new
labels); ``classes=[]`` was reported as "y has 0 samples"; ``predict_log_proba`` and
``partial_fit`` answered scikit-learn's text for NaN or a 1-D ``X``, and NumPy's for a string.
"""

from __future__ import annotations

import math
import os
import sys
import warnings

import numpy as np
import scipy.sparse as sp

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, row_tests  # noqa: E402

from ebantenna.ml import (  # noqa: E402
    SVC,
    MLPClassifier,
    MLPRegressor,
    backprop,
    kernels,
    optimizers,
    ovo,
    pair_kernels,
    platt,
    smo,
    smo_policy,
    sparse_input,
)

NAN = math.nan
RNG = np.random.default_rng(5)
X = RNG.normal(size=(15, 3))
Y3 = np.array([0, 1, 2] * 5)


def _mlp():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return MLPClassifier((4,), max_iter=20, random_state=0).fit(X, Y3)


def _svc():
    return SVC(probability=True, random_state=0).fit(X, Y3)


def _sgd(cls=MLPClassifier):
    return cls((3,), solver="sgd", random_state=0)


def _bowl():
    A = np.array([[3.0, 1.0], [1.0, 2.0]])
    return lambda w: (0.5 * float(w @ A @ w), A @ w)


def _estimator_rows():
    c, r, s = ("ebantenna.ml.mlp.MLPClassifier.", "ebantenna.ml.mlp.MLPRegressor.",
               "ebantenna.ml.svc.SVC.")
    return [
        Row(c + "predict_log_proba", "X-other-features",
            lambda: _mlp().predict_log_proba(X[:, :2]), ("X has 2 features",)),
        Row(c + "predict_log_proba", "X-nan", lambda: _mlp().predict_log_proba(X * NAN),
            ("X must contain only finite",)),
        Row(c + "predict_log_proba", "X-1-D", lambda: _mlp().predict_log_proba(X[0]),
            ("X must be a 2-D array",)),
        Row(c + "predict_log_proba", "X-str", lambda: _mlp().predict_log_proba("abc"), ("X",)),
        Row(c + "predict_log_proba", "X-ragged",
            lambda: _mlp().predict_log_proba([[1.0, 2.0, 3.0], [1.0]]),
            ("X must be a rectangular",)),
        Row(c + "predict_log_proba", "unfitted",
            lambda: MLPClassifier().predict_log_proba(X), ("fit",)),
        # the log of predict_proba, computed stably: equal to it within a few ulps of log(p)
        Row(c + "predict_log_proba", "log-of-predict_proba",
            lambda: (lambda m: (m.predict_log_proba(X), m.predict_proba(X)))(_mlp()),
            same=lambda r: np.allclose(np.exp(r[0]), r[1], rtol=1e-13, atol=0)),
        Row(c + "partial_fit", "y-outside-classes",
            lambda: _sgd().partial_fit(X, Y3, classes=[0, 1]), ("not in classes",)),
        Row(c + "partial_fit", "classes-str",
            lambda: _sgd().partial_fit(X, Y3, classes="abc"), ("classes",)),
        Row(c + "partial_fit", "classes-empty",
            lambda: _sgd().partial_fit(X, Y3, classes=[]), ("classes",)),
        Row(c + "partial_fit", "classes-2-D",
            lambda: _sgd().partial_fit(X, Y3, classes=[[0, 1], [2, 3]]), ("classes",)),
        Row(c + "partial_fit", "new-labels-on-the-second-call",
            lambda: _sgd().partial_fit(X, Y3, classes=[0, 1, 2]).partial_fit(X, Y3 + 5),
            ("not in classes",)),
        Row(c + "partial_fit", "X-nan-on-the-second-call",
            lambda: _sgd().partial_fit(X, Y3, classes=[0, 1, 2]).partial_fit(X * NAN, Y3),
            ("X must contain only finite",)),
        Row(c + "partial_fit", "X-other-features-on-the-second-call",
            lambda: _sgd().partial_fit(X, Y3, classes=[0, 1, 2]).partial_fit(X[:, :2], Y3),
            ("X has 2 features",)),
        # classes declared beyond those of the first batch are kept
        Row(c + "partial_fit", "classes-beyond-the-batch",
            lambda: _sgd().partial_fit(X, Y3, classes=[0, 1, 2, 7]).classes_,
            same=lambda r: r.tolist() == [0, 1, 2, 7]),
        Row(c + "fit", "warm-start-new-labels", lambda: MLPClassifier(
            (3,), max_iter=5, warm_start=True, random_state=0).fit(X, Y3).fit(X, Y3 + 5),
            ("not in classes_",)),
        Row(r + "partial_fit", "X-other-features-on-the-second-call",
            lambda: _sgd(MLPRegressor).partial_fit(X, X[:, 0]).partial_fit(X[:, :2], X[:, 0]),
            ("X has 2 features",)),
        Row(r + "partial_fit", "X-nan", lambda: _sgd(MLPRegressor).partial_fit(X * NAN, X[:, 0]),
            ("X must contain only finite",)),
        Row(r + "partial_fit", "X-1-D", lambda: _sgd(MLPRegressor).partial_fit(X[:, 0], X[:, 0]),
            ("X must be a 2-D array",)),
        Row(r + "partial_fit", "y-other-length",
            lambda: _sgd(MLPRegressor).partial_fit(X, X[:3, 0]), ("y must hold one target",)),
        Row(r + "partial_fit", "y-nan", lambda: _sgd(MLPRegressor).partial_fit(X, X[:, 0] * NAN),
            ("y must contain only finite",)),
        Row(r + "fit", "y-inf", lambda: MLPRegressor((3,), max_iter=5).fit(X, X[:, 0] * math.inf),
            ("y must contain only finite",)),
        Row(c + "partial_fit", "y-other-length",
            lambda: _sgd().partial_fit(X, Y3[:4], classes=[0, 1, 2]), ("y must hold one",)),
        Row(c + "fit", "y-ragged", lambda: MLPClassifier((3,), max_iter=5).fit(X, [[0, 1], [2]]),
            ("y must be a rectangular",)),
        Row(r + "partial_fit", "y-other-dimensions-on-the-second-call",
            lambda: _sgd(MLPRegressor).partial_fit(X, X[:, 0]).partial_fit(X, X[:, :2]),
            ("y has 2 dimension",)),
        # one epoch per call (as scikit-learn's): two losses recorded, 2 x 15 samples seen
        Row(r + "partial_fit", "one-epoch-per-call",
            lambda: _sgd(MLPRegressor).partial_fit(X, X[:, 0]).partial_fit(X, X[:, 0]),
            same=lambda m: m.t_ == 30 and len(m.loss_curve_) == 2),
        Row(s + "predict_log_proba", "X-other-features",
            lambda: _svc().predict_log_proba(X[:, :2]), ("X has 2 features",)),
        Row(s + "predict_log_proba", "X-inf", lambda: _svc().predict_log_proba(X * math.inf),
            ("X must contain only finite",)),
        Row(s + "predict_log_proba", "X-1-D", lambda: _svc().predict_log_proba(X[0]),
            ("X must be a 2-D array",)),
        Row(s + "predict_log_proba", "unfitted",
            lambda: SVC(probability=True).predict_log_proba(X), ("fit",)),
        Row(s + "predict_log_proba", "log-of-predict_proba",
            lambda: (lambda m: (m.predict_log_proba(X), m.predict_proba(X)))(_svc()),
            same=lambda r: np.array_equal(r[0], np.log(r[1]))),
    ]


def _network_rows():
    b, o = "ebantenna.ml.backprop.", "ebantenna.ml.optimizers."
    W = [np.ones((3, 2)), np.ones((2, 1))]
    bias = [np.zeros(2), np.zeros(1)]
    rows = [
        Row(b + "forward", "layers-do-not-chain",
            lambda: backprop.forward(X, [np.ones((3, 2)), np.ones((3, 1))], bias, "relu"),
            ("coefs[1]",)),
        Row(b + "forward", "X-other-features",
            lambda: backprop.forward(X[:, :2], W, bias, "relu"), ("coefs[0]",)),
        Row(b + "forward", "intercepts-short", lambda: backprop.forward(X, W, bias[:1], "relu"),
            ("intercepts",)),
        Row(b + "forward", "intercept-wrong-size",
            lambda: backprop.forward(X, W, [np.zeros(3), np.zeros(1)], "relu"),
            ("intercepts[0]",)),
        Row(b + "forward", "X-1-D", lambda: backprop.forward(X[0], W, bias, "relu"), ("X",)),
        Row(b + "forward", "activation-unknown", lambda: backprop.forward(X, W, bias, "x"),
            ("activation",)),
        Row(b + "forward", "coefs-empty", lambda: backprop.forward(X, [], [], "relu"),
            ("coefs",)),
        # all-ones weights, relu: each hidden unit is the row sum, the output twice that
        Row(b + "forward", "by-hand",
            lambda: backprop.forward(np.array([[1.0, 2.0, -0.5]]), W, bias, "relu")[-1],
            same=lambda z: z.tolist() == [[5.0]]),
        Row(b + "backprop", "delta-wrong-shape", lambda: backprop.backprop(
            backprop.forward(X, W, bias, "relu"), np.ones((15, 2)), W, "relu", 0.0), ("delta",)),
        Row(b + "backprop", "acts-short", lambda: backprop.backprop(
            [X], np.ones((15, 1)), W, "relu", 0.0), ("acts",)),
        Row(b + "backprop", "alpha-negative", lambda: backprop.backprop(
            backprop.forward(X, W, bias, "relu"), np.ones((15, 1)), W, "relu", -1.0),
            ("alpha_per_sample",)),
        Row(b + "backprop", "activation-unknown", lambda: backprop.backprop(
            backprop.forward(X, W, bias, "relu"), np.ones((15, 1)), W, "x", 0.0),
            ("activation",)),
        Row(b + "loss_and_gradients", "Y-wrong-shape", lambda: backprop.loss_and_gradients(
            X, np.ones((15, 2)), W, bias, "relu", "identity", 0.0), ("Y",)),
        Row(b + "loss_and_gradients", "alpha-nan", lambda: backprop.loss_and_gradients(
            X, np.ones((15, 1)), W, bias, "relu", "identity", NAN), ("alpha",)),
        Row(b + "loss_and_gradients", "out_activation-unknown",
            lambda: backprop.loss_and_gradients(X, np.ones((15, 1)), W, bias, "relu", "x", 0.0),
            ("out_activation",)),
        # the gradient against central differences of the loss (h = 1e-6: error O(h^2)
        # plus rounding 1e-16 / h, about 1e-10 on a loss of order 1)
        Row(b + "loss_and_gradients", "gradient-by-differences", lambda: _gradient_check(),
            same=lambda r: r < 1e-7),
    ]
    rows += [
        Row(o + "scg_init", "w-2-D", lambda: optimizers.scg_init(np.ones((2, 2)), _bowl()),
            ("w",)),
        Row(o + "scg_init", "w-nan", lambda: optimizers.scg_init(np.array([NAN, 1.0]), _bowl()),
            ("w",)),
        Row(o + "scg_init", "fg-not-callable", lambda: optimizers.scg_init(np.ones(2), 5),
            ("fg",)),
        Row(o + "scg_init", "lambda0-negative",
            lambda: optimizers.scg_init(np.ones(2), _bowl(), lambda0=-1.0), ("lambda0",)),
        Row(o + "scg_init", "gradient-wrong-shape",
            lambda: optimizers.scg_init(np.ones(2), lambda w: (1.0, np.ones(3))), ("fg",)),
        Row(o + "scg_init", "loss-inf",
            lambda: optimizers.scg_init(np.ones(2), lambda w: (math.inf, np.ones(2))),
            ("not finite",)),
        # at the start the direction is the steepest descent
        Row(o + "scg_init", "direction-is-minus-gradient",
            lambda: optimizers.scg_init(np.array([3.0, -4.0]), _bowl()),
            same=lambda st: st.d.tolist() == [-5.0, 5.0] and st.f == 17.5),
        Row(o + "scg_step", "state-dict", lambda: optimizers.scg_step({"w": 1}, _bowl()),
            ("state",)),
        Row(o + "scg_step", "sigma0-0", lambda: optimizers.scg_step(
            optimizers.scg_init(np.ones(2), _bowl()), _bowl(), sigma0=0.0), ("sigma0",)),
        Row(o + "scg_step", "fg-not-callable", lambda: optimizers.scg_step(
            optimizers.scg_init(np.ones(2), _bowl()), None), ("fg",)),
        # two undamped steps reach the minimum of a two-parameter quadratic (conjugate
        # gradients); 1e-6 covers the finite-difference curvature's rounding
        Row(o + "scg_step", "two-steps-to-the-minimum", lambda: _scg_two_steps(),
            same=lambda w: np.linalg.norm(w) < 1e-6),
        Row(o + "SCGState", "w-list", lambda: optimizers.SCGState([1.0], 1.0, np.ones(1),
                                                                  np.ones(1)), ("w",)),
        Row(o + "SCGState", "grad-other-shape", lambda: optimizers.SCGState(
            np.ones(2), 1.0, np.ones(3), np.ones(2)), ("grad",)),
        Row(o + "SCGState", "f-str", lambda: optimizers.SCGState(
            np.ones(2), "1", np.ones(2), np.ones(2)), ("f",)),
        Row(o + "SCGState", "beta-negative", lambda: optimizers.SCGState(
            np.ones(2), 1.0, np.ones(2), np.ones(2), beta=-1.0), ("beta",)),
        Row(o + "SCGState", "n_success-float", lambda: optimizers.SCGState(
            np.ones(2), 1.0, np.ones(2), np.ones(2), n_success=1.5), ("n_success",)),
    ]
    return rows


def _gradient_check():
    rng = np.random.default_rng(0)
    coefs = [rng.normal(size=(3, 2)), rng.normal(size=(2, 1))]
    intercepts = [rng.normal(size=2), rng.normal(size=1)]
    Yt = rng.normal(size=(15, 1))
    _, grads, _ = backprop.loss_and_gradients(X, Yt, coefs, intercepts, "tanh", "identity", 0.1)
    h, worst = 1e-6, 0.0
    for k in range(coefs[0].size):
        plus = [c.copy() for c in coefs]
        minus = [c.copy() for c in coefs]
        plus[0].flat[k] += h
        minus[0].flat[k] -= h
        lp = backprop.loss_and_gradients(X, Yt, plus, intercepts, "tanh", "identity", 0.1)[0]
        lm = backprop.loss_and_gradients(X, Yt, minus, intercepts, "tanh", "identity", 0.1)[0]
        worst = max(worst, abs((lp - lm) / (2 * h) - grads[0].flat[k]))
    return worst


def _scg_two_steps():
    st = optimizers.scg_init(np.array([3.0, -4.0]), _bowl(), lambda0=0.0)
    for _ in range(2):
        optimizers.scg_step(st, _bowl())
    return st.w


def _smo_rows():
    m = "ebantenna.ml.smo."
    y = np.array([1.0, 1.0, -1.0])
    K = np.eye(3)
    G, a, C = -np.ones(3), np.zeros(3), np.ones(3)
    K2 = np.array([[4.0, 0.0], [0.0, 0.0]])
    y2 = np.array([1.0, -1.0])
    rows = [
        Row(m + "select_working_set", "y-short",
            lambda: smo.select_working_set(G, y[:2], a, C, K), ("y",)),
        Row(m + "select_working_set", "G-list",
            lambda: smo.select_working_set([-1.0] * 3, y, a, C, K), ("G",)),
        Row(m + "select_working_set", "K-not-square",
            lambda: smo.select_working_set(G, y, a, C, np.ones((3, 2))), ("K",)),
        Row(m + "select_working_set", "rule-unknown",
            lambda: smo.select_working_set(G, y, a, C, K, rule="x"), ("rule",)),
        Row(m + "select_working_set", "empty",
            lambda: smo.select_working_set(np.ones(0), np.ones(0), np.ones(0), np.ones(0),
                                           np.ones((0, 0))), ("G",)),
        # at alpha = 0 every gradient is -1; I_up holds the positives: violation 1 - (-1)
        Row(m + "select_working_set", "by-hand", lambda: smo.select_working_set(G, y, a, C, K),
            same=lambda r: r == (0, 2, 2.0)),
        Row(m + "solve_two_variable", "i-out-of-range",
            lambda: smo.solve_two_variable(5, 1, np.zeros(2), -np.ones(2), y2, np.ones(2), K2),
            ("i",)),
        Row(m + "solve_two_variable", "j-negative",
            lambda: smo.solve_two_variable(0, -1, np.zeros(2), -np.ones(2), y2, np.ones(2), K2),
            ("j",)),
        Row(m + "solve_two_variable", "K-wrong-size",
            lambda: smo.solve_two_variable(0, 1, np.zeros(2), -np.ones(2), y2, np.ones(2), K),
            ("K",)),
        # two points at distance 2 (linear kernel): the margin's alphas, 2 / 2^2 each
        Row(m + "solve_two_variable", "by-hand", lambda: smo.solve_two_variable(
            0, 1, np.zeros(2), -np.ones(2), y2, np.full(2, 10.0), K2),
            same=lambda r: r == (0.5, 0.5)),
        Row(m + "update_gradient", "K-wrong-size",
            lambda: smo.update_gradient(-np.ones(2), K, y2, 0, 1, 0.5, 0.5), ("K",)),
        Row(m + "update_gradient", "j-out-of-range",
            lambda: smo.update_gradient(-np.ones(2), K2, y2, 0, 2, 0.5, 0.5), ("j",)),
        Row(m + "update_gradient", "by-hand",
            lambda: smo.update_gradient(-np.ones(2), K2, y2, 0, 1, 0.5, 0.5),
            same=lambda r: r.tolist() == [1.0, -1.0]),
        Row(m + "bias", "C-short", lambda: smo.bias(G, y, a, C[:2]), ("C",)),
        Row(m + "bias", "alpha-str", lambda: smo.bias(G, y, "abc", C), ("alpha",)),
        # the mean of y G over the free variables
        Row(m + "bias", "by-hand", lambda: smo.bias(np.array([0.5, -0.25]), y2,
                                                    np.array([0.5, 0.5]), np.ones(2)),
            same=lambda r: r == 0.375),
    ]
    lin = kernels.Kernel("linear")
    rows2 = kernels.KernelRows(np.array([[0.0], [2.0]]), lin, np.float64, cache_bytes=1 << 20)
    rows += [
        Row(m + "solve_smo", "rows-array",
            lambda: smo.solve_smo(K2, y2, np.ones(2), diagonal=np.diag(K2)), ("rows",)),
        Row(m + "solve_smo", "y-not-plus-minus-one",
            lambda: smo.solve_smo(rows2, np.array([0.0, 1.0]), np.ones(2),
                                  diagonal=np.diag(K2)), ("y",)),
        Row(m + "solve_smo", "C-negative",
            lambda: smo.solve_smo(rows2, y2, -np.ones(2), diagonal=np.diag(K2)), ("C",)),
        Row(m + "solve_smo", "diagonal-short",
            lambda: smo.solve_smo(rows2, y2, np.ones(2), diagonal=np.ones(1)), ("diagonal",)),
        Row(m + "solve_smo", "tol-0",
            lambda: smo.solve_smo(rows2, y2, np.ones(2), diagonal=np.diag(K2), tol=0.0),
            ("tol",)),
        Row(m + "solve_smo", "max_iter-0",
            lambda: smo.solve_smo(rows2, y2, np.ones(2), diagonal=np.diag(K2), max_iter=0),
            ("max_iter",)),
        # the margin is the whole gap: alpha = 2 / 2^2, the bias the midpoint
        Row(m + "solve_smo", "by-hand", lambda: smo.solve_smo(
            rows2, np.array([-1.0, 1.0]), np.full(2, 10.0), diagonal=np.array([0.0, 4.0])),
            same=lambda r: r.alpha.tolist() == [0.5, 0.5] and r.rho == 1.0 and r.converged),
        Row("ebantenna.ml.smo_policy.positive_semidefinite", "kernel-unknown",
            lambda: smo_policy.positive_semidefinite("gauss"), ("kernel",)),
        Row("ebantenna.ml.smo_policy.positive_semidefinite", "gram-missing",
            lambda: smo_policy.positive_semidefinite("precomputed"), ("gram",)),
        Row("ebantenna.ml.smo_policy.positive_semidefinite", "gram-not-square",
            lambda: smo_policy.positive_semidefinite("precomputed", np.ones((2, 3))), ("gram",)),
        Row("ebantenna.ml.smo_policy.positive_semidefinite", "gram-nan",
            lambda: smo_policy.positive_semidefinite("precomputed", np.full((2, 2), NAN)),
            ("gram",)),
        Row("ebantenna.ml.smo_policy.positive_semidefinite", "kernel-int",
            lambda: smo_policy.positive_semidefinite(5, np.eye(2)), ("kernel",)),
        Row("ebantenna.ml.smo_policy.positive_semidefinite", "coef0-nan",
            lambda: smo_policy.positive_semidefinite("poly", coef0=NAN), ("coef0",)),
        Row("ebantenna.ml.smo_policy.positive_semidefinite", "coef0-str",
            lambda: smo_policy.positive_semidefinite("poly", coef0="1"), ("coef0",)),
        # a Gram matrix X X^T is PSD; diag(1, -1) is not
        Row("ebantenna.ml.smo_policy.positive_semidefinite", "by-hand", lambda: (
            smo_policy.positive_semidefinite("precomputed", X @ X.T),
            smo_policy.positive_semidefinite("precomputed", np.diag([1.0, -1.0]))),
            same=lambda r: r == (True, False)),
    ]
    return rows


def _kernel_rows():
    k, p = "ebantenna.ml.kernels.", "ebantenna.ml.pair_kernels.PairKernels"
    pts = np.array([[0.0], [1.0], [3.0]])
    lin = kernels.Kernel("linear")

    def rows(cache=1 << 10):
        return kernels.KernelRows(pts, lin, np.float64, cache_bytes=cache)

    members = [np.array([0, 1]), np.array([2]), np.array([3, 4])]
    five = np.array([[0.0], [1.0], [3.0], [4.0], [6.0]])
    out = [
        Row(k + "KernelRows.row", "i-negative", lambda: rows().row(-1), ("i",)),
        Row(k + "KernelRows.row", "i-beyond", lambda: rows().row(3), ("i",)),
        Row(k + "KernelRows.row", "i-float", lambda: rows().row(1.0), ("i",)),
        Row(k + "KernelRows.row", "cached-by-hand", lambda: rows(cache=8).row(2),
            same=lambda r: r.tolist() == [0.0, 3.0, 9.0]),
        Row(k + "KernelRows.row64", "i-beyond", lambda: rows().row64(3), ("i",)),
        Row(k + "KernelRows.row64", "by-hand", lambda: kernels.KernelRows(
            pts, lin, np.float32, cache_bytes=1 << 10).row64(1),
            same=lambda r: r.dtype == np.float64 and r.tolist() == [0.0, 1.0, 3.0]),
        Row(k + "KernelRows.block64", "rows-list", lambda: rows().block64([2], np.array([0])),
            ("rows",)),
        Row(k + "KernelRows.block64", "cols-beyond",
            lambda: rows().block64(np.array([2]), np.array([0, 5])), ("cols",)),
        Row(k + "KernelRows.block64", "cols-float",
            lambda: rows().block64(np.array([2]), np.array([0.0])), ("cols",)),
        Row(k + "KernelRows.block64", "by-hand",
            lambda: rows().block64(np.array([2]), np.array([0, 1])),
            same=lambda r: r.tolist() == [[0.0, 3.0]]),
        Row(k + "rbf_in_place", "block-list",
            lambda: kernels.rbf_in_place([[1.0]], 0.5, np.ones(1), np.ones(1)), ("block",)),
        Row(k + "rbf_in_place", "block-int",
            lambda: kernels.rbf_in_place(np.ones((1, 1), dtype=int), 0.5, np.ones(1),
                                         np.ones(1)), ("block",)),
        Row(k + "rbf_in_place", "gamma-nan",
            lambda: kernels.rbf_in_place(np.ones((1, 1)), NAN, np.ones(1), np.ones(1)),
            ("gamma",)),
        Row(k + "rbf_in_place", "y_norms-short",
            lambda: kernels.rbf_in_place(np.ones((1, 2)), 0.5, np.ones(1), np.ones(1)),
            ("y_norms",)),
        Row(k + "rbf_in_place", "scratch-short",
            lambda: kernels.rbf_in_place(np.ones((2, 2)), 0.5, np.ones(2), np.ones(2),
                                         scratch=np.empty(3)), ("scratch",)),
        # |x|^2 = |y|^2 = 1, x.y = 1 and 0: squared distances 0 and 2, exp(-0.5 * that)
        Row(k + "rbf_in_place", "by-hand", lambda: _rbf_block(),
            same=lambda r: r[0, 0] == 1.0 and math.isclose(r[0, 1], math.exp(-1.0),
                                                            rel_tol=4e-16)),
        Row(p, "members-array",
            lambda: pair_kernels.PairKernels(five, np.arange(5), lin, np.float64, 1 << 20),
            ("members",)),
        Row(p, "members-beyond-X", lambda: pair_kernels.PairKernels(
            five, [np.array([0, 9]), np.array([2])], lin, np.float64, 1 << 20), ("members[0]",)),
        Row(p, "kernel-str", lambda: pair_kernels.PairKernels(
            five, members, "linear", np.float64, 1 << 20), ("kernel",)),
        Row(p, "cache_bytes-negative", lambda: pair_kernels.PairKernels(
            five, members, lin, np.float64, -1), ("cache_bytes",)),
        Row(p, "given-not-square", lambda: pair_kernels.PairKernels(
            None, members, None, np.float64, 1 << 20, given=np.ones((5, 4))), ("given",)),
        Row(p + ".rows", "a-not-below-b", lambda: pair_kernels.PairKernels(
            five, members, lin, np.float64, 1 << 20).rows(2, 1), ("b",)),
        Row(p + ".rows", "b-beyond", lambda: pair_kernels.PairKernels(
            five, members, lin, np.float64, 1 << 20).rows(0, 3), ("b",)),
        # point 1 against points 0, 1, 3, 4 of classes 0 and 2, in every layout
        *[Row(p + ".rows", f"by-hand-{cache}", (lambda cache=cache: pair_kernels.PairKernels(
            five, members, lin, np.float64, cache).rows(0, 2).row(1)),
            same=lambda r: r.tolist() == [0.0, 1.0, 4.0, 6.0]) for cache in (1 << 20, 8)],
        Row("ebantenna.ml.sparse_input.recompute_cancelled", "X-dense",
            lambda: sparse_input.recompute_cancelled(np.zeros((1, 1)), np.ones((1, 1)),
                                                     _csr([[1.0]]), np.ones(1), np.ones(1)),
            ("X",)),
        Row("ebantenna.ml.sparse_input.recompute_cancelled", "d-wrong-shape",
            lambda: sparse_input.recompute_cancelled(np.zeros((2, 2)), _csr([[1.0]]),
                                                     _csr([[1.0]]), np.ones(1), np.ones(1)),
            ("d",)),
        Row("ebantenna.ml.sparse_input.recompute_cancelled", "Y-other-columns",
            lambda: sparse_input.recompute_cancelled(np.zeros((1, 1)), _csr([[1.0]]),
                                                     _csr([[1.0, 2.0]]), np.ones(1), np.ones(1)),
            ("Y",)),
        Row("ebantenna.ml.sparse_input.recompute_cancelled", "y_norms-short",
            lambda: sparse_input.recompute_cancelled(np.zeros((1, 2)), _csr([[1.0]]),
                                                     _csr([[1.0], [2.0]]), np.ones(1),
                                                     np.ones(1)), ("y_norms",)),
        # x = (1e8, 1), y = (1e8, 0): the expansion loses the distance 1 entirely; recomputed
        Row("ebantenna.ml.sparse_input.recompute_cancelled", "cancelled-by-hand",
            lambda: _cancelled(), same=lambda r: r[0] == 1 and r[1] == 1.0),
    ]
    return out


def _csr(a):
    return sparse_input.as_csr(sp.csr_matrix(np.array(a)))


def _rbf_block():
    block = np.array([[1.0, 0.0]])
    kernels.rbf_in_place(block, 0.5, np.array([1.0]), np.array([1.0, 1.0]))
    return block


def _cancelled():
    Xs, Ys = _csr([[1e8, 1.0]]), _csr([[1e8, 0.0]])
    xn, yn = sparse_input.squared_norms_sparse(Xs), sparse_input.squared_norms_sparse(Ys)
    d = np.maximum(xn[:, None] + yn[None, :] - 2 * (Xs @ Ys.T).toarray(), 0.0)
    count = sparse_input.recompute_cancelled(d, Xs, Ys, xn, yn)
    return count, float(d[0, 0])


def _ovo_platt_rows():
    v, p = "ebantenna.ml.ovo.", "ebantenna.ml.platt."
    pair = (np.array([0, 1, 2]), np.array([0.5, 0.0, -0.5]))
    two = [np.array([0, 1]), np.array([2])]
    rows = [
        Row(v + "ovr_decision_function", "n_classes-1",
            lambda: ovo.ovr_decision_function(np.zeros((1, 0)), np.zeros((1, 0)), 1),
            ("n_classes",)),
        Row(v + "ovr_decision_function", "predictions-other-pairs",
            lambda: ovo.ovr_decision_function(np.zeros((1, 2)), np.zeros((1, 2)), 3),
            ("predictions",)),
        Row(v + "ovr_decision_function", "predictions-not-0-or-1",
            lambda: ovo.ovr_decision_function(np.full((1, 3), 2), np.zeros((1, 3)), 3),
            ("predictions",)),
        Row(v + "ovr_decision_function", "confidences-other-shape",
            lambda: ovo.ovr_decision_function(np.zeros((1, 3)), np.zeros((2, 3)), 3),
            ("confidences",)),
        Row(v + "ovr_decision_function", "confidences-nan",
            lambda: ovo.ovr_decision_function(np.zeros((1, 3)), np.full((1, 3), NAN), 3),
            ("confidences",)),
        # votes 2, 0, 1 and the confidences' tie-breaking terms s / (3 (|s| + 1))
        Row(v + "ovr_decision_function", "by-hand", lambda: ovo.ovr_decision_function(
            np.array([[0, 0, 1]]), np.array([[-1.0, -2.0, 0.5]]), 3),
            same=lambda r: np.allclose(r, [[2.25, -0.2, 0.8]], rtol=1e-15, atol=0)),
        Row(v + "one_vs_one_coef", "dual_coef-wrong-shape", lambda: ovo.one_vs_one_coef(
            np.ones((1, 3)), np.array([1, 1]), np.ones((2, 1))), ("dual_coef",)),
        Row(v + "one_vs_one_coef", "n_support-float", lambda: ovo.one_vs_one_coef(
            np.ones((1, 2)), np.array([1.0, 1.0]), np.ones((2, 1))), ("n_support",)),
        Row(v + "one_vs_one_coef", "support_vectors-short", lambda: ovo.one_vs_one_coef(
            np.ones((1, 2)), np.array([1, 1]), np.ones((1, 1))), ("support_vectors",)),
        Row(v + "one_vs_one_coef", "by-hand", lambda: ovo.one_vs_one_coef(
            np.array([[-0.5, 0.5]]), np.array([1, 1]), np.array([[0.0], [2.0]])),
            same=lambda r: r.tolist() == [[1.0]]),
        Row(v + "dual_layout", "n-0", lambda: ovo.dual_layout(0, two, {(0, 1): pair}), ("n",)),
        Row(v + "dual_layout", "members-beyond-n",
            lambda: ovo.dual_layout(2, two, {(0, 1): pair}), ("members[1]",)),
        Row(v + "dual_layout", "coefs-list", lambda: ovo.dual_layout(3, two, [pair]),
            ("coefs",)),
        Row(v + "dual_layout", "coefs-pair-reversed",
            lambda: ovo.dual_layout(3, two, {(1, 0): pair}), ("coefs",)),
        Row(v + "dual_layout", "coefs-short-idx",
            lambda: ovo.dual_layout(3, two, {(0, 1): (np.array([0, 1]), np.ones(2))}),
            ("coefs[0, 1]",)),
        Row(v + "dual_layout", "by-hand", lambda: ovo.dual_layout(3, two, {(0, 1): pair}),
            same=lambda r: r[0].tolist() == [0, 2] and r[1].tolist() == [1, 1]
            and r[2].tolist() == [[0.5, -0.5]]),
        Row(p + "pairwise_coupling", "decisions-other-pairs", lambda: platt.pairwise_coupling(
            np.zeros((1, 2)), np.ones(1), np.ones(1), 2), ("decisions",)),
        Row(p + "pairwise_coupling", "prob_a-short", lambda: platt.pairwise_coupling(
            np.zeros((1, 3)), np.ones(2), np.ones(3), 3), ("prob_a",)),
        Row(p + "pairwise_coupling", "decisions-nan", lambda: platt.pairwise_coupling(
            np.full((1, 1), NAN), np.ones(1), np.ones(1), 2), ("decisions",)),
        Row(p + "pairwise_coupling", "n_classes-1", lambda: platt.pairwise_coupling(
            np.zeros((1, 0)), np.ones(0), np.ones(0), 1), ("n_classes",)),
        # sigma(-A f - B) at f = 2, A = -1, B = 0: 1 / (1 + e^-2)
        Row(p + "pairwise_coupling", "by-hand", lambda: platt.pairwise_coupling(
            np.array([[2.0]]), np.array([-1.0]), np.array([0.0]), 2),
            same=lambda r: np.allclose(r, [[1 / (1 + math.exp(-2)), 1 / (1 + math.exp(2))]],
                                       rtol=0, atol=0.0025)),
        Row(p + "cross_validated_decisions", "positive-short",
            lambda: platt.cross_validated_decisions(10, np.ones(3, bool), _decide,
                                                    platt.LibsvmRandom(1)), ("positive",)),
        Row(p + "cross_validated_decisions", "decide-not-callable",
            lambda: platt.cross_validated_decisions(10, np.ones(10, bool), 5,
                                                    platt.LibsvmRandom(1)), ("decide",)),
        Row(p + "cross_validated_decisions", "rng-generator",
            lambda: platt.cross_validated_decisions(10, np.ones(10, bool), _decide,
                                                    np.random.default_rng(1)), ("rng",)),
        Row(p + "cross_validated_decisions", "n_folds-1",
            lambda: platt.cross_validated_decisions(10, np.ones(10, bool), _decide,
                                                    platt.LibsvmRandom(1), 1), ("n_folds",)),
        Row(p + "cross_validated_decisions", "n-0",
            lambda: platt.cross_validated_decisions(0, np.ones(0, bool), _decide,
                                                    platt.LibsvmRandom(1)), ("n",)),
        # every point is decided by a machine trained without it: decide() returns the test
        # indices themselves, so the result is minus each point's own index
        Row(p + "cross_validated_decisions", "each-point-held-out",
            lambda: platt.cross_validated_decisions(10, np.arange(10) % 2 == 0, _decide_idx,
                                                    platt.LibsvmRandom(1)),
            same=lambda r: r.tolist() == [-float(i) for i in range(10)]),
        Row(p + "pairwise_sigmoids", "members-one-class", lambda: platt.pairwise_sigmoids(
            [np.arange(4)], _block, _solve, platt.LibsvmRandom(1)), ("members",)),
        Row(p + "pairwise_sigmoids", "members-float", lambda: platt.pairwise_sigmoids(
            [np.arange(4.0), np.arange(4, 8)], _block, _solve, platt.LibsvmRandom(1)),
            ("members[0]",)),
        Row(p + "pairwise_sigmoids", "solve-not-callable", lambda: platt.pairwise_sigmoids(
            [np.arange(4), np.arange(4, 8)], _block, None, platt.LibsvmRandom(1)), ("solve",)),
        Row(p + "pairwise_sigmoids", "rng-int", lambda: platt.pairwise_sigmoids(
            [np.arange(4), np.arange(4, 8)], _block, _solve, 1), ("rng",)),
        # three classes give three pairs, in the order (0, 1), (0, 2), (1, 2)
        Row(p + "pairwise_sigmoids", "one-sigmoid-per-pair", lambda: platt.pairwise_sigmoids(
            [np.arange(5), np.arange(5, 10), np.arange(10, 15)], _block, _solve,
            platt.LibsvmRandom(1)),
            same=lambda r: r[0].shape == r[1].shape == (3,) and np.all(np.isfinite(r[0]))),
    ]
    return rows


def _decide(train, test):
    return np.zeros(test.size)


def _decide_idx(train, test):
    return test.astype(float)


def _block(rows, cols):
    return X[rows] @ X[cols].T


def _solve(points, labels, K):
    return labels * 0.1, 0.0


def all_rows():
    return _estimator_rows() + _network_rows() + _smo_rows() + _kernel_rows() + _ovo_platt_rows()


(IDS, test_the_rows_are_distinct, test_every_row_ends_in_a_clear_error_or_the_right_answer,
 contract_rows) = row_tests(all_rows, 'ebantenna.ml.')
