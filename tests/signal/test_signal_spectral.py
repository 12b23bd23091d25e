import numpy as np
import pytest

from ebantenna.signal import dominant_frequency, spectral
from ebantenna.signal._checks import check_signal
from ebantenna.signal.spectral import windowed_spectrum

FS = 1000.0
T = np.arange(1000) / FS


def _noisy_decays(n=60, seed=11, tau=0.3, noise=0.02):
    """One-second, 1 kHz damped tones at random frequencies and phases, with white noise."""
    rng = np.random.default_rng(seed)
    for f0 in rng.uniform(20.0, 450.0, n):
        x = np.exp(-T / tau) * np.sin(2 * np.pi * f0 * T + rng.uniform(0, 2 * np.pi))
        yield f0, x + noise * rng.standard_normal(T.size)


@pytest.mark.parametrize("method", ["jacobsen", "parabolic"])
def test_interpolated_estimators_within_005_hz_on_noisy_decays(method):
    errors = [abs(dominant_frequency(x, FS, method=method) - f0) for f0, x in _noisy_decays()]
    # Issue requirement: 0.05 Hz (1/20 of a bin). The worst of 60 draws here is about 0.02 Hz.
    assert max(errors) < 0.05


def test_plain_bin_is_only_within_half_a_bin():
    errors = np.array(
        [abs(dominant_frequency(x, FS, method="bin") - f0) for f0, x in _noisy_decays()]
    )
    assert errors.max() < 0.5 + 0.02  # half the 1 Hz bin, plus the noise's share
    assert errors.max() > 0.3  # ...and it does use that room: it is no sub-bin estimator
    assert np.median(errors) > 0.1


def test_jacobsen_is_exact_for_a_clean_tone_with_both_windows():
    for f0 in (100.0, 100.25, 100.5, 237.77):
        x = np.sin(2 * np.pi * f0 * T + 0.3)
        # Hann: exact up to the negative-frequency image (about 1e-9 bin here).
        assert dominant_frequency(x, FS, window="hann") == pytest.approx(f0, abs=1e-6)
        # Rectangular: the image leaks more, still within 1e-4 Hz.
        assert dominant_frequency(x, FS, window="rectangular") == pytest.approx(f0, abs=1e-4)


def test_zero_padding_shrinks_the_plain_bin_error():
    f0 = 100.37
    x = np.sin(2 * np.pi * f0 * T)
    errors = [abs(dominant_frequency(x, FS, method="bin", zero_pad=p) - f0) for p in (1, 4, 16)]
    assert errors[0] > errors[1] > errors[2]
    assert errors[2] <= 0.5 / 16 + 1e-12


def test_jacobsen_exact_on_padded_grid():
    x = np.exp(-T / 0.2) * np.sin(2 * np.pi * 77.7 * T)
    assert dominant_frequency(x, FS, zero_pad=4) == pytest.approx(77.7, abs=1e-4)


def test_band_limits_and_mean_removal():
    x = 5.0 + np.sin(2 * np.pi * 30 * T) + 0.5 * np.sin(2 * np.pi * 200 * T)
    assert dominant_frequency(x, FS) == pytest.approx(30.0, abs=1e-6)
    assert dominant_frequency(x, FS, fmin=100.0) == pytest.approx(200.0, abs=1e-6)
    # Without mean removal and with the band down to 0 Hz, DC wins.
    assert dominant_frequency(x, FS, fmin=0.0, remove_mean=False, method="bin") == 0.0


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(x=[], fs=FS), "x"),
        (dict(x=np.ones(100), fs=FS), "constant"),
        (dict(x=[1.0, np.nan, 2.0, 3.0], fs=FS), "finite"),
        (dict(x=[1.0, 2.0, 3.0], fs=FS), "at least 4"),
        (dict(x=np.ones((10, 10)), fs=FS), "dimension"),
        (dict(x=np.sin(T * 50), fs=0.0), "fs"),
        (dict(x=np.sin(T * 50), fs=-5.0), "fs"),
        (dict(x=np.sin(T * 50), fs=FS, fmax=600.0), "fs/2"),
        (dict(x=np.sin(T * 50), fs=FS, fmin=300.0, fmax=200.0), "fmin"),
        (dict(x=np.sin(T * 50), fs=FS, method="peak"), "method"),
        (dict(x=np.sin(T * 50), fs=FS, method="jacobsen", window="blackman"), "jacobsen"),
        (dict(x=np.sin(T * 50), fs=FS, zero_pad=0), "zero_pad"),
    ],
)
def test_bad_input(kwargs, match):
    x = kwargs.pop("x")
    fs = kwargs.pop("fs")
    with pytest.raises(ValueError, match=match):
        dominant_frequency(x, fs, **kwargs)


