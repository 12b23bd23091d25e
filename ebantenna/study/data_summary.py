"""Sections 2 and 3: the simulated data set (built once, then reused from its cache) and the
features of every recording."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._common import check_render, check_step

__all__ = ["DatasetResult", "compute", "render"]

#: How the report names each engine of the strike march a data set records.
MARCHES = {"numpy": "the NumPy block march", "compiled": "the compiled march (the fast extra)"}


@dataclass(frozen=True)
class DatasetResult:
    """What the study ran on.

    Attributes
    ----------
    path : str or None
        The cached data set file.
    signals, samples : int
        Recordings, and samples per recording.
    fs : float
        Sampling frequency, Hz.
    materials : tuple of str
        Touched materials, in data-set order.
    contacts : int
        Distinct contact positions.
    checksum : str or None
        SHA-256 of the data set's arrays.
    saturated : dict or None
        The recordings the chip's range held at a rail on at least one sample
        (``saturated_recordings``); None when the data set does not count them.
    strike_march : str or None
        The engine of the strike march that simulated it (``'numpy'`` or ``'compiled'``, from
        its configuration; the two agree within a bound, not bit for bit); None for a data set
        that does not say (recorded on the rig, or saved by a version that did not record it).
    """

    path: str | None
    signals: int
    samples: int
    fs: float
    materials: tuple
    contacts: int
    checksum: str | None
    saturated: dict | None = None
    strike_march: str | None = None

    def to_dict(self) -> dict:
        """The summary record of the data set.

        Examples
        --------
        >>> DatasetResult(None, 2, 10, 1000.0, ("brass",), 1, None).to_dict()["materials"]
        ['brass']
        """
        return {
            "path": self.path,
            "signals": self.signals,
            "samples": self.samples,
            "materials": list(self.materials),
            "contacts": self.contacts,
            "checksum_sha256": self.checksum,
            "saturated": self.saturated,
            "strike_march": self.strike_march,
        }


def compute(ds) -> DatasetResult:
    """Describe the data set ``ds`` (an :class:`ebantenna.simulate.Dataset`)."""
    check_step(ds=ds)
    return DatasetResult(
        path=str(ds.path) if ds.path else None,
        signals=ds.n_signals,
        samples=ds.n_samples,
        fs=float(ds.fs),
        materials=tuple(dict.fromkeys(ds.material.tolist())),
        contacts=int(np.unique(ds.contact).size),
        checksum=ds.metadata.get("checksum_sha256"),
        saturated=saturated_recordings(ds),
        strike_march=_strike_march(ds.metadata),
    )


def _strike_march(metadata: dict) -> str | None:
    """The strike march's engine a data set's configuration names, if it names one."""
    config = metadata.get("config")
    march = config.get("strike_march") if isinstance(config, dict) else None
    return march if isinstance(march, str) else None


def saturated_recordings(ds) -> dict | None:
    """The recordings of ``ds`` that reached the chip's range: ``recordings`` (with at least one
    sample at a rail), ``samples`` (in all, X and Z together), ``most`` (in one recording),
    ``by_material`` and ``contact_range_m`` (the nearest and farthest contact among them, None
    if there are none), from the data set's ``samples_saturated``; None if it has no such
    count (its scene has no ``clipping`` effect).

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> ds = SimpleNamespace(n_signals=3, metadata={"samples_saturated": [0, 2, 1]},
    ...                      material=np.array(["wood", "steel", "steel"]),
    ...                      contact=np.array([0.38, 0.36, 0.39]))
    >>> saturated_recordings(ds)["by_material"], saturated_recordings(ds)["contact_range_m"]
    ({'wood': 0, 'steel': 2}, [0.36, 0.39])
    """
    counts = ds.metadata.get("samples_saturated")
    if counts is None:
        return None
    counts = np.asarray(counts)
    if counts.shape != (ds.n_signals,):
        raise ValueError(f"the data set's samples_saturated must hold one count per recording "
                         f"({ds.n_signals}), got shape {counts.shape}")
    hit = counts > 0
    return {
        "recordings": int(hit.sum()),
        "samples": int(counts.sum()),
        "most": int(counts.max(initial=0)),
        "by_material": {m: int(np.sum(hit & (ds.material == m)))
                        for m in dict.fromkeys(ds.material.tolist())},
        "contact_range_m": ([float(ds.contact[hit].min()), float(ds.contact[hit].max())]
                            if hit.any() else None),
    }


def render(result: DatasetResult, report, figures) -> None:
    """One paragraph: what the data set holds and where it came from."""
    check_render(result, DatasetResult, report, figures)
    report.heading("Data set")
    report.paragraph(
        f"{result.signals} simulated recordings of {result.samples} samples at {result.fs:g} Hz: "
        f"{len(result.materials)} materials x {result.contacts} contact positions x "
        f"{_repetitions(result)}, from {result.path} (SHA-256 {result.checksum}"
        + (f"; strikes marched by {MARCHES[result.strike_march]}, which the other engine "
           "matches within a bound, not bit for bit, so the two make different data sets"
           if result.strike_march in MARCHES else "") + "). "
        + saturation_sentence(result.saturated)
    )


def saturation_sentence(saturated: dict | None) -> str:
    """What the chip's range did to the recordings, from :func:`saturated_recordings`.

    Examples
    --------
    >>> saturation_sentence(None)
    'Its scene has no accelerometer range (no clipping effect): nothing was held at a rail.'
    >>> saturation_sentence({"recordings": 0, "samples": 0, "most": 0, "by_material": {},
    ...                      "contact_range_m": None})
    "No recording reached the chip's range."
    """
    if saturated is None:
        return ("Its scene has no accelerometer range (no clipping effect): nothing was held at "
                "a rail.")
    n = saturated["recordings"]
    if n == 0:
        return "No recording reached the chip's range."
    lo, hi = saturated["contact_range_m"]
    where = f"at {lo:g} m" if lo == hi else f"between {lo:g} and {hi:g} m"
    materials = ", ".join(f"{k} {v}" for k, v in saturated["by_material"].items() if v)
    samples = saturated["samples"]
    return (f"{n} recording{'s' if n != 1 else ''} reached the chip's range ({materials}; "
            f"contacts {where}): {samples} sample{'s' if samples != 1 else ''} in all, at most "
            f"{saturated['most']} in one, held at the rail. They stay in the data set, as a real "
            "recording keeps them.")


def _repetitions(result: DatasetResult) -> str:
    """The repetitions per material and position, counted (the recordings over materials times
    positions), or 'repetitions' when they do not divide evenly."""
    cells = len(result.materials) * result.contacts
    if cells and result.signals % cells == 0:
        n = result.signals // cells
        return f"{n} repetition{'s' if n != 1 else ''}"
    return "repetitions"
