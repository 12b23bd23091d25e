"""The touched object's physics models: which modes, or which model stepped in time, each gives.

Without the ``object_modes`` effect the touched object is rigid: :func:`pinned_modes`, the probe
arrested by a pin (or by the ``contact_compliance`` spring), one FEM solve per distinct contact
and spring. With it, :func:`object_modes` reduces each touched rod once and the probe once per
distinct contact position (Craig-Bampton), and builds, for each distinct (contact, material,
preload) -- a :class:`~ebantenna.simulate.structure.ContactCase` -- every model of
:data:`OBJECT_MODELS` the scene needs, each built from the case by a function of its own module:

``coupled``
    X's modes: probe and rod joined by the contact spring
    (:func:`~ebantenna.simulate.modes.coupled_modes_of`).
``unilateral``
    X struck through a contact that only pushes, stepped in time between contact events
    (``unilateral_contact``, :func:`~ebantenna.simulate.strikes.strike_model_of`).
``friction``
    Z held by dry friction along the rod, stepped in time between stick and slip
    (``coulomb_friction``, :func:`~ebantenna.simulate.stick_slip.friction_model_of`).

A new model of the touched rod is one entry of :data:`OBJECT_MODELS`.

:func:`object_terms` is the simulator's step of the touched object (the third step of
:data:`~ebantenna.simulate.simulator.CHAIN`, at the end of this module, ``CHAIN_STEPS``): it
runs the physics model, then has X's modal parameters laid out as
:class:`~ebantenna.simulate.modes.ModalTerms` beside the modal sum that reads them
(:func:`~ebantenna.simulate.modes.x_terms`: the modes side by side, zero-padded, each signal's
row scaled by its sweep speed), and hands the responses' step, also beside the modal sum
(:mod:`ebantenna.simulate.modes`), which axis a model stepped in time gives (an
:class:`ObjectModel`'s ``respond``). Z's modes are the free probe's, whatever the object: the step
before, beside the modal sum, lays them out (:func:`~ebantenna.simulate.modes.free_probe_terms`);
:func:`signal_terms` gives both axes' terms as the two steps do. Every function here takes values
checked by the simulator's public entries (:mod:`ebantenna.simulate.simulator`).
"""

from __future__ import annotations

import dataclasses
import math
import threading
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .._progress import progress
from .._threads import limited_threads
from .._validate import check_bool, check_choice
from ..fem.coupling import craig_bampton, probe_substructure, rod_substructure
from ..fem.guards import check_contact
from ..probe import Probe
from ..probe import material as lookup_material
from .contact import tube_on_rod_spring
from .effects import effect_names
from .modes import arrest_modes, coupled_modes_of, free_probe_terms, x_terms
from .scene import Scene
from .stick_slip import friction_axis, friction_model_of
from .strikes import strike_axis, strike_model_of
from .structure import ContactCase

__all__ = [
    "ObjectModel",
    "OBJECT_MODELS",
    "pinned_modes",
    "object_modes",
    "object_terms",
    "signal_terms",
]


def pinned_modes(scene: Scene, contacts, materials, show_progress):
    """Arrest modes on a rigid object (a pin, or the ``contact_compliance`` spring).

    One FEM solve per distinct (contact, spring).

    Parameters
    ----------
    scene : Scene
    contacts : ndarray of shape (n,)
        Per-signal contact position, m.
    materials : ndarray of str, shape (n,)
        Per-signal material names.
    show_progress : bool or None
        The progress bar over the solves (None: on a terminal).

    Returns
    -------
    modes : list of ebantenna.simulate.modes.ArrestModes
        The modes of each distinct (contact, spring).
    inverse : ndarray of int, shape (n,)
        Which of them each signal uses.
    """
    _check_signal_inputs(scene, contacts, materials)
    if show_progress is not None:
        show_progress = check_bool("show_progress", show_progress)
    probe = scene.probe
    kw = dict(n_elements=scene.n_elements, n_modes=scene.n_modes, max_frequency=scene.max_frequency)
    compliance = scene.effect("contact_compliance")
    if compliance is not None:  # one FEM solve per (contact, material)
        stiffness = {m: compliance.stiffness(lookup_material(m), probe) for m in set(materials)}
        springs = np.array([stiffness[m] for m in materials])
    else:
        springs = np.full(contacts.size, math.inf)
    keys = np.stack([contacts, springs], axis=1)
    unique, inverse = np.unique(keys, axis=0, return_inverse=True)
    modes = [
        arrest_modes(probe, scene.hinge, float(c), contact_stiffness=float(k), **kw)
        for c, k in progress(unique, total=len(unique), desc="modes", enabled=show_progress)
    ]
    return modes, inverse.ravel()


