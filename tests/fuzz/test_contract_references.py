"""The input contract of the references' public names: a bad input is refused naming its
parameter; the spectral peak stays in its band whatever the record."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ebantenna.ml.mlp_base import training_optimizer
from ebantenna.signal import dominant_frequency, peak_frequencies

FS = 1000.0
T = np.arange(256) / FS
TONE = np.sin(2 * np.pi * 125.0 * T)


@pytest.mark.parametrize("value", ["yes", None, 1, 0.0, np.array([True])])
@pytest.mark.parametrize("function", [dominant_frequency,
                                      lambda x, fs, **kw: peak_frequencies(x, fs, 1, **kw)])
def test_transient_takes_a_bool_only(function, value):
    with pytest.raises(TypeError, match="transient"):
        function(TONE, FS, transient=value)


@pytest.mark.parametrize("kwargs, match", [
    (dict(name="sgd"), "name"),
    (dict(name=None), "name"),
    (dict(name="adam", engine="numba"), "engine"),
    (dict(name="momentum", engine=None), "engine"),
])
def test_training_optimizer_names_a_bad_choice(kwargs, match):
    with pytest.raises(ValueError, match=match):
        training_optimizer(params=[np.zeros(2)], **kwargs)


@settings(max_examples=60, deadline=None)
@given(f0=st.floats(0.0, FS / 2), fmin=st.floats(0.0, 400.0), width=st.floats(5.0, 100.0),
       transient=st.booleans(), method=st.sampled_from(["jacobsen", "parabolic", "bin"]))
def test_the_dominant_frequency_lies_in_its_band(f0, fmin, width, transient, method):
    x = np.exp(-T / 0.05) * np.sin(2 * np.pi * f0 * T) + 1e-3 * np.cos(2 * np.pi * 0.37 * T)
    fmax = min(fmin + width, FS / 2)
    f = dominant_frequency(x, FS, fmin=fmin, fmax=fmax, method=method, transient=transient)
    assert fmin <= f <= fmax
