"""One quick run of the study per test session, shared by every test that reads it."""

import pytest

from ebantenna.study import reproduce


@pytest.fixture(scope="session")
def quick_study(tmp_path_factory):
    """The quick study's result and its cache directory."""
    out = tmp_path_factory.mktemp("study")
    cache = tmp_path_factory.mktemp("cache")
    return reproduce(out, quick=True, cache_dir=cache, n_jobs=1, show_progress=False), cache
