"""Machine learning on feature arrays: a hand-written SMO support vector classifier, NumPy
multilayer perceptrons, metrics and persistence. The paper's two experiments built on them live
in :mod:`ebantenna.paper.experiments`.

Nothing here knows about beams or signals: every function takes plain arrays.

``check_engine()`` checks the engine that ``EBANTENNA_ENGINE`` asks for before a command's work;
``smo_engine_status()`` says whether the compiled SMO engine (numba, the ``fast`` extra) works
here, why not, and what loading it cost. Importing this package adds the SMO engines to
:data:`ebantenna.ml.smo.SMO_ENGINES`.
"""

from . import _smo_state  # noqa: F401  (adds "numpy" to smo.SMO_ENGINES)
from ._engine_check import check_engine
from ._smo_compiled import engine_status as smo_engine_status  # (adds "compiled" too)
from .mlp import MLPClassifier, MLPRegressor
from .persistence import load_model, save_model
from .svc import SVC

__all__ = ["SVC", "MLPClassifier", "MLPRegressor", "save_model", "load_model", "check_engine",
           "smo_engine_status"]