def test_peak_frequencies_of_three_damped_modes():
    from ebantenna.signal import peak_frequencies

    rng = np.random.default_rng(4)
    truth = np.array([31.37, 212.9, 411.15])
    x = sum(a * np.exp(-T / tau) * np.sin(2 * np.pi * f * T + rng.uniform(0, 6))
            for a, tau, f in zip((1.0, 0.4, 0.2), (0.3, 0.2, 0.15), truth, strict=True))
    x = x + 0.01 * rng.standard_normal(T.size)
    # 0.1 Hz: the weakest mode carries 1/40 of the energy of the first (measured error 0.06 Hz).
    np.testing.assert_allclose(peak_frequencies(x, FS, 3), truth, atol=0.1)
    assert peak_frequencies(x, FS, 3)[0] == pytest.approx(truth[0], abs=0.05)
    # The strongest peak alone is the dominant frequency.
    assert peak_frequencies(x, FS, 1)[0] == pytest.approx(dominant_frequency(x, FS), abs=1e-12)
    # Two peaks closer than the separation count as one.
    with pytest.raises(ValueError, match="n_peaks=4"):
        peak_frequencies(x, FS, 4, min_separation=150.0)
    with pytest.raises(ValueError, match="n_peaks"):
        peak_frequencies(x, FS, 0)
    with pytest.raises(ValueError, match="min_separation"):
        peak_frequencies(x, FS, 2, min_separation=-1.0)


def _analysed_samples(x, transient):
    """``m``, the samples ``dominant_frequency`` analyses (its first step says)."""
    return windowed_spectrum(x, FS, "hann", 1, None, None, True, transient)[1].n


def _stated_margin(tau, m):
    """The docstring's smallest distance of a tone from 0 and from fs/2: its half-bandwidth plus
    six bins of the record and two bins of the ``m`` samples analysed."""
    return 1.0 / (2 * np.pi * tau) + max(6 * FS / T.size, 2 * FS / m)


def _stated_accuracy(f0, tau, m):
    """The docstring's bound on the error for a tone analysed on ``m`` samples, or None where its
    statement does not cover the tone: tau from 5 ms for a transient analysed alone (m < n),
    from a tenth of the record for the whole record."""
    shortest = 0.005 if m < T.size else 0.1 * T.size / FS
    margin = _stated_margin(tau, m)
    if tau < shortest or not margin <= f0 <= FS / 2 - margin:
        return None
    return 0.15 / (2 * np.pi * tau) + 0.01 * FS / T.size


@pytest.mark.parametrize("transient", [False, True])
def test_short_and_long_decays_with_offsets_within_the_stated_accuracy(transient):
    # The grid of the docstring's accuracy statement: tau from 5 ms to 10 s, offsets up to 10 g,
    # each tone checked where the statement covers it (see _stated_accuracy).
    for f0 in (25.0, 50.0, 100.0, 200.0, 400.0, 480.0):
        for tau in (0.005, 0.01, 0.02, 0.03, 0.05, 0.1, 0.3, 1.0, 3.0, 10.0):
            for offset in (0.0, 98.1, -98.1):
                for phase in (0.0, 0.7, 2.0):
                    x = np.exp(-T / tau) * np.sin(2 * np.pi * f0 * T + phase) + offset
                    bound = _stated_accuracy(f0, tau, _analysed_samples(x, transient))
                    if bound is not None:
                        error = abs(dominant_frequency(x, FS, transient=transient) - f0)
                        assert error <= bound, (f0, tau, offset, phase)


