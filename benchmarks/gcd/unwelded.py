"""The design read off each newton target as another simulator would export it: its panels
unwelded. Each target is cut into a front and a back piece at the body's vertical plane through
its axis (faces by their centroid), the seam vertices doubled and the back's copies moved
``GAP`` back; a second copy has its back piece meshed twice as finely (each triangle in four, so
its seams carry a vertex between each two of the front's). unsew reads each (``unsew fit``'s
reading, through the target's repair on load) and the row says whether the type and every
structural choice read agree with the welded target's.

    python -m benchmarks gcd unwelded [--out CASES] [--only CASE ...] [--no-weld]

``--no-weld`` turns the repair's seam welding off (``SEAM_WELD`` 0): the readings as they were
before unsew welded open seams.
"""

from __future__ import annotations

import json
import tempfile
import warnings
from pathlib import Path

import numpy as np
import reading as gt_reading

#: How far the back piece's seam vertices are moved from the front's [m] (a sewn seam's gap).
GAP = 0.0005


def split_front_back(v: np.ndarray, f: np.ndarray, axis_z: float, *, gap: float = GAP, finer: bool = False):
    """(verts, faces) of the garment (V, 3) [m], (F, 3) cut at z = ``axis_z`` into a front and a
    back piece whose shared vertices are doubled, the back's copies ``gap`` [m] further back;
    ``finer``: the back piece's triangles each cut in four."""
    import trimesh

    v = np.asarray(v, dtype=np.float64)
    f = np.asarray(f, dtype=np.int64)
    front = v[f].mean(1)[:, 2] > axis_z
    seam = np.intersect1d(f[front].ravel(), f[~front].ravel())
    copy = np.arange(len(v))
    copy[seam] = len(v) + np.arange(len(seam))
    v2 = np.concatenate([v, v[seam] + [0.0, 0.0, -gap]])
    back = copy[f[~front]]
    if not finer:
        return v2, np.concatenate([f[front], back])
    b = trimesh.Trimesh(v2, back, process=False).subdivide()
    fr = trimesh.Trimesh(v2, f[front], process=False)
    both = trimesh.util.concatenate([fr, b])
    return np.asarray(both.vertices), np.asarray(both.faces)


def _reading(d: Path, v, f):
    """The DesignReading of garment (v, f) on case folder ``d``'s body, read as ``unsew fit`` reads
    a target (repaired on load), and what the repair welded."""
    import trimesh

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "target.obj"
        trimesh.Trimesh(v, f, process=False).export(path)
        from unsew.io.mesh import read_garment

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            _, _, rep = read_garment(path)
        r, _ = gt_reading.read_case(d, path)
    return r, rep.welded_vertices


def _said(r) -> str:
    return r.garment + " " + " ".join(str(x) for x in r.choices().values() if x is not None)


def unwelded_row(d: Path, target: Path) -> dict:
    """One case's row: the welded target's reading and whether each unwelded copy reads the same."""
    import trimesh

    from unsew.body.body import load_body

    skel = d / "skeleton.json"
    body = load_body(d / "body.obj", skel if skel.is_file() else None)
    axis_z = float(np.asarray(body.skeleton.position("spine"))[2])
    m = trimesh.load(target, process=False)
    v, f = np.asarray(m.vertices), np.asarray(m.faces)
    welded, _ = gt_reading.read_case(d, target)
    row = {"case": d.name, "read (welded)": _said(welded)}
    for key, finer in (("split", False), ("split, back finer", True)):
        r, n = _reading(d, *split_front_back(v, f, axis_z, finer=finer))
        same = r.garment == welded.garment and r.choices() == welded.choices()
        row[f"{key}: same"] = "yes" if same else f"no: {_said(r)}"
        row[f"{key}: welded"] = n
    return row


def cmd_unwelded(args, case_ids: list[str]) -> int:
    """Print one row per case with a newton target (``args.only`` or all) and the count alike."""
    from tables import print_table

    if args.no_weld:
        import unsew.geometry.repair as repair

        repair.SEAM_WELD = 0.0
    root = Path(args.out)
    rows = []
    for cid in args.only or case_ids:
        tgt = gt_reading.target_of(root, cid, None)
        if tgt is None or tgt[0] != "newton":
            continue
        rows.append(unwelded_row(root / cid, tgt[1]))
        print(json.dumps(rows[-1]), flush=True)
    print_table(rows, title=f"The design read off each target with its panels unwelded ({root})")
    for key in ("split", "split, back finer"):
        same = sum(r[f"{key}: same"] == "yes" for r in rows)
        print(f"{key}: read as the welded target on {same} of {len(rows)}")
    return 0
