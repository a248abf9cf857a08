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
