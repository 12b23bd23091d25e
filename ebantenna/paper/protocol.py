"""The paper's protocol: the data set it recorded and how it split and fed it to each model.

What the paper did, as data (sections 4.1 to 4.3): five materials touched every 5 mm along a
40 cm probe, 25 recordings each; 256 FFT magnitudes per recording divided by the data set's
largest; an RBF SVM trained one-vs-rest on an 80/20 split; networks trained on a 70/15/15 split;
the distance network restricted to the first 80 % of the probe. The experiments in
:mod:`ebantenna.paper.experiments` take their defaults from here, and the split helpers below
are the ones they use.

Examples
--------
>>> DATASET.contact_step, DATASET.repetitions
(0.005, 25)
>>> MATERIAL_ANN.hidden_layer_sizes, MATERIAL_ANN.fractions
((53,), (0.7, 0.15, 0.15))
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from sklearn.model_selection import train_test_split

from .._budget import check_allocation
from .._validate import check_array, check_choice, check_in_range, check_int, check_positive
from ..ml.mlp_base import ACTIVATIONS, SOLVERS

__all__ = [
    "DatasetProtocol",
    "SVMProtocol",
    "NetworkProtocol",
    "DATASET",
    "MATERIAL_SVM",
    "MATERIAL_ANN",
    "DISTANCE_LINEAR_REGION",
    "DISTANCE_FULL_LENGTH",
    "DECAY_REGION",
    "TIME_FREQUENCY_RATIOS",
    "normalise_by_max",
    "check_fractions",
    "three_way_split",
]


def check_fractions(fractions) -> tuple[float, float, float]:
    """Check (train, validation, test) shares: three values in (0, 1) adding up to 1.

    Examples
    --------
    >>> check_fractions((0.7, 0.15, 0.15))
    (0.7, 0.15, 0.15)
    """
    if isinstance(fractions, str | bytes) or not hasattr(fractions, "__iter__"):
        raise TypeError(f"fractions must be (train, validation, test), got {fractions!r:.60}")
    fractions = tuple(fractions)
    if len(fractions) != 3:
        raise ValueError(f"fractions must be (train, validation, test), got {fractions!r}")
    for name, f in zip(("train", "validation", "test"), fractions, strict=True):
        check_in_range(f"fractions[{name}]", f, 0.0, 1.0)
    if abs(sum(fractions) - 1.0) > 1e-9:
        raise ValueError(f"fractions must add up to 1, got {fractions!r}")
    return fractions


@dataclass(frozen=True)
class DatasetProtocol:
    """How the paper's data set was recorded.

    Attributes
    ----------
    materials : tuple of str
        Touched materials, in the order the paper lists them.
    probe_length : float
        Probe length, m.
    contact_step : float
        Spacing of the contact positions along the probe, m.
    repetitions : int
        Recordings per material and contact position.
    fft_bins : int
        FFT magnitudes per recording used as features.
    where : str
        Where the paper says so.
    """

    materials: tuple[str, ...]
    probe_length: float
    contact_step: float
    repetitions: int
    fft_bins: int
    where: str

    def __post_init__(self):
        _check_names("materials", self.materials)
        length = check_positive("probe_length", self.probe_length)
        step = check_positive("contact_step", self.contact_step)
        if step > length:
            raise ValueError(f"contact_step must be at most probe_length ({length!r} m), got "
                             f"{step!r}")
        check_int("repetitions", self.repetitions, minimum=1)
        check_int("fft_bins", self.fft_bins, minimum=1)
        _check_text("where", self.where)


@dataclass(frozen=True)
class SVMProtocol:
    """The paper's SVM material classifier.

    Attributes
    ----------
    gamma : float
        RBF kernel width of eq. 7, on features divided by their maximum, 1/(feature unit)^2.
    test_fraction : float
        Share held out for testing.
    strategy : str
        Multi-class strategy.
    where : str
        Where the paper says so.
    """

    gamma: float
    test_fraction: float
    strategy: str
    where: str

    def __post_init__(self):
        check_positive("gamma", self.gamma)
        check_in_range("test_fraction", self.test_fraction, 0.0, 1.0)
        check_choice("strategy", self.strategy, ("one-vs-rest", "one-vs-one"))
        _check_text("where", self.where)


@dataclass(frozen=True)
class NetworkProtocol:
    """One of the paper's networks.

    Attributes
    ----------
    hidden_layer_sizes : tuple of int
        Neurons per hidden layer.
    activation : str
        Hidden activation.
    solver : str
        Training algorithm (``"gd"``: gradient descent, ``"scg"``: scaled conjugate gradient).
    fractions : tuple of float
        Train, validation and test shares.
    region : float
        Part of the probe (fraction of its length, from the hinge) whose contacts are used.
    normalisation : str
        ``"max"``: the whole matrix divided by its largest magnitude; ``"min-max"``: each feature
        scaled to [0, 1].
    where : str
        Where the paper says so.
    """

    hidden_layer_sizes: tuple[int, ...]
    activation: str
    solver: str
    fractions: tuple[float, float, float]
    region: float
    normalisation: str
    where: str

    def __post_init__(self):
        sizes = self.hidden_layer_sizes
        if not isinstance(sizes, tuple) or not sizes:
            raise TypeError(f"hidden_layer_sizes must be a non-empty tuple of layer sizes, got "
                            f"{sizes!r:.60}")
        for i, size in enumerate(sizes):
            check_int(f"hidden_layer_sizes[{i}]", size, minimum=1, maximum=10**6)
        check_choice("activation", self.activation, ACTIVATIONS)
        check_choice("solver", self.solver, SOLVERS)
        check_fractions(self.fractions)
        check_in_range("region", self.region, 0.0, 1.0, high_inclusive=True)
        check_choice("normalisation", self.normalisation, ("max", "min-max"))
        _check_text("where", self.where)


def _check_text(name: str, value) -> None:
    if not isinstance(value, str) or not value.strip():
        raise TypeError(f"{name} must be a non-empty string, got {value!r:.60}")


def _check_names(name: str, value) -> None:
    if not isinstance(value, tuple) or not value:
        raise TypeError(f"{name} must be a non-empty tuple of names, got {value!r:.60}")
    for item in value:
        _check_text(f"each of {name}", item)
    if len({v.casefold() for v in value}) != len(value):
        raise ValueError(f"{name} must not name one thing twice, got {value!r}")


#: Sections 4.1.1 and 4.2: five materials, every 5 mm, 25 samples per contact, 256 FFT bins.
DATASET = DatasetProtocol(
    materials=("aluminium", "brass", "wood", "steel", "pvc"),
    probe_length=0.40,
    contact_step=0.005,
    repetitions=25,
    fft_bins=256,
    where="sections 4.1.1 and 4.2",
)
#: Section 4.3: RBF kernel, gamma 2.0, one-vs-all, 80/20 split of a batch of 6000 samples
#: (Fig. 15; the data set itself holds 5 x 79 x 25 = 9875 recordings).
MATERIAL_SVM = SVMProtocol(gamma=2.0, test_fraction=0.2, strategy="one-vs-rest",
                           where="section 4.3, eq. 7, Fig. 15")
#: Section 4.2: one hidden layer of 53 tanh neurons, gradient descent, 70/15/15 (Fig. 12).
MATERIAL_ANN = NetworkProtocol(
    hidden_layer_sizes=(53,), activation="tanh", solver="gd", fractions=(0.70, 0.15, 0.15),
    region=1.0, normalisation="max", where="section 4.2, Fig. 12",
)
#: Section 4.2: two tanh layers of 20, gradient descent, first 80 % of the probe (Fig. 13).
DISTANCE_LINEAR_REGION = NetworkProtocol(
    hidden_layer_sizes=(20, 20), activation="tanh", solver="gd", fractions=(0.70, 0.15, 0.15),
    region=0.8, normalisation="max", where="section 4.2, Fig. 13",
)
#: Section 4.2: 9 ReLU neurons, scaled conjugate gradient, whole probe, min-max, Table 2 filter
#: first (Fig. 14).
DISTANCE_FULL_LENGTH = NetworkProtocol(
    hidden_layer_sizes=(9,), activation="relu", solver="scg", fractions=(0.70, 0.15, 0.15),
    region=1.0, normalisation="min-max", where="section 4.2, Table 2, Fig. 14",
)
#: Section 2.3 and Fig. 11: the decay features (gain, time constant) are taken on the first 80 %
#: of the probe, a fraction of its length.
DECAY_REGION = 0.8
#: Figs. 18 and 19: the contact positions of the spectrograms and scalograms, fractions of L.
TIME_FREQUENCY_RATIOS = (0.25, 0.5, 0.75, 0.8, 0.9)


def normalise_by_max(X, rows=None) -> np.ndarray:
    """Divide the whole feature matrix by the largest magnitude of its training rows (section 4.2).

    The paper divides by the largest magnitude of all its features; a scaler fitted on the test
    rows too lets them shape the training, so here the peak is taken over ``rows`` only (the
    training rows) and every row, test rows included, is divided by it.

    Parameters
    ----------
    X : array-like of shape (n, n_features)
    rows : array-like of int, optional
        The rows the peak is taken from (default: all of them).

    Examples
    --------
    >>> normalise_by_max(np.array([[1.0, -4.0], [2.0, 0.0]]))
    array([[ 0.25, -1.  ],
           [ 0.5 ,  0.  ]])
    >>> normalise_by_max(np.array([[1.0, -4.0], [2.0, 0.0]]), rows=[1])
    array([[ 0.5, -2. ],
           [ 1. ,  0. ]])
    """
    X = check_array("X", X, ndim=2)
    if rows is not None:
        rows = np.asarray(rows)
        if rows.size == 0:
            raise ValueError("rows must select at least one row of X")
        if rows.ndim != 1 or rows.dtype.kind not in "iu":
            raise TypeError(f"rows must be a 1-D array of row indices, got dtype {rows.dtype} "
                            f"and shape {rows.shape}")
        if rows.size and (rows.min() < -X.shape[0] or rows.max() >= X.shape[0]):
            raise ValueError(f"rows must index the {X.shape[0]} rows of X, got indices from "
                             f"{rows.min()} to {rows.max()}")
    fit = X if rows is None else X[rows]
    if fit.size == 0:
        raise ValueError("rows must select at least one row of X")
    peak = np.abs(fit).max()
    if peak == 0:
        raise ValueError("X must not be all zeros on the rows the peak is taken from")
    return X / peak


def three_way_split(n, fractions, seed, stratify=None):
    """Indices of train / validation / test parts with the given fractions.

    The test part is drawn first (seed ``seed``), the validation part from the rest (seed
    ``seed + 1``); both stratified by ``stratify`` when given.

    Parameters
    ----------
    n : int
        Number of samples, at least 3.
    fractions : (float, float, float)
        Train, validation and test shares (:func:`check_fractions`).
    seed : int
        0 ... 2**32 - 2 (scikit-learn's seeds; the validation part uses ``seed + 1``).
    stratify : array-like of shape (n,), optional
        Class of each sample.

    Examples
    --------
    >>> train, val, test = three_way_split(20, (0.7, 0.15, 0.15), seed=0)
    >>> len(train), len(val), len(test)
    (14, 3, 3)
    """
    fractions = check_fractions(fractions)
    n = check_int("n", n, minimum=3)
    check_allocation(32 * n, parameter="n", what="the split's index arrays")
    seed = check_int("seed", seed, minimum=0, maximum=2**32 - 2)  # scikit-learn's, and seed + 1
    _, f_val, f_test = fractions
    n_test, n_val = int(round(f_test * n)), int(round(f_val * n))
    if min(n_test, n_val, n - n_test - n_val) < 1:
        raise ValueError(f"{n} samples cannot be split by fractions {fractions!r}")
    idx = np.arange(n)
    stratify = None if stratify is None else np.asarray(stratify)
    if stratify is not None:
        if stratify.shape != (n,):
            raise ValueError(f"stratify must hold one label for each of the n={n} samples, got "
                             f"shape {stratify.shape}")
        classes, counts = np.unique(stratify, return_counts=True)
        if counts.min() < 2 or min(n_test, n_val) < classes.size:
            raise ValueError(f"stratify: each part of a stratified split needs a sample of every "
                             f"class ({classes.size}) and every class 2 samples at least; the "
                             f"parts hold {n_test} (test) and {n_val} (validation), the rarest "
                             f"class {counts.min()}")
    rest, test = train_test_split(idx, test_size=n_test, random_state=seed, stratify=stratify)
    strat_rest = None if stratify is None else stratify[rest]
    train, val = train_test_split(rest, test_size=n_val, random_state=seed + 1,
                                  stratify=strat_rest)
    return train, val, test
