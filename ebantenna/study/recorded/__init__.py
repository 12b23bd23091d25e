"""The study on recorded data: a data set assembled from a recording session, the study's
sections that need only recordings run on it, and the scene calibrated from recordings."""

from .assemble import LABELS, MIN_SAMPLES, assemble_dataset

__all__ = ["assemble_dataset", "LABELS", "MIN_SAMPLES"]
