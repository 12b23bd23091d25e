"""The strike march compiled by numba: the block engine's algorithm, one scalar at a time
(private).

Used only by :mod:`ebantenna.simulate._block_march` when numba is installed and this module
compiled (``IMPORT_ERROR`` says why not); otherwise the strike is marched by the NumPy block
engine. :func:`march_strike` is :func:`ebantenna.simulate._block_march.march_in_blocks` on a
:class:`~ebantenna.simulate.unilateral.StrikeLaw` or a
:class:`~ebantenna.simulate.unilateral.HertzStrikeLaw` whose states all have the modal
propagator, written with plain loops so that one call marches the whole strike:

* each state is read a block of steps ahead from its modal coordinates ``z`` (the table
  ``fine[j] = e^(lambda h (j + 1))``, the engine's own); where :func:`stays_positive` (or, on a
  chord, the bound between its nodes) shows that no event can happen over ``span`` steps, only
  the output samples are read, with the powers of ``e^(lambda sub h)`` formed by repeated
  products as the engine's ``every_real``;
* the step that holds an event is taken through the law's ``advance``: the sign of the force
  or the gap (or a chord's nodes) watched, the root found by the same safeguarded Newton
  iteration (:func:`crossing`, that of :func:`ebantenna.simulate.unilateral.crossing`), the
  other state entered there;
* the sums run in another order than NumPy's products, so the values read differ from the
  engine's by rounding (a few ulps of the largest term): the events are the same, each time
  within the root tolerance of the engine's, the signals equal up to that rounding carried by
  the conditioning of the modal basis.

What it does not do it reports: a status of 1 when the contact events reach ``max_events`` or
the chords change too often (the NumPy engine then marches the strike from the start, and
raises or warns as the law says).
"""

from __future__ import annotations

import math

import numpy as np

try:
    import numba
except ImportError as exc:  # not installed, or not working with this NumPy
    numba = None
    IMPORT_ERROR = f"{type(exc).__name__}: {exc}"
else:
    IMPORT_ERROR = ""

__all__ = ["march_strike", "crossing", "IMPORT_ERROR", "MAX_ROOT_STEPS"]

#: Most iterations of the event root finder (as :mod:`ebantenna.simulate.unilateral`).
MAX_ROOT_STEPS = 200
_TINY = float(np.finfo(float).tiny)
# the control array: status (0 ok, 1 gave up), events, chord changes, servo stopped
_STATUS, _EVENTS, _CHORDS, _STOPPED = range(4)


def _plain(function):
    """Without numba the loops stay Python functions (this module still imports, and the
    block engine does not use it)."""
    return function


_jit = numba.njit(cache=True) if numba is not None else _plain


@_jit
def _modal(Vinv, G, H, x, K):
    """``z = V^-1 (y + G s + H s')``."""
    y = np.empty(K)
    s, sigma = x[K], x[K + 1]
    for r in range(K):
        y[r] = x[r] + G[r] * s + H[r] * sigma
    z = np.zeros(K, np.complex128)
    for r in range(K):
        acc = 0j
        for c in range(K):
            acc += Vinv[r, c] * y[c]
        z[r] = acc
    return z


@_jit
def _at(V, lam, G, H, x, z, tau, K):
    """The state ``tau`` after ``x`` (``z``: its modal coordinates)."""
    out = x.copy()
    if tau == 0:
        return out
    s, sigma = x[K], x[K + 1]
    e = np.empty(K, np.complex128)
    for c in range(K):
        e[c] = np.exp(lam[c] * tau) * z[c]
    for r in range(K):
        acc = 0j
        for c in range(K):
            acc += V[r, c] * e[c]
        out[r] = acc.real - G[r] * (s + sigma * tau) - H[r] * sigma
    out[K] = s + sigma * tau
    out[K + 1] = sigma
    return out


@_jit
def _curve(w, lam, a, b, s, sigma, tau, sign, node):
    """``sign (g(tau) - node)`` and its rate, for the monitored row ``g`` with modal weights
    ``w`` and servo weights ``a, b``."""
    value = 0.0
    rate = 0.0
    for c in range(w.size):
        e = w[c] * np.exp(lam[c] * tau)
        value += e.real
        rate += (e * lam[c]).real
    value = value + a * (s + sigma * tau) + b * sigma
    rate = rate + a * sigma
    return sign * (value - node), sign * rate


