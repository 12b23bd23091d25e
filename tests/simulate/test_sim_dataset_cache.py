"""The data set cache: what its key covers, how it heals, how a build ends, where it runs."""

import json
import logging
import os
import subprocess
import sys

import numpy as np
import pytest

from ebantenna._tempfiles import TEMPORARY_PREFIX
from ebantenna.simulate import DatasetDesign, build_dataset, builtin_scene, load_dataset
from ebantenna.simulate import dataset as dataset_module

SCENE = builtin_scene("paper")
DESIGN = DatasetDesign("tiny", ("steel", "pvc"), 0.1, 0.2, 1)  # 2 materials x 2 contacts


def build(out, scene=SCENE, **kwargs):
    return build_dataset(out, scene, DESIGN, seed=5, show_progress=False, **kwargs)


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    return build(tmp_path_factory.mktemp("reference"))


def rewrite(path, **changes):
    """Rewrite a data set file with some arrays or metadata changed and a fresh checksum."""
    with np.load(path) as f:
        arrays = {k: f[k] for k in f.files}
    metadata = json.loads(str(arrays.pop("metadata")))
    for key, value in changes.items():
        if key in arrays:
            arrays[key] = value
        else:
            metadata["config"][key] = value
    fs = float(arrays.pop("fs"))
    metadata["checksum_sha256"] = dataset_module._checksum(arrays, fs)
    np.savez_compressed(path, fs=fs, metadata=np.array(json.dumps(metadata)), **arrays)


def rebuilt(tmp_path, reference, caplog, damage, reason):
    data = build(tmp_path)
    damage(data.path)
    with caplog.at_level(logging.WARNING, logger="ebantenna.simulate.dataset"):
        again = build(tmp_path)
    assert again.checksum() == reference.checksum()
    assert load_dataset(again.path).checksum() == reference.checksum()  # the file healed
    messages = [r.getMessage() for r in caplog.records]
    assert any("rebuilding" in m and reason in m for m in messages), messages


def test_a_truncated_cache_file_is_rebuilt_saying_why(tmp_path, reference, caplog):
    def truncate(path):
        os.truncate(path, path.stat().st_size // 2)

    rebuilt(tmp_path, reference, caplog, truncate, "truncated or damaged")


@pytest.mark.parametrize(
    "content, reason",
    [(b"", "empty"), (b"t,ax\n1,2\n", "not an .npz archive"), (None, "missing")],
)
def test_a_foreign_cache_file_is_rebuilt_saying_why(tmp_path, reference, caplog, content, reason):
    def replace(path):
        if content is None:
            np.savez(path, ax=np.zeros(3))  # a valid archive, but not a data set
        else:
            path.write_bytes(content)

    rebuilt(tmp_path, reference, caplog, replace, reason)


def test_a_stale_cache_of_another_version_is_rebuilt_even_with_a_valid_checksum(
    tmp_path, reference, caplog
):
    def stale(path):
        rewrite(path, ebantenna_version="0.0.1", ax=np.zeros_like(reference.ax))

    rebuilt(tmp_path, reference, caplog, stale, "configuration changed (ebantenna_version)")


def test_a_cache_made_by_the_other_strike_march_is_rebuilt(tmp_path, reference, caplog):
    # the compiled and NumPy marches agree within a bound, not bit for bit: a data set made by
    # one is not the other's, and says which made it
    made_by = reference.metadata["config"]["strike_march"]
    assert made_by == dataset_module.march_engine() and made_by in ("numpy", "compiled")
    other = {"numpy": "compiled", "compiled": "numpy"}[made_by]

    def by_the_other(path):
        rewrite(path, strike_march=other, ax=np.zeros_like(reference.ax))

    rebuilt(tmp_path, reference, caplog, by_the_other, "configuration changed (strike_march)")


def test_the_strike_march_of_the_key_follows_the_engine_choice(monkeypatch):
    monkeypatch.setenv("EBANTENNA_ENGINE", "numpy")
    assert dataset_module.march_engine() == "numpy"
    monkeypatch.setenv("EBANTENNA_ENGINE", "auto")
    from ebantenna.simulate._block_march import compiled_status

    assert dataset_module.march_engine() == ("compiled" if compiled_status().available
                                             else "numpy")


def test_the_cache_key_covers_every_scene_parameter(tmp_path, reference, caplog):
    config = reference.metadata["config"]
    assert config["scene"] == json.loads(json.dumps(SCENE.to_dict()))
    assert set(config["materials"]) == {"steel", "pvc"}
    assert config["materials"]["pvc"]["loss_factor"] > 0  # the physics, not only the name
    build(tmp_path)
    # one effect's parameter changed: the physics changed, the file is stale
    effect = next(e for e in SCENE.effects if e.parameters())
    name, value = next(iter(effect.parameters().items()))
    changed = SCENE.with_(
        effects=tuple(
            type(e)(**{**e.parameters(), name: value * 1.5}) if e is effect else e
            for e in SCENE.effects
        )
    )
    with caplog.at_level(logging.WARNING, logger="ebantenna.simulate.dataset"):
        other = build(tmp_path, scene=changed)
    assert other.checksum() != reference.checksum()
    assert any("scene.effects" in r.getMessage() for r in caplog.records)


def test_leftover_temporary_files_of_dead_builds_are_removed(tmp_path, reference):
    path = tmp_path / reference.path.name
    dead = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"],
        capture_output=True,
        text=True,
        check=True,
    )
    left = path.with_name(f"{TEMPORARY_PREFIX}{int(dead.stdout)}-{path.name}")
    alive = path.with_name(f"{TEMPORARY_PREFIX}{os.getppid()}-{path.name}")  # a running one's
    left.write_bytes(b"half a file")
    alive.write_bytes(b"being written")
    build(tmp_path)
    assert not left.exists() and alive.exists()


