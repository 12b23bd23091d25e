"""Every example in the signal package's docstrings runs and prints what it shows."""

import doctest
import importlib
import inspect
import pkgutil

import pytest

import ebantenna.signal

MODULES = sorted(
    f"ebantenna.signal.{m.name}" for m in pkgutil.iter_modules(ebantenna.signal.__path__)
) + ["ebantenna.signal"]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.failed == 0


def test_public_functions_have_examples():
    for name in ebantenna.signal.__all__:
        obj = getattr(ebantenna.signal, name)
        if inspect.isfunction(obj) and obj.__module__.startswith("ebantenna.signal"):
            assert obj.__doc__ and "Examples" in obj.__doc__, name
