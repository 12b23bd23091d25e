"""The ``modes`` and ``exact`` commands: JSON contract, plots, errors."""

import json
import subprocess
import sys

import numpy as np
import pytest

from ebantenna.cli import main


def run_json(capsys, argv):
    assert main(argv) == 0
    out = capsys.readouterr().out
    return json.loads(out)


def test_modes_json_follows_the_contract(capsys):
    data = run_json(capsys, ["modes", "--ratio", "0.5", "--elements", "2", "--json"])
    assert set(data) == {"probe", "hinge", "contact", "elements", "frequencies_hz"}
    assert set(data["probe"]) == {"L", "E", "rho", "A", "I", "tip_mass"}
    assert data["contact"] == pytest.approx(0.2) and data["elements"] == 2
    assert data["hinge"] == "clamped" and len(data["frequencies_hz"]) == 3


def test_exact_and_fine_modes_agree(capsys):
    exact = run_json(capsys, ["exact", "--contact", "0.3", "--hinge", "pinned", "--json"])
    fem = run_json(
        capsys, ["modes", "--contact", "0.3", "--hinge", "pinned", "--elements", "128", "--json"]
    )
    assert exact["elements"] is None
    np.testing.assert_allclose(fem["frequencies_hz"], exact["frequencies_hz"], rtol=1e-7)


def test_modes_plot_writes_an_image(tmp_path, capsys):
    out = tmp_path / "modes.png"
    assert main(["modes", "--ratio", "0.8", "--plot", str(out)]) == 0
    assert out.stat().st_size > 10_000
    assert "mode 1" in capsys.readouterr().out


def test_bad_ratio_is_a_clear_error(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["modes", "--ratio", "1.5"])
    assert exc.value.code == 2
    assert "--ratio must lie in (0, 1)" in capsys.readouterr().err


def test_python_dash_m_runs_the_same_command():
    done = subprocess.run(
        [sys.executable, "-m", "ebantenna", "exact", "--no-contact", "--modes", "1", "--json"],
        capture_output=True,
        text=True,
        check=True,
    )
    assert json.loads(done.stdout)["frequencies_hz"][0] == pytest.approx(13.8828316, rel=1e-7)
