"""Result types the package builds and hands back, and the few methods on them that take input.

A result (a study section's ``...Result``, the calibration, an SMO solution, the features of a
data set) is made by the package and read by the user: it is exempt from bad-input rows, with
that reason, and so is every method of one that takes no argument (``to_dict``). The test below
holds the exemptions to what they claim: each exempt class is a dataclass of the package, each
exempt method takes ``self`` alone. The methods that do take input get rows.
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import math
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, check_row  # noqa: E402

from ebantenna.paper import printed  # noqa: E402
from ebantenna.simulate import builtin_scene  # noqa: E402
from ebantenna.study.recorded.calibration import Calibration  # noqa: E402
from ebantenna.study.seed_spread import NetworkRuns  # noqa: E402

#: Result types: ``dotted name`` (class), each built by the package.
RESULTS = [
    "ebantenna._engines.EngineStatus",
    "ebantenna.ml.smo.SMOResult",
    "ebantenna.paper.feature_table.SignalFeatures",
    "ebantenna.paper.controls.Ablation",
    "ebantenna.paper.experiments.ClassificationResult",
    "ebantenna.paper.experiments.RegressionResult",
    "ebantenna.study.ann_setup.AnnSetupResult",
    "ebantenna.study.contact_law.ContactLawResult",
    "ebantenna.study.data_summary.DatasetResult",
    "ebantenna.study.full_range.FullRangeResult",
    "ebantenna.study.hinge_fit.HingeResult",
    "ebantenna.study.learning.LearningResult",
    "ebantenna.study.material_splits.MaterialSplitsResult",
    "ebantenna.study.mode_zones.ModesResult",
    "ebantenna.study.physics_controls.ControlsResult",
    "ebantenna.study.recorded.calibration.Calibration",
    "ebantenna.study.rod_geometry.GeometryResult",
    "ebantenna.study.seed_spread.SeedSpreadResult",
    "ebantenna.study.seed_spread.NetworkRuns",
    "ebantenna.study.signals.DecayResult",
    "ebantenna.study.signals.FrequencyResult",
    "ebantenna.study.time_frequency.TimeFrequencyResult",
    "ebantenna.simulate.contact.ContactStiffness",
    "ebantenna.simulate.modes.ArrestModes",
    "ebantenna.fem.hinge.HingeFit",
    "ebantenna.fem.coupled_sweep.CoupledSweep",
    "ebantenna.fem.coupling.CraigBampton",
    "ebantenna.fem.symbolic.Erratum",
]
#: The types of the paper's printed numbers, which the package defines as constants.
PRINTED = ["ebantenna.paper.printed.PrintedNumber", "ebantenna.paper.printed.PaperConfusion"]
#: Methods of no argument but ``self``.
NO_ARGUMENT = [
    "ebantenna.paper.experiments.ClassificationResult.report",
    "ebantenna.paper.experiments.RegressionResult.report",
    "ebantenna.study.learning.LearningResult.distance_dict",
    "ebantenna.study.recorded.calibration.Calibration.to_dict",
    "ebantenna.simulate.dataset.Dataset.checksum",
    "ebantenna.simulate.dataset.DatasetDesign.to_dict",
    "ebantenna.simulate.modes.ArrestModes.strain_energy_share",
    "ebantenna.fem.assembly.Supports.describe",
    "ebantenna.fem.coupling.Rod.as_beam",
    "ebantenna.fem.modal.ModalResult.overhang_mass_fraction",
    "ebantenna.fem.zones.ZoneResult.boundaries",
    "ebantenna.signal.timefreq.TimeFrequency.ridge",
    "ebantenna.fem.symbolic.paper_errata",
    "ebantenna.fem.symbolic.paper_matrices",
    "ebantenna.fem.symbolic.lambdify_element_matrices",
    # actions and readings of the rig and its simulation, steps of the benches and engines
    "ebantenna.bench.contact_cost.scenes",
    "ebantenna.bench.ml_speed.engine_rows",
    "ebantenna.bench.ml_speed.engines",
    "ebantenna.bench.signal_accuracy.timefreq_rows",
    "ebantenna.bench.simulate_cost.scenarios",
    "ebantenna.device.clock.SystemClock.monotonic",
    "ebantenna.device.clock.VirtualClock.monotonic",
    "ebantenna.device.fifo.FifoStream.drain",
    "ebantenna.device.fifo.FifoStream.report",
    "ebantenna.device.fifo.FifoStream.segment_timing",
    "ebantenna.device.fifo.StreamFault.to_dict",
    "ebantenna.device.i2c.RetryPolicy.delays",
    "ebantenna.device.mpu6050.MPU6050.check_identity",
    "ebantenna.device.mpu6050.MPU6050.configure",
    "ebantenna.device.mpu6050.MPU6050.fifo_count",
    "ebantenna.device.mpu6050.MPU6050.initialize",
    "ebantenna.device.mpu6050.MPU6050.metadata",
    "ebantenna.device.mpu6050.MPU6050.read_acceleration",
    "ebantenna.device.mpu6050.MPU6050.read_fifo",
    "ebantenna.device.mpu6050.MPU6050.start_fifo",
    "ebantenna.device.mpu6050.MPU6050.stop_fifo",
    "ebantenna.device.mpu6050.MPU6050.who_am_i",
    "ebantenna.device.oe.OutputEnable.close",
    "ebantenna.device.oe.OutputEnable.disable_outputs",
    "ebantenna.device.oe.OutputEnable.enable_outputs",
    "ebantenna.device.pantilt.AcquisitionResult.summary",
    "ebantenna.device.pantilt.PanTilt.initialize",
    "ebantenna.device.pantilt.PanTilt.release",
    "ebantenna.device.pca9685.PCA9685.all_off",
    "ebantenna.device.pca9685.PCA9685.initialize",
    "ebantenna.device.plan.Plan.search_config",
    "ebantenna.device.plan.Plan.to_dict",
    "ebantenna.device.recording_session.Connection.close",
    "ebantenna.device.recording_session.RecordingSession.remaining",
    "ebantenna.device.safety.ServoGuard.release_with_retries",
    "ebantenna.device.servo.Servo.release",
    "ebantenna.device.servo.ServoCalibration.to_dict",
    "ebantenna.device.simulated.bus.SimulatedBus.close",
    "ebantenna.device.simulated.faults.FaultInjector.cancel",
    "ebantenna.device.simulated.faults.FaultInjector.late_error",
    "ebantenna.device.simulated.faults.FaultInjector.overcount",
    "ebantenna.device.simulated.faults.FaultInjector.transfer_error",
    "ebantenna.device.simulated.mpu6050.SimulatedMPU6050.brown_out",
    "ebantenna.device.simulated.mpu6050.SimulatedMPU6050.impossible_samples",
    "ebantenna.device.simulated.mpu6050.SimulatedMPU6050.lsb_per_g",
    "ebantenna.device.simulated.mpu6050.SimulatedMPU6050.reset",
    "ebantenna.device.simulated.mpu6050.SimulatedMPU6050.sample_rate",
    "ebantenna.device.simulated.mpu6050.SimulatedMPU6050.true_rate",
    "ebantenna.device.simulated.pca9685.SimulatedLine.close",
    "ebantenna.device.simulated.pca9685.SimulatedLine.off",
    "ebantenna.device.simulated.pca9685.SimulatedLine.on",
    "ebantenna.device.simulated.pca9685.SimulatedPCA9685.frequency",
    "ebantenna.device.simulated.pca9685.SimulatedPCA9685.oe_line",
    "ebantenna.device.simulated.pca9685.SimulatedPCA9685.outputs_enabled",
    "ebantenna.device.simulated.pca9685.SimulatedPCA9685.reset",
    "ebantenna.device.simulated.rig.SimulatedRig.oe_line",
    "ebantenna.device.simulated.world.ServoMotion.arrival",
    "ebantenna.device.sweep.EllipticalPath.peak_rate",
    "ebantenna.device.wiring.pin_positions",
    "ebantenna.ml.kernels.KernelRows.row_reader",
    "ebantenna.ml.kernels.KernelRows.stored_entries",
    "ebantenna.ml.pair_kernels.PairKernels.pairs",
    "ebantenna.probe.Probe.summary",
    "ebantenna.probe.Probe.to_dict",
] + [f"ebantenna.study.{m}.to_dict" for m in (
    "ann_setup.AnnSetupResult", "contact_law.ContactLawResult", "data_summary.DatasetResult",
    "full_range.FullRangeResult", "hinge_fit.HingeResult", "learning.LearningResult",
    "material_splits.MaterialSplitsResult", "mode_zones.ModesResult",
    "physics_controls.ControlsResult", "rod_geometry.GeometryResult",
    "seed_spread.SeedSpreadResult", "seed_spread.NetworkRuns", "signals.DecayResult",
    "signals.FrequencyResult",
    "time_frequency.TimeFrequencyResult")]


def _find(dotted: str):
    parts = dotted.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
            break
        except ImportError:
            continue
    for attr in parts[i:]:
        obj = getattr(obj, attr)
    return obj


@pytest.mark.parametrize("name", RESULTS + PRINTED)
def test_an_exempt_result_is_a_dataclass_of_the_package(name):
    cls = _find(name)
    assert inspect.isclass(cls) and dataclasses.is_dataclass(cls)
    assert cls.__module__.startswith("ebantenna.")


@pytest.mark.parametrize("name", NO_ARGUMENT)
def test_an_exempt_method_takes_no_argument(name):
    assert list(inspect.signature(_find(name)).parameters) in (["self"], [])


def _calibration() -> Calibration:
    """A calibration as ``calibrate`` returns it, with a hinge bounded on both sides."""
    return Calibration(5.0, 0.01, 0.0025, 1e-5, 0.03, 1e-3, np.array([0.1, 0.2]),
                       np.array([20.0, 30.0]), np.array([20.0, 30.0]), 4,
                       intervals={"hinge_stiffness": (4.0, 6.0), "tip_mass": (0.002, 0.003),
                                  "loss_factor": (0.028, 0.032)}, model="probe")


FIG = printed.PAPER_SVM
#: ``surface -> [(id, call, names or None, same)]``
ROWS = {
    "ebantenna.paper.printed.PaperConfusion.accuracy": [
        ("split-unknown", lambda: FIG.accuracy("x"), ("split",), None),
        ("split-int", lambda: FIG.accuracy(5), ("split",), None),
        # the trace over the total of the printed counts, recomputed by hand
        (f"{next(iter(FIG.matrices))}-by-hand", lambda: FIG.accuracy(next(iter(FIG.matrices))),
         None, lambda a: math.isclose(a, np.trace(next(iter(FIG.matrices.values())))
                                      / np.sum(next(iter(FIG.matrices.values()))),
                                      rel_tol=1e-15)),
    ],
    "ebantenna.paper.printed.percent": [
        ("number-float", lambda: printed.percent(0.5), ("number",), None),
        ("number-in-cm", lambda: printed.percent(printed.PROBE_LENGTH_CM), ("number",), None),
        ("svm-train-by-hand", lambda: printed.percent(printed.SVM_TRAIN_ACCURACY), None,
         lambda s: s == f"{100 * printed.SVM_TRAIN_ACCURACY.value:.1f} %"),
    ],
    "ebantenna.study.recorded.calibration.Calibration.interval": [
        ("name-unknown", lambda: _calibration().interval("x"), ("name",), None),
        ("name-int", lambda: _calibration().interval(3), ("name",), None),
        ("tip-mass", lambda: _calibration().interval("tip_mass"), None,
         lambda r: r == (0.002, 0.003)),
    ],
    "ebantenna.study.recorded.calibration.Calibration.scene": [
        ("base-str", lambda: _calibration().scene("paper"), ("base",), None),
        ("base-none", lambda: _calibration().scene(None), ("base",), None),
        ("fitted-values", lambda: _calibration().scene(builtin_scene("paper")), None,
         lambda s: s.hinge == 5.0 and s.probe.tip_mass == 0.0025
         and s.probe.loss_factor == 0.03 and s.name == "paper-calibrated"),
    ],
}


def _regression_result(positions=(0.1, 0.2, 0.3)):
    """A distance network's result as the package builds it, two recordings a position."""
    from ebantenna.paper.experiments import RegressionResult

    truth = np.repeat(positions, 2)
    pred = truth + 0.01 * np.tile([1.0, 3.0], len(positions))  # errors of 1 and 3 cm
    return RegressionResult("net", truth, pred, np.asarray(positions),
                            np.full(len(positions), 2.0), 0.0)


