"""Section 6c: what the material classifier learns: the ablation of every effect and the
equivalent-pair control."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .._validate import check_bool
from ..fem.coupling import Rod, craig_bampton, rod_substructure
from ..fem.modal import solve_modes
from ..paper.controls import (
    ABLATION_DESIGN,
    SPLIT_SEEDS,
    Ablation,
    ablation_accuracies,
    equivalent_pair_spread,
    equivalent_rod,
    grouped_svm_spread,
    twin_seeds,
)
from ..paper.data import QUICK_DESIGN
from ..paper.data import design as main_design
from ..paper.feature_table import mode_peaks
from ..paper.splits import distinct_split_seeds, grouped_split
from ..paper.uncertainty import (
    UNITS,
    clustered_entries,
    detectable_cell,
    detectable_text,
    format_clustered,
    percent,
    points,
    seed_spread,
    span,
)
from ..probe import material
from ..simulate import build_dataset
from ._common import check_render, check_step, classifier_call, fits_in_parallel, listed
from .seed_spread import TRAINING_REPETITIONS

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
    check_bool("quick", quick)
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
    paired : dict of str to ebantenna.paper.uncertainty.PairedDifference
        Every comparison, on the same folds and rows, paired within the position: ``"ablation:"``
        + each row of the ablation against all effects on; ``"mid_height"`` against the free
        end; ``"friction"`` with it against without; ``"contact_law"`` and
        ``"contact_law_mode_curves"``, the contact that only pushes against the linear one.
    law_spreads : dict or None
        ``("svm" | "mode_curves", "linear" | "unilateral")``: over the folds.
    loss_factors : (float, float, float) or None
        The design materials' smallest and largest loss factor (:func:`ebantenna.probe.material`)
        and the probe's: what the damping verdict assumes.
    contact_compliance : dict or None
        Per design material, the rod's compliance at the two contact heights the mid-height
        control compares (``_contact_compliance``); None without ``object_modes``.
    repetitions : (int, int) or None
        Repetitions of each material at each position in the controls' design and in the main
        data set's (:func:`ebantenna.paper.data.design`).
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
    paired: dict | None = None
    law_spreads: dict | None = None
    loss_factors: tuple | None = None
    contact_compliance: dict | None = None
    repetitions: tuple | None = None

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
        """Under ``materials``: ``ablation`` (over all five folds, each accuracy with its
        interval on the position, :func:`~ebantenna.paper.uncertainty.clustered_entries`),
        ``controls_paired`` (every comparison paired on the same folds and rows, with its
        interval, verdict and minimal detectable difference), the pairs, the contact laws and
        the moved assumptions likewise."""
        ab = self.ablation
        unit = UNITS["grouped"]
        folds = {k: v.folds() for k, v in ab.spreads.items()}
        first = (self.pairs or {}).get(PAIR_REFERENCES[0][0])
        out = {
            "controls_design": {
                "recordings": self.recordings,
                "test_recordings_per_fold": self.test_recordings,
                "folds": SPLIT_SEEDS,
                "unit": unit,
                "n_units": folds["none"].n_units,
            },
            **clustered_entries("ablation", folds),
            "ablation_seed_spread": {k: v.to_dict() for k, v in ab.spreads.items()},
            "ablation_dropped_together": {k: list(v) for k, v in ab.dropped_together.items()},
            "ablation_refused": dict(ab.refused),
            "ablation_changed": dict(ab.changed),
            **clustered_entries("equivalent_pair_accuracy",
                                None if first is None else first["svm"].folds()),
            **clustered_entries("equivalent_pair_mode_curve_accuracy",
                                None if first is None else first["mode_curves"].folds()),
            "equivalent_pairs": {
                ref: {"note": p["note"], "data_set_seeds": list(p["seeds"]),
                      **clustered_entries("svm", p["svm"].folds()),
                      **clustered_entries("mode_curves", p["mode_curves"].folds()),
                      "svm_seed_spread": p["svm"].to_dict(),
                      "mode_curves_seed_spread": p["mode_curves"].to_dict()}
                for ref, p in (self.pairs or {}).items()
            },
            "contact_lift_off_share": self.lift_off_share,
            "unilateral_restrike_share": (
                None if self.restrikes is None else float(np.mean(self.restrikes > 0))
            ),
            "unilateral_median_restrikes": (
                None if self.restrikes is None else float(np.median(self.restrikes))
            ),
            "controls_paired": {k: v.to_dict() for k, v in (self.paired or {}).items()},
        }
        laws = self.law_spreads or {}
        spreads = self.spreads or {}
        grouped = {
            "svm_grouped_unilateral_accuracy": laws.get(("svm", "unilateral")),
            "svm_grouped_linear_accuracy": laws.get(("svm", "linear")),
            "svm_grouped_mid_height_accuracy": spreads.get("mid_height"),
            "svm_grouped_friction_accuracy": spreads.get("friction"),
            "mode_curve_grouped_linear_accuracy": laws.get(("mode_curves", "linear")),
            "mode_curve_grouped_unilateral_accuracy": laws.get(("mode_curves", "unilateral")),
        }
        for name, spread in grouped.items():
            out.update(clustered_entries(name, None if spread is None else spread.folds()))
        out["svm_grouped_seed_spread"] = {k: v.to_dict() for k, v in spreads.items()}
        out["mid_height_contact_compliance"] = self.contact_compliance
        return out


def compute(scene, seed: int, quick: bool, cache_dir, n_jobs: int) -> ControlsResult:
    """Run the ablation over every effect of ``scene`` and, if it has rod modes, the pair, the
    two contact laws, the moved contact height and the friction along the rod."""
    check_step(scene=scene, seed=seed, quick=quick, cache_dir=cache_dir, n_jobs=n_jobs)
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
    base = ablation.spreads["none"]
    paired = {f"ablation:{k}": base.paired_with(v) for k, v in ablation.spreads.items()
              if k != "none"}
    laws = None
    if scene.effect("object_modes") is not None:
        lift_off, restrikes, laws = _contact_laws_compared(scene, ablation, **build)
        unilateral, linear_accuracy = (float(laws["svm", k].values[0])
                                       for k in ("unilateral", "linear"))
        curves = {k: float(laws["mode_curves", k].values[0]) for k in ("linear", "unilateral")}
        spreads = {
            "mid_height": _mid_height_spread(scene, **build),
            "friction": _friction_spread(scene, ablation, design, seed, cache_dir, n_jobs),
        }
        mid, friction = (float(spreads[k].values[0]) for k in ("mid_height", "friction"))
        compliance = {m: _contact_compliance(scene.effect("object_modes"), m)
                      for m in design.materials}
        without = ablation.spreads.get("coulomb_friction", base)
        paired.update(
            mid_height=base.paired_with(spreads["mid_height"]),
            friction=without.paired_with(spreads["friction"]),
            contact_law=laws["svm", "linear"].paired_with(laws["svm", "unilateral"]),
            contact_law_mode_curves=laws["mode_curves", "linear"].paired_with(
                laws["mode_curves", "unilateral"]),
        )  # fmt: skip
    else:
        spreads = compliance = None
    return ControlsResult(
        ablation, accuracy, note, pair_curves, n, 1 / len(design.materials), n_test, lift_off,
        unilateral, restrikes, mid, curves, linear_accuracy, pushes, friction, pairs, spreads,
        paired, laws, _assumed_loss(scene, design), compliance,
        (design.repetitions, main_design(quick).repetitions),
    )  # fmt: skip


def _contact_compliance(effect, material_name: str) -> dict:
    """How far the rod of ``effect`` (an :class:`~ebantenna.simulate.effects.ObjectModes`) in
    ``material_name`` gives under the contact at its free end (``"free_end"``) and halfway up
    (``"mid_height"``), read from the rod's own beam model (its Euler-Bernoulli elements,
    ``effect.rod_elements`` of them, clamped at the foot).

    Each height gives ``height_m``; ``static_m_per_n``, the deflection there per newton there
    (the inverse of the condensed stiffness at the contact,
    :func:`~ebantenna.fem.coupling.craig_bampton` with no mode kept; ``h^3 / (3 EI)`` for the
    uniform rod); and ``first_mode_m_per_n``, the first bending mode's share of it, its modal
    compliance ``phi_1(h)^2 / omega_1^2`` (``phi_1`` mass-normalised).

    Examples
    --------
    >>> from ebantenna.simulate.effects import ObjectModes
    >>> c = _contact_compliance(ObjectModes(), "steel")
    >>> round(c["free_end"]["static_m_per_n"] / c["mid_height"]["static_m_per_n"], 6)  # 2^3
    8.0
    """
    out = {}
    for where, height in (("free_end", effect.free_length), ("mid_height", effect.free_length / 2)):
        rod = Rod(material_name, effect.diameter, effect.free_length, height)
        sub = rod_substructure(rod, n_elements=effect.rod_elements)
        static = 1.0 / float(craig_bampton(sub, 0).stiffness[-1, -1])
        lam, phi = solve_modes(sub.stiffness, sub.mass, 1, shift=sub.scale)
        out[where] = {"height_m": float(height), "static_m_per_n": static,
                      "first_mode_m_per_n": float(phi[sub.interface, 0] ** 2 / lam[0])}
    return out


def _assumed_loss(scene, design) -> tuple[float, float, float]:
    """The touched materials' smallest and largest loss factor, and the probe's."""
    rods = [material(m).loss_factor for m in design.materials]
    return min(rods), max(rods), float(scene.probe.loss_factor)


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
            "seeds": twin_seeds(build["seed"]),
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
    linear contact would pull, the re-strikes, and the SVM and the mode-curve classifier over
    the folds under each law (``{(classifier, law): SeedSpread}``)."""
    pushes = scene.has("unilateral_contact")
    pushing, linear = _contact_laws(scene)
    build = dict(n_jobs=n_jobs, show_progress=False)
    ds = build_dataset(cache_dir, pushing, design, seed, **build)
    restrikes = np.asarray(ds.metadata["restrikes"], dtype=int)
    lin = build_dataset(cache_dir, linear, design, seed, **build)
    # each linear strike's largest pull over its preload, kept by the build (not simulated again)
    lift_off = float(np.mean(np.asarray(lin.metadata["lift_off_ratio"]) > 1))
    # The ablation has measured the scene itself ("none") and, when its contact pushes, the
    # linear variant (row "unilateral_contact", the same data set): fit only what is left.
    measured = ablation.spreads
    unilateral = measured["none"] if pushes else grouped_svm_spread(ds, seed=seed, n_jobs=n_jobs)
    linear_spread = measured.get("unilateral_contact") if pushes else measured["none"]
    if linear_spread is None:  # the ablation could not switch the contact off alone
        linear_spread = grouped_svm_spread(lin, seed=seed, n_jobs=n_jobs)
    laws = {
        ("svm", "linear"): linear_spread,
        ("svm", "unilateral"): unilateral,
        ("mode_curves", "linear"): mode_curve_spread(lin, seed, n_jobs),
        ("mode_curves", "unilateral"): mode_curve_spread(ds, seed, n_jobs),
    }
    return lift_off, restrikes, laws


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
    return grouped_svm_spread(ds, seed=seed, n_jobs=n_jobs)


