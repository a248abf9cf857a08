"""The paper's tables on our known-truth benchmark: one command per table, resumable.

    OMP_WAIT_POLICY=PASSIVE .venv/bin/python benchmarks/run.py --table accuracy [--quick]
        [--cases bench-out/paper/cases] [--out bench-out/paper] [--iterations 100] [--edge-length 0.025]

Tables (``--table``, repeatable or ``all``):

- ``accuracy`` (paper Table 2): per garment type, mean over its cases of the Chamfer distance
  [mm] and mean normal angle error [deg] (3D), turning-function distance [rad] and mean relative
  panel area error [%] (2D), for the base pattern, the graded pattern (phase one) and the final fit.
- ``ablation`` (paper Table 3): the full method against no curvature weighting, no seam loss,
  no material optimization and no grading (FitConfig switches), on the same cases.
- ``speed`` (paper Table 1): benchmarks/bench_sim.py's drape timings (1 and 20 steps, forward
  and reverse, loop vs static assembly) for 1K-3K vertex t-shirts, then the end-to-end time of
  every fit found under --out and its split by phase (metrics.json timings_s).
- ``material`` (paper 4.3, Fig. 10): one skirt pattern draped with two bending stiffnesses, and
  with two stretch stiffnesses; both fitted from cotton. Reports the area error between the two
  recovered patterns (must be <= 2%) and whether the recovered values come out in the right order.
- ``sensitivity``: one target fitted from the base pattern scaled by 0.9, 1.0 and 1.1 (the scaled
  base is a GarmentCode JSON passed as cfg.base); the spread of the final metrics.

``--set KEY=VALUE`` (repeatable) overrides a FitConfig option for every fit of the run (give it
its own ``--out``); the table header names the overrides.

``--quick`` keeps one case per garment type, the one with the fewest target vertices (ablation
and sensitivity: the smallest case overall). Cases missing under --cases are generated first
(benchmarks/make_cases.py). Every fit writes a result folder (FORMATS.md) under
``--out/results/<variant>/<case>``; a finished one (metrics.json present) is not redone and an
interrupted one resumes from its checkpoint. Beside each result, ``<case>.bench.json`` holds what
metrics.json lacks (the graded pattern's 2D metrics, wall time, load average). Tables are
printed and also written as Markdown to ``--out/tables/<table>[_quick].md``.

Timings are wall-clock on whatever machine runs this; the load average is printed with them.
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import numpy as np  # noqa: E402

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))  # make_cases beside this file

GARMENTS = ["tshirt", "dress", "pants", "shorts", "skirt"]

#: Ablation variants: name -> FitConfig overrides (paper Table 3 rows, plus no grading).
ABLATIONS = {
    "full": {},
    "no_curvature": {"loss": {"curvature_weighted": False}},
    "no_seam": {"loss": {"seam": 0.0}},
    "no_material": {"material": {"fit": []}},
    "no_grading": {"grading": False},
}

TABLES = ["accuracy", "ablation", "speed", "material", "sensitivity"]


# -- running fits ------------------------------------------------------------------------------


def _loadavg() -> float:
    try:
        return float(os.getloadavg()[0])
    except OSError:  # pragma: no cover
        return float("nan")


def n_verts(case_dir: Path) -> int:
    """Vertices of a case's target.obj."""
    with open(Path(case_dir) / "target.obj") as fh:
        return sum(1 for line in fh if line.startswith("v "))


#: Set by --retry-failed: refit cases whose fit raised before (default for fit_case).
RETRY_FAILED = False


