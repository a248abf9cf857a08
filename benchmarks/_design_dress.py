"""Drafts of the design space dressed with unsew.dress (``true_patterns --designs``).

Each design is drafted for the default body and placed around it (unsew.body.placement: the
start's widest seam [mm], the distance between a seam vertex's two copies, and that seam's
label), dressed (4 cm edges, the dressing's default settings) and judged: the drape verdict
(unsew.sim.checks), the widest seam left open after sewing [mm], the largest edge stretch [-],
inverted triangles, the share of vertices inside the body [%], and whether the dressing placed
the garment again (a sewing fault seen).

    python -m benchmarks true_patterns --designs [--edge-length 0.04] [--only NAME ...]
"""

from __future__ import annotations

import argparse
import time

#: The designs dressed: Design fields.
DESIGNS = (
    dict(garment="pants"),
    dict(sleeves="short", sleeve_pieces=2),
    dict(sleeves="short", cuffs=True),
    dict(sleeves="long", sleeve_pieces=2, cuffs=True, neckline_front="v", neckline_back="boat"),
    dict(sleeves="long", sleeve_pieces=2, neckline_front="v", neckline_back="boat"),
    dict(garment="dress", waist_seam=True, panels=4, neckline_front="square", sleeves="none"),
    dict(garment="jumpsuit", leg="knee", neckline_front="v"),
    dict(garment="skirt", skirt="circle", circle_fraction=0.75, panels=6, waistband=True),
    dict(garment="skirt", skirt="pencil", panels=4),
    dict(sleeves="none", darts=True, length=0.05),
    dict(garment="dress", waist_seam=True, waistband=True, darts=True, sleeves="short"),
    dict(garment="skirt", skirt="pencil", darts=True, waistband=True),
    dict(garment="shorts", darts=True, waistband=True),
    dict(garment="pants", darts=True),
)


def _start_gap(pattern, body, sdf, edge_length: float) -> tuple[float, str]:
    """The largest distance [m] between the two placed copies of a seam vertex at the start of
    the sewing, and the label of its stitch."""
    import numpy as np

    from unsew.body.placement import place_garment
    from unsew.meshing import mesh_pattern

    mesh = mesh_pattern(pattern, edge_length=edge_length)
    x = place_garment(pattern, mesh, body, sdf=sdf)
    worst = (0.0, "")
    for st in pattern.stitches:
        a = mesh.edge_verts[(st.a.panel, st.a.edge)]
        b = mesh.edge_verts[(st.b.panel, st.b.edge)][::-1]  # a's start meets b's end
        g = float(np.linalg.norm(x[a] - x[b], axis=1).max())
        worst = max(worst, (g, st.label))
    return worst


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        prog="true_patterns --designs",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    ap.add_argument("--edge-length", type=float, default=0.04, help="mesh edge length [m]")
    ap.add_argument("--only", nargs="*", default=None, help="design names to dress (default: all)")
    args = ap.parse_args(argv)

    from unsew.body.body import default_body
    from unsew.body.sdf import BodySDF
    from unsew.dress import DRESS_SETTINGS, dress, dress_stats
    from unsew.pattern.design import Design, design_name, draft
    from unsew.sim.checks import check_dressed

    body = default_body()
    sdf = BodySDF.build(body)
    settings = DRESS_SETTINGS.replace(edge_length=args.edge_length)
    print(
        "| design | start gap [mm] | its seam | verdict | seam gap [mm] | stretch | inverted | inside [%] "
        "| placed again | time [s] |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    for kw in DESIGNS:
        d = Design(**kw)
        name = design_name(d)
        if args.only and name not in args.only:
            continue
        t0 = time.perf_counter()
        p = draft(d)
        gap, seam = _start_gap(p, body, sdf, args.edge_length)
        r = dress(p, body, sdf=sdf, settings=settings)
        v, s = check_dressed(r, body=body), dress_stats(r)
        verdict = "ok" if v.ok else v.reason
        print(
            f"| {name} | {gap * 1000:.0f} | {seam} | {verdict} | {s['seam_gap'] * 1000:.1f} "
            f"| {s['stretch']:.2f} | {s['inverted']} "
            f"| {s['inside_pct']:.2f} | {'yes' if r.stats.get('placement_retry') else 'no'} "
            f"| {time.perf_counter() - t0:.0f} |",
            flush=True,
        )
    return 0
