"""How fast are the report's renders, and how much body shows through close cloth in them?

Usage: python -m benchmarks render [--sizes 5000 20000 60000] [--repeat 2] [--out DIR]
       python -m benchmarks render --bleed [--gaps 0.002 0.005 0.01] [--out DIR]

Each garment is a wavy open tube (a skirt-like surface of revolution with folds) of about the
given number of faces; "with body" adds a closed body-like ellipsoid of the same face count
inside it. Times are wall-clock seconds of one ``render_mesh`` call (front view, 600 x 800 px,
PNG written), best of ``--repeat``.

``--bleed``: the body is the default body without its arms; the cloth is its torso pushed out
along the vertex normals by a mean gap (2, 5, 10 mm) with +-3 mm of random variation per vertex,
as a drape lies within its contact thickness. Every body-grey pixel inside the cloth's
silhouette (eroded by 2 px against antialiasing) is the body showing through. The fixes compared
are none, a depth bias of the body in the sort (``render.BODY_DEPTH_BIAS``) and moving the body's
vertices inwards along their normals before drawing.
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
    f = np.concatenate(
        [np.stack([a, b, b + nu], -1).reshape(-1, 3), np.stack([a, b + nu, a + nu], -1).reshape(-1, 3)]
    )
    return v, f


def ellipsoid(n_faces: int) -> tuple[np.ndarray, np.ndarray]:
    """Closed UV ellipsoid standing in for a body: verts (V, 3) [m], faces (~n_faces, 3)."""
    nv = max(int(np.sqrt(n_faces / 4)), 4)
    nu = 2 * nv
    th = np.linspace(0, 2 * np.pi, nu, endpoint=False)
    ph = np.linspace(0.05, np.pi - 0.05, nv)
    T, P = np.meshgrid(th, ph)
    v = np.stack(
        [0.16 * np.sin(P) * np.sin(T), 1.0 - 0.75 * np.cos(P), 0.11 * np.sin(P) * np.cos(T)], -1
    ).reshape(-1, 3)
    i = np.arange(nu)
    j = np.arange(nv - 1)[:, None]
    a = j * nu + i
    b = j * nu + (i + 1) % nu
    f = np.concatenate(
        [np.stack([a, b + nu, b], -1).reshape(-1, 3), np.stack([a, a + nu, b + nu], -1).reshape(-1, 3)]
    )
    return v, f


def _normals(v, f):
    import trimesh

    return trimesh.Trimesh(v, f, process=False).vertex_normals


def _cloth(body_v, body_f, gap: float, *, jitter: float = 0.003, seed: int = 0):
    """Torso faces of the body moved out by ``gap`` +- ``jitter`` [m] (uniform per
    vertex), plus two degenerate faces at the body's bounding-box corners so that a render of the
    cloth alone is framed like one with the body: (verts, faces)."""
    n = _normals(body_v, body_f)
    c = body_v[body_f].mean(axis=1)
    keep = (c[:, 1] > 0.85) & (c[:, 1] < 1.40) & (np.abs(c[:, 0]) < 0.2)
    f = body_f[keep]
    used = np.unique(f)
    remap = np.full(len(body_v), -1)
    remap[used] = np.arange(len(used))
    g = gap + np.random.default_rng(seed).uniform(-jitter, jitter, len(used))
    v = body_v[used] + g[:, None] * n[used]
    lo, hi = body_v.min(axis=0), body_v.max(axis=0)
    k = len(v)
    corners = np.array([[k, k, k], [k + 1, k + 1, k + 1]])
    return np.concatenate([v, [lo, hi]]), np.concatenate([remap[f], corners])


def _bleed(path_png, mask_png) -> float:
    """Percent of the cloth's (eroded) silhouette pixels that are body grey."""
    import matplotlib.image as mpimg
    from scipy.ndimage import binary_erosion

    img = mpimg.imread(str(path_png))[..., :3]
    cloth_only = mpimg.imread(str(mask_png))[..., :3]
    mask = binary_erosion((1.0 - cloth_only).max(axis=2) > 0.04, iterations=2)
    grey = (np.ptp(img, axis=2) < 0.06) & (img.mean(axis=2) < 0.97)  # the body is drawn grey, cloth blue
    return 100.0 * float((grey & mask).sum()) / max(int(mask.sum()), 1)


