"""Scoring of the GarmentCode benchmark: per case, against the truth the fit never reads.

Per case (a fit result folder ``RESULTS/<case>`` from ``unsew fit CASE --out RESULTS/<case>``):
- ``type_right``: the recovered garment type (the first word of the base in metrics.json) is the
  truth's (truth.json, from design_params.yaml); ``type_given`` records whether the type was
  handed to the fit (``--base`` or meta.json), which makes that figure moot for the case;
- ``choices``: each structural choice (truth.CHOICES) of the recovered pattern.json against the
  truth; ``choices_right``: all of them right (the summary's ``choice_right``: per choice, the
  fitted cases that have it right);
- ``panel_err`` and ``turning``: judge.compare_patterns (both patterns merged first), each
  recovered piece standing for the true pieces it drapes over (the fit's garment.obj against the
  target's panels, or newton's drape of the true pattern where the target's rest mesh is not
  kept: :func:`true_cloth`); ``panel_match`` says "placement" where that could not be read;
  ``panels_true``/``panels_rec``: panel counts after merging;
- ``chamfer_mm``: the fit's garment.obj against target.obj (judge.chamfer_mm);
  ``chamfer_bar_mm``: the cross-simulator floor, ``unsew drape pattern_gt.json --body CASE``
  against the target; the fit's bar is max(5 mm, 1.5 x that floor) (the summary's
  ``chamfer_bar_median``, over the fitted cases, and ``chamfer_within_bar``; the floor's own median
  is ``chamfer_floor_median``);
- ``redrape_mm``: the recovered pattern draped by newton from its own placement, dressed as the
  targets are (their start and holds), against the target; ``floor_mm``: the true pattern
  draped so on a 10 % finer mesh against the target (that figure's floor); ``redrape_ratio`` =
  redrape_mm / floor_mm;
- ``own_redrape_mm``: the recovered pattern.json draped again by unsew from its own placement
  (``unsew drape RESULT/pattern.json --body CASE``, what a user does next in unsew) against the
  target, or ``own_redrape_error``: that drape's one line where it is refused (the summary's
  ``own_redrape_median`` and ``own_redrape_refused``);
- ``fit_s``: the fit's wall time (metrics.json timings_s).
A built case without a fit result, or whose fit failed (a non-zero exit in RESULTS/fits.json,
written by ``gcd fit``: ``fit_exit`` and ``fit_message`` say how), counts as a miss (type and
choices wrong); a case whose build failed counts too. Medians are over the fitted cases;
``fit_ok`` is the fit's own verdict (metrics.json ``"ok"``), ``fitted_ok`` and ``fit_over_10min``
count them.
"""

from __future__ import annotations

import hashlib
import json
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent

import build  # noqa: E402  (this folder on the path first)
import fits  # noqa: E402
import judge  # noqa: E402
import kept  # noqa: E402
from truth import CHOICES, built_choices, choices_of_spec, truth_of_design  # noqa: E402

#: Newton's drape of a recovered pattern, kept in its result folder (keyed on the pattern and the target).
REDRAPE_CACHE = "redrape_newton.json"
#: Where the true panels drape where the target's rest mesh is not kept, in the case folder.
TRUE_DRAPE_CACHE = "true_drape_newton.npz"

#: GarmentCode's skirt components that flare out from the hips: circle, asymmetric circle, the
#: many-panel (flared gores) and godet skirts (the circle and flared cases of the summary).
FLARED_BOTTOMS = ("SkirtCircle", "AsymmSkirtCircle", "SkirtManyPanels", "GodetSkirt")
#: The floor of the redrape figure: the true pattern meshed this much finer [share of the edge length].
FINER = 0.9
#: How newton dresses a floor and a re-drape: 2, as the targets (build.newton_start and
#: build.newton_dress); 1, from the bent placement alone, nothing held. A floor or re-drape
#: made by another recipe is made again.
NEWTON_RECIPE = 2
#: A fit's Chamfer bar: max(BAR_MIN_MM, BAR_PER_FLOOR x its cross-simulator floor) [mm].
BAR_MIN_MM, BAR_PER_FLOOR = 5.0, 1.5


