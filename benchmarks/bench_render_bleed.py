"""How much of the body shows through close-fitting cloth in the report's renders, per fix?

The body is the default body without its arms (which would hide cloth legitimately in the side
view); the cloth is its torso pushed out along the vertex normals by a
gap, as a drape lies on the body: a mean gap (2, 5, 10 mm) with +-3 mm of random variation per
vertex (a simulated drape touches and grazes the body within its contact thickness). Seen in
the report, such cloth should cover the body: every body-grey pixel inside the cloth's
silhouette (eroded by 2 px against antialiasing) is the body showing through. The
renders are the report's (painter's algorithm, front and side views, 600 x 800 px); the fixes
compared are none, a depth bias of the body in the sort (``render.BODY_DEPTH_BIAS``) and moving
the body's vertices inwards along their normals before drawing (changes its silhouette).

Usage: python -m benchmarks render_bleed [--gaps 0.002 0.005 0.01] [--out DIR]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np

from tables import print_table


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


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--gaps", type=float, nargs="+", default=[0.002, 0.005, 0.01], help="cloth-body gaps [m]")
    ap.add_argument("--out", type=Path, default=None, help="keep the PNGs here")
    args = ap.parse_args()

    import unsew.report.render as render
    from unsew.body.body import default_body

    out = args.out or Path(tempfile.mkdtemp(prefix="bench_bleed_"))
    out.mkdir(parents=True, exist_ok=True)
    body = default_body()
    bv, bf = np.asarray(body.verts, dtype=np.float64), np.asarray(body.faces)
    c = bv[bf].mean(axis=1)
    bf = bf[(np.abs(c[:, 0]) < 0.2) | (c[:, 1] < 0.9)]  # no arms (legs, torso and head kept)
    bn = _normals(bv, bf)
    fixes = [("none", 0.0, 0.0)] + [(f"depth bias {b * 1000:g} mm", b, 0.0) for b in (0.005, 0.01, 0.02, 0.04)] \
        + [(f"body inset {s * 1000:g} mm", 0.0, s) for s in (0.005, 0.01)]
    rows = []
    default_bias = render.BODY_DEPTH_BIAS
    try:
        for gap in args.gaps:
            cv, cf = _cloth(bv, bf, gap)
            masks = {}
            for view in ("front", "side"):
                masks[view] = render.render_mesh(out / f"cloth_{gap}_{view}.png", cv, cf, view=view, frame="all")
            for name, bias, inset in fixes:
                render.BODY_DEPTH_BIAS = bias
                row = {"gap [mm]": gap * 1000, "fix": name}
                for view in ("front", "side"):
                    p = render.render_mesh(out / f"{gap}_{name.replace(' ', '_')}_{view}.png", cv, cf, view=view,
                                           body=(bv - inset * bn, bf), frame="all")
                    row[f"{view}: body px in cloth [%]"] = _bleed(p, masks[view])
                rows.append(row)
    finally:
        render.BODY_DEPTH_BIAS = default_bias
    print_table(rows, title="Body pixels inside the cloth's silhouette (0 = no show-through)", digits=2)
    print(f"PNGs in {out}")


if __name__ == "__main__":
    main()
