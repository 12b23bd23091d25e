"""Exact natural frequencies of the probe from the transcendental frequency equation.

The reference that the finite elements must converge to. Each span of the beam obeys
``EI w'''' = rho A omega^2 w``, solved by ``w = C1 cos(beta x) + C2 sin(beta x) +
C3 cosh(beta x) + C4 sinh(beta x)`` with ``beta^4 = rho A omega^2 / EI``. Split the probe at the
contact pin into the span ``[0, a]`` and the overhang ``[a, L]`` (``b = L - a``), give the pin a
small rotation ``theta`` and ask what bending moment each part needs for it (sympy does this in a
few lines; the results are below). The pin carries no moment of its own, so the two curvatures
must agree:

- span, clamped at the hinge:  ``w''(a) / (beta theta) = -F(u) / H-(u)``
- span, pinned at the hinge:   ``w''(a) / (beta theta) =  P(u) / F(u)``
- overhang, free at the tip:   ``w''(a) / (beta theta) =  F(v) / H+(v)``

with ``u = beta a``, ``v = beta b`` and

    F(u) = sin u cosh u - cos u sinh u,   H-(u) = cos u cosh u - 1,
    H+(u) = cos u cosh u + 1,              P(u) = 2 sin u sinh u.

Clearing the denominators gives the frequency equations

    clamped:  F(u) H+(v) + F(v) H-(u) = 0,      pinned:  P(u) H+(v) - F(u) F(v) = 0.

Two numerical precautions make them good to 1e-10 everywhere: each term is divided by
``cosh u cosh v`` (so nothing overflows and the function stays of order one), and ``F``, ``H-``
and ``P`` are summed from their Taylor series for small arguments, where the closed forms lose all
their digits to cancellation (``F(u) ~ 2u^3/3``: a contact 1e-4 L from the hinge needs this).
Without a contact the probe is a cantilever (``H+(beta L) = 0``) or a pinned-free beam
(``F(beta L) = 0``, plus the rigid rotation at zero frequency).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from .._validate import check_choice, check_in_range, check_int, check_positive, check_real
from ..probe import Probe

__all__ = ["exact_frequencies", "frequency_equation"]

_SERIES_LIMIT = 1.0  # below this argument, Taylor series; above, closed forms
_FACT = [math.factorial(k) for k in range(40)]


def _series(u, first_power, sign_start, divide=0):
    """sum_k (-1)^k 4^(k+1) u^(4k+p-d) / (4k+p)! for k = 0.. (enough terms for u < 1).

    The division by ``u^d`` is done term by term, so that a tiny ``u`` (a contact 1e-300 m from
    the hinge) gives the finite limit instead of 0 / 0.
    """
    total = 0.0
    for k in range(7):
        p = 4 * k + first_power
        total += (-1) ** k * 4 ** (k + sign_start) * u ** (p - divide) / _FACT[p]
    return total


def _F_over_cosh(u, divide=0):
    """F(u) / (cosh(u) u^divide)."""
    if u < _SERIES_LIMIT:
        return _series(u, 3, 1, divide) / math.cosh(u)
    return (math.sin(u) - math.cos(u) * math.tanh(u)) / u**divide


def _Hminus_over_cosh(u, divide=0):
    """H-(u) / (cosh(u) u^divide)."""
    if u < _SERIES_LIMIT:
        # H-(u) = sum_{k>=1} (-1)^k 4^k u^(4k) / (4k)!
        #       = -(sum_{k>=0} (-1)^k 4^(k+1) u^(4k+4) / (4k+4)!)
        return -_series(u, 4, 1, divide) / math.cosh(u)
    return (math.cos(u) - 1.0 / math.cosh(u)) / u**divide


def _Hplus_over_cosh(u):
    return math.cos(u) + 1.0 / math.cosh(u)


def _P_over_cosh(u, divide=0):
    """P(u) / (cosh(u) u^divide)."""
    if u < _SERIES_LIMIT:
        return _series(u, 2, 1, divide) / math.cosh(u)
    return 2 * math.sin(u) * math.tanh(u) / u**divide


def frequency_equation(beta: float, length: float, contact: float | None, hinge: str) -> float:
    """The scaled frequency equation; its roots in ``beta`` (1/m) are the natural frequencies.

    Parameters
    ----------
    beta : float
        Wave number, 1/m (``beta^4 = rho A omega^2 / EI``).
    length, contact : float
        Probe length and contact position from the hinge, m (``contact=None``: no contact).
    hinge : {"clamped", "pinned"}
    """
    hinge = check_choice("hinge", hinge, ("clamped", "pinned"))
    beta, length = check_real("beta", beta), check_positive("length", length)
    if contact is not None:  # anywhere inside: the series keep a contact at 1e-100 m accurate
        contact = check_in_range("contact", contact, 0.0, length)
    if contact is None:
        if hinge == "clamped":
            return _Hplus_over_cosh(beta * length)
        return _F_over_cosh(beta * length, divide=3)
    u, v = beta * contact, beta * (length - contact)
    if hinge == "clamped":
        # divided by u^3 as well, so that a contact next to the hinge does not flatten it to zero
        span_f, span_h = _F_over_cosh(u, divide=3), _Hminus_over_cosh(u, divide=3)
        return span_f * _Hplus_over_cosh(v) + _F_over_cosh(v) * span_h
    span_p, span_f = _P_over_cosh(u, divide=2), _F_over_cosh(u, divide=2)
    return span_p * _Hplus_over_cosh(v) - span_f * _F_over_cosh(v)


def exact_frequencies(
    probe: Probe, contact: float | None, *, hinge: str = "clamped", n_modes: int = 3
) -> np.ndarray:
    """Exact natural frequencies of a probe pinned at the contact, Hz.

    Parameters
    ----------
    probe : Probe
        Must have no tip mass (the reference covers the bare beam).
    contact : float or None
        Contact position from the hinge, m, in ``(0, L)``; None for no contact.
    hinge : {"clamped", "pinned"}
        The hinge condition.
    n_modes : int
        Number of lowest frequencies.

    Returns
    -------
    ndarray of shape (n_modes,)
        Ascending; a pinned probe without contact starts with its rigid rotation at 0 Hz.

    Examples
    --------
    >>> from ebantenna import Probe
    >>> from ebantenna.fem.exact import exact_frequencies
    >>> exact_frequencies(Probe(), None, n_modes=2).round(4)   # cantilever, beta L = 1.8751, 4.6941
    array([13.8828, 87.0022])
    """
    from .assembly import Supports

    if not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
    supports = Supports(contact=contact, hinge=hinge)
    if not isinstance(hinge, str):
        raise ValueError(
            f"hinge must be 'clamped' or 'pinned' for the exact solution, got {hinge!r}"
        )
    n_modes = check_int("n_modes", n_modes, minimum=1)
    if probe.tip_mass != 0:
        raise ValueError(f"tip_mass must be 0 for the exact solution, got {probe.tip_mass!r}")
    L = probe.length
    if contact is not None and not contact < L:
        raise ValueError(f"contact must lie in (0, {L:g}) m, got {contact!r}")
    betas = []
    if supports.contact is None and hinge == "pinned":
        betas.append(0.0)  # rigid rotation
    step = math.pi / (64 * L)
    lo = step / 8
    f_lo = frequency_equation(lo, L, contact, hinge)
    while len(betas) < n_modes:
        hi = lo + step
        f_hi = frequency_equation(hi, L, contact, hinge)
        if f_lo == 0.0:
            betas.append(lo)
        elif f_lo * f_hi < 0:
            betas.append(
                brentq(
                    frequency_equation, lo, hi, args=(L, contact, hinge), xtol=1e-300, rtol=1e-15
                )
            )
        lo, f_lo = hi, f_hi
        if lo * L > 700:
            raise ValueError(f"n_modes={n_modes} is beyond the range of the exact solver")
    beta = np.array(betas[:n_modes])
    omega = beta**2 * math.sqrt(probe.flexural_rigidity / probe.mass_per_length)
    return omega / (2 * math.pi)
