r"""
Fitting the decay: time constant and gain
=========================================

The paper classifies materials by how fast the vibration dies away: it fits :math:`F(t) = a\,e^{bt}`
(its eq. 4) and calls :math:`a` the gain and :math:`1/b` the time constant.
:func:`ebantenna.signal.fit_decay <ebantenna.signal.decay.fit_decay>` fits the model to the envelope
of the signal (the magnitude of the analytic signal) and reports :math:`\tau = -1/b > 0`;
``method="sinusoid"`` fits the whole damped sinusoid to the signal itself instead, which has no
envelope bias. Here a damped tone with a known time constant, plus noise, checks them.
"""

import matplotlib.pyplot as plt
import numpy as np

from ebantenna.signal import DECAY_METHODS, envelope, fit_decay

fs = 1000.0  # Hz, the paper's sampling rate
t = np.arange(1000) / fs
tau_true, f0, a_true = 0.12, 95.0, 8.0  # s, Hz, m/s^2
rng = np.random.default_rng(0)
x = a_true * np.exp(-t / tau_true) * np.sin(2 * np.pi * f0 * t) + 0.05 * rng.standard_normal(t.size)

fits = {method: fit_decay(x, fs, method=method) for method in DECAY_METHODS}
for method, fit in fits.items():
    print(f"{method:9s}: tau = {fit.tau * 1e3:6.1f} ms (true {tau_true * 1e3:.0f}), "
          f"a = {fit.a:5.2f} (true {a_true}), status {fit.status}")

fig, ax = plt.subplots(figsize=(7, 4))
ax.plot(t, x, color="0.7", lw=0.6, label="signal")
ax.plot(t, envelope(x), color="0.3", lw=0.8, label="envelope")
best = fits["loglinear"]
ax.plot(t, best.model(t), "r--", label=rf"fit: $\tau$ = {best.tau * 1e3:.1f} ms")
ax.set_xlim(0, 0.6)
ax.set_xlabel("time (s)")
ax.set_ylabel("acceleration (m/s$^2$)")
ax.legend()
fig.tight_layout()
plt.show()
