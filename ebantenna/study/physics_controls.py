"""Section 6c: what the material classifier learns: the ablation of every effect and the
equivalent-pair control."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..fem.rod import Rod
from ..paper.controls import (
    ABLATION_DESIGN,
    SPLIT_SEEDS,
    Ablation,
    ablation_accuracies,
    equivalent_pair_spread,
    equivalent_rod,
    grouped_svm_accuracy,
    grouped_svm_spread,
)
from ..paper.data import QUICK_DESIGN
from ..paper.feature_table import signal_features
from ..paper.mode_curves import classify_materials_by_mode_curves
from ..paper.splits import grouped_split
from ..paper.uncertainty import (
    accuracy_entries,
    difference_resolved,
    format_interval,
    resolvable_difference,
)
from ..simulate import build_dataset, dataset_plan, simulate_batch
from ._common import beyond_chance, pct

__all__ = [
    "ControlsResult", "ENERGY_ABSORPTION", "PAIR_REFERENCES", "control_design", "compute",
    "render",
]  # fmt: skip

#: The effects through which the touched material absorbs the probe's vibration energy (the
#: rod's loss factor, :class:`ebantenna.simulate.effects.ObjectDamping`): the paper's
#: explanation of why the materials differ.
ENERGY_ABSORPTION = frozenset({"object_damping"})

#: The equivalent pairs: each reference rod (the scene's geometry) and the material of its
#: twin (:func:`~ebantenna.paper.controls.equivalent_rod`). Two references, so that the pair's
#: verdict does not rest on one choice of rod.
PAIR_REFERENCES = (("aluminium", "steel"), ("brass", "steel"))


def control_design(quick: bool):
    """The data set the controls rebuild: :data:`~ebantenna.paper.controls.ABLATION_DESIGN`
    (three repetitions), or for a quick run the quick design with one repetition (40
    recordings).

    Examples
    --------
    >>> control_design(True).repetitions, control_design(False).contact_step
    (1, 0.005)
    >>> control_design(False).repetitions
    3
    """
    return replace(QUICK_DESIGN, name="controls-quick", repetitions=1) if quick else ABLATION_DESIGN


@dataclass(frozen=True, eq=False)
class ControlsResult:
    """The ablation and the equivalent pair.

    Attributes
    ----------
    ablation : Ablation
    pair_accuracy : float or None
        Grouped-split accuracy between the aluminium rod and its steel equivalent; None when the
        scene has no ``object_modes`` effect (``pair_note`` says so).
    pair_note : str
        Why the pair was not simulated, or the two rods' dimensions.
    pair_mode_curve_accuracy : float or None
        The same pair told apart by the mode-curve classifier
        (:mod:`ebantenna.paper.mode_curves`); None with ``pair_accuracy``.
    recordings : int
        Recordings per rebuilt data set.
    chance : float
        Accuracy of guessing: one over the number of materials.
    test_recordings : int
        Recordings in each grouped test set.
    lift_off_share : float or None
        Share of the design's strikes in which the linear contact would have to pull harder than
        the preload (:meth:`ebantenna.simulate.ModalTerms.lift_off_ratio` above 1); None without
        ``object_modes``.
    unilateral_accuracy : float or None
        Grouped-split accuracy on the same design with the ``unilateral_contact`` effect (the
        probe lifts off and strikes again); None without ``object_modes``.
    restrikes : ndarray of int or None
        Each of those strikes' contacts after the first touch.
    mid_height_accuracy : float or None
        Grouped-split accuracy with the rods touched halfway up instead of at their free end
        (the assumption of :class:`~ebantenna.simulate.effects.ObjectModes`); None without
        ``object_modes``.
    mode_curve_accuracies : dict of str to float or None
        The mode-curve classifier on the same grouped split, with the ``"linear"`` contact and
        the ``"unilateral"`` one; None with ``unilateral_accuracy``.
    linear_accuracy : float or None
        Grouped-split accuracy with the linear contact (without ``unilateral_contact``); None
        with ``unilateral_accuracy``.
    friction_accuracy : float or None
        Grouped-split accuracy with dry friction along the rod
        (:class:`~ebantenna.simulate.effects.CoulombFriction` at its defaults, added where the
        scene leaves it out); None without ``object_modes``.
    pushes : bool
        Whether the scene's own contact only pushes (it lists ``unilateral_contact``).
    pairs : dict or None
        Per reference material of :data:`PAIR_REFERENCES`: ``"svm"`` and ``"mode_curves"``
        (:class:`~ebantenna.paper.uncertainty.SeedSpread` over the split seeds) and ``"note"``
        (the two rods); None without ``object_modes``.
    spreads : dict or None
        ``"mid_height"`` and ``"friction"``: the SVM over the split seeds.
    """

    ablation: Ablation
    pair_accuracy: float | None
    pair_note: str
    pair_mode_curve_accuracy: float | None
    recordings: int
    chance: float
    test_recordings: int
    lift_off_share: float | None = None
    unilateral_accuracy: float | None = None
    restrikes: np.ndarray | None = None
    mid_height_accuracy: float | None = None
    mode_curve_accuracies: dict | None = None
    linear_accuracy: float | None = None
    pushes: bool = False
    friction_accuracy: float | None = None
    pairs: dict | None = None
    spreads: dict | None = None

    @property
    def data_sets(self) -> int:
        """How many small data sets the controls built: one per ablation row, two per pair,
        one for the contact law the scene does not use (the ablation has the other), one for
        the moved contact height, and one for the friction the scene leaves out."""
        extra = [
            self.pair_accuracy, self.unilateral_accuracy, self.mid_height_accuracy,
            self.friction_accuracy,
        ]  # fmt: skip
        law = 0 if self.pushes else 1  # with it, the ablation's row is the linear contact
        friction = 0 if "coulomb_friction" in self.ablation.accuracies else 1  # likewise
        pair = 2 * len(self.pairs or {1: None})
        return len(self.ablation.accuracies) + sum(
            n for n, a in zip((pair, law, 1, friction), extra, strict=True) if a is not None
        )

    def to_dict(self) -> dict:
        """Under ``materials``: ``ablation`` and ``equivalent_pair_accuracy``, ...; every
        accuracy with its test count (``*_n_test``) and Wilson 95 % interval (``*_ci95``), the
        ablation and the pairs also over the split seeds (``*_seed_spread``)."""
        curves = self.mode_curve_accuracies or {}
        ab = self.ablation
        n = self.test_recordings
        pair_n = _pair_test_count(self.pairs)
        out = {
            "controls_design": {
                "recordings": self.recordings,
                "test_recordings": n,
                "split_seeds": SPLIT_SEEDS,
                "resolvable_difference": resolvable_difference(ab.accuracies["none"], n),
            },
            **accuracy_entries("ablation", dict(ab.accuracies),
                               {k: int(v.n_test[0]) for k, v in ab.spreads.items()}),
            "ablation_seed_spread": {k: v.to_dict() for k, v in ab.spreads.items()},
            "ablation_dropped_together": {k: list(v) for k, v in ab.dropped_together.items()},
            "ablation_refused": dict(ab.refused),
            "ablation_changed": dict(ab.changed),
            **accuracy_entries("equivalent_pair_accuracy", self.pair_accuracy, pair_n),
            **accuracy_entries("equivalent_pair_mode_curve_accuracy",
                               self.pair_mode_curve_accuracy, pair_n),
            "equivalent_pairs": {
                ref: {"note": p["note"], "svm": p["svm"].to_dict(),
                      "mode_curves": p["mode_curves"].to_dict()}
                for ref, p in (self.pairs or {}).items()
            },
            "contact_lift_off_share": self.lift_off_share,
            "unilateral_restrike_share": (
                None if self.restrikes is None else float(np.mean(self.restrikes > 0))
            ),
            "unilateral_median_restrikes": (
                None if self.restrikes is None else float(np.median(self.restrikes))
            ),
        }
        grouped = {
            "svm_grouped_unilateral_accuracy": self.unilateral_accuracy,
            "svm_grouped_linear_accuracy": self.linear_accuracy,
            "svm_grouped_mid_height_accuracy": self.mid_height_accuracy,
            "svm_grouped_friction_accuracy": self.friction_accuracy,
            "mode_curve_grouped_linear_accuracy": curves.get("linear"),
            "mode_curve_grouped_unilateral_accuracy": curves.get("unilateral"),
        }
        for name, a in grouped.items():
            out.update(accuracy_entries(name, a, n))
        out["svm_grouped_seed_spread"] = {
            k: v.to_dict() for k, v in (self.spreads or {}).items()
        }
        return out


def _pair_test_count(pairs) -> int | None:
    """Test recordings of the first pair's seed-0 split, or None without pairs."""
    if not pairs:
        return None
    return int(next(iter(pairs.values()))["svm"].n_test[0])


