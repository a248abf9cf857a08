"""GarmentCode design benchmark: designs nobody here drew, draped by another simulator, judged apart.

    python -m benchmarks gcd                       the table of the recorded results (results.json)
    python -m benchmarks gcd --summary             one JSON line of the recorded results
    python -m benchmarks gcd build [--out DIR] [--seeds 1-5] [--count 8] [--only gc_s1_000 ...] [--no-drape]
    python -m benchmarks gcd fit --results RESULTS_DIR [--only ...] [--redo] fit each built case
    python -m benchmarks gcd score --results RESULTS_DIR [--cases DIR] [--only-tried | --rejudge] [--record]
    python -m benchmarks gcd compare BEFORE AFTER [--only ...]   two folders of fits judged side by side
    python -m benchmarks gcd floor-fitted --results DIR [--record]   the material-fitted floor
    python -m benchmarks gcd reexport --results DIR --to DIR2 [--cases DIR]   fits placed as exported now
    python -m benchmarks gcd graded --results DIR --to DIR2     fits with the pattern phase two started from
    python -m benchmarks gcd status [--out DIR]    every case's build status
    python -m benchmarks gcd keep [--out DIR]      store the built targets in targets/ (kept.py)
    python -m benchmarks gcd settle --out DIR --to DIR2 [--only ...]   each built target run on to rest
    python -m benchmarks gcd remesh --out DIR --to DIR2 [--max-edge M] [--only ...]   targets meshed finer
    python -m benchmarks gcd types [--out DIR] [--drapes DIR] [--record]   the design read off the targets
    python -m benchmarks gcd judge-check           the judge on synthetic inputs (seconds)
    python -m benchmarks gcd panels --results R --cases DIR   per true piece, each fit stage; darts' floor
    python -m benchmarks gcd sew-probe CASE_DIR ['{"sew_contact_mu": 0.5}'] [--no-attach] [--no-guide]
    python -m benchmarks gcd starts [--out DIR] [--drapes DIR] [--only ...] [--record] [--drafts [--darts]]
    python -m benchmarks gcd unwelded [--out DIR] [--only ...] [--no-weld]   targets read with panels unwelded

``build`` samples GarmentCode's designs (seed k sized to and draped on body k of manifest.json),
drapes each with newton from the specification's own 3D placement and writes the case folders
(build.py). ``score`` judges fits: RESULTS_DIR holds one ``unsew fit`` result folder per case
(named by case id); each is scored against its case's truth by judge.py (no unsew metrics code),
with the cross-simulator floor (``unsew drape pattern_gt.json --body CASE``) and the recovered
pattern draped by newton. ``--record`` writes the scores to results.json. Cases default to
``benchmarks/gcd/cases`` (gitignored, a build step).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))

import build  # noqa: E402  (this folder on the path first)
import compare  # noqa: E402
import fits  # noqa: E402
import kept  # noqa: E402
import remesh  # noqa: E402
import score  # noqa: E402
import settle  # noqa: E402
import starts  # noqa: E402
import unwelded  # noqa: E402

RESULTS = HERE / "results.json"
TYPES_RECORD = HERE.parent / "results" / "gcd_types.json"
STARTS_RECORD = HERE.parent / "results" / "gcd_starts.json"
DEFAULT_CASES = HERE / "cases"


def _seeds(text: str) -> list[int]:
    out = []
    for part in text.split(","):
        a, _, b = part.partition("-")
        out += list(range(int(a), int(b or a) + 1))
    return out


def cmd_build(args) -> int:
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    ids = build.case_ids(_seeds(args.seeds), args.count)
    if args.only:
        unknown = [c for c in args.only if c not in {c for c, _, _ in ids}]
        if unknown:
            print(f"gcd build: unknown case(s) {unknown} (ids are gc_s<seed>_<index>)", file=sys.stderr)
            return 2
        ids = [t for t in ids if t[0] in args.only]
    for cid, seed, index in ids:
        if args.recheck:
            rec = build.recheck(out, cid)
            if rec is not None:
                build.record(out, rec)
                print(
                    f"{cid}: {rec['status']}" + (f" ({rec['reason']})" if rec.get("reason") else ""),
                    flush=True,
                )
            continue
        if args.no_drape and (out / cid / "target.obj").is_file():
            print(f"{cid}: draped already, left as it is", flush=True)
            continue
        t0 = time.time()
        try:
            rec = build.build_case(cid, seed, index, out, drape=not args.no_drape, count=args.count)
        except Exception as exc:  # noqa: BLE001 - recorded, counted, the rest go on
            rec = {
                "case": cid,
                "seed": seed,
                "status": "failed",
                "reason": f"{type(exc).__name__}: {str(exc)[:200]}",
                "seconds": round(time.time() - t0, 1),
            }
            print(f"{cid}: FAILED: {rec['reason']}", flush=True)
        if rec.get("status") == "placed":
            rec = kept.restore(out, cid) or rec
            if rec.get("restored_from"):
                print(f"{cid}: kept newton target restored", flush=True)
        build.record(out, rec)
    return 0


def cmd_keep(args) -> int:
    out = Path(args.out)
    if not (out / "_status").is_dir():
        print(f"gcd keep: {out} holds no build (no _status folder)", file=sys.stderr)
        return 2
    ids = [cid for cid, _, _ in build.case_ids()]
    stored = [cid for cid in ids if kept.keep(out, cid)]
    print(f"kept {len(stored)} of {len(ids)} targets in {kept.KEPT}: {' '.join(stored)}")
    return 0


def cmd_settle(args) -> int:
    """Every built case of ``--out`` (or ``--only``) copied to ``--to`` with its target settled."""
    src, dst = Path(args.out), Path(args.to)
    if not src.is_dir() or src.resolve() == dst.resolve():
        print(f"gcd settle: --out {src} is not a folder, or it is --to", file=sys.stderr)
        return 2
    dst.mkdir(parents=True, exist_ok=True)
    ids = args.only or [c for c, _, _ in build.case_ids() if (src / c / "target.obj").is_file()]
    for cid in ids:
        if not (src / cid / "target.obj").is_file():
            print(f"gcd settle: {cid} has no target in {src}", file=sys.stderr)
            return 2
        try:
            rec = settle.settle_case(src / cid, dst / cid, log=lambda *a: None)
        except (ValueError, RuntimeError) as exc:  # another mesh, or newton diverged
            print(f"gcd settle: {exc}", file=sys.stderr)
            return 2
        state = "at rest" if rec["at_rest"] else "still moving"
        speed = rec["speed_p99_m_s"] * 1000
        print(
            f"{cid}: {rec['frames']} frames, {state} (speed p99 {speed:.1f} mm/s), "
            f"moved {rec['moved_mm']:.2f} mm, {rec['seconds']:.0f} s",
            flush=True,
        )
    return 0


def cmd_remesh(args) -> int:
    """Every case of ``--out`` with a target (or ``--only``) copied to ``--to`` with its target
    meshed finer (remesh.py)."""
    src, dst = Path(args.out), Path(args.to)
    if not src.is_dir() or src.resolve() == dst.resolve():
        print(f"gcd remesh: --out {src} is not a folder, or it is --to", file=sys.stderr)
        return 2
    if not 0.001 <= args.max_edge <= 0.1:
        print(f"gcd remesh: --max-edge {args.max_edge:g} is in metres, within 0.001..0.1", file=sys.stderr)
        return 2
    ids = args.only or [c for c, _, _ in build.case_ids() if (src / c / "target.obj").is_file()]
    missing = [c for c in ids if not (src / c / "target.obj").is_file()]
    if missing:
        print(f"gcd remesh: {missing[0]} has no target in {src}", file=sys.stderr)
        return 2
    dst.mkdir(parents=True, exist_ok=True)
    if (src / "build.json").is_file():  # the copies count as built where the originals do
        (dst / "build.json").write_text((src / "build.json").read_text())
    for cid in ids:
        rec = remesh.remesh_case(src / cid, dst / cid, max_edge=args.max_edge)
        n0, n1 = rec["vertices"]
        print(f"{cid}: {n0} -> {n1} vertices, area {rec['area_m2'][0]:.4f} -> {rec['area_m2'][1]:.4f} m^2")
    return 0


def cmd_status(args) -> int:
    """Table of every case's build status (cases/build.json); cases never attempted listed too."""
    from tables import print_table

    p = Path(args.out) / "build.json"
    recs = json.loads(p.read_text()) if p.is_file() else {}
    rows = []
    for cid, seed, _ in build.case_ids():
        r = recs.get(cid, {})
        rows.append(
            {
                "case": cid,
                "body": build.seed_entry(seed)["body"]["name"],
                "type": r.get("type", ""),
                "status": r.get("status", "not attempted"),
                "vertices": r.get("vertices"),
                "inside %": None if r.get("inside_fraction") is None else 100 * r["inside_fraction"],
                "top drop cm": None if r.get("top_drop_m") is None else 100 * r["top_drop_m"],
                "seam gap mm": r.get("seam_gap_after_sewing_mm"),
                "s": r.get("seconds"),
                "reason": (r.get("reason") or "")[:90],
            }
        )
    print_table(rows, title=f"GarmentCode design benchmark: build status ({p})", digits=2)
    n = {k: sum(1 for r in rows if r["status"] == k) for k in ("built", "failed", "not attempted")}
    print(json.dumps(n))
    return 0


