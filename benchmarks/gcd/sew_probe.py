"""newton's sewing phase alone on a built case, for trying sewing settings: the widest seam gaps
per pair of panels after sewing and the garment's top against the start's.

    python -m benchmarks gcd sew-probe CASE_DIR ['{"sew_contact_mu": 0.5}'] [--no-attach] [--no-guide]

CASE_DIR holds pattern_gt.json and body.obj (a folder written by ``gcd build``); the JSON object
overrides the build's settings (newton_drape.SETTINGS, build.SEW_FROM_SPEC, build.GUIDED_SEWING).
"""

from __future__ import annotations

import json
import sys
from collections import defaultdict
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "foreign"))
sys.path.insert(0, str(HERE))


def main(argv: list[str]) -> int:
    import build
    import newton_drape as nd
    import warp as wp

    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__.split("\n\n")[1].strip())
        return 0 if argv else 2
    d = Path(argv[0])
    if not (d / "pattern_gt.json").is_file() or not (d / "body.obj").is_file():
        print(f"gcd sew-probe: {d} is not a built case folder (pattern_gt.json, body.obj)", file=sys.stderr)
        return 2
    over = json.loads(next((a for a in argv[1:] if a.startswith("{")), "{}"))
    spec = json.loads((d / "pattern_gt.json").read_text())
    body_v, body_f = build.read_body(d)
    mesh = build.mesh_spec(spec, d.name, build.manifest()["edge_length_m"])
    x0 = build.bend_around_body(build.spec_placement(spec, mesh), mesh, spec, body_v)
    x0 = build.clear_of_body(build.wrap_on_torso(x0, mesh, spec, body_v), mesh, body_v, body_f)
    att = None if "--no-attach" in argv else build.attachment(spec, mesh, x0)
    guide = None if "--no-guide" in argv else build.over_body_guide(spec, mesh, x0, body_v, body_f)
    guided = build.GUIDED_SEWING if guide is not None and len(guide[0]) else {}
    s = {**nd.SETTINGS, **build.SEW_FROM_SPEC, **guided, **over}
    wp.config.quiet = True
    bz = nd._to_z(body_v)
    runner = nd._Runner(s, 0.5 * (bz.min(axis=0) + bz.max(axis=0)))
    x1 = nd._sew(mesh, x0, (bz, body_f), runner, {}, print, att, guide)
    sp = np.asarray(mesh.seam_pairs)
    gaps = np.linalg.norm(x1[sp[:, 0]] - x1[sp[:, 1]], axis=1)
    pan = np.asarray(mesh.uv_panel)
    worst = defaultdict(float)
    for (i, j), g in zip(sp, gaps):
        key = (mesh.panel_names[pan[i]], mesh.panel_names[pan[j]])
        worst[key] = max(worst[key], float(g))
    for key, g in sorted(worst.items(), key=lambda kv: -kv[1])[:8]:
        print(f"  {key[0]} - {key[1]}: widest gap {g * 1000:.0f} mm")
    print(f"  top {x1[:, 1].max():.3f} m (start {x0[:, 1].max():.3f} m)")
    return 0
