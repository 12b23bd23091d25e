"""Data sets of simulated recordings: materials x contact positions x repetitions.

A :class:`DatasetDesign` says which recordings a data set holds (the touched materials, the
nominal contact positions, the repetitions of each) and how one repetition differs from the next:

- *impact speed*: the servo's speed at the contact varies (log-normal, ``speed_spread``);
- *tilt rate*: likewise the rate across the sweep plane (log-normal, ``tilt_spread``);
- *position*: the probe does not hit exactly the nominal point; the error is normal
  (``position_error``), and the realised position is rounded to a grid (``position_grid``, so that
  repetitions share FEM solves) and kept one grid step inside the probe;
- *the sensor*: noise, sample-clock jitter and the hum's phase, from each signal's own seed.

Every row can be reproduced alone: row ``i`` equals ``simulate(scene.with_(contact=contact_true[i],
material=material[i], sweep_speed=sweep_speed[i], tilt_ratio=tilt_ratio[i]), seed=seed_row[i])``.
The paper's own design, and the data set it recorded, are in :mod:`ebantenna.paper.data`.

A data set is saved as an ``.npz`` archive (accelerations as float32; not compressed, since
noise-dominated signals barely shrink under zlib, which costs seconds per build) with a JSON
metadata record and a SHA-256 checksum of the arrays, and reused when the same configuration asks
again. The configuration is the cache key: the file format, the package version, the seed, the
design, every parameter of the scene (probe, supports, sampling, each effect's parameters), every
property of the touched materials and the engine of the strike march (``strike_march``: NumPy or
compiled, which agree within a bound but not bit for bit), so that changed physics never reuses
stale data and a data set says which march made it. A cached file
that is damaged, truncated, foreign or stale is rebuilt, and the log says why. The simulation runs
through :class:`joblib.Parallel`, one task per material, so any joblib backend can run it: local
processes, or a Dask cluster (``joblib.parallel_config(backend="dask")``) to grow a sweep beyond one
machine without changing code. """

from __future__ import annotations

import dataclasses
import hashlib
import json
import logging
import math
from dataclasses import dataclass, fields
from pathlib import Path

import numpy as np
from joblib import Parallel, delayed

from .. import __version__
from .._budget import check_allocation
from .._progress import progress
from .._threads import limited_threads
from .._validate import (
    check_int,
    check_n_jobs,
    check_nonnegative,
    check_path,
    check_per_row,
    check_positive,
    load_json,
    open_npz,
    output_file_in,
    plain_name,
)
from ..probe import material
from ._block_march import march_engine
from ._dataset_files import remove_leftovers, stale_reason, write_whole
from .scene import Scene
from .simulator import physics_key, simulate_batch, simulate_sensor_variants

__all__ = [
    "Dataset", "DatasetDesign", "build_dataset", "build_datasets", "load_dataset", "dataset_plan",
    "dataset_path", "FORMAT",
]  # fmt: skip

log = logging.getLogger(__name__)

#: Format tag written into every data set file.
#: Raised whenever the simulated signals change for the same configuration, so that no cache
#: built by older code is reused: 2, a DatasetDesign; 3, package version and materials in the
#: key; 4, the coupled arrest's modal velocities over the probe's free DOFs only.
FORMAT = "ebantenna-dataset-4"
_ARRAYS = (
    "ax",
    "az",
    "material",
    "contact",
    "contact_true",
    "repetition",
    "sweep_speed",
    "tilt_ratio",
    "seed_row",
)


