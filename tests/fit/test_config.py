"""Fit configuration: YAML round trip, overrides, bad values."""

import pytest
import yaml

from unsew.errors import InputError
from unsew.fit.config import FitConfig, config_to_dict, load_config


def test_defaults_follow_the_paper():
    c = FitConfig()
    assert (c.lr, c.betas, c.lambda_open, c.lambda_mat, c.dt) == (1e-3, (0.9, 0.999), 0.1, 0.01, 0.05)
    assert 10 <= c.steps <= 20
    assert c.lr_decay == 1.0  # constant learning rate, as the paper states no schedule


def test_yaml_round_trip_and_overrides(tmp_path):
    c = FitConfig(iterations=7, curvature_weighted=False, betas=(0.8, 0.99))
    p = tmp_path / "fit.yaml"
    p.write_text(yaml.safe_dump(config_to_dict(c)))
    assert load_config(p) == c
    assert load_config(p, iterations=3).iterations == 3


@pytest.mark.parametrize(
    "text, match",
    [
        ("iterationz: 3\n", "unknown config option"),
        ("iterations: 2.5\n", "iterations"),
        ("grading: yes please\n", "grading"),
        ("edge_length: 2\n", "edge_length"),
        ("- a\n- b\n", "mapping"),
        ("a: [\n", "not valid YAML"),
        ("lr_decay: 0\n", "lr_decay"),
        ("lr_decay: 1.5\n", "lr_decay"),
        ("material: velvet\n", "unknown material 'velvet'"),
        ("fit_friction_eps: 0\n", "fit_friction_eps"),
        ("redress_check: maybe\n", "redress_check"),
        ("mesh_spread: 0.6\n", "mesh_spread"),
        ("mesh_spread: -0.1\n", "mesh_spread"),
        ("material: auto\nmaterial_candidates: silk,tweed\n", "unknown material 'tweed'"),
    ],
)
def test_bad_configs(tmp_path, text, match):
    p = tmp_path / "fit.yaml"
    p.write_text(text)
    with pytest.raises(InputError, match=match):
        load_config(p)


def test_missing_config(tmp_path):
    with pytest.raises(InputError, match="does not exist"):
        load_config(tmp_path / "none.yaml")


def test_precedence_flags_over_file_over_defaults(tmp_path):
    p = tmp_path / "fit.yaml"
    p.write_text("iterations: 9\nsteps: 11\n")
    c = load_config(p, defaults={"iterations": 30, "steps": 12, "edge_length": 0.03}, steps=13)
    assert (c.iterations, c.steps, c.edge_length) == (9, 13, 0.03)


def test_material_params_lists_entries_of_gamma():
    from unsew.errors import InputError
    from unsew.fit.config import load_config, material_mask

    assert material_mask("H00,H01,H11,H22,k") == (True,) * 5
    assert material_mask(" k , H22") == (False, False, False, True, True)
    for bad in ("", "k,H33", "bend"):
        with pytest.raises(InputError, match="material_params"):
            load_config(material_params=bad)
