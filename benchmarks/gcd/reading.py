"""The garment type and structural choices read off each GarmentCode case's target against the
design's truth (truth.py, from design_params.yaml).

A case's target is its newton drape where the build accepted it (``built`` in build.json);
otherwise the true pattern dressed by ``unsew drape`` (DRAPES/<case>.obj) stands in for it, and
where neither exists the newton drape that failed its checks. Each row names its target's source:
a stand-in is unsew's own drape, so a reading right on it says less than one on newton's. A
stand-in whose top hangs more than the build's ``MAX_DROP`` below where the specification puts it
(the newton build's slide check) is marked as slid. Sound targets: newton's accepted drapes and
the stand-ins that passed their check and did not slide; the summaries count all rows and these.
"""

from __future__ import annotations

import json
import subprocess
import warnings
from pathlib import Path

import numpy as np
import truth as gt_truth

#: Choices read off the shape and scored (truth.design_of's keys).
SCORED = ("sleeves", "neck_front", "neck_back", "collar", "skirt", "length")
#: The reading's measures printed beside each row (DesignReading.numbers' keys).
MEASURES = (
    "sleeve_share",
    "over_shoulders",
    "front_deg",
    "back_deg",
    "front_flat",
    "back_flat",
    "flare",
    "hem_share",
    "fit_ease",
)
#: Choices in the truth that the reading does not read (listed, not scored).
NOT_READ = ("cuffs", "waistband")
SOURCES = {
    "newton": "newton",
    "unsew": "unsew drape of the true pattern",
    "unsew-failed": "unsew drape of the true pattern (failed its check)",
    "newton-failed": "newton (failed its checks)",
}
#: Sources whose target is sound (the unsew ones only where they did not slide, :func:`slid`).
SOUND = ("newton", "unsew")


def spec_top(spec: dict) -> float:
    """The height [m] of the specification's highest panel vertex, placed by its panel's
    ``rotation`` and ``translation`` as the build places it (build.spec_placement)."""
    from build import spec_rotation

    scale = float(spec.get("properties", {}).get("units_in_meter", 100))
    top = -np.inf
    for pd in spec["pattern"]["panels"].values():
        V = np.asarray(pd["vertices"], np.float64)
        x = np.c_[V, np.zeros(len(V))] @ spec_rotation(pd.get("rotation", [0, 0, 0])).T
        top = max(top, float((x[:, 1] + float(pd.get("translation", [0, 0, 0])[1])).max()) / scale)
    return top


def slid(d: Path, verts) -> float:
    """How far [m] the target's top ``verts`` (V, 3) [m] hangs below where case folder ``d``'s
    specification puts it."""
    return spec_top(json.loads((d / "pattern_gt.json").read_text())) - float(np.asarray(verts)[:, 1].max())


def build_status(root: Path, cid: str) -> str:
    """The case's build status from build.json beside the case folders (following a symlinked
    case folder to its own root); "?" when none says."""
    for p in (root / "build.json", (root / cid).resolve().parent / "build.json"):
        if p.is_file():
            rec = json.loads(p.read_text()).get(cid)
            if rec:
                return rec.get("status", "?")
    return "?"


def target_of(root: Path, cid: str, drapes: Path | None) -> tuple[str, Path] | None:
    """(source key of :data:`SOURCES`, target mesh path) of a case, or None without any target."""
    d = root / cid
    newton = d / "target.obj"
    if newton.is_file() and build_status(root, cid) == "built":
        return "newton", newton
    if drapes is not None:
        for key, name in (("unsew", f"{cid}.obj"), ("unsew-failed", f"{cid}.failed.obj")):
            if (drapes / name).is_file():
                return key, drapes / name
    if newton.is_file():
        return "newton-failed", newton
    return None


def read_case(d: Path, target: Path):
    """(the DesignReading of the target mesh ``target`` on case folder ``d``'s body, how far [m]
    the target's top hangs below the specification's, :func:`slid`)."""
    from unsew.body.body import load_body
    from unsew.grading.design_reading import read_design
    from unsew.io.mesh import read_garment

    skel = d / "skeleton.json"
    body = load_body(d / "body.obj", skel if skel.is_file() else None)
    with warnings.catch_warnings():  # a repaired mesh is announced by a warning: not this table's news
        warnings.simplefilter("ignore")
        v, f, _ = read_garment(target)
    return read_design(v, f, body.skeleton, body=body), slid(d, v)


def truth_of(d: Path) -> dict:
    """{"type", and truth.design_of's choices} of case folder ``d``."""
    spec = json.loads((d / "pattern_gt.json").read_text())
    out = gt_truth.design_of((d / "design_params.yaml").read_text(), spec=spec)
    out["type"] = json.loads((d / "truth.json").read_text())["type"]
    return out


def _cell(true, read) -> str:
    """A table cell: the true value, and what was read where it differs ("-": no such part)."""
    t = "-" if true is None else ("yes" if true is True else "no" if true is False else str(true))
    if read == true:
        return t
    return f"{t} (read {'-' if read is None else read})"


