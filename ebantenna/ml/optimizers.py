"""Parameter-update rules for the multilayer perceptron.

Each optimiser works on a list of arrays (the weights and biases of every layer) and their
gradients. :class:`Momentum` is gradient descent with momentum (plain gradient descent with
``momentum=0``), :class:`Adam` is Kingma and Ba's, and :func:`scg_step` is the full-batch scaled
conjugate gradient in the form of Netlab's ``scg.m`` (I. Nabney, *Netlab: Algorithms for Pattern
Recognition*, Springer 2002), a variant of M. F. Møller's (1993) algorithm.

Netlab's variant differs from Møller's published one in how the Levenberg-Marquardt scale
:math:`\\lambda` (``beta`` in the code, ``lambda0`` its starting value) is adapted (multiplied by
4 after a poor step and halved after a good one, kept in :math:`[10^{-15}, 10^{100}]`, where
Møller raises it by an amount computed from the step) and in its defaults,
:math:`\\sigma_0 = 10^{-4}` and :math:`\\lambda_0 = 1`; MATLAB's ``trainscg`` uses
:math:`\\sigma = 5\\cdot 10^{-5}` and :math:`\\lambda = 5\\cdot 10^{-7}`. Both are settable.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .._validate import (
    check_array,
    check_bool,
    check_in_range,
    check_int,
    check_positive,
    check_real,
)

__all__ = ["Momentum", "Adam", "SCGState", "scg_step", "scg_init"]


class Momentum:
    """Stochastic gradient descent with (optionally Nesterov) momentum, as scikit-learn's.

    Each update first sets the velocity ``v <- momentum * v - lr * grad``; the step added to
    the parameters is then ``v`` itself, or with Nesterov ``momentum * v - lr * grad`` (with
    the new ``v``). With ``momentum=0`` both are plain gradient descent. :meth:`update` writes
    these two lines as they stand; the estimators train with an engine that runs the same
    operations in arrays allocated once (``ml._mlp_optimizers``, held equal bit
    for bit).

    Examples
    --------
    >>> p = [np.array([1.0])]
    >>> opt = Momentum(p, learning_rate=0.1, momentum=0.0, nesterov=False)
    >>> opt.update(p, [np.array([2.0])]); p[0]
    array([0.8])
    """

    def __init__(self, params, learning_rate: float, momentum: float = 0.9,
                 nesterov: bool = True):
        self.learning_rate = check_positive("learning_rate", learning_rate)
        self.momentum = check_in_range("momentum", momentum, 0.0, 1.0, low_inclusive=True,
                                       high_inclusive=True)
        self.nesterov = check_bool("nesterov", nesterov)
        self.velocities = [np.zeros_like(p) for p in params]

    def update(self, params, grads) -> None:
        """Move ``params`` (the arrays this optimiser was made for) in place by ``grads``."""
        _same_layout(params, grads, self.velocities)
        for p, g, v in zip(params, grads, self.velocities, strict=True):
            v[...] = self.momentum * v - self.learning_rate * g
            p += self.momentum * v - self.learning_rate * g if self.nesterov else v


class Adam:
    """Adam (Kingma and Ba, 2015) with scikit-learn's bias-corrected learning rate.

    At step :math:`t` (counted from 1), for each parameter array :math:`w` and its gradient
    :math:`g`:

    .. math::

        m &\\leftarrow \\beta_1 m + (1 - \\beta_1) g, \\qquad
        v \\leftarrow \\beta_2 v + (1 - \\beta_2) g^2, \\\\
        \\mathrm{lr}_t &= \\mathrm{lr} \\, \\sqrt{1 - \\beta_2^t} / (1 - \\beta_1^t), \\qquad
        w \\leftarrow w - \\mathrm{lr}_t \\, m / (\\sqrt{v} + \\epsilon).

    This is the "efficient" ordering of Kingma and Ba's section 2, which scikit-learn uses: the
    bias corrections of :math:`m` and :math:`v` are folded into :math:`\\mathrm{lr}_t`, so
    :math:`\\epsilon` is added to :math:`\\sqrt{v}` rather than to :math:`\\sqrt{\\hat v}` of their
    Algorithm 1 (it acts as :math:`\\epsilon / \\sqrt{1 - \\beta_2^t}` there).

    :meth:`update` writes the three lines as they stand. The estimators train with an engine
    (``ml._mlp_optimizers``) that runs the same operations in place on two
    temporaries, or as one compiled loop per array when numba is installed (``pip install
    ebantenna[fast]``): the same numbers, held equal bit for bit by the tests.

    Examples
    --------
    >>> p = [np.array([1.0])]
    >>> opt = Adam(p, learning_rate=0.1)
    >>> opt.update(p, [np.array([3.0])]); np.round(p[0], 6)
    array([0.9])
    """

    def __init__(self, params, learning_rate: float = 1e-3, beta_1: float = 0.9,
                 beta_2: float = 0.999, epsilon: float = 1e-8):
        self.learning_rate = check_positive("learning_rate", learning_rate)
        self.beta_1 = check_in_range("beta_1", beta_1, 0.0, 1.0, low_inclusive=True)
        self.beta_2 = check_in_range("beta_2", beta_2, 0.0, 1.0, low_inclusive=True)
        self.epsilon = check_positive("epsilon", epsilon)
        self.t = 0
        self.ms = [np.zeros_like(p) for p in params]
        self.vs = [np.zeros_like(p) for p in params]

    def learning_rate_at_step(self) -> float:
        """Advance the step count ``t`` and return :math:`\\mathrm{lr}_t`."""
        self.t += 1
        return (self.learning_rate * np.sqrt(1 - self.beta_2**self.t)
                / (1 - self.beta_1**self.t))

    def update(self, params, grads) -> None:
        """Move ``params`` (the arrays this optimiser was made for) in place by ``grads``."""
        _same_layout(params, grads, self.ms)
        lr_t = self.learning_rate_at_step()
        for w, g, m, v in zip(params, grads, self.ms, self.vs, strict=True):
            m[...] = self.beta_1 * m + (1 - self.beta_1) * g
            v[...] = self.beta_2 * v + (1 - self.beta_2) * g * g
            w -= lr_t * m / (np.sqrt(v) + self.epsilon)


def _same_layout(params, grads, state) -> None:
    """Refuse ``params`` and ``grads`` unless each holds one array of the optimiser's shapes."""
    for name, arrays in (("params", params), ("grads", grads)):
        shapes = [np.shape(a) for a in arrays]
        if shapes != [s.shape for s in state]:
            raise ValueError(f"{name} must hold arrays of the shapes the optimiser was made for, "
                             f"{[s.shape for s in state]}, got {shapes}")


