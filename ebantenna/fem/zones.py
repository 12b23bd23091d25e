"""The three zones of the dominant mode along the probe (Figs. 16 and 17 of the paper).

The paper's "dominant (most flexible) mode" is the lowest one. Where it lives changes as the contact
moves from the hinge to the tip:

- **zone 1**, contact near the hinge: the short span between hinge and contact is stiff and the
  overhang swings like a cantilever on the contact (Fig. 17a); almost all of the mode's kinetic
  energy is in the overhang;
- **zone 3**, contact near the tip: the overhang is now a short, stiff cantilever and the long span
  between hinge and contact vibrates instead (Fig. 17c); the overhang holds little of the energy;
- **zone 2** in between: both parts share the mode, which changes character (Fig. 17b).

The zones are read off the mode shapes, by the share of the lowest mode's kinetic energy in the
overhang (:meth:`~ebantenna.fem.modal.ModalResult.overhang_mass_fraction`), with thresholds that say
what "almost all" and "little" mean. The frequency itself stops rising in zone 2 and falls in zone
3: the lowest frequency is *not* monotonic in the contact position, which is why a calibration from
the dominant frequency alone fails beyond about 80 % of the length.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import check_array, check_in_range
from ..probe import Probe
from .assembly import Supports
from .modal import modal_analysis

__all__ = ["ZoneResult", "dominant_mode_zones"]


@dataclass(frozen=True, eq=False)
class ZoneResult:
    """Zones of the dominant mode along a sweep of contact positions.

    Attributes
    ----------
    contacts : ndarray
        Contact positions, m.
    frequency : ndarray
        Frequency of the dominant (lowest) mode, Hz.
    overhang_fraction : ndarray
        Share of that mode's kinetic energy between contact and tip (0..1).
    zone : ndarray of int
        1, 2 or 3 per contact.
    """

    contacts: np.ndarray
    frequency: np.ndarray
    overhang_fraction: np.ndarray
    zone: np.ndarray

    def boundaries(self) -> tuple[float, float]:
        """Contact positions (m) where zone 2 begins and zone 3 begins (NaN if never reached)."""

        def first(z):
            hits = np.flatnonzero(self.zone >= z)
            return float(self.contacts[hits[0]]) if hits.size else float("nan")

        return first(2), first(3)

    def plot(self, ax=None):
        """Dominant frequency against contact distance, zones shaded (Fig. 16); returns the Axes."""
        from .plot import plot_zones

        return plot_zones(self, ax=ax)


def dominant_mode_zones(
    probe: Probe,
    contacts,
    *,
    hinge="clamped",
    n_elements: int = 32,
    upper: float = 0.9,
    lower: float = 0.1,
) -> ZoneResult:
    """Classify contact positions into the three zones of Fig. 16 from the mode shapes.

    Parameters
    ----------
    probe : Probe
    contacts : array of shape (n,)
        Contact positions from the hinge, m, increasing, each in ``(0, L)``.
    hinge : {"clamped", "pinned"} or float
        As in :class:`Supports`.
    n_elements : int
        Mesh size for each position.
    upper, lower : float
        Zone 1 where the overhang holds at least ``upper`` of the dominant mode's kinetic energy,
        zone 3 where it holds at most ``lower``, zone 2 between.

    Returns
    -------
    ZoneResult

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna import Probe
    >>> from ebantenna.fem.zones import dominant_mode_zones
    >>> z = dominant_mode_zones(Probe(), np.array([0.1, 0.3, 0.38]) )
    >>> z.zone
    array([1, 2, 3])
    """
    contacts = check_array("contacts", contacts, ndim=1)
    upper = check_in_range("upper", upper, 0.0, 1.0)
    lower = check_in_range("lower", lower, 0.0, upper)
    frequency = np.empty(contacts.size)
    fraction = np.empty(contacts.size)
    for i, c in enumerate(contacts):
        res = modal_analysis(
            probe, Supports(contact=float(c), hinge=hinge), n_elements=n_elements, n_modes=1
        )
        frequency[i] = res.frequencies[0]
        fraction[i] = res.overhang_mass_fraction()[0]
    zone = np.where(fraction >= upper, 1, np.where(fraction <= lower, 3, 2))
    return ZoneResult(contacts, frequency, fraction, zone)