def fit_case(case_dir: Path, out: Path, cfg, *, log=print, retry_failed: bool | None = None) -> dict:
    """Fit ``case_dir`` into the result folder ``out`` unless it is finished already.

    Returns a record: metrics (metrics.json), material (material.json), bench (the sidecar:
    pattern_graded, wall_s, load), out. An interrupted fit (out.partial with a checkpoint) resumes.
    A fit that raises is recorded (metrics None, bench["error"]) and skipped on reruns unless
    ``retry_failed``.
    """
    from unsew.fit.run import partial_dir, run_fit
    from unsew.body.case import load_case

    out = Path(out)
    side = out.with_name(out.name + ".bench.json")
    retry_failed = RETRY_FAILED if retry_failed is None else retry_failed
    failed = json.loads(side.read_text()).get("error") if side.is_file() else None
    if failed and not (out / "metrics.json").is_file() and not retry_failed:
        log(f"  {case_dir.name}: FAILED before ({failed}); --retry-failed to try again")
        return {"out": out, "metrics": None, "material": {}, "bench": {"error": failed}}
    if not (out / "metrics.json").is_file():
        case = load_case(case_dir)
        resume = (partial_dir(out) / "checkpoint.pt").is_file() and not failed
        log(f"fit {case_dir.name} -> {out} ({'resuming' if resume else 'starting'}, load {_loadavg():.1f})")
        load0 = _loadavg()
        t = time.perf_counter()
        try:
            result, _ = run_fit(
                case, cfg, out, resume=resume, overwrite=True, progress=False, log=lambda s: None
            )
        except Exception as exc:  # a failed fit is a row of the table, not the end of the run
            return _failed(case_dir, out, exc, (time.perf_counter() - t, load0), log)
        wall = time.perf_counter() - t
        graded = _graded_metrics(case, result)
        side.write_text(
            json.dumps(
                {
                    "pattern_graded": graded,
                    "wall_s": wall,
                    "load_start": load0,
                    "unsew_commit": git_version(),
                    "load_end": _loadavg(),
                    "resumed": resume,
                },
                indent=2,
            )
        )
    rec = {
        "out": out,
        "metrics": json.loads((out / "metrics.json").read_text()),
        "material": json.loads((out / "material.json").read_text())
        if (out / "material.json").is_file()
        else {},
        "bench": json.loads(side.read_text()) if side.is_file() else {},
    }
    _log_record(case_dir, rec, log)
    return rec


def _failed(case_dir: Path, out: Path, exc: Exception, timing, log) -> dict:
    """Record a fit that raised in its sidecar (timing = (wall s, load at the start)) and return
    its record (metrics None)."""
    side = out.with_name(out.name + ".bench.json")
    err = f"{type(exc).__name__}: {exc}".splitlines()[0]
    side.parent.mkdir(parents=True, exist_ok=True)
    side.write_text(
        json.dumps(
            {"error": err, "wall_s": timing[0], "load_start": timing[1], "unsew_commit": git_version()},
            indent=2,
        )
    )
    log(f"  {case_dir.name}: FAILED ({err})")
    return {"out": out, "metrics": None, "material": {}, "bench": {"error": err}}


def _graded_metrics(case, result) -> dict | None:
    """The graded pattern's 2D metrics against the case's true pattern (None without either;
    {"error": reason} when they cannot be compared)."""
    if case.pattern_gt is None or result.graded_pattern is None:
        return None
    from unsew.metrics.panels import pattern_metrics

    try:
        return pattern_metrics(result.graded_pattern, case.pattern_gt)
    except Exception as exc:  # unmatched panels: report, keep the table going
        return {"error": str(exc)}


def _log_record(case_dir: Path, rec: dict, log) -> None:
    """One line: the fit's Chamfer [mm], normal error [deg] and area error [%]."""
    s = rec["metrics"]["surface"]
    p = rec["metrics"].get("pattern") or {}
    p = p if "error" not in p else {}
    log(
        f"  {case_dir.name}: Chamfer {s['chamfer_mm']:.2f} mm, normal {s['normal_error_deg']:.1f} deg, "
        f"area error {100 * p.get('area_error_rel_mean', float('nan')):.2f} %"
    )


def yaml_value(text: str):
    """A --set value parsed as YAML (numbers, booleans, lists), else the plain string."""
    import yaml

    try:
        return yaml.safe_load(text)
    except yaml.YAMLError:
        return text


def apply_sets(cfg, items):
    """``cfg`` with the ``--set KEY=VALUE`` overrides in ``items`` applied (checked by
    load_config); exits with a one-line reason on a malformed or unknown override."""
    from unsew.errors import InputError
    from unsew.fit.config import config_to_dict, load_config

    sets = {}
    for item in items or ():
        key, sep, val = item.partition("=")
        if not sep:
            sys.exit(f"--set {item!r}: expected KEY=VALUE")
        sets[key.strip()] = yaml_value(val)
    if not sets:
        return cfg
    try:
        return load_config(defaults=config_to_dict(cfg) | sets)
    except InputError as exc:
        sys.exit(f"--set: {exc}")


