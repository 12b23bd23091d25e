"""``simulate(scene) -> Recording``, and the same for many signals at once.

The simulator is a chain of steps, applied in one loop over an ordered list, :data:`CHAIN`. Each
entry names the effect that switches the step on (None: the step always runs), the step, a
function that takes the effect and the :class:`SignalBatch` it works on, and the other effects
the step reads (``reads``): every effect of the scene is a step or is read by one. Each step is
written beside the physics it applies: the sensor's and the acquisition's (``clock_jitter``'s,
the chip's reading of the axes stepped in time, and every step from ``gravity`` on) beside their
effects, in :mod:`~ebantenna.simulate.effects.sensor` (its ``CHAIN_STEPS``); the touched
object's beside the models it runs, in :mod:`~ebantenna.simulate.touched_object`, and the free
probe's and the responses' beside the modal sum, in :mod:`~ebantenna.simulate.modes` (their
``CHAIN_STEPS``);
the preload's is here. Each step finishes its work before the next starts, and hands the next
what it needs as values in the batch. A scene that does not list an effect skips its step, and a
new effect is one more entry in the list. In order:

1. ``preload_scatter``: each strike's preload. It sets the contact spring, so it comes before
   the modes.
2. *The free probe* (always, beside the modal sum in :mod:`~ebantenna.simulate.modes`): the
   modal parameters of Z (:func:`~ebantenna.simulate.modes.free_probe_terms`). Across the sweep
   plane the probe swings free, touching nothing, whatever the object. Reads
   ``structural_damping`` and ``tip_mass``.
3. *The touched object* (always, :func:`~ebantenna.simulate.touched_object.object_terms`): the
   modal parameters of X, and the time-stepped models, from one physics model of the touched
   object (below). Reads ``object_modes``, ``structural_damping``, ``contact_compliance``,
   ``tip_mass``, ``object_damping``, ``unilateral_contact``, ``hertz_contact`` and
   ``coulomb_friction``.
4. ``clock_jitter``: when each sample is taken. The responses are evaluated at these instants.
5. *The responses* (always): X and Z after the arrest. An axis read from its modes is their sum
   (:func:`~ebantenna.simulate.modes.modal_acceleration`) through the chip's low-pass filter
   (``dlpf``) and its decimation, in closed form; an axis with a time-stepped model in the scene
   (``unilateral_contact``, ``coulomb_friction``) is computed at the filter's internal rate.
6. *The chip's reading* (always) of the axes stepped in time: through its filter at its
   internal rate, then at the sample instants. The filter is read from the scene once, into
   ``SignalBatch.chip_filter``; steps 5, 6, 9 and 10 read it there.
7. ``clock_jitter`` again: a sample taken before the arrest reads no acceleration.
8. ``gravity``,
9. ``mains_hum`` and
10. ``sensor_noise``: what the chip measures besides the vibration. On the chip the filter acts
    on the sum, after the noise; it is linear, so applying it to each part as that part enters
    gives the same: to the modal exponentials exactly (step 5), to the hum by its gain and phase
    at the hum's frequency, to the noise as drawn at the chip's internal rate; gravity, a
    constant, passes the settled filter unchanged.
11. ``sensor_drift``: the chip's offset and sensitivity, after its filter.
12. ``clipping`` and
13. ``quantisation``: the chip's range and its 16-bit output.
14. ``kalman``: the filter on the Raspberry Pi, about each axis's resting level.

The touched object is one of four physics models, each a named step of
:mod:`~ebantenna.simulate.touched_object`: without ``object_modes`` it is rigid
(:func:`~ebantenna.simulate.touched_object.pinned_modes`, a pin or the ``contact_compliance``
spring); with it, :func:`~ebantenna.simulate.touched_object.object_modes` builds the models of
:data:`~ebantenna.simulate.touched_object.OBJECT_MODELS` for each distinct (contact, material,
preload): ``coupled`` (X's modes: probe and rod joined by the contact spring), ``unilateral`` (X
struck through a contact that only pushes, with ``unilateral_contact``) and ``friction`` (Z held
by dry friction along the rod, with ``coulomb_friction``).

The work is vectorised over signals: modal parameters come from one FEM solve per distinct contact
position (and one for the Z axis), material physics is applied to whole arrays, and every effect
acts on ``(n_signals, n_samples)`` arrays. The only Python loops run over distinct contact
positions, over materials and, to give each signal its own reproducible random numbers, over
signals (one generator per signal and random effect) -- never over samples.

Inputs are checked once, where they enter (:class:`~ebantenna.simulate.Scene`, :func:`simulate`,
:func:`simulate_batch`); every step below takes checked values.
"""

