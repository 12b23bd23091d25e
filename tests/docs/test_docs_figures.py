"""The figure check that the gallery runs on every figure, and the figures of the theory pages."""

import re
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pytest
from figure_check import figure_problems

DOCS = Path(__file__).resolve().parents[2] / "docs"


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def good_figure():
    fig, (a, b) = plt.subplots(1, 2, sharey=True)
    x = np.linspace(1, 10, 50)
    a.plot(x, x**2, label="square")
    a.set_xlabel("x (m)")
    a.set_ylabel("y (m$^2$)")
    a.legend()
    b.semilogx(x, np.sqrt(x))
    b.set_xlabel("x (m)")  # y is labelled on the shared axis
    return fig


def test_a_good_figure_passes():
    assert figure_problems(good_figure()) == []


def test_each_defect_is_found():
    fig = good_figure()
    fig.axes[0].set_xlabel("")
    assert figure_problems(fig) == ["axes 0: x axis without a label"]

    fig, (a, b) = plt.subplots(1, 2)
    a.plot([1, 2], [3, 4])
    a.set_xlabel("t (s)")
    a.set_ylabel("v (m/s)")
    assert figure_problems(fig) == ["axes 1: nothing drawn"]

    fig, ax = plt.subplots()
    mesh = ax.pcolormesh(np.ones((3, 3)))
    ax.set_xlabel("t (s)")
    ax.set_ylabel("f (Hz)")
    fig.colorbar(mesh, ax=ax)
    assert figure_problems(fig) == ["axes 1: colour bar without a label"]

    fig, ax = plt.subplots()
    ax.plot([1, 2], [1, 2], label="data")
    ax.plot([], [], "s", label="proxy")
    (hidden,) = ax.plot([1, 2], [2, 1], label="hidden")
    hidden.set_visible(False)
    ax.set_xlabel("a")
    ax.set_ylabel("b")
    ax.legend()
    assert figure_problems(fig) == [
        "axes 0: legend entry 'proxy' names a curve with no data",
        "axes 0: legend entry 'hidden' names a hidden artist",
    ]

    fig, ax = plt.subplots()
    ax.semilogy(np.arange(1.0, 101.0), np.concatenate([[1e-15], np.full(99, 1.0)]))
    ax.set_xlabel("f (Hz)")
    ax.set_ylabel("|X|")
    (problem,) = figure_problems(fig)
    assert problem.startswith("axes 0: log y axis spans")


def test_figure_level_labels_count():
    fig, axes = plt.subplots(2, 1)
    for ax in axes:
        ax.plot([0, 1], [0, 1])
    fig.supxlabel("time (s)")
    fig.supylabel("acceleration (m/s$^2$)")
    assert figure_problems(fig) == []


def test_the_packages_figures_pass():
    from ebantenna import Probe
    from ebantenna.fem import Supports, dominant_mode_zones, modal_analysis
    from ebantenna.fem.plot import plot_probe

    probe = Probe()
    fig, (a, b, c) = plt.subplots(3, 1)
    plot_probe(Probe(tip_mass=0.002), Supports(contact=0.3), ax=a)
    modal_analysis(probe, Supports(contact=0.3), n_modes=2).plot(ax=b)
    dominant_mode_zones(probe, np.linspace(0.1, 0.9, 9) * probe.length).plot(ax=c)
    assert figure_problems(fig) == []


def _plot_blocks():
    blocks = []
    for page in sorted(DOCS.rglob("*.rst")):
        if "_build" in page.parts:
            continue
        text = page.read_text()
        for match in re.finditer(r"^\.\. plot::\n((?:   .*\n|\n)+)", text, flags=re.M):
            body = [line[3:] for line in match.group(1).splitlines()]
            code = "\n".join(body[body.index("") :])  # the options end at the first blank line
            blocks.append(pytest.param(code, id=f"{page.stem}-{len(blocks)}"))
    return blocks


PLOT_BLOCKS = _plot_blocks()


def test_the_pages_have_figures():
    assert len(PLOT_BLOCKS) >= 7  # the probe's sketch twice, five signal-chain figures


@pytest.mark.parametrize("code", PLOT_BLOCKS)
def test_every_figure_of_the_pages_passes(code):
    exec(compile(code, "<plot directive>", "exec"), {})  # noqa: S102 - the docs' own code
    problems = [p for num in plt.get_fignums() for p in figure_problems(plt.figure(num))]
    assert problems == []


