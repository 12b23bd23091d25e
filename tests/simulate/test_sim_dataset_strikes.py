"""What a data set keeps of each strike besides its signals, so that a study reads it instead of
simulating the strikes again (the lift-off share of the linear contact, the re-strikes)."""

import json
import logging

import numpy as np
import pytest

from ebantenna.simulate import (
    DatasetDesign,
    build_dataset,
    builtin_scene,
    dataset_plan,
    simulate_batch,
)
from ebantenna.simulate import dataset as dataset_module

PAPER = builtin_scene("paper")
LINEAR = PAPER.with_(name="paper-linear",
                     effects=[e for e in PAPER.effects if e.name != "unilateral_contact"])
DESIGN = DatasetDesign("tiny", ("steel", "pvc"), 0.1, 0.35, 2)  # 2 materials x 2 contacts x 2


@pytest.fixture(scope="module")
def linear_set(tmp_path_factory):
    return build_dataset(tmp_path_factory.mktemp("linear"), LINEAR, DESIGN, seed=3, n_jobs=1,
                         show_progress=False)


def test_the_linear_contact_keeps_each_strikes_lift_off_ratio_as_simulate_batch_gives_it(
        linear_set):
    plan = dataset_plan(LINEAR, DESIGN, 3)
    _, _, _, x, _ = simulate_batch(
        LINEAR, contact=plan["contact_true"], material=plan["material"],
        sweep_speed=plan["sweep_speed"], tilt_ratio=plan["tilt_ratio"], seeds=plan["seed_row"],
        show_progress=False,
    )  # fmt: skip
    kept = np.asarray(linear_set.metadata["lift_off_ratio"])
    witness = x.lift_off_ratio(LINEAR.duration)
    assert kept.shape == (linear_set.n_signals,)
    # the same per-row arithmetic; only the batch's zero padding of the modes may regroup a
    # sum of about 30 terms, each at most the ratio's scale: 30 eps of it
    assert np.allclose(kept, witness, rtol=0, atol=30 * np.finfo(float).eps * np.abs(witness).max())
    assert "restrikes" not in linear_set.metadata


def test_the_unilateral_contact_keeps_its_restrikes_and_no_lift_off(tmp_path):
    ds = build_dataset(tmp_path, PAPER, DatasetDesign("one", ("steel",), 0.2, 0.2, 1), seed=0,
                       show_progress=False)
    assert len(ds.metadata["restrikes"]) == ds.n_signals
    assert "lift_off_ratio" not in ds.metadata


def test_a_scene_without_the_touched_objects_modes_keeps_neither(tmp_path):
    bare = PAPER.with_(name="bare", effects=("structural_damping", "tip_mass", "dlpf"))  # pinned
    ds = build_dataset(tmp_path, bare, DatasetDesign("one", ("steel",), 0.2, 0.2, 1), seed=0,
                       show_progress=False)
    assert not {"restrikes", "lift_off_ratio"} & set(ds.metadata)


@pytest.mark.parametrize("key", ["lift_off_ratio", "samples_saturated"])
def test_a_cached_set_written_without_what_it_keeps_is_rebuilt_and_says_why(
        linear_set, tmp_path, caplog, key):
    path = tmp_path / linear_set.path.name
    with np.load(linear_set.path) as f:
        arrays = {k: f[k] for k in f.files}
    metadata = json.loads(str(arrays.pop("metadata")))
    del metadata[key]  # as a data set of an earlier version was written
    np.savez(path, metadata=json.dumps(metadata), **arrays)
    with caplog.at_level(logging.WARNING, logger=dataset_module.__name__):
        again = build_dataset(tmp_path, LINEAR, DESIGN, seed=3, n_jobs=1, show_progress=False)
    assert f"does not keep each signal's {key}" in caplog.text
    assert again.metadata[key] == linear_set.metadata[key]
    assert np.array_equal(again.az, linear_set.az)


def test_each_signals_saturated_samples_are_those_beyond_the_range_without_it(tmp_path):
    """The count the data set keeps, against a witness: the same rows simulated without the
    range and the two steps after it (quantisation, Kalman filter), whose samples beyond the
    range are counted directly. Every random effect draws from its own stream, so the signals
    reaching the range are the same floats in both."""
    design = DatasetDesign("near-tip", ("steel", "brass", "pvc"), 0.30, 0.03, 1)
    ds = build_dataset(tmp_path, PAPER, design, seed=1, n_jobs=1, show_progress=False)
    plan = dataset_plan(PAPER, design, 1)
    open_ended = PAPER.with_(name="no-range", effects=[
        e for e in PAPER.effects if e.name not in ("clipping", "quantisation", "kalman")])
    _, ax, az, _, _ = simulate_batch(
        open_ended, contact=plan["contact_true"], material=plan["material"],
        sweep_speed=plan["sweep_speed"], tilt_ratio=plan["tilt_ratio"], seeds=plan["seed_row"],
        show_progress=False, x_modes=False,
    )  # fmt: skip
    low, high = PAPER.effect("clipping").limits()
    witness = ((ax < low) | (ax > high)).sum(axis=1) + ((az < low) | (az > high)).sum(axis=1)
    kept = np.asarray(ds.metadata["samples_saturated"])
    assert kept.tolist() == witness.tolist()
    # the design reaches the range (the metals near the tip) and not everywhere: the count can
    # tell the two apart
    assert 0 < np.count_nonzero(kept) < kept.size
    assert not np.any(kept[plan["material"] == "pvc"])
