"""The input contract of the simulator's effects: their parameters and the steps they apply.

Every parameter of every effect refuses NaN, a string and -1 (and a count beyond what can be
solved), naming the parameter; the methods the simulator calls refuse a generator that is not
a ``numpy.random.Generator``, a count of samples over the memory budget, a sampling rate of 0,
mismatched or non-numeric arrays, and a body that is not a ``Material`` or ``Probe``, naming
each; a few results are checked against the formulas they implement.

Found by these rows and fixed: ``AttributeError`` from every method given an integer for its
generator or body, NumPy's "negative dimensions" and a 7 TiB allocation for a count of
samples, a noise level for ``fs = 0`` or NaN, ``IndexError`` from the Kalman filter given a
scalar, mismatched ``ax`` and ``az`` accepted by gravity, a NaN preload accepted by the Hertz
spring, and an object-modes effect with 10**400 rod elements or modes accepted.
"""

from __future__ import annotations

import dataclasses
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, row_tests  # noqa: E402

from ebantenna import Probe  # noqa: E402
from ebantenna.chips.mpu6050 import STANDARD_GRAVITY  # noqa: E402
from ebantenna.probe import material  # noqa: E402
from ebantenna.simulate import effects as fx  # noqa: E402

NAN = math.nan
BRASS, PROBE = material("brass"), Probe()


def _tube_on_brass():
    from ebantenna.simulate.contact import tube_on_rod_stiffness

    effect = fx.ObjectModes()
    return tube_on_rod_stiffness(PROBE, BRASS, effect.diameter, effect.preload)
PARAMETERS = {cls: [f.name for f in dataclasses.fields(cls)]
              for cls in (getattr(fx, n) for n in fx.__all__)
              if isinstance(cls, type) and dataclasses.is_dataclass(cls)}
#: Counts with no bound of their own (a cap on events the caller chooses).
UNBOUNDED = {"max_events"}


def _rng():
    return np.random.default_rng(0)


def _construction_rows():
    rows = []
    for cls, fields in PARAMETERS.items():
        surface = f"{cls.__module__}.{cls.__qualname__}"
        for field in fields:
            values = [("nan", NAN), ("str", "x"), ("-1", -1)]
            if field not in UNBOUNDED:
                values.append(("10**400", 10**400))
            rows += [Row(surface, f"{field}={label}", (lambda c=cls, f=field, v=v: c(**{f: v})),
                         (field,)) for label, v in values]
    return rows


