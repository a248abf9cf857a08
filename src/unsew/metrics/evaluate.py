"""Evaluate a fit result folder against a case folder (FORMATS.md): the work of ``unsew eval``.

3D (always): the result's draped ``garment.obj`` against the case's ``target.obj``/``target.ply``
(:func:`unsew.metrics.surface.surface_metrics`). 2D (when the case has ``pattern_gt.json`` and
the result ``pattern.json``): :func:`unsew.metrics.panels.pattern_metrics`. The case is loaded
and checked as ``unsew fit`` loads it (:func:`unsew.body.case.load_case`: meta.json's or the
options' units/up/front, a target of plausible size that lies on its wearer); the result is in
unsew's world frame (metres).
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from unsew.errors import InputError
from unsew.io.atomic import atomic_write
from unsew.io.garmentcode import load_pattern
from unsew.io.mesh import read_mesh
from unsew.metrics.panels import pattern_metrics
from unsew.metrics.surface import surface_metrics

__all__ = ["evaluate_result", "EVAL_FORMAT_VERSION", "format_table", "write_eval_json"]

#: Version of the eval.json layout.
EVAL_FORMAT_VERSION = 1


def evaluate_result(
    result_dir,
    case_dir,
    *,
    n_samples: int = 100_000,
    seed: int = 0,
    units: str | None = None,
    up: str | None = None,
    front: str | None = None,
) -> dict:
    """All metrics of a result folder against a case folder, as a JSON-ready dict.

    result_dir: folder with ``garment.obj`` [m, world frame] and optionally ``pattern.json``.
    case_dir: a case folder (FORMATS.md: ``target.obj``/``target.ply``, ``meta.json``, the wearer,
        optionally ``pattern_gt.json``), refused as ``unsew fit`` refuses it.
    n_samples: surface samples per mesh for the 3D metrics. seed: their seed.
    units, up, front: the case files' frame, overriding meta.json's (as ``unsew fit --units``).
    Returns: ``{"format_version", "result", "case", "3d": {...}, "2d": {...} | None,
    "2d_skipped": reason | None}``, plus ``2d_base`` / ``2d_graded`` when the result folder holds
    the fit's ``pattern_base.json`` / ``pattern_graded.json``. Raises InputError / PatternError on bad input
    (missing files, empty or non-finite meshes, a pattern without panels); panels without a counterpart
    are listed in ``2d["unmatched"]``.
    """
    res, case = Path(result_dir), Path(case_dir)
    for d, what in ((res, "result"), (case, "case")):
        if not d.is_dir():
            raise InputError(f"{what} folder {d} does not exist")
    garment = res / "garment.obj"
    if not garment.is_file():
        raise InputError(f"result folder {res} has no garment.obj (the draped result); run `unsew fit` first")
    if n_samples < 1:
        raise InputError(f"--samples must be at least 1, got {n_samples}")
    gv, gf = read_mesh(garment)
    from unsew.body.case import load_case

    loaded = load_case(case, units=units, up=up, front=front)  # the fit's checks: units, frame, on the body
    tv, tf = loaded.target_verts, loaded.target_faces
    out = {
        "format_version": EVAL_FORMAT_VERSION,
        "result": str(res),
        "case": str(case),
        "units": {
            "chamfer": "mm",
            "angles": "deg",
            "vertex_l2": "cm",
            "turning_distance": "rad",
            "area": "m^2",
        },
        "3d": surface_metrics(gv, gf, tv, tf, n_samples=n_samples, seed=seed),
        "2d": None,
        "2d_skipped": None,
    }
    _pattern_entries(out, res, case)
    return out


def _pattern_entries(out: dict, res: Path, case: Path) -> None:
    """Fill ``out``'s "2d" (or "2d_skipped"), "2d_base" and "2d_graded" from the result folder's
    patterns against the case's pattern_gt.json (in place)."""
    gt, est = case / "pattern_gt.json", res / "pattern.json"
    if not gt.is_file():
        out["2d_skipped"] = "case has no pattern_gt.json"
    elif not est.is_file():
        out["2d_skipped"] = "result has no pattern.json"
    else:
        gt_pattern = load_pattern(gt)
        out["2d"] = pattern_metrics(load_pattern(est), gt_pattern)
        for key, name in (("2d_base", "pattern_base.json"), ("2d_graded", "pattern_graded.json")):
            if (res / name).is_file():  # the fit's starting points (unsew.fit.outputs)
                out[key] = pattern_metrics(load_pattern(res / name), gt_pattern)


def format_table(ev: dict) -> str:
    """A plain-text table of an :func:`evaluate_result` dict."""
    d3 = ev["3d"]
    lines = [
        f"3D: {ev['result']} vs {ev['case']} ({d3['n_samples']} samples per mesh, seed {d3['seed']})",
        f"  {'Chamfer (mean) [mm]':<28}{d3['chamfer_mm']:>12.3f}",
        f"  {'Chamfer p95 [mm]':<28}{d3['chamfer_p95_mm']:>12.3f}",
        f"  {'Hausdorff (sampled) [mm]':<28}{d3['hausdorff_mm']:>12.3f}",
        f"  {'normal error [deg]':<28}{d3['normal_error_deg']:>12.3f}",
        f"  {'normal cosine distance':<28}{d3['normal_cosine_distance']:>12.5f}",
    ]
    d2 = ev.get("2d")
    for key, what in (("2d_base", "base"), ("2d_graded", "graded")):
        d = ev.get(key)
        if d:
            lines.append(
                f"2D of the {what} pattern: area error {100 * d['area_error_weighted_rel']:.2f} % "
                f"(area-weighted), total area {100 * d['area_error_total_rel']:.2f} %"
            )
    if d2 is None:
        lines.append(f"2D: skipped ({ev.get('2d_skipped')})")
    else:
        lines.append("2D: panels (true <- estimated)")
        lines.append(f"  {'panel':<24}{'turning [rad]':>14}{'area err':>10}{'L2 [cm]':>9}")
        for name, p in d2["panels"].items():
            l2 = "-" if p["vertex_l2_cm"] is None else f"{p['vertex_l2_cm']:.2f}"
            lab = f"{name} <- {p['estimated_panel']}" if name != p["estimated_panel"] else name
            lines.append(f"  {lab:<24}{p['turning_distance']:>14.4f}{p['area_error_rel']:>10.4f}{l2:>9}")
        l2m = "-" if d2["vertex_l2_cm_mean"] is None else f"{d2['vertex_l2_cm_mean']:.2f}"
        lines.append(
            f"  {'mean (matched)':<24}{d2['turning_distance_mean']:>14.4f}"
            f"{d2['area_error_rel_mean']:>10.4f}{l2m:>9}"
        )
        un = d2.get("unmatched") or {}
        if un.get("estimated") or un.get("true"):
            lines.append(
                f"  unmatched panels: estimated {un.get('estimated') or '[]'}, true {un.get('true') or '[]'}"
            )
        if d2.get("area_error_weighted_rel") is not None:
            lines.append(
                "  area error, area-weighted (unmatched count in full) "
                f"{100 * d2['area_error_weighted_rel']:.2f} %, total area "
                f"{100 * d2['area_error_total_rel']:.2f} %"
            )
    return "\n".join(lines)


def write_eval_json(ev: dict, path: str | os.PathLike) -> None:
    """Write an evaluation dict as JSON, atomically."""
    with atomic_write(path) as tmp:
        Path(tmp).write_text(json.dumps(ev, indent=2) + "\n")
