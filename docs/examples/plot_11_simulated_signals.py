"""
Simulated signals and their norm spectra
========================================

:func:`ebantenna.simulate.simulate` turns a :class:`~ebantenna.simulate.Scene` into the
:class:`~ebantenna.recording.Recording` the accelerometer would deliver. The built-in ``paper``
scene models the paper's rig: the accelerometer board at the tip, the touched rod with its own
modes, a contact that only pushes, sensor noise, mains hum, the sensor's own low-pass filter and
more (print ``scene.effects``). Here the
probe touches brass at the paper's five positions; each recording is shown with the paper's
feature, the norm of the X and Z spectra (its eq. 1 applied to the FFTs), beside the lowest
natural frequencies of the finite-element model of the same probe, tip mass included.
"""

import matplotlib.pyplot as plt
import numpy as np

from ebantenna.fem import Supports, modal_analysis
from ebantenna.signal import norm_spectrum
from ebantenna.simulate import builtin_scene, simulate

scene = builtin_scene("paper").with_(material="brass")
print(scene.probe)
print("effects:", ", ".join(type(e).__name__ for e in scene.effects))

ratios = [0.25, 0.5, 0.75, 0.8, 0.9]
fig, axes = plt.subplots(len(ratios), 2, figsize=(10, 10), sharex="col")
for (ax_t, ax_f), a in zip(axes, ratios, strict=True):
    contact = a * scene.probe.length
    rec = simulate(scene.with_(contact=contact), seed=1)
    f, mag = norm_spectrum(rec, remove_mean=True)
    modes = modal_analysis(scene.probe, Supports(contact=contact), n_modes=3).frequencies
    ax_t.plot(rec.t, rec.ax, lw=0.6, label="X")
    ax_t.plot(rec.t, rec.az, lw=0.6, label="Z")
    ax_t.set_ylabel("m/s$^2$")
    ax_t.set_title(f"contact at {a:.2f} L", fontsize="small")
    ax_f.semilogy(f[1:], mag[1:], lw=0.8)  # the DC bin is ~0 after the mean is removed
    ax_f.set_ylim(mag[1:].min() / 2, 2 * mag[1:].max())
    for fm in modes[modes < rec.fs / 2]:
        ax_f.axvline(fm, color="tab:red", ls=":", lw=1)
    ax_f.set_ylabel("|FFT| norm")
    print(f"{a:.2f} L: strongest bin {f[np.argmax(mag[1:]) + 1]:6.1f} Hz; "
          f"model modes {np.round(modes, 1)} Hz")
axes[0, 0].legend(fontsize="small")
axes[-1, 0].set_xlabel("time (s)")
axes[-1, 1].set_xlabel("frequency (Hz); dotted: model's natural frequencies")
fig.tight_layout()

# %%
# Up to 0.8 L the strongest bin sits on the lowest mode. At 0.9 L the lowest mode lives in the
# long span between hinge and contact (zone 3) and hardly moves the tip, where the accelerometer
# is: the strongest bin jumps to the second mode. That is the jump in the paper's distance data.
plt.show()
