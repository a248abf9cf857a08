"""How long does newton's Style3D cloth take to settle? A cantilever in the targets' fabric.

A strip of the foreign benchmark's newton fabric (newton_drape.SETTINGS: density, membrane and
Style3D bending ke) lies flat on a platform (every vertex within ``PLATFORM`` of one end pinned)
and overhangs it by ``overhang``; gravity acts from the first frame, with newton_drape's frame
rate, substeps and iterations. After each number of frames the strip's tip drop is read as the
bending length c that the exact heavy elastica (bench_fabric_tests.elastica) gives that drop at
that overhang, and as the rigidity D_read = w g c^3 it stands for, beside the D_eq that
newton's bending gives a uniform bend (bench_fabric_tests.style3d_bending_rows). A settled strip
reads D_eq; a strip still sagging reads a stiffer fabric. The benchmark's newton drapes run
150-220 frames.

Run: python -m benchmarks fabric_tests --newton-cantilever [--frames 150 300 900 2400]
     [--overhang 0.15] [--edge 0.01] [--iterations 40] [--small]
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
PLATFORM = 0.01  #: length of the strip held flat [m]
WIDTH = 0.05  #: strip width [m]


def strip_mesh(length: float, width: float, edge: float):
    """A length x width [m] strip meshed by unsew's panel mesher: uv (V, 2) [m], faces (F, 3)."""
    from unsew.meshing.triangulate import triangulate_polygon

    corners = np.array([[0.0, 0.0], [length, 0.0], [length, width], [0.0, width], [0.0, 0.0]])
    parts = []
    for a, b in zip(corners[:-1], corners[1:]):
        n = max(1, round(float(np.linalg.norm(b - a)) / edge))
        parts.append(a + np.linspace(0.0, 1.0, n + 1)[:-1, None] * (b - a))
    uv, f = triangulate_polygon(np.concatenate(parts), edge_length=edge)
    return np.asarray(uv, np.float64), np.asarray(f, np.int64)


def bending_length(overhang: float, drop: float) -> float:
    """The bending length c [m] whose heavy elastica of ``overhang`` [m] drops its tip by
    ``drop`` [m] (bisection in log c; the drop falls as c grows)."""
    from bench_fabric_tests import elastica

    lo, hi = 1e-3 * overhang, 1e3 * overhang
    for _ in range(50):
        c = math.sqrt(lo * hi)
        if elastica(overhang / c)[1][-1] * c > drop:
            lo = c
        else:
            hi = c
    return math.sqrt(lo * hi)


def run(frames_list, overhang: float, edge: float, iterations: int | None = None) -> list[dict]:
    """One row per frame count (ints, each run from rest): newton's strip of ``overhang`` [m] on
    a mesh of ``edge`` [m] after that many frames, its tip drop [cm] read as a bending length [cm]
    and a rigidity [uN m] beside D_eq [uN m]; ``iterations``: the solver's iterations per substep
    (default newton_drape.SETTINGS', 10)."""
    import warp as wp

    sys.path.insert(0, str(HERE / "foreign"))
    import newton_drape as nd
    from bench_fabric_tests import style3d_bending_rows

    wp.config.quiet = True
    uv, f = strip_mesh(PLATFORM + overhang, WIDTH, edge)
    x = np.c_[uv[:, 0], np.ones(len(uv)), uv[:, 1]]  # Y up, the strip flat at 1 m
    s = {**nd.SETTINGS, "ground": False}
    if iterations is not None:
        s["iterations"] = iterations
    far = np.array([[5.0, -5, 5], [5.1, -5, 5], [5, -4.9, 5], [5, -5, 5.1]])  # a body out of reach
    tet = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    d_eq = float(np.mean([v for k, v in style3d_bending_rows(edges=(edge,))[1].items() if "axis" in k]))
    w = s["density_kg_m2"]
    rows = []
    for frames in sorted(frames_list):  # each from the flat strip at rest
        model = nd._model(nd._to_z(x), f, uv, f, nd._to_z(far), tet, s)
        nd._set_active(model, np.flatnonzero(uv[:, 0] <= PLATFORM + 1e-9), False)
        runner = nd._Runner(s, np.array([0.0, 0.0, 1.0]))
        xs = runner.run(model, x, frames, lambda _f: (1.0, False), np.zeros(0, np.int64))
        tip = uv[:, 0] > PLATFORM + overhang - 1e-9
        drop = float(1.0 - xs[tip, 1].mean())
        c = bending_length(overhang, drop)
        d_read = w * 9.81 * c**3 * 1e6
        rows.append(
            {
                "frames": frames,
                "iterations": s["iterations"],
                "simulated s": round(frames / s["fps"], 2),
                "tip drop cm": round(100 * drop, 2),
                "bending length read cm": round(100 * c, 2),
                "D read uN m": round(d_read, 1),
                "D_eq uN m": round(d_eq, 1),
                "read / D_eq": round(d_read / d_eq, 2),
            }
        )
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        prog="python -m benchmarks fabric_tests --newton-cantilever", description=__doc__.splitlines()[0]
    )
    ap.add_argument("--frames", nargs="+", type=int, default=[150, 300, 900, 2400])
    ap.add_argument("--overhang", type=float, default=0.15, help="overhang [m] (default 0.15)")
    ap.add_argument("--edge", type=float, default=0.01, help="mesh edge [m] (default 0.01)")
    ap.add_argument(
        "--iterations",
        type=int,
        default=None,
        help="solver iterations per substep (default: the targets', 10)",
    )
    ap.add_argument("--small", action="store_true", help="a coarse strip, two short runs (seconds)")
    args = ap.parse_args(argv)
    if args.small:
        args.frames, args.overhang, args.edge = [5, 10], 0.06, 0.02
    if min(args.frames) < 1:
        print("newton_cantilever: --frames must be positive", file=sys.stderr)
        return 2
    if args.iterations is not None and args.iterations < 1:
        print("newton_cantilever: --iterations must be positive", file=sys.stderr)
        return 2
    if not 0 < args.edge < args.overhang:
        print("newton_cantilever: --edge must be positive and shorter than --overhang", file=sys.stderr)
        return 2
    from tables import markdown_table

    rows = run(args.frames, args.overhang, args.edge, args.iterations)
    print(f"\nnewton Style3D cantilever, the targets' fabric, {args.overhang * 100:.0f} cm overhang\n")
    print(markdown_table(rows, digits=2))
    return 0
