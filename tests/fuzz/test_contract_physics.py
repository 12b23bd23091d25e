"""The input contract of scenes and of the contact laws.

A scene's effects are looked up by name; the contact laws take forces and approaches. Each gets
bad inputs (an effect name the package does not have, a non-numeric or negative force, a NaN
approach, a body that is not a ``Material``, a tolerance finer than the root finder's) and must
refuse each naming the parameter; a few results are checked against Hertz's formulas.

Found by these rows and fixed: ``scene.has("sensor_nois")`` answered False and
``scene.effect(5)`` None (a misspelt effect is never "not listed"), a Hertz-in-series law built
on an integer or a negative ring stiffness, NaN and negative forces and approaches accepted, a
chord bound of ``fa > fb`` computed, ``AttributeError`` from ``tube_on_rod_law`` given an
integer for its body, and SciPy's "f(a) and f(b) must have different signs" for a tolerance of
1e-300 N.
"""

from __future__ import annotations

import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, row_tests  # noqa: E402

from ebantenna import Probe  # noqa: E402
from ebantenna.probe import material  # noqa: E402
from ebantenna.simulate import builtin_scene  # noqa: E402
from ebantenna.simulate import contact as C  # noqa: E402
from ebantenna.simulate.scene import Scene, resolve_scene  # noqa: E402

NAN = math.nan
SCENE = builtin_scene("paper")
CYL = C.CrossedCylinders(0.004, 0.006, 3.5e9)
LAW = C.HertzInSeries(CYL, 2.7e5)
SPRING = C.PiecewiseSpring.linear(1e5)


