"""Counts of workers and the memory budget are bounded before any work.

Every function that takes ``n_jobs`` (a count of joblib workers) refuses, naming ``n_jobs`` and
before any work, a count that is not None, -1 (every core) or 1 to the machine's cores: 0, -2,
a fraction, a bool, a string, 10**400, and one more worker than the cores (``n_jobs=100000``
started a process for each task). Inside ``more_jobs_allowed`` (what ``--force-jobs`` sets on
the command line) more workers than cores are allowed. The memory budget takes a positive
integer, a NumPy one too, and refuses the rest naming ``nbytes``.
"""

from __future__ import annotations

import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Case, outcome  # noqa: E402

from ebantenna import memory_budget, set_memory_budget  # noqa: E402
from ebantenna._validate import check_n_jobs, more_jobs_allowed  # noqa: E402
from ebantenna.paper.data import build_paper_dataset  # noqa: E402
from ebantenna.paper.feature_table import mode_peaks, signal_features  # noqa: E402
from ebantenna.simulate import DatasetDesign, build_dataset, build_datasets, builtin_scene  # noqa
from ebantenna.study.recorded.study import reproduce_recorded  # noqa: E402
from ebantenna.study.reproduce import reproduce  # noqa: E402

CORES = os.cpu_count() or 1
#: Counts no ``n_jobs`` accepts: ``label -> value``.
BAD_JOBS = {"0": 0, "-2": -2, "2.5": 2.5, "True": True, "str-2": "2", "10**400": 10**400,
            "cores+1": CORES + 1, "100000": 100000, "nan": float("nan")}
SMALL = DatasetDesign("w", ("brass",), 0.1, 0.1, 1)
AX = np.zeros((2, 64))


def _surfaces(where):
    """``surface -> call(n_jobs)``; each writes (if it ran at all) under ``where``."""
    scene = builtin_scene("paper")
    return {
        "ebantenna.simulate.dataset.build_dataset":
            lambda n: build_dataset(where / "d", scene, SMALL, n_jobs=n, show_progress=False),
        "ebantenna.simulate.dataset.build_datasets":
            lambda n: build_datasets(where / "d", [scene], SMALL, n_jobs=n, show_progress=False),
        "ebantenna.paper.data.build_paper_dataset":
            lambda n: build_paper_dataset(where / "d", quick=True, n_jobs=n, show_progress=False),
        "ebantenna.paper.feature_table.signal_features":
            lambda n: signal_features(AX, AX, 1000.0, n_jobs=n, show_progress=False),
        "ebantenna.paper.feature_table.mode_peaks":
            lambda n: mode_peaks(AX, 1000.0, n_jobs=n, show_progress=False),
        "ebantenna.study.reproduce.reproduce":
            lambda n: reproduce(where / "r", quick=True, n_jobs=n, cache_dir=where / "c",
                                show_progress=False),
        "ebantenna.study.recorded.study.reproduce_recorded":
            lambda n: reproduce_recorded(where / "missing.npz", where / "r", n_jobs=n),
    }


SURFACES = list(_surfaces(None))


@pytest.mark.parametrize("label", BAD_JOBS)
@pytest.mark.parametrize("surface", SURFACES)
def test_a_bad_count_of_workers_is_refused_naming_n_jobs_before_any_work(tmp_path, surface,
                                                                         label):
    call = _surfaces(tmp_path)[surface]
    kind, what = outcome(Case(f"{surface}:n_jobs={label}", lambda: call(BAD_JOBS[label]),
                              "error", ("n_jobs",), timeout=10))
    assert kind == "clear", what
    assert list(tmp_path.iterdir()) == []  # nothing was made


def test_more_workers_than_cores_only_when_allowed():
    assert check_n_jobs("n_jobs", CORES) == CORES
    assert check_n_jobs("n_jobs", -1) == -1 and check_n_jobs("n_jobs", None) is None
    with pytest.raises(ValueError, match=f"n_jobs must be at most this machine's {CORES} core"):
        check_n_jobs("n_jobs", CORES + 1)
    with more_jobs_allowed():
        assert check_n_jobs("n_jobs", CORES + 1) == CORES + 1
        with more_jobs_allowed(False):
            with pytest.raises(ValueError, match="n_jobs"):
                check_n_jobs("n_jobs", CORES + 1)
        assert check_n_jobs("n_jobs", CORES + 1) == CORES + 1
    with pytest.raises(ValueError, match="n_jobs"):  # the context ended
        check_n_jobs("n_jobs", CORES + 1)


#: Budgets ``set_memory_budget`` refuses: ``label -> value``.
BAD_BUDGETS = {"0": 0, "-1": -1, "-10**5000": -(10**5000), "float": 1.5e6, "str": "1G",
               "bool": True, "list": [1], "np-float": np.float64(1e6)}


@pytest.mark.parametrize("label", BAD_BUDGETS)
def test_a_bad_memory_budget_is_refused_naming_nbytes(label):
    try:
        kind, what = outcome(Case(f"set_memory_budget:{label}",
                                  lambda: set_memory_budget(BAD_BUDGETS[label]), "error",
                                  ("nbytes",)))
    finally:
        set_memory_budget(None)
    assert kind == "clear", what


def test_a_memory_budget_of_any_integer_type_is_kept_as_an_int():
    try:
        for value in (1, 10**6, np.int64(10**6), np.uint32(4096), 10**400):
            set_memory_budget(value)
            assert memory_budget() == int(value) and type(memory_budget()) is int
        set_memory_budget(None)
        assert 0 < memory_budget()  # back to the default, read from the machine
    finally:
        set_memory_budget(None)


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    rows = {surface: [f"n_jobs={label}" for label in BAD_JOBS] for surface in SURFACES}
    rows["ebantenna._budget.set_memory_budget"] = [f"nbytes={label}" for label in BAD_BUDGETS]
    rows["ebantenna._budget.memory_budget"] = [
        "test_a_memory_budget_of_any_integer_type_is_kept_as_an_int"]
    return rows
