"""The compiled loops of the MLP (numba, optional) against its NumPy path: the same bits."""

import math
import subprocess
import sys
import warnings

import numpy as np
import pytest
from sklearn.exceptions import ConvergenceWarning

from ebantenna._engines import EngineStatus
from ebantenna.ml import MLPClassifier, MLPRegressor, _mlp_compiled, _mlp_numba
from ebantenna.ml._backprop_engine import Workspace, output_loss_into
from ebantenna.ml._mlp_optimizers import InPlaceAdam, InPlaceMomentum
from ebantenna.ml.optimizers import Adam, Momentum

ENGINE = "EBANTENNA_ENGINE"


def _gradients(rng, shape, steps):
    """Gradients spanning many magnitudes, zeros included (sqrt(v) + eps then near eps)."""
    out = []
    for _ in range(steps):
        g = rng.normal(size=shape) * 10.0 ** rng.integers(-12, 3, size=shape)
        g[rng.random(shape) < 0.05] = 0.0
        out.append(g)
    return out


def test_compiled_adam_step_equals_numpy_bit_for_bit(monkeypatch):
    """The compiled step (a Python loop without numba) does Adam's operations in NumPy's order:
    parameters and both moments equal to the last bit over 30 steps."""
    rng = np.random.default_rng(3)
    start = rng.normal(size=257)
    grads = _gradients(rng, start.shape, 30)
    monkeypatch.setenv(ENGINE, "numpy")
    p_numpy = [start.copy()]
    numpy_opt = Adam(p_numpy, learning_rate=0.01)
    for g in grads:
        numpy_opt.update(p_numpy, [g])
    p_loop, m, v = start.copy(), np.zeros_like(start), np.zeros_like(start)
    for t, g in enumerate(grads, start=1):
        lr = 0.01 * np.sqrt(1 - 0.999**t) / (1 - 0.9**t)
        _mlp_numba.adam_step(p_loop, g, m, v, 0.9, 0.999, 1 - 0.9, 1 - 0.999, lr, 1e-8)
    assert np.array_equal(p_loop, p_numpy[0])
    assert np.array_equal(m, numpy_opt.ms[0]) and np.array_equal(v, numpy_opt.vs[0])


def test_adam_takes_the_compiled_loop_on_contiguous_arrays_only(monkeypatch):
    """A 2-D C-ordered array goes through the loop as a flat view, a transposed one through
    NumPy calls; both land on the NumPy path's numbers."""
    if _mlp_compiled.compiled_kernels() is None:
        pytest.skip("numba is not available here")
    rng = np.random.default_rng(4)
    start = [rng.normal(size=(6, 5)), rng.normal(size=(5, 6)).T]
    grads = list(zip(_gradients(rng, (6, 5), 5), _gradients(rng, (6, 5), 5), strict=True))
    results = {}
    for engine in ("numpy", "compiled"):
        monkeypatch.setenv(ENGINE, engine)
        params = [p.copy(order="K") for p in start]
        opt = InPlaceAdam(params, learning_rate=0.05, compiled=_mlp_compiled.compiled_kernels())
        for pair in grads:
            opt.update(params, pair)
        results[engine] = params
    for a, b in zip(results["numpy"], results["compiled"], strict=True):
        assert np.array_equal(a, b)


@pytest.mark.parametrize("nesterov", [False, True])
def test_the_in_place_optimisers_equal_the_textbook_updates_bit_for_bit(nesterov):
    """The engine's updates on two temporaries against the reference's formulas, as written:
    the same operations in the same order, hence the same bits, over 30 steps."""
    rng = np.random.default_rng(5)
    start = [rng.normal(size=(7, 3)), rng.normal(size=3)]
    grads = list(zip(_gradients(rng, (7, 3), 30), _gradients(rng, (3,), 30), strict=True))
    for make_ref, make_engine in (
            (lambda p: Adam(p, 0.01), lambda p: InPlaceAdam(p, 0.01)),
            (lambda p: Momentum(p, 0.01, 0.9, nesterov),
             lambda p: InPlaceMomentum(p, 0.01, 0.9, nesterov))):
        p_ref, p_engine = [a.copy() for a in start], [a.copy() for a in start]
        ref, engine = make_ref(p_ref), make_engine(p_engine)
        for pair in grads:
            ref.update(p_ref, pair)
            engine.update(p_engine, pair)
        for a, b in zip(p_ref, p_engine, strict=True):
            assert np.array_equal(a, b)


