"""The HTML report of a fit: loss curves, target and result rendered front and side, a
per-vertex distance heat map, the base, graded and final patterns overlaid (and the true one),
and the metrics table."""

from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["write_fit_report"]


def write_fit_report(work: Path, result, case, metrics: dict) -> Path:
    """Write report.html (figures embedded) into ``work``; figures go to ``work/figures``."""
    from unsew.metrics.surface import closest_points
    from unsew.report.figures import pattern_outlines, plot_loss_curves, plot_patterns
    from unsew.report.html import write_report
    from unsew.report.render import render_comparison

    fig_dir = Path(work) / "figures"
    fig_dir.mkdir(parents=True, exist_ok=True)
    figs = []
    hist = {k: v for k, v in result.history.items() if v and any(x > 0 for x in v)}
    if hist:
        figs.append(("Loss per iteration of phase two (log scale)",
                     plot_loss_curves(fig_dir / "loss.png", hist)))
    faces = np.asarray(result.mesh.faces)
    d = _vertex_distance_mm(result.x, case.target_verts, case.target_faces, closest_points)
    body = (np.asarray(case.body.verts), np.asarray(case.body.faces))
    figs.append(("Target (top) and fitted garment (bottom), front and side; colour: distance of each "
                 "result vertex to the target surface [mm]",
                 render_comparison(fig_dir / "compare.png", (case.target_verts, case.target_faces),
                                   (result.x, faces), distance_mm=d, body=body)))
    pats = [("base", pattern_outlines(result.base_pattern))]
    if result.graded_pattern is not None and result.graded_pattern is not result.base_pattern:
        pats.append(("graded", pattern_outlines(result.graded_pattern)))
    if case.pattern_gt is not None:
        pats.append(("true", pattern_outlines(case.pattern_gt)))
    pats.append(("final", pattern_outlines(result.pattern)))
    figs.append(("Sewing patterns: base (dashed grey), graded (blue), final (black)"
                 + (", true (red)" if case.pattern_gt is not None else ""),
                 plot_patterns(fig_dir / "patterns.png", pats)))
    s = metrics.get("surface", {})
    summary = {
        "case": Path(case.path).name,
        "garment": case.garment or "custom",
        "chamfer_mm": s.get("chamfer_mm"),
        "normal_error_deg": s.get("normal_error_deg"),
        "iterations": result.iterations,
        "time_s": result.timings.get("total_s"),
    }
    if "pattern" in metrics and isinstance(metrics["pattern"], dict):
        summary["area_error_mean_pct"] = _pct(metrics["pattern"].get("area_error_rel_mean"))
    notes = [f"{r.get('warning')}" for r in (result.grade_table or []) if isinstance(r, dict) and r.get("warning")]
    table = {k: v for k, v in metrics.items() if k not in ("timings_s",)}
    table["timings_s"] = metrics.get("timings_s", {})
    if result.grade_table:
        table["grading"] = {str(i): _flat(r) for i, r in enumerate(result.grade_table)}
    return write_report(Path(work) / "report.html", title=f"unsew fit: {Path(case.path).name}",
                        summary=summary, metrics=table, figures=figs, notes=notes or None)


def _pct(x):
    return None if x is None else 100.0 * float(x)


def _flat(row) -> dict:
    if not isinstance(row, dict):
        return {"row": str(row)}
    return {k: (v if isinstance(v, (int, float, str)) or v is None else str(v)) for k, v in row.items()}


def _vertex_distance_mm(x, tv, tf, closest_points) -> np.ndarray:
    _, dist, _ = closest_points(np.asarray(x), np.asarray(tv), np.asarray(tf))
    return 1e3 * np.asarray(dist)