@_jit
def crossing(w, lam, a, b, s, sigma, sign, node, span, xtol, ga, gb):
    """:func:`ebantenna.simulate.unilateral.crossing` on the curve :func:`_curve`."""
    lo, hi = 0.0, span
    t = lo + ga * (hi - lo) / (ga - gb)
    last = span
    for _ in range(MAX_ROOT_STEPS):
        g, rate = _curve(w, lam, a, b, s, sigma, t, sign, node)
        if g > 0:
            lo = t
        else:
            hi = t
        if hi - lo <= xtol:
            return hi
        step = g / rate if rate != 0 else math.inf
        new = t - step
        if not (lo < new < hi) or abs(step) > last / 2:
            new = (lo + hi) / 2
        elif abs(step) < xtol / 2:
            new += math.copysign(xtol / 2, -step)
            if not lo < new < hi:
                new = (lo + hi) / 2
        last = abs(new - t)
        t = new
    return hi


@_jit
def _switch(st, x, t, penA, ev_t, ev_kind, ev_v, ctl, max_events):
    """Enter the other of the free state (0) and the first closed state (1); count."""
    entering = 0 if st == 1 else 1
    n = ctl[_EVENTS]
    v = 0.0
    for c in range(x.size):
        v += penA[st, c] * x[c]
    ev_t[n] = t
    ev_kind[n] = entering
    ev_v[n] = v
    ctl[_EVENTS] = n + 1
    if n + 1 >= max_events:
        ctl[_STATUS] = 1
    return entering


@_jit
def _advance_linear(x, st, t0, t1, crosses, T, ctl, ev_t, ev_kind, ev_v, max_events, xtol):
    """:meth:`ebantenna.simulate.unilateral.StrikeLaw.advance`."""
    V, Vinv, lam, G, H, rows, row_modes, row_s, row_speed, penA, K = T
    while True:
        if not crosses:
            z = _modal(Vinv[st], G[st], H[st], x, K)
            x1 = _at(V[st], lam[st], G[st], H[st], x, z, t1 - t0, K)
            g1 = 0.0
            for c in range(x1.size):
                g1 += rows[st, 0, c] * x1[c]
            if g1 > 0:
                return x1, st
        z = _modal(Vinv[st], G[st], H[st], x, K)
        w = row_modes[st, 0] * z
        s, sigma = x[K], x[K + 1]
        span = t1 - t0
        end = _curve(w, lam[st], row_s[st, 0], row_speed[st, 0], s, sigma, span, 1.0, 0.0)[0]
        if end > 0:
            return _at(V[st], lam[st], G[st], H[st], x, z, span, K), st
        crosses = False
        start = 0.0
        for c in range(x.size):
            start += rows[st, 0, c] * x[c]
        if start <= 0:
            tau = 0.0
        else:
            tau = crossing(w, lam[st], row_s[st, 0], row_speed[st, 0], s, sigma, 1.0, 0.0,
                           span, xtol, start, end)
        x = _at(V[st], lam[st], G[st], H[st], x, z, tau, K)
        t0 = t0 + tau
        st = _switch(st, x, t0, penA, ev_t, ev_kind, ev_v, ctl, max_events)
        if ctl[_STATUS]:
            return x, st


@_jit
def _advance_hertz(x, st, t0, t1, T, lower, upper, shift, ctl, ev_t, ev_kind, ev_v,
                   max_events, xtol, max_chord_changes):
    """:meth:`ebantenna.simulate.unilateral.HertzStrikeLaw.advance` (through
    ``_first_exit`` and ``_change``); state 0 is free, state ``j + 1`` chord ``j``."""
    V, Vinv, lam, G, H, rows, row_modes, row_s, row_speed, penA, K = T
    fresh = False
    while True:
        span = t1 - t0
        z = _modal(Vinv[st], G[st], H[st], x, K)
        w = row_modes[st, 0] * z
        s, sigma = x[K], x[K + 1]
        a, b = row_s[st, 0], row_speed[st, 0]
        found = False
        best = 0.0
        up = True
        for side in range(2):
            if st == 0:
                if side == 1:
                    continue
                node, sign, which_up = 0.0, 1.0, True
            elif side == 0:
                node, sign, which_up = lower[st], 1.0, False
            else:
                node, sign, which_up = upper[st], -1.0, True
            if math.isinf(node):
                continue
            end = _curve(w, lam[st], a, b, s, sigma, span, sign, node)[0]
            if end > 0:
                continue
            start = _curve(w, lam[st], a, b, s, sigma, 0.0, sign, node)[0]
            if start <= 0 and not fresh:
                tau = 0.0
            else:
                tau = crossing(w, lam[st], a, b, s, sigma, sign, node, span, xtol,
                               max(start, _TINY), end)
            if not found or tau < best:
                found, best, up = True, tau, which_up
        if not found:
            return _at(V[st], lam[st], G[st], H[st], x, z, span, K), st
        x = _at(V[st], lam[st], G[st], H[st], x, z, best, K)
        t0 += best
        if st == 0 or (st == 1 and not up):
            st = _switch(st, x, t0, penA, ev_t, ev_kind, ev_v, ctl, max_events)
            if ctl[_STATUS]:
                return x, st
        else:
            ctl[_CHORDS] += 1
            if ctl[_CHORDS] > max_chord_changes * (ctl[_EVENTS] + 1):
                ctl[_STATUS] = 1
                return x, st
            new = st + 1 if up else st - 1
            x[K] += shift[st] - shift[new]
            st = new
        fresh = True


