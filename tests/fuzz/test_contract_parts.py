"""The input contract of the parts behind the signal, finite-element and paper steps: the decay
fits and their statuses, the windowed spectrum and the peak picker, the sweep engines and their
static correction, substructures, the symbolic chain, the paper's protocol records and
confusion tables, the position-aware classification, the course's report and the recorded
study's intervals.

Each refuses a bad input of the kinds it takes with a ``ValueError`` or ``TypeError`` naming the
parameter, before any work; a good input is checked against a closed form, a value worked by
hand, or the computation the part stands in for.

Found by these rows and fixed: the decay fits took NaN times, envelopes of zero (their
logarithm) and mismatched lengths, and ``envelope_status`` divided by a rate of zero; the sweep
engines took a string probe, contacts beyond the tip and ``n_modes`` beyond the mesh (NumPy's
broadcast or index messages); ``windowed_spectrum`` and ``strongest_separated`` took unchecked
signals and bins (``IndexError``); ``format_confusion`` formatted a non-square, fractional or
all-zero matrix and dropped labels beyond its rows; the protocol records took any value;
``plot`` took any object as ``ax``; the recorded study's intervals answered ``AttributeError``
for a result of the wrong kind and ``IndexError`` for too few positions.
"""

from __future__ import annotations

import functools
import math
import os
import sys

import numpy as np
import sympy as sp

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, row_tests  # noqa: E402

from ebantenna import Probe  # noqa: E402
from ebantenna.course import CheckReport, check  # noqa: E402
from ebantenna.fem import banded, coupling, guards, secular, symbolic, zones  # noqa: E402
from ebantenna.fem.assembly import Supports  # noqa: E402
from ebantenna.fem.sweeps import reference_sweep  # noqa: E402
from ebantenna.paper import experiments, position_aware, protocol  # noqa: E402
from ebantenna.signal import decay, spectral  # noqa: E402
from ebantenna.study.recorded import calibration, study  # noqa: E402

NAN = math.nan
INF = math.inf
P = Probe()
T = np.linspace(0.0, 1.0, 11)
ENV = 2.0 * np.exp(-3.0 * T)
CLAMPED = dict(hinge_stiffness=INF, contact_stiffness=INF)


