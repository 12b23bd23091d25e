"""A data set from a session's recordings, in the package's data-set format.

:func:`assemble_dataset` reads a recording session's manifest
(:mod:`ebantenna.device.recording_session`) and puts its recordings together as a
:class:`~ebantenna.simulate.Dataset` that :func:`~ebantenna.simulate.load_dataset` reads and
the study runs on. Each recording is cut at its contact sample (the detector's trigger) to the
session's recorded duration and resampled onto the nominal sample grid from its own timestamps
(linear interpolation: it bridges the few samples a bus fault lost, and turns the chip's own
clock into host time). Inconsistent inputs are refused
by name, with the file at fault:

- a damaged file (its checksum differs from the manifest's, or it does not load);
- a missing label (material, contact distance, repetition), or one out of range or not the
  manifest's (a contact distance that is NaN or outside the probe, a fractional or boolean
  repetition, a material the plan does not place, a negative count of lost samples);
- a duplicate (the same material, distance and repetition twice, or the same file twice);
- a sample rate that differs (the configured rates, or an estimated rate off the configured one by
  more than ``rate_tolerance``);
- a recording too short for the features (fewer than ``2 * fft_bins`` samples after the contact,
  or shorter than the session's duration), or one that lost more than ``max_lost`` of its window.

The data set says where it came from (``metadata["provenance"]``): the session, its plan and rig,
every file and its checksum, and how many samples of each row were interpolated. The labels a rig
cannot know are not invented: ``contact_true`` is the nominal distance, ``sweep_speed`` and
``tilt_ratio`` are NaN, ``seed_row`` is -1.
"""

from __future__ import annotations

import datetime
import json
import math
from numbers import Integral, Real
from pathlib import Path

import numpy as np

from ... import __version__
from ..._files import inside
from ..._validate import check_in_range, check_path, check_positive, output_file_in
from ...device.plan import Plan
from ...device.recording_session import (
    MANIFEST,
    UNRECORDED_MAX_LOST,
    file_sha256,
    read_manifest,
    write_atomic,
)
from ...paper.protocol import DATASET
from ...recording import Recording
from ...simulate import Dataset
from ...simulate.dataset import FORMAT

__all__ = ["assemble_dataset", "MIN_SAMPLES", "LABELS"]

#: Fewest samples after the contact the features need: the FFT's length, two per bin kept.
MIN_SAMPLES = 2 * DATASET.fft_bins
#: The labels every recording must carry.
LABELS = ("material", "contact", "repetition")


def assemble_dataset(directory, out_dir=None, *, max_lost: float | None = None,
                     rate_tolerance: float = 0.01) -> Dataset:
    """Assemble a session's recordings into a data set file.

    Parameters
    ----------
    directory : path
        The session folder (holding ``session.json``).
    out_dir : path, optional
        Where to write ``recorded-<plan name>.npz``; default the session folder. Checked before
        any recording is read (a directory where the file goes is refused).
    max_lost : float, optional
        Largest share of a recording's window that may be missing, in [0, 1). Default the
        session's own limit (``max_lost`` in its manifest, the one ``record`` kept its
        recordings by; :data:`~ebantenna.device.recording_session.UNRECORDED_MAX_LOST`, 0.02, for a
        session that does not record it).
    rate_tolerance : float
        Largest relative difference between a recording's estimated sample rate and the
        configured one. Default 0.01 (the MPU-6050's clock is specified to 1 %).

    Returns
    -------
    Dataset
        Written whole (``path`` set), loadable by :func:`~ebantenna.simulate.load_dataset`.

    Raises
    ------
    ValueError
        Naming the file and what is wrong with it (see the module notes).
    """
    directory = Path(check_path("directory", directory))
    manifest_path = inside(directory, MANIFEST, str(directory / MANIFEST))
    manifest = read_manifest(manifest_path)
    if max_lost is None:  # the limit the session recorded with
        max_lost = manifest.get("max_lost", UNRECORDED_MAX_LOST)
    max_lost = check_in_range("max_lost", max_lost, 0.0, 1.0, low_inclusive=True)
    rate_tolerance = check_positive("rate_tolerance", rate_tolerance, maximum=1.0)
    if out_dir is not None:
        out_dir = Path(check_path("out_dir", out_dir))
    plan = Plan.from_dict(manifest["plan"], f"{manifest_path}: plan", complete=True)
    # the file written at the end, checked before any recording is read
    target = output_file_in("directory" if out_dir is None else "out_dir", out_dir or directory,
                            f"recorded-{plan.name}.npz", renamed=True)
    entries = sorted(manifest["recordings"].values(), key=lambda e: e["touch"])
    if not entries:
        raise ValueError(f"{directory}: the session holds no recordings yet")
    recordings = [_load_checked(directory, e) for e in entries]
    _check_labels_and_duplicates(recordings, entries, plan)
    fs = _common_rate(recordings, entries, rate_tolerance)
    n = round(manifest["search"]["duration"] * fs)
    if n < MIN_SAMPLES:
        raise ValueError(f"{directory}: the session recorded {n} samples after each contact; the "
                         f"features need at least {MIN_SAMPLES}")
    rows = [_resampled(rec, e["file"], fs, n, max_lost) for rec, e in zip(recordings, entries,
                                                                           strict=True)]
    arrays = _arrays(recordings, rows)
    metadata = _metadata(directory, manifest, entries, rows, fs,
                         [_flags(rec) for rec in recordings])
    return _write(arrays, metadata, fs, target)


