"""The "paper -> code" map: every figure, table and equation of the paper, and what reproduces it.

``.. paper-to-code::`` renders :data:`PAPER_MAP` as a table. The numbers in its last column come
from the same functions and the same summary keys as the report of ``ebantenna reproduce``:

- the modal analysis (Fig. 16, eq. 3) is computed while the page is built, by
  :func:`ebantenna.study.mode_zones.compute` on the paper scene's probe, exactly as ``reproduce``
  computes its ``modes`` section;
- the filter orders (Tables 1 and 2) by :func:`ebantenna.signal.filter_order`;
- the data-set results (accuracies, errors) need the simulated data set, minutes of computing: the
  column names the key of ``summary.json`` under which ``reproduce`` writes them.

The tests check that every name below exists, that every figure, table and equation of the paper
is listed, and that the summary keys are those ``reproduce`` writes.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass

from docutils import nodes
from sphinx.util.docutils import SphinxDirective

__all__ = [
    "Item",
    "PAPER_MAP",
    "PAPER_FIGURES",
    "PAPER_TABLES",
    "PAPER_EQUATIONS",
    "resolve",
    "build_values",
    "setup",
]

#: What the paper numbers: 19 figures, 2 tables, 7 equations.
PAPER_FIGURES = tuple(f"Fig. {k}" for k in range(1, 20))
PAPER_TABLES = ("Table 1", "Table 2")
PAPER_EQUATIONS = tuple(f"Eq. {k}" for k in range(1, 8))


@dataclass(frozen=True)
class Item:
    """One figure, table or equation of the paper and its counterpart here.

    Attributes
    ----------
    item : str
        ``"Fig. 9"``, ``"Table 1"``, ``"Eq. 4"``.
    shows : str
        What the paper shows there.
    code : tuple of str
        Dotted names of the functions and classes that reproduce it.
    gallery : tuple of str
        Gallery examples (file stems) that show it.
    printed : str
        Name in :data:`ebantenna.paper.printed.NUMBERS` of the number the paper prints there, or
        a short text; empty if none.
    reproduced : str
        ``"modes.KEY"`` (computed for the page), ``"filter:KIND"`` (a filter order), a
        ``"summary:SECTION.KEY"`` of ``reproduce``'s ``summary.json``, or a short text.
    """

    item: str
    shows: str
    code: tuple = ()
    gallery: tuple = ()
    printed: str = ""
    reproduced: str = ""


PAPER_MAP = (
    Item(
        "Fig. 1",
        "vibration signal, object at 17 cm",
        ("ebantenna.simulate.simulate", "ebantenna.simulate.builtin_scene"),
        ("plot_11_simulated_signals",),
    ),
    Item(
        "Fig. 2",
        "FFT norm spectrum at 17 cm",
        ("ebantenna.signal.norm_spectrum", "ebantenna.signal.fft_features"),
        ("plot_11_simulated_signals",),
        "max_frequency_hz",
    ),
    Item(
        "Fig. 3",
        "box plot of the data set",
        ("ebantenna.paper.data.build_paper_dataset", "ebantenna.study.data_summary.compute"),
        (),
        "",
        "summary:dataset.signals",
    ),
    Item(
        "Fig. 4",
        "the Euler-Bernoulli beam element; matrices K and M",
        (
            "ebantenna.fem.symbolic.element_matrices",
            "ebantenna.fem.elements.element_stiffness",
            "ebantenna.fem.elements.consistent_mass",
        ),
        ("plot_01_two_element_modes",),
    ),
    Item(
        "Fig. 5",
        "the structural model of the probe (P, Q, R)",
        ("ebantenna.fem.plot.plot_probe", "ebantenna.fem.symbolic.two_element_matrices"),
        ("plot_01_two_element_modes",),
        "probe_length_cm",
    ),
    Item(
        "Fig. 6",
        "the hardware set-up",
        (
            "ebantenna.device.MPU6050",
            "ebantenna.device.PCA9685",
            "ebantenna.device.PanTilt",
            "ebantenna.device.SimulatedRig",
        ),
        ("plot_12_device_simulated_bus",),
        "sampling_frequency_khz",
    ),
    Item(
        "Fig. 7",
        "animation of the 3D simulation of the rig",
        (),
        (),
        "",
        "not reproduced: an animation of the rig's motion",
    ),
    Item(
        "Fig. 8",
        "block diagram of the control algorithm",
        ("ebantenna.device.search_and_record", "ebantenna.device.SearchConfig"),
        ("plot_12_device_simulated_bus",),
    ),
    Item(
        "Fig. 9",
        "contact distance against the dominant frequency, five materials",
        (
            "ebantenna.signal.dominant_frequency",
            "ebantenna.study.signals.compute_frequency",
            "ebantenna.paper.FrequencyDistanceEstimator",
        ),
        ("plot_11_simulated_signals",),
        "deviation_cm",
        "summary:frequency.dominant_frequency_peak_cm",
    ),
    Item(
        "Fig. 10",
        "spread of the dominant frequency against contact distance",
        ("ebantenna.study.signals.compute_frequency",),
        (),
        "spread_ratio",
        "summary:frequency.spread_rises_at_cm",
    ),
    Item(
        "Fig. 11",
        "gain and time constant of the decay against contact distance",
        (
            "ebantenna.signal.fit_decay",
            "ebantenna.signal.band_passed_decay",
            "ebantenna.study.signals.compute_decay",
        ),
        ("plot_07_decay_fit",),
        "pvc_wood_overlap_cm",
        "summary:decay.decay_fit_ok_fraction",
    ),
    Item(
        "Table 1",
        "the Chebyshev band-pass before the decay fit",
        (
            "ebantenna.signal.paper_filter",
            "ebantenna.signal.filter_order",
            "ebantenna.paper.printed.TABLE_1",
        ),
        ("plot_06_paper_filters",),
        "order 2 (stated)",
        "filter:chebyshev",
    ),
    Item(
        "Fig. 12",
        "confusion matrix of the ANN material classifier",
        (
            "ebantenna.paper.experiments.classify_materials_ann",
            "ebantenna.paper.plots.plot_confusion_comparison",
            "ebantenna.ml.MLPClassifier",
        ),
        (),
        "ann_accuracy",
        "summary:ann.all_accuracy",
    ),
    Item(
        "Fig. 13",
        "the distance network over the first 80 % of the probe",
        ("ebantenna.paper.experiments.regress_distance_linear_region", "ebantenna.ml.MLPRegressor"),
        ("plot_09_mlp_training",),
        "",
        "summary:distance.linear_region_mae_cm",
    ),
    Item(
        "Table 2",
        "the elliptic band-pass before the full-length network",
        ("ebantenna.signal.paper_filter", "ebantenna.paper.printed.TABLE_2"),
        ("plot_06_paper_filters",),
        "order 2 (stated)",
        "filter:elliptic",
    ),
    Item(
        "Fig. 14",
        "the distance network over the whole probe",
        (
            "ebantenna.paper.experiments.regress_distance_full_length",
            "ebantenna.paper.plots.plot_distance_errors",
        ),
        (),
        "",
        "summary:distance.full_length_mae_cm",
    ),
    Item(
        "Fig. 15",
        "confusion matrix of the SVM material classifier",
        ("ebantenna.paper.experiments.classify_materials_svm", "ebantenna.ml.SVC"),
        ("plot_08_svm_vs_sklearn",),
        "svm_test_accuracy",
        "summary:svm.test_accuracy",
    ),
    Item(
        "Fig. 16",
        "the dominant frequency against contact distance, by zone",
        ("ebantenna.fem.dominant_mode_zones", "ebantenna.study.mode_zones.compute"),
        ("plot_04_zones",),
        "mode_change_ratio",
        "modes.lowest_frequency_peak_ratio",
    ),
    Item(
        "Fig. 17",
        "the modes of vibration",
        ("ebantenna.fem.modal_analysis", "ebantenna.fem.plot.plot_modes"),
        ("plot_01_two_element_modes", "plot_04_zones"),
        "",
        "modes.zone3_start_ratio",
    ),
    Item(
        "Fig. 18",
        "spectrograms at 0.25 L and 0.5 L",
        ("ebantenna.signal.spectrogram", "ebantenna.study.time_frequency.compute"),
        ("plot_10_spectrogram_scalogram",),
        "long_lived_samples",
    ),
    Item(
        "Fig. 19",
        "spectrograms at 0.75 L, 0.8 L and 0.9 L",
        ("ebantenna.signal.spectrogram", "ebantenna.signal.morlet_scalogram"),
        ("plot_10_spectrogram_scalogram",),
        "early_modes_samples",
    ),
    Item(
        "Eq. 1",
        "the resultant acceleration sqrt(X^2 + Z^2)",
        ("ebantenna.signal.resultant_acceleration",),
        ("plot_11_simulated_signals",),
    ),
    Item(
        "Eq. 2",
        "the generalized eigenproblem [K - w^2 M] phi = 0",
        ("ebantenna.fem.modal_analysis", "ebantenna.fem.exact_frequencies"),
        ("plot_02_convergence", "plot_03_naive_eigensolver"),
    ),
    Item(
        "Eq. 3",
        "the two-element eigenproblem with K1 and M1",
        ("ebantenna.fem.symbolic.two_element_matrices", "ebantenna.fem.symbolic.paper_errata"),
        ("plot_05_errata",),
        "",
        "modes.errata",
    ),
    Item(
        "Eq. 4",
        "the decay model F(x) = a e^(bx)",
        ("ebantenna.signal.fit_decay", "ebantenna.signal.DecayFit"),
        ("plot_07_decay_fit",),
    ),
    Item(
        "Eq. 5",
        "the dual of the SVM",
        ("ebantenna.ml.smo.solve_smo", "ebantenna.ml.SVC"),
        ("plot_08_svm_vs_sklearn",),
    ),
    Item(
        "Eq. 6",
        "the constraints of the dual (the box 0 <= alpha <= C)",
        ("ebantenna.ml.SVC",),
        ("plot_08_svm_vs_sklearn",),
    ),
    Item(
        "Eq. 7",
        "the Gaussian (RBF) kernel",
        ("ebantenna.ml.kernels.gram_matrix", "ebantenna.ml.kernels.resolve_gamma"),
        ("plot_08_svm_vs_sklearn",),
    ),
)


def resolve(dotted: str):
    """The object a dotted name refers to; ``LookupError`` if it does not exist."""
    parts = dotted.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        for name in parts[cut:]:
            if not hasattr(obj, name):
                raise LookupError(f"{dotted}: {'.'.join(parts[:cut])} has no {name!r}")
            obj = getattr(obj, name)
        return obj
    raise LookupError(f"{dotted}: no such module")


def build_values(quick: bool = False) -> dict:
    """The numbers computed for the page: the ``modes`` section of the report, the filter orders.

    ``modes.*`` is :func:`ebantenna.study.mode_zones.compute` on the paper scene's probe, as
    ``ebantenna reproduce`` runs it (its full run, unless ``quick``: then its quick run).
    """
    from ebantenna.signal import PAPER_FILTERS, filter_order
    from ebantenna.simulate import builtin_scene
    from ebantenna.study import mode_zones

    modes = mode_zones.compute(builtin_scene("paper").probe, quick=quick).to_dict()
    values = {f"modes.{key}": value for key, value in modes.items()}
    for kind, spec in PAPER_FILTERS.items():
        values[f"filter:{kind}"] = filter_order(spec)
    return values


def _defined_at(dotted: str) -> str:
    """Where the API reference documents a name: the module that defines it, not a re-export."""
    obj = resolve(dotted)
    module, qualname = getattr(obj, "__module__", None), getattr(obj, "__qualname__", None)
    return f"{module}.{qualname}" if module and qualname else dotted


def _format(value) -> str:
    if isinstance(value, float):
        return f"{value:.3g}"
    return str(value)


def _printed(key: str) -> str:
    from ebantenna.paper.printed import NUMBERS

    if key in NUMBERS:
        number = NUMBERS[key]
        return f"{_format(number.value)} {number.unit}"
    return key


def _reproduced(text: str, values: dict) -> str:
    if text in values:
        suffix = " (order)" if text.startswith("filter:") else ""
        return f"{_format(values[text])}{suffix}"
    if text.startswith("summary:"):
        return f"summary.json: {text.removeprefix('summary:')}"
    return text


def _paragraph(*children):
    para = nodes.paragraph()
    para.extend(children)
    return para


class PaperToCode(SphinxDirective):
    """``.. paper-to-code::``: the table of :data:`PAPER_MAP` with its numbers."""

    has_content = False

    def run(self):
        from sphinx import addnodes

        values = build_values()
        headers = ["paper", "what it shows", "code", "gallery", "paper's number", "here"]
        table = nodes.table(classes=["paper-map"])
        group = nodes.tgroup(cols=len(headers))
        table += group
        for width in (8, 22, 30, 18, 12, 14):
            group += nodes.colspec(colwidth=width)
        head = nodes.thead()
        row = nodes.row()
        for h in headers:
            row += nodes.entry("", nodes.paragraph(text=h))
        head += row
        group += head
        body = nodes.tbody()
        for item in PAPER_MAP:
            code = []
            for name in item.code:
                ref = addnodes.pending_xref(
                    "",
                    nodes.literal(name, name),
                    refdomain="py",
                    reftype="obj",
                    reftarget=_defined_at(name),
                    refexplicit=True,
                    refwarn=False,
                )
                code += [ref, nodes.Text(" ")]
            gallery = []
            for stem in item.gallery:
                ref = addnodes.pending_xref(
                    "",
                    nodes.inline(stem, stem),
                    refdomain="std",
                    reftype="doc",
                    reftarget=f"/auto_examples/{stem}",
                    refexplicit=True,
                    refwarn=True,
                )
                gallery += [ref, nodes.Text(" ")]
            row = nodes.row()
            for cell in (
                _paragraph(nodes.Text(item.item)),
                _paragraph(nodes.Text(item.shows)),
                _paragraph(*code),
                _paragraph(*gallery),
                _paragraph(nodes.Text(_printed(item.printed))),
                _paragraph(nodes.Text(_reproduced(item.reproduced, values))),
            ):
                row += nodes.entry("", cell)
            body += row
        group += body
        return [table]


def setup(app):
    app.add_directive("paper-to-code", PaperToCode)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