def compute(scene, seed: int, quick: bool, cache_dir, n_jobs: int) -> ControlsResult:
    """Run the ablation over every effect of ``scene`` and, if it has rod modes, the pair, the
    two contact laws, the moved contact height and the friction along the rod."""
    design = control_design(quick)
    ablation = ablation_accuracies(
        scene, design=design, seed=seed, cache_dir=cache_dir, n_jobs=n_jobs
    )
    build = dict(design=design, seed=seed, cache_dir=cache_dir, n_jobs=n_jobs)
    pairs, note = _equivalent_pairs(scene, **build)
    first = None if pairs is None else pairs[PAIR_REFERENCES[0][0]]
    accuracy = None if first is None else float(first["svm"].values[0])
    pair_curves = None if first is None else float(first["mode_curves"].values[0])
    n, n_test = _recordings(scene, design, seed)
    lift_off = unilateral = linear_accuracy = restrikes = curves = mid = friction = None
    pushes = scene.has("unilateral_contact")
    if scene.effect("object_modes") is not None:
        lift_off, restrikes, unilateral, linear_accuracy, curves = _contact_laws_compared(
            scene, ablation, **build
        )
        spreads = {
            "mid_height": _mid_height_spread(scene, **build),
            "friction": _friction_spread(scene, ablation, design, seed, cache_dir, n_jobs),
        }
        mid, friction = (float(spreads[k].values[0]) for k in ("mid_height", "friction"))
    else:
        spreads = None
    return ControlsResult(
        ablation, accuracy, note, pair_curves, n, 1 / len(design.materials), n_test, lift_off,
        unilateral, restrikes, mid, curves, linear_accuracy, pushes, friction, pairs, spreads,
    )  # fmt: skip


