"""Test-wide settings: figures render off-screen."""

import os

os.environ.setdefault("MPLBACKEND", "Agg")


def pytest_terminal_summary(terminalreporter):
    """After every run, the modules past the length hint of ``test_layers`` (not a failure)."""
    from test_layers import MODULE_LINES_HINT, long_modules

    rows = long_modules()
    if rows:
        terminalreporter.section(f"modules past {MODULE_LINES_HINT} lines (a hint, not a rule)")
        for module, n in rows:
            terminalreporter.write_line(f"{module}: {n} lines")
