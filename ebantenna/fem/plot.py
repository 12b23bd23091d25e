"""Figures of the modal analysis: mode shapes (Fig. 17) and the dominant mode's zones (Fig. 16)."""

from __future__ import annotations

import numpy as np

__all__ = ["plot_modes", "plot_zones"]


def _axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt

        _fig, ax = plt.subplots(figsize=(7, 4))
    return ax


def plot_modes(result, ax=None, modes=None, n_points: int = 400, label: str = "mode"):
    """Mode shapes drawn with the Hermite shape functions between nodes (not straight lines).

    Each shape is scaled to a peak of 1; nodes are marked, the hinge and the contact shown.

    Parameters
    ----------
    result : ModalResult
    ax : matplotlib Axes, optional
    modes : sequence of int, optional
        Which modes (0-based); all by default.
    n_points : int
        Points along the probe.
    label : str
        Legend prefix of each curve: ``"{label} {k}: {f} Hz"`` (to tell meshes or probes apart).

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _axes(ax)
    modes = range(result.n_modes) if modes is None else modes
    x = np.linspace(0.0, result.probe.length, n_points)
    w = result.displacement(x)
    wn = result.displacement(result.nodes)
    for m in modes:
        scale = np.max(np.abs(w[:, m])) or 1.0
        sign = 1.0 if w[np.argmax(np.abs(w[:, m])), m] > 0 else -1.0
        (line,) = ax.plot(
            100 * x,
            sign * w[:, m] / scale,
            label=f"{label} {m + 1}: {result.frequencies[m]:.1f} Hz",
        )
        if result.nodes.size <= 40:
            ax.plot(100 * result.nodes, sign * wn[:, m] / scale, "o", ms=3, color=line.get_color())
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.plot([0], [0], "ks", ms=8, label="hinge")
    if result.supports.contact is not None:
        ax.plot([100 * result.supports.contact], [0], "k^", ms=9, label="contact")
    ax.set_xlabel("distance from the hinge (cm)")
    ax.set_ylabel("normalised deflection")
    ax.legend(fontsize="small")
    return ax


def plot_zones(zones, ax=None):
    """Dominant frequency against contact distance, the three zones shaded (Fig. 16).

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _axes(ax)
    x = 100 * zones.contacts
    # each sample's zone covers the half-way points to its neighbours
    edges = np.concatenate([[x[0]], 0.5 * (x[1:] + x[:-1]), [x[-1]]])
    colours = {1: "tab:blue", 2: "tab:orange", 3: "tab:green"}
    for z, colour in colours.items():
        sel = zones.zone == z
        if np.any(sel):
            for i in np.flatnonzero(sel):
                ax.axvspan(edges[i], edges[i + 1], color=colour, alpha=0.15, lw=0)
            ax.plot(x[sel], zones.frequency[sel], ".", color=colour, label=f"zone {z}")
    ax.plot(x, zones.frequency, color="0.3", lw=0.8)
    ax.set_xlabel("contact distance from the hinge (cm)")
    ax.set_ylabel("dominant (lowest) frequency (Hz)")
    ax.legend(fontsize="small")
    return ax
