"""The SMO policy object: its presets, its checks, and the policy each SVC mode runs."""

from dataclasses import FrozenInstanceError, replace

import numpy as np
import pytest

from ebantenna.ml import SVC
from ebantenna.ml.kernels import Kernel, KernelRows
from ebantenna.ml.smo import solve_smo
from ebantenna.ml.smo_policy import DEFAULT, LIBSVM, SMOPolicy, fit_policy


def test_presets_name_each_convention():
    assert (DEFAULT.ties, DEFAULT.curvature_floor, DEFAULT.bias_sum) == ("first", "tau",
                                                                         "pairwise")
    assert (LIBSVM.ties, LIBSVM.curvature_floor, LIBSVM.bias_sum) == ("last", "nonpositive",
                                                                      "sequential")
    assert LIBSVM.shrinking and LIBSVM.float32_kernel
    assert not DEFAULT.shrinking and not DEFAULT.float32_kernel
    with pytest.raises(FrozenInstanceError):
        LIBSVM.ties = "first"


@pytest.mark.parametrize("field, value, error", [
    ("selection", "random", ValueError), ("ties", "middle", ValueError),
    ("curvature_floor", "zero", ValueError), ("bias_sum", "kahan", ValueError),
    ("shrinking", "yes", TypeError), ("float32_kernel", 1, TypeError),
])
def test_bad_fields_name_themselves(field, value, error):
    with pytest.raises(error, match=f"{field} must be .*{value!r}"):
        SMOPolicy(**{field: value})


def test_solve_smo_refuses_anything_but_a_policy():
    X = np.array([[0.0], [2.0]])
    rows = KernelRows(X, Kernel("linear"), np.float64, cache_bytes=1 << 20)
    with pytest.raises(TypeError, match="policy must be an SMOPolicy"):
        solve_smo(rows, np.array([-1.0, 1.0]), np.full(2, 1.0), diagonal=np.array([0.0, 4.0]),
                  policy="libsvm")


@pytest.mark.parametrize("params, whole_kernel, expected", [
    (dict(libsvm_compat=True), True, LIBSVM),
    (dict(libsvm_compat=True, shrinking=False), True, replace(LIBSVM, shrinking=False)),
    (dict(selection="first-order"), True,
     replace(DEFAULT, selection="first-order", shrinking=True)),
    # shrinking whether the whole kernel is in memory or not: the same policy either way
    (dict(), True, replace(DEFAULT, shrinking=True)),
    (dict(), False, replace(DEFAULT, shrinking=True)),
    (dict(shrinking=False), True, DEFAULT),
    (dict(shrinking=False), False, DEFAULT),
])
def test_each_svc_mode_runs_its_policy(params, whole_kernel, expected):
    svc = SVC(**params)
    assert fit_policy(svc.libsvm_compat, svc.selection, svc.shrinking,
                      whole_kernel=whole_kernel) == expected
