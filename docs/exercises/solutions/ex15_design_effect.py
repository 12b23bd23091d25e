"""Exercise 15: why 25 repetitions are not 25 tests: the design effect and the cluster bootstrap."""

import math

import numpy as np
from scipy.stats import t as student_t

from ebantenna.ml.metrics import accuracy_interval
from ebantenna.paper.uncertainty import ClusteredAccuracy, cluster_bootstrap, design_effect

# [data]
# 20 contact positions, 10 repetitions of each. Every position has its own rate of right
# answers, shared by its repetitions, drawn from a Beta(2, 0.5) distribution (mean 0.8).
n_positions, m = 20, 10
true_accuracy = 2.0 / (2.0 + 0.5)  # the mean of Beta(2, 0.5): the generator's accuracy


def draw_design(rng):
    """One design: whether each repetition was right, shape (positions, repetitions)."""
    rate = rng.beta(2.0, 0.5, size=n_positions)
    return rng.random((n_positions, m)) < rate[:, None]


right = draw_design(np.random.default_rng(15))  # the data set of steps 1 to 3
rng = np.random.default_rng(1500)
designs = np.array([draw_design(rng) for _ in range(1000)])  # 1000 more, for step 4
# [/data]
z = 1.959963984540054  # the standard normal's 97.5 % quantile: a two-sided 95 % interval
N = right.size  # 200 recordings
k = right.sum(axis=1)  # right answers per position
n = np.full(n_positions, m)  # recordings per position


def wilson(p, size, z=z):
    """Wilson's 95 % score interval of a proportion p on size trials (size may be real)."""
    centre = p + z * z / (2 * size)
    half = z * math.sqrt(p * (1 - p) / size + z * z / (4 * size * size))
    return (centre - half) / (1 + z * z / size), (centre + half) / (1 + z * z / size)


# 1. The accuracy, and Wilson's interval as if the 200 recordings were 200 independent tests.
p_hat = k.sum() / N
rec_low, rec_high = wilson(p_hat, N)
print(f"accuracy {p_hat:.3f}, recording-level 95 % interval {rec_low:.3f}-{rec_high:.3f}")
# the package's interval: the same closed form, a few roundings apart
assert np.allclose((rec_low, rec_high), accuracy_interval(int(k.sum()), N), rtol=0, atol=1e-12)

# 2. How much the repetitions of one position go together. One-way analysis of variance of the
#    0/1 outcomes by position: the mean squares between and within the positions.
p_j = k / m
ssb = m * np.sum((p_j - p_hat) ** 2)  # between the positions
ssw = np.sum(m * p_j * (1 - p_j))  # within: sum of (y - p_j)^2 of 0/1 outcomes
msb, msw = ssb / (n_positions - 1), ssw / (n_positions * (m - 1))
icc = (msb - msw) / (msb + (m - 1) * msw)
deff_icc = 1 + (m - 1) * icc
# The design effect as the theory page defines it: the variance of p_hat counting each position
# as one observation over the binomial variance counting each recording as one.
deff = max(1.0, np.sum((k - p_hat * n) ** 2) / (N * p_hat * (1 - p_hat)))
n_eff = N / deff
eff_low, eff_high = wilson(p_hat, n_eff)
print(f"ICC {icc:.3f}: 1 + (m - 1) ICC = {deff_icc:.3f}; design effect {deff:.3f}, "
      f"effective n {n_eff:.1f}, interval {eff_low:.3f}-{eff_high:.3f}")
# The two design effects are the same sum of squares: deff is 1 + (m - 1) times the ANOVA
# estimator with the between mean square over G instead of G - 1 (no degree of freedom spent on
# the mean), so deff_icc is the larger by a term of order 1/G.
icc_g = (ssb / n_positions - msw) / (ssb / n_positions + (m - 1) * msw)
assert abs(1 + (m - 1) * icc_g - deff) < 1e-12 * deff  # a few roundings of sums of squares
assert deff < deff_icc < deff * n_positions / (n_positions - 1)
# the package: the same ratio in whole numbers; its interval is Wilson's at N / deff with
# Student's quantile on G - 1 = 19 degrees of freedom in place of z (the design effect is
# estimated from 20 positions), a little wider than the one above
assert abs(design_effect(k, n) / deff - 1) < 1e-12  # 20 rounded squares against exact integers
t_19 = float(student_t.ppf(0.975, n_positions - 1))
clustered = ClusteredAccuracy(k, n, "position")
assert np.allclose(clustered.ci95, wilson(p_hat, n_eff, t_19), rtol=0, atol=1e-12)
assert clustered.ci95[0] < eff_low and clustered.ci95[1] > eff_high
assert eff_high - eff_low > 1.5 * (rec_high - rec_low)  # far wider than the recordings say

# 3. The cluster bootstrap by hand: draw 20 positions with replacement, whole, 10000 times, and
#    take the 2.5 % and 97.5 % percentiles of the accuracy of what was drawn.
resamples = 10_000
pick = np.random.default_rng(1).integers(0, n_positions, size=(resamples, n_positions))
boot = k[pick].sum(axis=1) / n[pick].sum(axis=1)
boot_low, boot_high = np.quantile(boot, [0.025, 0.975])
print(f"cluster bootstrap interval {boot_low:.3f}-{boot_high:.3f}")
# the package's, with the same seed, draws the same positions
assert (boot_low, boot_high) == cluster_bootstrap(k, n, resamples=resamples, seed=1)
# With infinitely many resamples: the total right of 20 positions drawn at random is a sum of
# 20 independent draws from the positions' counts k_j; its distribution is their 20-fold
# convolution, exact. Its variance is the cluster variance of the theory page, deff times the
# binomial one: the bootstrap and the design effect measure the same spread.
one = np.bincount(k, minlength=m + 1) / n_positions  # one position drawn: its count's pmf
total = np.array([1.0])
for _ in range(n_positions):
    total = np.convolve(total, one)
