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
from .probe import MATERIALS, Material, Probe, material
from .recording import Recording

__version__ = "0.2.0"

__all__ = ["Probe", "Material", "MATERIALS", "material", "Recording", "memory_budget",
           "set_memory_budget", "MemoryBudgetError", "__version__"]
