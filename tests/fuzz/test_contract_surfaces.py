"""The input contract of the building blocks a reader of the theory calls first.

The paper's splits and protocol, the accuracy intervals of the report, the classification
metrics, the Euler-Bernoulli element matrices and meshes, the report writer, the course's
tolerances and the spectral and envelope steps: each surface gets bad inputs of every kind it
takes (a number out of range, NaN, 10**400, a wrong type, a mismatched or ragged array, a path
out of its folder) and must refuse each with a ``ValueError`` or ``TypeError`` whose message
names the parameter, before any work; a few good inputs are checked against a value worked by
hand. Outcomes are sorted by ``contract_files_cases.outcome``.

Found by these rows and fixed: scikit-learn's messages from the splits (a seed of 2**70, a
class of one recording, ``labels`` and ``positions`` of different lengths accepted), a split of
10**12 samples allocating terabytes, ``OverflowError`` from an interval on 10**400 recordings,
"math domain error" from an accuracy of 2, a confusion matrix of fractions or negative counts
accepted, element matrices of a negative length, a mesh with its contact beyond the tip, a
report written into the working directory for ``directory=""`` or out of its folder for
``stem="../x"``, and a window of 10**12 weights.
"""

from __future__ import annotations

import math
import os
import sys
from fractions import Fraction

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, check_row, rows_by_surface  # noqa: E402

from ebantenna import Probe, course  # noqa: E402
from ebantenna.fem import assembly, elements, exact, guards, hinge, modal  # noqa: E402
from ebantenna.ml import metrics  # noqa: E402
from ebantenna.paper import protocol, splits  # noqa: E402
from ebantenna.paper import uncertainty as unc  # noqa: E402
from ebantenna.report import FigureSet, Report, text_table  # noqa: E402
from ebantenna.signal import decay, spectral  # noqa: E402

NAN = math.nan
#: Numbers no real parameter takes: ``label -> value``.
NOT_REAL = {"nan": NAN, "inf": math.inf, "10**400": 10**400, "str": "1", "None": None,
            "bool": True, "complex": 1j, "list": [1.0]}
LABELS = np.array(["al", "pvc"] * 10)
POSITIONS = np.repeat(np.arange(10) / 100, 2)
X = np.array([[1.0, -4.0], [2.0, 0.0], [0.5, 0.5]])


def _numbers(surface, param, make, extra=(), arrays=False):
    """A row per value of :data:`NOT_REAL` (and ``extra``) given as ``param`` (but the list
    where ``arrays`` are taken)."""
    values = [(k, v) for k, v in NOT_REAL.items() if not (arrays and k == "list")] + list(extra)
    return [Row(surface, f"{param}={label}", (lambda v=v: make(v)), (param,))
            for label, v in values]