def _method_rows():
    s = "ebantenna.simulate.effects."
    big = 10**12
    return [
        Row(s + "sensor.Clipping.apply", "a-str", lambda: fx.Clipping().apply("x"), ("a must",)),
        Row(s + "sensor.Clipping.apply", "a-nan", lambda: fx.Clipping().apply(np.array([NAN])),
            ("a must",)),
        Row(s + "sensor.Clipping.apply", "a-ragged",
            lambda: fx.Clipping().apply([[1.0], [2.0, 3.0]]), ("a must",)),
        Row(s + "sensor.Clipping.limits", "by-hand", lambda: fx.Clipping(16).limits(),
            same=lambda r: r == (-16 * STANDARD_GRAVITY,
                                 16 * STANDARD_GRAVITY * (1 - 2.0**-15))),
        Row(s + "sensor.Clipping.apply", "capped", lambda: fx.Clipping(2).apply(
            np.array([-1e3, 1.0, 1e3])), same=lambda r: r.tolist() == [
                -2 * STANDARD_GRAVITY, 1.0, 2 * STANDARD_GRAVITY * (1 - 2.0**-15)]),
        Row(s + "sensor.ClockJitter.offsets", "rng-int", lambda: fx.ClockJitter().offsets(5, 10),
            ("rng",)),
        Row(s + "sensor.ClockJitter.offsets", "n_samples-negative",
            lambda: fx.ClockJitter().offsets(_rng(), -1), ("n_samples",)),
        Row(s + "sensor.ClockJitter.offsets", "n_samples-10**12",
            lambda: fx.ClockJitter().offsets(_rng(), big), ("n_samples",)),
        Row(s + "sensor.ClockJitter.offsets", "shape",
            lambda: fx.ClockJitter().offsets(_rng(), 7), same=lambda r: r.shape == (7,)),
        Row(s + "sensor.Gravity.apply", "az-shorter",
            lambda: fx.Gravity().apply(np.ones(3), np.ones(2)), ("ax and az",)),
        Row(s + "sensor.Gravity.apply", "ax-str", lambda: fx.Gravity().apply("x", "y"), ("ax",)),
        Row(s + "sensor.Gravity.apply", "az-nan",
            lambda: fx.Gravity().apply(np.ones(2), np.array([0.0, NAN])), ("az",)),
        Row(s + "sensor.Gravity.apply", "adds-g", lambda: fx.Gravity(9.0).apply(
            np.zeros(2), np.ones(2)), same=lambda r: r[0].tolist() == [0, 0]
            and r[1].tolist() == [10.0, 10.0]),
        Row(s + "sensor.LowPassFilter.apply_internal", "fs-0",
            lambda: fx.LowPassFilter().apply_internal(np.ones(100), 0.0), ("fs",)),
        Row(s + "sensor.LowPassFilter.divider", "fs-nan",
            lambda: fx.LowPassFilter().divider(NAN), ("fs",)),
        Row(s + "sensor.LowPassFilter.divider", "fs-not-a-divisor",
            lambda: fx.LowPassFilter().divider(3000.0), ("fs",)),
        Row(s + "sensor.LowPassFilter.divider", "8000/1000",
            lambda: fx.LowPassFilter(internal_rate=8000.0).divider(1000.0), same=lambda r: r == 8),
        Row(s + "sensor.LowPassFilter.frequency_response", "frequency-str",
            lambda: fx.LowPassFilter().frequency_response("x"), ("frequency",)),
        Row(s + "sensor.LowPassFilter.frequency_response", "frequency-nan",
            lambda: fx.LowPassFilter().frequency_response([NAN]), ("frequency",)),
        # a Butterworth low-pass passes DC with gain 1 and is 3 dB down at its bandwidth
        Row(s + "sensor.LowPassFilter.frequency_response", "dc-and-corner",
            lambda: np.abs(fx.LowPassFilter(bandwidth=260.0).frequency_response([0.0, 260.0])),
            same=lambda r: abs(r[0] - 1) < 1e-12 and abs(r[1] - 2**-0.5) < 1e-12),
        # its design, made with it: one second-order section
        Row(s + "sensor.LowPassFilter", "design-second-order",
            lambda: fx.LowPassFilter().sos, same=lambda r: r.shape == (1, 6)),
        Row(s + "sensor.MainsHum.phases", "rng-int", lambda: fx.MainsHum().phases(5), ("rng",)),
        Row(s + "sensor.MainsHum.signal", "phase-nan",
            lambda: fx.MainsHum().signal(np.ones(3), NAN), ("phase",)),
        Row(s + "sensor.MainsHum.signal", "t-str", lambda: fx.MainsHum().signal("x", 0.0),
            ("t",)),
        Row(s + "sensor.MainsHum.signal", "quarter-period", lambda: fx.MainsHum(50.0, 0.5).signal(
            np.array([0.005]), 0.0), same=lambda r: abs(r[0] - 0.5) < 1e-15),
        Row(s + "sensor.Quantisation.apply", "a-str", lambda: fx.Quantisation().apply("x"),
            ("a must",)),
        Row(s + "sensor.Quantisation.apply", "a-nan",
            lambda: fx.Quantisation().apply(np.array([1.0, NAN])), ("a must",)),
        Row(s + "sensor.Quantisation.apply", "a-ragged",
            lambda: fx.Quantisation().apply([[1.0], [2.0, 3.0]]), ("a must",)),
        Row(s + "sensor.Quantisation.lsb", "by-hand", lambda: fx.Quantisation(16).lsb(),
            same=lambda r: r == 32 * STANDARD_GRAVITY / 2**16),
        Row(s + "sensor.SensorNoise.draw", "rng-int", lambda: fx.SensorNoise().draw(
            5, 10, 1000.0), ("rng",)),
        Row(s + "sensor.SensorNoise.draw", "n_samples-10**12", lambda: fx.SensorNoise().draw(
            _rng(), big, 1000.0), ("n_samples",)),
        Row(s + "sensor.SensorNoise.draw", "fs-0", lambda: fx.SensorNoise().draw(
            _rng(), 10, 0.0), ("fs",)),
        Row(s + "sensor.SensorNoise.std", "fs-nan", lambda: fx.SensorNoise().std(NAN), ("fs",)),
        Row(s + "sensor.SensorNoise.std", "by-hand", lambda: fx.SensorNoise(0.01).std(2000.0),
            same=lambda r: math.isclose(r, 0.01 * math.sqrt(1000.0), rel_tol=1e-15)),
        Row(s + "sensor.SensorNoise.draw_signals", "generators-int",
            lambda: fx.SensorNoise().draw_signals(5, 10, 1000.0), ("generators",)),
        Row(s + "sensor.SensorNoise.draw_signals", "n_samples-10**12",
            lambda: fx.SensorNoise().draw_signals([_rng()], big, 1000.0), ("n_samples",)),
        Row(s + "sensor.SensorNoise.draw_signals", "shape",
            lambda: fx.SensorNoise().draw_signals([_rng(), _rng()], 5, 1000.0),
            same=lambda r: r.shape == (2, 2, 5)),
        Row(s + "sensor.SteadyStateKalman.apply", "level-scalar",
            lambda: fx.SteadyStateKalman().apply(np.ones((1, 5)), NAN), ("level",)),
        Row(s + "sensor.SteadyStateKalman.apply", "a-1-D",
            lambda: fx.SteadyStateKalman().apply(np.ones(5), [0.0]), ("a",)),
        Row(s + "sensor.SteadyStateKalman.apply", "a-str",
            lambda: fx.SteadyStateKalman().apply("x", [0.0]), ("a",)),
        # started at the settled level of a constant, the filter stays on it
        Row(s + "sensor.SteadyStateKalman.apply", "settled", lambda: fx.SteadyStateKalman().apply(
            np.full((1, 5), 2.0), [2.0]), same=lambda r: np.allclose(r, 2.0, rtol=1e-15, atol=0)),
        Row(s + "sensor.SteadyStateKalman.gain", "ratio-1", lambda: fx.SteadyStateKalman(1.0)
            .gain(), same=lambda k: math.isclose(k, (1 + 5**0.5) / (3 + 5**0.5), rel_tol=1e-15)),
        Row(s + "objects.PreloadScatter.factor", "rng-int",
            lambda: fx.PreloadScatter().factor(5), ("rng",)),
        Row(s + "objects.PreloadScatter.factor", "no-spread",
            lambda: fx.PreloadScatter(0.0).factor(_rng()), same=lambda r: r == 1.0),
        Row(s + "sensor.SensorDrift.draw", "rng-int", lambda: fx.SensorDrift().draw(5),
            ("rng",)),
        Row(s + "sensor.SensorDrift.draw", "no-drift", lambda: fx.SensorDrift(0.0).draw(_rng()),
            same=lambda r: np.all(r[0] == 1.0) and np.all(r[1] == 0.0)),
        Row(s + "sensor.SensorDrift.gain_std", "scales",
            lambda: (fx.SensorDrift(2.0).gain_std(), fx.SensorDrift(1.0).gain_std()),
            same=lambda r: math.isclose(r[0], 2 * r[1], rel_tol=1e-15)),
        Row(s + "sensor.SensorDrift.offset_std", "scales",
            lambda: (fx.SensorDrift(2.0).offset_std(), fx.SensorDrift(1.0).offset_std()),
            same=lambda r: np.allclose(r[0], 2 * r[1], rtol=1e-15, atol=0)),
        Row(s + "_base.Effect.from_parameters", "params-str",
            lambda: fx.SensorNoise.from_parameters("x"), ("parameters",)),
        Row(s + "_base.Effect.from_parameters", "unknown-key",
            lambda: fx.SensorNoise.from_parameters({"x": 1}), ("x",)),
        Row(s + "_base.Effect.from_parameters", "bad-value",
            lambda: fx.SensorNoise.from_parameters({"density": -1}), ("density",)),
        Row(s + "_base.Effect.parameters", "round-trip",
            lambda: fx.MainsHum.from_parameters(fx.MainsHum(60.0, 0.1).parameters()),
            same=lambda e: e == fx.MainsHum(60.0, 0.1)),
        Row(s + "objects.ObjectModes.rod", "material-unknown",
            lambda: fx.ObjectModes().rod("gold"), ("gold",)),
        Row(s + "objects.ObjectModes.rod", "material-int", lambda: fx.ObjectModes().rod(5),
            ("material",)),
        Row(s + "objects.ObjectModes.rod", "its-geometry", lambda: fx.ObjectModes(
            diameter=0.01, free_length=0.2).rod("brass"),
            same=lambda r: r.diameter == 0.01 and r.free_length == 0.2),
        Row(s + "objects.ObjectModes.contact_stiffness", "obj-int",
            lambda: fx.ObjectModes().contact_stiffness(5, PROBE), ("obj",)),
        Row(s + "objects.ObjectModes.contact_stiffness", "probe-int",
            lambda: fx.ObjectModes().contact_stiffness(BRASS, 5), ("probe",)),
        Row(s + "objects.ObjectModes.contact_stiffness", "preload-negative",
            lambda: fx.ObjectModes().contact_stiffness(BRASS, PROBE, -1.0), ("preload",)),
        Row(s + "objects.ObjectModes.contact_loss_factor", "obj-int",
            lambda: fx.ObjectModes().contact_loss_factor(5, PROBE, object_loss=True), ("obj",)),
        Row(s + "objects.ObjectModes.contact_loss_factor", "object_loss-str",
            lambda: fx.ObjectModes().contact_loss_factor(BRASS, PROBE, object_loss="no"),
            ("object_loss",)),
        Row(s + "objects.ObjectModes.contact_spring", "obj-int",
            lambda: fx.ObjectModes().contact_spring(5, PROBE, object_loss=True), ("obj",)),
        Row(s + "objects.ObjectModes.contact_spring", "object_loss-str",
            lambda: fx.ObjectModes().contact_spring(BRASS, PROBE, object_loss="no"),
            ("object_loss",)),
        Row(s + "objects.ObjectModes.contact_spring", "preload-negative",
            lambda: fx.ObjectModes().contact_spring(BRASS, PROBE, object_loss=True, preload=-1.0),
            ("preload",)),
        # the Hertz spring and the tube wall's ring in series: 1/k = 1/k_hertz + 1/k_ring, to
        # the two divisions' and the sum's rounding
        Row(s + "objects.ObjectModes.contact_spring", "in-series",
            lambda: fx.ObjectModes().contact_spring(BRASS, PROBE, object_loss=True),
            same=lambda r: math.isclose(r[0], 1 / (1 / _tube_on_brass().hertz
                                                   + 1 / _tube_on_brass().ring),
                                        rel_tol=4 * np.finfo(float).eps)),
        # neither body loses energy: the spring is lossless, exactly
        Row(s + "objects.ObjectModes.contact_spring", "lossless-bodies",
            lambda: fx.ObjectModes().contact_spring(
                BRASS, dataclasses.replace(PROBE, loss_factor=0.0), object_loss=False),
            same=lambda r: r[1] == 0.0),
        Row(s + "physics.ContactCompliance.stiffness", "obj-int",
            lambda: fx.ContactCompliance().stiffness(5, PROBE), ("obj",)),
        Row(s + "physics.ContactCompliance.effective_modulus", "probe-int",
            lambda: fx.ContactCompliance().effective_modulus(BRASS, 5), ("probe",)),
        # Hertz: 1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2
        Row(s + "physics.ContactCompliance.effective_modulus", "by-hand",
            lambda: fx.ContactCompliance().effective_modulus(BRASS, PROBE),
            same=lambda e: math.isclose(1 / e, (1 - 0.39**2) / PROBE.youngs_modulus
                                        + (1 - BRASS.poisson_ratio**2) / BRASS.youngs_modulus,
                                        rel_tol=1e-14)),
        Row(s + "physics.StructuralDamping.damping_ratio", "probe-int",
            lambda: fx.StructuralDamping().damping_ratio(5), ("probe",)),
        Row(s + "physics.StructuralDamping.damping_ratio", "half-the-loss-factor",
            lambda: fx.StructuralDamping().damping_ratio(Probe(loss_factor=0.04)),
            same=lambda r: r == 0.02),
        Row(s + "hertz.HertzContact.spring", "preload-nan",
            lambda: fx.HertzContact().spring(BRASS, PROBE, 0.012, NAN), ("preload",)),
        Row(s + "hertz.HertzContact.spring", "obj-int",
            lambda: fx.HertzContact().spring(5, PROBE, 0.012, 0.5), ("obj",)),
        Row(s + "hertz.HertzContact.spring", "diameter-negative",
            lambda: fx.HertzContact().spring(BRASS, PROBE, -1.0, 0.5), ("diameter",)),
    ]


def all_rows():
    return _construction_rows() + _method_rows()


(IDS, test_the_rows_are_distinct, test_every_row_ends_in_a_clear_error_or_the_right_answer,
 contract_rows) = row_tests(all_rows, 'ebantenna.simulate.effects.')


def contract_exempt() -> dict[str, str]:
    """Effects of no parameter: their constructor takes nothing (read by the inventory test)."""
    return {f"{cls.__module__}.{cls.__qualname__}": "an effect of no parameter"
            for cls, fields in PARAMETERS.items() if not fields}
