"""Exercise 6: solve a small SVM dual with a general optimiser and compare with SMO."""

import numpy as np
from scipy.optimize import minimize

from ebantenna.course import parameters
from ebantenna.ml import SVC
from ebantenna.ml.smo import reference_smo

# [data]
STUDENT = None  # a graded variant: the id your teacher gave you, e.g. "s1234"
p = parameters("ex06", student=STUDENT)  # published: seed 3, spread 0.7
rng = np.random.default_rng(p["seed"])
s = p["spread"]
X = np.vstack([rng.normal([-1, -1], s, (15, 2)), rng.normal([1, 1], s, (15, 2))])
y = np.repeat([-1.0, 1.0], 15)
C = 1.0
# [/data]

# Dual: maximise sum(alpha) - 1/2 alpha^T Q alpha with Q_ij = y_i y_j x_i.x_j,
# subject to sum(alpha y) = 0 and 0 <= alpha <= C. minimize() wants a minimum: flip the sign.
Q = (y[:, None] * y[None, :]) * (X @ X.T)
result = minimize(
    lambda a: 0.5 * a @ Q @ a - a.sum(),
    x0=np.zeros(y.size),
    jac=lambda a: Q @ a - 1.0,
    bounds=[(0.0, C)] * y.size,
    constraints=[{"type": "eq", "fun": lambda a: a @ y, "jac": lambda a: y}],
    method="SLSQP",
    options={"ftol": 1e-12, "maxiter": 500},
)
# ftol is asked in the objective (of order 1 to 10): far below 1e-12 it meets the rounding of
# alpha^T Q alpha, and SLSQP then stops with "Positive directional derivative" on right answers.
alpha = result.x
w = (alpha * y) @ X
# The bias from the free support vectors (0 < alpha < C), where y_i f(x_i) = 1 exactly.
free = (alpha > 1e-6) & (alpha < C - 1e-6)
g = y - X @ w
# Without a free multiplier (it happens for a few draws of the data) the conditions of optimality
# only bound b, from below by the points at 0 with y = +1 and at C with y = -1, from above by the
# others: every b in [lower, upper] is optimal, and libsvm, and so SVC, take the middle.
at_zero, at_c = alpha <= 1e-6, alpha >= C - 1e-6
lower = g[(at_zero & (y > 0)) | (at_c & (y < 0))].max()
upper = g[(at_zero & (y < 0)) | (at_c & (y > 0))].min()
b = np.mean(g[free]) if np.any(free) else (lower + upper) / 2
print("w =", w.round(4), " b =", round(b, 4), " support vectors:", int((alpha > 1e-6).sum()))


def duality_gap(alpha, b):
    """Primal minus dual objective: zero at the optimum, and never below it (weak duality)."""
    w = (alpha * y) @ X
    primal = 0.5 * w @ w + C * np.maximum(0.0, 1.0 - y * (X @ w + b)).sum()
    return primal - (alpha.sum() - 0.5 * w @ w)


def optimal_bias(b_other):
    """Whether another solver's bias is optimal: b's value with a free multiplier, else in the
    interval [lower, upper] that the conditions of optimality leave open."""
    if np.any(free):
        return abs(b_other - b) < 1e-4
    return lower - 1e-6 <= b_other <= upper + 1e-6


# result.success is only SLSQP's own stopping test. The certificate of optimality is the gap:
# the primal is 1-strongly convex in w, so |w - w*| <= sqrt(2 gap) <= 4.5e-3 for a gap of 1e-5.
print("SLSQP:", result.message, " duality gap:", duality_gap(alpha, b))
assert abs(alpha @ y) < 1e-9 and np.all((alpha >= -1e-12) & (alpha <= C + 1e-12))
assert 0.0 <= duality_gap(alpha, b) + 1e-12 < 1e-5

# The same problem by the package's SMO.
svc = SVC(C=C, kernel="linear", tol=1e-8).fit(X, y)
alpha_smo = np.zeros(y.size)
# dual_coef_ holds y_i alpha_i of the support vectors (scikit-learn's layout).
alpha_smo[svc.support_] = np.abs(svc.dual_coef_[0])
w_smo = svc.dual_coef_[0] @ svc.support_vectors_

assert np.allclose(alpha, alpha_smo, atol=1e-5), np.abs(alpha - alpha_smo).max()
assert np.allclose(w, w_smo, atol=1e-5)
# SMO stops when no pair violates the conditions by more than tol, which bounds its gap by
# n C tol; its b is then optimal too, whichever point of [lower, upper] it took.
assert duality_gap(alpha_smo, svc.intercept_[0]) < y.size * C * 1e-8
assert optimal_bias(svc.intercept_[0])
# Both satisfy the constraints of the dual.
assert abs(alpha_smo @ y) < 1e-10 and np.all((alpha_smo >= 0) & (alpha_smo <= C))
# The multipliers are continuous, not +-1: the paper's remark confuses them with the labels
# (the published data have multipliers strictly between 0 and C).
assert np.any(free) or STUDENT is not None

# The textbook SMO (ebantenna/ml/smo.py) on the kernel matrix: the same multipliers, and its
# rho is -b (f(x) = sum alpha_i y_i k(x_i, x) - rho).
reference = reference_smo(X @ X.T, y, np.full(y.size, C), tol=1e-8)
print("reference SMO:", reference.n_iter, "updates")
assert reference.converged
assert np.allclose(reference.alpha, alpha_smo, atol=1e-5)
assert duality_gap(reference.alpha, -reference.rho) < y.size * C * 1e-8
assert optimal_bias(-reference.rho)

# The value of the dual at the optimum, sum(alpha) - |w|^2 / 2: by strong duality also the primal's.
dual_objective = alpha.sum() - 0.5 * w @ w
# The count of updates is printed, not graded: near-ties in the working-set selection are broken
# by the last bits of X X^T, which depend on the machine's BLAS, and the count follows them.

# The expected answers on the exercise page, checked against these values by the test suite.
ANSWERS = {"w1": w[0], "w2": w[1], "b": b, "n_support": int((alpha > 1e-6).sum()),
           "dual_objective": dual_objective}
# The tolerance of each answer: how far two correct ways of working may differ, and why.
SOLVER = "solvers stop at their own tolerance: SLSQP and SMO here agree to 1e-4"
TOLERANCES = {
    "w1": ("abs", 1e-3, SOLVER), "w2": ("abs", 1e-3, SOLVER), "b": ("abs", 1e-3, SOLVER),
    "n_support": ("abs", 0, "a count: multipliers above 1e-6"),
    "dual_objective": ("abs", 1e-4, "a solver stopped at a duality gap g is within g of the "
                       "optimum: SLSQP's below 1e-5 (about 1e-14 here), SMO's n C tol = 3e-7 "
                       "at tol=1e-8"),
}

print("ok: SLSQP and SMO find the same multipliers, hyperplane and bias")