def row_of(cid: str, source: str, t: dict, r) -> dict:
    """One table row: case, target source, and true (read) per choice."""
    row = {"case": cid, "target": source, "type": _cell(t["type"], r.garment if r else "refused")}
    ch = r.choices() if r is not None else {}
    for k in SCORED:
        row[k.replace("_", " ")] = _cell(t[k], ch.get(k))
    for k in NOT_READ:
        row[k] = _cell(t[k], t[k])
    row["evidence"] = "" if r is None else "; ".join(f"{k}: {v}" for k, v in r.evidence.items())[:160]
    # the measures each choice was read from (its thresholds' margins), printed, not recorded
    row["measures"] = "" if r is None else " ".join(f"{k}={v}" for k, v in r.numbers.items() if k in MEASURES)
    row["_right"] = {"type": r is not None and r.garment == t["type"]}
    row["_right"].update({k: t[k] == ch.get(k) for k in SCORED if t[k] is not None})
    return row


def summary(rows: list[dict]) -> dict:
    """{"cases", "type": (right, n), choice: (right, n), "choices": (right, n)} over ``rows``."""
    out = {"cases": len(rows)}
    for k in ("type", *SCORED):
        got = [r["_right"][k] for r in rows if k in r["_right"]]
        out[k] = (sum(got), len(got))
    out["choices"] = tuple(sum(out[k][i] for k in SCORED) for i in (0, 1))
    return out


def summary_line(s: dict, what: str) -> str:
    each = ", ".join(f"{k.replace('_', ' ')} {s[k][0]}/{s[k][1]}" for k in SCORED)
    return (
        f"{what}: type right {s['type'][0]}/{s['type'][1]}; {each}; "
        f"choices right overall {s['choices'][0]}/{s['choices'][1]}"
    )


def summary_row(s: dict, what: str) -> dict:
    """The summary as a table row (x/N per column)."""
    row = {
        "case": what,
        "target": f"{s['cases']} cases; choices right {s['choices'][0]}/{s['choices'][1]}",
        "type": f"{s['type'][0]}/{s['type'][1]}",
    }
    row.update({k.replace("_", " "): f"{s[k][0]}/{s[k][1]}" for k in SCORED})
    row.update({k: "not read" for k in NOT_READ})
    return row


def table(root: Path, drapes: Path | None, case_ids: list[str]) -> list[dict]:
    """One row per case of ``case_ids`` that has a target (see :func:`target_of`)."""
    from build import MAX_DROP

    from unsew.errors import InputError

    rows = []
    for cid in case_ids:
        d = root / cid
        if not (d / "truth.json").is_file():
            continue
        tgt = target_of(root, cid, drapes)
        if tgt is None:
            continue
        drop = 0.0
        try:
            r, drop = read_case(d, tgt[1])
        except InputError as exc:
            r = None
            print(f"{cid}: the reading refused: {str(exc).splitlines()[0]}", flush=True)
        row = row_of(cid, SOURCES[tgt[0]], truth_of(d), r)
        row["_sound"] = tgt[0] in SOUND and not (tgt[0] == "unsew" and drop > MAX_DROP)
        if tgt[0] == "unsew" and drop > MAX_DROP:
            row["target"] += f" (slid {100 * drop:.0f} cm)"
        rows.append(row)
    return rows


def _commit() -> str:
    try:
        out = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, check=True
        )
        return out.stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "?"


def cmd_types(args, case_ids: list[str], record: Path) -> int:
    """Print the table and the summaries; with ``args.record`` write them to ``record``."""
    from unsew.errors import InputError

    root = Path(args.out)
    drapes = Path(args.drapes) if args.drapes else None
    for p, what in ((root, "--out"), (drapes, "--drapes")):
        if p is not None and not p.is_dir():
            raise InputError(f"{what} {p} is not a folder")
    from tables import print_table  # benchmarks/tables.py (on the path when run as a benchmark)

    rows = table(root, drapes, case_ids)
    shown = [{k: v for k, v in r.items() if not k.startswith("_")} for r in rows]
    print_table(shown, title=f"Garment type and structural choices read off the targets in {root}")
    newton = [r for r in rows if r["target"] == SOURCES["newton"]]
    sound = [r for r in rows if r["_sound"]]
    lines = [summary_line(summary(rows), f"all {len(rows)} cases")]
    lines.append(summary_line(summary(sound), f"{len(sound)} sound targets"))
    lines.append(summary_line(summary(newton), f"{len(newton)} newton targets"))
    print("\n".join(lines))
    if args.record:
        all_row, newton_row = summary_row(summary(rows), "all"), summary_row(summary(newton), "newton only")
        sound_row = summary_row(summary(sound), "sound targets")
        rec = {
            "title": "GarmentCode design benchmark: the type and structural choices read off each target "
            "(true, and what was read where it differs)",
            "command": "python -m benchmarks gcd types --out CASES --drapes DRAPES --record",
            "commit": _commit(),
            "rows": [
                *({k: v for k, v in r.items() if k not in ("evidence", "measures")} for r in shown),
                all_row,
                sound_row,
                newton_row,
            ],
        }
        record.write_text(json.dumps(rec, indent=1) + "\n")
        print(f"wrote {record}")
    return 0