def base_config(args, **changes):
    from unsew.fit.config import config_to_dict, load_config

    cfg = load_config(
        drape={"edge_length": args.edge_length},
        optimizer={"iterations": args.iterations},
        output={"report": not args.no_report},
    )
    cfg = apply_sets(cfg, getattr(args, "set", None))
    return load_config(defaults=config_to_dict(cfg), **changes) if changes else cfg


# -- cases -------------------------------------------------------------------------------------


def ensure_cases(args) -> dict[str, list[Path]]:
    """Generate missing cases; garment -> its case folders (sorted by name)."""
    import make_cases

    cases_dir = Path(args.cases)
    out: dict[str, list[Path]] = {}
    for g in args.garments:
        out[g] = [
            make_cases.make_case(cases_dir, g, i, seed=args.seed, edge_length=args.case_edge_length)
            for i in range(args.per_type)
        ]
    return out


def smallest(cases: list[Path]) -> Path:
    return min(cases, key=lambda d: (n_verts(d), d.name))


def pick_cases(args, all_cases: dict[str, list[Path]]) -> dict[str, list[Path]]:
    if args.quick:
        return {g: [smallest(cs)] for g, cs in all_cases.items()}
    return all_cases


# -- formatting ---------------------------------------------------------------------------------


def _fmt(v, f):
    if v is None or (isinstance(v, float) and not np.isfinite(v)):
        return "-"
    return format(v, f)


def md_table(heads: list[str], rows: list[list], fmts: list[str]) -> str:
    lines = ["| " + " | ".join(heads) + " |", "|" + "|".join("---" for _ in heads) + "|"]
    for r in rows:
        lines.append("| " + " | ".join(_fmt(v, f) for v, f in zip(r, fmts)) + " |")
    return "\n".join(lines)


def _mean(xs):
    xs = [x for x in xs if x is not None and np.isfinite(x)]
    return float(np.mean(xs)) if xs else None


def _pm(d, key, scale=1.0):
    if not d or "error" in d or d.get(key) is None:
        return None
    return scale * d[key]


def git_version() -> str:
    """The checkout's commit (short hash, '+dirty' when tracked files under src/ differ)."""
    root = HERE.parent
    try:
        rev = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], cwd=root, capture_output=True, text=True, timeout=10
        ).stdout.strip()
        dirty = subprocess.run(
            ["git", "status", "--porcelain", "--untracked-files=no", "src"],
            cwd=root,
            capture_output=True,
            text=True,
            timeout=10,
        ).stdout.strip()
        return (rev or "?") + ("+dirty" if dirty else "")
    except (OSError, subprocess.SubprocessError):
        return "?"


def header(args, what: str) -> str:
    return (
        f"{what}: {datetime.datetime.now().isoformat(timespec='minutes')}, unsew at {git_version()}, "
        f"{platform.node()} "
        f"({os.cpu_count()} cores, load {_loadavg():.1f}), python {platform.python_version()}, "
        f"fit edge {args.edge_length} m, {args.iterations} iterations max, "
        f"{'quick' if args.quick else 'full'} mode"
        + (f", config overrides {' '.join(args.set)}" if getattr(args, "set", None) else "")
    )


def emit(args, name: str, text: str) -> None:
    print(text, flush=True)
    d = Path(args.out) / "tables"
    d.mkdir(parents=True, exist_ok=True)
    (d / f"{name}{'_quick' if args.quick else ''}.md").write_text(text + "\n")


# -- tables -------------------------------------------------------------------------------------