from __future__ import annotations

import copy
import json
import logging
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from .._budget import check_allocation
from .._validate import check_array, check_bool, check_int, check_real
from ..fem.guards import check_contact
from ..probe import material as lookup_material
from ..recording import Recording
from .effects import effect_names
from .effects.sensor import CHAIN_STEPS as SENSOR_STEPS
from .modes import CHAIN_STEPS as MODAL_STEPS
from .modes import ModalTerms
from .scene import Scene
from .touched_object import CHAIN_STEPS as OBJECT_STEPS
from .touched_object import signal_terms

__all__ = [
    "ModalTerms",
    "SignalBatch",
    "ChainStep",
    "CHAIN",
    "modal_terms",
    "simulate",
    "simulate_batch",
    "SENSOR_EFFECTS",
    "physics_key",
    "simulate_sensor_variants",
]

log = logging.getLogger(__name__)


# -------------------------------------------------------------------------------------------------
# The chain
# -------------------------------------------------------------------------------------------------
@dataclass(eq=False)
class SignalBatch:
    """What the chain passes from step to step: ``n`` signals' checked inputs and results so far.

    Attributes
    ----------
    scene : Scene
        Everything the signals share.
    contacts, speeds, tilts : ndarray of shape (n,)
        Per-signal contact position (m), sweep speed (rad/s) and tilt ratio.
    materials : ndarray of str, shape (n,)
        Per-signal canonical material names.
    seeds : list of int
        Per-signal seeds of the random effects.
    show_progress : bool or None
        The progress bar over contact positions (None: on a terminal).
    x_modes : bool
        As in :func:`simulate_batch`.
    preloads : ndarray of shape (n,) or None
        Per-strike preloads, N, once ``preload_scatter`` drew them.
    x, z : ModalTerms or None
        The modal parameters, once the touched object's step ran.
    timed : dict
        The models stepped in time by name
        (:data:`~ebantenna.simulate.touched_object.OBJECT_MODELS`).
    responders : dict
        For the responses: the axis (``"x"``, ``"z"``) each model stepped in time gives, to its
        ``respond`` and its built models; an axis not listed is read from its modes.
    timed_acc : dict
        The axes stepped in time, once the responses ran: axis to ``(acceleration, rate)``, the
        acceleration at the model's rate (Hz) until the chip reads it at the sample instants.
    inverse : ndarray of int or None
        Which contact case each signal uses.
    t : ndarray of shape (n_samples,)
        Nominal sample times, s.
    when : ndarray of shape (n_samples,) or (n, n_samples)
        When each sample is taken, s: ``t`` unless ``clock_jitter`` moves it.
    ax, az : ndarray of shape (n, n_samples) or None
        The signals, m/s^2, once the responses' step ran.
    levels_x, levels_z : ndarray of shape (n,)
        Each axis's resting reading, m/s^2 (gravity, the drift's offset), for the Kalman filter.
    saturated : ndarray of int, shape (n,) or None
        Per signal, the samples (X and Z together) that the chip's range moved to a rail, once
        the ``clipping`` step ran; None without it.
    chip_filter : ebantenna.simulate.effects.LowPassFilter or None
        The chip's low-pass filter (the scene's ``dlpf``), read from the scene here only; the
        steps whose ``reads`` (:class:`ChainStep`) name ``dlpf`` pass their part of the signal
        through it.
    """

    scene: Scene
    contacts: np.ndarray
    materials: np.ndarray
    speeds: np.ndarray
    tilts: np.ndarray
    seeds: list
    show_progress: bool | None = None
    x_modes: bool = True
    preloads: np.ndarray | None = None
    x: ModalTerms | None = None
    z: ModalTerms | None = None
    timed: dict = field(default_factory=dict)
    responders: dict = field(default_factory=dict)
    timed_acc: dict = field(default_factory=dict)
    inverse: np.ndarray | None = None
    t: np.ndarray = field(init=False)
    when: np.ndarray = field(init=False)
    ax: np.ndarray | None = None
    az: np.ndarray | None = None
    levels_x: np.ndarray = field(init=False)
    levels_z: np.ndarray = field(init=False)
    saturated: np.ndarray | None = None
    chip_filter: object = field(init=False)

    def __post_init__(self):
        if not isinstance(self.scene, Scene):
            raise TypeError(f"scene must be a Scene, got {type(self.scene).__name__}")
        for name in ("contacts", "materials", "speeds", "tilts"):
            value = getattr(self, name)
            if not isinstance(value, np.ndarray) or value.ndim != 1:
                raise TypeError(f"{name} must be a 1-D ndarray, one entry per signal, got "
                                f"{type(value).__name__}")
            if value.shape != self.contacts.shape:
                raise ValueError(f"{name} must have one entry per contact "
                                 f"({self.contacts.size}), got shape {value.shape}")
        if len(self.seeds) != self.contacts.size:
            raise ValueError(f"seeds must have one seed per signal ({self.contacts.size}), got "
                             f"{len(self.seeds)}")
        self.t = np.arange(self.scene.n_samples) / self.scene.fs
        self.when = self.t
        self.chip_filter = self.scene.effect("dlpf")
        self.levels_x, self.levels_z = np.zeros(self.n), np.zeros(self.n)

    @property
    def n(self) -> int:
        """Number of signals."""
        return self.contacts.size

    def rngs(self, effect) -> list[np.random.Generator]:
        """One generator per signal for a random ``effect``: from its seed and the effect's stream.

        Adding or removing one effect never changes the random numbers of another.
        """
        if not isinstance(getattr(effect, "stream", None), int):
            raise TypeError(f"effect must be a random effect of the scene (with a stream "
                            f"number), got {type(effect).__name__}")
        return [np.random.default_rng([s, effect.stream]) for s in self.seeds]


