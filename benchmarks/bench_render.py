"""Time unsew.report.render at several mesh sizes; prints a table (no assertions).

Usage: OMP_WAIT_POLICY=PASSIVE python benchmarks/bench_render.py [--sizes 5000 20000 60000]
       [--repeat 2] [--out DIR]

Each garment is a wavy open tube (a skirt-like surface of revolution with folds) of about the
given number of faces; "with body" adds a closed body-like ellipsoid of the same face count
inside it. Times are wall-clock seconds of one ``render_mesh`` call (front view, 600 x 800 px,
PNG written), best of ``--repeat``.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np


def wavy_tube(n_faces: int) -> tuple[np.ndarray, np.ndarray]:
    """Open tube around Y with folds: verts (V, 3) [m], faces (~n_faces, 3)."""
    nv = max(int(np.sqrt(n_faces / 2 / 2.5)), 4)  # rows
    nu = max(int(n_faces / 2 / (nv - 1)), 8)  # columns around
    th = np.linspace(0, 2 * np.pi, nu, endpoint=False)
    y = np.linspace(0.55, 1.45, nv)
    T, Y = np.meshgrid(th, y)
    R = 0.17 + 0.12 * (1.45 - Y) + 0.015 * (1.45 - Y) * np.sin(11 * T + 3 * Y)
    v = np.stack([R * np.sin(T), Y, 0.8 * R * np.cos(T)], -1).reshape(-1, 3)
    i = np.arange(nu)
    j = np.arange(nv - 1)[:, None]
    a = j * nu + i
    b = j * nu + (i + 1) % nu
    f = np.concatenate([np.stack([a, b, b + nu], -1).reshape(-1, 3),
                        np.stack([a, b + nu, a + nu], -1).reshape(-1, 3)])
    return v, f


def ellipsoid(n_faces: int) -> tuple[np.ndarray, np.ndarray]:
    """Closed UV ellipsoid standing in for a body: verts (V, 3) [m], faces (~n_faces, 3)."""
    nv = max(int(np.sqrt(n_faces / 4)), 4)
    nu = 2 * nv
    th = np.linspace(0, 2 * np.pi, nu, endpoint=False)
    ph = np.linspace(0.05, np.pi - 0.05, nv)
    T, P = np.meshgrid(th, ph)
    v = np.stack([0.16 * np.sin(P) * np.sin(T), 1.0 - 0.75 * np.cos(P),
                  0.11 * np.sin(P) * np.cos(T)], -1).reshape(-1, 3)
    i = np.arange(nu)
    j = np.arange(nv - 1)[:, None]
    a = j * nu + i
    b = j * nu + (i + 1) % nu
    f = np.concatenate([np.stack([a, b + nu, b], -1).reshape(-1, 3),
                        np.stack([a, a + nu, b + nu], -1).reshape(-1, 3)])
    return v, f


def _best(fn, repeat: int) -> float:
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return best


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[5000, 20000, 60000])
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--out", type=Path, default=None, help="keep the PNGs here")
    args = ap.parse_args()

    from unsew.report.render import render_mesh  # noqa: E402 (imports matplotlib)

    out = args.out or Path(tempfile.mkdtemp(prefix="bench_render_"))
    out.mkdir(parents=True, exist_ok=True)
    # warm up matplotlib (font cache, Agg) so the first row is not charged for it
    v, f = wavy_tube(500)
    render_mesh(out / "warmup.png", v, f, size_px=(200, 200))

    print(f"{'faces':>8} {'garment only [s]':>17} {'+ heat map [s]':>15} {'+ body [s]':>11} "
          f"{'faces with body':>16}")
    for n in args.sizes:
        gv, gf = wavy_tube(n)
        bv, bf = ellipsoid(n)
        d = np.abs(gv[:, 0]) * 1000.0
        t0 = _best(lambda: render_mesh(out / f"g{n}.png", gv, gf), args.repeat)
        t1 = _best(lambda: render_mesh(out / f"h{n}.png", gv, gf, vertex_values=d,
                                       colorbar_label="distance [mm]"), args.repeat)
        t2 = _best(lambda: render_mesh(out / f"b{n}.png", gv, gf, body=(bv, bf)), args.repeat)
        print(f"{len(gf):>8} {t0:>17.2f} {t1:>15.2f} {t2:>11.2f} {len(gf) + len(bf):>16}")
    print(f"PNGs in {out}")


if __name__ == "__main__":
    main()
