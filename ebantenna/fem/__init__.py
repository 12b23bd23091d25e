"""Finite elements of the probe: Euler-Bernoulli beam elements, assembly, modes, exact reference.

- :mod:`~ebantenna.fem.symbolic`: the element derived with sympy, the paper's errata;
- :mod:`~ebantenna.fem.elements`: the same matrices in NumPy, written out as the textbook prints
  them;
- :mod:`~ebantenna.fem.assembly`: mesh, the assembly loop, supports;
- :mod:`~ebantenna.fem.guards`: what a mesh can resolve (round-off, memory, a contact near an end);
- :mod:`~ebantenna.fem.modal`: the generalized eigenproblem and the mode shapes;
- :mod:`~ebantenna.fem.sweeps`: natural frequencies for many contact positions at once;
- :mod:`~ebantenna.fem.exact`: the exact frequencies from the transcendental frequency equation;
- :mod:`~ebantenna.fem.zones`: the three zones of the dominant mode along the probe (Fig. 16);
- :mod:`~ebantenna.fem.coupling`: the touched rod as a vibrating body, coupled to the probe through
  the contact spring by Craig-Bampton component-mode synthesis;
- :mod:`~ebantenna.fem.banded` and :mod:`~ebantenna.fem.secular`: the engines of the sweeps, on
  the banded matrices and by the secular equation of the contact (behind
  :func:`natural_frequencies`);
- :mod:`~ebantenna.fem.hinge`: hinge stiffness and tip mass fitted to where the dominant mode
  changes.

(:mod:`~ebantenna.fem.symbolic` imports sympy and is not loaded until asked for.)
"""

from . import _assembly_engine  # noqa: F401  (adds "scatter" to assembly.ASSEMBLY_ENGINES)
from .assembly import Supports
from .coupling import CoupledModes, Rod, coupled_modes, monolithic_modes
from .exact import exact_frequencies
from .modal import ModalResult, modal_analysis
from .sweeps import natural_frequencies
from .zones import ZoneResult, dominant_mode_zones

__all__ = [
    "Supports",
    "ModalResult",
    "modal_analysis",
    "natural_frequencies",
    "exact_frequencies",
    "ZoneResult",
    "dominant_mode_zones",
    "Rod",
    "CoupledModes",
    "coupled_modes",
    "monolithic_modes",
]
