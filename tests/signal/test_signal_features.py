import numpy as np
import pytest

from ebantenna.recording import Recording
from ebantenna.signal import fft_features, norm_spectrum, resultant_acceleration

FS = 1000.0


def _recording(n=1000, seed=0):
    rng = np.random.default_rng(seed)
    t = np.arange(n) / FS
    return Recording(t, rng.standard_normal(n), rng.standard_normal(n) + 9.81, FS)


def test_resultant_is_the_euclidean_norm_of_the_two_axes():
    rec = _recording()
    expected = np.sqrt(rec.ax**2 + rec.az**2)  # eq. 1 written out
    np.testing.assert_allclose(resultant_acceleration(rec), expected, rtol=1e-15)
    np.testing.assert_allclose(resultant_acceleration(rec.ax, rec.az), expected, rtol=1e-15)


def test_resultant_does_not_overflow():
    big = np.array([1e200, 3e200])
    np.testing.assert_allclose(resultant_acceleration(big, big), np.sqrt(2) * big)


def test_norm_spectrum_amplitudes_and_parseval():
    t = np.arange(1000) / FS
    ax = 0.7 * np.sin(2 * np.pi * 40 * t)
    az = 0.2 * np.cos(2 * np.pi * 130 * t) + 0.5
    f, mag = norm_spectrum(ax, az, FS)
    assert f[1] - f[0] == pytest.approx(1.0)
    # Integer-bin tones: one-sided amplitudes come out exactly, DC not doubled.
    assert mag[40] == pytest.approx(0.7, abs=1e-12)
    assert mag[130] == pytest.approx(0.2, abs=1e-12)
    assert mag[0] == pytest.approx(0.5, abs=1e-12)
    # Witness: Parseval; the mean square of both axes is the sum of squared one-sided
    # amplitudes over 2 (DC and Nyquist not halved).
    ms = np.mean(ax**2) + np.mean(az**2)
    parseval = mag[0] ** 2 + 0.5 * np.sum(mag[1:-1] ** 2) + mag[-1] ** 2
    assert parseval == pytest.approx(ms, rel=1e-12)


def test_norm_spectrum_remove_mean_and_recording():
    rec = _recording()
    f, mag = norm_spectrum(rec, remove_mean=True)
    assert mag[0] == pytest.approx(0.0, abs=1e-12)
    assert f[-1] == pytest.approx(500.0)


def test_fft_features_shape_normalisation_and_independent_dft():
    rng = np.random.default_rng(3)
    ax = rng.standard_normal((3, 1000))
    az = rng.standard_normal((3, 1000))
    v = fft_features(ax, az)
    assert v.shape == (3, 256)
    np.testing.assert_allclose(v.max(axis=1), 1.0)
    # Witness: an explicit DFT matrix on the first 512 samples.
    k = np.arange(256)[:, None]
    n = np.arange(512)[None, :]
    dft = np.exp(-2j * np.pi * k * n / 512)
    raw = np.hypot(np.abs(ax[:, :512] @ dft.T), np.abs(az[:, :512] @ dft.T))
    np.testing.assert_allclose(v, raw / raw.max(axis=1, keepdims=True), rtol=1e-9)
    vd = fft_features(ax, az, normalise="dataset")
    np.testing.assert_allclose(vd, raw / raw.max(), rtol=1e-9)
    np.testing.assert_allclose(fft_features(ax, az, normalise="none"), raw, rtol=1e-9)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: resultant_acceleration([], []), "ax"),
        (lambda: resultant_acceleration([1.0, np.nan], [1.0, 2.0]), "ax"),
        (lambda: resultant_acceleration([1.0, 2.0], [1.0]), "same shape"),
        (lambda: resultant_acceleration(np.ones((2, 2, 2)), np.ones((2, 2, 2))), "dimension"),
        (lambda: norm_spectrum([1.0, 2.0], [1.0, 2.0], 0.0), "fs"),
        (lambda: fft_features(np.ones(10), np.ones(10), n_bins=300), "n_bins"),
        (lambda: fft_features(np.ones(10), np.ones(10), normalise="max"), "normalise"),
        (lambda: fft_features(np.zeros(10), np.zeros(10)), "zero"),
    ],
)
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_bad_types():
    with pytest.raises(TypeError, match="az"):
        resultant_acceleration([1.0, 2.0])
    with pytest.raises(TypeError, match="fs"):
        norm_spectrum([1.0, 2.0], [1.0, 2.0], "1000")


def test_resultant_of_rows_is_the_resultant_of_each_row():
    rng = np.random.default_rng(4)
    ax, az = rng.standard_normal((2, 3, 50))
    rows = resultant_acceleration(ax, az)
    for i in range(3):
        np.testing.assert_array_equal(rows[i], resultant_acceleration(ax[i], az[i]))


def test_norm_spectrum_refuses_an_fs_other_than_the_recordings():
    # A 50 Hz tone in a 1 kHz recording: another fs would move its peak (to 100 Hz at 2 kHz).
    t = np.arange(1000) / 1000.0
    rec = Recording(t, np.sin(2 * np.pi * 50 * t), np.zeros(1000), fs=1000.0)
    with pytest.raises(ValueError, match="^fs must be the Recording's own"):
        norm_spectrum(rec, fs=2000.0)
    with pytest.raises(TypeError, match="^fs"):
        norm_spectrum(rec, fs="1000")
    for fs in (None, 1000.0, 1000):  # omitted or the recording's own: the same spectrum
        f, mag = norm_spectrum(rec, fs=fs)
        assert f[np.argmax(mag)] == 50.0
