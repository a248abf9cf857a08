"""Meshing benchmark: every base pattern at 1, 2 and 3 cm target edge length.

Prints, per pattern and edge length: 2D vertices (U), sewn vertices (X), triangles, the smallest
triangle angle [deg], the number of inverted/degenerate triangles, the meshing time [ms] (best of
``--repeat`` runs of ``mesh_pattern``) and the time to build the K -> U parameter maps [ms]
(``PatternParams.build``: symmetry, curve frames, mean value coordinates).

Run: OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_meshing.py [--repeat 3] [--no-params]
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-params", action="store_true", help="skip timing PatternParams.build")
    ap.add_argument("--garments", nargs="*", default=["tshirt", "dress", "pants", "shorts", "skirt"])
    args = ap.parse_args(argv)

    import torch

    torch.set_num_threads(1)
    from unsew.meshing import mesh_pattern
    from unsew.pattern.base import make_base_pattern
    from unsew.pattern.params import PatternParams

    head = (
        f"{'pattern':<8} {'h [cm]':>6} {'U verts':>8} {'X verts':>8} {'triangles':>9} {'min angle':>9} "
        f"{'bad':>4} {'mesh [ms]':>9}"
    )
    if not args.no_params:
        head += f" {'params [ms]':>11}"
    print(head)
    print("-" * len(head))
    for g in args.garments:
        pat = make_base_pattern(g)
        for h in (0.01, 0.02, 0.03):
            best = float("inf")
            for _ in range(max(1, args.repeat)):
                t0 = time.perf_counter()
                m = mesh_pattern(pat, edge_length=h)
                best = min(best, time.perf_counter() - t0)
            q = m.quality()
            row = (
                f"{g:<8} {h * 100:>6.0f} {q['uv_vertices']:>8} {q['sewn_vertices']:>8} {q['triangles']:>9} "
                f"{q['min_angle_deg']:>9.2f} {q['bad_triangles']:>4} {best * 1e3:>9.1f}"
            )
            if not args.no_params:
                t0 = time.perf_counter()
                PatternParams.build(pat, m)
                row += f" {(time.perf_counter() - t0) * 1e3:>11.0f}"
            print(row, flush=True)


if __name__ == "__main__":
    main()
