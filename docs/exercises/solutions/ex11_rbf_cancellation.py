"""Exercise 11: cancellation in the RBF kernel, seen in libsvm's training path."""

import numpy as np
from sklearn.svm import SVC as LibSVC

from ebantenna.ml import SVC

u = np.finfo(float).eps / 2  # unit roundoff of float64

# [data]
# Part 1: two random points in five dimensions.
rng = np.random.default_rng(8)
x0, y0 = rng.normal(size=5), rng.normal(size=5)
# Part 2: a three-class problem (300 training points) and 50 test points, from the same rng.
y_cls = rng.integers(0, 3, 300)
X = rng.normal(size=(3, 5))[y_cls] * 1.5 + 0.8 * rng.normal(size=(300, 5))
X_test = rng.normal(size=(50, 5)) * 1.5
# [/data]

# 1. The two points, both shifted by c in every coordinate.
true = float(np.sum((x0 - y0) ** 2))
print("      c   expansion error   direct error")
expansion_errors = {}
for c in [0.0, 1e2, 1e4, 1e6]:
    x, y = x0 + c, y0 + c
    expanded = x @ x + y @ y - 2 * x @ y  # what a GEMM-based kernel (and libsvm's training) does
    direct = float(np.sum((x - y) ** 2))
    expansion_errors[c] = abs(expanded - true)
    print(f"{c:7.0e}   {expansion_errors[c] / true:15.1e}   {abs(direct - true) / true:12.1e}")
    # Error bounds (first order in u, p = 5 coordinates): the direct difference only suffers from
    # rounding x0 + c and y0 + c (u c per coordinate) and its own sum; the expansion from the
    # rounding of three inner products of size up to |x| |y|, about 5 c^2, that do not cancel.
    assert abs(direct - true) <= 4 * u * c * np.abs(x0 - y0).sum() + 6 * u * true
    assert expansion_errors[c] <= 8 * u * (np.linalg.norm(x) + np.linalg.norm(y)) ** 2
# At c = 1e6 the expanded distance is a multiple of the spacing of floats near 5e12, about 1e-3:
# the true distance, a generic real number, is not. The direct one keeps ten digits.
assert expansion_errors[1e6] > 1e-8 * true

# The size of the error depends on the order of the sums: np.sum instead of @ rounds otherwise.
x, y = x0 + 1e6, y0 + 1e6
error_sums = abs(np.sum(x * x) + np.sum(y * y) - 2 * np.sum(x * y) - true)
print(f"at c = 1e6 with np.sum: {error_sums / true:.1e}")
assert error_sums <= 8 * u * (np.linalg.norm(x) + np.linalg.norm(y)) ** 2

# 2. The same flaw in a trained machine: shift every feature of the three-class problem by c.
params = dict(C=2.0, tol=1e-10, decision_function_shape="ovo")


def drift(make, c):
    """Largest change of the decision values caused by the shift c, relative."""
    d0 = make().fit(X, y_cls).decision_function(X_test)
    model = make().fit(X + c, y_cls)
    d1 = model.decision_function(X_test + c)
    return np.abs(d1 - d0).max() / np.abs(d0).max(), model.n_iter_


print("      c   libsvm drift (iterations)          ebantenna drift (iterations)")
drifts = {}
for c in [1e3, 1e6]:
    lib, lib_iter = drift(lambda: LibSVC(**params), c)
    ours, our_iter = drift(lambda: SVC(**params), c)
    print(f"{c:7.0e}   {lib:9.1e} {lib_iter}   {ours:20.1e} {our_iter}")
    drifts[c] = lib, ours
    # ebantenna centres the points before expanding: only the input rounding u * c is left
    assert ours < 1e-8
assert lib > 1e-5  # libsvm at c = 1e6: the training kernel is wrong in its fourth digit

# 3. libsvm_compat follows libsvm's arithmetic, cancellation included.
compat, _ = drift(lambda: SVC(libsvm_compat=True, **params), 1e6)
assert compat > 1e-5

# The bound of part 1 at c = 1e6, relative to the true distance: what the expansion may lose.
x, y = x0 + 1e6, y0 + 1e6
bound_1e6 = 8 * u * (np.linalg.norm(x) + np.linalg.norm(y)) ** 2 / true
# The measured errors (relative) are a tenth of the bound or less: it adds worst cases.
error_1e6, error_1e6_sums = expansion_errors[1e6] / true, error_sums / true
assert max(error_1e6, error_1e6_sums) < bound_1e6 / 5
direct_error_1e6 = abs(float(np.sum((x - y) ** 2)) - true) / true
ANSWERS = {"true": true, "bound_1e6": bound_1e6, "error_1e6": error_1e6,
           "error_1e6_sums": error_1e6_sums, "direct_error_1e6": direct_error_1e6,
           "libsvm_drift_1e6": drifts[1e6][0]}
# The tolerance of each answer: how far two correct ways of working may differ, and why.
ORDER = (
    "rounding errors depend on the order of the operations: sums in another order differ by a "
    "factor of up to 6"
)
TOLERANCES = {
    "true": ("rel", 1e-12, "a sum of five squares: only the last digits depend on the order"),
    "bound_1e6": ("rel", 1e-6, "the formula of the hint; norms summed in any order"),
    "error_1e6": ("factor", 10, ORDER), "error_1e6_sums": ("factor", 10, ORDER),
    "direct_error_1e6": ("factor", 10, ORDER),
    "libsvm_drift_1e6": ("factor", 3, (
        "scikit-learn versions and BLAS libraries round the training kernel differently"
    )),
}
print("ok")
