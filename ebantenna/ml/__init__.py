"""Machine learning on feature arrays: a hand-written SMO support vector classifier, NumPy
multilayer perceptrons, metrics, persistence and the paper's two experiments.

Nothing here knows about beams or signals: every function takes plain arrays.
"""

from .mlp import MLPClassifier, MLPRegressor
from .svc import SVC

__all__ = ["SVC", "MLPClassifier", "MLPRegressor"]