def _signal_rows():
    d, s = "ebantenna.signal.decay.", "ebantenna.signal.spectral."
    sine = (1.0, -10.1, 0.999, 500)
    t = np.arange(600) / 1000.0
    ring = 2.0 * np.exp(-t / 0.08) * np.sin(2 * np.pi * 61.3 * t + 0.9)
    tone = 3.0 + np.sin(2 * np.pi * 10 * np.arange(100) / 100.0)
    mag = np.array([0.0, 5.0, 4.0, 0.0, 3.0])
    return [
        Row(d + "weighted_line", "w-short", lambda: decay.weighted_line(T, T, T[:3]), ("w",)),
        Row(d + "weighted_line", "t-nan", lambda: decay.weighted_line(T * NAN, T, T), ("t",)),
        Row(d + "weighted_line", "w-negative", lambda: decay.weighted_line(T, T, -T), ("w",)),
        Row(d + "weighted_line", "w-all-zero", lambda: decay.weighted_line(T, T, 0 * T), ("w",)),
        # points on y = 1 + 2 t: the line itself, R^2 = 1 to rounding
        Row(d + "weighted_line", "exact-line", lambda: decay.weighted_line(T, 1 + 2 * T, 1 + T),
            same=lambda r: math.isclose(r[0], 1, rel_tol=1e-14)
            and math.isclose(r[1], 2, rel_tol=1e-14) and math.isclose(r[2], 1, rel_tol=1e-14)),
        Row(d + "loglinear_fit", "env-zero", lambda: decay.loglinear_fit(T, 0 * T), ("env",)),
        Row(d + "loglinear_fit", "env-short", lambda: decay.loglinear_fit(T, ENV[:4]), ("env",)),
        Row(d + "loglinear_fit", "t-str", lambda: decay.loglinear_fit("abc", ENV), ("t",)),
        # an exact exponential: a and b to a few ulps of the logarithm's rounding
        Row(d + "loglinear_fit", "exact-exponential", lambda: decay.loglinear_fit(T, ENV),
            same=lambda r: math.isclose(r[0], 2, rel_tol=1e-13)
            and math.isclose(r[1], -3, rel_tol=1e-13)),
        Row(d + "envelope_fit", "ek-negative",
            lambda: decay.envelope_fit(T, -ENV, nonlinear=False), ("ek",)),
        Row(d + "envelope_fit", "tk-inf",
            lambda: decay.envelope_fit(T * INF, ENV, nonlinear=False), ("tk",)),
        Row(d + "envelope_fit", "nonlinear-str",
            lambda: decay.envelope_fit(T, ENV, nonlinear="no"), ("nonlinear",)),
        Row(d + "envelope_fit", "exact-exponential",
            lambda: decay.envelope_fit(T, ENV, nonlinear=True),
            same=lambda r: math.isclose(r[1], -3, rel_tol=1e-10)
            and math.isclose(r[2], 1, rel_tol=1e-12)),
        Row(d + "damped_sinusoid_fit", "t-short",
            lambda: decay.damped_sinusoid_fit(ring, t[:10], 600, -11.0), ("t",)),
        Row(d + "damped_sinusoid_fit", "t-decreasing",
            lambda: decay.damped_sinusoid_fit(ring, t[::-1], 600, -11.0), ("t",)),
        Row(d + "damped_sinusoid_fit", "n_fit-float",
            lambda: decay.damped_sinusoid_fit(ring, t, 600.5, -11.0), ("n_fit",)),
        Row(d + "damped_sinusoid_fit", "b0-str",
            lambda: decay.damped_sinusoid_fit(ring, t, 600, "x"), ("b0",)),
        Row(d + "damped_sinusoid_fit", "x-nan",
            lambda: decay.damped_sinusoid_fit(ring * NAN, t, 600, -11.0), ("x",)),
        # a noiseless damped sinusoid: its amplitude and time constant (the solver's tolerance,
        # far below 1e-6 of each)
        Row(d + "damped_sinusoid_fit", "noiseless-ring",
            lambda: decay.damped_sinusoid_fit(ring, t, 600, -11.0),
            same=lambda r: math.isclose(r[0], 2.0, rel_tol=1e-6)
            and math.isclose(-1 / r[1], 0.08, rel_tol=1e-6) and r[3] == 600),
        Row(d + "envelope_status", "b-zero-decaying",
            lambda: decay.envelope_status(0.0, True, False, sine), ("b",)),
        Row(d + "envelope_status", "decaying-str",
            lambda: decay.envelope_status(-10.0, "yes", False, sine), ("decaying",)),
        Row(d + "envelope_status", "sine-list",
            lambda: decay.envelope_status(-10.0, True, False, [1.0, -10.0, 0.9, 5]), ("sine",)),
        Row(d + "envelope_status", "sine-nan-rate",
            lambda: decay.envelope_status(-10.0, True, False, (1.0, NAN, 0.999, 500)),
            ("sine",)),
        Row(d + "envelope_status", "by-hand", lambda: (
            decay.envelope_status(-10.0, True, False, sine),
            decay.envelope_status(-10.0, True, False, (1.0, -12.0, 0.999, 500)),
            decay.envelope_status(-10.0, True, True, None),
            decay.envelope_status(1.0, False, False, None)),
            same=lambda r: r == ("ok", "inconsistent", "too_few_points", "not_decaying")),
        Row(d + "sinusoid_status", "sine-short-tuple",
            lambda: decay.sinusoid_status((1.0, -10.0), True), ("sine",)),
        Row(d + "sinusoid_status", "envelope_decays-None",
            lambda: decay.sinusoid_status(None, None), ("envelope_decays",)),
        Row(d + "sinusoid_status", "by-hand", lambda: (
            decay.sinusoid_status((1.0, -10.0, 0.999, 500), True),
            decay.sinusoid_status(None, True), decay.sinusoid_status((1.0, 1.0, 0.999, 5), True),
            decay.sinusoid_status((1.0, -1.0, 0.5, 5), True)),
            same=lambda r: r == ("ok", "poor_fit", "not_decaying", "poor_fit")),
        Row(s + "windowed_spectrum", "fs-0",
            lambda: spectral.windowed_spectrum(tone, 0.0, "hann", 1, None, None, True), ("fs",)),
        Row(s + "windowed_spectrum", "window-unknown",
            lambda: spectral.windowed_spectrum(tone, 100.0, "x", 1, None, None, True),
            ("window",)),
        Row(s + "windowed_spectrum", "zero_pad-0",
            lambda: spectral.windowed_spectrum(tone, 100.0, "hann", 0, None, None, True),
            ("zero_pad",)),
        Row(s + "windowed_spectrum", "fmax-above-nyquist",
            lambda: spectral.windowed_spectrum(tone, 100.0, "hann", 1, None, 80.0, True),
            ("fmax",)),
        Row(s + "windowed_spectrum", "x-nan",
            lambda: spectral.windowed_spectrum(tone * NAN, 100.0, "hann", 1, None, None, True),
            ("x",)),
        Row(s + "windowed_spectrum", "remove_mean-str",
            lambda: spectral.windowed_spectrum(tone, 100.0, "hann", 1, None, None, "yes"),
            ("remove_mean",)),
        # 10 Hz in 1 Hz bins, the mean removed: bin 10 is the peak, DC left out of the band
        Row(s + "windowed_spectrum", "by-hand", lambda: spectral.windowed_spectrum(
            tone, 100.0, "rectangular", 1, None, 50.0, True),
            same=lambda r: int(np.argmax(np.abs(r[0]))) == 10 and (r[1].lo, r[1].hi) == (1, 50)),
        Row(s + "strongest_separated", "candidates-beyond",
            lambda: spectral.strongest_separated(mag, np.array([1, 9]), 2, 2.0, 1.0),
            ("candidates",)),
        Row(s + "strongest_separated", "candidates-float",
            lambda: spectral.strongest_separated(mag, np.array([1.0]), 2, 2.0, 1.0),
            ("candidates",)),
        Row(s + "strongest_separated", "magnitude-negative",
            lambda: spectral.strongest_separated(-mag, np.array([1]), 1, 2.0, 1.0),
            ("magnitude",)),
        Row(s + "strongest_separated", "n_peaks-0",
            lambda: spectral.strongest_separated(mag, np.array([1]), 0, 2.0, 1.0), ("n_peaks",)),
        Row(s + "strongest_separated", "separation-nan",
            lambda: spectral.strongest_separated(mag, np.array([1]), 1, NAN, 1.0),
            ("separation",)),
        Row(s + "strongest_separated", "df-0",
            lambda: spectral.strongest_separated(mag, np.array([1]), 1, 2.0, 0.0), ("df",)),
        # bin 2 lies 1 Hz from bin 1, closer than 2 Hz: skipped for bin 4
        Row(s + "strongest_separated", "by-hand",
            lambda: spectral.strongest_separated(mag, np.array([1, 2, 4]), 2, 2.0, 1.0),
            same=lambda r: r == [1, 4]),
    ]


