"""Everything that belongs to this paper and to no other.

- :mod:`~ebantenna.paper.printed`: every number, table and matrix the paper prints, with where.
- :mod:`~ebantenna.paper.protocol`: the data set it recorded and how each model was fed (materials,
  positions, repetitions, splits, network settings).
- :mod:`~ebantenna.paper.data`: the paper's data set, simulated in the ``paper`` scene, with
  the rig's assumed scatter from one repetition to the next.
- :mod:`~ebantenna.paper.feature_table`: the per-recording features the study computes from the data
  set (dominant frequency, two strongest peaks, decay fit, FFT vectors), in parallel.
- :mod:`~ebantenna.paper.estimators`: the distance and material estimators from those features,
  as scikit-learn estimators.
- :mod:`~ebantenna.paper.experiments` and :mod:`~ebantenna.paper.plots`: the paper's SVM and
  network experiments and their figures beside the printed ones.
- Beyond the paper: :mod:`~ebantenna.paper.position_aware` (the spectrum read at its estimated
  contact distance) and :mod:`~ebantenna.paper.mode_curves` (material and distance fitted
  together from two mode frequencies); :mod:`~ebantenna.paper.controls` (what a classifier
  learns).
- :mod:`~ebantenna.paper.uncertainty`: what an accuracy can carry: its unit of replication,
  the 95 % interval on that unit (clustered repetitions, the design effect), its spread over
  folds, and paired comparisons with the difference a design detects.

The generic stages (:mod:`ebantenna.fem`, :mod:`ebantenna.simulate`, :mod:`ebantenna.signal`,
:mod:`ebantenna.ml`) know nothing of this paper's numbers; this package may use all of them.
"""

from .estimators import (
    DecayMaterialClassifier,
    FrequencyDistanceEstimator,
    MultiModeDistanceEstimator,
)
from .printed import PAPER_ANN, PAPER_SVM, PaperConfusion, PrintedNumber

__all__ = [
    "FrequencyDistanceEstimator",
    "MultiModeDistanceEstimator",
    "DecayMaterialClassifier",
    "PrintedNumber",
    "PaperConfusion",
    "PAPER_ANN",
    "PAPER_SVM",
]
