"""Exercise 3: measure the order of convergence of the finite-element frequencies."""

import numpy as np

from ebantenna import Probe
from ebantenna.fem import Supports, exact_frequencies, modal_analysis

# [data]
probe = Probe()
contact = 0.25 * probe.length  # a node sits exactly at the contact for every mesh below
exact = exact_frequencies(probe, contact, n_modes=2)

meshes = [8, 16, 32, 64]
# [/data]
errors = np.array(
    [
        modal_analysis(probe, Supports(contact=contact), n_elements=n, n_modes=2).frequencies
        for n in meshes
    ]
) / exact - 1.0

# Halving h divides the error by 2^p: p = log2(e(h) / e(h/2)).
orders = np.log2(errors[:-1] / errors[1:])
print("relative errors:\n", errors)
print("observed orders:\n", orders.round(3))

# From above: every finite-element frequency is higher than the exact one.
assert np.all(errors > 0)
# Fourth order: on the finer meshes the observed order is 4 within 0.1 for both modes.
assert np.all(np.abs(orders[-2:] - 4.0) < 0.1), orders
# Richardson: with p = 4 two meshes give a better estimate than either,
# f_exact ~ (16 f_(h/2) - f_h) / 15.
f32, f64 = (1 + errors[-2:]) * exact
richardson = (16 * f64 - f32) / 15
print("relative error, 64 elements:  ", errors[-1])
print("relative error, extrapolated: ", richardson / exact - 1)
assert np.all(np.abs(richardson / exact - 1) < np.abs(errors[-1]) / 10)

# The expected answers on the exercise page, checked against these values by the test suite.
ANSWERS = {"order_mode1": orders[-1, 0], "order_mode2": orders[-1, 1],
           "error64_mode1": errors[-1, 0]}
# The tolerance of each answer: how far two correct ways of working may differ, and why.
ORDER = "the same meshes give the same order to many digits; 0.01 admits an own exact solver"
TOLERANCES = {
    "order_mode1": ("abs", 0.01, ORDER), "order_mode2": ("abs", 0.01, ORDER),
    # the error is the difference of two frequencies equal to nine digits: a root-finder
    # stopped at 1e-12 relative moves it by about 0.1 %
    "error64_mode1": ("rel", 0.01, (
        "an exact frequency from an own root-finder (tolerance 1e-12 or finer) moves this "
        "nine-digit difference by up to about 1 %"
    )),
}

print("ok: the error falls like h^4, from above")