@_jit
def _values(fr, fi, wr, wi, row_s, row_speed, s, sigma, step, h, out):
    """The three rows at ``step`` steps from the block's start: ``Re(sum w e) + affine``, from
    the real and imaginary parts of ``e`` (``fr``, ``fi``) and of ``w`` (``wr``, ``wi``)."""
    for r in range(3):
        acc = 0.0
        for c in range(fr.size):
            acc += wr[r, c] * fr[c] - wi[r, c] * fi[c]
        out[r] = acc
    if sigma == 0:
        for r in range(3):
            out[r] += s * row_s[r]
    else:
        for r in range(3):
            out[r] += (s + sigma * h * step) * row_s[r]
            out[r] += sigma * row_speed[r]


@_jit
def _quiet(st, z, s, sigma, m, h, T, lower, upper, peak, growing, hertz):
    """No event within ``m`` steps: the modal part of the monitored row within its swing
    (:func:`ebantenna.simulate._block_march.stays_positive`, or a chord's nodes)."""
    lam, row_modes, row_s, row_speed = T[2], T[6], T[7], T[8]
    reach = 0.0
    for c in range(z.size):
        if growing[st]:
            rate = lam[st, c].real
            pk = np.exp((rate * m if rate > 0 else rate) * h)
        else:
            pk = peak[st, c]
        reach += abs(row_modes[st, 0, c] * z[c]) * pk
    a, b = row_s[st, 0], row_speed[st, 0]
    e0, e1 = s * a, (s + sigma * h * m) * a
    if not hertz or st == 0:
        return min(e0, e1) + sigma * b > reach
    return (min(e0, e1) + sigma * b - reach > lower[st]
            and max(e0, e1) + sigma * b + reach < upper[st])


@_jit
def _ends(st, value, lower, upper, hertz):
    """Whether the state ends at a step where its monitored row is ``value``."""
    if not hertz or st == 0:
        return value <= 0
    return value <= lower[st] or value >= upper[st]


@_jit
def _record(i, x, st, sub, rows, acc, force):
    """``SwitchedSystem._record`` of :mod:`ebantenna.simulate.unilateral`."""
    if i % sub == 0:
        k = i // sub
        a = 0.0
        f = 0.0
        for c in range(x.size):
            a += rows[st, 1, c] * x[c]
            f += rows[st, 2, c] * x[c]
        acc[k], force[k] = a, f


