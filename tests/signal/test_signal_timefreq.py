import matplotlib.pyplot as plt
import numpy as np
import pytest
import pywt  # PyWavelets, the independent witness for the scalogram (test extra)
from scipy import signal as sps

from ebantenna.signal import morlet_scalogram, spectrogram

FS = 1000.0
# PyWavelets samples the wavelet on 2**precision points; before 1.9 (the last release for Python
# 3.10 is 1.8) that was 2**10, which costs up to about 1.5 % at the highest frequencies tested here.
# 1.9 raised it to 2**12. The witness is held to what its own precision allows.
PYWT_PRECISE = tuple(int(p) for p in pywt.__version__.split(".")[:2]) >= (1, 9)
T = np.arange(1000) / FS


def test_spectrogram_against_scipy():
    x = np.random.default_rng(0).standard_normal(1000)
    tf = spectrogram(x, FS, nperseg=64, noverlap=48)
    f, t, s = sps.spectrogram(x, FS, window="hann", nperseg=64, noverlap=48, detrend=False,
                              mode="magnitude", scaling="spectrum")
    np.testing.assert_allclose(tf.f, f)
    np.testing.assert_allclose(tf.t, t)
    # scipy's one-sided magnitude is not doubled; ours is (amplitude scaling), except DC/Nyquist.
    np.testing.assert_allclose(tf.values[1:-1], 2 * s[1:-1], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(tf.values[[0, -1]], s[[0, -1]], rtol=1e-12, atol=1e-15)


def test_spectrogram_ridge_follows_a_frequency_step():
    x = np.where(T < 0.5, np.sin(2 * np.pi * 62.5 * T), 0.5 * np.sin(2 * np.pi * 187.5 * T))
    tf = spectrogram(x, FS, nperseg=64, noverlap=32)
    ridge = tf.ridge()
    assert np.all(ridge[tf.t < 0.45] == 62.5)
    assert np.all(ridge[tf.t > 0.55] == 187.5)
    assert tf.values[:, tf.t < 0.45].max() == pytest.approx(1.0, rel=1e-9)


def _direct_cwt(x, freqs, bandwidth=1.5, center=1.0):
    """Witness: the defining sum W(a, b) = a^-1/2 sum_n x[n] conj(psi((n - b) / a)), termwise."""
    n = np.arange(x.size)
    out = np.empty((len(freqs), x.size), dtype=complex)
    for i, f in enumerate(freqs):
        a = center * FS / f
        u = (n[None, :] - n[:, None]) / a  # rows: b, columns: n
        psi = (np.pi * bandwidth) ** -0.5 * np.exp(-(u**2) / bandwidth) * np.exp(
            2j * np.pi * center * u)
        out[i] = (np.conj(psi) @ x) / np.sqrt(a)
    return out


def test_scalogram_equals_the_defining_sum():
    x = np.random.default_rng(1).standard_normal(400)
    freqs = np.array([25.0, 60.0, 140.0, 330.0])
    tf = morlet_scalogram(x, FS, freqs)
    ref = _direct_cwt(x, freqs)
    # Exact up to the Riemann-sum-versus-integral difference of the Fourier form (aliasing of a
    # Gaussian: below 1e-9 of the largest coefficient) and rounding.
    assert np.max(np.abs(tf.values - ref)) < 1e-9 * np.max(np.abs(ref))


@pytest.mark.parametrize("f0", [30.0, 47.3, 80.0, 123.4, 200.0, 300.0])
def test_scalogram_magnitude_against_pywavelets(f0):
    x = np.sin(2 * np.pi * f0 * T + 0.7)
    scale = FS / f0
    ref, ref_freqs = pywt.cwt(x, [scale], "cmor1.5-1.0", method="fft")
    assert ref_freqs[0] * FS == pytest.approx(f0)
    tf = morlet_scalogram(x, FS, [f0], bandwidth=1.5, center=1.0)
    mid = slice(200, 800)
    # PyWavelets averages the wavelet over one sample (integrate, then difference): a factor
    # sinc(f / fs) on a tone at f. Its centring leaves a half-sample shift, so compare magnitudes.
    expected = np.abs(tf.values[0, mid]) * np.sinc(f0 / FS)
    np.testing.assert_allclose(np.abs(ref[0, mid]), expected, rtol=5e-3 if PYWT_PRECISE else 2e-2)


def test_scalogram_of_a_broadband_decay_against_pywavelets():
    rng = np.random.default_rng(2)
    x = np.exp(-T / 0.2) * np.sin(2 * np.pi * 90 * T) + 0.05 * rng.standard_normal(T.size)
    freqs = np.array([60.0, 90.0, 150.0])
    ref, _ = pywt.cwt(x, FS / freqs, "cmor1.5-1.0", method="fft")
    mine = morlet_scalogram(x, FS, freqs).values
    mid = slice(150, 850)
    level = np.abs(ref[:, mid]).max()
    for i, f in enumerate(freqs):
        err = np.abs(np.abs(ref[i, mid]) - np.sinc(f / FS) * np.abs(mine[i, mid])).max()
        # The noise is broadband, so the sinc(f/fs) factor and the half-sample shift are only
        # approximate in rows the tone does not reach: 1 % of the map's peak (measured: 0.2 %).
        assert err < (0.01 if PYWT_PRECISE else 0.03) * level


def test_plot_returns_a_figure():
    tf = spectrogram(np.sin(2 * np.pi * 50 * T), FS)
    fig = tf.plot()
    assert fig.axes[0].get_xlabel() == "time (s)"
    plt.close(fig)
    fig, ax = plt.subplots()
    assert morlet_scalogram(np.sin(2 * np.pi * 50 * T), FS, [40.0, 50.0]).plot(ax, db=False) is fig
    plt.close(fig)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: spectrogram(np.ones(10), FS, nperseg=64), "x"),
        (lambda: spectrogram(np.ones(100), FS, nperseg=64, noverlap=64), "noverlap"),
        (lambda: spectrogram(np.ones(100), -1.0), "fs"),
        (lambda: spectrogram(np.ones(100), FS, window="kaiser"), "window"),
        (lambda: morlet_scalogram(np.ones(100), FS, [600.0]), "frequencies"),
        (lambda: morlet_scalogram(np.ones(100), FS, [0.0]), "frequencies"),
        (lambda: morlet_scalogram(np.ones(100), FS, []), "frequencies"),
        (lambda: morlet_scalogram(np.r_[1.0, np.nan], FS, [10.0]), "x"),
        (lambda: morlet_scalogram(np.ones(100), FS, [10.0], bandwidth=0.0), "bandwidth"),
    ],
)
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