def cmd_types(args) -> int:
    """The garment type and structural choices read off each case's target by unsew (what
    ``unsew fit`` does when meta.json names no type) against the design's truth (reading.py)."""
    import reading

    ids = [cid for cid, _, _ in build.case_ids()]
    return reading.cmd_types(args, ids, TYPES_RECORD)


def _add_types_parser(sub) -> None:
    """The ``types`` subcommand's options."""
    ty = sub.add_parser(
        "types", help="the garment type and structural choices read off each case's target against its truth"
    )
    ty.add_argument("--out", default=str(DEFAULT_CASES))
    ty.add_argument(
        "--drapes", help="folder of `unsew drape` results of the true patterns (<case>.obj): stand-in targets"
    )
    ty.add_argument(
        "--record", action="store_true", help="write the table to benchmarks/results/gcd_types.json"
    )


def _add_starts_parser(sub) -> None:
    """The ``starts`` subcommand's options."""
    st = sub.add_parser(
        "starts", help="the design read, the drafted candidates chosen, against the library's"
    )
    st.add_argument("--out", default=str(DEFAULT_CASES))
    st.add_argument("--drapes", help="folder of `unsew drape` results of the true patterns: stand-in targets")
    st.add_argument("--only", nargs="*", help="case ids (default: every case with a target)")
    st.add_argument(
        "--record", action="store_true", help="write the rows to benchmarks/results/gcd_starts.json"
    )
    st.add_argument(
        "--drafts",
        action="store_true",
        help="no drapes: the design read first, drafted, judged against the true pattern",
    )
    st.add_argument(
        "--darts",
        action="store_true",
        help="with --drafts: each draft judged with its waist darts off and on, and with bust darts",
    )