def _equivalent_pairs(scene, **build):
    """Each reference rod of :data:`PAIR_REFERENCES` against its twin: the SVM's and the
    mode-curve classifier's accuracies over the split seeds and the two rods' dimensions, and
    a note naming the first pair; or (None, why not) when the scene has no ``object_modes``."""
    effect = scene.effect("object_modes")
    if effect is None:
        return None, (
            "not simulated: the scene has no 'object_modes' effect, so the "
            "touched object has no dimensions to match"
        )
    pairs = {}
    for reference, other in PAIR_REFERENCES:
        rod = Rod(reference, diameter=effect.diameter, free_length=effect.free_length)
        twin = equivalent_rod(rod, other)
        pair = dict(reference=reference, other=other, **build)
        pairs[reference] = {
            "svm": equivalent_pair_spread(scene, **pair),
            "mode_curves": equivalent_pair_spread(scene, classifier="mode_curves", **pair),
            "note": (
                f"{reference} Ø{1e3 * rod.diameter:.2f} mm x {1e3 * rod.free_length:.1f} mm "
                f"against {other} Ø{1e3 * twin.diameter:.2f} mm x "
                f"{1e3 * twin.free_length:.1f} mm"
            ),
        }
    return pairs, pairs[PAIR_REFERENCES[0][0]]["note"]


def _recordings(scene, design, seed: int) -> tuple[int, int]:
    """Recordings in each rebuilt data set, and in its grouped test set."""
    n = len(design.materials) * design.repetitions * design.contacts(scene.probe.length).size
    positions = design.contacts(scene.probe.length)
    held = np.isin(positions, positions[grouped_split(positions, seed=seed)[1]])
    n_test = int(held.sum()) * len(design.materials) * design.repetitions
    return n, n_test


