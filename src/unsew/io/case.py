"""A fitting case folder (FORMATS.md): the target garment, its wearer, and what we know.

```
case/
  target.obj | target.ply   the draped garment to invert
  body.obj + skeleton.json  the wearer (or meta.json names a body model)
  meta.json                 {"garment": ..., "units": "m", "up": "y", "front": "z", "body": {...}?}
  pattern_gt.json           optional true pattern
```
Everything is checked here, at the boundary, with one-line errors naming the file and the fix.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from unsew.errors import InputError

__all__ = ["Case", "load_case", "GARMENT_TYPES"]

GARMENT_TYPES = ("tshirt", "dress", "pants", "shorts", "skirt")


@dataclass
class Case:
    """A loaded fitting case.

    target_verts: (V, 3) float64 [m], world frame; target_faces: (F, 3) int64.
    body: unsew.body.body.Body; garment: one of GARMENT_TYPES; pattern_gt: Pattern or None.
    """

    path: Path
    garment: str
    target_verts: np.ndarray
    target_faces: np.ndarray
    body: object
    meta: dict = field(default_factory=dict)
    pattern_gt: object = None
    files: dict = field(default_factory=dict)  #: the files read, for hashing into config.yaml
    target_repair: dict = field(default_factory=dict)  #: what loading cleaned (MeshRepair.as_dict)


def _read_meta(d: Path) -> dict:
    p = d / "meta.json"
    if not p.is_file():
        raise InputError(f"case {d} has no meta.json (it names the garment type and units; see FORMATS.md)")
    try:
        meta = json.loads(p.read_text())
    except json.JSONDecodeError as exc:
        raise InputError(f"{p} is not valid JSON: {exc.msg} at line {exc.lineno}") from None
    if not isinstance(meta, dict):
        raise InputError(f"{p} must hold a JSON object")
    return meta


def load_case(
    path: str | os.PathLike,
    *,
    units: str | None = None,
    up: str | None = None,
    front: str | None = None,
    garment: str | None = None,
) -> Case:
    """Load and check a case folder. Options override meta.json's units/up/front/garment."""
    from unsew.io.mesh import read_garment

    d = Path(path)
    if not d.is_dir():
        raise InputError(f"case folder {d} does not exist")
    meta = _read_meta(d)
    units = units or meta.get("units", "m")
    up = up or meta.get("up", "y")
    front = front or meta.get("front", "z")
    garment = garment or meta.get("garment")
    if garment is not None and garment not in GARMENT_TYPES:
        raise InputError(f"garment {garment!r} in {d / 'meta.json'} must be one of {', '.join(GARMENT_TYPES)}")

    target = next((d / n for n in ("target.obj", "target.ply") if (d / n).is_file()), None)
    if target is None:
        raise InputError(f"case {d} has no target.obj or target.ply (the draped garment to invert)")
    tv, tf, repair = read_garment(target, units=units, up=up, front=front)
    _check_target(tv, tf, target)

    files = {"target": target}
    body = _load_case_body(d, meta, units=units, up=up, front=front, files=files)
    _check_plausible_frame(tv, body, target)

    pattern_gt = None
    gt = d / "pattern_gt.json"
    if gt.is_file():
        from unsew.io.garmentcode import load_pattern

        pattern_gt = load_pattern(gt)
        files["pattern_gt"] = gt
    return Case(d, garment or "", tv, tf, body, meta, pattern_gt, files, repair.as_dict())


def _load_case_body(d: Path, meta: dict, *, units, up, front, files) -> object:
    spec = meta.get("body")
    mesh = next((d / n for n in ("body.obj", "body.ply") if (d / n).is_file()), None)
    if mesh is not None:
        skel = d / "skeleton.json"
        if not skel.is_file():
            raise InputError(f"case {d} has {mesh.name} but no skeleton.json (the wearer's joints; see FORMATS.md)")
        from unsew.body.body import load_body

        files["body"] = mesh
        files["skeleton"] = skel
        return load_body(mesh, skel, units=units, up=up, front=front)
    if spec is None or spec == "default":
        if spec is None:
            raise InputError(
                f"case {d} has no body.obj + skeleton.json and meta.json names no body "
                '(add them, or set "body": "default" or {"model": "anny", ...} in meta.json)'
            )
        from unsew.body.body import default_body

        return default_body()
    if isinstance(spec, dict) and spec.get("model") == "anny":
        from unsew.body.anny_body import make_anny_body

        return make_anny_body(phenotype=spec.get("phenotype", {}), pose=spec.get("pose", "A"))
    raise InputError(f'meta.json "body" must be "default" or {{"model": "anny", ...}}, got {spec!r}')


def _check_target(v: np.ndarray, f: np.ndarray, path: Path) -> None:
    import trimesh

    m = trimesh.Trimesh(v, f, process=False)
    if m.area <= 0:
        raise InputError(f"target {path} has zero area")
    # A garment is an open surface: hems, cuffs, necklines and waists are boundary loops.
    edges = np.sort(m.edges, axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    if not (counts == 1).any():
        raise InputError(
            f"target {path} is a closed surface with no open hem, cuff or neckline: "
            "give the garment alone (segmented from the body), not a watertight shape"
        )


def _check_plausible_frame(tv: np.ndarray, body, path: Path) -> None:
    ext = tv.max(0) - tv.min(0)
    if ext.max() > 3.0:
        raise InputError(
            f"target {path} is {ext.max():.1f} units across, implausible in metres: "
            "pass --units cm (or mm) or set \"units\" in meta.json"
        )
    if ext.max() < 0.05:
        raise InputError(f"target {path} is only {ext.max():.3f} m across; check its units (--units)")
    bv = np.asarray(body.verts)
    lo, hi = bv.min(0) - 0.3, bv.max(0) + 0.3
    c = tv.mean(0)
    if not ((c > lo) & (c < hi)).all():
        raise InputError(
            f"target {path} lies outside its wearer's bounding box: check --up/--front/--units "
            "so target and body share the world frame (Y up, facing +Z)"
        )
