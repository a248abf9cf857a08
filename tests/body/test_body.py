"""Default body, skeleton and bones, load_body's checks of bad input, and the body CLI."""

import json
import subprocess
import sys

import numpy as np
import pytest
from helpers import assert_close

from unsew.body.body import default_body, load_body
from unsew.body.skeleton import (
    Skeleton,
    axial_coordinate,
    distance_to_bone,
    encircled_bones,
    load_skeleton,
    save_skeleton,
)
from unsew.errors import InputError
from unsew.io.mesh import write_obj


def test_default_body_frame_and_shape():
    b = default_body()
    sk = b.skeleton
    assert b.verts.dtype == np.float64 and b.faces.dtype == np.int64
    assert b.to_trimesh().is_watertight and b.to_trimesh().volume > 0.03  # closed, normals out
    assert abs(b.verts[:, 1].min()) < 1e-6  # soles at y = 0
    assert_close(sk.position("pelvis")[[0, 2]], [0.0, 0.0], atol=1e-6)
    assert 1.5 < b.height < 1.8
    assert not sk.missing()
    # left at +X; facing +Z (the toes and the nose are in front of the ankles and the head)
    assert sk.position("left_shoulder")[0] > 0.1 and sk.position("right_hip")[0] < -0.05
    assert sk.position("left_toe")[2] > sk.position("left_ankle")[2] + 0.05
    face = b.verts[(b.verts[:, 1] > 1.45) & (b.verts[:, 1] < 1.55) & (np.abs(b.verts[:, 0]) < 0.01)]
    assert face[:, 2].max() > sk.position("head")[2] + 0.07
    # symmetric about x = 0
    assert_close(np.sort(b.verts[:, 0]), -np.sort(b.verts[:, 0])[::-1], atol=2e-3, what="mirror: ")
    # skinning weights: rows sum to 1, arm vertices are in the arms
    assert b.weights.shape == (len(b.verts), len(sk.names))
    assert_close(b.weights.sum(axis=1), 1.0, atol=1e-6)
    parts = b.vertex_parts()
    assert (b.verts[parts == "left_arm", 0] > 0.1).mean() > 0.95
    assert default_body() is b  # cached


def test_skeleton_bones_and_roundtrip(tmp_path):
    sk = default_body().skeleton
    bones = sk.bones()
    assert len(bones) == len(sk.names) - 1
    fore = sk.bone("left_wrist")
    assert fore.parent == "left_elbow" and fore.part == "left_arm"
    save_skeleton(sk, tmp_path / "s.json")
    sk2 = load_skeleton(tmp_path / "s.json")
    assert sk2.names == sk.names and sk2.parts == sk.parts
    assert_close(sk2.positions, sk.positions, atol=1e-12)
    # distance to the root along the skeleton: pelvis -> hip -> knee, then half the shin
    shin = sk.bone("left_ankle")
    exp = np.linalg.norm(sk.position("left_hip") - sk.position("pelvis"))
    exp += np.linalg.norm(sk.position("left_knee") - sk.position("left_hip")) + 0.5 * shin.length
    assert_close(sk.distance_to_root(shin, 0.5), exp, rtol=1e-12)


def test_axial_coordinate_distance_and_encircled_bones():
    sk = Skeleton(
        ["a", "b", "c"], [-1, 0, 1], [[0, 0, 0], [0, 1, 0], [1, 1, 0]], ["torso", "torso", "left_arm"]
    )
    ab, bc = sk.bones()
    p = np.array([[0.3, 0.25, 0.0], [0.0, 2.0, 0.0]])
    assert_close(axial_coordinate(p, ab), [0.25, 2.0], rtol=1e-12)
    assert_close(distance_to_bone(p, ab), [0.3, 1.0], rtol=1e-12)
    assert_close(distance_to_bone(p, ab, clamp=False), [0.3, 0.0], atol=1e-12)
    # a ring around the bone a->b at height 0.4: encircles ab only (u = 0.4, h = 0)
    t = np.linspace(0, 2 * np.pi, 17)[:-1]
    ring = np.stack([0.2 * np.cos(t), np.full_like(t, 0.4), 0.2 * np.sin(t)], axis=1)
    enc = encircled_bones(ring, sk.bones())
    assert [e.bone.name for e in enc] == ["b"]
    assert_close([enc[0].u, enc[0].h], [0.4, 0.0], atol=1e-12)
    # a ring around the arm bone b->c: both bones project inside? ab: u=1 -> excluded
    ring2 = np.stack([np.full_like(t, 0.7), 1 + 0.1 * np.cos(t), 0.1 * np.sin(t)], axis=1)
    enc2 = encircled_bones(ring2, sk.bones())
    assert enc2[0].bone.name == "c" and enc2[0].u == pytest.approx(0.7)


