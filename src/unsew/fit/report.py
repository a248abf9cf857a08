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
from unsew.report.measure import seam_table
from unsew.sim.material import material_to_dict

__all__ = [
    "write_fit_report",
    "truth_over",
    "patterns_coincide",
    "loss_phases",
    "material_for_reading",
    "choices_made",
]


def write_fit_report(work: Path, result, case, metrics: dict, *, config: dict | None = None) -> Path:
    """Write report.html (figures embedded) into ``work``; figures go to ``work/figures``."""
    faces = np.asarray(result.mesh.faces)
    _, dist, _ = closest_points(
        np.asarray(result.x), np.asarray(case.target_verts), np.asarray(case.target_faces)
    )
    graded = result.graded_pattern
    same = graded is not None and patterns_coincide(graded, result.pattern)
    summary = _summary(result, case, metrics)
    top = max((max(v) for v in result.history.values() if v), default=0.0)
    # terms that stay at round-off level (e.g. the seam loss of a symmetric skirt) would stretch
    # the log axis over 30 decades: leave them out of the plot (they are in the metrics table)
    hist = {k: v for k, v in result.history.items() if v and max(v) > 1e-12 * top}
    phases = loss_phases(result, metrics)
    notes = _notes(result, metrics, summary, same)  # before the tables: the summary's order
    tables = _tables(result, metrics, summary)
    return _write(
        work,
        title=f"unsew fit: {Path(case.path).name}",
        summary=summary,
        metrics=tables,
        target=(np.asarray(case.target_verts), np.asarray(case.target_faces)),
        result=(np.asarray(result.x), faces),
        body=(np.asarray(case.body.verts), np.asarray(case.body.faces)),
        distance_mm=1e3 * np.asarray(dist),
        history=hist or None,
        phases=phases if hist else None,
        patterns=_patterns_shown(result, case, metrics, same),
        config=config,
        notes=notes or None,
        material=material_for_reading(material_to_dict(result.material)),
        choices=choices_made(result, metrics),
    )


def _patterns_shown(result, case, metrics: dict, same: bool) -> list:
    """(label, pattern) pairs the pattern figure overlays: base, graded (unless it is the base or
    the final one), the true pattern placed over the final one, final."""
    patterns = [("base", result.base_pattern)]
    graded = result.graded_pattern
    if graded is not None and graded is not result.base_pattern and not same:
        patterns.append(("graded", graded))
    if case.pattern_gt is not None:
        patterns.append(("true", truth_over(case.pattern_gt, result.pattern, metrics.get("pattern"))))
    patterns.append(("final = graded" if same else "final", result.pattern))
    return patterns


def _summary(result, case, metrics: dict) -> dict:
    """The report's summary: case, garment, distances, iterations, time, and the area errors of
    the final pattern when a true pattern was given."""
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
    if isinstance(pat, dict) and pat.get("area_error_rel_mean") is not None:
        summary["area_error_mean_pct"] = 100.0 * float(pat["area_error_rel_mean"])
    if isinstance(pat, dict) and pat.get("area_error_weighted_rel") is not None:
        summary["area_error_weighted_pct"] = 100.0 * float(pat["area_error_weighted_rel"])
        summary["area_error_total_pct"] = 100.0 * float(pat["area_error_total_rel"])
    return summary


def _notes(result, metrics: dict, summary: dict, same: bool) -> list[str]:
    """The report's notes, in order: unmatched panels, how far the final pattern moved, grading's
    warnings, the re-dress check (its verdict also into ``summary``), where the drapes come from,
    the mesh spread, the time limit's cuts."""
    notes = _unmatched_notes(metrics)
    moved = _moved_note(result.graded_pattern, result.pattern) if not same else None
    notes += [moved] if moved else []
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
        notes.append(
            f"mesh spread: the returned pattern dressed from scratch on {100 * ms['edge_lengths_m'][0]:.2f} "
            f"and {100 * ms['edge_lengths_m'][1]:.2f} cm meshes lies {cf} from the target, the result "
            f"{ms['result_mm']:.2f} mm; differences smaller than these are within how far the triangulation "
            "alone moves the folds"
        )
    tl = metrics.get("time_limit") or {}
    if tl.get("cuts"):
        notes.append(f"time limit {tl['limit_s']:.0f} s (--time-limit): " + "; ".join(tl["cuts"]))
    return notes