def read_obj(path: Path):
    v, f = [], []
    with open(path) as fh:
        lines = fh.readlines()
    for ln in lines:
        if ln.startswith("v "):
            v.append([float(t) for t in ln.split()[1:4]])
        elif ln.startswith("f "):
            ids = [int(t.split("/")[0]) - 1 for t in ln.split()[1:]]
            f += [[ids[0], ids[k], ids[k + 1]] for k in range(1, len(ids) - 1)]
    return np.asarray(v, np.float64), np.asarray(f, np.int64)


def newton_redrape(spec: dict, case: Path, edge_length: float, lower: bool):
    """(verts (N, 3) [m], faces) of a specification draped by newton from its own placement, as
    the case's target was (:func:`build.newton_start`, :func:`build.newton_dress`)."""
    x, mesh = _newton_drape_mesh(spec, case, edge_length, lower)
    return x, np.asarray(mesh.faces)


def _newton_drape_mesh(spec: dict, case: Path, edge_length: float, lower: bool):
    """(verts (N, 3) [m], the panel mesh they belong to) of :func:`newton_redrape`."""
    body_v, body_f = build.read_body(case)
    mesh = build.mesh_spec(spec, case.name, edge_length)
    x0 = build.newton_start(spec, mesh, build.spec_placement(spec, mesh), body_v, body_f)
    x, _, _, _ = build.newton_dress(spec, mesh, x0, (body_v, body_f), lower)
    return x, mesh


def _panel_of_x(mesh, n_x: int) -> np.ndarray:
    """(n_x,) the name of a panel each vertex of a panel mesh belongs to (a seam's: one of its panels)."""
    names = np.asarray(mesh.panel_names, dtype=object)
    out = np.empty(n_x, dtype=object)
    out[np.asarray(mesh.x_of_u)] = names[np.asarray(mesh.uv_panel)]
    return out


def true_cloth(case: Path, spec_gt: dict, truth: dict, target, *, newton: bool = True):
    """(x (N, 3) [m], panel name per vertex (N,)) of where the true pattern's panels drape: the
    target's own vertices through the rest mesh it was draped on (:func:`kept.own_mesh`), else
    newton's drape of the true pattern on the floor's finer mesh, dressed as the target was (kept
    in the case folder, ``TRUE_DRAPE_CACHE``; None where it is not kept and not ``newton``)."""
    tv, tf = target
    edge = build.manifest()["edge_length_m"]
    mesh = build.mesh_spec(spec_gt, case.name, edge)
    rest = kept.own_mesh(case, mesh, tv, tf)
    if rest is not None and int(np.max(rest.uv_panel)) + 1 == len(mesh.panel_names):
        rest.panel_names = mesh.panel_names
        return tv, _panel_of_x(rest, len(tv))
    cache = case / TRUE_DRAPE_CACHE
    if cache.is_file():
        with np.load(cache, allow_pickle=False) as z:
            return z["x"], z["panel"].astype(object)
    if not newton:
        return None
    x, fine = _newton_drape_mesh(spec_gt, case, edge * FINER, truth["type"] in build.LOWER_TYPES)
    panel = _panel_of_x(fine, len(x))
    np.savez_compressed(cache, x=np.asarray(x, np.float64), panel=panel.astype(str))
    return x, panel


def panel_shares(
    case: Path, result: Path, spec_gt: dict, spec_rec: dict, truth: dict, target, *, newton=True
):
    """judge.drape_shares of the fit's garment.obj against where the true panels drape, or None
    where the garment's pieces cannot be told apart or the true drape is not at hand without
    ``newton`` (the judge then matches by placement)."""
    order = spec_rec["pattern"].get("panel_order") or list(spec_rec["pattern"]["panels"])
    try:
        x, f, _, mesh = fits.garment_panels(result, order)
    except ValueError:
        return None
    true = true_cloth(case, spec_gt, truth, target, newton=newton)
    return None if true is None else judge.drape_shares(*true, x, f, _panel_of_x(mesh, len(x)))