def test_ascii_mathematics_is_found_outside_mathtext():
    from figure_check import ascii_math

    assert ascii_math("error as h^4") == "^"
    assert ascii_math("x**2") == "**"
    assert ascii_math("(f_FEM - f_exact) / f_exact") == "f_F"
    assert ascii_math("l1 = |PQ|") == "l1"  # reads as I1 in a sans-serif font
    # typeset by mathtext, or no mathematics at all: nothing to find
    for text in (r"$l_1 = |PQ|$", "l = 25 cm", r"$\propto h^4$", "m/s$^2$",
                 r"$(f_\mathrm{FEM} - f)$", "modes_x_hz", "2 x 20"):
        assert ascii_math(text) is None, text

    fig, ax = plt.subplots()
    ax.plot([1, 2], [1, 2], label=r"$\propto h^4$")
    ax.set_xlabel("h (cm)")
    ax.set_ylabel("error")
    ax.legend()
    assert figure_problems(fig) == []
    ax.set_title("convergence as h^4")
    fig.suptitle("EI/l^3")
    assert figure_problems(fig) == [
        "figure: 'EI/l^3' writes mathematics in ASCII ('^'); use mathtext, $...$",
        "axes 0: 'convergence as h^4' writes mathematics in ASCII ('^'); use mathtext, $...$",
    ]


# --- the numbers the gallery's examples state in prose ------------------------------------------
#
# Each test recomputes, with the public API at the example's settings, what a sentence of the
# example says, and reads the sentence's numbers off the example's text (its comments and
# docstring, comment markers dropped, lines joined).

EXAMPLES = DOCS / "examples"


def _example_text(name: str) -> str:
    lines = (EXAMPLES / f"{name}.py").read_text().splitlines()
    return " ".join(" ".join(re.sub(r"^\s*# ?", "", line) for line in lines).split())


def _printed(value: float, stated: str) -> bool:
    """``value`` is ``stated`` to the digits printed: within half a unit of its last digit."""
    decimals = len(stated.partition(".")[2])
    return abs(value - float(stated)) <= 0.5 * 10.0**-decimals + 1e-12


def _decay_fit(transform, f, start, stop):
    """The example's fit: time constant (s) of the row nearest ``f`` from a straight line through
    log |row| on [start, stop] s, and the row's smallest and largest ratio to that line."""
    row = np.argmin(np.abs(transform.f - f))
    keep = (transform.t >= start) & (transform.t <= stop)
    log_mag = np.log(np.abs(transform.values[row, keep]))
    slope, offset = np.polyfit(transform.t[keep], log_mag, 1)
    ratio = np.exp(log_mag - (slope * transform.t[keep] + offset))
    return -1.0 / slope, ratio.min(), ratio.max()


