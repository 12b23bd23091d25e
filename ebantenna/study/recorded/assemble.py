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
- a missing label (material, contact distance, repetition);
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
from pathlib import Path

import numpy as np

from ... import __version__
from ...device.recording_session import MANIFEST, file_sha256, read_manifest, write_atomic
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
        Where to write ``recorded-<plan name>.npz``; default the session folder.
    max_lost : float, optional
        Largest share of a recording's window that may be missing, in [0, 1). Default the
        session's own limit (``max_lost`` in its manifest, the one ``record`` kept its
        recordings by; 0.02 for a session that does not record it).
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
    directory = Path(directory)
    manifest = read_manifest(directory / MANIFEST)
    if max_lost is None:
        max_lost = manifest.get("max_lost", 0.02)
    entries = sorted(manifest["recordings"].values(), key=lambda e: e["touch"])
    if not entries:
        raise ValueError(f"{directory}: the session holds no recordings yet")
    recordings = [_load_checked(directory, e) for e in entries]
    _check_labels_and_duplicates(recordings, entries)
    fs = _common_rate(recordings, entries, rate_tolerance)
    n = round(manifest["search"]["duration"] * fs)
    if n < MIN_SAMPLES:
        raise ValueError(f"{directory}: the session recorded {n} samples after each contact; the "
                         f"features need at least {MIN_SAMPLES}")
    rows = [_resampled(rec, e["file"], fs, n, max_lost) for rec, e in zip(recordings, entries,
                                                                           strict=True)]
    arrays = _arrays(recordings, rows)
    metadata = _metadata(directory, manifest, entries, rows, fs)
    return _write(arrays, metadata, fs, Path(out_dir or directory) /
                  f"recorded-{manifest['plan']['name']}.npz")


def _load_checked(directory: Path, entry: dict) -> Recording:
    """The entry's recording, its checksum verified."""
    path = directory / entry["file"]
    if not path.exists():
        raise ValueError(f"{path}: listed in the manifest but missing")
    if file_sha256(path) != entry["sha256"]:
        raise ValueError(f"{path}: damaged file (checksum differs from the manifest's)")
    try:
        return Recording.load(path)
    except ValueError as exc:
        raise ValueError(f"{path}: damaged file ({exc})") from None


def _check_labels_and_duplicates(recordings, entries) -> None:
    seen: dict = {}
    files: dict = {}
    for rec, entry in zip(recordings, entries, strict=True):
        missing = [k for k in LABELS if rec.metadata.get(k) is None]
        if missing:
            raise ValueError(f"{entry['file']}: missing label(s) {', '.join(missing)}")
        key = (rec.metadata["material"], round(float(rec.metadata["contact"]), 6),
               int(rec.metadata["repetition"]))
        if key in seen:
            raise ValueError(f"{entry['file']}: duplicate of {seen[key]} (material {key[0]}, "
                             f"contact {key[1]} m, repetition {key[2]})")
        if entry["sha256"] in files:
            raise ValueError(f"{entry['file']}: duplicate of {files[entry['sha256']]} (the "
                             "same file twice)")
        seen[key], files[entry["sha256"]] = entry["file"], entry["file"]


def _common_rate(recordings, entries, tolerance: float) -> float:
    """The configured sample rate all recordings share, Hz."""
    rates = [rec.metadata.get("sample_rate_hz") for rec in recordings]
    first = rates[0]
    for rec, rate, entry in zip(recordings, rates, entries, strict=True):
        if rate is None:
            raise ValueError(f"{entry['file']}: missing label sample_rate_hz (the configured "
                             "sample rate)")
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
    grid = start + np.arange(n) / fs
    # samples that may be missing, at the ends as inside: the budget record kept the recording
    # by (a share of its whole window), so that what record keeps, the data set takes
    budget = int(max_lost * (rec.n_samples + lost))
    if rec.t[-1] < grid[-1] - budget / fs or rec.t[0] > start + budget / fs:
        raise ValueError(f"{name}: too short: it covers {rec.t[-1] - start:.3f} s after the "
                         f"contact, the data set needs {(n - 1) / fs:.3f} s ({n} samples)")
    slots = np.rint((rec.t - start) * fs).astype(np.int64)
    interpolated = n - np.intersect1d(slots, np.arange(n)).size
    if interpolated > budget:
        raise ValueError(f"{name}: {interpolated} of the {n} samples after the contact lost, "
                         f"more than {max_lost:.0%} of its {rec.n_samples + lost}-sample window")
    return (np.interp(grid, rec.t, rec.ax), np.interp(grid, rec.t, rec.az), int(interpolated))


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


def _metadata(directory: Path, manifest: dict, entries, rows, fs: float) -> dict:
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
