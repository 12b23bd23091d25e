"""The paper's data set: five materials, contacts every 5 mm along the probe, 25 repetitions.

The paper (sections 2.1 and 4.2) records, for each of five touched materials, the probe's vibration
after a contact at every 5 mm along the probe, 25 times each. Here the recordings come from the
``paper`` scene. What varies from one repetition to the next, and why:

- *impact speed*: the servo's speed at the contact varies by 10 % (log-normal): the sweep is an
  ellipse and the object is met at slightly different points of it;
- *tilt rate*: likewise the rate across the sweep plane varies by 20 % (log-normal);
- *position*: the probe does not hit exactly the nominal point; the error is normal with a
  standard deviation of 1 mm, and the realised position is rounded to a 0.5 mm grid (so that
  repetitions share FEM solves) and kept at least 0.5 mm inside the probe;
- *the sensor*: noise, sample-clock jitter and the hum's phase, from each signal's own seed.

Every row can be reproduced alone: row ``i`` equals ``simulate(scene.with_(contact=contact_true[i],
material=material[i], sweep_speed=sweep_speed[i], tilt_ratio=tilt_ratio[i]), seed=seed_row[i])``.
The material enters the signals only through the contact's compliance and damping.

The data set is saved as a compressed ``.npz`` (accelerations as float32) with a JSON metadata
record and a SHA-256 checksum of the arrays, and reused when the same configuration asks again.
"""

from __future__ import annotations

import hashlib
import json
import logging
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import __version__
from .._progress import progress
from .._validate import check_int
from ..probe import material_names
from .scene import Scene, builtin_scene
from .simulator import simulate_batch

__all__ = ["Dataset", "build_dataset", "load_dataset", "dataset_plan", "FORMAT"]

log = logging.getLogger(__name__)

#: Format tag written into every data set file.
FORMAT = "ebantenna-dataset-1"
STEP = 0.005  # m, the paper's contact spacing
REPETITIONS = 25
POSITION_ERROR = 1e-3  # m, standard deviation
POSITION_GRID = 5e-4  # m
SPEED_SPREAD = 0.10  # log-normal sigma of the sweep speed
TILT_SPREAD = 0.20  # log-normal sigma of the tilt ratio
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
        Configuration (scene, seed, quick), variation model, checksum.
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


def dataset_plan(scene: Scene, seed: int = 0, quick: bool = False) -> dict:
    """The rows of the data set before simulation: labels and per-repetition variation.

    Returns a dict of arrays ``material``, ``contact``, ``contact_true``, ``repetition``,
    ``sweep_speed``, ``tilt_ratio``, ``seed_row``, in material, contact, repetition order.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.simulate import builtin_scene
    >>> from ebantenna.simulate.dataset import dataset_plan
    >>> plan = dataset_plan(builtin_scene("paper"), seed=0)
    >>> plan["contact"].size, np.unique(plan["contact"])[[0, -1]]
    (9875, array([0.005, 0.395]))
    """
    seed = check_int("seed", seed, minimum=0)
    length = scene.probe.length
    if quick:
        nominal = np.arange(0.025, length, 0.05)
        repetitions = 3
    else:
        nominal = np.arange(1, int(np.floor(length / STEP + 1e-9)) + 1) * STEP
        nominal = nominal[nominal < length - 1e-12]
        repetitions = REPETITIONS
    nominal = np.round(nominal, 6)
    materials = material_names()
    mat, con, rep = np.meshgrid(
        np.arange(len(materials)), nominal, np.arange(repetitions), indexing="ij"
    )
    n = mat.size
    rng = np.random.default_rng([seed, 0xDA7A])
    error = rng.normal(0.0, POSITION_ERROR, n)
    true = np.round((con.ravel() + error) / POSITION_GRID) * POSITION_GRID
    true = np.round(np.clip(true, POSITION_GRID, length - POSITION_GRID), 9)
    return {
        "material": np.array(materials)[mat.ravel()],
        "contact": con.ravel(),
        "contact_true": true,
        "repetition": rep.ravel().astype(np.int64),
        "sweep_speed": scene.sweep_speed * np.exp(rng.normal(0.0, SPEED_SPREAD, n)),
        "tilt_ratio": scene.tilt_ratio * np.exp(rng.normal(0.0, TILT_SPREAD, n)),
        "seed_row": rng.integers(0, 2**62, n, dtype=np.int64),
    }


def _config(scene: Scene, seed: int, quick: bool) -> dict:
    return {
        "format": FORMAT,
        "seed": seed,
        "quick": bool(quick),
        "scene": scene.to_dict(),
        "variation": {
            "repetitions": 3 if quick else REPETITIONS,
            "contact_step_m": 0.05 if quick else STEP,
            "position_error_std_m": POSITION_ERROR,
            "position_grid_m": POSITION_GRID,
            "sweep_speed_lognormal_sigma": SPEED_SPREAD,
            "tilt_ratio_lognormal_sigma": TILT_SPREAD,
        },
    }


