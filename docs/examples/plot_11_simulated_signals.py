"""
Simulated signals and their norm spectra
========================================

:func:`ebantenna.simulate.simulate <ebantenna.simulate.simulator.simulate>` turns a
:class:`~ebantenna.simulate.scene.Scene` into the
:class:`~ebantenna.recording.Recording` the accelerometer would deliver. The built-in ``paper``
scene models the paper's rig: the accelerometer board at the tip, the touched rod with its own
modes, a contact that only pushes, sensor noise, mains hum, the sensor's own low-pass filter and
more (print ``scene.effects``). Here the
probe touches brass at the paper's five positions; each recording is shown with the paper's
feature, the norm of the X and Z spectra (its eq. 1 applied to the FFTs), beside the lowest
natural frequencies of the finite-element model of the same probe, tip mass included, pinned at
the contact (dotted). The simulator's own modes, probe and rod coupled through the contact, are
in the recording's metadata (``rec.metadata["modes_x_hz"]``).
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
          f"model modes {np.round(modes, 1)} Hz; "
          f"simulated (probe and rod) {rec.metadata['modes_x_hz'][:3]} Hz")
axes[0, 0].legend(fontsize="small")
axes[-1, 0].set_xlabel("time (s)")
axes[-1, 1].set_xlabel("frequency (Hz); dotted: model's natural frequencies")
fig.tight_layout()

# %%
# Up to 0.8 L the strongest bin sits on the lowest mode: within one bin (1 Hz, the resolution of
# a one-second record) of the simulated lowest frequency, which lies up to 1.2 Hz below the
# pinned model's because the rod and the contact spring give a little.
#
# At 0.9 L the lowest mode (70.4 Hz) lives in the long span between hinge and contact (zone 3)
# and hardly moves the tip, where the accelerometer is: its bin holds about a tenth of the
# strongest. The strongest bin, 89 Hz, is no mode of the probe at all. It is the brass rod's own
# first bending mode: 94.4 Hz for the rod alone in its stand, 89.0 Hz with the probe pressing on
# it (the second of the simulated modes). Brass loses little energy: that mode's damping ratio is
# 0.0008, against about 0.015 for the probe's modes, so it rings through the whole second while
# the probe's modes die away. The probe's second mode (near 187 Hz) holds about a fifth.
#
# On a rigid object the rod's modes are gone. The same scene without them (and without what
# needs them: the rod's damping, the scatter of the preload and the contact that only pushes,
# the set that ``ebantenna reproduce`` switches off together) shows what the tube alone does.
rod_effects = ("object_modes", "object_damping", "preload_scatter", "unilateral_contact")
rigid = scene.with_(effects=[e for e in scene.effects if e.name not in rod_effects])
contact = 0.9 * scene.probe.length
modes = modal_analysis(scene.probe, Supports(contact=contact), n_modes=3).frequencies
fig, ax = plt.subplots(figsize=(7, 4))
for label, s in (("brass rod", scene), ("rigid object", rigid)):
    rec = simulate(s.with_(contact=contact), seed=1)
    f, mag = norm_spectrum(rec, remove_mean=True)
    peak = f[np.argmax(mag[1:]) + 1]
    ax.semilogy(f[1:], mag[1:] / mag[1:].max(), lw=0.8,
                label=f"{label}: strongest bin {peak:.0f} Hz")
    print(f"0.90 L, {label}: strongest bin {peak:.1f} Hz")
for fm in modes[modes < rec.fs / 2]:
    ax.axvline(fm, color="tab:red", ls=":", lw=1)
ax.set_xlim(0, 400)
ax.set_xlabel("frequency (Hz); dotted: the probe's modes, pinned at the contact")
ax.set_ylabel("|FFT| norm / its largest bin")
ax.set_title("contact at 0.90 L")
ax.legend(fontsize="small")
fig.tight_layout()

# %%
# On the rigid object the strongest bin jumps to the probe's second mode (186.7 Hz): the lowest
# mode hardly reaches the tip. On the brass rod it lands on the rod's own mode instead. Either way
# the dominant frequency leaves the lowest mode beyond the peak of zone 2, which is the jump in
# the paper's distance data; where it lands depends on what the probe touched.
#
# sphinx_gallery_thumbnail_number = 2
plt.show()
