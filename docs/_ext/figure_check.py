"""A check of every figure the documentation shows: labelled axes, no empty panel, honest legends.

:func:`figure_problems` inspects a matplotlib figure and lists what a reader would trip over:

- an axes with nothing drawn in it;
- a shown axis (ticks with labels) without a label, unless a shared axis or the figure's
  ``supxlabel``/``supylabel`` labels it; a colour bar without a label;
- a legend entry whose artist is hidden or has no data (an empty ``plot([], [])`` proxy);
- a logarithmic axis whose limits reach more than two decades beyond the bulk of the data
  (its 1st to 100th percentile): the axis then shows a stray value, not the data;
- ASCII mathematics in a title, an axis label, a legend entry or a text: ``^`` or ``**`` for a
  power, or a one-letter name with an ``_`` subscript (``f_FEM``), outside mathtext's ``$...$``,
  where ``$h^4$`` and ``$f_{FEM}$`` typeset them.

The gallery runs it on every figure before the figure is saved: ``image_scrapers`` names this
module, whose :func:`_get_sg_image_scraper` hands sphinx-gallery :func:`checked_scraper`, and a
figure with a problem fails the build. The tests run it on the figures of the theory pages.
"""

from __future__ import annotations

import re

import numpy as np

__all__ = ["figure_problems", "ascii_math", "checked_scraper"]

#: How far a log axis may reach beyond the bulk of the data, in decades.
LOG_SLACK_DECADES = 2.0


def _has_tick_labels(axis) -> bool:
    return any(t.get_visible() and t.get_text().strip() for t in axis.get_ticklabels())


def _labelled_elsewhere(ax, which: str) -> bool:
    fig = ax.figure
    sup = getattr(fig, f"_sup{which}label", None)
    if sup is not None and sup.get_text().strip():
        return True
    shared = ax.get_shared_x_axes() if which == "x" else ax.get_shared_y_axes()
    return any(
        (other.get_xlabel() if which == "x" else other.get_ylabel()).strip()
        for other in shared.get_siblings(ax)
        if other is not ax
    )


def _legend_problems(ax) -> list[str]:
    from matplotlib.lines import Line2D

    legend = ax.get_legend()
    if legend is None:
        return []
    problems = []
    by_label = {}
    for artist in ax.get_children():
        label = artist.get_label() if hasattr(artist, "get_label") else ""
        if isinstance(label, str) and label and not label.startswith("_"):
            by_label.setdefault(label, []).append(artist)
    for text in legend.get_texts():
        label = text.get_text()
        for artist in by_label.get(label, []):
            if not artist.get_visible():
                problems.append(f"legend entry {label!r} names a hidden artist")
            elif isinstance(artist, Line2D) and len(artist.get_xdata()) == 0:
                problems.append(f"legend entry {label!r} names a curve with no data")
    return problems


def _axis_values(ax, which: str) -> np.ndarray:
    column = 0 if which == "x" else 1
    values = [line.get_xydata()[:, column] for line in ax.get_lines() if len(line.get_xdata())]
    for collection in ax.collections:
        offsets = np.asarray(collection.get_offsets())
        if offsets.ndim == 2 and offsets.shape[0] > 1:
            values.append(offsets[:, column])
    if not values:
        return np.empty(0)
    values = np.concatenate([np.asarray(v, dtype=float) for v in values])
    return values[np.isfinite(values) & (values > 0)]


def _log_problems(ax) -> list[str]:
    problems = []
    for which in ("x", "y"):
        if (ax.get_xscale() if which == "x" else ax.get_yscale()) != "log":
            continue
        values = _axis_values(ax, which)
        if values.size == 0:
            continue
        low, high = sorted(ax.get_xlim() if which == "x" else ax.get_ylim())
        bulk_low, top = np.percentile(values, 1), values.max()
        below = np.log10(bulk_low / low) if low > 0 else np.inf
        above = np.log10(high / top)
        if below > LOG_SLACK_DECADES or above > LOG_SLACK_DECADES:
            problems.append(
                f"log {which} axis spans [{low:.3g}, {high:.3g}], the data [{bulk_low:.3g}, "
                f"{top:.3g}]: more than {LOG_SLACK_DECADES:g} decades beyond"
            )
    return problems


