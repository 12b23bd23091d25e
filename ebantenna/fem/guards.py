"""Guards of the finite-element model: what a mesh can resolve, what the machine can hold.

Three limits are checked before anything is assembled; they live here, apart from the mesh and
the assembly, so that those read as the textbook writes them.

**Round-off** sets a limit to refinement. The assembled ``K`` is a discrete fourth derivative:
its entries grow like ``EI / h^3`` while ``K phi`` for the probe's low modes stays of the order
of ``EI phi / L^4``, so its condition number grows like ``(L/h)^4 = N^4``. Every solve with it
(Cholesky, LU, shift-invert Lanczos) returns mode shapes carrying rounding noise of relative size
about ``eps N^4`` at the mesh's own wavelength, and that noise, stiff as it is, raises the
frequencies. Even refined by the curvature Rayleigh quotient (:mod:`~ebantenna.fem.modal`), the
lowest frequency is then off by about ``(c eps N^4)^2``, with ``c`` between 1e-4 and 0.04 for
the probe's hinges and contacts (measured against :mod:`~ebantenna.fem.exact` at 2048 to 8192
elements). :func:`roundoff_error` is that estimate with ``c = 0.05``, above every ``c`` measured
up to :data:`MAX_ELEMENTS` (at 16384 elements one run exceeded it), and
:data:`MAX_ELEMENTS` the finest mesh whose estimate stays within :data:`ROUNDOFF_RTOL`:
:func:`check_resolvable` refuses finer ones, where more elements buy no accuracy, only noise.

**Memory.** :func:`check_memory` refuses a dense solve or a batch of sweeps that would take more
than the package's memory budget, before it is allocated.

**A contact the mesh can hold.** :func:`check_contact` refuses a contact closer to the hinge or
the tip than :data:`MIN_SPAN` of the length, where the short element beside it would leave the
factorisation of ``K`` without digits.

The public entry points (:func:`~ebantenna.fem.modal.modal_analysis`,
:func:`~ebantenna.fem.sweeps.natural_frequencies`, :func:`~ebantenna.fem.coupling.coupled_modes`,
...) call these once; the functions behind them take checked values.
"""

from __future__ import annotations

import math

import numpy as np

from .._budget import check_allocation
from .._validate import (
    check_array,
    check_in_range,
    check_int,
    check_nonnegative,
    check_positive,
    describe,
)

__all__ = [
    "roundoff_error",
    "check_resolvable",
    "check_memory",
    "check_contact",
    "check_sweep",
    "check_uniform_mesh",
    "ROUNDOFF_RTOL",
    "MAX_ELEMENTS",
    "MIN_SPAN",
]


#: Relative accuracy of the lowest frequency that a mesh must be able to hold in double precision.
ROUNDOFF_RTOL = 1e-6

#: The upper-bound constant ``c`` of :func:`roundoff_error` (measured: 1e-4 ... 0.04, the
#: eigenproblem theory page).
_ROUNDOFF_C = 0.05


def roundoff_error(n_elements: int) -> float:
    """A-priori estimate of the round-off error of the lowest frequency on ``n_elements``, relative.

    ``(c eps N^4)^2`` with ``c = 0.05`` (see the module's introduction): the condition number
    ``N^4`` of the assembled stiffness, times the machine epsilon, squared by the Rayleigh
    quotient. The discretisation error falls like ``N^-4``; the two cross at a few hundred
    elements below 1e-12, so a finer mesh than that buys nothing.

    Examples
    --------
    >>> from ebantenna.fem.guards import roundoff_error
    >>> f"{roundoff_error(2048):.0e}", f"{roundoff_error(16384):.0e}"
    ('4e-08', '6e-01')
    """
    n_elements = check_int("n_elements", n_elements, minimum=1)
    return (_ROUNDOFF_C * np.finfo(float).eps * float(n_elements) ** 4) ** 2


#: The finest mesh whose :func:`roundoff_error` stays within :data:`ROUNDOFF_RTOL`.
MAX_ELEMENTS = int((math.sqrt(ROUNDOFF_RTOL) / (_ROUNDOFF_C * np.finfo(float).eps)) ** 0.25)


def check_resolvable(n_elements: int, name: str = "n_elements") -> int:
    """Return ``n_elements``; raise ``ValueError`` above :data:`MAX_ELEMENTS` (round-off limit).

    ``name`` is the parameter the user passed (``rod_elements`` for the touched rod's mesh).
    """
    n_elements = check_int(name, n_elements, minimum=1)
    if n_elements > MAX_ELEMENTS:
        # the estimates in floats: N^4 and its square overflow beyond N ~ 1e38
        here = min(n_elements, 10**30)
        least = "" if here == n_elements else "at least "
        raise ValueError(
            f"{name} must be <= {MAX_ELEMENTS}, got {describe(n_elements)}: the stiffness "
            f"matrix's condition number grows like N^4 (here {least}{float(here) ** 4:.0e}), "
            f"and in double precision the lowest frequency would be off by {least}about "
            f"{roundoff_error(here):.0e} (relative), beyond {ROUNDOFF_RTOL:g}; at {MAX_ELEMENTS} "
            "elements the discretisation error is already far below that"
        )
    return n_elements