def _friction_spread(scene, ablation, design, seed, cache_dir, n_jobs):
    """Grouped-split SVM accuracy over the split seeds with ``coulomb_friction``: the scene's
    own (the ablation's ``none`` row) where it lists it, else the scene with it added."""
    if scene.has("coulomb_friction"):
        return ablation.spreads["none"]
    rubbing = scene.with_(
        name=f"{scene.name}-with-coulomb_friction", effects=(*scene.effects, "coulomb_friction")
    )
    ds = build_dataset(cache_dir, rubbing, design, seed, n_jobs=n_jobs, show_progress=False)
    return grouped_svm_spread(ds, seed=seed, n_jobs=n_jobs)


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
    check_render(result, ControlsResult, report, figures)
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
    base = spreads["none"].folds()
    report.heading("What the classifier learns: one effect at a time switched off")
    report.paragraph(
        f"The data set ({r.recordings} recordings, a reduced design) is simulated again with one "
        "effect of the scene switched off, and the paper's SVM is tested on whole held-out "
        f"positions over all {SPLIT_SEEDS} folds of the grouped split, so that every recording "
        f"is tested once ({base.n_units} positions). Every rebuilt data set holds the same "
        "rows (same positions, same seeds), so each row is compared with the baseline "
        "recording by recording on the same folds: the difference's 95 % interval is on the "
        "position, and a change is 'resolved' when that interval leaves out zero. The last "
        "column is the smallest change this design detects four times in five (80 % power), "
        "found by resampling the design's own paired differences, at the two ends of how a "
        "change can come: spread over recordings that turn independently (the least clustered, "
        "the smallest) and as whole positions turning at once (the most clustered); a real "
        "change lies between."
    )
    report.paragraph(_baseline_relation(r))
    rows = [["none (all effects on)", format_clustered(base), "", "", ""]]
    for name in acc:
        if name != "none":
            pair = r.paired[f"ablation:{name}"]
            rows.append([name, format_clustered(spreads[name].folds()), _difference(pair),
                         "unchanged" if pair.identical else "yes" if pair.resolved else "no",
                         _detectable(pair)])
    report.table(["switched off", "grouped test accuracy, all folds",
                  "paired change (95 % CI)", "resolved",
                  "detectable at 80 % power, points: spread / whole positions"], rows)
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
    report.paragraph(_verdict(r))


