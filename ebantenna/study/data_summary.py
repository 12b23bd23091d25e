"""Sections 2 and 3: the simulated data set (built once, then reused from its cache) and the
features of every recording."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._common import check_render, check_step

__all__ = ["DatasetResult", "compute", "render"]


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
    """

    path: str | None
    signals: int
    samples: int
    fs: float
    materials: tuple
    contacts: int
    checksum: str | None

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
    )


def render(result: DatasetResult, report, figures) -> None:
    """One paragraph: what the data set holds and where it came from."""
    check_render(result, DatasetResult, report, figures)
    report.heading("Data set")
    report.paragraph(
        f"{result.signals} simulated recordings of {result.samples} samples at {result.fs:g} Hz: "
        f"{len(result.materials)} materials x {result.contacts} contact positions x "
        f"{_repetitions(result)}, from {result.path} (SHA-256 {result.checksum})."
    )


def _repetitions(result: DatasetResult) -> str:
    """The repetitions per material and position, counted (the recordings over materials times
    positions), or 'repetitions' when they do not divide evenly."""
    cells = len(result.materials) * result.contacts
    if cells and result.signals % cells == 0:
        n = result.signals // cells
        return f"{n} repetition{'s' if n != 1 else ''}"
    return "repetitions"
