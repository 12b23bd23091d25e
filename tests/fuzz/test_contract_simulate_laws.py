"""The input contract of the contact laws' public steps and of the modal terms.

The strike and the stick-slip take matrices, forces, coefficients and a march; the overtravel and
the step grid take the structure and the rates they are built from; the modal terms are read per
signal. Each gets bad inputs (a matrix that is not symmetric, a negative spring, a NaN speed, a
march the package does not have, a row beyond the signals, a duration of zero) and must refuse
each naming the parameter; a few results are checked against the closed form of one mass.
"""

from __future__ import annotations

import functools
import math
import os
import sys

import numpy as np
import scipy.linalg as spl
import scipy.signal as sps

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, row_tests  # noqa: E402

from ebantenna.fem.coupling import Rod, craig_bampton, probe_substructure, rod_substructure  # noqa: E402, E501
from ebantenna.probe import Probe  # noqa: E402
from ebantenna.simulate import builtin_scene  # noqa: E402
from ebantenna.simulate import friction_ode as F  # noqa: E402
from ebantenna.simulate import modes as MO  # noqa: E402
from ebantenna.simulate import stick_slip as S  # noqa: E402
from ebantenna.simulate import strikes as ST  # noqa: E402
from ebantenna.simulate import unilateral as U  # noqa: E402
from ebantenna.simulate.contact import PiecewiseSpring  # noqa: E402
from ebantenna.simulate.effects import LowPassFilter, read_through_dlpf  # noqa: E402
from ebantenna.simulate.modes import ModalTerms  # noqa: E402
from ebantenna.simulate.simulator import ChainStep, SignalBatch  # noqa: E402
from ebantenna.simulate.touched_object import (  # noqa: E402
    OBJECT_MODELS,
    ObjectModel,
    object_modes,
    pinned_modes,
)

NAN = math.nan
#: One mass of 1 kg striking a 1e4 N/m contact at 1 m/s, recorded 50 ms at 1 kHz.
ONE = dict(base=0, approach_speed=1.0, duration=0.05, fs=1000.0)


def _one_mass(**kw):
    return U.unilateral_response([[1.0]], [[0.0]], 0, 1e4, **{**ONE, **kw})


def _states():
    """The two states of 1 kg on 100 N/m pressed by a 300 N/m contact (20 rad/s closed)."""
    free, closed, _ = U.contact_states(np.eye(1), np.array([[100.0]]), np.zeros((1, 1)),
                                       np.ones(1), 300.0, np.ones(1))
    return [free, closed]


def _terms(preload=None, force=True):
    """One signal, one mode at 100 rad/s damped 0.1 (and a padded one), 2 N/s of contact force."""
    return ModalTerms(np.array([[100.0, 1.0]]), np.array([[0.1, 0.0]]), np.array([[1.0, 0.0]]),
                      np.array([[True, False]]),
                      np.array([[2.0, 0.0]]) if force else None, preload)


def _force_by_hand(t):
    """``F q'(0) / omega_d e^(-zeta omega t) sin(omega_d t)`` for the one mode of :func:`_terms`."""
    wd = 100.0 * math.sqrt(1 - 0.1**2)
    return 2.0 / wd * np.exp(-10.0 * t) * np.sin(wd * t)


def _stick_slip(**kw):
    args = dict(static_friction=1.0, kinetic_friction=1.0, duration=2.0, fs=100.0,
                velocity=[1.0])
    return S.stick_slip_response([[1.0]], [[100.0]], kw.pop("contact", 0),
                                 kw.pop("normal_force", 1.0), **{**args, **kw})


#: Two rows of accelerations at the DLPF's internal rate (8 kHz), 10 ms and one sample.
ACC = np.random.default_rng(5).normal(size=(2, 81))
#: The sample times at 1 kHz: whole internal samples.
WHEN = np.arange(10) / 1000.0
#: The chip's filter design at its default settings (second-order sections at 8 kHz).
SOS = LowPassFilter().sos


def _coulomb(**kw):
    args = dict(static_friction=1.0, kinetic_friction=1.0, duration=2.0, fs=100.0,
                displacement=[0.1])
    return F.coulomb_response([[1.0]], [[100.0]], kw.pop("tangential", 0),
                              kw.pop("normal_force", 1.0), **{**args, **kw})


@functools.cache
def _reductions():
    """The probe reduced at 0.2 m and a steel rod (the docstrings' examples)."""
    return (craig_bampton(probe_substructure(Probe(), 0.2, n_elements=40), 16),
            craig_bampton(rod_substructure(Rod("steel"), n_elements=16), 8))


def _strike_model(**kw):
    p, r = _reductions()
    args = dict(contact=0.2, contact_stiffness=1.8e5, preload=0.5, max_frequency=3000.0)
    return ST.strike_model(kw.pop("probe_reduction", p), kw.pop("rod_reduction", r),
                           **{**args, **kw})


def _strike_accelerations(**kw):
    args = dict(rate=8000.0, n_samples=9, max_events=200, method="blocks")
    return ST.strike_accelerations(kw.pop("models", [_strike_model()]), kw.pop("inverse", [0]),
                                   kw.pop("speeds", [1.0]), **{**args, **kw})


def _structure(**kw):
    """1 kg on 100 N/m and 2 N s/m, touching a 300 N/m contact (the docstring's example)."""
    args = dict(Minv=np.eye(1), K=np.array([[100.0]]), C=np.array([[2.0]]), c=np.ones(1),
                contact_stiffness=300.0, output=np.ones(1))
    return U.contact_states(**{**args, **kw})


def _coupled(**kw):
    """The probe arrested at 0.2 m on a steel rod (the docstring's example), or with ``kw``."""
    p, r = _reductions()
    args = dict(probe_reduction=p, rod_reduction=r, contact_stiffness=1.8e5,
                contact_loss_factor=0.0, max_frequency=480.0)
    return MO.coupled_arrest_modes(kw.pop("probe", Probe()), "clamped", 0.2, Rod("steel"),
                                   **{**args, **kw})


def _case(**kw):
    """The probe at 0.2 m on a steel rod (the docstrings' reductions) as one contact case of the
    ``ideal`` scene (clamped, 480 Hz), or with ``kw``."""
    from ebantenna.simulate.structure import ContactCase

    p, r = _reductions()
    args = dict(scene=builtin_scene("ideal"), probe=Probe(), contact=0.2, material="steel",
                preload=0.5, rod=Rod("steel"), probe_reduction=p, rod_reduction=r,
                stiffness=1.8e5, loss_factor=0.0)
    return ContactCase(**{**args, **kw})


def _filtered_by_hand():
    """One damped exponential (100 Hz, decaying at 50/s) through the DLPF: its closed form and
    the witness, SciPy's filter at the internal rate, over 800 internal samples."""
    dlpf = LowPassFilter()
    coef, rate = np.array([[1.0 + 0.0j]]), np.array([[-50.0 + 2j * math.pi * 100.0]])
    n = np.arange(800)
    u = np.imag(coef[0, 0] * np.exp(rate[0, 0] * n / dlpf.internal_rate))
    out_coef, out_rate = MO.filtered_exponentials(coef, rate, dlpf.sos, dlpf.internal_rate)
    closed = np.imag(np.exp(np.multiply.outer(n / dlpf.internal_rate, out_rate[0])) @ out_coef[0])
    return closed, sps.sosfilt(dlpf.sos, u)


def _strike_law():
    """The one-mass strike's law, its first state and its steps (as unilateral_response)."""
    options = dict(max_events=10, on_max_events="raise", time_tolerance=1e-12,
                   return_states=False)
    law, grid, _ = U.strike_law((np.eye(1), np.zeros((1, 1)), np.zeros((1, 1)), np.ones(1),
                                 np.ones(1), np.ones(1)), 1e4, 0.0, 1.0, 1000.0, 0.05, options)
    return (law, *law.first_touch(1.0), grid[3])


def _hertz_law():
    """The one-mass strike through a Hertz law's chords."""
    from ebantenna.simulate.contact import CrossedCylinders, HertzInSeries

    spring = HertzInSeries(CrossedCylinders(0.004, 0.006, 3.5e9), 2.7e5).piecewise(0.01, 5.0)
    options = dict(max_events=10, on_max_events="raise", time_tolerance=1e-12,
                   return_states=False)
    law, _, _ = U.strike_law((np.eye(1), np.zeros((1, 1)), np.zeros((1, 1)), np.ones(1),
                              np.ones(1), np.ones(1)), spring, 0.0, 1.0, 1000.0, 0.05, options)
    return law


def _stick_slip_law():
    """Coulomb's oscillator of stick_slip_response's example, as its law."""
    states = S.friction_states(np.eye(1), np.array([[100.0]]), np.zeros((1, 1)), np.eye(1), 0,
                               0, 1.0, 1.0)
    grid = U.step_grid(list(states.values()), 100.0, 2.0, U.STEPS_PER_PERIOD)
    return S.StickSlipLaw(states, 0, grid, hold_limit=1.0, max_events=100,
                          time_tolerance=1e-12)


