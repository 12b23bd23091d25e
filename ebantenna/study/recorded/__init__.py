"""The study on recorded data: a data set assembled from a recording session, and the study's
sections that need only recordings run on it, and the scene calibrated from recordings."""

from .assemble import LABELS, MIN_SAMPLES, assemble_dataset
from .calibration import (
    Calibration,
    IdentifiabilityWarning,
    ModelMisfitWarning,
    calibrate,
    plot_calibration,
)
from .planning import protocol_plan
from .study import (
    NOT_APPLICABLE,
    RECORDED_STEPS,
    SECTION_MINIMUM,
    classification_interval,
    intervals,
    placement_interval,
    reproduce_recorded,
)

__all__ = ["assemble_dataset", "LABELS", "MIN_SAMPLES", "protocol_plan", "reproduce_recorded",
           "intervals", "classification_interval", "placement_interval", "NOT_APPLICABLE",
           "RECORDED_STEPS", "SECTION_MINIMUM", "Calibration", "calibrate", "plot_calibration",
           "IdentifiabilityWarning", "ModelMisfitWarning"]
