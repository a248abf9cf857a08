"""Body SDF benchmark: grid build time and the process's peak memory for the default body or a
case's body (no cache), accuracy against exact point-to-mesh distance, and query time of 8K
points with gradient (forward + backward).

    OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_sdf.py [--threads 2] [--voxel 0.005]
        [--case DIR]

The peak (``ru_maxrss``) is read before and after the build; the build is the first large
allocation after the body is loaded, so run one body per process.

Prints a table; never asserts timings.
"""

import argparse
import os
import resource
import time

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def _time_queries(sdf, pts, rng, n_points: int) -> list[tuple]:
    """(label, median forward ms, median forward + gradient ms) of SDF queries on n_points near
    the surface points ``pts`` (N, 3) [m], in float64 and float32, random and sorted order."""
    import numpy as np
    import torch

    xq = torch.tensor(pts[rng.integers(0, len(pts), n_points)] + rng.normal(0, 0.02, (n_points, 3)))
    # garment vertices are spatially coherent; random order is the worst case for the cache
    key = np.lexsort(np.floor(xq.numpy() / 0.02).T)
    rows = []
    for dtype, order in ((torch.float64, "random"), (torch.float32, "random"), (torch.float64, "sorted")):
        xx = (xq[key] if order == "sorted" else xq).to(dtype).requires_grad_(True)
        sdf.query(xx)  # warm: grid tensors on this device/dtype
        ts_f, ts_fb = [], []
        for _ in range(20):
            t = time.perf_counter()
            with torch.no_grad():
                sdf.query(xx)
            ts_f.append(time.perf_counter() - t)
            t = time.perf_counter()
            dd, nn = sdf.query(xx)
            (g,) = torch.autograd.grad(dd.sum(), xx)
            ts_fb.append(time.perf_counter() - t)
        rows.append(
            (
                f"{str(dtype).replace('torch.', '')}, {order} order",
                np.median(ts_f) * 1e3,
                np.median(ts_fb) * 1e3,
            )
        )
    return rows


def _compare_igl(body, sdf, t_build: float) -> None:
    """Time libigl's exact unsigned distance at every grid node against the grid's."""
    import numpy as np

    nz, ny, nx = sdf.shape
    from unsew.geometry.distance import MeshQuery

    Z, rem = np.divmod(np.arange(nx * ny * nz), ny * nx)
    Y, X = np.divmod(rem, nx)
    nodes = sdf.origin + sdf.voxel * np.stack([X, Y, Z], axis=1).astype(np.float64)
    del X, Y, Z, rem
    t = time.perf_counter()
    exact = MeshQuery(body.verts, body.faces).distance(nodes).reshape(sdf.shape)
    t_igl = time.perf_counter() - t
    diff = np.abs(np.abs(sdf.values) - exact)
    print()
    print("| unsigned distance at every node | time [s] | max abs difference from the grid, < 5 cm [mm] |")
    print("|---|---|---|")
    print(f"| unsew grid build (band + propagation + sign) | {t_build:.1f} | |")
    print(f"| libigl AABB, exact, unsigned only | {t_igl:.1f} | {diff[exact < 0.05].max() * 1e3:.2f} |")


def _parse(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--voxel", type=float, default=0.005)
    ap.add_argument("--points", type=int, default=8192)
    ap.add_argument("--accuracy-points", type=int, default=1000)
    ap.add_argument(
        "--case", default=None, help="a fitting case folder: its body instead of the default body"
    )
    ap.add_argument(
        "--compare-igl",
        action="store_true",
        help="also time libigl's exact unsigned distance (AABB tree) at every grid node",
    )
    return ap.parse_args(argv)


def main(argv=None) -> None:
    args = _parse(argv)

    import numpy as np
    import torch
    import trimesh

    torch.set_num_threads(args.threads)
    from unsew.body.body import default_body
    from unsew.body.sdf import BodySDF, mesh_distance

    if args.case:
        from unsew.body.case import load_case

        body, name = load_case(args.case).body, os.path.basename(os.path.normpath(args.case)) + "'s body"
    else:
        body, name = default_body(), "default body"
    rss0 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # [MB] (Linux: KiB)
    t = time.perf_counter()
    sdf = BodySDF.build(body, voxel=args.voxel, use_cache=False, floor=False)  # the mesh part alone
    t_build = time.perf_counter() - t
    rss1 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    nz, ny, nx = sdf.shape

    m = body.to_trimesh()
    rng = np.random.default_rng(0)
    pts, fi = trimesh.sample.sample_surface(m, args.accuracy_points, seed=0)
    x = pts + m.face_normals[fi] * rng.uniform(-0.05, 0.05, size=(len(pts), 1))
    d_ex, _ = mesh_distance(x, body.verts, body.faces)
    d, _ = sdf.query(torch.tensor(x))
    err = np.abs(d.numpy()) - d_ex  # magnitude error; the sign is tested in tests/body
    near = d_ex < 0.05

    rows = _time_queries(sdf, pts, rng, args.points)

    print(f"{name}: {len(body.verts)} verts, {len(body.faces)} faces; torch threads {args.threads}")
    print(
        "| grid | voxel [mm] | nodes | build [s] | peak before / after the build [MB] | RMS err <5cm [mm] | "
        "max err <5cm [mm] |"
    )
    print("|---|---|---|---|---|---|---|")
    print(
        f"| {nx}x{ny}x{nz} | {args.voxel * 1e3:.1f} | {nx * ny * nz / 1e6:.1f}M | {t_build:.1f} | {rss0:.0f} "
        f"/ {rss1:.0f} | {np.sqrt(np.mean(err[near] ** 2)) * 1e3:.2f} | {np.abs(err[near]).max() * 1e3:.2f} |"
    )
    print()
    print(f"| query {args.points} points | forward [ms] | forward + gradient [ms] |")
    print("|---|---|---|")
    for name, f, fb in rows:
        print(f"| {name} | {f:.2f} | {fb:.2f} |")
    if args.compare_igl:
        _compare_igl(body, sdf, t_build)


if __name__ == "__main__":
    main()
