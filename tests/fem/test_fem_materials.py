"""The touched materials: every number inside its sources' range, and bad values refused."""

import pytest

from ebantenna.fem.coupling import Rod
from ebantenna.probe import ALIASES, MATERIALS, Material, material, material_names


def test_the_paper_materials_in_the_paper_order():
    assert material_names() == ("aluminium", "brass", "wood", "steel", "pvc")


@pytest.mark.parametrize("name", list(MATERIALS))
def test_every_material_is_sourced_and_inside_its_ranges(name):
    m = MATERIALS[name]
    assert m.source and m.ranges
    for field, low, high in m.ranges:
        assert low <= getattr(m, field) <= high
    assert 0 < m.loss_factor < 0.1 and 0 < m.poisson_ratio < 0.5
    assert 0 < m.transverse_modulus <= m.youngs_modulus


def test_oak_is_stiffer_along_the_grain_and_metals_are_isotropic():
    oak = material("Oak")
    # FPL table 5-1: E_R / E_L = 0.154, E_T / E_L = 0.082 for red oak; their mean is taken
    assert oak.transverse_modulus / oak.youngs_modulus == pytest.approx(0.118, abs=0.002)
    for name in ("aluminium", "brass", "steel", "pvc"):
        assert material(name).youngs_modulus_across is None


def test_aliases_and_old_names_still_work():
    for alias, name in ALIASES.items():
        assert material(alias.upper()) is MATERIALS[name]
    assert material("wood").name == "wood"


def test_the_loss_factors_order_metals_below_wood_and_pvc():
    eta = {n: m.loss_factor for n, m in MATERIALS.items()}
    assert max(eta["aluminium"], eta["steel"], eta["brass"]) < min(eta["wood"], eta["pvc"])


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"loss_factor": -0.01}, "loss_factor must be >= 0"),
        ({"youngs_modulus": 0.0}, "youngs_modulus must be > 0"),
        ({"density": -1.0}, "density must be > 0"),
        ({"poisson_ratio": 0.6}, r"poisson_ratio must lie in \(-1, 0.5\)"),
        ({"youngs_modulus_across": -1e9}, "youngs_modulus_across must be > 0"),
        ({"ranges": (("density", 1.0, 2.0),)}, r"density must lie in its sources' range"),
    ],
)
def test_bad_material_names_the_parameter(kwargs, message):
    base = dict(
        name="x",
        youngs_modulus=1e9,
        density=1000.0,
        poisson_ratio=0.3,
        loss_factor=0.01,
        source="test",
    )
    with pytest.raises(ValueError, match=message):
        Material(**(base | kwargs))


def test_a_rod_of_a_lossy_material_refuses_a_negative_loss_factor():
    with pytest.raises(ValueError, match="loss_factor must be >= 0"):
        Rod(Material("bad", 1e9, 1000.0, 0.3, -1e-3, "test"))