def _simulate_material(scene: Scene, name: str, plan: dict):
    rows = np.flatnonzero(plan["material"] == name)
    _, bx, bz, _, _ = simulate_batch(
        scene,
        contact=plan["contact_true"][rows],
        material=name,
        sweep_speed=plan["sweep_speed"][rows],
        tilt_ratio=plan["tilt_ratio"][rows],
        seeds=plan["seed_row"][rows],
        show_progress=False,
    )
    return rows, bx.astype(np.float32), bz.astype(np.float32)


def build_dataset(
    out_dir,
    seed: int = 0,
    quick: bool = False,
    *,
    scene: Scene | None = None,
    n_jobs: int = 1,
    show_progress=None,
) -> Dataset:
    """Build (or reuse) the paper's data set in ``out_dir``.

    Parameters
    ----------
    out_dir : path
        Directory for the ``.npz`` file (created if needed).
    seed : int
        Seed of everything random in the data set.
    quick : bool
        A small version (contacts every 5 cm, 3 repetitions) for tests and documentation.
    scene : Scene, optional
        The scene to record; default the built-in ``paper`` scene.
    n_jobs : int
        Worker processes (one material per task, :mod:`joblib`); the result does not depend on it.
    show_progress : bool, optional
        Force the progress bar on or off (default: on a terminal).

    Returns
    -------
    Dataset
        Also saved as ``<scene name>-dataset-seed<seed>[-quick].npz`` (``paper-dataset-seed0.npz``
        by default); a file there with the same configuration and a valid checksum is loaded
        instead of simulated again.

    Examples
    --------
    >>> import tempfile
    >>> from ebantenna.simulate import build_dataset
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     data = build_dataset(tmp, seed=1, quick=True)
    >>> data.ax.shape, sorted({str(m) for m in data.material})[:2]
    ((120, 1000), ['aluminium', 'brass'])
    """
    seed = check_int("seed", seed, minimum=0)
    n_jobs = check_int("n_jobs", n_jobs, minimum=1)
    scene = builtin_scene("paper") if scene is None else scene
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene, got {type(scene).__name__}")
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / f"{scene.name}-dataset-seed{seed}{'-quick' if quick else ''}.npz"
    config = _config(scene, seed, quick)
    if path.is_file():
        try:
            cached = load_dataset(path)
        except ValueError as exc:
            log.warning("rebuilding %s: %s", path, exc)
        else:
            if cached.metadata.get("config") == json.loads(json.dumps(config)):
                log.info("reusing %s", path)
                return cached
            log.info("rebuilding %s: configuration changed", path)

    plan = dataset_plan(scene, seed, quick)
    n = plan["contact"].size
    ax = np.empty((n, scene.n_samples), dtype=np.float32)
    az = np.empty_like(ax)
    names = material_names()
    if n_jobs == 1:
        parts = (_simulate_material(scene, name, plan) for name in names)
    else:
        from joblib import Parallel, delayed

        parts = Parallel(n_jobs=n_jobs, return_as="generator")(
            delayed(_simulate_material)(scene, name, plan) for name in names
        )
    for rows, bx, bz in progress(parts, total=len(names), desc="dataset", enabled=show_progress):
        ax[rows], az[rows] = bx, bz
    arrays = dict(plan, ax=ax, az=az)
    metadata = {
        "config": config,
        "ebantenna_version": __version__,
        "n_signals": int(n),
        "units": {"ax": "m/s^2", "az": "m/s^2", "contact": "m", "sweep_speed": "rad/s", "fs": "Hz"},
        "checksum_sha256": _checksum(arrays, scene.fs),
    }
    tmp = path.with_name(path.name + f".tmp{os.getpid()}.npz")
    np.savez_compressed(
        tmp, fs=np.float64(scene.fs), metadata=np.array(json.dumps(metadata)), **arrays
    )
    os.replace(tmp, path)
    log.info("wrote %s (%d signals)", path, n)
    for a in arrays.values():
        a.setflags(write=False)
    return Dataset(fs=float(scene.fs), metadata=metadata, path=path, **arrays)


def load_dataset(path) -> Dataset:
    """Load a data set written by :func:`build_dataset`, verifying its checksum.

    Raises
    ------
    ValueError
        If the file is not such a data set or its arrays do not match the checksum.
    """
    path = Path(path)
    with np.load(path, allow_pickle=False) as data:
        missing = [k for k in (*_ARRAYS, "fs", "metadata") if k not in data]
        if missing:
            raise ValueError(f"{path} is not an ebantenna data set (missing {', '.join(missing)})")
        arrays = {k: data[k] for k in _ARRAYS}
        fs = float(data["fs"])
        metadata = json.loads(str(data["metadata"]))
    if metadata.get("config", {}).get("format") != FORMAT:
        raise ValueError(f"{path}: unknown data set format")
    if _checksum(arrays, fs) != metadata.get("checksum_sha256"):
        raise ValueError(f"{path}: checksum mismatch, the file is corrupt or was modified")
    for a in arrays.values():
        a.setflags(write=False)
    return Dataset(fs=fs, metadata=metadata, path=path, **arrays)
