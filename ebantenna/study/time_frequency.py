"""Section 8: spectrograms and scalograms at 0.25 L ... 0.9 L (Figs. 18, 19)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..paper.protocol import TIME_FREQUENCY_RATIOS
from ..signal import morlet_scalogram, spectrogram
from ..simulate import simulate
from ._common import check_render, check_step

__all__ = ["TimeFrequencyResult", "compute", "render"]


@dataclass(frozen=True, eq=False)
class TimeFrequencyResult:
    """Time-frequency maps of brass contacts along the probe.

    Attributes
    ----------
    ratios : tuple of float
        Contact positions, fractions of the probe length.
    spectrograms, scalograms : tuple of ebantenna.signal.TimeFrequency
        One map of each kind per position.
    max_frequency : float
        Highest scalogram frequency, Hz.
    """

    ratios: tuple
    spectrograms: tuple
    scalograms: tuple
    max_frequency: float

    def to_dict(self) -> dict:
        """Nothing of this section enters the summary: it is read from its figure."""
        return {}


def compute(scene, seed: int) -> TimeFrequencyResult:
    """Simulate a brass contact at each ratio and map its sweep-plane acceleration."""
    check_step(scene=scene, seed=seed)
    L = scene.probe.length
    frequencies = np.linspace(5, 450, 120)
    spectrograms, scalograms = [], []
    for r in TIME_FREQUENCY_RATIOS:
        rec = simulate(scene.with_(contact=r * L, material="brass"), seed=seed)
        x = rec.ax - rec.ax.mean()
        spectrograms.append(spectrogram(x, rec.fs, nperseg=64))
        scalograms.append(morlet_scalogram(x, rec.fs, frequencies))
    return TimeFrequencyResult(TIME_FREQUENCY_RATIOS, tuple(spectrograms), tuple(scalograms),
                               float(frequencies[-1]))


def render(result: TimeFrequencyResult, report, figures) -> None:
    """Figs. 18 and 19 in one figure."""
    check_render(result, TimeFrequencyResult, report, figures)
    import matplotlib.pyplot as plt

    n = len(result.ratios)
    fig, axes = plt.subplots(2, n, figsize=(3.2 * n, 6), sharey=True)
    for j, r in enumerate(result.ratios):
        result.spectrograms[j].plot(ax=axes[0, j])
        result.scalograms[j].plot(ax=axes[1, j])
        axes[0, j].set_ylim(0, result.max_frequency)
        axes[0, j].set_title(f"spectrogram, {r:.2f} L")
        axes[1, j].set_title(f"scalogram, {r:.2f} L")
    fig.tight_layout()
    name = figures.save(fig, "fig18_19_time_frequency")
    report.heading("Spectrograms and scalograms (Figs. 18, 19)")
    report.paragraph(
        "Sweep-plane acceleration after contact with brass at 0.25 L ... 0.9 L: short-time FFT "
        "(64-sample frames) above, Morlet scalogram below. Near the hinge one long-lived component "
        "dominates; towards the tip several modes start strong and die out quickly, as the paper "
        "describes."
    )
    report.figure(name, "Spectrograms (top) and scalograms (bottom) at five contact positions")