@_jit
def march_strike(x, st, n_steps, h, sub, block, span, stop_time, stopped, base,
                 V, Vinv, lam, G, H, rows, row_modes, row_s, row_speed, penA,
                 fine_re, fine_im, every_re, every_im, peak, growing, hertz, lower, upper, shift,
                 xtol, max_events, max_chord_changes, acc, force, ev_t, ev_kind, ev_v):
    """March a strike ``n_steps`` steps from ``(x, st)``, recording into ``acc`` and ``force``
    and the events into ``ev_t``, ``ev_kind`` (1: contact, 0: separation), ``ev_v``.

    The states are stacked along the first axis of the tables (0: free; 1: closed, or the
    first chord, then the next chords); ``fine[st, j] = e^(lambda h (j + 1))``, ``every[st] =
    e^(lambda sub h)``, each as its real and imaginary parts. Returns ``(x, st, control)`` with
    ``control = (status, events, chord changes, stopped)``; status 1: gave up (``max_events``
    reached or too many changes of chord), the records partial.
    """
    K = lam.shape[1]
    T = (V, Vinv, lam, G, H, rows, row_modes, row_s, row_speed, penA, K)
    ctl = np.zeros(4, np.int64)
    ctl[_STOPPED] = 1 if stopped else 0
    vals = np.empty(3)
    wr = np.empty((3, K))
    wi = np.empty((3, K))
    ekr = np.empty(K)
    eki = np.empty(K)
    i = 0
    while i < n_steps:
        if ctl[_STOPPED] == 0 and stop_time < (i + 1) * h:  # the servo stops in this step
            t0 = i * h
            for part in range(2):
                if hertz:
                    x, st = _advance_hertz(x, st, t0, stop_time if part == 0 else (i + 1) * h,
                                           T, lower, upper, shift, ctl, ev_t, ev_kind, ev_v,
                                           max_events, xtol, max_chord_changes)
                else:
                    x, st = _advance_linear(x, st, t0, stop_time if part == 0 else (i + 1) * h,
                                            False, T, ctl, ev_t, ev_kind, ev_v, max_events,
                                            xtol)
                if ctl[_STATUS]:
                    return x, st, ctl
                if part == 0:
                    n = base.size
                    x = x.copy()
                    for c in range(n):
                        x[n + c] += base[c] * x[2 * n + 1]
                    x[2 * n + 1] = 0.0
                    ctl[_STOPPED] = 1
                    t0 = stop_time
            i += 1
            _record(i, x, st, sub, rows, acc, force)
            continue
        limit = n_steps - i
        if ctl[_STOPPED] == 0:
            limit = min(limit, int(math.floor(stop_time / h)) - i)
        first = (-(i + 1)) % sub
        z = _modal(Vinv[st], G[st], H[st], x, K)
        s, sigma = x[K], x[K + 1]
        for r in range(3):
            for c in range(K):
                w = row_modes[st, r, c] * z[c]
                wr[r, c], wi[r, c] = w.real, w.imag
        event = False
        if _quiet(st, z, s, sigma, min(span, limit), h, T, lower, upper, peak, growing, hertz):
            m = min(span, limit)
            # the output samples only, the powers of e^(lambda sub h) by repeated products
            for c in range(K):
                e0 = np.exp(lam[st, c] * (h * (first + 1)))
                for r in range(3):
                    w = complex(wr[r, c], wi[r, c]) * e0
                    wr[r, c], wi[r, c] = w.real, w.imag
                ekr[c], eki[c] = 1.0, 0.0
            j = first
            while j < m:
                _values(ekr, eki, wr, wi, row_s[st], row_speed[st], s, sigma, j + 1, h, vals)
                k = (i + 1 + j) // sub
                acc[k], force[k] = vals[1], vals[2]
                for c in range(K):
                    a_, b_ = ekr[c], eki[c]
                    ekr[c] = a_ * every_re[st, c] - b_ * every_im[st, c]
                    eki[c] = a_ * every_im[st, c] + b_ * every_re[st, c]
                j += sub
        else:
            m = min(block, limit)
            for j in range(m):
                v0 = 0.0
                for c in range(K):
                    v0 += wr[0, c] * fine_re[st, j, c] - wi[0, c] * fine_im[st, j, c]
                if sigma == 0:
                    v0 += s * row_s[st, 0]
                else:
                    v0 += (s + sigma * h * (j + 1)) * row_s[st, 0]
                    v0 += sigma * row_speed[st, 0]
                if _ends(st, v0, lower, upper, hertz):
                    m = j
                    event = True
                    break
            j = first
            while j < m:
                _values(fine_re[st, j], fine_im[st, j], wr, wi, row_s[st], row_speed[st], s,
                        sigma, j + 1, h, vals)
                k = (i + 1 + j) // sub
                acc[k], force[k] = vals[1], vals[2]
                j += sub
        if m:
            x = _at(V[st], lam[st], G[st], H[st], x, z, m * h, K)
            i += m
        if event:
            if hertz:
                x, st = _advance_hertz(x, st, i * h, (i + 1) * h, T, lower, upper, shift, ctl,
                                       ev_t, ev_kind, ev_v, max_events, xtol,
                                       max_chord_changes)
            else:
                x, st = _advance_linear(x, st, i * h, (i + 1) * h, True, T, ctl, ev_t,
                                        ev_kind, ev_v, max_events, xtol)
            if ctl[_STATUS]:
                return x, st, ctl
            i += 1
            _record(i, x, st, sub, rows, acc, force)
    return x, st, ctl
