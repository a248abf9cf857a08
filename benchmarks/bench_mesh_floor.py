"""The floor a fit's Chamfer cannot honestly go below: the *true* pattern in the *true* material,
dressed from scratch on another triangulation of its panels.

A fit meshes its own (graded, then optimized) pattern, so even a perfect pattern is draped on a
triangulation other than the one the target was made with. For each case folder (FORMATS.md,
with pattern_gt.json and meta.json's truth.material, as benchmarks/make_cases.py and
bench_fit.py write them) the true pattern is dressed with the fit's settings (FitConfig: sew and
settle steps, dt) in its true material, meshed at each of ``--edge-lengths``; the Chamfer
distance [mm] of each drape to the target is printed, with the vertex count. At the target's own
edge length the drape reproduces the target (0.00 mm); the other rows show how far the folds of
the same garment move for a different triangulation.

Run: OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_mesh_floor.py CASE_DIR [CASE_DIR ...]
     [--edge-lengths 0.024 0.025 0.026]
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cases", nargs="+")
    ap.add_argument("--edge-lengths", type=float, nargs="+", default=[0.024, 0.025, 0.026],
                    help="panel mesh edge lengths to dress the true pattern at [m]")
    ap.add_argument("--samples", type=int, default=20000)
    args = ap.parse_args()
    from truth_cases import check_case_dirs, truth_cases

    check_case_dirs(ap, args.cases)
    import torch

    torch.set_num_threads(1)
    from unsew.dress import dress
    from unsew.fit.config import FitConfig
    from unsew.metrics.surface import chamfer_mm
    from unsew.sim.material import MATERIALS

    cfg = FitConfig()
    print(f"{'case':<12} {'fabric':<10} {'edge m':>7} {'verts':>6} {'Chamfer mm':>10} {'time s':>7}")
    for name, case, truth, sdf, tv, tf in truth_cases(args.cases):
        for h in args.edge_lengths:
            t = time.perf_counter()
            dr = dress(case.pattern_gt, case.body, sdf=sdf, edge_length=h, material=MATERIALS[truth],
                       sew_steps=cfg.sew_steps, settle_steps=cfg.settle_steps, dt=cfg.dt)
            cf = chamfer_mm(dr.x.numpy(), dr.mesh.faces, tv, tf, n_samples=args.samples).mean_mm
            print(f"{name:<12} {truth:<10} {h:>7.4f} {len(dr.x):>6d} {cf:>10.2f} {time.perf_counter() - t:>7.1f}",
                  flush=True)


if __name__ == "__main__":
    main()
