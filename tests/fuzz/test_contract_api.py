"""The input contract of the public Python API, by parameter kind: every outcome is classified.

Each case calls one public function, class or method with one generated argument and says what
the contract promises: for a bad input, a clear error (``ValueError``, ``TypeError`` or
:class:`~ebantenna.MemoryBudgetError`) whose message names the parameter; for a good one, a
result checked against an independent computation (a closed form, the generating parameter of
a synthetic signal, an integer conversion done by hand). :func:`classify` sorts an outcome into
one of the classes of :data:`CLASSES`; the test asserts the first two only.

The kinds, each generated for every parameter of that kind (:func:`number_cases`,
:func:`array_cases`):

- numbers: NaN, +-inf, +-10**400, a Fraction of 10**400, and wrong types (a string, None, a
  bool, a complex number, a list); for a positive parameter also 0 and -1; for a parameter
  with a stated range, values beyond it;
- arrays: complex, masked, datetime, bool, numeric-string, object (10**400), ragged, empty,
  NaN, inf, a wrong number of dimensions, None;
- sizes: requests over a memory budget of 64 MiB (set for the module);
- right answers: float32, int and extreme-scale data, extreme sampling frequencies.

The case list is built by :func:`build_cases`, a plain function of no argument, so that the same
list can be classified against another tree of the package (the count in the docs was made
that way, see ``docs/user_guide/input_contract.rst``).
"""

from __future__ import annotations

import math
import traceback
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np
import pytest
from unloaded_time import time_limit  # tests/, on the path by its conftest

import ebantenna
from ebantenna import Probe, Recording, device, fem, ml, simulate
from ebantenna import signal as sig

#: The classes an outcome falls into; only the first two keep the contract.
CLASSES = ("clear error", "right", "vague error", "refused a valid input",
           "traceback from internals", "MemoryError or timeout", "silently wrong")

#: The memory budget the cases run under, bytes.
BUDGET = 64 * 2**20

#: Seconds a case may take before it counts as a timeout (on ``unloaded_time``'s clock).
TIMEOUT = 20


@dataclass
class Case:
    """One call: ``call()`` with a bad input naming ``param``, or a good one ``check``-ed."""

    name: str
    call: object
    param: str | None = None  # a bad input: the parameter the error must name
    check: object = None  # a good input: check(result) -> bool
    tags: tuple = field(default_factory=tuple)


# ------------------------------------------------------------------ fixtures of the cases
FS = 1000.0
N = 512
T = np.arange(N) / FS
TONE = np.sin(2 * np.pi * 125.0 * T)
DECAY = np.exp(-T / 0.05) * np.sin(2 * np.pi * 62.5 * T)
X2 = np.array([[0.0, 0.0], [1.0, 1.0], [0.0, 1.0], [1.0, 0.0]] * 3)
Y2 = np.array([0, 1, 0, 1] * 3)
PROBE = Probe()


def _mpu():
    rig = device.SimulatedRig.quiet(seed=1)
    return device.MPU6050(rig.bus, None, clock=rig.clock)


def _rod(**kw):
    return fem.Rod("pvc", **kw)


#: Values no real parameter accepts: ``(label, value)``.
NOT_NUMBERS = [
    ("nan", math.nan), ("inf", math.inf), ("-inf", -math.inf), ("10**400", 10**400),
    ("-10**400", -(10**400)), ("Fraction(10**400)", Fraction(10**400)),
    ("np.float64-nan", np.float64("nan")), ("str", "1.0"), ("None", None), ("bool", True),
    ("complex", 1 + 2j), ("list", [1.0]),
]
NOT_POSITIVE = [("zero", 0.0), ("-1", -1.0), ("-5e-324", -5e-324)]