def _scatter_preloads(scatter, batch: SignalBatch) -> None:
    """``preload_scatter``: each strike's preload, the nominal one times a random factor."""
    nominal = batch.scene.effect("object_modes").preload
    batch.preloads = np.array([nominal * scatter.factor(r) for r in batch.rngs(scatter)])


@dataclass(frozen=True)
class ChainStep:
    """One entry of :data:`CHAIN`.

    Attributes
    ----------
    effect : str or None
        The effect that switches the step on; None: the step always runs.
    apply : callable
        ``apply(effect, batch)``: changes the :class:`SignalBatch` in place (``effect`` is the
        scene's instance, or None for a step that always runs).
    reads : tuple of str
        The other effects the step reads when the scene lists them: every effect of
        :func:`~ebantenna.simulate.effects.effect_names` is the ``effect`` of a step or read by
        one.
    """

    effect: str | None
    apply: Callable
    reads: tuple[str, ...] = ()

    def __post_init__(self):
        names = effect_names()
        if self.effect is not None and self.effect not in names:
            raise ValueError(f"effect must be None or an effect of effect_names(), got "
                             f"{self.effect!r}")
        if not callable(self.apply):
            raise TypeError(f"apply must be callable, got {type(self.apply).__name__}")
        if not isinstance(self.reads, tuple) or not all(r in names for r in self.reads):
            raise ValueError(f"reads must be a tuple of effects of effect_names(), got "
                             f"{self.reads!r}")


#: The simulator's steps, in the order it applies them (see the module's docstring for why).
CHAIN = (
    ChainStep("preload_scatter", _scatter_preloads, reads=("object_modes",)),
    ChainStep(None, MODAL_STEPS["free_probe"], reads=("structural_damping", "tip_mass")),
    ChainStep(None, OBJECT_STEPS["touched_object"],
              reads=("object_modes", "structural_damping", "contact_compliance", "tip_mass",
                     "object_damping", "unilateral_contact", "hertz_contact",
                     "coulomb_friction")),
    ChainStep("clock_jitter", SENSOR_STEPS["sample_instants"]),
    ChainStep(None, MODAL_STEPS["responses"],
              reads=("unilateral_contact", "coulomb_friction", "dlpf")),
    ChainStep(None, SENSOR_STEPS["read_timed"], reads=("dlpf",)),
    ChainStep("clock_jitter", SENSOR_STEPS["rest_before_arrest"]),
    ChainStep("gravity", SENSOR_STEPS["gravity"]),
    ChainStep("mains_hum", SENSOR_STEPS["mains_hum"], reads=("dlpf",)),
    ChainStep("sensor_noise", SENSOR_STEPS["sensor_noise"], reads=("dlpf",)),
    ChainStep("sensor_drift", SENSOR_STEPS["sensor_drift"]),
    ChainStep("clipping", SENSOR_STEPS["clipping"]),
    ChainStep("quantisation", SENSOR_STEPS["quantisation"]),
    ChainStep("kalman", SENSOR_STEPS["kalman"]),
)