class _Resting(U.SwitchedSystem):
    """The smallest law: one state that never ends (each step the state's own propagation)."""

    def state(self, key):
        return key

    def advance(self, x, key, t0, t1, crosses=False):
        return key.step(x, t1 - t0), key


def _new_strike_law(**kw):
    """A StrikeLaw of the one-mass strike's states, built as strike_law builds it."""
    free, closed, pen = _structure()
    args = dict(free=free, closed=closed, pen=pen, base=np.ones(1), stop_time=0.0,
                grid=(0.001, 1, 51, 50), max_events=10, on_max_events="raise",
                time_tolerance=1e-12, return_states=False)
    args.update(kw)
    return U.StrikeLaw(args.pop("free"), args.pop("closed"), args.pop("pen"), args.pop("base"),
                       args.pop("stop_time"), args.pop("grid"), **args)


def _new_stick_slip_law(**kw):
    states = S.friction_states(np.eye(1), np.array([[100.0]]), np.zeros((1, 1)), np.eye(1), 0,
                               0, 1.0, 1.0)
    args = dict(states=states, contact=0, grid=(0.01, 1, 201, 200), hold_limit=1.0,
                max_events=100, time_tolerance=1e-12)
    args.update(kw)
    return S.StickSlipLaw(args.pop("states"), args.pop("contact"), args.pop("grid"), **args)


def _friction_states(**kw):
    args = dict(M=np.eye(1), K=np.array([[100.0]]), C=np.zeros((1, 1)), Minv=np.eye(1), b=0,
                o=0, hold=1.0, slide=1.0)
    return S.friction_states(**{**args, **kw})


def _model(**kw):
    args = dict(name="mine", axis="x", effect=None, build=lambda case: case)
    return ObjectModel(**{**args, **kw})


def _batch(**kw):
    one = np.ones(1)
    args = dict(scene=builtin_scene("paper"), contacts=0.25 * one,
                materials=np.array(["brass"], dtype=object), speeds=one, tilts=0.1 * one,
                seeds=[3])
    return SignalBatch(**{**args, **kw})


def _cases(which, **kw):
    scene = builtin_scene("ideal")
    args = dict(scene=scene, contacts=np.array([0.2]), materials=np.array(["brass"]),
                show_progress=False)
    if which is object_modes:
        scene = builtin_scene("paper")
        args.update(scene=scene, preloads=np.array([scene.effect("object_modes").preload]))
    return which(**{**args, **kw})


def _one_arrest_mode():
    """One mode at 100 rad/s whose tip starts at 2 x 0.5 = 1 m/s per unit sweep speed."""
    return MO.ArrestModes(np.array([100.0]), np.array([2.0]), np.array([0.5]), None)


def _axis_batch(inverse=0):
    """A batch of the paper scene as the responses step has it: which case each signal uses."""
    batch = _batch()
    batch.inverse = np.array([inverse])
    return batch


def _batch_rate_and_timed_rate():
    """``batch_rate`` of a batch, and ``timed_rate`` of its scene, instants and filter."""
    batch = _axis_batch()
    return (ST.batch_rate(batch, "inverse"),
            ST.timed_rate(batch.scene, batch.when, batch.chip_filter))


