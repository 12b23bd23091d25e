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
    # Not a formality: a subpackage whose docstrings lost their examples fails here. The
    # examples are counted as doctest finds them (what testmod would run); running them is
    # test_docstring_examples' part, so they are not run a second time here.
    finder = doctest.DocTestFinder()
    for sub in ("fem", "simulate", "signal", "ml", "device", "paper", "study"):
        found = sum(
            len(test.examples)
            for n in MODULES
            if n.startswith(f"ebantenna.{sub}")
            for test in finder.find(importlib.import_module(n))
        )
        assert found >= 3, sub
