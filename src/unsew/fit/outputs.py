"""The result folder of a fit (FORMATS.md): pattern.json, pattern.svg, pattern.dxf, pattern.pdf (tiled
A4 pages at 1:1), garment.obj,
garment_rest.obj, material.json, metrics.json, config.yaml, report.html and its figures; and, an
addition FORMATS.md does not list (docs/ARCHITECTURE.md), the fit's starting points
pattern_base.json (the base pattern before grading) and pattern_graded.json (after grading;
absent when grading is off), GarmentCode JSON like pattern.json.

Everything is written into a work folder that is renamed onto the result folder only when all
files are complete, so a failed or interrupted run never leaves a folder that looks finished.
"""

from __future__ import annotations

import hashlib
import json
import os
import platform
from pathlib import Path

import numpy as np

from unsew import __version__
from unsew._memory import peak_rss_mb
from unsew.fit.config import config_to_dict
from unsew.fit.report import write_fit_report
from unsew.geometry.repair import triangle_areas
from unsew.grading.area import pattern_area
from unsew.io.dxf import write_dxf
from unsew.io.garmentcode import save_pattern
from unsew.io.mesh import write_obj
from unsew.io.pdf import write_pdf
from unsew.io.svg import write_svg
from unsew.meshing import write_rest_obj
from unsew.metrics.panels import pattern_metrics
from unsew.metrics.surface import surface_metrics
from unsew.pattern.seams import seam_changes_mm
from unsew.sim.material import material_to_dict

__all__ = [
    "write_result",
    "result_metrics",
    "fit_verdict",
    "FAR_MM",
    "pattern_errors",
    "file_sha256",
    "pattern_with_extras",
    "placed_where_draped",
    "BASE_PATTERN_FILE",
    "GRADED_PATTERN_FILE",
]

#: The starting points of the fit, saved beside pattern.json so their pattern errors can be
#: recomputed (``unsew eval``): unsew's base pattern before grading, and the graded pattern.
BASE_PATTERN_FILE = "pattern_base.json"
GRADED_PATTERN_FILE = "pattern_graded.json"


def file_sha256(path: str | os.PathLike) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def placed_where_draped(pattern, mesh, uv, x, body=None):
    """A copy of ``pattern`` with each panel moved within its own plane (its rotation and its
    distance along its normal kept) so that its placed mesh vertices' centroid lies over its
    draped ones' (the panel's translation [m]): the exported placement starts another simulator
    where the fit's drape hangs, not where the base was drafted before grading changed the panels.
    Only panels facing front or back move so (normal within
    :data:`unsew.body.placement.FACING_DEG` of the body's front axis: a bodice's, a skirt's, a
    trouser leg's): a sleeve, cuff or hood drapes round a limb or the head, its centroid inside
    it, and keeps the placement it was drafted with. A panel that hangs from an open labelled
    edge (:func:`unsew.dress.hanging_edges`) stays where the drape held those edges (all of them
    within :data:`unsew.dress.HELD_WITHIN`, at the median, as :func:`unsew.dress.held_anchors`
    tells a held drape); where it did not hold them, it moves up or down only, so that its edge
    lies at the height it drapes at: a simulator that holds such an edge where the file places
    it (unsew's drape, GarmentCode's) hangs the garment from there, not from where grading
    lifted it to start. Given the ``body``, the halves of a sleeve (panels
    :func:`unsew.body.placement.panel_roles` puts round an arm, facing front or back) are laid as
    another simulator sews them round the arm: each turned and moved as a whole onto its drape
    (the rigid fit of its placed vertices to its draped ones), then out along its normal, away
    from the upper arm's bone, until every draped vertex lies between it and the bone.

    mesh: the pattern's GarmentMesh (its ``uv_panel``, ``x_of_u``, ``edge_verts`` and
    ``panel_names``); uv: (Nu, 2) float panel-frame positions of its rest vertices [m]; x: (n_x, 3)
    float draped sewn positions [m] (numpy or torch); body: the wearer (a Body), or None. Returns
    the moved copy (a Pattern; translations [m])."""
    from unsew.body.placement import FACING_DEG, panel_roles
    from unsew.dress import HELD_WITHIN

    p = pattern.copy()
    uv = np.asarray(uv.detach().cpu() if hasattr(uv, "detach") else uv, np.float64)
    x = np.asarray(x.detach().cpu() if hasattr(x, "detach") else x, np.float64)
    on = np.asarray(mesh.uv_panel)
    draped = x[np.asarray(mesh.x_of_u)]
    drops = _hanging_drops(p, mesh, uv, draped)
    held = bool(drops) and np.median(np.abs(np.concatenate(list(drops.values())))) < HELD_WITHIN
    roles = panel_roles(p, body) if body is not None else {}
    for i, name in enumerate(mesh.panel_names):
        pan = p.panels[name]
        if name in drops:  # hangs from an open edge
            if not held:
                pan.translation = pan.translation + np.array([0.0, drops[name].mean(), 0.0])
            continue
        n = pan.rotation_matrix()[:, 2]
        if abs(n[2]) < np.cos(np.radians(FACING_DEG)):
            continue
        if roles.get(name, "").endswith("_sleeve"):
            _laid_round_the_arm(pan, uv[on == i], draped[on == i], body, roles[name].split("_")[0])
            continue
        placed = pan.to_world(uv[on == i])
        d = draped[on == i].mean(axis=0) - placed.mean(axis=0)
        pan.translation = pan.translation + d - (d @ n) * n
    return p