def _unmatched_notes(metrics: dict) -> list[str]:
    """A note per compared pattern with panels that have no counterpart in the other."""
    notes = []
    for key, what in (("pattern_base", "base"), ("pattern_graded", "graded"), ("pattern", "final")):
        un = (metrics.get(key) or {}).get("unmatched") or {}
        if un.get("estimated") or un.get("true"):
            notes.append(
                f"{what} pattern: panels without a counterpart, estimated {un.get('estimated') or []}, "
                f"true {un.get('true') or []} (left out of the per-panel means; the area-weighted "
                "area error counts each at its full area)"
            )
    return notes


def _moved_note(graded, final) -> str | None:
    """How far the final pattern's corners lie from the graded one's (same panels), or None."""
    if graded is None or set(graded.panels) != set(final.panels):
        return None
    moved = [
        np.abs(np.asarray(final.panels[n].vertices) - np.asarray(p.vertices)).max(initial=0.0)
        for n, p in graded.panels.items()
        if np.shape(p.vertices) == np.shape(final.panels[n].vertices)
    ]
    if not moved:
        return None
    return (
        f"final pattern: its corners lie at most {1e3 * max(moved):.1f} mm from the graded "
        "pattern's (in the pattern figure the graded outline shows only where they differ by more "
        "than the line width)"
    )


def _tables(result, metrics: dict, summary: dict) -> dict:
    """The report's tables: the returned pattern's seams first, then the metrics with the base
    and material choices in words (the base and the start material also into ``summary``), the
    contact's stiffness with its unit, and grading's rows."""
    tables = dict(metrics)
    if "base" in tables:
        summary["base"] = tables.pop("base")
    bases = tables.pop("base_choice", None)
    if bases:
        tables["base choice (each base dressed on a coarse mesh, Chamfer mm)"] = {
            r["base"]: _base_said(r) for r in bases
        }
    choice = tables.pop("material_choice", None)
    if choice:
        summary["start_material"] = choice[0]["material"]
        tables["material choice (pattern dressed in each from scratch, Chamfer mm)"] = {
            f"{r['material']} ({r.get('pattern', '?')})": round(float(r["chamfer_mm"]), 2) for r in choice
        }
    if isinstance(tables.get("contact"), dict) and "stiffness" in tables["contact"]:
        c = dict(tables["contact"])  # body repulsion kc of unsew.sim.drape.DrapeSettings
        c["stiffness [N/m⁴]"] = c.pop("stiffness")
        tables["contact"] = c
    if result.grade_table:
        tables["grading"] = {str(i): _flat(r) for i, r in enumerate(result.grade_table)}
    return {
        "seams of the returned pattern (sew-line lengths; codes as printed on the pieces)": seam_table(
            result.pattern
        ),
        **tables,
    }


def _base_said(r: dict) -> str:
    """A base choice row in words: its distance [mm], over the torso and graded where measured."""
    if r["chamfer_mm"] is None:
        return "failed"
    s = f"{float(r['chamfer_mm']):.2f}"
    if r.get("torso_mm") is not None:
        s += f", over the torso {float(r['torso_mm']):.2f}"
    if r.get("graded_mm") is not None:
        s += f", graded {float(r['graded_mm']):.2f}"
    return s


def patterns_coincide(a, b, *, tol: float = 1e-9) -> bool:
    """Whether patterns ``a`` and ``b`` have the same panels with the same corners (within
    ``tol`` [m]) and edges (a phase two that was not kept returns the graded pattern itself)."""
    if a is b:
        return True
    if set(a.panels) != set(b.panels):
        return False
    for n, pa in a.panels.items():
        pb = b.panels[n]
        if np.shape(pa.vertices) != np.shape(pb.vertices) or len(pa.edges) != len(pb.edges):
            return False
        if np.abs(np.asarray(pa.vertices) - np.asarray(pb.vertices)).max(initial=0.0) > tol:
            return False
        for ea, eb in zip(pa.edges, pb.edges):
            ca, cb = ea.curvature, eb.curvature
            if (ca is None) != (cb is None) or (
                ca is not None
                and (
                    ca.kind != cb.kind
                    or not np.allclose(
                        np.asarray(ca.params, float), np.asarray(cb.params, float), atol=tol, rtol=0
                    )
                )
            ):
                return False
    return True