def _contact_laws_compared(scene, ablation, *, design, seed, cache_dir, n_jobs):
    """The contact that only pushes against the linear one: the share of strikes in which the
    linear contact would pull, the re-strikes, the SVM's accuracy under each law and the
    mode-curve classifier's (``{"linear": ..., "unilateral": ...}``)."""
    pushes = scene.has("unilateral_contact")
    pushing, linear = _contact_laws(scene)
    plan = dataset_plan(linear, design, seed)
    _, _, _, x, _ = simulate_batch(
        linear, contact=plan["contact_true"], material=plan["material"],
        sweep_speed=plan["sweep_speed"], tilt_ratio=plan["tilt_ratio"],
        seeds=plan["seed_row"], show_progress=False,
    )  # fmt: skip
    lift_off = float(np.mean(x.lift_off_ratio(scene.duration) > 1))
    build = dict(n_jobs=n_jobs, show_progress=False)
    ds = build_dataset(cache_dir, pushing, design, seed, **build)
    restrikes = np.asarray(ds.metadata["restrikes"], dtype=int)
    lin = build_dataset(cache_dir, linear, design, seed, **build)
    # The ablation has measured the scene itself ("none") and, when its contact pushes, the
    # linear variant (row "unilateral_contact", the same data set): fit only what is left.
    measured = ablation.accuracies
    unilateral = measured["none"] if pushes else grouped_svm_accuracy(ds, seed=seed)
    linear_accuracy = measured.get("unilateral_contact") if pushes else measured["none"]
    if linear_accuracy is None:  # the ablation could not switch the contact off alone
        linear_accuracy = grouped_svm_accuracy(lin, seed=seed)
    curves = {
        "linear": _mode_curve_accuracy(lin, seed, n_jobs),
        "unilateral": _mode_curve_accuracy(ds, seed, n_jobs),
    }
    return lift_off, restrikes, unilateral, linear_accuracy, curves


def _mid_height_spread(scene, *, design, seed, cache_dir, n_jobs):
    """Grouped-split SVM accuracy over the split seeds with the assumed contact height moved:
    the rods touched halfway up instead of at their free end."""
    effect = scene.effect("object_modes")
    halfway = replace(effect, contact_height=effect.free_length / 2)
    moved = scene.with_(
        name=f"{scene.name}-mid-height",
        effects=[halfway if e.name == "object_modes" else e for e in scene.effects],
    )
    ds = build_dataset(cache_dir, moved, design, seed, n_jobs=n_jobs, show_progress=False)
    return grouped_svm_spread(ds, seed=seed)


def _friction_spread(scene, ablation, design, seed, cache_dir, n_jobs):
    """Grouped-split SVM accuracy over the split seeds with ``coulomb_friction``: the scene's
    own (the ablation's ``none`` row) where it lists it, else the scene with it added."""
    if scene.has("coulomb_friction"):
        return ablation.spreads["none"]
    rubbing = scene.with_(
        name=f"{scene.name}-with-coulomb_friction", effects=(*scene.effects, "coulomb_friction")
    )
    ds = build_dataset(cache_dir, rubbing, design, seed, n_jobs=n_jobs, show_progress=False)
    return grouped_svm_spread(ds, seed=seed)


def _contact_laws(scene):
    """The scene with a contact that only pushes and with the linear one; one of them is
    ``scene`` itself, the other named as the ablation names it (so its data set is shared)."""
    law = "unilateral_contact"
    if scene.has(law):
        others = [e for e in scene.effects if e.name != law]
        return scene, scene.with_(name=f"{scene.name}-without-{law}", effects=others)
    return scene.with_(name=f"{scene.name}-unilateral", effects=(*scene.effects, law)), scene


def render(result: ControlsResult, report, figures) -> None:
    """The ablation table and the pair, with what they mean; then, where they were measured,
    the contact that only pushes, the moved contact height and the friction along the rod."""
    r = result
    _render_ablation(r, report)
    _render_equivalent_pair(r, report)
    if r.lift_off_share is not None:
        report.heading("A contact that only pushes")
        report.paragraph(_lift_off(r))
    if r.mid_height_accuracy is not None:
        _render_mid_height(r, report)
    if r.friction_accuracy is not None:
        _render_friction(r, report)