def _difference(pair) -> str:
    """``'-10.4 points (-14.6 to -6.2)'``."""
    lo, hi = (points(v).split()[0] for v in pair.ci95)
    return f"{points(pair.difference)} ({lo} to {hi})"


def _detectable(pair) -> str:
    """The minimal detectable differences, spread over recordings and by whole positions,
    unsigned, in points (the table's header says so)."""
    return detectable_cell(pair.detectable, pair.detectable_clustered)


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
        f"The baseline here ({percent(r.ablation.spreads['none'].folds().estimate)}) is "
        f"measured on the reduced design, {r.recordings} recordings, not on the main data set"
        + _repetitions_text(r.repetitions) + " Whether that accounts for the difference is "
        "measured in the section 'How much the numbers carry': the main data set's grouped "
        f"accuracy {_fewer_repetitions(r.repetitions)}. The "
        "ablation compares rows with one another on one design, which this does not change."
    )


def _fewer_repetitions(repetitions) -> str:
    """Which fewer repetitions of the main data set the section 'How much the numbers carry'
    measures (those of :data:`~.seed_spread.TRAINING_REPETITIONS` below the data set's own).

    Examples
    --------
    >>> _fewer_repetitions((3, 25)), _fewer_repetitions((1, 3))
    ('with only its first 1, 3 and 5 repetitions', 'with only its first repetition')
    """
    fewer = [n for n in TRAINING_REPETITIONS if repetitions is None or n < repetitions[1]]
    if not fewer:
        return "with every repetition (the data set holds no more than one)"
    if fewer == [1]:
        return "with only its first repetition"
    return f"with only its first {listed(str(n) for n in fewer)} repetitions"


