r"""
Spectrogram against wavelet scalogram
=====================================

The paper verifies the mode change with time-frequency pictures of the vibration (its Figs. 18 and
19): near the tip several modes ring at first and die quickly. Here a signal is built from the
probe's own first three modes at a contact near the tip (0.9 L), each decaying with the
structural loss factor of the tube (a mode of frequency :math:`f` decays with the time constant
:math:`1/(\pi \eta f)`), and looked at with a short-time FFT and with a Morlet wavelet.

The spectrogram has one time resolution for all frequencies; the wavelet uses short windows at high
frequency and long ones at low frequency, so it follows the fast-dying high modes and still
resolves the slow low one.
"""

import matplotlib.pyplot as plt
import numpy as np

from ebantenna import Probe
from ebantenna.fem import Supports, modal_analysis
from ebantenna.signal import morlet_scalogram, spectrogram

probe = Probe()
fs = 1000.0  # Hz
res = modal_analysis(probe, Supports(contact=0.9 * probe.length), n_modes=3)
f_modes = res.frequencies[res.frequencies < fs / 2]  # what the sampling rate can see
print("modes below the Nyquist frequency (Hz):", np.round(f_modes, 1))

t = np.arange(int(0.6 * fs)) / fs
taus = 1.0 / (np.pi * probe.loss_factor * f_modes)
amplitudes = np.array([1.0, 2.0, 1.5])[: f_modes.size]
x = sum(a * np.exp(-t / tau) * np.sin(2 * np.pi * f * t)
        for a, f, tau in zip(amplitudes, f_modes, taus, strict=True))
print("decay time constants (ms):", np.round(1e3 * taus, 1))

stft = spectrogram(x, fs, nperseg=64, noverlap=56)
# up to just below the Nyquist frequency, so that the third mode (about 477 Hz) is on the map
cwt = morlet_scalogram(x, fs, np.linspace(10.0, 495.0, 140), bandwidth=1.5)

fig, ax = plt.subplots(figsize=(7, 3))
ax.plot(t, x, lw=0.7)
ax.set_xlabel("time (s)")
ax.set_ylabel("signal (sum of unit modes)")
fig.tight_layout()

# %%
# The same signal as a spectrogram, then as a scalogram; dotted lines: the modes.
for transform in (stft, cwt):
    fig, ax = plt.subplots(figsize=(7, 3.6))
    transform.plot(ax=ax, dynamic_range=50)
    for f in f_modes:
        ax.axhline(f, color="w", lw=0.5, ls=":")
    fig.tight_layout()

# sphinx_gallery_thumbnail_number = 3
plt.show()