def _load_checked(directory: Path, entry: dict) -> Recording:
    """The entry's recording, inside the session folder, its checksum verified."""
    path = inside(directory, entry["file"], str(directory / MANIFEST))
    if not path.exists():
        raise ValueError(f"{path}: listed in the manifest but missing")
    if file_sha256(path) != entry["sha256"]:
        raise ValueError(f"{path}: damaged file (checksum differs from the manifest's)")
    try:
        return Recording.load(path)
    except ValueError as exc:
        raise ValueError(f"{path}: damaged file ({exc})") from None


def _label(entry: dict, rec: Recording, name: str, ok, what: str):
    """The label ``name`` of ``rec``, refused unless ``ok(value)`` (``what`` it must be)."""
    value = rec.metadata.get(name)
    if value is None:
        raise ValueError(f"{entry['file']}: missing label(s) {name}")
    if not ok(value):
        raise ValueError(f"{entry['file']}: label {name} must be {what}, got {value!r:.60}")
    return value


def _is_int(v) -> bool:
    return isinstance(v, Integral) and not isinstance(v, bool)


def _is_real(v) -> bool:
    return isinstance(v, Real) and not isinstance(v, bool) and math.isfinite(v)


def _check_labels_and_duplicates(recordings, entries, plan: Plan) -> None:
    """Every label in range and equal to the manifest's entry; no touch or file twice."""
    seen: dict = {}
    files: dict = {}
    length = plan.probe_length
    for rec, entry in zip(recordings, entries, strict=True):
        material = _label(entry, rec, "material", lambda v: v in plan.materials,
                          f"one of the plan's materials ({', '.join(plan.materials)})")
        contact = _label(entry, rec, "contact", lambda v: _is_real(v) and 0 < v < length,
                         f"a distance in (0, {length:g}) m")
        repetition = _label(entry, rec, "repetition",
                             lambda v: _is_int(v) and 0 <= v < plan.repetitions,
                             f"a whole number in [0, {plan.repetitions})")
        _label(entry, rec, "samples_lost", lambda v: _is_int(v) and v >= 0,
               "a whole number >= 0")
        _label(entry, rec, "trigger_time", _is_real, "a finite time, s")
        key = (material, round(float(contact), 6), int(repetition))
        if key in seen:
            raise ValueError(f"{entry['file']}: duplicate of {seen[key]} (material {key[0]}, "
                             f"contact {key[1]} m, repetition {key[2]})")
        if entry["sha256"] in files:
            raise ValueError(f"{entry['file']}: duplicate of {files[entry['sha256']]} (the "
                             "same file twice)")
        for name, value in (("material", material), ("contact", contact),
                            ("repetition", repetition)):
            if value != entry[name]:
                raise ValueError(f"{entry['file']}: label {name} is {value!r}, the manifest's "
                                 f"entry has {entry[name]!r}")
        seen[key], files[entry["sha256"]] = entry["file"], entry["file"]


def _common_rate(recordings, entries, tolerance: float) -> float:
    """The configured sample rate all recordings share, Hz."""
    rates = [rec.metadata.get("sample_rate_hz") for rec in recordings]
    first = rates[0]
    for rec, rate, entry in zip(recordings, rates, entries, strict=True):
        if rate is None:
            raise ValueError(f"{entry['file']}: missing label sample_rate_hz (the configured "
                             "sample rate)")
        if not (_is_real(rate) and rate > 0):
            raise ValueError(f"{entry['file']}: label sample_rate_hz must be a positive "
                             f"rate, Hz, got {rate!r:.60}")
        if rate != first:
            raise ValueError(f"{entry['file']}: sample rate {rate:g} Hz differs from "
                             f"{first:g} Hz of {entries[0]['file']}")
        if abs(rec.fs / rate - 1.0) > tolerance:
            raise ValueError(f"{entry['file']}: sample rate estimated {rec.fs:.3f} Hz differs from "
                             f"the configured {rate:g} Hz by more than {tolerance:.1%}")
    return float(first)