def _repetitions_text(repetitions) -> str:
    """The controls' repetitions per position against the main data set's, as a clause.

    Examples
    --------
    >>> _repetitions_text((3, 25))
    ': every position carries 3 repetitions of each material, against 25 there.'
    >>> _repetitions_text((25, 25))
    ': every position carries as many repetitions of each material (25).'
    """
    if repetitions is None:
        return "."
    few, main = repetitions
    if few == main:
        return f": every position carries as many repetitions of each material ({few})."
    return (f": every position carries {few} repetition{'s' if few != 1 else ''} of each "
            f"material, against {main} there.")


def _render_equivalent_pair(r: ControlsResult, report) -> None:
    """Two rods of equal stiffness and frequencies in different materials told apart, or not."""
    report.heading("The equivalent pair: impedance or chemistry?")
    if r.pairs is None:
        report.paragraph(f"The equivalent pair was {r.pair_note}.")
        return
    report.paragraph(
        "Two rods of different materials with the same cantilever stiffness 3EI/l^3 and the "
        "same bending frequencies, hence the same modal masses, so the probe meets the same "
        "mechanical impedance but for the loss factor and the contact. Each twin is simulated "
        "with its own scatter (its own data-set seed): were the scatter shared, each pair of "
        "twins would be one recording but for the rod, a classifier blind to the rod would "
        "label both alike, and the accuracy would be 50 % by construction whatever the probe "
        "feels. Two twins, built from two reference rods; each over all "
        f"{SPLIT_SEEDS} folds of the grouped split, the interval on the position."
    )
    rows = []
    for p in r.pairs.values():
        for label, key in (("paper's SVM", "svm"), ("mode curves", "mode_curves")):
            f = p[key].folds()
            rows.append([p["note"], label, format_clustered(f), _pair_verdict(f)])
    report.table(["pair", "classifier", "grouped test accuracy, all folds", "what it shows"],
                 rows)
    report.paragraph(
        "What the control can show: whether the simulated probe tells two rods of one "
        "impedance apart by what is left (the loss factor, the contact). What it cannot: that "
        "the rig would, since the rods' loss factors and the contact are the scene's "
        "assumptions, not measurements."
    )