def loss_phases(result, metrics: dict) -> list[tuple[int, str]]:
    """The phases the loss plot shades: the pattern alone from iteration 0; 'pattern + material'
    from the material's start only where the material did move there (a material held fixed,
    by the configuration or because the start came after the last iteration, shades nothing);
    each name says when phase two's result was not kept."""
    start = result.material_start_iteration
    moved = start is not None and start < result.iterations
    last, first = getattr(result, "gamma_last", None), getattr(result, "start_material", None)
    if moved and last is not None and first is not None and hasattr(first, "gamma"):
        g0 = np.asarray(first.gamma() if callable(first.gamma) else first.gamma, dtype=float)
        moved = not np.allclose(np.asarray(last, dtype=float), g0, rtol=1e-9, atol=0.0)
    rd = metrics.get("redress") or {}
    tail = " (not kept)" if rd and not rd.get("phase_two_kept", True) else ""
    return [(0, "pattern" + tail)] + ([(start, "pattern + material" + tail)] if moved else [])


#: How the report names the material's entries (material.json keeps its keys).
MATERIAL_WORDS = {
    "H00_N_per_m": "stretch stiffness along the panels' x (warp, u) [N/m]",
    "H11_N_per_m": "stretch stiffness along the panels' y (weft, v) [N/m]",
    "H01_N_per_m": "coupling of the two stretches (Poisson effect) [N/m]",
    "H22_N_per_m": "shear stiffness [N/m]",
    "bending_N_m": "bending stiffness [N·m]",
    "density_kg_per_m2": "mass per area [kg/m²]",
    "friction": "friction coefficient against the body [-]",
}


def material_for_reading(m: dict) -> dict:
    """The material's entries under the names a pattern maker reads (:data:`MATERIAL_WORDS`),
    the file's key kept in brackets for the symbol (H00 ... H22 of the membrane stiffness)."""
    out = {}
    for k, v in m.items():
        word = MATERIAL_WORDS.get(k)
        sym = k.split("_")[0]
        if word and sym.startswith("H"):
            word = f"{word[: word.rindex(' [')]} ({sym}) {word[word.rindex(' [') :].strip()}"
        out[word or k] = v
    return out


def choices_made(result, metrics: dict) -> list[str]:
    """'What was chosen and why': the base pattern, the fabric and whether phase two's pattern
    was kept, each with the figures that decided it (from metrics.json)."""
    out = []
    bases = metrics.get("base_choice") or []
    base = metrics.get("base") or getattr(result, "base_name", "") or "the given pattern"
    if bases:
        ok = [r for r in bases if r.get("chamfer_mm") is not None]
        rest = ", ".join(f"{r['base']} {float(r['chamfer_mm']):.2f} mm" for r in ok[1:4])
        out.append(
            f"Base pattern: {base}, whose coarse drape lay {float(ok[0]['chamfer_mm']):.2f} mm (Chamfer) "
            f"from the target" + (f", closer than {rest}" if rest else "") + "."
            if ok
            else f"Base pattern: {base} (no candidate could be draped)."
        )
    else:
        out.append(f"Base pattern: {base}, as given (--base or the configuration); no other base was tried.")
    choice = metrics.get("material_choice") or []
    mat_name = choice[0]["material"] if choice else None
    if choice:
        rest = ", ".join(f"{r['material']} {float(r['chamfer_mm']):.2f} mm" for r in choice[1:4])
        out.append(
            f"Fabric to start from: {mat_name}, whose drape lay {float(choice[0]['chamfer_mm']):.2f} mm from "
            "the target" + (f", closer than {rest}" if rest else "") + "."
        )
    else:
        start = getattr(result, "start_material", None)
        out.append(
            "Fabric to start from: as configured (material.start)"
            + (f", {start.name}" if getattr(start, "name", "") else "")
            + "; no other fabric was tried."
        )
    out.append(
        "Fabric returned: fitted in phase two."
        if result.material_fitted
        else "Fabric returned: the starting fabric (phase two's material was not kept or not fitted)."
    )
    rd = metrics.get("redress")
    if rd:
        out.append("Phase two: " + _redress_note(rd).split(": ", 1)[1] + ".")
    else:
        out.append("Phase two: its pattern is returned (no re-dress check was run).")
    return out


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

    pairs = {
        ng: row["estimated_panel"]
        for ng, row in ((matched or {}).get("panels") or {}).items()
        if isinstance(row, dict) and row.get("estimated_panel") in final.panels and ng in pattern_gt.panels
    }
    if not pairs:
        return pattern_gt
    taken = set(pairs.values())
    names = {ng: pairs.get(ng, f"{ng} (true)" if ng in taken else ng) for ng in pattern_gt.panels}
    panels = {}
    for ng, panel in pattern_gt.panels.items():
        shift = panel_centroid2d(final.panels[pairs[ng]]) - panel_centroid2d(panel) if ng in pairs else 0.0
        panels[names[ng]] = dataclasses.replace(
            panel, name=names[ng], vertices=np.asarray(panel.vertices) + shift
        )
    order = [names[n] for n in (pattern_gt.panel_order or pattern_gt.panels)]
    return dataclasses.replace(pattern_gt, panels=panels, panel_order=order, stitches=[])


