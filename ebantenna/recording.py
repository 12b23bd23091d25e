"""`Recording`: the accelerations of the probe tip, as the simulator or the device delivers them."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ._validate import check_array, check_positive, describe, load_json, open_npz, output_path

__all__ = ["Recording"]

#: How far a step of ``t`` may lie from one sampling period, in periods: a device's sample times
#: carry timing jitter. A longer step is a gap where samples were lost (the device counts them).
STEP_TOLERANCE = 0.25


def _check_times(t: np.ndarray, fs: float) -> None:
    """Raise unless ``t`` increases in steps of one sampling period ``1/fs``, gaps aside.

    Samples may be missing (a device that loses some leaves gaps), but no step may be shorter
    than a period, and the typical (median) step must be one period: a ``t`` sampled at 500 Hz
    given with ``fs = 1000`` is refused, and so is a ``t`` with steps of random length.
    """
    steps = np.diff(t)
    if np.any(steps <= 0):
        i = int(np.argmax(steps <= 0))
        raise ValueError(
            f"t must increase strictly (sample times, s), got t[{i + 1}] = {t[i + 1]!r} "
            f"after t[{i}] = {t[i]!r}"
        )
    if steps.size == 0:
        return
    with np.errstate(over="ignore"):
        periods = steps * fs
    short = periods < 1.0 - STEP_TOLERANCE
    if np.any(short):
        i = int(np.argmax(short))
        raise ValueError(
            f"t must be sampled at fs = {fs:g} Hz, got a step of {periods[i]:.3g} periods of "
            f"1/fs after t[{i}] (no step may be shorter than {1 - STEP_TOLERANCE:g} period)"
        )
    typical = float(np.median(periods))
    if abs(typical - 1.0) > STEP_TOLERANCE:
        raise ValueError(
            f"t is not sampled uniformly at fs = {fs:g} Hz: its median step is {typical:.3g} "
            f"periods of 1/fs, not 1 (within {STEP_TOLERANCE:g})"
        )


def _check_metadata(metadata, where: str = "metadata") -> None:
    """Raise unless ``metadata`` is a dict with ``str`` keys (at every depth), JSON-serialisable.

    JSON turns a key ``1`` into ``"1"``: a recording saved and loaded would not equal itself.
    """
    if not isinstance(metadata, dict):
        raise TypeError(f"metadata must be a dict, got {type(metadata).__name__}")
    stack = [(metadata, where)]
    while stack:
        value, path = stack.pop()
        if isinstance(value, dict):
            for key, item in value.items():
                if not isinstance(key, str):
                    raise TypeError(
                        f"metadata keys must be str (JSON would turn {describe(key)} into a "
                        f"string), got {describe(key)} in {path}"
                    )
                stack.append((item, f"{path}[{key!r}]"))
        elif isinstance(value, list | tuple):  # only containers can hold a key
            stack.extend((item, f"{path}[{i}]") for i, item in enumerate(value)
                         if isinstance(item, dict | list | tuple))
    try:
        json.dumps(metadata)
    except (TypeError, ValueError, RecursionError) as exc:
        raise TypeError(f"metadata must be JSON-serialisable: {exc}") from exc


@dataclass(frozen=True, eq=False)
class Recording:
    """Tip accelerations in the sweep plane (X) and across it (Z), sampled at ``fs``.

    Parameters
    ----------
    t : array of shape (n,)
        Sample times, s.
    ax, az : arrays of shape (n,)
        Accelerations along X and Z, m/s^2.
    fs : float
        Nominal sampling frequency, Hz.
    metadata : dict
        JSON-serialisable description of where the data came from (scene, seed, device, samples
        lost).

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.recording import Recording
    >>> t = np.arange(4) / 1000.0
    >>> rec = Recording(t, np.zeros(4), np.ones(4), fs=1000.0)
    >>> rec.n_samples, rec.duration
    (4, 0.004)
    """

    t: np.ndarray
    ax: np.ndarray
    az: np.ndarray
    fs: float
    metadata: dict = field(default_factory=dict)

    def __post_init__(self):
        t = check_array("t", self.t, ndim=1)
        ax = check_array("ax", self.ax, ndim=1)
        az = check_array("az", self.az, ndim=1)
        if not (t.shape == ax.shape == az.shape):
            raise ValueError(
                f"t, ax and az must have the same length, got {t.shape}, {ax.shape}, {az.shape}"
            )
        fs = check_positive("fs", self.fs)
        _check_times(t, fs)
        for name, value in (("t", t), ("ax", ax), ("az", az)):
            value.setflags(write=False)
            object.__setattr__(self, name, value)
        object.__setattr__(self, "fs", fs)
        _check_metadata(self.metadata)

    @property
    def n_samples(self) -> int:
        """Number of samples."""
        return int(self.t.shape[0])

    @property
    def duration(self) -> float:
        """Nominal duration ``n_samples / fs``, s."""
        return self.n_samples / self.fs

    def save(self, path) -> Path:
        """Save as compressed ``.npz``: arrays ``t``, ``ax``, ``az``, ``fs``, JSON ``metadata``.

        Returns the file written: ``path`` with ``.npz`` appended if it lacks it. An empty name
        or a directory raises ``ValueError``.
        """
        path = output_path("path", path, ".npz")
        np.savez_compressed(
            path,
            t=self.t,
            ax=self.ax,
            az=self.az,
            fs=np.float64(self.fs),
            metadata=np.array(json.dumps(self.metadata, sort_keys=True)),
        )
        return path

    @classmethod
    def load(cls, path) -> Recording:
        """Load a recording written by :meth:`save` (never unpickles anything).

        Raises
        ------
        FileNotFoundError
            If there is no such file.
        TypeError
            If ``path`` is not a ``str`` or ``os.PathLike`` (bytes are refused).
        ValueError
            Naming the file, if it is not a regular file (a directory, a FIFO), truncated,
            damaged, declares arrays over the memory budget, or is not a recording (an array
            missing or of the wrong shape, metadata that is not a JSON object or nests too
            deeply).
        """
        what = "a recording"
        with open_npz(path, what) as data:
            path = Path(path)
            try:
                text = str(data["metadata"]) if "metadata" in data else "{}"
                metadata = load_json(text, path, what)
                if not isinstance(metadata, dict):
                    raise ValueError("metadata must be a JSON object")
                fs = data["fs"]
                if fs.shape != ():
                    raise ValueError(f"fs must be one number, got shape {fs.shape}")
                return cls(data["t"], data["ax"], data["az"], float(fs), metadata)
            except (TypeError, ValueError) as exc:  # json's errors are ValueErrors
                if str(path) in str(exc):
                    raise
                raise ValueError(f"{path} is not {what}: {exc}") from None
