"""The newton targets kept in the repository, so that a clone has the sample without hours of draping.

    python -m benchmarks gcd keep --out CASES      store every built case's target in targets/
    python -m benchmarks gcd build --no-drape      restores a kept target beside each placed case

A kept target is ``targets/<case>.obj.gz`` (the drape as build wrote it), ``targets/<case>.rest.npz``
(the rest mesh it was draped on: where each vertex lies in its panel), ``targets/<case>.spec.json.gz``
(the specification it was draped from) and ``targets/<case>.json``: its build record, meta.json's
simulator and checks, and the SHA-256 of that specification, its numbers rounded to SPEC_DECIMALS.
It is restored only beside a freshly sampled ``pattern_gt.json`` that is the same specification:
the same digest, or the same text and structure with every number within SPEC_TOLERANCE_CM of the
kept one's. So a changed sampler, sizing or body never pairs a design with another design's drape,
while the noise another processor's arithmetic leaves in the sampler's numbers, which can flip a
rounding and so the digest, does not count (docs/gcd.md has what was measured).
"""

from __future__ import annotations

import gzip
import hashlib
import json
import shutil
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
KEPT = HERE / "targets"


#: Decimals a specification's numbers (cm) keep in its digest: 10 nm.
SPEC_DECIMALS = 6

#: Largest difference [cm] between a kept specification's number and a fresh one's that still
#: counts as the same design: far above another processor's noise (docs/gcd.md), below a micrometre.
SPEC_TOLERANCE_CM = 1e-5


def _rounded(value):
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return round(float(value), SPEC_DECIMALS) + 0.0  # 1 and 1.0, -0.0 and 0.0 alike
    if isinstance(value, list):
        return [_rounded(v) for v in value]
    if isinstance(value, dict):
        return {k: _rounded(v) for k, v in value.items()}
    return value


def spec_digest(spec_path: Path) -> str:
    """SHA-256 of a specification's content, its numbers rounded to SPEC_DECIMALS (JSON
    re-serialised: key order and spacing don't count)."""
    spec = _rounded(json.loads(Path(spec_path).read_text()))
    return hashlib.sha256(json.dumps(spec, sort_keys=True).encode()).hexdigest()


def same_spec(a, b, tol: float = SPEC_TOLERANCE_CM) -> bool:
    """Whether two specifications (parsed JSON) agree: the same keys, lengths and text, and each
    number within ``tol`` [cm] of the other's."""
    num = (int, float)
    if isinstance(a, num) and isinstance(b, num) and not isinstance(a, bool) and not isinstance(b, bool):
        return abs(float(a) - float(b)) <= tol
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same_spec(x, y, tol) for x, y in zip(a, b, strict=True))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same_spec(a[k], b[k], tol) for k in a)
    return type(a) is type(b) and a == b


def store_spec(spec_path: Path, cid: str, store: Path = KEPT) -> None:
    """Keep the specification ``spec_path`` beside case ``cid``'s target (gzip, no timestamp)."""
    with open(spec_path, "rb") as src, gzip.GzipFile(store / f"{cid}.spec.json.gz", "wb", mtime=0) as dst:
        shutil.copyfileobj(src, dst)


def _kept_spec(cid: str, store: Path) -> dict | None:
    path = store / f"{cid}.spec.json.gz"
    if not path.is_file():
        return None
    with gzip.open(path, "rt") as f:
        return json.load(f)


def is_kept_spec(kept: dict, spec_path: Path, store: Path = KEPT) -> bool:
    """Whether ``spec_path`` is the specification the kept target (its record ``kept``) was draped
    from: the same digest, or within SPEC_TOLERANCE_CM of the kept specification."""
    if kept.get("spec_digest") == spec_digest(spec_path):
        return True
    own = _kept_spec(kept["case"], store)
    return own is not None and same_spec(own, json.loads(Path(spec_path).read_text()))


