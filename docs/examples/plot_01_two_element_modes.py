"""
The paper's two-element model and its modes
============================================

The paper models the probe with two Euler-Bernoulli elements: one from the hinge to the contact,
one from the contact to the free tip. Here we solve that model for the five contact positions the
paper studies (0.25 L to 0.9 L), print the three natural frequencies, and draw the lowest
("dominant") mode shape beside the same mode computed with 64 elements.

The shapes are drawn with the Hermite shape functions between the nodes, so even the two-element
model gives a smooth curve.
"""

import matplotlib.pyplot as plt
import numpy as np

from ebantenna import Probe
from ebantenna.fem import Supports, modal_analysis, natural_frequencies

probe = Probe()  # acrylic tube: 40 cm long, 8 mm outside, 6 mm inside diameter
print(f"EI = {probe.flexural_rigidity:.4f} N m^2, rho A = {probe.mass_per_length * 1e3:.2f} g/m")

# %%
# Frequencies of the two-element model
# ------------------------------------
# ``n_elements=2`` with a contact is exactly the paper's model: the clamped hinge and the pinned
# contact leave three free degrees of freedom, hence three frequencies.

ratios = [0.25, 0.5, 0.75, 0.8, 0.9]
for a in ratios:
    res = modal_analysis(probe, Supports(contact=a * probe.length), n_elements=2, n_modes=3)
    print(f"contact at {a:.2f} L: " + ", ".join(f"{f:8.2f} Hz" for f in res.frequencies))

# %%
# The dominant mode, coarse and fine
# ----------------------------------
# Full lines: two elements, their three nodes P (hinge), Q (contact) and R (tip) marked. Dashed: 64
# elements. With the contact near the hinge the two agree for this lowest mode; with the contact
# towards the tip, the single element of the long span cannot follow the mode that now lives
# there. Agreement in the lowest mode does not make the two-element model converged: its second
# and third frequencies are at best about 20 % and 38 % too high (see the
# theory page on convergence).

fig, axes = plt.subplots(len(ratios), 1, figsize=(7, 9), sharex=True)
for ax, a in zip(axes, ratios, strict=True):
    supports = Supports(contact=a * probe.length)
    coarse = modal_analysis(probe, supports, n_elements=2, n_modes=1)
    fine = modal_analysis(probe, supports, n_elements=64, n_modes=1)
    coarse.plot(ax=ax, label="2 elements, mode")  # the mode, the hinge and the contact
    w2 = coarse.displacement(np.linspace(0, probe.length, 400))[:, 0]
    peak = w2[np.argmax(np.abs(w2))]  # plot() scales each mode to a peak of +1
    ax.plot(100 * coarse.nodes, coarse.displacement(coarse.nodes)[:, 0] / peak, "o",
            color="tab:blue", ms=4, label="2 elements: nodes P, Q, R")
    x = fine.nodes
    w = fine.displacement(x)[:, 0]
    ax.plot(100 * x, w / w[np.argmax(np.abs(w))], "k--", lw=1,
            label=f"64 elements: {fine.frequencies[0]:.1f} Hz")
    ax.set_title(f"contact at {a:.2f} L", fontsize="small")
    ax.set_xlabel("")
    ax.set_ylabel("")
    ax.legend(fontsize="x-small", loc="lower left")
axes[-1].set_xlabel("distance from the hinge (cm)")
fig.supylabel("normalised deflection of the lowest mode")
fig.tight_layout()

# %%
# The lowest frequency along the whole probe
# ------------------------------------------
# The same comparison for every contact position: the two-element model's lowest frequency
# follows the fine mesh's while the contact is near the hinge and leaves it towards the tip.
sweep = np.linspace(0.05, 0.95, 91) * probe.length
fig, ax = plt.subplots(figsize=(6.5, 4))
for n, style in ((64, "k-"), (2, "o")):
    f1 = natural_frequencies(probe, sweep, n_modes=1, n_elements=n)[:, 0]
    ax.plot(100 * sweep, f1, style, ms=3, label=f"{n} elements")
ax.set_xlabel("contact distance from the hinge (cm)")
ax.set_ylabel("lowest natural frequency (Hz)")
ax.legend()
fig.tight_layout()

# sphinx_gallery_thumbnail_number = 2
plt.show()
