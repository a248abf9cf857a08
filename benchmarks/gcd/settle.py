"""A built case's newton target run on until it is at rest (newton_drape.settle_newton).

The build's drape ends 105 frames after sewing, at the drape's 10 solver iterations, where
newton's cloth is still moving (docs/decisions/031). ``settle_case`` copies a built case folder
and replaces its target by the same drape settled: full gravity, 40 iterations, the edges held
while draping held at the heights they reached, until the 99th percentile of the vertices'
speeds is under 5 mm/s (checked every 30 frames) or 600 frames. settle.json beside it says how
far it moved (Chamfer to the drape it started from, judge.chamfer_mm) and whether it came to rest;
the case's floors.json (floors measured against the drape before settling) is left out.
"""

from __future__ import annotations

import json
import shutil
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent


def settle_case(case: Path, out: Path, *, settle: dict | None = None, log=print) -> dict:
    """Copy the built case folder ``case`` to ``out`` (replaced if there) with its target.obj
    settled; returns the record written to ``out/settle.json``."""
    sys.path.insert(0, str(HERE.parent / "foreign"))
    import build
    import judge
    import newton_drape
    import trimesh

    meta = json.loads((case / "meta.json").read_text())
    spec = json.loads((case / "pattern_gt.json").read_text())
    mesh = build.mesh_spec(spec, case.name, meta["simulator"]["mesh_edge_length_m"])
    import kept

    tm = trimesh.load(case / "target.obj", process=False, force="mesh")
    x0 = np.asarray(tm.vertices, np.float64)
    x = kept.target_on_mesh(case, mesh, x0, tm.faces)  # moved onto this machine's mesh of the spec
    if x is None:
        n = mesh.n_x
        raise ValueError(f"{case.name}: target.obj has {len(x0)} vertices, the specification's mesh {n}")
    held = np.unique(np.asarray(mesh.x_of_u)[build.attached_uv(spec, mesh)])
    body_v, body_f = build.read_body(case)
    settings = {k: (float("inf") if v is None else v) for k, v in meta["simulator"]["settings"].items()}
    settings = {**newton_drape.SETTINGS, **settings}
    x2, info = newton_drape.settle_newton(
        mesh, x, body_v, body_f, settings=settings, attach=held, settle=settle, log=log
    )
    faces = np.asarray(mesh.faces)
    moved = round(judge.chamfer_mm(x, faces, x2, faces)["chamfer_mm"], 3)
    tmp = out.parent / f".{out.name}.tmp"
    shutil.rmtree(tmp, ignore_errors=True)
    shutil.copytree(case, tmp)
    (tmp / "floors.json").unlink(missing_ok=True)  # measured against the drape before settling
    header = f"GarmentCode design {case.name} draped by newton, settled {info['frames']} frames"
    build.write_obj(tmp / "target.obj", x2, faces, header)
    meta["simulator"]["settled"] = {**newton_drape.SETTLE, **(settle or {}), **info}
    (tmp / "meta.json").write_text(json.dumps(meta, indent=1))
    rec = {"case": case.name, **info, "moved_mm": moved}
    (tmp / "settle.json").write_text(json.dumps(rec, indent=1))
    shutil.rmtree(out, ignore_errors=True)
    tmp.rename(out)
    return rec