#: The sensor stage: the effects of the steps at the end of :data:`CHAIN`, from ``gravity`` on.
#: They read the signals, the sample instants, the seeds and the sampling, never the physics, and
#: the physics never reads them: scenes that differ only in these share the steps before them.
SENSOR_EFFECTS = ("gravity", "mains_hum", "sensor_noise", "sensor_drift", "clipping",
                  "quantisation", "kalman")
_SENSOR_STAGE = next(i for i, s in enumerate(CHAIN) if s.effect in SENSOR_EFFECTS)
assert all(s.effect in SENSOR_EFFECTS for s in CHAIN[_SENSOR_STAGE:])


def physics_key(scene: Scene) -> str:
    """What the steps before the sensor stage read of ``scene``: its parameters without its name
    and without the :data:`SENSOR_EFFECTS`, as canonical JSON. Two scenes with the same key
    give the same signals up to the sensor stage.

    Examples
    --------
    >>> from ebantenna.simulate import builtin_scene
    >>> paper = builtin_scene("paper")
    >>> quiet = paper.with_(name="quiet", effects=[e for e in paper.effects
    ...                                            if e.name != "sensor_noise"])
    >>> physics_key(quiet) == physics_key(paper)
    True
    >>> physics_key(paper.with_(contact=0.3)) == physics_key(paper)
    False
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    d = scene.to_dict()
    del d["name"]
    d["effects"] = {k: v for k, v in d["effects"].items() if k not in SENSOR_EFFECTS}
    return json.dumps(d, sort_keys=True)


def _run_chain(batch: SignalBatch, steps=None) -> SignalBatch:
    """Apply every step of ``steps`` (default :data:`CHAIN`) that the scene asks for, in order."""
    for step in CHAIN if steps is None else steps:
        effect = None if step.effect is None else batch.scene.effect(step.effect)
        if step.effect is None or effect is not None:
            step.apply(effect, batch)
    log.debug("simulated %d signals of %d samples", batch.n, batch.scene.n_samples)
    return batch


# -------------------------------------------------------------------------------------------------
# The public entries: inputs are checked here, once
# -------------------------------------------------------------------------------------------------
def _per_signal(name, value, default, n):
    if value is None:
        value = default
    if isinstance(value, str):
        return np.array([value] * n, dtype=object)
    if np.ndim(value) == 0:
        value = value.item() if isinstance(value, np.ndarray | np.generic) else value
        return np.full(n, check_real(name, value))
    if isinstance(value, np.ma.MaskedArray):
        array = value  # refused by check_array, naming it: its mask would be lost here
    else:
        try:
            array = np.asarray(value)
        except ValueError:
            raise ValueError(f"{name} must be a scalar or a 1-D array, got a ragged list") from None
    if array.shape != (n,):
        raise ValueError(f"{name} must be a scalar or have shape ({n},), got shape {array.shape}")
    return array


def _size_of(name: str, value) -> int:
    """The number of values of an argument that is a scalar or a 1-D sequence."""
    try:
        return int(np.size(value))
    except ValueError:
        raise ValueError(f"{name} must be a scalar or a 1-D array, got a ragged list") from None


def _seeds(seeds, n: int) -> list[int]:
    """``n`` seeds as Python ints >= 0 (any size: they enter a SeedSequence), from one or ``n``."""
    if isinstance(seeds, int | np.integer) and not isinstance(seeds, bool):
        return [check_int("seeds", seeds, minimum=0)] * n
    values = list(np.asarray(seeds, dtype=object).ravel()) if np.ndim(seeds) == 1 else None
    if values is None or len(values) != n:
        raise ValueError(f"seeds must be an int or {n} ints, got {seeds!r}")
    return [check_int("seeds", v, minimum=0) for v in values]


def _checked_batch(scene, contact, material, sweep_speed, tilt_ratio, seeds, **options):
    """The :class:`SignalBatch` of :func:`simulate_batch`'s arguments, every one checked here.

    The scene's own values, the defaults, were checked when it was built.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    given = {"contact": contact, "sweep_speed": sweep_speed, "tilt_ratio": tilt_ratio,
             "seeds": seeds}
    sizes = {k: _size_of(k, v) for k, v in given.items() if v is not None}
    if material is not None and not isinstance(material, str):
        sizes["material"] = len(material)
    n = max([*sizes.values(), 1])
    # the signals ax and az, and about as much again in the modal sums that make them
    check_allocation(32 * n * scene.n_samples, parameter=max(sizes, key=sizes.get, default="n"),
                     what=f"{n} signals of {scene.n_samples} samples")
    contacts = check_array("contact", _per_signal("contact", contact, scene.contact, n), ndim=1)
    for c in contacts:  # the one contact check of the probe model (fem.guards)
        check_contact("contact", float(c), scene.probe.length)
    names = _per_signal("material", material, scene.material, n)
    materials = np.array([lookup_material(str(m)).name for m in names], dtype=object)
    speeds = check_array(
        "sweep_speed", _per_signal("sweep_speed", sweep_speed, scene.sweep_speed, n), ndim=1
    )
    tilts = check_array(
        "tilt_ratio", _per_signal("tilt_ratio", tilt_ratio, scene.tilt_ratio, n), ndim=1
    )
    if np.any(speeds <= 0) or np.any(tilts < 0):
        raise ValueError("sweep_speed must be > 0 and tilt_ratio >= 0 for every signal")
    return SignalBatch(scene, contacts, materials, speeds, tilts, _seeds(seeds, n), **options)


