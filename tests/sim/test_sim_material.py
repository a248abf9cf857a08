"""Material library and Gamma checks."""

import pytest
import torch

from unsew.errors import InputError
from unsew.sim.material import MATERIALS, Material, check_gamma, get_material


@pytest.mark.parametrize("name", ["cotton", "denim", "silk", "polyester", "jersey", "knit", "wool"])
def test_library_materials_are_valid(name):
    m = get_material(name)
    g = m.gamma()
    assert g.shape == (5,) and g.dtype == torch.float64
    check_gamma(g)  # positive definite membrane, non-negative bending
    assert 0.03 < m.density < 0.5  # kg/m^2: real fabric weights
    assert 1e-7 < m.bend < 1e-4  # N*m: KES range converted


def test_denim_stiffer_and_heavier_than_silk():
    d, s = MATERIALS["denim"], MATERIALS["silk"]
    assert d.h00 > s.h00 and d.bend > s.bend and d.density > s.density


@pytest.mark.parametrize(
    "kw",
    [
        dict(h00=-1.0),
        dict(h22=0.0),
        dict(bend=-1e-6),
        dict(h01=5000.0),
        dict(density=0.0),
        dict(friction=-0.1),
    ],
)
def test_bad_material_raises(kw):
    base = dict(h00=1000.0, h01=100.0, h11=1000.0, h22=50.0, bend=1e-6, density=0.1)
    base.update(kw)
    with pytest.raises(InputError):
        Material(**base)


def test_unknown_material_names_choices():
    with pytest.raises(InputError, match="cotton"):
        get_material("kevlar")


def test_material_dict_round_trip_and_errors():
    import pytest

    from unsew.errors import InputError
    from unsew.sim.material import MATERIALS, MATERIAL_KEYS, material_from_dict, material_to_dict

    for m in MATERIALS.values():
        d = material_to_dict(m)
        assert tuple(d) == MATERIAL_KEYS
        assert material_from_dict(d) == m
    d = material_to_dict(MATERIALS["cotton"])
    with pytest.raises(InputError, match="lacks 'friction'"):
        material_from_dict({k: v for k, v in d.items() if k != "friction"})
    with pytest.raises(InputError, match="must be numbers"):
        material_from_dict({**d, "H00_N_per_m": "stiff"})
    with pytest.raises(InputError, match="positive"):
        material_from_dict({**d, "H22_N_per_m": -1.0})
