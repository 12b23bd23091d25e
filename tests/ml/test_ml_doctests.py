"""The Examples sections of ebantenna.ml run as doctests and give what they print."""

import doctest
import importlib

import pytest

MODULES = ["kernels", "smo", "svc", "optimizers", "mlp", "metrics", "persistence", "experiments"]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    module = importlib.import_module(f"ebantenna.ml.{name}")
    result = doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0, f"ebantenna.ml.{name} has no examples"
    assert result.failed == 0