def _fem_rows():
    b, c, g = "ebantenna.fem.banded.banded_sweep", "ebantenna.fem.secular.", "ebantenna.fem."
    two = np.array([0.1, 0.25])
    shift = 1.0e3
    nodes = np.linspace(0.0, 0.4, 5)
    sub = coupling.probe_substructure(P, 0.2, n_elements=8)
    fields = dict(stiffness=sub.stiffness, mass=sub.mass, interface=sub.interface,
                  nodes=sub.nodes, free=sub.free, loss_factor=sub.loss_factor, scale=sub.scale)

    def substructure(**change):
        return coupling.Substructure(**{**fields, **change})

    def reference():
        return reference_sweep(P, two, Supports(None), 16, 3)

    def hertz(lam):
        return np.sqrt(lam) / (2 * np.pi)

    rows = [
        Row(b, "probe-str", lambda: banded.banded_sweep("p", two, n_elements=16, n_modes=3,
                                                        shift=shift, **CLAMPED), ("probe",)),
        Row(b, "contacts-beyond-tip", lambda: banded.banded_sweep(
            P, np.array([0.5]), n_elements=16, n_modes=3, shift=shift, **CLAMPED), ("contacts",)),
        Row(b, "n_modes-beyond-mesh", lambda: banded.banded_sweep(
            P, two, n_elements=4, n_modes=9, shift=shift, **CLAMPED), ("n_modes",)),
        Row(b, "n_elements-1", lambda: banded.banded_sweep(
            P, two, n_elements=1, n_modes=1, shift=shift, **CLAMPED), ("n_elements",)),
        Row(b, "shift-nan", lambda: banded.banded_sweep(
            P, two, n_elements=16, n_modes=3, shift=NAN, **CLAMPED), ("shift",)),
        Row(b, "hinge-negative", lambda: banded.banded_sweep(
            P, two, n_elements=16, n_modes=3, shift=shift, hinge_stiffness=-1.0,
            contact_stiffness=INF), ("hinge_stiffness",)),
        Row(b, "contact_stiffness-0", lambda: banded.banded_sweep(
            P, two, n_elements=16, n_modes=3, shift=shift, hinge_stiffness=INF,
            contact_stiffness=0.0), ("contact_stiffness",)),
        # the engine against the reference (one modal analysis per contact); both solve one
        # eigenproblem to rounding: 1e-9 of the frequency is far above it
        Row(b, "equals-the-reference", lambda: (hertz(banded.banded_sweep(
            P, two, n_elements=16, n_modes=3, shift=shift, **CLAMPED)), reference()),
            same=lambda r: np.allclose(r[0], r[1], rtol=1e-9, atol=0)),
        Row(c + "secular_sweep", "probe-none", lambda: secular.secular_sweep(
            None, two, n_elements=16, n_modes=3, **CLAMPED), ("probe",)),
        Row(c + "secular_sweep", "contacts-nan", lambda: secular.secular_sweep(
            P, two * NAN, n_elements=16, n_modes=3, **CLAMPED), ("contacts",)),
        Row(c + "secular_sweep", "chunk-0", lambda: secular.secular_sweep(
            P, two, n_elements=16, n_modes=3, chunk=0, **CLAMPED), ("chunk",)),
        Row(c + "secular_sweep", "static-str", lambda: secular.secular_sweep(
            P, two, n_elements=16, n_modes=3, static="no", **CLAMPED), ("static",)),
        Row(c + "secular_sweep", "n_modes-0", lambda: secular.secular_sweep(
            P, two, n_elements=16, n_modes=0, **CLAMPED), ("n_modes",)),
        # the contacts on nodes of the 16-element mesh (0.1 and 0.25 m of 0.4 m, h = 0.025 m):
        # the secular roots are the pinned mesh's eigenvalues, to the root finder's tolerance
        Row(c + "secular_sweep", "equals-the-reference-on-nodes", lambda: (hertz(
            secular.secular_sweep(P, two, n_elements=16, n_modes=3, **CLAMPED)), reference()),
            same=lambda r: np.allclose(r[0], r[1], rtol=1e-9, atol=0)),
        Row(c + "static_correction", "nodes-not-uniform", lambda: secular.static_correction(
            np.array([0.0, 0.1, 0.4]), np.array([0.1]), 1.0), ("nodes",)),
        Row(c + "static_correction", "contacts-beyond", lambda: secular.static_correction(
            nodes, np.array([0.5]), 1.0), ("contacts",)),
        Row(c + "static_correction", "flexural_rigidity-0", lambda: secular.static_correction(
            nodes, np.array([0.1]), 0.0), ("flexural_rigidity",)),
        # zero on a node (the mesh is exact there), positive inside an element
        Row(c + "static_correction", "node-and-middle", lambda: secular.static_correction(
            nodes, np.array([0.1, 0.15]), 1.0),
            same=lambda r: r[0] == 0.0 and r[1] > 0),
        Row(c + "contact_weights", "phi-rows", lambda: secular.contact_weights(
            nodes, np.arange(2, 10), np.ones((7, 2)), np.array([0.1])), ("phi",)),
        Row(c + "contact_weights", "free-beyond", lambda: secular.contact_weights(
            nodes, np.arange(2, 11), np.ones((9, 2)), np.array([0.1])), ("free",)),
        Row(c + "contact_weights", "contacts-negative", lambda: secular.contact_weights(
            nodes, np.arange(2, 10), np.ones((8, 2)), np.array([-0.1])), ("contacts",)),
        # on node 1 (0.1 m) the weight is the mode's deflection there: DOF 2, row 0 of phi
        Row(c + "contact_weights", "on-a-node", lambda: secular.contact_weights(
            nodes, np.arange(2, 10), np.arange(16.0).reshape(8, 2), np.array([0.1])),
            same=lambda r: np.allclose(r, [[0.0, 1.0]], rtol=0, atol=1e-15)),
        Row(g + "guards.check_sweep", "probe-int",
            lambda: guards.check_sweep(5, two, INF, INF, 8, 2), ("probe",)),
        Row(g + "guards.check_sweep", "n_modes-beyond",
            lambda: guards.check_sweep(P, two, INF, INF, 8, 20), ("n_modes",)),
        Row(g + "guards.check_sweep", "pinned-and-spring",
            lambda: guards.check_sweep(P, two, 0.0, 1e5, 8, 2)[1:], same=lambda r: r == (8, 2)),
        Row(g + "guards.check_uniform_mesh", "not-from-0",
            lambda: guards.check_uniform_mesh(nodes + 0.1), ("nodes",)),
        Row(g + "guards.check_uniform_mesh", "one-node",
            lambda: guards.check_uniform_mesh([0.0]), ("nodes",)),
        Row(g + "guards.check_uniform_mesh", "linspace",
            lambda: guards.check_uniform_mesh(nodes)[1], same=lambda h: h == 0.1),
        Row(g + "coupling.Substructure", "stiffness-not-square",
            lambda: substructure(stiffness=sub.stiffness[:, :-1]), ("stiffness",)),
        Row(g + "coupling.Substructure", "mass-other-size",
            lambda: substructure(mass=sub.mass[:-1, :-1]), ("mass",)),
        Row(g + "coupling.Substructure", "interface-beyond",
            lambda: substructure(interface=10**6), ("interface",)),
        Row(g + "coupling.Substructure", "free-repeated",
            lambda: substructure(free=np.zeros_like(sub.free)), ("free",)),
        Row(g + "coupling.Substructure", "loss_factor-nan",
            lambda: substructure(loss_factor=NAN), ("loss_factor",)),
        Row(g + "coupling.Substructure", "scale-0", lambda: substructure(scale=0.0), ("scale",)),
        Row(g + "coupling.Substructure", "nodes-decreasing",
            lambda: substructure(nodes=sub.nodes[::-1]), ("nodes",)),
        Row(g + "coupling.Substructure", "rebuilt-equals",
            lambda: substructure().full(np.ones(sub.free.size)),
            same=lambda r: r.sum() == sub.free.size and r.size == 2 * sub.nodes.size),
        Row(g + "symbolic.assemble_chain", "a-matrix",
            lambda: symbolic.assemble_chain(sp.eye(4)), ("element_list",)),
        Row(g + "symbolic.assemble_chain", "empty", lambda: symbolic.assemble_chain([]),
            ("element_list",)),
        Row(g + "symbolic.assemble_chain", "3x3",
            lambda: symbolic.assemble_chain([sp.eye(3)]), ("element_list[0]",)),
        # two identity blocks share node 1: 2 on its two DOFs, 1 elsewhere
        Row(g + "symbolic.assemble_chain", "shared-node",
            lambda: symbolic.assemble_chain([sp.eye(4), sp.eye(4)]),
            same=lambda G: G.shape == (6, 6) and [G[i, i] for i in range(6)] == [1, 1, 2, 2, 1, 1]),
        Row(g + "zones.ZoneResult.plot", "ax-str", lambda: _zones().plot(ax="x"), ("ax",)),
        Row(g + "zones.ZoneResult.plot", "draws-the-frequency", lambda: _zone_plot(),
            same=lambda r: r[0] and np.allclose(r[1], r[2], rtol=0, atol=0)),
    ]
    return rows