def _resampled(rec: Recording, name: str, fs: float, n: int, max_lost: float):
    """``(ax, az, interpolated)``: ``n`` samples from the contact on, on the nominal grid."""
    meta = rec.metadata
    lost = meta.get("samples_lost", 0)
    if lost > max_lost * (rec.n_samples + lost):
        raise ValueError(f"{name}: {lost} of {rec.n_samples + lost} samples of the window lost, "
                         f"more than {max_lost:.0%}")
    if meta.get("trigger_time") is None:
        raise ValueError(f"{name}: missing label trigger_time (the contact sample's time)")
    start = round(meta["trigger_time"] * fs) / rec.fs  # the trigger slot on the estimated grid
    # samples that may be missing, at the ends as inside: the budget record kept the recording
    # by (a share of its whole window), so that what record keeps, the data set takes; checked
    # before the grid is made, so that a window longer than the recording allocates nothing
    budget = int(max_lost * (rec.n_samples + lost))
    if (n - budget > rec.n_samples + lost or rec.t[-1] < start + (n - 1 - budget) / fs
            or rec.t[0] > start + budget / fs):
        raise ValueError(f"{name}: too short: it covers {rec.t[-1] - start:.3f} s after the "
                         f"contact, the data set needs {(n - 1) / fs:.3f} s ({n} samples)")
    grid = start + np.arange(n) / fs
    slots = np.rint((rec.t - start) * fs).astype(np.int64)
    interpolated = n - np.intersect1d(slots, np.arange(n)).size
    # A gap of k lost samples spans k + 1 periods of the recording's own clock, but the samples
    # after it are placed by timestamps anchored anew, within the recording's stated uncertainty:
    # on the nominal grid the gap may hold that many points more than the driver counted lost
    # (at least one: the rounding to the grid); the loss itself is held to the driver's count
    # above. Only the gaps that reach into the window count.
    per_gap = max(1, math.ceil(meta.get("timestamp_uncertainty_s", 0.0) * fs))
    before, after = slots[:-1], slots[1:]
    gaps = int(np.count_nonzero((after - before > 1) & (before + 1 < n) & (after > 0)))
    if interpolated > budget + gaps * per_gap:
        raise ValueError(f"{name}: {interpolated} of the {n} samples after the contact lost, "
                         f"more than {max_lost:.0%} of its {rec.n_samples + lost}-sample window")
    return (np.interp(grid, rec.t, rec.ax), np.interp(grid, rec.t, rec.az), int(interpolated))


def _flags(rec: Recording) -> dict:
    """What the driver flagged in a recording and the data set would otherwise lose: samples
    whose timestamps are suspect (resampling reads them), a clock beyond its tolerance, and the
    sensor's own check (a stuck sensor, a second device); empty for a clean recording."""
    meta = rec.metadata
    flags = {}
    if meta.get("samples_timing_suspect"):
        flags["samples_timing_suspect"] = int(meta["samples_timing_suspect"])
    if meta.get("clock_outside_tolerance_suspected"):
        flags["clock_outside_tolerance_suspected"] = True
    sensor = (meta.get("sensor_check") or {}).get("flags") or []
    if sensor:
        flags["sensor_check"] = list(sensor)
    return flags


def _arrays(recordings, rows) -> dict:
    n = len(recordings)
    contact = np.array([float(r.metadata["contact"]) for r in recordings])
    return {
        "ax": np.array([r[0] for r in rows], dtype=np.float32),
        "az": np.array([r[1] for r in rows], dtype=np.float32),
        "material": np.array([str(r.metadata["material"]) for r in recordings]),
        "contact": contact,
        "contact_true": contact.copy(),
        "repetition": np.array([int(r.metadata["repetition"]) for r in recordings],
                               dtype=np.int64),
        "sweep_speed": np.full(n, np.nan),
        "tilt_ratio": np.full(n, np.nan),
        "seed_row": np.full(n, -1, dtype=np.int64),
    }


def _metadata(directory: Path, manifest: dict, entries, rows, fs: float, flags) -> dict:
    plan = manifest["plan"]
    config = {"format": FORMAT, "source": "recordings", "ebantenna_version": __version__,
              "scene": {"name": "recorded", "fs": fs,
                        "probe": {"length": plan["probe_length"]}},
              "plan": plan, "rig": manifest["rig"], "search": manifest["search"]}
    provenance = {
        "session": str(directory.resolve()),
        "manifest_sha256": file_sha256(directory / MANIFEST),
        "assembled_at": datetime.datetime.now(datetime.timezone.utc).isoformat(
            timespec="seconds"),
        "recordings": [{"file": e["file"], "sha256": e["sha256"],
                        "recorded_at": e.get("recorded_at")} for e in entries],
        "samples_interpolated": [r[2] for r in rows],
        "flags": flags,
        "recordings_flagged": sum(bool(f) for f in flags),
        "resampling": "cut at the contact sample, linear interpolation onto the nominal grid "
                      "from each recording's own timestamps",
    }
    return json.loads(json.dumps({"config": config, "provenance": provenance,
                                  "ebantenna_version": __version__, "n_signals": len(entries),
                                  "units": {"ax": "m/s^2", "az": "m/s^2", "contact": "m",
                                            "fs": "Hz"}}))


def _write(arrays: dict, metadata: dict, fs: float, path: Path) -> Dataset:
    path.parent.mkdir(parents=True, exist_ok=True)
    data = Dataset(fs=fs, metadata=metadata, path=path, **arrays)
    metadata["checksum_sha256"] = data.checksum()
    text = np.array(json.dumps(metadata))
    write_atomic(path, lambda tmp: np.savez_compressed(tmp, fs=np.float64(fs), metadata=text,
                                                       **arrays))
    for a in arrays.values():
        a.setflags(write=False)
    return data
