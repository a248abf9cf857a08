"""Fits of the GarmentCode benchmark's built cases, each one's outcome kept (a failed fit is a miss).

``python -m benchmarks gcd fit --cases DIR --results RESULTS [--only ...] [--redo]`` runs
``python -m unsew fit CASE --out RESULTS/<case> --no-progress`` on every built case, one at a
time, and writes each fit's exit code, wall time [s] and last stderr line to
``RESULTS/fits.json`` as soon as it ends, so that ``gcd score`` counts a fit that stopped with
an error (and wrote no result folder) as a tried case, not as one never run.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

#: Wall-clock limit of one fit [s]; the benchmark's bar is 10 min on 2 cores, this only stops a hung one.
FIT_TIMEOUT_S = 3600

LOG_NAME = "fits.json"


def read_log(results: Path) -> dict:
    """``{case: {"exit", "seconds", "message"}}`` of the fits run into ``results`` (empty if none)."""
    p = results / LOG_NAME
    return json.loads(p.read_text()) if p.is_file() else {}


def _write_log(results: Path, log: dict) -> None:
    tmp = results / (LOG_NAME + ".tmp")
    tmp.write_text(json.dumps(log, indent=1, sort_keys=True) + "\n")
    tmp.replace(results / LOG_NAME)


def run_fit(case: Path, out: Path, timeout: int = FIT_TIMEOUT_S, *, material_only: bool = False) -> dict:
    """One ``unsew fit`` of ``case`` into ``out``: ``{"exit", "seconds", "message"}`` (message:
    the last stderr line, the one-line reason of a failed fit or a warning of a missed one). With
    ``material_only`` the case's true pattern is held and only its fabric fitted (the
    material-fitted floor: ``--material-only --base CASE/pattern_gt.json``)."""
    cmd = [sys.executable, "-m", "unsew", "fit", str(case), "--out", str(out), "--no-progress"]
    if material_only:
        cmd += ["--material-only", "--base", str(case / "pattern_gt.json")]
    if out.exists():
        cmd.append("--overwrite")
    env = dict(os.environ, OMP_WAIT_POLICY=os.environ.get("OMP_WAIT_POLICY", "PASSIVE"))
    t0 = time.time()
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, check=False, timeout=timeout, env=env)
        code, err = r.returncode, r.stderr
    except subprocess.TimeoutExpired as exc:
        code, err = (
            124,
            f"timed out after {timeout} s\n" + (exc.stderr or b"").decode(errors="replace")[-200:],
        )
    lines = [ln for ln in err.strip().splitlines() if ln.strip()]
    return {"exit": code, "seconds": round(time.time() - t0, 1), "message": lines[-1][:300] if lines else ""}


def cmd_fit(args, case_ids: list[str]) -> int:
    """Fit every built case of ``args.cases`` (or ``args.only``) into ``args.results``; a case with
    an outcome in fits.json is skipped unless ``args.redo``; ``args.material_only``: the true
    pattern's material only (``gcd floor-fitted`` records those)."""
    cases, results = Path(args.cases), Path(args.results)
    built_p = cases / "build.json"
    if not built_p.is_file():
        print(
            f"gcd fit: no build.json in {cases} (run `python -m benchmarks gcd build` first)", file=sys.stderr
        )
        return 2
    built = json.loads(built_p.read_text())
    todo = [c for c in case_ids if built.get(c, {}).get("status") == "built"]
    if args.only:
        unknown = sorted(set(args.only) - set(case_ids))
        if unknown:
            print(f"gcd fit: unknown case(s) {unknown}", file=sys.stderr)
            return 2
        todo = [c for c in todo if c in args.only]
    results.mkdir(parents=True, exist_ok=True)
    log = read_log(results)
    for cid in todo:
        if cid in log and not args.redo:
            continue
        print(f"{cid}: fitting", flush=True)
        log[cid] = run_fit(cases / cid, results / cid, material_only=getattr(args, "material_only", False))
        _write_log(results, log)
        o = log[cid]
        print(f"{cid}: exit {o['exit']} in {o['seconds']} s {o['message']}", flush=True)
    return 0