@functools.cache
def _zones():
    return zones.dominant_mode_zones(P, np.linspace(0.05, 0.35, 7), n_elements=16)


def _zone_plot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    z = _zones()
    fig, ax = plt.subplots()
    try:
        back = z.plot(ax=ax)
        line = ax.get_lines()[-1].get_ydata()
        return back is ax, np.asarray(line), z.frequency
    finally:
        plt.close(fig)


def _paper_rows():
    f, p = "ebantenna.paper.experiments.format_confusion", "ebantenna.paper.protocol."
    good = dict(materials=("brass", "pvc"), probe_length=0.4, contact_step=0.005,
                repetitions=25, fft_bins=256, where="here")
    net = dict(hidden_layer_sizes=(53,), activation="tanh", solver="gd",
               fractions=(0.7, 0.15, 0.15), region=1.0, normalisation="max", where="here")
    rows = [
        Row(f, "not-square", lambda: experiments.format_confusion(np.ones((2, 3)), ["a", "b"]),
            ("matrix",)),
        Row(f, "empty", lambda: experiments.format_confusion(np.zeros((0, 0)), []),
            ("matrix",)),
        Row(f, "all-zero", lambda: experiments.format_confusion(np.zeros((2, 2)), ["a", "b"]),
            ("matrix",)),
        Row(f, "fractional", lambda: experiments.format_confusion([[1.5]], ["a"]), ("matrix",)),
        Row(f, "negative", lambda: experiments.format_confusion([[-1, 2], [0, 1]], ["a", "b"]),
            ("matrix",)),
        Row(f, "nan", lambda: experiments.format_confusion([[NAN]], ["a"]), ("matrix",)),
        Row(f, "labels-short", lambda: experiments.format_confusion([[1, 2], [3, 4]], ["a"]),
            ("labels",)),
        Row(f, "labels-long",
            lambda: experiments.format_confusion([[1, 2], [3, 4]], ["a", "b", "c"]), ("labels",)),
        Row(f, "labels-str", lambda: experiments.format_confusion([[1, 2], [3, 4]], "ab"),
            ("labels",)),
        Row(f, "by-hand", lambda: experiments.format_confusion(np.array([[5, 1], [0, 4]]),
                                                               ["al", "pvc"]),
            same=lambda r: r.splitlines() == ["true \\ predicted     al    pvc",
                                              "al                    5      1",
                                              "pvc                   0      4"]),
        Row(p + "DatasetProtocol", "materials-str",
            lambda: protocol.DatasetProtocol(**{**good, "materials": "brass"}), ("materials",)),
        Row(p + "DatasetProtocol", "materials-twice",
            lambda: protocol.DatasetProtocol(**{**good, "materials": ("brass", "Brass")}),
            ("materials",)),
        Row(p + "DatasetProtocol", "probe_length-nan",
            lambda: protocol.DatasetProtocol(**{**good, "probe_length": NAN}), ("probe_length",)),
        Row(p + "DatasetProtocol", "contact_step-beyond",
            lambda: protocol.DatasetProtocol(**{**good, "contact_step": 1.0}), ("contact_step",)),
        Row(p + "DatasetProtocol", "repetitions-1.5",
            lambda: protocol.DatasetProtocol(**{**good, "repetitions": 1.5}), ("repetitions",)),
        Row(p + "DatasetProtocol", "fft_bins-0",
            lambda: protocol.DatasetProtocol(**{**good, "fft_bins": 0}), ("fft_bins",)),
        Row(p + "DatasetProtocol", "where-None",
            lambda: protocol.DatasetProtocol(**{**good, "where": None}), ("where",)),
        Row(p + "DatasetProtocol", "the-paper's", lambda: protocol.DatasetProtocol(
            **{**good, "materials": protocol.DATASET.materials}),
            same=lambda d: d.repetitions * len(d.materials) == 125),
        Row(p + "SVMProtocol", "gamma-negative",
            lambda: protocol.SVMProtocol(-2.0, 0.2, "one-vs-rest", "x"), ("gamma",)),
        Row(p + "SVMProtocol", "test_fraction-1",
            lambda: protocol.SVMProtocol(2.0, 1.0, "one-vs-rest", "x"), ("test_fraction",)),
        Row(p + "SVMProtocol", "strategy-unknown",
            lambda: protocol.SVMProtocol(2.0, 0.2, "all", "x"), ("strategy",)),
        Row(p + "SVMProtocol", "the-paper's", lambda: protocol.SVMProtocol(
            2.0, 0.2, "one-vs-rest", "section 4.3"), same=lambda s: s == protocol.MATERIAL_SVM
            .__class__(2.0, 0.2, "one-vs-rest", "section 4.3")),
        Row(p + "NetworkProtocol", "hidden-list",
            lambda: protocol.NetworkProtocol(**{**net, "hidden_layer_sizes": [53]}),
            ("hidden_layer_sizes",)),
        Row(p + "NetworkProtocol", "hidden-0",
            lambda: protocol.NetworkProtocol(**{**net, "hidden_layer_sizes": (0,)}),
            ("hidden_layer_sizes",)),
        Row(p + "NetworkProtocol", "activation-unknown",
            lambda: protocol.NetworkProtocol(**{**net, "activation": "x"}), ("activation",)),
        Row(p + "NetworkProtocol", "solver-unknown",
            lambda: protocol.NetworkProtocol(**{**net, "solver": "x"}), ("solver",)),
        Row(p + "NetworkProtocol", "fractions-sum",
            lambda: protocol.NetworkProtocol(**{**net, "fractions": (0.7, 0.2, 0.2)}),
            ("fractions",)),
        Row(p + "NetworkProtocol", "fractions-int",
            lambda: protocol.NetworkProtocol(**{**net, "fractions": 1}), ("fractions",)),
        Row(p + "NetworkProtocol", "region-0",
            lambda: protocol.NetworkProtocol(**{**net, "region": 0.0}), ("region",)),
        Row(p + "NetworkProtocol", "normalisation-unknown",
            lambda: protocol.NetworkProtocol(**{**net, "normalisation": "z"}),
            ("normalisation",)),
        Row(p + "NetworkProtocol", "the-paper's", lambda: protocol.NetworkProtocol(**net),
            same=lambda n: n == protocol.MATERIAL_ANN.__class__(**net)
            and n.hidden_layer_sizes == protocol.MATERIAL_ANN.hidden_layer_sizes),
    ]
    a = "ebantenna.paper.position_aware.classify_materials_position_aware"
    X, y, d, peaks, split = _position_design()
    rows += [
        Row(a, "X-1-D", lambda: position_aware.classify_materials_position_aware(
            X[:, 0], y, d, peaks, peaks[:, 0], split), ("X",)),
        Row(a, "positions-short", lambda: position_aware.classify_materials_position_aware(
            X, y, d[:5], peaks, peaks[:, 0], split), ("positions",)),
        Row(a, "materials-short", lambda: position_aware.classify_materials_position_aware(
            X, y[:5], d, peaks, peaks[:, 0], split), ("materials",)),
        Row(a, "split-str", lambda: position_aware.classify_materials_position_aware(
            X, y, d, peaks, peaks[:, 0], "x"), ("split",)),
        Row(a, "split-beyond", lambda: position_aware.classify_materials_position_aware(
            X, y, d, peaks, peaks[:, 0], (split[0], np.array([10**6]))), ("split",)),
        Row(a, "positions-nan", lambda: position_aware.classify_materials_position_aware(
            X, y, d * NAN, peaks, peaks[:, 0], split), ("positions",)),
        # the documented example: whole positions held out, read at their estimated distance
        Row(a, "documented-example", lambda: position_aware.classify_materials_position_aware(
            X, y, d, peaks, peaks[:, 0], split),
            same=lambda r: r.method == "position-aware" and r.accuracies["test"] > 0.9),
    ]
    return rows


