"""``unsew pattern mesh P.json --edge-length 0.02 --out REST.obj``: triangulate and sew the panels,
write the flat panels as OBJ (pattern coordinates as UVs) and print the mesh figures."""

from __future__ import annotations

import argparse
import time

from unsew.commands._output import check_out
from unsew.errors import InputError

__all__ = ["run"]


def run(args: argparse.Namespace) -> int:
    from unsew.commands._checks import check_triangle_budget
    from unsew.io.garmentcode import load_pattern
    from unsew.meshing.sew import EDGE_LENGTH_RANGE, mesh_pattern, write_rest_obj

    lo, hi = EDGE_LENGTH_RANGE
    h = float(args.edge_length)
    if not (lo <= h <= hi):
        raise InputError(f"--edge-length {h:g} m is outside {lo:g}-{hi:g} m; the usual range is 0.01-0.03 m")
    if not str(args.out).lower().endswith(".obj"):
        raise InputError(f"--out {args.out} should name an .obj file")
    if args.max_triangles < 1:
        raise InputError(f"--max-triangles must be positive, got {args.max_triangles}")
    pattern = load_pattern(args.pattern)
    check_triangle_budget(pattern, h, limit=args.max_triangles)  # before minutes of meshing
    check_out(args.out, overwrite=args.overwrite)
    t0 = time.perf_counter()
    mesh = mesh_pattern(pattern, edge_length=h)
    dt = time.perf_counter() - t0
    write_rest_obj(mesh, args.out)
    q = mesh.quality()
    print(f"panels            {len(mesh.panel_names)}")
    print(f"edge length       {h * 100:.3g} cm")
    print(f"vertices (2D)     {q['uv_vertices']}")
    print(f"vertices (sewn)   {q['sewn_vertices']}")
    print(f"triangles         {q['triangles']}")
    print(f"seam pairs        {len(mesh.seam_pairs)}")
    print(f"min angle         {q['min_angle_deg']:.2f} deg")
    print(f"meshing time      {dt * 1e3:.0f} ms")
    print(f"wrote {args.out}")
    return 0
