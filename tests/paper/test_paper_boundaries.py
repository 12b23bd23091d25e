"""Where the paper ends: generic stages know nothing of it, study and bench stay apart, and the
simulated data set follows the paper's protocol."""

import ast
from pathlib import Path

import numpy as np
import pytest

import ebantenna
from ebantenna.paper import printed
from ebantenna.paper.protocol import DATASET
from ebantenna.probe import material_names
from ebantenna.simulate import builtin_scene
from ebantenna.simulate.dataset import dataset_plan

ROOT = Path(ebantenna.__file__).parent


def _imports(path: Path) -> set[str]:
    """Absolute names of the ebantenna modules that ``path`` imports."""
    package = ".".join(("ebantenna", *path.relative_to(ROOT).with_suffix("").parts))
    if path.name == "__init__.py":
        package = package.rsplit(".", 1)[0] + ".__init__"
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names if a.name.startswith("ebantenna")}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: -node.level]
                name = ".".join(base + ([node.module] if node.module else []))
            else:
                name = node.module or ""
            if name.startswith("ebantenna"):
                out.add(name)
                out |= {f"{name}.{a.name}" for a in node.names}
    return out


def _modules(sub: str):
    target = ROOT / sub
    return sorted(target.rglob("*.py")) if target.is_dir() else [target.with_suffix(".py")]


@pytest.mark.parametrize("stage", ["fem", "signal", "ml", "simulate", "device", "report"])
def test_generic_code_does_not_reach_up(stage):
    forbidden = ("ebantenna.paper", "ebantenna.study", "ebantenna.bench")
    for path in _modules(stage):
        bad = {m for m in _imports(path) if m.startswith(forbidden)}
        assert not bad, f"{path.relative_to(ROOT)} imports {sorted(bad)}"


@pytest.mark.parametrize("here, there", [("study", "bench"), ("bench", "study")])
def test_study_and_bench_do_not_import_each_other(here, there):
    for path in _modules(here):
        bad = {m for m in _imports(path) if m.startswith(f"ebantenna.{there}")}
        assert not bad, f"{path.relative_to(ROOT)} imports {sorted(bad)}"


@pytest.mark.parametrize("sub", ["paper", "study", "bench", "report"])
def test_no_module_grows_past_500_lines(sub):
    for path in _modules(sub):
        n = len(path.read_text(encoding="utf-8").splitlines())
        assert n <= 500, f"{path.relative_to(ROOT)} has {n} lines"


def test_the_simulated_data_set_follows_the_paper_protocol():
    # simulate may not import the paper, so its data set builder carries the same design; this
    # is the witness that the two agree
    assert material_names() == DATASET.materials
    assert builtin_scene("paper").probe.length == pytest.approx(DATASET.probe_length)
    assert DATASET.probe_length == pytest.approx(printed.PROBE_LENGTH_CM.value / 100)
    plan = dataset_plan(builtin_scene("paper"), seed=0)
    contacts = np.unique(plan["contact"])
    np.testing.assert_allclose(np.diff(contacts), DATASET.contact_step, atol=1e-9)
    assert np.bincount(plan["repetition"]).size == DATASET.repetitions
    assert set(plan["material"]) == set(DATASET.materials)


def test_every_printed_number_says_where_it_is_printed():
    for name, number in printed.NUMBERS.items():
        assert number.where and number.quote, name
        assert number.unit in printed.UNITS, name
    with pytest.raises(ValueError, match="unit must be one of"):
        printed.PrintedNumber(1.0, "furlong", "nowhere", "")
    # the confusion matrices carry the printed accuracies (their counts are checked against
    # them in test_paper_experiments.py)
    assert printed.PAPER_SVM.reported_accuracy == {"train": 0.997, "test": 0.992}
    assert printed.PAPER_ANN.reported_accuracy == {"all": 0.808}
    with pytest.raises(ValueError, match="number must be a fraction"):
        printed.percent(printed.DEVIATION_CM)


def test_module_names_are_unique():
    """Two modules of one name would be two meanings of one word (and ambiguous in the docs)."""
    names = [p.name for p in ROOT.rglob("*.py") if p.name not in ("__init__.py", "_cli.py")]
    assert sorted({n for n in names if names.count(n) > 1}) == []


def test_the_default_probe_and_paper_scene_are_what_the_paper_prints():
    from ebantenna.probe import Probe

    probe, scene = Probe(), builtin_scene("paper")
    assert probe.length == pytest.approx(printed.PROBE_LENGTH_CM.value / 100)
    assert probe.outer_diameter == pytest.approx(printed.TUBE_OUTER_DIAMETER_CM.value / 100)
    assert probe.inner_diameter == pytest.approx(printed.TUBE_INNER_DIAMETER_CM.value / 100)
    assert scene.fs == pytest.approx(1000 * printed.SAMPLING_FREQUENCY_KHZ.value)