@dataclass
class SCGState:
    """Working variables of Møller's scaled conjugate gradient (one per training run)."""

    w: np.ndarray
    f: float
    grad: np.ndarray
    d: np.ndarray  # search direction
    beta: float = 1.0  # Levenberg-Marquardt scale: lambda of the module text (Møller's)
    success: bool = True
    n_success: int = 0
    mu: float = 0.0
    kappa: float = 0.0
    gamma: float = 0.0

    def __post_init__(self):
        if not (isinstance(self.w, np.ndarray) and self.w.ndim == 1 and self.w.size
                and self.w.dtype == np.float64):
            raise TypeError(f"w must be a non-empty 1-D float64 array (the packed weights), got "
                            f"{type(self.w).__name__} {getattr(self.w, 'shape', '')}")
        for name in ("grad", "d"):
            if np.shape(getattr(self, name)) != self.w.shape:
                raise ValueError(f"{name} must have the shape of w {self.w.shape}, got "
                                 f"{np.shape(getattr(self, name))}")
        check_real("f", self.f, allow_inf=True)
        if check_real("beta", self.beta) < 0:
            raise ValueError(f"beta must be >= 0, got {self.beta!r}")
        check_bool("success", self.success)
        check_int("n_success", self.n_success, minimum=0)


#: Bounds of the scale parameter, as in Netlab's ``scg``.
_BETA_MIN, _BETA_MAX = 1e-15, 1e100


