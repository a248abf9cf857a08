"""Do unsew's base patterns drape on GarmentCode's bodies, rigged from their mesh alone?

Each body of ``shared/foreign/bodies/`` (GarmentCode's mean bodies: A-pose female, male and
all, and the "all" body in T-pose; OBJ in metres, Y up, no skeleton) is read by
``unsew.body.body.load_body`` with no skeleton.json, so its 17 joints come from
``unsew.body.rig``; it is measured (``measure_body``), and each of unsew's five base patterns is
sized to those measurements, written to GarmentCode JSON and read back, then draped as
``unsew drape`` does it (:func:`unsew.dress.dress` with ``DRESS_SETTINGS`` at the given edge
length, cotton) and judged by :func:`unsew.sim.checks.check_dressed`.

Prints one row per (body, garment): the body's load + rig time [s], the verdict (``ok`` or the
reason the drape was refused), the share of vertices inside the body [%], whether the garment
fell (reason starting "fallen"), the garment's height range [m], the largest and
99th-percentile edge stretch (3D length over pattern length), vertices off the body [%], sewn
vertices, and the wall time of sizing + placing + sewing + settling [s]; then whether each drape
meets issue 23's bar (< 0.5 % inside, not fallen, verdict ok). ``--png-dir`` renders each drape
(front and side, garment over body). A ``--garments`` entry ending in ``.json`` is a pattern
draped as it is, not sized to the body, in its own fitted material when it carries one:
retargeting, e.g. a ``pattern.json`` fitted by ``unsew fit`` on another body model.

Run: OMP_WAIT_POLICY=PASSIVE PYTHONPATH=src .venv/bin/python -m benchmarks gcbodies
     [--bodies mean_all mean_all_tpose ...] [--garments tshirt dress ...] [--png-dir DIR]
     [--edge-length 0.025] [--folder ../shared/foreign/bodies]
"""

from __future__ import annotations

import argparse
import os
import time
import warnings
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

HERE = Path(__file__).resolve().parent
GARMENTS = ["tshirt", "dress", "pants", "shorts", "skirt"]
#: issue 23's bar for a drape on these bodies: share of vertices inside the body [%]
INSIDE_BAR_PCT = 0.5


def foreign_bodies() -> Path:
    """``shared/foreign/bodies`` beside the repository (``../shared`` from its root, as CI has it)
    or beside a folder above it, or under ``$UNSEW_SHARED``."""
    if os.environ.get("UNSEW_SHARED"):
        return Path(os.environ["UNSEW_SHARED"]) / "foreign" / "bodies"
    for up in HERE.parents:
        d = up / "shared" / "foreign" / "bodies"
        if d.is_dir():
            return d
    raise SystemExit("no shared/foreign/bodies found beside the repository (../shared from its root)")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--folder", type=Path, default=None, help="folder of GarmentCode bodies (*.obj)")
    ap.add_argument("--bodies", nargs="*", default=None, help="body names (file stems); default: all")
    ap.add_argument("--garments", nargs="*", default=GARMENTS,
                    help="base garment names, or pattern JSON files draped as they are (retargeting)")
    ap.add_argument("--edge-length", type=float, default=0.025)
    ap.add_argument("--png-dir", type=Path, default=None, help="render each drape (front, side) here")
    args = ap.parse_args()

    import tempfile

    import numpy as np
    import torch

    torch.set_num_threads(1)
    from _drapes import verdict_cells
    from tables import print_table

    from unsew.body.body import load_body
    from unsew.body.measure import measure_body
    from unsew.body.sdf import BodySDF
    from unsew.dress import DRESS_SETTINGS, dress
    from unsew.errors import UnsewError
    from unsew.io.garmentcode import load_pattern, save_pattern
    from unsew.pattern.base import make_base_pattern
    from unsew.sim.checks import check_dressed
    from unsew.sim.material import material_from_dict

    folder = args.folder or foreign_bodies()
    meshes = sorted(folder.glob("*.obj"))
    if args.bodies:
        meshes = [m for m in meshes if m.stem in args.bodies]
    if not meshes:
        raise SystemExit(f"no bodies to drape in {folder}")
    settings = DRESS_SETTINGS.replace(edge_length=args.edge_length)
    rows = []
    for mesh in meshes:
        t0 = time.perf_counter()
        body = load_body(mesh)  # no skeleton.json: rigged from the mesh
        rig_s = time.perf_counter() - t0
        assert body.rigged
        meas = measure_body(body)
        sdf = BodySDF.build(body)
        for g in args.garments:
            given = g.endswith(".json")
            row = dict(body=mesh.stem, garment=Path(g).parent.name + "/" + Path(g).name if given else g, rig_s=rig_s)
            t0 = time.perf_counter()
            try:
                with tempfile.TemporaryDirectory() as tmp:
                    path = Path(g) if given else Path(tmp) / f"{g}.json"
                    if not given:
                        save_pattern(make_base_pattern(g, meas), path)
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")
                        pat = load_pattern(path)
                # a fitted pattern drapes in its own fitted material, as `unsew drape` does
                fitted = (getattr(pat, "unsew", None) or {}).get("material") if given else None
                material = material_from_dict(fitted) if fitted else "cotton"
                d = dress(pat, body, sdf=sdf, material=material, settings=settings)
            except UnsewError as exc:
                row.update(verdict=f"error: {exc}", time_s=time.perf_counter() - t0, meets_bar=False)
                rows.append(row)
                print(row, flush=True)
                continue
            v = check_dressed(d, body=body)
            fallen = v.reason.startswith("fallen")
            row.update(verdict_cells(v, d), fallen=fallen, time_s=time.perf_counter() - t0,
                       meets_bar=bool(v.ok and v.inside_pct < INSIDE_BAR_PCT and not fallen))
            rows.append(row)
            print({k: (round(x, 3) if isinstance(x, float) else x) for k, x in row.items()}, flush=True)
            if args.png_dir is not None:
                from unsew.report.render import render_views

                os.makedirs(args.png_dir, exist_ok=True)
                render_views(
                    args.png_dir / f"{Path(g).stem}_{mesh.stem}.png", d.x.numpy(), d.mesh.faces,
                    body=(np.asarray(body.verts), np.asarray(body.faces)), frame="all",
                    views=("front", "side"), title=f"{'pattern ' + row['garment'] if given else 'base ' + g} on GarmentCode {mesh.stem} (rigged): {row['verdict']}",
                )
    cols = ["body", "garment", "rig_s", "verdict", "inside_pct", "fallen", "y_range", "stretch_max", "stretch_p99",
            "off_body_pct", "verts", "time_s", "meets_bar"]
    print_table(rows, cols, title=f"unsew's base patterns draped on GarmentCode bodies rigged from their mesh, "
                                  f"{args.edge_length * 100:g} cm edges, cotton (a given pattern: its fitted material)")
    n_ok = sum(bool(r.get("meets_bar")) for r in rows)
    print(f"\n{n_ok} of {len(rows)} drapes pass the checks with < {INSIDE_BAR_PCT:g} % of vertices inside and none fallen")


if __name__ == "__main__":
    main()