def all_rows():
    s, c = "ebantenna.simulate.scene.", "ebantenna.simulate.contact."
    return [
        Row(s + "Scene.effect", "name-misspelt", lambda: SCENE.effect("sensor_nois"),
            ("sensor_nois",)),
        Row(s + "Scene.effect", "name-int", lambda: SCENE.effect(5), ("name",)),
        Row(s + "Scene.effect", "listed", lambda: SCENE.effect("gravity"),
            same=lambda e: e is not None and e.name == "gravity"),
        Row(s + "Scene.effect", "not-listed", lambda: builtin_scene("ideal").effect(
            "sensor_noise"), same=lambda e: e is None),
        Row(s + "Scene.has", "name-misspelt", lambda: SCENE.has("gravty"), ("gravty",)),
        Row(s + "Scene.has", "name-None", lambda: SCENE.has(None), ("name",)),
        Row(s + "Scene.has", "listed", lambda: SCENE.has("gravity"), same=lambda r: r is True),
        Row(s + "Scene.from_dict", "data-str", lambda: Scene.from_dict("x"), ("scene",)),
        Row(s + "Scene.from_dict", "unknown-field", lambda: Scene.from_dict({"colour": 1}),
            ("colour",)),
        Row(s + "Scene.from_dict", "probe-length-negative", lambda: Scene.from_dict(
            {**SCENE.to_dict(), "probe": {"length": -1}}), ("length",)),
        Row(s + "Scene.from_dict", "round-trip", lambda: Scene.from_dict(SCENE.to_dict()),
            same=lambda sc: sc == SCENE),
        Row(s + "Scene.to_dict", "round-trip", lambda: Scene.from_dict(
            builtin_scene("ideal").to_dict()).to_dict(),
            same=lambda d: d == builtin_scene("ideal").to_dict()),
        Row(s + "Scene.save", "path-empty", lambda: SCENE.save(""), ("path",)),
        Row(s + "Scene.save", "path-a-folder", lambda: SCENE.save(os.sep), ("path",)),
        Row(s + "Scene.save", "path-int", lambda: SCENE.save(5), ("path",)),
        Row(s + "Scene.with_", "unknown-field", lambda: SCENE.with_(colour=5), ("colour",)),
        Row(s + "Scene.with_", "fs-negative", lambda: SCENE.with_(fs=-1.0), ("fs",)),
        Row(s + "Scene.with_", "contact-beyond-tip", lambda: SCENE.with_(contact=1.0),
            ("contact",)),
        Row(s + "resolve_scene", "int", lambda: resolve_scene(5), ("scene",)),
        Row(s + "resolve_scene", "unknown", lambda: resolve_scene("nope"), ("nope",)),
        Row(s + "resolve_scene", "paper", lambda: resolve_scene("paper"),
            same=lambda sc: sc == SCENE),
        Row(c + "CrossedCylinders", "radius1-negative",
            lambda: C.CrossedCylinders(-1.0, 0.01, 1e9), ("radius1",)),
        Row(c + "CrossedCylinders", "modulus-nan", lambda: C.CrossedCylinders(0.01, 0.01, NAN),
            ("modulus",)),
        Row(c + "CrossedCylinders.approach", "force-negative", lambda: CYL.approach(-1.0),
            ("force",)),
        Row(c + "CrossedCylinders.force", "approach-str", lambda: CYL.force("x"),
            ("approach",)),
        Row(c + "CrossedCylinders.force", "approach-nan", lambda: CYL.force([NAN]),
            ("approach",)),
        # Hertz: P = (delta / delta(1 N))^(3/2), and no tension
        Row(c + "CrossedCylinders.force", "inverse-of-approach",
            lambda: CYL.force([CYL.approach(0.5), -1e-6]),
            same=lambda f: math.isclose(f[0], 0.5, rel_tol=1e-13) and f[1] == 0.0),
        Row(c + "CrossedCylinders.semi_axes", "force-nan", lambda: CYL.semi_axes(NAN),
            ("force",)),
        Row(c + "CrossedCylinders.stiffness", "preload-0", lambda: CYL.stiffness(0.0),
            ("preload",)),
        Row(c + "CrossedCylinders.stiffness", "three-halves-secant",
            lambda: CYL.stiffness(0.5),
            same=lambda k: math.isclose(k, 1.5 * 0.5 / CYL.approach(0.5), rel_tol=1e-15)),
        Row(c + "HertzInSeries", "ring-negative", lambda: C.HertzInSeries(CYL, -1.0),
            ("ring",)),
        Row(c + "HertzInSeries", "hertz-int", lambda: C.HertzInSeries(5, 1e6), ("hertz",)),
        Row(c + "HertzInSeries.approach", "force-nan", lambda: LAW.approach(NAN), ("force",)),
        Row(c + "HertzInSeries.approach", "force-negative", lambda: LAW.approach(-1.0),
            ("force",)),
        Row(c + "HertzInSeries.approach", "compliances-add",
            lambda: LAW.approach(0.5), same=lambda p: math.isclose(
                p, CYL.approach(0.5) + 0.5 / 2.7e5, rel_tol=1e-14)),
        Row(c + "HertzInSeries.stiffness", "force-negative", lambda: LAW.stiffness(-1.0),
            ("force",)),
        Row(c + "HertzInSeries.force", "approach-str", lambda: LAW.force("x"), ("approach",)),
        Row(c + "HertzInSeries.force", "inverse-of-approach",
            lambda: LAW.force(LAW.approach(0.5)),
            same=lambda f: math.isclose(f, 0.5, rel_tol=1e-12)),
        Row(c + "HertzInSeries.chord_bound", "fa-above-fb", lambda: LAW.chord_bound(2.0, 1.0),
            ("fa",)),
        Row(c + "HertzInSeries.chord_bound", "fb-nan", lambda: LAW.chord_bound(0.0, NAN),
            ("fb",)),
        Row(c + "HertzInSeries.piecewise", "tolerance-0", lambda: LAW.piecewise(0.0, 10.0),
            ("tolerance",)),
        Row(c + "HertzInSeries.piecewise", "tolerance-1e-300",
            lambda: LAW.piecewise(1e-300, 10.0), ("tolerance",)),
        Row(c + "HertzInSeries.piecewise", "max_force-nan", lambda: LAW.piecewise(0.01, NAN),
            ("max_force",)),
        Row(c + "HertzInSeries.piecewise", "within-tolerance",
            lambda: LAW.piecewise(0.01, 5.0, through=(0.5,)),
            same=lambda sp: sp.bound <= 0.01 and bool(np.any(sp.forces == 0.5))),
        Row(c + "PiecewiseSpring", "approaches-short", lambda: C.PiecewiseSpring(
            np.array([0.0, 1.0]), np.array([0.0]), np.array([1.0])), ("approaches",)),
        Row(c + "PiecewiseSpring.linear", "stiffness-negative",
            lambda: C.PiecewiseSpring.linear(-1.0), ("stiffness",)),
        Row(c + "PiecewiseSpring.linear", "hooke", lambda: C.PiecewiseSpring.linear(1e5).force(
            2e-6), same=lambda f: math.isclose(f, 0.2, rel_tol=1e-15)),
        Row(c + "PiecewiseSpring.approach_at", "force-nan", lambda: SPRING.approach_at(NAN),
            ("force",)),
        Row(c + "PiecewiseSpring.approach_at", "force-negative",
            lambda: SPRING.approach_at(-1.0), ("force",)),
        Row(c + "PiecewiseSpring.approach_at", "hooke", lambda: SPRING.approach_at(0.2),
            same=lambda p: math.isclose(p, 2e-6, rel_tol=1e-15)),
        Row(c + "PiecewiseSpring.force", "approach-str", lambda: SPRING.force("x"),
            ("approach",)),
        Row(c + "contact_modulus", "body1-int-without-poisson",
            lambda: C.contact_modulus(5, material("brass")), ("body1",)),
        Row(c + "contact_modulus", "body1-a-probe", lambda: C.contact_modulus(
            Probe(), material("brass")), ("body1",)),
        Row(c + "ring_stiffness", "inner-above-outer",
            lambda: C.ring_stiffness(0.01, 0.02, 1e9), ("inner_diameter",)),
        Row(c + "ring_stiffness", "youngs_modulus-negative",
            lambda: C.ring_stiffness(0.02, 0.01, -1.0), ("youngs_modulus",)),
        Row(c + "tube_on_rod_law", "obj-int", lambda: C.tube_on_rod_law(Probe(), 5, 0.012),
            ("obj",)),
        Row(c + "tube_on_rod_law", "probe-str", lambda: C.tube_on_rod_law(
            "probe", material("brass"), 0.012), ("probe",)),
        Row(c + "tube_on_rod_law", "rod_diameter-negative",
            lambda: C.tube_on_rod_law(Probe(), material("brass"), -1.0), ("rod_diameter",)),
        Row(c + "tube_on_rod_stiffness", "preload-nan", lambda: C.tube_on_rod_stiffness(
            Probe(), material("brass"), 0.012, NAN), ("preload",)),
        # the stiffness is the law's, linearised at the preload
        Row(c + "tube_on_rod_stiffness", "the-law's", lambda: (
            C.tube_on_rod_stiffness(Probe(), material("steel"), 0.012, 0.5),
            C.tube_on_rod_law(Probe(), material("steel"), 0.012).stiffness(0.5)),
            same=lambda r: math.isclose(r[0].total, r[1], rel_tol=1e-12)),
        Row(c + "tube_on_rod_spring", "object_loss-str", lambda: C.tube_on_rod_spring(
            Probe(), material("brass"), 0.012, 0.5, object_loss="no"), ("object_loss",)),
        Row(c + "tube_on_rod_spring", "preload-nan", lambda: C.tube_on_rod_spring(
            Probe(), material("brass"), 0.012, NAN, object_loss=True), ("preload",)),
        Row(c + "tube_on_rod_spring", "obj-int", lambda: C.tube_on_rod_spring(
            Probe(), 5, 0.012, 0.5, object_loss=True), ("obj",)),
        # the stiffness is tube_on_rod_stiffness's; bodies that lose alike give the spring their
        # loss factor (a compliance-weighted mean of equal values; a few roundings of it)
        Row(c + "tube_on_rod_spring", "equal-losses-weigh-to-theirs", lambda: (
            C.tube_on_rod_spring(Probe(loss_factor=material("steel").loss_factor),
                                 material("steel"), 0.012, 0.5, object_loss=True),
            C.tube_on_rod_stiffness(Probe(), material("steel"), 0.012, 0.5).total),
            same=lambda r: r[0][0] == r[1]
            and math.isclose(r[0][1], material("steel").loss_factor, rel_tol=1e-14)),
        # a lossless rod (object_loss False) and a lossless probe: a lossless spring
        Row(c + "tube_on_rod_spring", "lossless-bodies", lambda: C.tube_on_rod_spring(
            Probe(loss_factor=0.0), material("steel"), 0.012, 0.5, object_loss=False),
            same=lambda r: r[1] == 0.0 and r[0] > 0),
    ]


(IDS, test_the_rows_are_distinct, test_every_row_ends_in_a_clear_error_or_the_right_answer,
 contract_rows) = row_tests(all_rows, 'ebantenna.simulate.')