def _laid_round_the_arm(pan, uv, draped, body, side: str) -> None:
    """Place the sleeve half ``pan`` (in place) by the rigid fit of its rest vertices ``uv``
    (k, 2) [m] placed to where they drape, ``draped`` (k, 3) [m], then moved along its normal,
    away from the ``side`` (left/right) upper arm's bone of ``body``, to the outermost of them."""
    from scipy.spatial.transform import Rotation

    from unsew.pattern.model import matrix_to_euler_xyz

    placed = pan.to_world(uv)
    pc, dc = placed.mean(axis=0), draped.mean(axis=0)
    turn = Rotation.align_vectors(draped - dc, placed - pc)[0].as_matrix()
    R = turn @ pan.rotation_matrix()
    n = R[:, 2]
    sh, el = body.skeleton.position(f"{side}_shoulder"), body.skeleton.position(f"{side}_elbow")
    axis = (el - sh) / np.linalg.norm(el - sh)
    out = (dc - sh) - ((dc - sh) @ axis) * axis  # from the bone to the half's drape
    n_out = n if n @ out >= 0 else -n
    lift = float(((draped - dc) @ n_out).max())
    pan.rotation = matrix_to_euler_xyz(R)
    pan.translation = turn @ (pan.translation - pc) + dc + lift * n_out


def _hanging_drops(pattern, mesh, uv, draped) -> dict:
    """{panel: (k,) heights [m] its open labelled edges' vertices drape at over where ``pattern``
    places them} for each panel hanging from such an edge (:func:`unsew.dress.hanging_edges`);
    uv (Nu, 2) rest positions [m], draped (Nu, 3) their draped positions [m]."""
    from unsew.dress import hanging_edges

    hung = sorted(hanging_edges(pattern))
    out = {}
    for name in mesh.panel_names:
        idx = [np.asarray(mesh.edge_verts[key], np.int64) for key in hung if key[0] == name]
        if idx:
            idx = np.unique(np.concatenate(idx))
            out[name] = draped[idx, 1] - pattern.panels[name].to_world(uv[idx])[:, 1]
    return out


def pattern_with_extras(result, body=None) -> object:
    """The final pattern, placed where it drapes (:func:`placed_where_draped`), with unsew's
    additions under its ``unsew`` key: control points per panel,
    symmetry (pairs, mirror axes, effective K), the material and, when the fit's drapes did not use
    the default body contact (``contact: target``), that contact (``{"threshold_m",
    "stiffness_n_m4"}``, :func:`unsew.commands.drape.pattern_contact` reads it back)."""
    p = placed_where_draped(result.pattern, result.mesh, result.uv, result.x, body)
    params = result.params
    extras = dict(p.unsew)
    try:
        extras["control_points"] = params.controls.to_dict() if hasattr(params.controls, "to_dict") else None
    except Exception:  # pragma: no cover - serialisation of optional extras must not sink a fit
        extras["control_points"] = None
    sym = getattr(params, "symmetry", None)
    if sym is not None and hasattr(sym, "to_dict"):
        extras["symmetry"] = sym.to_dict()
    extras["material"] = material_to_dict(result.material)
    contact = getattr(result, "contact", None) or {}
    if contact.get("mode", "default") != "default":  # ``unsew drape`` of the pattern rests it as the fit did
        extras["contact"] = {
            "threshold_m": contact["threshold_mm"] * 1e-3,
            "stiffness_n_m4": contact["stiffness"],
        }
    p.unsew = {k: v for k, v in extras.items() if v is not None}
    return p