# ------------------------------------------------------------------ the paper's splits
def _split_rows():
    s = "ebantenna.paper.splits."
    rows = _numbers(s + "random_split", "test_fraction",
                    lambda v: splits.random_split(LABELS, test_fraction=v),
                    [("0", 0.0), ("1", 1.0), ("1.5", 1.5)])
    rows += _numbers(s + "random_split", "seed", lambda v: splits.random_split(LABELS, seed=v),
                     [("-1", -1), ("2**32", 2**32), ("2**70", 2**70), ("1.5", 1.5)])
    rows += [
        Row(s + "random_split", "labels-2-D", lambda: splits.random_split(np.ones((3, 3))),
            ("labels",)),
        Row(s + "random_split", "labels-empty", lambda: splits.random_split([]), ("labels",)),
        Row(s + "random_split", "labels-one-row", lambda: splits.random_split([0]), ("labels",)),
        Row(s + "random_split", "labels-class-of-one",
            lambda: splits.random_split(["a"] * 9 + ["b"]), ("labels",)),
        Row(s + "random_split", "labels-too-many-classes-for-the-test",
            lambda: splits.random_split(np.repeat(np.arange(10), 2), test_fraction=0.2),
            ("labels",)),
        Row(s + "random_split", "labels-float", lambda: splits.random_split(np.arange(20) / 2),
            ("labels",)),
        Row(s + "random_split", "stratified-by-hand", lambda: splits.random_split(LABELS),
            same=lambda r: (r[1].size == 4 and sorted(LABELS[r[1]].tolist())
                            == ["al", "al", "pvc", "pvc"]
                            and sorted([*r[0], *r[1]]) == list(range(20)))),
    ]
    rows += _numbers(s + "grouped_split", "every",
                     lambda v: splits.grouped_split(POSITIONS, every=v),
                     [("0", 0), ("1", 1), ("11", 11), ("1.5", 1.5)])
    rows += [Row(s + "grouped_split", "positions-nan",
                 lambda: splits.grouped_split([NAN, 0.1, 0.2]), ("positions",)),
             Row(s + "grouped_split", "positions-one", lambda: splits.grouped_split([0.1] * 4),
                 ("positions",))]
    rows += _numbers(s + "blocked_split", "test_fraction",
                     lambda v: splits.blocked_split(POSITIONS, test_fraction=v),
                     [("0", 0.0), ("1", 1.0)])
    rows += [Row(s + "blocked_split", "positions-str", lambda: splits.blocked_split("abc"),
                 ("positions",)),
             Row(s + "blocked_split", "positions-2-D",
                 lambda: splits.blocked_split(np.ones((4, 4))), ("positions",))]
    rows += [
        Row(s + "split_rows", "kind-unknown", lambda: splits.split_rows("x", LABELS, POSITIONS),
            ("kind",)),
        Row(s + "split_rows", "positions-shorter-than-labels",
            lambda: splits.split_rows("random", LABELS, POSITIONS[:3]), ("positions",)),
        Row(s + "split_rows", "labels-shorter-than-positions",
            lambda: splits.split_rows("grouped", LABELS[:3], POSITIONS), ("labels",)),
        Row(s + "split_rows", "test_fraction-nan",
            lambda: splits.split_rows("grouped", LABELS, POSITIONS, test_fraction=NAN),
            ("test_fraction",)),
    ]
    d = s + "distinct_split_seeds"
    rows += [
        Row(d, "count-0", lambda: splits.distinct_split_seeds("random", LABELS, POSITIONS,
                                                              count=0), ("count",)),
        Row(d, "count-above-search", lambda: splits.distinct_split_seeds(
            "random", LABELS, POSITIONS, count=10**9), ("count",)),
        Row(d, "search-10**12", lambda: splits.distinct_split_seeds(
            "grouped", LABELS, POSITIONS, count=6, search=10**12), ("search",)),
        Row(d, "seed-negative", lambda: splits.distinct_split_seeds(
            "random", LABELS, POSITIONS, seed=-1), ("seed",)),
        Row(d, "more-than-there-are", lambda: splits.distinct_split_seeds(
            "grouped", LABELS, POSITIONS, count=6, search=50), ("count=6",)),
        # every = 5 on 10 positions: 5 offsets, so 5 distinct grouped splits from the first 5+
        Row(d, "five-grouped-folds", lambda: splits.distinct_split_seeds(
            "grouped", LABELS, POSITIONS, count=5),
            same=lambda seeds: len(seeds) == 5 and len({tuple(splits.split_rows(
                "grouped", LABELS, POSITIONS, seed=x)[1]) for x in seeds}) == 5),
    ]
    rows += [Row(s + "split_folds", "labels-every-class-below-folds", lambda: splits.split_folds(
        "random", ["a", "b"] * 4, POSITIONS[:8]), ("labels",)),
             Row(s + "split_folds", "seed-2**32", lambda: splits.split_folds(
                 "random", LABELS, POSITIONS, seed=2**32), ("seed",))]
    return rows