def test_the_stated_accuracy_holds_at_the_edges_of_the_stated_band():
    # The tones closest to 0 and to fs/2 that the statement covers, where a peak is nearest its
    # mirror image: a 6 ms decay near 466 Hz, analysed on 45 samples, is the reviewed case. At
    # 80 ms the decay is too long to be found and too short for the whole record: not covered.
    checked = set()
    for tau in (0.005, 0.006, 0.008, 0.01, 0.02, 0.03, 0.05, 0.08, 0.1, 0.3):
        decay = np.exp(-T / tau)
        margin = _stated_margin(tau, _analysed_samples(decay * np.sin(2 * np.pi * 200 * T), True))
        for f0 in (margin, FS / 2 - margin):
            for offset in (0.0, 98.1, -98.1):
                for phase in np.linspace(0.0, 2 * np.pi, 12, endpoint=False):
                    x = decay * np.sin(2 * np.pi * f0 * T + phase) + offset
                    bound = _stated_accuracy(f0, tau, _analysed_samples(x, True))
                    if bound is not None:
                        error = abs(dominant_frequency(x, FS, transient=True) - f0)
                        assert error <= bound, (f0, tau, offset, phase)
                        checked.add((tau, f0 > FS / 4))
    assert {(0.006, True), (0.006, False), (0.3, True)} <= checked


def test_the_accuracy_notes_examples_are_what_the_code_gives():
    def estimate(f0, tau, phase=0.0):
        x = np.exp(-T / tau) * np.sin(2 * np.pi * f0 * T + phase)
        return dominant_frequency(x, FS, transient=True), _analysed_samples(x, True)

    # the notes print one decimal: within half of its last digit
    assert estimate(28.0, 0.008) == (pytest.approx(33.3, abs=0.05), 60)  # the band's edge
    assert estimate(466.0, 0.006, 4.47) == (pytest.approx(470.3, abs=0.05), 45)  # the mirror
    # too long to be found as a transient, too short for the whole record: the band's edge
    assert estimate(9.0, 0.08) == (1.0, T.size)
    # the decay is found as a transient up to about 70 ms
    found = [_analysed_samples(np.exp(-T / tau) * np.sin(2 * np.pi * 200 * T), True) < T.size
             for tau in (0.06, 0.065, 0.075, 0.08)]
    assert found == [True, True, False, False]


def test_a_short_decay_is_analysed_on_its_own_only_when_asked():
    # A 30 ms decay under a Hann window over the whole second is weighted by about zero.
    x = np.exp(-T / 0.03) * np.sin(2 * np.pi * 25.0 * T)
    accuracy = 0.15 / (2 * np.pi * 0.03)
    assert dominant_frequency(x, FS, transient=True) == pytest.approx(25.0, abs=accuracy)
    # the default analyses every sample: the same number as the whole record's spectrum
    whole = dominant_frequency(x, FS, fmin=FS / T.size)
    assert dominant_frequency(x, FS) == whole
    assert abs(whole - 25.0) > accuracy  # which is another number: the choice matters here
    # a decay that starts later in the record (a tap at 0.6 s) is found as well
    late = np.where(T >= 0.6, np.exp(-(T - 0.6) / 0.02) * np.sin(2 * np.pi * 140 * (T - 0.6)), 0)
    accuracy = 0.15 / (2 * np.pi * 0.02)
    assert dominant_frequency(late + 9.81, FS, transient=True) == pytest.approx(140.0,
                                                                                abs=accuracy)
    with pytest.raises(TypeError, match="transient"):
        dominant_frequency(x, FS, transient="yes")


