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

With ``--bodies CASE ...`` each pattern is put on each case folder's wearer instead (patterns sized
to GarmentCode's mean body on other bodies, as a user may give them), with the garment's top over
the wearer's neck joint beside the drape's measures (:func:`run_on_wearers`).

    python -m benchmarks true_patterns --bodies benchmarks/foreign/cases/shirt_gc__tall_thin ... --out DIR

With ``--gcd`` the same for the GarmentCode design benchmark's 40 cases (benchmarks/gcd, built
with ``python -m benchmarks gcd build``, ``--no-drape`` is enough): each case's ``pattern_gt.json``
dressed on its own ``body.obj`` (+ ``skeleton.json``). One drape at a time; each case's row is
written to ``OUT/<case>.json`` as soon as it is measured and a case with a row is not dressed again
(``--redo`` dresses it again), so a stopped run resumes. ``--record`` then writes
benchmarks/results/true_patterns_gcd.json and the table between the ``gcd table`` markers of
docs/true_patterns.md from all the rows in OUT.

    python -m benchmarks true_patterns --gcd [--cases DIR] [--only gc_s1_000 ...] [--out DIR] [--redo]
    python -m benchmarks true_patterns --gcd --seams       # and each garment's most stretched edges
    python -m benchmarks true_patterns --gcd --record      # the table from the rows in OUT

With ``--designs`` drafts of unsew's own design space (``unsew.pattern.design``) instead, dressed
on the default body (``_design_dress.py``: the start's widest seam, the verdict, the seam left open,
stretch, inside):

    python -m benchmarks true_patterns --designs [--edge-length 0.04] [--only NAME ...]

With ``--trace`` one GarmentCode case's true pattern is dressed step by step, printing the largest
stretch and the edges passing through the body per step (``_dress_trace.py``: where a drape goes
wrong):

    python -m benchmarks true_patterns --trace --cases CASES --only gc_s5_004 [--every 10]
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import subprocess
import sys
import tempfile
import time
import warnings
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
    """inside_pct [%], stretch_max and stretch_p99 [-], area_pct (how much larger the draped
    cloth is than its pattern [%]: a crumpled drape loses area) and the vertex count of a draped OBJ."""
    import torch
    import trimesh

    from _dress_trace import edge_stretch
    from unsew.meshing.triangulate import signed_areas

    x, f, uv, fu = read_obj_uv(obj)
    r = edge_stretch(x, f, fu, uv)
    with torch.no_grad():
        d, _ = sdf.query(torch.as_tensor(x))
    rest = np.abs(signed_areas(uv, fu)).sum()
    return {
        "vertices": len(x),
        "inside_pct": float((d < 0).double().mean()) * 100.0,
        "stretch_max": float(r.max()),
        "stretch_p99": float(np.percentile(r, 99)),
        "area_pct": float(100 * (trimesh.Trimesh(x, f, process=False).area / rest - 1)),
    }


#: the columns of a most-stretched-edge row
SEAM_COLUMNS = ["pattern", "panel", "edge", "label", "rest_cm", "stretch_max", "stretch_whole", "y_m"]


def seam_rows(
    name: str,
    obj: Path,
    *,
    foreign: Path | None = None,
    pattern: Path | None = None,
    edge_length=0.025,
    top=3,
) -> list[dict]:
    """The ``top`` pattern edges of a draped OBJ with the longest mesh edge over its rest length:
    per (panel, edge) its largest and its overall stretch (3D length along the edge over its
    pattern length) and its mean height [m]. The pattern (``pattern``, else GarmentCode's sample
    ``name`` under ``foreign``) is meshed again at ``edge_length``, as ``unsew drape`` meshed it
    (the same mesh: checked by its vertex count), and ``sewn_ratio`` (:func:`_sewn_ratio`)."""
    import warnings

    from unsew.io.garmentcode import load_pattern
    from unsew.meshing import mesh_pattern

    pattern = pattern or foreign / "patterns" / f"{name}_specification.json"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # clockwise panels mirrored, seam length warnings
        pat = load_pattern(pattern)
        mesh = mesh_pattern(pat, edge_length=edge_length)
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
                "label": pat.panels[panel].edges[edge].label or "",
                "rest_cm": float(100.0 * l2.sum()),
                "stretch_max": float((l3 / l2).max()),
                "stretch_whole": float(l3.sum() / l2.sum()),
                "y_m": float(xv[:, 1].mean()),
            }
        )
    rows = sorted(rows, key=lambda r: -r["stretch_max"])[:top]
    for r in rows:
        r["sewn_ratio"] = _sewn_ratio(pat, r["panel"], r["edge"])
    return rows


