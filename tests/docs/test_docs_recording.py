"""The numbers of user_guide/recording.rst ("Recording your own data set") hold for what the
package computes from the search settings."""

from pathlib import Path

import pytest

from ebantenna.chips.mpu6050 import RESET_WAIT
from ebantenna.device.pantilt import SearchConfig
from ebantenna.device.plan import MOVE_SECONDS, session_time
from ebantenna.study.recorded import protocol_plan

PAGE = (Path(__file__).resolve().parents[2] / "docs" / "user_guide" / "recording.rst").read_text()


@pytest.mark.parametrize("quick, touches, placements, typical, worst", [
    (False, "9875", "395", "11.9 h", "39.4 h"),
    (True, "120", "40", "26 min", "46 min"),
])
def test_session_times_as_stated(quick, touches, placements, typical, worst):
    t = session_time(protocol_plan(quick=quick))
    assert (str(t["touches"]), str(t["placements"])) == (touches, placements)
    unit = 60.0 if quick else 3600.0
    suffix = " min" if quick else " h"
    digits = 0 if quick else 1
    assert f"{t['total_s'] / unit:.{digits}f}{suffix}" == typical
    assert f"{t['worst_s'] / unit:.{digits}f}{suffix}" == worst
    row = f"     - {touches}\n     - {placements}\n     - {typical}\n     - {worst}"
    assert row in PAGE


def test_per_touch_figures_as_stated():
    config = SearchConfig()
    t = session_time(protocol_plan())
    stated = (
        f"{RESET_WAIT:g} s reset wait",
        f"within one {config.path.period:g} s loop",
        f"{config.path.period / 2:g} s on average",
        f"the {config.max_search_time:g} s",
        f"records {config.pre_trigger + config.duration:.2f} s around the contact",
        f"{t['touch_s']:.2f} s on average",
        f"assumed to take {MOVE_SECONDS:g} s",
    )
    for text in stated:
        assert text in " ".join(PAGE.split()), text