@dataclass(frozen=True)
class DatasetDesign:
    """Which recordings a data set holds, and how one repetition differs from the next.

    Parameters
    ----------
    name : str
        Names the data set's file, ``<scene name>-<name>-seed<seed>.npz``.
    materials : tuple of str
        Touched materials (names of :data:`ebantenna.probe.MATERIALS`).
    first_contact, contact_step : float
        Nominal contact positions ``first_contact + k contact_step`` short of the probe's tip, m.
    repetitions : int
        Recordings per material and nominal position.
    position_error : float
        Standard deviation of the realised contact position about the nominal one, m.
    position_grid : float
        Grid the realised position is rounded to, m (> 0). It must leave each nominal position,
        rounded to it, a grid point of its own at least one grid step inside the probe (checked
        by :meth:`contacts`, which knows the probe's length): so about no coarser than the
        nominal positions' spacing and the first one's distance from the hinge, and below half
        the probe's length.
    speed_spread, tilt_spread : float
        Log-normal sigmas of the sweep speed and of the tilt ratio, dimensionless.

    Examples
    --------
    >>> d = DatasetDesign("small", ("brass", "pvc"), 0.1, 0.1, 2)
    >>> d.contacts(0.4)
    array([0.1, 0.2, 0.3])
    """

    name: str
    materials: tuple[str, ...]
    first_contact: float
    contact_step: float
    repetitions: int
    position_error: float = 0.0
    position_grid: float = 5e-4
    speed_spread: float = 0.0
    tilt_spread: float = 0.0

    def __post_init__(self):
        if not (isinstance(self.name, str) and self.name.replace("-", "").isalnum()):
            raise ValueError(f"name must be letters, digits and '-', got {self.name!r}")
        if isinstance(self.materials, str) or not self.materials:
            raise ValueError(
                f"materials must be a non-empty tuple of names, got {self.materials!r}"
            )
        object.__setattr__(self, "materials", tuple(material(m).name for m in self.materials))
        repeated = sorted({m for m in self.materials if self.materials.count(m) > 1})
        if repeated:
            raise ValueError(
                f"materials must name each material once (a repeated one would make two "
                f"classes of the same recordings), got {', '.join(repeated)} more than once"
            )
        check_positive("first_contact", self.first_contact)
        check_positive("contact_step", self.contact_step)
        check_int("repetitions", self.repetitions, minimum=1)
        check_nonnegative("position_error", self.position_error)
        check_positive("position_grid", self.position_grid)
        check_nonnegative("speed_spread", self.speed_spread)
        check_nonnegative("tilt_spread", self.tilt_spread)

    def contacts(self, length: float) -> np.ndarray:
        """The nominal contact positions on a probe of ``length`` (m), m."""
        check_positive("length", length)
        with np.errstate(over="ignore"):
            count = np.floor((length - self.first_contact) / self.contact_step + 1e-9) + 1
        # three float arrays of that many positions are made below
        check_allocation(24 * max(float(count), 0.0), parameter="contact_step",
                         what=f"{count:.3g} nominal contact positions")
        k = np.arange(max(int(count), 0))
        nominal = self.first_contact + k * self.contact_step
        nominal = nominal[nominal < length - 1e-12]
        if nominal.size == 0:
            raise ValueError(
                f"first_contact must lie on the probe (< {length:g} m), got {self.first_contact!r}"
            )
        nominal = np.round(nominal, 6)
        _check_grid(self.position_grid, nominal, length)
        return nominal

    def to_dict(self) -> dict:
        """The design as plain JSON values."""
        return {
            f.name: list(v) if isinstance(v := getattr(self, f.name), tuple) else v
            for f in fields(self)
        }


def _check_grid(grid: float, nominal: np.ndarray, length: float) -> None:
    """Refuse a ``position_grid`` that would move or merge the ``nominal`` positions (m) on a
    probe of ``length`` (m): rounded to the grid, each must keep a grid point of its own within
    ``[grid, length - grid]``, the band the realised positions are kept in."""
    on_grid = np.round(np.round(nominal / grid) * grid, 9)
    low, high = round(grid, 9), round(length - grid, 9)
    outside = np.flatnonzero((on_grid < low) | (on_grid > high))
    if outside.size or np.unique(on_grid).size < on_grid.size:
        i = outside[0] if outside.size else 0
        what = (f"rounds the nominal {nominal[i]:g} m to {on_grid[i]:g} m, outside [{low:g}, "
                f"{high:g}] m" if outside.size else "rounds two nominal positions to one point")
        raise ValueError(
            f"position_grid must leave every nominal contact position a grid point of its own at "
            f"least one grid step inside the {length:g} m probe; got {grid!r} m, which {what}"
        )


