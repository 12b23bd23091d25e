"""The controls: the equivalent rod against the closed-form cantilever, the ablation on a tiny
design."""

import math
from dataclasses import replace

import numpy as np
import pytest

from ebantenna.fem.coupling import Rod
from ebantenna.paper.controls import (
    ABLATION_DESIGN,
    _ablated_scene,
    ablation_accuracies,
    equivalent_pair_accuracy,
    equivalent_pair_scenes,
    equivalent_rod,
)
from ebantenna.probe import material
from ebantenna.simulate import builtin_scene

#: The solver's result passes through a fifth root, a square and a square root, and the checks
#: through fourth powers and cubes: some tens of roundings of 1.1e-16 each.
ROUNDING = 1e-14


def stiffness(rod: Rod) -> float:
    """Tip stiffness of the rod as a cantilever, 3EI/l^3, N/m (I = pi d^4 / 64)."""
    E = rod.material.youngs_modulus
    return 3 * E * math.pi * rod.diameter**4 / 64 / rod.free_length**3


@pytest.mark.parametrize("other", ["steel", "brass", "pvc", "wood"])
@pytest.mark.parametrize(("d", "length"), [(0.012, 0.25), (0.02, 0.4), (0.005, 0.1)])
def test_equivalent_rod_matches_stiffness_frequencies_and_mass(other, d, length):
    al = Rod("aluminium", diameter=d, free_length=length)
    twin = equivalent_rod(al, other)
    assert twin.material.name == material(other).name
    # the closed forms, written independently of the solver
    assert stiffness(twin) == pytest.approx(stiffness(al), rel=ROUNDING)
    assert twin.cantilever_frequency() == pytest.approx(al.cantilever_frequency(), rel=ROUNDING)
    # and through the package's own beam: flexural rigidity over l^3
    k = [3 * r.as_beam().flexural_rigidity / r.free_length**3 for r in (al, twin)]
    assert k[1] == pytest.approx(k[0], rel=ROUNDING)
    # k = m_eff omega^2 with matched k and omega: the mass matches too (rho A l)
    mass = [r.as_beam().mass_per_length * r.free_length for r in (al, twin)]
    assert mass[1] == pytest.approx(mass[0], rel=ROUNDING)
    # the contact stays at the same point of the mode shapes
    assert twin.contact_height / twin.free_length == pytest.approx(1.0, rel=ROUNDING)


def test_equivalent_of_the_same_material_is_the_same_rod():
    al = Rod("aluminium")
    twin = equivalent_rod(al, "aluminium")
    assert twin.diameter == pytest.approx(al.diameter, rel=ROUNDING)
    assert twin.free_length == pytest.approx(al.free_length, rel=ROUNDING)


def test_the_pair_needs_the_rod_modes():
    scene = builtin_scene("paper")
    without = scene.with_(
        effects=[
            e
            for e in scene.effects
            if e.name
            not in ("object_modes", "object_damping", "preload_scatter", "unilateral_contact")
        ]
    )
    with pytest.raises(ValueError, match="object_modes"):
        equivalent_pair_scenes(without)
    with pytest.raises(TypeError, match="reference"):
        equivalent_rod("aluminium", "steel")


def test_ablation_on_a_tiny_design(tmp_path):
    scene = builtin_scene("paper")
    tiny = replace(ABLATION_DESIGN, materials=("brass", "pvc"), contact_step=0.05, repetitions=1)
    ab = ablation_accuracies(
        scene, ["gravity", "object_modes", "tip_mass"], design=tiny, cache_dir=tmp_path
    )
    # the three need the rod's modes
    both = "object_modes+object_damping+preload_scatter+unilateral_contact"
    assert list(ab.accuracies) == ["none", "gravity", both]
    assert all(0.0 <= a <= 1.0 for a in ab.accuracies.values())
    # 2 held-out positions x 2 materials: accuracies are multiples of 1/4
    assert all(np.isclose(4 * a, round(4 * a)) for a in ab.accuracies.values())
    assert ab.dropped_together == {"object_modes": tuple(both.split("+"))}
    assert "tip mass" in ab.refused["tip_mass"]
    # one cached data set per scene, each with the effects it was built without
    files = sorted(p.name for p in tmp_path.glob("*.npz"))
    assert len(files) == 3 and any("without-gravity" in f for f in files)
    with pytest.raises(ValueError, match="names must be effects"):
        ablation_accuracies(scene, ["no_such_effect"], design=tiny, cache_dir=tmp_path)


def test_equivalent_pair_scenes_touch_the_matched_rods():
    scene = builtin_scene("paper")
    al_scene, steel_scene = equivalent_pair_scenes(scene)
    assert (al_scene.material, steel_scene.material) == ("aluminium", "steel")
    al, st = al_scene.effect("object_modes"), steel_scene.effect("object_modes")
    assert (al.diameter, al.free_length) == (0.012, 0.25)  # the scene's own rod
    twin = equivalent_rod(Rod("aluminium", diameter=0.012, free_length=0.25), "steel")
    assert (st.diameter, st.free_length) == (twin.diameter, twin.free_length)
    # every other effect and parameter is the scene's
    assert [e for e in steel_scene.effects if e.name != "object_modes"] == [
        e for e in scene.effects if e.name != "object_modes"
    ]
    assert al_scene.name != steel_scene.name  # cached apart


def test_equivalent_pair_accuracy_on_a_tiny_design(tmp_path):
    tiny = replace(ABLATION_DESIGN, contact_step=0.05, repetitions=1)
    acc = equivalent_pair_accuracy(builtin_scene("paper"), design=tiny, cache_dir=tmp_path)
    # 2 held-out positions x 2 materials x 1 repetition: a multiple of 1/4
    assert 0.0 <= acc <= 1.0 and np.isclose(4 * acc, round(4 * acc))
    assert len(list(tmp_path.glob("*pair-aluminium*.npz"))) == 1
    assert len(list(tmp_path.glob("*pair-steel*.npz"))) == 1
    # the mode-curve classifier on the same two data sets, read from the cache
    curves = equivalent_pair_accuracy(
        builtin_scene("paper"), design=tiny, cache_dir=tmp_path, classifier="mode_curves"
    )
    assert 0.0 <= curves <= 1.0 and np.isclose(4 * curves, round(4 * curves))
    assert len(list(tmp_path.glob("*.npz"))) == 2
    with pytest.raises(ValueError, match="classifier"):
        equivalent_pair_accuracy(builtin_scene("paper"), cache_dir=tmp_path, classifier="knn")


def test_switching_off_the_dlpf_simulates_only_what_the_sampling_holds():
    # The paper scene simulates modes up to 3 kHz because the chip filters at 8 kHz before it
    # decimates; without the filter the scene at fs = 1 kHz can hold modes below 500 Hz only.
    scene = builtin_scene("paper")
    ablated, dropped, reason, change = _ablated_scene(scene, "dlpf")
    assert dropped == ("dlpf",) and reason is None
    assert ablated.max_frequency == scene.fs / 2 and "dlpf" not in ablated.effect_names
    assert "max_frequency lowered from 3000 to 500 Hz" in change
    # an effect that can simply go changes nothing else
    assert _ablated_scene(scene, "gravity")[3] is None
