"""Exercise 12: what a random split hides, and what the SVM learns from the touched rod."""

from dataclasses import replace

import numpy as np

from ebantenna.paper.data import QUICK_DESIGN
from ebantenna.paper.experiments import classify_materials_svm
from ebantenna.paper.splits import grouped_split, random_split
from ebantenna.signal import fft_features
from ebantenna.simulate import build_dataset, builtin_scene
from ebantenna.study import default_cache_dir

# [data]
# A small data set of the paper scene: 5 materials, contacts every 2.5 cm, 2 repetitions.
design = replace(QUICK_DESIGN, name="ex12", first_contact=0.025, contact_step=0.025, repetitions=2)
scene = builtin_scene("paper")
# simulated on the first run, then read from the package's cache (as `ebantenna reproduce` does)
ds = build_dataset(default_cache_dir(), scene, design, seed=12)
X = fft_features(np.asarray(ds.ax, float), np.asarray(ds.az, float))
# [/data]

# 1. Two ways to hold out a fifth of the recordings.
splits = {"random": random_split(ds.material, seed=0), "grouped": grouped_split(ds.contact, seed=0)}
seen = {}
for name, (train, test) in splits.items():
    # how many test recordings were made at a position the training set also has
    seen[name] = float(np.isin(ds.contact[test], ds.contact[train]).mean())
print("test recordings at a position seen in training:", seen)
assert seen["random"] > 0.9 and seen["grouped"] == 0.0

# 2. The paper's SVM on both splits.
accuracy = {
    name: classify_materials_svm(X, ds.material, split=split).accuracies["test"]
    for name, split in splits.items()
}
print("SVM test accuracy:", accuracy)
# Neighbouring recordings of one position are near-copies: the random split flatters.
assert accuracy["random"] > accuracy["grouped"]

# 3. The touched rod made rigid: the same data set without the rod's own modes (and without
#    what needs the rod: its damping, its preload's scatter, its contact that only pushes).
rod_effects = ("object_modes", "object_damping", "preload_scatter", "unilateral_contact")
# (a name of its own: the data set's cache file is named after the scene, and one file holds one
# configuration)
without_rod = [e for e in scene.effects if e.name not in rod_effects]
rigid = scene.with_(name="paper-rigid", effects=without_rod)
flat = build_dataset(default_cache_dir(), rigid, design, seed=12)
X_rigid = fft_features(np.asarray(flat.ax, float), np.asarray(flat.az, float))
rigid_accuracy = classify_materials_svm(X_rigid, flat.material, split=splits["random"])
rigid_accuracy = rigid_accuracy.accuracies["test"]
print("random split, rigid object:", rigid_accuracy)
# Without the rod the material reaches the signal nowhere: the recordings of one position are
# the same for every material but for their noise, and the SVM can only guess.
assert rigid_accuracy < accuracy["random"]

n_materials = len(design.materials)
ANSWERS = {"chance": 1 / n_materials, "seen_random": seen["random"],
           "seen_grouped": seen["grouped"], "accuracy_random": accuracy["random"],
           "accuracy_grouped": accuracy["grouped"], "accuracy_rigid": rigid_accuracy}
# The tolerance of each answer: how far two correct ways of working may differ, and why.
SPLIT = "the same data and split; another solver tolerance may flip one test recording of 30"
TOLERANCES = {
    "chance": ("abs", 0.005, "one over the number of materials, rounded to two digits"),
    "seen_random": ("abs", 0, "a share of whole recordings, from the seeded split"),
    "seen_grouped": ("abs", 0, "a share of whole recordings, from the seeded split"),
    "accuracy_random": ("abs", 0.035, SPLIT), "accuracy_grouped": ("abs", 0.035, SPLIT),
    "accuracy_rigid": ("abs", 0.035, SPLIT),
}
# The accuracies count recordings: another machine's last-bit rounding may move one by one test
# recording (a recording near a tie of the solver).
STEPS = {"accuracy_random": 1 / len(splits["random"][1]),
         "accuracy_grouped": 1 / len(splits["grouped"][1]),
         "accuracy_rigid": 1 / len(splits["random"][1])}
print("ok")
