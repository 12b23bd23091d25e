"""The paper's data set and the ``simulate`` / ``dataset`` commands."""

import json
import os

import numpy as np
import pytest

from ebantenna._validate import more_jobs_allowed
from ebantenna.cli import main
from ebantenna.paper.data import build_paper_dataset, paper_dataset_plan
from ebantenna.probe import material_names
from ebantenna.recording import Recording
from ebantenna.simulate import builtin_scene, load_dataset, simulate


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    out = tmp_path_factory.mktemp("data")
    return out, build_paper_dataset(out, seed=3, quick=True, show_progress=False)


def test_quick_dataset_layout(quick):
    _, data = quick
    n_contacts = np.arange(0.025, 0.4, 0.05).size
    assert data.ax.shape == data.az.shape == (5 * n_contacts * 3, 1000)
    assert data.ax.dtype == np.float32
    assert tuple(dict.fromkeys(str(m) for m in data.material)) == material_names()
    assert np.unique(data.repetition).tolist() == [0, 1, 2]
    assert np.all(np.abs(data.contact_true - data.contact) <= 0.006)  # 1 mm std, 6 sigma
    assert np.all((data.contact_true > 0) & (data.contact_true < 0.4))
    assert data.fs == 1000.0 and data.checksum() == data.metadata["checksum_sha256"]
    assert data.metadata["config"]["scene"]["name"] == "paper"


def test_rows_are_single_simulations(quick):
    _, data = quick
    scene = builtin_scene("paper")
    for i in (0, 37, data.n_signals - 1):
        rec = simulate(
            scene.with_(
                contact=float(data.contact_true[i]),
                material=str(data.material[i]),
                sweep_speed=float(data.sweep_speed[i]),
                tilt_ratio=float(data.tilt_ratio[i]),
            ),
            seed=int(data.seed_row[i]),
        )
        assert np.array_equal(rec.ax.astype(np.float32), data.ax[i])
        assert np.array_equal(rec.az.astype(np.float32), data.az[i])


def test_deterministic_by_seed_cached_and_checked(quick, tmp_path):
    out, data = quick
    path = data.path
    mtime = os.stat(path).st_mtime_ns
    again = build_paper_dataset(out, seed=3, quick=True, show_progress=False)
    assert os.stat(path).st_mtime_ns == mtime  # reused, not rebuilt
    assert again.checksum() == data.checksum()
    with more_jobs_allowed():  # two workers, on a machine of one core too
        fresh = build_paper_dataset(tmp_path, seed=3, quick=True, n_jobs=2, show_progress=False)
    assert fresh.checksum() == data.checksum()  # same seed, same bytes, whatever the workers
    assert load_dataset(fresh.path).checksum() == data.checksum()
    other = paper_dataset_plan(seed=4, quick=True)
    assert not np.array_equal(other["contact_true"], data.contact_true)
    # A modified file is refused by load_dataset.
    with np.load(fresh.path) as f:
        arrays = {k: f[k] for k in f.files}
    arrays["ax"] = arrays["ax"].copy()
    arrays["ax"][0, 0] += 1.0
    bad = tmp_path / "bad.npz"
    np.savez_compressed(bad, **arrays)
    with pytest.raises(ValueError, match="checksum mismatch"):
        load_dataset(bad)


def test_full_plan_matches_the_paper():
    plan = paper_dataset_plan(seed=0)
    contacts = np.unique(plan["contact"])
    assert contacts.size == 79 and np.allclose(np.diff(contacts), 0.005)
    assert plan["contact"].size == 5 * 79 * 25
    assert np.std(np.log(plan["sweep_speed"])) == pytest.approx(0.10, rel=0.05)