def _add_fit_score_parsers(sub) -> None:
    """The ``fit`` and ``score`` subcommands' options."""
    s = sub.add_parser("score", help="judge fit results against the cases' truth")
    s.add_argument("--results", required=True, help="folder of fit results, one folder per case id")
    s.add_argument("--cases", default=str(DEFAULT_CASES))
    s.add_argument("--record", action="store_true", help="write the scores to results.json")
    s.add_argument(
        "--no-redrape", action="store_true", help="skip the newton drapes of the recovered and true patterns"
    )
    s.add_argument("--no-floor", action="store_true", help="skip unsew's drape of the true pattern")
    s.add_argument(
        "--only-tried",
        action="store_true",
        help="score only the built cases fitted or tried (a result folder or an outcome in fits.json); "
        "the others keep their recorded rows",
    )
    s.add_argument(
        "--rejudge",
        action="store_true",
        help="judge the recorded fits' patterns again (type, choices, panel error, turning) from "
        "RESULTS, where its fit drapes as the recorded one did; every other figure stands",
    )
    co = sub.add_parser("compare", help="two folders of fits of the same cases judged side by side")
    co.add_argument("before", help="folder of fit results (one folder per case id)")
    co.add_argument("after", help="folder of fit results of the same cases")
    co.add_argument("--cases", default=str(DEFAULT_CASES))
    co.add_argument("--only", nargs="*", help="case ids (default: every case fitted in either folder)")
    fi = sub.add_parser(
        "fit", help="run unsew fit on every built case, each outcome kept in RESULTS/fits.json"
    )
    fi.add_argument("--cases", default=str(DEFAULT_CASES))
    fi.add_argument("--results", required=True, help="folder for one fit result folder per case id")
    fi.add_argument("--only", nargs="*", help="case ids (default: every built case)")
    fi.add_argument("--redo", action="store_true", help="fit again a case with an outcome already")
    gr = sub.add_parser(
        "graded", help="copy the fits whose phase two was kept with their graded pattern as the result"
    )
    gr.add_argument("--results", required=True, help="folder of fit results, one folder per case id")
    gr.add_argument("--to", required=True, help="folder for the copies")
    gr.add_argument("--cases", default=str(DEFAULT_CASES), help="the case folders (their wearers)")
    rx = sub.add_parser(
        "reexport", help="copy fit results with each pattern.json placed where its garment.obj drapes it"
    )
    rx.add_argument("--results", required=True, help="folder of fit results, one folder per case id")
    rx.add_argument("--to", required=True, help="folder for the re-exported copies")
    rx.add_argument("--cases", default=str(DEFAULT_CASES), help="the case folders (their wearers)")
    fi.add_argument(
        "--material-only",
        action="store_true",
        help="hold each case's true pattern and fit its material only (the material-fitted floor)",
    )


