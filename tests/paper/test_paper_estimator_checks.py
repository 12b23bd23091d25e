"""scikit-learn's own estimator checks on the paper's estimators, where they apply.

The checks fit on generic random data: Gaussian features of any width, shifted to start at 0 for
estimators tagged ``positive_only``. The paper's estimators take physical measurements: the
distance estimators mode frequencies in Hz (strictly positive, they work with log f), the
single-mode one exactly one column, and the decay classifier exactly three columns (distance,
tau, gain) with tau and gain > 0. On data outside that domain each raises a ValueError naming the
problem, which is the behaviour we want; the checks that cannot give such data are listed below,
each with its reason, and every other check must pass. A check listed here that starts to pass
fails the test (strict xfail), so the list cannot silently go stale.
"""

import pytest
from sklearn.utils.estimator_checks import parametrize_with_checks

from ebantenna.paper.estimators import (
    DecayMaterialClassifier,
    FrequencyDistanceEstimator,
    MultiModeDistanceEstimator,
)

ESTIMATORS = [
    FrequencyDistanceEstimator(out_of_range="clip"),
    MultiModeDistanceEstimator(n_grid=200),
    DecayMaterialClassifier(degree=0),
]

# Checks that fit on several generic feature columns, or on features that start at exactly 0.
_GENERIC_DATA = (
    "check_fit_score_takes_y",
    "check_estimators_overwrite_params",
    "check_dont_overwrite_parameters",
    "check_estimators_fit_returns_self",
    "check_readonly_memmap_input",
    "check_n_features_in_after_fitting",
    "check_positive_only_tag_during_fit",
    "check_estimators_dtypes",
    "check_dtype_object",
    "check_pipeline_consistency",
    "check_estimators_nan_inf",
    "check_estimators_pickle",
    "check_f_contiguous_array_estimator",
    "check_methods_sample_order_invariance",
    "check_methods_subset_invariance",
    "check_dict_unchanged",
    "check_fit_idempotent",
    "check_fit_check_is_fitted",
    "check_n_features_in",
    "check_fit2d_predict1d",
    "check_fit2d_1sample",
    "check_fit2d_1feature",
)
_REGRESSOR_DATA = (
    "check_regressors_train",
    "check_regressor_data_not_an_array",
    "check_regressors_no_decision_function",
    "check_supervised_y_2d",
    "check_regressors_int",
)
_CLASSIFIER_DATA = (
    "check_estimators_overwrite_params",
    "check_estimators_fit_returns_self",
    "check_readonly_memmap_input",
    "check_n_features_in_after_fitting",
    "check_positive_only_tag_during_fit",
    "check_estimators_dtypes",
    "check_dtype_object",
    "check_pipeline_consistency",
    "check_estimators_pickle",
    "check_classifier_data_not_an_array",
    "check_classifiers_classes",
    "check_classifiers_train",
    "check_fit2d_1sample",
    "check_fit2d_1feature",
    "check_fit_idempotent",
    "check_fit_check_is_fitted",
    "check_n_features_in",
)


def _expected_failures(estimator):
    if isinstance(estimator, FrequencyDistanceEstimator):
        reason = ("generic data: the estimator takes one column of positive frequencies whose "
                  "calibration curve rises over its first three distances")
        out = dict.fromkeys(_GENERIC_DATA + _REGRESSOR_DATA, reason)
        out["check_fit1d"] = ("a 1-D array of dominant frequencies is read as one column: the "
                              "paper's feature is one number per recording")
        return out
    if isinstance(estimator, MultiModeDistanceEstimator):
        reason = "generic data: mode frequencies must be > 0 Hz (the cost uses log f)"
        return dict.fromkeys(_GENERIC_DATA + _REGRESSOR_DATA, reason)
    reason = "generic data: X must be (distance, tau > 0, gain > 0), three columns"
    return dict.fromkeys(_CLASSIFIER_DATA, reason)


@pytest.mark.filterwarnings("ignore::sklearn.exceptions.DataConversionWarning")
@parametrize_with_checks(ESTIMATORS, expected_failed_checks=_expected_failures)
def test_sklearn_estimator_checks(estimator, check):
    check(estimator)


@pytest.mark.filterwarnings("ignore::sklearn.exceptions.SkipTestWarning")
@pytest.mark.filterwarnings("ignore::sklearn.exceptions.DataConversionWarning")
@pytest.mark.parametrize("estimator", ESTIMATORS, ids=lambda e: type(e).__name__)
def test_enough_checks_apply(estimator):
    """Most API checks (parameters, cloning, unfitted errors, sparse and empty input, tags) pass;
    the domain-bound ones are at most two thirds."""
    from sklearn.utils.estimator_checks import check_estimator

    results = check_estimator(estimator, on_fail=None,
                              expected_failed_checks=_expected_failures(estimator))
    passed = [r for r in results if r["status"] == "passed"]
    failed = [r for r in results if r["status"] == "failed"]
    assert not failed, [r["check_name"] for r in failed]
    assert len(passed) >= 15, len(passed)
