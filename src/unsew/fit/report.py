"""The HTML report of a fit: this module gathers what a FitResult holds and hands it to
:func:`unsew.report.fit_report.write_fit_report` (loss curves with the phase marks, target and
result rendered front and side, the per-vertex distance heat map and its histogram, base /
graded / final / true patterns overlaid, the metrics tables, the config)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from unsew.fit.checks import mm_list
from unsew.metrics.surface import closest_points
from unsew.report.fit_report import write_fit_report as _write
from unsew.sim.material import material_to_dict

__all__ = ["write_fit_report", "truth_over"]


def write_fit_report(work: Path, result, case, metrics: dict, *, config: dict | None = None) -> Path:
    """Write report.html (figures embedded) into ``work``; figures go to ``work/figures``."""
    faces = np.asarray(result.mesh.faces)
    _, dist, _ = closest_points(np.asarray(result.x), np.asarray(case.target_verts), np.asarray(case.target_faces))
    patterns = [("base", result.base_pattern)]
    if result.graded_pattern is not None and result.graded_pattern is not result.base_pattern:
        patterns.append(("graded", result.graded_pattern))
    if case.pattern_gt is not None:
        patterns.append(("true", truth_over(case.pattern_gt, result.pattern, metrics.get("pattern"))))
    patterns.append(("final", result.pattern))
    s = metrics.get("surface", {})
    summary = {
        "case": Path(case.path).name,
        "garment": case.garment or "custom",
        "chamfer_mm": s.get("chamfer_mm"),
        "normal_error_deg": s.get("normal_error_deg"),
        "iterations": result.iterations,
        "time_s": result.timings.get("total_s"),
    }
    pat = metrics.get("pattern")
    notes = []
    if isinstance(pat, dict) and pat.get("area_error_rel_mean") is not None:
        summary["area_error_mean_pct"] = 100.0 * float(pat["area_error_rel_mean"])
    if isinstance(pat, dict) and pat.get("area_error_weighted_rel") is not None:
        summary["area_error_weighted_pct"] = 100.0 * float(pat["area_error_weighted_rel"])
        summary["area_error_total_pct"] = 100.0 * float(pat["area_error_total_rel"])
    for key, what in (("pattern_base", "base"), ("pattern_graded", "graded"), ("pattern", "final")):
        un = (metrics.get(key) or {}).get("unmatched") or {}
        if un.get("estimated") or un.get("true"):
            notes.append(f"{what} pattern: panels without a counterpart, estimated {un.get('estimated') or []}, "
                         f"true {un.get('true') or []} (left out of the per-panel means; the area-weighted "
                         "area error counts each at its full area)")
    for row in result.grade_table or []:
        for w in (row.get("warnings") or []) if isinstance(row, dict) else []:
            notes.append(f"grading: {w}")
    rd = metrics.get("redress")
    if rd:
        summary["returned"] = "phase two's pattern" if rd["phase_two_kept"] else "the graded pattern"
        notes.append(_redress_note(rd))
    if metrics.get("drapes"):
        notes.append(_drapes_note(metrics["drapes"], (metrics.get("surface_warm") or {}).get("chamfer_mm")))
    ms = metrics.get("mesh_spread")
    if ms:
        cf = " / ".join("failed" if v is None else f"{v:.2f} mm" for v in ms["chamfer_mm"])
        notes.append(f"mesh spread: the returned pattern dressed from scratch on {100 * ms['edge_lengths_m'][0]:.2f} "
                     f"and {100 * ms['edge_lengths_m'][1]:.2f} cm meshes lies {cf} from the target, the result "
                     f"{ms['result_mm']:.2f} mm; differences smaller than these are within how far the triangulation "
                     "alone moves the folds")
    tl = metrics.get("time_limit") or {}
    if tl.get("cuts"):
        notes.append(f"time limit {tl['limit_s']:.0f} s (--time-limit): " + "; ".join(tl["cuts"]))
    top = max((max(v) for v in result.history.values() if v), default=0.0)
    # terms that stay at round-off level (e.g. the seam loss of a symmetric skirt) would stretch
    # the log axis over 30 decades: leave them out of the plot (they are in the metrics table)
    hist = {k: v for k, v in result.history.items() if v and max(v) > 1e-12 * top}
    start = result.material_start_iteration
    phases = [(0, "pattern")] + ([(start, "pattern + material")] if start is not None and start < result.iterations else [])
    tables = dict(metrics)
    if "base" in tables:
        summary["base"] = tables.pop("base")
    bases = tables.pop("base_choice", None)
    if bases:
        def said(r):
            if r["chamfer_mm"] is None:
                return "failed"
            s = f"{float(r['chamfer_mm']):.2f}"
            if r.get("torso_mm") is not None:
                s += f", over the torso {float(r['torso_mm']):.2f}"
            if r.get("graded_mm") is not None:
                s += f", graded {float(r['graded_mm']):.2f}"
            return s

        tables["base choice (each base dressed on a coarse mesh, Chamfer mm)"] = {r["base"]: said(r) for r in bases}
    choice = tables.pop("material_choice", None)
    if choice:
        summary["start_material"] = choice[0]["material"]
        tables["material choice (pattern dressed in each from scratch, Chamfer mm)"] = {
            f"{r['material']} ({r.get('pattern', '?')})": round(float(r["chamfer_mm"]), 2) for r in choice}
    if result.grade_table:
        tables["grading"] = {str(i): _flat(r) for i, r in enumerate(result.grade_table)}
    return _write(
        work, title=f"unsew fit: {Path(case.path).name}", summary=summary, metrics=tables,
        target=(np.asarray(case.target_verts), np.asarray(case.target_faces)), result=(np.asarray(result.x), faces),
        body=(np.asarray(case.body.verts), np.asarray(case.body.faces)), distance_mm=1e3 * np.asarray(dist),
        history=hist or None, phases=phases if hist else None, patterns=patterns, config=config, notes=notes or None,
        material=material_to_dict(result.material),
    )


def truth_over(pattern_gt, final, matched: dict | None):
    """The true pattern as the report draws it over the final one: each true panel matched to a
    final panel (``matched``: metrics.json's ``pattern``, whose ``panels`` map a true name to its
    ``estimated_panel``) takes that panel's name, so both share a cell of the figure and a column
    of the measurements, and is moved in its own frame so its area centroid lies on the final
    panel's. Unmatched true panels keep their names (with " (true)" added where a final panel's
    name is taken); without a matching, ``pattern_gt`` as is.

    pattern_gt, final: :class:`unsew.pattern.model.Pattern` (vertices [m]); returns a new Pattern
    (no stitches: it is drawn and measured, never sewn)."""
    import dataclasses

    from unsew.metrics.panels import panel_centroid2d

    pairs = {ng: row["estimated_panel"] for ng, row in ((matched or {}).get("panels") or {}).items()
             if isinstance(row, dict) and row.get("estimated_panel") in final.panels and ng in pattern_gt.panels}
    if not pairs:
        return pattern_gt
    taken = set(pairs.values())
    names = {ng: pairs.get(ng, f"{ng} (true)" if ng in taken else ng) for ng in pattern_gt.panels}
    panels = {}
    for ng, panel in pattern_gt.panels.items():
        shift = panel_centroid2d(final.panels[pairs[ng]]) - panel_centroid2d(panel) if ng in pairs else 0.0
        panels[names[ng]] = dataclasses.replace(panel, name=names[ng], vertices=np.asarray(panel.vertices) + shift)
    order = [names[n] for n in (pattern_gt.panel_order or pattern_gt.panels)]
    return dataclasses.replace(pattern_gt, panels=panels, panel_order=order, stitches=[])


def _flat(row) -> dict:
    if not isinstance(row, dict):
        return {"row": str(row)}
    return {k: (v if isinstance(v, (int, float, str)) or v is None else str(v)) for k, v in row.items()}


_DRAPE_WORDS = {"fresh": "its pattern dressed from scratch on the fit's mesh",
                "graded start": "the graded drape the material choice let settle",
                "phase two": "phase two's own drape, warm-started along the optimizer's path"}


def _drapes_note(drapes: dict, warm_mm: float | None) -> str:
    """The report's line on where the result's and the graded drapes come from (metrics.json's
    ``drapes``; ``warm_mm``: a kept phase two's own drape's Chamfer [mm], surface_warm)."""
    line = (f"drapes: the result's is {_DRAPE_WORDS.get(drapes.get('result'), drapes.get('result'))}, the graded "
            f"pattern's is {_DRAPE_WORDS.get(drapes.get('graded'), drapes.get('graded'))}")
    if warm_mm is not None:
        line += f"; phase two's own warm-started drape lay {warm_mm:.2f} mm from the target"
    return line


def _redress_note(rd: dict) -> str:
    """The report's line on the re-dress check (metrics.json's ``redress``)."""
    graded = "the graded pattern and its drape are returned (the final and graded patterns coincide)"
    if rd.get("refused"):
        return f"re-dress check: phase two's pattern cannot be meshed afresh or read back ({rd['refused']}); {graded}"
    if rd.get("failed"):
        return f"re-dress check: phase two's pattern dressed from scratch failed ({rd['failed']}); {graded}"
    verdict = "phase two's pattern is returned" if rd["phase_two_kept"] else graded
    if rd.get("meshes", 1) == 3:
        means = (f"means {rd['fit_mean_mm']:.2f} against {rd['graded_mean_mm']:.2f} mm"
                 if rd.get("fit_mean_mm") is not None and rd.get("graded_mean_mm") is not None else "no mean")
        return (f"re-dress check on three meshes ({' / '.join(f'{100 * h:.2f}' for h in rd['edge_lengths_m'])} cm "
                f"edges): the fitted pattern dressed from scratch lies {mm_list(rd['fit_mm'])} mm from the target, the "
                f"graded one {mm_list(rd['graded_fresh_mm'])} mm ({means}); {verdict}")
    return (f"re-dress check: the fitted pattern dressed from scratch lies {rd['fit_redressed_mm']:.2f} mm from the "
            f"target, the graded one {rd['graded_mm']:.2f} mm; {verdict}")