def keep(out: Path, cid: str, store: Path = KEPT) -> bool:
    """Store case ``cid``'s target from the build folder ``out``; False where it is not built."""
    d, st = Path(out) / cid, Path(out) / "_status" / f"{cid}.json"
    if not (d / "target.obj").is_file() or not st.is_file():
        return False
    rec = json.loads(st.read_text())
    if rec.get("status") != "built":
        return False
    meta = json.loads((d / "meta.json").read_text())
    store.mkdir(parents=True, exist_ok=True)
    with open(d / "target.obj", "rb") as src, gzip.GzipFile(store / f"{cid}.obj.gz", "wb", mtime=0) as dst:
        shutil.copyfileobj(src, dst)
    kept = {
        "case": cid,
        "spec_digest": spec_digest(d / "pattern_gt.json"),
        "record": rec,
        "simulator": meta.get("simulator"),
        "checks": meta.get("checks"),
    }
    (store / f"{cid}.json").write_text(json.dumps(kept, indent=1) + "\n")
    store_spec(d / "pattern_gt.json", cid, store)
    mesh = _spec_mesh(d, meta)
    n = sum(1 for line in open(d / "target.obj") if line.startswith("v "))
    if mesh is not None and mesh.n_x == n:
        save_rest(store / f"{cid}.rest.npz", mesh)
    return True


def _spec_mesh(d: Path, meta: dict):
    """The case's specification meshed as the build meshed it (None where meta.json lacks it)."""
    import warnings

    from unsew.io.garmentcode import load_pattern
    from unsew.meshing import mesh_pattern

    edge = (meta.get("simulator") or {}).get("mesh_edge_length_m")
    if edge is None:
        return None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # GarmentCode's gathered seams: lengths apart
        return mesh_pattern(load_pattern(d / "pattern_gt.json"), edge_length=edge)


def save_rest(path: Path, mesh) -> None:
    """Store where each vertex of ``mesh`` (a GarmentMesh) lies in its panel: uv (Nu, 2) [m],
    uv_panel (Nu,), faces_uv (F, 3), x_of_u (Nu,)."""
    np.savez_compressed(
        path,
        uv=np.asarray(mesh.uv, np.float64),
        uv_panel=np.asarray(mesh.uv_panel, np.int32),
        faces_uv=np.asarray(mesh.faces_uv, np.int32),
        x_of_u=np.asarray(mesh.x_of_u, np.int32),
    )


