"""The input contract of the references behind the engines, and of a calibration's question.

:func:`~ebantenna.ml.backprop.train_epochs` and
:func:`~ebantenna.ml.mlp_base.training_optimizer` (the MLP's training loop and its optimiser),
:func:`~ebantenna.simulate.modes.direct_exponentials` and
:func:`~ebantenna.simulate.touched_object.signal_terms` (the simulator's references) and
:meth:`~ebantenna.study.recorded.calibration.Calibration.identifiable`. A bad input is refused
with a ValueError or TypeError naming the parameter; a good one is checked against a witness
the surface does not compute (a closed form, a loss evaluated apart, Adam's first step).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from ebantenna.fem import Supports, modal_analysis
from ebantenna.ml.backprop import glorot_uniform, loss_and_gradients, train_epochs
from ebantenna.ml.mlp_base import training_optimizer
from ebantenna.simulate import builtin_scene
from ebantenna.simulate.modes import direct_exponentials, free_probe_terms
from ebantenna.simulate.touched_object import object_terms, signal_terms
from ebantenna.study.recorded.calibration import Calibration

# ------------------------------------------------------------------ training loop
RNG = np.random.default_rng(0)
X = RNG.normal(size=(12, 2))
Y = np.eye(2)[(X[:, 0] > 0).astype(int)]
LAYERS = dict(activation="tanh", out_activation="softmax", alpha=1e-3)


class PlainStep:
    """Gradient descent by hand: the witness of what the loop hands its optimiser."""

    def __init__(self, rate):
        self.rate, self.seen = rate, []

    def update(self, params, grads):
        self.seen.append([g.copy() for g in grads])
        for p, g in zip(params, grads, strict=True):
            p -= self.rate * g


def _weights():
    return glorot_uniform([2, 3, 2], "tanh", np.random.default_rng(1))


TRAIN_BAD = [  # (id, changes, error, name)
    ("batch-zero", dict(batch_size=0), ValueError, "batch_size"),
    ("batch-float", dict(batch_size=4.0), TypeError, "batch_size"),
    ("epochs-negative", dict(n_epochs=-1), ValueError, "n_epochs"),
    ("epochs-text", dict(n_epochs="3"), TypeError, "n_epochs"),
    ("optimizer-none", dict(optimizer=None), TypeError, "optimizer"),
    ("rng-seed", dict(rng=0), TypeError, "rng"),
    ("end-not-callable", dict(end_of_epoch=True), TypeError, "end_of_epoch"),
]


@pytest.mark.parametrize("row", TRAIN_BAD, ids=[r[0] for r in TRAIN_BAD])
def test_train_epochs_refuses_bad_input(row):
    _, changes, error, name = row
    coefs, intercepts = _weights()
    args = {"optimizer": PlainStep(0.1), "batch_size": 4, "n_epochs": 2, **LAYERS, **changes}
    with pytest.raises(error, match=name):
        train_epochs(X, Y, coefs, intercepts, args.pop("optimizer"), **args)


def test_one_full_batch_epoch_is_one_gradient_step():
    coefs, intercepts = _weights()
    loss0, coef_grads, intercept_grads = loss_and_gradients(X, Y, coefs, intercepts, **LAYERS)
    expected = [w - 0.1 * g for w, g in zip([*coefs, *intercepts],
                                            [*coef_grads, *intercept_grads], strict=True)]
    losses = train_epochs(X, Y, coefs, intercepts, PlainStep(0.1), batch_size=len(X),
                          n_epochs=1, **LAYERS)
    assert losses == [loss0]  # the same operations on the same rows: the same bits
    for got, want in zip([*coefs, *intercepts], expected, strict=True):
        np.testing.assert_array_equal(got, want)
    assert train_epochs(X, Y, coefs, intercepts, PlainStep(0.1), batch_size=4, n_epochs=0,
                        **LAYERS) == []


OPTIMIZER_BAD = [  # (id, kwargs, error, name)
    ("name-sgd", dict(name="sgd"), ValueError, "name"),
    ("engine-numba", dict(engine="numba"), ValueError, "engine"),
    ("params-text", dict(params="abc"), TypeError, "params"),
    ("params-int-array", dict(params=[np.zeros(2, int)]), TypeError, "params"),
    ("rate-zero", dict(learning_rate=0.0), ValueError, "learning_rate"),
    ("rate-text", dict(learning_rate="0.1"), TypeError, "learning_rate"),
    ("momentum-above-one", dict(name="momentum", momentum=1.5), ValueError, "momentum"),
    ("nesterov-text", dict(name="momentum", nesterov="no"), TypeError, "nesterov"),
    ("beta1-one", dict(beta_1=1.0), ValueError, "beta_1"),
    ("beta2-negative", dict(beta_2=-0.1), ValueError, "beta_2"),
    ("epsilon-zero", dict(epsilon=0.0), ValueError, "epsilon"),
]


@pytest.mark.parametrize("engine", ["reference", "auto"])
@pytest.mark.parametrize("row", OPTIMIZER_BAD, ids=[r[0] for r in OPTIMIZER_BAD])
def test_training_optimizer_refuses_bad_input(row, engine):
    _, kwargs, error, name = row
    args = {"name": "adam", "params": [np.zeros(2)], "engine": engine, **kwargs}
    with pytest.raises(error, match=name):
        training_optimizer(**args)


@pytest.mark.parametrize("engine", ["reference", "auto"])
def test_adams_first_step_is_the_rate_against_the_gradients_sign(engine):
    # Adam's first step: m = (1 - b1) g and v = (1 - b2) g^2, the rate bias-corrected by
    # sqrt(1 - b2) / (1 - b1): the move is lr sign(g) but for eps against sqrt(v), so within
    # lr eps / (sqrt(1 - b2) |g|) of it (and rounding, 1e-15 of the unit-sized weights).
    start = np.array([1.0, -2.0, 0.5])
    g = np.array([3.0, -0.25, 1e-2])
    p = [start.copy()]
    opt = training_optimizer("adam", p, 0.1, engine=engine)
    opt.update(p, [g.copy()])
    bound = 0.1 * 1e-8 / (math.sqrt(1 - 0.999) * np.abs(g)) + 1e-15
    assert np.all(np.abs(p[0] - (start - 0.1 * np.sign(g))) <= bound)


# ------------------------------------------------------------------ damped exponentials
T = np.arange(64) / 64.0


@pytest.mark.parametrize(("row", "args", "error", "name"), [
    ("coef-list", (T, [[1 + 0j]], np.array([[2j]]), 100), TypeError, "coef"),
    ("t-int", (np.arange(4), np.ones((1, 1), complex), np.ones((1, 1), complex), 100),
     TypeError, "t"),
    ("shapes-differ", (T, np.ones((1, 1), complex), np.ones((1, 2), complex), 100),
     ValueError, "rate"),
    ("t-rows-differ", (np.zeros((2, 4)), np.ones((3, 1), complex), np.ones((3, 1), complex), 9),
     ValueError, "t"),
    ("max-elements-zero", (T, np.ones((1, 1), complex), np.ones((1, 1), complex), 0),
     ValueError, "max_elements"),
    ("max-elements-float", (T, np.ones((1, 1), complex), np.ones((1, 1), complex), 1e3),
     TypeError, "max_elements"),
])
def test_direct_exponentials_refuse_bad_input(row, args, error, name):
    with pytest.raises(error, match=name):
        direct_exponentials(*args)


@pytest.mark.parametrize("max_elements", [1, 10**6])
def test_direct_exponentials_are_damped_sines(max_elements):
    amp = np.array([[2.0, 0.5], [1.0, 0.0]], complex)
    a = np.array([[3.0, 0.5], [1.0, 2.0]])
    w = 2 * np.pi * np.array([[5.0, 11.0], [2.0, 7.0]])
    got = direct_exponentials(T, amp, -a + 1j * w, max_elements)
    want = np.einsum("sk,skn->sn", amp.real,
                     np.exp(-a[..., None] * T) * np.sin(w[..., None] * T))
    # a sum of two terms of size <= 2: a few ulps of each exponential and sine
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-14)


# ------------------------------------------------------------------ signal terms
SCENE = builtin_scene("ideal")
ONE = np.array([1.0])


@pytest.mark.parametrize(("row", "changes", "error", "name"), [
    ("scene-name", dict(scene="ideal"), TypeError, "scene"),
    ("contacts-list", dict(contacts=[0.2]), TypeError, "contacts"),
    ("contacts-nan", dict(contacts=np.array([math.nan])), ValueError, "contacts"),
    ("contacts-beyond-probe", dict(contacts=np.array([0.5])), ValueError, "contacts"),
    ("speeds-two", dict(speeds=np.array([1.0, 1.0])), ValueError, "speeds"),
    ("tilts-text", dict(tilts=np.array(["0"])), TypeError, "tilts"),
    ("materials-list", dict(materials=["brass"]), TypeError, "materials"),
    ("preloads-two", dict(preloads=np.array([1.0, 2.0])), ValueError, "preloads"),
    ("x-modes-text", dict(x_modes="yes"), TypeError, "x_modes"),
    ("progress-text", dict(show_progress="no"), TypeError, "show_progress"),
])
def test_signal_terms_refuse_bad_input(row, changes, error, name):
    args = {"scene": SCENE, "contacts": np.array([0.2]), "materials": np.array(["brass"]),
            "speeds": ONE, "tilts": np.zeros(1), **changes}
    with pytest.raises(error, match=name):
        signal_terms(**args)


@pytest.mark.parametrize(("row", "changes", "error", "name"), [
    ("scene-name", dict(scene="ideal"), TypeError, "scene"),
    ("contacts-nan", dict(contacts=np.array([math.nan])), ValueError, "contacts"),
    ("speeds-two", dict(speeds=np.array([1.0, 1.0])), ValueError, "speeds"),
    ("materials-list", dict(materials=["brass"]), TypeError, "materials"),
    ("preloads-two", dict(preloads=np.array([1.0, 2.0])), ValueError, "preloads"),
    ("x-modes-text", dict(x_modes="yes"), TypeError, "x_modes"),
    ("progress-text", dict(show_progress="no"), TypeError, "show_progress"),
])
def test_object_terms_refuse_bad_input(row, changes, error, name):
    args = {"scene": SCENE, "contacts": np.array([0.2]), "materials": np.array(["brass"]),
            "speeds": ONE, **changes}
    with pytest.raises(error, match=name):
        object_terms(**args)


def test_object_terms_on_a_pin_are_the_pinned_probes_modes():
    """The ideal scene's object is a rigid pin: X rings at the modes of the probe on its hinge
    and the pin (the finite-element model's own solve), below the scene's band."""
    x, timed, inverse = object_terms(SCENE, np.array([0.2, 0.2]), np.array(["brass"] * 2),
                                     np.array([1.0, 2.0]))
    res = modal_analysis(SCENE.probe, Supports(contact=0.2, hinge=SCENE.hinge),
                         n_elements=SCENE.n_elements, n_modes=SCENE.n_modes)
    want = res.frequencies[res.frequencies < SCENE.max_frequency]
    # the same model solved the same way: equal to a few roundings of the frequencies
    np.testing.assert_allclose(x.frequencies(), want, rtol=1e-13)
    np.testing.assert_allclose(x.amplitude[1], 2 * x.amplitude[0], rtol=1e-15)  # per speed
    assert timed == {} and list(inverse) == [0, 0]


def test_z_terms_are_the_free_cantilevers_modes():
    """Across the sweep plane the probe is a cantilever free at its tip (the ideal scene has no
    tip mass): ``f_n = (beta_n L)^2 / (2 pi L^2) sqrt(E I / (rho A))``."""
    p = SCENE.probe
    assert p.tip_mass == 0
    EI = p.youngs_modulus * math.pi / 64 * (p.outer_diameter**4 - p.inner_diameter**4)
    rhoA = p.density * math.pi / 4 * (p.outer_diameter**2 - p.inner_diameter**2)
    roots = np.array([1.8751040687, 4.6940911330, 7.8547574382])  # cos(b) cosh(b) = -1
    want = roots**2 / (2 * np.pi * p.length**2) * math.sqrt(EI / rhoA)
    _, z, timed, inverse = signal_terms(SCENE, np.array([0.2, 0.3, 0.2]),
                                        np.array(["brass"] * 3), np.ones(3), np.zeros(3))
    # Hermite cubic elements converge as h^4: the model's mesh is well inside 1e-5 relative
    np.testing.assert_allclose(z.frequencies()[:3], want, rtol=1e-5)
    assert timed == {} and list(inverse) == [0, 1, 0]  # equal contacts share one case


@pytest.mark.parametrize(("row", "changes", "error", "name"), [
    ("scene-name", dict(scene="ideal"), TypeError, "scene"),
    ("scene-probe", dict(scene=SCENE.probe), TypeError, "scene"),
    ("speeds-2d", dict(speeds=np.ones((1, 1))), ValueError, "speeds"),
    ("tilts-two-for-one", dict(tilts=np.ones(2)), ValueError, "tilts"),
])
def test_free_probe_terms_refuse_bad_input(row, changes, error, name):
    args = {"scene": SCENE, "speeds": ONE, "tilts": ONE, **changes}
    with pytest.raises(error, match=name):
        free_probe_terms(**args)


def test_free_probe_terms_are_the_free_probes_modes_damped_by_the_scene():
    """Z of a scene: the probe on its hinge alone (the finite-element model's own solve) below
    the scene's band, every mode at the structural damping effect's ratio, each row scaled by
    its signal's tilt times speed."""
    scene = SCENE.with_(effects=("structural_damping",))
    z = free_probe_terms(scene, np.array([1.0, 2.0]), np.array([0.5, 0.75]))
    res = modal_analysis(scene.probe, Supports(hinge=scene.hinge), n_elements=scene.n_elements,
                         n_modes=scene.n_modes)
    want = res.frequencies[res.frequencies < scene.max_frequency]
    # the same model solved the same way: equal to a few roundings of the frequencies
    np.testing.assert_allclose(z.frequencies(), want, rtol=1e-13)
    zeta = scene.effect("structural_damping").damping_ratio(scene.probe)
    assert zeta > 0 and np.all(z.zeta == zeta)
    np.testing.assert_allclose(z.amplitude[1], 3 * z.amplitude[0], rtol=1e-15)  # 1.5 / 0.5


# ------------------------------------------------------------------ calibration
def _calibration(not_identifiable):
    return Calibration(
        hinge_stiffness=50.0, log10_stiffness_sd=0.1, tip_mass=0.0, tip_mass_sd=1e-4,
        loss_factor=0.03, loss_factor_sd=0.002, contacts=np.array([0.1, 0.2]),
        measured_hz=np.array([30.0, 60.0]), fitted_hz=np.array([30.1, 59.9]), decay_used=2,
        intervals={"hinge_stiffness": (40.0, math.inf), "tip_mass": (0.0, 2e-4),
                   "loss_factor": (0.026, 0.034)},
        not_identifiable=not_identifiable)


@pytest.mark.parametrize(("row", "name"), [
    ("unknown", "stiffness"), ("none", None), ("list", ["tip_mass"]), ("int", 1),
], ids=lambda v: v if isinstance(v, str) else "")
def test_identifiable_names_a_parameter(row, name):
    with pytest.raises(ValueError, match="name"):
        _calibration({}).identifiable(name)


def test_identifiable_is_what_the_calibration_could_not_determine():
    cal = _calibration({"hinge_stiffness": "no upper bound: a clamp fits as well"})
    assert [cal.identifiable(n) for n in ("hinge_stiffness", "tip_mass", "loss_factor")] == [
        False, True, True]


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    return {
        "ebantenna.ml.backprop.train_epochs": [r[0] for r in TRAIN_BAD] + ["one-gradient-step"],
        "ebantenna.ml.mlp_base.training_optimizer": [r[0] for r in OPTIMIZER_BAD]
        + ["adam-first-step"],
        "ebantenna.simulate.modes.direct_exponentials": [
            "coef-list", "t-int", "shapes-differ", "t-rows-differ", "max-elements-zero",
            "max-elements-float", "damped-sines"],
        "ebantenna.simulate.modes.free_probe_terms": [
            "scene-name", "scene-probe", "speeds-2d", "tilts-two-for-one", "free-probe-damped"],
        "ebantenna.simulate.touched_object.object_terms": [
            "scene-name", "contacts-nan", "speeds-two", "materials-list", "preloads-two",
            "x-modes-text", "progress-text", "pinned-probe"],
        "ebantenna.simulate.touched_object.signal_terms": [
            "scene-name", "contacts-list", "contacts-nan", "contacts-beyond-probe", "speeds-two",
            "tilts-text", "materials-list", "preloads-two", "x-modes-text", "progress-text",
            "free-cantilever"],
        "Calibration.identifiable": ["unknown", "none", "list", "int", "not-determined"],
    }


def contract_exempt() -> dict[str, str]:
    """Public names that take no input from a user."""
    return {"ebantenna.ml.optimizers.Adam.learning_rate_at_step": "no argument"}
