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

Without case folders, ``--garment G`` makes the true pattern of bench_fit's case for G
(unsew.fit.synthetic.DEFAULT_ALTERATIONS, default body) and, for every fabric of ``--fabrics``
and every edge length h of ``--resolutions``, dresses it at h (the reference) and at h times
(1 - spread) and (1 + spread); the floor is the Chamfer distance of those two drapes to the
reference. It answers whether the floor is a property of the fabric or of the mesh resolution.
``--from-target A`` also starts each of the two drapes a fraction A of the way from its own
drape to the closest points of the reference and lets it settle (``--settle`` steps): whether
the other mesh has an equilibrium near the reference's folds at all.

     bench_mesh_floor.py --garment dress [--fabrics silk cotton ...] [--resolutions 0.025 0.0125]
     [--spread 0.04] [--from-target 0.8] [--settle 120]
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cases", nargs="*")
    ap.add_argument("--edge-lengths", type=float, nargs="+", default=[0.024, 0.025, 0.026],
                    help="panel mesh edge lengths to dress the true pattern at [m]")
    ap.add_argument("--samples", type=int, default=20000)
    ap.add_argument("--garment", choices=["tshirt", "dress", "pants", "shorts", "skirt"],
                    help="no case folders: bench_fit's true pattern of this garment, in --fabrics")
    ap.add_argument("--fabrics", nargs="+", default=None, help="library fabrics (default: the case's own)")
    ap.add_argument("--resolutions", type=float, nargs="+", default=[0.025], help="reference edge lengths [m]")
    ap.add_argument("--spread", type=float, default=0.04, help="relative edge length change of the other meshes")
    ap.add_argument("--from-target", type=float, default=0.0, metavar="A",
                    help="also settle each other drape from A of the way to the reference (0: skip)")
    ap.add_argument("--settle", type=int, default=120, help="settle steps after --from-target's start")
    args = ap.parse_args()
    if bool(args.cases) == bool(args.garment):
        ap.error("give case folders or --garment, not both and not neither")
    if args.cases and (args.fabrics or args.from_target > 0 or args.resolutions != [0.025]):
        ap.error("--fabrics, --resolutions and --from-target go with --garment; case folders take --edge-lengths")
    if not 0.0 <= args.from_target <= 1.0:
        ap.error("--from-target must be in [0, 1]")
    if not 0.0 < args.spread < 0.5 or min(args.resolutions) <= 0:
        ap.error("--spread must be in (0, 0.5) and --resolutions positive")
    if args.garment:
        from unsew.sim.material import MATERIALS

        unknown = [f for f in args.fabrics or () if f not in MATERIALS]
        if unknown:
            ap.error(f"unknown fabric(s) {', '.join(unknown)}; known: {', '.join(MATERIALS)}")
        return _by_resolution(args)
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
            dr = dress(case.pattern_gt, case.body, sdf=sdf, material=MATERIALS[truth],
                       settings=cfg.drape.replace(edge_length=h))
            cf = chamfer_mm(dr.x.numpy(), dr.mesh.faces, tv, tf, n_samples=args.samples).mean_mm
            print(f"{name:<12} {truth:<10} {h:>7.4f} {len(dr.x):>6d} {cf:>10.2f} {time.perf_counter() - t:>7.1f}",
                  flush=True)


def _by_resolution(args) -> None:
    """``--garment`` mode: the floor per fabric and reference edge length (module docstring)."""
    import torch
    import trimesh

    torch.set_num_threads(1)
    from unsew.body.body import default_body
    from unsew.body.sdf import BodySDF
    from unsew.dress import dress
    from unsew.errors import SimulationError
    from unsew.fit.config import FitConfig
    from unsew.fit.synthetic import DEFAULT_ALTERATIONS, make_truth_pattern
    from unsew.metrics.surface import chamfer_mm
    from unsew.sim.drape import drape
    from unsew.sim.material import get_material
    from unsew.sim.state import SimState

    cfg = FitConfig()
    body = default_body()
    sdf = BodySDF.build(body)
    alt = DEFAULT_ALTERATIONS[args.garment]
    pattern = make_truth_pattern(args.garment, alt, body=body)
    fabrics = args.fabrics or [alt.material]
    lo, hi = 1 - args.spread, 1 + args.spread
    head = f"{'garment':<8} {'fabric':<10} {'edge m':>7} {'verts':>6} {'floor x' + format(lo, '.2f'):>12} {'x' + format(hi, '.2f'):>7}"
    if args.from_target > 0:
        head += f" {'from target':>12} {'':>7}"
    print(head + f" {'time s':>7}")
    for fabric in fabrics:
        mat = get_material(fabric)
        for h in args.resolutions:
            t = time.perf_counter()
            ref = dress(pattern, body, sdf=sdf, material=mat, settings=cfg.drape.replace(edge_length=h))
            rv, rf = ref.x.numpy(), ref.mesh.faces
            near = trimesh.Trimesh(rv, rf, process=False)
            floors, guided = [], []
            for f in (lo, hi):
                d = dress(pattern, body, sdf=sdf, material=mat, settings=cfg.drape.replace(edge_length=h * f))
                x = d.x.numpy()
                floors.append(chamfer_mm(x, d.mesh.faces, rv, rf, n_samples=args.samples).mean_mm)
                if args.from_target > 0:
                    cp = trimesh.proximity.closest_point(near, x)[0]
                    x0 = torch.as_tensor(x + args.from_target * (cp - x))
                    try:
                        st = drape(d.model, SimState.at_rest(x0), sdf, uv=d.uv, gamma=mat.gamma(),
                                   density=mat.density, settings=cfg.drape, steps=args.settle, friction=mat.friction)
                        guided.append(chamfer_mm(st.x.detach().numpy(), d.mesh.faces, rv, rf,
                                                 n_samples=args.samples).mean_mm)
                    except SimulationError:
                        guided.append(float("nan"))  # the projected start was too crumpled to solve
            row = f"{args.garment:<8} {fabric:<10} {h:>7.4f} {len(rv):>6d} {floors[0]:>12.2f} {floors[1]:>7.2f}"
            if guided:
                row += f" {guided[0]:>12.2f} {guided[1]:>7.2f}"
            print(row + f" {time.perf_counter() - t:>7.1f}", flush=True)


if __name__ == "__main__":
    main()