def _best(fn, repeat: int) -> float:
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return best


def bleed(gaps, out_dir: Path | None) -> list[dict]:
    """Body pixels inside the cloth's silhouette [%], per gap [m] and fix, front and side."""
    from tables import print_table

    import unsew.report.render as render
    from unsew.body.body import default_body

    out = out_dir or Path(tempfile.mkdtemp(prefix="bench_bleed_"))
    out.mkdir(parents=True, exist_ok=True)
    body = default_body()
    bv, bf = np.asarray(body.verts, dtype=np.float64), np.asarray(body.faces)
    c = bv[bf].mean(axis=1)
    bf = bf[(np.abs(c[:, 0]) < 0.2) | (c[:, 1] < 0.9)]  # no arms (legs, torso and head kept)
    bn = _normals(bv, bf)
    fixes = (
        [("none", 0.0, 0.0)]
        + [(f"depth bias {b * 1000:g} mm", b, 0.0) for b in (0.005, 0.01, 0.02, 0.04)]
        + [(f"body inset {s * 1000:g} mm", 0.0, s) for s in (0.005, 0.01)]
    )
    rows = []
    default_bias = render.BODY_DEPTH_BIAS
    try:
        for gap in gaps:
            cv, cf = _cloth(bv, bf, gap)
            masks = {}
            for view in ("front", "side"):
                masks[view] = render.render_mesh(
                    out / f"cloth_{gap}_{view}.png", cv, cf, view=view, frame="all"
                )
            for name, bias, inset in fixes:
                render.BODY_DEPTH_BIAS = bias
                row = {"gap [mm]": gap * 1000, "fix": name}
                for view in ("front", "side"):
                    p = render.render_mesh(
                        out / f"{gap}_{name.replace(' ', '_')}_{view}.png",
                        cv,
                        cf,
                        view=view,
                        body=(bv - inset * bn, bf),
                        frame="all",
                    )
                    row[f"{view}: body px in cloth [%]"] = _bleed(p, masks[view])
                rows.append(row)
    finally:
        render.BODY_DEPTH_BIAS = default_bias
    print_table(rows, title="Body pixels inside the cloth's silhouette (0 = no show-through)", digits=2)
    print(f"PNGs in {out}")
    return rows


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[5000, 20000, 60000])
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--out", type=Path, default=None, help="keep the PNGs here")
    ap.add_argument(
        "--bleed", action="store_true", help="measure the body showing through close cloth instead"
    )
    ap.add_argument(
        "--gaps", type=float, nargs="+", default=[0.002, 0.005, 0.01], help="--bleed: cloth-body gaps [m]"
    )
    args = ap.parse_args(argv)
    if args.bleed:
        bleed(args.gaps, args.out)
        return

    from unsew.report.render import render_mesh  # noqa: E402 (imports matplotlib)

    out = args.out or Path(tempfile.mkdtemp(prefix="bench_render_"))
    out.mkdir(parents=True, exist_ok=True)
    # warm up matplotlib (font cache, Agg) so the first row is not charged for it
    v, f = wavy_tube(500)
    render_mesh(out / "warmup.png", v, f, size_px=(200, 200))

    print(
        f"{'faces':>8} {'garment only [s]':>17} {'+ heat map [s]':>15} {'+ body [s]':>11} "
        f"{'faces with body':>16}"
    )
    for n in args.sizes:
        gv, gf = wavy_tube(n)
        bv, bf = ellipsoid(n)
        d = np.abs(gv[:, 0]) * 1000.0
        t0 = _best(lambda: render_mesh(out / f"g{n}.png", gv, gf), args.repeat)
        t1 = _best(
            lambda: render_mesh(out / f"h{n}.png", gv, gf, vertex_values=d, colorbar_label="distance [mm]"),
            args.repeat,
        )
        t2 = _best(lambda: render_mesh(out / f"b{n}.png", gv, gf, body=(bv, bf)), args.repeat)
        print(f"{len(gf):>8} {t0:>17.2f} {t1:>15.2f} {t2:>11.2f} {len(gf) + len(bf):>16}")
    print(f"PNGs in {out}")


if __name__ == "__main__":
    main()
