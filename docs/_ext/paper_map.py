"""The "paper -> code" map: every figure, table and equation of the paper, and what ebantenna gives.

``.. paper-to-code::`` renders :data:`PAPER_MAP` as a table of three columns, *paper*,
*ebantenna* and *status*. Its numbers come from two sources:

- a summary of a full ``ebantenna reproduce`` run, kept in the repository as
  ``docs/_data/reproduce_summary.json`` with the commit and the date it was made from (the data
  set alone takes minutes to simulate, too long for a page build). Refresh it after a change that
  moves the study's results::

      ebantenna reproduce --json --seed 0 --out /tmp/study --cache /tmp/cache \\
          > /tmp/summary.json
      python docs/_ext/paper_map.py /tmp/summary.json

- numbers computed while the page is built, in seconds: the filter orders, the probe and the scene,
  the errata, and where the dominant frequency peaks (:func:`build_values`).

A status is one of *agrees*, *differs: why*, *not computed: why*, *shown* (a figure or a method
with no printed number to compare) or *implemented*. Where the paper prints a number, the item
names a tolerance (or, for an estimate with a 95 % interval in the summary, the interval) and the
build refuses a status whose verdict ("agrees", "differs") is not the one the numbers give.
``.. paper-peaks::`` renders where the dominant frequency peaks, for the bare tube and with the
sensor board, with a clamped hinge, the fitted one and a pinned one.

The tests check that every name below exists, that every figure, table and equation of the paper
is listed, that the summary has every key the map reads, and that those keys are the ones
``reproduce`` writes.
"""

from __future__ import annotations

import datetime
import functools
import importlib
import json
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

from sphinx.errors import ExtensionError
from sphinx.util.docutils import SphinxDirective

__all__ = [
    "Item",
    "PAPER_MAP",
    "PAPER_FIGURES",
    "PAPER_TABLES",
    "PAPER_EQUATIONS",
    "SUMMARY_PATH",
    "STATUSES",
    "resolve",
    "load_summary",
    "flatten",
    "build_values",
    "peak_positions",
    "verdict",
    "fill",
    "refresh",
    "setup",
]

#: What the paper numbers: 19 figures, 2 tables, 7 equations.
PAPER_FIGURES = tuple(f"Fig. {k}" for k in range(1, 20))
PAPER_TABLES = ("Table 1", "Table 2")
PAPER_EQUATIONS = tuple(f"Eq. {k}" for k in range(1, 8))

#: The stored summary of a full ``ebantenna reproduce`` run.
SUMMARY_PATH = Path(__file__).resolve().parents[1] / "_data" / "reproduce_summary.json"

#: How a status cell may begin.
STATUSES = ("agrees", "differs", "not computed", "shown", "implemented")


@dataclass(frozen=True)
class Item:
    """One figure, table or equation of the paper and what ebantenna gives for it.

    ``shows``, ``here`` and ``status`` are reST; ``[[KEY|FORMAT]]`` in them is replaced by the
    value ``KEY`` (see :func:`fill`): ``summary:SECTION.NAME`` from the stored summary, any other
    key from :func:`build_values`.

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
        a short reST text; empty if none.
    here : str
        What ebantenna gives: a number with its unit, or the figure.
    status : str
        One of :data:`STATUSES`, then a colon and the reason where there is one.
    check : tuple
        ``(KEY, tolerance)``: the value compared with the printed number, in the printed number's
        unit; the status must then begin with the verdict. Where the summary gives the value's
        95 % interval (``KEY_ci95``), the verdict is whether that interval holds the printed
        number, and the tolerance is not used: an estimate is judged with the uncertainty of its
        design, never by its point alone. Empty: nothing to compare.
    """

    item: str
    shows: str
    code: tuple = ()
    gallery: tuple = ()
    printed: str = ""
    here: str = ""
    status: str = ""
    check: tuple = ()


