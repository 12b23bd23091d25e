"""MLP: one gradient step against scikit-learn, gradients against finite differences, numerics."""

import warnings

import numpy as np
import pytest
from mlp_reference import EPS, max_abs, one_step_pair, rounding
from sklearn.exceptions import ConvergenceWarning
from sklearn.neural_network import MLPClassifier as SkClassifier
from sklearn.neural_network import MLPRegressor as SkRegressor

from ebantenna.ml import MLPClassifier, MLPRegressor
from ebantenna.ml.backprop import pack
from ebantenna.ml.optimizers import scg_init, scg_step


def _data(n=60, d=4, seed=0):
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(n, d))
    return X, rng


STEP = dict(alpha=0.3, max_iter=1, learning_rate_init=0.05, random_state=0)
SK_STEP = dict(solver="sgd", momentum=0.0, shuffle=False, **STEP)


@pytest.mark.parametrize("activation", ["tanh", "relu", "logistic", "identity"])
@pytest.mark.parametrize("n_classes", [2, 3])
def test_gd_step_equals_sklearn_full_batch_sgd(activation, n_classes):
    X, rng = _data()
    y = rng.integers(0, n_classes, X.shape[0])
    ours = MLPClassifier(hidden_layer_sizes=(7, 5), activation=activation, solver="gd", **STEP)
    theirs = SkClassifier(hidden_layer_sizes=(7, 5), activation=activation,
                          batch_size=X.shape[0], **SK_STEP)
    one_step_pair(ours, theirs, X, y)
    # same loss (L2 term included) and the same updated weights, to rounding
    loss = theirs.loss_curve_[-1]
    assert abs(ours.loss_curve_[-1] - loss) <= rounding(X, (7, 5), max(1.0, loss))
    weights = theirs.coefs_ + theirs.intercepts_
    atol = rounding(X, (7, 5), max_abs(weights))
    for a, b in zip(ours.coefs_ + ours.intercepts_, weights, strict=True):
        np.testing.assert_allclose(a, b, rtol=0, atol=atol)
    # probabilities lie in [0, 1]: the same bound, scaled by 1
    np.testing.assert_allclose(ours.predict_proba(X), theirs.predict_proba(X), rtol=0,
                               atol=rounding(X, (7, 5)))