def _pair_verdict(f) -> str:
    """What a twin pair's accuracy shows, from its interval against chance (50 %).

    Examples
    --------
    >>> from ebantenna.paper.uncertainty import ClusteredAccuracy
    >>> _pair_verdict(ClusteredAccuracy([3, 3, 2, 3, 3], [3] * 5, "position"))[:11]
    'told apart:'
    >>> _pair_verdict(ClusteredAccuracy([2, 1, 2, 1, 1, 2], [3] * 6, "position"))[:16]
    'not told apart: '
    """
    lo, hi = f.ci95
    if lo > 0.5:
        return f"told apart: {span(f.ci95)} % lies above chance (50 %)"
    if hi < 0.5:
        return f"below chance: {span(f.ci95)} % lies under 50 %"
    return (f"not told apart: {span(f.ci95)} % holds 50 %, and reaches at most "
            f"{points(max(0.5 - lo, hi - 0.5)).lstrip('+')} from it")


def _render_mid_height(r: ControlsResult, report) -> None:
    """The SVM with the rods touched halfway up instead of at their free end."""
    pair = r.paired["mid_height"]
    report.heading("Where the rod is touched: an assumption moved")
    report.paragraph(
        "The paper does not say where on the rods the probe touched; the scene assumes their "
        "free end. " + _height_text(r.contact_compliance) + " Touched "
        "halfway up instead, the same SVM on whole held-out positions (all folds) reaches "
        f"{format_clustered(r.spreads['mid_height'].folds())} against "
        f"{format_clustered(r.ablation.spreads['none'].folds())} at the free end (chance "
        f"{percent(r.chance)}). Paired on the same rows and folds: {pair}, "
        + _change_words(pair)
        + ". The accuracies of this report hold for the assumed rod and contact, not for "
        "every rod."
    )


def _height_text(compliance: dict | None) -> str:
    """What the assumed contact height is for the rod, read from its model's compliance at the
    two heights (``_contact_compliance``, per material): the static one and the first
    mode's share.

    Examples
    --------
    >>> end = {"height_m": 0.25, "static_m_per_n": 8e-5, "first_mode_m_per_n": 6e-5}
    >>> mid = {"height_m": 0.125, "static_m_per_n": 1e-5, "first_mode_m_per_n": 7e-6}
    >>> _height_text({"steel": {"free_end": end, "mid_height": mid}}).split(":")[0]
    'In the rod model the free end is the softer of the two contact points'
    >>> _height_text({"steel": {"free_end": mid, "mid_height": end}}).split(":")[0]
    'In the rod model halfway up is the softer of the two contact points'
    """
    if not compliance:
        return ""
    static = [c["free_end"]["static_m_per_n"] / c["mid_height"]["static_m_per_n"]
              for c in compliance.values()]
    modal = [c["free_end"]["first_mode_m_per_n"] / c["mid_height"]["first_mode_m_per_n"]
             for c in compliance.values()]

    def ratio(values):
        lo, hi = min(values), max(values)
        return f"{lo:.3g}" if f"{lo:.3g}" == f"{hi:.3g}" else f"{lo:.3g} to {hi:.3g}"

    def where(values):
        """Which contact point the ratios (free end over halfway up) favour, for every
        material; None where they do not agree."""
        return "the free end" if min(values) > 1 else "halfway up" if max(values) < 1 else None

    softer, moved = where(static), where(modal)
    if softer is None:
        said = ("In the rod model neither contact point is the softer for every material: the "
                "rod's static compliance at the free end is")
    else:
        said = (f"In the rod model {softer} is the softer of the two contact points: the rod's "
                "static compliance at the free end is")
    said += (f" {ratio(static)} times that halfway up, and its first bending mode's modal "
             f"compliance {ratio(modal)} times, so ")
    said += (f"its first mode moves the contact more at {moved}" if moved else
             "its first mode does not move the contact more at one point for every material")
    return said + " (every material of the design; the clamped rod is the scene's assumption)."


