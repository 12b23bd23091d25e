"""Signal processing for the antenna probe.

Features, filters, decay fit, time-frequency views, noise filtering and frequency tracking. The
paper's estimators built on these features live in :mod:`ebantenna.paper.estimators`.

Everything here takes a :class:`~ebantenna.recording.Recording` or plain arrays; nothing depends on
how the signal was made (beam model, simulator or the real accelerometer).
"""

from .decay import (
    DECAY_METHODS,
    MIN_DECAY_SAMPLES,
    DecayFit,
    band_passed_decay,
    envelope,
    fit_decay,
)
from .features import fft_features, norm_spectrum, resultant_acceleration
from .filters import (
    PAPER_FILTERS,
    STATED_ORDER,
    FilterSpec,
    SpecReport,
    apply_filter,
    check_specification,
    design_bandpass,
    filter_order,
    filter_time_constant,
    paper_filter,
)
from .kalman import KalmanFilter, KalmanResult
from .spectral import FREQUENCY_METHODS, WINDOWS, dominant_frequency, peak_frequencies
from .timefreq import TimeFrequency, morlet_scalogram, spectrogram
from .tracking import FrequencyTracker, TrackingResult

__all__ = [
    "resultant_acceleration",
    "norm_spectrum",
    "fft_features",
    "dominant_frequency",
    "peak_frequencies",
    "FREQUENCY_METHODS",
    "WINDOWS",
    "FilterSpec",
    "SpecReport",
    "PAPER_FILTERS",
    "STATED_ORDER",
    "filter_order",
    "design_bandpass",
    "paper_filter",
    "apply_filter",
    "check_specification",
    "filter_time_constant",
    "DecayFit",
    "DECAY_METHODS",
    "MIN_DECAY_SAMPLES",
    "envelope",
    "fit_decay",
    "band_passed_decay",
    "TimeFrequency",
    "spectrogram",
    "morlet_scalogram",
    "KalmanFilter",
    "KalmanResult",
    "FrequencyTracker",
    "TrackingResult",
]
