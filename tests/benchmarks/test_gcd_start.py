"""The gcd build's start: arm pieces stay around the arm, a wide front stays in front."""

import json
from pathlib import Path

import numpy as np
import pytest

from benchmarks.gcd import build

ROOT = Path(__file__).resolve().parents[2]
SHARED = next((p / "shared" for p in ROOT.parents if (p / "shared" / "garmentcode").is_dir()), None)


def _rect(x0, x1, y0, y1, z):
    """A GarmentCode panel [cm]: a rectangle from (x0, y0) to (x1, y1) in the plane z, facing +Z."""
    w, h = x1 - x0, y1 - y0
    return {
        "translation": [x0, y0, z],
        "rotation": [0.0, 0.0, 0.0],
        "vertices": [[0.0, 0.0], [w, 0.0], [w, h], [0.0, h]],
        "edges": [{"endpoints": [i, (i + 1) % 4]} for i in range(4)],
    }


@pytest.fixture(scope="module")
def placed():
    """GarmentCode's male body, a front wider than half the girth (a flared skirt's), a back, a
    left torso half reaching the centre front, and a left sleeve's front beside the torso."""
    if SHARED is None:
        pytest.skip("needs shared/ (GarmentCode's bodies) beside the checkout")
    d = SHARED / "foreign" / "bodies"
    body_v, _ = _body(d / "mean_male.obj")
    panels = {
        "front": _rect(-100, 100, 80, 100, 25),
        "back": _rect(-30, 30, 80, 100, -20),
        "torso_half": _rect(0, 22, 105, 140, 25),
        "sleeve_f": _rect(20, 45, 110, 135, 20),
    }
    spec = {"pattern": {"panels": panels, "stitches": []}, "properties": {"units_in_meter": 100}}
    mesh = build.mesh_spec(json.loads(json.dumps(spec)), "probe", 0.05)
    x_spec = build.spec_placement(spec, mesh)
    x0 = build.wrap_on_torso(build.bend_around_body(x_spec, mesh, spec, body_v), mesh, spec, body_v)
    return mesh, spec, body_v, x_spec, x0


def _body(path):
    import trimesh

    m = trimesh.load(path, process=False, force="mesh")
    return np.asarray(m.vertices, np.float64), np.asarray(m.faces, np.int64)


def _panel(mesh, name, x):
    i = list(mesh.panel_names).index(name)
    return x[int(mesh.panel_offsets[i]) : int(mesh.panel_offsets[i + 1])]


def test_arm_piece_keeps_its_placement_and_torso_pieces_are_bent(placed):
    mesh, spec, body_v, x_spec, x0 = placed
    beside = dict(zip(mesh.panel_names, build.beside_torso(x_spec, mesh, body_v)))
    assert beside == {"front": False, "back": False, "torso_half": False, "sleeve_f": True}
    np.testing.assert_array_equal(_panel(mesh, "sleeve_f", x0), _panel(mesh, "sleeve_f", x_spec))
    assert np.abs(_panel(mesh, "torso_half", x0) - _panel(mesh, "torso_half", x_spec)).max() > 0.05


def test_wide_front_is_wrapped_on_the_front(placed):
    """A front 2 m wide bent round the body has most of its width past the sides; it is still a
    front panel: its centre column stays in front of the body, not behind."""
    mesh, spec, body_v, x_spec, x0 = placed
    side = build._front_back(mesh, spec, body_v)
    assert set(_panel(mesh, "front", side.astype(float))) == {1.0}
    assert set(_panel(mesh, "back", side.astype(float))) == {-1.0}
    f, fs = _panel(mesh, "front", x0), _panel(mesh, "front", x_spec)
    centre = np.abs(fs[:, 0]) < 0.1
    assert centre.any() and f[centre, 2].min() > body_v[:, 2].max() - 0.05