@dataclass(frozen=True, eq=False)
class Dataset:
    """A set of simulated recordings, one row per signal.

    Attributes
    ----------
    ax, az : ndarray of float32, shape (n_signals, n_samples)
        Tip accelerations, m/s^2.
    material : ndarray of str, shape (n_signals,)
        Touched material of each signal.
    contact : ndarray of shape (n_signals,)
        Nominal contact position, m (the label to estimate).
    contact_true : ndarray of shape (n_signals,)
        Where the probe actually touched, m.
    repetition : ndarray of int, shape (n_signals,)
        Repetition number, 0-based.
    sweep_speed, tilt_ratio : ndarray of shape (n_signals,)
        The impact's sweep speed (rad/s) and tilt ratio.
    seed_row : ndarray of int64, shape (n_signals,)
        Seed of each signal's random effects.
    fs : float
        Sampling frequency, Hz.
    metadata : dict
        Configuration (scene, design, seed), package version, checksum, and what each strike
        gives besides its signals: with the ``unilateral_contact`` effect ``restrikes``, each
        strike's contacts after the first; with ``object_modes`` and the linear contact
        ``lift_off_ratio``, each strike's largest pull of the contact over its preload
        (:meth:`~ebantenna.simulate.ModalTerms.lift_off_ratio`; above 1 the probe would lift
        off); with the ``clipping`` effect ``samples_saturated``, each signal's samples (X and Z
        together) that the chip's range moved to a rail.
    path : Path or None
        The file it was loaded from.
    """

    ax: np.ndarray
    az: np.ndarray
    material: np.ndarray
    contact: np.ndarray
    contact_true: np.ndarray
    repetition: np.ndarray
    sweep_speed: np.ndarray
    tilt_ratio: np.ndarray
    seed_row: np.ndarray
    fs: float
    metadata: dict
    path: Path | None = None

    @property
    def n_signals(self) -> int:
        """Number of signals (rows)."""
        return int(self.ax.shape[0])

    @property
    def n_samples(self) -> int:
        """Samples per signal."""
        return int(self.ax.shape[1])

    @property
    def t(self) -> np.ndarray:
        """Nominal sample times, s."""
        return np.arange(self.n_samples) / self.fs

    def checksum(self) -> str:
        """SHA-256 of the arrays (hex), as stored in the metadata."""
        return _checksum({name: getattr(self, name) for name in _ARRAYS}, self.fs)


def _checksum(arrays: dict, fs: float) -> str:
    h = hashlib.sha256()
    for name in _ARRAYS:
        a = np.ascontiguousarray(arrays[name])
        h.update(name.encode())
        h.update(str(a.dtype).encode())
        h.update(str(a.shape).encode())
        h.update(a.tobytes())
    h.update(repr(float(fs)).encode())
    return h.hexdigest()


