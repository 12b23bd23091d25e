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
``reads`` of the step that uses it). A scene makes its effects from their names
(:func:`ebantenna.simulate.scene.make_effects`).

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

def effect_names() -> tuple[str, ...]:
    """Names of every effect, in the order the simulator applies them.

    Examples
    --------
    >>> effect_names()[:2]
    ('structural_damping', 'contact_compliance')
    """
    return tuple(cls.name for cls in EFFECT_TYPES)
