"""The input contract by parameter kind, with hypothesis drawing the values.

:mod:`tests.fuzz.test_contract_api` lists fixed cases; here each kind gets a strategy and a
property: a number outside the float range or below a parameter's range is refused naming it,
an array of a refused dtype is refused naming it, float32 and integer arrays give exactly what
their float64 copies give (they are computed in float64), and a tone's frequency does not
depend on the signal's scale.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from ebantenna import Probe, Recording, fem, signal

FS = 1000.0
T = np.arange(256) / FS
TONE = np.sin(2 * np.pi * 125.0 * T)

runs = settings(max_examples=25, deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.too_slow])

#: Beyond the float range, of any size and either sign, as ints and as fractions.
beyond_float = st.integers(min_value=2**1024, max_value=10**4000).flatmap(
    lambda n: st.sampled_from([n, -n, Fraction(n), Fraction(-n, 1)]))
not_positive = st.one_of(st.floats(max_value=0.0, allow_nan=False),
                         st.integers(max_value=0), beyond_float.filter(lambda v: v < 0))
not_a_number = st.one_of(st.text(max_size=3), st.none(), st.booleans(),
                         st.complex_numbers(allow_nan=False), st.lists(st.floats(), max_size=2))

#: Public entries with one positive real parameter each: ``(parameter, call)``.
POSITIVE = [
    ("fs", lambda v: signal.dominant_frequency(TONE, v)),
    ("fs", lambda v: signal.fit_decay(TONE, v)),
    ("fs", lambda v: Recording(T, TONE, TONE, v)),
    ("fs", lambda v: signal.FrequencyTracker(v)),
    ("length", lambda v: Probe(length=v)),
    ("density", lambda v: Probe(density=v)),
    ("diameter", lambda v: fem.Rod("pvc", diameter=v)),
]


@pytest.mark.parametrize(("param", "call"), POSITIVE, ids=[f"{i}-{p}" for i, (p, _) in
                                                            enumerate(POSITIVE)])
@runs
@given(value=st.one_of(beyond_float, not_positive, not_a_number,
                       st.sampled_from([math.nan, math.inf, -math.inf])))
def test_a_bad_number_is_refused_naming_its_parameter(param, call, value):
    with pytest.raises((ValueError, TypeError)) as caught:
        call(value)
    assert param in str(caught.value)


refused_dtypes = st.sampled_from(["complex128", "complex64", "bool", "datetime64[s]",
                                  "timedelta64[s]", "U4", "S4", "O"])


@runs
@given(dtype=refused_dtypes, n=st.integers(8, 64), where=st.sampled_from(["x", "ax", "contacts"]))
def test_an_array_of_a_refused_dtype_is_refused_naming_its_parameter(dtype, n, where):
    values = np.arange(1, n + 1) / (2 * n)  # in (0, 0.5]: inside the probe for contacts
    if dtype == "O":
        array = np.array([10**400] * n, dtype=object)
    elif dtype.startswith(("datetime", "timedelta")):
        array = np.arange(n).astype(dtype)
    else:
        array = values.astype(dtype)
    calls = {
        "x": lambda a: signal.dominant_frequency(a, FS),
        "ax": lambda a: Recording(np.arange(n) / FS, a, np.zeros(n), FS),
        "contacts": lambda a: fem.natural_frequencies(Probe(), a[:2], n_modes=1, n_elements=4),
    }
    with pytest.raises(TypeError) as caught:
        calls[where](array)
    assert where in str(caught.value)


@runs
@given(x=hnp.arrays(st.sampled_from([np.float32, np.int16, np.int32, np.float16]),
                    st.integers(16, 200),
                    elements=st.integers(-1000, 1000)))
def test_float32_and_integer_data_are_computed_in_float64(x):
    def outcome(data):
        try:
            return signal.dominant_frequency(data, FS)
        except ValueError as exc:  # a constant or transient record: the same refusal
            return str(exc)

    # the same float64 computation, so the same answer (or the same error), bit for bit
    assert outcome(x) == outcome(x.astype(np.float64))


@runs
@given(k=st.integers(8, 120), exponent=st.integers(-300, 300))
def test_a_tone_is_found_at_any_scale(k, exponent):
    n = 256
    x = 10.0**exponent * np.sin(2 * np.pi * k * np.arange(n) / n)
    # a tone on bin k: the interpolated peak is k fs / n to far better than a thousandth of a bin
    assert abs(signal.dominant_frequency(x, FS) - k * FS / n) < 1e-3 * FS / n


@runs
@given(rows=st.lists(st.integers(1, 6), min_size=2, max_size=4).filter(
    lambda r: len(set(r)) > 1))
def test_a_ragged_list_is_refused_naming_its_parameter(rows):
    ragged = [[0.5] * r for r in rows]
    with pytest.raises(ValueError, match="x must be a rectangular array"):
        signal.dominant_frequency(ragged, FS)
