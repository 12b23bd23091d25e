"""Machine learning on feature arrays: a hand-written SMO support vector classifier, NumPy
multilayer perceptrons, metrics and persistence. The paper's two experiments built on them live
in :mod:`ebantenna.paper.experiments`.

Nothing here knows about beams or signals: every function takes plain arrays.
"""

from ._engine_check import check_engine
from .mlp import MLPClassifier, MLPRegressor
from .persistence import load_model, save_model
from .svc import SVC

__all__ = ["SVC", "MLPClassifier", "MLPRegressor", "save_model", "load_model", "check_engine"]
