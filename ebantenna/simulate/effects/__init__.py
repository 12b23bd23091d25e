"""The effects a scene may call for, each a small frozen dataclass with its physics and sources.

A scene lists the effects it wants; an effect that is not listed is not computed at all. The modal
response itself (superposition of the FEM modes after the arrest, see :mod:`.modes`) is not an
effect: it is always there. Effects fall in two groups:

*Physics of the probe, the contact and the touched object* (:mod:`.physics`, :mod:`.objects`),
which change the modal parameters: :class:`StructuralDamping`, :class:`ContactCompliance` (a rigid
object behind a spring), :class:`ObjectModes` (the object as a rod with its own modes, coupled to
the probe), :class:`ObjectDamping` (that rod's material damping), :class:`PreloadScatter` (the
contact's preload from strike to strike), :class:`UnilateralContact` (the probe lifts off and
strikes again), :class:`HertzContact` (the strike's contact follows the Hertz law),
:class:`CoulombFriction` (the probe sticks to the rod and slips along it),
:class:`TipMass`.

*The sensor and the acquisition* (:mod:`.sensor`), which act on the sampled signals, in this order:
:class:`ClockJitter` (when the samples are taken), :class:`Gravity`, :class:`MainsHum`,
:class:`SensorNoise`, :class:`LowPassFilter` (the MPU6050's DLPF, at its internal rate, and the
decimation), :class:`SensorDrift` (offset and gain between sessions), :class:`Clipping`,
:class:`Quantisation`, :class:`SteadyStateKalman` (on the Raspberry Pi).

The simulator applies them in one loop over an ordered list of steps,
:data:`ebantenna.simulate.simulator.CHAIN`; :mod:`~ebantenna.simulate.simulator` gives the order
and why (the filter is linear, so it acts on each part of the signal as that part enters). Each
effect is a step of that list or is read by one (a step's ``reads``). The touched rod's models
are the list :data:`ebantenna.simulate.touched_object.OBJECT_MODELS`. A new effect is a class
here, an entry of :data:`EFFECT_TYPES` and one step in the simulator's list (or a name in the
``reads`` of the step that uses it).

All arrays here have shape ``(n_signals, n_samples)``: every effect is vectorised over signals.
Random effects draw from a :class:`numpy.random.Generator` per signal that the simulator makes
from the signal's seed and the effect's own ``stream`` number, so that adding or removing one
effect never changes the random numbers of another.
"""

from __future__ import annotations

from .hertz import HertzContact
from .objects import (
    CoulombFriction,
    ObjectDamping,
    ObjectModes,
    PreloadScatter,
    UnilateralContact,
)
from .physics import GY521_MASS, ContactCompliance, StructuralDamping, TipMass
from .sensor import (
    DLPF_BANDWIDTHS,
    STANDARD_GRAVITY,
    Clipping,
    ClockJitter,
    Gravity,
    LowPassFilter,
    MainsHum,
    Quantisation,
    SensorDrift,
    SensorNoise,
    SteadyStateKalman,
    read_through_dlpf,
)

__all__ = [
    "STANDARD_GRAVITY",
    "GY521_MASS",
    "DLPF_BANDWIDTHS",
    "StructuralDamping",
    "ContactCompliance",
    "ObjectModes",
    "ObjectDamping",
    "PreloadScatter",
    "UnilateralContact",
    "HertzContact",
    "CoulombFriction",
    "SensorDrift",
    "TipMass",
    "ClockJitter",
    "Gravity",
    "MainsHum",
    "SensorNoise",
    "LowPassFilter",
    "Clipping",
    "Quantisation",
    "SteadyStateKalman",
    "read_through_dlpf",
    "EFFECT_TYPES",
    "effect_names",
    "make_effect",
    "make_effects",
]

#: Every effect type, in the order the simulator applies them.
EFFECT_TYPES = (
    StructuralDamping,
    ContactCompliance,
    ObjectModes,
    ObjectDamping,
    PreloadScatter,
    UnilateralContact,
    HertzContact,
    CoulombFriction,
    TipMass,
    ClockJitter,
    Gravity,
    MainsHum,
    SensorNoise,
    LowPassFilter,
    SensorDrift,
    Clipping,
    Quantisation,
    SteadyStateKalman,
)

_BY_NAME = {cls.name: cls for cls in EFFECT_TYPES}


def effect_names() -> tuple[str, ...]:
    """Names of every effect, in the order the simulator applies them.

    Examples
    --------
    >>> effect_names()[:2]
    ('structural_damping', 'contact_compliance')
    """
    return tuple(_BY_NAME)


def make_effect(effect, params: dict | None = None):
    """An effect instance from a name (with optional parameters) or an instance.

    Raises
    ------
    ValueError
        For an unknown name, listing the valid ones.

    Examples
    --------
    >>> make_effect("sensor_noise", {"density": 0.01})
    SensorNoise(density=0.01)
    """
    if isinstance(effect, EFFECT_TYPES):
        if params:
            raise TypeError("parameters can only be given with an effect's name, not an instance")
        return effect
    if not isinstance(effect, str):
        raise TypeError(f"an effect must be a name or an effect instance, got {effect!r}")
    if effect not in _BY_NAME:
        raise ValueError(f"unknown effect {effect!r}; valid effects: {', '.join(_BY_NAME)}")
    return _BY_NAME[effect].from_parameters(params or {})


def make_effects(effects) -> tuple:
    """A scene's effects, each made by :func:`make_effect`, in the order the simulator applies
    them (:func:`effect_names`).

    Parameters
    ----------
    effects : sequence or dict
        Effect names or instances, or ``{name: {parameter: value}}``; none listed twice.

    Raises
    ------
    TypeError
        For a string or anything else that is not a sequence of names or instances.
    ValueError
        For an unknown name, or an effect listed twice.

    Examples
    --------
    >>> [e.name for e in make_effects(["sensor_noise", "gravity"])]
    ['gravity', 'sensor_noise']
    """
    if isinstance(effects, str | bytes):
        raise TypeError("effects must be a sequence of effect names or instances, not a string")
    if isinstance(effects, dict):
        items = [make_effect(name, params) for name, params in effects.items()]
    else:
        try:
            items = [make_effect(e) for e in effects]
        except TypeError as exc:
            if "not iterable" in str(exc):
                raise TypeError(f"effects must be a sequence, got {effects!r}") from exc
            raise
    names = [e.name for e in items]
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        raise ValueError(f"effects must not repeat; {', '.join(duplicates)} listed twice")
    position = {name: i for i, name in enumerate(effect_names())}
    return tuple(sorted(items, key=lambda e: position[e.name]))
