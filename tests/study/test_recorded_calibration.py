"""Calibrating the scene from recordings (ebantenna.study.recorded.calibration): known hinge
stiffness, tip mass and loss factor recovered from simulated-rig recordings within the stated 95 %
intervals, and the calibrated scene usable by ``simulate`` and ``dataset``."""

from __future__ import annotations

import json

import numpy as np
import pytest

from ebantenna import Probe
from ebantenna.cli import main
from ebantenna.device.plan import Plan
from ebantenna.device.recording_session import RecordingSession
from ebantenna.device.simulated.touches import simulated_connect
from ebantenna.simulate import DatasetDesign, Scene, build_dataset, simulate
from ebantenna.simulate.effects import SensorNoise, StructuralDamping, TipMass
from ebantenna.simulate.scene import load_scene
from ebantenna.study.recorded import assemble_dataset, calibrate

#: The simulated rig's probe: a hinge of 20 N m/rad and a 4 g tip, the tube's loss factor 0.03.
TRUE_HINGE, TRUE_TIP = 20.0, 0.004
RIG = Scene(name="rig", probe=Probe(tip_mass=TRUE_TIP), hinge=TRUE_HINGE,
            effects=(StructuralDamping(), TipMass(), SensorNoise()))


@pytest.fixture(scope="module")
def recorded(tmp_path_factory):
    """Six distances x 2 repetitions of brass, recorded through the simulated rig, assembled."""
    where = tmp_path_factory.mktemp("calibration")
    plan = Plan("calibration", ("brass",), (0.05, 0.10, 0.15, 0.20, 0.25, 0.30), 2)
    RecordingSession(where / "session", plan, simulated_connect(RIG, simulate, seed=1),
                     show_progress=False).run()
    return assemble_dataset(where / "session", where)


def test_calibration_recovers_the_rig_within_its_stated_uncertainty(recorded):
    cal = calibrate(recorded, Probe())  # starts from the bare tube: no tip, its own loss factor
    for name, truth in (("hinge_stiffness", TRUE_HINGE), ("tip_mass", TRUE_TIP),
                        ("loss_factor", RIG.probe.loss_factor)):
        lo, hi = cal.interval(name)
        assert lo <= truth <= hi, (name, lo, truth, hi)
    assert cal.rms_residual_hz < 0.01  # Hz: the model explains the measured frequencies


def test_the_calibrated_scene_is_usable_by_simulate_and_dataset(recorded, tmp_path, capsys):
    assert main(["calibrate", "--data", str(recorded.path), "--scene", "paper",
                 "--out", str(tmp_path), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert (tmp_path / "calibration.png").stat().st_size > 0
    scene = load_scene(summary["scene"])
    assert scene.hinge == pytest.approx(summary["hinge_stiffness_n_m_per_rad"], rel=1e-12)
    assert scene.probe.tip_mass == pytest.approx(summary["tip_mass_kg"], rel=1e-12)
    rec = simulate(scene.with_(contact=0.2), seed=0)
    assert np.isfinite(rec.ax).all()
    data = build_dataset(tmp_path / "data", scene, DatasetDesign("tiny", ("brass",), 0.1, 0.1, 1))
    assert data.n_signals == 3
    assert main(["simulate", "--scene", summary["scene"], "--ratio", "0.5",
                 "--out", str(tmp_path / "one.npz"), "--json"]) == 0
