"""The compiled SMO engine (numba) against the NumPy engines, bit for bit, and the choice between
them: the environment variable, the fallback and its one message."""

import logging
import sys
from dataclasses import replace

import numpy as np
import pytest
from sklearn import datasets
from sklearn.preprocessing import StandardScaler

import ebantenna.ml
from ebantenna import _engines as _engine_choice
from ebantenna.ml import SVC, _smo_compiled, smo
from ebantenna.ml import svc as svc_module
from ebantenna.ml._smo_compiled import ENGINE_VARIABLE, choose_engine, engine_status
from ebantenna.ml.kernels import Kernel, KernelRows
from ebantenna.ml.smo_policy import LIBSVM

STATUS = engine_status()
needs_numba = pytest.mark.skipif(
    not STATUS.available, reason=f"the compiled engine is not available: {STATUS.reason}")


def _subsample(X, y, n, seed=0):
    """At most ``n`` points, drawn without replacement, features standardised."""
    if len(y) > n:
        keep = np.sort(np.random.default_rng(seed).choice(len(y), n, replace=False))
        X, y = X[keep], y[keep]
    return StandardScaler().fit_transform(X), y


def _project_features():
    """Features as the paper's (non-negative spectra of overlapping classes), small."""
    from ebantenna.bench.ml_speed import spectra_like

    X, y = spectra_like(300, 32, 5, seed=3)
    return X / X.max(), y


DATA = {
    "project": _project_features,
    "iris": lambda: _subsample(*datasets.load_iris(return_X_y=True), 150),
    "wine": lambda: _subsample(*datasets.load_wine(return_X_y=True), 178),
    "breast_cancer": lambda: _subsample(*datasets.load_breast_cancer(return_X_y=True), 260),
    "digits": lambda: _subsample(*datasets.load_digits(return_X_y=True), 300),
    "classification": lambda: _subsample(*datasets.make_classification(
        3000, 40, n_informative=12, n_classes=6, random_state=0), 300),
}


def _same(a, b):
    """Both engines' results of one binary problem, to the last bit."""
    np.testing.assert_array_equal(a.alpha, b.alpha)
    assert (a.rho, a.n_iter, a.violation, a.objective, a.converged) == (
        b.rho, b.n_iter, b.violation, b.objective, b.converged)


@pytest.fixture
def both_engines(monkeypatch):
    """Make every ``solve_smo`` of an ``SVC`` fit run on both engines and compare them; the
    fit continues with the NumPy result. Yields the list of compared results."""
    compared = []

    def twice(rows, y, C, **kwargs):
        numpy = smo.solve_smo(rows, y, C, engine="numpy", **kwargs)
        compiled = smo.solve_smo(rows, y, C, engine="compiled", **kwargs)
        _same(numpy, compiled)
        compared.append(numpy)
        return numpy

    monkeypatch.setattr(svc_module, "solve_smo", twice)
    return compared


@needs_numba
@pytest.mark.parametrize("shrinking", [False, True])
@pytest.mark.parametrize("libsvm_compat", [False, True])
@pytest.mark.parametrize("kernel", ["linear", "poly", "rbf", "sigmoid"])
@pytest.mark.parametrize("name", list(DATA))
def test_compiled_engine_takes_the_same_steps(both_engines, name, kernel, libsvm_compat,
                                              shrinking):
    # The same IEEE operations in the same order (the module text of _smo_numba): the same
    # alpha, rho, number of updates and violation, to the last bit; libsvm's conventions bring
    # the float32 kernel, ties to the last index and the curvature floor a <= 0 -> tau, which
    # the sigmoid kernel (not positive semi-definite) reaches.
    X, y = DATA[name]()
    params = dict(kernel=kernel, C=2.0, gamma="scale", degree=3, coef0=0.5, tol=1e-4,
                  shrinking=shrinking, libsvm_compat=libsvm_compat)
    if kernel == "sigmoid":
        params["coef0"] = -0.5
    SVC(**params).fit(X, y)
    k = len(np.unique(y))
    assert len(both_engines) == k * (k - 1) // 2