# ------------------------------------------------------------------ the paper's protocol
def _protocol_rows():
    p = "ebantenna.paper.protocol."
    rows = [
        Row(p + "check_fractions", "two", lambda: protocol.check_fractions((0.5, 0.5)),
            ("fractions",)),
        Row(p + "check_fractions", "nan", lambda: protocol.check_fractions((NAN, 0.5, 0.5)),
            ("fractions",)),
        Row(p + "check_fractions", "sum-0.9",
            lambda: protocol.check_fractions((0.5, 0.2, 0.2)), ("fractions",)),
        Row(p + "check_fractions", "str", lambda: protocol.check_fractions("abc"),
            ("fractions",)),
        Row(p + "normalise_by_max", "X-str", lambda: protocol.normalise_by_max("abc"), ("X",)),
        Row(p + "normalise_by_max", "X-complex", lambda: protocol.normalise_by_max(X + 1j),
            ("X",)),
        Row(p + "normalise_by_max", "X-1-D", lambda: protocol.normalise_by_max([1.0, 2.0]),
            ("X",)),
        Row(p + "normalise_by_max", "X-nan", lambda: protocol.normalise_by_max(X * NAN),
            ("X",)),
        Row(p + "normalise_by_max", "X-zeros", lambda: protocol.normalise_by_max(X * 0),
            ("X",)),
        Row(p + "normalise_by_max", "rows-out-of-X",
            lambda: protocol.normalise_by_max(X, rows=[10]), ("rows",)),
        Row(p + "normalise_by_max", "rows-float",
            lambda: protocol.normalise_by_max(X, rows=[0.5]), ("rows",)),
        Row(p + "normalise_by_max", "rows-empty",
            lambda: protocol.normalise_by_max(X, rows=np.array([], dtype=int)), ("rows",)),
        # the peak of rows 1 and 2 is 2: every row, row 0 too, divided by it
        Row(p + "normalise_by_max", "by-hand", lambda: protocol.normalise_by_max(X, rows=[1, 2]),
            same=lambda r: np.array_equal(r, X / 2)),
    ]
    t = p + "three_way_split"
    rows += _numbers(t, "n", lambda v: protocol.three_way_split(v, (0.6, 0.2, 0.2), 0),
                     [("0", 0), ("2", 2), ("1.5", 1.5), ("10**12", 10**12)])
    rows += _numbers(t, "seed", lambda v: protocol.three_way_split(20, (0.6, 0.2, 0.2), v),
                     [("-1", -1), ("2**32", 2**32)])
    rows += [
        Row(t, "stratify-mismatch", lambda: protocol.three_way_split(
            10, (0.6, 0.2, 0.2), 0, stratify=[0, 1]), ("stratify",)),
        Row(t, "stratify-class-of-one", lambda: protocol.three_way_split(
            20, (0.6, 0.2, 0.2), 0, stratify=[0] * 19 + [1]), ("stratify",)),
        Row(t, "stratify-more-classes-than-test", lambda: protocol.three_way_split(
            20, (0.8, 0.1, 0.1), 0, stratify=np.repeat(np.arange(5), 4)), ("stratify",)),
        Row(t, "fractions-bad", lambda: protocol.three_way_split(20, (1.0, 0.0, 0.0), 0),
            ("fractions",)),
        Row(t, "sizes-by-hand", lambda: protocol.three_way_split(20, (0.7, 0.15, 0.15), 0),
            same=lambda r: [len(a) for a in r] == [14, 3, 3]
            and sorted(np.concatenate(r).tolist()) == list(range(20))),
    ]
    return rows


# ------------------------------------------------------------------ accuracies and intervals
def _wilson(k, n, z=1.959963984540054):
    p = k / n
    centre, half = p + z * z / (2 * n), z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return (centre - half) / (1 + z * z / n), (centre + half) / (1 + z * z / n)


def _uncertainty_rows():
    u = "ebantenna.paper.uncertainty."
    rows = []
    for name, call in (("interval", unc.interval), ("correct_count", unc.correct_count),
                       ("format_interval", unc.format_interval),
                       ("resolvable_difference", unc.resolvable_difference)):
        rows += _numbers(u + name, "accuracy", lambda v, c=call: c(v, 10),
                         [("1.5", 1.5), ("-0.1", -0.1), ("2", 2)])
        rows += _numbers(u + name, "n", lambda v, c=call: c(0.5, v),
                         [("0", 0), ("-1", -1), ("3.7", 3.7)])
    rows += [
        Row(u + "correct_count", "not-a-count", lambda: unc.correct_count(0.33, 10),
            ("accuracy",)),
        Row(u + "correct_count", "by-hand", lambda: unc.correct_count(0.8325, 400),
            same=lambda k: k == 333),
        Row(u + "interval", "wilson-by-hand", lambda: unc.interval(0.65, 80),
            same=lambda r: np.allclose(r, _wilson(52, 80), rtol=0, atol=1e-15)),
        Row(u + "interval", "n-2**53+1", lambda: unc.interval(0.5, 2**53 + 2), ("n",)),
        Row(u + "resolvable_difference", "by-hand", lambda: unc.resolvable_difference(0.5, 200),
            same=lambda d: math.isclose(d, 0.1, rel_tol=1e-15)),
        Row(u + "difference_resolved", "a-nan", lambda: unc.difference_resolved(NAN, 0.5, 10),
            ("a",)),
        Row(u + "difference_resolved", "b-1.5", lambda: unc.difference_resolved(0.5, 1.5, 10),
            ("b",)),
        Row(u + "difference_resolved", "n-0", lambda: unc.difference_resolved(0.5, 0.6, 0),
            ("n",)),
        # 0.5 apart at p = 0.5 on 8 each: 2 sqrt(2 p (1 - p) / 8) = 0.5 exactly, not more; on
        # 9 each the resolvable difference is smaller
        Row(u + "difference_resolved", "at-the-edge", lambda: [
            unc.difference_resolved(0.75, 0.25, n) for n in (8, 9)],
            same=lambda r: r == [False, True]),
        Row(u + "accuracy_entries", "name-int", lambda: unc.accuracy_entries(5, 0.5, 10),
            ("name",)),
        Row(u + "accuracy_entries", "name-empty", lambda: unc.accuracy_entries("", 0.5, 10),
            ("name",)),
        Row(u + "accuracy_entries", "n-missing-a-key",
            lambda: unc.accuracy_entries("x", {"a": 0.5, "b": 0.5}, {"a": 10}), ("n",)),
        Row(u + "accuracy_entries", "n-fraction", lambda: unc.accuracy_entries("x", 0.5, 10.5),
            ("n",)),
        Row(u + "accuracy_entries", "none-stays-none",
            lambda: unc.accuracy_entries("x", None, None),
            same=lambda r: r == {"x": None, "x_n_test": None, "x_ci95": None}),
        Row(u + "seed_spread", "measure-not-callable", lambda: unc.seed_spread(5, [1, 2]),
            ("measure",)),
        Row(u + "seed_spread", "seeds-one", lambda: unc.seed_spread(lambda s: (0.5, 4), [1]),
            ("seeds",)),
        Row(u + "seed_spread", "seeds-negative",
            lambda: unc.seed_spread(lambda s: (0.5, 4), [-1, 2]), ("seeds",)),
        Row(u + "seed_spread", "measure-returns-a-number",
            lambda: unc.seed_spread(lambda s: 0.5, [1, 2]), ("measure",)),
        Row(u + "seed_spread", "by-hand", lambda: unc.seed_spread(
            lambda s: ((s + 1) / 4, 4), [0, 1, 2]),
            same=lambda r: r.mean == 0.5 and r.std == 0.25),
        Row(u + "SeedSpread", "values-one-short", lambda: unc.SeedSpread([1, 2], [0.5], [10, 10]),
            ("values",)),
        Row(u + "SeedSpread", "values-above-1", lambda: unc.SeedSpread([1, 2], [0.5, 1.5],
                                                                       [10, 10]), ("values",)),
        Row(u + "SeedSpread", "n_test-0", lambda: unc.SeedSpread([1, 2], [0.5, 0.5], [10, 0]),
            ("n_test",)),
        Row(u + "SeedSpread", "values-nan", lambda: unc.SeedSpread([1, 2], [0.5, NAN],
                                                                   [10, 10]), ("values",)),
        Row(u + "SeedSpread.to_dict", "by-hand",
            lambda: unc.SeedSpread([1, 2], [0.5, 0.75], [4, 4]).to_dict(),
            same=lambda d: d["mean"] == 0.625 and d["seeds"] == [1, 2]),
    ]
    return rows


