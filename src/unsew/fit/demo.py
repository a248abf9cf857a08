"""The embedded default job (``unsew demo``): make a t-shirt target with known truth by draping,
with our simulator, a t-shirt whose proportions and material differ from the base, fit it from the
base t-shirt, print the pattern and 3D metrics, and drape the fitted pattern on another body.

Everything it needs ships with unsew (the default body is embedded; no download, no anny).
"""

from __future__ import annotations

import json
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from unsew.body.body import default_body
from unsew.body.case import load_case
from unsew.dress import DRESS_SETTINGS, dress
from unsew.fit.config import load_config
from unsew.fit.run import run_fit
from unsew.fit.synthetic import Alteration, make_truth_case as _make
from unsew.io.mesh import write_obj
from unsew.report.render import Layout, render_views

__all__ = ["DemoTruth", "DEMO_TRUTH", "DEMO_CONFIG", "make_truth_case", "run_demo", "other_body"]


@dataclass(frozen=True)
class DemoTruth:
    """How the demo's true t-shirt differs from the base t-shirt.

    hem_length: the hem moved down by this much [m]; hem_girth: the hem widened by this
    fraction [-]; sleeve_length: the sleeve hems moved out by this much [m]; material: the true
    fabric (library name), different from the fit's starting material.
    """

    hem_length: float = 0.06
    hem_girth: float = 0.06
    sleeve_length: float = 0.03
    material: str = "jersey"


DEMO_TRUTH = DemoTruth()

#: The demo's fit settings (under --config and flags): a 3 cm mesh and a budget that finishes the
#: whole demo in well under five minutes on two cores.
DEMO_CONFIG = {
    "drape": {"edge_length": 0.03, "steps": 12},
    "optimizer": {"iterations": 80},
    "material": {"start_iteration": 20},
}


def other_body():
    """A second wearer for the retargeting step: the default body 8% wider and deeper."""
    return default_body().transformed(scale=np.array([1.08, 1.0, 1.08]))


def make_truth_case(case_dir: Path, *, truth: DemoTruth = DEMO_TRUTH, settings=None, progress=None) -> Path:
    """Write the demo's case folder (FORMATS.md): the true t-shirt draped on the default body,
    with pattern_gt.json. ``settings``: DrapeSettings of the target's drape (default: FitConfig's
    on a 3 cm mesh, see :func:`unsew.fit.synthetic.make_truth_case`). Returns the folder."""
    alt = Alteration(
        {"hem": (truth.hem_length, truth.hem_girth), "sleeves": (truth.sleeve_length, 0.0)}, truth.material
    )
    return _make(case_dir, garment="tshirt", alteration=alt, settings=settings, progress=progress)


def run_demo(out: Path, *, cfg=None, progress: bool = True, log=None) -> dict:
    """Run the whole demo into ``out`` (case/, fit/, retarget/). Returns a summary dict."""
    log = log or (lambda s: print(s, file=sys.stderr))
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    cfg = cfg or load_config(defaults=DEMO_CONFIG)
    t0 = time.perf_counter()
    log(
        f"[1/3] making the target: a t-shirt {DEMO_TRUTH.hem_length * 100:.0f} cm longer, hem "
        f"{DEMO_TRUTH.hem_girth * 100:.0f}% wider, sleeves {DEMO_TRUTH.sleeve_length * 100:.0f} cm longer, "
        f"in {DEMO_TRUTH.material} (the fit starts from the base t-shirt"
        + (
            ", in the library fabric whose drape is closest)"
            if cfg.material.start == "auto"
            else f" in {cfg.material.start})"
        )
    )
    case_dir = make_truth_case(out / "case", settings=cfg.drape)
    t_case = time.perf_counter() - t0
    log("[2/3] fitting the target from the base t-shirt")
    case = load_case(case_dir)
    result, metrics = run_fit(case, cfg, out / "fit", overwrite=True, progress=progress, log=log)
    log("[3/3] retargeting the fitted pattern to another body (8% wider and deeper)")
    body2 = other_body()
    d2 = dress(
        result.pattern,
        body2,
        material=result.material,
        settings=DRESS_SETTINGS.replace(edge_length=cfg.drape.edge_length),
    )
    (out / "retarget").mkdir(exist_ok=True)
    write_obj(
        out / "retarget" / "garment.obj",
        d2.x.numpy(),
        d2.mesh.faces,
        uv=d2.mesh.uv,
        faces_uv=d2.mesh.faces_uv,
        header="fitted pattern draped on another body",
    )
    write_obj(out / "retarget" / "body.obj", body2.verts, body2.faces)
    try:
        render_views(
            out / "retarget" / "retarget.png",
            d2.x.numpy(),
            d2.mesh.faces,
            body=(body2.verts, body2.faces),
            layout=Layout(views=("front", "side"), title="fitted t-shirt on another body"),
        )
    except Exception as exc:  # a picture must not sink the demo
        log(f"(retarget picture skipped: {exc})")
    summary = _summary(metrics, time.perf_counter() - t0, t_case)
    print(_table(summary))
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    log(f"results in {out}/ (open {out / 'fit' / 'report.html'})")
    return summary


def _summary(metrics: dict, total_s: float, case_s: float) -> dict:
    s, sb = metrics.get("surface", {}), metrics.get("surface_base", {})
    sg = metrics.get("surface_graded", {})
    pat, patb = metrics.get("pattern", {}) or {}, metrics.get("pattern_base", {}) or {}
    patg = metrics.get("pattern_graded", {}) or {}
    return {
        "chamfer_mm": {
            "base": sb.get("chamfer_mm"),
            "graded": sg.get("chamfer_mm"),
            "final": s.get("chamfer_mm"),
        },
        "normal_error_deg": {
            "base": sb.get("normal_error_deg"),
            "graded": sg.get("normal_error_deg"),
            "final": s.get("normal_error_deg"),
        },
        "area_error_mean": {
            "base": patb.get("area_error_rel_mean"),
            "graded": patg.get("area_error_rel_mean"),
            "final": pat.get("area_error_rel_mean"),
        },
        "turning_distance_mean": {
            "base": patb.get("turning_distance_mean"),
            "graded": patg.get("turning_distance_mean"),
            "final": pat.get("turning_distance_mean"),
        },
        "time_s": {"target": case_s, "total": total_s},
    }


def _fmt(v, pct=False):
    if v is None:
        return "-"
    return f"{100 * v:.2f}%" if pct else f"{v:.3f}"


def _table(s: dict) -> str:
    rows = [
        ("Chamfer [mm]", s["chamfer_mm"], False),
        ("normal error [deg]", s["normal_error_deg"], False),
        ("panel area error", s["area_error_mean"], True),
        ("turning distance", s["turning_distance_mean"], False),
    ]
    lines = [f"{'metric':<22}{'base':>12}{'graded':>12}{'final':>12}", "-" * 58]
    for name, d, pct in rows:
        lines.append(
            f"{name:<22}{_fmt(d.get('base'), pct):>12}{_fmt(d.get('graded'), pct):>12}"
            f"{_fmt(d.get('final'), pct):>12}"
        )
    lines.append(
        f"time: {s['time_s']['total']:.0f} s in all ({s['time_s']['target']:.0f} s to make the target)"
    )
    return "\n".join(lines)
