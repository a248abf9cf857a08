"""Does a damaged target give the same pattern as the clean one (issue 22)?

Takes a case folder (FORMATS.md) whose target is clean, writes a copy whose target.obj is damaged
as exports and scans are: ``--duplicates`` (default 50) faces repeated, each copy inserted at a
random place in the face list; a fin of 3 triangles (2 new vertices standing one edge length off
the surface on an interior edge, a third twice as far) hanging on an interior edge of the target,
so that edge has 3 faces; and one degenerate face (a repeated vertex). Then it fits both with the
real command line, ``python -m unsew fit CASE --out OUT --config CONFIG --no-progress``, each in a fresh
process, and prints:

- one row per fit: exit, Chamfer [mm] of the result against that case's target (metrics.json
  ``surface``), the fit process's peak resident memory [MB] (metrics.json ``peak_memory_mb``) and
  what loading cleaned (metrics.json ``target_repair``);
- one row per panel: its area [m^2] in the clean and in the damaged fit's pattern.json
  (:func:`unsew.metrics.panels.panel_area`, panels matched by name: both start from the same base)
  and the difference |A_damaged - A_clean| / A_clean [%] (two significant digits); the last row
  sums all panels.

Loading cleans the damaged target back to the clean triangles (unsew.geometry.repair), but listed
in another order where a duplicate came before its original, so sums run in another order and the
metrics' surface samples differ: the Chamfer of the two fits differs a little even when the
patterns agree to rounding.

Default case: the demo's known-truth t-shirt (:func:`unsew.fit.demo.make_truth_case`) made in
small mode; default fit configuration: small mode as tests/fit/test_fit_small.py (4 cm mesh,
3 iterations, 8 drape steps, cotton), so the comparison takes minutes. ``--config FILE`` fits with
another YAML configuration (e.g. the defaults: an empty file), ``--case DIR`` damages another case
(e.g. one written by ``python -m benchmarks make_cases``).

    python -m benchmarks damaged [--out bench-out/damaged] [--case DIR] [--config FIT.yaml]
        [--duplicates 50] [--seed 0]
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

ROOT = Path(__file__).resolve().parent.parent

#: tests/fit/test_fit_small.py's small mode (FitConfig's flat names)
SMALL = dict(edge_length=0.04, iterations=3, steps=8, sew_steps=60, settle_steps=20, target_points=1500,
             material_start=1, material="cotton")


def damage(verts, faces, *, duplicates: int = 50, seed: int = 0):
    """A damaged copy of a clean garment mesh: ``duplicates`` faces repeated (each copy inserted at
    a random place), a 3-face fin on a random interior edge, one degenerate face appended.

    verts: (V, 3) float64 [m]; faces: (F, 3) int. Returns (verts (V + 3, 3) [m], faces
    (F + duplicates + 4, 3) int64); the first V vertices are ``verts`` unchanged.
    """
    import numpy as np

    from unsew.geometry.topology import unique_edges

    rng = np.random.default_rng(seed)
    v = np.asarray(verts, np.float64)
    f = np.asarray(faces, np.int64)
    edges, _, cnt = unique_edges(f)
    interior = np.flatnonzero(cnt == 2)
    e0, e1 = edges[interior[rng.integers(len(interior))]]
    # the fin stands along the normal of a face on that edge, one edge length off the surface
    on_edge = np.flatnonzero(((f == e0) | (f == e1)).sum(axis=1) == 2)[0]
    a, b, c = v[f[on_edge]]
    nrm = np.cross(b - a, c - a)
    nrm /= np.linalg.norm(nrm)
    length = float(np.linalg.norm(v[e1] - v[e0]))
    n = len(v)
    fin_v = np.array([v[e0] + length * nrm, v[e1] + length * nrm, 0.5 * (v[e0] + v[e1]) + 2 * length * nrm])
    fin_f = np.array([[e0, e1, n + 1], [e0, n + 1, n], [n, n + 1, n + 2]])
    k = int(rng.integers(len(f)))
    degenerate = np.array([[f[k, 0], f[k, 1], f[k, 1]]])
    dup = f[rng.choice(len(f), duplicates, replace=False)]
    out = list(f)
    for row, at in zip(dup, rng.integers(0, len(f) + 1, size=duplicates)):
        out.insert(int(at), row)
    return np.concatenate([v, fin_v]), np.concatenate([np.array(out), fin_f, degenerate])


def _fit(case: Path, out: Path, config: Path) -> dict:
    """Run the CLI fit of ``case`` into ``out`` in a fresh process; its status and metrics."""
    shutil.rmtree(out, ignore_errors=True)
    shutil.rmtree(out.with_name(out.name + ".partial"), ignore_errors=True)
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"), OMP_WAIT_POLICY="PASSIVE")
    cmd = [sys.executable, "-m", "unsew", "fit", str(case), "--out", str(out), "--config", str(config), "--no-progress"]
    print(f"fitting {case} -> {out}", file=sys.stderr, flush=True)
    t = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT)
    wall = time.perf_counter() - t
    lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
    res = {"rc": r.returncode, "wall_s": wall, "stderr": lines}
    if r.returncode == 0 and (out / "metrics.json").is_file():
        res["metrics"] = json.loads((out / "metrics.json").read_text())
    return res


def _areas(pattern_json: Path) -> dict[str, float]:
    from unsew.io.garmentcode import load_pattern
    from unsew.metrics.panels import panel_area

    return {name: panel_area(p) for name, p in load_pattern(pattern_json).panels.items()}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(ROOT / "bench-out" / "damaged"), help="work folder")
    ap.add_argument("--case", help="clean case folder to damage (default: the demo t-shirt, made in small mode)")
    ap.add_argument("--config", help="fit configuration YAML (default: small mode, see the docstring)")
    ap.add_argument("--duplicates", type=int, default=50, help="duplicate faces to insert")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)

    import yaml

    from tables import print_table
    from unsew.fit.config import load_config
    from unsew.io.mesh import read_mesh, write_obj

    work = Path(args.out).resolve()
    work.mkdir(parents=True, exist_ok=True)
    if args.config:
        config = Path(args.config).resolve()
    else:
        config = work / "small.yaml"
        config.write_text(yaml.safe_dump(SMALL))
    if args.case:
        clean = Path(args.case).resolve()
    else:
        clean = work / "clean_case"
        if not (clean / "target.obj").is_file():
            from unsew.fit.demo import make_truth_case

            print(f"making the demo t-shirt case in {clean}", file=sys.stderr, flush=True)
            make_truth_case(clean, settings=load_config(config).drape)
    damaged = work / "damaged_case"
    shutil.rmtree(damaged, ignore_errors=True)
    shutil.copytree(clean, damaged)
    v, f = read_mesh(clean / "target.obj")
    vd, fd = damage(v, f, duplicates=args.duplicates, seed=args.seed)
    write_obj(damaged / "target.obj", vd, fd, header=f"{clean.name}'s target damaged by benchmarks/bench_damaged.py")

    fits = {"clean": _fit(clean, work / "fit_clean", config), "damaged": _fit(damaged, work / "fit_damaged", config)}
    rows = []
    for name, r in fits.items():
        m = r.get("metrics") or {}
        rep = m.get("target_repair") or {}
        rows.append({
            "target": name, "exit": "ok" if "metrics" in r else (r["stderr"][-1] if r["stderr"] else f"exit {r['rc']}"),
            "faces in file": len(f) if name == "clean" else len(fd),
            "wall s": r["wall_s"], "chamfer mm": (m.get("surface") or {}).get("chamfer_mm"),
            "peak MB": m.get("peak_memory_mb"),
            "cleaned on load": ", ".join(f"{k} {v}" for k, v in rep.items()
                                         if v and k != "components" and not isinstance(v, list)) or "nothing",
        })
    print_table(rows, title=f"Fits of the clean and the damaged target ({clean.name}, config {config.name})", digits=2)
    if not all("metrics" in r for r in fits.values()):
        return 1
    a_clean, a_dmg = _areas(work / "fit_clean" / "pattern.json"), _areas(work / "fit_damaged" / "pattern.json")
    prow = []
    for name in sorted(set(a_clean) | set(a_dmg)):
        ac, ad = a_clean.get(name), a_dmg.get(name)
        prow.append({"panel": name, "area clean m2": ac, "area damaged m2": ad,
                     "difference %": None if ac is None or ad is None else f"{100.0 * abs(ad - ac) / ac:.2g}"})
    tc, td = sum(a_clean.values()), sum(a_dmg.values())
    prow.append({"panel": "all panels", "area clean m2": tc, "area damaged m2": td,
                 "difference %": f"{100.0 * abs(td - tc) / tc:.2g}"})
    print_table(prow, title="Panel areas of the two results", digits=4)
    return 0


if __name__ == "__main__":
    sys.exit(main())