def _array_kinds(good: np.ndarray) -> list:
    """Bad arrays shaped like ``good`` (1-D or 2-D): ``(label, value)``."""
    n = good.shape[-1]
    kinds = [
        ("complex", good + 0j), ("masked", np.ma.masked_array(good, mask=good * 0 != 0)),
        ("datetime", np.arange(good.size).astype("datetime64[s]").reshape(good.shape)),
        ("bool", good > 0), ("numeric-str", good.astype(str)),
        ("object-10**400", np.array([10**400] * good.size, dtype=object).reshape(good.shape)),
        ("empty", np.empty((0,) * good.ndim)), ("None", None),
    ]
    with_nan = good.copy()
    with_nan.flat[0] = math.nan
    with_inf = good.copy()
    with_inf.flat[-1] = math.inf
    kinds += [("nan", with_nan), ("inf", with_inf), ("3-D", good[None, None])]
    if good.ndim == 1:
        kinds.append(("ragged", [list(good[: n // 2]), list(good)]))
    else:
        kinds.append(("ragged", [list(good[0]), list(good[1][:-1])] + good[2:].tolist()))
    return kinds


def number_cases(name: str, make, param: str, *, positive=True, optional=False,
                 beyond=()) -> list[Case]:
    """A case per bad number of ``param``: ``make(value)`` must refuse each naming ``param``.

    ``optional``: None is a valid value (a default), not a bad one.
    """
    values = NOT_NUMBERS + (NOT_POSITIVE if positive else []) + list(beyond)
    if optional:
        values = [(label, v) for label, v in values if v is not None]
    return [Case(f"{name}:{param}={label}", _bind(make, v), param=param) for label, v in values]


def array_cases(name: str, make, param: str, good: np.ndarray, *,
                optional=False) -> list[Case]:
    """A case per bad array of ``param``: ``make(value)`` must refuse each naming ``param``."""
    return [Case(f"{name}:{param}=array-{label}", _bind(make, v), param=param)
            for label, v in _array_kinds(good) if not (optional and v is None)]


def _bind(make, value):
    return lambda: make(value)


# ------------------------------------------------------------------ bad numbers and arrays
def _signal_cases() -> list[Case]:
    c = []
    c += array_cases("dominant_frequency", lambda v: sig.dominant_frequency(v, FS), "x", TONE)
    c += number_cases("dominant_frequency", lambda v: sig.dominant_frequency(TONE, v), "fs",
                      beyond=[("1e309-int", 10**309)])
    c += number_cases("dominant_frequency", lambda v: sig.dominant_frequency(TONE, FS, fmax=v),
                      "fmax", optional=True, beyond=[("above-nyquist", 501.0)])
    c += number_cases("dominant_frequency",
                      lambda v: sig.dominant_frequency(TONE, FS, zero_pad=v), "zero_pad",
                      beyond=[("65", 65), ("2**70", 2**70)])
    c += array_cases("fit_decay", lambda v: sig.fit_decay(v, FS), "x", DECAY)
    c += number_cases("fit_decay", lambda v: sig.fit_decay(DECAY, v), "fs")
    c += number_cases("fit_decay", lambda v: sig.fit_decay(DECAY, FS, floor_factor=v),
                      "floor_factor", beyond=[("1e7", 1e7)])
    c += number_cases("fit_decay", lambda v: sig.fit_decay(DECAY, FS, min_r_squared=v),
                      "min_r_squared", positive=False, beyond=[("1.5", 1.5), ("-0.1", -0.1)])
    c += array_cases("envelope", sig.envelope, "x", DECAY)
    c += array_cases("spectrogram", lambda v: sig.spectrogram(v, FS), "x", TONE)
    c += number_cases("spectrogram", lambda v: sig.spectrogram(TONE, FS, nperseg=v), "nperseg",
                      beyond=[("10**400-int", 10**400), ("longer-than-x", N + 1), ("3", 3)])
    c += number_cases("spectrogram", lambda v: sig.spectrogram(TONE, v), "fs")
    c += array_cases("morlet_scalogram", lambda v: sig.morlet_scalogram(v, FS, [100.0]), "x",
                     TONE)
    c += array_cases("morlet_scalogram",
                     lambda v: sig.morlet_scalogram(TONE, FS, v), "frequencies",
                     np.array([50.0, 100.0]))
    c += number_cases("morlet_scalogram",
                      lambda v: sig.morlet_scalogram(TONE, FS, [100.0], bandwidth=v), "bandwidth")
    sos = sig.paper_filter(next(iter(sig.PAPER_FILTERS)))
    c += array_cases("apply_filter", lambda v: sig.apply_filter(sos, v), "x", TONE)
    c += array_cases("resultant_acceleration", lambda v: sig.resultant_acceleration(v, TONE),
                     "ax", TONE)
    c += array_cases("fft_features", lambda v: sig.fft_features(TONE, v), "az", TONE)
    c += number_cases("FrequencyTracker", lambda v: sig.FrequencyTracker(v), "fs")
    c += number_cases("FrequencyTracker",
                      lambda v: sig.FrequencyTracker(FS, block=v).track(TONE), "block",
                      beyond=[("10**9-longer-than-x", 10**9), ("7", 7)])
    c += number_cases("FrequencyTracker",
                      lambda v: sig.FrequencyTracker(FS, pole_radius=v), "pole_radius",
                      beyond=[("1", 1.0)])
    c += array_cases("FrequencyTracker.track", lambda v: sig.FrequencyTracker(FS).track(v), "x",
                     TONE)
    kf = sig.KalmanFilter.random_walk(process_std=0.1, measurement_std=1.0)
    c += array_cases("KalmanFilter.filter", kf.filter, "y", TONE)
    c += number_cases("KalmanFilter.random_walk",
                      lambda v: sig.KalmanFilter.random_walk(v, 1.0), "process_std")
    return c


def _recording_cases() -> list[Case]:
    c = []
    for p in ("t", "ax", "az"):
        def make(v, p=p):
            args = {"t": T, "ax": TONE, "az": TONE}
            args[p] = v
            return Recording(args["t"], args["ax"], args["az"], FS)
        c += array_cases("Recording", make, p, TONE if p != "t" else T)
    c += number_cases("Recording", lambda v: Recording(T, TONE, TONE, v), "fs")
    c += [
        Case("Recording:t-at-500Hz-with-fs-1000", lambda: Recording(2 * T, TONE, TONE, FS),
             param="t"),
        Case("Recording:t-non-uniform", lambda: Recording(np.sort(np.random.default_rng(0)
             .uniform(0, 1, N)), TONE, TONE, FS), param="t"),
        Case("Recording:metadata-int-key", lambda: Recording(T, TONE, TONE, FS, {1: "a"}),
             param="metadata"),
        Case("Recording:metadata-nested-int-key",
             lambda: Recording(T, TONE, TONE, FS, {"a": {2: "b"}}), param="metadata"),
        Case("Recording:metadata-int-key-in-a-list-after-numbers",
             lambda: Recording(T, TONE, TONE, FS, {"a": [0.5, "x", ([{4: "d"}],)]}),
             param="metadata"),
        Case("Recording:metadata-not-json", lambda: Recording(T, TONE, TONE, FS, {"a": {1j}}),
             param="metadata"),
    ]
    return c


def _fem_cases() -> list[Case]:
    c = []
    for p in ("length", "outer_diameter", "youngs_modulus", "density"):
        c += number_cases("Probe", lambda v, p=p: Probe(**{p: v}), p,
                          beyond=[("5e-324", 5e-324), ("1e300", 1e300)])
    c += number_cases("Probe", lambda v: Probe(tip_mass=v), "tip_mass", positive=False,
                      beyond=[("1e300", 1e300), ("-1", -1.0)])
    c += number_cases("Probe", lambda v: Probe(loss_factor=v), "loss_factor", positive=False,
                      beyond=[("1e300", 1e300), ("2", 2.0), ("-1", -1.0)])
    for p in ("diameter", "free_length"):
        c += number_cases("Rod.cantilever_frequency",
                          lambda v, p=p: _rod(**{p: v}).cantilever_frequency(), p,
                          beyond=[("5e-324", 5e-324), ("1e300", 1e300)])
    c += array_cases("natural_frequencies",
                     lambda v: fem.natural_frequencies(PROBE, v, n_modes=2, n_elements=8),
                     "contacts", np.array([0.1, 0.2]))
    c += number_cases("natural_frequencies",
                      lambda v: fem.natural_frequencies(PROBE, [0.2], n_modes=2, n_elements=v),
                      "n_elements", beyond=[("5000", 5000)])
    c += number_cases("modal_analysis",
                      lambda v: fem.modal_analysis(PROBE, fem.Supports(0.2), n_elements=8,
                                                   n_modes=v), "n_modes",
                      beyond=[("17", 17)])
    c += number_cases("modal_analysis",
                      lambda v: fem.modal_analysis(PROBE, fem.Supports(v), n_elements=8),
                      "contact", optional=True, beyond=[("beyond-tip", 1.0)])
    def coupled(**kw):
        return fem.coupled_modes(PROBE, _rod(), 0.2, 2e5, n_modes=2, n_elements=16,
                                 rod_elements=8, probe_modes=8, rod_modes=4, **kw)
    c += number_cases("coupled_modes", lambda v: coupled(contact_loss_factor=v),
                      "contact_loss_factor", positive=False,
                      beyond=[("1e300", 1e300), ("2", 2.0), ("-1", -1.0)])
    c += [
        Case("coupled_modes:rod_elements=5000", lambda: fem.coupled_modes(
            PROBE, _rod(), 0.2, 2e5, n_modes=2, rod_elements=5000), param="rod_elements"),
        Case("coupled_modes:probe_modes-default-on-a-coarse-mesh", lambda: fem.coupled_modes(
            PROBE, _rod(), 0.2, 2e5, n_modes=3, n_elements=16, rod_elements=8),
            param="probe_modes"),
        Case("coupled_modes:rod_modes-above-mesh", lambda: fem.coupled_modes(
            PROBE, _rod(), 0.2, 2e5, n_modes=2, n_elements=16, rod_elements=4,
            probe_modes=8), param="rod_modes"),
        Case("natural_frequencies:complex-contact",
             lambda: fem.natural_frequencies(PROBE, [0.2 + 0j], n_modes=2, n_elements=8),
             param="contacts"),
    ]
    return c


def _simulate_cases() -> list[Case]:
    scene = simulate.builtin_scene("paper")
    c = number_cases("simulate_batch", lambda v: simulate.simulate_batch(scene, contact=v),
                     "contact", optional=True, beyond=[("beyond-tip", 1.0)])
    c += array_cases("simulate_batch", lambda v: simulate.simulate_batch(scene, contact=v),
                     "contact", np.array([0.1, 0.2]), optional=True)
    design = simulate.DatasetDesign
    c += number_cases("dataset_plan", lambda v: simulate.dataset_plan(
        scene, design("d", ("brass",), 0.1, 0.1, v)), "repetitions", beyond=[("1.5", 1.5)])
    c += number_cases("DatasetDesign", lambda v: design("d", ("brass",), v, 0.1, 1),
                      "first_contact")
    c += [Case("DatasetDesign:materials-repeated",
               lambda: design("d", ("brass", "brass"), 0.1, 0.1, 1), param="materials")]
    terms = simulate.ModalTerms if hasattr(simulate, "ModalTerms") else None
    if terms is not None:
        omega = np.array([[10.0, 20.0], [30.0, 40.0]])
        live = np.ones((2, 2), dtype=bool)
        made = terms(omega, omega * 0, omega * 0, live)
        c += [Case(f"ModalTerms.frequencies:row={r}", _bind(made.frequencies, r), param="row")
              for r in (-1, 2, 10**400, 1.0, "0")]
    return c


def _ml_cases() -> list[Case]:
    c = []
    for p, positive in (("C", True), ("tol", True), ("cache_size", True), ("coef0", False)):
        c += number_cases("SVC.fit", lambda v, p=p: ml.SVC(**{p: v}).fit(X2, Y2), p,
                          positive=positive)
    c += number_cases("SVC.fit", lambda v: ml.SVC(gamma=v).fit(X2, Y2), "gamma",
                      positive=False, beyond=[("-1", -1.0)])
    c += [Case(f"SVC.fit:class_weight={{0: {w!r}}}",
               _bind(lambda w: ml.SVC(class_weight={0: w}).fit(X2, Y2), w), param="class_weight")
          for w in (-1, -1.0, math.nan, math.inf, 10**400)]
    c += number_cases("SVC.fit", lambda v: ml.SVC(kernel="poly", degree=v).fit(X2, Y2),
                      "degree", positive=False, beyond=[("2**31", 2**31), ("-1", -1)])
    # the shared training kernel: of another width, another shape, not finite, a list, or
    # given beside a kernel that is its own matrix
    K2 = ml.kernels.Kernel("rbf", gamma=0.5).gram(X2)
    nan = K2.copy()
    nan[3, 5] = math.nan
    inf, both = K2.copy(), K2.copy()  # the finiteness check sums: inf, and inf - inf = NaN
    inf[2, 1] = both[0, 4] = math.inf
    both[4, 0] = -math.inf
    for label, K in (("gamma-2", ml.kernels.Kernel("rbf", gamma=2.0).gram(X2)),
                     ("11-rows", K2[:11, :11]), ("nan", nan), ("inf", inf),
                     ("inf-and-minus-inf", both), ("list", K2.tolist()),
                     ("int", K2.astype(int)), ("linear", ml.kernels.Kernel("linear").gram(X2))):
        c.append(Case(f"SVC.fit:kernel_matrix={label}",
                      _bind(lambda K: ml.SVC(gamma=0.5).fit(X2, Y2, kernel_matrix=K), K),
                      param="kernel_matrix"))
    c.append(Case("SVC.fit:kernel_matrix-with-precomputed",
                  lambda: ml.SVC(kernel="precomputed").fit(K2, Y2, kernel_matrix=K2),
                  param="kernel_matrix"))
    for p in ("alpha", "learning_rate_init", "tol"):
        c += number_cases("MLPClassifier.fit",
                          lambda v, p=p: ml.MLPClassifier(**{p: v}, max_iter=5).fit(X2, Y2), p,
                          positive=p == "learning_rate_init")
    c += [Case("MLPClassifier.fit:hidden_layer_sizes=(10**9,)",
               lambda: ml.MLPClassifier(hidden_layer_sizes=(10**9,)).fit(X2, Y2),
               param="hidden_layer_sizes"),
          Case("MLPClassifier.fit:hidden_layer_sizes=(10**400,)",
               lambda: ml.MLPClassifier(hidden_layer_sizes=(10**400,)).fit(X2, Y2),
               param="hidden_layer_sizes")]
    return c


def _device_cases() -> list[Case]:
    c = number_cases("MPU6050Config", lambda v: device.MPU6050Config(fs=v), "fs",
                     beyond=[("5e-324", 5e-324), ("1e300", 1e300), ("0.5", 0.5)])
    c += number_cases("prescale_for", lambda v: device.pca9685.prescale_for(v), "frequency",
                      beyond=[("5e-324", 5e-324), ("1e300", 1e300)])
    c += number_cases("prescale_for",
                      lambda v: device.pca9685.prescale_for(50.0, oscillator_hz=v),
                      "oscillator_hz", beyond=[("5e-324", 5e-324), ("1e300", 1e300)])
    c += [Case(f"MPU6050.decode:{len(raw)}-bytes", _bind(device.MPU6050.decode, raw),
               param="raw") for raw in (b"\x01\x02\x03", b"\x00" * 7, b"\x00" * 11)]
    c += [Case("MPU6050.decode:str", lambda: device.MPU6050.decode("abcdef"), param="raw")]
    return c


def _size_cases() -> list[Case]:
    """Requests over the 64 MiB budget: each must be a MemoryBudgetError naming its parameter."""
    scene = simulate.builtin_scene("paper")
    spec = next(iter(sig.PAPER_FILTERS.values()))
    sos = sig.paper_filter(next(iter(sig.PAPER_FILTERS)))
    return [
        Case("morlet_scalogram:1e6-frequencies", lambda: sig.morlet_scalogram(
            TONE, FS, np.linspace(1.0, 499.0, 10**6)), param="frequencies", tags=("size",)),
        Case("dominant_frequency:1e6-samples-zero_pad-64", lambda: sig.dominant_frequency(
            np.sin(np.arange(10**6) * 0.3), FS, zero_pad=64), param="zero_pad",
            tags=("size",)),
        Case("check_specification:n_points=10**9",
             lambda: sig.check_specification(sos, spec, n_points=10**9), param="n_points",
             tags=("size",)),
        Case("simulate_batch:1e6-seeds",
             lambda: simulate.simulate_batch(scene, seeds=np.arange(10**6)), param="seeds",
             tags=("size",)),
        Case("dataset_plan:2.9-TiB-design", lambda: simulate.dataset_plan(
            scene, simulate.DatasetDesign("d", ("brass", "pvc"), 0.01, 0.01, 10**7)),
            param="design", tags=("size",)),
        Case("MLPClassifier.fit:hidden=(10**6,10**3)",
             lambda: ml.MLPClassifier(hidden_layer_sizes=(10**6, 10**3)).fit(X2, Y2),
             param="hidden_layer_sizes", tags=("size",)),
        Case("MPU6050.record:1e5-s", lambda: _mpu().record(1e5), param="duration",
             tags=("size",)),
        Case("DatasetDesign.contacts:contact_step=5e-324", lambda: simulate.DatasetDesign(
            "d", ("brass",), 0.1, 5e-324, 1).contacts(0.4), param="contact_step",
            tags=("size",)),
    ]


# ------------------------------------------------------------------ right answers
def _right_cases() -> list[Case]:
    rng = np.random.default_rng(31)
    c = []
    for i in range(40):  # a tone on a bin: the peak is its frequency, whatever the scale or type
        k = int(rng.integers(8, N // 2 - 8))
        scale = 10.0 ** float(rng.uniform(-300, 300))
        dtype = (np.float64, np.float32, np.float64)[i % 3]
        x = (np.sin(2 * np.pi * k * np.arange(N) / N) * (1 if dtype is np.float32 else scale))
        x = x.astype(dtype)
        c.append(Case(f"dominant_frequency:bin-{k}-{dtype.__name__}-scale-{scale:.0e}",
                      _bind(lambda x: sig.dominant_frequency(x, FS), x),
                      check=_near(k * FS / N, 1e-3 * FS / N)))
    for _ in range(30):  # a decaying sine: tau in samples is the generating one at any fs
        tau = float(rng.uniform(60, 200))
        fs = 10.0 ** float(rng.choice([-300, -100, -3, 0, 3, 100, 300]) + rng.uniform(-1, 1))
        n = np.arange(2048)
        x = np.exp(-n / tau) * np.sin(2 * np.pi * 0.05 * n)
        # the envelope fit is biased by under 2 % here (measured against the generating tau)
        c.append(Case(f"fit_decay:tau-{tau:.0f}-samples-fs-{fs:.1e}",
                      _bind(lambda x, fs=fs: sig.fit_decay(x, fs), x),
                      check=_decay_near(tau, fs)))
    for _ in range(20):  # a steady tone at any scale: the tracker ends on it
        f0 = float(rng.uniform(60, 300))
        scale = 10.0 ** float(rng.uniform(-300, 300))
        x = scale * np.sin(2 * np.pi * f0 * np.arange(2000) / FS)
        c.append(Case(f"FrequencyTracker:f0-{f0:.1f}-scale-{scale:.0e}",
                      _bind(lambda x: sig.FrequencyTracker(FS).track(x).final_frequency(), x),
                      check=_near(f0, 0.01 * f0)))
    for dtype in (np.float32, np.int16, np.int64, np.uint8, np.float16):  # converted exactly
        ax = (rng.uniform(0, 100, N)).astype(dtype)
        c.append(Case(f"Recording:ax-{np.dtype(dtype).name}",
                      _bind(lambda ax: Recording(T, ax, ax, FS).ax, ax),
                      check=(lambda r, ax=ax: r.dtype == np.float64
                                        and np.array_equal(r, [float(v) for v in ax]))))
    for _ in range(20):  # a cantilever's first frequency: the Euler-Bernoulli closed form
        length = float(rng.uniform(0.1, 2.0))
        d = float(rng.uniform(0.002, 0.05))
        probe = Probe(length=length, outer_diameter=d, inner_diameter=0.5 * d,
                      youngs_modulus=float(rng.uniform(1e9, 2e11)),
                      density=float(rng.uniform(500, 9000)))
        exact = 1.8751040687119611**2 / (2 * math.pi * length**2) * math.sqrt(
            probe.flexural_rigidity / probe.mass_per_length)
        # 16 elements: the h^4 discretisation error of the first mode is below 1e-6
        c.append(Case(f"modal_analysis:cantilever-L{length:.2f}-d{d:.3f}",
                      _bind(lambda p: fem.modal_analysis(p, fem.Supports(None), n_elements=16,
                                                         n_modes=1).frequencies[0], probe),
                      check=_near(exact, 1e-5 * exact)))
    for _ in range(10):  # huge gamma: K = I, every training point its own support vector
        gamma = 10.0 ** float(rng.uniform(10, 300))
        X = rng.normal(size=(30, 3))
        y = (rng.uniform(size=30) > 0.4).astype(int)
        c.append(Case(f"SVC:gamma-{gamma:.0e}-predicts-training-labels",
                      _bind(lambda X, y=y, g=gamma: ml.SVC(gamma=g).fit(X, y).predict(X), X),
                      check=(lambda p, y=y: np.array_equal(p, y))))
    # dlpf_cfg=0: 8000 Hz / (1 + n), n in [0, 255], at most 1000 Hz
    c += [Case(f"MPU6050Config:fs-8000/{1 + n}",
               _bind(lambda n: device.MPU6050Config(fs=8000.0 / (1 + n)).smplrt_div, n),
               check=_near(n, 0)) for n in (7, 9, 15, 39, 79, 199, 255)]
    for f in rng.uniform(24, 1526, 15):  # DS equation 1
        c.append(Case(f"prescale_for:{f:.1f}Hz", _bind(device.pca9685.prescale_for, float(f)),
                      check=_near(round(25e6 / (4096 * f)) - 1, 0)))
    for i in range(10):  # big-endian 16-bit words, by hand
        raw = rng.integers(0, 256, 6 * (i + 1), dtype=np.uint8).tobytes()
        words = [int.from_bytes(raw[j: j + 2], "big", signed=True) for j in range(0, len(raw), 2)]
        c.append(Case(f"MPU6050.decode:{len(raw)}-bytes", _bind(device.MPU6050.decode, raw),
                      check=(lambda r, w=words: r.ravel().tolist() == w)))
    return c


def _near(expected, tol):
    return lambda got: abs(float(got) - expected) <= tol


def _decay_near(tau, fs):
    def check(fit):
        return fit.status == "ok" and abs(fit.tau * fs / tau - 1.0) < 0.02
    return check


def build_cases() -> list[Case]:
    """Every case, in a fixed order (the random ones from a fixed seed)."""
    return (_signal_cases() + _recording_cases() + _fem_cases() + _simulate_cases()
            + _ml_cases() + _device_cases() + _size_cases() + _right_cases())


# ------------------------------------------------------------------ classification
class _Timeout(Exception):
    pass


def _time_limit(seconds: float):
    """``_Timeout`` after ``seconds`` of the case's own time (waits for a CPU left out)."""
    return time_limit(seconds, _Timeout)


def _raised_in_package(exc: BaseException) -> bool:
    """Was ``exc`` raised by the package's own code (not NumPy, SciPy, scikit-learn, Python)?"""
    frames = traceback.extract_tb(exc.__traceback__)
    return bool(frames) and "/ebantenna/" in frames[-1].filename.replace("\\", "/")


def classify(case: Case) -> tuple[str, str]:
    """The class of ``case``'s outcome (one of :data:`CLASSES`) and a one-line detail."""
    import warnings

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            with _time_limit(TIMEOUT):
                result = case.call()
    except (MemoryError, _Timeout) as exc:
        return "MemoryError or timeout", type(exc).__name__
    except Exception as exc:  # noqa: BLE001 - the class of any exception is the point
        detail = f"{type(exc).__name__}: {str(exc)[:200]}"
        if case.param is None:
            return "refused a valid input", detail
        clear = isinstance(exc, ValueError | TypeError)
        if clear and case.param in str(exc):
            return "clear error", detail
        if clear and _raised_in_package(exc) and type(exc).__module__ != "numpy":
            return "vague error", detail
        return "traceback from internals", detail
    if case.param is not None:
        return "silently wrong", f"accepted, returned {type(result).__name__}"
    try:
        ok = bool(case.check(result))
    except Exception as exc:  # noqa: BLE001
        return "silently wrong", f"result unusable: {exc!r}"[:200]
    return ("right", "") if ok else ("silently wrong", f"returned {result!r}"[:200])


def count(cases=None) -> dict[str, int]:
    """The number of cases in each class of :data:`CLASSES`."""
    totals = dict.fromkeys(CLASSES, 0)
    for case in build_cases() if cases is None else cases:
        totals[classify(case)[0]] += 1
    return totals


CASES = build_cases()


@pytest.fixture(autouse=True, scope="module")
def _small_budget():
    ebantenna.set_memory_budget(BUDGET)
    yield
    ebantenna.set_memory_budget(None)


def test_at_least_a_thousand_cases_across_the_kinds():
    assert len(CASES) >= 1000
    assert len({case.name for case in CASES}) == len(CASES)
    assert sum(case.param is None for case in CASES) >= 150  # right answers checked


@pytest.mark.parametrize("case", CASES, ids=[case.name for case in CASES])
def test_every_outcome_is_a_clear_error_or_a_right_answer(case):
    outcome, detail = classify(case)
    assert outcome in ("clear error", "right"), f"{outcome}: {detail}"


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these cases cover, by the name before ``:`` (read by the inventory test)."""
    rows: dict[str, list[str]] = {}
    for case in CASES:
        surface = case.name.split(":")[0].split("[")[0].split(" ")[0]
        rows.setdefault(surface, []).append(case.name)
    return rows
