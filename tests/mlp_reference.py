"""Comparing an MLP's training with a reference run of the same steps (scikit-learn's, or our own
on other input)."""

import warnings

import numpy as np
from sklearn.exceptions import ConvergenceWarning

EPS = np.finfo(float).eps


def rounding(X, widths, scale=1.0):
    """How far two correct implementations of one gradient step may drift apart by rounding alone.

    They sum the same products in different orders (BLAS blocking differs between CPU kernels and
    between the two codes). A sum of m products is off by at most m eps times the sum of their
    magnitudes (Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., eq. 3.5); the
    longest sums here run over the samples (backward) and the widest layer (forward), and a step
    chains a few of them (forward, backward, update; both codes): 8 m eps, scaled.
    """
    m = X.shape[0] * max([X.shape[1], *widths])
    return 8 * m * EPS * scale


def max_abs(arrays):
    return max(1.0, max(float(np.abs(a).max()) for a in arrays))


def one_step_pair(ours, theirs, X, y, **then):
    """Fit both once (to set up), copy our initial weights into theirs, take one step each
    (or what the parameters ``then`` set for the second fit, e.g. ``max_iter=10``)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        ours.fit(X, y)
        theirs.fit(X, y)
        c0 = [c.copy() for c in ours.coefs_]
        b0 = [b.copy() for b in ours.intercepts_]
        for est in (ours, theirs):
            est.coefs_ = [c.copy() for c in c0]
            est.intercepts_ = [b.copy() for b in b0]
            est.set_params(warm_start=True, **then)
            est.fit(X, y)
    return c0, b0