def _change_words(pair, *, subject: str = "the change") -> str:
    """``'lower, resolved'`` and the like, from a paired difference's interval.

    Examples
    --------
    >>> from ebantenna.paper.uncertainty import PairedDifference
    >>> _change_words(PairedDifference([3, 3, 2, 3], [2, 1, 1, 2], [3] * 4, "position"))
    'lower: the interval of the paired difference leaves out zero'
    >>> _change_words(PairedDifference([2, 1, 1, 2], [3, 3, 2, 3], [3] * 4, "position"))
    'higher: the interval of the paired difference leaves out zero'
    >>> _change_words(PairedDifference([2, 1, 2, 1], [1, 2, 1, 2], [3] * 4, "position"))[:26]
    'not resolved: the interval'
    """
    if pair.identical:
        return "unchanged: every position counts as many right with the change as without"
    if pair.resolved:
        return f"{pair.direction}: the interval of the paired difference leaves out zero"
    return (f"not resolved: the interval of the paired difference holds zero, and the "
            f"design detects at 80 % power "
            f"{detectable_text(pair.detectable, pair.detectable_clustered, pair.unit)}, so "
            f"{subject} is either smaller than that or missed")


def _render_friction(r: ControlsResult, report) -> None:
    """The SVM with dry friction along the rod against without."""
    pair = r.paired["friction"]
    report.heading("Friction along the rod")
    report.paragraph(
        "Across the sweep plane the probe slides along the rod. In the simulator, with dry "
        "friction there (the 'coulomb_friction' effect, under the preload), the contact point "
        "can stick to the rod, and the Z axis then rings as the probe pinned at the contact, "
        "where without it Z rings at the free probe's frequencies whatever was touched; the "
        "rod is taken as rigid along its axis (an assumption). What that does to the material "
        "accuracy is measured: the SVM on whole held-out positions (all folds) reaches "
        f"{format_clustered(r.spreads['friction'].folds())} with friction; paired against "
        f"without it on the same rows: {pair}, " + _change_words(pair) + "."
    )


