"""Fit configuration: grouped YAML round trip, old keys refused, overrides, bad values, the count
of settings."""

import pytest
import yaml

from unsew.errors import InputError
from unsew.fit.config import (
    FitConfig,
    LossWeights,
    OptimizerSettings,
    config_to_dict,
    load_config,
    user_settings,
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
        optimizer=OptimizerSettings(iterations=7, lr=2e-3),
        loss=LossWeights(curvature_weighted=False),
        drape=DrapeSettings(sew_steps=33),
    )
    p = tmp_path / "fit.yaml"
    text = yaml.safe_dump(config_to_dict(c))
    assert "candidates: []" in text and "- H00" in text  # lists as lists
    p.write_text(text)
    assert load_config(p) == c
    assert load_config(p, **{"optimizer.iterations": 3}).optimizer.iterations == 3
    assert load_config(p, optimizer={"iterations": 4}).optimizer == OptimizerSettings(iterations=4, lr=2e-3)


@pytest.mark.parametrize(
    "text, match",
    [
        ("iterations: 9\n", "config key 'iterations' was renamed: use 'optimizer.iterations'"),
        ("material: silk\n", "config key 'material' was renamed: use 'material.start'"),
        ("lambda_seam: 0.5\n", "config key 'lambda_seam' was renamed: use 'loss.seam'"),
        ("seam_loss: false\n", "config key 'seam_loss' was renamed: use 'loss.seam \\(0: off\\)'"),
        (
            "betas: [0.8, 0.9]\n",
            "'betas' is no longer a setting: it is the constant .*OptimizerSettings.betas",
        ),
        ("drape:\n  gravity: 9\n", "'drape.gravity' is no longer a setting: it is the constant .*gravity"),
        ("material:\n  regrade: 1\n", "'material.regrade' is no longer a setting: .*material.REGRADE"),
    ],
)
def test_an_old_key_is_refused_with_its_name_now(tmp_path, text, match):
    """A key of the flat files of earlier versions, or a former setting, is refused in one line
    that says what to write instead (or which constant it became)."""
    p = tmp_path / "old.yaml"
    p.write_text(text)
    with pytest.raises(InputError, match=match) as err:
        load_config(p)
    assert "\n" not in str(err.value)


def test_at_most_thirty_settings_each_with_a_default():
    """The settings a user sets, counted from the config's dataclass fields: at most 30, each
    loadable by its dotted name with its own default."""
    settings = user_settings()
    assert 0 < len(settings) <= 30, list(settings)
    assert load_config(**settings) == FitConfig()


def test_a_result_folders_config_loads(tmp_path):
    c = load_config(optimizer={"iterations": 5}, drape={"edge_length": 0.03})
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
        ("optimizer:\n  iterations: 2.5\n", "optimizer.iterations"),
        ("optimizer:\n  iterations: 0\n", "optimizer.iterations must be at least 1"),
        ("optimizer:\n  lr: 0\n", "optimizer.lr must be positive"),
        ("grading: yes please\n", "grading"),
        ("drape:\n  edge_length: 2\n", "drape.edge_length must be within 0.005-0.1 m"),
        ("drape:\n  dt: 0\n", "drape.dt must be in"),
        ("- a\n- b\n", "mapping"),
        ("a: [\n", "not valid YAML"),
        ("material:\n  start: velvet\n", "unknown material 'velvet'"),
        ("checks:\n  redress: maybe\n", "checks.redress"),
        ("checks:\n  mesh_spread: 0.6\n", "checks.mesh_spread must be in"),
        ("checks:\n  mesh_spread: -0.1\n", "checks.mesh_spread"),
        ("area: all\n", "area must be one of free, target"),
        ("side_seams: curved\n", "side_seams must be one of none, girth"),
        ("time_limit: -1\n", "time_limit must be >= 0"),
        ("loss:\n  seam: -1\n", "loss.seam must be >= 0"),
        ("material:\n  start: auto\n  candidates: silk,tweed\n", "unknown material 'tweed'"),
        ("material:\n  candidates: [silk, tweed]\n", "unknown material 'tweed'"),
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
    p.write_text("optimizer:\n  iterations: 9\ndrape:\n  steps: 11\n")
    c = load_config(
        p,
        defaults={"optimizer.iterations": 30, "drape.steps": 12, "drape.edge_length": 0.03},
        **{"drape.steps": 13},
    )
    assert (c.optimizer.iterations, c.drape.steps, c.drape.edge_length) == (9, 13, 0.03)
    c = load_config(p, defaults={"drape": {"steps": 12, "edge_length": 0.03}}, drape={"steps": 14})
    assert (c.optimizer.iterations, c.drape.steps, c.drape.edge_length) == (9, 14, 0.03)


def test_material_fit_lists_entries_of_gamma():
    from unsew.fit.config import material_mask

    assert material_mask(("H00", "H01", "H11", "H22", "k")) == (True,) * 5
    assert material_mask(" k , H22") == (False, False, False, True, True)
    assert material_mask(()) == (False,) * 5  # the material stays fixed
    for bad in ("k,H33", "bend"):
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
