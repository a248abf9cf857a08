"""Fit configuration: grouped YAML round trip, old flat files, overrides, bad values."""

import pytest
import yaml

from unsew.errors import InputError
from unsew.fit.config import (
    LEGACY_KEYS,
    FitConfig,
    LossWeights,
    OptimizerSettings,
    config_to_dict,
    load_config,
)
from unsew.sim.drape import DrapeSettings


def test_defaults_follow_the_paper():
    c = FitConfig()
    o, w = c.optimizer, c.loss
    assert (o.lr, o.betas, w.open, w.material, c.drape.dt) == (1e-3, (0.9, 0.999), 0.1, 0.01, 0.05)
    assert 10 <= c.drape.steps <= 20
    assert o.lr_decay == 1.0  # constant learning rate, as the paper states no schedule


def test_yaml_round_trip_and_overrides(tmp_path):
    c = FitConfig(
        optimizer=OptimizerSettings(iterations=7, betas=(0.8, 0.99)),
        loss=LossWeights(curvature_weighted=False),
        drape=DrapeSettings(sew_steps=33),
    )
    p = tmp_path / "fit.yaml"
    text = yaml.safe_dump(config_to_dict(c))
    assert "candidates: []" in text and "- H00" in text  # lists as lists
    p.write_text(text)
    assert load_config(p) == c
    assert load_config(p, iterations=3).optimizer.iterations == 3
    assert load_config(p, optimizer={"iterations": 4}).optimizer == OptimizerSettings(
        iterations=4, betas=(0.8, 0.99)
    )


def test_old_flat_file_loads_into_the_groups(tmp_path):
    """A config.yaml of the flat format still loads; its on/off switches become a zero weight
    and an empty list."""
    p = tmp_path / "old.yaml"
    p.write_text(
        "iterations: 9\nsew_steps: 70\nmaterial: silk\nmaterial_candidates: cotton,silk\n"
        "lambda_seam: 0.5\nseam_loss: false\noptimize_material: false\nmaterial_params: H22,k\n"
        "redress_check: false\nreport: false\nfit_friction_eps: 0.002\nbetas: [0.8, 0.9]\n"
    )
    c = load_config(p)
    assert (c.optimizer.iterations, c.drape.sew_steps, c.material.start) == (9, 70, "silk")
    assert c.material.candidates == ("cotton", "silk") and c.optimizer.betas == (0.8, 0.9)
    assert c.loss.seam == 0.0 and c.material.fit == () and not c.fits_material
    assert (c.checks.redress, c.output.report, c.optimizer.friction_eps) == (False, False, 0.002)
    assert load_config(material_params="H22,k").material.fit == ("H22", "k")
    assert load_config(seam_loss=True, lambda_seam=0.5).loss.seam == 0.5
    for old, place in LEGACY_KEYS.items():  # every old name lands on a field that exists
        group, name = place.split(".")
        assert hasattr(getattr(FitConfig(), group), name), old


def test_a_result_folders_config_loads(tmp_path):
    c = load_config(iterations=5, edge_length=0.03)
    p = tmp_path / "config.yaml"
    p.write_text(
        yaml.safe_dump({"config": config_to_dict(c), "case": "x", "unsew_version": "0"}, sort_keys=False)
    )
    assert load_config(p) == c


