r"""
Digits lost by the naive eigensolver on fine meshes
===================================================

``scipy.linalg.eigh(K, M)`` finds every eigenvalue to an *absolute* accuracy of about
:math:`\varepsilon\,\omega_\mathrm{max}^2`. On a fine mesh the largest eigenvalue grows like the
fourth power of the number of elements, and the lowest modes, the ones we want, lose their digits.
The package inverts the problem instead (see the theory page on the eigenproblem). Here both are
compared with the exact frequency.

Two errors add up in this comparison. The mesh's own error falls like :math:`n^{-4}` (the theory
page on convergence): on 16 elements it is about :math:`10^{-6}` and no solver can do better, so
there the two solvers agree because both are limited by the mesh, not because the model has
converged. Somewhere between 40 and 80 elements the mesh's error falls below the bound of the
naive solver's rounding error, :math:`\varepsilon\,\omega_\mathrm{max}^2/(2\,\omega_1^2)`, which
grows like :math:`n^4`. The error a run actually makes lies under that bound, and how far under
depends on the last bits of the linear algebra library's sums; from there on only the inverted
solver keeps following the mesh.
"""

import matplotlib.pyplot as plt
import numpy as np

from ebantenna import Probe
from ebantenna.fem import Supports, exact_frequencies, modal_analysis

probe = Probe()
supports = Supports(contact=0.5 * probe.length)
exact = exact_frequencies(probe, supports.contact, n_modes=1)[0]

meshes = [16, 64, 256, 512, 1024]
errors = {"naive": [], "auto": []}
for n in meshes:
    for solver in errors:
        f = modal_analysis(probe, supports, n_elements=n, n_modes=1, solver=solver).frequencies[0]
        errors[solver].append(abs(f / exact - 1.0))
    print(f"{n:5d} elements: naive {errors['naive'][-1]:.1e}, inverted {errors['auto'][-1]:.1e}")

fig, ax = plt.subplots(figsize=(6, 4.5))
ax.loglog(meshes, errors["naive"], "o-", label="scipy.linalg.eigh(K, M)")
ax.loglog(meshes, errors["auto"], "s-", label="inverted + Rayleigh quotient (package)")
# the mesh's own error, n**-4 through the coarsest mesh, where rounding plays no part
ax.loglog(meshes, errors["auto"][0] * (meshes[0] / np.array(meshes)) ** 4, "k:",
          label="discretisation error alone, $\\propto n^{-4}$")
ax.set_xlabel("number of elements")
ax.set_ylabel("relative error of the first frequency")
ax.legend()
fig.tight_layout()
plt.show()