@pytest.mark.parametrize("learning_rate", ["constant", "invscaling", "adaptive"])
@pytest.mark.parametrize("solver", ["gd", "sgd", "adam"])
def test_several_epochs_follow_sklearn(solver, learning_rate):
    X, rng = _data()
    y = rng.integers(0, 3, X.shape[0])
    batch = X.shape[0] if solver == "gd" else 20
    # adaptive: tol=10 makes every epoch one without improvement, so the rate drops by 5 often
    common = dict(hidden_layer_sizes=(7,), activation="tanh", learning_rate=learning_rate,
                  learning_rate_init=0.05, shuffle=False, alpha=0.01, random_state=0,
                  power_t=0.5, tol=10.0 if learning_rate == "adaptive" else 0.0,
                  n_iter_no_change=1 if learning_rate == "adaptive" else 50)
    ours = MLPClassifier(solver=solver, batch_size=batch, **common)
    theirs = SkClassifier(solver="sgd" if solver == "gd" else solver, batch_size=batch,
                          **({"momentum": 0.0} if solver == "gd" else {}), **common)
    epochs = 8
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        for est in (ours, theirs):
            est.set_params(max_iter=1).fit(X, y)
        c0 = [c.copy() for c in ours.coefs_]
        b0 = [b.copy() for b in ours.intercepts_]
        for est in (ours, theirs):
            est.coefs_ = [c.copy() for c in c0]
            est.intercepts_ = [b.copy() for b in b0]
            est.t_ = 0
            est.set_params(warm_start=True, max_iter=epochs).fit(X, y)
    assert ours.n_iter_ == theirs.n_iter_ and ours.t_ == theirs.t_
    # Each step adds at most one step's rounding; these small steps (rate <= 0.05 on a loss of
    # curvature below 1) carry earlier errors with a gain below 2 over the run.
    n_steps = epochs * (X.shape[0] // batch)
    atol = 2 * n_steps * rounding(X, (7,), max_abs(theirs.coefs_ + theirs.intercepts_))
    np.testing.assert_allclose(ours.loss_curve_[1:], theirs.loss_curve_[1:], rtol=0, atol=atol)
    for a, b in zip(ours.coefs_ + ours.intercepts_, theirs.coefs_ + theirs.intercepts_,
                    strict=True):
        np.testing.assert_allclose(a, b, rtol=0, atol=atol)


@pytest.mark.parametrize("kind, solver, learning_rate", [
    ("classifier", "sgd", "invscaling"), ("classifier", "adam", "constant"),
    ("regressor", "sgd", "constant"), ("regressor", "adam", "constant"),
])
def test_partial_fit_follows_sklearn(kind, solver, learning_rate):
    X, rng = _data()
    y = rng.integers(0, 3, X.shape[0]) if kind == "classifier" else X[:, 0] - X[:, 1] ** 2
    Ours, Theirs = ((MLPClassifier, SkClassifier) if kind == "classifier"
                    else (MLPRegressor, SkRegressor))
    common = dict(hidden_layer_sizes=(6,), activation="tanh", solver=solver, batch_size=15,
                  learning_rate=learning_rate, learning_rate_init=0.02, shuffle=False,
                  alpha=0.01, random_state=0, max_iter=1)
    ours, theirs = Ours(**common), Theirs(**common)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        for est in (ours, theirs):
            est.fit(X, y)  # sets up the network; then both start from our weights
        for est in (ours, theirs):
            est.coefs_ = [c.copy() for c in ours.coefs_]
            est.intercepts_ = [b.copy() for b in ours.intercepts_]
            est.t_ = 0
            if hasattr(est, "_optimizer"):
                del est._optimizer  # scikit-learn's would continue the one of fit
    halves = (slice(0, 30), slice(30, 60))
    for call in range(6):
        part = halves[call % 2]
        extra = {"classes": np.arange(3)} if kind == "classifier" else {}
        ours.partial_fit(X[part], y[part], **extra)
        theirs.partial_fit(X[part], y[part], **extra)
        assert ours.n_iter_ == theirs.n_iter_ == 1 and ours.t_ == theirs.t_
    # 12 steps, each adding one step's rounding, carried with a gain below 2 (small steps)
    atol = 2 * 12 * rounding(X, (6,), max_abs(theirs.coefs_ + theirs.intercepts_))
    np.testing.assert_allclose(ours.loss_curve_[1:], theirs.loss_curve_[1:], rtol=0, atol=atol)
    for a, b in zip(ours.coefs_ + ours.intercepts_, theirs.coefs_ + theirs.intercepts_,
                    strict=True):
        np.testing.assert_allclose(a, b, rtol=0, atol=atol)


def test_partial_fit_refusals():
    X, rng = _data()
    y = rng.integers(0, 3, X.shape[0])
    with pytest.raises(ValueError, match="classes must be passed"):
        MLPClassifier().partial_fit(X, y)
    assert not hasattr(MLPClassifier(solver="scg"), "partial_fit")
    with pytest.raises(ValueError, match="early_stopping"):
        MLPRegressor(early_stopping=True).partial_fit(X, X[:, 0])
    clf = MLPClassifier((4,), random_state=0).partial_fit(X, y, classes=[0, 1, 2, 3])
    assert clf.classes_.tolist() == [0, 1, 2, 3]  # a class not seen yet is still a class
    with pytest.raises(ValueError, match="not the same"):
        clf.partial_fit(X, y, classes=[0, 1])


@pytest.mark.parametrize("kind", ["classifier", "regressor"])
def test_lbfgs_follows_sklearn(kind):
    X, rng = _data()
    y = rng.integers(0, 3, X.shape[0]) if kind == "classifier" else X[:, 0] - X[:, 1] ** 2
    Ours, Theirs = ((MLPClassifier, SkClassifier) if kind == "classifier"
                    else (MLPRegressor, SkRegressor))
    common = dict(hidden_layer_sizes=(7,), activation="tanh", solver="lbfgs", alpha=0.01,
                  random_state=0, max_iter=1)
    ours, theirs = Ours(**common), Theirs(**common)
    one_step_pair(ours, theirs, X, y, max_iter=10)
    # Both stop at the same iteration, the reference run's, within the budget of 10.
    assert ours.n_iter_ == theirs.n_iter_ <= 10
    assert ours.loss_curve_[-1] == pytest.approx(theirs.loss_, rel=1e-9)
    # L-BFGS is deterministic in f and g, which the two codes compute with sums in different
    # orders; its line search and two-loop recursion carry that rounding on with a gain that
    # stays far below 1e5 over ten iterations of this well-scaled problem (after hundreds of
    # iterations the non-convex paths may fork, as any two runs of L-BFGS)
    atol = 1e5 * rounding(X, (7,), max_abs(theirs.coefs_ + theirs.intercepts_))
    for a, b in zip(ours.coefs_ + ours.intercepts_, theirs.coefs_ + theirs.intercepts_,
                    strict=True):
        np.testing.assert_allclose(a, b, rtol=0, atol=atol)


def test_lbfgs_warns_when_it_stops_early_and_learns():
    X = np.linspace(0, 1, 40)[:, None]
    y = np.sin(3 * X[:, 0])
    with pytest.warns(ConvergenceWarning, match="lbfgs failed to converge"):
        MLPRegressor((8,), solver="lbfgs", max_iter=3, random_state=0).fit(X, y)
    reg = MLPRegressor((8,), activation="tanh", solver="lbfgs", max_iter=500, tol=1e-8,
                       random_state=0).fit(X, y)
    assert reg.score(X, y) > 0.999
    assert len(reg.loss_curve_) == reg.n_iter_ and reg.best_loss_ == min(reg.loss_curve_)


def test_gd_step_equals_sklearn_for_single_output_regression():
    X, rng = _data()
    y = X @ rng.normal(size=4) + 0.1 * rng.normal(size=X.shape[0])
    ours = MLPRegressor(hidden_layer_sizes=(6,), activation="tanh", solver="gd", **STEP)
    theirs = SkRegressor(hidden_layer_sizes=(6,), activation="tanh", batch_size=X.shape[0],
                         **SK_STEP)
    one_step_pair(ours, theirs, X, y)
    loss = theirs.loss_curve_[-1]
    assert abs(ours.loss_curve_[-1] - loss) <= rounding(X, (6,), max(1.0, loss))
    weights = theirs.coefs_ + theirs.intercepts_
    atol = rounding(X, (6,), max_abs(weights))
    for a, b in zip(ours.coefs_ + ours.intercepts_, weights, strict=True):
        np.testing.assert_allclose(a, b, rtol=0, atol=atol)


def test_multi_output_regression_uses_the_true_gradient():
    X, rng = _data()
    Y = np.column_stack([X[:, 0], X[:, 1] ** 2, -X[:, 2]])  # three outputs
    params = dict(hidden_layer_sizes=(5,), activation="tanh", alpha=0.0, max_iter=1,
                  learning_rate_init=0.05, random_state=0)
    ours = MLPRegressor(solver="gd", **params)
    theirs = SkRegressor(solver="sgd", momentum=0.0, shuffle=False, batch_size=X.shape[0],
                         **params)
    c0, b0 = one_step_pair(ours, theirs, X, Y)
    # the same reported loss ...
    loss = theirs.loss_curve_[-1]
    assert abs(ours.loss_curve_[-1] - loss) <= rounding(X, (5,), max(1.0, loss))
    # ... but scikit-learn's step is n_outputs = 3 times the step of the true gradient (the
    # differences of the weights carry their rounding, scaled by the weights themselves)
    atol = rounding(X, (5,), max_abs(c0 + b0))
    for ours_new, theirs_new, start in zip(ours.coefs_ + ours.intercepts_,
                                           theirs.coefs_ + theirs.intercepts_, c0 + b0,
                                           strict=True):
        np.testing.assert_allclose(theirs_new - start, 3.0 * (ours_new - start), rtol=0,
                                   atol=atol)
    # and ours is the gradient of the reported loss: a central difference agrees
    _check_gradient(ours, X, Y)


def _check_gradient(model, X, Y, eps=1e-6, rtol=1e-6):
    """Compare the backpropagated gradient with central finite differences of the loss."""
    w0 = pack(model.coefs_, model.intercepts_)
    _, grad = model.loss_and_gradient(X, Y, w0)
    rng = np.random.default_rng(1)
    picks = rng.choice(w0.size, size=min(40, w0.size), replace=False)
    fd = np.empty(picks.size)
    for k, i in enumerate(picks):
        wp, wm = w0.copy(), w0.copy()
        wp[i] += eps
        wm[i] -= eps
        fd[k] = (model.loss_and_gradient(X, Y, wp)[0] - model.loss_and_gradient(X, Y, wm)[0])
        fd[k] /= 2 * eps
    # central differences are exact to O(eps^2) ~ 1e-12 plus rounding ~ 1e-16 / eps = 1e-10
    np.testing.assert_allclose(grad[picks], fd, rtol=rtol, atol=1e-8)


@pytest.mark.parametrize("activation", ["tanh", "logistic", "identity", "relu"])
@pytest.mark.parametrize("kind", ["binary", "multiclass", "multilabel", "regression"])
def test_gradient_matches_finite_differences(activation, kind):
    X, rng = _data(n=30, d=3, seed=2)
    common = dict(hidden_layer_sizes=(4, 3), activation=activation, alpha=0.7, max_iter=3,
                  solver="gd", random_state=3)
    if kind == "regression":
        model, y = MLPRegressor(**common), rng.normal(size=(30, 2))
        Y = y
    else:
        model = MLPClassifier(**common)
        y = {"binary": rng.integers(0, 2, 30), "multiclass": rng.integers(0, 4, 30),
             "multilabel": rng.integers(0, 2, (30, 3))}[kind]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        model.fit(X, y)
    if kind != "regression":
        Y = model._label_binarizer.transform(y).astype(float)
    _check_gradient(model, X, Y)


def test_saturated_outputs_give_finite_loss_and_probabilities():
    X, rng = _data(n=20, d=2)
    y = rng.integers(0, 3, 20)
    clf = MLPClassifier(hidden_layer_sizes=(3,), activation="logistic", solver="gd",
                        max_iter=1, random_state=0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        clf.fit(X, y)
    clf.coefs_ = [c * 1e4 for c in clf.coefs_]  # huge logits: exp would overflow naively
    Xbig = X * 1e6
    Y = clf._label_binarizer.transform(y).astype(float)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow or divide-by-zero RuntimeWarning
        loss, grad = clf.loss_and_gradient(Xbig, Y)
        proba = clf.predict_proba(Xbig)
        log_proba = clf.predict_log_proba(Xbig)
    assert np.isfinite(loss) and loss > 1.0  # confidently wrong somewhere: a large loss
    assert np.all(np.isfinite(grad))
    assert np.all(np.isfinite(proba)) and np.allclose(proba.sum(axis=1), 1.0)
    assert np.all(np.isfinite(log_proba))
    # log-probabilities from log-sum-exp stay exact where probabilities underflow to 0
    np.testing.assert_allclose(np.exp(log_proba), proba, atol=1e-300)


def test_binary_logistic_output_stable_for_huge_logits():
    X = np.array([[0.0], [1.0], [2.0], [3.0]])
    y = np.array([0, 0, 1, 1])
    clf = MLPClassifier(hidden_layer_sizes=(2,), solver="gd", max_iter=1, random_state=0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        clf.fit(X, y)
    clf.coefs_[-1][:] = 1e5
    clf.intercepts_[-1][:] = -1e8  # logit about -1e8 for every sample
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        loss, _ = clf.loss_and_gradient(X, clf._label_binarizer.transform(y).astype(float))
        lp = clf.predict_log_proba(X)
    # half the samples are positives predicted with log-probability about -1e8
    assert 0.4e8 < loss < 0.6e8
    assert np.all(np.isfinite(lp))


def test_constant_features_are_harmless():
    X, rng = _data(n=80, d=3)
    X = np.column_stack([X, np.full(80, 5.0), np.zeros(80)])
    y = (X[:, 0] > 0).astype(int)
    clf = MLPClassifier(hidden_layer_sizes=(6,), activation="tanh", solver="scg", max_iter=100,
                        random_state=0).fit(X, y)
    assert clf.score(X, y) > 0.95
    assert all(np.all(np.isfinite(c)) for c in clf.coefs_)


@pytest.mark.parametrize("solver", ["gd", "sgd", "adam", "scg"])
def test_every_solver_learns_a_smooth_function(solver):
    X = np.linspace(-1, 1, 80)[:, None]
    y = np.sin(2 * X[:, 0])
    lr = {"gd": 0.2, "sgd": 0.05, "adam": 0.01, "scg": 0.001}[solver]
    reg = MLPRegressor(hidden_layer_sizes=(10,), activation="tanh", solver=solver,
                       learning_rate_init=lr, max_iter=400, tol=0.0, n_iter_no_change=400,
                       random_state=0, batch_size=20)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        reg.fit(X, y)
    assert reg.loss_curve_[-1] < 0.5 * reg.loss_curve_[0]
    assert reg.score(X, y) > 0.9


def test_scg_beats_gd_for_the_same_number_of_epochs():
    X = np.linspace(0, 1, 60)[:, None]
    y = np.where(X[:, 0] < 0.5, X[:, 0], 1.0 - X[:, 0])
    common = dict(hidden_layer_sizes=(9,), activation="relu", max_iter=150, tol=0.0,
                  n_iter_no_change=150, random_state=4)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        scg = MLPRegressor(solver="scg", **common).fit(X, y)
        gd = MLPRegressor(solver="gd", learning_rate_init=0.1, **common).fit(X, y)
    assert scg.loss_curve_[-1] < gd.loss_curve_[-1]
    # every accepted SCG step lowers the loss: the curve never goes up (beyond the rounding of
    # the loss itself, a sum over 60 samples: 60 eps relative)
    curve = np.asarray(scg.loss_curve_)
    assert np.all(np.diff(curve) <= 60 * EPS * curve[:-1])


def test_scg_minimises_a_quadratic_like_conjugate_gradients():
    rng = np.random.default_rng(0)
    M = rng.normal(size=(6, 6))
    A = M @ M.T + 6 * np.eye(6)
    b = rng.normal(size=6)

    def fg(w):
        return 0.5 * float(w @ A @ w) - float(b @ w), A @ w - b

    state = scg_init(np.zeros(6), fg)
    for _ in range(40):
        scg_step(state, fg)
    np.testing.assert_allclose(state.w, np.linalg.solve(A, b), rtol=1e-7, atol=1e-9)


def test_scg_sigma0_and_lambda0_are_netlabs_settable_constants():
    rng = np.random.default_rng(2)
    M = rng.normal(size=(4, 4))
    A = M @ M.T + np.eye(4)

    def fg(w):
        return 0.5 * float(w @ A @ w), A @ w

    assert scg_init(np.ones(4), fg).beta == 1.0  # Netlab's lambda0
    state = scg_init(np.ones(4), fg, lambda0=5e-7)  # trainscg's
    assert state.beta == 5e-7
    d = state.d.copy()  # the first direction: steepest descent
    scg_step(state, fg, sigma0=5e-5)
    # on a quadratic the finite difference of gradients is d^T A d for any sigma0, up to the
    # rounding of A (w + sigma d) - A w: about eps |A| |w| / sigma relative to |A| |d|
    assert state.gamma == pytest.approx(float(d @ A @ d), rel=1e-8)
    X, _ = _data(n=40, d=3, seed=1)
    y = X[:, 0] - X[:, 1]
    common = dict(hidden_layer_sizes=(5,), solver="scg", max_iter=30, random_state=0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        netlab = MLPRegressor(**common).fit(X, y)
        matlab = MLPRegressor(sigma0=5e-5, lambda0=5e-7, **common).fit(X, y)
    assert netlab.loss_curve_[0] == matlab.loss_curve_[0]  # same start, different scale path
    assert netlab.loss_curve_ != matlab.loss_curve_
    with pytest.raises(ValueError, match="lambda0"):
        MLPRegressor(solver="scg", lambda0=0.0).fit(X, y)


@pytest.mark.parametrize("scale_x, scale_y", [(1.0, 1e200), (1e200, 1.0)])
def test_scg_refuses_a_loss_that_is_not_finite(scale_x, scale_y):
    X, _ = _data(n=40, d=3, seed=1)
    y = X[:, 0]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # NumPy's overflow, the cause named below
        with pytest.raises(ValueError, match="not finite"):
            MLPRegressor((5,), solver="scg", max_iter=5).fit(scale_x * X, scale_y * y)


def test_early_stopping_keeps_the_best_validation_weights():
    X, rng = _data(n=200, d=5, seed=6)
    y = (X[:, 0] + 0.8 * rng.normal(size=200) > 0).astype(int)
    clf = MLPClassifier(hidden_layer_sizes=(30,), solver="adam", learning_rate_init=0.05,
                        early_stopping=True, validation_fraction=0.2, n_iter_no_change=5,
                        max_iter=500, random_state=0).fit(X, y)
    assert clf.n_iter_ < 500
    assert len(clf.validation_scores_) == clf.n_iter_
    assert clf.best_validation_score_ == max(clf.validation_scores_)
    # stopped n_iter_no_change + 1 epochs after the last improvement by tol
    assert clf.n_iter_ - 1 - int(np.argmax(clf.validation_scores_)) >= 5


def test_max_iter_warns():
    X, rng = _data()
    with pytest.warns(ConvergenceWarning, match="maximum iterations"):
        MLPRegressor(hidden_layer_sizes=(3,), solver="gd", max_iter=2).fit(X, X[:, 0])


def test_same_seed_same_bytes():
    X, rng = _data()
    y = rng.integers(0, 3, X.shape[0])
    a = MLPClassifier(hidden_layer_sizes=(5,), max_iter=20, random_state=7, tol=0.0,
                      n_iter_no_change=100)
    b = MLPClassifier(hidden_layer_sizes=(5,), max_iter=20, random_state=7, tol=0.0,
                      n_iter_no_change=100)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        a.fit(X, y)
        b.fit(X, y)
    for u, v in zip(a.coefs_, b.coefs_, strict=True):
        assert u.tobytes() == v.tobytes()


@pytest.mark.parametrize(
    "params, error, match",
    [
        (dict(solver="newton"), ValueError, "solver"),
        (dict(activation="softplus"), ValueError, "activation"),
        (dict(hidden_layer_sizes=(0,)), ValueError, "hidden_layer_sizes"),
        (dict(hidden_layer_sizes="wide"), ValueError, "hidden_layer_sizes"),
        (dict(alpha=-1.0), ValueError, "alpha"),
        (dict(learning_rate_init=0.0), ValueError, "learning_rate_init"),
        (dict(momentum=1.5), ValueError, "momentum"),
        (dict(max_iter=0), ValueError, "max_iter"),
        (dict(batch_size=2.5), TypeError, "batch_size"),
        (dict(validation_fraction=1.0), ValueError, "validation_fraction"),
    ],
)
def test_bad_parameters_name_themselves(params, error, match):
    X, rng = _data(n=10)
    with pytest.raises(error, match=match):
        MLPRegressor(**params).fit(X, X[:, 0])


def test_warm_start_with_wrong_shapes_is_refused():
    X, rng = _data(n=10)
    reg = MLPRegressor(hidden_layer_sizes=(3,), warm_start=True)
    reg.coefs_ = [np.zeros((2, 3)), np.zeros((3, 1))]
    reg.intercepts_ = [np.zeros(3), np.zeros(1)]
    with pytest.raises(ValueError, match="coefs_"):
        reg.fit(X, X[:, 0])


def test_user_set_weights_on_a_fresh_estimator_take_one_gd_step():
    X, rng = _data()
    y = rng.integers(0, 3, X.shape[0])
    ours = MLPClassifier(hidden_layer_sizes=(7, 5), activation="tanh", solver="gd", **STEP)
    theirs = SkClassifier(hidden_layer_sizes=(7, 5), activation="tanh", batch_size=X.shape[0],
                          **SK_STEP)
    c0, b0 = one_step_pair(ours, theirs, X, y)
    fresh = MLPClassifier(hidden_layer_sizes=(7, 5), activation="tanh", solver="gd",
                          warm_start=True, **STEP)
    fresh.coefs_ = [c.copy() for c in c0]
    fresh.intercepts_ = [b.copy() for b in b0]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        fresh.fit(X, y)
    atol = rounding(X, (7, 5), max_abs(theirs.coefs_))
    for a, b in zip(fresh.coefs_, theirs.coefs_, strict=True):
        np.testing.assert_allclose(a, b, rtol=0, atol=atol)


def test_early_stopping_refuses_a_class_too_small_to_stratify_as_scikit_learn_does():
    # one member of a class cannot be split in proportion: scikit-learn raises; a silent
    # unstratified split could leave the validation rows without that class
    X = np.random.default_rng(0).normal(size=(40, 3))
    y = np.array([0] * 39 + [1])
    with pytest.raises(ValueError, match="least populated"):
        SkClassifier(early_stopping=True, max_iter=5).fit(X, y)
    with pytest.raises(ValueError, match="early_stopping: the validation split cannot hold"):
        MLPClassifier((3,), early_stopping=True, max_iter=5).fit(X, y)