def garment_panels(src: Path, panel_order: list, pattern=None):
    """(x (V, 3) [m], faces (F, 3), uv (Nu, 2) [m], mesh) of a fit's garment.obj, ``mesh`` with
    ``uv_panel`` (Nu,) indices into ``panel_names`` (= ``panel_order``, the pattern's panels in its
    file's order) and ``x_of_u`` (Nu,): each panel's rest mesh is one piece of the OBJ's pattern
    coordinates, written in the pattern's panel order. Given the ``pattern`` (a Pattern), also
    ``edge_verts``: (panel, edge index) -> the rest vertices lying on that edge."""
    from types import SimpleNamespace

    import numpy as np
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
    from bench_true_patterns import read_obj_uv

    x, f, uv, fu = read_obj_uv(src / "garment.obj")
    x_of_u = np.zeros(len(uv), np.int64)
    x_of_u[fu.ravel()] = f.ravel()
    ij = np.concatenate([fu[:, [0, 1]], fu[:, [1, 2]]])
    n, comp = connected_components(coo_matrix((np.ones(len(ij)), (ij[:, 0], ij[:, 1])), (len(uv), len(uv))))
    if n != len(panel_order):
        raise ValueError(f"{src}: garment.obj has {n} pieces for {len(panel_order)} panels")
    first = [np.flatnonzero(comp == k).min() for k in range(n)]
    uv_panel = np.argsort(np.argsort(first))[comp]
    mesh = SimpleNamespace(uv_panel=uv_panel, x_of_u=x_of_u, panel_names=list(panel_order))
    if pattern is not None:
        mesh.edge_verts = _edge_verts(pattern, uv, uv_panel, list(panel_order))
    return x, f, uv, mesh


#: How far [m] from an edge of its panel's outline a rest vertex may lie and count as on it.
ON_EDGE = 1e-3


def _edge_verts(pattern, uv, uv_panel, names: list) -> dict:
    """(panel, edge index) -> (k,) indices of the rest vertices ``uv`` (Nu, 2) [m] of that panel
    (``uv_panel`` (Nu,) into ``names``) within ``ON_EDGE`` of the edge (sampled finely)."""
    import numpy as np

    from unsew.pattern.curves import sample_edge

    out = {}
    for i, name in enumerate(names):
        ids = np.flatnonzero(uv_panel == i)
        pts = uv[ids]
        pan = pattern.panels[name]
        for e in range(len(pan.edges)):
            q = sample_edge(pan, e, 256)
            a, d = q[:-1], np.diff(q, axis=0)
            w = pts[:, None] - a[None]  # (k, S, 2) from each segment's start
            t = np.clip((w * d[None]).sum(-1) / np.maximum((d * d).sum(-1), 1e-30), 0.0, 1.0)
            dist = np.linalg.norm(w - t[..., None] * d[None], axis=-1).min(axis=1)
            out[(name, e)] = ids[dist <= ON_EDGE]
    return out


def reexport(src: Path, dst: Path, body=None) -> None:
    """The fit result folder ``src`` copied to ``dst`` with its pattern.json placed as ``unsew
    fit`` exports it now (:func:`unsew.fit.outputs.placed_where_draped`: each panel moved over
    where garment.obj drapes it; ``body``, the wearer, lays a sleeve's halves round its arm), for
    fits made before that export; newton's re-drape of the earlier pattern is not copied."""
    import shutil

    from unsew.fit.outputs import placed_where_draped
    from unsew.io.garmentcode import load_pattern, save_pattern

    pattern = load_pattern(src / "pattern.json")
    x, _, uv, mesh = garment_panels(src, list(pattern.panel_order), pattern)
    placed = placed_where_draped(pattern, mesh, uv, x, body)  # made before anything is written
    shutil.copytree(src, dst, ignore=shutil.ignore_patterns("redrape_newton*"), dirs_exist_ok=True)
    save_pattern(placed, dst / "pattern.json")


def graded_placed(src: Path, body=None):
    """The graded pattern of the fit result folder ``src`` (pattern_graded.json, the pattern phase
    two started from) placed where the fit's drape hangs its panels, as the fit places its own
    (:func:`unsew.fit.outputs.placed_where_draped`, ``body`` the wearer); None where phase two's
    pattern was not kept: the fit returned the graded pattern already."""
    from unsew.fit.outputs import placed_where_draped
    from unsew.io.garmentcode import load_pattern

    metrics = json.loads((src / "metrics.json").read_text())
    if not (metrics.get("redress") or {}).get("phase_two_kept"):
        return None
    graded = load_pattern(src / "pattern_graded.json")
    x, _, uv, mesh = garment_panels(src, list(graded.panel_order), graded)
    return placed_where_draped(graded, mesh, uv, x, body)


