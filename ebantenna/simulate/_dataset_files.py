"""The files of a cached data set: why one is stale, leftovers of interrupted builds, whole writes.

Private to :mod:`ebantenna.simulate.dataset`.
"""

from __future__ import annotations

import json
import logging
import os
import re
from pathlib import Path

import numpy as np

from .._tempfiles import TEMPORARY_PREFIX, process_running

__all__ = ["stale_reason", "remove_leftovers", "write_whole"]

#: The data set module's own logger: what is logged here belongs to its build.
log = logging.getLogger("ebantenna.simulate.dataset")


def stale_reason(stored, config: dict) -> str | None:
    """Why a cached file's configuration is not ``config`` (None when it is)."""
    if not isinstance(stored, dict):
        return "it records no configuration"
    changed = sorted(k for k in config.keys() | stored.keys() if stored.get(k) != config.get(k))
    if not changed:
        return None
    if "scene" in changed and isinstance(stored.get("scene"), dict):
        scene = config["scene"]
        changed.remove("scene")
        changed += [
            f"scene.{k}"
            for k in sorted(scene.keys() | stored["scene"].keys())
            if stored["scene"].get(k) != scene.get(k)
        ]
    return f"configuration changed ({', '.join(changed)})"


def remove_leftovers(path: Path) -> None:
    """Delete temporary files of ``path`` left by builds whose process no longer runs."""
    pattern = re.compile(re.escape(TEMPORARY_PREFIX) + r"(\d+)-" + re.escape(path.name))
    for tmp in path.parent.glob(f"{TEMPORARY_PREFIX}*-{path.name}"):
        match = pattern.fullmatch(tmp.name)
        if match is None or process_running(int(match.group(1))):
            continue  # another build still writing
        log.info("removing %s, left by an interrupted build", tmp)
        tmp.unlink(missing_ok=True)


def write_whole(path: Path, arrays: dict, metadata: dict, fs: float) -> None:
    """Save the data set at ``path`` so that a reader never sees half a file.

    Written under a name of its own, then renamed: concurrent builds into one folder each write
    their own. Interrupted, it is removed. The archive is not compressed: the signals are
    noise-dominated float32, which zlib barely shrinks, at seconds per main data set to write
    and again to read.
    """
    tmp = path.with_name(f"{TEMPORARY_PREFIX}{os.getpid()}-{path.name}")
    try:
        np.savez(
            tmp, fs=np.float64(fs), metadata=np.array(json.dumps(metadata)), **arrays
        )
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    log.info("wrote %s (%d signals)", path, metadata["n_signals"])
