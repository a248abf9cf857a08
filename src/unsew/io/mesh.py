"""Triangle-mesh files (OBJ, PLY, anything trimesh reads) in and out, with frame conversion.

Inside unsew meshes are metres in the world frame of FORMATS.md (Y up, body facing +Z, body's
left at +X). Files in another frame are converted here, and only here, from explicit options:
``units`` (m, cm, mm), ``up`` (the file's up axis, e.g. "z") and ``front`` (the file's front axis,
e.g. "-y"). Nothing is guessed silently.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from unsew.errors import InputError
from unsew.geometry.repair import repair_garment
from unsew.io.atomic import atomic_write

__all__ = ["read_mesh", "read_garment", "write_obj", "frame_matrix", "UNIT_SCALE"]

#: metres per file unit
UNIT_SCALE = {"m": 1.0, "cm": 0.01, "mm": 0.001}

_AXES = {"x": 0, "y": 1, "z": 2}


def _axis(spec: str) -> np.ndarray:
    s = spec.strip().lower()
    sign = -1.0 if s.startswith("-") else 1.0
    s = s.lstrip("+-")
    if s not in _AXES:
        raise InputError(f"axis {spec!r} must be one of x, y, z, -x, -y, -z")
    v = np.zeros(3)
    v[_AXES[s]] = sign
    return v


def frame_matrix(*, up: str = "y", front: str = "z") -> np.ndarray:
    """Rotation (3, 3) taking file coordinates to the world frame (Y up, front +Z).

    ``up``/``front`` name the file's axes that point up and towards the body's front.
    """
    u, f = _axis(up), _axis(front)
    if abs(u @ f) > 0.5:
        raise InputError(f"--up {up} and --front {front} must be different axes")
    left = np.cross(u, f)  # world +X = up x front (Y x Z = X)
    R = np.stack([left, u, f])  # rows: where each world axis lies in file coordinates
    return R


def read_mesh(path: str | os.PathLike, *, units: str = "m", up: str = "y", front: str = "z"):
    """Read a triangle mesh and convert it to metres in the world frame.

    Returns (verts (V, 3) float64 [m], faces (F, 3) int64). Raises InputError for a missing
    file, an unreadable or empty mesh, non-triangle faces that cannot be triangulated, or
    non-finite coordinates.
    """
    import trimesh

    p = Path(path)
    if not p.is_file():
        raise InputError(f"mesh file {p} does not exist")
    if p.stat().st_size == 0:
        raise InputError(f"mesh file {p} is empty")
    if units not in UNIT_SCALE:
        raise InputError(f"units {units!r} must be one of {sorted(UNIT_SCALE)}")
    try:
        m = trimesh.load(p, force="mesh", process=False, skip_materials=True)
    except Exception as exc:  # trimesh raises many types for bad files
        raise InputError(f"cannot read mesh {p}: {type(exc).__name__}: {exc}") from None
    verts = np.asarray(getattr(m, "vertices", np.zeros((0, 3))), dtype=np.float64)
    faces = np.asarray(getattr(m, "faces", np.zeros((0, 3))), dtype=np.int64)
    if len(verts) == 0 or len(faces) == 0:
        raise InputError(f"mesh {p} has no triangles")
    if not np.isfinite(verts).all():
        raise InputError(f"mesh {p} has non-finite (NaN or inf) vertex coordinates")
    if faces.min() < 0 or faces.max() >= len(verts):
        raise InputError(f"mesh {p} has faces that index missing vertices")
    R = frame_matrix(up=up, front=front)
    verts = (verts * UNIT_SCALE[units]) @ R.T
    return verts, faces


def read_garment(
    path: str | os.PathLike, *, units: str = "m", up: str = "y", front: str = "z", what: str = "target"
):
    """Read a garment mesh (:func:`read_mesh`) and repair it (:func:`unsew.geometry.repair.repair_garment`):
    duplicate/degenerate faces and duplicate/unreferenced vertices cleaned, fins and loose debris
    cut off; a branching surface or several garments raise InputError naming where.

    Returns (verts (V, 3) float64 [m], faces (F, 3) int64, repair :class:`~unsew.geometry.repair.MeshRepair`
    with the counts). A repair is also announced in one line by ``warnings.warn``.
    """
    import warnings

    verts, faces = read_mesh(path, units=units, up=up, front=front)
    verts, faces, rep = repair_garment(verts, faces, what=f"{what} {Path(path).name}")
    if rep.changed:
        warnings.warn(f"{what} {Path(path).name} repaired: {rep.summary()}", stacklevel=2)
    return verts, faces, rep


def write_obj(
    path: str | os.PathLike,
    verts: np.ndarray,
    faces: np.ndarray,
    *,
    uv: np.ndarray | None = None,
    faces_uv: np.ndarray | None = None,
    header: str | None = None,
) -> None:
    """Write a triangle mesh as OBJ, atomically.

    verts: (V, 3) [m]; faces: (F, 3) int, 0-based; uv: optional (Nu, 2) texture coordinates
    (unsew writes pattern coordinates in metres as UVs); faces_uv: (F, 3) int into uv (defaults
    to ``faces`` when uv has one entry per vertex). The file records its units in a comment.
    """
    verts = np.asarray(verts, dtype=np.float64)
    faces = np.asarray(faces, dtype=np.int64)
    if uv is not None and faces_uv is None:
        if len(uv) != len(verts):
            raise ValueError("faces_uv is required when uv does not have one row per vertex")
        faces_uv = faces
    lines = [f"# {header}" if header else "# written by unsew", "# units: m"]
    buf = [("\n".join(lines) + "\n").encode()]
    buf.append(_rows("v", verts, "%.9g %.9g %.9g"))
    if uv is not None:
        buf.append(_rows("vt", np.asarray(uv, dtype=np.float64), "%.9g %.9g"))
        f = np.concatenate([faces[:, :, None], np.asarray(faces_uv)[:, :, None]], axis=2) + 1
        body = "\n".join("f " + " ".join(f"{a}/{b}" for a, b in tri) for tri in f.tolist())
        buf.append((body + "\n").encode())
    else:
        buf.append(_rows("f", faces + 1, "%d %d %d"))
    with atomic_write(path) as tmp:
        with open(tmp, "wb") as fh:
            for b in buf:
                fh.write(b)


def _rows(tag: str, arr: np.ndarray, fmt: str) -> bytes:
    if len(arr) == 0:
        return b""
    import io

    s = io.StringIO()
    np.savetxt(s, arr, fmt=f"{tag} {fmt}")
    return s.getvalue().encode()