PAPER_MAP = (
    Item(
        "Fig. 1",
        "vibration signal, brass touched at 17 cm",
        ("ebantenna.simulate.simulate", "ebantenna.simulate.builtin_scene"),
        ("plot_11_simulated_signals",),
        here="``builtin_scene(\"paper\")`` touches brass at [[scene:contact_cm|.0f]] cm: "
        "[[scene:samples|d]] samples at [[scene:fs_khz|g]] kHz",
        status="shown: a simulated recording, not the paper's",
    ),
    Item(
        "Fig. 2",
        "FFT norm spectrum at 17 cm",
        ("ebantenna.signal.norm_spectrum", "ebantenna.signal.fft_features"),
        ("plot_11_simulated_signals",),
        "max_frequency_hz",
        here="spectrum up to [[scene:nyquist_hz|.0f]] Hz in [[scene:bin_hz|g]] Hz bins",
        status="differs: sampling at 1 kHz sees up to its Nyquist frequency, "
        "[[scene:nyquist_hz|.0f]] Hz; 512 Hz would need 1.024 kHz",
        check=("scene:nyquist_hz", 0.5),
    ),
    Item(
        "Fig. 3",
        "box plot of the data set: a high spread of the dominant frequency near 30 cm",
        ("ebantenna.paper.data.build_paper_dataset", "ebantenna.study.data_summary.compute",
         "ebantenna.study.signals.compute_frequency"),
        (),
        "",
        here="[[summary:dataset.signals|d]] recordings, [[summary:dataset.contacts|d]] contacts "
        "× 5 materials; the spread grows from [[summary:frequency.spread_rises_at_cm|.1f]] cm",
        status="differs: the spread is taken over all five materials, whose rods shift the "
        "probe's coupled frequencies each its own way (the report's section *material and "
        "distance from two frequencies*)",
    ),
    Item(
        "Fig. 4",
        "the Euler–Bernoulli beam element; matrices :math:`K` and :math:`M`",
        (
            "ebantenna.fem.symbolic.element_matrices",
            "ebantenna.fem.elements.element_stiffness",
            "ebantenna.fem.elements.consistent_mass",
        ),
        ("plot_01_two_element_modes",),
        here="both derived with sympy; [[errata:element|d]] printed entry differs",
        status="differs: :math:`K_{34}` is printed with the wrong sign (:doc:`theory/errata`)",
    ),
    Item(
        "Fig. 5",
        "the structural model of the probe (:math:`P`, :math:`Q`, :math:`R`)",
        ("ebantenna.fem.plot.plot_probe", "ebantenna.fem.symbolic.two_element_matrices"),
        ("plot_01_two_element_modes",),
        "probe_length_cm",
        here=":class:`~ebantenna.probe.Probe`: [[probe:length_cm|g]] cm, "
        "[[probe:outer_mm|g]] / [[probe:inner_mm|g]] mm tube",
        status="agrees",
        check=("probe:length_cm", 0.0),
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
        here="drivers of both chips, run on a simulated I2C bus; sampling at "
        "[[scene:fs_khz|g]] kHz",
        status="agrees",
        check=("scene:fs_khz", 0.0),
    ),
    Item(
        "Fig. 7",
        "animation of the 3D simulation of the rig",
        here="the rig's motion is simulated "
        "(:class:`~ebantenna.device.simulated.rig.SimulatedRig`), not drawn",
        status="not computed: an animation, nothing to compute",
    ),
    Item(
        "Fig. 8",
        "block diagram of the control algorithm",
        ("ebantenna.device.search_and_record", "ebantenna.device.SearchConfig"),
        ("plot_12_device_simulated_bus",),
        here="sweep, detect the touch, stop the servos, record, release",
        status="implemented: run on the simulated bus in the tests and in the gallery",
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
        here="no material's median dominant frequency is highest before "
        "[[summary:frequency.first_material_peak_cm|.1f]] cm",
        status="differs: the paper's 29.5 cm is where the curve leaves a straight line; beyond "
        "the lowest mode's peak the strongest bin jumps to a higher mode (the rod's or the "
        "probe's second, see example 11), so the simulated curve keeps rising",
        check=("summary:frequency.first_material_peak_cm", 1.0),
    ),
    Item(
        "Fig. 10",
        "spread of the dominant frequency against contact distance",
        ("ebantenna.study.signals.compute_frequency",),
        (),
        "spread_ratio",
        here="the spread grows from [[summary:frequency.spread_rises_at_cm|.1f]] cm "
        "([[derived:spread_rises_at_ratio|.2f]] L)",
        status="differs: the spread is over all materials, as for Fig. 3",
        check=("derived:spread_rises_at_ratio", 0.05),
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
        here="a usable decay fit (status 'ok') in [[summary:decay.decay_fit_ok_fraction|pct2]] of "
        "the recordings on the first 80 % of the probe",
        status="not computed: where PVC and wood overlap; the band-pass of Table 1, at the order "
        "[[filter:chebyshev|d]] its table needs, rings on and lengthens short decays",
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
        here="order [[filter:chebyshev|d]], the lowest that meets the table",
        status="differs: order 2 attenuates the stop band by "
        "[[stated_attenuation_db:chebyshev|.1f]] dB of the [[required_attenuation_db:chebyshev|g]] "
        "dB the table asks",
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
        here="[[summary:ann.all_accuracy|pct]] (all samples, gradient descent)",
        status="differs: what ended the main run: [[summary:ann.stopped_by|s]], after "
        "[[summary:ann.epochs|d]] of [[summary:ann.max_epochs|d]] epochs; with no validation "
        "stop, at step [[summary:materials.ann_training_setup.long_run.lr|g]], its test "
        "accuracy first reaches the paper's value at epoch "
        "[[summary:materials.ann_training_setup.long_run.reached_paper_test_epoch|d]], where "
        "the run stops (what ended it: "
        "[[summary:materials.ann_training_setup.long_run.stopped_by|s]]): the epoch is the "
        "finding; the accuracy there is picked on the test rows, so it is no test result and "
        "has no test interval; the same network "
        "reaches [[summary:materials.ann.scg|pct]] with scaled conjugate gradients and "
        "[[summary:materials.ann.adam|pct]] with Adam (test)",
        check=("summary:ann.all_accuracy", 0.02),
    ),
    Item(
        "Fig. 13",
        "the distance network over the first 80 % of the probe",
        ("ebantenna.paper.experiments.regress_distance_linear_region", "ebantenna.ml.MLPRegressor"),
        ("plot_09_mlp_training",),
        "",
        here="mean absolute error [[summary:distance.linear_region_mae_cm|.2f]] cm (gradient "
        "descent), [[summary:distance.linear_region_mae_cm_by_trainer.adam|.2f]] cm (Adam)",
        status="shown: the paper prints no error for this network",
    ),
    Item(
        "Table 2",
        "the elliptic band-pass before the full-length network",
        ("ebantenna.signal.paper_filter", "ebantenna.paper.printed.TABLE_2"),
        ("plot_06_paper_filters",),
        "order 2 (stated)",
        here="order [[filter:elliptic|d]], the lowest that meets the table",
        status="differs: order 2 attenuates the stop band by "
        "[[stated_attenuation_db:elliptic|.1f]] dB of the [[required_attenuation_db:elliptic|g]] "
        "dB the table asks",
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
        here="mean absolute error [[summary:distance.full_length_mae_cm|.2f]] cm; two spectral "
        "peaks with the material fitted: [[summary:distance.full_range_joint_mae_cm|.2f]] cm",
        status="shown: the paper prints no error for this network",
    ),
    Item(
        "Fig. 15",
        "confusion matrix of the SVM material classifier",
        ("ebantenna.paper.experiments.classify_materials_svm", "ebantenna.ml.SVC"),
        ("plot_08_svm_vs_sklearn",),
        "svm_test_accuracy",
        here="[[summary:svm.test_accuracy|pct]] on a random split (the paper's 80/20 split "
        "does not say how its test recordings were chosen: at random is the study's "
        "assumption); on held-out positions "
        "[[summary:materials.svm_grouped_test_accuracy|pct]] (interleaved), "
        "[[summary:materials.svm_blocked_test_accuracy|pct]] (a contiguous range held out, the "
        "mean of five such folds)",
        status="differs: simulated recordings, nothing tuned towards the paper; a random split "
        "of neighbouring positions can flatter a classifier (the report's section *random "
        "recordings against held-out positions* compares the intervals)",
        check=("summary:svm.test_accuracy", 0.02),
    ),
    Item(
        "Fig. 16",
        "the dominant frequency against contact distance, by zone",
        ("ebantenna.fem.dominant_mode_zones", "ebantenna.study.mode_zones.compute"),
        ("plot_04_zones",),
        "mode_change_ratio",
        here="the lowest frequency peaks at [[summary:modes.lowest_frequency_peak_ratio|.2f]] L "
        "(clamped hinge, [[scene:tip_mass_g|g]] g sensor board at the tip)",
        status="differs: the tip mass moves the peak outwards; the bare tube's is at "
        "[[peak:bare-clamped|.2f]] L (see below)",
        check=("summary:modes.lowest_frequency_peak_ratio", 0.03),
    ),
    Item(
        "Fig. 17",
        "the modes of vibration",
        ("ebantenna.fem.modal_analysis", "ebantenna.fem.plot.plot_modes"),
        ("plot_01_two_element_modes", "plot_04_zones"),
        "",
        here="zone 2 from [[summary:modes.zone2_start_ratio|.2f]] L, zone 3 from "
        "[[summary:modes.zone3_start_ratio|.2f]] L; the shapes drawn with the shape functions",
        status="shown: the paper prints no positions of the zones",
    ),
    Item(
        "Fig. 18",
        "spectrograms at 0.25 L and 0.5 L",
        ("ebantenna.signal.spectrogram", "ebantenna.study.time_frequency.compute"),
        ("plot_10_spectrogram_scalogram",),
        "long_lived_samples",
        here="spectrograms and scalograms of the simulated recordings "
        "(``[[summary:figures.fig18_19_time_frequency|s]]``)",
        status="not computed: how many samples a component lasts is not measured",
    ),
    Item(
        "Fig. 19",
        "spectrograms at 0.75 L, 0.8 L and 0.9 L",
        ("ebantenna.signal.spectrogram", "ebantenna.signal.morlet_scalogram"),
        ("plot_10_spectrogram_scalogram",),
        "early_modes_samples",
        here="as Fig. 18, in the same figure",
        status="not computed: how many samples a component lasts is not measured",
    ),
    Item(
        "Eq. 1",
        r"the resultant acceleration :math:`\sqrt{X^2 + Z^2}`",
        ("ebantenna.signal.resultant_acceleration",),
        ("plot_11_simulated_signals",),
        here="used before the decay fit (Fig. 11)",
        status="implemented: Fig. 9 reads X alone here, because Z carries gravity and the square "
        "root would mix the static 1 g into the spectrum",
    ),
    Item(
        "Eq. 2",
        r"the generalized eigenproblem :math:`[K - \omega^2 M]\,\phi = 0`",
        ("ebantenna.fem.modal_analysis", "ebantenna.fem.exact_frequencies"),
        ("plot_02_convergence", "plot_03_naive_eigensolver"),
        here="solved inverted, with a Rayleigh quotient; 64 elements within :math:`10^{-6}` of "
        "the exact frequencies",
        status="agrees: the frequencies converge to the exact ones from above, as :math:`h^4`",
    ),
    Item(
        "Eq. 3",
        r"the two-element eigenproblem with :math:`K_1` and :math:`M_1`",
        ("ebantenna.fem.symbolic.two_element_matrices", "ebantenna.fem.symbolic.paper_errata"),
        ("plot_05_errata",),
        "",
        here="derived with sympy; [[errata:two_element|d]] printed entries differ",
        status=r"differs: typos, and one factor :math:`EI/l^3`, :math:`\rho A l/420` with an "
        r":math:`l` that is right only when :math:`l_1 = l_2` (:doc:`theory/errata`)",
    ),
    Item(
        "Eq. 4",
        r"the decay model :math:`F(x) = a\,e^{bx}`",
        ("ebantenna.signal.fit_decay", "ebantenna.signal.DecayFit"),
        ("plot_07_decay_fit",),
        here=r"the fit's :math:`a`, :math:`b` and :math:`\tau = -1/b`",
        status=r"differs: for a decay :math:`b < 0`, so the time constant is :math:`-1/b`, not "
        r"the paper's :math:`1/b`",
    ),
    Item(
        "Eq. 5",
        "the dual of the SVM",
        ("ebantenna.ml.smo.solve_smo", "ebantenna.ml.SVC"),
        ("plot_08_svm_vs_sklearn",),
        here="sequential minimal optimisation",
        status="agrees: with ``libsvm_compat=True`` the decision values equal scikit-learn's to "
        "rounding (example 8)",
    ),
    Item(
        "Eq. 6",
        r"the constraints of the dual, the box :math:`0 \le b_i \le 1/(2ny)`",
        ("ebantenna.ml.SVC",),
        ("plot_08_svm_vs_sklearn",),
        here=r"the box :math:`0 \le \alpha_i \le C`",
        status=r"differs: the printed :math:`y` stands for a regularisation :math:`\lambda`, and "
        r":math:`C = 1/(2n\lambda)` (:doc:`theory/svm`)",
    ),
    Item(
        "Eq. 7",
        r"the Gaussian (RBF) kernel :math:`\exp(-\gamma \lVert x_i - x_j \rVert^2)`",
        ("ebantenna.ml.kernels.gram_matrix", "ebantenna.ml.kernels.resolve_gamma"),
        ("plot_08_svm_vs_sklearn",),
        here=r"the same kernel; the study's :math:`\gamma` = [[svm:gamma|g]], as printed",
        status="agrees",
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


def load_summary(path=SUMMARY_PATH) -> dict:
    """The stored record: ``made`` (command, commit, date) and ``summary`` (reproduce's JSON)."""
    record = json.loads(Path(path).read_text(encoding="utf-8"))
    if set(record) != {"made", "summary"}:
        raise ValueError(f"{path}: expected the keys 'made' and 'summary', got {sorted(record)}")
    return record


def flatten(tree: dict, prefix: str = "") -> dict:
    """Each leaf of a nested dict under its dotted key: ``{"a": {"b": 1}}`` to ``{"a.b": 1}``."""
    flat = {}
    for key, value in tree.items():
        if isinstance(value, dict):
            flat.update(flatten(value, f"{prefix}{key}."))
        else:
            flat[f"{prefix}{key}"] = value
    return flat


def peak_positions(hinge_stiffness: float) -> dict:
    """Where the lowest frequency peaks, fraction of L: bare tube and paper scene, three hinges.

    Keys ``"peak:TUBE-HINGE"`` with TUBE ``bare`` (the default :class:`~ebantenna.probe.Probe`) or
    ``board`` (the paper scene's probe, sensor board at the tip) and HINGE ``clamped``,
    ``fitted`` (``hinge_stiffness``, N m/rad) or ``pinned``.
    """
    from ebantenna import Probe
    from ebantenna.fem.hinge import transition_position
    from ebantenna.simulate import builtin_scene

    probes = {"bare": Probe(), "board": builtin_scene("paper").probe}
    hinges = {"clamped": "clamped", "fitted": hinge_stiffness, "pinned": "pinned"}
    return {
        f"peak:{tube}-{name}": transition_position(probe, hinge=hinge) / probe.length
        for tube, probe in probes.items()
        for name, hinge in hinges.items()
    }


def build_values(summary: dict) -> dict:
    """Every value the map reads: ``summary:KEY`` from ``summary``, the rest computed here."""
    from ebantenna.fem.symbolic import paper_errata
    from ebantenna.paper.protocol import MATERIAL_SVM
    from ebantenna.signal import PAPER_FILTERS, check_specification, filter_order, paper_filter
    from ebantenna.simulate import builtin_scene

    values = {f"summary:{key}": value for key, value in flatten(summary).items()}
    for kind, spec in PAPER_FILTERS.items():
        values[f"filter:{kind}"] = filter_order(spec)
        stated = check_specification(paper_filter(kind, "stated"), spec)
        values[f"stated_attenuation_db:{kind}"] = stated.stopband_attenuation
        values[f"required_attenuation_db:{kind}"] = spec.attenuation
    scene = builtin_scene("paper")
    probe = scene.probe
    values.update({
        "scene:contact_cm": 100 * scene.contact, "scene:samples": scene.n_samples,
        "scene:fs_khz": scene.fs / 1e3, "scene:nyquist_hz": scene.fs / 2,
        "scene:bin_hz": scene.fs / scene.n_samples, "scene:tip_mass_g": 1e3 * probe.tip_mass,
        "probe:length_cm": 100 * probe.length, "probe:outer_mm": 1e3 * probe.outer_diameter,
        "probe:inner_mm": 1e3 * probe.inner_diameter, "svm:gamma": MATERIAL_SVM.gamma,
    })  # fmt: skip
    errata = paper_errata()
    values["errata:element"] = sum(e.matrix in ("K", "M") for e in errata)
    values["errata:two_element"] = sum(e.matrix in ("K1", "M1") for e in errata)
    values["derived:spread_rises_at_ratio"] = (
        values["summary:frequency.spread_rises_at_cm"] / values["probe:length_cm"]
    )
    values.update(peak_positions(values["summary:hinge.hinge_stiffness_n_m_per_rad"]))
    return values


@functools.lru_cache(maxsize=1)
def _cached_values(text: str) -> dict:
    """:func:`build_values` once per build for both tables (the peaks take seconds)."""
    return build_values(json.loads(text)["summary"])


PLACEHOLDER = re.compile(r"\[\[([^|\]]+)\|([^\]]*)\]\]")


def _formatted(value, spec: str) -> str:
    """One value as the page shows it: ``pct`` through the report's own formatter
    (:func:`ebantenna.paper.uncertainty.percent`), so a number reads the same in both."""
    if spec.startswith("pct"):  # pct, or pct2 for two decimals
        from ebantenna.paper.uncertainty import percent

        return percent(value, int(spec[3:] or 1))
    return format(value, spec)


def fill(text: str, values: dict) -> str:
    """``text`` with every ``[[KEY|FORMAT]]`` replaced (FORMAT ``pct``, ``pct2``: a fraction as
    percent, to one or two decimals)."""

    def one(match):
        key, spec = match.groups()
        if key not in values:
            raise KeyError(f"the paper map reads {key!r}, which no source gives")
        return _formatted(values[key], spec)

    return PLACEHOLDER.sub(one, text)


def keys_read(item: Item) -> list[str]:
    """The value keys an item reads, its check's included."""
    keys = [m.group(1) for t in (item.here, item.status) for m in PLACEHOLDER.finditer(t)]
    return keys + ([item.check[0]] if item.check else [])


def verdict(item: Item, values: dict) -> str | None:
    """``"agrees"`` or ``"differs"`` from the item's check, or None where it has none."""
    if not item.check:
        return None
    from ebantenna.paper.printed import NUMBERS

    key, tolerance = item.check
    printed = NUMBERS[item.printed].value
    interval = values.get(f"{key}_ci95")
    if interval is not None:
        low, high = interval
        return "agrees" if low <= printed <= high else "differs"
    return "agrees" if abs(values[key] - printed) <= tolerance else "differs"


def _defined_at(dotted: str) -> str:
    """Where the API reference documents a name: the module that defines it, not a re-export."""
    obj = resolve(dotted)
    module, qualname = getattr(obj, "__module__", None), getattr(obj, "__qualname__", None)
    return f"{module}.{qualname}" if module and qualname else dotted


def _printed(key: str) -> str:
    from ebantenna.paper.printed import NUMBERS

    if key in NUMBERS:
        number = NUMBERS[key]
        if number.unit in ("fraction", "fraction of L"):
            value = f"{100 * number.value:.1f} %" if number.unit == "fraction" else (
                f"{number.value:g} L")
            return f"{value} ({number.where})"
        return f"{number.value:g} {number.unit} ({number.where})"
    return key


def _cells(item: Item, values: dict) -> tuple[str, str, str]:
    """The three cells of an item as reST: paper, ebantenna, status."""
    paper = f"**{item.item}** {item.shows}"
    if item.printed:
        paper += f"; printed: {_printed(item.printed)}"
    names = [f":py:obj:`~{_defined_at(name)}`" for name in item.code]
    examples = [
        f":doc:`example {int(stem.split('_')[1])} </auto_examples/{stem}>`" for stem in item.gallery
    ]
    ours = fill(item.here, values)
    if names or examples:
        ours += " — " + ", ".join(names + examples)
    found = verdict(item, values)
    if found is not None and not item.status.startswith(found):
        raise ExtensionError(
            f"paper map, {item.item}: the status says {item.status.split(':')[0]!r}, the "
            f"numbers say {found!r}"
        )
    return paper, ours, fill(item.status, values)


def _list_table(rows, header, widths, css: str) -> list[str]:
    lines = [".. list-table::", "   :header-rows: 1", f"   :widths: {widths}",
             f"   :class: {css}", ""]
    for row in [header, *rows]:
        for k, cell in enumerate(row):
            lines.append(f"   {'*' if k == 0 else ' '} - {cell}")
    return lines


class _Table(SphinxDirective):
    """A table built from the stored summary and the computed values by ``self.lines``."""

    has_content = False

    def run(self):
        record = load_summary()
        self.env.note_dependency(str(SUMMARY_PATH))
        values = _cached_values(SUMMARY_PATH.read_text(encoding="utf-8"))
        return self.parse_text_to_nodes("\n".join(self.lines(values, record)))


class PaperToCode(_Table):
    """``.. paper-to-code::``: the table of :data:`PAPER_MAP`, paper | ebantenna | status."""

    def lines(self, values, record):
        rows = [_cells(item, values) for item in PAPER_MAP]
        made = record["made"]
        lines = _list_table(rows, ("paper", "ebantenna", "status"), "30 42 28", "paper-map")
        note = (f"Numbers of the data set from ``{made['command']}`` at commit "
                f"``{made['commit'][:10]}``, {made['date']}.")
        return [note, "", *lines]


class PaperPeaks(_Table):
    """``.. paper-peaks::``: where the lowest frequency peaks, by tip mass and hinge."""

    def lines(self, values, record):
        k = values["summary:hinge.hinge_stiffness_n_m_per_rad"]
        hinges = (("clamped", "clamped"), ("fitted", f"rotational spring, {k:.2f} N m/rad"
                                           + _as_close(values)), ("pinned", "pinned"))
        rows = [
            (text, f"{values[f'peak:bare-{h}']:.3f} L", f"{values[f'peak:board-{h}']:.3f} L")
            for h, text in hinges
        ]
        header = ("hinge", "bare tube", f"{values['scene:tip_mass_g']:g} g board at the tip")
        return _list_table(rows, header, "40 30 30", "paper-peaks")


def _as_close(values) -> str:
    """How loosely the observations set the fitted hinge, from the stored summary: how many of
    the search's stiffnesses come within the observations' 2.5 mm, and their range.

    Examples
    --------
    >>> print(_as_close({
    ...     "summary:hinge.stiffness_within_resolution_n_m_per_rad": [3.16, 21.5, 1000.0],
    ...     "summary:hinge.search_stiffness_n_m_per_rad": [0.1, 3.16, 21.5, 1000.0]}))
    ... # doctest: +NORMALIZE_WHITESPACE
     (least squares; as close within the observations' 2.5 mm: 3 of the search's 4
     stiffnesses, 3.16 to 1000 N m/rad)
    """
    within = values.get("summary:hinge.stiffness_within_resolution_n_m_per_rad")
    search = values.get("summary:hinge.search_stiffness_n_m_per_rad")
    if not within or not search:
        return ""
    lo, hi = _sig3(min(within)), _sig3(max(within))
    return (f" (least squares; as close within the observations' 2.5 mm: {len(within)} of the "
            f"search's {len(search)} stiffnesses, {lo} to {hi} N m/rad)")


def _sig3(x: float) -> str:
    """``x`` to three significant figures, without an exponent (1000, 147, 3.16, 0.0681)."""
    return f"{float(f'{x:.3g}'):f}".rstrip("0").rstrip(".")


def refresh(source, target=SUMMARY_PATH, commit: str | None = None) -> dict:
    """Store the summary that ``ebantenna reproduce --json`` printed (or wrote) as ``target``.

    Paths are cut to their file names (they name the machine that ran it); ``made`` records the
    command, the commit of the working tree (``git rev-parse HEAD``, ``+dirty`` if the package has
    uncommitted changes) and the date the summary was written, UTC.
    """
    source = Path(source)
    summary = json.loads(source.read_text(encoding="utf-8"))
    if summary.get("quick"):
        raise ValueError(f"{source}: a --quick run; the map needs the full study")
    summary["dataset"]["path"] = Path(summary["dataset"]["path"]).name
    for group in ("report", "figures"):
        summary[group] = {k: Path(v).name for k, v in summary[group].items()}
    if commit is None:
        root = Path(__file__).resolve().parents[2]
        git = ["git", "-C", str(root)]
        commit = subprocess.run([*git, "rev-parse", "HEAD"], capture_output=True, text=True,
                                check=True).stdout.strip()
        dirty = subprocess.run([*git, "status", "--porcelain", "--", "ebantenna"],
                               capture_output=True, text=True, check=True).stdout.strip()
        commit += "+dirty" if dirty else ""
    mtime = datetime.datetime.fromtimestamp(source.stat().st_mtime, datetime.timezone.utc)
    made = {"command": f"ebantenna reproduce --json --seed {summary['seed']}",
            "commit": commit, "date": mtime.strftime("%Y-%m-%d %H:%M UTC")}
    record = {"made": made, "summary": summary}
    Path(target).parent.mkdir(parents=True, exist_ok=True)
    Path(target).write_text(json.dumps(record, indent=1) + "\n", encoding="utf-8")
    return record


def setup(app):
    app.add_directive("paper-to-code", PaperToCode)
    app.add_directive("paper-peaks", PaperPeaks)
    return {"version": "2.0", "parallel_read_safe": True, "parallel_write_safe": True}


if __name__ == "__main__":  # python docs/_ext/paper_map.py SUMMARY.json [COMMIT]
    refresh(sys.argv[1], commit=sys.argv[2] if len(sys.argv) > 2 else None)