def _position_design():
    rng = np.random.default_rng(1)
    d = np.tile(np.repeat(np.linspace(0.02, 0.38, 19), 3), 2)
    y = np.repeat(["al", "pvc"], d.size // 2)
    bins = np.arange(40)
    X = np.exp(-0.5 * ((bins - 60 * d[:, None]) / 2) ** 2) + 0.2 * np.exp(
        -0.5 * (bins - 30 - 2 * (y == "pvc")[:, None]) ** 2) + 0.02 * rng.random((114, 40))
    peaks = np.column_stack([10 + 30 * d, 80 - 50 * d])
    test = np.flatnonzero(np.isin(d, d[::15]))
    return X, y, d, peaks, (np.setdiff1d(np.arange(114), test), test)


def _classified():
    rows = np.arange(8)
    right = np.array([True, True, False, True, True, True, False, True])
    return experiments.ClassificationResult(
        "svm", ("a", "b"), {"test": np.array([[3, 1], [1, 3]])}, 0.0,
        tested={"test": (rows, right)})


def _regressed():
    truth = np.repeat([0.1, 0.2], 4)
    predicted = truth + np.array([0.001, 0.004, -0.001, 0.0, 0.002, 0.01, -0.003, 0.0])
    return experiments.RegressionResult("x", truth, predicted, np.array([0.1, 0.2]),
                                        np.zeros(2), 0.0)


def _other_rows():
    r, k = "ebantenna.study.recorded.", "ebantenna.course.CheckReport"
    positions = np.repeat([0.1, 0.2, 0.3, 0.4], 2)
    return [
        Row(k, "exercise-int", lambda: CheckReport(5, ("a",), (True,)), ("exercise",)),
        Row(k, "lines-list", lambda: CheckReport("ex01", ["a"], (True,)), ("lines",)),
        Row(k, "passed-str", lambda: CheckReport("ex01", ("a",), ("yes",)), ("passed",)),
        Row(k, "passed-short", lambda: CheckReport("ex01", ("a", "b"), (True,)), ("passed",)),
        Row(k, "as-check-makes-it", lambda: check("ex01", M11=156, M14=-12),
            same=lambda rep: isinstance(rep, CheckReport) and rep.passed == (True, False)
            and not rep.ok),
        Row(r + "study.classification_interval", "result-dict",
            lambda: study.classification_interval({}, positions), ("result",)),
        Row(r + "study.classification_interval", "positions-short",
            lambda: study.classification_interval(_classified(), positions[:3]),
            ("positions",)),
        Row(r + "study.classification_interval", "positions-nan",
            lambda: study.classification_interval(_classified(), positions * NAN),
            ("positions",)),
        # 6 of 8 right: the estimate is the share itself, its unit the 4 positions
        Row(r + "study.classification_interval", "by-hand",
            lambda: study.classification_interval(_classified(), positions),
            same=lambda d: d["test_accuracy"] == 0.75 and d["n_test"] == 8
            and d["n_units"] == 4 and d["interval95"][0] <= 0.75 <= d["interval95"][1]),
        Row(r + "study.placement_interval", "result-classification",
            lambda: study.placement_interval(_classified(), 0.005), ("result",)),
        Row(r + "study.placement_interval", "contact_step-0",
            lambda: study.placement_interval(_regressed(), 0.0), ("contact_step",)),
        # errors 0.1, 0.4, 0.1, 0, 0.2, 1.0, 0.3, 0 cm; within half of 0.5 cm: 5 of 8; their
        # mean 2.1 / 8 cm, to the rounding of the differences (1e-12 is far above it)
        Row(r + "study.placement_interval", "by-hand",
            lambda: study.placement_interval(_regressed(), 0.005),
            same=lambda d: d["placed"] == 0.625 and math.isclose(d["mae_cm"], 0.2625,
                                                                  rel_tol=1e-12)),
        Row(r + "study.intervals", "learnt-dict", lambda: study.intervals({}, 0.005),
            ("learnt",)),
        Row(r + "study.intervals", "contact_step-nan", lambda: study.intervals(
            _learnt(positions), NAN), ("contact_step",)),
        Row(r + "study.intervals", "the-four-results",
            lambda: study.intervals(_learnt(positions), 0.005),
            same=lambda d: sorted(d) == ["ann", "full_length", "linear_region", "svm"]
            and d["svm"]["test_accuracy"] == 0.75 and d["full_length"]["placed"] == 0.625),
        Row(r + "calibration.plot_calibration", "cal-dict",
            lambda: calibration.plot_calibration({}, None), ("cal",)),
    ]


def _learnt(positions):
    from ebantenna.study.learning import LearningResult

    return LearningResult(_classified(), _classified(), _regressed(), _regressed(), positions)


@functools.cache
def all_rows():
    return _signal_rows() + _fem_rows() + _paper_rows() + _other_rows()


(IDS, test_the_rows_are_distinct, test_every_row_ends_in_a_clear_error_or_the_right_answer,
 contract_rows) = row_tests(all_rows, 'ebantenna.')
