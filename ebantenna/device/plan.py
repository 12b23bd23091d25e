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

import re
from dataclasses import dataclass, field, fields
from pathlib import Path

from .._files import read_document, require
from .._validate import check_int, check_nonnegative, check_path, check_positive, check_real
from ..chips.mpu6050 import RESET_WAIT
from ..chips.pca9685 import OSCILLATOR_STARTUP
from ..probe import material as lookup_material
from .pantilt import SearchConfig

__all__ = ["Touch", "Plan", "load_plan", "session_time", "check_session_length", "plan_differences",
           "SEARCH_SETTINGS", "MOVE_SECONDS", "MAX_TOUCHES", "MAX_NAME", "LONG_SESSION_S",
           "LONG_WORST_S", "KEY_RESOLUTION"]

#: Assumed time for the operator to move the object to a new distance or material, s.
MOVE_SECONDS = 30.0

#: Most touches a plan may hold: at the rig's ~3 s a touch, 100,000 touches take about 4 days.
MAX_TOUCHES = 100_000
#: Longest plan name, characters.
MAX_NAME = 64
#: A session expected to take longer than this (s) starts only when the operator agrees.
LONG_SESSION_S = 3600.0
#: ... and so does one that may take longer than this at worst (every search its longest), s.
LONG_WORST_S = 86400.0
#: Contact distances closer than this (m) share a touch's key (``%.4f`` m, 0.1 mm).
KEY_RESOLUTION = 1e-4
_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9-]*")
#: The keys of a plan file; the first four are required.
_KEYS = ("name", "materials", "contacts_m", "repetitions", "probe_length", "search", "simulation")

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

    def __post_init__(self):
        check_int("index", self.index, minimum=0)
        if not isinstance(self.material, str) or not self.material:
            raise TypeError(f"material must be a material's name, got {self.material!r}")
        check_positive("contact", self.contact)
        check_int("repetition", self.repetition, minimum=0)
        if not isinstance(self.simulation, dict):
            raise TypeError(f"simulation must be a dict, got "
                            f"{type(self.simulation).__name__}")

    @property
    def key(self) -> str:
        """The name of the touch in the manifest: ``material/contact in m/repetition``."""
        return f"{self.material}/{self.contact:.4f}/{self.repetition}"

    def labels(self, probe_length: float) -> dict:
        """The labels a recording of this touch carries (JSON values)."""
        probe_length = check_positive("probe_length", probe_length)
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
        if not (isinstance(self.name, str) and len(self.name) <= MAX_NAME
                and _NAME.fullmatch(self.name)):
            raise ValueError(f"plan name must be 1 to {MAX_NAME} letters, digits and '-' "
                             f"(ASCII, not starting with '-'), got {self.name!r:.100}")
        object.__setattr__(self, "materials", _materials(self.materials))
        check_positive("probe_length", self.probe_length)
        object.__setattr__(self, "probe_length", float(self.probe_length))
        object.__setattr__(self, "contacts", _contacts(self.contacts, self.probe_length))
        check_int("repetitions", self.repetitions, minimum=1, maximum=MAX_TOUCHES)
        touches = len(self.materials) * len(self.contacts) * self.repetitions
        if touches > MAX_TOUCHES:
            raise ValueError(
                f"the plan holds {touches} touches ({len(self.materials)} materials x "
                f"{len(self.contacts)} contacts_m x {self.repetitions} repetitions), more than "
                f"the {MAX_TOUCHES} a plan may hold")
        if not isinstance(self.search, dict):
            raise TypeError(f"search must be a table of settings, got "
                            f"{type(self.search).__name__}")
        self.search_config()  # refuses unknown or bad settings now, not at the first touch
        if isinstance(self.simulation, str | dict) or not all(
                isinstance(s, dict) for s in self.simulation):
            raise TypeError("simulation must be a list of tables, one per touch")
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
    def from_dict(cls, data: dict, where: str = "plan", *, complete: bool = False) -> Plan:
        """A plan from the values of a plan file (see the module notes).

        ``where`` names the file in the messages; with ``complete`` every key of
        :meth:`to_dict` is required (a session's manifest stores them all).
        """
        if not isinstance(where, str):
            raise TypeError(f"where must be a str (the file's name), got {type(where).__name__}")
        if not isinstance(data, dict):
            raise ValueError(f"{where}: a plan must be a table of settings, got "
                             f"{type(data).__name__}")
        require(data, ("name", "materials", "contacts_m", "repetitions")
                + (("probe_length", "search") if complete else ()), where)
        unknown = sorted(str(k) for k in set(data) - set(_KEYS))
        if unknown:
            raise ValueError(f"{where}: unknown key(s) {', '.join(unknown)}; a plan has "
                             f"{', '.join(_KEYS)}")
        for key in ("materials", "contacts_m", "simulation"):
            if key in data and not isinstance(data[key], list | tuple):
                raise ValueError(f"{where}: {key} must be a list, got "
                                 f"{type(data[key]).__name__} {data[key]!r:.60}")
        if "search" in data and not isinstance(data["search"], dict):
            raise ValueError(f"{where}: search must be a table of settings, got "
                             f"{type(data['search']).__name__}")
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


#: What each setting of :meth:`Plan.to_dict` is called in a message (the simulated variation
#: also says which options make it).
_SETTING_WORDS = {
    "name": "the name", "materials": "the materials", "contacts_m": "the contacts (m)",
    "repetitions": "the repetitions", "probe_length": "the probe length (m)",
    "search": "the search settings",
    "simulation": "the simulated touches' variation (true contact, sweep speed, tilt and seed "
                  "of each touch: another --seed or --scene makes another)",
}