def _metrics_rows():
    m = "ebantenna.ml.metrics."
    return [
        Row(m + "absolute_errors", "mismatch", lambda: metrics.absolute_errors([1, 2], [1]),
            ("y_pred",)),
        Row(m + "absolute_errors", "y_true-str", lambda: metrics.absolute_errors(["a"], ["b"]),
            ("y_true",)),
        Row(m + "absolute_errors", "y_true-nan", lambda: metrics.absolute_errors([NAN], [1.0]),
            ("y_true",)),
        Row(m + "absolute_errors", "y_pred-inf", lambda: metrics.absolute_errors([1.0], [math.inf]),
            ("y_pred",)),
        Row(m + "absolute_errors", "y_pred-complex",
            lambda: metrics.absolute_errors([1.0], [1j]), ("y_pred",)),
        Row(m + "absolute_errors", "by-hand",
            lambda: metrics.absolute_errors([0.25, 0.5], [0.5, 0.375]),
            same=lambda r: r.tolist() == [0.25, 0.125]),
        Row(m + "confusion_matrix", "mismatch",
            lambda: metrics.confusion_matrix([0, 1], [0], [0, 1]), ("y_pred",)),
        Row(m + "confusion_matrix", "labels-repeated",
            lambda: metrics.confusion_matrix([0, 1], [0, 1], [0, 0, 1]), ("labels",)),
        Row(m + "confusion_matrix", "labels-empty",
            lambda: metrics.confusion_matrix([0, 1], [0, 1], []), ("labels",)),
        # a sample whose label is not listed is left out (as documented)
        Row(m + "confusion_matrix", "unlisted-left-out",
            lambda: metrics.confusion_matrix([0, 5, 1], [0, 1, 1], [0, 1]),
            same=lambda r: r.tolist() == [[1, 0], [0, 1]]),
        Row(m + "per_class_rates", "1-D", lambda: metrics.per_class_rates([1, 2]), ("matrix",)),
        Row(m + "per_class_rates", "not-square",
            lambda: metrics.per_class_rates(np.ones((2, 3))), ("matrix",)),
        Row(m + "per_class_rates", "negative",
            lambda: metrics.per_class_rates(-np.ones((2, 2))), ("matrix",)),
        Row(m + "per_class_rates", "fractional",
            lambda: metrics.per_class_rates(np.full((2, 2), 0.5)), ("matrix",)),
        Row(m + "per_class_rates", "nan", lambda: metrics.per_class_rates([[NAN, 1], [0, 1]]),
            ("matrix",)),
        Row(m + "per_class_rates", "str", lambda: metrics.per_class_rates("ab"), ("matrix",)),
        # recall 3/4, 4/4; precision 3/3, 4/5; a class with no sample: zeros, as documented
        Row(m + "per_class_rates", "by-hand", lambda: metrics.per_class_rates([[3, 1], [0, 4]]),
            same=lambda r: r[0].tolist() == [0.75, 1.0] and r[1].tolist() == [1.0, 0.8]),
        Row(m + "per_class_rates", "no-samples-zeros",
            lambda: metrics.per_class_rates(np.zeros((2, 2))),
            same=lambda r: r[0].tolist() == [0, 0] and r[1].tolist() == [0, 0]),
    ]


