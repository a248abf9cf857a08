"""Dressing benchmark: every base pattern placed, sewn and settled on two bodies.

Each base pattern is sized to the body's measurements (``measure_body``).

Prints, per body and garment: sewn vertices, placement / sewing / settling time [s], the
deepest vertex inside the body [mm], the share of vertices inside [%], the largest gap between
the two copies of a seam vertex after sewing [mm], the largest edge stretch (3D length over
rest length), folded-through triangles, the fastest vertex after settling [m/s], and the
garment's bounding box height range [m] (is it still where it belongs?). Also checks the
placement: vertices inside the body and stitches whose edges are not closer to each other than
to other panels.

Run: OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_dress.py [--edge-length 0.03]
     [--garments tshirt pants] [--bodies default wide] [--png-dir DIR]
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

#: The second body: the default one 8 % wider and deeper.
WIDE = [1.08, 1.0, 1.08]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--edge-length", type=float, default=0.03)
    ap.add_argument("--garments", nargs="*", default=["tshirt", "dress", "pants", "shorts", "skirt"])
    ap.add_argument("--bodies", nargs="*", default=["default", "wide"])
    ap.add_argument("--png-dir", default=None, help="render each drape (front, side) here")
    args = ap.parse_args()

    import numpy as np
    import torch

    torch.set_num_threads(1)
    from unsew.body.body import default_body
    from unsew.body.measure import measure_body
    from unsew.body.placement import place_garment, stitch_distances
    from unsew.body.sdf import BodySDF
    from unsew.dress import dress, dress_stats
    from unsew.meshing import mesh_pattern
    from unsew.pattern.base import make_base_pattern

    head = (
        f"{'body':<8} {'garment':<7} {'verts':>6} {'place s':>7} {'sew s':>6} {'settle s':>8} {'depth mm':>8} "
        f"{'inside %':>8} {'gap mm':>6} {'stretch':>7} {'folded':>6} {'speed m/s':>9} {'y range m':>11} "
        f"{'pl.in':>5} {'pl.bad':>6}"
    )
    print(f"edge length {args.edge_length} m, cotton, torch threads 1")
    print(head)
    print("-" * len(head))
    for bname in args.bodies:
        body = default_body() if bname == "default" else default_body().transformed(scale=WIDE)
        sdf = BodySDF.build(body)
        meas = measure_body(body)  # base patterns sized to the body they dress
        for g in args.garments:
            pat = make_base_pattern(g, meas)
            mesh = mesh_pattern(pat, edge_length=args.edge_length)
            xp = place_garment(pat, mesh, body, sdf=sdf)
            with torch.no_grad():
                dp, _ = sdf.query(torch.as_tensor(xp))
            bad = sum(r["pair"] >= r["other"] for r in stitch_distances(mesh, xp))
            t0 = time.perf_counter()
            d = dress(pat, body, sdf=sdf, mesh=mesh)
            s = dress_stats(d)
            bb = s["bbox"]
            print(
                f"{bname:<8} {g:<7} {s['n_x']:>6} {s['place_s']:>7.2f} {s['sew_s']:>6.2f} {s['settle_s']:>8.2f} "
                f"{s['depth_mm']:>8.2f} {s['inside_pct']:>8.2f} {s['seam_gap'] * 1000:>6.2f} {s['stretch']:>7.3f} "
                f"{s['inverted']:>6d} {s['max_speed']:>9.3f} {bb[0, 1]:>5.2f}-{bb[1, 1]:<5.2f} "
                f"{int((dp < 0).sum()):>5d} {bad:>6d}",
                flush=True,
            )
            if args.png_dir:
                from unsew.report.render import render_views

                os.makedirs(args.png_dir, exist_ok=True)
                render_views(os.path.join(args.png_dir, f"{bname}_{g}.png"), d.x.numpy(), mesh.faces,
                             views=("front", "side"), body=(body.verts, body.faces), title=f"{g} on {bname}")
            del t0
    print("pl.in: placed vertices inside the body; pl.bad: stitches whose edges are not closer to "
          "each other than to any other panel (mean distances)")


if __name__ == "__main__":
    main()
