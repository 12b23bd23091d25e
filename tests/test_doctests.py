"""Every Examples section in the package runs as a doctest and prints what it promises."""

import doctest
import importlib
import pkgutil

import pytest

import ebantenna

MODULES = sorted(
    m.name for m in pkgutil.walk_packages(ebantenna.__path__, prefix="ebantenna.")
    if m.name != "ebantenna.__main__"
)
FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=FLAGS)
    assert result.failed == 0


def test_the_public_subpackages_have_examples():
    # Not a formality: a subpackage whose docstrings lost their examples fails here.
    for sub in ("fem", "simulate", "signal", "ml", "device", "paper", "study"):
        attempted = sum(
            doctest.testmod(importlib.import_module(n), optionflags=FLAGS, report=False).attempted
            for n in MODULES
            if n.startswith(f"ebantenna.{sub}")
        )
        assert attempted >= 3, sub