def _sewn_ratio(pattern, panel: str, edge: int) -> float | None:
    """Length of the edge stitched to ``panel``'s ``edge`` over its own [-] (over 1: the edge is
    gathered onto a longer one, as GarmentCode sews a tier, a waistband or a sleeve cap), or None."""
    from unsew.pattern.seams import stitch_length_ratios

    for st, a_over_b in zip(pattern.stitches, stitch_length_ratios(pattern)):
        if (st.a.panel, st.a.edge) == (panel, edge):
            return float(1.0 / a_over_b)
        if (st.b.panel, st.b.edge) == (panel, edge):
            return float(a_over_b)
    return None


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
    """Run ``unsew drape`` on one of GarmentCode's sample patterns and measure what it wrote
    (module docstring)."""
    row = drape_file(
        name,
        foreign / "patterns" / f"{name}_specification.json",
        ["--body", str(foreign / "bodies" / f"{body}.obj")],
        out,
        sdf=sdf,
        edge_length=edge_length,
        sew_steps=sew_steps,
        settle_steps=settle_steps,
    )
    return {"pattern": name, "body": f"{body}.obj", **row}


def drape_file(
    name: str,
    pattern: Path,
    body_args: list[str],
    out: Path,
    *,
    sdf,
    edge_length=None,
    sew_steps=None,
    settle_steps=None,
) -> dict:
    """``unsew drape PATTERN BODY_ARGS --out OUT/NAME.obj --keep-failed`` in a subprocess and the
    measures of the OBJ it wrote: exit, time_s [s], message (the last line when it failed),
    inside_pct, stretch_max, stretch_p99, vertices (when an OBJ was written) and ok."""
    obj = out / f"{name}.obj"
    for old in (obj, obj.with_name(obj.stem + ".failed.obj")):
        old.unlink(missing_ok=True)
    cmd = [
        sys.executable,
        "-m",
        "unsew",
        "drape",
        str(pattern),
        *body_args,
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
    row = {"exit": r.returncode, "time_s": time.perf_counter() - t0}
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


def run_on_wearers(names, wearers, *, out: Path, **kw) -> list[dict]:
    """One row per pattern and wearer (a case folder: ``unsew drape PATTERN --body CASE``), the
    patterns sized to GarmentCode's mean body put on other bodies, as a user may give them; with
    ``top_to_neck_m``, the garment's highest point over the wearer's neck joint [m] (a top hangs
    from the shoulders at about 0, a hood reaches 0.2, a bodice slid to the hips lies far below)."""
    from unsew.body.case import load_wearer
    from unsew.body.sdf import BodySDF

    foreign, rows = foreign_dir(), []
    for case in map(Path, wearers):
        body = load_wearer(case)
        sdf, neck = BodySDF.build(body), float(body.skeleton.position("neck")[1])
        for name in names:
            spec = foreign / "patterns" / f"{name}_specification.json"
            row = drape_file(f"{name}__{case.name}", spec, ["--body", str(case)], out, sdf=sdf, **kw)
            row = {"pattern": name, "body": case.name, **row}
            obj = out / f"{name}__{case.name}.obj"
            obj = obj if obj.is_file() else obj.with_name(obj.stem + ".failed.obj")
            row["top_to_neck_m"] = float(read_obj_uv(obj)[0][:, 1].max()) - neck if obj.is_file() else None
            rows.append(row)
            print({k: (round(v, 3) if isinstance(v, float) else v) for k, v in row.items()}, flush=True)
    return rows


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


# ---------------------------------------------------------------- the GarmentCode design benchmark

GCD = HERE / "gcd"
#: where `gcd build` writes the cases, and where the drapes and their rows go by default
GCD_CASES = GCD / "cases"
GCD_OUT = GCD_CASES / "_true_patterns"
GCD_RESULTS = HERE / "results" / "true_patterns_gcd.json"
DOC = ROOT / "docs" / "true_patterns.md"
DOC_BEGIN = "<!-- gcd table: written by python -m benchmarks true_patterns --gcd --record -->"
DOC_END = "<!-- gcd table end -->"
#: columns of the gcd table: row key -> heading
GCD_COLUMNS = {
    "case": "case",
    "type": "type",
    "body": "body",
    "exit": "exit",
    "inside_pct": "inside %",
    "stretch_max": "stretch max",
    "stretch_p99": "stretch p99",
    "area_pct": "area +%",
    "newton_stretch_max": "newton's stretch max",
    "to_newton_mm": "to newton's, per vertex mm",
    "above_newton_mm": "above newton's mm",
    "newton_area_pct": "newton's area +%",
    "sleeve_cover": "sleeve cover",
    "newton_sleeve_cover": "newton's sleeve cover",
    "vertices": "vertices",
    "time_s": "time s",
    "ok": "good",
    "message": "message",
}


def _target_on_mesh(case_dir: Path):
    """(target vertices (n_x, 3) [m] on the specification's mesh, that mesh, the target as draped
    (m, 3) [m], the rest mesh it was draped on) of a case's newton target (``target.obj``: the
    other simulator's drape of the same pattern, on the specification meshed as ``gcd build``
    meshed it, or moved onto this machine's mesh of it through the rest mesh it was draped on,
    ``gcd/kept.py``); None without a target, or where neither mesh matches it."""
    import trimesh

    from unsew.io.garmentcode import load_pattern
    from unsew.meshing import mesh_pattern

    target = case_dir / "target.obj"
    if not target.is_file():
        return None
    edge = json.loads((HERE / "gcd" / "manifest.json").read_text())["edge_length_m"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # GarmentCode's gathered seams: lengths apart
        mesh = mesh_pattern(load_pattern(case_dir / "pattern_gt.json"), edge_length=edge)
    sys.path.insert(0, str(HERE / "gcd"))
    import kept

    tm = trimesh.load(target, process=False, force="mesh")
    x0 = np.asarray(tm.vertices, np.float64)
    own = kept.own_mesh(case_dir, mesh, x0, tm.faces)
    if own is None:
        return None
    x = x0 if own is mesh else kept.moved_to_mesh(x0, vars(own), mesh)
    return x, mesh, x0, own


def newton_stretch(case_dir: Path, target=None):
    """The largest edge length over its pattern length [-] in the case's newton target, measured
    as :func:`measure` measures unsew's drapes; None without a target that matches the mesh.
    ``target``: :func:`_target_on_mesh`'s answer when already read."""
    from _dress_trace import edge_stretch

    got = _target_on_mesh(case_dir) if target is None else target
    if got is None:
        return None
    _, _, x0, own = got  # on the mesh it was draped on
    return float(edge_stretch(x0, np.asarray(own.faces), np.asarray(own.faces_uv), np.asarray(own.uv)).max())


def to_newton(case_dir: Path, obj: Path, target=None) -> dict:
    """Where unsew's drape ``obj`` (written by ``unsew drape``, the same mesh) puts each point of
    the cloth against where the case's newton target puts it: {"to_newton_mm": the median of the
    vertices' distances, "above_newton_mm": the mean of their height differences (unsew's minus
    newton's) [mm], "newton_area_pct": how much larger the target's cloth is than its pattern
    [%]}; empty without a matching target or drape. ``target``: :func:`_target_on_mesh`'s answer
    when already read. A surface distance (Chamfer) misses cloth that lies on the same surface
    from another place: a bodice bunched up over its skirt."""
    import trimesh

    from unsew.meshing.triangulate import signed_areas

    got = _target_on_mesh(case_dir) if target is None else target
    if got is None or not obj.is_file():
        return {}
    x, mesh, x0, own = got
    v, f, _, _ = read_obj_uv(obj)
    if len(v) != len(x) or not np.array_equal(f, np.asarray(mesh.faces)):
        return {}
    rest = np.abs(signed_areas(np.asarray(own.uv), np.asarray(own.faces_uv))).sum()
    area = trimesh.Trimesh(x0, np.asarray(own.faces), process=False).area  # on its own mesh
    return {
        "to_newton_mm": float(1000 * np.median(np.linalg.norm(v - x, axis=1))),
        "above_newton_mm": float(1000 * np.mean(v[:, 1] - x[:, 1])),
        "newton_area_pct": float(100 * (area / rest - 1)),
    }


def sleeve_covers(case_dir: Path, obj: Path, target=None) -> dict:
    """How well each sleeve goes round its arm (:func:`unsew.sim.checks.sleeve_cover`, the least
    over the design's sleeves, docs/decisions/062) in unsew's drape ``obj`` (or the failed drape
    ``unsew drape --keep-failed`` wrote beside it) and in the case's newton target:
    {"sleeve_cover", "newton_sleeve_cover"} [-], each None where no sleeve is judged or the mesh
    differs; empty for a design without sleeves. ``target``: :func:`_target_on_mesh`'s answer."""
    from unsew.body.body import load_body
    from unsew.io.garmentcode import load_pattern
    from unsew.meshing import mesh_pattern
    from unsew.sim.checks import sleeve_cover, sleeve_vertices

    edge = json.loads((HERE / "gcd" / "manifest.json").read_text())["edge_length_m"]
    skel = case_dir / "skeleton.json"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # GarmentCode's gathered seams: lengths apart
        pattern = load_pattern(case_dir / "pattern_gt.json")
        mesh = mesh_pattern(pattern, edge_length=edge)
        body = load_body(case_dir / "body.obj", skel if skel.is_file() else None)
    sleeves = sleeve_vertices(pattern, mesh, body)
    if not sleeves:
        return {}

    def least(x):
        if x is None or len(x) != mesh.n_x:
            return None
        covers = [sleeve_cover(x, idx, body, side) for side, idx in sleeves.items()]
        covers = [c for c in covers if np.isfinite(c)]
        return min(covers) if covers else None

    obj = obj if obj.is_file() else obj.with_name(obj.stem + ".failed.obj")
    drape = read_obj_uv(obj)[0] if obj.is_file() else None
    return {"sleeve_cover": least(drape), "newton_sleeve_cover": least(None if target is None else target[0])}


def gcd_case_ids() -> list[str]:
    """The benchmark's case ids in order (benchmarks/gcd/manifest.json: gc_s<seed>_<index>)."""
    m = json.loads((GCD / "manifest.json").read_text())
    return [f"gc_s{s['seed']}_{i:03d}" for s in m["seeds"] for i in range(m["count"])]


def _commit() -> str:
    r = subprocess.run(
        ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=ROOT, check=False
    )
    return r.stdout.strip() or "?"


def run_gcd(
    cases: Path, ids, *, out: Path, redo: bool = False, edge_length=None, sew_steps=None, settle_steps=None
) -> list[dict]:
    """Dress each case's pattern_gt.json on its body (:func:`drape_file`), one at a time, writing
    each row to ``out/<case>.json`` as soon as it is measured; a case that has a row there is not
    dressed again unless ``redo``. A case without pattern_gt.json or body.obj gets a row with no
    exit (not written, so a later run dresses it). Returns the rows of ``ids`` in order."""
    from unsew.body.body import load_body
    from unsew.body.sdf import BodySDF

    out.mkdir(parents=True, exist_ok=True)
    sdfs, rows = {}, []
    for cid in ids:
        d, done = cases / cid, out / f"{cid}.json"
        if done.is_file() and not redo:
            rows.append(json.loads(done.read_text()))
            continue
        truth = json.loads((d / "truth.json").read_text()) if (d / "truth.json").is_file() else {}
        meta = json.loads((d / "meta.json").read_text()) if (d / "meta.json").is_file() else {}
        row = {
            "case": cid,
            "type": truth.get("type", ""),
            "body": (meta.get("source", {}).get("body") or {}).get("name", ""),
        }
        if not (d / "pattern_gt.json").is_file() or not (d / "body.obj").is_file():
            rows.append({**row, "exit": None, "ok": False, "message": "no case (pattern_gt.json, body.obj)"})
            continue
        skel = d / "skeleton.json"
        body_args = ["--body", str(d / "body.obj")] + (["--skeleton", str(skel)] if skel.is_file() else [])
        key = hashlib.sha1((d / "body.obj").read_bytes()).hexdigest()
        if key not in sdfs:
            sdfs[key] = BodySDF.build(load_body(d / "body.obj", skel if skel.is_file() else None))
        row.update(
            drape_file(
                cid,
                d / "pattern_gt.json",
                body_args,
                out,
                sdf=sdfs[key],
                edge_length=edge_length,
                sew_steps=sew_steps,
                settle_steps=settle_steps,
            )
        )
        row["commit"] = _commit()
        done.write_text(json.dumps(row, indent=1))
        rows.append(row)
        print({k: (round(v, 3) if isinstance(v, float) else v) for k, v in row.items()}, flush=True)
    return rows


#: the start of unsew's one-line reason of a failed drape, left out of the table
FAILED = "unsew: error: drape of pattern_gt failed: "


def _cell(key: str, value):
    if isinstance(value, float):
        return int(round(value)) if key == "time_s" else round(value, 3 if "stretch_max" in key else 2)
    if key == "ok":
        return "yes" if value else "no"
    if key == "message" and value:
        return value.removeprefix(FAILED).removeprefix("unsew: ")
    return value


def gcd_table_rows(rows: list[dict]) -> list[dict]:
    """Rows as recorded and shown: headed by :data:`GCD_COLUMNS`, floats rounded."""
    return [{h: _cell(k, r.get(k)) for k, h in GCD_COLUMNS.items()} for r in rows]


def gcd_count_line(rows: list[dict]) -> str:
    n_ok = sum(bool(r.get("ok")) for r in rows)
    n_exit0 = sum(r.get("exit") == 0 for r in rows)
    line = (
        f"{n_ok} of {len(rows)} dressed (exit 0, <= {INSIDE_MAX_PCT} % inside, no edge over "
        f"{STRETCH_MAX}x); {n_exit0} of {len(rows)} exit 0."
    )
    newton = [r for r in rows if r.get("newton_stretch_max") is not None]
    if newton:
        over = [r for r in newton if r["newton_stretch_max"] > STRETCH_MAX]
        line += (
            f" newton's own drape has an edge over {STRETCH_MAX}x in {len(over)} of the {len(newton)}"
            f" with a newton target ({sum(bool(r.get('ok')) for r in over)} of those {len(over)} dressed"
            " by unsew within the bars)."
        )
    return line


def record_gcd(rows: list[dict], *, results: Path = GCD_RESULTS, doc: Path = DOC) -> None:
    """Write the rows to ``results`` (benchmarks/report.py's record format) and their table between
    :data:`DOC_BEGIN` and :data:`DOC_END` in ``doc`` (appended at its end the first time)."""
    from tables import markdown_table

    commits = sorted({r.get("commit", "") for r in rows} - {""})
    command = "python -m benchmarks true_patterns --gcd --record"
    results.write_text(
        json.dumps(
            {
                "title": "The GarmentCode design benchmark's true patterns dressed by unsew drape",
                "command": command,
                "commit": ", ".join(commits),
                "rows": gcd_table_rows(rows),
            },
            indent=1,
        )
        + "\n"
    )
    block = "\n".join(
        [
            DOC_BEGIN,
            "",
            f"Command: `{command}` (drapes made at {', '.join(commits) or '?'}).",
            "",
            markdown_table(
                [
                    {
                        **r,
                        **{
                            k: f"{r[k]:.3f}"
                            for k in ("stretch max", "newton's stretch max")
                            if r[k] is not None
                        },
                    }
                    for r in gcd_table_rows(rows)
                ],
                list(GCD_COLUMNS.values()),
                digits=2,
            ),
            "",
            gcd_count_line(rows),
            "",
            DOC_END,
        ]
    )
    text = doc.read_text() if doc.is_file() else ""
    if DOC_BEGIN in text and DOC_END in text:
        head, rest = text.split(DOC_BEGIN, 1)
        text = head + block + rest.split(DOC_END, 1)[1]
    else:
        text = text.rstrip("\n") + "\n\n" + block + "\n"
    doc.write_text(text)


def _parse(argv=None):
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
    ap.add_argument(
        "--bodies",
        nargs="*",
        default=None,
        help="case folders whose wearers the patterns are put on instead of their own body",
    )
    ap.add_argument("--gcd", action="store_true", help="the GarmentCode design benchmark's cases instead")
    ap.add_argument("--cases", default=str(GCD_CASES), help="--gcd: the built cases' folder")
    ap.add_argument("--only", nargs="*", default=None, help="--gcd: these case ids only")
    ap.add_argument("--redo", action="store_true", help="--gcd: dress cases that have a row in --out again")
    ap.add_argument(
        "--record",
        action="store_true",
        help="--gcd: write benchmarks/results/true_patterns_gcd.json and the table in docs/true_patterns.md",
    )
    return ap.parse_args(argv)


def _dress_foreign(args) -> tuple[list[dict], list[dict]]:
    """Dress GarmentCode's sample patterns; (their rows, the most stretched edges' rows with --seams)."""
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
        if args.bodies:
            return run_on_wearers(names, args.bodies, out=out, **kw), []
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
    return rows, seams


def main() -> None:
    if "--trace" in sys.argv[1:]:
        from _dress_trace import main as trace

        raise SystemExit(trace([a for a in sys.argv[1:] if a != "--trace"]))
    if "--designs" in sys.argv[1:]:
        from _design_dress import main as designs

        raise SystemExit(designs([a for a in sys.argv[1:] if a != "--designs"]))
    args = _parse()
    from tables import print_table

    if args.gcd:
        raise SystemExit(main_gcd(args))
    rows, seams = _dress_foreign(args)
    print()
    cols = ["pattern", "body", "exit", "inside_pct", "stretch_max", "stretch_p99", "vertices", "time_s", "ok"]
    print_table(rows, cols + (["top_to_neck_m"] if args.bodies else []) + ["message"])
    if seams:
        print_table(
            seams,
            [*SEAM_COLUMNS, "sewn_ratio"],
            title="most stretched pattern edges",
        )
    n_ok = sum(r["ok"] for r in rows)
    print(
        f"\n{n_ok} of {len(rows)} dressed (exit 0, <= {INSIDE_MAX_PCT} % inside, no edge over {STRETCH_MAX}x)"
    )


def _measure_against_targets(rows: list[dict], cases: Path, out: Path) -> None:
    """Each row's columns against its case's newton target and its sleeves' arms, measured again
    each time (the targets are the cases', the rows unsew's drapes in ``out``)."""
    for r in rows:
        d = cases / r["case"]
        target = _target_on_mesh(d)  # meshed once for every measure
        r["newton_stretch_max"] = newton_stretch(d, target) if target is not None else None
        r.update(to_newton(d, out / f"{r['case']}.obj", target) if target is not None else {})
        if (d / "pattern_gt.json").is_file() and (d / "body.obj").is_file() and r.get("vertices"):
            r.update(sleeve_covers(d, out / f"{r['case']}.obj", target))


def main_gcd(args) -> int:
    """``--gcd``: dress the cases, print their table, record it when asked."""
    from tables import markdown_table

    ids = gcd_case_ids()
    if not Path(args.cases).is_dir():
        print(
            f"true_patterns --gcd: --cases {args.cases} is not a folder (python -m benchmarks gcd build)",
            file=sys.stderr,
        )
        return 2
    if args.only:
        unknown = sorted(set(args.only) - set(ids))
        if unknown:
            print(
                f"true_patterns --gcd: unknown case(s) {unknown} (ids are gc_s<seed>_<index>)",
                file=sys.stderr,
            )
            return 2
        ids = [c for c in ids if c in args.only]
    kw = {}
    out = Path(args.out) if args.out else GCD_OUT
    if args.small:
        ids = ids[:1]
        kw = {k: SMALL[k] for k in ("edge_length", "sew_steps", "settle_steps")}
        out = Path(args.out) if args.out else Path(tempfile.mkdtemp(prefix="true_patterns_gcd_"))
    elif args.edge_length is not None:
        kw = {"edge_length": args.edge_length}
    rows = run_gcd(Path(args.cases), ids, out=out, redo=args.redo, **kw)
    _measure_against_targets(rows, Path(args.cases), out)
    print()
    print(markdown_table(gcd_table_rows(rows), list(GCD_COLUMNS.values())))
    if args.seams:
        seams = []
        for r in rows:
            obj = out / f"{r['case']}.obj"
            obj = obj if obj.is_file() else obj.with_name(obj.stem + ".failed.obj")
            if obj.is_file():
                pattern = Path(args.cases) / r["case"] / "pattern_gt.json"
                seams += seam_rows(r["case"], obj, pattern=pattern, edge_length=kw.get("edge_length", 0.025))
        print("\nmost stretched pattern edges\n")
        print(markdown_table(seams, [*SEAM_COLUMNS, "sewn_ratio"]))
    print("\n" + gcd_count_line(rows))
    if args.record:
        if args.small or kw:
            print("true_patterns --gcd: --record records the full run only", file=sys.stderr)
            return 2
        record_gcd(rows)
        print(f"wrote {GCD_RESULTS} and the table in {DOC}")
    return 0


if __name__ == "__main__":
    main()
