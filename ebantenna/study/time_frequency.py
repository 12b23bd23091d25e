"""Section 8: spectrograms and scalograms at 0.25 L ... 0.9 L (Figs. 18, 19)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..paper.protocol import TIME_FREQUENCY_RATIOS
from ..paper.uncertainty import percent
from ..signal import morlet_scalogram, spectrogram
from ..simulate import simulate
from ._common import check_render, check_step, listed

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
        """Nothing of this section enters the summary: it is read from its figure and from
        the two numbers :func:`render` reads off each spectrogram."""
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
        "Sweep-plane acceleration after contact with brass at "
        f"{result.ratios[0]:.2f} L ... {result.ratios[-1]:.2f} L: short-time FFT (64-sample "
        "frames) above, Morlet scalogram below. The paper describes one long-lived component "
        "near the hinge and, towards the tip, several modes that start strong and die out "
        "quickly. Below, two numbers read from each spectrogram: the share of its energy in its "
        "strongest frequency band, and the time from its strongest frame until 90 % of its "
        "energy has arrived."
    )
    shares = [band_share(m) for m in result.spectrograms]
    times = [energy_time(m) for m in result.spectrograms]
    report.table(
        ["contact", "strongest band (Hz)", "its share of the energy", "90 % of the energy after"],
        [[f"{r:.2f} L", f"{m.f[np.argmax((m.magnitude ** 2).sum(axis=1))]:.0f}", percent(s),
          f"{1000 * t:.0f} ms"]
         for r, m, s, t in zip(result.ratios, result.spectrograms, shares, times, strict=True)],
    )
    step = float(np.median(np.diff(result.spectrograms[0].t)))
    report.paragraph(profile_sentence(result.ratios, shares, times, step))
    report.figure(name, "Spectrograms (top) and scalograms (bottom) at five contact positions")


def band_share(tf) -> float:
    """Share of a time-frequency map's energy (squared magnitude summed over time) in its
    strongest frequency row.

    Examples
    --------
    >>> from ebantenna.signal.timefreq import TimeFrequency
    >>> m = TimeFrequency(np.arange(2.0), np.array([10.0, 20.0]),
    ...                   np.array([[3.0, 0.0], [1.0, 1.0]]), "spectrogram")
    >>> band_share(m)
    0.8181818181818182
    """
    rows = (tf.magnitude ** 2).sum(axis=1)
    return float(rows.max() / rows.sum())


def energy_time(tf, share: float = 0.9) -> float:
    """Time, s, from a map's strongest column (energy summed over frequency) to the column by
    which ``share`` of its energy has arrived.

    Examples
    --------
    >>> from ebantenna.signal.timefreq import TimeFrequency
    >>> m = TimeFrequency(np.array([0.0, 0.1, 0.2, 0.3]), np.array([10.0]),
    ...                   np.array([[0.0, 3.0, 1.0, 0.5]]), "spectrogram")
    >>> round(energy_time(m), 3)
    0.1
    """
    energy = (tf.magnitude ** 2).sum(axis=0)
    arrived = np.cumsum(energy) / energy.sum()
    return float(tf.t[np.searchsorted(arrived, share)] - tf.t[np.argmax(energy)])


def profile_sentence(ratios, shares, times, step: float = 0.0) -> str:
    """Each map's strongest band's share and time to 90 % of its energy against the hinge-most
    map's, and whether the change goes the way the paper describes (one long-lived component
    near the hinge, several short-lived modes towards the tip: the share and the time both fall)
    at every later position, at none, or at some only, which it names.

    ``step`` is the maps' time step, s: the times are whole steps, and two no further apart
    than one step are not told apart.

    Examples
    --------
    >>> profile_sentence([0.25, 0.9], [0.8, 0.4], [0.3, 0.1]).count("as the paper describes")
    2
    >>> profile_sentence([0.25, 0.9], [0.4, 0.8], [0.1, 0.3]).count("unlike the paper")
    2
    >>> "within one time step" in profile_sentence([0.25, 0.9], [0.8, 0.4], [0.3, 0.28], 0.032)
    True
    >>> text = profile_sentence([0.25, 0.5, 0.9], [0.8, 0.5, 0.4], [0.7, 0.3, 0.67], 0.032)
    >>> text[text.index("ms after"):]
    'ms after the strongest frame (time step 32 ms): sooner than at 0.25 L by more than one \
time step (32 ms) at 0.50 L, not so at 0.90 L, so the shorter life the paper describes towards \
the tip shows at some positions only; one simulated brass recording per position.'
    """
    where = [f"{r:.2f} L" for r in ratios]
    first, later = where[0], where[1:]
    lower = [w for w, v in zip(later, shares[1:], strict=True) if v < shares[0]]
    if len(lower) == len(later):
        share_words = (f"less at every later position than at {first}: it spreads over more "
                       "frequencies, as the paper describes")
    elif not lower:
        share_words = (f"no less at any later position than at {first}, unlike the paper's "
                       "description")
    else:
        share_words = (f"less than at {first} at {listed(lower)}, not at "
                       f"{listed(w for w in later if w not in lower)}, so the paper's spread over "
                       "more frequencies towards the tip shows at some positions only")
    return (
        f"From {first} to {where[-1]} the strongest band holds "
        f"{listed(percent(v) for v in shares)} of the energy, {share_words}; 90 % of it has "
        f"arrived {listed(f'{1000 * t:.0f}' for t in times)} ms after the strongest frame"
        + (f" (time step {1000 * step:.0f} ms)" if step else "")
        + f": {_time_words(first, later, times, step)}; one simulated brass recording per "
        "position."
    )


def _time_words(first: str, later, times, step: float) -> str:
    """The later positions' times against the first one's, as :func:`profile_sentence` says
    them (times within one ``step`` are not told apart; the frame times round to whole steps)."""
    tol = step * (1 + 1e-9)
    sooner = [w for w, t in zip(later, times[1:], strict=True) if t < times[0] - tol]
    late = [w for w, t in zip(later, times[1:], strict=True) if t > times[0] + tol]
    if len(sooner) == len(later):
        return f"sooner at every later position than at {first}, as the paper describes"
    if sooner:
        by = f" by more than one time step ({1000 * step:.0f} ms)" if step else ""
        return (f"sooner than at {first}{by} at {listed(sooner)}, not{' so' if step else ''} at "
                f"{listed(w for w in later if w not in sooner)}, so the shorter life the paper "
                "describes towards the tip shows at some positions only")
    if not late:
        alike = (f"within one time step of {first}'s at every later position" if step else
                 f"as soon at every later position as at {first}")
        return f"{alike}, which does not show the shorter life the paper describes towards the tip"
    return f"later than at {first} at {listed(late)}, unlike the paper's description"