@pytest.mark.parametrize("f", [400.0, 450.0])
def test_morlet_near_nyquist_beats_with_the_mirror_image(f):
    from ebantenna.signal import morlet_scalogram

    fs, b, c = 1000.0, 1.5, 1.0
    t = np.arange(1000) / fs
    a = c * fs / f
    gain = np.exp(-np.pi**2 * b * c**2 * (fs / f - 2) ** 2)  # the image's: 0.025, then 0.48
    ratio = np.concatenate([
        np.abs(morlet_scalogram(np.sin(2 * np.pi * f * t + phi), fs, [f]).values[0, 300:700])
        / (np.sqrt(a) / 2) for phi in np.linspace(0, np.pi, 9)])
    # the docstring's range 1 -+ g; the other aliases add below 1e-11 (g at 300 Hz), and the
    # edges are 300 samples (many wavelet lengths) away
    assert ratio.min() == pytest.approx(1 - gain, abs=2e-3)
    assert ratio.max() == pytest.approx(1 + gain, abs=2e-3)


def test_spectrogram_drops_the_samples_after_the_last_whole_frame():
    from ebantenna.signal import spectrogram

    x = np.zeros(1000)
    x[992:] = 1.0  # only in the 8 samples after the last whole frame (64 long, 32 apart)
    tf = spectrogram(x, 1000.0)
    assert tf.values.shape[1] == 1 + (1000 - 64) // 32
    assert np.all(tf.values == 0.0)


def test_the_ridge_half_a_bin_off_is_as_low_as_documented():
    # timefreq.rst: between bins the ridge of a steady tone of amplitude 1 goes down to 0.85
    # (Hann) and 0.64, about 2/pi (rectangular), half a bin off; the documents round to 0.01.
    lowest = {}
    for window in ("hann", "rectangular"):
        ridges = [spectrogram(np.sin(2 * np.pi * (k + 0.5) * FS / 64 * T + phase), FS,
                              nperseg=64, window=window).values.max(axis=0)
                  for k in range(2, 30) for phase in np.linspace(0, 2 * np.pi, 4, endpoint=False)]
        lowest[window] = round(float(np.min(ridges)), 2)
    assert lowest == {"hann": 0.85, "rectangular": 0.64}
