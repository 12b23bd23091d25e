"""A data set assembled from a session's recordings, and the inconsistent inputs it refuses by
name (ebantenna.study.recorded.assemble_dataset)."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest

from ebantenna.cli import main
from ebantenna.device.plan import Plan
from ebantenna.device.recording_session import MANIFEST, RecordingSession, file_sha256
from ebantenna.device.simulated.touches import simulated_connect
from ebantenna.recording import Recording
from ebantenna.simulate import builtin_scene, load_dataset, simulate
from ebantenna.study.recorded import MIN_SAMPLES, assemble_dataset


@pytest.fixture(scope="module")
def recorded(tmp_path_factory):
    """A finished session of 2 materials x 2 distances x 2 repetitions on the simulated rig."""
    where = tmp_path_factory.mktemp("session") / "s"
    plan = Plan("tiny", ("brass", "pvc"), (0.1, 0.3), 2)
    RecordingSession(where, plan, simulated_connect(builtin_scene("paper"), simulate, seed=2),
                     rig={"simulated": True}, show_progress=False).run()
    return where


@pytest.fixture
def session(recorded, tmp_path):
    """A copy of the finished session to spoil."""
    return shutil.copytree(recorded, tmp_path / "s")


def rewrite(session, touch: int, change) -> str:
    """Replace one recording by ``change(recording)``, the manifest's checksum updated (so that
    only the change itself is wrong)."""
    manifest = json.loads((session / MANIFEST).read_text())
    entry = next(e for e in manifest["recordings"].values() if e["touch"] == touch)
    path = session / entry["file"]
    rec = change(Recording.load(path))
    rec.save(path)
    entry["sha256"] = file_sha256(path)
    (session / MANIFEST).write_text(json.dumps(manifest))
    return entry["file"]


def with_meta(rec, **changes):
    meta = {**rec.metadata, **changes}
    return Recording(rec.t, rec.ax, rec.az, rec.fs, {k: v for k, v in meta.items()
                                                    if v is not None})


def test_assembled_data_set_loads_with_its_labels_and_provenance(recorded, tmp_path):
    data = assemble_dataset(recorded, tmp_path)
    again = load_dataset(data.path)  # its checksum verified
    assert again.n_signals == 8 and again.n_samples == 1000 and again.fs == 1000.0
    assert again.material.tolist() == ["brass"] * 4 + ["pvc"] * 4
    np.testing.assert_array_equal(again.contact, [0.1, 0.1, 0.3, 0.3] * 2)
    np.testing.assert_array_equal(again.repetition, [0, 1] * 4)
    assert np.isnan(again.sweep_speed).all() and (again.seed_row == -1).all()  # not invented
    provenance = again.metadata["provenance"]
    assert provenance["manifest_sha256"] == file_sha256(recorded / MANIFEST)
    assert len(provenance["recordings"]) == 8
    assert again.metadata["config"]["source"] == "recordings"


def test_the_drivers_flags_reach_the_data_set(session, tmp_path, capsys):
    # a recording with suspect timestamps and one whose sensor check flagged a second device:
    # resampled from their timestamps, they would enter the data set unmarked; the provenance
    # names them, and the command says how many
    rewrite(session, 1, lambda r: with_meta(r, samples_timing_suspect=37))
    rewrite(session, 5, lambda r: with_meta(r, sensor_check={**r.metadata.get("sensor_check",
                                                                                {}),
                                                            "flags": ["second device"]}))
    data = assemble_dataset(session, tmp_path)
    flags = data.metadata["provenance"]["flags"]
    assert len(flags) == data.n_signals and data.metadata["provenance"]["recordings_flagged"] == 2
    assert flags[1] == {"samples_timing_suspect": 37}
    assert flags[5] == {"sensor_check": ["second device"]}
    assert not any(f for i, f in enumerate(flags) if i not in (1, 5))
    assert main(["dataset", "--from-recordings", str(session), "--out", str(tmp_path / "cli"),
                 "--json"]) == 0
    out = capsys.readouterr()
    assert json.loads(out.out)["recordings_flagged"] == 2
    assert "2 of the recordings carry the driver's flags" in out.err


def test_a_damaged_file_is_refused_by_name(session, tmp_path):
    manifest = json.loads((session / MANIFEST).read_text())
    entry = manifest["recordings"]["pvc/0.1000/1"]
    path = session / entry["file"]
    path.write_bytes(path.read_bytes()[:200])
    with pytest.raises(ValueError, match=f"{path.name}: damaged file"):
        assemble_dataset(session, tmp_path)


def test_a_missing_label_is_refused_by_name(session, tmp_path):
    name = rewrite(session, 3, lambda r: with_meta(r, material=None))
    with pytest.raises(ValueError, match=f"{name}: missing label\\(s\\) material"):
        assemble_dataset(session, tmp_path)


def test_a_duplicate_is_refused_by_name(session, tmp_path):
    name = rewrite(session, 1, lambda r: with_meta(r, repetition=0))
    with pytest.raises(ValueError, match=f"{name}: duplicate of .*t00000"):
        assemble_dataset(session, tmp_path)


def test_a_sample_rate_that_differs_is_refused_by_name(session, tmp_path):
    name = rewrite(session, 5, lambda r: with_meta(r, sample_rate_hz=500.0))
    with pytest.raises(ValueError, match=f"{name}: sample rate 500 Hz differs from 1000 Hz"):
        assemble_dataset(session, tmp_path)
    rewrite(session, 5, lambda r: with_meta(r, sample_rate_hz=1000.0))
    fast = rewrite(session, 6, lambda r: Recording(r.t / 1.03, r.ax, r.az, r.fs * 1.03,
                                                   r.metadata))
    with pytest.raises(ValueError, match=f"{fast}: sample rate estimated .* by more than 1.0%"):
        assemble_dataset(session, tmp_path)


def test_what_record_keeps_the_data_set_takes_whatever_its_timestamps_round_to(session, tmp_path):
    """A recording that lost exactly the session's limit in one gap, whose timestamps after the
    gap sit 0.56 of a period late (a restart re-anchors them within their stated uncertainty,
    0.7 of a period here; the simulated rig made such a recording): on the nominal grid the gap
    holds one point more than was lost. ``record`` kept it, so the data set takes it; one sample
    more lost is refused."""
    limit = json.loads((session / MANIFEST).read_text())["max_lost"]

    def gap(lost):
        def change(r):
            lost_here = r.metadata.get("samples_lost", 0)
            window = r.n_samples + lost_here
            cut = np.r_[0:300, 300 + lost:r.n_samples]
            t = r.t[cut] + np.where(cut >= 300, 0.56 / r.fs, 0.0)
            return Recording(t, r.ax[cut], r.az[cut], r.fs,
                             {**r.metadata, "samples_lost": window - cut.size,
                              "timestamp_uncertainty_s": 0.7 / r.fs})
        return change

    window = Recording.load(session / rewrite(session, 3, lambda r: r)).n_samples
    budget = int(limit * window)
    rewrite(session, 3, gap(budget))
    data = assemble_dataset(session, tmp_path)
    assert data.metadata["provenance"]["samples_interpolated"][3] == budget + 1
    shutil.rmtree(tmp_path / "data", ignore_errors=True)
    name = rewrite(session, 4, gap(budget + 1))
    with pytest.raises(ValueError, match=f"{name}: {budget + 1} of {window} samples of the window "
                                         "lost"):
        assemble_dataset(session, tmp_path)


def test_a_recording_too_short_for_the_features_is_refused_by_name(session, tmp_path):
    cut = MIN_SAMPLES  # the window from the contact on then holds fewer samples than needed
    name = rewrite(session, 2, lambda r: Recording(r.t[:cut], r.ax[:cut], r.az[:cut], r.fs,
                                                   r.metadata))
    with pytest.raises(ValueError, match=f"{name}: too short"):
        assemble_dataset(session, tmp_path)
