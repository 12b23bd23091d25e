"""scikit-learn's own estimator checks, run on the hand-written estimators."""

import pytest
from sklearn.utils.estimator_checks import parametrize_with_checks

from ebantenna.ml import SVC, MLPClassifier, MLPRegressor

ESTIMATORS = [
    SVC(),
    SVC(libsvm_compat=True, kernel="linear", selection="first-order"),
    SVC(probability=True, random_state=0),
    SVC(kernel="precomputed"),
    MLPClassifier(hidden_layer_sizes=(10,), max_iter=200, random_state=0),
    MLPClassifier(hidden_layer_sizes=(8,), solver="scg", max_iter=50, random_state=0),
    MLPRegressor(hidden_layer_sizes=(10,), max_iter=300, random_state=0),
    MLPClassifier(hidden_layer_sizes=(8,), solver="lbfgs", max_iter=100, random_state=0),
    MLPRegressor(hidden_layer_sizes=(8,), solver="lbfgs", max_iter=200, random_state=0),
]


def _expected_failures(estimator):
    """The checks that scikit-learn itself expects its own SVC to fail, for the same reason."""
    if isinstance(estimator, SVC):
        # weights multiply C per sample, as in libsvm: a repeated sample and a doubled weight
        # give the same optimum but different SMO paths, hence different points of the
        # tolerance neighbourhood
        reason = "sample_weight is not equivalent to removing/repeating samples."
        return {"check_sample_weight_equivalence_on_dense_data": reason,
                "check_sample_weight_equivalence_on_sparse_data": reason}
    return {}


# The checks fit on tiny data sets with few epochs: convergence warnings there say nothing.
@pytest.mark.filterwarnings("ignore::sklearn.exceptions.ConvergenceWarning")
@parametrize_with_checks(ESTIMATORS, expected_failed_checks=_expected_failures)
def test_sklearn_estimator_checks(estimator, check):
    check(estimator)