def test_plot_10_wavelet_follows_mode_two_not_mode_three_as_stated():
    # plot_10_spectrogram_scalogram: the decays read off both pictures' rows, the third mode's
    # scalogram row beating with its mirror image (morlet_scalogram's gain g)
    from ebantenna import Probe
    from ebantenna.fem import Supports, modal_analysis
    from ebantenna.signal import morlet_scalogram, spectrogram

    page = _example_text("plot_10_spectrogram_scalogram")
    probe, fs, bandwidth = Probe(), 1000.0, 1.5
    f_modes = modal_analysis(probe, Supports(contact=0.9 * probe.length), n_modes=3).frequencies
    assert np.all(f_modes < fs / 2)
    t = np.arange(int(0.6 * fs)) / fs
    taus = 1.0 / (np.pi * probe.loss_factor * f_modes)
    x = sum(a * np.exp(-t / tau) * np.sin(2 * np.pi * f * t)
            for a, f, tau in zip([1.0, 2.0, 1.5], f_modes, taus, strict=True))
    stft = spectrogram(x, fs, nperseg=64, noverlap=56)
    cwt = morlet_scalogram(x, fs, np.linspace(10.0, 495.0, 140), bandwidth=bandwidth)
    assert 'ax.set_ylabel(f"signal (modes of amplitude {' in (EXAMPLES / (
        "plot_10_spectrogram_scalogram.py")).read_text()  # the label lists the amplitudes

    window = re.search(r"logarithm of the magnitude from (\d+) to (\d+) ms \(the third mode falls "
                       r"by :math:`e\^\{-([\d.]+)\}` there\)", page)
    assert window, "the fit's window changed in the text: update this test"
    start, stop = 1e-3 * float(window[1]), 1e-3 * float(window[2])
    assert _printed((stop - start) / taus[2], window[3])
    fits = [[_decay_fit(tf, f, start, stop) for tf in (stft, cwt)] for f in f_modes]

    # the first two modes: both pictures' time constants within 0.1 ms, both rows on their lines
    assert "Both pictures give the first two time constants to within 0.1 ms" in page
    for k in (0, 1):
        for tau_fit, low, high in fits[k]:
            assert abs(tau_fit - taus[k]) <= 0.1e-3
            assert 0.99 <= low and high <= 1.01  # "keep to their fitted lines": within 1 %
    # the third: the spectrogram's row within the stated percentage, its time constant as printed
    third = re.search(r"For the third mode \(([\d.]+) ms\) the spectrogram's row still does, "
                      r"within (\d+) %, and gives ([\d.]+) ms", page)
    assert third, "the sentence on the third mode's spectrogram row changed: update this test"
    (tau_s, low, high), (tau_w, low_w, high_w) = fits[2]
    assert _printed(1e3 * taus[2], third[1]) and _printed(1e3 * tau_s, third[3])
    assert 1 - float(third[2]) / 100 <= low and high <= 1 + float(third[2]) / 100
    # the scalogram's row: mirror image, gain, beat, swing and time constant to the digits printed
    mirror = re.search(r"mirror image at :math:`f_s - f` = (\d+) Hz enters with the gain "
                       r"g = ([\d.]+), and the two beat at their difference, (\d+) Hz \(every "
                       r"(\d+) ms: the stripes of the third figure\), so the row swings between "
                       r"([\d.]+) and ([\d.]+) times its fitted line, and the time constant read "
                       r"off it is ([\d.]+) ms instead of ([\d.]+) ms", page)
    assert mirror, "the sentence on the scalogram's third row changed: update this test"
    f3 = f_modes[2]
    gain = np.exp(-(np.pi**2) * bandwidth * (fs / f3 - 2) ** 2)  # morlet_scalogram's docstring
    assert _printed(fs - f3, mirror[1]) and _printed(gain, mirror[2])
    assert _printed(fs - 2 * f3, mirror[3]) and _printed(1e3 / (fs - 2 * f3), mirror[4])
    assert _printed(low_w, mirror[5]) and _printed(high_w, mirror[6])
    assert _printed(1e3 * tau_w, mirror[7]) and _printed(1e3 * taus[2], mirror[8])
    # "g below 1e-11 up to 300 Hz at this sampling rate, where the first two modes lie"
    assert "with g below :math:`10^{-11}` up to 300 Hz at this sampling rate" in page
    assert np.exp(-(np.pi**2) * bandwidth * (fs / 300.0 - 2) ** 2) < 1e-11
    assert np.all(f_modes[:2] < 300.0)


def _plot_11_seeds(ratio):
    """The example's brass scene at ``ratio`` L with the seeds 0 to 19: per seed the strongest bin
    (Hz), the first three simulated modes (Hz) and the shares of the strongest bin that the bins
    within one bin of them hold."""
    from ebantenna.signal import norm_spectrum
    from ebantenna.simulate import builtin_scene, simulate

    assert "seeds = range(20)" in (EXAMPLES / "plot_11_simulated_signals.py").read_text()
    scene = builtin_scene("paper").with_(material="brass")
    peaks, modes, shares = [], [], []
    for seed in range(20):
        rec = simulate(scene.with_(contact=ratio * scene.probe.length), seed=seed)
        f, mag = norm_spectrum(rec, remove_mean=True)
        simulated = np.array(rec.metadata["modes_x_hz"][:3])
        peaks.append(f[np.argmax(mag[1:]) + 1])
        modes.append(simulated)
        shares.append([mag[np.abs(f - m) <= f[1] - f[0]].max() / mag[1:].max() for m in simulated])
    peaks, modes = np.array(peaks), np.array(modes)
    on = np.abs(peaks[:, None] - modes) <= 1.0  # per seed and mode: within one bin (1 Hz)
    return peaks, modes, np.array(shares), on


@pytest.mark.parametrize("ratio", [0.25, 0.5, 0.75])
def test_plot_11_seeds_up_to_three_quarters_as_stated(ratio):
    # plot_11_simulated_signals: the strongest bin on the lowest mode with every seed 0 to 19, the
    # rod's bin at most 0.11 of it (printed to two decimals)
    page = _example_text("plot_11_simulated_signals")
    assert ("At 0.25, 0.5 and 0.75 L the strongest bin sits on the lowest mode with every one of "
            "these seeds, and the rod's bin holds at most 0.11 of it.") in page
    _, _, shares, on = _plot_11_seeds(ratio)
    assert on[:, 0].all()
    assert shares[:, 1].max() <= 0.11 + 0.005  # printed to two decimals


