"""Quasi-static drape (implicit-function-theorem gradients) against the dynamic rollout.

A small sewn garment: a sleeve, two panels sewn along both long sides into a jersey tube of radius
7 cm around a horizontal capsule (an arm, radius 5 cm), its shoulder ring pinned, resting on the
arm (2 mm above it along the top, in the contact band); its weight presses it onto the arm.
For each size:

- static: ``drape_static`` forward (Newton-CG to tol), backward with the exact adjoint and with
  the projected one;
- dynamic: ``drape`` for K steps from the same start (friction 0, so both share the equilibrium)
  forward + backward, as the fit runs it (15 steps) and longer;

and the gradients of one loss, L = sum(w * x) with fixed random w, w.r.t. uv and Gamma:
direction cosine with the static exact-adjoint gradient, and the distance of each result to the
static solution x*. Times are minima of --repeat runs [s]; the load average is printed.

    OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_static.py [--sizes 8,16] [--steps 15,50,150] [--repeat 2]
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import numpy as np  # noqa: E402
import torch  # noqa: E402

GAMMA = (600.0, 60.0, 300.0, 100.0, 2.94e-6)  # jersey (material.py) [N/m] x4, [N*m]
DENSITY = 0.18  # [kg/m^2]
R_ARM = 0.05  # capsule radius [m]
R_SLEEVE = 0.07  # tube radius [m]
LENGTH = 0.4  # sleeve length [m]
DROP = 0.018  # the sleeve starts this far below concentric [m]: 2 mm over the arm, in the contact band


def tube(n: int):
    """Two panels (n x 2n quads, around x along) sewn into a tube around the x axis; returns
    faces, faces_uv, uv (Nu, 2) [m], x0 (N, 3) [m], N and the pinned shoulder ring (u = 0)."""
    from unsew.sim.meshes import grid_sheet

    width = np.pi * R_SLEEVE  # half the circumference [m], along the panel's v
    uv_a, f_a = grid_sheet(2 * n, n, LENGTH, width)  # u along the sleeve, v around it
    nv = len(uv_a)
    gap = width * 1.2
    uv = np.concatenate([uv_a, uv_a + [0.0, gap]])
    faces_uv = np.concatenate([f_a, f_a + nv])
    cols = np.arange(2 * n + 1)
    bottom, topr = cols, n * (2 * n + 1) + cols  # v = 0 and v = width rows of a panel
    x_of_u = np.arange(2 * nv)
    x_of_u[nv + bottom] = topr  # B's v = 0 edge onto A's v = width edge
    x_of_u[nv + topr] = bottom  # B's v = width edge onto A's v = 0 edge
    uniq, x_of_u = np.unique(x_of_u, return_inverse=True)
    n_x = len(uniq)
    on_b = np.arange(2 * nv) >= nv
    theta = np.where(on_b, np.pi, 0.0) + (uv[:, 1] - np.where(on_b, gap, 0.0)) / width * np.pi
    xyz_u = np.c_[uv[:, 0], R_SLEEVE * np.cos(theta) - DROP, R_SLEEVE * np.sin(theta)]
    x0 = np.zeros((n_x, 3))
    x0[x_of_u] = xyz_u
    pinned = np.unique(x_of_u[np.isclose(uv[:, 0], 0.0)])
    return x_of_u[faces_uv], faces_uv, uv, x0, n_x, pinned


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="8,16", help="quads across each panel (vertices ~ 4 n^2)")
    ap.add_argument("--steps", default="15,50,150")
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args()
    torch.set_num_threads(1)
    from unsew.sim import CapsuleSDF, SimModel, SimState, drape
    from unsew.sim.integrator import StepParams, forces, rest_data, total_energy
    from unsew.sim.static import StaticInfo, drape_static

    sdf = CapsuleSDF((-0.1, 0.0, 0.0), (0.5, 0.0, 0.0), R_ARM)
    gamma0 = torch.tensor(GAMMA, dtype=torch.float64)
    print(f"torch {torch.__version__}, 1 thread, min of {args.repeat} runs; load average {os.getloadavg()[0]:.2f} (2 shared cores)")
    hdr = (
        f"{'verts':>5} {'method':>18} | {'fwd s':>6} {'rev s':>6} {'iters':>5} | {'|x-x*| mm':>9} {'min d mm':>8} | "
        f"{'cos uv':>7} {'cos Gam':>7} {'|g_uv|/|g*|':>11} | {'E mJ':>9} {'|grad E|':>8} | {'load':>4}"
    )
    print(hdr)
    print("-" * len(hdr))
    for n in [int(s) for s in args.sizes.split(",")]:
        faces, faces_uv, uv, x0, n_x, top = tube(n)
        model = SimModel.build(faces, faces_uv, n=n_x, pinned=top)
        uvt = torch.as_tensor(uv)
        x0t = torch.as_tensor(x0)
        w = torch.randn(n_x, 3, generator=torch.Generator().manual_seed(0), dtype=torch.float64)

        def run_static(adjoint):
            uvp, gp = uvt.clone().requires_grad_(), gamma0.clone().requires_grad_()
            info = StaticInfo()
            t0 = time.perf_counter()
            xs = drape_static(model, x0t, sdf, uv=uvp, gamma=gp, density=DENSITY, adjoint=adjoint, info=info)
            t1 = time.perf_counter()
            g = torch.autograd.grad((w * xs).sum(), (uvp, gp))
            t2 = time.perf_counter()
            return xs.detach(), g, t1 - t0, t2 - t1, f"{info.iterations}/{info.adjoint_iterations}"

        def run_dynamic(steps):
            uvp, gp = uvt.clone().requires_grad_(), gamma0.clone().requires_grad_()
            t0 = time.perf_counter()
            out = drape(model, SimState.at_rest(x0t), sdf, uv=uvp, gamma=gp, density=DENSITY, steps=steps, friction=0.0)
            t1 = time.perf_counter()
            g = torch.autograd.grad((w * out.x).sum(), (uvp, gp))
            t2 = time.perf_counter()
            return out.x.detach(), g, t1 - t0, t2 - t1, str(steps)

        methods = [("static exact", lambda: run_static("exact")), ("static projected", lambda: run_static("projected"))]
        methods += [(f"dynamic {k} steps", (lambda k=k: run_dynamic(k))) for k in [int(s) for s in args.steps.split(",")]]
        best = {}
        for _ in range(args.repeat):
            for name, fn in methods:
                xs, g, tf, tr, its = fn()
                b = best.get(name)
                best[name] = (xs, g, min(tf, b[2]) if b else tf, min(tr, b[3]) if b else tr, its)
        xstar, gstar = best["static exact"][0], best["static exact"][1]
        rest = rest_data(model, uvt, DENSITY)
        params = StepParams(friction=0.0)
        load = os.getloadavg()[0]
        for name, _ in methods:
            xs, g, tf, tr, its = best[name]
            cos = [float((a * b).sum() / (a.norm() * b.norm())) for a, b in zip(g, gstar)]
            ratio = float(g[0].norm() / gstar[0].norm())
            d, _ = sdf.query(xs[~model.pinned])  # free vertices (the pinned ring sits 2 mm over the arm)
            energy = float(total_energy(model, rest, xs, sdf, gamma0, params))
            fres = float((forces(model, rest, xs, torch.zeros_like(xs), sdf, gamma0, params, hessian=False)[0][~model.pinned]).abs().max())
            fres /= float(rest.mass.max() * params.gravity)
            print(
                f"{n_x:>5} {name:>18} | {tf:6.3f} {tr:6.3f} {its:>5} | {float((xs - xstar).norm(dim=1).max()) * 1e3:9.4f} "
                f"{float(d.min()) * 1e3:8.3f} | {cos[0]:7.4f} {cos[1]:7.4f} {ratio:11.4f} | {energy * 1e3:9.5f} {fres:8.1e} | {load:4.1f}",
                flush=True,
            )
    print("iters: Newton/adjoint-CG iterations (static) or steps (dynamic); cos: direction cosine of the")
    print("gradient w.r.t. uv / Gamma with the static exact-adjoint one; |x-x*|: largest vertex distance to it;")
    print("E: total potential energy of the result; |grad E|: max force residual / heaviest vertex weight.")


if __name__ == "__main__":
    main()