def all_rows():
    u, s = "ebantenna.simulate.unilateral.", "ebantenna.simulate.stick_slip."
    t = "ebantenna.simulate.touched_object."
    d = "ebantenna.simulate.effects.sensor.read_through_dlpf"
    f, m = "ebantenna.simulate.friction_ode.", "ebantenna.simulate.modes."
    st, sim = "ebantenna.simulate.strikes.", "ebantenna.simulate.simulator."
    t_fine = np.linspace(0.0, 0.1, 201)
    dlpf = LowPassFilter()
    no_friction = builtin_scene("ideal")
    return [
        Row(d, "dlpf-str", lambda: read_through_dlpf("dlpf", ACC, 8000.0, WHEN), ("dlpf",)),
        Row(d, "acc-1d", lambda: read_through_dlpf(None, ACC[0], 8000.0, WHEN), ("acc",)),
        Row(d, "acc-nan", lambda: read_through_dlpf(None, ACC * NAN, 8000.0, WHEN), ("acc",)),
        Row(d, "rate-zero", lambda: read_through_dlpf(None, ACC, 0.0, WHEN), ("rate",)),
        Row(d, "rate-not-the-filter's", lambda: read_through_dlpf(dlpf, ACC, 1000.0, WHEN),
            ("rate",)),
        Row(d, "when-rows", lambda: read_through_dlpf(None, ACC, 8000.0, np.zeros((3, 10))),
            ("when",)),
        Row(d, "when-3d", lambda: read_through_dlpf(None, ACC, 8000.0, np.zeros((2, 2, 2))),
            ("when",)),
        # at whole internal samples the reading is the filter's output there, exactly: the
        # witness is SciPy's filter at the internal rate, every eighth sample
        Row(d, "filtered-at-whole-samples", lambda: read_through_dlpf(dlpf, ACC, 8000.0, WHEN),
            same=lambda r: np.array_equal(r, sps.sosfilt(dlpf.sos, ACC)[:, ::8][:, :10])),
        Row(d, "unfiltered-ramp", lambda: read_through_dlpf(
            None, np.arange(16.0)[None, :], 8000.0, np.array([0.0, 0.001, 0.0005])),
            same=lambda r: r.tolist() == [[0.0, 8.0, 4.0]]),
        Row(m + "filtered_exponentials", "coef-1d",
            lambda: MO.filtered_exponentials(np.ones(3), np.ones(3), SOS, 8000.0), ("coef",)),
        Row(m + "filtered_exponentials", "rate-nan",
            lambda: MO.filtered_exponentials(np.ones((1, 2)), np.array([[NAN, 1.0]]), SOS, 8000.0),
            ("rate",)),
        Row(m + "filtered_exponentials", "rate-shape",
            lambda: MO.filtered_exponentials(np.ones((1, 2)), np.ones((1, 3)), SOS, 8000.0),
            ("rate",)),
        Row(m + "filtered_exponentials", "coef-str",
            lambda: MO.filtered_exponentials(np.array([["a"]]), np.ones((1, 1)), SOS, 8000.0),
            ("coef",)),
        Row(m + "filtered_exponentials", "sos-one-section-of-5",
            lambda: MO.filtered_exponentials(np.ones((1, 2)), np.ones((1, 2)), SOS[:, :5], 8000.0),
            ("sos",)),
        Row(m + "filtered_exponentials", "sos-nan",
            lambda: MO.filtered_exponentials(np.ones((1, 2)), np.ones((1, 2)), SOS * NAN, 8000.0),
            ("sos",)),
        Row(m + "filtered_exponentials", "internal_rate-zero",
            lambda: MO.filtered_exponentials(np.ones((1, 2)), np.ones((1, 2)), SOS, 0.0),
            ("internal_rate",)),
        # the closed form is the filter's recursion exactly; SciPy's rounding grows at most by
        # one eps of the signal (of size 1) per sample, over 800 samples
        Row(m + "filtered_exponentials", "one-exponential-against-sosfilt", _filtered_by_hand,
            same=lambda r: np.abs(r[0] - r[1]).max() < 64 * 800 * np.finfo(float).eps),
        Row(s + "friction_accelerations", "scene-without-coulomb_friction",
            lambda: S.friction_accelerations(no_friction, [], [], [], rate=8000.0, n_samples=9),
            ("coulomb_friction",)),
        Row(s + "friction_accelerations", "rate-zero",
            lambda: S.friction_accelerations(no_friction, [], [], [], rate=0.0, n_samples=9),
            ("rate",)),
        Row(s + "friction_accelerations", "n_samples-one",
            lambda: S.friction_accelerations(no_friction, [], [], [], rate=8000.0, n_samples=1),
            ("n_samples",)),
        Row(u + "unilateral_response", "mass-not-symmetric", lambda: U.unilateral_response(
            [[1.0, 2.0], [0.0, 1.0]], np.zeros((2, 2)), 0, 1e4, **ONE), ("mass",)),
        Row(u + "unilateral_response", "contact_stiffness-negative", lambda: U.unilateral_response(
            [[1.0]], [[0.0]], 0, -1e4, **ONE), ("contact_stiffness",)),
        Row(u + "unilateral_response", "approach_speed-nan",
            lambda: _one_mass(approach_speed=NAN), ("approach_speed",)),
        Row(u + "unilateral_response", "contact-beyond", lambda: U.unilateral_response(
            [[1.0]], [[0.0]], 3, 1e4, **ONE), ("contact",)),
        Row(u + "unilateral_response", "method-unknown", lambda: _one_mass(method="rk4"),
            ("method",)),
        # the mass leaves the spring after half its period, pi sqrt(m / k) = pi / 100 s, at the
        # speed it came with; the event is placed within time_tolerance (1e-12 s) of the root,
        # and the propagation's rounding over 32 steps moves it by far less than 1e-9 s
        Row(u + "unilateral_response", "one-mass-by-hand", _one_mass,
            same=lambda r: len(r.events) == 1 and r.events[0].kind == "separation"
            and abs(r.events[0].time - math.pi / 100) < 1e-9
            and abs(r.events[0].velocity + 1.0) < 1e-9),
        Row(u + "preload_overtravel", "free-structure", lambda: U.preload_overtravel(
            np.zeros((1, 1)), np.ones(1), 100.0, 1.0), ("preload",)),
        Row(u + "preload_overtravel", "contact_stiffness-zero", lambda: U.preload_overtravel(
            np.array([[100.0]]), np.ones(1), 0.0, 1.0), ("contact_stiffness",)),
        Row(u + "preload_overtravel", "preload-nan", lambda: U.preload_overtravel(
            np.array([[100.0]]), np.ones(1), 100.0, NAN), ("preload",)),
        Row(u + "preload_overtravel", "c-wrong-length", lambda: U.preload_overtravel(
            np.array([[100.0]]), np.ones(2), 100.0, 1.0), ("c",)),
        # 1 N on the contact spring (100 N/m) in series with the structure (100 N/m): 1/50 m
        Row(u + "preload_overtravel", "in-series-by-hand", lambda: U.preload_overtravel(
            np.array([[100.0]]), np.ones(1), 100.0, 1.0),
            same=lambda r: math.isclose(r, 0.02, rel_tol=4 * np.finfo(float).eps)),
        Row(u + "step_grid", "fs-negative", lambda: U.step_grid(_states(), -1.0, 0.05, 16),
            ("fs",)),
        Row(u + "step_grid", "duration-zero", lambda: U.step_grid(_states(), 1000.0, 0.0, 16),
            ("duration",)),
        Row(u + "step_grid", "steps_per_period-zero",
            lambda: U.step_grid(_states(), 1000.0, 0.05, 0), ("steps_per_period",)),
        Row(u + "step_grid", "states-empty", lambda: U.step_grid([], 1000.0, 0.05, 16),
            ("states",)),
        # 16 steps of the closed state's period (2 pi / 20 s) are longer than 1 ms: the step is
        # the sample interval; 51 samples over 50 ms, both ends included
        Row(u + "step_grid", "by-hand", lambda: U.step_grid(_states(), 1000.0, 0.05, 16),
            same=lambda r: r == (0.001, 1, 51, 50)),
        Row(s + "check_coefficients", "kinetic-above-static",
            lambda: S.check_coefficients(0.3, 0.4), ("kinetic_friction",)),
        Row(s + "check_coefficients", "static-negative",
            lambda: S.check_coefficients(-0.1, 0.0), ("static_friction",)),
        Row(s + "check_coefficients", "static-str", lambda: S.check_coefficients("0.5", 0.4),
            ("static_friction",)),
        Row(s + "check_coefficients", "as-given", lambda: S.check_coefficients(0.5, 0.4),
            same=lambda r: r == (0.5, 0.4)),
        Row(s + "stick_slip_response", "contact-beyond", lambda: _stick_slip(contact=1),
            ("contact",)),
        Row(s + "stick_slip_response", "normal_force-negative",
            lambda: _stick_slip(normal_force=-1.0), ("normal_force",)),
        Row(s + "stick_slip_response", "kinetic-above-static",
            lambda: _stick_slip(kinetic_friction=2.0), ("kinetic_friction",)),
        Row(s + "stick_slip_response", "method-unknown", lambda: _stick_slip(method="rk4"),
            ("method",)),
        # Coulomb's oscillator loses 2 mu N / k = 2 cm of amplitude every half period and sticks
        # where the spring no longer overcomes mu_s N (the docstring's example)
        Row(s + "stick_slip_response", "oscillator-by-hand", _stick_slip,
            same=lambda r: [kind for _, kind in r.events]
            == ["slip+", "slip-", "slip+", "slip-", "slip+", "slip-", "stick"]),
        Row(f + "coulomb_response", "mass-not-symmetric", lambda: F.coulomb_response(
            [[1.0, 2.0], [0.0, 1.0]], np.zeros((2, 2)), 0, 1.0, static_friction=1.0,
            kinetic_friction=1.0, duration=1.0, fs=100.0), ("mass",)),
        Row(f + "coulomb_response", "tangential-beyond", lambda: _coulomb(tangential=4),
            ("tangential",)),
        Row(f + "coulomb_response", "normal_force-nan", lambda: _coulomb(normal_force=NAN),
            ("normal_force",)),
        Row(f + "coulomb_response", "surface_speed-inf",
            lambda: _coulomb(surface_speed=math.inf), ("surface_speed",)),
        Row(f + "coulomb_response", "kinetic-above-static",
            lambda: _coulomb(kinetic_friction=2.0), ("kinetic_friction",)),
        # released from 10 cm against mu N = 1 N on 100 N/m: 4 cm of amplitude lost per cycle,
        # stuck within mu_s N / k = 1 cm of rest (the docstring's example); the integrator's
        # rtol of 1e-10 places each turning point far within 1e-6 m
        Row(f + "coulomb_response", "oscillator-by-hand", _coulomb,
            same=lambda r: [e.kind for e in r.events]
            == ["slip-", "slip+", "slip-", "slip+", "slip-", "stick"]
            and np.allclose([e.position for e in r.events],
                            [0.1, -0.08, 0.06, -0.04, 0.02, 0.0], rtol=0, atol=1e-6)),
        Row(m + "coupled_arrest_modes", "probe-int", lambda: _coupled(probe=5), ("probe",)),
        Row(m + "coupled_arrest_modes", "max_frequency-nan",
            lambda: _coupled(max_frequency=NAN), ("max_frequency",)),
        Row(m + "coupled_arrest_modes", "max_frequency-beyond-the-reductions",
            lambda: _coupled(max_frequency=1e6), ("max_frequency",)),
        Row(m + "coupled_arrest_modes", "contact_stiffness-negative",
            lambda: _coupled(contact_stiffness=-1.0), ("contact_stiffness",)),
        Row(m + "coupled_arrest_modes", "contact_loss_factor-nan",
            lambda: _coupled(contact_loss_factor=NAN), ("contact_loss_factor",)),
        Row(u + "contact_states", "K-not-symmetric",
            lambda: _structure(K=np.array([[1.0, 2.0], [0.0, 1.0]])), ("K",)),
        Row(u + "contact_states", "C-wrong-size", lambda: _structure(C=np.zeros((2, 2))),
            ("C",)),
        Row(u + "contact_states", "Minv-nan", lambda: _structure(Minv=np.array([[NAN]])),
            ("Minv",)),
        Row(u + "contact_states", "c-wrong-length", lambda: _structure(c=np.ones(2)), ("c",)),
        Row(u + "contact_states", "output-index-beyond", lambda: _structure(output=3),
            ("output",)),
        Row(u + "contact_states", "contact_stiffness-zero",
            lambda: _structure(contact_stiffness=0.0), ("contact_stiffness",)),
        # closed: M q'' = -(K + k_c) q - C q' - k_c s, every entry an integer
        Row(u + "contact_states", "closed-by-hand", lambda: _structure()[1].A,
            same=lambda A: np.array_equal(A, [[0, 1, 0, 0], [-400, -2, -300, 0],
                                              [0, 0, 0, 1], [0, 0, 0, 0]])),
        Row(u + "check_structure", "K-nan", lambda: U.check_structure(
            np.eye(1), [[NAN]], np.zeros((1, 1)), np.ones(1), np.ones(1)), ("K",)),
        Row(u + "check_structure", "c-index", lambda: U.check_structure(
            np.eye(2), np.eye(2), np.zeros((2, 2)), 1, 0),
            same=lambda r: r[3].tolist() == [0.0, 1.0] and r[4].tolist() == [1.0, 0.0]),
        Row(u + "segment_states", "spring-float", lambda: U.segment_states(
            np.eye(1), np.array([[100.0]]), np.zeros((1, 1)), np.ones(1), 300.0, np.ones(1)),
            ("spring",)),
        Row(u + "segment_states", "K-wrong-size", lambda: U.segment_states(
            np.eye(1), np.eye(2), np.zeros((1, 1)), np.ones(1), PiecewiseSpring.linear(300.0),
            np.ones(1)), ("C",)),
        # one chord of slope 300 N/m through 0: the linear contact's closed state
        Row(u + "segment_states", "one-chord-is-the-linear-contact", lambda: U.segment_states(
            np.eye(1), np.array([[100.0]]), np.array([[2.0]]), np.ones(1),
            PiecewiseSpring.linear(300.0), np.ones(1))[1][0].A,
            same=lambda A: np.array_equal(A, _structure()[1].A)),
        Row(st + "check_reduction", "substructure", lambda: ST.check_reduction(
            "probe_reduction", _reductions()[0].substructure), ("probe_reduction",)),
        Row(st + "check_reduction", "a-reduction", lambda: ST.check_reduction(
            "probe_reduction", _reductions()[0]), same=lambda r: r is None),
        Row(st + "reduced_body", "reduction-str", lambda: ST.reduced_body("probe", 3000.0),
            ("reduction",)),
        Row(st + "reduced_body", "max_frequency-negative",
            lambda: ST.reduced_body(_reductions()[0], -1.0), ("max_frequency",)),
        # the probe at 0.2 m keeps 8 fixed-interface modes below 3 kHz, and its interface
        Row(st + "reduced_body", "probe-below-3-kHz",
            lambda: ST.reduced_body(_reductions()[0], 3000.0),
            same=lambda r: [a.shape for a in r] == [(9, 9), (9, 9), (r[2].shape[0], 9), (9, 9)]),
        Row(st + "strike_model", "rod_reduction-None",
            lambda: _strike_model(rod_reduction=None), ("rod_reduction",)),
        Row(st + "strike_model", "contact-negative", lambda: _strike_model(contact=-0.2),
            ("contact",)),
        Row(st + "strike_model", "contact_stiffness-nan",
            lambda: _strike_model(contact_stiffness=NAN), ("contact_stiffness",)),
        Row(st + "strike_model", "preload-negative", lambda: _strike_model(preload=-0.5),
            ("preload",)),
        Row(st + "strike_model", "max_frequency-zero", lambda: _strike_model(max_frequency=0.0),
            ("max_frequency",)),
        # probe: 8 modes below 3 kHz and the interface; rod: 2 and the interface
        Row(st + "strike_model", "sizes", _strike_model,
            same=lambda m: m.structure.mass.shape == (12, 12) and m.preload == 0.5),
        Row(st + "timed_rate", "scene-str", lambda: ST.timed_rate("paper", WHEN, None),
            ("scene",)),
        Row(st + "timed_rate", "when-nan", lambda: ST.timed_rate(
            builtin_scene("paper"), np.array([0.0, NAN]), None), ("when",)),
        Row(st + "timed_rate", "dlpf-str", lambda: ST.timed_rate(
            builtin_scene("paper"), WHEN, "dlpf"), ("dlpf",)),
        # without the DLPF: 8 fs; the samples reach one past the record's last reading
        Row(st + "timed_rate", "unfiltered", lambda: ST.timed_rate(
            builtin_scene("paper"), np.arange(1000) / 1000.0, None),
            same=lambda r: r == (8000.0, 7994)),
        Row(st + "batch_rate", "batch-str", lambda: ST.batch_rate("batch"), ("batch",)),
        # a batch without a field the caller reads is refused by name
        Row(st + "batch_rate", "batch-without-tilts",
            lambda: ST.batch_rate(_axis_batch(), "tilts", "no_such_field"), ("batch",)),
        Row(st + "batch_rate", "axis-batch", _batch_rate_and_timed_rate,
            same=lambda r: r[0] == r[1]),
        Row(st + "strike_axis", "batch-str", lambda: ST.strike_axis("batch", []), ("batch",)),
        Row(st + "strike_axis", "models-not-strike-models",
            lambda: ST.strike_axis(_axis_batch(), ["model"]), ("models",)),
        Row(s + "friction_axis", "batch-str", lambda: S.friction_axis("batch", []), ("batch",)),
        Row(s + "friction_axis", "scene-without-coulomb_friction",
            lambda: S.friction_axis(_axis_batch(), []), ("coulomb_friction",)),
        Row(st + "strike_accelerations", "rate-zero", lambda: _strike_accelerations(rate=0.0),
            ("rate",)),
        Row(st + "strike_accelerations", "n_samples-one",
            lambda: _strike_accelerations(n_samples=1), ("n_samples",)),
        Row(st + "strike_accelerations", "max_events-zero",
            lambda: _strike_accelerations(max_events=0), ("max_events",)),
        Row(st + "strike_accelerations", "method-unknown",
            lambda: _strike_accelerations(method="rk4"), ("method",)),
        Row(st + "strike_accelerations", "speeds-nan",
            lambda: _strike_accelerations(speeds=[NAN]), ("speeds",)),
        Row(st + "strike_accelerations", "inverse-beyond",
            lambda: _strike_accelerations(inverse=[1]), ("inverse",)),
        Row(st + "strike_accelerations", "inverse-float",
            lambda: _strike_accelerations(inverse=[0.0]), ("inverse",)),
        Row(st + "strike_accelerations", "models-str",
            lambda: _strike_accelerations(models=["strike"]), ("models",)),
        Row(s + "friction_model_of", "case-str", lambda: S.friction_model_of("case"), ("case",)),
        # the case's reduction, preload and max_frequency, as friction_model takes them
        Row(s + "friction_model_of", "as-friction_model", lambda: S.friction_model_of(_case()),
            same=lambda m: np.array_equal(m.mass, S.friction_model(
                _reductions()[0], 0.5, 480.0).mass) and m.normal_force == 0.5),
        Row(st + "strike_model_of", "case-str", lambda: ST.strike_model_of(3), ("case",)),
        # without hertz_contact: the linearised spring, as strike_model takes it
        Row(st + "strike_model_of", "as-strike_model", lambda: ST.strike_model_of(_case()),
            same=lambda m: np.array_equal(m.structure.stiffness, _strike_model(
                max_frequency=480.0).structure.stiffness) and m.contact_stiffness == 1.8e5),
        Row(m + "coupled_modes_of", "case-str", lambda: MO.coupled_modes_of(None), ("case",)),
        # the case's bodies, reductions and spring, as coupled_arrest_modes takes them
        Row(m + "coupled_modes_of", "as-coupled_arrest_modes",
            lambda: MO.coupled_modes_of(_case()),
            same=lambda a: np.array_equal(a.omega, _coupled().omega)),
        Row("ebantenna.simulate.structure.check_case", "case-dict",
            lambda: __import__("ebantenna.simulate.structure", fromlist=["x"]).check_case({}),
            ("case",)),
        Row("ebantenna.simulate.structure.check_case", "a-case",
            lambda: __import__("ebantenna.simulate.structure", fromlist=["x"]).check_case(
                _case()), same=lambda r: r is None),
        Row(s + "friction_model", "probe_reduction-str",
            lambda: S.friction_model("probe", 0.5, 3000.0), ("probe_reduction",)),
        Row(s + "friction_model", "max_frequency-nan",
            lambda: S.friction_model(_reductions()[0], 0.5, NAN), ("max_frequency",)),
        Row(s + "friction_model", "preload-zero",
            lambda: S.friction_model(_reductions()[0], 0.0, 3000.0), ("preload",)),
        Row(u + "march_step_by_step", "system-str",
            lambda: U.march_step_by_step("law", np.zeros(4), None, 10), ("system",)),
        Row(u + "march_step_by_step", "n_steps-negative",
            lambda: U.march_step_by_step(*_strike_law()[:3], -1), ("n_steps",)),
        # the one-mass strike leaves the spring after pi / 100 s (as unilateral_response's row)
        Row(u + "march_step_by_step", "one-mass-by-hand", lambda: (
            lambda law, x, key, n: (U.march_step_by_step(law, x, key, n), law.events)[1])(
                *_strike_law()),
            same=lambda ev: len(ev) == 1 and abs(ev[0].time - math.pi / 100) < 1e-9),
        Row(u + "StrikeLaw.first_touch", "approach_speed-zero",
            lambda: _strike_law()[0].first_touch(0.0), ("approach_speed",)),
        Row(u + "StrikeLaw.first_touch", "at-the-touch", lambda: _strike_law()[1],
            same=lambda x: x.tolist() == [0.0, 1.0, 0.0, 0.0]),  # stopped at once: q' = r v0
        Row(u + "StrikeLaw.stop_servo", "x-short",
            lambda: _strike_law()[0].stop_servo(np.zeros(3)), ("x",)),
        # the servo's speed passes to the structure, q' += r s', and the servo rests
        Row(u + "StrikeLaw.stop_servo", "by-hand",
            lambda: _strike_law()[0].stop_servo(np.array([0.0, 0.5, 0.1, 2.0])),
            same=lambda x: x.tolist() == [0.0, 2.5, 0.1, 0.0]),
        Row(u + "StrikeLaw.switch", "st-not-the-law's",
            lambda: _strike_law()[0].switch(_structure()[1], np.zeros(4), 0.0), ("st",)),
        Row(u + "StrikeLaw.switch", "closed-to-free", lambda: (
            lambda law: (law.switch(law.closed, np.zeros(4), 0.01) is law.free,
                         law.events[-1].kind))(_strike_law()[0]),
            same=lambda r: r == (True, "separation")),
        Row(u + "StrikeLaw.advance", "t1-before-t0", lambda: (
            lambda law, x, key, n: law.advance(x, key, 0.002, 0.001))(*_strike_law()), ("t1",)),
        Row(u + "StrikeLaw.advance", "t1-nan", lambda: (
            lambda law, x, key, n: law.advance(x, key, 0.0, NAN))(*_strike_law()), ("t1",)),
        # closing at 1 m/s on 1e4 N/m: after 1 ms, p = sin(100 t) / 100 m
        Row(u + "StrikeLaw.advance", "one-step-by-hand", lambda: (
            lambda law, x, key, n: law.advance(x, key, 0.0, 0.001))(*_strike_law()),
            same=lambda r: abs(r[0][0] - math.sin(0.1) / 100) < 1e-15),
        Row(u + "HertzStrikeLaw.advance", "t1-before-t0",
            lambda: _hertz_law().advance(np.zeros(4), _hertz_law().closed, 0.002, 0.001),
            ("t1",)),
        Row(s + "StickSlipLaw.start", "velocity-long",
            lambda: _stick_slip_law().start(np.ones(2)), ("velocity",)),
        Row(s + "StickSlipLaw.start", "from-rest-it-sticks",
            lambda: _stick_slip_law().start(np.zeros(1))[1], same=lambda name: name == "stick"),
        Row(s + "StickSlipLaw.state", "key-unknown", lambda: _stick_slip_law().state("slide"),
            ("key",)),
        Row(s + "StickSlipLaw.state", "the-stick", lambda: (
            lambda law: law.state("stick") is law.stick)(_stick_slip_law()),
            same=lambda r: r is True),
        Row(s + "StickSlipLaw.switch", "name-unknown",
            lambda: _stick_slip_law().switch("slide", np.zeros(4), 0.0), ("name",)),
        Row(s + "StickSlipLaw.switch", "x-short",
            lambda: _stick_slip_law().switch("stick", np.zeros(3), 0.0), ("x",)),
        Row(s + "StickSlipLaw.advance", "t1-before-t0",
            lambda: _stick_slip_law().advance(np.zeros(4), "stick", 1.0, 0.5), ("t1",)),
        Row(u + "check_step", "backwards", lambda: U.check_step(1.0, 0.5), ("t1",)),
        Row(u + "check_step", "nowhere", lambda: U.check_step(1.0, 1.0),
            same=lambda r: r is None),
        Row(u + "check_state", "nan", lambda: U.check_state("x", np.array([NAN, 0.0]), 2),
            ("x",)),
        Row(u + "check_state", "a-state", lambda: U.check_state("x", np.zeros(4), 4),
            same=lambda r: r is None),
        Row(u + "SwitchedSystem", "h-zero", lambda: _Resting(0.0, 1, 10), ("h",)),
        Row(u + "SwitchedSystem", "sub-zero", lambda: _Resting(0.001, 0, 10), ("sub",)),
        Row(u + "SwitchedSystem", "n_samples-float", lambda: _Resting(0.001, 1, 10.5),
            ("n_samples",)),
        Row(u + "SwitchedSystem", "n_states-zero", lambda: _Resting(0.001, 1, 10, 0),
            ("n_states",)),
        # a state at rest stays at rest: the march records zeros at every sample
        Row(u + "SwitchedSystem", "at-rest", lambda: (
            lambda law: (U.march_step_by_step(law, np.zeros(4), _structure()[0], 9), law.acc)[1])(
                _Resting(0.001, 1, 10)), same=lambda acc: acc.tolist() == [0.0] * 10),
        Row(u + "StrikeLaw", "free-str", lambda: _new_strike_law(free="free"), ("free",)),
        Row(u + "StrikeLaw", "pen-short", lambda: _new_strike_law(pen=np.zeros(3)), ("pen",)),
        Row(u + "StrikeLaw", "stop_time-negative", lambda: _new_strike_law(stop_time=-1.0),
            ("stop_time",)),
        Row(u + "StrikeLaw", "grid-list", lambda: _new_strike_law(grid=[0.001, 1, 51, 50]),
            ("grid",)),
        Row(u + "StrikeLaw", "on_max_events-ignore",
            lambda: _new_strike_law(on_max_events="ignore"), ("on_max_events",)),
        Row(u + "StrikeLaw", "time_tolerance-zero",
            lambda: _new_strike_law(time_tolerance=0.0), ("time_tolerance",)),
        Row(u + "StrikeLaw", "base-nan", lambda: _new_strike_law(base=np.array([NAN])),
            ("base",)),
        Row(u + "StrikeLaw", "as-built", _new_strike_law,
            same=lambda law: law.state(law.closed) is law.closed and law.acc.size == 51),
        Row(u + "StrikeLaw.state", "the-key-itself", lambda: (
            lambda law: law.state(law.free) is law.free)(_new_strike_law()),
            same=lambda r: r is True),
        Row(u + "HertzStrikeLaw", "spring-float", lambda: U.HertzStrikeLaw(
            _structure()[0], [_structure()[1]], _structure()[2], np.ones(1), 0.0,
            (0.001, 1, 51, 50), 300.0, max_events=10, on_max_events="raise",
            time_tolerance=1e-12, return_states=False), ("spring",)),
        Row(u + "HertzStrikeLaw", "segments-one-too-many", lambda: U.HertzStrikeLaw(
            _structure()[0], [_structure()[1]] * 2, _structure()[2], np.ones(1), 0.0,
            (0.001, 1, 51, 50), PiecewiseSpring.linear(300.0), max_events=10,
            on_max_events="raise", time_tolerance=1e-12, return_states=False), ("segments",)),
        Row(s + "StickSlipLaw", "states-list", lambda: _new_stick_slip_law(states=[]),
            ("states",)),
        Row(s + "StickSlipLaw", "contact-beyond", lambda: _new_stick_slip_law(contact=1),
            ("contact",)),
        Row(s + "StickSlipLaw", "hold_limit-negative",
            lambda: _new_stick_slip_law(hold_limit=-1.0), ("hold_limit",)),
        Row(s + "StickSlipLaw", "max_events-zero", lambda: _new_stick_slip_law(max_events=0),
            ("max_events",)),
        Row(s + "StickSlipLaw", "frictionless", lambda: _new_stick_slip_law(hold_limit=0.0),
            same=lambda law: law.frictionless),
        Row(u + "check_grid", "three", lambda: U.check_grid((0.001, 1, 51)), ("grid",)),
        Row(u + "check_grid", "step_grid's", lambda: U.check_grid(U.step_grid(
            _states(), 1000.0, 0.05, 16)), same=lambda g: g == (0.001, 1, 51, 50)),
        Row(u + "LinearState", "A-not-square",
            lambda: U.LinearState(np.zeros((4, 3)), 1, np.ones(4), np.ones(4), np.ones(4)),
            ("A",)),
        Row(u + "LinearState", "n-zero",
            lambda: U.LinearState(np.zeros((4, 4)), 0, np.ones(4), np.ones(4), np.ones(4)),
            ("n",)),
        Row(u + "LinearState", "monitor-short",
            lambda: U.LinearState(np.zeros((4, 4)), 1, np.ones(3), np.ones(4), np.ones(4)),
            ("monitor",)),
        Row(u + "LinearState", "accel-nan",
            lambda: U.LinearState(np.zeros((4, 4)), 1, np.ones(4), np.ones(4),
                                  np.array([1.0, NAN, 0.0, 0.0])), ("accel",)),
        # 1 kg on 100 + 300 N/m with 2 N s/m: -1 +- i sqrt(399) rad/s (and the servo's double
        # zero); eig's error is a few eps of |lambda| = 20 for this well-conditioned 4 x 4
        Row(u + "LinearState", "closed-eigenvalues", lambda: _structure()[1].lam,
            same=lambda lam: np.allclose(np.sort_complex(lam[np.abs(lam) > 1]),
                                         [-1 - 1j * math.sqrt(399), -1 + 1j * math.sqrt(399)],
                                         rtol=0, atol=64 * 20 * np.finfo(float).eps)),
        Row(u + "LinearState.watching", "force-long",
            lambda: _structure()[1].watching(np.ones(4), np.ones(5), np.ones(4)), ("force",)),
        Row(s + "friction_states", "b-beyond", lambda: _friction_states(b=1), ("b",)),
        Row(s + "friction_states", "hold-negative", lambda: _friction_states(hold=-1.0),
            ("hold",)),
        Row(s + "friction_states", "M-not-symmetric",
            lambda: _friction_states(M=np.array([[1.0, 2.0], [0.0, 1.0]])), ("M",)),
        Row(s + "friction_states", "o-beyond", lambda: _friction_states(o=2), ("o",)),
        Row(s + "friction_states", "the-four-states", _friction_states,
            same=lambda st: sorted(st) == ["slip+", "slip-", "stick", "stick lower"]),
        Row(t + "ObjectModel", "axis-y", lambda: _model(axis="y"), ("axis",)),
        Row(t + "ObjectModel", "effect-misspelt", lambda: _model(effect="unilateral"),
            ("effect",)),
        Row(t + "ObjectModel", "build-None", lambda: _model(build=None), ("build",)),
        Row(t + "ObjectModel", "respond-int", lambda: _model(respond=3), ("respond",)),
        Row(t + "ObjectModel", "name-empty", lambda: _model(name=""), ("name",)),
        Row(t + "ObjectModel.wanted", "scene-str",
            lambda: OBJECT_MODELS[0].wanted("paper", True), ("scene",)),
        Row(t + "ObjectModel.wanted", "x_modes-str",
            lambda: OBJECT_MODELS[0].wanted(builtin_scene("paper"), "no"), ("x_modes",)),
        # the paper scene strikes through unilateral_contact: its linear modes only when X's
        # modes are asked for
        Row(t + "ObjectModel.wanted", "paper-scene", lambda: [
            [m.wanted(builtin_scene("paper"), x) for m in OBJECT_MODELS] for x in (True, False)],
            same=lambda r: r == [[True, True, False], [False, True, False]]),
        Row(sim + "ChainStep", "effect-misspelt", lambda: ChainStep("gravty", print), ("effect",)),
        Row(sim + "ChainStep", "apply-str", lambda: ChainStep("gravity", "apply"), ("apply",)),
        Row(sim + "ChainStep", "reads-str", lambda: ChainStep(None, print, reads="dlpf"),
            ("reads",)),
        Row(sim + "ChainStep", "a-step", lambda: ChainStep("gravity", print, ("dlpf",)),
            same=lambda s: s.reads == ("dlpf",)),
        Row(sim + "SignalBatch", "scene-str", lambda: _batch(scene="paper"), ("scene",)),
        Row(sim + "SignalBatch", "speeds-list", lambda: _batch(speeds=[1.0]), ("speeds",)),
        Row(sim + "SignalBatch", "tilts-two", lambda: _batch(tilts=np.ones(2)), ("tilts",)),
        Row(sim + "SignalBatch", "seeds-none", lambda: _batch(seeds=[]), ("seeds",)),
        # the paper scene's 1000 samples at 1 kHz, read through its DLPF
        Row(sim + "SignalBatch", "paper", _batch,
            same=lambda b: b.t.size == 1000 and b.chip_filter is not None and b.n == 1),
        Row(sim + "SignalBatch.rngs", "effect-name", lambda: _batch().rngs("sensor_noise"),
            ("effect",)),
        # one generator per signal, seeded by (seed, stream): the same draws as numpy's own
        Row(sim + "SignalBatch.rngs", "seed-and-stream", lambda: _batch().rngs(
            builtin_scene("paper").effect("sensor_noise"))[0].random(3),
            same=lambda r: np.array_equal(r, np.random.default_rng([3, 3]).random(3))),
        Row(t + "pinned_modes", "scene-str", lambda: _cases(pinned_modes, scene="ideal"),
            ("scene",)),
        Row(t + "pinned_modes", "contacts-beyond-tip",
            lambda: _cases(pinned_modes, contacts=np.array([5.0])), ("contacts",)),
        Row(t + "pinned_modes", "materials-two",
            lambda: _cases(pinned_modes, materials=np.array(["brass", "pvc"])), ("materials",)),
        Row(t + "pinned_modes", "show_progress-str",
            lambda: _cases(pinned_modes, show_progress="no"), ("show_progress",)),
        Row(t + "pinned_modes", "one-pin", lambda: _cases(pinned_modes),
            same=lambda r: len(r[0]) == 1 and r[1].tolist() == [0]),
        Row(t + "object_modes", "preloads-nan",
            lambda: _cases(object_modes, preloads=np.array([NAN])), ("preloads",)),
        Row(t + "object_modes", "preloads-None",
            lambda: _cases(object_modes, preloads=None), ("preloads",)),
        Row(t + "object_modes", "scene-without-object_modes",
            lambda: _cases(object_modes, scene=builtin_scene("ideal")), ("object_modes",)),
        Row(t + "object_modes", "x_modes-str", lambda: _cases(object_modes, x_modes="yes"),
            ("x_modes",)),
        Row(t + "object_modes", "contacts-nan",
            lambda: _cases(object_modes, contacts=np.array([NAN])), ("contacts",)),
        Row(m + "x_terms", "modes-not-arrest-modes",
            lambda: MO.x_terms(["m"], np.array([0]), np.ones(1)), ("modes",)),
        Row(m + "x_terms", "rows-beyond-modes",
            lambda: MO.x_terms([_one_arrest_mode()], np.array([1]), np.ones(1)), ("rows",)),
        Row(m + "x_terms", "speeds-nan",
            lambda: MO.x_terms([_one_arrest_mode()], np.array([0]), np.array([NAN])),
            ("speeds",)),
        Row(m + "x_terms", "zeta-one",
            lambda: MO.x_terms([_one_arrest_mode()], np.array([0]), np.ones(1), zeta=1.0),
            ("zeta",)),
        Row(m + "x_terms", "preloads-two-for-one",
            lambda: MO.x_terms([_one_arrest_mode()], np.array([0]), np.ones(1),
                               preloads=np.ones(2)), ("preloads",)),
        # each signal's row is its modes' tip velocity times its own speed
        Row(m + "x_terms", "scaled-by-speed",
            lambda: MO.x_terms([_one_arrest_mode()], np.array([0, 0]), np.array([1.0, 3.0]),
                               zeta=0.01),
            same=lambda x: x.amplitude.tolist() == [[1.0], [3.0]] and x.zeta.tolist() == [[0.01],
                                                                                     [0.01]]),
        Row(m + "z_terms", "tilts-two-for-one", lambda: MO.z_terms(
            Probe(), "clamped", np.ones(1), np.ones(2), 0.0, n_elements=8, n_modes=4,
            max_frequency=100.0), ("tilts",)),
        Row(m + "z_terms", "zeta-negative", lambda: MO.z_terms(
            Probe(), "clamped", np.ones(1), np.ones(1), -0.1, n_elements=8, n_modes=4,
            max_frequency=100.0), ("zeta",)),
        Row(m + "z_terms", "speeds-2d", lambda: MO.z_terms(
            Probe(), "clamped", np.ones((1, 1)), np.ones(1), 0.0, n_elements=8, n_modes=4,
            max_frequency=100.0), ("speeds",)),
        Row(m + "ModalTerms.damping_ratios", "row-negative",
            lambda: _terms().damping_ratios(-1), ("row",)),
        Row(m + "ModalTerms.damping_ratios", "row-beyond",
            lambda: _terms().damping_ratios(1), ("row",)),
        Row(m + "ModalTerms.damping_ratios", "padding-dropped",
            lambda: _terms().damping_ratios(0), same=lambda r: r.tolist() == [0.1]),
        Row(m + "ModalTerms.dynamic_contact_force", "no-contact-spring",
            lambda: _terms(force=False).dynamic_contact_force(t_fine), ("contact_force",)),
        Row(m + "ModalTerms.dynamic_contact_force", "t-nan",
            lambda: _terms().dynamic_contact_force(np.array([0.0, NAN])), ("t",)),
        Row(m + "ModalTerms.dynamic_contact_force", "t-2d",
            lambda: _terms().dynamic_contact_force(np.zeros((2, 2))), ("t",)),
        # one mode: each value a few roundings of exp and sin of size <= 0.02 N
        Row(m + "ModalTerms.dynamic_contact_force", "one-mode-by-hand",
            lambda: _terms().dynamic_contact_force(t_fine),
            same=lambda r: r.shape == (1, t_fine.size)
            and np.abs(r[0] - _force_by_hand(t_fine)).max() < 64 * np.finfo(float).eps * 0.02),
        Row(m + "ModalTerms.lift_off_ratio", "no-preload",
            lambda: _terms().lift_off_ratio(), ("preload",)),
        Row(m + "ModalTerms.lift_off_ratio", "duration-zero",
            lambda: _terms(np.array([1.0])).lift_off_ratio(0.0), ("duration",)),
        Row(m + "ModalTerms.lift_off_ratio", "rate-negative",
            lambda: _terms(np.array([1.0])).lift_off_ratio(1.0, -8000.0), ("rate",)),
        Row(m + "ModalTerms.lift_off_ratio", "rate-nan",
            lambda: _terms(np.array([1.0])).lift_off_ratio(1.0, NAN), ("rate",)),
        *_linear_state_rows(),
        *_coulomb_law_rows(),
    ]


