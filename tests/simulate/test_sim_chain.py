"""The simulator's chain as data: one loop over an ordered list of steps, one entry per effect."""

import numpy as np
import pytest

from ebantenna.simulate import builtin_scene, effect_names, simulate, simulator
from ebantenna.simulate.effects.sensor import CHAIN_STEPS as SENSOR_STEPS
from ebantenna.simulate.modes import CHAIN_STEPS as MODAL_STEPS
from ebantenna.simulate.simulator import CHAIN, ChainStep
from ebantenna.simulate.touched_object import CHAIN_STEPS as OBJECT_STEPS
from ebantenna.simulate.touched_object import OBJECT_MODELS


def _chain_effects():
    seen = []
    for step in CHAIN:
        if step.effect is not None and step.effect not in seen:
            seen.append(step.effect)
    return seen


def _step(apply):
    (step,) = [step for step in CHAIN if step.apply is apply]
    return step


def test_every_effect_is_a_step_of_the_chain_or_read_by_one():
    read = {name for step in CHAIN for name in step.reads}
    assert set(effect_names()) == set(_chain_effects()) | read
    models = {model.effect for model in OBJECT_MODELS if model.effect is not None}
    touched, respond = (_step(OBJECT_STEPS["touched_object"]), _step(MODAL_STEPS["responses"]))
    assert models <= set(touched.reads) and models <= set(respond.reads)


def test_the_chip_filter_is_read_from_the_scene_in_one_place():
    # the package's source reads the scene's dlpf once, where the batch is made; the steps
    # that pass a part of the signal through it say so in their reads
    from pathlib import Path

    import ebantenna.simulate as package

    root = Path(package.__file__).parent
    readers = [str(p.relative_to(root)) for p in root.rglob("*.py")
               if 'effect("dlpf")' in p.read_text()]
    assert sorted(readers) == ["scene.py", "simulator.py"]  # scene.py: checks its settings
    assert Path(root, "simulator.py").read_text().count('effect("dlpf")') == 1
    # the responses, the chip's reading of the axes stepped in time, the hum and the noise
    readers = [step.apply for step in CHAIN if "dlpf" in step.reads]
    assert readers == [MODAL_STEPS["responses"], SENSOR_STEPS["read_timed"],
                       SENSOR_STEPS["mains_hum"], SENSOR_STEPS["sensor_noise"]]


def test_the_chain_applies_effects_in_the_order_a_scene_lists_them():
    order = [name for name in effect_names() if name in set(_chain_effects())]
    assert _chain_effects() == order


def test_a_step_left_out_of_the_chain_is_its_effect_left_out_of_the_scene(monkeypatch):
    scene = builtin_scene("paper").with_(contact=0.3)
    without = scene.with_(effects=[e for e in scene.effects if e.name != "kalman"])
    expected = simulate(without, seed=4)
    monkeypatch.setattr(simulator, "CHAIN", tuple(s for s in CHAIN if s.effect != "kalman"))
    got = simulate(scene, seed=4)
    # the same operations on the same numbers in the same order: equal to the bit
    np.testing.assert_array_equal(got.ax, expected.ax)
    np.testing.assert_array_equal(got.az, expected.az)


def test_a_new_effect_is_one_entry(monkeypatch):
    scene = builtin_scene("ideal").with_(contact=0.2, effects=["gravity"])
    plain = simulate(scene)

    def shift(gravity, batch):  # a made-up step: 1 m/s^2 more on X wherever gravity is listed
        batch.ax = batch.ax + 1.0

    monkeypatch.setattr(simulator, "CHAIN", CHAIN + (ChainStep("gravity", shift),))
    shifted = simulate(scene)
    np.testing.assert_array_equal(shifted.ax, plain.ax + 1.0)  # one addition, exact
    np.testing.assert_array_equal(shifted.az, plain.az)
    np.testing.assert_array_equal(simulate(scene.with_(effects=[])).ax, plain.ax)


@pytest.mark.parametrize("x_modes", [True, False])
def test_the_models_of_the_touched_rod_follow_the_scene(x_modes):
    paper = builtin_scene("paper")  # strikes that only push, no friction
    linear = paper.with_(effects=[e for e in paper.effects if e.name != "unilateral_contact"])
    rubbing = linear.with_(effects=(*linear.effects, "coulomb_friction"))
    wanted = {
        name: {m.name for m in OBJECT_MODELS if m.wanted(scene, x_modes)}
        for name, scene in (("paper", paper), ("linear", linear), ("rubbing", rubbing))
    }
    assert wanted["paper"] == ({"coupled", "unilateral"} if x_modes else {"unilateral"})
    assert wanted["linear"] == {"coupled"}
    assert wanted["rubbing"] == {"coupled", "friction"}
