"""Scenes: validation, built-in scenes, TOML/JSON files."""

import json

import numpy as np
import pytest

from ebantenna.probe import Probe
from ebantenna.simulate import Scene, builtin_scene, load_scene
from ebantenna.simulate.effects import ObjectModes, SensorNoise, effect_names
from ebantenna.simulate.scene import resolve_scene


def test_builtin_scenes():
    ideal = builtin_scene("ideal")
    paper = builtin_scene("paper")
    assert ideal.effects == ()
    assert ideal.probe.tip_mass == 0
    # Every effect in application order, but the rigid object's spring (the rod brings its own)
    # and the friction along the rod (no tabulated coefficient for most of the materials), and
    # the contact's Hertz law (several times the linearised strike's cost, ebantenna bench).
    left_out = ("contact_compliance", "coulomb_friction", "hertz_contact")
    assert paper.effect_names == tuple(n for n in effect_names() if n not in left_out)
    assert 2e-3 <= paper.probe.tip_mass <= 3e-3  # the GY-521 board
    with pytest.raises(ValueError, match="ideal, paper"):
        builtin_scene("nope")


def test_with_replaces_and_validates():
    scene = builtin_scene("paper").with_(contact=0.25, material="Brass")
    assert (scene.contact, scene.material) == (0.25, "brass")
    with pytest.raises(ValueError, match="contact must lie in"):
        scene.with_(contact=0.5)
    with pytest.raises(TypeError, match="no field"):
        scene.with_(colour="red")


@pytest.mark.parametrize("ratio", [0.0, 1e-9, 1 - 1e-9, 1.0])
def test_a_contact_at_an_end_is_refused_at_every_entry(ratio):
    # fem.guards.check_contact: a span shorter than MIN_SPAN of the length cannot be meshed
    from ebantenna.fem.guards import MIN_SPAN
    from ebantenna.simulate import simulate_batch
    from ebantenna.simulate.structure import probe_contact_model

    scene = builtin_scene("ideal")
    contact = ratio * scene.probe.length
    assert min(ratio, 1 - ratio) < MIN_SPAN
    with pytest.raises(ValueError, match="contact must lie in"):
        scene.with_(contact=contact)
    with pytest.raises(ValueError, match="contact must lie in"):
        simulate_batch(scene, contact=[0.2, contact])
    with pytest.raises(ValueError, match="contact must lie in"):
        probe_contact_model(scene.probe, contact)


@pytest.mark.parametrize(
    "changes, message",
    [
        ({"duration": -1.0}, "duration must be > 0"),
        ({"duration": 1e9}, "at most 1e\\+07 samples"),
        ({"fs": 900.0}, "fs must be at least twice max_frequency"),
        ({"effects": ("gravity", "wobble")}, "unknown effect 'wobble'; valid effects: structural"),
        ({"effects": ("gravity", "gravity")}, "listed twice"),
        ({"material": "cheese"}, "aluminium, brass, wood, steel, pvc"),
        ({"hinge": "glued"}, "hinge must be one of"),
        ({"effects": ("object_damping",)}, "needs 'object_modes'"),
        ({"effects": ("object_modes", "contact_compliance")}, "both set the contact spring"),
        ({"effects": {"object_modes": {"preload": 0.0}}}, "preload must be > 0"),
        ({"effects": {"object_modes": {"contact_height": 0.3}}}, "contact_height"),
        ({"effects": {"object_modes": {"diameter": -0.01}}}, "diameter must be > 0"),
        ({"effects": {"dlpf": {"internal_rate": 7500.0}}}, "whole multiple of fs"),
        ({"effects": ("dlpf",), "max_frequency": 4100.0}, "internal_rate must be at least"),
        ({"probe": Probe(tip_mass=0.002)}, "'tip_mass' effect must be listed"),
        ({"effects": ("tip_mass",)}, "'tip_mass' effect must be listed"),
        ({"sweep_speed": 0.0}, "sweep_speed must be > 0"),
        ({"effects": {"dlpf": {"bandwidth": 100.0}}}, "bandwidth must be one of"),
        ({"effects": {"sensor_noise": {"color": "pink"}}}, "unknown parameter"),
    ],
)
def test_bad_scenes_are_clear_errors(changes, message):
    with pytest.raises(ValueError, match=message):
        builtin_scene("ideal").with_(**changes)


def test_effects_accept_names_instances_and_tables_in_canonical_order():
    scene = Scene(effects=[SensorNoise(density=0.01), "gravity", "contact_compliance"])
    assert scene.effect_names == ("contact_compliance", "gravity", "sensor_noise")
    assert scene.effect("sensor_noise").density == 0.01
    same = Scene(
        effects={"gravity": {}, "sensor_noise": {"density": 0.01}, "contact_compliance": {}}
    )
    assert same == scene
    assert scene.effect("dlpf") is None


@pytest.mark.parametrize("suffix", [".toml", ".json"])
def test_save_load_roundtrip(tmp_path, suffix):
    scene = builtin_scene("paper").with_(
        contact=0.3,
        material="wood",
        hinge=12.5,
        effects=builtin_scene("paper").effects[:1]
        + (ObjectModes(diameter=0.01, contact_height=0.2), "object_damping", "tip_mass"),
        max_frequency=480.0,  # no sensor filter: the modes must stay below fs / 2
    )
    path = scene.save(tmp_path / f"scene{suffix}")
    loaded = load_scene(path)
    assert loaded == scene
    assert loaded.to_dict() == scene.to_dict()
    assert resolve_scene(path) == scene
    assert resolve_scene("paper") == builtin_scene("paper")
    # Parameters left at None (the rod touched at its free end) survive both formats.
    paper = builtin_scene("paper")
    assert load_scene(paper.save(tmp_path / f"paper{suffix}")) == paper


def test_load_rejects_unknown_fields(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text(json.dumps({"contact": 0.2, "speed_of_light": 3e8}))
    with pytest.raises(ValueError, match="unknown scene field"):
        load_scene(path)
    with pytest.raises(ValueError, match="existing .toml/.json"):
        resolve_scene(tmp_path / "missing.toml")


def test_the_default_sweep_keeps_the_readings_in_range_up_to_035_m():
    # Scene.sweep_speed: "keeps the paper rig's readings inside +-16 g with the contact up to
    # 0.35 m from the hinge; nearer the tip the metals' strikes reach up to 26 g (steel at
    # 0.39 m), and the paper scene's clipping holds those samples at the rail"
    from ebantenna.probe import material_names
    from ebantenna.simulate import simulate_batch

    paper = builtin_scene("paper")
    sensor = {"clipping", "quantisation", "sensor_noise", "mains_hum", "sensor_drift",
              "clock_jitter", "kalman"}
    motion = paper.with_(effects=[e for e in paper.effects if e.name not in sensor])
    names = material_names()
    full_scale = 16 * 9.80665
    for contact, within in ((0.35, True), (0.39, False)):
        ax = simulate_batch(motion, contact=np.full(len(names), contact), material=names,
                            show_progress=False)[1]
        peaks = dict(zip(names, np.abs(ax).max(axis=1), strict=True))
        assert (max(peaks.values()) < full_scale) == within, (contact, peaks)
    assert 25 <= peaks["steel"] / 9.80665 < 27  # "up to 26 g": steel at 0.39 m
    chip = paper.with_(effects=[e for e in paper.effects if e.name != "kalman"])
    ax = simulate_batch(chip, contact=[0.39], material=["steel"], seeds=[0], show_progress=False)[1]
    low, high = paper.effect("clipping").limits()
    assert np.any((ax <= low) | (ax >= high))  # held at the rail
