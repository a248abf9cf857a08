"""``unsew fit CASE_DIR --out RESULT_DIR``: the two-phase inverse fit of a case folder."""

from __future__ import annotations

import argparse

from unsew.commands._output import check_out
from unsew.commands._help import FIT_SETTINGS, HelpFormatter, add_progress_switch, examples
from unsew.errors import InputError

__all__ = ["register", "run", "add_fit_options", "config_from_args"]


def add_fit_options(p: argparse.ArgumentParser, *, demo: bool = False) -> None:
    """Options shared by ``fit``, ``demo`` and ``batch`` (each maps to a FitConfig field);
    ``demo``: state the demo's defaults (unsew.fit.demo.DEMO_CONFIG) instead of FitConfig's."""
    d = DEMO_DEFAULTS if demo else FIT_DEFAULTS
    p.add_argument(
        "--config",
        metavar="FIT.yaml",
        help="fit configuration (YAML; `unsew fit --help` lists its settings); flags below override it "
        "(default: none, the built-in configuration)",
    )
    p.add_argument(
        "--iterations",
        type=int,
        metavar="N",
        help=f"iteration budget of phase two (default: {d['iterations']})",
    )
    p.add_argument(
        "--edge-length",
        type=float,
        metavar="M",
        help=f"panel mesh edge length [m] (default: {d['edge_length']})",
    )
    p.add_argument(
        "--material",
        help="starting material from the library (e.g. cotton, denim, silk), or auto: the library "
        "material whose drape of the graded pattern is closest to the target (default: auto)",
    )
    p.add_argument(
        "--steps", type=int, metavar="N", help=f"drape steps per iteration (default: {d['steps']})"
    )
    p.add_argument("--no-grading", action="store_true", help="ablation: skip phase one (linear grading)")
    p.add_argument("--plain-chamfer", action="store_true", help="ablation: Chamfer without curvature weights")
    p.add_argument("--no-seam-loss", action="store_true", help="ablation: drop the seam-length loss")
    p.add_argument("--no-material", action="store_true", help="ablation: keep the material fixed")
    p.add_argument("--device", help="torch device, cpu or cuda (default: cpu)")
    p.add_argument(
        "--time-limit",
        type=float,
        metavar="SECONDS",
        help="seconds the fit aims to end within (default 540): the material search, phase two and the "
        "mesh spread give way; 0: no limit",
    )
    p.add_argument("--no-report", action="store_true", help="skip report.html")
    add_progress_switch(p)


#: Defaults --help states (FitConfig's, and the demo's overrides); a test checks they agree.
FIT_DEFAULTS = {"iterations": 100, "edge_length": 0.025, "steps": 15}
DEMO_DEFAULTS = {"iterations": 80, "edge_length": 0.03, "steps": 12}


