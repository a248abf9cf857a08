"""Where is a fit's cloth stretched: its openings' rest lengths and its drapes' longest edges?

For each result folder of ``unsew fit`` (``--results DIR ...``) on one case (``--case DIR``): the
true pattern (the case's pattern_gt.json), and each result's graded and fitted patterns, dressed
from scratch in the result's fitted material (pattern.json's) on ``--edges`` meshes, as
``unsew drape`` dresses them. Prints one row per pattern and mesh: the drape's verdict
(:func:`unsew.sim.checks.check_dressed`), its largest and 99th-percentile edge stretch (edge
length over rest length), where the longest edge lies (height [m], panel), and for each opening
of the garment (open boundary loop of the sewn mesh; named neck, hem, left/right by where its
drape lies) its rest length on the pattern and its draped length [cm].

The question it answers (docs/benchmarks.md, "Drapes from scratch judged before they decide; a
barrier against overstretched cloth"): does a fit hold its garment up by an opening stretched over
the body (a neckline pulled round the neck)?

    python -m benchmarks stretch --case benchmarks/foreign/cases/CASE --results OUT/CASE [OUT2/CASE ...]
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

import numpy as np

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def _edges(mesh):
    """The triangles' edges as index pairs into the sewn vertices and into the rest vertices
    ((3F, 2) int64 each, :func:`unsew.losses.stretch.triangle_edges`) and their rest lengths
    (3F,) [m]."""
    from unsew.losses.stretch import triangle_edges

    e, eu = (t.numpy() for t in triangle_edges(mesh.faces, mesh.faces_uv))
    uv = np.asarray(mesh.uv)
    return e, eu, np.linalg.norm(uv[eu[:, 0]] - uv[eu[:, 1]], axis=1)


def openings(x, mesh) -> list[dict]:
    """The garment's openings: each open boundary loop of the sewn mesh with its rest length
    (the pattern's edges that form it) and its draped length [m], named by where its drape lies
    (the highest "neck", the lowest "hem", the others "left"/"right" by their side, +x the body's
    left). x: (n_x, 3) [m] on ``mesh`` (a GarmentMesh). Returns dicts with "name", "centre"
    (3,) [m], "rest" and "draped" [m]."""
    from unsew.geometry.topology import boundary_loops

    e, _, rest = _edges(mesh)
    rest_of = dict(zip(map(tuple, e.tolist()), rest.tolist()))  # a boundary edge appears once, as its face has it
    out = []
    for loop in boundary_loops(mesh.faces):
        nxt = np.roll(loop, -1)
        r = sum(rest_of.get((a, b), rest_of.get((b, a), 0.0)) for a, b in zip(loop.tolist(), nxt.tolist()))
        draped = float(np.linalg.norm(x[loop] - x[nxt], axis=1).sum())
        out.append({"centre": x[loop].mean(axis=0), "rest": r, "draped": draped})
    ys = [o["centre"][1] for o in out]
    for k, o in enumerate(out):
        o["name"] = ("neck" if k == int(np.argmax(ys)) and len(out) > 1 else "hem" if k == int(np.argmin(ys))
                     else "left" if o["centre"][0] > 0 else "right")
    return out


def longest_edge(x, mesh) -> tuple[float, str]:
    """Where the drape x (n_x, 3) [m] on ``mesh`` is stretched most: the height of its longest
    edge (over rest length) [m] and that edge's panel."""
    e, eu, rest = _edges(mesh)
    k = int(np.argmax(np.linalg.norm(x[e[:, 0]] - x[e[:, 1]], axis=1) / np.maximum(rest, 1e-12)))
    return float(x[e[k]].mean(axis=0)[1]), mesh.panel_names[int(mesh.uv_panel[eu[k, 0]])]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--case", required=True, type=Path, help="the case folder the results fitted")
    ap.add_argument("--results", nargs="+", required=True, type=Path, help="result folders of unsew fit")
    ap.add_argument("--edges", default="0.024,0.025,0.026", help="mesh edge lengths [m], comma-separated")
    args = ap.parse_args(argv)
    for d in [args.case, *args.results]:
        if not d.is_dir():
            print(f"bench stretch: no such folder {d}", file=sys.stderr)
            return 2
    for f in [args.case / "meta.json"] + [r / n for r in args.results for n in ("pattern.json", "pattern_graded.json")]:
        if not f.is_file():
            print(f"bench stretch: {f} is missing (--case is a case folder, --results result folders of unsew fit)",
                  file=sys.stderr)
            return 2
    from tables import print_table

    from unsew.body.case import load_case
    from unsew.body.sdf import BodySDF
    from unsew.dress import dress
    from unsew.fit.config import load_config
    from unsew.io.garmentcode import load_pattern
    from unsew.sim.checks import check_dressed
    from unsew.sim.material import material_from_dict

    case = load_case(args.case)
    sdf, cfg = BodySDF.build(case.body), load_config(None)
    edges = [float(h) for h in args.edges.split(",") if h]
    rows = []
    for res in args.results:
        fitted = load_pattern(res / "pattern.json")
        if not (fitted.unsew or {}).get("material"):
            print(f"bench stretch: {res / 'pattern.json'} carries no fitted material (not a result of unsew fit)",
                  file=sys.stderr)
            return 2
        material = material_from_dict(fitted.unsew["material"])
        patterns = [("true", case.pattern_gt), ("graded", load_pattern(res / "pattern_graded.json")), ("fitted", fitted)]
        for label, pattern in patterns:
            if pattern is None:
                continue
            for h in edges:
                d = dress(pattern, case.body, sdf=sdf, material=material, settings=cfg.drape.replace(edge_length=h))
                x = d.x.numpy()
                v = check_dressed(d, body=case.body)
                y, panel = longest_edge(x, d.mesh)
                row = {"result": res.parent.name + "/" + res.name, "pattern": label, "edge [cm]": 100 * h,
                       "verdict": "ok" if v.ok else v.reason.split(":")[0], "stretch max": v.stretch_max,
                       "p99": v.stretch_p99,
                       "longest at y [m]": y, "panel": panel}
                for o in openings(x, d.mesh):
                    row[f"{o['name']} rest / draped [cm]"] = f"{100 * o['rest']:.1f} / {100 * o['draped']:.1f}"
                rows.append(row)
                print(" | ".join(f"{k}: {v:.3f}" if isinstance(v, float) else f"{k}: {v}" for k, v in row.items()),
                      file=sys.stderr, flush=True)
    columns = list(dict.fromkeys(k for r in rows for k in r))  # every opening's column, in order of appearance
    print_table(rows, columns, title=f"Stretch of fresh drapes on {args.case.name} (each result's fitted material)",
                digits=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