def _flat(row) -> dict:
    """A grading row as table cells: numbers and words as they are, a list of numbers as one
    cell (the table prints it as "a, b, c"), nested entries under dotted keys, anything else as
    words."""
    if not isinstance(row, dict):
        return {"row": str(row)}
    out = {}
    for k, v in row.items():
        if isinstance(v, dict):
            for k2, v2 in _flat(v).items():
                out[f"{k}.{k2}"] = v2
        elif isinstance(v, (list, tuple)) and all(
            isinstance(x, (int, float)) and not isinstance(x, bool) for x in v
        ):
            out[k] = [round(float(x), 4) for x in v]
        elif isinstance(v, (list, tuple)):
            out[k] = "; ".join(str(x) for x in v)
        elif isinstance(v, (int, float, str)) or v is None:
            out[k] = v
        else:
            out[k] = str(v)
    return out


_DRAPE_WORDS = {
    "fresh": "its pattern dressed from scratch on the fit's mesh",
    "graded start": "the graded drape the material choice let settle",
    "phase two": "phase two's own drape, warm-started along the optimizer's path",
}


def _drapes_note(drapes: dict, warm_mm: float | None) -> str:
    """The report's line on where the result's and the graded drapes come from (metrics.json's
    ``drapes``; ``warm_mm``: a kept phase two's own drape's Chamfer [mm], surface_warm)."""
    line = (
        f"drapes: the result's is {_DRAPE_WORDS.get(drapes.get('result'), drapes.get('result'))}, the graded "
        f"pattern's is {_DRAPE_WORDS.get(drapes.get('graded'), drapes.get('graded'))}"
    )
    if warm_mm is not None:
        line += f"; phase two's own warm-started drape lay {warm_mm:.2f} mm from the target"
    return line


def _redress_note(rd: dict) -> str:
    """The report's line on the re-dress check (metrics.json's ``redress``)."""
    graded = "the graded pattern and its drape are returned (the final and graded patterns coincide)"
    if rd.get("refused"):
        return (
            "re-dress check: phase two's pattern cannot be meshed afresh or read back "
            f"({rd['refused']}); {graded}"
        )
    if rd.get("failed"):
        return f"re-dress check: phase two's pattern dressed from scratch failed ({rd['failed']}); {graded}"
    verdict = "phase two's pattern is returned" if rd["phase_two_kept"] else graded
    if rd.get("meshes", 1) == 3:
        means = (
            f"means {rd['fit_mean_mm']:.2f} against {rd['graded_mean_mm']:.2f} mm"
            if rd.get("fit_mean_mm") is not None and rd.get("graded_mean_mm") is not None
            else "no mean"
        )
        return (
            f"re-dress check on three meshes ({' / '.join(f'{100 * h:.2f}' for h in rd['edge_lengths_m'])} "
            f"cm edges): the fitted pattern dressed from scratch lies {mm_list(rd['fit_mm'])} mm from the "
            f"target, the graded one {mm_list(rd['graded_fresh_mm'])} mm ({means}); {verdict}"
        )
    return (
        f"re-dress check: the fitted pattern dressed from scratch lies {rd['fit_redressed_mm']:.2f} mm from "
        f"the target, the graded one {rd['graded_mm']:.2f} mm; {verdict}"
    )
