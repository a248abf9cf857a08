"""Case folders: loading, frames, and one-line errors for what is missing or wrong."""

import json

import numpy as np
import pytest
import trimesh

from unsew.errors import InputError
from unsew.body.case import load_case
from unsew.io.mesh import write_obj


def _tube(y0=0.9, y1=1.3, r=0.2):
    """An open cylinder around the default body's torso: a stand-in garment with two open loops."""
    m = trimesh.creation.cylinder(radius=r, height=y1 - y0, sections=32)
    keep = np.abs(m.face_normals[:, 2]) < 0.5  # drop the caps
    v = m.vertices[:, [0, 2, 1]] * [1, 1, -1] + [0, (y0 + y1) / 2, 0.05]
    f = m.faces[keep][:, [0, 2, 1]]
    used = np.unique(f)
    remap = -np.ones(len(v), int)
    remap[used] = np.arange(len(used))
    return v[used], remap[f]


def _case(tmp_path, *, meta=None, target=True, scale=1.0):
    d = tmp_path / "case"
    d.mkdir()
    if target:
        v, f = _tube()
        write_obj(d / "target.obj", v * scale, f)
    (d / "meta.json").write_text(json.dumps(meta or {"garment": "tshirt", "body": "default"}))
    return d


def test_loads_default_body_case(tmp_path):
    c = load_case(_case(tmp_path))
    assert c.garment == "tshirt"
    assert c.target_verts.shape[1] == 3 and len(c.target_faces) > 0
    assert c.body.verts.shape[1] == 3
    assert c.pattern_gt is None


def test_units_cm_detected_and_accepted(tmp_path):
    d = _case(tmp_path, scale=100.0)
    with pytest.raises(InputError, match="--units cm"):
        load_case(d)
    c = load_case(d, units="cm")
    assert c.target_verts.max() < 3


def test_missing_pieces(tmp_path):
    with pytest.raises(InputError, match="does not exist"):
        load_case(tmp_path / "nope")
    with pytest.raises(InputError, match="no target"):
        load_case(_case(tmp_path, target=False))


def test_no_meta(tmp_path):
    d = _case(tmp_path)
    (d / "meta.json").unlink()
    with pytest.raises(InputError, match="meta.json"):
        load_case(d)


def test_bad_garment_and_body_spec(tmp_path):
    with pytest.raises(InputError, match="must be one of"):
        load_case(_case(tmp_path, meta={"garment": "hat", "body": "default"}))


def test_a_jumpsuit_may_be_named(tmp_path):
    assert load_case(_case(tmp_path, meta={"garment": "jumpsuit", "body": "default"})).garment == "jumpsuit"


def test_no_body(tmp_path):
    with pytest.raises(InputError, match="no body"):
        load_case(_case(tmp_path, meta={"garment": "tshirt"}))


def test_closed_target_is_refused(tmp_path):
    d = _case(tmp_path)
    s = trimesh.creation.icosphere(subdivisions=2, radius=0.2)
    write_obj(d / "target.obj", s.vertices + [0, 1.1, 0], s.faces)
    with pytest.raises(InputError, match="closed surface"):
        load_case(d)