def _render_ablation(r: ControlsResult, report) -> None:
    """One effect at a time switched off: the table, the effects that had to go together, and
    which effect carries the material."""
    acc, spreads = r.ablation.accuracies, r.ablation.spreads
    base = acc["none"]
    report.heading("What the classifier learns: one effect at a time switched off")
    report.paragraph(
        f"The data set ({r.recordings} recordings, a reduced design) is simulated again with one "
        "effect of the scene switched off, and the paper's SVM is tested on whole held-out "
        f"positions (every 5th; {r.test_recordings} test recordings at split seed 0). The "
        "effect whose removal drops the accuracy towards chance is the one that carries the "
        "material; one whose removal leaves it unchanged does not. Each row is also measured "
        f"over {SPLIT_SEEDS} split seeds on the same data set, each holding out other positions "
        "(together every position once; mean ± standard deviation). Two "
        "accuracies near the baseline differ by two standard deviations of their difference at "
        f"{100 * resolvable_difference(base, r.test_recordings):.1f} points: a change is "
        "'resolved' beyond that."
    )
    report.paragraph(_baseline_relation(r))
    rows = [["none (all effects on)", format_interval(base, _n(spreads, "none", r)),
             str(spreads["none"]), "", ""]]
    for name, a in acc.items():
        if name != "none":
            resolved = difference_resolved(base, a, r.test_recordings)
            rows.append([name, format_interval(a, _n(spreads, name, r)), str(spreads[name]),
                         f"{100 * (a - base):+.1f} points", "yes" if resolved else "no"])
    report.table(["switched off", "grouped test accuracy (seed 0)",
                  f"over {SPLIT_SEEDS} split seeds", "change", "resolved"], rows)
    for name, together in r.ablation.dropped_together.items():
        report.paragraph(
            f"'{name}' cannot go alone (the scene requires it for "
            + ", ".join(f"'{n}'" for n in together[1:])
            + "): they were switched off together. "
            + _isolated(name, together, acc)
        )
    for name, change in r.ablation.changed.items():
        report.paragraph(f"'{name}' switched off with {change}.")
    for name, reason in r.ablation.refused.items():
        report.paragraph(f"'{name}' cannot be switched off by removing effects: {reason}")
    report.paragraph(_verdict(acc, r.chance, r.test_recordings))


def _n(spreads: dict, name: str, r: ControlsResult) -> int:
    """Test recordings of an ablation row at split seed 0."""
    return int(spreads[name].n_test[0]) if name in spreads else r.test_recordings


def _isolated(name: str, together, accuracies: dict) -> str:
    """Which of the effects dropped together have a row of their own (switched off alone or in
    a smaller set), so that the row's change can be apportioned.

    Examples
    --------
    >>> _isolated("a", ("a", "b"), {"b": 0.5, "a+b": 0.4})
    "Of these, 'b' has a row of its own."
    """
    own = [n for n in together[1:] if any(
        k == n or (set(k.split("+")) < set(together) and n in k.split("+")) for k in accuracies
    )]
    if not own:
        return "None of the others can be switched off alone."
    return "Of these, " + ", ".join(f"'{n}'" for n in own) + " " + (
        "has a row of its own." if len(own) == 1 else "have rows of their own (alone or in a "
        "smaller set), so what the row adds is the difference from those rows."
    )


def _baseline_relation(r: ControlsResult) -> str:
    """Why the ablation's baseline is not the main study's grouped accuracy."""
    return (
        f"The baseline here ({pct(r.ablation.accuracies['none'])}) is measured on the reduced "
        f"design, {r.recordings} recordings, not on the main data set: every position carries "
        "fewer repetitions, so the SVM learns from fewer recordings of each material near a "
        "held-out position, and its accuracy is lower than the main study's grouped split. "
        "The section 'How much the numbers carry' measures it directly: the main data set's "
        "grouped accuracy with its first 1, 3 and 5 repetitions only. The ablation compares "
        "rows with one another on one design, which this does not change."
    )


def _render_equivalent_pair(r: ControlsResult, report) -> None:
    """Two rods of equal stiffness and frequencies in different materials told apart, or not."""
    report.heading("The equivalent pair: impedance, not chemistry")
    if r.pairs is None:
        report.paragraph(f"The equivalent pair was {r.pair_note}.")
        return
    report.paragraph(
        "Two rods of different materials with the same cantilever stiffness 3EI/l^3 and the "
        "same bending frequencies, hence the same modal masses, so the probe meets the same "
        "mechanical impedance but for the loss factor and the contact. Near 50 % (chance) the "
        "probe feels impedance, not chemistry; well above it, what is left (loss factor, "
        "Hertz contact) still tells them apart. Two twins, built from two reference rods, so "
        f"that the verdict does not rest on one choice; each over {SPLIT_SEEDS} split seeds."
    )
    rows = []
    for p in r.pairs.values():
        for label, key in (("paper's SVM", "svm"), ("mode curves", "mode_curves")):
            spread = p[key]
            rows.append([p["note"], label,
                         format_interval(float(spread.values[0]), int(spread.n_test[0])),
                         str(spread)])
    report.table(["pair", "classifier", "grouped test accuracy (seed 0)",
                  f"over {SPLIT_SEEDS} split seeds"], rows)


