"""The fit on altered targets: 1 mm noise, half the vertices, a file in cm; and (slow)
another pose and another body shape. Small mode: coarse mesh, few iterations; each must still
improve on the base pattern."""

import json
import shutil

import numpy as np
import pytest

from unsew.fit.config import load_config
from unsew.io.mesh import read_mesh, write_obj

SMALL = {
    "drape.edge_length": 0.03,
    "optimizer.iterations": 2,
    "drape.steps": 8,
    "drape.sew_steps": 60,
    "drape.settle_steps": 20,
    "loss.target_points": 1500,
    "material.start_iteration": 1,
    "material.start": "cotton",
}


def _settings(edge_length):
    """The targets' drape: the small fits' sewing and settling on a mesh of ``edge_length`` [m]."""
    return load_config(**SMALL).drape.replace(edge_length=edge_length)


@pytest.fixture(scope="module")
def base_case(tmp_path_factory):
    from unsew.fit.synthetic import make_truth_case

    return make_truth_case(
        tmp_path_factory.mktemp("c") / "tshirt", garment="tshirt", settings=_settings(0.03)
    )


def _fit(case_dir, out, **kw):
    from unsew.fit.run import run_fit
    from unsew.body.case import load_case

    cfg = load_config(**{**SMALL, "output.report": False, "checks.mesh_spread": 0.0})
    return run_fit(load_case(case_dir, **kw), cfg, out, progress=False, log=lambda s: None)


def _variant(base_case, tmp_path, name):
    d = tmp_path / name
    shutil.copytree(base_case, d)
    v, f = read_mesh(d / "target.obj")
    kw = {}
    if name == "noise":
        write_obj(d / "target.obj", v + np.random.default_rng(0).normal(scale=0.001, size=v.shape), f)
    elif name == "decimate":
        import trimesh  # quadric edge collapse (fast-simplification, in the test extra)

        m = trimesh.Trimesh(v, f, process=False).simplify_quadric_decimation(face_count=len(f) // 2)
        assert len(m.vertices) <= 0.55 * len(v)
        write_obj(d / "target.obj", m.vertices, m.faces)
    elif name == "cm":
        write_obj(d / "target.obj", v * 100.0, f)
        meta = json.loads((d / "meta.json").read_text())
        meta.pop("units")
        (d / "meta.json").write_text(json.dumps(meta))
        kw["units"] = "cm"
    return d, kw


@pytest.mark.parametrize("name", ["noise", "decimate", "cm"])
def test_robust_targets(base_case, tmp_path, name):
    d, kw = _variant(base_case, tmp_path, name)
    _, m = _fit(d, tmp_path / "r", **kw)
    assert m["surface"]["chamfer_mm"] < m["surface_base"]["chamfer_mm"]
    assert m["pattern"]["area_error_rel_mean"] < m["pattern_base"]["area_error_rel_mean"]


@pytest.mark.slow
@pytest.mark.parametrize("which", ["pose", "body"])
def test_other_pose_and_body(tmp_path, which):
    from unsew.body.body import default_body
    from unsew.body.pose import pose_body
    from unsew.fit.synthetic import make_truth_case

    b = (
        pose_body(default_body(), "left_arm_up")
        if which == "pose"
        else default_body().transformed(scale=np.array([1.08, 1.0, 1.08]))
    )
    d = make_truth_case(tmp_path / which, garment="tshirt", body=b, body_meta=None, settings=_settings(0.04))
    assert (d / "body.obj").is_file() and (d / "skeleton.json").is_file()
    _, m = _fit(d, tmp_path / "r")
    assert m["surface"]["chamfer_mm"] < m["surface_base"]["chamfer_mm"]
    assert m["pattern"]["area_error_rel_mean"] < m["pattern_base"]["area_error_rel_mean"]
