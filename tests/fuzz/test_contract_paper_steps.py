"""The input contract of the paper's experiments and plots, and of the simulator's modal steps.

Each refuses a feature matrix that is not one, labels and targets of the wrong length, a
negative regularisation or length, a result of another type, a scene or data set that is not
one, unsorted or non-numeric nodes, a non-symmetric stiffness and damping ratios outside
[0, 1), naming the parameter; good inputs are checked by hand.

Found by these rows and fixed: ``AttributeError`` from the plots given a number for a result,
from the grouped-split controls given a number for a data set, from the probe's contact model,
``physics_key`` and ``sweep_velocity`` given a number or a string, "damping ratios must lie
in [0, 1)" (now naming ``zeta``), and a ``split`` of the classifiers that is not a pair of row
index arrays ("invalid literal for int()", an ``IndexError`` for rows beyond ``X``).
"""

from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, check_row  # noqa: E402

from ebantenna import Probe  # noqa: E402
from ebantenna.paper import controls, experiments, mode_curves, plots  # noqa: E402
from ebantenna.simulate import builtin_scene, modes, simulator, structure, unilateral  # noqa: E402

NAN = math.nan
RNG = np.random.default_rng(0)
X = RNG.normal(size=(40, 3))
MATS = np.array(["a", "b"] * 20)
DIST = RNG.uniform(0.05, 0.35, 40)


def _filtered_modes() -> bool:
    import scipy.signal as sps

    from ebantenna.simulate.effects import LowPassFilter

    dlpf = LowPassFilter()
    d = dlpf.divider(1000.0)
    modal = (np.ones((1, 2)), np.array([[2 * np.pi * 40, 2 * np.pi * 310]]), np.full((1, 2), 0.02))
    read = modes.modal_acceleration(np.arange(50) / 1000.0, *modal, low_pass=dlpf)[0]
    u = modes.modal_acceleration(np.arange(50 * d) / dlpf.internal_rate, *modal)[0]
    witness = sps.sosfilt(dlpf.sos, u)[::d]
    # a few roundings per internal sample, accumulated by the recursion over the record
    return bool(np.max(np.abs(read - witness)) <= 64 * np.finfo(float).eps * u.size
                * np.max(np.abs(u)))
e, s = "ebantenna.paper.experiments.", "ebantenna.simulate."

