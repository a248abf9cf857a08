"""Do GarmentCode's bodies measure their own bust, waist and hips whatever skeleton comes with them?

For each body of GarmentCode (``<bodies>/*.obj`` with its ``.yaml`` giving bust, waist and hips
in cm) the body is measured as ``unsew body measure`` does (``load_body`` then
``cross_check_rig``) with four skeletons:

- ``none``: no skeleton.json (rigged from the mesh);
- ``rig``: the skeleton ``unsew body rig`` writes, given as skeleton.json;
- ``limb``: the same joints with the limb labels many rigs put on the limbs' root joints
  (``left_shoulder: left_arm``, ``left_hip: left_leg``);
- ``smpl``: SMPL-style joint placements (:func:`smpl_style`): the pelvis 9 cm above the hip
  joints, which sit inside the pelvis 6 cm from the mid-plane, three spine joints, collar joints,
  limb labels, joints listed in shuffled order.

Prints one row per body and skeleton (measured / the yaml's, cm) and the largest absolute error
over the acceptance's three skeletons (none, rig, limb) and over all four. A skeleton refused
(one line) is printed as such.

``--anny``: the same on the anny bodies of benchmarks/data and the default body written as files
(body.obj and its own skeleton.json, so without skinning weights), against the girths the body
reads with its own skinning weights; the skeleton ``own`` is anny's joints, ``limb`` and ``smpl``
are made from them; and the reading with the rig's skeleton (``none``) beside them.

``--record``: the table of GarmentCode's bodies into benchmarks/results/body_measure.json (the
skeletons that read the same grouped in one row) with its command and commit.

``--cause``: per body, where the bust is read and how its section is cut: the bust level and
girth with the rig's skeleton and with the SMPL-style one, and each skeleton's girth at the
other's level (a different level, or the same level cut otherwise: the arms' faces).

Run: PYTHONPATH=src:benchmarks .venv/bin/python -m benchmarks body_measure
     [--bodies ../shared/foreign/bodies] [--names mean_female,mean_male] [--quick] [--anny]
     [--record] [--cause]
"""

from __future__ import annotations

import argparse
import copy
import json
import os
import random
import tempfile
from pathlib import Path

import numpy as np

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

HERE = Path(__file__).resolve().parent
BODIES = Path(os.environ.get("UNSEW_SHARED", HERE.parents[1] / "shared")) / "foreign" / "bodies"
VARIANTS = ("none", "rig", "limb", "smpl")
ACCEPTANCE = ("none", "rig", "limb")
GIRTHS = (("bust", "bust"), ("waist", "waist"), ("hip", "hips"))  # (Measurements field, yaml key)


def limb_labelled(d: dict) -> dict:
    """A skeleton.json mapping with the limbs' root joints labelled with their limb."""
    out = copy.deepcopy(d)
    for j in out["joints"]:
        for side in ("left", "right"):
            if j["name"] == f"{side}_shoulder":
                j["part"] = f"{side}_arm"
            if j["name"] == f"{side}_hip":
                j["part"] = f"{side}_leg"
    return out


def smpl_style(d: dict, *, seed: int = 0) -> dict:
    """A skeleton.json mapping [m] with SMPL's joint placements built from our 17 joints: the hip
    joints 3 cm lower and 6 cm from the mid-plane, the pelvis 9 cm above them, spine / spine2 /
    chest at 25, 55 and 65 % of the way pelvis -> neck, collar joints between chest and
    shoulders, limb-labelled limb roots; the joints listed in an order shuffled by ``seed``."""
    J = {j["name"]: np.asarray(j["position"], dtype=np.float64) for j in d["joints"]}
    hip_y = 0.5 * (J["left_hip"][1] + J["right_hip"][1]) - 0.03
    P = np.array([J["pelvis"][0], hip_y + 0.09, J["pelvis"][2]])
    neck = J["neck"]
    out = []

    def add(name, parent, pos, part):
        out.append({"name": name, "parent": parent, "position": [float(v) for v in pos], "part": part})

    add("pelvis", None, P, "torso")
    add("spine", "pelvis", P + 0.25 * (neck - P), "torso")
    add("spine2", "spine", P + 0.55 * (neck - P), "torso")
    add("chest", "spine2", P + 0.65 * (neck - P), "torso")
    add("neck", "chest", neck, "torso")
    add("head", "neck", J["head"], "head")
    for side, sign in (("left", 1.0), ("right", -1.0)):
        sh = J[f"{side}_shoulder"]
        add(f"{side}_collar", "chest", [P[0] + sign * 0.07, sh[1] - 0.03, sh[2]], "torso")
        add(f"{side}_shoulder", f"{side}_collar", sh, f"{side}_arm")
        add(f"{side}_elbow", f"{side}_shoulder", J[f"{side}_elbow"], f"{side}_arm")
        add(f"{side}_wrist", f"{side}_elbow", J[f"{side}_wrist"], f"{side}_arm")
        add(f"{side}_hip", "pelvis", [P[0] + sign * 0.06, hip_y, J[f"{side}_hip"][2]], f"{side}_leg")
        add(f"{side}_knee", f"{side}_hip", J[f"{side}_knee"], f"{side}_leg")
        add(f"{side}_ankle", f"{side}_knee", J[f"{side}_ankle"], f"{side}_leg")
    random.Random(seed).shuffle(out)
    return {"units": "m", "joints": out}


