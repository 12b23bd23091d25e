"""Supports of the probe: the hinge at x = 0, the touched object at the contact, the free tip."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .._validate import check_choice, check_positive

__all__ = ["Supports", "HINGES"]

#: Named hinge conditions; a positive number instead means a rotational spring (N m/rad).
HINGES = ("clamped", "pinned")


@dataclass(frozen=True)
class Supports:
    """How the probe is held and touched.

    Parameters
    ----------
    contact : float or None
        Distance of the contact point from the hinge, m, inside ``(0, L)``; ``None`` for a probe
        that touches nothing.
    hinge : {"clamped", "pinned"} or float
        The hinge at x = 0 (the servo shaft): clamped (no deflection, no rotation), pinned (no
        deflection, free rotation) or, as a positive number, a rotational spring in N m/rad.
    contact_stiffness : float
        Translational stiffness of the contact, N/m; ``math.inf`` (default) is a rigid pin.

    Examples
    --------
    >>> from ebantenna.fem import Supports
    >>> Supports(contact=0.2).hinge
    'clamped'
    >>> Supports(contact=0.2, hinge=50.0).hinge_stiffness
    50.0
    """

    contact: float | None = None
    hinge: str | float = "clamped"
    contact_stiffness: float = math.inf

    def __post_init__(self):
        if self.contact is not None:
            check_positive("contact", self.contact)
        if isinstance(self.hinge, str):
            check_choice("hinge", self.hinge, HINGES)
        else:
            object.__setattr__(
                self, "hinge", check_positive("hinge (rotational stiffness)", self.hinge)
            )
        object.__setattr__(
            self,
            "contact_stiffness",
            check_positive("contact_stiffness", self.contact_stiffness, allow_inf=True),
        )

    @property
    def hinge_stiffness(self) -> float:
        """Rotational stiffness of the hinge, N m/rad: inf if clamped, 0 if pinned."""
        if self.hinge == "clamped":
            return math.inf
        if self.hinge == "pinned":
            return 0.0
        return float(self.hinge)

    @property
    def rigid_contact(self) -> bool:
        """True when the contact is a rigid pin (and there is a contact)."""
        return self.contact is not None and math.isinf(self.contact_stiffness)

    def describe(self) -> str:
        """The hinge as the CLI's JSON reports it."""
        return self.hinge if isinstance(self.hinge, str) else f"spring {self.hinge:g} N m/rad"