def _stage_values(rec) -> dict:
    if rec["metrics"] is None:  # failed fit
        return {k: (None, None, None, None) for k in ("base", "graded", "fit")}
    m, b = rec["metrics"], rec["bench"]
    sb, sg, s = m.get("surface_base") or {}, m.get("surface_graded") or {}, m["surface"]
    pb, pg, p = m.get("pattern_base"), b.get("pattern_graded"), m.get("pattern")
    return {
        "base": (
            sb.get("chamfer_mm"),
            sb.get("normal_error_deg"),
            _pm(pb, "turning_distance_mean"),
            _pm(pb, "area_error_rel_mean", 100),
        ),
        "graded": (
            sg.get("chamfer_mm"),
            sg.get("normal_error_deg"),
            _pm(pg, "turning_distance_mean"),
            _pm(pg, "area_error_rel_mean", 100),
        ),
        "fit": (
            s.get("chamfer_mm"),
            s.get("normal_error_deg"),
            _pm(p, "turning_distance_mean"),
            _pm(p, "area_error_rel_mean", 100),
        ),
    }


def _per_case_table(recs: list[dict]) -> str:
    """The accuracy table's per-case rows: Chamfer, normal and area errors per stage, turning,
    iterations, fit time and any failure."""
    return md_table(
        [
            "case",
            "body",
            "verts",
            "CF base",
            "CF graded",
            "CF fit",
            "N base",
            "N fit",
            "A base %",
            "A graded %",
            "A fit %",
            "turn fit",
            "iters",
            "fit s",
            "failure",
        ],
        [
            [
                r["case"],
                r["body"],
                r["verts"],
                *(_stage_values(r)[k][0] for k in ("base", "graded", "fit")),
                _stage_values(r)["base"][1],
                _stage_values(r)["fit"][1],
                *(_stage_values(r)[k][3] for k in ("base", "graded", "fit")),
                _stage_values(r)["fit"][2],
                (r["metrics"] or {}).get("iterations"),
                (r["metrics"] or {}).get("timings_s", {}).get("total_s"),
                r["bench"].get("error", ""),
            ]
            for r in recs
        ],
        ["s", "s", "d", ".2f", ".2f", ".2f", ".1f", ".1f", ".2f", ".2f", ".2f", ".3f", "d", ".0f", "s"],
    )


def table_accuracy(args, cases: dict[str, list[Path]]) -> list[dict]:
    cfg = base_config(args)
    recs = []
    for g, cs in cases.items():
        for c in cs:
            r = fit_case(c, Path(args.out) / "results" / "full" / c.name, cfg)
            r.update(
                garment=g,
                case=c.name,
                verts=n_verts(c),
                body=json.loads((c / "meta.json").read_text()).get("benchmark", {}).get("body_name", "?"),
            )
            recs.append(r)
    heads = ["garment", "fits done", "stage", "Chamfer mm", "normal deg", "turning rad", "area err %"]
    fmts = ["s", "s", "s", ".2f", ".1f", ".3f", ".2f"]
    rows = []
    for g in cases:
        rs = [r for r in recs if r["garment"] == g]
        for stage in ("base", "graded", "fit"):
            vals = [_stage_values(r)[stage] for r in rs]
            rows.append(
                [g, f"{sum(r['metrics'] is not None for r in rs)}/{len(rs)}", stage]
                + [_mean([v[i] for v in vals]) for i in range(4)]
            )
    per_case = _per_case_table(recs)
    text = (
        f"## Accuracy (Table 2)\n\n{header(args, 'measured')}\n\n"
        f"Per garment type (mean over its cases):\n\n{md_table(heads, rows, fmts)}\n\nPer "
        f"case:\n\n{per_case}\n"
    )
    emit(args, "accuracy", text)
    return recs


def table_ablation(args, cases: dict[str, list[Path]]) -> None:
    chosen = (
        [smallest([c for cs in cases.values() for c in cs])]
        if args.quick
        else [c for cs in cases.values() for c in cs]
    )
    if args.ablation_cases:
        chosen = [Path(args.cases) / n for n in args.ablation_cases]
    rows = []
    for name, changes in ABLATIONS.items():
        cfg = base_config(args, **changes)
        recs = [fit_case(c, Path(args.out) / "results" / name / c.name, cfg) for c in chosen]
        vals = [_stage_values(r)["fit"] for r in recs]
        rows.append(
            [name, f"{sum(r['metrics'] is not None for r in recs)}/{len(recs)}"]
            + [_mean([v[i] for v in vals]) for i in range(4)]
            + [_mean([(r["metrics"] or {}).get("timings_s", {}).get("total_s") for r in recs])]
        )
    text = (
        f"## Ablation (Table 3)\n\n{header(args, 'measured')}\n\nCases: "
        f"{', '.join(c.name for c in chosen)}\n\n"
        + md_table(
            ["variant", "fits done", "Chamfer mm", "normal deg", "turning rad", "area err %", "fit s"],
            rows,
            ["s", "s", ".2f", ".1f", ".3f", ".2f", ".0f"],
        )
        + "\n"
    )
    emit(args, "ablation", text)