# ------------------------------------------------------------------ finite elements
def _hinge_fit():
    """A hinge fit with a 2 x 2 search lattice, made by hand."""
    one = np.ones(1)
    return hinge.HingeFit(5.0, 0.0, one, one, one, "peak",
                          lattice=(np.array([1.0, 10.0]), np.array([0.0, 0.01]), np.ones((2, 2))))


def _fem_rows():
    e, a = "ebantenna.fem.elements.", "ebantenna.fem.assembly."
    rows = []
    for name, call, first in (("element_stiffness", elements.element_stiffness, "EI"),
                              ("consistent_mass", elements.consistent_mass, "rhoA")):
        rows += _numbers(e + name, first, lambda v, c=call: c(v, 0.1),
                         [("0", 0.0), ("-1", -1.0)], arrays=True)
        rows += _numbers(e + name, "l", lambda v, c=call: c(1.0, v), [("0", 0.0), ("-1", -1.0)],
                         arrays=True)
        rows.append(Row(e + name, "l-array-with-a-zero", lambda c=call: c(1.0, [0.1, 0.0]),
                        ("l",)))
    rows += [
        # exact on Fractions: 12 EI / l^3 and 156 rhoA l / 420 in the first corner
        Row(e + "element_stiffness", "fractions-exact",
            lambda: elements.element_stiffness(Fraction(3), Fraction(1, 2))[0, 0],
            same=lambda r: r == Fraction(288)),
        Row(e + "consistent_mass", "fractions-exact",
            lambda: elements.consistent_mass(Fraction(2), Fraction(1, 2))[0, 0],
            same=lambda r: r == Fraction(156, 420)),
    ]
    for name, call in (("hermite", elements.hermite), ("hermite_slope", elements.hermite_slope)):
        rows += _numbers(e + name, "xi", lambda v, c=call: c(v, 0.1),
                         [("-0.5", -0.5), ("1.5", 1.5)], arrays=True)
        rows += _numbers(e + name, "l", lambda v, c=call: c(0.5, v), [("0", 0.0)], arrays=True)
    b = "ebantenna.fem.modal.bending_energy"
    rows += [
        # at xi = 1/2 the end deflections share equally and the slopes give +-l/8
        Row(e + "hermite", "midpoint-by-hand", lambda: elements.hermite(0.5, 0.4),
            same=lambda r: np.allclose(r, [0.5, 0.05, 0.5, -0.05], rtol=0, atol=1e-16)),
        Row(b, "u-too-short", lambda: modal.bending_energy(1.0, 0.1, [1.0]),
            ("u",)),
        Row(b, "u-odd", lambda: modal.bending_energy(1.0, 0.1, [0.0] * 5),
            ("u",)),
        Row(b, "u-nan",
            lambda: modal.bending_energy(1.0, 0.1, [0.0, NAN, 0.0, 0.0]), ("u",)),
        # a solver's own unresolved shape: NaN passes through for it to report in its words
        Row(b, "u-nan-unchecked", lambda: modal.bending_energy(
            1.0, 0.1, [0.0, NAN, 0.0, 0.0], check_finite=False), same=math.isnan),
        Row(b, "check_finite-str",
            lambda: modal.bending_energy(1.0, 0.1, [0.0] * 4, check_finite="no"),
            ("check_finite",)),
        Row(b, "EI-negative",
            lambda: modal.bending_energy(-1.0, 0.1, [0.0] * 4), ("EI",)),
        # a uniform curvature k = 2 / l^2 ... : u^T K u with K from element_stiffness
        Row(b, "equals-uKu", lambda: modal.bending_energy(
            2.0, 0.5, np.array([0.0, 0.1, 0.03, -0.2])),
            same=lambda r: math.isclose(r, (lambda u: u @ elements.element_stiffness(2.0, 0.5)
                                             @ u)(np.array([0.0, 0.1, 0.03, -0.2])),
                                        rel_tol=1e-14)),
    ]
    x = "ebantenna.fem.exact.frequency_equation"
    rows += [Row(x, "hinge-unknown", lambda: exact.frequency_equation(1.0, 0.4, 0.2, "x"),
                 ("hinge",)),
             Row(x, "contact-beyond-tip", lambda: exact.frequency_equation(1.0, 0.4, 0.5,
                                                                           "clamped"),
                 ("contact",))]
    rows += _numbers(x, "beta", lambda v: exact.frequency_equation(v, 0.4, 0.2, "clamped"))
    rows += _numbers(x, "length", lambda v: exact.frequency_equation(1.0, v, None, "pinned"),
                     [("0", 0.0)])
    rows += _numbers(a + "beam_mesh", "length", lambda v: assembly.beam_mesh(v, None, 8),
                     [("0", 0.0), ("-1", -1.0)])
    rows += [
        Row(a + "beam_mesh", "contact-beyond-tip", lambda: assembly.beam_mesh(0.4, 0.5, 8),
            ("contact",)),
        Row(a + "beam_mesh", "contact-nan", lambda: assembly.beam_mesh(0.4, NAN, 8),
            ("contact",)),
        Row(a + "beam_mesh", "n_elements-0", lambda: assembly.beam_mesh(0.4, 0.2, 0),
            ("n_elements",)),
        Row(a + "beam_mesh", "n_elements-10**9", lambda: assembly.beam_mesh(0.4, 0.2, 10**9),
            ("n_elements",)),
        Row(a + "beam_mesh", "by-hand", lambda: assembly.beam_mesh(0.4, 0.1, 4),
            same=lambda r: np.allclose(r, [0, 0.1, 0.2, 0.3, 0.4], rtol=0, atol=1e-16)),
        Row(a + "contact_node", "contact-beyond",
            lambda: assembly.contact_node(np.linspace(0, 0.4, 9), 0.5), ("contact",)),
        Row(a + "contact_node", "nodes-one",
            lambda: assembly.contact_node(np.zeros(1), 0.1), ("nodes",)),
        Row(a + "contact_node", "by-hand",
            lambda: assembly.contact_node(np.linspace(0, 0.4, 9), 0.15), same=lambda r: r == 3),
    ]
    g = "ebantenna.fem.guards."
    rows += [
        Row(g + "check_contact", "nan", lambda: guards.check_contact("contact", NAN, 0.4),
            ("contact",)),
        Row(g + "check_contact", "at-the-hinge",
            lambda: guards.check_contact("contact", 1e-9, 0.4), ("contact",)),
        Row(g + "check_resolvable", "0", lambda: guards.check_resolvable(0), ("n_elements",)),
        Row(g + "check_resolvable", "1.5", lambda: guards.check_resolvable(1.5),
            ("n_elements",)),
        Row(g + "check_resolvable", "beyond", lambda: guards.check_resolvable(10**7),
            ("n_elements",)),
        Row(g + "roundoff_error", "0", lambda: guards.roundoff_error(0), ("n_elements",)),
        Row(g + "roundoff_error", "str", lambda: guards.roundoff_error("8"), ("n_elements",)),
        Row(g + "check_memory", "nan", lambda: guards.check_memory(NAN, "x"), ("n_elements",)),
        Row(g + "check_memory", "negative", lambda: guards.check_memory(-8, "x", "n_modes"),
            ("n_modes",)),
        Row(g + "check_memory", "10**400", lambda: guards.check_memory(10**400, "x", "n_modes"),
            ("n_modes",)),
    ]
    h = "ebantenna.fem.hinge."
    rows += [
        Row(h + "transition_position", "probe-int", lambda: hinge.transition_position(5),
            ("probe",)),
        Row(h + "transition_position", "criterion-unknown",
            lambda: hinge.transition_position(Probe(), criterion="x"), ("criterion",)),
        Row(h + "transition_position", "n_elements-0",
            lambda: hinge.transition_position(Probe(), n_elements=0), ("n_elements",)),
        Row(h + "fit_hinge_and_tip", "probe-none",
            lambda: hinge.fit_hinge_and_tip(None, [0.4], [0.3]), ("probe",)),
        Row(h + "fit_hinge_and_tip", "observed-beyond-length",
            lambda: hinge.fit_hinge_and_tip(Probe(), [0.4, 0.3], [0.3, 0.5]), ("observed",)),
        Row(h + "fit_hinge_and_tip", "lengths-mismatch",
            lambda: hinge.fit_hinge_and_tip(Probe(), [0.4, 0.3], [0.3]), ("observed",)),
        Row(h + "fit_hinge_and_tip", "stiffness_bounds-zero",
            lambda: hinge.fit_hinge_and_tip(Probe(), [0.4], [0.3], stiffness_bounds=(0, 1e4)),
            ("stiffness_bounds",)),
        Row(h + "fit_hinge_and_tip", "stiffness_bounds-one",
            lambda: hinge.fit_hinge_and_tip(Probe(), [0.4], [0.3], stiffness_bounds=(1.0,)),
            ("stiffness_bounds",)),
        Row(h + "fit_hinge_and_tip", "mass_bounds-negative",
            lambda: hinge.fit_hinge_and_tip(Probe(), [0.4], [0.3], mass_bounds=(-1, 1)),
            ("mass_bounds",)),
        Row(h + "fit_hinge_and_tip", "n_jobs-zero",
            lambda: hinge.fit_hinge_and_tip(Probe(), [0.4], [0.3], n_jobs=0), ("n_jobs",)),
        Row(h + "HingeFit.stiffness_within", "tolerance-negative",
            lambda: _hinge_fit().stiffness_within(-0.001), ("tolerance",)),
        Row(h + "HingeFit.stiffness_within", "tolerance-nan",
            lambda: _hinge_fit().stiffness_within(NAN), ("tolerance",)),
        Row(h + "HingeFit.stiffness_within", "no-lattice",
            lambda: hinge.HingeFit(5.0, 0.0, *[np.ones(1)] * 3, "peak").stiffness_within(0.0),
            ("lattice",)),
    ]
    return rows