def _render_mid_height(r: ControlsResult, report) -> None:
    """The SVM with the rods touched halfway up instead of at their free end."""
    acc = r.ablation.accuracies
    report.heading("Where the rod is touched: an assumption moved")
    report.paragraph(
        "The paper does not say where on the rods the probe touched; the scene assumes their "
        "free end, the softest point, where the rod's modes move the contact most. Touched "
        "halfway up instead, the same SVM on whole held-out positions reaches "
        f"{format_interval(r.mid_height_accuracy, r.test_recordings)}; "
        f"{_over_seeds(r, 'mid_height')} (free end: "
        f"{format_interval(acc['none'], r.test_recordings)}, chance {pct(r.chance)}), "
        + (
            _resolved(acc["none"], r.mid_height_accuracy, r.test_recordings)
            or "within two binomial standard deviations"
        )
        + ". The accuracies of this report hold for the assumed rod and contact, not for "
        "every rod."
    )


def _render_friction(r: ControlsResult, report) -> None:
    """The SVM with dry friction along the rod against without."""
    acc = r.ablation.accuracies
    report.heading("Friction along the rod")
    listed = "coulomb_friction" in acc
    without = acc["coulomb_friction"] if listed else acc["none"]
    report.paragraph(
        "Across the sweep plane the probe slides along the rod. With dry friction there "
        "(the 'coulomb_friction' effect, mu = 0.45 unless the scene says otherwise, under "
        "the preload) the contact point sticks to the rod (within 20 ms wherever it lies "
        "beyond a fifth of the probe from the hinge) and the Z axis then rings as the probe "
        "pinned at the contact, where without it Z rings at "
        "the free probe's frequencies whatever was touched. The SVM on whole held-out "
        f"positions reaches {format_interval(r.friction_accuracy, r.test_recordings)} with "
        f"friction ({_over_seeds(r, 'friction')}) against "
        f"{format_interval(without, r.test_recordings)} without, "
        + (_resolved(without, r.friction_accuracy, r.test_recordings)
           or "within two binomial standard deviations")
        + ". The rod is rigid along its axis, so friction adds the contact's position to "
        "Z, not the material."
    )


def _over_seeds(r: ControlsResult, name: str) -> str:
    """``"x ± y % over 5 split seeds"`` for a spread of ``r.spreads``, or ``""``."""
    spread = (r.spreads or {}).get(name)
    return "" if spread is None else f"{spread} over {len(spread.seeds)} split seeds"


def _resolved(base: float, other: float, n: int) -> str | None:
    """How ``other`` differs from ``base`` beyond two standard deviations of their difference
    (binomial, ``n`` test recordings each), or None within them.

    Examples
    --------
    >>> _resolved(0.6, 0.45, 240), _resolved(0.6, 0.55, 240)
    ('lower by more than two binomial standard deviations', None)
    """
    if not difference_resolved(base, other, n):
        return None
    direction = "lower" if other < base else "higher"
    return f"{direction} by more than two binomial standard deviations"


def _lift_off(r: ControlsResult) -> str:
    """The paragraph on the contact that only pushes.

    Examples
    --------
    >>> from ebantenna.paper.controls import Ablation
    >>> r = ControlsResult(Ablation({"none": 0.5}, {}, {}), None, "", None, 395, 0.2, 80, 0.6,
    ...                    0.5, np.array([0, 3, 5, 9]), linear_accuracy=0.6, pushes=True)
    >>> _lift_off(r).endswith("this design does not resolve a change by the contact law.")
    True
    """
    law = (
        "the 'unilateral_contact' effect: the pan-tilt's approach, the overtravel that builds "
        "the preload, lift-off and re-strike, integrated between contact events"
    )
    pull = (
        f"in {pct(r.lift_off_share)} of these strikes its dynamic force would have to exceed the "
        "preload in pulling"
    )
    if r.pushes:
        text = (
            f"The data set's contact only pushes ({law}). A linear contact, which pushes and "
            f"pulls, would hold on: {pull}, a force that no real contact gives."
        )
    else:
        text = (
            f"The data set's contact is linear: it pushes and pulls, and {pull}: on the rig the "
            "probe would lift off the rod, ring free and strike again (chatter)."
        )
    if r.unilateral_accuracy is None:
        return text + " How much that changes the accuracies above is not measured here."
    share = float(np.mean(r.restrikes > 0))
    linear, pushing = r.linear_accuracy, r.unilateral_accuracy
    difference = _resolved(linear, pushing, r.test_recordings)
    verdict = (
        "within two binomial standard deviations of each other: this design does not resolve "
        "a change by the contact law"
        if difference is None
        else difference + ": the contact law matters here"
    )
    other = (
        ""
        if r.pushes
        else f" The same design simulated again with a contact that only pushes ({law}):"
    )
    measured = (
        f"{other} {pct(share)} of the strikes strike again, a median of "
        f"{np.median(r.restrikes):g} times. The SVM on whole held-out positions reaches "
        f"{pct(pushing)} with the contact that only pushes against {pct(linear)} with the "
        f"linear one ({r.test_recordings} test recordings), {verdict}."
    )
    return text + measured + _curves_under_both_laws(r)