def check_memory(nbytes: float, what: str, parameter: str = "n_elements") -> None:
    """Raise before ``what`` allocates more than the package's memory budget.

    ``nbytes`` is the caller's a-priori estimate and ``parameter`` the argument that sets it.
    The budget is the one every allocation is held to (:func:`ebantenna.memory_budget`: half
    the available memory unless set), so the error is a :class:`ebantenna.MemoryBudgetError`, a
    :class:`ValueError`.
    """
    check_allocation(nbytes, parameter=parameter, what=what)


#: The shortest span, as a fraction of the probe's length, between the contact and the hinge or
#: the tip. The element there has a stiffness growing like ``h^-3``, and a soft contact near the
#: free tip leaves a short, nearly free end piece whose rounding reaches the lowest modes.
#: Measured on 64 elements against the same contact placed inside an element by the element's
#: shape functions: with a 1 N/m contact 1e-5 L from the tip the lowest frequency is 3 % off, and
#: at 1e-6 L the factorisation fails; from 2e-4 L on it agrees to 1e-9 for every stiffness from
#: 0.01 N/m to rigid (a rigid contact stays good to 2.5e-8 L, against :mod:`~ebantenna.fem.exact`).
#: 5e-4 L keeps a margin: 0.2 mm on the paper's probe, where the touched rod is 12 mm wide.
MIN_SPAN = 5e-4


def check_contact(name: str, contact, length: float) -> float:
    """Return ``contact``; raise unless it lies in the probe, :data:`MIN_SPAN` from either end.

    Examples
    --------
    >>> from ebantenna.fem.guards import check_contact
    >>> check_contact("contact", 0.2, 0.4)
    0.2
    >>> check_contact("contact", 1e-9, 0.4)
    Traceback (most recent call last):
    ...
    ValueError: contact must lie in [0.0002, 0.3998] m (0.0005 of the length ...), got 1e-09
    """
    contact = check_in_range(name, contact, 0.0, length)
    low, high = MIN_SPAN * length, (1.0 - MIN_SPAN) * length
    if not low <= contact <= high:
        raise ValueError(
            f"{name} must lie in [{low:.7g}, {high:.7g}] m ({MIN_SPAN:g} of the length or more "
            f"from the hinge and from the tip), got {contact!r}"
        )
    return contact


def check_sweep(probe, contacts, hinge_stiffness, contact_stiffness, n_elements, n_modes,
                shift=None):
    """The arguments of a sweep engine checked: ``(contacts, n_elements, n_modes)``.

    ``probe`` a :class:`~ebantenna.probe.Probe`; ``contacts`` a 1-D array of positions on it
    (:func:`check_contact`); ``hinge_stiffness`` >= 0 N m/rad (0 pinned, inf clamped);
    ``contact_stiffness`` > 0 N/m (inf rigid); ``n_elements`` from 2 to :data:`MAX_ELEMENTS`;
    ``n_modes`` from 1 to ``2 n_elements - 1`` (the free DOFs of the mesh); ``shift`` (1/s^2),
    when given, > 0. Anything else raises, naming the parameter.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.probe import Probe
    >>> check_sweep(Probe(), np.array([0.1]), np.inf, np.inf, 8, 20)
    Traceback (most recent call last):
    ...
    ValueError: n_modes must be <= 15, got 20
    """
    from ..probe import Probe

    if not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
    contacts = check_array("contacts", contacts, ndim=1)
    for contact in (contacts.min(), contacts.max()):  # the two nearest the ends
        check_contact("contacts", contact, probe.length)
    check_nonnegative("hinge_stiffness", hinge_stiffness, allow_inf=True)
    check_positive("contact_stiffness", contact_stiffness, allow_inf=True)
    n_elements = check_resolvable(check_int("n_elements", n_elements, minimum=2))
    n_modes = check_int("n_modes", n_modes, minimum=1, maximum=2 * n_elements - 1)
    if shift is not None:
        check_positive("shift", shift)
    return contacts, n_elements, n_modes


def check_uniform_mesh(nodes) -> tuple[np.ndarray, float]:
    """``nodes`` checked as a uniform mesh from 0 (at least two nodes, equal steps): ``(nodes,
    step)``. The steps may differ by the rounding of ``numpy.linspace`` (a few units in
    the last place of the length; 1e-9 of the step is far above it)."""
    nodes = check_array("nodes", nodes, ndim=1, min_length=2)
    step = (nodes[-1] - nodes[0]) / (nodes.size - 1)
    if nodes[0] != 0.0 or not step > 0 or np.any(np.abs(np.diff(nodes) - step) > 1e-9 * step):
        raise ValueError("nodes must be a uniform mesh from 0 (equal steps, increasing), as "
                         "numpy.linspace(0, length, n_elements + 1) makes")
    return nodes, float(nodes[1] - nodes[0])
