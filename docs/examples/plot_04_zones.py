"""
The three zones: why the dominant frequency stops rising near 80 % of the length
=================================================================================

As the contact moves from the hinge to the tip, the lowest mode moves from the overhang (zone 1)
to the span between hinge and contact (zone 3). The dominant frequency rises, turns over and
falls: it is not monotonic, and a distance read off it becomes ambiguous (the paper's Fig. 16).
"""

import matplotlib.pyplot as plt
import numpy as np

from ebantenna import Probe
from ebantenna.fem import Supports, dominant_mode_zones, modal_analysis, natural_frequencies

probe = Probe()
contacts = np.linspace(0.05, 0.975, 75) * probe.length  # 2 cm to 39 cm on the 40 cm probe
zones = dominant_mode_zones(probe, contacts)
start2, start3 = zones.boundaries()
print(f"zone 2 starts at {100 * start2:.1f} cm, zone 3 at {100 * start3:.1f} cm "
      f"({start2 / probe.length:.0%} and {start3 / probe.length:.0%} of the length)")

# %%
# Where is the maximum? A fine sweep with the batched solver; the paper's two-element model puts
# it further out.
fine = np.linspace(0.5, 0.95, 451) * probe.length
f64 = natural_frequencies(probe, fine, n_modes=1)[:, 0]
f2 = natural_frequencies(probe, fine, n_modes=1, n_elements=2)[:, 0]

fig, ax1 = plt.subplots(figsize=(7, 4.2))
zones.plot(ax=ax1)
ax1.plot(100 * fine, f2, ":", color="k", lw=1, label="two-element model")
ax1.legend(fontsize="small")
ax1.set_title("dominant frequency against contact position")
fig.tight_layout()
print(f"maximum at {fine[np.argmax(f64)] / probe.length:.3f} L (64 elements), "
      f"{fine[np.argmax(f2)] / probe.length:.3f} L (two elements)")

# %%
# Mode shapes on both sides of the maximum: the overhang swings (zone 1), then the span does
# (zone 3).
fig, ax2 = plt.subplots(figsize=(7, 4.2))
for a, style in ((0.5, "-"), (0.8, "--"), (0.95, ":")):
    res = modal_analysis(probe, Supports(contact=a * probe.length), n_modes=1)
    x = np.linspace(0, probe.length, 300)
    w = res.displacement(x)[:, 0]
    w = w / w[np.argmax(np.abs(w))]
    ax2.plot(100 * x, w, style, label=f"contact {a:.2f} L, {res.frequencies[0]:.1f} Hz")
    ax2.plot(100 * a * probe.length, 0, "k^")
ax2.axhline(0, color="0.6", lw=0.8)
ax2.set_xlabel("distance from the hinge (cm)")
ax2.set_ylabel("lowest mode (peak = 1)")
ax2.legend(fontsize="small")
fig.tight_layout()
plt.show()