#: A result whose drape lies farther than this mean surface distance [mm] from its target is a
#: miss: its metrics.json says ``"ok": false`` and the command ends with a warning line.
FAR_MM = 20.0


def fit_verdict(surface: dict) -> dict:
    """``{"ok": bool, "miss": reason or None}`` of a result from its surface metrics (the
    :func:`unsew.metrics.surface.surface_metrics` dict of its drape against the target)."""
    cf = float(surface.get("chamfer_mm", float("nan")))
    if np.isfinite(cf) and cf <= FAR_MM:
        return {"ok": True, "miss": None}
    return {
        "ok": False,
        "miss": f"the fitted garment lies {cf:.1f} mm from its target on average "
        f"(over {FAR_MM:.0f} mm): its pattern is not the target's",
    }


def result_metrics(result, case, *, n_samples: int = 50_000) -> dict:
    """3D metrics of the final drape against the target and, if the case has a true pattern,
    the pattern metrics; plus the final loss terms and timings."""
    m = _surfaces(result, case, n_samples)
    if getattr(result, "drapes", None):
        m["drapes"] = result.drapes  # where the result's and the graded drapes come from: fresh or settled
    if case.pattern_gt is not None:
        m.update(pattern_errors(result, case.pattern_gt))
    m.update(fit_verdict(m["surface"]))
    # total panel areas [m^2] against the target's surface area (a drape barely stretches, so a
    # pattern that fits has about the target's area; config "area", unsew.grading.area)
    patterns = {"base": result.base_pattern, "graded": result.graded_pattern, "result": result.pattern}
    m["area_m2"] = {
        "target": float(triangle_areas(case.target_verts, case.target_faces).sum()),
        **{k: pattern_area(p) for k, p in patterns.items() if p is not None},
    }
    # how far apart stitched edges are in length (ease the base has left out): a pattern that sews
    m["seams"] = seam_changes_mm(patterns)
    h = result.history
    m["loss_final"] = {k: (v[-1] if v else None) for k, v in h.items()}
    m["loss_history"] = {k: [float(f"{x:.6g}") for x in v] for k, v in h.items()}  # per iteration
    m["iterations"] = result.iterations
    m["best_iteration"] = result.best_iteration
    m["material_fitted"] = result.material_fitted
    m.update(_stages(result))
    m["timings_s"] = result.timings
    if getattr(result, "time_limit", None):
        m["time_limit"] = result.time_limit  # the fit's time limit [s] and what gave way to it
    m["peak_memory_mb"] = peak_rss_mb()  # the process's peak resident memory so far [MB]
    if getattr(result, "memory_mb", None):
        m["peak_memory_stages_mb"] = result.memory_mb  # the peak so far at the end of each stage [MB]
    if result.drape_check is not None:
        m["drape_check"] = result.drape_check.as_dict()  # the result on its body: inside %, stretch, ...
    if getattr(case, "notes", None):
        m["input_notes"] = list(case.notes)  # what loading did to the inputs (e.g. the wearer rigged)
    if getattr(case, "target_repair", None):
        m["target_repair"] = case.target_repair  # what loading cleaned in the target (counts)
    return m


def _surfaces(result, case, n_samples: int) -> dict:
    """Surface metrics against the target of the result's drape ("surface") and, where the result
    has them, of the base's, the graded pattern's and phase two's own warm-started drape."""
    faces = np.asarray(result.mesh.faces)
    drapes = {
        "surface": (result.x, faces),
        "surface_base": (result.x_base, _faces_of(result, "base") if result.x_base is not None else None),
        "surface_graded": (result.x_graded, faces),
        "surface_warm": (getattr(result, "x_warm", None), faces),  # a kept phase two's own drape
    }
    return {
        key: surface_metrics(x, f, case.target_verts, case.target_faces, n_samples=n_samples)
        for key, (x, f) in drapes.items()
        if x is not None
    }


