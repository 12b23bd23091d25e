"""Scenes that differ only in their sensor stage share the physics, bit for bit.

The controls rebuild the data set once per effect switched off; for the effects of the sensor
stage (:data:`ebantenna.simulate.simulator.SENSOR_EFFECTS`) the physics before that stage is
the same, and :func:`ebantenna.simulate.build_datasets` simulates it once. These tests pin the
claim that this changes no number: every data set equals the one built alone, array for array.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from ebantenna._validate import more_jobs_allowed
from ebantenna.paper.controls import ABLATION_DESIGN
from ebantenna.simulate import (
    build_dataset,
    build_datasets,
    builtin_scene,
    simulate,
    simulate_batch,
)
from ebantenna.simulate.simulator import (
    SENSOR_EFFECTS,
    physics_key,
    simulate_sensor_variants,
)

SMALL = replace(ABLATION_DESIGN, name="variants", materials=("brass", "oak"), contact_step=0.1,
                repetitions=2)


def _without(scene, name):
    return scene.with_(name=f"{scene.name}-without-{name}",
                       effects=[e for e in scene.effects if e.name != name])


@pytest.fixture(scope="module")
def paper():
    return builtin_scene("paper")


def test_physics_key_ignores_the_name_and_the_sensor_stage_only(paper):
    for name in SENSOR_EFFECTS:
        assert physics_key(_without(paper, name)) == physics_key(paper), name
    for name in ("clock_jitter", "dlpf", "preload_scatter", "object_damping"):
        changed = _without(paper, name) if name != "dlpf" else paper.with_(
            effects=[e for e in paper.effects if e.name != "dlpf"], max_frequency=500.0)
        assert physics_key(changed) != physics_key(paper), name


def test_sensor_variants_equal_each_scene_simulated_alone(paper):
    scenes = [paper, _without(paper, "sensor_noise"), _without(paper, "gravity"),
              _without(paper, "kalman")]
    rows = dict(contact=np.array([0.05, 0.2, 0.35]), material=np.array(["brass", "pvc", "oak"]),
                sweep_speed=np.array([0.5, 0.45, 0.55]), tilt_ratio=0.25, seeds=[3, 4, 5],
                show_progress=False, x_modes=False)
    shared = simulate_sensor_variants(scenes, **rows)
    for scene, (t, ax, az, x, _) in zip(scenes, shared, strict=True):
        t1, ax1, az1, x1, _ = simulate_batch(scene, **rows)
        assert np.array_equal(t, t1) and np.array_equal(ax, ax1) and np.array_equal(az, az1), \
            scene.name
        assert np.array_equal(x.restrikes, x1.restrikes)
    # the variants do differ: the test would not pass by giving every scene the first's signals
    assert not np.array_equal(shared[0][2], shared[2][2])  # Z without gravity


def test_each_variant_counts_the_samples_its_own_range_saturated(paper):
    """A narrower range (8 g) is a sensor variant of the paper's 16 g: the shared physics, its
    own count of saturated samples, equal to the scene simulated alone and to the single
    recording's metadata."""
    narrow = paper.with_(name="paper-8g", effects=[
        replace(e, range_g=8) if e.name in ("clipping", "quantisation") else e
        for e in paper.effects])
    rows = dict(contact=np.array([0.2, 0.36, 0.39]), material=np.array(["steel", "brass", "pvc"]),
                seeds=[3, 4, 5], show_progress=False, x_modes=False)
    shared = simulate_sensor_variants([paper, narrow], **rows, return_saturated=True)
    counts = []
    for scene, result in zip((paper, narrow), shared, strict=True):
        assert len(result) == 6
        alone = simulate_batch(scene, **rows, return_saturated=True)[5]
        assert alone.tolist() == result[5].tolist(), scene.name
        single = [simulate(scene.with_(contact=c, material=m), seed=s).metadata[
            "samples_saturated"] for c, m, s in zip(rows["contact"], rows["material"],
                                                    rows["seeds"], strict=True)]
        assert single == result[5].tolist(), scene.name
        counts.append(result[5])
    # the narrower range holds at least the samples the wider one does, and more here
    assert np.all(counts[1] >= counts[0]) and counts[1].sum() > counts[0].sum()
    assert len(simulate_batch(paper, **rows)) == 5  # without the flag, as before


def test_sensor_variants_refuse_scenes_that_differ_in_the_physics(paper):
    with pytest.raises(ValueError, match="only in the sensor stage.*paper-without-clock_jitter"):
        simulate_sensor_variants([paper, _without(paper, "clock_jitter")], contact=0.2)


def test_data_sets_built_together_equal_those_built_alone(paper, tmp_path):
    scenes = [paper, _without(paper, "mains_hum"), _without(paper, "quantisation"),
              _without(paper, "preload_scatter")]  # the last: physics of its own
    with more_jobs_allowed():  # two workers, on a machine of one core too
        together = build_datasets(tmp_path / "together", scenes, SMALL, seed=2, n_jobs=2,
                                  show_progress=False)
    for scene, ds in zip(scenes, together, strict=True):
        alone = build_dataset(tmp_path / scene.name, scene, SMALL, seed=2, show_progress=False)
        assert ds.checksum() == alone.checksum() == alone.metadata["checksum_sha256"]
        assert ds.metadata["config"] == alone.metadata["config"]
        assert ds.metadata.get("restrikes") == alone.metadata.get("restrikes")
        assert ds.path.name == alone.path.name
    # and they are cached: built again, every one is loaded, not simulated
    again = build_datasets(tmp_path / "together", scenes, SMALL, seed=2, show_progress=False)
    assert [d.checksum() for d in again] == [d.checksum() for d in together]


def test_a_data_set_does_not_depend_on_the_number_of_workers(paper, tmp_path):
    # without quantisation a float32 signal keeps every last bit: a worker process runs BLAS on
    # one thread, the caller on its own count, and some OpenBLAS builds round a product
    # differently on two threads (NumPy 1.24's did), so the build pins BLAS to one thread
    scene = _without(paper, "quantisation")
    one = build_dataset(tmp_path / "one", scene, SMALL, seed=2, n_jobs=1, show_progress=False)
    with more_jobs_allowed():  # two workers, on a machine of one core too
        two = build_dataset(tmp_path / "two", scene, SMALL, seed=2, n_jobs=2,
                            show_progress=False)
    assert one.checksum() == two.checksum()


def test_build_datasets_refuses_two_scenes_of_one_name(paper, tmp_path):
    with pytest.raises(ValueError, match="distinct names"):
        build_datasets(tmp_path, [paper, paper], SMALL)
    with pytest.raises(TypeError, match="scenes must be Scenes, got str"):
        build_datasets(tmp_path, [paper, "paper"], SMALL)