def _own_options(argv: list) -> int:
    """``panels`` (the judge's per-piece errors of each fit stage) and ``sew-probe`` (newton's
    sewing phase alone on one case), which parse their own options."""
    if argv[0] == "panels":
        import panels

        return panels.main(argv[1:])
    import sew_probe

    return sew_probe.main(argv[1:])


def _folders_given(args) -> bool:
    """Whether the folders ``types``, ``starts`` and ``unwelded`` read exist (else one line on stderr: a
    missing folder is an error, not an empty table)."""
    for opt in ("out", "drapes"):
        d = getattr(args, opt, None)
        if d is not None and not Path(d).is_dir():
            print(f"gcd {args.cmd}: --{opt} {d} is not a folder", file=sys.stderr)
            return False
    return True


def _add_build_parsers(sub) -> None:
    b = sub.add_parser("build", help="sample, drape with newton and write the case folders")
    b.add_argument("--out", default=str(DEFAULT_CASES))
    b.add_argument("--seeds", default="1-5", help="seeds, e.g. 1-5 or 1,3")
    b.add_argument("--count", type=int, default=None, help="designs per seed (default: the manifest's)")
    b.add_argument("--only", nargs="*", help="case ids to build (gc_s1_000 ...)")
    b.add_argument(
        "--no-drape",
        action="store_true",
        help="sample, size, mesh and place only (no newton); kept targets are restored (kept.py)",
    )
    b.add_argument(
        "--recheck", action="store_true", help="re-run the acceptance checks on the written cases (no drape)"
    )
    ff = sub.add_parser(
        "floor-fitted", help="record the material-fitted floor of the built cases (the true pattern's fit)"
    )
    ff.add_argument(
        "--results", required=True, help="folder of `gcd fit --material-only` results, one per case id"
    )
    ff.add_argument("--cases", default=str(DEFAULT_CASES))
    ff.add_argument("--record", action="store_true", help="write them into results.json")


