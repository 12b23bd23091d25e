"""Scenes: what is simulated, down to the list of effects.

A :class:`Scene` fixes the probe and its supports, the contact position and the touched material,
the excitation (the servo's sweep, arrested by the object), the acquisition (sampling frequency and
duration) and the explicit list of effects. Two scenes are built in (:func:`builtin_scene`):

``ideal``
    The modal response only: the bare tube, rigid contact, no damping, no sensor.
``paper``
    The paper's rig: the tube with the MPU6050 board at its tip touching a rod of the given
    material, every effect of :mod:`ebantenna.simulate.effects` at its documented default but
    those in ``PAPER_LEAVES_OUT``, the probe's and the rod's modes up to 3 kHz, which the
    sensor's filter and decimation fold into the 0-500 Hz band as on the chip.

A scene makes its effects from their names, parameters or instances (:func:`make_effects`,
each by :func:`make_effect`), in the order the simulator applies them. Scenes are saved to and
loaded from TOML or JSON (:meth:`Scene.save`, :func:`load_scene`).
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

from .._validate import (
    check_choice,
    check_int,
    check_nonnegative,
    check_path,
    check_positive,
    load_json,
    output_path,
    read_text,
)
from ..fem.assembly import HINGES
from ..fem.guards import check_contact, check_resolvable
from ..probe import Probe, material
from .effects import EFFECT_TYPES, GY521_MASS, effect_names

#: Effects the ``paper`` scene leaves out: ``contact_compliance``, because the rod's own contact
#: spring (in ``object_modes``) replaces it, and ``coulomb_friction``, because no friction
#: coefficient of the tube on four of the five materials is tabulated (a scene that asks for it
#: lists it with its own). Its contact only pushes (``unilateral_contact``); what a linear
#: contact would change is measured by ``ebantenna reproduce``.
#: ``hertz_contact`` too: it costs several times the linearised contact's strike (``ebantenna
#: bench``); ``ebantenna reproduce`` measures what it changes on the controls' design.
PAPER_LEAVES_OUT = frozenset({"contact_compliance", "coulomb_friction", "hertz_contact"})

__all__ = ["Scene", "builtin_scene", "scene_names", "load_scene", "resolve_scene", "make_effect",
           "make_effects"]

#: Effects that need another effect listed with them: (effect, needed, why).
EFFECT_NEEDS = (
    ("object_damping", "object_modes", "it damps the touched rod's modes"),
    (
        "unilateral_contact",
        "object_modes",
        "it is the contact with the touched rod that only pushes",
    ),
    ("hertz_contact", "unilateral_contact", "it is the force law of the strike's contact"),
    ("coulomb_friction", "object_modes", "its normal force is the rod contact's preload"),
    ("preload_scatter", "object_modes", "the preload it scatters is the rod contact's"),
)

#: Every effect type by its name (:func:`make_effect`).
_BY_NAME = {cls.name: cls for cls in EFFECT_TYPES}

#: Most samples one simulated recording may have.
MAX_SAMPLES = 10_000_000


@dataclass(frozen=True)
class Scene:
    """Everything the simulator needs, validated on construction.

    Parameters
    ----------
    name : str
        A label saved with the results.
    probe : Probe
        The tube (and its tip mass, when the ``tip_mass`` effect is listed).
    hinge : {"clamped", "pinned"} or float
        The hinge at the servo: clamped, pinned or a rotational spring in N m/rad.
    contact : float
        Contact position from the hinge, m, inside ``(0, L)``.
    material : str
        Touched material, one of :func:`ebantenna.probe.material_names` (stored by its canonical
        name).
    fs : float
        Sampling frequency, Hz: at least twice ``max_frequency``, or with the ``dlpf`` effect a
        whole divisor of its internal rate. Default 1 kHz (the paper,
        section 3).
    duration : float
        Length of the recording after the arrest, s. Default 1 s: an assumption, long enough for
        the paper's 512-sample spectra and for the damped ringing to fade.
    sweep_speed : float
        Angular speed ``Omega`` of the sweep when the probe hits the object, rad/s. Default
        0.5 rad/s: an assumption, a slow search sweep (the MG996R turns at up to about 6 rad/s:
        0.17 s per 60 degrees at 4.8 V in its data sheet) that keeps the paper rig's readings
        inside +-16 g with the contact up to about 0.34 m from the hinge; from about 0.345 m on
        some of the metals' strikes reach the rail, up to 26 g (steel at 0.39 m), and the
        ``paper`` scene's ``clipping`` holds those samples there (the data set counts them:
        ``samples_saturated``).
    tilt_ratio : float
        Angular speed across the sweep plane at the contact, as a fraction of ``sweep_speed``
        (dimensionless): what drives the Z axis (see :mod:`ebantenna.simulate.modes`). Default
        0.25: an assumption for a point on the elliptical search path (the paper's Fig. 7).
    effects : sequence of str or effect instances, or dict
        The effects to simulate (names, instances, or ``{name: {parameter: value}}``); stored as
        instances in the order they are applied. None listed: the modal response only.
    n_elements : int
        Beam elements of the FEM model. Default 40: the modes below 480 Hz are then within
        1e-5 (relative) of a 160-element mesh.
    n_modes : int
        Modes the FEM computes; they must reach ``max_frequency``. Default 8.
    max_frequency : float
        Only modes below this frequency are simulated, Hz. Default 480 Hz, just under the Nyquist
        frequency of 1 kHz sampling. With the ``dlpf`` effect the modes are sampled at the chip's
        internal rate and may reach its Nyquist frequency: what the filter lets through above
        ``fs / 2`` then aliases, as on the chip (the ``paper`` scene simulates up to 3 kHz, where
        the 260 Hz filter's gain has fallen below 1 %).

    Examples
    --------
    >>> from ebantenna.simulate import Scene
    >>> scene = Scene(contact=0.25, material="Aluminum", effects=["gravity"])
    >>> scene.material, scene.effect_names, scene.n_samples
    ('aluminium', ('gravity',), 1000)
    >>> scene.with_(fs=500.0)
    Traceback (most recent call last):
    ...
    ValueError: fs must be at least twice max_frequency (2 x 480 Hz = 960 Hz), got 500.0 Hz
    """

    name: str = "custom"
    probe: Probe = field(default_factory=Probe)
    hinge: str | float = "clamped"
    contact: float = 0.17
    material: str = "brass"
    fs: float = 1000.0
    duration: float = 1.0
    sweep_speed: float = 0.5
    tilt_ratio: float = 0.25
    effects: tuple = ()
    n_elements: int = 40
    n_modes: int = 8
    max_frequency: float = 480.0

    def __post_init__(self):
        self._check_setup()
        self._check_acquisition()
        object.__setattr__(self, "effects", make_effects(self.effects))
        self._check_effects()
        self._check_rates()

    def _put(self, name, value):
        object.__setattr__(self, name, value)

    def _check_setup(self):
        """The label, the probe, its hinge, the contact and the touched material."""
        if not isinstance(self.name, str):
            raise TypeError(f"name must be a string, got {self.name!r}")
        if not isinstance(self.probe, Probe):
            raise TypeError(f"probe must be a Probe, got {type(self.probe).__name__}")
        if isinstance(self.hinge, str):
            if self.hinge not in HINGES:
                raise ValueError(
                    f"hinge must be one of {', '.join(HINGES)} or a rotational stiffness > 0 "
                    f"(N m/rad); got {self.hinge!r}"
                )
        else:
            self._put("hinge", check_positive("hinge (rotational stiffness, N m/rad)", self.hinge))
        self._put("contact", check_contact("contact", self.contact, self.probe.length))
        self._put("material", material(self.material).name)

    def _check_acquisition(self):
        """The band, the sampling, the sweep and the FEM model's size."""
        self._put("max_frequency", check_positive("max_frequency", self.max_frequency))
        fs = check_positive("fs", self.fs)
        self._put("fs", fs)
        self._put("duration", check_positive("duration", self.duration))
        if self.n_samples < 2:
            raise ValueError(
                f"duration * fs must give at least 2 samples, got {self.duration!r} s at {fs:g} Hz"
            )
        if self.n_samples > MAX_SAMPLES:
            raise ValueError(
                f"duration * fs must give at most {MAX_SAMPLES:.0e} samples (a recording of "
                f"{8 * MAX_SAMPLES / 1e6:g} MB per axis), got duration={self.duration!r} s at "
                f"{fs:g} Hz"
            )
        self._put("sweep_speed", check_positive("sweep_speed", self.sweep_speed))
        self._put("tilt_ratio", check_nonnegative("tilt_ratio", self.tilt_ratio))
        n_elements = check_resolvable(check_int("n_elements", self.n_elements, minimum=2))
        self._put("n_elements", n_elements)
        self._put("n_modes", check_int("n_modes", self.n_modes, minimum=1))

    def _check_effects(self):
        """The listed effects agree with the probe and with one another."""
        names = self.effect_names
        if ("tip_mass" in names) != (self.probe.tip_mass > 0):
            raise ValueError(
                "the 'tip_mass' effect must be listed exactly when the probe carries a tip mass; "
                f"got probe.tip_mass={self.probe.tip_mass!r} kg with effects {list(names)}"
            )
        for effect, needed, why in EFFECT_NEEDS:
            if effect in names and needed not in names:
                raise ValueError(f"effect '{effect}' needs '{needed}' ({why})")
        if "object_modes" in names and "contact_compliance" in names:
            raise ValueError(
                "effects 'object_modes' and 'contact_compliance' both set the contact spring; "
                "list one of them"
            )
        if "clipping" in names and "quantisation" in names:
            if self.effect("clipping").range_g != self.effect("quantisation").range_g:
                raise ValueError("clipping and quantisation must use the same range_g")

    def _check_rates(self):
        """The modes and the hum within the rates that sample them."""
        dlpf = self.effect("dlpf")
        if dlpf is not None:  # the modes are sampled at the chip's internal rate, then decimated
            dlpf.divider(self.fs)
            rate, what = dlpf.internal_rate, "the dlpf's internal_rate"
        else:
            rate, what = self.fs, "fs"
        if rate < 2 * self.max_frequency:
            raise ValueError(
                f"{what} must be at least twice max_frequency (2 x {self.max_frequency:g} Hz = "
                f"{2 * self.max_frequency:g} Hz), got {rate!r} Hz"
            )
        hum = self.effect("mains_hum")
        if hum is not None and not hum.frequency < self.fs / 2:
            raise ValueError(
                f"mains_hum frequency {hum.frequency:g} Hz must be below fs/2 = {self.fs / 2:g} Hz"
            )

    # ---------------------------------------------------------------------------------------------
    @property
    def n_samples(self) -> int:
        """Number of samples, ``round(duration * fs)``."""
        return int(round(self.duration * self.fs))

    @property
    def effect_names(self) -> tuple[str, ...]:
        """Names of the listed effects, in the order they are applied."""
        return tuple(e.name for e in self.effects)

    @property
    def probe_damping_ratio(self) -> float:
        """Damping ratio of the probe's modes (dimensionless): the ``structural_damping``
        effect's, 0 when it is not listed."""
        damping = self.effect("structural_damping")
        return damping.damping_ratio(self.probe) if damping is not None else 0.0

    def has(self, name: str) -> bool:
        """Whether the effect ``name`` (one of :func:`~ebantenna.simulate.effect_names`) is
        listed."""
        return _check_effect_name(name) in self.effect_names

    def effect(self, name: str):
        """The listed effect called ``name`` (one of :func:`~ebantenna.simulate.effect_names`),
        or None."""
        _check_effect_name(name)
        return next((e for e in self.effects if e.name == name), None)

    def with_(self, **changes) -> Scene:
        """A copy with some fields replaced, validated like a new scene.

        Examples
        --------
        >>> from ebantenna.simulate import builtin_scene
        >>> builtin_scene("paper").with_(contact=0.25, material="wood").contact
        0.25
        """
        self._check_fields(changes)
        return dataclasses.replace(self, **changes)

    def _check_fields(self, changes) -> None:
        """Every name of ``changes`` is a field of the scene (a misspelt one is never ignored)."""
        valid = [f.name for f in dataclasses.fields(self)]
        unknown = sorted(set(changes) - set(valid))
        if unknown:
            raise TypeError(
                f"Scene has no field(s) {', '.join(unknown)}; fields: {', '.join(valid)}"
            )

    # ---------------------------------------------------------------------------------------------
    def to_dict(self) -> dict:
        """A JSON-ready description: scalars, ``probe`` and ``effects`` ({name: parameters})."""
        return {**{f.name: getattr(self, f.name) for f in dataclasses.fields(self)},
                "probe": self.probe.to_dict(),
                "effects": {e.name: e.parameters() for e in self.effects}}

    @classmethod
    def from_dict(cls, data: dict) -> Scene:
        """Build a scene from :meth:`to_dict`'s layout; missing fields take their defaults."""
        if not isinstance(data, dict):
            raise TypeError(f"a scene must be a table/dict, got {type(data).__name__}")
        valid = [f.name for f in dataclasses.fields(cls)]
        unknown = sorted(set(data) - set(valid))
        if unknown:
            raise ValueError(
                f"unknown scene field(s) {', '.join(unknown)}; fields: {', '.join(valid)}"
            )
        data = dict(data)
        if "probe" in data:
            probe = data["probe"]
            if not isinstance(probe, dict):
                raise TypeError("scene field 'probe' must be a table/dict of Probe parameters")
            probe_fields = {f.name for f in dataclasses.fields(Probe)}
            bad = sorted(set(probe) - probe_fields)
            if bad:
                raise ValueError(
                    f"unknown probe field(s) {', '.join(bad)}; "
                    f"fields: {', '.join(sorted(probe_fields))}"
                )
            data["probe"] = Probe(**probe)
        return cls(**data)

    def save(self, path) -> Path:
        """Save as TOML (``.toml``) or JSON (any other suffix); returns the path.

        The path must be a ``str`` or ``os.PathLike`` naming a file in a directory that exists.
        """
        path = output_path("path", path, "")
        data = self.to_dict()
        if path.suffix.lower() == ".toml":
            path.write_text(_to_toml(data), encoding="utf-8")
        else:
            path.write_text(json.dumps(data, indent=2) + "\n", encoding="utf-8")
        return path


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


def _check_effect_name(name) -> str:
    """``name`` if it names an effect of the package (a misspelt one is never "not listed")."""
    return check_choice("name", name, effect_names())


def _toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value)  # a JSON string is a valid TOML basic string
    raise TypeError(f"cannot write {value!r} to TOML")


def _to_toml(data: dict) -> str:
    lines = [f"{k} = {_toml_value(v)}" for k, v in data.items() if not isinstance(v, dict)]
    lines += ["", "[probe]"] + [f"{k} = {_toml_value(v)}" for k, v in data["probe"].items()]
    for name, params in data["effects"].items():
        # TOML has no null: a parameter at None (its default) is left out, and read back as None.
        lines += ["", f"[effects.{name}]"] + [
            f"{k} = {_toml_value(v)}" for k, v in params.items() if v is not None
        ]
    if not data["effects"]:
        lines += ["", "[effects]"]
    return "\n".join(lines) + "\n"


def load_scene(path) -> Scene:
    """Load a scene saved by :meth:`Scene.save` (TOML by suffix ``.toml``, otherwise JSON).

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    TypeError
        If ``path`` is not a ``str`` or ``os.PathLike`` (bytes are refused), or a field has the
        wrong type.
    ValueError
        Naming the file, if it is not a regular file (a directory, a FIFO), is longer than a
        scene can be, is not UTF-8 text, not valid TOML or JSON, nests too deeply, or does not
        hold one table; or if a field is unknown or out of its range.
    """
    path = Path(check_path("path", path))
    text = read_text(path, "a scene file")
    if path.suffix.lower() == ".toml":
        try:
            import tomllib  # novermin (guarded: Python 3.10 falls back to tomli below)
        except ModuleNotFoundError:  # Python 3.10: the same parser, from PyPI
            import tomli as tomllib
        try:
            data = tomllib.loads(text)
        except (tomllib.TOMLDecodeError, RecursionError) as exc:
            raise ValueError(f"{path}: not valid TOML: {exc}") from None
    else:
        data = load_json(text, path, "a scene file")
    if not isinstance(data, dict):
        kind = type(data).__name__
        raise ValueError(f"{path}: a scene file holds one table/object, not a {kind}")
    try:
        return Scene.from_dict(data)
    except (TypeError, ValueError) as exc:  # a field out of its range: say in which file
        raise (TypeError if isinstance(exc, TypeError) else ValueError)(f"{path}: {exc}") from None


def scene_names() -> tuple[str, ...]:
    """Names of the built-in scenes."""
    return ("ideal", "paper")


def builtin_scene(name: str) -> Scene:
    """A built-in scene: ``"ideal"`` (modal response only) or ``"paper"`` (the paper's rig).

    Both touch brass 17 cm from the hinge, as in the paper's Fig. 1.

    Examples
    --------
    >>> from ebantenna.simulate import builtin_scene
    >>> builtin_scene("ideal").effects
    ()
    >>> builtin_scene("paper").probe.tip_mass
    0.0025
    """
    if name == "ideal":
        return Scene(name="ideal")
    if name == "paper":
        return Scene(
            name="paper",
            probe=Probe(tip_mass=GY521_MASS),
            effects=tuple(cls.name for cls in EFFECT_TYPES if cls.name not in PAPER_LEAVES_OUT),
            n_modes=16,
            max_frequency=3000.0,
        )
    raise ValueError(f"scene must be one of {', '.join(scene_names())}; got {name!r}")


def resolve_scene(name_or_path) -> Scene:
    """A built-in scene by name, or a scene file (TOML or JSON) by path."""
    text = check_path("scene", name_or_path)
    if text in scene_names():
        return builtin_scene(text)
    path = Path(text)
    if not path.is_file():
        raise ValueError(
            f"scene must be one of {', '.join(scene_names())} or an existing .toml/.json file; "
            f"got {str(name_or_path)!r}"
        )
    return load_scene(path)
