"""Exercise 13: the material and the contact distance from two frequencies."""

import tempfile
from dataclasses import replace

import numpy as np

from ebantenna.paper.data import QUICK_DESIGN
from ebantenna.paper.experiments import classify_materials_svm
from ebantenna.paper.mode_curves import ModeCurveClassifier
from ebantenna.paper.splits import grouped_split
from ebantenna.signal import fft_features, peak_frequencies
from ebantenna.simulate import build_dataset, builtin_scene

# [data]
# A small data set of the paper scene: 5 materials, contacts every 1 cm, 2 repetitions.
design = replace(QUICK_DESIGN, name="ex13", first_contact=0.02, contact_step=0.01, repetitions=2)
with tempfile.TemporaryDirectory() as tmp:
    ds = build_dataset(tmp, builtin_scene("paper"), design, seed=13)
ax = np.asarray(ds.ax, float)
# [/data]

# 1. The two strongest peaks of X in every recording (the band starts one bin above DC).
fmin = ds.fs / ax.shape[1]
peaks = np.array([peak_frequencies(row, ds.fs, 2, fmin=fmin) for row in ax])
print("peaks of the first recording (Hz):", peaks[0])

# 2. At one contact position, how far apart are the materials' peaks?
here = ds.contact == ds.contact[0]
for name in np.unique(ds.material):
    mean = peaks[here & (ds.material == name)].mean(axis=0)
    print(f"{name:>9}: f1 = {mean[0]:7.2f} Hz, f2 = {mean[1]:7.2f} Hz")
spread = peaks[here].max(axis=0) / peaks[here].min(axis=0) - 1
print("relative spread over the materials at one position:", spread)
assert np.all(spread > 0.005)  # the rod moves the modes by more than half a percent
repeat = max(
    (peaks[here & (ds.material == n)].max(axis=0) / peaks[here & (ds.material == n)].min(axis=0)
     - 1).max()
    for n in np.unique(ds.material)
)
print("largest spread between repetitions of one material:", repeat)
assert repeat < spread.min()  # the rig's scatter is smaller than what the material does

# 3. Whole positions held out; the curves are calibrated on the others.
train, test = grouped_split(ds.contact, seed=0)
clf = ModeCurveClassifier().fit(peaks[train], ds.material[train], ds.contact[train])
n_correct = int(np.sum(clf.predict(peaks[test]) == ds.material[test]))
curve_accuracy = n_correct / len(test)
distance_cm = float(100 * np.abs(clf.predict_distance(peaks[test]) - ds.contact[test]).mean())
X = fft_features(ax, np.asarray(ds.az, float))
svm_accuracy = classify_materials_svm(X, ds.material, split=(train, test)).accuracies["test"]
print(f"held-out positions: mode curves {curve_accuracy:.2f}, SVM {svm_accuracy:.2f}, "
      f"distance error {distance_cm:.2f} cm")
assert curve_accuracy > svm_accuracy
assert curve_accuracy > 2 / len(design.materials)  # far above chance (0.2)

ANSWERS = {"spread_f1_pct": 100 * spread[0], "spread_f2_pct": 100 * spread[1],
           "repeat_pct": 100 * repeat, "curve_accuracy": curve_accuracy,
           "n_correct": n_correct, "n_test": len(test), "distance_cm": distance_cm,
           "svm_accuracy": svm_accuracy}
# The tolerance of each answer: how far two correct ways of working may differ, and why.
PEAK = (
    "peak_frequencies interpolates between FFT bins: another interpolation moves a peak by a "
    "small part of a bin"
)
SPLIT = "the same data and split; another solver tolerance may flip a recording or two of 80"
TOLERANCES = {
    "spread_f1_pct": ("rel", 0.1, PEAK), "spread_f2_pct": ("rel", 0.1, PEAK),
    "repeat_pct": ("rel", 0.1, PEAK),
    "curve_accuracy": ("abs", 0.03, SPLIT), "n_correct": ("abs", 2, SPLIT),
    "n_test": ("abs", 0, "the held-out recordings of the seeded grouped split"),
    "distance_cm": ("rel", 0.1, PEAK), "svm_accuracy": ("abs", 0.03, SPLIT),
}
print("ok")