def _lift_off(r: ControlsResult) -> str:
    """The paragraph on the contact that only pushes, its verdict from the paired difference
    of the two laws on the same rows and folds."""
    law = (
        "the 'unilateral_contact' effect: the pan-tilt's approach, the overtravel that builds "
        "the preload, lift-off and re-strike, integrated between contact events"
    )
    pull = (
        f"in {percent(r.lift_off_share)} of these strikes its dynamic force would have to "
        "exceed the preload in pulling"
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
    if r.law_spreads is None:
        return text + " How much that changes the accuracies above is not measured here."
    share = float(np.mean(r.restrikes > 0))
    pair = r.paired["contact_law"]
    verdict = (f"{pair}: " + _change_words(pair, subject="the effect of the contact law")
               + (": the contact law matters here" if pair.resolved else ""))
    other = (
        ""
        if r.pushes
        else f" The same design simulated again with a contact that only pushes ({law}):"
    )
    measured = (
        f"{other} {percent(share)} of the strikes strike again, a median of "
        f"{np.median(r.restrikes):g} times. The SVM on whole held-out positions (all folds) "
        f"reaches {format_clustered(r.law_spreads['svm', 'unilateral'].folds())} with the "
        "contact that only pushes against "
        f"{format_clustered(r.law_spreads['svm', 'linear'].folds())} with the linear one; "
        f"paired, {verdict}."
    )
    return text + measured + _curves_under_both_laws(r)


def _curves_under_both_laws(r: ControlsResult) -> str:
    """The mode-curve classifier with either contact law, if measured."""
    if r.law_spreads is None:
        return ""
    pushing = r.law_spreads["mode_curves", "unilateral"].folds()
    pair = r.paired["contact_law_mode_curves"]
    return (
        f" The mode-curve classifier reaches {format_clustered(pushing)} with it; paired "
        f"against the linear contact, {pair}, " + _change_words(pair) + ": "
        + _survives(pair, pushing.ci95[0] > r.chance, percent(r.chance))
    )


def _survives(pair, above_chance: bool, chance: str) -> str:
    """What the lift-offs do to the mode curves, from the paired difference and the interval
    against chance.

    Examples
    --------
    >>> from ebantenna.paper.uncertainty import PairedDifference
    >>> drop = PairedDifference([3, 3, 2, 3], [2, 1, 1, 2], [3] * 4, "position")
    >>> _survives(drop, True, "20.0 %")[:44]
    'the lift-offs cost the mode curves accuracy,'
    >>> flat = PairedDifference([2, 1, 2, 1], [1, 2, 1, 2], [3] * 4, "position")
    >>> _survives(flat, True, "20.0 %")[:40]
    "what the rod does to the probe's modes i"
    """
    if pair.resolved and pair.direction == "lower":
        return ("the lift-offs cost the mode curves accuracy, "
                + ("though what is left stays above chance." if above_chance else
                   f"and with them the interval reaches chance ({chance})."))
    if above_chance:
        return ("what the rod does to the probe's modes is still read above chance with the "
                "lift-offs, and no loss is resolved.")
    return f"with lift-offs its interval reaches chance ({chance})."


def mode_curve_spread(ds, seed: int, n_jobs: int):
    """The mode-curve classifier over the folds of the grouped split of data set ``ds``."""
    dominant, peaks = mode_peaks(ds.ax, ds.fs, n_jobs=n_jobs, show_progress=False)
    seeds = distinct_split_seeds("grouped", ds.material, ds.contact, seed=seed,
                                 count=SPLIT_SEEDS)
    calls = [classifier_call("mode_curves", None, ds.material, ds.contact, peaks, dominant,
                             grouped_split(ds.contact, seed=s)) for s in seeds]
    fitted = dict(zip(seeds, fits_in_parallel(calls, n_jobs), strict=True))

    def measure(s):
        result = fitted[s]
        return (result.accuracies["test"], result.counts["test"], result.rows(),
                result.correct())

    spread = seed_spread(measure, seeds)
    spread.positions = np.asarray(ds.contact)
    return spread


def _verdict(r: ControlsResult) -> str:
    """Which effect carries the material, and what the rod's damping does, in words generated
    from the paired differences (``verdict_from``)."""
    return verdict_from(
        {k.split(":", 1)[1]: v for k, v in (r.paired or {}).items() if k.startswith("ablation:")},
        r.ablation.spreads["none"].folds(), r.chance, r.ablation.spreads, r.loss_factors)


def _damping_clauses(paired: dict, spreads, carrier: str) -> list[str]:
    """What switching the rod's damping off does, from its own paired difference: a row that
    switches other effects off with it (``'object_damping+unilateral_contact'``) is read
    against the row of those others alone, when the ablation has it, and otherwise says that
    the damping's own share is not separated."""
    clauses = []
    for k, p in paired.items():
        parts = k.split("+")
        if not ENERGY_ABSORPTION & set(parts) or k == carrier:
            continue
        others = "+".join(e for e in parts if e not in ENERGY_ABSORPTION)
        if not others:
            clauses.append(_damping_words(f"Switched off ('{k}'), the rod's damping", p))
        elif spreads is not None and others in spreads and k in spreads:
            own = spreads[others].paired_with(spreads[k])
            clauses.append(f"Row '{k}' switches off '{others}' too: {p}. Against '{others}' "
                           "switched off alone, " + _damping_words(
                               f"the rod's damping, switched off where '{others}' is off too,",
                               own, f" without '{others}'"))
        else:
            clauses.append(f"Row '{k}' switches off '{others}' too: {p}; no row switches off "
                           f"'{others}' alone, so the rod's damping's own share is not "
                           "separated.")
    return clauses


def _damping_words(subject: str, p, where: str = "") -> str:
    """What ``subject`` (the rod's damping switched off, as a row or as its own share) does to
    the accuracy, from the sign of its paired difference ``p`` (or from its being none: every
    position as many right with it as without); ``where`` names what else the compared rows
    leave out (the scene the finding holds in)."""
    if p.direction == "lower":
        return (f"{subject} lowers it too, {p}: in the simulator{where} this agrees with the "
                "paper's explanation, that the materials differ by how much vibration energy "
                "they absorb.")
    if p.direction == "higher":
        return (f"{subject} raises the accuracy, {p}: in the simulator{where} the rods' damping "
                "blurs the materials rather than separating them, against the paper's "
                "explanation that they differ by the energy they absorb.")
    if p.identical:
        return (f"{subject} changes no position's count of right answers ({p.n_units} "
                f"{p.unit}s): in the simulator{where} these recordings show no part for the "
                "rods' damping, as assumed, in telling the materials apart.")
    return f"{subject} changes it by {p}, not resolved."


def verdict_from(paired: dict, base, chance: float, spreads: dict | None = None,
                 loss_factors=None) -> str:
    """The ablation's verdict, every clause generated from a number.

    Parameters
    ----------
    paired : dict of str to ebantenna.paper.uncertainty.PairedDifference
        Each ablation row against all effects on.
    base : ClusteredAccuracy or FoldAccuracy
        All effects on.
    chance : float
    spreads : dict, optional
        The rows' spreads (their :meth:`~ebantenna.paper.uncertainty.SeedSpread.folds` give
        each row's interval against chance).
    loss_factors : (float, float, float), optional
        The touched rods' smallest and largest assumed loss factor and the probe's.

    Examples
    --------
    >>> from ebantenna.paper.uncertainty import ClusteredAccuracy, PairedDifference
    >>> base = ClusteredAccuracy([3] * 8 + [2] * 8, [3] * 16, "position")
    >>> drop = PairedDifference([3] * 8 + [2] * 8, [0, 1] * 8, [3] * 16, "position")
    >>> flat = PairedDifference([3] * 8 + [2] * 8, [3, 2] * 8, [3] * 16, "position")
    >>> up = PairedDifference([3] * 8 + [2] * 8, [3] * 16, [3] * 16, "position")
    >>> text = verdict_from({"object_modes": drop, "object_damping": up}, base, 0.2)
    >>> "carries the material" in text, "raises the accuracy" in text
    (True, True)
    >>> text = verdict_from({"object_modes": drop, "object_damping": drop}, base, 0.2)
    >>> "lowers it too" in text
    True
    >>> "no single effect" in verdict_from({"gravity": flat}, base, 0.2)
    True
    """
    lowered = {k: p for k, p in paired.items() if p.direction == "lower"}
    if not base.ci95[0] > chance:
        return (
            f"With every effect on, the classifier reaches {format_clustered(base)} (chance "
            f"{percent(chance)}): its interval reaches chance, so switching an effect off "
            "cannot show what carries the material in this data set."
        )
    if not lowered:
        return (
            f"With every effect on, the classifier reaches {format_clustered(base)} (chance "
            f"{percent(chance)}); no single effect's removal is resolved as lowering it: in "
            "this data set no one effect is shown to carry the material."
        )
    carrier = min(lowered, key=lambda k: lowered[k].difference)
    pair = lowered[carrier]
    left = ""
    if spreads is not None and carrier in spreads:
        f = spreads[carrier].folds()
        left = (f" Without it the classifier is at {format_clustered(f)}, "
                + ("still above chance." if f.ci95[0] > chance else
                   f"an interval that reaches chance ({percent(chance)}): without it the "
                   "classifier is not shown to find any material information."))
    words = (
        f"Switching off '{carrier}' costs the most, {pair}: in this scene it carries the "
        f"material information.{left} "
    )
    clauses = _damping_clauses(paired, spreads, carrier)
    if clauses and loss_factors is not None:
        lo, hi, probe = loss_factors
        relation = "all below" if hi < probe else "not all below"
        clauses.append(
            f"This is a statement about the simulator's assumptions, not about the rig: the "
            f"rods' assumed loss factors ({lo:g} to {hi:g}) are {relation} the probe's own "
            f"({probe:g}), and whether the real rods absorb as assumed was not measured."
        )
    elif clauses:
        clauses.append("This is a statement about the simulator's assumptions, not about the "
                       "rig.")
    return words + " ".join(clauses)
