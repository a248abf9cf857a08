"""Creep of a dressed garment: how far it keeps moving after ``dress()`` has settled it.

A fit's phase two drapes 15 steps per iteration, each warm-started from the last, so after 30
iterations the garment has been simulated 450 steps beyond the drape that the benchmark targets
were made with (sew 80 + settle 40 steps, FitConfig's defaults). If the garment is still moving
then, the optimizer chases a drape that drifts away from the target with the pattern held fixed.

The friction of the simulator is Coulomb friction made viscous below a slip speed
``friction_eps`` [m/s] (StepParams; the damping is mu f_n / sqrt(|v_t|^2 + eps^2)), so a garment
that friction should hold creeps at up to about eps under a steady tangential load. This
benchmark dresses each garment with the library defaults, then continues the drape in chunks
with the shipped eps and with smaller ones (the continuation only: the dressing itself always
uses the default), and prints after each chunk: the mean vertical displacement of the garment
[mm], the largest displacement of any vertex [mm], the vertical displacement of each open
contour's centre [mm], and the fastest vertex [m/s].

Run: OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_creep.py [--garments shorts tshirt]
     [--eps 1e-2 1e-3 1e-4] [--chunks 12] [--chunk-steps 40] [--edge-length 0.025]
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--garments", nargs="+", default=["shorts", "tshirt"],
                    choices=["tshirt", "dress", "pants", "shorts", "skirt"])
    ap.add_argument("--eps", nargs="+", type=float, default=[1e-2, 1e-3, 1e-4], help="friction_eps values [m/s]")
    ap.add_argument("--chunks", type=int, default=12)
    ap.add_argument("--chunk-steps", type=int, default=40)
    ap.add_argument("--edge-length", type=float, default=0.025)
    ap.add_argument("--material", default="cotton")
    args = ap.parse_args()
    if min(args.eps) <= 0 or args.chunks < 1 or args.chunk_steps < 1:
        ap.error("--eps values, --chunks and --chunk-steps must be positive")
    from unsew.sim.material import MATERIALS

    if args.material not in MATERIALS:
        ap.error(f"--material {args.material!r}: not a library material ({', '.join(MATERIALS)})")

    import numpy as np
    import torch

    torch.set_num_threads(1)
    from unsew.body.body import default_body
    from unsew.body.sdf import BodySDF
    from unsew.dress import dress
    from unsew.fit.config import FitConfig
    from unsew.losses.contours import open_contours
    from unsew.pattern.base import make_base_pattern
    from unsew.sim.drape import drape
    from unsew.sim.integrator import StepParams
    from unsew.sim.state import SimState

    cfg = FitConfig()
    body = default_body()
    sdf = BodySDF.build(body)
    ds = cfg.drape.replace(edge_length=args.edge_length)
    print(f"dress: sew {ds.sew_steps} + settle {ds.settle_steps} steps, dt {ds.dt} s, {args.material}, "
          f"edge {args.edge_length} m; shipped friction_eps {StepParams.friction_eps} m/s")
    for g in args.garments:
        d = dress(make_base_pattern(g), body, sdf=sdf, material=args.material, settings=ds)
        x0 = d.x.detach().numpy().copy()
        contours = open_contours(x0, d.mesh.faces)
        m = d.material
        for eps in args.eps:
            print(f"\n{g}: {len(x0)} vertices, friction_eps {eps:g} m/s (max speed after dressing "
                  f"{d.stats['max_speed']:.4f} m/s)")
            print(f"{'steps':>6} {'mean dy mm':>11} {'max |dx| mm':>12} {'max speed m/s':>14}  contour dy mm")
            st = SimState.at_rest(d.x.detach().clone())
            t = time.perf_counter()
            for k in range(args.chunks):
                with torch.no_grad():
                    st = drape(d.model, st, sdf, uv=d.uv, gamma=m.gamma(), density=m.density,
                               settings=ds.replace(friction_eps=eps), steps=args.chunk_steps, friction=m.friction)
                x = st.x.numpy()
                dy = [1000 * float(x[c.indices, 1].mean() - x0[c.indices, 1].mean()) for c in contours]
                print(f"{(k + 1) * args.chunk_steps:>6} {1000 * float((x[:, 1] - x0[:, 1]).mean()):>11.1f} "
                      f"{1000 * float(np.abs(x - x0).max()):>12.1f} {float(st.v.norm(dim=1).max()):>14.4f}  "
                      + " ".join(f"{v:+.1f}" for v in dy))
            print(f"({time.perf_counter() - t:.0f} s)")


if __name__ == "__main__":
    main()
