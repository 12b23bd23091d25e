"""Bad input to the accuracy intervals and the intervals on clusters: a clear error that names
the parameter, never a silently truncated count, an OverflowError or a ZeroDivisionError."""

import numpy as np
import pytest

from ebantenna.ml.metrics import accuracy, accuracy_interval
from ebantenna.paper.splits import split_folds
from ebantenna.paper.uncertainty import (
    ClusteredAccuracy,
    FoldAccuracy,
    PairedDifference,
    cluster_bootstrap,
    cluster_counts,
    cluster_mean_interval,
    design_effect,
    minimal_detectable_difference,
)

ROWS = [
    (lambda: accuracy_interval(3.7, 10), ValueError, "correct"),
    (lambda: accuracy_interval(3, 10.5), ValueError, "n"),
    (lambda: accuracy_interval(3, 10**400), ValueError, "n"),
    (lambda: accuracy_interval(float("nan"), 10), ValueError, "correct"),
    (lambda: accuracy_interval(True, 3), TypeError, "correct"),
    (lambda: accuracy_interval("3", 10), TypeError, "correct"),
    (lambda: accuracy_interval(4, 3), ValueError, "correct"),
    (lambda: accuracy(np.zeros((3, 3))), ValueError, "matrix"),
    (lambda: accuracy(np.array([])), ValueError, "matrix"),
    (lambda: accuracy(np.ones((2, 3))), ValueError, "matrix"),
    (lambda: accuracy(np.array([[np.nan, 1], [0, 1]])), ValueError, "matrix"),
    (lambda: accuracy(np.array([[-1, 2], [0, 1]])), ValueError, "matrix"),
    (lambda: design_effect([], []), ValueError, "k and n"),
    (lambda: design_effect([1.5, 2], [3, 3]), ValueError, "k"),
    (lambda: design_effect([4, 2], [3, 3]), ValueError, "k_j"),
    (lambda: design_effect([0, 0], [0, 3]), ValueError, "n_j"),
    (lambda: ClusteredAccuracy([1, 2], [3, 3], ""), TypeError, "unit"),
    (lambda: ClusteredAccuracy([1, 2], [3], "position"), ValueError, "k and n"),
    (lambda: cluster_counts([], []), ValueError, "correct"),
    (lambda: cluster_counts([1, 2], [0, 1]), ValueError, "correct"),
    (lambda: cluster_counts([1, 0], [0]), ValueError, "clusters"),
    (lambda: cluster_bootstrap([1, 2], [3, 3], resamples=0), ValueError, "resamples"),
    (lambda: cluster_bootstrap([1, 2], [3, 3], level=1.5), ValueError, "level"),
    (lambda: cluster_bootstrap([1, 2], [3, 3], seed=-1), ValueError, "seed"),
    (lambda: PairedDifference([1], [1], [2], "position"), ValueError, "two clusters"),
    (lambda: PairedDifference.from_recordings([1, 0], [1], [0, 1], "position"), ValueError,
     "correct_a"),
    (lambda: minimal_detectable_difference([1, 2], [2, 2], [3, 3], power=1.0), ValueError,
     "power"),
    (lambda: FoldAccuracy([(np.ones(3, bool), np.arange(3))], "position"), ValueError,
     "two folds"),
    (lambda: cluster_mean_interval([1.0, 2.0], [0, 0]), ValueError, "two clusters"),
    (lambda: cluster_mean_interval([1.0], [0, 1]), ValueError, "values and clusters"),
    (lambda: split_folds("grouped", [0, 1] * 3, [0.1, 0.2] * 3, folds=5), ValueError, "folds"),
    (lambda: split_folds("grouped", [0] * 6, np.arange(6), folds=1), ValueError, "folds"),
    (lambda: split_folds("grouped", [0] * 6, np.arange(6), folds=2.5), TypeError, "folds"),
    (lambda: split_folds("sideways", [0] * 6, np.arange(6)), ValueError, "kind"),
    (lambda: split_folds("blocked", [0] * 6, np.arange(6), seed=-2), ValueError, "seed"),
]


@pytest.mark.parametrize("call, error, name", ROWS)
def test_bad_input_is_refused_by_name(call, error, name):
    with pytest.raises(error, match=name):
        call()
