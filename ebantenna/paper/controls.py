"""Controls that show what the material classifier learns.

*Ablation* (:func:`ablation_accuracies`): the data set is simulated again with one effect of the
scene switched off, and the SVM's accuracy on whole held-out positions
(:func:`~ebantenna.paper.splits.grouped_split`) is measured each time. The effect whose removal
brings the accuracy down to chance is the one that carries the material.

*Equivalent pair* (:func:`equivalent_rod`, :func:`equivalent_pair_accuracy`): an aluminium and a
steel rod whose dimensions make them the same mechanical object for the probe (same cantilever
stiffness, same bending frequencies, hence the same modal masses), labelled by material. If the
probe feels mechanical impedance and not chemistry, no classifier tells them apart better than a
coin (0.5).

Both rebuild data sets with :func:`ebantenna.simulate.build_dataset`, on a small design
(:data:`ABLATION_DESIGN`, or :data:`~ebantenna.paper.data.QUICK_DESIGN` for quick runs), cached
per scene like any data set.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field, replace

import numpy as np
from joblib import Parallel, delayed

from .._threads import limited_threads
from .._validate import check_choice, check_int, check_n_jobs, check_positive, output_dir
from ..fem.coupling import Rod
from ..probe import material
from ..signal import fft_features
from ..simulate import DatasetDesign, Scene, build_datasets
from ..simulate import build_dataset as _build
from .data import PAPER_DESIGN
from .experiments import classify_materials_svm
from .feature_table import mode_peaks
from .mode_curves import classify_materials_by_mode_curves
from .splits import distinct_split_seeds, grouped_split
from .uncertainty import seed_spread

__all__ = [
    "ABLATION_DESIGN",
    "Ablation",
    "ablation_accuracies",
    "grouped_svm_accuracy",
    "grouped_svm_spread",
    "SPLIT_SEEDS",
    "equivalent_rod",
    "equivalent_pair_scenes",
    "equivalent_pair_accuracy",
    "equivalent_pair_spread",
    "twin_seeds",
]

#: The reduced data set of the controls: the paper's materials, positions (every 5 mm) and
#: scatter, three recordings per material and position: 1,185 recordings, 240 of them in a
#: grouped test set (16 of the 79 positions held out). Two accuracies near 65 % on 240
#: recordings each differ by two standard deviations of their difference at
#: ``2 sqrt(2 * 0.65 * 0.35 / 240)``, 8.7 points: the design resolves a 10-point change (one
#: repetition, 80 test recordings, would need 15 points,
#: :func:`~ebantenna.paper.uncertainty.resolvable_difference`). The positions stay 5 mm apart
#: because the grouped split asks the classifier to interpolate between neighbours; with 2 cm
#: between them the SVM is at chance even with every effect on.
ABLATION_DESIGN = replace(PAPER_DESIGN, name="controls-3rep", repetitions=3)

#: How many split seeds every control is measured with (the data set's seed fixed): the
#: accuracy's spread over them is a second measure of its uncertainty.
SPLIT_SEEDS = 5


def _check_build(design, cache_dir, n_jobs, splits) -> None:
    """Refuse, naming the parameter and before any data set is built, a ``design`` that is not a
    :class:`~ebantenna.simulate.DatasetDesign`, a ``cache_dir`` that cannot hold the data sets
    (not a path, a file, a folder that refuses files: ``_validate.output_dir``), an ``n_jobs``
    that is not -1, None or a count of workers within the machine's cores, and fewer than two
    ``splits``."""
    if not isinstance(design, DatasetDesign):
        raise TypeError(f"design must be a DatasetDesign, got {type(design).__name__}")
    output_dir("cache_dir", cache_dir)
    check_n_jobs("n_jobs", n_jobs)
    check_int("splits", splits, minimum=2)


def _check_dataset(ds) -> None:
    """Refuse a ``ds`` that is not a data set of recordings (``ax``, ``az``, labels)."""
    needed = ("ax", "az", "material", "contact")
    if not all(hasattr(ds, a) for a in needed):
        raise TypeError(f"ds must be a data set (ebantenna.simulate.Dataset) with "
                        f"{', '.join(needed)}; got {type(ds).__name__}")


def grouped_svm_accuracy(ds, *, seed: int = 0, every: int = 5) -> float:
    """SVM test accuracy on whole held-out positions of data set ``ds``.

    The paper's features (FFT magnitudes of X and Z, :func:`ebantenna.signal.fft_features`) and
    SVM (:func:`~ebantenna.paper.experiments.classify_materials_svm`) on
    :func:`~ebantenna.paper.splits.grouped_split` by the nominal positions ``ds.contact``.

    Examples
    --------
    >>> import tempfile
    >>> from ebantenna.simulate import builtin_scene, build_dataset
    >>> design = replace(ABLATION_DESIGN, materials=("brass", "pvc"), contact_step=0.05)
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     ds = build_dataset(tmp, builtin_scene("paper"), design)
    >>> 0.0 <= grouped_svm_accuracy(ds, every=2) <= 1.0
    True
    """
    _check_dataset(ds)
    X = fft_features(np.asarray(ds.ax, float), np.asarray(ds.az, float))
    split = grouped_split(ds.contact, every=every, seed=seed)
    result = classify_materials_svm(X, ds.material, split=split)
    return result.accuracies["test"]


def grouped_svm_spread(ds, *, seed: int = 0, splits: int = SPLIT_SEEDS, n_jobs: int = 1):
    """:func:`grouped_svm_accuracy` over ``splits`` split seeds from ``seed`` that hold out
    different positions (:func:`~ebantenna.paper.splits.distinct_split_seeds`; with five,
    every position is held out once).

    Parameters
    ----------
    n_jobs : int
        Worker processes for the fits (one fold each). Every fit runs with one BLAS thread
        wherever it runs, so the result does not depend on ``n_jobs``.

    Returns
    -------
    ebantenna.paper.uncertainty.SeedSpread
        One accuracy and one test count per split seed; ``values[0]`` is
        ``grouped_svm_accuracy(ds, seed=seed)``.
    """
    return _grouped_svm_spreads([ds], seed=seed, splits=splits, n_jobs=n_jobs)[0]


def _fold_fit(X, y, contact, split_seed: int) -> tuple:
    """The paper's SVM on one fold of the grouped split, with one BLAS thread: its accuracy,
    test count, test rows and whether each was right (what :func:`seed_spread` keeps)."""
    with limited_threads(1):
        result = classify_materials_svm(X, y, split=grouped_split(contact, seed=split_seed))
    return (result.accuracies["test"], result.counts["test"], result.rows(), result.correct())


def _fold_fits(calls, n_jobs) -> list:
    """:func:`_fold_fit` of every call ``(X, y, contact, split_seed)``, on ``n_jobs`` workers
    (None: one), in the order of ``calls``."""
    n_jobs = check_n_jobs("n_jobs", n_jobs) or 1
    if n_jobs == 1 or len(calls) < 2:
        return [_fold_fit(*call) for call in calls]
    return Parallel(n_jobs=min(n_jobs, len(calls)))(delayed(_fold_fit)(*call) for call in calls)


def _grouped_svm_spreads(datasets, *, seed: int, splits: int, n_jobs: int) -> list:
    """:func:`grouped_svm_spread` of every data set of ``datasets``, all their folds fitted in
    one pool of ``n_jobs`` workers (a control has a dozen data sets of five folds each)."""
    count = check_int("splits", splits, minimum=2)
    check_n_jobs("n_jobs", n_jobs)  # before the features, not after
    plans = []
    for ds in datasets:
        _check_dataset(ds)
        X = fft_features(np.asarray(ds.ax, float), np.asarray(ds.az, float))
        seeds = distinct_split_seeds("grouped", ds.material, ds.contact, seed=seed, count=count)
        plans.append((ds, X, seeds))
    results = iter(_fold_fits(
        [(X, ds.material, ds.contact, s) for ds, X, seeds in plans for s in seeds], n_jobs))
    spreads = []
    for ds, _, seeds in plans:
        by_seed = {s: next(results) for s in seeds}
        spread = seed_spread(by_seed.__getitem__, seeds)
        spread.positions = np.asarray(ds.contact)
        spreads.append(spread)
    return spreads


@dataclass(frozen=True)
class Ablation:
    """Grouped-split SVM accuracy with each effect switched off.

    Attributes
    ----------
    accuracies : dict of str to float
        ``"none"`` (nothing switched off: the baseline) and one entry per effect switched off;
        effects dropped together are named ``"a+b"``.
    dropped_together : dict of str to tuple of str
        For an effect the scene refused to lose alone: it and the effects dropped with it.
    refused : dict of str to str
        Effects that could not be switched off at all, with the scene's reason.
    changed : dict of str to str
        Effects that could only be switched off with a scene parameter changed, and how.
    spreads : dict of str to ebantenna.paper.uncertainty.SeedSpread
        For every entry of ``accuracies``: the accuracy over the split seeds (the data set's
        seed fixed; the five folds of the grouped split), ``values[0]`` the one in
        ``accuracies``, with each seed's test rows and whether each was right.
    contacts : ndarray, optional
        The nominal contact position of every row, the same in every rebuilt data set (same
        design, same seed): the rows pair up across the rows of the ablation.
    """

    accuracies: dict
    dropped_together: dict
    refused: dict
    changed: dict = field(default_factory=dict)
    spreads: dict = field(default_factory=dict)
    contacts: np.ndarray | None = None


#: What an ablation may not leave behind although the scene itself allows it: a contact that only
#: pushes between bodies without damping chatters without end (a lesson of its own, not a
#: data set), so switching off either damping switches that contact off with it.
ABLATION_NEEDS = {"unilateral_contact": ("structural_damping", "object_damping")}


def _without(scene: Scene, names, **changes) -> Scene:
    ablated = scene.with_(effects=[e for e in scene.effects if e.name not in names], **changes)
    for effect, needs in ABLATION_NEEDS.items():
        missing = [n for n in needs if not ablated.has(n)]
        if ablated.has(effect) and missing:
            raise ValueError(
                f"effect {effect!r} needs {' and '.join(map(repr, missing))} in an ablation "
                "(undamped bodies chatter without end on a contact that only pushes)"
            )
    return ablated


def _ablated_scene(scene: Scene, name: str, most: int = 3):
    """The scene without ``name`` and the fewest other effects that must go with it.

    Returns ``(scene, dropped names, None, change)``, or ``(None, (name,), reason, None)`` when no
    set of at most ``most`` other effects makes the scene valid. ``change`` says which scene
    parameter had to change instead (or None): without the ``dlpf`` nothing stands between the
    modes and the sampling at ``fs``, so only the modes below ``fs / 2`` are simulated.
    """
    others = [n for n in scene.effect_names if n != name]
    reason = None
    for size in range(most + 1):
        for extra in itertools.combinations(others, size):
            try:
                return _without(scene, {name, *extra}), (name, *extra), None, None
            except ValueError as exc:
                reason = reason or str(exc)  # the scene's reason for refusing ``name`` alone
    if "max_frequency" not in reason:
        return None, (name,), reason, None
    nyquist = scene.fs / 2  # the sampling can no longer hold the modes simulated: fewer modes
    try:
        ablated = _without(scene, {name}, max_frequency=nyquist)
    except ValueError:
        return None, (name,), reason, None
    change = (
        f"max_frequency lowered from {scene.max_frequency:g} to {nyquist:g} Hz: without it "
        "nothing stands between the modes and the sampling, so only the modes below fs/2 are "
        "simulated (no aliasing)"
    )
    return ablated, (name,), None, change


def ablation_accuracies(
    scene: Scene,
    names=None,
    *,
    design: DatasetDesign = ABLATION_DESIGN,
    seed: int = 0,
    cache_dir,
    n_jobs: int = 1,
    splits: int = SPLIT_SEEDS,
) -> Ablation:
    """Rebuild the data set with each effect switched off; the grouped SVM accuracy of each.

    An effect that others require cannot go alone: the scene raises ``ValueError``, and the
    effect is dropped together with the fewest others (at most two, the first such set in the
    scene's order) whose removal makes the scene valid; an effect that cannot be dropped by
    removing effects at all (e.g. ``tip_mass``, which the probe's own tip mass demands) is
    reported in ``refused`` with the scene's reason.

    Parameters
    ----------
    scene : Scene
        The full scene.
    names : sequence of str, optional
        Effects to switch off, one at a time (default: every effect of the scene).
    design : DatasetDesign
        The data set rebuilt each time (default :data:`ABLATION_DESIGN`).
    seed : int
        Seed of the data set and of the split.
    cache_dir : path
        Where the data sets are cached (one file per ablated scene): a folder that accepts new
        files, or one that can be made. The design, the cache folder, ``n_jobs`` and
        ``splits`` are checked before any data set is built.
    n_jobs : int
        Worker processes of each build, and of the fits (every fold of every data set in one
        pool; each fit on one BLAS thread, so the numbers do not depend on it).
    splits : int
        Split seeds per data set (``seed ...``), for the ``spreads`` of :class:`Ablation`.

    Returns
    -------
    Ablation

    Examples
    --------
    >>> import tempfile
    >>> from ebantenna.simulate import builtin_scene
    >>> design = replace(ABLATION_DESIGN, materials=("brass", "pvc"), contact_step=0.05)
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     ab = ablation_accuracies(builtin_scene("paper"), ["object_modes", "tip_mass"],
    ...                              design=design, cache_dir=tmp)
    >>> sorted(ab.accuracies)
    ['none', 'object_modes+object_damping+preload_scatter+unilateral_contact']
    >>> sorted(ab.refused)
    ['tip_mass']
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    names = scene.effect_names if names is None else tuple(names)
    unknown = sorted(set(names) - set(scene.effect_names))
    if unknown:
        raise ValueError(
            f"names must be effects of the scene ({', '.join(scene.effect_names)}); got {unknown}"
        )
    seed = check_int("seed", seed, minimum=0)
    _check_build(design, cache_dir, n_jobs, splits)

    scenes = {"none": scene}
    together, refused, changed = {}, {}, {}
    for name in names:
        ablated, dropped, reason, change = _ablated_scene(scene, name)
        if ablated is None:
            refused[name] = reason
            continue
        if len(dropped) > 1:
            together[name] = dropped
        if change is not None:
            changed[name] = change
        label = "+".join(dropped)
        scenes[label] = ablated.with_(name=f"{scene.name}-without-{label}")
    # built together: the rows that switch off a sensor effect share the physics of the others
    built = build_datasets(cache_dir, list(scenes.values()), design, seed, n_jobs=n_jobs,
                           show_progress=False)
    spreads = dict(zip(scenes, _grouped_svm_spreads(built, seed=seed, splits=splits,
                                                    n_jobs=n_jobs), strict=True))
    accuracies = {label: float(spread.values[0]) for label, spread in spreads.items()}
    contacts = np.asarray(built[0].contact)
    for ds in built[1:]:
        if not (np.array_equal(ds.contact, contacts)
                and np.array_equal(ds.material, built[0].material)):
            raise RuntimeError("the rebuilt data sets do not hold the same rows in one order")
    return Ablation(accuracies, together, refused, changed, spreads, contacts)


# ------------------------------------------------------------------ the equivalent pair
def _cantilever(rod: Rod) -> tuple[float, float]:
    """Cantilever tip stiffness 3EI/l^3 (N/m) and first bending frequency (Hz) of ``rod``."""
    beam = rod.as_beam()
    return 3 * beam.flexural_rigidity / rod.free_length**3, rod.cantilever_frequency()


def equivalent_rod(reference: Rod, other) -> Rod:
    """The rod of material ``other`` that the probe cannot tell from ``reference``.

    For a solid round cantilever of diameter ``d``, free length ``l``, Young's modulus ``E``
    and density ``rho``, ``I = pi d^4 / 64`` and ``A = pi d^2 / 4``, so

    .. math::

        k = \\frac{3 E I}{l^3} = \\frac{3 \\pi E d^4}{64\\, l^3}, \\qquad
        f_n = \\frac{(\\beta_n l)^2}{2 \\pi l^2} \\sqrt{\\frac{E I}{\\rho A}}
            = \\frac{(\\beta_n l)^2}{8 \\pi} \\frac{d}{l^2} c, \\quad c = \\sqrt{E / \\rho}.

    Every mode of the family has the same ``beta_n l``, so matching ``f_1`` matches every
    bending frequency. With ratios ``lambda = l'/l``, ``delta = d'/d``, ``epsilon = E'/E``,
    ``kappa = c'/c``: equal frequencies need ``delta kappa / lambda^2 = 1``, i.e.
    ``delta = lambda^2 / kappa``; equal stiffness needs ``epsilon delta^4 / lambda^3 = 1``, and
    with the first, ``epsilon lambda^5 / kappa^4 = 1``:

    .. math::

        \\lambda = \\left(\\frac{\\kappa^4}{\\epsilon}\\right)^{1/5}, \\qquad
        \\delta = \\frac{\\lambda^2}{\\kappa}.

    With ``k = m_eff omega_1^2`` the effective (and every modal) mass then matches too, and the
    mode shapes are those of one family: the point mobility at the free end is the same but for
    the loss factor. For aluminium to steel (``kappa`` close to 1, ``epsilon`` about 2.9), a
    Ø12 mm x 250 mm aluminium rod matches a steel rod of about Ø7.8 mm x 203 mm. The contact
    height scales with the length (the same point of the mode shapes).

    Parameters
    ----------
    reference : Rod
        The rod to match.
    other : Material or str
        The material of the equivalent rod.

    Returns
    -------
    Rod
        Of material ``other``, with the diameter and free length above.

    Examples
    --------
    >>> al = Rod("aluminium", diameter=0.012, free_length=0.25)
    >>> steel = equivalent_rod(al, "steel")
    >>> round(1e3 * steel.diameter, 2), round(1e3 * steel.free_length, 1)  # mm
    (7.81, 202.9)
    >>> round(steel.cantilever_frequency() / al.cantilever_frequency(), 12)
    1.0
    """
    if not isinstance(reference, Rod):
        raise TypeError(f"reference must be a Rod, got {type(reference).__name__}")
    a, b = reference.material, material(other) if isinstance(other, str) else other
    if not (hasattr(b, "youngs_modulus") and hasattr(b, "density")):
        raise TypeError(f"other must be a material name or a Material, got "
                        f"{type(other).__name__}")
    epsilon = b.youngs_modulus / a.youngs_modulus
    kappa = math.sqrt((b.youngs_modulus / b.density) / (a.youngs_modulus / a.density))
    lam = (kappa**4 / epsilon) ** 0.2
    delta = lam**2 / kappa
    return Rod(
        b,
        diameter=delta * reference.diameter,
        free_length=lam * reference.free_length,
        contact_height=lam * reference.contact_height,
    )


def equivalent_pair_scenes(scene: Scene, *, reference: str = "aluminium", other: str = "steel"):
    """Two scenes touching a ``reference`` rod and its :func:`equivalent_rod` of ``other``.

    The scene must list the ``object_modes`` effect; its ``diameter``, ``free_length`` and
    ``contact_height`` set the reference rod, and the other scene gets the equivalent rod's
    (the contact height scaled with the length, unless it is the free end).

    Examples
    --------
    >>> from ebantenna.simulate import builtin_scene
    >>> al, steel = equivalent_pair_scenes(builtin_scene("paper"))
    >>> al.material, steel.material, round(1e3 * steel.effect("object_modes").diameter, 2)
    ('aluminium', 'steel', 7.81)

    Returns
    -------
    (Scene, Scene)
        Touching ``reference`` and ``other``, named ``<scene>-pair-<reference>`` and
        ``<scene>-pair-<other>-of-<reference>`` (one cache file per twin: two references may
        share the other material).
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    effect = scene.effect("object_modes")
    if effect is None:
        raise ValueError(
            "scene must list the 'object_modes' effect (the touched rod's own modes); "
            f"it lists {', '.join(scene.effect_names) or 'none'}"
        )
    height = getattr(effect, "contact_height", None)  # None: the rod's free end
    rod = Rod(
        reference,
        diameter=check_positive("diameter", effect.diameter),
        free_length=check_positive("free_length", effect.free_length),
        contact_height=height,
    )
    twin = equivalent_rod(rod, other)
    changed = {"diameter": twin.diameter, "free_length": twin.free_length}
    if height is not None:  # the same point of the mode shapes
        changed["contact_height"] = twin.contact_height
    twin_effect = replace(effect, **changed)
    effects = [twin_effect if e.name == "object_modes" else e for e in scene.effects]
    return (
        scene.with_(name=f"{scene.name}-pair-{reference}", material=reference),
        scene.with_(name=f"{scene.name}-pair-{other}-of-{reference}", material=other,
                    effects=effects),
    )


def twin_seeds(seed: int) -> tuple[int, int]:
    """The data-set seeds of the two twins: different, so that each twin draws its own scatter.

    With one seed, the two one-material data sets would draw the same scatter row by row
    (position error, sweep speed, tilt, noise): each twin pair would then be the same recording
    but for the rod, and a classifier that cannot tell the rods apart would give both the same
    label, scoring exactly one of two right, 50 %, however it classified. With their own
    scatter, a classifier that cannot tell the rods apart scatters around 50 % as guessing
    does, and one that can rises above it.

    Examples
    --------
    >>> twin_seeds(0), twin_seeds(2**32 - 2)
    ((0, 1), (4294967294, 4294967293))
    """
    seed = check_int("seed", seed, minimum=0)
    return seed, (seed + 1 if seed < 2**32 - 2 else seed - 1)


def equivalent_pair_accuracy(
    scene: Scene,
    *,
    design: DatasetDesign = ABLATION_DESIGN,
    seed: int = 0,
    cache_dir,
    n_jobs: int = 1,
    classifier: str = "svm",
    reference: str = "aluminium",
    other: str = "steel",
) -> float:
    """Grouped-split accuracy between a ``reference`` rod and its equivalent of ``other``.

    Both data sets follow ``design`` with one material each (``reference`` in one scene,
    ``other`` in the other, :func:`equivalent_pair_scenes`), each with its own scatter
    (:func:`twin_seeds`), and are put together with the material as the label. Two classes:
    0.5 is chance.

    Parameters
    ----------
    classifier : {"svm", "mode_curves"}
        The paper's SVM on the FFT features, or
        :func:`~ebantenna.paper.mode_curves.classify_materials_by_mode_curves` on the two
        strongest peaks.
    reference, other : str
        The material of the scene's rod and that of its twin.

    Returns
    -------
    float
        Test accuracy on whole held-out positions (split seed ``seed``).
    """
    spread = equivalent_pair_spread(
        scene, design=design, seed=seed, cache_dir=cache_dir, n_jobs=n_jobs,
        classifier=classifier, reference=reference, other=other, splits=2,
    )  # fmt: skip
    return float(spread.values[0])


def equivalent_pair_spread(
    scene: Scene,
    *,
    design: DatasetDesign = ABLATION_DESIGN,
    seed: int = 0,
    cache_dir,
    n_jobs: int = 1,
    classifier: str = "svm",
    reference: str = "aluminium",
    other: str = "steel",
    splits: int = SPLIT_SEEDS,
):
    """:func:`equivalent_pair_accuracy` over ``splits`` split seeds from ``seed`` that hold out
    different positions (the data sets' seed fixed). The design, the cache folder, ``n_jobs``
    and ``splits`` are checked, as in :func:`ablation_accuracies`, before any data set is built.

    Returns
    -------
    ebantenna.paper.uncertainty.SeedSpread
        One accuracy and one test count per split seed.

    Examples
    --------
    >>> import tempfile
    >>> from ebantenna.simulate import builtin_scene
    >>> design = replace(ABLATION_DESIGN, contact_step=0.05, repetitions=1)
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     s = equivalent_pair_spread(builtin_scene("paper"), design=design, cache_dir=tmp,
    ...                                reference="brass", splits=2)
    >>> [int(n) % 2 for n in s.n_test]  # whole positions, each with both materials
    [0, 0]
    """
    check_choice("classifier", classifier, ("svm", "mode_curves"))
    _check_build(design, cache_dir, n_jobs, splits)
    parts = []
    for s, name, data_seed in zip(equivalent_pair_scenes(scene, reference=reference, other=other),
                                  (reference, other), twin_seeds(seed), strict=True):
        parts.append(
            _build(cache_dir, s, replace(design, materials=(name,)), data_seed, n_jobs=n_jobs,
                   show_progress=False)
        )
    ax = np.vstack([np.asarray(p.ax, float) for p in parts])
    az = np.vstack([np.asarray(p.az, float) for p in parts])
    y = np.concatenate([p.material for p in parts])
    contact = np.concatenate([p.contact for p in parts])
    seeds = distinct_split_seeds("grouped", y, contact, seed=seed,
                                 count=check_int("splits", splits, minimum=2))
    if classifier == "svm":  # the folds' fits on the workers
        X = fft_features(ax, az)
        measure = dict(zip(seeds, _fold_fits([(X, y, contact, s) for s in seeds], n_jobs),
                           strict=True)).__getitem__
    else:
        dominant, peaks = mode_peaks(ax, parts[0].fs, n_jobs=n_jobs, show_progress=False)

        def measure(split_seed):
            result = classify_materials_by_mode_curves(peaks, dominant, y, contact,
                                                       grouped_split(contact, seed=split_seed))
            return (result.accuracies["test"], result.counts["test"], result.rows(),
                    result.correct())

    spread = seed_spread(measure, seeds)
    spread.positions = contact
    return spread