def test_plot_11_seeds_at_four_fifths_as_stated():
    # plot_11_simulated_signals, 0.8 L over the seeds 0 to 19: the rod's mode comes close and wins
    # with some seeds; the probe's second mode comes close and never wins
    page = _example_text("plot_11_simulated_signals")
    stated = re.search(r"At 0.8 L the brass rod's own mode, near (\d+) Hz, comes close: its bin "
                       r"holds ([\d.]+) to 1 of the strongest, and with (\d+) of the 20 seeds it "
                       r"is the strongest itself. The probe's second mode, near (\d+) Hz, comes "
                       r"close there too \(([\d.]+) to ([\d.]+)\), but is never the strongest "
                       r"with these seeds.", page)
    assert stated, "the sentences on 0.8 L changed: update this test"
    _, modes, shares, on = _plot_11_seeds(0.8)
    assert np.all(np.abs(modes[:, 1] - float(stated[1])) <= 0.5)  # "near": to the hertz
    assert _printed(shares[:, 1].min(), stated[2]) and shares[:, 1].max() == 1.0
    assert on[:, 1].sum() == int(stated[3]) == (~on[:, 0]).sum()  # the misses are the rod's
    assert np.all(np.abs(modes[:, 2] - float(stated[4])) <= 0.5)
    assert _printed(shares[:, 2].min(), stated[5]) and _printed(shares[:, 2].max(), stated[6])
    assert not on[:, 2].any()


def test_plot_11_seeds_at_nine_tenths_as_stated():
    # plot_11_simulated_signals, 0.9 L: the strongest bin 89 Hz with every seed 0 to 19; the
    # shares of the lowest and of the probe's second mode with seed 1 (the example's) and their
    # range over the seeds, printed to two decimals
    page = _example_text("plot_11_simulated_signals")
    stated = re.search(r"its bin holds ([\d.]+) of the strongest with this seed, ([\d.]+) to "
                       r"([\d.]+) over the seeds 0 to 19. The strongest bin, 89 Hz with every one "
                       r"of those seeds, .* The probe's second mode \(near 187 Hz\) holds ([\d.]+) "
                       r"with this seed, ([\d.]+) to ([\d.]+) over the seeds.", page)
    assert stated, "the sentences on 0.9 L changed: update this test"
    peaks, _, shares, _ = _plot_11_seeds(0.9)
    assert np.all(peaks == 89.0)
    for mode, (seed_1, low, high) in ((0, stated.groups()[:3]), (2, stated.groups()[3:])):
        assert _printed(shares[1, mode], seed_1)  # seed 1, the example's
        assert _printed(shares[:, mode].min(), low) and _printed(shares[:, mode].max(), high)


def test_plot_11_zone_at_nine_tenths_as_stated():
    # plot_11_simulated_signals: the lowest mode at 0.9 L by the package's zones, for the paper
    # scene's probe (tip mass), on the example's grid of 0.001 L
    import inspect

    from ebantenna.fem import dominant_mode_zones
    from ebantenna.simulate import builtin_scene

    page = _example_text("plot_11_simulated_signals")
    stated = re.search(r"the overhang holds ([\d.]+) of its kinetic energy, which "
                       r":func:`~ebantenna.fem.dominant_mode_zones` counts as zone (\d), near its "
                       r"end \(zone 3, where the overhang holds at most ([\d.]+), begins at "
                       r"([\d.]+) L\)", page)
    assert stated, "the sentence on the zone at 0.9 L changed: update this test"
    peak = re.search(r"beyond the peak of the lowest frequency in zone 2 \(([\d.]+) L with the tip "
                     r"mass\)", page)
    assert peak, "the sentence on the peak changed: update this test"
    scene = builtin_scene("paper")
    L = scene.probe.length
    assert scene.probe.tip_mass > 0
    # the example's grid from 0.85 L on, where the peak and the start of zone 3 lie
    grid = np.linspace(0.5, 0.95, 451)[350:] * L
    zones = dominant_mode_zones(scene.probe, grid, hinge=scene.hinge)
    assert zones.zone[0] == 2 and 0 < np.argmax(zones.frequency) < grid.size - 1
    k = np.argmin(np.abs(grid - 0.9 * L))
    assert _printed(zones.overhang_fraction[k], stated[1])
    assert zones.zone[k] == int(stated[2])
    lower = inspect.signature(dominant_mode_zones).parameters["lower"].default
    assert lower == float(stated[3])
    assert _printed(zones.boundaries()[1] / L, stated[4])  # the grid's first point in zone 3
    assert _printed(grid[np.argmax(zones.frequency)] / L, peak[1])
    assert zones.zone[np.argmax(zones.frequency)] == 2


