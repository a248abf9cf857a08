"""unsew fit / unsew demo on bad input: one line, non-zero exit, nothing left behind."""

import json
import subprocess
import sys

import numpy as np
import pytest
import trimesh

from unsew.cli import main
from unsew.io.mesh import write_obj


def _case(tmp_path, *, target="tube", meta=None):
    d = tmp_path / "case"
    d.mkdir()
    if target == "tube":
        m = trimesh.creation.cylinder(radius=0.2, height=0.4, sections=24)
        keep = np.abs(m.face_normals[:, 2]) < 0.5
        v = m.vertices[:, [0, 2, 1]] + [0, 1.1, 0.0]
        write_obj(d / "target.obj", v, m.faces[keep])
    elif target == "sphere":
        s = trimesh.creation.icosphere(subdivisions=2, radius=0.2)
        write_obj(d / "target.obj", s.vertices + [0, 1.1, 0], s.faces)
    (d / "meta.json").write_text(json.dumps(meta or {"garment": "tshirt", "body": "default"}))
    return d


def _run(args, capsys):
    code = main(args)
    err = capsys.readouterr().err
    return code, err


def test_missing_case_folder(tmp_path, capsys):
    code, err = _run(["fit", str(tmp_path / "nope"), "--out", str(tmp_path / "r")], capsys)
    assert code == 2 and "does not exist" in err and err.count("\n") == 1
    assert not (tmp_path / "r").exists()


def test_missing_target(tmp_path, capsys):
    d = _case(tmp_path, target=None)
    code, err = _run(["fit", str(d), "--out", str(tmp_path / "r")], capsys)
    assert code == 2 and "no target" in err
    assert not (tmp_path / "r").exists() and not (tmp_path / "r.partial").exists()


def test_closed_sphere_is_not_a_garment(tmp_path, capsys):
    d = _case(tmp_path, target="sphere")
    code, err = _run(["fit", str(d), "--out", str(tmp_path / "r")], capsys)
    assert code == 2 and "closed surface" in err
    assert not (tmp_path / "r").exists()


def test_wrong_base_type(tmp_path, capsys):
    d = _case(tmp_path)
    code, err = _run(
        ["fit", str(d), "--base", "pants", "--out", str(tmp_path / "r"), "--no-progress"], capsys
    )
    assert code == 2 and "cannot make a tshirt" in err
    assert not (tmp_path / "r").exists() and not (tmp_path / "r.partial").exists()


def test_units_hint(tmp_path, capsys):
    d = _case(tmp_path)
    v, f = (
        trimesh.load(d / "target.obj", process=False).vertices,
        trimesh.load(d / "target.obj", process=False).faces,
    )
    write_obj(d / "target.obj", v * 100, f)
    code, err = _run(["fit", str(d), "--out", str(tmp_path / "r")], capsys)
    assert code == 2 and "--units cm" in err


def test_bad_config_value(tmp_path, capsys):
    d = _case(tmp_path)
    cfg = tmp_path / "fit.yaml"
    cfg.write_text("optimizer:\n  iterations: -3\n")
    code, err = _run(["fit", str(d), "--config", str(cfg), "--out", str(tmp_path / "r")], capsys)
    assert code == 2 and "optimizer.iterations must be at least 1" in err


def test_existing_output_is_not_overwritten(tmp_path, capsys):
    d = _case(tmp_path)
    (tmp_path / "r").mkdir()
    (tmp_path / "r" / "keep.txt").write_text("mine")
    code, err = _run(["fit", str(d), "--out", str(tmp_path / "r")], capsys)
    assert code == 2 and "exists" in err
    assert (tmp_path / "r" / "keep.txt").read_text() == "mine"


def test_no_traceback_in_a_real_process(tmp_path):
    r = subprocess.run(
        [sys.executable, "-m", "unsew", "fit", str(tmp_path / "nope"), "--out", str(tmp_path / "r")],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 2 and "Traceback" not in r.stderr and r.stderr.startswith("unsew: error:")


def test_unavailable_device(tmp_path, capsys):
    import torch

    if torch.cuda.is_available():
        pytest.skip("a CUDA device is present")
    d = _case(tmp_path)
    code, err = _run(
        ["fit", str(d), "--device", "cuda", "--out", str(tmp_path / "r"), "--no-progress"], capsys
    )
    assert code == 2 and "--device cpu" in err
    assert not (tmp_path / "r").exists() and not (tmp_path / "r.partial").exists()