#: A state ``(q, q', s, s')`` of one mass: displaced, moving, the servo at 2 mm and 0.5 m/s.
X = np.array([0.01, 1.0, 0.002, 0.5])
EPS = np.finfo(float).eps


def _damped_states():
    """The free and closed states of 1 kg on 100 N/m and 2 N s/m, touching 300 N/m."""
    free, closed, _ = _structure()
    return free, closed


def _rigid_free():
    """The free state of 1 kg on no spring: a rigid-body motion, propagated by ``expm``."""
    return U.contact_states(np.eye(1), np.zeros((1, 1)), np.zeros((1, 1)), np.ones(1), 300.0,
                            np.ones(1))[0]


def _exact(st, tau):
    """The witness: SciPy's matrix exponential of the state's whole system matrix."""
    return spl.expm(st.A * tau) @ X


def _near(a, b, st, scale):
    """``a`` equals ``b`` up to the propagation's rounding: the eigenvector route loses
    ``cond(V)`` times a few eps of the largest value involved (``scale``)."""
    return np.abs(np.asarray(a) - np.asarray(b)).max() <= 64 * EPS * np.linalg.cond(st.V) * scale


class _NoAdvance(U.SwitchedSystem):
    """A law that gives its states but no step."""

    def state(self, key):
        return key