@pytest.fixture(scope="module")
def plot_12_runs():
    """The example's search and recording (wood at 0.5 L, seed 4), without and with 2 % failing
    transfers, each run once for the tests below: rate -> (the rig, its accelerometer, the
    result, the driver's log messages)."""
    import logging

    from ebantenna.device import (
        MPU6050,
        PCA9685,
        Faults,
        PanTilt,
        SearchConfig,
        SimulatedRig,
        search_and_record,
    )

    class Kept(logging.Handler):
        def __init__(self):
            super().__init__(logging.INFO)
            self.messages = []

        def emit(self, record):
            self.messages.append(record.getMessage())

    logger = logging.getLogger("ebantenna.device")
    runs, level = {}, logger.level
    for rate in (0.0, 0.02):
        rig = SimulatedRig.for_contact(scene="paper", material="wood", ratio=0.5, seed=4,
                                       faults=Faults(error_rate=rate))
        kept = Kept()
        logger.addHandler(kept)
        logger.setLevel(logging.INFO)
        try:
            mpu = MPU6050(rig.bus, clock=rig.clock)
            mpu.initialize()
            unit = PanTilt(PCA9685(rig.bus, clock=rig.clock))
            unit.initialize()
            result = search_and_record(mpu, unit, SearchConfig(duration=0.5))
        finally:
            logger.removeHandler(kept)
            logger.setLevel(level)
        rig.bus.close()
        runs[rate] = (rig, mpu, result, kept.messages)
    return runs


def test_plot_12_retries_as_stated(plot_12_runs):
    # plot_12_device_simulated_bus: at 2 % failing transfers every failure is retried once and
    # goes through, each a missing acknowledge (errno 121); nothing lost, no kept sample wrong
    rig, mpu, result, messages = plot_12_runs[0.02]
    retries = [m for m in messages if "retry" in m]
    assert retries and all("[Errno 121]" in m and "retry 1 of" in m for m in retries)
    assert any("register 0x74" in m for m in retries)  # FIFO_R_W reads among them
    assert result.samples_lost == 0 and result.stream["fifo_restarts"] == 0
    assert rig.wrong_samples(mpu, result.recording) == 0


def test_plot_12_two_separate_runs_as_stated(plot_12_runs):
    # plot_12_device_simulated_bus: the runs without and with faults are separate realisations
    # (contact detected at different samples, samples not all equal); the kept samples are right
    # by the count against the simulated chip's ground truth, not by the overlay
    page = _example_text("plot_12_device_simulated_bus")
    stated = re.search(r"the contact was detected at sample (\d+) in one and (\d+) in the other",
                       page)
    assert stated, "the sentence on the two runs changed: update this test"
    assert "what the printed count ``wrong=0`` says" in page
    contacts, recordings = [], []
    for rig, mpu, result, messages in plot_12_runs.values():
        (sample,) = (int(m[1]) for message in messages
                     if (m := re.match(r"contact at sample (\d+)", message)))
        contacts.append(sample)
        recordings.append(result.recording)
        assert rig.wrong_samples(mpu, result.recording) == 0
    assert contacts == [int(stated[1]), int(stated[2])]
    assert recordings[0].n_samples == recordings[1].n_samples
    assert not np.array_equal(recordings[0].az, recordings[1].az)


def test_plot_13_z_the_same_for_every_material_in_the_model():
    # plot_13_stick_slip: in the simulator the rod is rigid along its axis and one pair of friction
    # coefficients and one preload serve every material, so Z with friction is the same, sample
    # for sample, whatever was touched (at the example's contact and seed)
    import ebantenna.simulate.stick_slip
    from ebantenna.probe import material_names
    from ebantenna.simulate import builtin_scene, simulate
    from ebantenna.simulate.effects import CoulombFriction

    page = _example_text("plot_13_stick_slip")
    assert ("The simulator takes the rod as rigid along its axis and gives every material one pair "
            "of friction coefficients (0.45 for both,") in page
    assert "That is the model's assumption, not a finding about the rig" in page
    assert "The rod is rigid along its axis" in ebantenna.simulate.stick_slip.__doc__
    friction = CoulombFriction()
    assert friction.static_friction == friction.kinetic_friction == 0.45
    names = material_names()
    assert len(names) == 5  # "the five materials"
    signals = []
    for name in names:
        scene = builtin_scene("paper").with_(contact=0.3, material=name)
        assert scene.effect("object_modes").preload == builtin_scene("paper").effect(
            "object_modes").preload  # one preload
        signals.append(simulate(scene.with_(effects=(*scene.effects, friction)), seed=1).az)
    assert all(np.array_equal(signals[0], z) for z in signals[1:])