def unsew_drape(case: Path, timeout: int = 1800, pattern: Path | None = None):
    """(verts, faces) of ``unsew drape PATTERN --body CASE`` (default: the case's
    pattern_gt.json), or an error string."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "garment.obj"
        cmd = [
            sys.executable,
            "-m",
            "unsew",
            "drape",
            str(case / "pattern_gt.json" if pattern is None else pattern),
            "--body",
            str(case),
            "--out",
            str(out),
            "--no-progress",
        ]
        try:
            r = subprocess.run(cmd, capture_output=True, text=True, check=False, timeout=timeout)
        except subprocess.TimeoutExpired:
            return f"timed out after {timeout} s"
        if r.returncode or not out.is_file():
            return f"exit {r.returncode}: {(r.stderr.strip().splitlines() or [''])[-1][:200]}"
        return read_obj(out)


def case_truth(case: Path) -> tuple[dict, dict]:
    """(truth.json with its choices read from the design itself, pattern_gt.json) of a case
    (truth.json's choices may predate a choice scored now)."""
    truth = json.loads((case / "truth.json").read_text())
    spec_gt = json.loads((case / "pattern_gt.json").read_text())
    design = truth_of_design((case / "design_params.yaml").read_text())["choices"]
    truth["choices"] = built_choices(design, spec_gt)
    return truth, spec_gt


def score_case(case: Path, result: Path | None, *, floor: bool = True, redrape: bool = True) -> dict:
    """The score record of one built case (``result``: its fit folder, or None: not fitted)."""
    truth, spec_gt = case_truth(case)
    tv, tf = read_obj(case / "target.obj")
    rec = {"case": case.name, "type_true": truth["type"], "choices_true": truth["choices"]}
    rec.update(_floors(case, spec_gt, truth, (tv, tf), floor=floor, redrape=redrape))
    if result is None or not (result / "pattern.json").is_file():
        rec.update(fitted=False, type_right=False, choices_right=False)
        return rec
    _score_pattern(rec, case, result, truth, spec_gt, (tv, tf), newton=redrape)
    _score_drapes(rec, case, result, truth, (tv, tf), redrape=redrape)
    return rec


def unsew_code() -> str:
    """The first 12 hex digits of the SHA-256 of unsew's source files (their paths and bytes):
    what unsew's drape of a true pattern depends on besides the case."""
    import unsew

    root = Path(unsew.__file__).resolve().parent
    h = hashlib.sha256()
    for p in sorted(root.rglob("*.py")):
        h.update(p.relative_to(root).as_posix().encode())
        h.update(p.read_bytes())
    return h.hexdigest()[:12]


def _floors(case: Path, spec_gt: dict, truth: dict, target, *, floor: bool, redrape: bool) -> dict:
    """The case's floors, kept in floors.json: unsew's drape of the true pattern against the
    target (chamfer_bar_mm; made again when unsew's source has changed since, ``bar_code``) and
    newton's on a finer mesh (floor_mm, made once) [mm]."""
    tv, tf = target
    cache = case / "floors.json"
    known = json.loads(cache.read_text()) if cache.is_file() else {}
    code = unsew_code()
    if floor and ("chamfer_bar_mm" not in known or known.get("bar_code") != code):
        known.pop("chamfer_bar_error", None)
        known["bar_code"] = code
        d = unsew_drape(case)
        known["chamfer_bar_mm"] = (
            round(judge.chamfer_mm(*d, tv, tf)["chamfer_mm"], 2) if isinstance(d, tuple) else None
        )
        if not isinstance(d, tuple):
            known["chamfer_bar_error"] = d
        cache.write_text(json.dumps(known, indent=1))
    if known.get("floor_recipe") != NEWTON_RECIPE:
        for k in ("floor_mm", "floor_error", "floor_recipe"):
            known.pop(k, None)
    if redrape and "floor_mm" not in known:
        edge = build.manifest()["edge_length_m"]
        known.pop("floor_error", None)
        try:
            x, f = newton_redrape(spec_gt, case, edge * FINER, truth["type"] in build.LOWER_TYPES)
            known["floor_mm"] = round(judge.chamfer_mm(x, f, tv, tf)["chamfer_mm"], 2)
        except Exception as exc:  # noqa: BLE001 - recorded per case, the rest go on
            known["floor_mm"], known["floor_error"] = None, f"{type(exc).__name__}: {str(exc)[:160]}"
        known["floor_recipe"] = NEWTON_RECIPE
        cache.write_text(json.dumps(known, indent=1))
    return known


def _score_pattern(
    rec: dict, case: Path, result: Path, truth: dict, spec_gt: dict, target, *, newton: bool
) -> None:
    """The recovered pattern's type, structural choices and panels against the truth, into ``rec``."""
    metrics = json.loads((result / "metrics.json").read_text()) if (result / "metrics.json").is_file() else {}
    spec_rec = json.loads((result / "pattern.json").read_text())
    base = str(metrics.get("base", ""))
    rec["type_rec"] = type_of_base(base)
    cfg = (result / "config.yaml").read_text() if (result / "config.yaml").is_file() else ""
    meta = json.loads((case / "meta.json").read_text())
    rec["type_given"] = type_given(meta, cfg)
    rec["type_right"] = rec["type_rec"] == truth["type"]
    ch = choices_of_spec(spec_rec)
    rec["choices_rec"] = ch
    rec["choices_ok"] = {k: ch[k] == truth["choices"][k] for k in CHOICES}
    rec["choices_right"] = all(rec["choices_ok"].values())
    shares = panel_shares(case, result, spec_gt, spec_rec, truth, target, newton=newton)
    rec["panel_match"] = "placement" if shares is None else "drape"
    cmp = judge.compare_patterns(spec_gt, spec_rec, shares)
    keys = ("panel_err", "turning", "panels_true", "panels_rec", "panels_true_raw", "panels_rec_raw")
    rec.update({k: cmp[k] for k in keys})
    t = metrics.get("timings_s") or {}
    total = t.get("total_s", t.get("total"))
    rec["fit_s"] = round(float(total), 1) if total is not None else None
    rec["fit_ok"] = bool(metrics.get("ok", True))
    rec["fitted"] = True


def _score_drapes(rec: dict, case: Path, result: Path, truth: dict, target, *, redrape: bool) -> None:
    """The fit's drape against the target and, with ``redrape``, newton's drape of the recovered
    pattern (and its ratio to the floor), into ``rec`` [mm]."""
    tv, tf = target
    gv, gf = read_obj(result / "garment.obj")
    rec["chamfer_mm"] = round(judge.chamfer_mm(gv, gf, tv, tf)["chamfer_mm"], 2)
    if not redrape:
        return
    text = (result / "pattern.json").read_text()
    cache = result / REDRAPE_CACHE
    key = {
        "pattern_sha256": hashlib.sha256(text.encode()).hexdigest(),
        "target": str((case / "target.obj").resolve()),
        "recipe": NEWTON_RECIPE,
    }
    known = json.loads(cache.read_text()) if cache.is_file() else {}
    if all(known.get(k) == v for k, v in key.items()) and "redrape_mm" in known:
        rec["redrape_mm"] = known["redrape_mm"]
        if known.get("redrape_error"):
            rec["redrape_error"] = known["redrape_error"]
    else:
        edge = build.manifest()["edge_length_m"]
        try:
            x, f = newton_redrape(json.loads(text), case, edge, truth["type"] in build.LOWER_TYPES)
            rec["redrape_mm"] = round(judge.chamfer_mm(x, f, tv, tf)["chamfer_mm"], 2)
            keep_redrape(result, case, x, f, rec["redrape_mm"])
        except Exception as exc:  # noqa: BLE001 - recorded per case, the rest go on
            rec["redrape_mm"], rec["redrape_error"] = None, f"{type(exc).__name__}: {str(exc)[:160]}"
        cache.write_text(json.dumps({**key, **{k: rec.get(k) for k in ("redrape_mm", "redrape_error")}}))
    if rec.get("redrape_mm") and rec.get("floor_mm"):
        rec["redrape_ratio"] = round(rec["redrape_mm"] / rec["floor_mm"], 3)
    own_redrape(rec, case, result, target)


#: unsew's drape of a fit's pattern.json, kept beside it with the hashes it was made from
OWN_REDRAPE_CACHE = "redrape_unsew.json"


def own_redrape(rec: dict, case: Path, result: Path, target) -> None:
    """``own_redrape_mm`` (or ``own_redrape_error``) into ``rec``: the fit's pattern.json dressed
    by ``unsew drape`` on the case's body against ``target`` (verts, faces) [mm], made again only
    when the file or unsew's source (:func:`unsew_code`) changed."""
    key = {
        "pattern_sha256": hashlib.sha256((result / "pattern.json").read_bytes()).hexdigest(),
        "code": unsew_code(),
    }
    cache = result / OWN_REDRAPE_CACHE
    known = json.loads(cache.read_text()) if cache.is_file() else {}
    if any(known.get(k) != v for k, v in key.items()):
        got = unsew_drape(case, pattern=result / "pattern.json")
        mm = None if isinstance(got, str) else round(judge.chamfer_mm(*got, *target)["chamfer_mm"], 2)
        known = {**key, "mm": mm, "error": got if isinstance(got, str) else None}
        cache.write_text(json.dumps(known))
    rec["own_redrape_mm"] = known["mm"]
    if known["error"]:
        rec["own_redrape_error"] = known["error"]


def keep_redrape(result: Path, case: Path, x: np.ndarray, f: np.ndarray, mm: float) -> None:
    """newton's drape of the recovered pattern, x (N, 3) [m] and faces f, beside it: an OBJ and
    a picture of it on the body (``redrape_newton.obj``, ``redrape_newton.png``)."""
    sys.path.insert(0, str(build.HERE.parent / "foreign"))
    import checks

    what = f"{case.name}: the recovered pattern draped by newton"
    build.write_obj(result / "redrape_newton.obj", x, f, what)
    title = f"{what}, {mm:.1f} mm from the target"
    checks.preview(result / "redrape_newton.png", x, f, *build.read_body(case), title=title)


def type_of_base(base: str) -> str | None:
    """The garment type a fit's base names: a library base (``dress_straight``) or a design drafted
    from the reading (``shorts-shorts-band-length0.63``) names it first; None for no base."""
    return re.split(r"[_-]", base)[0] if base else None


def type_given(meta: dict, config_yaml: str) -> bool:
    """Whether a fit was handed its garment type: the case's meta.json names one, or the result's
    config.yaml names a base (its ``base:`` line not empty)."""
    import yaml

    cfg = yaml.safe_load(config_yaml) or {} if config_yaml.strip() else {}
    cfg = cfg.get("config", cfg) if isinstance(cfg, dict) else {}
    return bool(meta.get("garment")) or bool(cfg.get("base"))


def cmd_score(args, record_file: Path) -> int:
    if getattr(args, "rejudge", False):
        return cmd_rejudge(args, record_file)
    cases = Path(args.cases)
    results = Path(args.results)
    built = json.loads((cases / "build.json").read_text()) if (cases / "build.json").is_file() else {}
    fit_log = fits.read_log(results)
    old = json.loads(record_file.read_text()).get("cases", {}) if record_file.is_file() else {}
    recs = {}
    for cid, _, _ in build.case_ids():
        b = built.get(cid)
        if (b is None or b.get("status") != "built") and args.only_tried and old.get(cid, {}).get("built"):
            # built where it was recorded; its kept target is not restored here (kept.py: the
            # sampler gave this machine another specification's digest)
            print(f"{cid}: not built in {cases}; its recorded row stands", file=sys.stderr)
            recs[cid] = old[cid]
            continue
        if b is None or b.get("status") != "built":
            recs[cid] = {
                "case": cid,
                "type_true": (b or {}).get("type"),
                "built": False,
                "build": (b or {}).get("status", "not built"),
                "reason": (b or {}).get("reason"),
                "fitted": False,
                "type_right": False,
                "choices_right": False,
            }
            continue
        res = results / cid
        outcome = fit_log.get(cid)
        if not res.is_dir() and outcome is None and args.only_tried:
            if old.get(cid, {}).get("built"):  # its recorded row stands (fitted elsewhere)
                recs[cid] = old[cid]
            continue
        failed = outcome is not None and outcome["exit"] != 0
        t0 = time.time()
        rec = score_case(
            cases / cid,
            res if res.is_dir() and not failed else None,
            floor=not args.no_floor,
            redrape=not args.no_redrape,
        )
        rec["built"] = True
        if outcome is not None:
            rec.update(fit_exit=outcome["exit"], fit_message=outcome["message"])
            rec.setdefault("fit_s", outcome["seconds"])
        rec["score_s"] = round(time.time() - t0, 1)
        recs[cid] = rec
        print(json.dumps(rec), flush=True)
    carry_over(recs, old)
    if args.record:  # the table of the record as written, with the rows another scoring wrote
        stood = {cid for cid, r in recs.items() if r is old.get(cid)} if args.only_tried else set()
        recs = write_record(record_file, recs, stood, "python -m benchmarks gcd score --results DIR --record")
    print_record({"cases": recs})
    return 0


def write_record(record_file: Path, recs: dict, stood: set, about: str) -> dict:
    """Write ``recs`` as the recorded results, the rows of ``stood`` (kept as recorded, not scored
    now) read again from the file as it is at this moment, under a lock: two ``gcd score
    --only-tried --record`` runs over different fit folders can run side by side. Returns the
    rows written."""
    import fcntl

    with open(record_file.with_name(record_file.name + ".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        now = json.loads(record_file.read_text()).get("cases", {}) if record_file.is_file() else {}
        rows = {cid: now.get(cid, r) if cid in stood else r for cid, r in recs.items()}
        record_file.write_text(json.dumps({"about": about, "cases": rows}, indent=1) + "\n")
    return rows


#: How far [mm] a fit's drape may lie from its recorded Chamfer and still be the fit of record.
SAME_FIT_MM = 0.01


def cmd_rejudge(args, record_file: Path) -> int:
    """``gcd score --rejudge``: each recorded fit's pattern judged again (:func:`_score_pattern`:
    type, choices, panel error, turning) from ``RESULTS/<case>``, where that folder's garment.obj
    lies within ``SAME_FIT_MM`` of the recorded Chamfer (the fit of record made again); every
    other figure of the row stands, and a case whose fit drapes otherwise keeps its row."""
    cases, results = Path(args.cases), Path(args.results)
    for what, d in (("--results", results), ("--cases", cases)):
        if not d.is_dir():
            print(f"gcd score --rejudge: {what} {d} is not a folder", file=sys.stderr)
            return 2
    if not record_file.is_file():
        print(f"gcd score --rejudge: no recorded results in {record_file}", file=sys.stderr)
        return 2
    recs = json.loads(record_file.read_text())["cases"]
    kept_rows = []
    for cid, old in recs.items():
        case, res = cases / cid, results / cid
        if (
            not old.get("fitted")
            or not all((res / fn).is_file() for fn in ("pattern.json", "garment.obj"))
            or not (case / "target.obj").is_file()
        ):
            if old.get("fitted"):
                kept_rows.append(f"{cid} (no fit or target here)")
            continue
        tv, tf = read_obj(case / "target.obj")
        mm = round(judge.chamfer_mm(*read_obj(res / "garment.obj"), tv, tf)["chamfer_mm"], 2)
        if abs(mm - old.get("chamfer_mm", np.inf)) > SAME_FIT_MM:
            kept_rows.append(f"{cid} (drapes {mm} mm from the target, recorded {old.get('chamfer_mm')})")
            continue
        truth, spec_gt = case_truth(case)
        rec = dict(old)
        _score_pattern(rec, case, res, truth, spec_gt, (tv, tf), newton=not args.no_redrape)
        rec["fit_s"] = old.get("fit_s", rec.get("fit_s"))  # the fit of record's time
        recs[cid] = rec
        print(
            json.dumps({k: rec.get(k) for k in ("case", "panel_err", "turning", "panel_match")}), flush=True
        )
    for row in kept_rows:
        print(f"kept as recorded: {row}", file=sys.stderr)
    print_record({"cases": recs})
    if args.record:
        about = "python -m benchmarks gcd score --results DIR --record; patterns judged again with --rejudge"
        write_record(record_file, recs, set(), about)
    return 0


def carry_over(recs: dict, old: dict) -> None:
    """Fill each built case's record from the recorded ``old`` ones where it lacks them: the
    material-fitted floor and whether the case is a circle or flared skirt (recorded apart,
    :func:`cmd_floor_fitted`) and newton's floor (made once into floors.json, which a case folder
    built again from the kept targets has lost) where it was made by :data:`NEWTON_RECIPE`."""
    for cid, r in recs.items():
        o = old.get(cid, {})
        keys = ("floor_fitted_mm", "floor_fitted_s", "flared")
        if o.get("floor_recipe") == NEWTON_RECIPE:  # newton's floor, when made as it is made now
            keys += ("floor_mm", "floor_recipe")
        for k in keys:
            if k in o and r.get("built"):
                r.setdefault(k, o[k])


def cmd_floor_fitted(args, record_file: Path) -> int:
    """Record each built case's material-fitted floor: the Chamfer [mm] of ``RESULTS/<case>/
    garment.obj`` (``unsew fit CASE --material-only --base CASE/pattern_gt.json --out
    RESULTS/<case>``: the true pattern, its material fitted) to the target, and that fit's time
    [s], into the recorded results' case records (nothing else in them changes)."""
    cases, results = Path(args.cases), Path(args.results)
    for what, d in (("--results", results), ("--cases", cases)):
        if not d.is_dir():
            print(f"gcd floor-fitted: {what} {d} is not a folder", file=sys.stderr)
            return 2
    rec = load_record(record_file)
    rows = []
    for cid, _, _ in build.case_ids():
        r = rec["cases"].get(cid)
        garment = results / cid / "garment.obj"
        if r is None or not r.get("built") or not garment.is_file():
            continue
        tv, tf = read_obj(cases / cid / "target.obj")
        gv, gf = read_obj(garment)
        r["floor_fitted_mm"] = round(judge.chamfer_mm(gv, gf, tv, tf)["chamfer_mm"], 2)
        truth = json.loads((cases / cid / "truth.json").read_text())
        r["flared"] = truth.get("bottom") in FLARED_BOTTOMS
        mp = results / cid / "metrics.json"
        t = (json.loads(mp.read_text()).get("timings_s") or {}) if mp.is_file() else {}
        total = t.get("total_s", t.get("total"))
        r["floor_fitted_s"] = round(float(total), 1) if total is not None else None
        rows.append(
            {
                "case": cid,
                "floor_fitted_mm": r["floor_fitted_mm"],
                "floor_mm": r.get("floor_mm"),
                "chamfer_bar_mm": r.get("chamfer_bar_mm"),
                "fit_s": r["floor_fitted_s"],
            }
        )
    sys.path.insert(0, str(HERE.parent))
    from tables import print_table

    print_table(rows, title="material-fitted floor (the true pattern, its material fitted)", digits=2)
    print(json.dumps(summary(rec)))
    if args.record:
        record_file.write_text(json.dumps(rec, indent=1) + "\n")
    return 0


def load_record(path: Path) -> dict:
    if not path.is_file():
        raise SystemExit(
            f"no recorded results at {path}; run `python -m benchmarks gcd score --results DIR --record`"
        )
    return json.loads(path.read_text())


def _median(xs):
    xs = [x for x in xs if x is not None]
    return round(float(np.median(xs)), 4) if xs else None


def _bar(floor_mm):
    """A fit's Chamfer bar [mm]: max(5 mm, 1.5 x its cross-simulator floor); None without a floor."""
    return None if floor_mm is None else max(BAR_MIN_MM, BAR_PER_FLOOR * floor_mm)


def summary(rec: dict) -> dict:
    """One line of the recorded results (the figures of the benchmark, see the module docstring)."""
    n_cases = len(build.case_ids())
    rs = list(rec["cases"].values())
    fit = [r for r in rs if r.get("fitted")]
    return {
        "cases": n_cases,
        "built": sum(1 for r in rs if r.get("built")),
        "fitted": len(fit),
        "fitted_ok": sum(1 for r in fit if r.get("fit_ok", True)),
        "fit_failed": sum(1 for r in rs if r.get("fit_exit") not in (None, 0)),
        "fit_over_10min": sum(1 for r in rs if (r.get("fit_s") or 0) > 600),
        "type_right": sum(1 for r in rs if r.get("type_right")),
        "choices_right": sum(1 for r in rs if r.get("choices_right")),
        "choice_right": {k: sum(1 for r in fit if (r.get("choices_ok") or {}).get(k)) for k in CHOICES},
        "panel_err_median": _median([r.get("panel_err") for r in fit]),
        "panel_err_p90": round(float(np.percentile([r["panel_err"] for r in fit], 90)), 4) if fit else None,
        "turning_median": _median([r.get("turning") for r in fit]),
        "chamfer_median": _median([r.get("chamfer_mm") for r in fit]),
        "chamfer_bar_median": _median([_bar(r.get("chamfer_bar_mm")) for r in fit]),
        "chamfer_within_bar": sum(
            1
            for r in fit
            if r.get("chamfer_bar_mm") is not None and r["chamfer_mm"] <= _bar(r["chamfer_bar_mm"])
        ),
        "chamfer_floor_median": _median([r.get("chamfer_bar_mm") for r in rs]),
        "redrape_ratio_median": _median([r.get("redrape_ratio") for r in fit]),
        "own_redrape_median": _median([r.get("own_redrape_mm") for r in fit]),
        "own_redrape_refused": sum(1 for r in fit if r.get("own_redrape_error")),
        "fit_s_median": _median([r.get("fit_s") for r in fit]),
        "floor_median": _median([r.get("floor_mm") for r in rs]),
        "floor_fitted_median": _median([r.get("floor_fitted_mm") for r in rs]),
        "floor_fitted_flared_median": _median([r.get("floor_fitted_mm") for r in rs if r.get("flared")]),
    }


def _fitted_cell(r: dict) -> str:
    """'yes', 'yes, ok false', 'exit N' (a failed fit) or 'no' (never fitted)."""
    if r.get("fitted"):
        return "yes" if r.get("fit_ok", True) else "yes, ok false"
    return f"exit {r['fit_exit']}" if r.get("fit_exit") not in (None, 0) else "no"


def print_record(rec: dict) -> None:
    sys.path.insert(0, str(HERE.parent))
    from tables import print_table

    rows = []
    for cid, _, _ in build.case_ids():
        r = rec["cases"].get(cid, {"case": cid})
        rows.append(
            {
                "case": cid,
                "type": r.get("type_true") or "",
                "built": "yes" if r.get("built") else (r.get("build") or "no"),
                "fitted": _fitted_cell(r),
                "type ok": ("yes" if r.get("type_right") else "no")
                + (" (given)" if r.get("type_given") else ""),
                "choices ok": "yes" if r.get("choices_right") else "no",
                "panel err": r.get("panel_err"),
                "turning": r.get("turning"),
                "panels t/r": f"{r['panels_true']}/{r['panels_rec']}" if "panels_rec" in r else "",
                "chamfer mm": r.get("chamfer_mm"),
                "bar mm": _bar(r.get("chamfer_bar_mm")),
                "redrape mm": r.get("redrape_mm"),
                "newton floor mm": r.get("floor_mm"),
                "fit s": r.get("fit_s"),
            }
        )
    print_table(rows, title="GarmentCode design benchmark (recorded results)", digits=3)
    print(json.dumps(summary(rec)))


def judge_check() -> int:
    """The judge on synthetic inputs: a square against itself and shifted, two mirror halves merged."""
    sq = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    f = np.array([[0, 1, 2], [0, 2, 3]])
    print(
        "chamfer self mm",
        round(judge.chamfer_mm(v, f, v, f)["chamfer_mm"], 3),
        "shifted 1 cm",
        round(judge.chamfer_mm(v, f, v + [0, 0, 0.01], f)["chamfer_mm"], 3),
    )
    print(
        "turning square/square",
        round(judge.turning_distance(sq, sq), 4),
        "square/rectangle",
        round(judge.turning_distance(sq, sq * [2, 1]), 4),
    )
    return 0
