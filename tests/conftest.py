"""Test-wide settings: figures render off-screen; one BLAS thread per pytest-xdist worker."""

import os

os.environ.setdefault("MPLBACKEND", "Agg")

if os.environ.get("PYTEST_XDIST_WORKER"):
    # With ``-n N`` the workers already take the cores: a BLAS thread pool per worker on top only
    # spins against the other workers (the MLP's small products ran 2-3x the CPU time on two).
    # Results do not depend on it: the suite runs under any kernel and thread count.
    for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(_var, "1")
    import numpy  # noqa: F401  (loads the BLAS library, so that the limit below reaches it)
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=1, user_api="blas")


def pytest_terminal_summary(terminalreporter):
    """After every run, the modules past the length hint of ``test_layers`` (not a failure)."""
    from test_layers import MODULE_LINES_HINT, long_modules

    rows = long_modules()
    if rows:
        terminalreporter.section(f"modules past {MODULE_LINES_HINT} lines (a hint, not a rule)")
        for module, n in rows:
            terminalreporter.write_line(f"{module}: {n} lines")