def _curves_under_both_laws(r: ControlsResult) -> str:
    """The mode-curve classifier with either contact law, if measured."""
    if r.mode_curve_accuracies is None:
        return ""
    linear, pushing = r.mode_curve_accuracies["linear"], r.mode_curve_accuracies["unilateral"]
    difference = _resolved(linear, pushing, r.test_recordings)
    survives = beyond_chance(pushing, r.chance, r.test_recordings)
    return (
        f" The mode-curve classifier reaches {pct(pushing)} with it against {pct(linear)} with "
        "the linear contact, "
        + ("within two binomial standard deviations" if difference is None else difference)
        + (
            ": what the rod does to the probe's modes survives the lift-offs."
            if survives
            else ": with lift-offs it falls to chance."
        )
    )


def _mode_curve_accuracy(ds, seed: int, n_jobs: int) -> float:
    """The mode-curve classifier's accuracy on whole held-out positions of data set ``ds``."""
    feats = signal_features(ds.ax, ds.az, ds.fs, n_jobs=n_jobs, show_progress=False)
    split = grouped_split(ds.contact, seed=seed)
    result = classify_materials_by_mode_curves(
        feats.peaks, feats.dominant, ds.material, ds.contact, split
    )
    return result.accuracies["test"]


def _verdict(accuracies: dict, chance: float, n: int) -> str:
    """Which effect carries the material, in plain words; ``n`` test recordings per accuracy.

    A difference counts only beyond two binomial standard deviations of guessing
    (:func:`~._common.beyond_chance`).

    Examples
    --------
    >>> _verdict({"none": 0.9, "gravity": 0.9, "object_modes": 0.25}, 0.2, 80)[:52]
    "Switching off 'object_modes' costs the most (90.0 % "
    >>> "contradicts" in _verdict({"none": 0.6, "object_modes": 0.2, "object_damping": 0.62},
    ...                           0.2, 80)
    True
    >>> "agrees" in _verdict({"none": 0.6, "object_modes": 0.2, "object_damping": 0.3}, 0.2, 80)
    True
    >>> _verdict({"none": 0.25, "gravity": 0.2}, 0.2, 40)[:40]
    'With every effect on, the classifier is '
    """
    base = accuracies["none"]
    drops = {k: base - a for k, a in accuracies.items() if k != "none"}
    carrier = max(drops, key=drops.get) if drops else None
    if (
        carrier is None
        or not beyond_chance(base, chance, n)
        or not beyond_chance(chance + drops[carrier], chance, n)
    ):
        return (
            f"With every effect on, the classifier is at {pct(base)} (chance {pct(chance)}, "
            f"{n} test recordings) and no single effect's removal lowers it by more than "
            "guessing would: in this data set no one effect is shown to carry the material."
        )
    alone = {k: d for k, d in drops.items() if k in ENERGY_ABSORPTION}  # switched off alone
    absorbs = [k for k, d in alone.items() if beyond_chance(chance + d, chance, n)]
    if absorbs:
        paper = (
            f"Switched off alone, '{absorbs[0]}' lowers it too: this agrees with the paper's "
            "explanation, that the materials differ by how much vibration energy they absorb."
        )
    else:
        measured = "; ".join(
            f"switched off alone, '{k}' changes it by {100 * -d:+.1f} points"
            for k, d in alone.items()
        )
        paper = (
            "This contradicts the paper's explanation, that the materials differ by how much "
            "vibration energy they absorb: "
            + (measured + ", no more than guessing would. " if measured else "")
            + "The probe tells the materials by the touched object's own modes, not by its damping."
        )
    return (
        f"Switching off '{carrier}' costs the most ({pct(base)} to {pct(accuracies[carrier])}, "
        f"chance {pct(chance)}, {n} test recordings): in this scene it carries the material "
        "information. " + paper
    )
