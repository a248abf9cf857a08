"""Does `unsew drape` dress GarmentCode's true patterns on their own bodies (exit, inside, stretch)?

For each of GarmentCode's four sample specifications (``shared/foreign/patterns`` beside the
repository: pencil dress, hoodie, jumpsuit, shirt; designs unsew did not make), runs the command a
user runs,

    python -m unsew drape PATTERN --body BODY --out OUT/NAME.obj --keep-failed --no-progress

in a subprocess, on the GarmentCode body its name names (``shared/foreign/bodies``: mean_all.obj
for ``*_mean`` and ``*_mean_all``; the pencil dress names none and is drafted for the same mean
body), and measures the garment it wrote (``NAME.obj``, or ``NAME.failed.obj`` when the drape
failed its checks): the share of vertices inside the body [%] (the body's signed distance grid),
the largest and 99th-percentile edge stretch (3D edge length over its length on the pattern, read
from the OBJ's UVs, which are pattern coordinates [m]), and the wall time [s]; with ``--seams`` also
each garment's most stretched pattern edges (:func:`seam_rows`). A good drape exits
0, has at most 0.5 % of its vertices inside and no edge over 1.5 times its length.

    python -m benchmarks true_patterns [--patterns shirt_mean ...] [--out DIR] [--edge-length 0.025] [--seams]
    python -m benchmarks true_patterns --small     # one pattern, coarse mesh, short sewing (tests)
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent

#: pattern -> body file it is dressed on (module docstring)
PATTERNS = {
    "dress_pencil": "mean_all",
    "hoody_mean": "mean_all",
    "js_mean_all": "mean_all",
    "shirt_mean": "mean_all",
}
#: what a good drape stays within: vertices inside the body [%], largest edge stretch [-]
INSIDE_MAX_PCT = 0.5
STRETCH_MAX = 1.5
#: --small: the pattern, edge length [m] and sewing / settling steps of the quick run
SMALL = {"pattern": "hoody_mean", "edge_length": 0.04, "sew_steps": 40, "settle_steps": 10}


def foreign_dir() -> Path:
    """``shared/foreign`` beside the repository (``../shared`` from its root) or beside a folder above."""
    for up in HERE.parents:
        d = up / "shared" / "foreign"
        if (d / "patterns").is_dir() and (d / "bodies").is_dir():
            return d
    raise SystemExit(
        "no shared/foreign/{patterns,bodies} found beside the repository (../shared from its root)"
    )


def read_obj_uv(path: Path):
    """(verts (V, 3) [m], faces (F, 3), uv (Nu, 2) [m], faces_uv (F, 3)) of an OBJ written by
    ``unsew drape`` (``f a/b`` corners, 1-based)."""
    v, vt, f, ft = [], [], [], []
    for line in Path(path).read_text().splitlines():
        if line.startswith("v "):
            v.append([float(t) for t in line.split()[1:4]])
        elif line.startswith("vt "):
            vt.append([float(t) for t in line.split()[1:3]])
        elif line.startswith("f "):
            corners = [c.split("/") for c in line.split()[1:4]]
            f.append([int(c[0]) - 1 for c in corners])
            ft.append([int(c[1]) - 1 for c in corners])
    return np.asarray(v), np.asarray(f, np.int64), np.asarray(vt), np.asarray(ft, np.int64)


def measure(obj: Path, sdf) -> dict:
    """inside_pct [%], stretch_max and stretch_p99 [-] and the vertex count of a draped OBJ."""
    import torch

    x, f, uv, fu = read_obj_uv(obj)
    cols = [0, 1, 1, 2, 2, 0]
    e, eu = f[:, cols].reshape(-1, 2), fu[:, cols].reshape(-1, 2)
    r = np.linalg.norm(x[e[:, 0]] - x[e[:, 1]], axis=1) / np.linalg.norm(uv[eu[:, 0]] - uv[eu[:, 1]], axis=1)
    with torch.no_grad():
        d, _ = sdf.query(torch.as_tensor(x))
    return {
        "vertices": len(x),
        "inside_pct": float((d < 0).double().mean()) * 100.0,
        "stretch_max": float(r.max()),
        "stretch_p99": float(np.percentile(r, 99)),
    }


def seam_rows(name: str, obj: Path, *, foreign: Path, edge_length: float = 0.025, top: int = 3) -> list[dict]:
    """The ``top`` pattern edges of a draped OBJ with the longest mesh edge over its rest length:
    per (panel, edge) its largest and its overall stretch (3D length along the edge over its
    pattern length) and its mean height [m]. The pattern is meshed again at ``edge_length``, as
    ``unsew drape`` meshed it (the same mesh: checked by its vertex count)."""
    import warnings

    from unsew.io.garmentcode import load_pattern
    from unsew.meshing import mesh_pattern

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # clockwise panels mirrored, seam length warnings
        mesh = mesh_pattern(
            load_pattern(foreign / "patterns" / f"{name}_specification.json"), edge_length=edge_length
        )
    x = read_obj_uv(obj)[0]
    if len(x) != mesh.n_x:
        return []
    rows = []
    for (panel, edge), vs in mesh.edge_verts.items():
        xv, uv = x[mesh.x_of_u[vs]], mesh.uv[vs]
        l3 = np.linalg.norm(np.diff(xv, axis=0), axis=1)
        l2 = np.linalg.norm(np.diff(uv, axis=0), axis=1)
        rows.append(
            {
                "pattern": name,
                "panel": panel,
                "edge": edge,
                "rest_cm": float(100.0 * l2.sum()),
                "stretch_max": float((l3 / l2).max()),
                "stretch_whole": float(l3.sum() / l2.sum()),
                "y_m": float(xv[:, 1].mean()),
            }
        )
    return sorted(rows, key=lambda r: -r["stretch_max"])[:top]


def drape_one(
    name: str,
    body: str,
    out: Path,
    *,
    foreign: Path,
    sdf,
    edge_length=None,
    sew_steps=None,
    settle_steps=None,
) -> dict:
    """Run ``unsew drape`` on one true pattern and measure what it wrote (module docstring)."""
    obj = out / f"{name}.obj"
    cmd = [
        sys.executable,
        "-m",
        "unsew",
        "drape",
        str(foreign / "patterns" / f"{name}_specification.json"),
        "--body",
        str(foreign / "bodies" / f"{body}.obj"),
        "--out",
        str(obj),
        "--keep-failed",
        "--no-progress",
    ]
    for flag, val in (
        ("--edge-length", edge_length),
        ("--sew-steps", sew_steps),
        ("--settle-steps", settle_steps),
    ):
        if val is not None:
            cmd += [flag, str(val)]
    env = {**os.environ, "OMP_WAIT_POLICY": "PASSIVE"}
    t0 = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT, check=False)
    row = {"pattern": name, "body": f"{body}.obj", "exit": r.returncode, "time_s": time.perf_counter() - t0}
    written = obj if obj.is_file() else obj.with_name(obj.stem + ".failed.obj")
    if written.is_file():
        row.update(measure(written, sdf))
    lines = (r.stderr.strip() or r.stdout.strip()).splitlines()
    row["message"] = "" if r.returncode == 0 else (lines[-1] if lines else "")
    row["ok"] = bool(
        r.returncode == 0
        and row.get("inside_pct", 100.0) <= INSIDE_MAX_PCT
        and row.get("stretch_max", np.inf) <= STRETCH_MAX
    )
    return row


def run(names, *, out: Path, edge_length=None, sew_steps=None, settle_steps=None) -> list[dict]:
    """One row per pattern (:func:`drape_one`), the body SDFs built once per body."""
    from unsew.body.body import load_body
    from unsew.body.sdf import BodySDF

    foreign = foreign_dir()
    sdfs, rows = {}, []
    for name in names:
        body = PATTERNS[name]
        if body not in sdfs:
            sdfs[body] = BodySDF.build(load_body(foreign / "bodies" / f"{body}.obj", None))
        row = drape_one(
            name,
            body,
            out,
            foreign=foreign,
            sdf=sdfs[body],
            edge_length=edge_length,
            sew_steps=sew_steps,
            settle_steps=settle_steps,
        )
        rows.append(row)
        print({k: (round(v, 3) if isinstance(v, float) else v) for k, v in row.items()}, flush=True)
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--patterns", nargs="*", default=list(PATTERNS), choices=list(PATTERNS))
    ap.add_argument("--out", default=None, help="folder for the draped OBJs (default: a temporary one)")
    ap.add_argument(
        "--edge-length", type=float, default=None, help="mesh edge length [m] (default: unsew drape's)"
    )
    ap.add_argument("--small", action="store_true", help="one pattern, coarse mesh, short sewing (for tests)")
    ap.add_argument(
        "--seams", action="store_true", help="also list each garment's most stretched pattern edges"
    )
    args = ap.parse_args()
    from tables import print_table

    kw = {}
    names = args.patterns
    if args.small:
        names = [SMALL["pattern"]]
        kw = {k: SMALL[k] for k in ("edge_length", "sew_steps", "settle_steps")}
    elif args.edge_length is not None:
        kw = {"edge_length": args.edge_length}
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(args.out or tmp)
        out.mkdir(parents=True, exist_ok=True)
        rows = run(names, out=out, **kw)
        seams = []
        if args.seams:
            for r in rows:
                obj = out / f"{r['pattern']}.obj"
                obj = obj if obj.is_file() else obj.with_name(obj.stem + ".failed.obj")
                if obj.is_file():
                    seams += seam_rows(
                        r["pattern"], obj, foreign=foreign_dir(), edge_length=kw.get("edge_length", 0.025)
                    )
    print()
    print_table(
        rows,
        [
            "pattern",
            "body",
            "exit",
            "inside_pct",
            "stretch_max",
            "stretch_p99",
            "vertices",
            "time_s",
            "ok",
            "message",
        ],
    )
    if seams:
        print_table(
            seams,
            ["pattern", "panel", "edge", "rest_cm", "stretch_max", "stretch_whole", "y_m"],
            title="most stretched pattern edges",
        )
    n_ok = sum(r["ok"] for r in rows)
    print(
        f"\n{n_ok} of {len(rows)} dressed (exit 0, <= {INSIDE_MAX_PCT} % inside, no edge over {STRETCH_MAX}x)"
    )


if __name__ == "__main__":
    main()