@dataclass(frozen=True)
class ObjectModel:
    """One physics model of the touched rod, built for each distinct contact case.

    Attributes
    ----------
    name : str
        ``"coupled"``, ``"unilateral"`` or ``"friction"``.
    axis : {"x", "z"}
        The axis the model gives.
    effect : str or None
        The effect that asks for the model (None: every scene with ``object_modes``).
    build : callable
        ``build(case)``: the model of one contact case
        (:class:`~ebantenna.simulate.structure.ContactCase`).
    respond : callable or None
        ``respond(batch, models) -> (acceleration, rate)``: the axis, for a model stepped in
        time, at the rate it is computed (``(n, n_int)`` array, Hz), which the chip then reads
        at the sample instants; None for modes, which the modal sum reads
        (:data:`~ebantenna.simulate.simulator.CHAIN`, the responses).
    unless : str or None
        An effect that gives the same axis in time: when it is listed and the caller asked for no
        X modes (``x_modes=False``, as a data set build does), the model is left out.
    """

    name: str
    axis: str
    effect: str | None
    build: Callable
    respond: Callable | None = None
    unless: str | None = None

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name:
            raise TypeError(f"name must be a non-empty str, got {self.name!r}")
        check_choice("axis", self.axis, ("x", "z"))
        for field in ("effect", "unless"):
            value = getattr(self, field)
            if value is not None and value not in effect_names():
                raise ValueError(f"{field} must be None or an effect of effect_names(), got "
                                 f"{value!r}")
        if not callable(self.build):
            raise TypeError(f"build must be callable, got {type(self.build).__name__}")
        if self.respond is not None and not callable(self.respond):
            raise TypeError(f"respond must be callable or None, got {type(self.respond).__name__}")

    def wanted(self, scene: Scene, x_modes: bool) -> bool:
        """Whether ``scene`` needs this model (``x_modes`` as in
        :func:`~ebantenna.simulate.simulator.simulate_batch`)."""
        if not isinstance(scene, Scene):
            raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
        x_modes = check_bool("x_modes", x_modes)
        if self.effect is not None and not scene.has(self.effect):
            return False
        return x_modes or self.unless is None or not scene.has(self.unless)


#: The models of the touched rod (``object_modes``), in the order they are built for each
#: contact case. A model stepped in time (``respond`` set) gives its axis instead of the modes.
OBJECT_MODELS = (
    ObjectModel("coupled", "x", None, coupled_modes_of, unless="unilateral_contact"),
    ObjectModel("unilateral", "x", "unilateral_contact", strike_model_of, strike_axis),
    ObjectModel("friction", "z", "coulomb_friction", friction_model_of, friction_axis),
)


def _contact_cases(scene: Scene, probe: Probe, contact: float, rods: dict, pairs, object_loss):
    """The contact cases at one position: the probe reduced once, then each (material, preload).

    ``pairs`` lists the (material, preload) of the signals touching at ``contact``; yields one
    :class:`~ebantenna.simulate.structure.ContactCase` per distinct pair, in sorted order.
    ``rods`` holds each touched rod and its Craig-Bampton reduction by material: a rod not in it
    yet is reduced here, once for the whole batch.
    """
    obj = scene.effect("object_modes")
    reduced = _probe_reduction(probe, contact, scene.hinge, scene.n_elements, obj.probe_modes)
    for name, preload in sorted(set(pairs)):
        if name not in rods:
            rod = obj.rod(lookup_material(name))
            sub = rod_substructure(rod, n_elements=obj.rod_elements)
            if not object_loss:
                sub = dataclasses.replace(sub, loss_factor=0.0)
            rods[name] = (rod, craig_bampton(sub, obj.rod_modes))
        rod, rod_reduced = rods[name]
        stiffness, loss_factor = tube_on_rod_spring(probe, rod.material, obj.diameter, preload,
                                                    object_loss=object_loss)
        yield ContactCase(
            scene=scene,
            probe=probe,
            contact=contact,
            material=name,
            preload=preload,
            rod=rod,
            probe_reduction=reduced,
            rod_reduction=rod_reduced,
            stiffness=stiffness,
            loss_factor=loss_factor,
        )


#: The probe's reductions kept for reuse in this process, least recently used first, at most
#: :data:`_KEPT_BYTES` of arrays in all. A reduction depends only on the probe, the contact, the
#: hinge and the mesh, and a study's data sets touch the same contacts again (the controls
#: rebuild one design a dozen times, each effect switched off in turn, every one with the same
#: positions): 537 distinct contacts there, about 155 KB each with the paper's mesh.
_KEPT: OrderedDict = OrderedDict()
_KEPT_BYTES = 128 * 2**20
_kept_lock = threading.Lock()


