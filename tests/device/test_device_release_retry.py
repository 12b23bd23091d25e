"""The I2C release of the servos, retried while the OE pin holds their outputs off: a release
that lands within the retries is a release (exit 0 from acquire); one that never lands still
ends with the instruction to cut the servo supply (exit 3). Judged on the simulated
controller's own registers and OE pin."""

from __future__ import annotations

import json

import pytest
from test_device_trust import _search  # the rig, the chip and one search, as there

from ebantenna.cli import main
from ebantenna.device.i2c import BusHealth
from ebantenna.device.safety import MAX_HELD_RETRY, ReleaseError, ServoGuard
from ebantenna.device.simulated import Faults
from ebantenna.device.watchdog import StreamStalledError


@pytest.fixture(scope="module")
def search_end():
    """Virtual time at which the fault-free search of seed 1 ends (its release begins)."""
    rig, _, search = _search(None, oe=False)
    search()
    return rig.clock.monotonic()


@pytest.mark.parametrize("fails_for", [4.0, 8.0])
def test_a_release_that_lands_while_the_oe_pin_holds_the_outputs_is_a_release(
        search_end, fails_for):
    # before: the first 2 s of retries failed, the OE pin held the outputs, and the run ended
    # "switch off the servo supply" though the bus answered again seconds later
    rig, mpu, search = _search(Faults(release_fails_until=search_end + fails_for), oe=True)
    result = search()
    assert result.servos_released and result.servos_released_by == "i2c"
    # released by the registers: whatever the OE line does at exit, no output has a pulse
    assert all(rig.pca.pulse(ch) == 0 for ch in (0, 1))
    assert rig.clock.monotonic() - search_end <= fails_for + 1.0 + 2.0  # one interval + a try


def test_without_the_oe_pin_the_release_is_not_retried_past_its_deadline(search_end):
    rig, mpu, search = _search(Faults(release_fails_until=search_end + 4.0), oe=False)
    with pytest.raises(ReleaseError, match="switch off the servo supply"):
        search()
    assert rig.pca.outputs_enabled()  # nothing holds the servos: the operator must act now


def test_a_release_that_never_lands_is_retried_for_a_bounded_time_and_refused(search_end):
    rig, mpu, search = _search(Faults(release_fails=True), oe=True)
    with pytest.raises(ReleaseError, match="only while this program runs.*switch off the "
                                           "servo supply") as info:
        search()
    assert info.value.result.servos_released_by == "oe" and not rig.pca.outputs_enabled()
    refused = [t for t, kind in rig.bus.injector.log if kind == "release refused"]
    # the first round (2 s deadline), then the held retries: 10 s, one attempt a second
    assert refused[-1] - refused[0] <= 2.0 + 10.0 + 1e-9
    assert len({round(t) for t in refused if t > refused[0] + 2.5}) >= 5


def test_a_bus_declared_dead_is_tried_again_while_the_outputs_are_held():
    # stuck for 3 s, each transfer hanging 1 s: the bus is declared dead, the stream stalls,
    # the release fails at once (BusDeadError); the OE pin holds the outputs, and the held
    # retries try the bus again (revived) once it answers
    faults = Faults(stuck_at=0.777, stuck_duration=6.0, transfer_timeout=1.0)
    rig, mpu, search = _search(faults, oe=True)
    with pytest.raises(StreamStalledError) as info:
        search()
    assert info.value.servos_released is True
    assert not rig.pca.outputs_enabled() and rig.pca.pulse(0) == 0 and rig.pca.pulse(1) == 0


def test_acquire_exits_0_when_the_held_retries_release_the_servos(search_end, capsys, tmp_path,
                                                                   monkeypatch):
    # acquire's simulated rig is the same as the search's here (seed 1, the paper scene); with
    # no --out, an unreleased run keeps its recording in the working folder: a fresh one
    monkeypatch.chdir(tmp_path)
    code = main(["acquire", "--simulated", "--seed", "1", "--oe-gpio", "17", "--json"])
    plain = json.loads(capsys.readouterr().out)
    assert code == 0 and plain["servos_released_by"] == "i2c"
    code = main(["acquire", "--simulated", "--seed", "1", "--release-fails", "--oe-gpio", "17",
                 "--json"])
    captured = capsys.readouterr()
    assert code == 3 and "switch off the servo supply" in captured.err.strip().splitlines()[-1]
    assert len(list(tmp_path.glob("acquire-unreleased-*.npz"))) == 1  # what it recorded, kept


def test_the_guard_refuses_bad_retry_settings():
    from ebantenna.device.clock import VirtualClock

    clock = VirtualClock()
    for bad, error in ((("held_retry", -1.0), ValueError), (("held_retry", MAX_HELD_RETRY + 1),
                                                            ValueError),
                       (("held_interval", 0.0), ValueError), (("revive", 3), TypeError)):
        with pytest.raises(error, match=bad[0]):
            ServoGuard(lambda: None, clock, **{bad[0]: bad[1]})


def test_revive_lets_the_next_transfer_try_a_dead_bus():
    health = BusHealth()
    health.failed(1.0)
    assert health.failing_for(5.0) == 4.0
    health.revive()
    assert health.failing_for(5.0) == 0.0