@pytest.mark.parametrize("activation", ["tanh", "relu", "logistic"])
@pytest.mark.parametrize("solver", ["adam", "sgd", "lbfgs"])
def test_fits_on_both_paths_are_bit_identical(monkeypatch, solver, activation):
    """A whole fit, with mini-batches of two sizes (the last one shorter): the same weights and
    the same loss curve whichever path ran."""
    if _mlp_compiled.compiled_kernels() is None:
        pytest.skip("numba is not available here")
    rng = np.random.default_rng(5)
    X = rng.normal(size=(70, 6))
    y = rng.integers(0, 3, 70)
    fits = {}
    for engine in ("numpy", "compiled"):
        monkeypatch.setenv(ENGINE, engine)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ConvergenceWarning)
            fits[engine] = MLPClassifier((7, 4), activation=activation, solver=solver,
                                         batch_size=16, max_iter=6, alpha=0.01,
                                         random_state=0).fit(X, y)
    a, b = fits["numpy"], fits["compiled"]
    assert a.loss_curve_ == b.loss_curve_
    for u, w in zip(a.coefs_ + a.intercepts_, b.coefs_ + b.intercepts_, strict=True):
        assert np.array_equal(u, w)


@pytest.mark.parametrize("solver", ["gd", "scg", "adam"])
@pytest.mark.parametrize("hidden, outputs", [((5,), 2), ((1, 4), 1)])
def test_regressor_fits_on_both_paths_are_bit_identical(monkeypatch, solver, hidden, outputs):
    """Regression, one output or two, a hidden layer of one unit: layers of one column, whose
    bias gradient NumPy sums pairwise, as well as wider ones."""
    if _mlp_compiled.compiled_kernels() is None:
        pytest.skip("numba is not available here")
    rng = np.random.default_rng(6)
    X = rng.normal(size=(50, 3))
    y = np.column_stack([X[:, 0] - X[:, 1] ** 2, X[:, 2]])[:, :outputs].squeeze()
    fits = {}
    for engine in ("numpy", "compiled"):
        monkeypatch.setenv(ENGINE, engine)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ConvergenceWarning)
            fits[engine] = MLPRegressor(hidden, solver=solver, batch_size=12, max_iter=5,
                                        random_state=0).fit(X, y)
    a, b = fits["numpy"], fits["compiled"]
    assert a.loss_curve_ == b.loss_curve_
    for u, w in zip(a.coefs_ + a.intercepts_, b.coefs_ + b.intercepts_, strict=True):
        assert np.array_equal(u, w)


def test_engine_choice(monkeypatch):
    assert _mlp_compiled.compiled_kernels("numpy") is None
    with pytest.raises(ValueError, match="EBANTENNA_ENGINE must be one of"):
        monkeypatch.setenv(ENGINE, "fast")
        _mlp_compiled.compiled_kernels()
    missing = EngineStatus(False, "numba is not installed", math.nan)
    monkeypatch.setattr(_mlp_compiled, "_status", lambda: missing)
    assert _mlp_compiled.compiled_kernels("auto") is None
    with pytest.raises(RuntimeError, match="numba is not installed"):
        _mlp_compiled.compiled_kernels("compiled")


@pytest.mark.parametrize("value", [np.inf, -np.inf, np.nan, 1e308])
def test_compiled_softmax_matches_numpy_on_extreme_logits(value):
    """The row maximum the compiled loop picks is the one ``argmax`` picks (the first NaN, an
    infinity): the same loss and gradient, NaN where NumPy's is NaN."""
    rng = np.random.default_rng(7)
    z = rng.normal(size=(6, 4))
    z[1, 2] = value
    z[3, 0], z[3, 3] = value, -value
    Y = np.eye(4)[rng.integers(0, 4, 6)]
    results = []
    for compiled in (None, _mlp_numba):
        work = Workspace(6, [3, 4], compiled)
        with np.errstate(all="ignore"):
            loss, delta = output_loss_into("softmax", z.copy(), Y, work)
        results.append((loss, delta.copy()))
    (loss_a, delta_a), (loss_b, delta_b) = results
    assert loss_a == loss_b or (np.isnan(loss_a) and np.isnan(loss_b))
    assert np.array_equal(delta_a, delta_b, equal_nan=True)


def test_importing_the_estimators_does_not_import_numba():
    # numba is imported the first time a compiled loop is asked for, not on `import
    # ebantenna.ml` (about a second of start-up when the fast extra is installed)
    code = "import sys, ebantenna.ml; print('numba' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