def test_an_interrupted_write_leaves_no_temporary_file(tmp_path, monkeypatch):
    def interrupted_savez(file, **arrays):
        with open(file, "wb") as f:
            f.write(b"PK\x03\x04 half")
        raise KeyboardInterrupt

    monkeypatch.setattr(dataset_module.np, "savez", interrupted_savez)
    with pytest.raises(KeyboardInterrupt):
        build(tmp_path)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    "content, match",
    [
        (b"", "is empty"),
        (b"not an archive", "not an .npz archive"),
        ({"ax": np.zeros(2)}, "missing az"),
    ],
)
def test_load_dataset_names_the_file_and_what_is_wrong(tmp_path, content, match):
    path = tmp_path / "d.npz"
    if isinstance(content, dict):
        np.savez(path, **content)
    else:
        path.write_bytes(content)
    with pytest.raises(ValueError, match=match) as exc:
        load_dataset(path)
    assert str(path) in str(exc.value)


def test_load_dataset_refuses_metadata_that_is_not_json(tmp_path, reference):
    path = tmp_path / "d.npz"
    with np.load(reference.path) as f:
        arrays = {k: f[k] for k in f.files}
    arrays["metadata"] = np.array("{not json")
    np.savez(path, **arrays)
    with pytest.raises(ValueError, match="is not an ebantenna data set"):
        load_dataset(path)


def test_the_build_runs_on_a_dask_cluster_through_joblib(tmp_path, reference):
    distributed = pytest.importorskip(
        "distributed", reason="dask.distributed is not installed (pip install ebantenna[cluster])"
    )
    from joblib import parallel_config

    # two workers: with room for one task only, joblib would run the tasks in this process
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    )
    with cluster, distributed.Client(cluster) as client:
        with parallel_config(backend="dask"):
            data = build(tmp_path)
        executed = client.run(lambda dask_worker: dask_worker.state.executed_count)
    assert sum(executed.values()) >= len(DESIGN.materials)  # ran in the cluster's workers
    assert data.checksum() == reference.checksum()  # same bytes as on one machine
