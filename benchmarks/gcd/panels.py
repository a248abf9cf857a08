"""Which true panels carry the GarmentCode benchmark's panel error and turning distance, and the
turning distance a pattern without darts cannot go below.

Per built case with a result folder (``RESULTS/<case>``), per stage of the fit (``--files``: the
chosen start ``pattern_base.json``, the graded ``pattern_graded.json``, the final ``pattern.json``):
the judge's panel error and turning distance (benchmarks/gcd/judge.py, both patterns merged
first), the pieces' counts, and per true piece the recovered pieces standing for it, relative
area error (1: none) and turning distance. Then the darts' floor: each true piece against itself with
every dart closed (a point of the outline where it turns by more than ``DART_TURN``, moved to
the middle of its neighbours), the turning distance of a pattern whose outlines are the true
ones but without darts.

    python -m benchmarks gcd panels --results R --cases CASES [--files pattern_base.json,pattern.json]
        [--by-placement]
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))
import judge  # noqa: E402

#: An outline point turning by more than this is a dart's tip [rad].
DART_TURN = np.radians(140.0)


def close_darts(loop: np.ndarray) -> tuple[np.ndarray, int]:
    """The closed outline (N, 2) with each dart tip moved to the middle of its neighbours, and the
    number of tips moved."""
    out, k = loop.copy(), 0
    for i in range(len(out)):
        a, b, c = out[i - 1], out[i], out[(i + 1) % len(out)]
        d1, d2 = b - a, c - b
        if abs(np.arctan2(d1[0] * d2[1] - d1[1] * d2[0], d1 @ d2)) > DART_TURN:
            out[i], k = 0.5 * (a + c), k + 1
    return out, k


def dart_floor(spec: dict) -> tuple[float, int]:
    """(mean turning distance [rad] of the true pieces against themselves without darts, darts)."""
    pieces = judge.merge_invisible(spec)
    dists, darts = [], 0
    for p in pieces:
        closed, k = close_darts(p.loop())
        darts += k
        dists.append(judge.turning_distance(p.loop(), closed) if k else 0.0)
    return float(np.mean(dists)), darts


def case_rows(case: Path, result: Path, files: list[str], *, by_placement: bool = False) -> list[dict]:
    """One row per stage file of ``result`` against ``case``'s true pattern, with its pieces: each
    stage's pieces stand for the true ones the final garment.obj drapes them over (the stages
    share their panels), by placement where that is not at hand or ``by_placement`` (``match``)."""
    spec = json.loads((case / "pattern_gt.json").read_text())
    shares = None if by_placement else _final_shares(case, result, spec)
    rows = []
    for fn in files:
        if not (result / fn).is_file():
            continue
        spec_rec = json.loads((result / fn).read_text())
        use = shares if shares is not None and set(spec_rec["pattern"]["panels"]) <= set(shares) else None
        cmp = judge.compare_patterns(spec, spec_rec, use)
        pieces = "; ".join(
            f"{'+'.join(t)} -> {'+'.join(r)} {e:.2f}/{tu:.2f}" for t, r, e, tu in cmp["matched"]
        )
        rows.append(
            {
                "case": case.name,
                "stage": fn.removesuffix(".json"),
                "panel err": round(cmp["panel_err"], 3),
                "turning": round(cmp["turning"], 3) if cmp["turning"] is not None else None,
                "pieces t/r": f"{cmp['panels_true']}/{cmp['panels_rec']}",
                "match": "placement" if use is None else "drape",
                "matched (area err/turning)": pieces,
            }
        )
    return rows


def _final_shares(case: Path, result: Path, spec: dict):
    """score.panel_shares of the fit's final pattern and garment.obj, or None (newton drapes the
    true pattern once where the target's rest mesh is not kept: score.true_cloth)."""
    import score

    if not (result / "pattern.json").is_file() or not (result / "garment.obj").is_file():
        return None
    truth = json.loads((case / "truth.json").read_text())
    spec_rec = json.loads((result / "pattern.json").read_text())
    target = score.read_obj(case / "target.obj")
    return score.panel_shares(case, result, spec, spec_rec, truth, target)