def plan_differences(stored: dict, given: dict) -> list[str]:
    """The settings in which two plans (as :meth:`Plan.to_dict` gives them) differ, each
    phrased for a message: ``["the repetitions: 3 in the folder, 2 given"]``.

    A session folder holds one plan: a resume with another is refused, and the refusal says in
    what the two differ (a seed or a repetition count is otherwise hard to spot in two long
    tables).

    Examples
    --------
    >>> a = Plan("demo", ("brass",), (0.1, 0.2), 3).to_dict()
    >>> b = Plan("demo", ("brass",), (0.1, 0.2), 2).to_dict()
    >>> plan_differences(a, b)
    ['the repetitions: 3 in the folder, 2 given']
    >>> plan_differences(a, a)
    []
    """
    for name, value in (("stored", stored), ("given", given)):
        if not isinstance(value, dict):
            raise TypeError(f"{name} must be a plan as a dict (Plan.to_dict), got "
                            f"{type(value).__name__}")
    out = []
    order = {k: i for i, k in enumerate(_KEYS)}
    for key in sorted(set(stored) | set(given), key=lambda k: (order.get(k, len(_KEYS)), str(k))):
        a, b = stored.get(key), given.get(key)
        if a == b:
            continue
        words = _SETTING_WORDS.get(key, f"the setting {key!r}")
        if key == "simulation" or a is None or b is None:
            out.append(words + (" (in the folder only)" if b is None else
                                " (given only)" if a is None else ""))
        else:
            out.append(f"{words}: {_short(a)} in the folder, {_short(b)} given")
    return out


def _short(value, limit: int = 60) -> str:
    """A value for a message, cut to about ``limit`` characters."""
    text = repr(value)
    return text if len(text) <= limit else text[:limit - 3] + "..."


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


def check_session_length(plan: Plan, *, agreed: bool = False,
                         flag: str = "--yes") -> dict:
    """Refuse to start a session expected to last over :data:`LONG_SESSION_S` (or, every search
    taking its longest, over :data:`LONG_WORST_S`) unless ``agreed``.

    Returns :func:`session_time`'s estimate. The message gives the estimate and names ``flag``,
    the command's way of agreeing.

    Examples
    --------
    >>> check_session_length(Plan("long", ("brass",), (0.1,), 2000))
    Traceback (most recent call last):
    ...
    ValueError: plan 'long': 2000 touches take about 1.8 h (at worst 7.3 h); pass --yes to start it
    """
    t = session_time(plan)
    if (t["total_s"] > LONG_SESSION_S or t["worst_s"] > LONG_WORST_S) and not agreed:
        raise ValueError(f"plan {plan.name!r}: {len(plan)} touches take about "
                         f"{_hours(t['total_s'])} (at worst {_hours(t['worst_s'])}); pass "
                         f"{flag} to start it")
    return t


def _hours(seconds: float) -> str:
    return f"{seconds / 3600:.2g} h" if seconds < 360000 else f"{seconds / 86400:.3g} days"


def _materials(materials) -> tuple[str, ...]:
    """The materials' canonical names; a string, an empty list or a repeat refused."""
    if isinstance(materials, str) or not isinstance(materials, list | tuple) or not materials:
        raise ValueError(f"materials must be a non-empty list of names, got {materials!r:.80}")
    if len(materials) > MAX_TOUCHES:
        raise ValueError(f"materials lists {len(materials)} names, more than {MAX_TOUCHES}")
    names, given = [], {}
    for m in materials:
        name = lookup_material(m).name
        if name in given:
            raise ValueError(f"materials names {name} twice ({given[name]!r} and {m!r}); each "
                             "material is placed once")
        given[name] = m
        names.append(name)
    return tuple(names)


def _contacts(contacts, probe_length: float) -> tuple[float, ...]:
    """The contact distances as floats, each in (0, probe_length), no two sharing a key."""
    if isinstance(contacts, str) or not isinstance(contacts, list | tuple) or not contacts:
        raise ValueError(f"contacts_m must be a non-empty list of distances, m, got "
                         f"{contacts!r:.80}")
    if len(contacts) > MAX_TOUCHES:
        raise ValueError(f"contacts_m lists {len(contacts)} distances, more than {MAX_TOUCHES}")
    values = tuple(check_real("contacts_m", c) for c in contacts)
    outside = [c for c in values if not 0.0 < c < probe_length]
    if outside:
        raise ValueError(f"contacts_m must be distances in (0, {probe_length:g}) m, got "
                         f"{outside[0]!r}")
    keys: dict = {}
    for c in values:
        key = f"{c:.4f}"
        if key in keys:
            raise ValueError(f"contacts_m {keys[key]!r} and {c!r} m are the same touch (a "
                             f"touch's key holds a distance to {KEY_RESOLUTION * 1000:g} mm, "
                             f"{key}); give distances at least 0.1 mm apart")
        keys[key] = c
    return values


def load_plan(path) -> Plan:
    """Read a plan file: TOML by suffix ``.toml``, otherwise JSON (see the module notes).

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    ValueError
        Naming the file (and the key): not a regular file, too long or nested too deeply, not
        valid TOML/JSON, a key missing or unknown, or a value out of range.
    """
    path = Path(check_path("plan", path))
    data = read_document(path, "a plan file", max_bytes=2**24,
                         toml=path.suffix.lower() == ".toml")
    return Plan.from_dict(data, str(path))