def _probe_reduction(probe: Probe, contact: float, hinge, n_elements: int, n_modes: int):
    """The probe's Craig-Bampton reduction at ``contact``, computed once per process (see
    :data:`_KEPT`); its arrays are read-only, as they are shared."""
    key = (probe, contact, hinge, n_elements, n_modes)
    with _kept_lock:
        got = _KEPT.get(key)
        if got is not None:
            _KEPT.move_to_end(key)
            return got[0]
    sub = probe_substructure(probe, contact, hinge=hinge, n_elements=n_elements)
    reduced = craig_bampton(sub, n_modes)
    arrays = [reduced.stiffness, reduced.mass, reduced.basis, reduced.fixed_interface_omega,
              sub.stiffness, sub.mass, sub.nodes, sub.free]
    for a in arrays:
        a.flags.writeable = False
    with _kept_lock:
        _KEPT[key] = (reduced, sum(a.nbytes for a in arrays))
        total = sum(size for _, size in _KEPT.values())
        while total > _KEPT_BYTES and len(_KEPT) > 1:
            total -= _KEPT.popitem(last=False)[1][1]
    return reduced


def object_modes(scene: Scene, contacts, materials, preloads, show_progress, x_modes=True):
    """The models of the touched rod (the ``object_modes`` effect), coupled to the probe.

    Each rod is reduced once, the probe once per distinct contact position (and kept for the
    process's later calls: a study's data sets touch the same positions); what is left per
    (position, material, preload) is each model of :data:`OBJECT_MODELS` the scene needs.
    Returns the coupled modes (X), which case each signal uses, and the models stepped in time
    by name (``timed``, only those built); the parameters are those of :func:`object_terms`,
    ``preloads`` given.
    """
    _check_signal_inputs(scene, contacts, materials, preloads)
    if preloads is None or not scene.has("object_modes"):
        raise ValueError("object_modes needs a scene that lists object_modes, and the preloads")
    if show_progress is not None:
        show_progress = check_bool("show_progress", show_progress)
    x_modes = check_bool("x_modes", x_modes)
    probe = scene.probe
    if not scene.has("structural_damping"):
        probe = dataclasses.replace(probe, loss_factor=0.0)
    object_loss = scene.has("object_damping")
    models = [model for model in OBJECT_MODELS if model.wanted(scene, x_modes)]
    built = {model.name: [] for model in OBJECT_MODELS}
    rods = {}  # each rod reduced once, at its first contact case
    unique_c, inverse_c = np.unique(contacts, return_inverse=True)
    inverse_c = inverse_c.ravel()
    key_of = {}
    for i in progress(range(unique_c.size), desc="modes", enabled=show_progress):
        here = inverse_c == i
        pairs = zip(materials[here], preloads[here], strict=True)
        for case in _contact_cases(scene, probe, float(unique_c[i]), rods, pairs, object_loss):
            key_of[i, case.material, case.preload] = len(key_of)
            for model in models:
                built[model.name].append(model.build(case))
    inverse = np.array(
        [key_of[key] for key in zip(inverse_c, materials, preloads, strict=True)], dtype=int
    )
    modes = built.pop("coupled")
    return modes, inverse, {name: got for name, got in built.items() if got}


def _check_signal_inputs(scene, contacts, materials, preloads=None, **per_signal) -> int:
    """The number of signals, once every per-signal array (``per_signal`` by name, such as
    ``speeds`` and ``tilts``) is one finite entry per signal."""
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    arrays = {"contacts": contacts, **per_signal}
    if preloads is not None:
        arrays["preloads"] = preloads
    for name, value in arrays.items():
        if not isinstance(value, np.ndarray) or value.ndim != 1 or value.dtype.kind not in "fiu":
            raise TypeError(f"{name} must be a 1-D real ndarray, one entry per signal, got "
                            f"{type(value).__name__} {getattr(value, 'dtype', '')}")
        if not np.all(np.isfinite(value)):
            raise ValueError(f"{name} must be finite")
    if not isinstance(materials, np.ndarray) or materials.dtype.kind not in "UO":
        raise TypeError(f"materials must be an ndarray of material names, got "
                        f"{type(materials).__name__}")
    n = contacts.size
    for name, value in {**arrays, "materials": materials}.items():
        if value.shape != (n,):
            raise ValueError(f"{name} must have one entry per contact ({n}), got shape "
                             f"{value.shape}")
    for contact in np.unique(contacts):  # the one contact check of the probe model
        check_contact("contacts", float(contact), scene.probe.length)
    return n