def _sim_timings(args) -> str:
    """bench_sim.py's drape timings at --sim-sizes, run in a subprocess, as a markdown block."""
    cmd = [
        sys.executable,
        str(HERE / "bench_sim.py"),
        "--sizes",
        args.sim_sizes,
        "--repeat",
        "1",
        "--variants",
        "ring:cholespy",
    ]
    print("running", " ".join(cmd), flush=True)
    r = subprocess.run(cmd, capture_output=True, text=True)
    return (
        "Drape timings (`"
        + " ".join(["benchmarks/bench_sim.py"] + cmd[2:])
        + "`):\n\n```\n"
        + r.stdout.strip()
        + ("\n" + r.stderr.strip()[-2000:] if r.returncode else "")
        + "\n```\n"
    )


def _fit_timing_rows(results: Path) -> list[list]:
    """One row per fit under ``results`` (variant/case): vertices, iterations and the timings [s]
    of its stages, with the sidecar's wall time and load."""
    rows = []
    for mfile in sorted(results.glob("*/*/metrics.json")):
        m = json.loads(mfile.read_text())
        t = m.get("timings_s", {})
        side = mfile.parent.with_name(mfile.parent.name + ".bench.json")
        b = json.loads(side.read_text()) if side.is_file() else {}
        it = m.get("iterations") or 0
        gm = mfile.parent / "garment.obj"
        nv = sum(1 for line in open(gm) if line.startswith("v ")) if gm.is_file() else None
        rows.append(
            [
                f"{mfile.parent.parent.name}/{mfile.parent.name}",
                nv,
                it,
                t.get("total_s"),
                t.get("body_sdf_s"),
                t.get("grading_s"),
                t.get("material_choice_s"),
                t.get("optimization_s"),
                (t.get("optimization_s") or 0) / it if it else None,
                t.get("redress_s"),
                b.get("wall_s"),
                b.get("load_start"),
            ]
        )
    return rows


def table_speed(args) -> None:
    parts = [f"## Speed (Table 1)\n\n{header(args, 'measured')}\n"]
    if not args.skip_sim:
        parts.append(_sim_timings(args))
    rows = _fit_timing_rows(Path(args.out) / "results")
    parts.append(
        "End-to-end fits found under the results folder (seconds; `fit` = run_fit's total, `wall` "
        "includes writing the result folder and report):\n\n"
        + md_table(
            [
                "variant/case",
                "verts",
                "iters",
                "total s",
                "body SDF s",
                "grading s",
                "fabric choice s",
                "optim s",
                "s/iter",
                "re-dress s",
                "wall s",
                "load",
            ],
            rows,
            ["s", "d", "d", ".0f", ".1f", ".1f", ".0f", ".0f", ".2f", ".1f", ".0f", ".1f"],
        )
        + "\n"
    )
    if rows:
        tot = [r[3] for r in rows if r[3]]
        parts.append(f"{len(rows)} fits: median {np.median(tot):.0f} s, max {np.max(tot):.0f} s.\n")
    emit(args, "speed", "\n".join(parts))


#: The material table's pairs: name -> (what is scaled, factors, Material fields scaled).
MATERIAL_PAIRS = {
    "bending": ((0.2, 5.0), ("bend",)),
    "stretch": ((0.5, 2.0), ("h00", "h01", "h11", "h22")),
}
#: The skirt design and the library material both members of each pair start from.
MATERIAL_SKIRT = {"hem": (0.04, 0.08)}
MATERIAL_BASE = "jersey"


