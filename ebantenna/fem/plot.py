"""Figures of the modal analysis: the probe's sketch, mode shapes (Fig. 17), zones (Fig. 16)."""

from __future__ import annotations

import numpy as np

from .._budget import check_allocation
from .._validate import check_int

__all__ = ["plot_probe", "plot_modes", "plot_zones"]


def _axes(ax):
    """``ax``, or new axes when it is None; anything but matplotlib axes is refused."""
    if ax is None:
        import matplotlib.pyplot as plt

        _fig, ax = plt.subplots(figsize=(7, 4))
        return ax
    from matplotlib.axes import Axes

    if not isinstance(ax, Axes):
        raise TypeError(f"ax must be matplotlib Axes or None, got {type(ax).__name__}")
    return ax


def plot_probe(probe, supports=None, ax=None):
    """Sketch of the probe: P the hinge, Q the contact, R the free tip, drawn to scale along x.

    The tube is the thick bar from P (x = 0) to R (x = L); the hinge is a hatched wall when
    clamped, a triangle when pinned and a spiral-spring symbol when elastic; the touched object
    is a pin under Q; the accelerometer board at R is a square when the probe has a tip mass. The
    two elements of the paper's model, :math:`l_1 = |PQ|` and :math:`l_2 = |QR|`, are dimensioned
    below, in math italics so that the l cannot be read as an I.
    Only the length is to scale: the diameter is drawn thick enough to see.

    Parameters
    ----------
    probe : Probe
    supports : Supports, optional
        The hinge and the contact; a clamped probe touching nothing by default. The contact must
        lie inside ``(0, L)``.
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> from ebantenna import Probe
    >>> from ebantenna.fem import Supports
    >>> from ebantenna.fem.plot import plot_probe
    >>> ax = plot_probe(Probe(), Supports(contact=0.3))
    >>> [t.get_text() for t in ax.texts][:3]
    ['P', 'Q', 'R']
    """
    from ..probe import Probe
    from .assembly import Supports

    if not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
    if supports is not None and not isinstance(supports, Supports):
        raise TypeError(f"supports must be a Supports or None, got {type(supports).__name__}")
    from .._validate import check_in_range

    supports = Supports() if supports is None else supports
    length = 100 * probe.length  # cm, as on every other figure of the probe
    contact = None
    if supports.contact is not None:
        contact = 100 * check_in_range("supports.contact", supports.contact, 0.0, probe.length)
    ax = _axes(ax)
    ax.plot([0, length], [0, 0], color="0.45", lw=6, solid_capstyle="butt", zorder=2)
    hinge = _draw_hinge(ax, supports.hinge, length)
    ax.text(0, 0.42, "P", ha="center", fontsize="large", weight="bold")
    # the contact
    if contact is not None:
        ax.plot([contact], [-0.055], "^", color="tab:red", ms=12, zorder=3)
        ax.plot([contact - 0.03 * length, contact + 0.03 * length], [-0.1, -0.1], color="tab:red")
        ax.text(contact, 0.42, "Q", ha="center", fontsize="large", weight="bold", color="tab:red")
    # the tip and its accelerometer
    if probe.tip_mass > 0:
        ax.plot(
            [length],
            [0],
            "s",
            color="tab:blue",
            ms=11,
            zorder=3,
            label=f"tip mass {1e3 * probe.tip_mass:g} g",
        )
    ax.text(length, 0.42, "R", ha="center", fontsize="large", weight="bold")
    # dimensions: the whole length above, the paper's two elements below
    ax.annotate("", (0, 0.25), (length, 0.25), arrowprops={"arrowstyle": "<->", "lw": 0.8})
    ax.text(length / 2, 0.28, f"L = {length:g} cm", ha="center", va="bottom")
    if contact is not None:
        for a, b, name in ((0, contact, r"$l_1 = |PQ|$"), (contact, length, r"$l_2 = |QR|$")):
            ax.annotate("", (a, -0.3), (b, -0.3), arrowprops={"arrowstyle": "<->", "lw": 0.8})
            ax.text((a + b) / 2, -0.34, f"{name} = {b - a:.4g} cm", ha="center", va="top")
    ax.text(0, -0.62, hinge, fontsize="small")
    ax.set_xlim(-0.08 * length, 1.06 * length)
    ax.set_ylim(-0.7, 0.6)
    ax.set_yticks([])
    for side in ("left", "right", "top"):
        ax.spines[side].set_visible(False)
    ax.set_xlabel("distance from the hinge (cm)")
    if probe.tip_mass > 0:
        ax.legend(loc="lower right", fontsize="small", frameon=False)
    return ax


def _draw_hinge(ax, hinge, length: float) -> str:
    """Draw the hinge at x = 0 (a hatched wall, a triangle or a spiral spring); return its label."""
    if hinge == "clamped":
        ax.fill_between(
            [-0.04 * length, 0], -0.3, 0.3, facecolor="0.92", edgecolor="0.4", hatch="///", lw=0
        )
        ax.plot([0, 0], [-0.3, 0.3], color="k", lw=1.5)
        return "P: clamped hinge"
    if hinge == "pinned":
        ax.plot([0], [-0.055], "k^", ms=12, zorder=3)
        return "P: pinned hinge"
    turns = np.linspace(0, 4 * np.pi, 200)
    radius = 0.012 * length * (1 + turns) / (1 + 4 * np.pi)
    ax.plot(radius * np.cos(turns), 0.1 * radius / (0.012 * length) * np.sin(turns), "k-", lw=1)
    return f"P: elastic hinge, {hinge:g} N m/rad"


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
    _check_result("result", result, "ModalResult (modal_analysis)",
                  ("n_modes", "probe", "nodes", "supports", "frequencies", "displacement"))
    n_points = check_int("n_points", n_points, minimum=2)
    if modes is None:
        modes = range(result.n_modes)
    else:
        if isinstance(modes, int | np.integer):
            modes = [modes]
        modes = [check_int("modes", m, minimum=0, maximum=result.n_modes - 1) for m in modes]
    # the positions, the deflection of every mode there, and matplotlib's copy of each curve
    check_allocation(8 * n_points * (1 + 3 * result.n_modes), parameter="n_points",
                     what=f"mode shapes on {n_points} points")
    ax = _axes(ax)
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
    _check_result("zones", zones, "ZoneResult (mode_zones)", ("contacts", "frequency", "zone"))
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


def _check_result(name: str, value, kind: str, attributes) -> None:
    """Refuse ``value`` unless it has the ``attributes`` the figure reads (by what it holds,
    not by class: the result classes call these functions, so importing them here would make
    a circle)."""
    if not all(hasattr(value, a) for a in attributes):
        raise TypeError(f"{name} must be a {kind}, got {type(value).__name__}")
