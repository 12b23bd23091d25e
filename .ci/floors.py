"""Print every runtime and test requirement of pyproject.toml pinned to its declared floor.

CI installs these pins into a second fresh virtual environment and runs the whole suite there, so a
floor in pyproject.toml is a tested claim, not a guess. A requirement without a ``>=`` floor, or
whose environment marker does not apply to this interpreter, is an error or is left out.
"""

import sys
from pathlib import Path

import tomllib
from packaging.requirements import Requirement

root = Path(__file__).resolve().parent.parent
project = tomllib.loads((root / "pyproject.toml").read_text())["project"]
requirements = project["dependencies"] + project["optional-dependencies"]["test"]
for line in requirements:
    req = Requirement(line)
    if req.marker is not None and not req.marker.evaluate():
        continue
    floors = [spec.version for spec in req.specifier if spec.operator == ">="]
    if len(floors) != 1:
        sys.exit(f"{line!r}: every requirement needs exactly one '>=' floor")
    print(f"{req.name}=={floors[0]}")