#: Outside ``$...$``: a power written ``^`` or ``**``, a one-letter name with a subscript, or a
#: lower-case l with a digit (``l1``), which reads as I1 in the figures' sans-serif font.
ASCII_MATH = re.compile(r"\^|\*\*|\b[A-Za-z]_[{A-Za-z0-9]|\bl[0-9]\b")


def ascii_math(text: str) -> str | None:
    """The first piece of ASCII mathematics in a figure text outside mathtext, or None."""
    outside = re.sub(r"(?<!\\)\$.*?(?<!\\)\$", " ", text)  # drop every $...$ span
    match = ASCII_MATH.search(outside)
    return match.group(0) if match else None


def _texts(ax) -> list[str]:
    texts = [ax.get_title(loc) for loc in ("left", "center", "right")]
    texts += [ax.get_xlabel(), ax.get_ylabel()] + [t.get_text() for t in ax.texts]
    legend = ax.get_legend()
    if legend is not None:
        texts += [t.get_text() for t in legend.get_texts()]
    return [t for t in texts if t]


def _text_problems(fig) -> list[str]:
    problems = []
    named = [("figure", t) for t in _figure_texts(fig)]
    named += [(f"axes {k}", t) for k, ax in enumerate(fig.axes) for t in _texts(ax)]
    for where, text in named:
        found = ascii_math(text)
        if found is not None:
            problems.append(f"{where}: {text!r} writes mathematics in ASCII ({found!r}); "
                            "use mathtext, $...$")
    return problems


def _figure_texts(fig) -> list[str]:
    sup = [getattr(fig, f"_sup{w}", None) for w in ("title", "xlabel", "ylabel")]
    return [t.get_text() for t in sup if t is not None and t.get_text()]


def figure_problems(fig) -> list[str]:
    """What is wrong with a figure, as sentences; an empty list when nothing is.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        Drawn once here (on its own canvas) so that tick labels exist.
    """
    fig.canvas.draw()
    problems = []
    for k, ax in enumerate(fig.axes):
        if not ax.get_visible() or not ax.axison:
            continue
        name = f"axes {k}" + (f" ({ax.get_title()!r})" if ax.get_title() else "")
        colorbar = getattr(ax, "_colorbar", None)
        if colorbar is not None:
            axis = ax.yaxis if colorbar.orientation == "vertical" else ax.xaxis
            if not axis.get_label_text().strip():
                problems.append(f"{name}: colour bar without a label")
            continue
        if not ax.has_data():
            problems.append(f"{name}: nothing drawn")
            continue
        for which, axis in (("x", ax.xaxis), ("y", ax.yaxis)):
            labelled = axis.get_label_text().strip() or _labelled_elsewhere(ax, which)
            if not labelled and _has_tick_labels(axis):
                problems.append(f"{name}: {which} axis without a label")
        problems += [f"{name}: {p}" for p in _legend_problems(ax) + _log_problems(ax)]
    return problems + _text_problems(fig)


def checked_scraper(block, block_vars, gallery_conf):
    """sphinx-gallery's matplotlib scraper, after :func:`figure_problems` found nothing."""
    import matplotlib.pyplot as plt
    from sphinx_gallery.scrapers import matplotlib_scraper

    problems = [
        f"figure {num}: {problem}"
        for num in plt.get_fignums()
        for problem in figure_problems(plt.figure(num))
    ]
    if problems:
        raise ValueError(f"{block_vars['src_file']}: " + "; ".join(problems))
    return matplotlib_scraper(block, block_vars, gallery_conf)


def _get_sg_image_scraper():
    """The hook by which sphinx-gallery finds a scraper named by its module."""
    return checked_scraper