values = np.arange(total.size) / N  # the accuracy of each total, on a lattice of 1/N
mean = values @ total
assert abs(mean - p_hat) < 1e-12
assert abs((values - mean) ** 2 @ total / (deff * p_hat * (1 - p_hat) / N) - 1) < 1e-9
# How far another student's 10000 resamples may put an end: the empirical 2.5 % point's CDF
# scatters with sd sqrt(q (1 - q) / B); within 4 sd the end stays between the lattice values
# where the exact CDF crosses q -+ 4 sd. Half a lattice step more covers quantile conventions.
cdf = np.cumsum(total)
boot_tolerance = 0.0
for q, end in ((0.025, boot_low), (0.975, boot_high)):
    sd = math.sqrt(q * (1 - q) / resamples)
    band = values[np.searchsorted(cdf, [q - 4 * sd, q + 4 * sd])]
    assert band[0] - 1e-12 <= end <= band[1] + 1e-12  # this run's end is inside
    boot_tolerance = max(boot_tolerance, end - band[0], band[1] - end)
steps = round(boot_tolerance * N)  # whole lattice steps of 1/N
boot_tolerance = (steps + 0.5) / N
print(f"another seed moves an end by at most {boot_tolerance:.4f}")

# 4. Coverage: of 1000 designs drawn from the same generator, how often does each interval hold
#    the generator's accuracy 0.8?
covered = {"recording": 0, "deff": 0}
deffs = []
margin = math.inf  # how near the truth the nearest end of any interval comes
shift = 0.0  # how far z = 1.96 instead of 1.95996 moves an end
for design in designs:
    kd = design.sum(axis=1)
    p = kd.sum() / N
    d = max(1.0, np.sum((kd - p * n) ** 2) / (N * p * (1 - p)))
    deffs.append(d)
    for name, (lo, hi) in (("recording", wilson(p, N)), ("deff", wilson(p, N / d))):
        covered[name] += lo <= true_accuracy <= hi
        margin = min(margin, abs(lo - true_accuracy), abs(hi - true_accuracy))
    for size in (N, N / d):
        shift = max(shift, *np.abs(np.subtract(wilson(p, size, 1.96), wilson(p, size))))
    assert np.allclose(ClusteredAccuracy(kd, n, "position").ci95, wilson(p, N / d, t_19),
                       atol=1e-12)
mean_deff = float(np.mean(deffs))
coverage_recording = covered["recording"] / len(designs)
coverage_deff = covered["deff"] / len(designs)
print(f"coverage of 95 % intervals over {len(designs)} designs: recording-level "
      f"{coverage_recording:.3f}, design effect {coverage_deff:.3f}; nearest end {margin:.2e}")
assert coverage_recording < 0.85 < coverage_deff
# The generator's own design effect: repetitions of a rate drawn from Beta(a, b) have intraclass
# correlation 1 / (a + b + 1). Twenty positions estimate it low on average, one reason why the
# design-effect interval still falls short of 95 %.
deff_generator = 1 + (m - 1) / (2.0 + 0.5 + 1)
print(f"the generator's design effect {deff_generator:.2f}, estimated on average {mean_deff:.2f}")
assert mean_deff < deff_generator
# No end lies near enough the truth for z = 1.96 instead of 1.95996, or rounding, to flip a
# design in or out: every right way of working counts the same designs.
print(f"z = 1.96 moves an end by at most {shift:.1e}")
assert margin > 1e-4 > 10 * shift

ANSWERS = {"accuracy": p_hat, "rec_low": rec_low, "rec_high": rec_high, "icc": icc,
           "deff_icc": deff_icc, "deff": deff, "n_eff": n_eff, "eff_low": eff_low,
           "eff_high": eff_high, "boot_low": boot_low, "boot_high": boot_high,
           "coverage_recording": coverage_recording, "coverage_deff": coverage_deff}
# How far a right answer may lie from these values, and why.
SUMS = "sums of squares of whole counts: rounding only, or five copied digits"
CLOSED = "a closed form of the stated data: rounding, z = 1.96 for 1.95996, or five copied digits"
COVER = ("a share of 1000 designs: no interval's end lies within 1e-4 of 0.8, so rounding or "
         "z = 1.96 flips none; half a design")
TOLERANCES = {
    "accuracy": ("abs", 0.5 / N, "a count of right answers out of 200: half of one in 200"),
    **{name: ("rel", 1e-4, SUMS) for name in ("icc", "deff_icc", "deff", "n_eff")},
    **{name: ("rel", 1e-4, CLOSED) for name in ("rec_low", "rec_high", "eff_low", "eff_high")},
    **{name: ("abs", boot_tolerance, "another seed's 10000 resamples move an end by at most "
              f"{steps} steps of 1/200 (4 sd of a percentile), half a step for quantile "
              "conventions")
       for name in ("boot_low", "boot_high")},
    "coverage_recording": ("abs", 0.5 / len(designs), COVER),
    "coverage_deff": ("abs", 0.5 / len(designs), COVER),
}
print("ok")
