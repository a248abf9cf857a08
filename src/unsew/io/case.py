"""A fitting case folder (FORMATS.md) as files: the target garment, the wearer's files, what we know.

```
case/
  target.obj | target.ply   the draped garment to invert
  body.obj [+ skeleton.json] the wearer (or meta.json names a body model)
  meta.json                 {"garment": ..., "units": "m", "up": "y", "front": "z", "body": {...}?}
  pattern_gt.json           optional true pattern
```
This module reads and checks the files, with one-line errors naming the file and the fix; it knows
no body. Loading a whole case, wearer included, is ``unsew.body.case.load_case``.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from unsew.errors import InputError
from unsew.geometry.topology import boundary_edges
from unsew.io.garmentcode import load_pattern
from unsew.io.mesh import read_garment

__all__ = ["Case", "CaseFiles", "read_case", "read_meta", "GARMENT_TYPES"]

GARMENT_TYPES = ("tshirt", "dress", "pants", "shorts", "skirt", "jumpsuit")


@dataclass
class Case:
    """A loaded fitting case.

    target_verts: (V, 3) float64 [m], world frame; target_faces: (F, 3) int64.
    body: unsew.body.body.Body (``body.rigged`` says its joints were estimated from its mesh);
    garment: one of GARMENT_TYPES; pattern_gt: Pattern or None.
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
    garment_note: str = ""  #: how the garment type was read off the target when meta.json names none
    design: object = None  #: the DesignReading read off the target when meta.json names no type

    @property
    def notes(self) -> list[str]:
        """What loading did to the inputs (the wearer rigged from its mesh, parts dropped, the
        garment type read off the target), one line each, for the report and metrics.json."""
        return list(getattr(self.body, "notes", ())) + ([self.garment_note] if self.garment_note else [])


@dataclass
class CaseFiles:
    """What a case folder holds, read and checked, before its wearer is built.

    target_verts (V, 3) float64 [m] world frame, target_faces (F, 3) int64; body_mesh /
    skeleton: paths or None; body_spec: meta.json's "body" entry or None; units/up/front: the
    files' frame (options win over meta.json).
    """

    path: Path
    meta: dict
    garment: str
    units: str
    up: str
    front: str
    target_verts: np.ndarray
    target_faces: np.ndarray
    body_mesh: Path | None
    skeleton: Path | None
    body_spec: object
    pattern_gt: object
    files: dict
    target_repair: dict = field(default_factory=dict)  #: what loading cleaned (MeshRepair.as_dict)


def read_meta(d: str | os.PathLike, *, required: bool = True) -> dict:
    """A case folder's meta.json as a dict; InputError when it is not a JSON object, or when it is
    missing and ``required`` (else ``{}``)."""
    d = Path(d)
    p = d / "meta.json"
    if not p.is_file():
        if not required:
            return {}
        raise InputError(f"case {d} has no meta.json (it names the garment type and units; see FORMATS.md)")
    try:
        meta = json.loads(p.read_text())
    except json.JSONDecodeError as exc:
        raise InputError(f"{p} is not valid JSON: {exc.msg} at line {exc.lineno}") from None
    if not isinstance(meta, dict):
        raise InputError(f"{p} must hold a JSON object")
    return meta


def read_case(
    path: str | os.PathLike,
    *,
    units: str | None = None,
    up: str | None = None,
    front: str | None = None,
    garment: str | None = None,
    need_target: bool = True,
    need_truth: bool = True,
) -> CaseFiles:
    """Read and check a case folder's files. Options override meta.json's units/up/front/garment.
    ``need_target=False``: a folder without target.obj or target.ply reads as its wearer alone
    (empty target arrays), as ``unsew drape --body CASE`` needs it. ``need_truth=False``: its
    pattern_gt.json is left unread (``pattern_gt`` None), so a wearer's case says nothing of it."""
    d = Path(path)
    if not d.is_dir():
        raise InputError(f"case folder {d} does not exist")
    meta = read_meta(d)
    units = units or meta.get("units", "m")
    up = up or meta.get("up", "y")
    front = front or meta.get("front", "z")
    garment = garment or meta.get("garment")
    if garment is not None and garment not in GARMENT_TYPES:
        raise InputError(
            f"garment {garment!r} in {d / 'meta.json'} must be one of {', '.join(GARMENT_TYPES)}"
        )

    tv, tf, repaired, files = _read_target(d, (units, up, front), need=need_target)
    mesh = next((d / n for n in ("body.obj", "body.ply") if (d / n).is_file()), None)
    skel = d / "skeleton.json" if (d / "skeleton.json").is_file() else None
    if mesh is not None:
        files["body"] = mesh
        if skel is not None:
            files["skeleton"] = skel
    elif meta.get("body") is None:
        raise InputError(
            f"case {d} has no body.obj and meta.json names no body "
            '(add body.obj, or set "body": "default" or {"model": "anny", ...} in meta.json)'
        )
    pattern_gt = None
    gt = d / "pattern_gt.json"
    if need_truth and gt.is_file():
        pattern_gt = load_pattern(gt)
        files["pattern_gt"] = gt
    return CaseFiles(
        d,
        meta,
        garment or "",
        units,
        up,
        front,
        tv,
        tf,
        mesh,
        skel,
        meta.get("body"),
        pattern_gt,
        files,
        repaired,
    )


def _read_target(d: Path, frame: tuple[str, str, str], *, need: bool):
    """The case's target: (verts (V, 3) [m], faces (F, 3), what loading repaired, {"target": path});
    empty arrays and no file where it has none and ``need`` is False. frame: (units, up, front)."""
    target = next((d / n for n in ("target.obj", "target.ply") if (d / n).is_file()), None)
    if target is None:
        if need:
            raise InputError(f"case {d} has no target.obj or target.ply (the draped garment to invert)")
        return np.zeros((0, 3)), np.zeros((0, 3), np.int64), {}, {}
    units, up, front = frame
    tv, tf, repair = read_garment(target, units=units, up=up, front=front)
    _check_target(tv, tf, target)
    return tv, tf, repair.as_dict(), {"target": target}


def _check_target(v: np.ndarray, f: np.ndarray, path: Path) -> None:
    # [m^2]
    area = 0.5 * np.linalg.norm(np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]), axis=1).sum()
    if area <= 0:
        raise InputError(f"target {path} has zero area")
    # A garment is an open surface: hems, cuffs, necklines and waists are boundary loops.
    if len(boundary_edges(f)) == 0:
        raise InputError(
            f"target {path} is a closed surface with no open hem, cuff or neckline: "
            "give the garment alone (segmented from the body), not a watertight shape"
        )
    ext = v.max(0) - v.min(0)
    if ext.max() > 3.0:
        raise InputError(
            f"target {path} is {ext.max():.1f} units across, implausible in metres: "
            'pass --units cm (or mm) or set "units" in meta.json'
        )
    if ext.max() < 0.05:
        raise InputError(f"target {path} is only {ext.max():.3f} m across; check its units (--units)")
