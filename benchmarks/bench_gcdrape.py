"""Does `unsew drape` put any GarmentCode pattern on any body (and say so when it cannot)?

Drapes, as ``unsew drape`` does (:func:`unsew.dress.dress` then
:func:`unsew.sim.checks.check_dressed`), GarmentCode's four sample specifications
(``shared/foreign/patterns/`` beside the repository: shirt, pencil dress, hoodie, 12-panel jumpsuit; not made by
unsew) and unsew's five base patterns (written to GarmentCode JSON and read back, so they go
through the same reader) on three anny bodies:

- ``default``: the embedded default body (A-pose);
- ``tpose``: the same phenotype in T-pose (``benchmarks/data/body_tpose.npz``, made with anny
  by ``--make-tpose`` when missing);
- ``pose_step``: the left arm raised 0.3 rad and the right leg stepped 0.2 rad forward
  (``benchmarks/data/body_pose_step.npz``, see make_bodies.py).

Prints one row per (pattern, body): the verdict (``ok`` or the reason the drape was refused),
the share of vertices inside the body [%], the garment's height range [m], the largest and
99th-percentile edge stretch (3D length over pattern length), vertices off the body [%], sewn
vertices, and the wall time of placing + sewing + settling [s]. With ``--png-dir`` it renders
each drape (front and side, garment over body) for a look.

Run: OMP_WAIT_POLICY=PASSIVE PYTHONPATH=src .venv/bin/python -m benchmarks gcdrape
     [--patterns shirt_mean base_skirt ...] [--bodies default tpose pose_step] [--png-dir DIR]
     [--edge-length 0.025]
"""

from __future__ import annotations

import argparse
import os
import time
import warnings
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

HERE = Path(__file__).resolve().parent


def foreign_patterns() -> Path:
    """The folder of GarmentCode's sample specifications: ``shared/foreign/patterns`` beside the
    repository (``../shared`` from its root, as CI has it) or beside a folder above it."""
    for up in HERE.parents:
        d = up / "shared" / "foreign" / "patterns"
        if d.is_dir():
            return d
    raise SystemExit("no shared/foreign/patterns found beside the repository (../shared from its root)")



SAMPLES = ["shirt_mean", "dress_pencil", "hoody_mean", "js_mean_all"]
BASES = ["tshirt", "dress", "pants", "shorts", "skirt"]
BODIES = ["default", "tpose", "pose_step"]


def load_body(name: str, *, make_tpose: bool = False):
    """A benchmark body by name (see the module docstring)."""
    from unsew.body.body import body_from_npz, default_body

    if name == "default":
        return default_body()
    path = HERE / "data" / f"body_{name}.npz"
    if name == "tpose" and not path.is_file():
        if not make_tpose:
            raise SystemExit(f"{path} is missing: rerun with --make-tpose (needs anny)")
        from unsew.body.anny_body import make_anny_body, save_body_npz

        save_body_npz(make_anny_body({}, pose="T"), path, meta={"pose": "T"})
    return body_from_npz(path)


def load_patterns(names, tmp: Path) -> dict:
    """name -> Pattern, the samples read from ``FOREIGN`` and the base patterns written to
    GarmentCode JSON in ``tmp`` and read back."""
    from unsew.io.garmentcode import load_pattern, save_pattern
    from unsew.pattern.base import make_base_pattern

    out = {}
    for n in names:
        if n.startswith("base_"):
            path = tmp / f"{n}.json"
            save_pattern(make_base_pattern(n[5:]), path)
        else:
            path = foreign_patterns() / f"{n}_specification.json"
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # clockwise panels mirrored, seam length warnings
            out[n] = load_pattern(path)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--patterns", nargs="*", default=SAMPLES + [f"base_{g}" for g in BASES])
    ap.add_argument("--bodies", nargs="*", default=BODIES)
    ap.add_argument("--edge-length", type=float, default=0.025)
    ap.add_argument("--png-dir", default=None, help="render each drape (front, side) here")
    ap.add_argument("--make-tpose", action="store_true", help="build benchmarks/data/body_tpose.npz with anny")
    args = ap.parse_args()

    import tempfile

    import numpy as np
    import torch

    torch.set_num_threads(1)
    from _drapes import verdict_cells
    from tables import print_table

    from unsew.body.sdf import BodySDF
    from unsew.dress import DRESS_SETTINGS, dress
    from unsew.errors import UnsewError
    from unsew.sim.checks import check_dressed

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        patterns = load_patterns(args.patterns, Path(tmp))
    for bname in args.bodies:
        body = load_body(bname, make_tpose=args.make_tpose)
        sdf = BodySDF.build(body)
        for pname, pat in patterns.items():
            if bname == "default" and pname.startswith("base_"):
                continue  # the base patterns on the default body: benchmarks/bench_dress.py
            t0 = time.perf_counter()
            row = dict(pattern=pname, body=bname)
            try:
                d = dress(pat.copy(), body, sdf=sdf, settings=DRESS_SETTINGS.replace(edge_length=args.edge_length))
            except UnsewError as exc:
                row.update(verdict=f"error: {exc}", time_s=time.perf_counter() - t0)
                rows.append(row)
                print(row, flush=True)
                continue
            v = check_dressed(d, body=body)
            row.update(verdict_cells(v, d), time_s=time.perf_counter() - t0)
            rows.append(row)
            print({k: (round(x, 3) if isinstance(x, float) else x) for k, x in row.items()}, flush=True)
            if args.png_dir:
                from unsew.report.render import render_views

                os.makedirs(args.png_dir, exist_ok=True)
                render_views(
                    Path(args.png_dir) / f"{pname}_{bname}.png", d.x.numpy(), d.mesh.faces,
                    body=(np.asarray(body.verts), np.asarray(body.faces)), frame="all",
                    views=("front", "side"), title=f"{pname} on {bname}: {row['verdict']}",
                )
    cols = ["pattern", "body", "verdict", "inside_pct", "y_range", "stretch_max", "stretch_p99", "off_body_pct",
            "verts", "time_s"]
    print_table(rows, cols, title=f"unsew drape of GarmentCode patterns, {args.edge_length * 100:g} cm edges")
    n_ok = sum(r["verdict"] == "ok" for r in rows)
    print(f"\n{n_ok} of {len(rows)} drapes pass the checks")


if __name__ == "__main__":
    main()
