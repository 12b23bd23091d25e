"""The touched object's physics models: which modes, or which model stepped in time, each gives.

Without the ``object_modes`` effect the touched object is rigid: :func:`pinned_modes`, the probe
arrested by a pin (or by the ``contact_compliance`` spring), one FEM solve per distinct contact
and spring. With it, :func:`object_modes` reduces each touched rod once and the probe once per
distinct contact position (Craig-Bampton), and builds, for each distinct (contact, material,
preload) -- a :class:`ContactCase` -- every model of :data:`OBJECT_MODELS` the scene needs:

``coupled``
    X's modes: probe and rod joined by the contact spring
    (:func:`~ebantenna.simulate.modes.coupled_arrest_modes`).
``unilateral``
    X struck through a contact that only pushes, stepped in time between contact events
    (``unilateral_contact``, :mod:`ebantenna.simulate.strikes`).
``friction``
    Z held by dry friction along the rod, stepped in time between stick and slip
    (``coulomb_friction``, :mod:`ebantenna.simulate.stick_slip`).

A new model of the touched rod is one entry of :data:`OBJECT_MODELS`. Every function here takes
values checked by the simulator's public entries (:mod:`ebantenna.simulate.simulator`).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .._progress import progress
from ..fem.coupling import craig_bampton, probe_substructure, rod_substructure
from ..probe import Probe
from ..probe import material as lookup_material
from .modes import ArrestModes, arrest_modes, coupled_arrest_modes
from .scene import Scene
from .stick_slip import friction_axis, friction_model
from .strikes import strike_model, unilateral_axis

__all__ = [
    "ContactCase",
    "ObjectModel",
    "OBJECT_MODELS",
    "pinned_modes",
    "object_modes",
]


def pinned_modes(scene: Scene, contacts, materials, show_progress):
    """Arrest modes on a rigid object (a pin, or the ``contact_compliance`` spring).

    One FEM solve per distinct (contact, spring); takes checked values.
    """
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


@dataclass(frozen=True, eq=False)
class ContactCase:
    """One distinct (contact position, material, preload) of a batch on a rod (``object_modes``).

    What every model of the touched rod needs: the bodies, their Craig-Bampton reductions and
    the contact spring. Built by the simulator from checked values.

    Attributes
    ----------
    scene : Scene
        The scene simulated.
    probe : Probe
        The probe (without its loss factor unless ``structural_damping`` is listed).
    contact : float
        Contact position from the hinge, m.
    material : str
        Canonical name of the touched material.
    preload : float
        The contact's static force, N.
    rod : Rod
        The touched rod.
    probe_reduction, rod_reduction : ebantenna.fem.coupling.CraigBampton
        The two bodies reduced at the contact (:func:`ebantenna.fem.coupling.craig_bampton`).
    stiffness : float
        The contact spring under ``preload``, N/m.
    loss_factor : float
        The contact's loss factor (dimensionless).
    """

    scene: Scene
    probe: Probe
    contact: float
    material: str
    preload: float
    rod: object
    probe_reduction: object
    rod_reduction: object
    stiffness: float
    loss_factor: float


def _coupled_model(case: ContactCase) -> ArrestModes:
    """The ``coupled`` model: the arrest modes of probe and rod joined by the contact spring."""
    return coupled_arrest_modes(
        case.probe,
        case.scene.hinge,
        case.contact,
        case.rod,
        probe_reduction=case.probe_reduction,
        rod_reduction=case.rod_reduction,
        contact_stiffness=case.stiffness,
        contact_loss_factor=case.loss_factor,
        max_frequency=case.scene.max_frequency,
    )


def _unilateral_model(case: ContactCase):
    """The ``unilateral`` model: the same reductions, struck through a contact that only pushes
    (with ``hertz_contact``: its force law the Hertz law's chords, not the linearised spring)."""
    spring = case.stiffness
    hertz = case.scene.effect("hertz_contact")
    if hertz is not None:
        diameter = case.scene.effect("object_modes").diameter
        spring = hertz.spring(case.rod.material, case.probe, diameter, case.preload)
    return strike_model(
        case.probe_reduction,
        case.rod_reduction,
        case.contact,
        spring,
        case.preload,
        case.scene.max_frequency,
    )


def _friction_model(case: ContactCase):
    """The ``friction`` model: Z along the rod, held by dry friction under the preload."""
    return friction_model(case.probe_reduction, case.preload, case.scene.max_frequency)


def _strike_axis(batch, models) -> np.ndarray:
    """X from the ``unilateral`` strikes; records each strike's contacts after the first."""
    ax, restrikes = unilateral_axis(batch.scene, models, batch.inverse, batch.speeds, batch.when)
    batch.x = dataclasses.replace(batch.x, restrikes=restrikes)
    return ax


def _friction_axis(batch, models) -> np.ndarray:
    """Z from the ``friction`` model: stick and slip along the rod, at the tilt rotation's speed."""
    return friction_axis(batch.scene, models, batch.inverse, batch.tilts * batch.speeds, batch.when)


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
        ``build(case: ContactCase)``: the model of one contact case.
    respond : callable or None
        ``respond(batch, models) -> (n, n_samples) array``: the axis, for a model stepped in
        time; None for modes, which the modal sum reads
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

    def wanted(self, scene: Scene, x_modes: bool) -> bool:
        """Whether ``scene`` needs this model (``x_modes`` as in
        :func:`~ebantenna.simulate.simulator.simulate_batch`)."""
        if self.effect is not None and not scene.has(self.effect):
            return False
        return x_modes or self.unless is None or not scene.has(self.unless)


#: The models of the touched rod (``object_modes``), in the order they are built for each
#: contact case. A model stepped in time (``respond`` set) gives its axis instead of the modes.
OBJECT_MODELS = (
    ObjectModel("coupled", "x", None, _coupled_model, unless="unilateral_contact"),
    ObjectModel("unilateral", "x", "unilateral_contact", _unilateral_model, _strike_axis),
    ObjectModel("friction", "z", "coulomb_friction", _friction_model, _friction_axis),
)


def _reduced_rods(scene: Scene, materials, object_loss: bool) -> dict:
    """Each touched rod and its Craig-Bampton reduction, once per material."""
    obj = scene.effect("object_modes")
    rods = {}
    for name in sorted(set(materials)):
        rod = obj.rod(lookup_material(name))
        sub = rod_substructure(rod, n_elements=obj.rod_elements)
        if not object_loss:
            sub = dataclasses.replace(sub, loss_factor=0.0)
        rods[name] = (rod, craig_bampton(sub, obj.rod_modes))
    return rods


def _contact_cases(scene: Scene, probe: Probe, contact: float, rods: dict, pairs, object_loss):
    """The contact cases at one position: the probe reduced once, then each (material, preload).

    ``pairs`` lists the (material, preload) of the signals touching at ``contact``; yields one
    :class:`ContactCase` per distinct pair, in sorted order.
    """
    obj = scene.effect("object_modes")
    sub = probe_substructure(probe, contact, hinge=scene.hinge, n_elements=scene.n_elements)
    reduced = craig_bampton(sub, obj.probe_modes)
    for name, preload in sorted(set(pairs)):
        rod, rod_reduced = rods[name]
        yield ContactCase(
            scene=scene,
            probe=probe,
            contact=contact,
            material=name,
            preload=preload,
            rod=rod,
            probe_reduction=reduced,
            rod_reduction=rod_reduced,
            stiffness=obj.contact_stiffness(rod.material, probe, preload),
            loss_factor=obj.contact_loss_factor(
                rod.material, probe, object_loss=object_loss, preload=preload
            ),
        )


def object_modes(scene: Scene, contacts, materials, preloads, show_progress, x_modes=True):
    """The models of the touched rod (the ``object_modes`` effect), coupled to the probe.

    Each rod is reduced once, the probe once per distinct contact position; what is left per
    (position, material, preload) is each model of :data:`OBJECT_MODELS` the scene needs.
    Takes checked values. Returns the coupled modes (X), which case each signal uses, and the
    models stepped in time by name (``timed``, only those built).
    """
    probe = scene.probe
    if not scene.has("structural_damping"):
        probe = dataclasses.replace(probe, loss_factor=0.0)
    object_loss = scene.has("object_damping")
    rods = _reduced_rods(scene, materials, object_loss)
    models = [model for model in OBJECT_MODELS if model.wanted(scene, x_modes)]
    built = {model.name: [] for model in OBJECT_MODELS}
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