def dataset_plan(scene: Scene, design: DatasetDesign, seed: int = 0) -> dict:
    """The rows of the data set before simulation: labels and per-repetition variation.

    Returns a dict of arrays ``material``, ``contact``, ``contact_true``, ``repetition``,
    ``sweep_speed``, ``tilt_ratio``, ``seed_row``, in material, contact, repetition order.

    Examples
    --------
    >>> from ebantenna.simulate import builtin_scene
    >>> design = DatasetDesign("small", ("brass", "pvc"), 0.1, 0.1, 2)
    >>> plan = dataset_plan(builtin_scene("paper"), design, seed=0)
    >>> plan["contact"].size, sorted({str(m) for m in plan["material"]})
    (12, ['brass', 'pvc'])
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    if not isinstance(design, DatasetDesign):
        raise TypeError(f"design must be a DatasetDesign, got {type(design).__name__}")
    return _plan(scene, design, check_int("seed", seed, minimum=0))


def _plan(scene: Scene, design: DatasetDesign, seed: int) -> dict:
    """:func:`dataset_plan` of checked values."""
    length = scene.probe.length
    nominal = design.contacts(length)
    materials = design.materials
    n_rows = len(materials) * nominal.size * design.repetitions
    # two float32 signals per row, and about 10 label and variation arrays of 8 bytes a row
    check_allocation(n_rows * (8 * scene.n_samples + 80), parameter="design",
                     what=f"a data set of {n_rows} recordings of {scene.n_samples} samples "
                     f"({len(materials)} materials x {nominal.size} contacts x "
                     f"{design.repetitions} repetitions)")
    mat, con, rep = np.meshgrid(
        np.arange(len(materials)), nominal, np.arange(design.repetitions), indexing="ij"
    )
    n = mat.size
    rng = np.random.default_rng([seed, 0xDA7A])
    grid = design.position_grid
    error = rng.normal(0.0, design.position_error, n)
    true = np.round((con.ravel() + error) / grid) * grid
    true = np.round(np.clip(true, grid, length - grid), 9)
    return {
        "material": np.array(materials)[mat.ravel()],
        "contact": con.ravel(),
        "contact_true": true,
        "repetition": rep.ravel().astype(np.int64),
        "sweep_speed": scene.sweep_speed * np.exp(rng.normal(0.0, design.speed_spread, n)),
        "tilt_ratio": scene.tilt_ratio * np.exp(rng.normal(0.0, design.tilt_spread, n)),
        "seed_row": rng.integers(0, 2**62, n, dtype=np.int64),
    }


def _config(scene: Scene, design: DatasetDesign, seed: int) -> dict:
    """The cache key: everything the arrays depend on, as plain JSON values."""
    config = {
        "format": FORMAT,
        "ebantenna_version": __version__,
        "seed": seed,
        "scene": scene.to_dict(),
        "design": design.to_dict(),
        "materials": {name: dataclasses.asdict(material(name)) for name in design.materials},
        "strike_march": march_engine(),
    }
    return json.loads(json.dumps(config))  # tuples as lists, as they come back from the file


#: Tasks per material: contiguous ranges of contact positions (each task shares its probe
#: reductions), enough for a few workers to finish together when strikes differ in cost.
PARTS_PER_MATERIAL = 4


def _tasks(plan: dict, materials) -> list[np.ndarray]:
    """The rows of each task: per material, its rows sorted by contact, in equal parts."""
    tasks = []
    for name in materials:
        rows = np.flatnonzero(plan["material"] == name)
        rows = rows[np.argsort(plan["contact_true"][rows], kind="stable")]
        tasks += [part for part in np.array_split(rows, PARTS_PER_MATERIAL) if part.size]
    return tasks


def _per_strike_keys(scene: Scene) -> tuple[str, ...]:
    """What a data set of ``scene`` keeps of each strike besides its signals, in its metadata:
    ``"restrikes"`` with ``unilateral_contact`` (the contacts after the first touch), and
    ``"lift_off_ratio"`` with ``object_modes`` and the linear contact (the largest pull of the
    contact over its preload; above 1 the linear model holds the probe by a pull a real contact
    cannot give). Kept so that a study reads them from the data set it built instead of
    simulating its strikes again.

    Examples
    --------
    >>> from ebantenna.simulate import builtin_scene
    >>> paper = builtin_scene("paper")
    >>> _per_strike_keys(paper)
    ('restrikes',)
    >>> _per_strike_keys(paper.with_(effects=[e for e in paper.effects
    ...                                      if e.name != "unilateral_contact"]))
    ('lift_off_ratio',)
    """
    if scene.has("unilateral_contact"):
        return ("restrikes",)
    return ("lift_off_ratio",) if scene.has("object_modes") else ()


def _kept_keys(scene: Scene) -> tuple[str, ...]:
    """What a data set of ``scene`` keeps of each signal in its metadata: its strike's
    (``_per_strike_keys``) and, with the ``clipping`` effect, ``"samples_saturated"``."""
    return _per_strike_keys(scene) + (("samples_saturated",) if scene.has("clipping") else ())


def _per_strike(scene: Scene, x) -> dict:
    """The ``_per_strike_keys`` of ``scene`` read from its strikes' modal terms ``x``."""
    got = {"restrikes": lambda: x.restrikes, "lift_off_ratio": lambda: x.lift_off_ratio(
        scene.duration)}
    return {key: got[key]() for key in _per_strike_keys(scene)}


