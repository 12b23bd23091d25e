"""
Convergence to the exact frequencies: from above, as h⁴
========================================================

The exact natural frequencies of the probe come from the transcendental frequency equation
(:func:`ebantenna.fem.exact_frequencies <ebantenna.fem.exact.exact_frequencies>`). The
finite-element frequencies must approach them **from above** (the method minimises the Rayleigh
quotient over a subspace) and with the **fourth power** of the element size :math:`h` (cubic
elements, energy with second derivatives).
"""

import matplotlib.pyplot as plt
import numpy as np

from ebantenna import Probe
from ebantenna.fem import Supports, exact_frequencies, modal_analysis

probe = Probe()
contact = 0.625 * probe.length  # 5/8 L: a node of every uniform mesh of 8 elements or more
exact = exact_frequencies(probe, contact, n_modes=3)
print("exact frequencies (Hz):", np.round(exact, 6))

# (4 elements are left out: their nodes miss 5/8 L, so the mesh would move a node onto the contact
# and its elements would no longer all be L/4 long, which the plot's h assumes)
meshes = np.array([8, 16, 32, 64, 128, 256])
errors = np.array(
    [
        modal_analysis(probe, Supports(contact=contact), n_elements=n, n_modes=3).frequencies
        for n in meshes
    ]
) / exact - 1.0

# %%
# Every error is positive: the mesh is too stiff, never too soft.
print("all finite-element frequencies above the exact ones:", bool(np.all(errors > 0)))

# %%
# The slope between successive meshes is the observed order; it tends to 4.
orders = np.log2(errors[:-1] / errors[1:])
for n, p in zip(meshes[1:], orders, strict=True):
    print(f"{n:4d} elements: observed order", np.round(p, 2))

fig, ax = plt.subplots(figsize=(6, 4.5))
h = probe.length / meshes
for k in range(3):
    ax.loglog(100 * h, errors[:, k], "o-", label=f"mode {k + 1}")
ax.loglog(100 * h, errors[-1, 0] * (h / h[-1]) ** 4, "k--", lw=1, label=r"$\propto h^4$")
ax.set_xlabel("element size h (cm)")
ax.set_ylabel(r"relative error $(f_\mathrm{FEM} - f_\mathrm{exact})\,/\,f_\mathrm{exact}$")
ax.set_title(f"contact at {contact * 100:.0f} cm, clamped hinge")
ax.legend()
fig.tight_layout()
plt.show()
