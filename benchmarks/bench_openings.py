"""How far are the openings of targets unsew did not make stretched over the body?

For every foreign case: each opening of the target (a boundary loop of target.obj) against the
same opening of its true pattern (pattern_gt.json meshed as the fit meshes it): the draped
length over the rest length. Openings are named on both sides as ``bench stretch`` names them
(the highest "neck", the lowest "hem", the others "left"/"right" by their side), the pattern's
by where its panels are placed (their JSON translations and rotations). Prints one row per case
and the median and largest ratio per opening.

The question it answers (docs/benchmarks.md, "The side seams graded by girth, again; an opening
stretched over the body read from its cloth"): when grading meets a drape whose opening is
stretched round the body, how stretched is the target's own?

    python -m benchmarks openings [--cases a,b] [--edge 0.025]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "benchmarks" / "foreign" / "cases"


def placed_positions(mesh) -> np.ndarray:
    """The sewn vertices (n_x, 3) [m] at their panels' placed positions (the mean over the uv
    vertices sewn into each)."""
    x = np.zeros((mesh.n_x, 3))
    n = np.zeros(mesh.n_x)
    np.add.at(x, mesh.x_of_u, np.asarray(mesh.uv_placed3d, dtype=np.float64))
    np.add.at(n, mesh.x_of_u, 1.0)
    return x / np.maximum(n, 1.0)[:, None]


def target_openings(verts: np.ndarray, faces: np.ndarray) -> dict[str, float]:
    """Name -> draped length [m] of each boundary loop of a target surface, named as
    :func:`bench_stretch.openings` names a drape's."""
    from unsew.geometry.topology import boundary_loops

    loops = []
    for loop in boundary_loops(faces):
        nxt = np.roll(loop, -1)
        loops.append((verts[loop].mean(axis=0), float(np.linalg.norm(verts[loop] - verts[nxt], axis=1).sum())))
    ys = [c[1] for c, _ in loops]
    out = {}
    for k, (c, length) in enumerate(loops):
        name = ("neck" if k == int(np.argmax(ys)) and len(loops) > 1 else "hem" if k == int(np.argmin(ys))
                else "left" if c[0] > 0 else "right")
        out[name] = length
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default="", help="comma-separated case ids (default: every case)")
    ap.add_argument("--edge", type=float, default=0.025, help="mesh edge length of the true patterns [m]")
    args = ap.parse_args(argv)
    import warnings

    import trimesh
    from bench_stretch import openings
    from tables import print_table

    from unsew.io.garmentcode import load_pattern
    from unsew.meshing.sew import mesh_pattern

    from unsew.meshing.sew import EDGE_LENGTH_RANGE

    lo, hi = EDGE_LENGTH_RANGE
    if not lo <= args.edge <= hi:
        print(f"bench openings: --edge {args.edge} m is outside [{lo}, {hi}] m", file=sys.stderr)
        return 2
    want = [c for c in args.cases.split(",") if c]
    cases = [CASES / c for c in want] if want else sorted(p for p in CASES.iterdir() if (p / "target.obj").is_file())
    missing = [c.name for c in cases if not (c / "target.obj").is_file()]
    if missing:
        print(f"bench openings: no such case: {', '.join(missing)}", file=sys.stderr)
        return 2
    rows, ratios = [], {}
    for case in cases:
        t = trimesh.load(case / "target.obj", process=False)
        drape = target_openings(np.asarray(t.vertices, dtype=np.float64), np.asarray(t.faces, dtype=np.int64))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # GarmentCode's clockwise panels and stitch-length notes
            mesh = mesh_pattern(load_pattern(case / "pattern_gt.json"), edge_length=args.edge)
        rest = {o["name"]: o["rest"] for o in openings(placed_positions(mesh), mesh)}
        only_d, only_r = set(drape) - set(rest), set(rest) - set(drape)
        if len(only_d) == 1 and len(only_r) == 1:  # trousers' second leg: the lowest one is "hem" on either side
            rest[only_d.pop()] = rest.pop(only_r.pop())
        row = {"case": case.name}
        for name in ("neck", "left", "right", "hem"):
            if name in rest and name in drape and rest[name] > 0:
                r = drape[name] / rest[name]
                row[f"{name} draped / rest"] = f"{100 * drape[name]:.1f} / {100 * rest[name]:.1f} = {r:.2f}"
                ratios.setdefault(name, []).append(r)
        rows.append(row)
    print_table(rows, ["case", "neck draped / rest", "left draped / rest", "right draped / rest", "hem draped / rest"],
                title="Openings of the foreign targets: draped length / the true pattern's rest length [cm]")
    print()
    print_table([{"opening": k, "cases": len(v), "median": float(np.median(v)), "largest": float(np.max(v)),
                  "over 1.05": int(np.sum(np.asarray(v) > 1.05))} for k, v in ratios.items()],
                ["opening", "cases", "median", "largest", "over 1.05"], title="Draped / rest per opening", digits=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