def _scene_batch(scene: Scene, seed: int) -> SignalBatch:
    """The one signal of a checked scene, with a checked seed."""
    one = np.ones(1)
    return SignalBatch(
        scene,
        np.array([scene.contact]),
        np.array([scene.material], dtype=object),
        scene.sweep_speed * one,
        scene.tilt_ratio * one,
        [seed],
    )


def modal_terms(scene: Scene) -> tuple[ModalTerms, ModalTerms]:
    """The X and Z modal parameters of one scene (one row each).

    Examples
    --------
    >>> from ebantenna.simulate import builtin_scene, modal_terms
    >>> x, z = modal_terms(builtin_scene("ideal").with_(contact=0.2))
    >>> x.frequencies().round(1), z.frequencies().round(1)
    (array([ 39. , 243.5, 350.7]), array([ 13.9,  87. , 243.6, 477.4]))
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    b = _scene_batch(scene, 0)
    return signal_terms(scene, b.contacts, b.materials, b.speeds, b.tilts)[:2]


def simulate_batch(
    scene: Scene,
    *,
    contact=None,
    material=None,
    sweep_speed=None,
    tilt_ratio=None,
    seeds=0,
    show_progress=None,
    x_modes=True,
    return_saturated=False,
):
    """Simulate many signals of one scene, each with its own contact, material, speed and seed.

    Row ``i`` equals ``simulate(scene.with_(contact=contact[i], material=material[i],
    sweep_speed=sweep_speed[i], tilt_ratio=tilt_ratio[i]), seed=seeds[i])``.

    Parameters
    ----------
    scene : Scene
        Everything that is shared.
    contact, sweep_speed, tilt_ratio : float or array of shape (n,), optional
        Per-signal values (m, rad/s, dimensionless); the scene's by default.
    material : str or array of str of shape (n,), optional
        Per-signal touched materials; the scene's by default.
    seeds : int or array of int of shape (n,)
        Seeds of the signals' random effects.
    show_progress : bool, optional
        Force the progress bar over contact positions on or off (default: on a terminal).
    x_modes : bool
        Whether ``x`` carries the coupled modes even where the strikes of ``unilateral_contact``
        give the X axis (one eigenproblem per strike); False leaves them out there (``x`` then
        has no modes, only ``preload`` and ``restrikes``), as a data set build does.
    return_saturated : bool
        Also return ``saturated``.

    Returns
    -------
    t : ndarray of shape (n_samples,)
        Nominal sample times, s.
    ax, az : ndarray of shape (n, n_samples)
        Tip accelerations, m/s^2.
    x, z : ModalTerms
        The modal parameters used.
    saturated : ndarray of int, shape (n,), or None
        Only with ``return_saturated``: per signal, the samples (X and Z together) that the chip's
        range (the ``clipping`` effect) moved to a rail; None if the scene has no range.
    """
    check_bool("return_saturated", return_saturated)
    batch = _checked_batch(
        scene, contact, material, sweep_speed, tilt_ratio, seeds,
        show_progress=show_progress, x_modes=x_modes,
    )  # fmt: skip
    _run_chain(batch)
    return _batch_result(batch, return_saturated)


def _batch_result(batch: SignalBatch, return_saturated: bool) -> tuple:
    """What :func:`simulate_batch` returns of a batch the chain ran on."""
    done = (batch.t, batch.ax, batch.az, batch.x, batch.z)
    return (*done, batch.saturated) if return_saturated else done


def simulate_sensor_variants(
    scenes, *, contact=None, material=None, sweep_speed=None, tilt_ratio=None, seeds=0,
    show_progress=None, x_modes=True, return_saturated=False,
):
    """:func:`simulate_batch` of each of ``scenes``, which differ only in their sensor stage
    (the same :func:`physics_key`): the steps before it run once, on the first scene.

    Each result is bit for bit :func:`simulate_batch` of that scene with the same ``rows``: the
    steps of the sensor stage change only the signals and the levels, which are copied for each
    scene, and every random effect draws from its own stream (:meth:`SignalBatch.rngs`).

    Parameters
    ----------
    scenes : sequence of Scene
        At least one, all with the same :func:`physics_key`.
    contact, material, sweep_speed, tilt_ratio, seeds, show_progress, x_modes, return_saturated
        As in :func:`simulate_batch`.

    Returns
    -------
    list of tuple
        Per scene, what :func:`simulate_batch` returns.
    """
    check_bool("return_saturated", return_saturated)
    if isinstance(scenes, Scene) or not hasattr(scenes, "__iter__"):
        raise TypeError(f"scenes must be a non-empty sequence of Scene, got "
                        f"{type(scenes).__name__}")
    scenes = list(scenes)
    if not scenes or not all(isinstance(s, Scene) for s in scenes):
        raise TypeError("scenes must be a non-empty sequence of Scene")
    key = physics_key(scenes[0])
    other = [s.name for s in scenes[1:] if physics_key(s) != key]
    if other:
        raise ValueError(
            f"scenes must differ from {scenes[0].name!r} only in the sensor stage "
            f"({', '.join(SENSOR_EFFECTS)}); {', '.join(map(repr, other))} differ in more"
        )
    batch = _checked_batch(
        scenes[0], contact, material, sweep_speed, tilt_ratio, seeds,
        show_progress=show_progress, x_modes=x_modes,
    )  # fmt: skip
    shared = _run_chain(batch, CHAIN[:_SENSOR_STAGE])
    out = []
    for scene in scenes:
        batch = copy.copy(shared)
        batch.scene = scene
        batch.ax, batch.az = shared.ax.copy(), shared.az.copy()
        batch.levels_x, batch.levels_z = shared.levels_x.copy(), shared.levels_z.copy()
        _run_chain(batch, CHAIN[_SENSOR_STAGE:])
        out.append(_batch_result(batch, return_saturated))
    return out


def simulate(scene: Scene, seed: int = 0) -> Recording:
    """Simulate the tip accelerations of one scene.

    Parameters
    ----------
    scene : Scene
        What to simulate (:func:`~ebantenna.simulate.builtin_scene` or your own).
    seed : int
        Seed of the random effects (noise, jitter, hum phase); a scene without random effects does
        not depend on it.

    Returns
    -------
    Recording
        ``t`` (s), ``ax``, ``az`` (m/s^2), ``fs`` (Hz) and metadata: the scene, the seed and the
        simulated modes of X and Z (frequencies in Hz, damping ratios); with the
        ``unilateral_contact`` effect also ``restrikes``, the contacts after the first touch;
        with the ``clipping`` effect ``samples_saturated``, the samples (X and Z together) that
        the chip's range moved to a rail.

    Examples
    --------
    >>> from ebantenna.simulate import builtin_scene, simulate
    >>> rec = simulate(builtin_scene("paper").with_(contact=0.25, material="brass"), seed=3)
    >>> rec.n_samples, rec.fs
    (1000, 1000.0)
    >>> rec.metadata["modes_x_hz"][:4]  # the probe's and the brass rod's coupled modes
    [32.82, 92.58, 185.89, 372.96]
    """
    seed = check_int("seed", seed, minimum=0)
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    batch = _run_chain(_scene_batch(scene, seed))
    x, z = batch.x, batch.z
    metadata = {
        "source": "ebantenna.simulate",
        "scene": scene.to_dict(),
        "seed": seed,
        "modes_x_hz": [round(float(f), 2) for f in x.frequencies()],
        "zeta_x": [float(v) for v in x.damping_ratios()],
        "modes_z_hz": [round(float(f), 2) for f in z.frequencies()],
        "zeta_z": [float(v) for v in z.damping_ratios()],
    }
    if x.restrikes is not None:  # the unilateral contact: strikes after the first touch
        metadata["restrikes"] = int(x.restrikes[0])
    if batch.saturated is not None:  # the chip's range
        metadata["samples_saturated"] = int(batch.saturated[0])
    return Recording(batch.t, batch.ax[0], batch.az[0], scene.fs, metadata)
