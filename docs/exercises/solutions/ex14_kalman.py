"""Exercise 14: the steady Kalman gain by hand, and a Kalman filter on a drifting level."""

import numpy as np

from ebantenna.signal import KalmanFilter

# [data]
fs = 1000.0  # Hz
n = 3000  # samples, 3 s
q_std, r_std = 0.01, 0.2  # m/s^2: the drift's step per sample, the sensor's noise
rng = np.random.default_rng(14)
level = 9.81 + np.cumsum(q_std * rng.standard_normal(n))  # the slowly drifting level, m/s^2
y = level + r_std * rng.standard_normal(n)  # what the accelerometer reports, m/s^2
# [/data]
q, r = q_std**2, r_std**2

# 1. The steady gain by hand. The scalar filter predicts P- = P + q, takes the gain
#    K = P- / (P- + r) and keeps P = (1 - K) P-. At a fixed point P- = P + q, which gives the
#    Riccati equation P-^2 - q P- - q r = 0, and its positive root.
p_minus = 0.5 * (q + np.sqrt(q * q + 4 * q * r))
k_hand = p_minus / (p_minus + r)
p_steady = (1 - k_hand) * p_minus  # the variance of the steady estimate, (m/s^2)^2
# the same gain as theory/kalman.rst writes it, in x = q / r
x = q / r
assert abs(k_hand - 0.5 * (-x + np.sqrt(x * x + 4 * x))) < 1e-12  # two forms, rounding apart
print(f"steady gain by hand: K = {k_hand:.6f}, estimate's standard deviation "
      f"{np.sqrt(p_steady):.4f} m/s^2")

# 2. The filter. Its variance converges to the fixed point geometrically, by the factor
#    (1 - K)^2 per step: after 3000 steps only rounding separates its gain from the fixed point's.
kf = KalmanFilter.random_walk(process_std=q_std, measurement_std=r_std)
res = kf.filter(y)
k_filter = res.gain[-1, 0]
print(f"the filter's last gain: K = {k_filter:.6f}")
assert abs(k_filter / k_hand - 1) < 1e-9
assert abs(res.variance[-1] / p_steady - 1) < 1e-9  # and its variance is P, too

# 3. Against the true level, once the start is over (1000 samples, about fifty times 1/K).
settled = slice(1000, None)
assert 1000 * k_hand > 45  # the start's transient has decayed by (1 - K)^1000 < e^-45
rms_raw = np.sqrt(np.mean((y[settled] - level[settled]) ** 2))
rms_filtered = np.sqrt(np.mean((res.estimate[settled] - level[settled]) ** 2))
print(f"RMS error: measurement {rms_raw:.4f}, filtered {rms_filtered:.4f}, "
      f"predicted {np.sqrt(p_steady):.4f} m/s^2")
# The steady error is an AR(1) sequence with coefficient phi = 1 - K: its sample variance over N
# samples scatters with relative standard deviation sqrt(2 (1 + phi^2) / (N (1 - phi^2))).
phi, n_settled = 1 - k_hand, n - 1000
spread = np.sqrt(2 * (1 + phi**2) / (n_settled * (1 - phi**2)))
assert abs(rms_filtered**2 / p_steady - 1) < 3 * spread  # within three standard deviations
assert abs(rms_raw**2 / r - 1) < 3 * np.sqrt(2 / n_settled)  # white noise: N independent squares

# 4. A filter tuned for another drift: q a hundred times too small lags the drift, a hundred
#    times too large follows the noise. The tuned one is the best of the three.
rms_tuned = {}
for factor in (0.01, 1.0, 100.0):
    other = KalmanFilter.random_walk(process_std=q_std * np.sqrt(factor), measurement_std=r_std)
    estimate = other.filter(y).estimate
    rms_tuned[factor] = np.sqrt(np.mean((estimate[settled] - level[settled]) ** 2))
    print(f"q x {factor:g}: RMS error {rms_tuned[factor]:.4f} m/s^2")
assert rms_tuned[1.0] < rms_tuned[0.01] and rms_tuned[1.0] < rms_tuned[100.0]

# The expected answers on the exercise page, checked against these values by the test suite.
ANSWERS = {
    "k_steady": k_hand,
    "sigma_steady": np.sqrt(p_steady),
    "rms_raw": rms_raw,
    "rms_filtered": rms_filtered,
    "rms_q_small": rms_tuned[0.01],
    "rms_q_large": rms_tuned[100.0],
}
# How far a right answer may lie from these values, and why.
CLOSED_FORM = "a closed form: any right algebra gives it to rounding, or to five copied digits"
SAME_DATA = "the statement fixes the data, the filter and the cut at 1000 samples: only sums differ"
TOLERANCES = {"k_steady": ("rel", 1e-4, CLOSED_FORM), "sigma_steady": ("rel", 1e-4, CLOSED_FORM),
              "rms_raw": ("rel", 1e-3, SAME_DATA), "rms_filtered": ("rel", 1e-3, SAME_DATA),
              "rms_q_small": ("rel", 1e-3, SAME_DATA), "rms_q_large": ("rel", 1e-3, SAME_DATA)}

print("ok")
