"""The glossary's terms are the ones the course needs, and every code name it gives exists."""

from __future__ import annotations

import inspect
import math
import re
from dataclasses import fields
from pathlib import Path

import numpy as np

from ebantenna import Probe
from ebantenna.fem import Supports, symbolic
from ebantenna.ml import SVC
from ebantenna.probe import Material
from ebantenna.recording import Recording
from ebantenna.signal import DecayFit, KalmanFilter, fit_decay

DOCS = Path(__file__).resolve().parents[2] / "docs"
TEXT = (DOCS / "glossary.rst").read_text()


def _terms() -> set[str]:
    body = TEXT.split(".. glossary::", 1)[1]
    return set(re.findall(r"^   (\S[^\n]*)$", body, flags=re.M))


def test_every_symbol_of_the_notation_is_a_term():
    wanted = {"E", "I", "EI", "ρA", "l", "h", "L", "P", "Q", "R", "zone", "fs", "τ", "1/b", "η",
              "ζ", "C", "γ"}
    assert wanted <= _terms()


def test_every_term_link_resolves_to_a_term():
    for target in re.findall(r":term:`(?:[^`<]*<)?([^`>]+)>?`", TEXT):
        assert target in _terms(), target


def test_code_names_exist():
    names = {f.name for f in fields(Probe)}
    assert {"youngs_modulus", "length", "density", "loss_factor"} <= names
    assert {"second_moment", "flexural_rigidity", "mass_per_length", "area"} <= set(dir(Probe))
    assert "loss_factor" in {f.name for f in fields(Material)}
    assert {"hinge", "contact"} <= {f.name for f in fields(Supports)}
    assert "fs" in {f.name for f in fields(Recording)}
    assert {"tau", "b"} <= {f.name for f in fields(DecayFit)}
    assert "damping_ratio" in inspect.signature(KalmanFilter.resonator).parameters
    assert {"C", "gamma"} <= set(SVC().get_params())
    assert {str(s) for s in (symbolic.l, symbolic.l1, symbolic.l2)} == {"l", "l1", "l2"}


def test_definitions_hold_for_the_default_probe():
    probe = Probe()
    d_out, d_in = probe.outer_diameter, probe.inner_diameter
    # I = pi (D^4 - d^4) / 64 and EI, rho A as the glossary defines them (a few roundings)
    assert math.isclose(probe.second_moment, math.pi * (d_out**4 - d_in**4) / 64, rel_tol=1e-15)
    assert math.isclose(probe.flexural_rigidity, probe.youngs_modulus * probe.second_moment,
                        rel_tol=1e-15)
    assert math.isclose(probe.mass_per_length, probe.density * probe.area, rel_tol=1e-15)


def test_tau_is_minus_one_over_b():
    fs, tau = 1000.0, 0.12
    t = np.arange(1000) / fs
    fit = fit_decay(np.exp(-t / tau) * np.sin(2 * np.pi * 95.0 * t), fs)
    assert fit.b < 0
    assert math.isclose(fit.tau, -1.0 / fit.b, rel_tol=1e-12)  # one division, rounded once
