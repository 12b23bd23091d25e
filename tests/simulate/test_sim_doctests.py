"""The simulator's docstring examples run as part of the test suite."""

import doctest
import importlib

import pytest

MODULES = [
    "ebantenna.simulate",
    "ebantenna.simulate.effects",
    "ebantenna.simulate.modes",
    "ebantenna.simulate.scene",
    "ebantenna.simulate.simulator",
    "ebantenna.simulate.dataset",
]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0
    assert result.failed == 0