def config_from_args(args: argparse.Namespace, *, defaults: dict | None = None):
    """FitConfig from the flags over --config over ``defaults`` (e.g. the demo's) over FitConfig's."""
    from unsew.fit.config import load_config

    over = {
        "optimizer": {"iterations": args.iterations},
        "drape": {"edge_length": args.edge_length, "steps": args.steps},
        "material": {"start": args.material},
        "loss": {},
        "output": {},
        "device": args.device,
        "time_limit": args.time_limit,
        "base": getattr(args, "base", None),
    }
    if args.no_grading:
        over["grading"] = False
    if args.plain_chamfer:
        over["loss"]["curvature_weighted"] = False
    if args.no_seam_loss:
        over["loss"]["seam"] = 0.0
    if args.no_material:
        over["material"]["fit"] = []
    if args.no_report:
        over["output"]["report"] = False
    if getattr(args, "material_only", False):
        base = getattr(args, "base", None) or ""
        if not base.lower().endswith(".json"):
            raise InputError("--material-only fits the material of a pattern you give: pass --base P.json")
        over["grading"], over["area"] = False, "free"
        over["optimizer"]["pattern_start"] = 1 << 30  # the control points never move
        over["material"]["start_iteration"] = 0
    groups = {
        k: {f: v for f, v in g.items() if v is not None} for k, g in over.items() if isinstance(g, dict)
    }
    tops = {k: v for k, v in over.items() if not isinstance(v, dict) and v is not None}
    return load_config(args.config, defaults=defaults, **tops, **{k: g for k, g in groups.items() if g})


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "fit",
        help="recover the sewing pattern and material of a draped garment (case folder)",
        formatter_class=HelpFormatter,
        description="Recover the sewing pattern and material of a draped garment: phase one grades a base "
        "pattern to the target, phase two optimises pattern and material through the differentiable drape. "
        "Writes RESULT_DIR/ with pattern.json, pattern.svg, pattern.dxf, pattern.pdf, garment.obj, "
        "metrics.json, report.html (FORMATS.md).",
        epilog=examples(
            "unsew fit case/ --out result/",
            "unsew fit case/ --out result/ --material denim --iterations 40 --edge-length 0.03 --no-progress",
            "unsew fit case/ --out result/ --config fit.yaml",
        )
        + "\n\n"
        + FIT_SETTINGS,
    )
    p.add_argument(
        "case",
        metavar="CASE_DIR",
        help="case folder: target.obj, body.obj + skeleton.json or meta body, meta.json",
    )
    p.add_argument("--out", required=True, metavar="RESULT_DIR", help="result folder to create")
    p.add_argument(
        "--base",
        help="base pattern: a garment type or library base (unsew pattern new --help lists them) or a "
        "GarmentCode JSON (default: chosen by draping among the library's bases of meta.json's garment)",
    )
    p.add_argument(
        "--units", choices=["m", "cm", "mm"], help="units of the case's meshes (default: meta.json's, else m)"
    )
    p.add_argument("--up", help="the case files' up axis, e.g. z (default: meta.json's, else y)")
    p.add_argument("--front", help="the case files' front axis, e.g. -y (default: meta.json's, else z)")
    p.add_argument(
        "--resume",
        action="store_true",
        help="continue an interrupted fit from RESULT_DIR.partial/checkpoint.pt",
    )
    p.add_argument("--overwrite", action="store_true", help="replace an existing RESULT_DIR")
    p.add_argument(
        "--material-only",
        action="store_true",
        help="hold the --base P.json pattern as given (no grading, no area scaling, its control points "
        "never move) and fit only its material: how near this simulator can drape that pattern to the "
        "target (with the true pattern: the simulator's own floor)",
    )
    add_fit_options(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    import time
    from pathlib import Path

    started = time.perf_counter()  # the time limit counts from here: loading the case and its body included
    from unsew.fit.run import run_fit
    from unsew.body.case import load_case

    cfg = config_from_args(args)
    out = Path(args.out)
    check_out(out, overwrite=args.overwrite, folder=True)  # a bad --out fails now, not after the fit
    case = load_case(args.case, units=args.units, up=args.up, front=args.front)
    _check_inputs(case, cfg)
    run_fit(
        case, cfg, out, resume=args.resume, overwrite=args.overwrite, progress=not args.quiet, started=started
    )
    return 0


def _check_inputs(case, cfg) -> None:
    """Refuse, before the fit, a --base pattern far out of scale for the body
    (:mod:`unsew.commands._checks`); a target its body does not wear is refused by ``load_case``."""
    from pathlib import Path

    from unsew.commands._checks import check_pattern_scale

    base = getattr(cfg, "base", None)
    if base and Path(str(base)).suffix.lower() == ".json":
        from unsew.io.garmentcode import load_pattern

        if not Path(str(base)).is_file():
            raise InputError(
                f"--base {base}: no such pattern file (give a GarmentCode JSON or a garment type)"
            )
        check_pattern_scale(load_pattern(base), case.body)
