"""The setup page's install check prints what the page says it prints, and the rig page states
only datasheet figures the package holds."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest
from unloaded_time import run

DOCS = Path(__file__).resolve().parents[2] / "docs"
INSTALL = DOCS / "user_guide" / "install.rst"


def _console_sessions(text: str) -> list[tuple[str, str]]:
    """``(command, output)`` of every ``$ ebantenna ...`` line of the page's console blocks."""
    sessions = []
    for block in re.findall(r"^\.\. code-block:: console\n\n((?:   .*\n|\n)+)", text, flags=re.M):
        lines = [line[3:] for line in block.rstrip("\n").splitlines()]
        for k, line in enumerate(lines):
            if line.startswith("$ ebantenna"):
                end = next((j for j in range(k + 1, len(lines)) if lines[j].startswith("$ ")),
                           len(lines))
                sessions.append((line[2:], "\n".join(lines[k + 1:end]).rstrip()))
    return sessions


def _mask_version(text: str) -> str:
    return re.sub(r"^ebantenna \S+$", "ebantenna <version>", text, flags=re.M)


SESSIONS = _console_sessions(INSTALL.read_text())


def test_the_check_shows_the_version_and_a_model():
    assert [command for command, _ in SESSIONS] == [
        "ebantenna --version", "ebantenna modes --ratio 0.5 --elements 2"]


@pytest.mark.parametrize("command, documented", SESSIONS, ids=[c for c, _ in SESSIONS])
def test_documented_output_is_what_the_command_prints(command, documented):
    args = [sys.executable, "-m", "ebantenna", *command.split()[1:]]
    # a start-up and a 2-element model, about a second of CPU: 120 s of the child's own time
    # (waits for a CPU left out) is a hang
    done = run(args, 120, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert _mask_version(done.stdout.rstrip()) == _mask_version(documented)


def test_a_changed_output_would_be_caught():
    command, documented = SESSIONS[1]
    assert _mask_version(documented.replace("39.08", "39.09")) != _mask_version(documented)
    assert _mask_version("ebantenna 9.9.9") == _mask_version("ebantenna 0.2.0")


def test_every_route_is_described():
    text = INSTALL.read_text()
    for needle in ("python3 -m venv .venv", "py -3 -m venv .venv", r".venv\Scripts\Activate.ps1",
                   "conda create", 'pip download "ebantenna[teach]" -d wheelhouse',
                   'pip install --no-index --find-links wheelhouse "ebantenna[teach]"'):
        assert needle in text, needle
    extras = re.search(r"^teach = \[(.*)\]$", (DOCS.parent / "pyproject.toml").read_text(),
                       flags=re.M).group(1)
    for package in re.findall(r'"([a-z]+)', extras):
        assert package in text.replace("JupyterLab", "jupyterlab"), package


def _range(pair, unit):
    low, high = pair
    return f"{low:g}–{high:g} {unit}"


def test_rig_page_states_the_packages_figures():
    from ebantenna.device import wiring

    text = (DOCS / "user_guide" / "rig.rst").read_text()
    stated = [
        f"address 0x{wiring.MPU6050_ADDRESS:02X}", f"address 0x{wiring.PCA9685_ADDRESS:02X}",
        _range(wiring.MPU6050_VDD, "V"), _range(wiring.PCA9685_VDD, "V"),
        _range(wiring.SERVO_VOLTAGE, "V"), _range(wiring.SERVO_SUPPLY, "V"),
        f"{wiring.SERVO_STALL_CURRENT:.1f} A", f"{wiring.servo_supply_current():.1f} A",
        f"i2c_arm_baudrate={wiring.FAST_MODE_HZ}", f"i2cdetect -y {wiring.I2C_BUS}",
        f"``--oe-gpio {wiring.OE_GPIO}``", f"GPIO {wiring.OE_GPIO} (header pin "
        f"{wiring.HEADER_PIN[f'GPIO {wiring.OE_GPIO}']})",
        f"pin {wiring.HEADER_PIN[f'GPIO {wiring.SDA_GPIO}']} (GPIO {wiring.SDA_GPIO})",
        f"pin {wiring.HEADER_PIN[f'GPIO {wiring.SCL_GPIO}']} (GPIO {wiring.SCL_GPIO})",
        f"pan into output {wiring.PAN_CHANNEL}, tilt into output {wiring.TILT_CHANNEL}",
        f"pin {wiring.HEADER_PIN['3.3 V']} (3.3 V)",
    ]
    for figure in stated:
        assert figure in text.replace("\n   ", " ").replace("\n", " "), figure
    # every volt and ampere figure on the page is one of those above
    for number in re.findall(r"(\d+(?:\.\d+)?) ?(?:V|A)\b", text):
        assert any(number in figure for figure in stated), number
    assert "\n   draw_wiring()\n" in text
    # the device page's wiring list gives the same supply (a safety figure: a supply sized below
    # the stall current browns out)
    device = " ".join((DOCS / "user_guide" / "device.rst").read_text().split())
    supply = (f"{_range(wiring.SERVO_SUPPLY, 'V')} supply able to give "
              f"{wiring.SERVO_STALL_CURRENT:.1f} A per MG996R (its stall current: "
              f"{wiring.servo_supply_current():.1f} A for the two)")
    assert supply in device, supply
    # the checklist is linked, not copied: it lives on the device page
    assert "Hardware-in-the-loop checklist" in (DOCS / "user_guide" / "device.rst").read_text()
