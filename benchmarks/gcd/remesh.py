"""How much a fit moves with the meshing of its target alone: each case copied with its target's
triangles split (trimesh's ``subdivide_to_size``: edges halved until none is longer than
``max_edge``), the surface, its openings and every other file unchanged. Fitting the copies
(``gcd fit --cases DIR``) and judging them against the originals (``gcd compare``) says how far a
fit's figures move when a user's target is meshed otherwise: the noise a change to the method must
clear on a case before it says anything.

    python -m benchmarks gcd remesh --out CASES --to DIR [--max-edge 0.0125] [--only ...]
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np

#: Longest target edge of the copies [m]: half the fit's drape edge (0.025 m), the meshing of
#: newton's targets (their median edge about 2 cm) about six times finer in vertex count.
MAX_EDGE = 0.0125


def remesh_case(case: Path, out: Path, *, max_edge: float = MAX_EDGE) -> dict:
    """Copy the case folder ``case`` to ``out`` (replaced if there) with its target.obj's
    triangles split until no edge is longer than ``max_edge`` [m]; returns the record written to
    ``out/remesh.json`` (vertex counts, areas [m^2] before and after)."""
    import trimesh

    tm = trimesh.load(case / "target.obj", process=False, force="mesh")
    v, f = np.asarray(tm.vertices, np.float64), np.asarray(tm.faces, np.int64)
    v2, f2 = trimesh.remesh.subdivide_to_size(v, f, max_edge=max_edge, max_iter=16)
    tmp = out.parent / f".{out.name}.tmp"
    shutil.rmtree(tmp, ignore_errors=True)
    shutil.copytree(case, tmp)
    (tmp / "floors.json").unlink(missing_ok=True)  # a floor is measured against the target as it was
    trimesh.Trimesh(v2, f2, process=False).export(tmp / "target.obj")
    rec = {
        "case": case.name,
        "max_edge_m": max_edge,
        "vertices": [len(v), len(v2)],
        "area_m2": [round(float(tm.area), 6), round(float(trimesh.Trimesh(v2, f2, process=False).area), 6)],
    }
    (tmp / "remesh.json").write_text(json.dumps(rec, indent=1))
    shutil.rmtree(out, ignore_errors=True)
    tmp.rename(out)
    return rec