def _simulate_rows(scenes, rows: np.ndarray, plan: dict):
    """The signals of ``rows`` of ``plan`` in each of ``scenes`` (the same physics key), as
    float32, and what each row's strike gives besides (``_per_strike_keys``).

    BLAS runs on one thread here, as in a joblib worker: some OpenBLAS builds (NumPy 1.24's)
    round a product differently on two threads, and a data set must not depend on ``n_jobs``.
    """
    with limited_threads(1):
        return _simulated_rows(scenes, rows, plan)


def _simulated_rows(scenes, rows: np.ndarray, plan: dict):
    given = dict(
        contact=plan["contact_true"][rows],
        material=plan["material"][rows],
        sweep_speed=plan["sweep_speed"][rows],
        tilt_ratio=plan["tilt_ratio"][rows],
        seeds=plan["seed_row"][rows],
        show_progress=False,
        x_modes=False,  # the data set keeps the signals, not the modes
    )
    if len(scenes) == 1:
        done = [simulate_batch(scenes[0], **given, return_saturated=True)]
    else:
        done = simulate_sensor_variants(scenes, **given, return_saturated=True)
    signals = [(bx.astype(np.float32), bz.astype(np.float32), saturated)
               for _, bx, bz, _, _, saturated in done]
    return rows, signals, _per_strike(scenes[0], done[0][3])


