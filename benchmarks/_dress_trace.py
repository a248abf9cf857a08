"""Where does a true pattern's drape go wrong: its largest stretch and edges through the body per step?

Dresses one case of the GarmentCode design benchmark (``CASES/<case>/pattern_gt.json`` on its
``body.obj``, with ``skeleton.json`` when there is one) as :func:`unsew.dress.dress` does once
(placement, the sewing phase, settling; without its retry and its extra settling) with
``DRESS_SETTINGS``, and prints a row after the placement and after each step: the phase, the
step, the largest edge length over its pattern length, the share of vertices inside the body,
the largest speed [m/s], and the edges passing through the body (:func:`through_edges`: the
segment between the edge's ends goes more than THROUGH_DEPTH inside it, so the cloth is
stretched across a limb or the torso rather than lying on it).

    python -m benchmarks true_patterns --trace --cases CASES --only gc_s5_004 gc_s3_006
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

import numpy as np
import torch

#: An edge passes through the body when a point of it lies this far inside [m].
THROUGH_DEPTH = 0.005
#: Points sampled along each edge (ends excluded) [-].
EDGE_SAMPLES = 5


def edge_stretch(x, faces, faces_uv, uv) -> np.ndarray:
    """Length over pattern length [-] of every triangle edge, (3F,) float64; x (n, 3) [m] on
    the vertices ``faces`` (F, 3) index, uv (Nu, 2) [m] the pattern's, faces_uv (F, 3) into it."""
    e = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    eu = faces_uv[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    L = np.linalg.norm(x[e[:, 0]] - x[e[:, 1]], axis=1)
    return L / np.linalg.norm(uv[eu[:, 0]] - uv[eu[:, 1]], axis=1)


def through_edges(x, edges, sdf, *, depth: float = THROUGH_DEPTH) -> np.ndarray:
    """Which edges (E, 2) int of positions x (n, 3) [m] pass more than ``depth`` [m] inside the
    body (``sdf.query``) somewhere between their ends: (E,) bool."""
    xt = torch.as_tensor(np.asarray(x), dtype=torch.float64)
    ts = torch.linspace(0.0, 1.0, EDGE_SAMPLES + 2, dtype=torch.float64)[1:-1]  # (S,)
    ee = torch.as_tensor(np.asarray(edges), dtype=torch.int64)
    pts = xt[ee[:, 0], None] * (1 - ts[None, :, None]) + xt[ee[:, 1], None] * ts[None, :, None]
    with torch.no_grad():
        d = sdf.query(pts.reshape(-1, 3))[0].reshape(len(ee), -1)  # (E, S)
    return (d.min(dim=1).values < -depth).numpy()


def _row(phase, k, x, faces, mesh, sdf, speed) -> dict:
    """One printed row: the state x (n, 3) [m] on ``faces`` after step k of ``phase``."""
    xn = np.asarray(x.detach() if torch.is_tensor(x) else x, np.float64)
    r = edge_stretch(xn, faces, mesh.faces_uv, np.asarray(mesh.uv))
    e = np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    e, first = np.unique(e, axis=0, return_index=True)
    thr = through_edges(xn, e, sdf)
    with torch.no_grad():
        d = sdf.query(torch.as_tensor(xn))[0]
    return dict(
        phase=phase,
        step=k,
        stretch=float(r.max()),
        inside_pct=float((d < 0).double().mean()) * 100.0,
        speed=speed,
        through=int(thr.sum()),
        through_over_2=int((thr & (r[first] > 2.0)).sum()),
        over_2=int((r[first] > 2.0).sum()),
    )


def trace(case_dir: Path) -> list[dict]:
    """Rows of one case's drape (module docstring)."""
    from unsew.body.body import load_body
    from unsew.body.placement import place_garment
    from unsew.body.sdf import BodySDF
    from unsew.dress import DRESS_SETTINGS, hold_vertices, resolve_material
    from unsew.io.garmentcode import load_pattern
    from unsew.meshing import mesh_pattern
    from unsew.sim.drape import Cloth, drape, merge_sewn, sew
    from unsew.sim.model import SimModel
    from unsew.sim.state import SimState

    skel = case_dir / "skeleton.json"
    body = load_body(case_dir / "body.obj", skel if skel.is_file() else None)
    sdf = BodySDF.build(body)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        pattern = load_pattern(case_dir / "pattern_gt.json")
    s = DRESS_SETTINGS
    mesh = mesh_pattern(pattern, edge_length=s.edge_length)
    mat = resolve_material("cotton")
    uv = torch.as_tensor(np.asarray(mesh.uv), dtype=torch.float64)
    cloth = Cloth(uv, mat.gamma(), mat.density, friction=mat.friction)
    x0 = place_garment(pattern, mesh, body, sdf=sdf)
    rows = [_row("place", 0, x0, mesh.faces_uv, mesh, sdf, 0.0)]

    def on(phase, faces):
        return lambda k, st: rows.append(
            _row(phase, k + 1, st.x, faces, mesh, sdf, float(st.v.norm(dim=1).max()))
        )

    hold = hold_vertices(pattern, mesh, body, x0)
    unsewn = SimModel.build(mesh.faces_uv, mesh.faces_uv, springs=mesh.seam_pairs)
    xs = sew(
        unsewn,
        x0,
        sdf,
        cloth,
        settings=s,
        hold=hold if len(hold) else None,
        callback=on("sew", mesh.faces_uv),
    )
    x = merge_sewn(xs, mesh.x_of_u, mesh.n_x)
    model = SimModel.build(mesh.faces, mesh.faces_uv)
    with torch.no_grad():
        drape(
            model,
            SimState.at_rest(x),
            sdf,
            cloth,
            settings=s,
            steps=s.settle_steps,
            callback=on("settle", mesh.faces),
        )
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        prog="python -m benchmarks true_patterns --trace", description=__doc__.splitlines()[0]
    )
    ap.add_argument("--cases", type=Path, required=True, help="folder of case folders")
    ap.add_argument("--only", nargs="+", required=True, help="case names")
    ap.add_argument("--every", type=int, default=5, help="print every N-th step (and the first two)")
    args = ap.parse_args(argv)
    for cid in args.only:
        head = "| phase | step | stretch max | inside % | speed m/s | through | through, over 2x | over 2x |"
        print(f"\n{cid}\n\n{head}")
        print("|---|---|---|---|---|---|---|---|")
        for r in trace(args.cases / cid):
            if r["step"] <= 2 or r["step"] % args.every == 0:
                print(
                    f"| {r['phase']} | {r['step']} | {r['stretch']:.2f} | {r['inside_pct']:.2f} | "
                    f"{r['speed']:.2f} | {r['through']} | {r['through_over_2']} | {r['over_2']} |",
                    flush=True,
                )
    return 0
