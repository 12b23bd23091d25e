"""The input contract of the textbook SMO, its kernel rows and policy, and the MLP's base class.

The reference SMO checks its problem once (a square finite kernel matrix, labels of +1 or -1,
one positive bound per label, a positive tolerance, at least one update, a known selection
rule); the kernel rows check their points, kernel and cache; the policy its counts. Each bad
input is refused naming the parameter; the reference's documented two-point problem is solved
by hand.

Found by these rows and fixed: the reference SMO ran on labels that are not +1 or -1, a
negative bound, a NaN tolerance and no updates at all; a non-square kernel matrix ended in
NumPy's broadcast message and an unknown rule in "'float' object is not subscriptable"; the
kernel rows took a string for their points (``AttributeError``), an integer for their kernel
and a negative cache; a user's kernel that is not callable ended in Python's message.
"""

from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, check_row  # noqa: E402

from ebantenna.ml import MLPRegressor, kernels, smo, smo_policy  # noqa: E402
from ebantenna.ml import fitted as fitted_module  # noqa: E402

NAN = math.nan
RNG = np.random.default_rng(0)
X = RNG.normal(size=(10, 2))
Y = np.array([1.0, -1.0] * 5)
KX = X @ X.T
C = np.ones(10)
K2 = np.array([[0.0, 0.0], [0.0, 4.0]])  # the points 0 and 2, linear kernel
m = "ebantenna.ml."

#: ``surface -> [(id, call, names or None, same)]``
ROWS = {
    m + "smo.reference_smo": [
        ("K-not-square", lambda: smo.reference_smo(np.ones((3, 2)), Y[:3], C[:3]), ("K",), None),
        ("K-nan", lambda: smo.reference_smo(KX * NAN, Y, C), ("K",), None),
        ("y-not-plus-minus-one", lambda: smo.reference_smo(KX, np.arange(10.0), C), ("y",),
         None),
        ("y-short", lambda: smo.reference_smo(KX, Y[:3], C), ("y",), None),
        ("C-negative", lambda: smo.reference_smo(KX, Y, -C), ("C",), None),
        ("C-scalar", lambda: smo.reference_smo(KX, Y, 1.0), ("C",), None),
        ("tol-nan", lambda: smo.reference_smo(KX, Y, C, tol=NAN), ("tol",), None),
        ("max_iter-0", lambda: smo.reference_smo(KX, Y, C, max_iter=0), ("max_iter",), None),
        ("selection-unknown", lambda: smo.reference_smo(KX, Y, C, selection="x"),
         ("selection",), None),
        # points 0 and 2, labels -1 and +1: the margins give w = 1 and rho = 1, and w = 2 alpha
        ("two-points-by-hand", lambda: smo.reference_smo(K2, np.array([-1.0, 1.0]),
                                                         np.full(2, 10.0)), None,
         lambda r: r.alpha.tolist() == [0.5, 0.5] and r.rho == 1.0 and r.n_iter == 1),
    ],
    m + "kernels.KernelRows": [
        ("X-str", lambda: kernels.KernelRows("x", kernels.Kernel(), np.float64, 1000), ("X",),
         None),
        ("kernel-int", lambda: kernels.KernelRows(X, 5, np.float64, 1000), ("kernel",), None),
        ("cache_bytes-negative", lambda: kernels.KernelRows(X, kernels.Kernel(), np.float64, -1),
         ("cache_bytes",), None),
        ("row-equals-gram", lambda: (kernels.KernelRows(X, kernels.Kernel("linear"), np.float64,
                                                        10**6).row64(3), KX[3]), None,
         lambda r: np.allclose(r[0], r[1], rtol=1e-14, atol=1e-14)),
    ],
    m + "kernels.call_kernel": [
        ("kernel-int", lambda: kernels.call_kernel(5, X, X), ("kernel",), None),
        ("wrong-shape", lambda: kernels.call_kernel(lambda a, b: np.ones(3), X, X), ("shape",),
         None),
        ("nan", lambda: kernels.call_kernel(lambda a, b: a @ b.T * NAN, X, X), ("finite",),
         None),
        ("by-hand", lambda: kernels.call_kernel(lambda a, b: a @ b.T, np.eye(2), np.ones((1, 2))),
         None, lambda r: r.tolist() == [[1.0], [1.0]]),
    ],
    m + "smo_policy.SMOPolicy": [
        ("selection-unknown", lambda: smo_policy.SMOPolicy(selection="x"), ("selection",), None),
    ],
    m + "smo_policy.SMOPolicy.kernel_dtype": [
        ("n-negative", lambda: smo_policy.SMOPolicy().kernel_dtype(-1, 100), ("n",), None),
        ("cache_bytes-str", lambda: smo_policy.SMOPolicy().kernel_dtype(10, "1"),
         ("cache_bytes",), None),
        # float64 rows fit: 10 x 10 x 8 bytes in a cache of 800
        ("fits-by-hand", lambda: (smo_policy.SMOPolicy().kernel_dtype(10, 800),
                                  smo_policy.SMOPolicy().kernel_dtype(10, 799)), None,
         lambda r: r == (np.float64, np.float32)),
    ],
    m + "smo_policy.fit_policy": [
        ("selection-unknown", lambda: smo_policy.fit_policy(False, "x", True, True),
         ("selection",), None),
    ],
    m + "fitted.FittedAttribute": [
        ("kind-unknown", lambda: fitted_module.FittedAttribute("a", "x"), ("kind",), None),
    ],
    m + "fitted.FittedAttribute.check": [
        ("wrong-dimensions", lambda: fitted_module.FittedAttribute("a", "array", ndim=2).check(
            np.ones(3)), ("a",), None),
    ],
    m + "mlp_base.BaseMLP": [
        ("alpha-negative", lambda: MLPRegressor(alpha=-1.0, max_iter=3).fit(X, Y), ("alpha",),
         None),
        ("hidden_layer_sizes-zero", lambda: MLPRegressor(hidden_layer_sizes=(0,), max_iter=3)
         .fit(X, Y), ("hidden_layer_sizes",), None),
    ],
    m + "mlp_base.BaseMLP.loss_and_gradient": [
        ("unfitted", lambda: MLPRegressor().loss_and_gradient(X, Y), ("fit",), None),
        ("w-short", lambda: MLPRegressor(max_iter=3).fit(X, Y).loss_and_gradient(
            X, Y, w=np.ones(3)), ("w",), None),
    ],
}
CASES = [(surface, *row) for surface, rows in ROWS.items() for row in rows]


@pytest.mark.parametrize(("surface", "id_", "call", "names", "same"), CASES,
                         ids=[f"{s.rsplit('.', 1)[-1]}:{i}" for s, i, *_ in CASES])
def test_every_row_ends_in_a_clear_error_or_the_right_answer(surface, id_, call, names, same):
    check_row(Row(surface, id_, call, names or (), same), id_)


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    return {surface: [row[0] for row in rows] for surface, rows in ROWS.items()}