def test_default_body_encircles_forearm_with_a_cuff():
    b = default_body()
    fore = b.skeleton.bone("left_wrist")
    o = fore.a + 0.6 * (fore.b - fore.a)
    e1 = np.cross(fore.direction, [0, 0, 1.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(fore.direction, e1)
    t = np.linspace(0, 2 * np.pi, 25)[:-1]
    cuff = o + 0.05 * (np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2)
    enc = encircled_bones(cuff, b.skeleton.bones())
    assert enc[0].bone.name == "left_wrist" and enc[0].bone.part == "left_arm"
    assert enc[0].u == pytest.approx(0.6, abs=1e-9)


# -- load_body and bad input ----------------------------------------------------------------


def _write_case(tmp_path, verts, faces, sk_dict, name="b"):
    d = tmp_path / name
    d.mkdir()
    write_obj(d / "body.obj", verts, faces)
    (d / "skeleton.json").write_text(json.dumps(sk_dict))
    return d / "body.obj", d / "skeleton.json"


def test_load_body_roundtrip(tmp_path):
    b = default_body()
    m, s = _write_case(tmp_path, b.verts, b.faces, b.skeleton.to_dict())
    b2 = load_body(m, s)
    assert len(b2.verts) == len(b.verts) and b2.weights is None
    assert_close(b2.verts, b.verts, atol=1e-6)


def test_load_body_fills_small_holes_and_refuses_big_ones(tmp_path):
    b = default_body()
    # remove two adjacent triangles on the belly: a small hole
    c = b.verts[b.faces].mean(axis=1)
    k = int(np.argmin(np.linalg.norm(c - [0.0, 1.05, 0.15], axis=1)))
    drop = np.zeros(len(b.faces), bool)
    drop[k] = True
    m, s = _write_case(tmp_path, b.verts, b.faces[~drop], b.skeleton.to_dict(), "small")
    b2 = load_body(m, s)
    assert b2.to_trimesh().is_watertight
    # cut the whole head off: a neck-sized hole is refused with a message
    keep = b.verts[b.faces][:, :, 1].max(axis=1) < 1.45
    m, s = _write_case(tmp_path, b.verts, b.faces[keep], b.skeleton.to_dict(), "big")
    with pytest.raises(InputError, match="hole"):
        load_body(m, s)


def test_skeleton_missing_joints_are_named(tmp_path):
    b = default_body()
    d = b.skeleton.to_dict()
    d["joints"] = [j for j in d["joints"] if j["name"] not in ("left_knee", "neck")]
    for j in d["joints"]:  # re-parent orphans so only the missing names matter
        if j["parent"] in ("left_knee", "neck"):
            j["parent"] = "pelvis"
    m, s = _write_case(tmp_path, b.verts, b.faces, d)
    with pytest.raises(InputError, match=r"left_knee.*neck|neck.*left_knee"):
        load_body(m, s)


def test_body_in_cm_is_detected(tmp_path):
    b = default_body()
    d = b.skeleton.to_dict()
    d.pop("units")
    for j in d["joints"]:
        j["position"] = [100 * v for v in j["position"]]
    m, s = _write_case(tmp_path, b.verts * 100, b.faces, d)
    with pytest.raises(InputError, match="--units cm"):
        load_body(m, s)
    assert_close(load_body(m, s, units="cm").verts, b.verts, atol=1e-6)


def test_body_z_up_is_detected(tmp_path):
    b = default_body()
    R = np.array([[1.0, 0, 0], [0, 0, -1.0], [0, 1.0, 0]])  # world -> a Z-up file frame facing -Y
    d = b.skeleton.to_dict()
    for j in d["joints"]:
        j["position"] = (R @ np.array(j["position"])).tolist()
    m, s = _write_case(tmp_path, b.verts @ R.T, b.faces, d)
    with pytest.raises(InputError, match="--up z"):
        load_body(m, s)
    b2 = load_body(m, s, up="z", front="-y")
    assert_close(b2.verts, b.verts, atol=1e-6)


def test_body_facing_back_is_detected(tmp_path):
    b = default_body()
    R = np.diag([-1.0, 1.0, -1.0])  # turned around: faces -Z, left at -X
    d = b.skeleton.to_dict()
    for j in d["joints"]:
        j["position"] = (R @ np.array(j["position"])).tolist()
    m, s = _write_case(tmp_path, b.verts @ R.T, b.faces, d)
    with pytest.raises(InputError, match="--front -z"):
        load_body(m, s)


def test_cli_body_measure_and_errors(tmp_path):
    r = subprocess.run(
        [sys.executable, "-m", "unsew", "body", "measure", "default", "--json"],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["units"] == "m" and 0.8 < out["bust"] < 1.0
    r = subprocess.run(
        [sys.executable, "-m", "unsew", "body", "measure", str(tmp_path)], capture_output=True, text=True
    )
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1 and "body.obj" in r.stderr


def test_default_body_is_exactly_mirror_symmetric():
    """The stored float32 body is symmetric to 0.4 mm only; loading makes it exact (a symmetric
    garment must drape symmetrically on it)."""
    from scipy.spatial import cKDTree

    from unsew.body.body import symmetrize

    b = default_body()
    v = np.asarray(b.verts)
    d, _ = cKDTree(v).query(v * [-1.0, 1.0, 1.0])
    assert d.max() < 1e-12
    sk = b.skeleton
    for n in sk.names:
        if n.startswith("left_"):
            assert np.allclose(sk.position(n) * [-1, 1, 1], sk.position("right_" + n[5:]), atol=1e-12)
    # an asymmetric body is left alone
    w = v.copy()
    w[v[:, 0] > 0.1, 0] += 0.01
    w2, sk2 = symmetrize(w, sk)
    assert w2 is w and sk2 is sk