# ------------------------------------------------------------------ the report
def _report_rows(where):
    r = "ebantenna.report."
    return [
        Row(r + "Report", "title-int", lambda: Report(5), ("title",)),
        Row(r + "Report", "blocks-str", lambda: Report("t", "abc"), ("blocks",)),
        Row(r + "Report.heading", "text-None", lambda: Report("t").heading(None), ("text",)),
        Row(r + "Report.paragraph", "text-bytes", lambda: Report("t").paragraph(b"x"),
            ("text",)),
        Row(r + "Report.preformatted", "text-list", lambda: Report("t").preformatted(["x"]),
            ("text",)),
        Row(r + "Report.table", "row-short", lambda: Report("t").table(["a", "b"], [[1]]),
            ("rows[0]",)),
        Row(r + "Report.table", "rows-str", lambda: Report("t").table(["a"], "ab"), ("rows",)),
        Row(r + "Report.table", "headers-str", lambda: Report("t").table("ab", [[1, 2]]),
            ("headers",)),
        Row(r + "Report.figure", "path-int", lambda: Report("t").figure(5, "c"), ("path",)),
        Row(r + "Report.figure", "caption-None", lambda: Report("t").figure("a.png", None),
            ("caption",)),
        Row(r + "Report.write", "directory-empty", lambda: Report("t").write(""),
            ("directory",)),
        Row(r + "Report.write", "stem-up-a-folder", lambda: Report("t").write(where, "../x"),
            ("stem",)),
        Row(r + "Report.write", "stem-empty", lambda: Report("t").write(where, ""), ("stem",)),
        Row(r + "Report.write", "directory-missing",
            lambda: Report("t").write(os.path.join(where, "none")), ("none",)),
        Row(r + "Report.markdown", "by-hand", lambda: _table_report().markdown(),
            same=lambda md: md.splitlines()[2:5] == ["| a | b |", "| --- | --- |",
                                                     "| 1 | 2.5 |"]),
        Row(r + "Report.html", "escaped", lambda: Report("<t>").html(),
            same=lambda page: "<title>&lt;t&gt;</title>" in page),
        Row(r + "FigureSet", "dpi-0", lambda: FigureSet(where, dpi=0), ("dpi",)),
        Row(r + "FigureSet", "dpi-10**6", lambda: FigureSet(where, dpi=10**6), ("dpi",)),
        Row(r + "FigureSet", "out_dir-empty", lambda: FigureSet(""), ("out_dir",)),
        Row(r + "FigureSet.save", "name-up-a-folder",
            lambda: FigureSet(where).save(_figure(), "../x"), ("name",)),
        Row(r + "FigureSet.save", "name-backslash",
            lambda: FigureSet(where).save(_figure(), "a\\b"), ("name",)),
        Row(r + "text_table", "column-of-one", lambda: text_table([("a",)], [{"a": 1}]),
            ("columns",)),
        Row(r + "text_table", "row-without-a-key",
            lambda: text_table([("a", "A", "d")], [{"b": 1}]), ("rows[0]",)),
        Row(r + "text_table", "row-not-a-dict",
            lambda: text_table([("a", "A", "d")], [[1]]), ("rows[0]",)),
        Row(r + "text_table", "by-hand", lambda: text_table([("t", "t", "5.2f")], [{"t": 0.5}]),
            same=lambda s: s == "    t\n 0.50"),
    ]


