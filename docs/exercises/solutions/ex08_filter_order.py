"""Exercise 8: the order Table 1 needs, and why the filter must run as second-order sections."""

import numpy as np
from scipy import signal

from ebantenna.signal import PAPER_FILTERS, check_specification, design_bandpass, filter_order


def chebyshev_order(spec):
    """Order of the Chebyshev I band-pass meeting ``spec``, by the textbook formula."""
    # 1. pre-warp the edges for the bilinear transform: Omega = tan(pi f / fs)
    warp = np.tan(np.pi * np.array([*spec.passband, *spec.stopband]) / spec.fs)
    p1, p2, s1, s2 = warp
    # 2. band-pass -> low-pass: Omega -> (Omega^2 - p1 p2) / (Omega (p2 - p1)); the pass band
    #    maps to [-1, 1], and the nearer stop-band edge sets the low-pass selectivity
    selectivity = min(abs((s**2 - p1 * p2) / (s * (p2 - p1))) for s in (s1, s2))
    # 3. the Chebyshev order formula
    ratio = np.sqrt((10 ** (spec.attenuation / 10) - 1) / (10 ** (spec.ripple / 10) - 1))
    return int(np.ceil(np.arccosh(ratio) / np.arccosh(selectivity))), selectivity


table1 = PAPER_FILTERS["chebyshev"]
order, selectivity = chebyshev_order(table1)
print(f"Table 1: low-pass selectivity {selectivity:.4f}, order {order} ({2 * order} poles)")
assert order == filter_order(table1) == 13
# The paper's "second order" misses the table by far:
assert not check_specification(design_bandpass(table1, 2), table1).meets
assert check_specification(design_bandpass(table1), table1).meets

# The same filter as one transfer function (b, a) and as second-order sections
b, a = design_bandpass(table1, output="ba")
sos = design_bandpass(table1, output="sos")
radius_ba = np.abs(np.roots(a)).max()
radius_sos = max(np.abs(np.roots(section[3:])).max() for section in sos)
print(f"largest pole radius: (b, a) {radius_ba:.4f}, sections {radius_sos:.6f}")
assert radius_ba > 1.0 > radius_sos  # rounding the 27 coefficients pushed poles outside

# What that does to a signal: the impulse response of the (b, a) form grows without bound
impulse = np.zeros(3000)
impulse[0] = 1.0
h_ba = signal.lfilter(b, a, impulse)
h_sos = signal.sosfilt(sos, impulse)
print(f"impulse response after 3 s: (b, a) {abs(h_ba[-1]):.1e}, sections {abs(h_sos[-1]):.1e}")
assert abs(h_ba[-1]) > 1e3 and abs(h_sos[-1]) < 1e-2

# The same question for Table 2
assert filter_order(PAPER_FILTERS["elliptic"]) == 8

# The expected answers on the exercise page, checked against these values by the test suite.
ANSWERS = {"order": order, "selectivity": selectivity, "radius_sos": radius_sos,
           "n_coefficients_ba": len(a)}
# The tolerance of each answer: how far two correct ways of working may differ, and why.
TOLERANCES = {
    "order": ("abs", 0, "an integer: the next one above the formula's value"),
    "selectivity": ("rel", 1e-6, "the same closed formula; the edges' pre-warping is exact"),
    "radius_sos": ("rel", 1e-6, "roots of quadratics from the same design, to rounding"),
    "n_coefficients_ba": ("abs", 0, "a count of coefficients, which no rounding moves"),
}
print("ok: Table 1 needs order 13; as (b, a) that filter is unstable, as sections it is not")
