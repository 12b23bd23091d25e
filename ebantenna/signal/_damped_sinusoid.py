"""The damped-sinusoid fit of :func:`~ebantenna.signal.fit_decay` (private).

The ``"sinusoid"`` method of :func:`~ebantenna.signal.fit_decay`, and the witness every envelope
fit is checked against: least squares of the whole damped sinusoid
``exp(b t) (p cos wt + q sin wt) + c`` to the signal itself, with its Jacobian, by
:func:`scipy.optimize.least_squares`. It takes checked values: :func:`~ebantenna.signal.fit_decay`
validates its arguments and scales the signal before calling it.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize

__all__ = ["damped_sinusoid_fit"]


def damped_sinusoid_fit(x, t, n_fit, a0, b0, omega0):
    """Least squares of ``exp(b t) (p cos wt + q sin wt) + c`` to the first ``n_fit`` samples.

    Started from the envelope fit ``(a0, b0)`` (or, if that does not decay, the energy centroid
    of the signal) and the frequency ``omega0`` (rad/s) refined on a zero-padded spectrum of the
    window; the linear parameters ``p, q, c`` start from their least-squares values.

    Returns
    -------
    tuple (a, b, r_squared, n_fit) or None
        ``a`` the amplitude at ``t = 0``; None when the window holds less than one period of the
        fitted frequency or the solver fails.
    """
    n_fit = min(n_fit, x.size)
    if n_fit < 8:
        return None
    y, t0 = x[:n_fit], t[0]
    tw = t[:n_fit] - t0
    if not b0 < 0:
        energy = y**2
        b0 = -0.5 / max(float((tw * energy).sum() / energy.sum()), tw[1])
    # the strongest peak of the window's spectrum, 8x zero-padded, near the record's dominant bin
    spectrum = np.abs(np.fft.rfft(y - y.mean(), 8 * n_fit))
    omegas = 2 * np.pi * np.fft.rfftfreq(8 * n_fit, tw[1])
    omega = float(omegas[1 + np.argmax(spectrum[1:])]) if spectrum.size > 1 else omega0

    def columns(b, w):
        e = np.exp(b * tw)
        return e, np.cos(w * tw), np.sin(w * tw)

    e, co, si = columns(b0, omega)
    lin, *_ = np.linalg.lstsq(np.column_stack([e * co, e * si, np.ones(n_fit)]), y, rcond=None)

    def residual(v):
        b, w, p, q, c = v
        e, co, si = columns(b, w)
        return e * (p * co + q * si) + c - y

    def jacobian(v):
        b, w, p, q, c = v
        e, co, si = columns(b, w)
        osc = e * (p * co + q * si)
        return np.column_stack([tw * osc, tw * e * (q * co - p * si), e * co, e * si,
                                np.ones(n_fit)])

    sol = optimize.least_squares(residual, x0=[b0, omega, *lin], jac=jacobian, method="lm",
                                 x_scale="jac")
    b, w, p, q, _ = sol.x
    if not (sol.success and np.all(np.isfinite(sol.x))) or abs(w) * tw[-1] < 2 * np.pi:
        return None
    ss_tot = float(((y - y.mean()) ** 2).sum())
    r2 = 1.0 - float((sol.fun**2).sum()) / ss_tot if ss_tot > 0 else 0.0
    return math.hypot(p, q) * math.exp(-b * t0), float(b), r2, n_fit