def test_cli_simulate_json(tmp_path, capsys):
    out = tmp_path / "rec.npz"
    code = main(
        [
            "simulate",
            "--scene",
            "paper",
            "--ratio",
            "0.5",
            "--material",
            "pvc",
            "--seed",
            "4",
            "--out",
            str(out),
            "--json",
        ]
    )
    assert code == 0
    report = json.loads(capsys.readouterr().out)
    assert report["contact"] == pytest.approx(0.2) and report["material"] == "pvc"
    rec = Recording.load(out)
    expected = simulate(builtin_scene("paper").with_(contact=0.2, material="pvc"), seed=4)
    assert np.array_equal(rec.ax, expected.ax) and rec.fs == 1000.0
    assert report["modes_x_hz"] == expected.metadata["modes_x_hz"]


def test_cli_simulate_scene_file_and_errors(tmp_path, capsys):
    scene_file = builtin_scene("ideal").with_(contact=0.1).save(tmp_path / "s.toml")
    assert main(["simulate", "--scene", str(scene_file), "--out", str(tmp_path / "r.npz")]) == 0
    assert "touched at 10.00 cm" in capsys.readouterr().out
    with pytest.raises(SystemExit) as exc:
        main(["simulate", "--scene", "ideal", "--contact", "0.5", "--out", str(tmp_path / "r.npz")])
    assert exc.value.code == 2
    assert "contact must lie in" in capsys.readouterr().err


def test_cli_dataset_json(tmp_path, capsys):
    assert main(["dataset", "--out", str(tmp_path), "--quick", "--seed", "3", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["signals"] == 120 and report["repetitions"] == 3 and report["quick"] is True
    assert report["materials"] == sorted(material_names())
    from ebantenna.simulate._block_march import march_engine

    assert report["strike_march"] == march_engine()  # the checksum is that engine's


def test_a_design_of_ones_own_and_its_cache_key(tmp_path):
    from ebantenna.simulate import DatasetDesign
    from ebantenna.simulate import build_dataset as build

    scene = builtin_scene("paper")
    design = DatasetDesign("pair", ("steel", "pvc"), 0.1, 0.15, 2)
    data = build(tmp_path, scene, design, seed=2, show_progress=False)
    assert data.path.name == "paper-pair-seed2.npz"
    assert sorted(set(data.material)) == ["pvc", "steel"]
    np.testing.assert_array_equal(np.unique(data.contact), [0.1, 0.25])
    # no scatter asked for: the realised positions are the nominal ones, the speeds the scene's
    np.testing.assert_array_equal(data.contact_true, data.contact)
    assert np.all(data.sweep_speed == scene.sweep_speed)
    # row 0 is simulate() of its own scene and seed
    rec = simulate(scene.with_(contact=float(data.contact_true[0]), material=str(data.material[0])),
                   seed=int(data.seed_row[0]))
    np.testing.assert_array_equal(data.ax[0], rec.ax.astype(np.float32))
    # another design under the same name is another configuration: rebuilt, not reused
    wider = DatasetDesign("pair", ("steel", "pvc"), 0.1, 0.15, 3)
    again = build(tmp_path, scene, wider, seed=2, show_progress=False)
    assert again.n_signals == 3 * data.n_signals // 2


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(repetitions=0), "repetitions"),
        (dict(contact_step=0.0), "contact_step"),
        (dict(first_contact=-0.1), "first_contact"),
        (dict(materials=("gold",)), "gold"),
        (dict(materials="steel"), "materials"),
        (dict(position_error=-1e-3), "position_error"),
        (dict(name="a b"), "name"),
    ],
)
def test_a_bad_design_names_its_parameter(kwargs, match):
    from ebantenna.simulate import DatasetDesign

    params = dict(name="d", materials=("steel",), first_contact=0.1, contact_step=0.1,
                  repetitions=1)
    with pytest.raises(ValueError, match=match):
        DatasetDesign(**{**params, **kwargs})


def test_a_first_contact_beyond_the_probe_is_refused():
    from ebantenna.simulate import DatasetDesign

    with pytest.raises(ValueError, match="first_contact"):
        DatasetDesign("d", ("steel",), 0.5, 0.1, 1).contacts(0.4)
