"""Timings of the losses and metrics at 2K, 10K and 50K points. Prints tables; asserts nothing.

    OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/bench_losses.py [--repeat 3] [--threads 2]

Each figure is the minimum over ``--repeat`` runs [ms] (the machine is shared: minima are the
least noisy). Chamfer rows are forward + backward between two random point sets of N points.
Curvature and contour rows use meshes of about N vertices (icospheres of 2562, 10242, 40962
vertices; open cylinders of N vertices). Surface-metric rows sample N points on each of two
icospheres and project them exactly onto the other surface.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import numpy as np  # noqa: E402
import torch  # noqa: E402


def _best(fn, repeat):
    ts = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t0)
    return 1e3 * min(ts)


def _cylinder(n):
    nu = int(np.sqrt(n * 4))
    nv = max(2, n // nu)
    th = np.linspace(0, 2 * np.pi, nu, endpoint=False)
    T, Y = np.meshgrid(th, np.linspace(0, 1, nv))
    V = np.stack([np.cos(T), Y, np.sin(T)], -1).reshape(-1, 3)
    j, i = np.meshgrid(np.arange(nv - 1), np.arange(nu), indexing="ij")
    a = (j * nu + i).ravel()
    b = (j * nu + (i + 1) % nu).ravel()
    F = np.concatenate([np.stack([a, a + nu, b], 1), np.stack([b, a + nu, b + nu], 1)])
    return V, F


def _point_rows(n: int, g, put, repeat: int) -> None:
    """Nearest-neighbour and Chamfer timings [ms] on n random points each side."""
    from unsew.losses.chamfer import loss_chamfer
    from unsew.losses.nn import nearest_indices

    x = torch.rand(n, 3, generator=g, dtype=torch.float64, requires_grad=True)
    t = torch.rand(n, 3, generator=g, dtype=torch.float64)
    w = torch.rand(n, generator=g, dtype=torch.float64) + 0.5

    def nn_both_ways(**kw):
        return nearest_indices(x, t, **kw), nearest_indices(t, x, **kw)

    put("nn indices, KD-tree (both ways)", f"{_best(lambda: nn_both_ways(method='kdtree'), repeat):.1f}")
    if n <= 10000:
        put(
            "nn indices, chunked cdist mm (both ways)",
            f"{_best(lambda: nn_both_ways(method='cdist'), repeat):.1f}",
        )
        exact = dict(method="cdist", compute_mode="donot_use_mm_for_euclid_dist")
        put(
            "nn indices, chunked cdist exact (both ways)",
            f"{_best(lambda: nn_both_ways(**exact), repeat):.1f}",
        )
    else:
        put("nn indices, chunked cdist mm (both ways)", "-")
        put("nn indices, chunked cdist exact (both ways)", "-")

    def fb(**kw):
        x.grad = None
        loss_chamfer(x, t, **kw).backward()

    put("Chamfer fwd+bwd (KD-tree)", f"{_best(lambda: fb(), repeat):.1f}")
    put("Chamfer fwd+bwd curvature-weighted (KD-tree)", f"{_best(lambda: fb(weights_t=w), repeat):.1f}")
    if n <= 10000:
        put("Chamfer fwd+bwd (cdist mm)", f"{_best(lambda: fb(method='cdist'), repeat):.1f}")
    else:
        put("Chamfer fwd+bwd (cdist mm)", "-")


def _mesh_rows(n: int, put, repeat: int) -> None:
    """Curvature weights, open contours and their loss, and surface metrics timings [ms] at size n."""
    import trimesh

    from unsew.losses.contours import loss_open_contours, open_contours
    from unsew.losses.curvature import curvature_weights
    from unsew.metrics.surface import surface_metrics

    sub = {2000: 4, 10000: 5, 50000: 6}
    m = trimesh.creation.icosphere(subdivisions=sub.get(n, 5), radius=0.3)
    put(
        "curvature_weights (icosphere, verts)",
        f"{_best(lambda: curvature_weights(m.vertices, m.faces), repeat):.1f} ({len(m.vertices)})",
    )
    V, F = _cylinder(n)
    put("open_contours (open cylinder)", f"{_best(lambda: open_contours(V, F), repeat):.1f}")
    cs = open_contours(V, F)
    xt = torch.tensor(V, requires_grad=True)
    tt = torch.tensor(V) + 0.01

    def oc():
        xt.grad = None
        loss_open_contours(xt, cs, tt, cs).backward()

    put("loss_open_contours fwd+bwd", f"{_best(oc, repeat):.1f}")
    a = trimesh.creation.icosphere(subdivisions=4, radius=0.3)
    b = trimesh.creation.icosphere(subdivisions=3, radius=0.31)
    reps = 1 if n > 10000 else repeat

    def sm():
        return surface_metrics(a.vertices, a.faces, b.vertices, b.faces, n_samples=n)

    put("surface_metrics (N samples per mesh)", f"{_best(sm, reps):.1f}")


def _print_defaults_and_turning(repeat: int) -> None:
    """surface_metrics at its default sample count, and turning_distance on random stars [ms]."""
    import trimesh

    from unsew.metrics.surface import surface_metrics
    from unsew.metrics.turning import turning_distance

    a = trimesh.creation.icosphere(subdivisions=5, radius=0.3)
    b = trimesh.creation.icosphere(subdivisions=4, radius=0.31)
    ms = _best(lambda: surface_metrics(a.vertices, a.faces, b.vertices, b.faces), 2)
    print(f"surface_metrics, default 100000 samples per mesh (icospheres 20480 / 5120 faces): {ms:.0f} ms")
    print()
    print("turning_distance between two random star polygons [ms]")
    rng = np.random.default_rng(0)
    for k in (16, 64, 256):

        def star():
            th = np.sort(rng.uniform(0, 2 * np.pi, k))
            r = rng.uniform(0.5, 1.5, k)
            return np.c_[r * np.cos(th), r * np.sin(th)]

        p, q = star(), star()
        print(f"  {k:>4} x {k:<4} vertices: {_best(lambda: turning_distance(p, q), repeat):10.1f}")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--sizes", default="2000,10000,50000")
    args = ap.parse_args(argv)
    torch.set_num_threads(args.threads)

    sizes = [int(s) for s in args.sizes.split(",")]
    rows: dict[str, list[str]] = {}

    def put(name, val):
        rows.setdefault(name, []).append(val)

    g = torch.Generator().manual_seed(0)
    for n in sizes:
        _point_rows(n, g, put, args.repeat)
        _mesh_rows(n, put, args.repeat)

    w0 = 52
    print(f"torch {torch.__version__}, {torch.get_num_threads()} threads, min of {args.repeat} runs [ms]")
    print(f"{'operation':<{w0}}" + "".join(f"{f'N={n}':>16}" for n in sizes))
    for name, vals in rows.items():
        print(f"{name:<{w0}}" + "".join(f"{v:>16}" for v in vals))
    _print_defaults_and_turning(args.repeat)


if __name__ == "__main__":
    main()