def _locate(points: np.ndarray, corners: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For 2D points (n, 2) and triangles' corners (t, 3, 2): the triangle holding each point (the
    most nearly holding, among the 16 with the nearest centroids) and its barycentric weights
    (n, 3), clipped to the triangle."""
    from scipy.spatial import cKDTree

    k = min(16, len(corners))
    _, near = cKDTree(corners.mean(axis=1)).query(points, k=k)
    near = near.reshape(len(points), k)
    a, b, c = (corners[near, i] for i in range(3))  # (n, k, 2)
    v0, v1, v2 = b - a, c - a, points[:, None, :] - a
    det = v0[..., 0] * v1[..., 1] - v0[..., 1] * v1[..., 0]
    w1 = (v2[..., 0] * v1[..., 1] - v2[..., 1] * v1[..., 0]) / det
    w2 = (v0[..., 0] * v2[..., 1] - v0[..., 1] * v2[..., 0]) / det
    w = np.stack([1.0 - w1 - w2, w1, w2], axis=-1)  # (n, k, 3)
    best = w.min(axis=-1).argmax(axis=1)
    rows = np.arange(len(points))
    wb = w[rows, best].clip(0.0, None)
    return near[rows, best], wb / wb.sum(axis=1, keepdims=True)


def moved_to_mesh(x: np.ndarray, rest: dict, mesh) -> np.ndarray:
    """Positions (n_x, 3) [m] on ``mesh`` (a GarmentMesh of the same specification, meshed
    elsewhere) of a drape ``x`` (m, 3) [m] of the rest mesh ``rest`` (:func:`save_rest`'s arrays):
    each of ``mesh``'s vertices is found in its panel's rest triangles and takes the drape's
    position there, interpolated. A vertex of a seam takes its first panel's."""
    out = np.zeros((mesh.n_x, 3))
    uv, panel_of = np.asarray(mesh.uv), np.asarray(mesh.uv_panel)
    rest_panel = rest["uv_panel"][rest["faces_uv"][:, 0]]
    for p in range(len(mesh.panel_names)):
        mine = np.flatnonzero(panel_of == p)
        faces = rest["faces_uv"][rest_panel == p]
        tri, w = _locate(uv[mine], rest["uv"][faces])
        corners = x[rest["x_of_u"][faces[tri]]]  # (n, 3 corners, 3)
        out[np.asarray(mesh.x_of_u)[mine]] = np.einsum("nc,ncd->nd", w, corners)
    return out


def own_mesh(case_dir: Path, mesh, x: np.ndarray, faces: np.ndarray, store: Path = KEPT):
    """The rest mesh the case's newton target (vertices ``x`` (m, 3) [m], triangles ``faces``
    (F, 3) int) was draped on, as an object with ``uv`` (Nu, 2) [m], ``faces_uv`` (F, 3),
    ``faces`` (F, 3) into x and ``x_of_u`` (Nu,): ``mesh`` (its specification meshed here) where
    that is it, else the kept one; None where neither is."""
    from types import SimpleNamespace

    f = np.asarray(faces)
    if len(x) == mesh.n_x and f.shape == np.asarray(mesh.faces).shape and np.array_equal(f, mesh.faces):
        return mesh
    path = Path(store) / f"{Path(case_dir).name}.rest.npz"
    if not path.is_file():
        return None
    with np.load(path) as z:
        rest = {k: z[k] for k in z.files}
    if int(rest["x_of_u"].max()) + 1 != len(x):  # not the mesh this target was draped on
        return None
    faces_uv = rest["faces_uv"].astype(np.int64)
    x_of_u = rest["x_of_u"].astype(np.int64)
    return SimpleNamespace(
        uv=rest["uv"], uv_panel=rest["uv_panel"], faces_uv=faces_uv, x_of_u=x_of_u, faces=x_of_u[faces_uv]
    )


def target_on_mesh(case_dir: Path, mesh, x: np.ndarray, faces: np.ndarray, store: Path = KEPT):
    """The case's newton target (``x`` (m, 3) [m], ``faces`` (F, 3) int) as positions (n_x, 3)
    [m] of ``mesh`` (its specification meshed here): itself where it was draped on this very
    mesh, else moved to it through the kept rest mesh it was draped on (Triangle refined the
    panels otherwise before decision 041); None where neither holds."""
    own = own_mesh(case_dir, mesh, x, faces, store)
    if own is None:
        return None
    return x if own is mesh else moved_to_mesh(x, vars(own), mesh)


def restore(out: Path, cid: str, store: Path = KEPT) -> dict | None:
    """Put the kept target of ``cid`` into the placed case folder ``out/cid`` (target.obj and
    meta.json's simulator and checks); returns its build record, or None where none is kept or
    the kept one was draped from another specification than the folder's."""
    d, info = Path(out) / cid, store / f"{cid}.json"
    if not info.is_file() or not (d / "pattern_gt.json").is_file():
        return None
    kept = json.loads(info.read_text())
    if not is_kept_spec(kept, d / "pattern_gt.json", store):
        return None
    with gzip.open(store / f"{cid}.obj.gz", "rb") as src, open(d / ".target.obj.tmp", "wb") as dst:
        shutil.copyfileobj(src, dst)
    meta = json.loads((d / "meta.json").read_text())
    meta |= {"simulator": kept["simulator"], "checks": kept["checks"]}
    (d / "meta.json").write_text(json.dumps(meta, indent=1))
    (d / ".target.obj.tmp").replace(d / "target.obj")
    return dict(kept["record"], restored_from="benchmarks/gcd/targets")