ROWS["ebantenna.study.seed_spread.NetworkRuns.from_results"] = [
    ("results-not-results", lambda: NetworkRuns.from_results((0, 1), [1.0, 2.0]), ("results",),
     None),
    ("seeds-one-short", lambda: NetworkRuns.from_results(
        (0,), [_regression_result(), _regression_result()]), ("seeds",), None),
    ("seeds-str", lambda: NetworkRuns.from_results(
        "01", [_regression_result(), _regression_result()]), ("seeds",), None),
    ("results-one", lambda: NetworkRuns.from_results((0,), [_regression_result()]),
     ("results",), None),
    # every position's mean error is 2 cm: the runs' mean 2, no spread over positions
    ("by-hand", lambda: NetworkRuns.from_results((0, 1), [_regression_result()] * 2), None,
     lambda r: r.mae_cm.tolist() == [2.0, 2.0] and r.se_cm.tolist() == [0.0, 0.0]
     and r.spread == 0.0 and r.ratio is None),
]

CASES = [(surface, *row) for surface, rows in ROWS.items() for row in rows]


@pytest.mark.parametrize(("surface", "id_", "call", "names", "same"), CASES,
                         ids=[f"{s.rsplit('.', 2)[-2]}.{s.rsplit('.', 1)[-1]}:{i}"
                              for s, i, *_ in CASES])
def test_every_row_ends_in_a_clear_error_or_the_right_answer(surface, id_, call, names, same):
    check_row(Row(surface, id_, call, names or (), same), id_, timeout=3.0)


def contract_rows() -> dict[str, list[str]]:
    """The methods of results that take input (read by the inventory test)."""
    return {surface: [row[0] for row in rows] for surface, rows in ROWS.items()}


def contract_exempt() -> dict[str, str]:
    """Result types and their methods of no argument (read by the inventory test)."""
    return {**{name: "a result type the package builds and hands back" for name in RESULTS},
            **{name: "the type of the paper's printed numbers, constants the package defines"
               for name in PRINTED},
            **{name: "a method or function that takes no argument" for name in NO_ARGUMENT}}
