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
