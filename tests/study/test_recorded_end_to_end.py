"""From the rig to the report on the simulated rig: the quick design recorded through the simulated
I2C bus with injected faults and an interruption that resumes, assembled into a data set, the
study run on it with ``reproduce --data``, and its SVM and distance results set beside the same
design simulated directly."""

from __future__ import annotations

import json
import time

import pytest

from ebantenna.cli import main
from ebantenna.device.recording_session import RecordingSession, read_manifest
from ebantenna.device.simulated import Faults
from ebantenna.device.simulated.touches import simulated_connect
from ebantenna.paper import experiments
from ebantenna.paper.data import build_paper_dataset
from ebantenna.paper.feature_table import signal_features
from ebantenna.simulate import builtin_scene, simulate
from ebantenna.study.recorded import (
    NOT_APPLICABLE,
    classification_interval,
    placement_interval,
    protocol_plan,
)

#: The quick design's contact spacing, m (QUICK_DESIGN.contact_step).
STEP = 0.05
#: Share of I2C transfers that fail, every kind.
FAULT_RATE = 0.002


class InterruptingBus:
    """A bus that raises KeyboardInterrupt (Ctrl-C) at its ``after``-th FIFO read: mid-search."""

    def __init__(self, bus, after: int):
        self._bus, self._after, self._reads = bus, after, 0

    def __getattr__(self, name):
        attr = getattr(self._bus, name)
        if name != "read_i2c_block_data":
            return attr

        def read(*args, **kwargs):
            self._reads += 1
            if self._reads == self._after:
                raise KeyboardInterrupt
            return attr(*args, **kwargs)

        return read


def record_with_an_interruption(out, plan, scene, at: int) -> dict:
    """Record ``plan``, interrupted mid-touch at touch ``at``, then resumed to the end."""
    faults = Faults.every_kind(FAULT_RATE)
    connect = simulated_connect(scene, simulate, faults=faults, seed=0)

    def interrupted(touch, attempt):
        conn = connect(touch, attempt)
        if touch.index == at:
            conn.bus = InterruptingBus(conn.bus, after=10)
        return conn

    first = RecordingSession(out, plan, interrupted, rig={"simulated": True},
                             show_progress=False)
    with pytest.raises(KeyboardInterrupt):
        first.run()
    saved = dict(read_manifest(first.manifest_path)["recordings"])
    assert sorted(e["touch"] for e in saved.values()) == list(range(at))
    resumed = RecordingSession(out, plan, connect, rig={"simulated": True}, show_progress=False)
    resumed.open()
    assert len(resumed.remaining()) == len(plan) - at
    manifest = resumed.run()
    for key, entry in saved.items():  # nothing saved was lost or made again
        assert manifest["recordings"][key] == entry
    assert sorted(e["touch"] for e in manifest["recordings"].values()) == list(range(len(plan)))
    return manifest


def simulated_directly(cache) -> dict:
    """The SVM and the two distance networks on the same design simulated directly (the quick
    data set in ``cache``: the quick study's, built there by its direct simulation)."""
    ds = build_paper_dataset(cache, seed=0, quick=True, n_jobs=1, show_progress=False)
    feats = signal_features(ds.ax, ds.az, ds.fs, n_jobs=1, show_progress=False)
    return {
        "svm": classification_interval(experiments.classify_materials_svm(feats.fft, ds.material,
                                                                          seed=0), ds.contact),
        "linear_region": placement_interval(experiments.regress_distance_linear_region(
            feats.fft, ds.contact, probe_length=0.40, seed=0), STEP),
        "full_length": placement_interval(experiments.regress_distance_full_length(
            feats.fft_elliptic, ds.contact, seed=0), STEP),
    }


def test_quick_design_from_the_rig_to_the_report(quick_study, tmp_path, capsys):
    start, cpu = time.perf_counter(), time.process_time()
    scene = builtin_scene("paper")
    plan = protocol_plan(quick=True, scene=scene, seed=0)
    manifest = record_with_an_interruption(tmp_path / "session", plan, scene, at=len(plan) // 3)
    assert len(manifest["recordings"]) == len(plan) == 120

    assert main(["dataset", "--from-recordings", str(tmp_path / "session"),
                 "--out", str(tmp_path / "data"), "--json"]) == 0
    assembled = json.loads(capsys.readouterr().out)
    assert assembled["signals"] == 120 and assembled["source"] == "recordings"

    assert main(["reproduce", "--data", assembled["path"], "--out", str(tmp_path / "report"),
                 "--jobs", "1", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["data"]["source"] == "recordings"
    assert summary["data"]["checksum_sha256"] == assembled["checksum_sha256"]
    assert set(summary["not_applicable"]) == set(NOT_APPLICABLE)
    report = (tmp_path / "report" / "report.md").read_text()
    assert "Sections not applicable to this data set" in report
    assert "How much the numbers carry" not in report  # the seeds section does not run here
    assert str(tmp_path / "session") in report  # it says which data it ran on
    for section in ("svm_grouped_test_accuracy", "svm_blocked_test_accuracy",
                    "mode_curve_test_accuracy"):
        assert section in summary["materials"]

    direct = simulated_directly(quick_study[1])  # the data set read, not simulated again
    recorded = summary["intervals"]
    lines = []
    for name, sim in direct.items():
        rec = recorded[name]
        share = "test_accuracy" if name == "svm" else "placed"
        lo_r, hi_r = rec["interval95"]
        lo_s, hi_s = sim["interval95"]
        lines.append(f"{name}: recorded {rec[share]:.3f} [{lo_r:.3f}, {hi_r:.3f}] of "
                     f"{rec['n_test']}, simulated {sim[share]:.3f} [{lo_s:.3f}, {hi_s:.3f}] "
                     f"of {sim['n_test']}")
        # agreement: each estimate lies within the other's 95 % interval
        assert lo_s <= rec[share] <= hi_s and lo_r <= sim[share] <= hi_r, lines[-1]
    print("\n".join(lines) + f"\nwhole path: {time.perf_counter() - start:.0f} s wall, "
          f"{time.process_time() - cpu:.0f} s CPU in this process")