def measure_variants(mesh: Path, variants=VARIANTS) -> dict:
    """{variant: Measurements or the one-line refusal (str)} for one body mesh."""
    from unsew.body.body import load_body
    from unsew.body.measure import cross_check_rig

    rigged = load_body(mesh)
    rig = rigged.skeleton.to_dict()
    files = {"rig": rig, "limb": limb_labelled(rig), "smpl": smpl_style(rig)}
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        for v in variants:
            if v == "none":
                out[v] = cross_check_rig(rigged)
                continue
            path = Path(tmp) / f"{v}.json"
            path.write_text(json.dumps(files[v]))
            out[v] = _measured(mesh, path)
    return out


def anny_rows() -> list[dict]:
    """Rows {body, variant, measured, reference} for the default body and benchmarks/data's anny
    bodies as files: the reference is the girths [cm] read with the body's skinning weights."""
    from unsew.body.body import body_from_npz, default_body
    from unsew.body.measure import measure_body
    from unsew.body.skeleton import save_skeleton
    from unsew.io.mesh import write_obj

    bodies = [("default", default_body())]
    bodies += [(p.stem, body_from_npz(p)) for p in sorted((HERE / "data").glob("body_*.npz"))]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, b in bodies:
            m0 = measure_body(b)
            ref = {rk: getattr(m0, k) * 100 for k, rk in GIRTHS}
            mesh = Path(tmp) / f"{name}.obj"
            write_obj(mesh, b.verts, b.faces)
            save_skeleton(b.skeleton, Path(tmp) / "own.json")
            own = json.loads((Path(tmp) / "own.json").read_text())
            got = measure_variants(mesh, ("none",))
            for v, d in (("own", own), ("limb", limb_labelled(own)), ("smpl", smpl_style(own))):
                (Path(tmp) / f"{v}.json").write_text(json.dumps(d))
                got[v] = _measured(mesh, Path(tmp) / f"{v}.json")
            rows += [{"body": name, "variant": v, "measured": m, "reference": ref} for v, m in got.items()]
    return rows


def _measured(mesh: Path, skeleton: Path):
    """What ``unsew body measure`` reads: Measurements, or its one-line refusal (str)."""
    from unsew.body.body import load_body
    from unsew.body.measure import cross_check_rig
    from unsew.errors import InputError

    try:
        return cross_check_rig(load_body(mesh, skeleton))
    except InputError as exc:
        return str(exc)


def table(rows: list[dict], variants=VARIANTS) -> tuple[str, dict]:
    """The Markdown table of rows {body, variant, measured, reference} and the largest absolute
    error [cm] per group of variants ({"acceptance": ..., "all": ...}; inf when one was refused)."""
    lines = [
        "| body | skeleton | bust [cm] | waist [cm] | hips [cm] | max abs error [cm] |",
        "|---|---|---|---|---|---|",
    ]
    worst = {"acceptance": 0.0, "all": 0.0}
    for r in rows:
        m, ref = r["measured"], r["reference"]
        if isinstance(m, str):
            lines.append(f"| {r['body']} | {r['variant']} | refused: {m} | | | |")
            err = float("inf")
        else:
            errs = [abs(getattr(m, k) * 100 - ref[rk]) for k, rk in GIRTHS]
            err = max(errs)
            cells = [f"{getattr(m, k) * 100:.1f} / {ref[rk]:.1f}" for k, rk in GIRTHS]
            lines.append(f"| {r['body']} | {r['variant']} | " + " | ".join(cells) + f" | {err:.1f} |")
        worst["all"] = max(worst["all"], err)
        if r["variant"] in ACCEPTANCE:
            worst["acceptance"] = max(worst["acceptance"], err)
    return "\n".join(lines), worst


def run(bodies: Path, names: list[str], variants=VARIANTS) -> tuple[str, dict]:
    return table(run_rows(bodies, names, variants), variants)


def run_rows(bodies: Path, names: list[str], variants=VARIANTS) -> list[dict]:
    """Rows {body, variant, measured, reference} of GarmentCode's bodies (see :func:`run`)."""
    import yaml

    from unsew.errors import InputError

    rows = []
    for name in names:
        mesh = bodies / f"{name}.obj"
        if not mesh.is_file() or not mesh.with_suffix(".yaml").is_file():
            raise InputError(f"no GarmentCode body {mesh} with its .yaml; pass --bodies")
        ref = yaml.safe_load(mesh.with_suffix(".yaml").read_text())["body"]
        for v, m in measure_variants(mesh, variants).items():
            rows.append({"body": name, "variant": v, "measured": m, "reference": ref})
    return rows


