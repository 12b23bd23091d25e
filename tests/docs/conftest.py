"""Shared set-up of the documentation tests: figures never open a window, and the exercises
share one data set cache."""

import os
import sys
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

DOCS = Path(__file__).resolve().parents[2] / "docs"
for sub in ("_ext", "_tools"):
    if str(DOCS / sub) not in sys.path:
        sys.path.insert(0, str(DOCS / sub))


@pytest.fixture(scope="session", autouse=True)
def _one_cache_for_the_exercises(tmp_path_factory):
    """The exercises' data sets go to the package's cache (``EBANTENNA_CACHE``), here one folder
    for the session: a data set simulated by the first notebook or solution that asks for it is
    read by the others (each worker simulates it at most once), and nothing is written to the
    home of whoever runs the suite."""
    before = os.environ.get("EBANTENNA_CACHE")
    os.environ["EBANTENNA_CACHE"] = str(tmp_path_factory.mktemp("exercise-cache"))
    yield
    if before is None:
        del os.environ["EBANTENNA_CACHE"]
    else:
        os.environ["EBANTENNA_CACHE"] = before