@pytest.mark.parametrize("method", ["jacobsen", "parabolic", "bin"])
def test_the_frequency_returned_lies_in_the_search_band(method):
    # A strong tone just below fmin: the strongest bin of the band is its lowest, and an
    # interpolation there points below the band; the answer stays in [fmin, fmax].
    from ebantenna.signal import peak_frequencies

    x = np.sin(2 * np.pi * 0.4 * T) + 0.01 * np.sin(2 * np.pi * 100.0 * T)
    for zero_pad in (1, 4):
        f = dominant_frequency(x, FS, fmin=1.0, method=method, zero_pad=zero_pad)
        assert 1.0 <= f <= FS / 2
    high = np.sin(2 * np.pi * 300.4 * T)  # just above fmax
    assert 50.0 <= dominant_frequency(high, FS, fmin=50.0, fmax=300.0, method=method) <= 300.0
    peaks = peak_frequencies(x + np.sin(2 * np.pi * 250.0 * T), FS, 2, fmin=1.0, method=method)
    assert np.all((1.0 <= peaks) & (peaks <= FS / 2))


@pytest.mark.parametrize("scale", [1e-300, 1e-200, 1e200, 1e308])
def test_extreme_amplitudes(scale):
    x = np.sin(2 * np.pi * 123.37 * T) * np.exp(-T / 0.2)
    ref = dominant_frequency(x, FS)
    # the power-of-two scaling inside is exact; only the rounding of scale * x is left
    assert dominant_frequency(scale * x, FS) == pytest.approx(ref, abs=1e-9)


# --- each step of the reference checks its own arguments ------------------------------------

#: a Hann-windowed tone of 10.25 cycles over 64 samples: 33 complex bins, its peak at bin 10
TONE = np.fft.rfft(np.hanning(65)[:-1] * np.sin(2 * np.pi * 10.25 * np.arange(64) / 64))
WITH_NAN = np.array([0.0, 3.0, np.nan, 5.0, 2.0])


def _interpolated(spectrum=TONE, k=10, fs=64.0, n=64, method="jacobsen", window="hann",
                  zero_pad=1):
    return spectral.interpolated_frequency(spectrum, k, fs, n, method, window, zero_pad)