@needs_numba
def test_same_bits_with_many_shrinks_and_at_max_iter():
    # 1300 points: thousands of updates, so libsvm's shrinking reorders the variables and
    # rebuilds the gradient several times; and a run cut by max_iter reports the same state
    rng = np.random.default_rng(7)
    X = rng.normal(size=(1300, 2))
    y = np.where(X[:, 0] + X[:, 1] ** 2 + 0.8 * rng.normal(size=1300) > 1.0, 1.0, -1.0)
    kern = Kernel("rbf", gamma=0.5)
    rows = KernelRows(X, kern, np.float32, 1 << 24)
    C = np.full(y.size, 4.0)
    for policy, max_iter in ((LIBSVM, 10_000_000), (LIBSVM, 1500),
                             (replace(LIBSVM, shrinking=False), 10_000_000)):
        numpy, compiled = (smo.solve_smo(rows, y, C, diagonal=kern.diagonal(X), tol=1e-5,
                                         policy=policy, max_iter=max_iter, engine=engine)
                           for engine in ("numpy", "compiled"))
        _same(numpy, compiled)
        assert numpy.converged == (max_iter > 1500) and numpy.n_iter > 1000


@needs_numba
def test_rows_computed_on_demand_stay_on_numpy():
    # a kernel that does not fit in the memory given is computed row by row in NumPy: the
    # compiled loop, which reads a stored matrix, leaves it to the NumPy engines
    X = np.random.default_rng(0).normal(size=(40, 3))
    y = np.where(X[:, 0] > 0, 1.0, -1.0)
    kern = Kernel("rbf", gamma=0.5)
    rows = KernelRows(X, kern, np.float64, cache_bytes=8 * 40 * 4)
    assert rows.stored_entries() is None
    assert _smo_compiled.run_compiled(rows, y, np.ones(40), kern.diagonal(X), LIBSVM, 1e-3,
                                      100.0) is None
    res = smo.solve_smo(rows, y, np.ones(40), diagonal=kern.diagonal(X), engine="compiled")
    _same(res, smo.solve_smo(rows, y, np.ones(40), diagonal=kern.diagonal(X), engine="numpy"))


@pytest.mark.parametrize("policy", [LIBSVM, replace(LIBSVM, ties="first", curvature_floor="tau",
                                                    bias_sum="pairwise", float32_kernel=False)])
def test_the_loop_as_plain_python_takes_the_same_steps(monkeypatch, policy):
    # The compiled loop's source runs as Python too (numba's py_func, or the module as it
    # imports without numba): its logic is held to the NumPy engines in every CI environment
    from ebantenna.ml import _smo_numba

    loop = getattr(_smo_numba.smo_loop, "py_func", _smo_numba.smo_loop)
    monkeypatch.setattr(_smo_numba, "smo_loop", loop)
    rng = np.random.default_rng(11)
    X = rng.normal(size=(70, 2))
    y = np.where(X[:, 0] * X[:, 1] + 0.3 * rng.normal(size=70) > 0, 1.0, -1.0)
    kern = Kernel("rbf", gamma=1.0)
    rows = KernelRows(X, kern, policy.kernel_dtype(70, 1 << 20), 1 << 20)
    C, diagonal = np.full(70, 5.0), kern.diagonal(X)
    y_, C_, alpha, yG, perm, n_iter, converged, violation = _smo_compiled.run_compiled(
        rows, y, C, diagonal, policy, 1e-4, 1e7)
    numpy = smo.solve_smo(rows, y, C, diagonal=diagonal, tol=1e-4, policy=policy,
                          engine="numpy")
    assert (n_iter, converged, violation) == (numpy.n_iter, numpy.converged, numpy.violation)
    assert n_iter > 70  # past the first shrinking with LIBSVM
    np.testing.assert_array_equal(alpha[np.argsort(perm)], numpy.alpha)


@pytest.fixture
def fresh_status():
    """Probe numba again in this test, and once more after it."""
    engine_status.cache_clear()
    yield
    engine_status.cache_clear()


