"""ebantenna: a vibrating antenna probe, from Euler-Bernoulli beams to material classification.

Subpackages, in the order the data flows:

- :mod:`ebantenna.fem`: beam elements derived with sympy, assembly, modal analysis, exact reference;
- :mod:`ebantenna.simulate`: scene-based simulator of the tip accelerometer;
- :mod:`ebantenna.signal`: features, filters, decay fit, time-frequency views, tracking;
- :mod:`ebantenna.ml`: hand-written SMO kernel SVM and NumPy MLP;
- :mod:`ebantenna.device`: MPU6050 and PCA9685 drivers, with a simulated I2C bus.

Below them all, :mod:`ebantenna.chips` holds the chips' register maps and datasheet constants.
"""

from ._budget import MemoryBudgetError, memory_budget, set_memory_budget

__version__ = "0.2.0"

__all__ = ["Probe", "Material", "MATERIALS", "material", "Recording", "memory_budget",
           "set_memory_budget", "MemoryBudgetError", "__version__"]


def __getattr__(name: str):
    """The names that need NumPy, imported on first use (PEP 562).

    ``import ebantenna`` then takes milliseconds, not the second or more that NumPy takes on a
    loaded machine: the ``ebantenna`` command installs its signal handlers before anything heavy
    is imported, so that Ctrl-C at any moment of its start ends in one line.
    """
    if name in ("Probe", "Material", "MATERIALS", "material", "probe"):
        from .probe import MATERIALS, Material, Probe, material

        found = {"Probe": Probe, "Material": Material, "MATERIALS": MATERIALS,
                 "material": material}
    elif name in ("Recording", "recording"):
        from .recording import Recording

        found = {"Recording": Recording}
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    # the import has set the submodule (``ebantenna.probe``) as an attribute of the package
    return found[name] if name in found else globals()[name]


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