class _NoState(U.SwitchedSystem):
    """A law that steps but does not say what its states are."""

    def advance(self, x, key, t0, t1, crosses=False):
        return x, key


def _linear_state_rows():
    """Rows of a linear state's propagation, the event finder and the march's interface."""
    u = "ebantenna.simulate.unilateral."
    ls = u + "LinearState."
    free, closed = _damped_states()
    scale = np.abs(closed.A).max() * np.abs(X).max()  # the largest rate of the closed state
    return [
        Row(ls + "modal", "x-short", lambda: closed.modal(np.zeros(3)), ("x",)),
        Row(ls + "modal", "x-nan", lambda: closed.modal([0.0, NAN, 0.0, 0.0]), ("x",)),
        Row(ls + "modal", "x-str", lambda: closed.modal(["a", "b", "c", "d"]), ("x",)),
        # the modal coordinates rebuild y + G s + H s' through the eigenvectors
        Row(ls + "modal", "rebuilds-the-state", lambda: closed.modal(X),
            same=lambda z: _near(closed.V @ z, X[:2] + closed.G * X[2] + closed.H * X[3],
                                 closed, 1.0)),
        Row(ls + "modal", "none-for-a-rigid-body", lambda: _rigid_free().modal(X),
            same=lambda z: z is None),
        Row(ls + "at", "tau-negative", lambda: closed.at(X, closed.modal(X), -0.001), ("tau",)),
        Row(ls + "at", "tau-nan", lambda: closed.at(X, closed.modal(X), NAN), ("tau",)),
        Row(ls + "at", "z-short", lambda: closed.at(X, np.zeros(1), 0.001), ("z",)),
        Row(ls + "at", "z-None-for-an-eigen-state", lambda: closed.at(X, None, 0.001), ("z",)),
        Row(ls + "at", "z-given-to-an-expm-state",
            lambda: _rigid_free().at(X, np.zeros(2), 0.001), ("z",)),
        Row(ls + "at", "x-long", lambda: closed.at(np.zeros(5), closed.modal(X), 0.001),
            ("x",)),
        Row(ls + "at", "against-expm", lambda: (free.at(X, free.modal(X), 0.013),
                                                closed.at(X, closed.modal(X), 0.013)),
            same=lambda r: _near(r[0], _exact(free, 0.013), free, 1.0)
            and _near(r[1], _exact(closed, 0.013), closed, 1.0)),
        # no spring: q + q' tau, the servo at s + s' tau; expm of a nilpotent matrix is exact
        Row(ls + "at", "rigid-body-by-hand", lambda: _rigid_free().at(X, None, 0.5),
            same=lambda r: np.allclose(r, [0.51, 1.0, 0.252, 0.5], rtol=0, atol=4 * EPS)),
        Row(ls + "step", "tau-inf", lambda: closed.step(X, math.inf), ("tau",)),
        Row(ls + "step", "tau-str", lambda: closed.step(X, "0.001"), ("tau",)),
        Row(ls + "step", "x-ragged", lambda: closed.step([[0.0], [1.0, 2.0]], 0.001), ("x",)),
        # 1 kg on 100 + 300 N/m released at 1 m/s: a quarter period (pi / 40 s) later it rests
        # at 1 / 20 m
        Row(ls + "step", "quarter-period-by-hand",
            lambda: _states()[1].step([0.0, 1.0, 0.0, 0.0], math.pi / 40),
            same=lambda r: _near(r, [0.05, 0.0, 0.0, 0.0], _states()[1], 1.0)),
        Row(ls + "curve", "x-nan", lambda: closed.curve([NAN] * 4, closed.modal(X)), ("x",)),
        Row(ls + "curve", "z-wrong-length", lambda: closed.curve(X, np.zeros(3)), ("z",)),
        # the force and its rate along the motion, against expm
        Row(ls + "curve", "against-expm", lambda: closed.curve(X, closed.modal(X))(0.013),
            same=lambda r: _near(r[0], closed.monitor @ _exact(closed, 0.013), closed, scale)
            and _near(r[1], closed.monitor @ closed.A @ _exact(closed, 0.013), closed,
                      scale * np.abs(closed.A).max())),
        Row(u + "crossing", "curve-str", lambda: U.crossing("g", 1.0, 1e-9, 1.0, -1.0),
            ("curve",)),
        Row(u + "crossing", "span-zero", lambda: U.crossing(_line, 0.0, 1e-9, 1.0, -1.0),
            ("span",)),
        Row(u + "crossing", "xtol-nan", lambda: U.crossing(_line, 2.0, NAN, 1.0, -1.0),
            ("xtol",)),
        Row(u + "crossing", "ga-negative", lambda: U.crossing(_line, 2.0, 1e-9, -1.0, -1.0),
            ("ga",)),
        Row(u + "crossing", "gb-positive", lambda: U.crossing(_line, 2.0, 1e-9, 1.0, 0.5),
            ("gb",)),
        Row(u + "crossing", "ga-str", lambda: U.crossing(_line, 2.0, 1e-9, "1", -1.0),
            ("ga",)),
        # cos reaches zero at pi / 2: the far end of a bracket of width xtol, where cos <= 0
        Row(u + "crossing", "cosine-by-hand", lambda: U.crossing(
            lambda tau: (math.cos(tau), -math.sin(tau)), 3.0, 1e-12, 1.0, math.cos(3.0)),
            same=lambda b: math.cos(b) <= 0 and b - math.pi / 2 <= 1e-12),
        Row(u + "SwitchedSystem.advance", "a-law-without-advance",
            lambda: _NoAdvance(0.001, 1, 10), ("advance",)),
        Row(u + "SwitchedSystem.state", "a-law-without-state", lambda: _NoState(0.001, 1, 10),
            ("state",)),
    ]


