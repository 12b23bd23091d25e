"""The study on recorded data: a data set assembled from a recording session, and the study's
sections that need only recordings run on it."""

from .assemble import LABELS, MIN_SAMPLES, assemble_dataset
from .study import NOT_APPLICABLE, RECORDED_STEPS, intervals, reproduce_recorded

__all__ = ["assemble_dataset", "LABELS", "MIN_SAMPLES", "reproduce_recorded", "intervals",
           "NOT_APPLICABLE", "RECORDED_STEPS"]