def record_rows(rows: list[dict]) -> list[dict]:
    """The recorded table's rows: per body, the skeletons whose bust, waist and hips read the same
    (to 0.1 cm) in one row ("none, rig, limb"; SMPL-style named so), measured / the .yaml [cm]
    and the largest absolute error [cm]; a refused skeleton's row says so."""
    names = {"smpl": "SMPL-style"}
    out: list[dict] = []
    for body in dict.fromkeys(r["body"] for r in rows):
        groups: dict = {}
        for r in (r for r in rows if r["body"] == body):
            m, ref = r["measured"], r["reference"]
            if isinstance(m, str):
                cells = {"bust": f"refused: {m}", "waist": "", "hips": "", "max error": None}
            else:
                cells = {rk: f"{getattr(m, k) * 100:.1f} / {ref[rk]:.1f}" for k, rk in GIRTHS}
                cells["max error"] = round(max(abs(getattr(m, k) * 100 - ref[rk]) for k, rk in GIRTHS), 1)
            groups.setdefault(json.dumps(cells), []).append(names.get(r["variant"], r["variant"]))
        out += [{"body": body, "skeleton": ", ".join(v), **json.loads(k)} for k, v in groups.items()]
    return out


def record(rows: list[dict], path: Path = HERE / "results" / "body_measure.json") -> None:
    """Write the table of GarmentCode's bodies with its command and commit (benchmarks/report.py
    makes docs/benchmarks.md from it)."""
    from tables import git_commit

    rec = {
        "title": "GarmentCode's bodies measured with no skeleton, the mesh rig's, a limb-labelled and an "
        "SMPL-style one (cm; measured / the body's .yaml)",
        "command": "python -m benchmarks body_measure --record",
        "commit": git_commit(),
        "rows": record_rows(rows),
    }
    path.write_text(json.dumps(rec, indent=1) + "\n")


def cause_rows(bodies: Path, names: list[str]) -> str:
    """Markdown table: per body, the bust level [m] and girth [cm] with the rig's skeleton and the
    SMPL-style one, and each one's girth at the other's level [cm]."""
    from unsew.body.body import load_body
    from unsew.body.measure import bust_reading

    lines = [
        "| body | rig: level m, bust cm | SMPL-style: level m, bust cm | rig at SMPL's level | "
        "SMPL-style at the rig's level |",
        "|---|---|---|---|---|",
    ]
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            mesh = bodies / f"{name}.obj"
            rig = load_body(mesh)
            path = Path(tmp) / "smpl.json"
            path.write_text(json.dumps(smpl_style(rig.skeleton.to_dict())))
            smpl = load_body(mesh, path)
            (g_r, y_r), (g_s, y_s) = bust_reading(rig), bust_reading(smpl)
            lines.append(
                f"| {name} | {y_r:.3f}, {g_r * 100:.1f} | {y_s:.3f}, {g_s * 100:.1f} | "
                f"{bust_reading(rig, at=y_s)[0] * 100:.1f} | {bust_reading(smpl, at=y_r)[0] * 100:.1f} |"
            )
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bodies", default=str(BODIES), help="folder of GarmentCode's body .obj and .yaml files")
    ap.add_argument("--names", default="", help="comma-separated body names (default: every .obj there)")
    ap.add_argument("--quick", action="store_true", help="one body (mean_female) only")
    ap.add_argument("--record", action="store_true", help="write benchmarks/results/body_measure.json")
    ap.add_argument("--cause", action="store_true", help="where the bust is read with each skeleton")
    ap.add_argument(
        "--anny", action="store_true", help="anny's bodies as files, against their skinning weights' reading"
    )
    args = ap.parse_args()
    from unsew.errors import InputError

    if args.anny:
        text, worst = table(anny_rows())
        print(text)
        print(f"\nmax abs error against the weights' reading: {worst['all']:.1f} cm")
        return
    bodies = Path(args.bodies)
    if not bodies.is_dir():
        raise InputError(f"--bodies {bodies} is not a folder")
    names = [n for n in args.names.split(",") if n] or sorted(p.stem for p in bodies.glob("*.obj"))
    if args.quick:
        names = ["mean_female"]
    if args.cause:
        print(cause_rows(bodies, names))
        return
    rows = run_rows(bodies, names)
    text, worst = table(rows)
    print(text)
    print(
        f"\nmax abs error, skeletons none/rig/limb: {worst['acceptance']:.1f} cm; with smpl: "
        f"{worst['all']:.1f} cm"
    )
    if args.record:
        record(rows)


if __name__ == "__main__":
    main()