def _add_copy_parsers(sub) -> None:
    """The modes that copy the built cases with their targets changed: settle, remesh."""
    se = sub.add_parser("settle", help="copy the built cases with each newton target run on until at rest")
    se.add_argument("--out", default=str(DEFAULT_CASES), help="the built cases")
    se.add_argument("--to", required=True, help="folder for the settled copies")
    se.add_argument("--only", nargs="*", help="case ids (default: every case with a target)")
    rm = sub.add_parser("remesh", help="copy the cases with each target meshed finer (the same surface)")
    rm.add_argument("--out", default=str(DEFAULT_CASES), help="the built cases")
    rm.add_argument("--to", required=True, help="folder for the copies")
    rm.add_argument("--max-edge", type=float, default=remesh.MAX_EDGE, help="longest target edge [m]")
    rm.add_argument("--only", nargs="*", help="case ids (default: every case with a target)")


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] in (["panels"], ["sew-probe"]):  # the modes with their own options
        return _own_options(argv)
    ap = argparse.ArgumentParser(prog="python -m benchmarks gcd", description=__doc__.splitlines()[0])
    ap.add_argument("--summary", action="store_true", help="one JSON line of the recorded results")
    ap.add_argument("--record-file", default=str(RESULTS), help=argparse.SUPPRESS)
    sub = ap.add_subparsers(dest="cmd")
    _add_build_parsers(sub)
    _add_fit_score_parsers(sub)
    sub.add_parser("judge-check", help="the judge on synthetic inputs")
    sub.add_parser(
        "panels", help="per true piece of each fit stage, and the darts' floor (gcd panels --help)"
    )
    st = sub.add_parser("status", help="table of every case's build status")
    st.add_argument("--out", default=str(DEFAULT_CASES))
    kp = sub.add_parser("keep", help="store the built cases' newton targets in benchmarks/gcd/targets")
    kp.add_argument("--out", default=str(DEFAULT_CASES))
    _add_copy_parsers(sub)
    _add_types_parser(sub)
    _add_starts_parser(sub)
    uw = sub.add_parser("unwelded", help="the design read off each newton target with its panels unwelded")
    uw.add_argument("--out", default=str(DEFAULT_CASES))
    uw.add_argument("--only", nargs="*", help="case ids (default: every case with a newton target)")
    uw.add_argument("--no-weld", action="store_true", help="the repair's seam welding off (as before it)")
    args = ap.parse_args(argv)
    if args.cmd in ("types", "starts", "unwelded") and not _folders_given(args):
        return 2
    if args.cmd == "starts" and args.darts and not args.drafts:
        print("gcd starts: --darts judges the drafts; give it with --drafts", file=sys.stderr)
        return 2
    modes = {
        "types": cmd_types,
        "starts": lambda a: starts.cmd_starts(a, [cid for cid, _, _ in build.case_ids()], STARTS_RECORD),
        "unwelded": lambda a: unwelded.cmd_unwelded(a, [cid for cid, _, _ in build.case_ids()]),
        "build": cmd_build,
        "fit": lambda a: fits.cmd_fit(a, [cid for cid, _, _ in build.case_ids()]),
        "score": lambda a: score.cmd_score(a, Path(a.record_file)),
        "compare": lambda a: compare.cmd_compare(a, [cid for cid, _, _ in build.case_ids()]),
        "reexport": lambda a: fits.cmd_reexport(a, [cid for cid, _, _ in build.case_ids()]),
        "graded": lambda a: fits.cmd_graded(a, [cid for cid, _, _ in build.case_ids()]),
        "floor-fitted": lambda a: score.cmd_floor_fitted(a, Path(a.record_file)),
        "status": cmd_status,
        "keep": cmd_keep,
        "settle": cmd_settle,
        "remesh": cmd_remesh,
        "judge-check": lambda a: score.judge_check(),
    }
    if args.cmd in modes:
        return modes[args.cmd](args)
    rec = score.load_record(Path(args.record_file))
    if args.summary:
        print(json.dumps(score.summary(rec)))
        return 0
    score.print_record(rec)
    return 0


if __name__ == "__main__":
    sys.exit(main())
