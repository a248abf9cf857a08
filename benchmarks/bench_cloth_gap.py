"""How far from the body does a target's cloth rest, and how far does unsew's drape of it rest?

For each foreign case (benchmarks/foreign/cases), prints low percentiles (1st, 5th, 10th) of the
distances [mm] from the target's vertices to the body surface (unsew.geometry.distance, exact;
negative inside the body by the body's SDF), and, with ``--results DIR``, the same of the fit's
drape DIR/CASE/garment.obj (its vertices merged where the OBJ splits them at texture seams). The
lowest percentiles are the cloth pressed on the body: newton's cloth never comes nearer than its
particle radius (4 mm); unsew's comes as near as its collision thickness (1 mm) where it presses
(docs/benchmarks.md, "The cloth's gap to the body").

    python -m benchmarks cloth_gap [--cases a,b] [--results DIR]
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "benchmarks" / "foreign" / "cases"
PERCENTILES = (1, 5, 10)


def gaps_mm(points, body, sdf) -> list[float]:
    """PERCENTILES of the signed distances [mm] of ``points`` (N, 3) [m] to ``body``'s surface."""
    import numpy as np

    from unsew.fit.contact import signed_body_distance

    return [float(v) for v in np.percentile(signed_body_distance(points, body, sdf) * 1e3, PERCENTILES)]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", default="", help="comma-separated case folder names (default: all)")
    ap.add_argument("--results", type=Path, default=None, help="a foreign_fit --out folder: also its drapes")
    args = ap.parse_args(argv)

    import trimesh
    from tables import print_table

    from unsew.body.case import load_case
    from unsew.body.sdf import BodySDF
    from unsew.errors import UnsewError

    names = [n for n in args.cases.split(",") if n] or sorted(p.parent.name for p in CASES.glob("*/meta.json"))
    rows = []
    for name in names:
        try:
            case = load_case(CASES / name)
        except UnsewError as exc:
            print(f"cloth_gap: {name}: {exc}", file=sys.stderr)
            return 2
        sdf = BodySDF.build(case.body)
        r = {"case": name}
        r.update({f"target_p{q}_mm": v for q, v in zip(PERCENTILES, gaps_mm(case.target_verts, case.body, sdf))})
        obj = args.results / name / "garment.obj" if args.results else None
        if obj is not None and obj.is_file():
            m = trimesh.load(obj, process=True)  # merges the vertices an OBJ splits at texture seams
            r.update({f"drape_p{q}_mm": v for q, v in zip(PERCENTILES, gaps_mm(m.vertices, case.body, sdf))})
        rows.append(r)
        print(r, flush=True)
    cols = ["case"] + [f"target_p{q}_mm" for q in PERCENTILES]
    if args.results:
        cols += [f"drape_p{q}_mm" for q in PERCENTILES]
    print_table(rows, cols, title="Cloth-body distance, low percentiles [mm]", digits=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