def _table_report():
    r = Report("T")
    r.table(["a", "b"], [[1, 2.5]])
    return r


def _figure():
    from matplotlib.figure import Figure

    return Figure()


# ------------------------------------------------------------------ course, signal steps
def _course_and_signal_rows():
    t = "ebantenna.course.Tolerance"
    rows = [
        Row(t, "width-str", lambda: course.Tolerance("abs", "1", "r"), ("width",)),
        Row(t, "width-10**400", lambda: course.Tolerance("abs", 10**400, "r"), ("width",)),
        Row(t, "width-negative", lambda: course.Tolerance("rel", -0.1, "r"), ("width",)),
        Row(t, "kind-unknown", lambda: course.Tolerance("x", 0.1, "r"), ("kind",)),
        Row(t, "reason-None", lambda: course.Tolerance("abs", 0.1, None), ("reason",)),
        Row(t + ".accepts", "value-str", lambda: course.Tolerance("abs", 0.1, "r").accepts(
            "a", 1.0), ("value",)),
        Row(t + ".accepts", "expected-10**400", lambda: course.Tolerance("rel", 0.1, "r")
            .accepts(1.0, 10**400), ("expected",)),
        # a factor 2: 1.9 and 1/1.9 of the answer pass, a sign change does not
        Row(t + ".accepts", "factor-by-hand", lambda: [course.Tolerance("factor", 2.0, "r")
                                                       .accepts(v, 3.0) for v in
                                                       (5.7, 3 / 1.9, -3.0, 6.3)],
            same=lambda r: r == [True, True, False, False]),
        Row(t + ".describe", "by-hand", lambda: [course.Tolerance(k, w, "r").describe() for
                                                 k, w in (("abs", 0), ("rel", 0.01),
                                                          ("factor", 3))],
            same=lambda r: r == ["exact", "±1 %", "a factor 3"]),
        Row("ebantenna.course.tolerances", "exercise-unknown",
            lambda: course.tolerances("x"), ("x",)),
        Row("ebantenna.course.tolerances", "exercise-int", lambda: course.tolerances(5),
            ("exercise",)),
        Row("ebantenna.course.exercises", "names-have-tolerances",
            lambda: [course.tolerances(e) for e in course.exercises()],
            same=lambda r: len(r) > 0 and all(isinstance(t, dict) and t for t in r)),
    ]
    s = "ebantenna.signal.spectral.window_weights"
    rows += [
        Row(s, "window-unknown", lambda: spectral.window_weights("x", 8), ("window",)),
        Row(s, "n-0", lambda: spectral.window_weights("hann", 0), ("n",)),
        Row(s, "n-float", lambda: spectral.window_weights("hann", 8.0), ("n",)),
        Row(s, "n-10**12", lambda: spectral.window_weights("hann", 10**12), ("n",)),
        Row(s, "hann-by-hand", lambda: spectral.window_weights("hann", 4),
            same=lambda r: np.allclose(r, [0, 0.5, 1, 0.5], rtol=0, atol=1e-16)),
    ]
    e = "ebantenna.signal.decay.analytic_envelope"
    rows += [
        Row(e, "x-str", lambda: decay.analytic_envelope("abc"), ("x",)),
        Row(e, "x-2-D", lambda: decay.analytic_envelope(np.ones((2, 2))), ("x",)),
        Row(e, "x-empty", lambda: decay.analytic_envelope(np.ones(0)), ("x",)),
        Row(e, "x-nan", lambda: decay.analytic_envelope(np.array([1.0, NAN])), ("x",)),
        Row(e, "cos-by-hand", lambda: decay.analytic_envelope([1.0, 0.0, -1.0, 0.0]),
            same=lambda r: np.allclose(r, 1.0, rtol=0, atol=1e-15)),
    ]
    return rows


def all_rows(where="."):
    """Every row; ``where`` is a folder the report rows may write into."""
    return (_split_rows() + _protocol_rows() + _uncertainty_rows() + _metrics_rows()
            + _fem_rows() + _report_rows(str(where)) + _course_and_signal_rows())


IDS = [f"{row.surface.removeprefix('ebantenna.')}:{row.id}" for row in all_rows()]


def test_the_rows_are_distinct():
    assert len(set(IDS)) == len(IDS)


@pytest.mark.parametrize("index", range(len(IDS)), ids=IDS)
def test_every_row_ends_in_a_clear_error_or_the_right_answer(tmp_path, monkeypatch, index):
    monkeypatch.chdir(tmp_path)  # a row that writes where it should not is seen here
    (tmp_path / "out").mkdir()
    check_row(all_rows(tmp_path / "out")[index], IDS[index])
    assert sorted(os.listdir(tmp_path)) == ["out"]  # nothing written beside the folder


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    return rows_by_surface(all_rows())
