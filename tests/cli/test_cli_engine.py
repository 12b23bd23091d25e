"""The engine choice in the environment is checked before any command runs.

``EBANTENNA_ENGINE=compiled`` where the compiled engines cannot load (numba missing or broken)
ended ``reproduce`` part-way with a ``RuntimeError`` traceback; an unknown engine name was
refused only where an estimator first ran. Both now end in one line naming the variable, before
any work.
"""

import pytest

from ebantenna import _engines as _engine_choice
from ebantenna.cli import main
from ebantenna.ml import _engine_check

UNAVAILABLE = _engine_choice.EngineStatus(False, "numba is not installed: (test)", float("nan"))


def _error(capsys, argv) -> str:
    with pytest.raises(SystemExit) as caught:
        main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert caught.value.code == 2 and len(err) == 1, err
    return err[0]


@pytest.mark.parametrize("argv", [["modes", "--no-contact"], ["exact", "--ratio", "0.5"]])
def test_compiled_without_its_engines_is_one_clear_error(monkeypatch, capsys, argv):
    monkeypatch.setenv("EBANTENNA_ENGINE", "compiled")
    monkeypatch.setattr(_engine_check, "smo_status", lambda: UNAVAILABLE)
    monkeypatch.setattr(_engine_check, "mlp_status", lambda: UNAVAILABLE)
    line = _error(capsys, argv)
    assert "EBANTENNA_ENGINE=compiled" in line and "numba is not installed" in line


@pytest.mark.parametrize("value", ["fast", "", "COMPILED", "numba"])
def test_an_unknown_engine_is_refused_by_the_variables_name(monkeypatch, capsys, value):
    monkeypatch.setenv("EBANTENNA_ENGINE", value)
    assert "EBANTENNA_ENGINE must be one of" in _error(capsys, ["modes", "--no-contact"])


@pytest.mark.parametrize("value", ["numpy", "auto"])
def test_a_valid_choice_runs(monkeypatch, capsys, value):
    monkeypatch.setenv("EBANTENNA_ENGINE", value)
    assert main(["exact", "--ratio", "0.5"]) == 0


def contract_rows() -> dict[str, list[str]]:
    """The environment's engine choice, met by every command (read by the inventory test)."""
    return {"cli:modes": ["engine-compiled-unavailable", "engine-unknown"],
            "cli:exact": ["engine-compiled-unavailable", "engine-valid"],
            "ml.check_engine": ["engine-compiled-unavailable", "engine-unknown"]}


def test_check_engine_returns_the_choice(monkeypatch):
    from ebantenna.ml import check_engine

    monkeypatch.setenv("EBANTENNA_ENGINE", "numpy")
    assert check_engine() == "numpy"
    monkeypatch.delenv("EBANTENNA_ENGINE")
    assert check_engine() == "auto"
    monkeypatch.setenv("EBANTENNA_ENGINE", "x")
    with pytest.raises(ValueError, match="EBANTENNA_ENGINE must be one of"):
        check_engine()
