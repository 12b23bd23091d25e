"""Saving a finished recording so that it survives what comes after: written whole or not at all,
and, when the folder asked for cannot be written (a full disk, a folder removed while the rig
ran), written to a fallback location instead of being lost.

Used by ``acquire`` and ``record`` before anything else that can fail, so that a run whose
servos could not be released never loses the recording it made.
"""

from __future__ import annotations

import logging
import os
import tempfile
from pathlib import Path

__all__ = ["save_recording", "fallback_paths"]

logger = logging.getLogger(__name__)


def fallback_paths(name: str) -> list[Path]:
    """Where a recording goes when its own path cannot be written: the working directory, then
    the system's temporary folder, each under ``name`` with the process id (two runs never
    overwrite each other's fallback)."""
    stem = Path(name).name.removesuffix(".npz")
    unique = f"{stem}-{os.getpid()}.npz"
    return [Path.cwd() / unique, Path(tempfile.gettempdir()) / unique]


def save_recording(recording, path, *, fallback_name: str) -> tuple[Path | None, list[str]]:
    """Write ``recording`` atomically to ``path`` (None: straight to the fallbacks), else to the
    first of :func:`fallback_paths` that can be written.

    Returns the path written (None when nothing could be) and what failed on the way, one line
    per failed location; it never raises :class:`OSError` (an interrupt does go through: the
    caller decides what it means).
    """
    from .recording_session import write_atomic

    candidates = ([] if path is None else [Path(path)]) + fallback_paths(fallback_name)
    failures = []
    for candidate in candidates:
        try:
            target = candidate if candidate.suffix == ".npz" else candidate.with_name(
                candidate.name + ".npz")
            return write_atomic(target, recording.save), failures
        except (OSError, ValueError) as exc:
            failures.append(f"could not write {candidate} ({exc})")
            logger.error("could not save the recording to %s: %s", candidate, exc)
    return None, failures