def phase_two_rows(rows: list[dict], results: Path, record: dict) -> list[dict]:
    """Per case fitted in both stages: phase two's move (graded -> final) in the fit's own
    Chamfer [mm] (metrics.json) and in the judge's panel error and turning distance, beside the
    case's material-fitted floor [mm] (``gcd floor-fitted``, from the recorded results)."""
    by = {(r["case"], r["stage"]): r for r in rows}
    out = []
    for cid in sorted({c for c, _ in by}):
        g, f = by.get((cid, "pattern_graded")), by.get((cid, "pattern"))
        mp = results / cid / "metrics.json"
        if g is None or f is None or not mp.is_file():
            continue
        m = json.loads(mp.read_text())
        cg, cf = (m.get("surface_graded") or {}).get("chamfer_mm"), (m.get("surface") or {}).get("chamfer_mm")
        floor = (record.get("cases", {}).get(cid) or {}).get("floor_fitted_mm")
        moved = abs(f["panel err"] - g["panel err"]) > 1e-3 or f["turning"] != g["turning"]
        out.append(
            {
                "case": cid,
                "Chamfer graded -> final mm": f"{cg:.2f} -> {cf:.2f}" if cg and cf else "-",
                "floor fitted mm": floor,
                "below floor": None if floor is None or cf is None else cf < floor,
                "panel err": f"{g['panel err']:.3f} -> {f['panel err']:.3f}",
                "turning": f"{g['turning']:.3f} -> {f['turning']:.3f}"
                if g["turning"] and f["turning"]
                else "-",
                "pattern moved": moved,
                "panel err worse": f["panel err"] > g["panel err"] + 1e-3,
            }
        )
    return out


def _phase_two_line(rows: list[dict]) -> str:
    """One line: of the cases phase two moved, how many it made worse, and of those ending below
    their material-fitted floor, how many it made worse."""
    moved = [r for r in rows if r["pattern moved"]]
    below = [r for r in moved if r["below floor"]]
    return (
        f"phase two moved the pattern of {len(moved)} of {len(rows)} cases, its panel error worse on "
        f"{sum(r['panel err worse'] for r in moved)}; {len(below)} of them end below their "
        f"material-fitted floor, worse on {sum(r['panel err worse'] for r in below)}"
    )


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks gcd panels", description=__doc__.splitlines()[0])
    ap.add_argument("--results", required=True, help="folder of fit results, one per case")
    ap.add_argument("--cases", required=True, help="folder of built cases (target.obj, pattern_gt.json)")
    ap.add_argument("--files", default="pattern_base.json,pattern_graded.json,pattern.json")
    ap.add_argument(
        "--by-placement",
        action="store_true",
        help="match the pieces one to one by their placement (the judge without drapes), "
        "not by where they drape",
    )
    args = ap.parse_args(argv)
    for what, d in (("--results", args.results), ("--cases", args.cases)):
        if not Path(d).is_dir():
            print(f"gcd panels: {what} {d} is not a folder", file=sys.stderr)
            return 2
    from tables import print_table

    files = args.files.split(",")
    cases = sorted(d for d in Path(args.cases).iterdir() if (d / "target.obj").is_file())
    build = Path(args.cases) / "build.json"
    if build.is_file():  # the built cases only (a failed build leaves its folder)
        built = json.loads(build.read_text())
        cases = [d for d in cases if built.get(d.name, {}).get("status") == "built"]
    rows, floors = [], []
    for case in cases:
        if (Path(args.results) / case.name).is_dir():
            rows += case_rows(case, Path(args.results) / case.name, files, by_placement=args.by_placement)
        f, k = dart_floor(json.loads((case / "pattern_gt.json").read_text()))
        floors.append({"case": case.name, "darts": k, "turning without darts": round(f, 3)})
    print_table(rows, title="panels of the recovered patterns against the true ones", digits=3)
    for fn in files:
        got = [r for r in rows if r["stage"] == fn.removesuffix(".json")]
        if got:
            e, t = [r["panel err"] for r in got], [r["turning"] for r in got if r["turning"] is not None]
            print(
                f"{fn}: {len(got)} cases, panel err median {np.median(e):.3f} "
                f"p90 {np.percentile(e, 90):.3f}, turning median {np.median(t):.3f}"
            )
    if "pattern_graded.json" in files and "pattern.json" in files:
        rec_p = HERE / "results.json"
        two = phase_two_rows(
            rows, Path(args.results), json.loads(rec_p.read_text()) if rec_p.is_file() else {}
        )
        print_table(two, title="phase two: graded -> final, beside the material-fitted floor", digits=2)
        print(_phase_two_line(two))
    print_table(floors, title="the true pieces against themselves with their darts closed", digits=3)
    print(f"turning without darts: median {np.median([f['turning without darts'] for f in floors]):.3f}")
    return 0