def _stages(result) -> dict:
    """What each stage decided, as metrics.json keys: the base and its choice, the material choice,
    convergence, the contact, phase two's start, the re-dress check and the mesh spread (each only
    when the result has it)."""
    m = {}
    if getattr(result, "base_name", ""):
        m["base"] = result.base_name  # the base pattern phase one started from
    if getattr(result, "base_choice", None):
        m["base_choice"] = result.base_choice  # base chosen by draping: candidates, best first
    if result.material_choice:
        m["material_choice"] = result.material_choice  # material: auto, best first
    m["converged"] = result.converged
    if getattr(result, "contact", None):
        m["contact"] = result.contact  # the body contact every drape of the fit used (unsew.fit.contact)
    if getattr(result, "rest", None):
        m["phase_two_start"] = result.rest  # steps the graded drape settled before phase two
    if result.redress is not None:
        m["redress"] = result.redress.as_dict()  # the re-dress check: phase two kept or not
    if result.mesh_spread is not None:
        m["mesh_spread"] = result.mesh_spread.as_dict()  # the returned pattern on two other meshes
    return m


def pattern_errors(result, pattern_gt) -> dict:
    """Pattern metrics (:func:`unsew.metrics.panels.pattern_metrics`) of the final, base and graded
    patterns against the true one, keyed ``pattern``, ``pattern_base``, ``pattern_graded`` (the
    last absent without grading). Panels without a counterpart (a waistband the base lacks) are
    listed under each key's ``unmatched``; a pattern that cannot be compared at all gets
    ``{"error": reason}`` under its key without sinking the others."""
    out = {}
    for key, pat in (
        ("pattern", result.pattern),
        ("pattern_base", result.base_pattern),
        ("pattern_graded", result.graded_pattern),
    ):
        if pat is None:
            continue
        try:
            out[key] = pattern_metrics(pat, pattern_gt)
        except Exception as exc:  # a metric must not sink a finished fit: report it
            out[key] = {"error": f"{type(exc).__name__}: {exc}"}
    return out


def _faces_of(result, which: str):
    mesh = result.base_mesh if which == "base" else None
    return np.asarray((mesh or result.mesh).faces)


def write_result(work: Path, result, case, cfg, *, report: bool = True, metrics: dict | None = None) -> dict:
    """Write every output file of a fit into the folder ``work`` (which the caller renames).
    Returns the metrics dict."""
    import yaml

    work = Path(work)
    work.mkdir(parents=True, exist_ok=True)
    pattern = pattern_with_extras(result, case.body)
    save_pattern(pattern, work / "pattern.json")
    save_pattern(result.base_pattern, work / BASE_PATTERN_FILE)
    if result.graded_pattern is not None:
        save_pattern(result.graded_pattern, work / GRADED_PATTERN_FILE)
    write_svg(pattern, work / "pattern.svg")
    write_dxf(pattern, work / "pattern.dxf")
    write_pdf(pattern, work / "pattern.pdf")
    mesh = result.mesh
    write_obj(
        work / "garment.obj",
        result.x,
        mesh.faces,
        uv=result.uv,
        faces_uv=mesh.faces_uv,
        header="unsew draped garment; vt = pattern coordinates [m]",
    )
    write_rest_obj(mesh, work / "garment_rest.obj")
    _write_json(work / "material.json", {"units": "SI", **material_to_dict(result.material)})
    if metrics is None:
        metrics = result_metrics(result, case)
    _write_json(work / "metrics.json", metrics)
    cfg_out = {
        "config": config_to_dict(cfg),
        "case": str(case.path),
        "inputs_sha256": {k: file_sha256(v) for k, v in case.files.items()},
        "unsew_version": __version__,
        "python": platform.python_version(),
    }
    (work / "config.yaml").write_text(yaml.safe_dump(cfg_out, sort_keys=False))
    if report:
        write_fit_report(work, result, case, metrics, config=cfg_out)
    return metrics


def _write_json(path: Path, obj) -> None:
    path.write_text(json.dumps(obj, indent=2, default=_json_default) + "\n")


def _json_default(o):
    if isinstance(o, (np.floating, np.integer)):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    if hasattr(o, "__dict__"):
        return {k: v for k, v in vars(o).items() if not k.startswith("_")}
    return str(o)