def scg_init(w: np.ndarray, fg: Callable[[np.ndarray], tuple[float, np.ndarray]],
             lambda0: float = 1.0) -> SCGState:
    """Start SCG at ``w``: ``fg(w)`` returns the loss and its gradient.

    ``lambda0`` is the initial Levenberg-Marquardt scale (Netlab: 1). A loss or gradient that is
    not finite at ``w`` raises a ``ValueError``: no step could be judged from it.

    Examples
    --------
    On a quadratic bowl SCG without damping (``lambda0=0``) behaves like conjugate
    gradients: two steps reach the minimum of a two-parameter problem (up to the rounding of
    the finite-difference curvature). With the default ``lambda0=1`` the Levenberg-Marquardt
    term shortens the first steps, and it takes ten to get as close.

    >>> A = np.array([[3.0, 1.0], [1.0, 2.0]])
    >>> fg = lambda w: (0.5 * float(w @ A @ w), A @ w)
    >>> st = scg_init(np.array([3.0, -4.0]), fg, lambda0=0.0)
    >>> for _ in range(2):
    ...     _ = scg_step(st, fg)
    >>> bool(np.linalg.norm(st.w) < 1e-6)
    True
    """
    w = np.asarray(check_array("w", w, ndim=1))
    if not callable(fg):
        raise TypeError(f"fg must be a callable fg(w) -> (loss, gradient), got "
                        f"{type(fg).__name__}")
    lambda0 = check_real("lambda0", lambda0)
    if lambda0 < 0:
        raise ValueError(f"lambda0 must be >= 0, got {lambda0!r}")
    f, g = fg(w.copy())
    if np.shape(g) != w.shape:
        raise ValueError(f"fg must return a gradient of the shape of w {w.shape}, got "
                         f"{np.shape(g)}")
    if not (np.isfinite(f) and np.all(np.isfinite(g))):
        raise ValueError(f"scg: the loss ({f!r}) or its gradient is not finite at the start: "
                         "scale the features and targets")
    return SCGState(w=np.array(w, dtype=np.float64), f=float(f), grad=g, d=-g,
                    beta=float(lambda0))


def scg_step(state: SCGState, fg, sigma0: float = 1e-4) -> bool:
    r"""One iteration of Møller's scaled conjugate gradient; returns True if ``w`` moved.

    The curvature along the search direction :math:`d` is estimated by a finite difference of
    gradients, :math:`\gamma = d^T(E'(w + \sigma d) - E'(w)) / \sigma`; a Levenberg–Marquardt term
    :math:`\lambda |d|^2` (``beta * kappa`` in the code, their sum ``delta``) keeps it positive,
    and :math:`\lambda` is adapted by the ratio :math:`\Delta` (``ratio``) of the actual to the
    predicted decrease, so no line search is needed. Directions follow Polak–Ribière and
    restart at the steepest descent after as many successful steps as there are parameters. This is
    the formulation of Netlab's ``scg`` (Nabney, 2002); ``sigma0`` is its :math:`\sigma_0`.

    A step to a point where the loss is not finite counts as a failed step (the scale grows); a
    curvature estimate that is not finite raises a ``ValueError``.
    """
    if not isinstance(state, SCGState):
        raise TypeError(f"state must be an SCGState (from scg_init), got {type(state).__name__}")
    if not callable(fg):
        raise TypeError(f"fg must be a callable fg(w) -> (loss, gradient), got "
                        f"{type(fg).__name__}")
    check_positive("sigma0", sigma0)
    st = state
    if st.success:
        st.mu = float(st.d @ st.grad)
        if st.mu >= 0:
            st.d = -st.grad
            st.mu = float(st.d @ st.grad)
        st.kappa = float(st.d @ st.d)
        if st.kappa < np.finfo(float).eps:
            return False
        sigma = sigma0 / np.sqrt(st.kappa)
        _, g_plus = fg(st.w + sigma * st.d)
        st.gamma = float(st.d @ (g_plus - st.grad)) / sigma
        if not np.isfinite(st.gamma):
            raise ValueError("scg: the gradient is not finite a distance sigma0 along the search "
                             "direction: scale the features and targets")
    delta = st.gamma + st.beta * st.kappa
    if delta <= 0:
        delta = st.beta * st.kappa
        st.beta = st.beta - st.gamma / st.kappa
    alpha = -st.mu / delta
    w_new = st.w + alpha * st.d
    f_new, g_new = fg(w_new)
    ratio = 2.0 * (f_new - st.f) / (alpha * st.mu) if alpha * st.mu != 0 else -1.0
    moved = bool(np.isfinite(f_new) and ratio >= 0)
    if moved:
        st.success = True
        st.n_success += 1
        g_old = st.grad
        st.w, st.f, st.grad = w_new, float(f_new), g_new
    else:
        st.success = False
    if ratio < 0.25:
        st.beta = min(4.0 * st.beta, _BETA_MAX)
    elif ratio > 0.75:
        st.beta = max(0.5 * st.beta, _BETA_MIN)
    if st.n_success == st.w.size:
        st.d = -st.grad
        st.n_success = 0
    elif moved:
        pr = float((g_old - st.grad) @ st.grad) / st.mu
        st.d = pr * st.d - st.grad
    return moved