#: ``(call, exception, the parameter the error names first)``
STEP_BAD_INPUTS = {
    "interpolated_frequency-spectrum-None": (lambda: _interpolated(None), TypeError, "spectrum"),
    "interpolated_frequency-spectrum-nan": (lambda: _interpolated(TONE * np.nan), ValueError,
                                            "spectrum"),
    "interpolated_frequency-spectrum-2-D": (lambda: _interpolated(np.ones((3, 3)) + 0j),
                                            ValueError, "spectrum"),
    "interpolated_frequency-spectrum-real-for-jacobsen": (lambda: _interpolated(np.abs(TONE)),
                                                          TypeError, "spectrum"),
    "interpolated_frequency-k-beyond": (lambda: _interpolated(k=500), ValueError, "k"),
    "interpolated_frequency-k-negative": (lambda: _interpolated(k=-3, method="bin"), ValueError,
                                          "k"),
    "interpolated_frequency-k-float": (lambda: _interpolated(k=10.5), TypeError, "k"),
    "interpolated_frequency-fs-negative": (lambda: _interpolated(fs=-64.0), ValueError, "fs"),
    "interpolated_frequency-fs-nan": (lambda: _interpolated(fs=np.nan), ValueError, "fs"),
    "interpolated_frequency-n-0": (lambda: _interpolated(n=0), ValueError, "n"),
    "interpolated_frequency-n-float": (lambda: _interpolated(n=64.0), TypeError, "n"),
    "interpolated_frequency-zero_pad-0": (lambda: _interpolated(zero_pad=0), ValueError,
                                          "zero_pad"),
    "interpolated_frequency-method-unknown": (lambda: _interpolated(method="x"), ValueError,
                                              "method"),
    "interpolated_frequency-window-unknown": (lambda: _interpolated(method="bin", window="x"),
                                              ValueError, "window"),
    "interpolated_frequency-jacobsen-blackman": (lambda: _interpolated(window="blackman"),
                                                 ValueError, "method 'jacobsen' needs window"),
    "parabolic_offset-spectrum-nan": (lambda: spectral.parabolic_offset(WITH_NAN, 1), ValueError,
                                      "spectrum"),
    "parabolic_offset-spectrum-imag-inf": (lambda: spectral.parabolic_offset(TONE + 1j * np.inf,
                                                                              10),
                                           ValueError, "spectrum"),
    "parabolic_offset-spectrum-str": (lambda: spectral.parabolic_offset("abc", 1), TypeError,
                                      "spectrum"),
    "jacobsen_offset-spectrum-nan": (lambda: spectral.jacobsen_offset(TONE * np.nan, 10, 1,
                                                                      "hann"),
                                     ValueError, "spectrum"),
    "jacobsen_offset-spectrum-real": (lambda: spectral.jacobsen_offset(np.abs(TONE), 10, 1,
                                                                       "hann"),
                                      TypeError, "spectrum"),
    "jacobsen_offset-window-blackman": (lambda: spectral.jacobsen_offset(TONE, 10, 1,
                                                                         "blackman"),
                                        ValueError, "window"),
    "strongest_bin-magnitude-nan": (lambda: spectral.strongest_bin(WITH_NAN, 0, 4), ValueError,
                                    "magnitude"),
    "strongest_bin-magnitude-negative": (lambda: spectral.strongest_bin(-np.abs(TONE), 0, 32),
                                         ValueError, "magnitude"),
    "strongest_bin-magnitude-complex": (lambda: spectral.strongest_bin(TONE, 0, 32), TypeError,
                                        "magnitude"),
    "local_maxima-magnitude-nan": (lambda: spectral.local_maxima(WITH_NAN, 0, 4), ValueError,
                                   "magnitude"),
    "local_maxima-magnitude-negative": (lambda: spectral.local_maxima(-np.abs(TONE), 0, 32),
                                        ValueError, "magnitude"),
    "local_maxima-magnitude-None": (lambda: spectral.local_maxima(None, 0, 4), TypeError,
                                    "magnitude"),
}


@pytest.mark.parametrize("case", STEP_BAD_INPUTS)
def test_each_step_answers_bad_input_with_an_error_naming_the_parameter(case):
    call, exception, name = STEP_BAD_INPUTS[case]
    with pytest.raises(exception, match=f"^{name}"):
        call()


def test_the_public_functions_check_once_and_run_the_unchecked_cores(monkeypatch):
    # The module's notes: validated once, then the steps' cores, so nothing is checked twice.
    x = np.exp(-T / 0.2) * np.sin(2 * np.pi * 123.37 * T)
    expected = (dominant_frequency(x, FS), spectral.peak_frequencies(x, FS, 1))
    calls = []

    def counted(*args, **kwargs):
        calls.append(args[0])
        return check_signal(*args, **kwargs)

    def refused(*args, **kwargs):
        raise AssertionError("a public step was called")

    monkeypatch.setattr(spectral, "check_signal", counted)
    for step in ("windowed_spectrum", "window_weights", "strongest_bin", "interpolated_frequency",
                 "parabolic_offset", "jacobsen_offset", "local_maxima", "strongest_separated"):
        monkeypatch.setattr(spectral, step, refused)
    assert dominant_frequency(x, FS) == expected[0]
    assert spectral.peak_frequencies(x, FS, 1) == expected[1]
    assert calls == ["x", "x"]  # once for each public function