def material_cases(args) -> dict[str, list[tuple[float, Path]]]:
    from unsew.fit.synthetic import Alteration, make_truth_case
    from unsew.sim.drape import DrapeSettings
    from unsew.sim.material import get_material

    base = get_material(MATERIAL_BASE)
    out = {}
    for pair, (factors, fields) in MATERIAL_PAIRS.items():
        out[pair] = []
        for f in factors:
            d = Path(args.cases) / f"material_{pair}_x{f:g}"
            if not (d / "meta.json").is_file():
                mat = dataclasses.replace(base, **{k: getattr(base, k) * f for k in fields})
                make_truth_case(
                    d,
                    garment="skirt",
                    alteration=Alteration(MATERIAL_SKIRT, mat),
                    settings=DrapeSettings(edge_length=args.case_edge_length),
                )
            out[pair].append((f, d))
    return out


def table_material(args) -> None:
    from unsew.io.garmentcode import load_pattern
    from unsew.metrics.panels import pattern_metrics

    cfg = base_config(args)
    rows = []
    for pair, members in material_cases(args).items():
        fields = MATERIAL_PAIRS[pair][1]
        recs = [(f, fit_case(d, Path(args.out) / "results" / "material" / d.name, cfg)) for f, d in members]
        if any(r["metrics"] is None for _, r in recs):
            between = {"area_error_rel_mean": float("nan")}
        else:
            pats = [load_pattern(r["out"] / "pattern.json") for _, r in recs]
            between = pattern_metrics(pats[0], pats[1])
        key = "bending_N_m" if pair == "bending" else "H00_N_per_m"
        vals = [r["material"].get(key) for _, r in recs]
        order_ok = vals[0] is not None and vals[1] is not None and vals[0] < vals[1]
        for (f, r), v in zip(recs, vals):
            m = r["metrics"] or {}
            rows.append(
                [
                    pair,
                    f"x{f:g} ({'/'.join(fields)})",
                    m.get("surface", {}).get("chamfer_mm"),
                    _pm(m.get("pattern"), "area_error_rel_mean", 100),
                    v,
                    100 * between["area_error_rel_mean"],
                    "yes" if order_ok else "NO",
                    "yes" if between["area_error_rel_mean"] <= 0.02 else "NO",
                ]
                + [r["bench"].get("error", "")]
            )
    from unsew.sim.material import get_material

    b = get_material(MATERIAL_BASE)
    text = (
        f"## Material recovery (paper 4.3, Fig. 10)\n\n{header(args, 'measured')}\n\n"
        f"One skirt pattern (base skirt, hem {MATERIAL_SKIRT['hem']}) draped in {MATERIAL_BASE} "
        f"(bending {b.bend:.3g} N m, H00 {b.h00:g} N/m) with the listed stiffnesses scaled; each fitted "
        f"with material: {cfg.material.start}. `recovered` is the fit's bending [N m] or H00 [N/m]; `A "
        "between` is the mean panel area error between the pair's two recovered patterns.\n\n"
        + md_table(
            [
                "pair",
                "truth",
                "Chamfer mm",
                "area err vs truth %",
                "recovered",
                "A between %",
                "order right",
                "A between <= 2%",
                "failure",
            ],
            rows,
            ["s", "s", ".2f", ".2f", ".4g", ".2f", "s", "s", "s"],
        )
        + "\n"
    )
    emit(args, "material", text)


def _scaled_base(case_dir: Path, garment: str, s: float, path: Path) -> Path:
    """The base pattern of ``garment`` sized to the case's body, every panel scaled by ``s``
    about its 2D centroid, saved as GarmentCode JSON at ``path``."""
    from unsew.body.measure import measure_body
    from unsew.body.case import load_case
    from unsew.io.garmentcode import save_pattern
    from unsew.pattern.base import make_base_pattern

    if path.is_file():
        return path
    case = load_case(case_dir)
    p = make_base_pattern(garment, measure_body(case.body))
    for panel in p.panels.values():
        c = panel.vertices.mean(axis=0)
        panel.vertices = c + s * (panel.vertices - c)
    p.name = f"base_{garment}_x{s:g}"
    path.parent.mkdir(parents=True, exist_ok=True)
    save_pattern(p, path)
    return path


