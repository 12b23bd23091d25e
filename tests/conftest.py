"""Test-wide settings: figures render off-screen; one BLAS thread per pytest-xdist worker; the
tests of a costly session fixture on one worker."""

import os
import re
import shlex
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

os.environ.setdefault("MPLBACKEND", "Agg")

# Hypothesis's two wall-clock checks, off for every test (a test's own ``settings`` inherit
# this): the 200 ms deadline per example and the "data generation too slow" health check fail
# an example that a loaded machine merely delays, and say nothing about the code under test.
# Loaded before the test modules are imported, so that their ``@settings`` take it as parent.
settings.register_profile("suite", deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.load_profile("suite")

if os.environ.get("PYTEST_XDIST_WORKER"):
    # With ``-n N`` the workers already take the cores: a BLAS thread pool per worker on top only
    # spins against the other workers (the MLP's small products ran 2-3x the CPU time on two).
    # Results do not depend on it: the suite runs under any kernel and thread count. Set, not
    # defaulted: a library loaded later (SciPy's own OpenBLAS) reads the variable when it loads,
    # and a count exported for other work must not multiply the workers' threads.
    for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ[_var] = "1"
    import numpy  # noqa: F401  (loads the BLAS library, so that the limit below reaches it)
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=1, user_api="blas")


#: Session fixtures that cost tens of seconds: the test files that use one run on the same
#: pytest-xdist worker, so that the fixture is built once per run, not once per worker.
SHARED_FIXTURES = ("quick_study",)


@pytest.hookimpl(tryfirst=True, optionalhook=True)
def pytest_xdist_make_scheduler(config, log):
    """``pytest -n N``: xdist's ``load`` distribution, except that the tests of the files using
    a fixture of :data:`SHARED_FIXTURES` go, all of them, to the first worker at the start (the
    longest work starts first). Another ``--dist`` given on the command line is kept.

    xdist's own ``--dist loadgroup`` would do this from ``xdist_group`` marks, but it names the
    groups by editing ``Item._nodeid``, which pytest 9 no longer reads: the groups are lost.
    """
    if config.getvalue("dist") != "load" or _dist_given(config):
        return None
    from xdist.scheduler import LoadScheduling

    shared = _files_using(Path(config.rootpath), SHARED_FIXTURES)

    class SharedFixtureScheduling(LoadScheduling):
        """``load``, with the first batch led by every test of the files in ``shared``."""

        _grouped = False

        def _send_tests(self, node, num: int) -> None:
            if not self._grouped:  # the first batch of the initial distribution
                self._grouped = True
                first = {i for i in self.pending if self.collection[i].split("::", 1)[0] in shared}
                self.pending.sort(key=lambda i: i not in first)  # stable: the group, the rest
                num = max(num, len(first))
            super()._send_tests(node, num)

    return SharedFixtureScheduling(config, log)


def _files_using(root: Path, fixtures) -> set[str]:
    """Test files (relative to ``root``, as in a node id) with a test taking one of ``fixtures``
    (read from the ``def test...(...)`` lines: xdist's controller has node ids, not items)."""
    found = set()
    pattern = re.compile(r"^\s*def test\w*\(([^)]*)\)", re.MULTILINE)
    for path in sorted((root / "tests").rglob("test_*.py")):
        params = " ".join(pattern.findall(path.read_text(encoding="utf-8")))
        for name in fixtures:
            if re.search(rf"\b{name}\b", params):
                found.add(path.relative_to(root).as_posix())
                break
    return found


def _dist_given(config) -> bool:
    """Was ``--dist`` (or ``-d``) given, on the command line or in ``PYTEST_ADDOPTS``?"""
    args = [*config.invocation_params.args, *shlex.split(os.environ.get("PYTEST_ADDOPTS", ""))]
    return any(str(a).startswith("--dist") or a == "-d" for a in args)

def pytest_terminal_summary(terminalreporter):
    """After every run, the modules past the length hint of ``test_layers`` (not a failure)."""
    from test_layers import MODULE_LINES_HINT, long_modules

    rows = long_modules()
    if rows:
        terminalreporter.section(f"modules past {MODULE_LINES_HINT} lines (a hint, not a rule)")
        for module, n in rows:
            terminalreporter.write_line(f"{module}: {n} lines")