#: ``surface -> [(id, call, names or None, same)]``
ROWS = {
    e + "classify_materials_svm": [
        ("X-str", lambda: experiments.classify_materials_svm("x", MATS), ("X",), None),
        ("materials-short", lambda: experiments.classify_materials_svm(X, MATS[:3]),
         ("materials",), None),
        ("C-negative", lambda: experiments.classify_materials_svm(X, MATS, C=-1), ("C",), None),
        ("test_fraction-2", lambda: experiments.classify_materials_svm(X, MATS,
                                                                       test_fraction=2.0),
         ("test_fraction",), None),
        ("split-str", lambda: experiments.classify_materials_svm(X, MATS, split="x"),
         ("split",), None),
        ("split-beyond-rows", lambda: experiments.classify_materials_svm(
            X, MATS, split=(np.arange(30), np.arange(35, 45))), ("split", "0 ... 39"), None),
        ("split-fractional-rows", lambda: experiments.classify_materials_svm(
            X, MATS, split=(np.arange(30) + 0.5, np.arange(30, 40))), ("split",), None),
        ("split-overlap", lambda: experiments.classify_materials_svm(
            X, MATS, split=(np.arange(30), np.arange(29, 40))), ("split", "both"), None),
        # a given split is the one used: its 10 test rows are the ones tested
        ("split-used", lambda: experiments.classify_materials_svm(
            X, MATS, split=(np.arange(30), np.arange(30, 40)), gamma="scale"), None,
         lambda r: int(r.confusions["test"].sum()) == 10),
    ],
    e + "classify_materials_ann": [
        ("materials-short", lambda: experiments.classify_materials_ann(X, MATS[:3]),
         ("materials",), None),
        ("X-nan", lambda: experiments.classify_materials_ann(X * NAN, MATS), ("X",), None),
    ],
    e + "regress_distance_full_length": [
        ("distances-short", lambda: experiments.regress_distance_full_length(X, DIST[:3]),
         ("distances",), None),
    ],
    e + "regress_distance_linear_region": [
        ("probe_length-negative", lambda: experiments.regress_distance_linear_region(
            X, DIST, probe_length=-1.0), ("probe_length",), None),
        ("split-one-part", lambda: experiments.regress_distance_linear_region(
            X, DIST, probe_length=0.4, split=(np.arange(30),)), ("split",), None),
    ],
    "ebantenna.paper.plots.plot_confusion_comparison": [
        ("result-int", lambda: plots.plot_confusion_comparison(5), ("result",), None),
    ],
    "ebantenna.paper.plots.plot_distance_errors": [
        ("results-int", lambda: plots.plot_distance_errors(5), ("results",), None),
        ("none", lambda: plots.plot_distance_errors(), ("RegressionResult",), None),
    ],
    "ebantenna.paper.mode_curves.classify_materials_by_mode_curves": [
        ("materials-short", lambda: mode_curves.classify_materials_by_mode_curves(
            np.abs(X), np.abs(X[:, 0]), MATS[:3], DIST, "random"), ("materials",), None),
        ("split-str", lambda: mode_curves.classify_materials_by_mode_curves(
            np.abs(X), np.abs(X[:, 0]), MATS, DIST, "random"), ("split",), None),
    ],
    "ebantenna.paper.controls.grouped_svm_accuracy": [
        ("ds-int", lambda: controls.grouped_svm_accuracy(5), ("ds",), None),
    ],
    "ebantenna.paper.controls.grouped_svm_spread": [
        ("ds-str", lambda: controls.grouped_svm_spread("data.npz"), ("ds",), None),
    ],
    s + "modes.damped_exponentials": [
        ("t-str", lambda: modes.damped_exponentials("x", np.ones(2), np.ones(2)), ("t ",), None),
        ("t-complex", lambda: modes.damped_exponentials([1j], np.ones(2), np.ones(2)), ("t ",),
         None),
    ],
    s + "modes.modal_exponentials": [
        ("zeta-negative", lambda: modes.modal_exponentials(np.ones(2), np.ones(2), -np.ones(2)),
         ("zeta",), None),
        ("zeta-1", lambda: modes.modal_exponentials(np.ones(2), np.ones(2), np.ones(2)),
         ("zeta",), None),
        # undamped: the rate is i omega
        ("undamped-by-hand", lambda: modes.modal_exponentials(
            np.ones((1, 1)), np.full((1, 1), 3.0), np.zeros((1, 1)))[1], None,
         lambda rate: np.allclose(rate, 3.0j, rtol=0, atol=1e-15)),
    ],
    s + "modes.modal_acceleration": [
        ("zeta-above-1", lambda: modes.modal_acceleration(np.zeros(3), np.ones(2), np.ones(2),
                                                          np.full(2, 2.0)), ("zeta",), None),
        ("low_pass-str", lambda: modes.modal_acceleration(
            np.zeros(3), np.ones((1, 1)), np.ones((1, 1)), np.zeros((1, 1)), low_pass="dlpf"),
         ("low_pass",), None),
        # through the chip's filter: the unfiltered sum at the internal rate, run through the
        # filter's sections by scipy and decimated, to the rounding the recursion accumulates
        ("low_pass-against-sosfilt", _filtered_modes, None, lambda r: r),
    ],
    s + "modes.sweep_velocity": [
        ("nodes-str", lambda: modes.sweep_velocity("x"), ("nodes",), None),
        ("nodes-2-D", lambda: modes.sweep_velocity(np.ones((2, 2))), ("nodes",), None),
        ("by-hand", lambda: modes.sweep_velocity(np.array([0.0, 0.1, 0.2])), None,
         lambda r: r.tolist() == [0.0, 1.0, 0.1, 1.0, 0.2, 1.0]),
    ],
    s + "modes.arrest_modes": [
        ("probe-int", lambda: modes.arrest_modes(5, "clamped", 0.2, n_elements=8, n_modes=2,
                                                 max_frequency=1000.0), ("probe",), None),
        ("contact-beyond-tip", lambda: modes.arrest_modes(
            Probe(), "clamped", 0.5, n_elements=8, n_modes=2, max_frequency=1000.0),
         ("contact",), None),
    ],
    s + "structure.check_dof_vector": [
        ("wrong-length", lambda: structure.check_dof_vector("v", np.ones(3), 4), ("v",), None),
        ("index-beyond", lambda: structure.check_dof_vector("v", 7, 4), ("v",), None),
    ],
    s + "structure.check_symmetric_matrix": [
        ("not-symmetric", lambda: structure.check_symmetric_matrix(
            "K", np.array([[1.0, 2.0], [0.0, 1.0]])), ("K",), None),
        ("nan", lambda: structure.check_symmetric_matrix("K", np.full((2, 2), NAN)), ("K",),
         None),
    ],
    s + "unilateral.mass_inverse": [
        ("singular", lambda: unilateral.mass_inverse(np.zeros((2, 2))), ("mass",), None),
        ("diagonal-by-hand", lambda: unilateral.mass_inverse(np.diag([2.0, 4.0])), None,
         lambda r: np.allclose(r, np.diag([0.5, 0.25]), rtol=1e-15, atol=0)),
    ],
    s + "structure.probe_contact_model": [
        ("probe-int", lambda: structure.probe_contact_model(5, 0.2), ("probe",), None),
        ("contact-beyond-tip", lambda: structure.probe_contact_model(Probe(), 0.5),
         ("contact",), None),
        ("n_modes-0", lambda: structure.probe_contact_model(Probe(), 0.2, n_modes=0),
         ("n_modes",), None),
    ],
    s + "simulator.physics_key": [
        ("scene-int", lambda: simulator.physics_key(5), ("scene",), None),
        ("sensor-stage-left-out", lambda: (simulator.physics_key(builtin_scene("paper")),
                                           simulator.physics_key(builtin_scene("paper").with_(
                                               name="other"))), None, lambda r: r[0] == r[1]),
    ],
    s + "simulator.simulate_sensor_variants": [
        ("scenes-int", lambda: simulator.simulate_sensor_variants(5), ("scenes",), None),
        ("scenes-a-scene", lambda: simulator.simulate_sensor_variants(builtin_scene("paper")),
         ("scenes",), None),
        ("scenes-empty", lambda: simulator.simulate_sensor_variants([]), ("scenes",), None),
        ("return_saturated-str", lambda: simulator.simulate_sensor_variants(
            [builtin_scene("paper")], return_saturated="yes"), ("return_saturated",), None),
    ],
    s + "simulator.simulate_batch": [
        ("return_saturated-str", lambda: simulator.simulate_batch(
            builtin_scene("paper"), return_saturated="yes"), ("return_saturated",), None),
        # the ideal scene has no range: nothing counted, said by None
        ("return_saturated-no-range", lambda: simulator.simulate_batch(
            builtin_scene("ideal"), return_saturated=True), None, lambda r: r[5] is None),
    ],
}
CASES = [(surface, *row) for surface, rows in ROWS.items() for row in rows]


@pytest.mark.parametrize(("surface", "id_", "call", "names", "same"), CASES,
                         ids=[f"{s_.rsplit('.', 1)[-1]}:{i}" for s_, i, *_ in CASES])
def test_every_row_ends_in_a_clear_error_or_the_right_answer(surface, id_, call, names, same):
    check_row(Row(surface, id_, call, names or (), same), id_)


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    return {surface: [row[0] for row in rows] for surface, rows in ROWS.items()}