def table_sensitivity(args, cases: dict[str, list[Path]]) -> None:
    if args.sensitivity_case:
        c = Path(args.cases) / args.sensitivity_case
    else:
        c = smallest([c for cs in cases.values() for c in cs])
    garment = json.loads((c / "meta.json").read_text())["garment"]
    rows, vals = [], []
    for s in (0.9, 1.0, 1.1):
        if s == 1.0:
            rec = fit_case(c, Path(args.out) / "results" / "full" / c.name, base_config(args))
        else:
            base = _scaled_base(c, garment, s, Path(args.out) / "bases" / f"{c.name}_x{s:g}.json")
            rec = fit_case(
                c, Path(args.out) / "results" / f"scale{s:g}" / c.name, base_config(args, base=str(base))
            )
        v = _stage_values(rec)
        vals.append(v["fit"])
        rows.append(
            [f"x{s:g}", v["base"][0], v["base"][3], *v["fit"], (rec["metrics"] or {}).get("iterations")]
        )
    arr = np.array([[np.nan if x is None else x for x in v] for v in vals], dtype=float)
    spread = list(np.nanmax(arr, axis=0) - np.nanmin(arr, axis=0))
    rows.append(["spread (max-min)", None, None, *spread, None])
    text = (
        f"## Sensitivity to the starting pattern\n\n{header(args, 'measured')}\n\nCase {c.name} ({garment}): "
        "the base pattern scaled about each panel's centroid, then graded and fitted as usual.\n\n"
        + md_table(
            [
                "start",
                "CF start mm",
                "A start %",
                "CF fit mm",
                "normal fit deg",
                "turning fit rad",
                "A fit %",
                "iters",
            ],
            rows,
            ["s", ".2f", ".2f", ".2f", ".1f", ".3f", ".2f", "d"],
        )
        + "\n"
    )
    emit(args, "sensitivity", text)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--table", action="append", choices=TABLES + ["all"], required=True)
    ap.add_argument("--quick", action="store_true", help="one case per garment type (the smallest)")
    ap.add_argument("--cases", default="bench-out/paper/cases")
    ap.add_argument("--out", default="bench-out/paper")
    ap.add_argument("--garments", nargs="+", default=GARMENTS, choices=GARMENTS)
    ap.add_argument("--per-type", type=int, default=4, help="cases per garment type")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--case-edge-length", type=float, default=0.025, help="mesh of the target drapes [m]")
    ap.add_argument("--edge-length", type=float, default=0.025, help="mesh of the fit [m]")
    ap.add_argument("--iterations", type=int, default=100)
    ap.add_argument("--no-report", action="store_true", help="skip report.html in result folders")
    ap.add_argument(
        "--ablation-cases", nargs="*", help="case names for the ablation (default: all or smallest)"
    )
    ap.add_argument("--sensitivity-case", help="case name for the sensitivity table (default: the smallest)")
    ap.add_argument("--sim-sizes", default="1000,2000,3000", help="bench_sim.py sizes for the speed table")
    ap.add_argument("--skip-sim", action="store_true", help="speed table: only the fits' timings")
    ap.add_argument(
        "--set",
        action="append",
        metavar="KEY=VALUE",
        help="override a FitConfig option for every fit (repeatable); use a separate --out",
    )
    ap.add_argument("--retry-failed", action="store_true", help="refit cases whose fit raised before")
    args = ap.parse_args(argv)
    global RETRY_FAILED
    RETRY_FAILED = args.retry_failed
    tables = TABLES if "all" in args.table else args.table

    import torch

    torch.set_num_threads(1)
    need_cases = any(t in tables for t in ("accuracy", "ablation", "sensitivity"))
    cases = pick_cases(args, ensure_cases(args)) if need_cases else {}
    for t in tables:
        if t == "accuracy":
            table_accuracy(args, cases)
        elif t == "ablation":
            table_ablation(args, cases)
        elif t == "speed":
            table_speed(args)
        elif t == "material":
            table_material(args)
        elif t == "sensitivity":
            table_sensitivity(args, cases)


if __name__ == "__main__":
    main()