def _line(tau):
    """``g = 1 - tau`` and its rate."""
    return 1.0 - tau, -1.0


def _coulomb_law(**kw):
    """1 kg on 100 N/m (and ``C``), pressed by 1 N against mu_s = mu_k = 1, at rest (or ``kw``)."""
    args = dict(K=[[100.0]], C=[[0.0]], Minv=[[1.0]], tangential=0, normal_force=lambda t: 1.0,
                static_friction=1.0, kinetic_friction=1.0, surface_speed=0.0)
    args.update(kw)
    return F.CoulombLaw(**args)


def _record(n_samples=3, n=1):
    return np.zeros((n_samples, 2 * n)), np.zeros(n_samples), np.zeros(n_samples)


def _coulomb_law_rows():
    """Rows of Coulomb's law as the ODE witness integrates it, each method checked by hand."""
    c = "ebantenna.simulate.friction_ode.CoulombLaw"
    law = _coulomb_law()
    y = [0.05, 0.0]  # 5 cm out, at rest: the spring pulls back with 5 N
    t_out = np.linspace(0.0, 1.0, 101)  # four turns of the oscillator, every pi / 10 s
    return [
        Row(c, "K-not-symmetric", lambda: _coulomb_law(K=[[1.0, 2.0], [0.0, 1.0]]), ("K",)),
        Row(c, "Minv-wrong-size", lambda: _coulomb_law(Minv=np.eye(2)), ("Minv",)),
        Row(c, "tangential-zero", lambda: _coulomb_law(tangential=[0.0]), ("tangential",)),
        Row(c, "tangential-beyond", lambda: _coulomb_law(tangential=3), ("tangential",)),
        Row(c, "normal_force-float", lambda: _coulomb_law(normal_force=1.0), ("normal_force",)),
        Row(c, "kinetic-above-static", lambda: _coulomb_law(kinetic_friction=2.0),
            ("kinetic_friction",)),
        Row(c, "surface_speed-nan", lambda: _coulomb_law(surface_speed=NAN), ("surface_speed",)),
        Row(c, "as-built", _coulomb_law, same=lambda law: law.tMt == 1.0 and law.n == 1),
        Row(c + ".stick_force", "t-nan", lambda: law.stick_force(NAN, y), ("t",)),
        Row(c + ".stick_force", "y-short", lambda: law.stick_force(0.0, [0.05]), ("y",)),
        Row(c + ".stick_force", "y-str", lambda: law.stick_force(0.0, ["a", "b"]), ("y",)),
        # holding 5 cm on 100 N/m against a 2 N s/m dashpot moving at 0.5 m/s: 5 + 1 N
        Row(c + ".stick_force", "spring-and-dashpot-by-hand",
            lambda: _coulomb_law(C=[[2.0]]).stick_force(0.0, [0.05, 0.5]),
            same=lambda r: r == 6.0),
        Row(c + ".friction", "state-misspelt", lambda: law.friction("slide", 0.0, y),
            ("state",)),
        Row(c + ".friction", "t-inf", lambda: law.friction("stick", math.inf, y), ("t",)),
        # slipping faster than the surface: -mu_k N = -0.5 x 2 N
        Row(c + ".friction", "slip+-by-hand", lambda: _coulomb_law(
            normal_force=lambda t: 2.0, kinetic_friction=0.5).friction("slip+", 0.0, y),
            same=lambda r: r == -1.0),
        Row(c + ".rhs", "state-None", lambda: law.rhs(None), ("state",)),
        # slipping forward at 0.5 m/s from 5 cm: -100 x 0.05 - 1 N on 1 kg
        Row(c + ".rhs", "slip+-by-hand", lambda: law.rhs("slip+")(0.0, np.array([0.05, 0.5])),
            same=lambda r: r.tolist() == [0.5, -6.0]),
        Row(c + ".relative_speed", "y-nan", lambda: law.relative_speed(0.0, [0.0, NAN]),
            ("y",)),
        Row(c + ".relative_speed", "t-str", lambda: law.relative_speed("0", y), ("t",)),
        Row(c + ".relative_speed", "belt-by-hand",
            lambda: _coulomb_law(surface_speed=0.2).relative_speed(0.0, [0.0, 0.5]),
            same=lambda r: math.isclose(r, 0.3, rel_tol=2 * EPS)),
        Row(c + ".stick_limit", "y-long", lambda: law.stick_limit(0.0, [0.0, 0.0, 0.0]),
            ("y",)),
        # 5 mm out: 0.5 N held of the 1 N the contact can hold
        Row(c + ".stick_limit", "by-hand", lambda: law.stick_limit(0.0, [0.005, 0.0]),
            same=lambda r: math.isclose(r, 0.5, rel_tol=4 * EPS)),
        Row(c + ".end_event", "state-misspelt", lambda: law.end_event("stuck"), ("state",)),
        # a stick ends as the margin falls, a forward slip as the speed falls, a backward one
        # as it rises; each ends its state
        Row(c + ".end_event", "directions", lambda: [law.end_event(s) for s in F.STATES],
            same=lambda ev: [e.direction for e in ev] == [-1, -1, 1]
            and all(e.terminal for e in ev)),
        Row(c + ".entered", "previous-misspelt", lambda: law.entered(0.0, y, "slip"),
            ("previous",)),
        Row(c + ".entered", "y-3d", lambda: law.entered(0.0, np.zeros((2, 1, 1))), ("y",)),
        # at rest within mu_s N / k = 1 cm it holds; beyond, it slips back; moving, it slips
        Row(c + ".entered", "by-hand", lambda: [law.entered(0.0, p) for p in
                                                 ([0.005, 0.0], y, [0.0, 1.0])],
            same=lambda r: r == ["stick", "slip-", "slip+"]),
        Row(c + ".next_state", "y-list", lambda: law.next_state("slip+", 0.0, [0.05, 0.001]),
            ("y",)),
        Row(c + ".next_state", "state-misspelt",
            lambda: law.next_state("stuck", 0.0, np.array([0.05, 0.0])), ("state",)),
        # a forward slip ends 5 cm out: the speed lands on 0 and the spring (5 N > 1 N) pulls
        # the contact back
        Row(c + ".next_state", "lands-on-the-surface-speed", lambda: (
            lambda yy: (law.next_state("slip+", 0.0, yy), yy.tolist()))(np.array([0.05, 1e-3])),
            same=lambda r: r == ("slip-", [0.05, 0.0])),
        Row(c + ".respond", "t_out-decreasing",
            lambda: law.respond([0.1], [0.0], t_out[::-1], 0, rtol=1e-10, max_events=100),
            ("t_out",)),
        Row(c + ".respond", "t_out-before-zero",
            lambda: law.respond([0.1], [0.0], t_out - 1.0, 0, rtol=1e-10, max_events=100),
            ("t_out",)),
        Row(c + ".respond", "q0-short",
            lambda: law.respond([], [0.0], t_out, 0, rtol=1e-10, max_events=100), ("q0",)),
        Row(c + ".respond", "rtol-zero",
            lambda: law.respond([0.1], [0.0], t_out, 0, rtol=0.0, max_events=100), ("rtol",)),
        Row(c + ".respond", "max_events-zero",
            lambda: law.respond([0.1], [0.0], t_out, 0, rtol=1e-10, max_events=0),
            ("max_events",)),
        Row(c + ".respond", "output-beyond",
            lambda: law.respond([0.1], [0.0], t_out, 2, rtol=1e-10, max_events=100),
            ("output",)),
        # released from 10 cm: 4 cm of amplitude lost per cycle (4 mu N / k), a turn every
        # pi / 10 s; rtol 1e-10 places each turn far within 1e-6 m and 1e-6 s
        Row(c + ".respond", "oscillator-by-hand",
            lambda: law.respond([0.1], [0.0], t_out, 0, rtol=1e-10, max_events=100),
            same=lambda r: [e.kind for e in r.events] == ["slip-", "slip+", "slip-", "slip+"]
            and np.allclose([e.position for e in r.events], [0.1, -0.08, 0.06, -0.04],
                            rtol=0, atol=1e-6)
            and np.allclose([e.time for e in r.events], np.arange(4) * math.pi / 10,
                            rtol=0, atol=1e-6)),
        Row(c + ".integrate", "record-list", lambda: law.integrate(
            "slip-", 0.0, [0.1, 0.0], t_out, 0, [], rtol=1e-10, atol=1e-12), ("record",)),
        Row(c + ".integrate", "record-short", lambda: law.integrate(
            "slip-", 0.0, [0.1, 0.0], t_out, 0, _record(), rtol=1e-10, atol=1e-12),
            ("record",)),
        Row(c + ".integrate", "atol-negative", lambda: law.integrate(
            "slip-", 0.0, [0.1, 0.0], t_out, 0, _record(101), rtol=1e-10, atol=-1.0), ("atol",)),
        Row(c + ".integrate", "t-nan", lambda: law.integrate(
            "slip-", NAN, [0.1, 0.0], t_out, 0, _record(101), rtol=1e-10, atol=1e-12), ("t",)),
        Row(c + ".integrate", "state-misspelt", lambda: law.integrate(
            "slip", 0.0, [0.1, 0.0], t_out, 0, _record(101), rtol=1e-10, atol=1e-12),
            ("state",)),
        # the first backward slip from 10 cm ends at the turn, pi / 10 s later, 8 cm the other
        # side (the closed form of the oscillator about its shifted rest at -1 cm)
        Row(c + ".integrate", "first-half-period-by-hand", lambda: law.integrate(
            "slip-", 0.0, [0.1, 0.0], t_out, 0, _record(101), rtol=1e-10, atol=1e-12),
            same=lambda sol: sol.status == 1 and abs(sol.t[-1] - math.pi / 10) < 1e-6
            and abs(sol.y[0, -1] + 0.08) < 1e-6),
    ]


(IDS, test_the_rows_are_distinct, test_every_row_ends_in_a_clear_error_or_the_right_answer,
 contract_rows) = row_tests(all_rows, 'ebantenna.simulate.')


#: What the contact laws and the touched object's step build and hand back: nothing a user gives.
RESULTS = ("unilateral.ContactEvent", "unilateral.UnilateralResponse",
           "stick_slip.StickSlipResponse", "friction_ode.FrictionEvent",
           "friction_ode.FrictionResponse", "strikes.StrikeModel", "stick_slip.FrictionModel",
           "structure.ContactCase", "structure.ContactModel")


def contract_exempt() -> dict[str, str]:
    """Result types (read by the inventory test)."""
    return {f"ebantenna.simulate.{name}": "a result type the package builds and hands back"
            for name in RESULTS}
