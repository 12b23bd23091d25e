"""Every number the paper prints, once, with where it is printed.

The reproduction quotes these beside its own results; nothing here is computed. Each scalar is a
:class:`PrintedNumber` (value, unit, figure/table/section, and the sentence it comes from); the
two confusion matrices are :class:`PaperConfusion` records transcribed cell by cell. Printed
material that belongs to a stage's public contract stays with that stage and is only indexed
here: the filter specifications of Tables 1 and 2 (:data:`TABLE_1`, :data:`TABLE_2`, from
:data:`ebantenna.signal.PAPER_FILTERS`) and the element and two-element matrices of section 2.2,
printed between its eqs. 2 and 3 without numbers of their own
(:func:`ebantenna.fem.symbolic.paper_matrices`, with their errata).

Examples
--------
>>> from ebantenna.paper import printed
>>> printed.SVM_TEST_ACCURACY.value, printed.SVM_TEST_ACCURACY.where
(0.992, 'Fig. 15, section 4.3')
>>> printed.percent(printed.ANN_ACCURACY)
'80.8 %'
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..ml.metrics import accuracy
from ..signal.filters import PAPER_FILTERS

__all__ = [
    "PrintedNumber",
    "PaperConfusion",
    "UNITS",
    "PRIOR_DISTANCE_ACCURACY_CM",
    "PROBE_LENGTH_CM",
    "TUBE_OUTER_DIAMETER_CM",
    "TUBE_INNER_DIAMETER_CM",
    "SENSOR_RANGE_G",
    "SAMPLING_FREQUENCY_KHZ",
    "MAX_FREQUENCY_HZ",
    "I2C_RATE_KHZ",
    "DEVIATION_CM",
    "DEVIATION_50CM_PROBE_CM",
    "SPREAD_RATIO",
    "MODE_CHANGE_RATIO",
    "PVC_WOOD_OVERLAP_CM",
    "HIGH_BAND_CUTOFFS_HZ",
    "ANN_ACCURACY",
    "SVM_TRAIN_ACCURACY",
    "SVM_TEST_ACCURACY",
    "SVM_ITERATIONS",
    "SVM_SAMPLES",
    "EARLY_MODES_SAMPLES",
    "LONG_LIVED_SAMPLES",
    "PAPER_ANN",
    "PAPER_SVM",
    "TABLE_1",
    "TABLE_2",
    "NUMBERS",
    "percent",
]


#: The units a printed number may carry (fractions for percentages).
UNITS = ("cm", "fraction", "fraction of L", "Hz", "kHz", "g", "samples", "iterations")


@dataclass(frozen=True)
class PrintedNumber:
    """One number as the paper prints it.

    Attributes
    ----------
    value : float
        The value in the unit given (fractions for percentages: 0.808 for 80.8 %).
    unit : str
        Its unit: one of :data:`UNITS`.
    where : str
        Figure, table, equation or section that prints it.
    quote : str
        The sentence (shortened) the number comes from.
    """

    value: float
    unit: str
    where: str
    quote: str

    def __post_init__(self):
        if self.unit not in UNITS:
            raise ValueError(f"unit must be one of {UNITS}, got {self.unit!r}")


def percent(number: PrintedNumber) -> str:
    """A printed fraction as the paper writes it, with one decimal: ``'99.7 %'``.

    Examples
    --------
    >>> percent(SVM_TRAIN_ACCURACY)
    '99.7 %'
    """
    if not isinstance(number, PrintedNumber):
        raise TypeError(f"number must be a PrintedNumber, got {type(number).__name__}")
    if number.unit not in ("fraction", "fraction of L"):
        raise ValueError(f"number must be a fraction, got unit {number.unit!r}")
    return f"{100 * number.value:.1f} %"


PRIOR_DISTANCE_ACCURACY_CM = PrintedNumber(
    0.5, "cm", "section 1 (Hoinville et al., 2014)",
    "predicting the contact distances up to an accuracy level of 0.5 cm, using an ANN",
)
PROBE_LENGTH_CM = PrintedNumber(
    40.0, "cm", "section 2.1 and section 4.1.1",
    "the antenna length is taken as 40 cm",
)
TUBE_OUTER_DIAMETER_CM = PrintedNumber(
    0.8, "cm", "section 3",
    "an acrylic fiber tube of 0.8 cm outer diameter, 0.6 cm inner diameter, and 40 cm length",
)
TUBE_INNER_DIAMETER_CM = PrintedNumber(
    0.6, "cm", "section 3",
    "an acrylic fiber tube of 0.8 cm outer diameter, 0.6 cm inner diameter, and 40 cm length",
)
SENSOR_RANGE_G = PrintedNumber(
    16.0, "g", "section 3",
    "The maximum sensitivity of the sensor is +-16g (g = 9.81 m/s^2)",
)
SAMPLING_FREQUENCY_KHZ = PrintedNumber(
    1.0, "kHz", "section 3",
    "The sampling frequency of the data acquisition is set as 1 kHz",
)
MAX_FREQUENCY_HZ = PrintedNumber(
    512.0, "Hz", "section 3",
    "to capture all frequencies of vibration up to 512 Hz",
)
I2C_RATE_KHZ = PrintedNumber(
    400.0, "kHz", "section 3",
    "the maximum data transferring rate of the sensor via I2C is 400 kHz",
)
DEVIATION_CM = PrintedNumber(
    29.5, "cm", "Fig. 9, section 4.1.1",
    "a deviation from that linear behavior could be observed at 29.5 cm away from the hinge point",
)
DEVIATION_50CM_PROBE_CM = PrintedNumber(
    39.5, "cm", "section 4.1.1",
    "After increasing the length of the antenna to 50 cm, a similar deviation could be observed "
    "at 39.5cm away from the hinge point",
)
SPREAD_RATIO = PrintedNumber(
    0.8, "fraction of L", "Fig. 10, section 4.1.1",
    "this variation occurs at 80% of the antenna length away from the hinge point",
)
MODE_CHANGE_RATIO = PrintedNumber(
    0.8, "fraction of L", "Fig. 16, section 4.4",
    "at the 80% of the total antenna length, the mode of vibration is entirely changed",
)
PVC_WOOD_OVERLAP_CM = PrintedNumber(
    26.0, "cm", "Fig. 11, section 4.1.2",
    "an overlap is observed between PVC and WOOD at 26 cm away from the hinge point",
)
HIGH_BAND_CUTOFFS_HZ = (
    PrintedNumber(100.0, "Hz", "section 4.1.2",
                  "pass band cutoff frequencies are set in the range of 100 Hz- 200 Hz"),
    PrintedNumber(200.0, "Hz", "section 4.1.2",
                  "pass band cutoff frequencies are set in the range of 100 Hz- 200 Hz"),
)
ANN_ACCURACY = PrintedNumber(
    0.808, "fraction", "Fig. 12, section 4.2",
    "The average overall accuracy for material classification is 80.8%",
)
SVM_TRAIN_ACCURACY = PrintedNumber(
    0.997, "fraction", "Fig. 15, section 4.3",
    "The accuracy for training and testing is 99.7% and 99.2%, respectively",
)
SVM_TEST_ACCURACY = PrintedNumber(
    0.992, "fraction", "Fig. 15, section 4.3",
    "The accuracy for training and testing is 99.7% and 99.2%, respectively",
)
SVM_ITERATIONS = PrintedNumber(
    50, "iterations", "section 4.3",
    "The optimum model was obtained for 2.0 gamma values and with 50 iterations",
)
SVM_SAMPLES = PrintedNumber(
    6000, "samples", "section 4.3",
    "The batch size is selected as 6000 samples and 80% of it is used as the training dataset",
)
EARLY_MODES_SAMPLES = PrintedNumber(
    100, "samples", "Fig. 19, section 4.4",
    "in the beginning there are many vibration modes and most of them disappear after 100 samples",
)
LONG_LIVED_SAMPLES = PrintedNumber(
    300, "samples", "Fig. 18, section 4.4",
    "these frequency components remain powerful during more than 300 samples of the signal",
)


@dataclass(frozen=True)
class PaperConfusion:
    """A confusion matrix as printed in the paper.

    Attributes
    ----------
    figure : str
        Where it is printed.
    labels : tuple of str
        Class names in the printed order.
    matrices : dict of str to ndarray
        Counts per split ('train', 'test' or 'all'), rows = true class, columns = predicted class.
    reported_accuracy : dict of str to float
        The accuracies printed with the figure (fractions).
    note : str
        How the printed figure was read.

    Examples
    --------
    >>> round(PAPER_SVM.accuracy("train"), 4), PAPER_SVM.reported_accuracy["train"]
    (0.9965, 0.997)
    >>> int(PAPER_SVM.matrices["test"].sum())
    1200
    """

    figure: str
    labels: tuple[str, ...]
    matrices: dict = field(default_factory=dict)
    reported_accuracy: dict = field(default_factory=dict)
    note: str = ""

    def accuracy(self, split: str) -> float:
        """Accuracy recomputed from the printed counts of ``split``."""
        if split not in self.matrices:
            raise ValueError(f"split must be one of {sorted(self.matrices)}, got {split!r}")
        return accuracy(self.matrices[split])


_FIG12_PRINTED = np.array(
    [  # rows: output (predicted) class; columns: target (true) class, MATLAB's plotconfusion
        [808, 58, 22, 52, 20],
        [32, 685, 33, 74, 23],
        [14, 41, 709, 39, 55],
        [31, 79, 53, 648, 41],
        [21, 43, 70, 55, 757],
    ]
)

#: Fig. 12: the 53-neuron tanh network, all samples (training, validation and test together).
PAPER_ANN = PaperConfusion(
    figure="Fig. 12",
    labels=("aluminium", "pvc", "brass", "wood", "steel"),
    matrices={"all": _FIG12_PRINTED.T.copy()},
    reported_accuracy={"all": ANN_ACCURACY.value},
    note="Printed as MATLAB's plotconfusion (rows: output class, columns: target class); stored "
    "transposed. The printed row totals give the precisions (84.2 % for aluminium), the column "
    "totals the recalls (89.2 %). The wood row prints '76.1' without its percent sign.",
)

#: Fig. 15: the RBF SVM trained one-vs-rest; white cells training, red cells test.
PAPER_SVM = PaperConfusion(
    figure="Fig. 15",
    labels=("aluminium", "brass", "pvc", "steel", "wood"),
    matrices={
        "train": np.array([
            [886, 1, 0, 1, 1],
            [3, 966, 0, 1, 0],
            [0, 1, 980, 3, 0],
            [2, 0, 0, 1020, 1],
            [1, 0, 1, 1, 931],
        ]),
        "test": np.array([
            [217, 2, 1, 1, 1],
            [0, 238, 0, 0, 1],
            [0, 0, 272, 0, 0],
            [2, 2, 0, 238, 0],
            [0, 0, 0, 0, 225],
        ]),
    },
    reported_accuracy={"train": SVM_TRAIN_ACCURACY.value, "test": SVM_TEST_ACCURACY.value},
    note="Rows are read as the true class (the row labels of the figure); each row has a "
    "training line (white) and a test line (red). The counts add up to 4800 and 1200 samples, "
    "the 80/20 split of 6000, and give 99.65 % (printed 99.7 %) and 99.17 % (printed 99.2 %).",
)

#: Table 1: the Chebyshev band-pass before the decay fit (section 4.1.2).
TABLE_1 = PAPER_FILTERS["chebyshev"]
#: Table 2: the elliptic band-pass before the full-length distance network (section 4.2).
TABLE_2 = PAPER_FILTERS["elliptic"]

#: Every printed scalar by name, for listing and checking.
NUMBERS = {
    "prior_distance_accuracy_cm": PRIOR_DISTANCE_ACCURACY_CM,
    "probe_length_cm": PROBE_LENGTH_CM,
    "tube_outer_diameter_cm": TUBE_OUTER_DIAMETER_CM,
    "tube_inner_diameter_cm": TUBE_INNER_DIAMETER_CM,
    "sensor_range_g": SENSOR_RANGE_G,
    "sampling_frequency_khz": SAMPLING_FREQUENCY_KHZ,
    "max_frequency_hz": MAX_FREQUENCY_HZ,
    "i2c_rate_khz": I2C_RATE_KHZ,
    "deviation_cm": DEVIATION_CM,
    "deviation_50cm_probe_cm": DEVIATION_50CM_PROBE_CM,
    "spread_ratio": SPREAD_RATIO,
    "mode_change_ratio": MODE_CHANGE_RATIO,
    "pvc_wood_overlap_cm": PVC_WOOD_OVERLAP_CM,
    "high_band_low_cutoff_hz": HIGH_BAND_CUTOFFS_HZ[0],
    "high_band_high_cutoff_hz": HIGH_BAND_CUTOFFS_HZ[1],
    "ann_accuracy": ANN_ACCURACY,
    "svm_train_accuracy": SVM_TRAIN_ACCURACY,
    "svm_test_accuracy": SVM_TEST_ACCURACY,
    "svm_iterations": SVM_ITERATIONS,
    "svm_samples": SVM_SAMPLES,
    "early_modes_samples": EARLY_MODES_SAMPLES,
    "long_lived_samples": LONG_LIVED_SAMPLES,
}