def object_terms(scene: Scene, contacts, materials, speeds, preloads=None, show_progress=None,
                 x_modes=True):
    """The touched object's step of the simulator: its physics model, then X's terms per signal.

    The touched object is a rod coupled to the probe with ``object_modes`` (:func:`object_modes`)
    and rigid without (:func:`pinned_modes`); on a rigid contact the modes carry the probe's
    structural damping (:attr:`~ebantenna.simulate.Scene.probe_damping_ratio`). Each signal's
    row is its contact case's modes scaled by its sweep speed. Takes checked values (the
    simulator's public entries check them).

    Parameters
    ----------
    scene : Scene
    contacts, speeds : ndarray of shape (n,)
        Per-signal contact position (m) and sweep speed (rad/s).
    materials : ndarray of str, shape (n,)
        Per-signal material names.
    preloads : ndarray of shape (n,), optional
        Per-strike preloads, N (default: the ``object_modes`` effect's preload).
    show_progress : bool or None
        The progress bar over contact positions (None: on a terminal).
    x_modes : bool
        Build X's modes (False: only the models stepped in time give X).

    Returns
    -------
    x : ebantenna.simulate.modes.ModalTerms
        The modal parameters of X per signal.
    timed : dict
        The models stepped in time by name (:data:`OBJECT_MODELS`), only those built.
    inverse : ndarray of int, shape (n,)
        Which contact case each signal uses.
    """
    n = _check_signal_inputs(scene, contacts, materials, preloads, speeds=speeds)
    if show_progress is not None:
        show_progress = check_bool("show_progress", show_progress)
    x_modes = check_bool("x_modes", x_modes)
    # Many small eigenproblems: BLAS threads only add overhead (and thrash on a busy machine).
    with limited_threads(1, user_api=None):
        if scene.has("object_modes"):
            if preloads is None:
                preloads = np.full(n, scene.effect("object_modes").preload)
            modes, inverse, timed = object_modes(
                scene, contacts, materials, preloads, show_progress, x_modes
            )
        else:
            (modes, inverse), timed = pinned_modes(scene, contacts, materials, show_progress), {}
    # with object_modes the coupled modes carry every body's damping (zeta None: their own)
    zeta = None if scene.has("object_modes") else scene.probe_damping_ratio
    return x_terms(modes, inverse, speeds, zeta=zeta, preloads=preloads), timed, inverse


def signal_terms(
    scene: Scene, contacts, materials, speeds, tilts, preloads=None, show_progress=None,
    x_modes=True,
):  # fmt: skip
    """Both axes' modal terms, as the simulator's steps give them: Z's of the free probe
    (:func:`~ebantenna.simulate.modes.free_probe_terms`, driven across the sweep plane at each
    signal's speed and tilt), then X's and the models stepped in time of the touched object
    (:func:`object_terms`, whose parameters these are, with ``tilts``: each signal's tilt ratio).

    Returns
    -------
    x, z : ebantenna.simulate.modes.ModalTerms
        The modal parameters of X and Z per signal.
    timed : dict
        The models stepped in time by name, as in :func:`object_terms`.
    inverse : ndarray of int, shape (n,)
        Which contact case each signal uses, as in :func:`object_terms`.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.simulate import builtin_scene
    >>> from ebantenna.simulate.touched_object import signal_terms
    >>> scene = builtin_scene("ideal")
    >>> x, z, timed, inverse = signal_terms(scene, np.array([0.2]), np.array(["brass"]),
    ...                                     np.array([1.0]), np.array([0.0]))
    >>> x.frequencies().size > 0, timed
    (True, {})
    """
    _check_signal_inputs(scene, contacts, materials, preloads, speeds=speeds, tilts=tilts)
    z = free_probe_terms(scene, speeds, tilts)
    x, timed, inverse = object_terms(scene, contacts, materials, speeds, preloads, show_progress,
                                     x_modes)
    return x, z, timed, inverse


# ------------------------------------------------------------- the simulator's step
def _touched_object(_, batch) -> None:
    """The touched object: the modal parameters of X, and the models stepped in time; for the
    responses, which axis each of those gives, with its ``respond`` (:data:`OBJECT_MODELS`)."""
    batch.x, batch.timed, batch.inverse = object_terms(
        batch.scene,
        batch.contacts,
        batch.materials,
        batch.speeds,
        batch.preloads,
        batch.show_progress,
        batch.x_modes,
    )
    batch.responders = {model.axis: (model.respond, batch.timed[model.name])
                        for model in OBJECT_MODELS
                        if model.respond is not None and model.name in batch.timed}


#: The simulator's step of the touched object, written beside the models it runs: it takes
#: ``(effect, batch)`` and changes the simulator's
#: :class:`~ebantenna.simulate.simulator.SignalBatch` in place, with values the simulator
#: checked. :data:`ebantenna.simulate.simulator.CHAIN` puts it in order, and says why.
CHAIN_STEPS = {"touched_object": _touched_object}
