"""What a recording session touches, in which order: materials x contact distances x repetitions.

A :class:`Plan` lists the touches of a session, one :class:`Touch` each, material by material (the
operator places one material, then works along the probe), contact distance by distance, and
repetition by repetition. It comes from the paper's protocol (built by the ``record`` command) or
from a *plan file*, TOML (``.toml``) or JSON (any other suffix)::

    name = "bench-check"              # letters, digits and '-'
    materials = ["brass", "pvc"]      # names of ebantenna.probe.MATERIALS
    contacts_m = [0.10, 0.20, 0.30]   # contact distances from the hinge, m
    repetitions = 3                   # touches per material and distance
    probe_length = 0.40               # m; every contact lies inside (0, probe_length)

    [search]                          # optional: settings of the search, as SearchConfig names
    threshold = 2.0                   # m/s^2
    duration = 1.0                    # s recorded after the contact

Each touch's *key* (``"brass/0.1000/2"``) names it in the session's manifest, so that a session
that resumes knows which touches it has made.

Examples
--------
>>> plan = Plan("demo", ("brass", "pvc"), (0.1, 0.2), 2)
>>> len(plan), plan[0].key, plan[-1].key
(8, 'brass/0.1000/0', 'pvc/0.2000/1')
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field, fields
from pathlib import Path

from .._validate import check_int, check_nonnegative, check_positive, check_real
from ..chips.mpu6050 import RESET_WAIT
from ..chips.pca9685 import OSCILLATOR_STARTUP
from ..probe import material as lookup_material
from .pantilt import SearchConfig

__all__ = ["Touch", "Plan", "load_plan", "session_time", "SEARCH_SETTINGS", "MOVE_SECONDS"]

#: Assumed time for the operator to move the object to a new distance or material, s.
MOVE_SECONDS = 30.0

#: The :class:`~ebantenna.device.pantilt.SearchConfig` settings a plan file may set (numbers).
SEARCH_SETTINGS = tuple(f.name for f in fields(SearchConfig) if f.name != "path")


@dataclass(frozen=True)
class Touch:
    """One touch of a session.

    Attributes
    ----------
    index : int
        Its place in the plan, from 0.
    material : str
        The material to place.
    contact : float
        Contact distance from the hinge, m.
    repetition : int
        Repetition number at this material and distance, from 0.
    simulation : dict
        For a simulated rig only: what the simulator varies from touch to touch
        (``contact_true``, ``sweep_speed``, ``tilt_ratio``, ``seed``); empty on the real rig.
    """

    index: int
    material: str
    contact: float
    repetition: int
    simulation: dict = field(default_factory=dict, compare=False)

    @property
    def key(self) -> str:
        """The name of the touch in the manifest: ``material/contact in m/repetition``."""
        return f"{self.material}/{self.contact:.4f}/{self.repetition}"

    def labels(self, probe_length: float) -> dict:
        """The labels a recording of this touch carries (JSON values)."""
        return {"material": self.material, "contact": self.contact,
                "ratio": self.contact / probe_length, "repetition": self.repetition,
                "touch": self.index, "touch_key": self.key}


@dataclass(frozen=True)
class Plan:
    """The touches of a session.

    Parameters
    ----------
    name : str
        Letters, digits and '-'.
    materials : tuple of str
        Materials, in the order the operator places them.
    contacts : tuple of float
        Contact distances from the hinge, m, each in (0, ``probe_length``).
    repetitions : int
        Touches per material and distance, >= 1.
    probe_length : float
        Probe length, m. Default 0.40 m, the paper's.
    search : dict
        Settings of the search (names of :data:`SEARCH_SETTINGS`).
    simulation : tuple of dict
        Per touch, in plan order, what a simulated rig varies (see :class:`Touch`); empty for a
        real rig.
    """

    name: str
    materials: tuple[str, ...]
    contacts: tuple[float, ...]
    repetitions: int
    probe_length: float = 0.40
    search: dict = field(default_factory=dict)
    simulation: tuple = ()

    def __post_init__(self):
        if not (isinstance(self.name, str) and self.name.replace("-", "").isalnum()):
            raise ValueError(f"plan name must be letters, digits and '-', got {self.name!r}")
        if isinstance(self.materials, str) or not self.materials:
            raise ValueError(f"materials must be a non-empty list of names, got "
                             f"{self.materials!r}")
        object.__setattr__(self, "materials",
                           tuple(lookup_material(m).name for m in self.materials))
        check_positive("probe_length", self.probe_length)
        contacts = tuple(float(check_real("contacts_m", c)) for c in self.contacts)
        outside = [c for c in contacts if not 0.0 < c < self.probe_length]
        if not contacts or outside:
            raise ValueError(f"contacts_m must be distances in (0, {self.probe_length:g}) m, got "
                             f"{list(self.contacts)!r}")
        object.__setattr__(self, "contacts", contacts)
        check_int("repetitions", self.repetitions, minimum=1)
        self.search_config()  # refuses unknown or bad settings now, not at the first touch
        if self.simulation and len(self.simulation) != len(self):
            raise ValueError(f"simulation must hold one entry per touch ({len(self)}), got "
                             f"{len(self.simulation)}")

    def __len__(self) -> int:
        return len(self.materials) * len(self.contacts) * self.repetitions

    def __getitem__(self, i: int) -> Touch:
        n = len(self)
        i = check_int("touch", i, minimum=-n, maximum=n - 1) % n
        per_material = len(self.contacts) * self.repetitions
        m, rest = divmod(i, per_material)
        c, r = divmod(rest, self.repetitions)
        extra = dict(self.simulation[i]) if self.simulation else {}
        return Touch(i, self.materials[m], self.contacts[c], r, extra)

    def __iter__(self):
        return (self[i] for i in range(len(self)))

    def search_config(self) -> SearchConfig:
        """The search settings as a :class:`~ebantenna.device.pantilt.SearchConfig`."""
        unknown = sorted(set(self.search) - set(SEARCH_SETTINGS))
        if unknown:
            raise ValueError(f"unknown search setting(s) {', '.join(unknown)}; a plan may set "
                             f"{', '.join(SEARCH_SETTINGS)}")
        return SearchConfig(**self.search)

    def to_dict(self) -> dict:
        """The plan as plain JSON values (what :func:`load_plan` reads back)."""
        out = {"name": self.name, "materials": list(self.materials),
               "contacts_m": list(self.contacts), "repetitions": self.repetitions,
               "probe_length": self.probe_length, "search": dict(self.search)}
        if self.simulation:
            out["simulation"] = [dict(s) for s in self.simulation]
        return out

    @classmethod
    def from_dict(cls, data: dict, where: str = "plan") -> Plan:
        """A plan from the values of a plan file (see the module notes)."""
        if not isinstance(data, dict):
            raise ValueError(f"{where}: a plan must be a table of settings")
        known = {"name", "materials", "contacts_m", "repetitions", "probe_length", "search",
                 "simulation"}
        unknown = sorted(set(data) - known)
        missing = sorted({"name", "materials", "contacts_m", "repetitions"} - set(data))
        if unknown or missing:
            raise ValueError(f"{where}: " + "; ".join(
                ([f"unknown key(s) {', '.join(unknown)}"] if unknown else [])
                + ([f"missing key(s) {', '.join(missing)}"] if missing else [])))
        try:
            return cls(data["name"], tuple(data["materials"]), tuple(data["contacts_m"]),
                       data["repetitions"], data.get("probe_length", 0.40),
                       dict(data.get("search", {})), tuple(data.get("simulation", ())))
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{where}: {exc}") from None

    @property
    def placements(self) -> int:
        """How many times the operator places an object: once per material and distance."""
        return len(self.materials) * len(self.contacts)


def session_time(plan: Plan, *, move: float = MOVE_SECONDS) -> dict:
    """How long a session of ``plan`` takes on the rig, from its search settings, s.

    Each touch checks the rig (the PCA9685's oscillator start-up and the MPU-6050's reset wait),
    searches, and records ``pre_trigger + duration`` around the contact. An object anywhere on
    the search path is met within one loop of it: half a loop on average, ``max_search_time``
    at worst (then the session stops). The operator moves the object ``plan.placements`` times,
    ``move`` seconds each (an assumption; default :data:`MOVE_SECONDS`).

    Returns
    -------
    dict
        ``touch_s`` (a touch on average), ``touch_worst_s``, ``touches``, ``placements``,
        ``total_s`` and ``worst_s`` (every search taking its longest).

    Examples
    --------
    >>> t = session_time(Plan("demo", ("brass",), (0.1, 0.2), 2))
    >>> round(t["touch_s"], 4), t["placements"], round(t["total_s"], 1)
    (3.1505, 2, 72.6)
    """
    if not isinstance(plan, Plan):
        raise TypeError(f"plan must be a Plan, got {type(plan).__name__}")
    move = check_nonnegative("move", move)
    config = plan.search_config()
    check = OSCILLATOR_STARTUP + RESET_WAIT
    window = config.pre_trigger + config.duration
    typical = check + 0.5 * config.path.period + window
    worst = check + config.max_search_time + window
    moving = plan.placements * move
    return {"touch_s": typical, "touch_worst_s": worst, "touches": len(plan),
            "placements": plan.placements, "total_s": len(plan) * typical + moving,
            "worst_s": len(plan) * worst + moving}


def load_plan(path) -> Plan:
    """Read a plan file: TOML by suffix ``.toml``, otherwise JSON (see the module notes)."""
    path = Path(path)
    text = path.read_text(encoding="utf-8")
    try:
        if path.suffix.lower() == ".toml":
            try:
                import tomllib  # novermin (guarded: Python 3.10 falls back to tomli below)
            except ModuleNotFoundError:  # Python 3.10: the same parser, from PyPI
                import tomli as tomllib
            data = tomllib.loads(text)
        else:
            data = json.loads(text)
    except ValueError as exc:  # TOMLDecodeError and JSONDecodeError are ValueErrors
        raise ValueError(f"{path}: not a valid plan file: {exc}") from None
    return Plan.from_dict(data, str(path))