def dataset_path(out_dir, scene: Scene, design: DatasetDesign, seed: int = 0, *,
                 parameter: str = "out_dir") -> Path:
    """Where :func:`build_dataset` saves (and looks for) the data set of ``design`` recorded in
    ``scene`` with ``seed``: ``out_dir/<scene name>-<design name>-seed<seed>.npz``, checked
    before anything is simulated.

    Parameters
    ----------
    out_dir : path
        The directory: an existing one must accept new files, a missing one must be creatable.
    scene : Scene
        Its name is the file name's first part: a plain name (no path separator, not ``.`` or
        ``..``).
    design : DatasetDesign
        Its name is the second part.
    seed : int
        The seed (>= 0).
    parameter : str
        The name errors give the directory (``--out`` for a command).

    Raises
    ------
    TypeError
        If ``out_dir`` is not a path, ``scene`` not a Scene or ``design`` not a DatasetDesign.
    ValueError
        Naming ``parameter``, if a directory stands where the file goes (a FIFO or a device
        there is replaced, as a damaged cached file is), or the scene's name cannot name a
        file.
    OSError
        Naming ``parameter``, if ``out_dir`` is a file or cannot be written.

    Examples
    --------
    >>> from ebantenna.simulate import builtin_scene
    >>> design = DatasetDesign("small", ("brass", "pvc"), 0.1, 0.1, 2)
    >>> dataset_path("cache", builtin_scene("paper"), design, 1).as_posix()
    'cache/paper-small-seed1.npz'
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    if not isinstance(design, DatasetDesign):
        raise TypeError(f"design must be a DatasetDesign, got {type(design).__name__}")
    seed = check_int("seed", seed, minimum=0)
    name = scene.name
    if not plain_name(name):
        raise ValueError(f"scene's name must be a plain name (it names the data set's file), got "
                         f"{name!r:.80}")
    # the file is written whole and renamed into place: a FIFO or a device there is replaced
    return output_file_in(parameter, out_dir, f"{name}-{design.name}-seed{seed}.npz",
                          renamed=True)


def build_dataset(
    out_dir,
    scene: Scene,
    design: DatasetDesign,
    seed: int = 0,
    *,
    n_jobs: int | None = None,
    show_progress=None,
) -> Dataset:
    """Build (or reuse) the data set of ``design`` recorded in ``scene``, in ``out_dir``.

    The paper's data set is :func:`ebantenna.paper.data.build_paper_dataset`.

    Parameters
    ----------
    out_dir : path
        Directory for the ``.npz`` file (created if needed).
    scene : Scene
        The scene to record.
    design : DatasetDesign
        Materials, contact positions, repetitions and their scatter.
    seed : int
        Seed of everything random in the data set.
    n_jobs : int, optional
        Workers (:class:`joblib.Parallel`; each task a range of contact positions of one material),
        at most the machine's cores, or -1 (every core); default: the active
        ``joblib.parallel_config`` (one process outside any). The result does not depend on it,
        nor on the backend.
    show_progress : bool, optional
        Force the progress bar on or off (default: on a terminal).

    Raises
    ------
    TypeError, ValueError, OSError
        Naming the parameter, for a bad input; ``out_dir`` is checked before anything is
        simulated (:func:`dataset_path`: a file where the directory goes, a directory where the
        data set's file goes, a directory that cannot be written).

    Returns
    -------
    Dataset
        Also saved as ``<scene name>-<design name>-seed<seed>.npz``; a file there with the same
        configuration (format, package version, every scene parameter, design, materials, seed,
        strike march's engine) and a valid checksum is loaded instead of simulated again. A
        damaged or stale file is rebuilt (logged at WARNING with the reason). An interruption
        leaves no temporary file.

    Examples
    --------
    >>> import tempfile
    >>> from ebantenna.simulate import builtin_scene
    >>> design = DatasetDesign("small", ("brass", "pvc"), 0.1, 0.1, 2)
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     data = build_dataset(tmp, builtin_scene("paper"), design, seed=1)
    >>> data.ax.shape, data.path.name
    ((12, 1000), 'paper-small-seed1.npz')
    """
    seed = check_int("seed", seed, minimum=0)
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    return build_datasets(out_dir, [scene], design, seed, n_jobs=n_jobs,
                          show_progress=show_progress)[0]


def build_datasets(
    out_dir,
    scenes,
    design: DatasetDesign,
    seed: int = 0,
    *,
    n_jobs: int | None = None,
    show_progress=None,
) -> list[Dataset]:
    """:func:`build_dataset` of each of ``scenes`` with the same design and seed.

    Scenes that differ only in their sensor stage (the same
    :func:`~ebantenna.simulate.simulator.physics_key`: gravity, hum, noise, drift, clipping,
    quantisation, Kalman filter) are simulated together: the physics once, then each scene's
    sensor stage (:func:`~ebantenna.simulate.simulator.simulate_sensor_variants`). Each data set
    is bit for bit the one :func:`build_dataset` makes of its scene alone, saved and reused
    from the cache the same way.

    Parameters
    ----------
    out_dir, design, seed, n_jobs, show_progress
        As in :func:`build_dataset`.
    scenes : sequence of Scene
        Each with its own name (one file each).

    Returns
    -------
    list of Dataset
        In the order of ``scenes``.
    """
    seed = check_int("seed", seed, minimum=0)
    n_jobs = check_n_jobs("n_jobs", n_jobs)
    scenes = list(scenes)
    bad = [type(s).__name__ for s in scenes if not isinstance(s, Scene)]
    if bad or not scenes:
        raise TypeError(f"scenes must be Scenes, got {', '.join(bad) or 'none'}")
    if not isinstance(design, DatasetDesign):
        raise TypeError(f"design must be a DatasetDesign, got {type(design).__name__}")
    names = [s.name for s in scenes]
    if len(set(names)) < len(names):
        raise ValueError(f"scenes must have distinct names (one file each), got {names}")
    paths = [dataset_path(out_dir, scene, design, seed) for scene in scenes]  # before any work
    paths[0].parent.mkdir(parents=True, exist_ok=True)
    found, todo = {}, {}
    for i, (scene, path) in enumerate(zip(scenes, paths, strict=True)):
        remove_leftovers(path)
        config = _config(scene, design, seed)
        found[i] = _reusable(path, config, _kept_keys(scene))
        if found[i] is None:  # grouped by what the steps before the sensor stage read
            todo.setdefault(physics_key(scene), []).append((i, scene, path, config))
    for group in todo.values():
        plan = _plan(group[0][1], design, seed)  # the plan reads only the physics key's values
        signals, strikes = _simulate_plan(
            [g[1] for g in group], plan, design.materials, n_jobs, show_progress
        )
        for (i, scene, path, config), (ax, az, saturated) in zip(group, signals, strict=True):
            found[i] = _save(path, scene, config, dict(plan, ax=ax, az=az), strikes, saturated)
    return [found[i] for i in range(len(scenes))]


def _save(path: Path, scene: Scene, config: dict, arrays: dict, strikes: dict,
          saturated) -> Dataset:
    """Write the data set of ``arrays`` (the plan and the signals) to ``path``, with what each
    strike gives besides (``strikes``, ``_per_strike_keys``) and each signal's samples the
    range moved to a rail (``saturated``, None without ``clipping``) in its metadata; return
    it."""
    metadata = {
        "config": config,
        "ebantenna_version": __version__,
        "n_signals": int(arrays["ax"].shape[0]),
        "units": {"ax": "m/s^2", "az": "m/s^2", "contact": "m", "sweep_speed": "rad/s", "fs": "Hz"},
        "checksum_sha256": _checksum(arrays, scene.fs),
    }
    metadata.update({key: strikes[key].tolist() for key in _per_strike_keys(scene)})
    if saturated is not None:
        metadata["samples_saturated"] = saturated.tolist()
    write_whole(path, arrays, metadata, scene.fs)
    for a in arrays.values():
        a.setflags(write=False)
    return Dataset(fs=float(scene.fs), metadata=metadata, path=path, **arrays)


def _reusable(path: Path, config: dict, keys) -> Dataset | None:
    """The data set cached at ``path`` if it loads, has ``config`` and keeps ``keys`` of each
    signal (``_kept_keys``); None (logged why) if not."""
    if not path.exists():
        return None
    try:
        cached = load_dataset(path)
    except ValueError as exc:
        log.warning("rebuilding %s: %s", path, exc)
        return None
    why = stale_reason(cached.metadata.get("config"), config)
    missing = [key for key in keys if key not in cached.metadata]
    if why is None and missing:  # written before the data set kept them
        why = f"its metadata does not keep each signal's {', '.join(missing)}"
    if why is not None:
        log.warning("rebuilding %s: %s", path, why)
        return None
    log.info("reusing %s", path)
    return cached


def _simulate_plan(scenes, plan: dict, materials, n_jobs, show_progress):
    """The signals of every row of ``plan`` in each of ``scenes`` (the same physics key), one
    joblib task per range of contacts.

    Returns per scene ``ax`` and ``az`` (float32, ``(n, n_samples)``) and ``saturated`` (the
    samples each row's range moved to a rail; None without ``clipping``), and what each row's
    strike gives besides (``{key: (n,) array}``, ``_per_strike_keys``; the scenes share
    their strikes). Takes checked values.
    """
    n = plan["contact"].size
    signals = [
        (np.empty((n, s.n_samples), dtype=np.float32), np.empty((n, s.n_samples), np.float32),
         np.zeros(n, dtype=np.int64) if s.has("clipping") else None)
        for s in scenes
    ]
    tasks = _tasks(plan, materials)
    if n_jobs is not None:
        n_jobs = min(n_jobs, len(tasks))
    parts = Parallel(n_jobs=n_jobs, return_as="generator")(
        delayed(_simulate_rows)(scenes, rows, plan) for rows in tasks
    )
    strikes = {}
    for rows, part, given in progress(
        parts, total=len(tasks), desc="dataset", enabled=show_progress
    ):
        for (ax, az, saturated), (bx, bz, cx) in zip(signals, part, strict=True):
            ax[rows], az[rows] = bx, bz
            if saturated is not None:
                saturated[rows] = cx
        for key, values in given.items():
            strikes.setdefault(key, np.zeros(n, dtype=values.dtype))[rows] = values
    return signals, strikes


def _check_rows(path, arrays: dict) -> None:
    """Raise, naming the file, unless the arrays describe one set of rows (a forged archive
    whose checksum was recomputed may not: its rows would be read out of range later)."""
    ax, az = arrays["ax"], arrays["az"]
    if ax.ndim != 2 or az.shape != ax.shape or ax.shape[0] < 1 or ax.shape[1] < 1:
        raise ValueError(f"{path}: ax and az must be two arrays of the same shape (signals, "
                         f"samples), got {ax.shape} and {az.shape}")
    if ax.dtype.kind != "f" or az.dtype.kind != "f" or not (
            np.all(np.isfinite(ax)) and np.all(np.isfinite(az))):
        raise ValueError(f"{path}: ax and az must hold finite real numbers")
    per_row = {k: v for k, v in arrays.items() if k not in ("ax", "az")}
    try:
        check_per_row(ax.shape[0], "ax", **per_row)
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None
    contact = arrays["contact"]
    if contact.dtype.kind != "f" or not np.all(np.isfinite(contact)) or np.any(contact <= 0):
        raise ValueError(f"{path}: contact must hold positive distances, m")
    if arrays["material"].dtype.kind != "U":
        raise ValueError(f"{path}: material must hold names")
    if arrays["repetition"].dtype.kind not in "iu" or np.any(arrays["repetition"] < 0):
        raise ValueError(f"{path}: repetition must hold whole numbers >= 0")


def _check_probe_length(path, config: dict) -> None:
    """Raise, naming the file, unless the data set names its probe's length (the studies place
    the distance networks' region and the positions by it)."""
    try:
        length = config["scene"]["probe"]["length"]
    except (KeyError, TypeError):
        raise ValueError(f"{path}: its metadata does not give the probe's length "
                         "(config.scene.probe.length)") from None
    if isinstance(length, bool) or not isinstance(length, int | float) or not (
            math.isfinite(length) and length > 0):
        raise ValueError(f"{path}: the probe's length (config.scene.probe.length) must be a "
                         f"positive number of metres, got {length!r:.40}")


def load_dataset(path) -> Dataset:
    """Load a data set written by :func:`build_dataset`, verifying its checksum.

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    TypeError
        If ``path`` is not a ``str`` or ``os.PathLike`` (bytes are refused).
    ValueError
        Naming the file, if it is not a regular file, truncated, damaged, declares arrays over
        the memory budget, is not such a data set, of another format, its arrays do not match
        the checksum or one another, or its sample rate or probe length is not positive.
    """
    path = Path(check_path("path", path))
    what = "an ebantenna data set"
    with open_npz(path, what) as data:
        missing = [k for k in (*_ARRAYS, "fs", "metadata") if k not in data]
        if missing:
            raise ValueError(f"{path} is not {what} (missing {', '.join(missing)})")
        arrays = {k: data[k] for k in _ARRAYS}
        fs_array, text = data["fs"], data["metadata"]
    try:
        fs = float(fs_array)
    except (TypeError, ValueError) as exc:  # a foreign file with arrays of these names
        raise ValueError(f"{path} is not {what}: {exc}") from None
    metadata = load_json(str(text), path, what)
    if not isinstance(metadata, dict):
        raise ValueError(f"{path} is not {what}: its metadata is not a JSON object")
    config = metadata.get("config")
    fmt = config.get("format") if isinstance(config, dict) else None
    if fmt != FORMAT:
        raise ValueError(f"{path}: data set format {fmt!r}, this version reads {FORMAT!r}")
    if _checksum(arrays, fs) != metadata.get("checksum_sha256"):
        raise ValueError(f"{path}: checksum mismatch, the file is corrupt or was modified")
    if not (math.isfinite(fs) and fs > 0):
        raise ValueError(f"{path}: fs must be a positive sample rate, Hz, got {fs!r}")
    _check_probe_length(path, config)
    _check_rows(path, arrays)
    for a in arrays.values():
        a.setflags(write=False)
    return Dataset(fs=fs, metadata=metadata, path=path, **arrays)
