"""Mesh files: round trip, frame and unit conversion, bad input."""

import numpy as np
import pytest
from helpers import assert_close

from unsew.errors import InputError
from unsew.io.mesh import frame_matrix, read_mesh, write_obj


def _tet():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float) * 0.1
    f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    return v, f


def test_round_trip_with_uv(tmp_path):
    v, f = _tet()
    uv = v[:, :2] * 2
    write_obj(tmp_path / "a.obj", v, f, uv=uv)
    v2, f2 = read_mesh(tmp_path / "a.obj")
    assert_close(v2, v, atol=1e-12)
    assert (f2 == f).all()
    assert "units: m" in (tmp_path / "a.obj").read_text()


def test_units_and_frame(tmp_path):
    v, f = _tet()
    write_obj(tmp_path / "a.obj", v * 100, f)  # the file is in cm
    v2, _ = read_mesh(tmp_path / "a.obj", units="cm")
    assert_close(v2, v, atol=1e-12)
    # A Z-up, -Y-front file (anny's frame): its +Z becomes world +Y, its -Y world +Z.
    R = frame_matrix(up="z", front="-y")
    assert_close(R @ np.array([0, 0, 1.0]), [0, 1, 0], atol=1e-15)
    assert_close(R @ np.array([0, -1.0, 0]), [0, 0, 1], atol=1e-15)
    assert np.isclose(np.linalg.det(R), 1.0)


@pytest.mark.parametrize("content", ["", "v 0 0 0\n", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"])
def test_bad_meshes(tmp_path, content):
    p = tmp_path / "bad.obj"
    p.write_text(content)
    with pytest.raises(InputError):
        read_mesh(p)


def test_missing_and_bad_options(tmp_path):
    with pytest.raises(InputError, match="does not exist"):
        read_mesh(tmp_path / "none.obj")
    v, f = _tet()
    write_obj(tmp_path / "a.obj", v, f)
    with pytest.raises(InputError):
        read_mesh(tmp_path / "a.obj", units="inch")
    with pytest.raises(InputError):
        read_mesh(tmp_path / "a.obj", up="y", front="-y")


def test_failed_write_leaves_nothing(tmp_path):
    from unsew.io.atomic import atomic_write

    with pytest.raises(RuntimeError):
        with atomic_write(tmp_path / "x.txt") as tmp:
            tmp.write_text("half")
            raise RuntimeError("boom")
    assert list(tmp_path.iterdir()) == []


def test_read_garment_cleans_a_damaged_target(tmp_path):
    """50 duplicate faces, a 3-face fin and a degenerate face: read back as the clean mesh, with
    the counts and a one-line warning."""
    from unsew.io.mesh import read_garment

    th = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    y = np.linspace(0.0, 0.5, 9)
    T, Y = np.meshgrid(th, y)
    v = np.stack([0.2 * np.cos(T), Y, 0.2 * np.sin(T)], -1).reshape(-1, 3)
    i, j = np.arange(8)[:, None] * 24, np.arange(24)[None, :]
    a, b = (i + j).ravel(), (i + (j + 1) % 24).ravel()
    f = np.concatenate([np.stack([a, b, b + 24], 1), np.stack([a, b + 24, a + 24], 1)])
    write_obj(tmp_path / "clean.obj", v, f)
    n = len(v)
    e0, e1 = f[0, 0], f[0, 2]
    out = np.array([0.05, 0.0, 0.0])
    fin_v = np.array([v[e0] + out, v[e1] + out, 0.5 * (v[e0] + v[e1]) + 2 * out])
    fin_f = np.array([[e0, e1, n + 1], [e0, n + 1, n], [n, n + 1, n + 2]])
    dup = f[np.random.default_rng(0).choice(len(f), 50, replace=False)]
    bad = np.concatenate([f, dup, fin_f, [[f[7, 0], f[7, 1], f[7, 1]]]])
    write_obj(tmp_path / "bad.obj", np.concatenate([v, fin_v]), bad)
    vc, fc, rc = read_garment(tmp_path / "clean.obj")
    with pytest.warns(UserWarning, match=r"repaired: .*50 duplicate faces.*fin"):
        vb, fb, rb = read_garment(tmp_path / "bad.obj")
    assert not rc.changed
    assert (rb.duplicate_faces, rb.fin_faces, rb.degenerate_faces) == (50, 3, 1)
    assert_close(vb, vc, atol=0)
    assert (fb == fc).all()