def graded_copy(src: Path, dst: Path, placed=None) -> bool:
    """The fit result folder ``src`` copied to ``dst`` with its graded pattern as pattern.json
    (``placed``, or :func:`graded_placed`): judged as a result, it says what phase two changed.
    garment.obj stays the fit's drape, so only the pattern's figures and newton's re-drape in
    ``gcd score --results DST`` are the graded pattern's. False (nothing written) where phase
    two's pattern was not kept."""
    import shutil

    from unsew.io.garmentcode import save_pattern

    placed = graded_placed(src) if placed is None else placed
    if placed is None:
        return False
    shutil.copytree(src, dst, ignore=shutil.ignore_patterns("redrape_newton*"), dirs_exist_ok=True)
    save_pattern(placed, dst / "pattern.json")
    return True


def cmd_graded(args, cases: list[str]) -> int:
    """``gcd graded --results IN --to OUT``: each fit of IN whose phase two was kept, with its
    graded pattern in place of its result (:func:`graded_copy`), and IN's outcomes of them. Every
    pattern is placed before anything is written: a fit that cannot be read leaves OUT as it was."""
    from unsew.errors import UnsewError

    src, dst = Path(args.results), Path(args.to)
    if not src.is_dir() or dst.resolve() == src.resolve():
        print(f"gcd graded: --results {src} must be a folder and --to another one", file=sys.stderr)
        return 2
    if not Path(args.cases).is_dir():
        print(f"gcd graded: --cases {args.cases} is not a folder (the wearers)", file=sys.stderr)
        return 2
    placed = {}
    for cid in cases:
        if not (src / cid / "pattern_graded.json").is_file():
            continue
        try:
            p = graded_placed(src / cid, _wearer(Path(args.cases) / cid))
        except (UnsewError, OSError, ValueError) as exc:
            print(f"gcd graded: {cid}: {str(exc).splitlines()[0]} (nothing written)", file=sys.stderr)
            return 2
        if p is not None:
            placed[cid] = p
    if not placed:
        print(f"gcd graded: no fit in {src} kept phase two's pattern", file=sys.stderr)
        return 2
    for cid, p in placed.items():
        graded_copy(src / cid, dst / cid, p)
    print(f"{len(placed)} fits with their graded pattern in {dst}: {' '.join(placed)}")
    log = read_log(src)
    _write_log(dst, {cid: log[cid] for cid in placed if cid in log})
    return 0


def _wearer(case: Path):
    """The Body of a case folder (body.obj, with its skeleton.json where it has one), or None
    without a body.obj."""
    from unsew.body.body import load_body

    if not (case / "body.obj").is_file():
        return None
    skel = case / "skeleton.json"
    return load_body(case / "body.obj", skel if skel.is_file() else None)


def cmd_reexport(args, cases: list[str]) -> int:
    """``gcd reexport --results IN --to OUT``: every fitted case of IN re-exported into OUT
    (:func:`reexport`), with IN's fits.json."""
    from unsew.errors import UnsewError

    src, dst = Path(args.results), Path(args.to)
    if not src.is_dir():
        print(f"gcd reexport: --results {src} is not a folder", file=sys.stderr)
        return 2
    if dst.resolve() == src.resolve():
        print("gcd reexport: --to must be another folder than --results", file=sys.stderr)
        return 2
    done = [cid for cid in cases if (src / cid / "pattern.json").is_file()]
    if not done:
        print(f"gcd reexport: no fit result folder in {src}", file=sys.stderr)
        return 2
    if not Path(args.cases).is_dir():
        print(f"gcd reexport: --cases {args.cases} is not a folder (the wearers)", file=sys.stderr)
        return 2
    for cid in done:
        try:
            reexport(src / cid, dst / cid, _wearer(Path(args.cases) / cid))
        except (UnsewError, OSError, ValueError) as exc:  # an unreadable fit, or a drape of another pattern
            print(f"gcd reexport: {cid}: {str(exc).splitlines()[0]}", file=sys.stderr)
            return 2
        print(f"{cid}: re-exported", flush=True)
    log = read_log(src)
    if log:
        _write_log(dst, log)
    return 0
