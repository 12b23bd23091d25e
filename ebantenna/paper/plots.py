"""Figures of the paper's learning experiments: confusion matrices beside the printed ones, and
distance errors along the probe.

Examples
--------
>>> from ebantenna.paper.experiments import ClassificationResult
>>> from ebantenna.paper.printed import PAPER_ANN
>>> res = ClassificationResult("ann", PAPER_ANN.labels, {"all": PAPER_ANN.matrices["all"]}, 0.0)
>>> len(plot_confusion_comparison(res).axes)
2
"""

from __future__ import annotations

import numpy as np

from ..ml.metrics import accuracy
from .experiments import ClassificationResult, RegressionResult
from .printed import PAPER_ANN, PAPER_SVM, PaperConfusion

__all__ = ["plot_confusion_comparison", "plot_distance_errors"]


def _reorder(paper: PaperConfusion, split: str, labels) -> tuple[np.ndarray, tuple]:
    """The paper's matrix in ``labels`` order when the names match, else as printed."""
    m = paper.matrices[split]
    if set(labels) == set(paper.labels):
        pos = [paper.labels.index(lab) for lab in labels]
        return m[np.ix_(pos, pos)], tuple(labels)
    return m, paper.labels


def _draw_matrix(ax, m, labels, title):
    m = np.asarray(m)
    rows = m.sum(axis=1, keepdims=True)
    share = np.divide(m, rows, out=np.zeros(m.shape), where=rows > 0)
    ax.imshow(share, cmap="Blues", vmin=0, vmax=1)
    for (i, j), v in np.ndenumerate(m):
        ax.text(j, i, str(int(v)), ha="center", va="center", fontsize=8,
                color="white" if share[i, j] > 0.6 else "black")
    ax.set_xticks(range(len(labels)), labels, rotation=45, ha="right")
    ax.set_yticks(range(len(labels)), labels)
    ax.set_xlabel("predicted class")
    ax.set_ylabel("true class")
    ax.set_title(f"{title}\naccuracy {100 * accuracy(m):.1f} %", fontsize=9)


def plot_confusion_comparison(result: ClassificationResult, paper: PaperConfusion | None = None):
    """Our confusion matrices beside the paper's printed ones.

    Parameters
    ----------
    result : ClassificationResult
    paper : PaperConfusion, optional
        Default: :data:`PAPER_SVM` for an SVM result, :data:`PAPER_ANN` for an ANN result.

    Returns
    -------
    matplotlib.figure.Figure
        Top row: this run; bottom row: the paper, for each split the paper prints.

    Examples
    --------
    >>> res = ClassificationResult("ann", PAPER_ANN.labels, {"all": PAPER_ANN.matrices["all"]},
    ...                            0.0)
    >>> fig = plot_confusion_comparison(res)
    >>> len(fig.axes)
    2
    """
    from matplotlib.figure import Figure

    from .experiments import ClassificationResult
    from .printed import PaperConfusion

    if not isinstance(result, ClassificationResult):
        raise TypeError(f"result must be a ClassificationResult, got {type(result).__name__}")
    if paper is not None and not isinstance(paper, PaperConfusion):
        raise TypeError(f"paper must be a PaperConfusion or None, got {type(paper).__name__}")
    if paper is None:
        paper = PAPER_SVM if result.method == "svm" else PAPER_ANN
    splits = list(paper.matrices)
    fig = Figure(figsize=(4.2 * len(splits), 8.0), layout="constrained")
    axes = fig.subplots(2, len(splits), squeeze=False)
    for col, split in enumerate(splits):
        ours = result.confusions.get(split)
        if ours is None:
            axes[0, col].set_axis_off()
            axes[0, col].set_title(f"no '{split}' split in this run", fontsize=9)
        else:
            _draw_matrix(axes[0, col], ours, result.labels,
                         f"this run, {result.method.upper()} {split}")
        m, labs = _reorder(paper, split, result.labels)
        printed = paper.reported_accuracy.get(split)
        note = "" if printed is None else f" (printed {100 * printed:.1f} %)"
        _draw_matrix(axes[1, col], m, labs, f"paper {paper.figure}, {split}{note}")
    return fig


def plot_distance_errors(*results: RegressionResult):
    """Mean absolute error (cm) along the probe for one or more regressions.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> r = RegressionResult("net", np.array([0.1, 0.2]), np.array([0.11, 0.2]),
    ...                      np.array([0.1, 0.2]), np.array([1.0, 0.0]), 0.0)
    >>> fig = plot_distance_errors(r)
    >>> fig.axes[0].get_xlabel()
    'contact distance from the hinge (cm)'
    """
    from matplotlib.figure import Figure

    from .experiments import RegressionResult

    if not results:
        raise ValueError("plot_distance_errors needs at least one RegressionResult")
    bad = [type(r).__name__ for r in results if not isinstance(r, RegressionResult)]
    if bad:
        raise TypeError(f"results must be RegressionResults, got {', '.join(bad)}")
    fig = Figure(figsize=(7.0, 4.0), layout="constrained")
    ax = fig.subplots()
    for r in results:
        ax.plot(100 * r.distance_test, r.errors_cm, ".", alpha=0.25, ms=3)
        ax.plot(100 * r.positions, r.mean_error_cm, "-o", ms=3,
                label=f"{r.name}: MAE {r.mae_cm:.2f} cm", color=ax.lines[-1].get_color())
    ax.set_xlabel("contact distance from the hinge (cm)")
    ax.set_ylabel("absolute error (cm)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return fig
