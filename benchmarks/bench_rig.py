"""How well does `unsew body rig` find the joints of a body from its mesh alone, and measure bodies
that come without a skeleton?

    ANNY_CACHE_DIR=... python -m benchmarks rig [--previews DIR] [--foreign ../shared/foreign/bodies]

1. Anny bodies with known joints (needs the anny extra): shapes and poses (A, T, a limb moved),
   each rigged from its mesh by ``unsew.body.rig.rig_skeleton``; per body the median and worst
   error [cm] over the 17 joints of FORMATS.md, then the median and worst over all. The reference
   joints are anny's own, mapped by ``unsew.body.anny_body.JOINT_MAP`` (the head of the anny bone:
   pelvis=root, spine=spine03, chest=spine01, neck=neck01, head=head, shoulder=upperarm01,
   elbow=lowerarm01, wrist=wrist, hip=upperleg01, knee=lowerleg01, ankle=foot). The rig's fixed
   shares were read on the "tuning" bodies; the "held-out" bodies were added after the last change
   to the rig and not looked at before this table.
2. Bust with the arms raised (anny): each shape of (1) built in A- and in T-pose; the arms-down
   bust (``measure_body`` on the A body with anny's joints), the trunk girth at the bust points of
   the T body rigged from its mesh, their ratio (its median is ``unsew.body.measure.RAISED_ARM_BUST``),
   and the rigged T body's bust as ``measure_body`` reads it now; also the A body's bust once rigged.
   Likewise the shoulder width: arms down (A, anny's joints) against the rigged T body's shoulder
   joints (the median of half their difference is ``RAISED_ARM_SHOULDER_OUT``).
3. GarmentCode's bodies (no skeleton): rigged, then ``measure_body`` against their .yaml (cm).

Prints tables; asserts nothing.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np
from tables import print_table

D = np.deg2rad
#: name -> (phenotype, pose, group)
ANNY_BODIES = {
    "avg_A": ({}, "A", "tuning"),
    "female_A": ({"gender": 0.1, "weight": 0.35, "height": 0.35, "muscle": 0.4}, "A", "tuning"),
    "male_heavy_A": ({"gender": 0.9, "weight": 0.75, "height": 0.8, "muscle": 0.7}, "A", "tuning"),
    "avg_T": ({}, "T", "tuning"),
    "male_T": ({"gender": 0.85, "weight": 0.55, "height": 0.65}, "T", "tuning"),
    "female_arm_fwd_knee": ({"gender": 0.2, "weight": 0.6, "proportions": 0.3},
                            {"left_shoulder": [-D(60), 0, 0], "right_knee": [D(45), 0, 0]}, "tuning"),
    "male_leg_fwd_elbow": ({"gender": 0.7, "age": 0.7, "weight": 0.4},
                           {"right_hip": [-D(30), 0, 0], "left_elbow": [-D(70), 0, 0]}, "tuning"),
    "avg_arm_up_side": ({"proportions": 0.7}, {"right_shoulder": [0, 0, -D(80)], "left_hip": [0, 0, D(20)]}, "tuning"),
    "young_slim_T": ({"gender": 0.3, "age": 0.35, "weight": 0.2, "height": 0.6}, "T", "tuning"),
    "old_heavy_A": ({"gender": 0.6, "age": 0.9, "weight": 0.8, "muscle": 0.3}, "A", "tuning"),
    "tall_arm_fwd": ({"gender": 0.5, "height": 0.9, "proportions": 0.6},
                     {"right_shoulder": [-D(45), 0, 0], "left_knee": [D(30), 0, 0]}, "tuning"),
    "short_leg_side": ({"gender": 0.15, "height": 0.1, "muscle": 0.7},
                       {"right_hip": [0, 0, -D(15)], "left_shoulder": [0, 0, D(30)]}, "tuning"),
    "heavy_T": ({"gender": 0.4, "age": 0.4, "weight": 0.9, "height": 0.45}, "T", "held-out"),
    "slim_tall_A": ({"gender": 0.65, "weight": 0.15, "height": 0.85, "muscle": 0.6}, "A", "held-out"),
    "elbows_bent": ({"proportions": 0.4}, {"left_elbow": [-D(50), 0, 0], "right_elbow": [-D(50), 0, 0]}, "held-out"),
    "step_back_arm_side": ({"gender": 0.25, "age": 0.6},
                           {"left_hip": [D(20), 0, 0], "left_shoulder": [0, 0, D(60)]}, "held-out"),
}
YAML_KEYS = {"height": "height", "bust": "bust", "waist": "waist", "hip": "hips"}


def _anny_table(previews: Path | None) -> None:
    from unsew.body.anny_body import make_anny_body
    from unsew.body.rig import RIG_JOINTS, rig_skeleton

    rows, errs, per_joint = [], {"tuning": [], "held-out": []}, {n: [] for n in RIG_JOINTS}
    for name, (ph, pose, group) in ANNY_BODIES.items():
        body = make_anny_body(ph, pose=pose)
        t = time.perf_counter()
        sk = rig_skeleton(body.verts, body.faces)
        dt = time.perf_counter() - t
        e = {n: float(np.linalg.norm(sk.position(n) - body.skeleton.position(n))) * 100 for n in RIG_JOINTS}
        worst = max(e, key=e.get)
        errs[group] += list(e.values())
        for n, v in e.items():
            per_joint[n].append(v)
        rows.append({"body": name, "group": group, "pose": pose if isinstance(pose, str) else "limb moved",
                     "height m": body.height, "median cm": float(np.median(list(e.values()))),
                     "worst cm": e[worst], "worst joint": worst, "rig s": dt})
        if previews is not None:
            from unsew.body.body import Body
            from unsew.body.preview import render_rig_preview

            render_rig_preview(Body(body.verts, body.faces, sk, rigged=True, name=name), previews / f"rig_{name}.png")
    print_table(rows, title="Joints rigged from the mesh vs anny's own (17 joints per body)")
    allv = errs["tuning"] + errs["held-out"]
    print_table([{"bodies": g, "joints": len(v), "median cm": float(np.median(v)), "worst cm": float(np.max(v))}
                 for g, v in (("tuning", errs["tuning"]), ("held-out", errs["held-out"]), ("all", allv))],
                title="Over all joints")
    print_table([{"joint": n, "median cm": float(np.median(v)), "worst cm": float(np.max(v))} for n, v in per_joint.items()],
                title="Per joint, over all bodies")


def _bust_pose_table() -> None:
    from unsew.body.anny_body import make_anny_body
    from unsew.body.body import Body
    from unsew.body.measure import RAISED_ARM_BUST, RAISED_ARM_SHOULDER_OUT, bust_point_girth, measure_body
    from unsew.body.rig import rig_skeleton

    rows, seen = [], set()
    for name, (ph, pose, _group) in ANNY_BODIES.items():
        key = tuple(sorted(ph.items()))
        if not isinstance(pose, str) or key in seen:
            continue
        seen.add(key)
        a, t = make_anny_body(ph, pose="A"), make_anny_body(ph, pose="T")
        a_rig = Body(a.verts, a.faces, rig_skeleton(a.verts, a.faces), rigged=True)
        t_rig = Body(t.verts, t.faces, rig_skeleton(t.verts, t.faces), rigged=True)
        ma, mt = measure_body(a), measure_body(t_rig)
        g_t = bust_point_girth(t_rig)[0]
        sk = t_rig.skeleton
        joints_t = abs(sk.position("left_shoulder")[0] - sk.position("right_shoulder")[0])
        rows.append({"shape": name, "A bust cm": ma.bust * 100, "A bust rigged cm": measure_body(a_rig).bust * 100,
                     "T bust-point girth cm": g_t * 100, "ratio A/T": ma.bust / g_t,
                     "T bust rigged cm": mt.bust * 100, "T - A cm": (mt.bust - ma.bust) * 100,
                     "A shoulder cm": ma.shoulder_width * 100, "T shoulder joints cm": joints_t * 100,
                     "out cm": (ma.shoulder_width - joints_t) / 2 * 100,
                     "T shoulder rigged cm": mt.shoulder_width * 100})
    print_table(rows, title="Bust and shoulder width with the arms raised: anny shapes in A- and T-pose", digits=2)
    print(f"median ratio {np.median([r['ratio A/T'] for r in rows]):.4f}  (RAISED_ARM_BUST = {RAISED_ARM_BUST}); "
          f"median out {np.median([r['out cm'] for r in rows]):.2f} cm  (RAISED_ARM_SHOULDER_OUT = {RAISED_ARM_SHOULDER_OUT} m)")


def _foreign_table(folder: Path, previews: Path | None) -> None:
    import yaml

    from unsew.body.body import load_body
    from unsew.body.measure import measure_body

    rows = []
    for mesh in sorted(folder.glob("*.obj")):
        ref = yaml.safe_load(mesh.with_suffix(".yaml").read_text())["body"]
        t = time.perf_counter()
        body = load_body(mesh)  # no skeleton: rigged from the mesh
        dt = time.perf_counter() - t
        m = measure_body(body).as_dict()
        row = {"body": mesh.stem, "rigged": body.rigged, "load+rig s": dt}
        worst = 0.0
        for k, yk in YAML_KEYS.items():
            row[f"{k} cm"] = m[k] * 100
            row[f"{k} yaml"] = float(ref[yk])
            worst = max(worst, abs(m[k] * 100 - float(ref[yk])))
        row["worst diff cm"] = worst
        rows.append(row)
        if previews is not None:
            from unsew.body.preview import render_rig_preview

            render_rig_preview(body, previews / f"rig_{mesh.stem}.png")
    print_table(rows, title=f"GarmentCode bodies ({folder}), rigged and measured vs their .yaml [cm]", digits=1)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    here = Path(__file__).resolve().parents[1]
    shared = Path(os.environ.get("UNSEW_SHARED", here.parent / "shared"))
    ap.add_argument("--foreign", type=Path, default=shared / "foreign" / "bodies",
                    help="folder of GarmentCode bodies (.obj + .yaml); default ../shared/foreign/bodies or $UNSEW_SHARED/...")
    ap.add_argument("--previews", type=Path, help="write a front/side PNG of each rigged body here")
    ap.add_argument("--skip-anny", action="store_true", help="only the GarmentCode bodies")
    args = ap.parse_args()
    if args.previews is not None:
        os.makedirs(args.previews, exist_ok=True)
    if not args.skip_anny:
        try:
            import anny  # noqa: F401
        except ImportError:
            print("anny is not installed (pip install unsew[anny]): skipping the anny bodies")
        else:
            _anny_table(args.previews)
            _bust_pose_table()
    if args.foreign.is_dir():
        _foreign_table(args.foreign, args.previews)
    else:
        print(f"no GarmentCode bodies at {args.foreign}: skipping them")


if __name__ == "__main__":
    main()