@pytest.mark.parametrize(
    "text, match",
    [
        ("iterationz: 3\n", "unknown config option"),
        ("optimizer:\n  iterationz: 3\n", "unknown config option.*optimizer.iterationz"),
        ("iterations: 2.5\n", "iterations"),
        ("grading: yes please\n", "grading"),
        ("edge_length: 2\n", "edge_length"),
        ("drape:\n  edge_length: 2\n", "drape.edge_length"),
        ("- a\n- b\n", "mapping"),
        ("a: [\n", "not valid YAML"),
        ("lr_decay: 0\n", "lr_decay"),
        ("lr_decay: 1.5\n", "lr_decay"),
        ("material: velvet\n", "unknown material 'velvet'"),
        ("fit_friction_eps: 0\n", "fit_friction_eps"),
        ("redress_check: maybe\n", "redress_check"),
        ("seam_loss: maybe\n", "seam_loss"),
        ("mesh_spread: 0.6\n", "mesh_spread"),
        ("mesh_spread: -0.1\n", "mesh_spread"),
        ("checks:\n  redress_meshes: 2\n", "checks.redress_meshes must be 1 or 3"),
        ("optimizer:\n  bands: loose\n", "optimizer.bands must be one of free, height, held"),
        ("optimizer:\n  seams: tight\n", "optimizer.seams must be one of held, soft, trued"),
        ("loss:\n  area: -1\n", "loss.area must be >= 0"),
        ("lambda_prior: -0.5\n", "must be >= 0"),
        ("material: auto\nmaterial_candidates: silk,tweed\n", "unknown material 'tweed'"),
        ("material:\n  candidates: [silk, tweed]\n", "unknown material 'tweed'"),
        ("drape:\n  backend: pardiso\n", "drape.backend: unknown solver backend 'pardiso'"),
    ],
)
def test_bad_configs(tmp_path, text, match):
    p = tmp_path / "fit.yaml"
    p.write_text(text)
    with pytest.raises(InputError, match=match) as err:
        load_config(p)
    assert "\n" not in str(err.value)  # one line


def test_missing_config(tmp_path):
    with pytest.raises(InputError, match="does not exist"):
        load_config(tmp_path / "none.yaml")


def test_precedence_flags_over_file_over_defaults(tmp_path):
    p = tmp_path / "fit.yaml"
    p.write_text("iterations: 9\nsteps: 11\n")
    c = load_config(p, defaults={"iterations": 30, "steps": 12, "edge_length": 0.03}, steps=13)
    assert (c.optimizer.iterations, c.drape.steps, c.drape.edge_length) == (9, 13, 0.03)
    c = load_config(p, defaults={"drape": {"steps": 12, "edge_length": 0.03}}, drape={"steps": 14})
    assert (c.optimizer.iterations, c.drape.steps, c.drape.edge_length) == (9, 14, 0.03)


def test_material_fit_lists_entries_of_gamma():
    from unsew.fit.config import material_mask

    assert material_mask(("H00", "H01", "H11", "H22", "k")) == (True,) * 5
    assert material_mask(" k , H22") == (False, False, False, True, True)
    assert material_mask(()) == (False,) * 5  # the material stays fixed
    for bad in ("k,H33", "bend"):
        with pytest.raises(InputError, match="material_params"):
            load_config(material_params=bad)
        with pytest.raises(InputError, match="material.fit"):
            load_config(material={"fit": bad.split(",")})


def test_cli_flags_map_onto_the_groups():
    import argparse

    from unsew.commands.fit import add_fit_options, config_from_args

    p = argparse.ArgumentParser()
    add_fit_options(p)
    args = p.parse_args(
        [
            "--iterations",
            "4",
            "--edge-length",
            "0.03",
            "--steps",
            "9",
            "--material",
            "silk",
            "--no-grading",
            "--plain-chamfer",
            "--no-seam-loss",
            "--no-material",
            "--no-report",
            "--time-limit",
            "300",
        ]
    )
    c = config_from_args(args, defaults={"optimizer": {"iterations": 80}})
    assert (c.optimizer.iterations, c.drape.edge_length, c.drape.steps, c.material.start) == (
        4,
        0.03,
        9,
        "silk",
    )
    assert not c.grading and not c.loss.curvature_weighted and c.loss.seam == 0.0
    assert c.material.fit == () and not c.output.report and c.time_limit == 300.0
    c = config_from_args(p.parse_args([]), defaults={"optimizer": {"iterations": 80}})
    assert c.optimizer.iterations == 80 and c.time_limit == 540.0
