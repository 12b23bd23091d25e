"""Shared set-up of the documentation tests: figures never open a window."""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

DOCS = Path(__file__).resolve().parents[2] / "docs"
for sub in ("_ext", "_tools"):
    if str(DOCS / sub) not in sys.path:
        sys.path.insert(0, str(DOCS / sub))
