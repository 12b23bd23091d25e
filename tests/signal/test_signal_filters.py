import numpy as np
import pytest
from scipy import signal as sps

from ebantenna.signal import (
    PAPER_FILTERS,
    FilterSpec,
    apply_filter,
    check_specification,
    design_bandpass,
    filter_order,
    filter_time_constant,
    paper_filter,
)
from ebantenna.signal.filters import freqz_sos

FS = 1000.0


def _steady_gain_db(sos, f, fs=FS, n=6000):
    """Independent witness: the amplitude of a long tone after the filter, in the time domain."""
    t = np.arange(n) / fs
    y = sps.sosfilt(sos, np.sin(2 * np.pi * f * t))
    tail = y[n // 2 :]
    ref = np.sin(2 * np.pi * f * t[n // 2 :])
    # Least-squares amplitude of the steady-state sinusoid (sine and cosine parts).
    basis = np.column_stack([ref, np.cos(2 * np.pi * f * t[n // 2 :])])
    coef, *_ = np.linalg.lstsq(basis, tail, rcond=None)
    return 20 * np.log10(np.hypot(*coef))


@pytest.mark.parametrize("kind, order", [("chebyshev", 13), ("elliptic", 8)])
def test_order_selection_and_specification(kind, order):
    spec = PAPER_FILTERS[kind]
    assert filter_order(spec) == order
    sos = paper_filter(kind)
    assert sos.shape == (order, 6)
    report = check_specification(sos, spec)
    assert report.meets
    assert report.passband_loss == pytest.approx(spec.ripple, abs=1e-3)  # equiripple: uses it all
    assert report.stopband_attenuation >= spec.attenuation
    # One order less fails the table: the selected order is the smallest that works.
    assert not check_specification(design_bandpass(spec, order - 1), spec).meets


@pytest.mark.parametrize("kind", ["chebyshev", "elliptic"])
def test_time_domain_tones_confirm_the_band_edges(kind):
    spec = PAPER_FILTERS[kind]
    sos = paper_filter(kind)
    centre = 0.5 * sum(spec.passband)
    for f in (*spec.passband, centre):
        assert _steady_gain_db(sos, f) >= -spec.ripple - 0.05  # 0.05 dB: finite-record estimate
    for f in spec.stopband:
        assert _steady_gain_db(sos, f) <= -spec.attenuation + 0.05


@pytest.mark.parametrize("kind", ["chebyshev", "elliptic"])
def test_stated_second_order_does_not_meet_the_table(kind):
    spec = PAPER_FILTERS[kind]
    sos = paper_filter(kind, "stated")
    assert sos.shape == (2, 6)
    report = check_specification(sos, spec)
    assert not report.meets
    # Only a few dB at the stop-band edges, instead of 30 or 45 dB.
    assert report.stopband_attenuation < 5.0
    assert filter_time_constant(sos, FS) < 0.02


def test_transfer_function_form_fails_where_sections_do_not():
    spec = PAPER_FILTERS["chebyshev"]
    b, a = design_bandpass(spec, output="ba")
    # The rounded degree-26 denominator has roots outside the unit circle: an unstable filter.
    assert np.max(np.abs(np.roots(a))) > 1.0
    f = np.array([60.0, 100.0, 160.0])
    _, h_ba = sps.freqz(b, a, worN=f, fs=FS)
    _, h_sos = freqz_sos(paper_filter("chebyshev"), worN=f, fs=FS)
    loss_ba = -20 * np.log10(np.abs(h_ba))
    loss_sos = -20 * np.log10(np.abs(h_sos))
    assert np.all(loss_sos <= 1.0 + 1e-6)
    assert loss_ba.max() > 10.0  # the (b, a) response misses the pass band by tens of dB
    # ...and running it diverges, while the sections stay bounded.
    x = np.random.default_rng(0).standard_normal(3000)
    assert np.max(np.abs(sps.lfilter(b, a, x))) > 1e6
    assert np.max(np.abs(sps.sosfilt(paper_filter("chebyshev"), x))) < 10.0


def test_zero_phase_squares_the_magnitude_and_keeps_the_phase():
    sos = paper_filter("chebyshev")
    t = np.arange(4000) / FS
    x = np.sin(2 * np.pi * 110 * t)
    y = apply_filter(sos, x)
    mid = slice(1500, 2500)
    _, h = freqz_sos(sos, worN=[110.0], fs=FS)
    np.testing.assert_allclose(y[mid], np.abs(h[0]) ** 2 * x[mid], atol=1e-3)


def test_filter_time_constant_against_impulse_response():
    sos = paper_filter("chebyshev")
    tau = filter_time_constant(sos, FS)
    assert tau == pytest.approx(0.42, abs=0.01)
    impulse = np.zeros(6000)
    impulse[0] = 1.0
    h = sps.sosfilt(sos, impulse)
    # Witness: envelope of the late impulse response decays with the slowest pole's rate.
    from ebantenna.signal import envelope

    env = envelope(h)
    t = np.arange(h.size) / FS
    window = (t > 1.5) & (t < 4.0)
    slope = np.polyfit(t[window], np.log(env[window]), 1)[0]
    assert -1 / slope == pytest.approx(tau, rel=0.03)


def test_other_sampling_rate_and_bands_beyond_nyquist():
    sos = paper_filter("elliptic", fs=2000.0)
    assert check_specification(sos, PAPER_FILTERS["elliptic"].at(2000.0)).meets
    with pytest.raises(ValueError, match="fs/2"):
        paper_filter("elliptic", fs=600.0)
    with pytest.raises(ValueError, match="passband"):
        FilterSpec("chebyshev", 1000.0, (60.0, 520.0), (55.0, 530.0), 1.0, 30.0)
    with pytest.raises(ValueError, match="enclose"):
        FilterSpec("chebyshev", 1000.0, (60.0, 160.0), (65.0, 165.0), 1.0, 30.0)


@pytest.mark.parametrize(
    "call, exc, match",
    [
        (lambda: paper_filter("butterworth"), ValueError, "kind"),
        (lambda: paper_filter("chebyshev", 0), ValueError, "order"),
        (lambda: paper_filter("chebyshev", "paper"), ValueError, "order"),
        (lambda: paper_filter("chebyshev", 2.5), TypeError, "order"),
        (lambda: apply_filter(paper_filter("chebyshev"), np.ones(20)), ValueError, "x"),
        (lambda: apply_filter(np.ones((2, 5)), np.ones(200)), ValueError, "sos"),
        (lambda: apply_filter(paper_filter("chebyshev"), np.full(200, np.nan)), ValueError, "x"),
        (lambda: filter_time_constant(paper_filter("chebyshev"), 0.0), ValueError, "fs"),
        (lambda: filter_order("chebyshev"), TypeError, "spec"),
    ],
)
def test_bad_input(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


def test_rows_are_filtered_one_by_one():
    # A 2-D input is a stack of signals: each row equals the 1-D result, bit for bit.
    x = np.random.default_rng(7).standard_normal((4, 600))
    sos = paper_filter("elliptic")
    rows = apply_filter(sos, x)
    for i in range(4):
        np.testing.assert_array_equal(rows[i], apply_filter(sos, x[i]))


def test_designs_are_cached_but_never_shared():
    a = paper_filter("chebyshev")
    a[0, 0] = 123.0
    assert paper_filter("chebyshev")[0, 0] != 123.0


def test_the_default_order_is_the_tables_at_the_given_fs():
    # paper_filter's docstring: 13 and 8 at 1 kHz, 13 and 9 at 2 kHz, 14 and 9 at 10 kHz; each
    # the smallest order that meets the table there (one less does not).
    stated = {1000.0: (13, 8), 2000.0: (13, 9), 10000.0: (14, 9)}
    for fs, orders in stated.items():
        for kind, order in zip(("chebyshev", "elliptic"), orders, strict=True):
            spec = PAPER_FILTERS[kind].at(fs)
            assert len(paper_filter(kind, fs=fs)) == order
            assert check_specification(paper_filter(kind, order, fs=fs), spec).meets
            assert not check_specification(paper_filter(kind, order - 1, fs=fs), spec).meets


def test_an_fs_too_low_for_the_table_is_named_fs():
    # The caller gave fs alone: the error names fs and says how high it must be (twice the
    # highest stop-band edge), through paper_filter and through band_passed_decay.
    from ebantenna.signal import band_passed_decay

    x = np.exp(-np.arange(600) / 60.0) * np.sin(2 * np.pi * 0.2 * np.arange(600))
    for kind, lowest in (("chebyshev", 330.0), ("elliptic", 660.0)):
        for fs in (lowest / 2, lowest):
            message = rf"^fs must exceed {lowest:g} Hz.*fs/2 = {fs / 2:g} Hz\); got {fs:g} Hz"
            with pytest.raises(ValueError, match=message):
                paper_filter(kind, fs=fs)
            with pytest.raises(ValueError, match=message):
                band_passed_decay(x, fs, kind=kind)
        assert len(paper_filter(kind, fs=lowest + 10.0)) >= 1  # just above: designed