def test_without_numba_numpy_runs_and_says_why_once(monkeypatch, fresh_status, caplog):
    monkeypatch.setattr(_engine_choice.importlib.util, "find_spec",
                        lambda name, *args: None if name == "numba" else sys.modules[name])
    monkeypatch.delenv(ENGINE_VARIABLE, raising=False)
    with caplog.at_level(logging.INFO, logger=_engine_choice.__name__):
        assert choose_engine() == "numpy"
        assert choose_engine("auto") == "numpy"
        res = smo.solve_smo(KernelRows(np.array([[0.0], [2.0]]), Kernel("linear"), np.float64,
                                       1 << 20), np.array([-1.0, 1.0]), np.full(2, 10.0),
                            diagonal=np.array([0.0, 4.0]))
    assert res.n_iter == 1 and np.array_equal(res.alpha, [0.5, 0.5])  # alpha = 2 / 2**2
    messages = [r.getMessage() for r in caplog.records if r.name == _engine_choice.__name__]
    assert len(messages) == 1 and "numba is not installed" in messages[0]
    assert "ebantenna[fast]" in messages[0]
    with pytest.raises(RuntimeError, match="compiled SMO engine was asked for but numba is not"):
        choose_engine("compiled")


def test_a_broken_numba_warns_once_and_falls_back(monkeypatch, fresh_status):
    # numba present but unable to build the loop (for instance too old for this NumPy, where
    # importing numba itself raises ImportError): one RuntimeWarning, then the NumPy engines
    monkeypatch.setattr(_engine_choice.importlib.util, "find_spec", lambda name, *args: object())
    monkeypatch.delattr(ebantenna.ml, "_smo_numba", raising=False)
    monkeypatch.setitem(sys.modules, "ebantenna.ml._smo_numba", None)  # import fails
    with pytest.warns(RuntimeWarning, match="compiled SMO engine failed with NumPy") as caught:
        assert choose_engine() == "numpy"
        assert choose_engine() == "numpy"
    assert len(caught) == 1


def test_the_engine_variable_and_argument(monkeypatch):
    monkeypatch.setenv(ENGINE_VARIABLE, "numpy")
    assert choose_engine() == "numpy"
    assert choose_engine("auto") == ("compiled" if STATUS.available else "numpy")
    monkeypatch.setenv(ENGINE_VARIABLE, "fortran")
    with pytest.raises(ValueError, match="EBANTENNA_ENGINE must be one of 'auto', 'numpy', "
                                         "'compiled'; got 'fortran'"):
        choose_engine()
    with pytest.raises(ValueError, match="engine must be one of"):
        choose_engine("gpu")


def _interrupted_inside_numba(*args, **kwargs):
    """What numba makes of a Ctrl-C that arrives while its own C code runs: a SystemError caused
    by the KeyboardInterrupt."""
    try:
        raise KeyboardInterrupt
    except KeyboardInterrupt as exc:
        raise SystemError("<function _numba_unpickle> returned a result with an exception "
                          "set") from exc


def test_a_ctrl_c_inside_the_compiled_loops_reaches_the_caller_as_itself(monkeypatch):
    # the SMO loop: a stand-in module for the compiled one (numba need not be installed)
    import types

    from ebantenna.ml import MLPClassifier

    fake = types.ModuleType("ebantenna.ml._smo_numba")
    fake.smo_loop = _interrupted_inside_numba
    monkeypatch.setitem(sys.modules, "ebantenna.ml._smo_numba", fake)
    monkeypatch.setattr(ebantenna.ml, "_smo_numba", fake, raising=False)
    X, y = _project_features()
    X = X[:40]
    rows = KernelRows(X, Kernel("linear"), np.float64, 1 << 20)
    yy = np.where(y[:40] == y[0], 1.0, -1.0)
    with pytest.raises(KeyboardInterrupt):
        _smo_compiled.run_compiled(rows, yy, np.ones(yy.size), np.ones(yy.size), LIBSVM,
                                   1e-3, 1e5)
    # the network's training, where the compiled kernels run inside the epochs
    from ebantenna.ml import mlp_base

    monkeypatch.setattr(mlp_base.BaseMLP, "_loss_and_gradients_into", _interrupted_inside_numba)
    with pytest.raises(KeyboardInterrupt):
        MLPClassifier(hidden_layer_sizes=(3,), max_iter=2).fit(X[:20], y[:20])
